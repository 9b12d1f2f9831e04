//! The families: exact decisions on the home-pose axes, then Paden–Kahan subproblems on the
//! exact axis data. Every step is a [`Formula`] in the target symbols, the parameters and the
//! joints solved before it.

use super::axes::{
    add, cross, dot, home_axes, intersection, is_zero3, on_line, relation, scale, sub, zero3, Axis,
    Relation, V3,
};
use super::{
    Branch, BranchPart, BranchSigns, Fact, Formula, FreeChoice, IkError, IkMethod, IkOptions,
    IkSolution, IkStep, Phrase, Reach, TARGET_SYMBOLS,
};
use crate::kin::{JointKind, Robot};
use crate::{Matrix4, Scalar, ScalarError};
use thiserror::Error;

mod divisor;
mod short;
mod slides;

use divisor::{homogenize, meet, on_line_scaled, parts_mut, INV_SCALE};
use short::{five_joints, pitch_arm, pitch_arm_axes};

/// Why a family's derivation stopped: a limit (reported as the limit), or a fact of the
/// geometry (reported with the geometry found).
#[derive(Clone, Debug, Error)]
pub(crate) enum PlanError {
    /// An exact computation reached a limit or failed.
    #[error(transparent)]
    Scalar(#[from] ScalarError),
    /// A subproblem's coefficients vanish for every target.
    #[error("the subproblem for {variable} is degenerate for every target ({method})")]
    Degenerate {
        /// The joint variable.
        variable: String,
        /// The subproblem, in words.
        method: String,
    },
    /// A point the family needs has no exact form here.
    #[error("{0} is not exact")]
    NotExact(&'static str),
}

/// The first error among exact values: a limit reached while they were computed.
fn first_error<'a>(xs: impl IntoIterator<Item = &'a Scalar>) -> Result<(), ScalarError> {
    match xs.into_iter().find_map(Scalar::as_error) {
        Some(e) => Err(e.clone()),
        None => Ok(()),
    }
}

pub(crate) const FAMILIES: &str = "planar 2R (position) and 3R; SCARA-type RRPR (three parallel \
revolute axes, a prismatic joint along them); 6 joints with a spherical wrist (axes 4, 5, 6 \
through one point) and either axes 2 and 3 parallel, or axes 1 and 2 intersecting (joint 3 \
revolute or prismatic), or axes 2 and 3 intersecting off axis 1; the same read backwards (a \
spherical shoulder: axes 1, 2, 3 through one point, with axes 4 and 5 parallel, axes 5 and 6 \
intersecting, or axes 4 and 5 intersecting off axis 6); 6R with axes 2, 3, 4 parallel and axes \
5 and 6 intersecting (UR type); 4R with axes 2, 3, 4 parallel (position and one angle); 5 \
joints with axes 1-3 as in a spherical-wrist arm and axes 4 and 5 intersecting (position and \
approach axis); 6 joints of three turns and three slides in any order (3R3P, no two \
consecutive turns about parallel axes); 7 joints with one joint given by --free reducing to one \
of these";

/// The target pose and the home pose: `G = T M⁻¹`, the motion `E1 ... En`.
struct Target {
    r: [[Scalar; 3]; 3],
    p: V3,
    /// `R_M`, `t_M` of the home pose.
    rm: [[Scalar; 3]; 3],
    tm: V3,
    /// The motion is `G⁻¹ = M T⁻¹` (the chain reversed) instead of `G`.
    inverse: bool,
}

impl Target {
    fn new(home: &Matrix4<Scalar>) -> Target {
        let s = |n: &str| Scalar::sym(n);
        let r = std::array::from_fn(|i| std::array::from_fn(|j| s(TARGET_SYMBOLS[i][j])));
        let p = std::array::from_fn(|i| s(TARGET_SYMBOLS[i][3]));
        let rm = std::array::from_fn(|i| std::array::from_fn(|j| home.rows[i][j].clone()));
        let tm = std::array::from_fn(|i| home.rows[i][3].clone());
        Target {
            r,
            p,
            rm,
            tm,
            inverse: false,
        }
    }

    /// The target of the reversed chain: `G⁻¹ = E6⁻¹ ⋯ E1⁻¹`.
    fn reversed(&self) -> Target {
        Target {
            r: self.r.clone(),
            p: self.p.clone(),
            rm: self.rm.clone(),
            tm: self.tm.clone(),
            inverse: !self.inverse,
        }
    }

    fn mat(m: &[[Scalar; 3]; 3], v: &V3) -> V3 {
        std::array::from_fn(|i| dot(&m[i], v))
    }

    fn mat_t(m: &[[Scalar; 3]; 3], v: &V3) -> V3 {
        std::array::from_fn(|i| &m[0][i] * &v[0] + &m[1][i] * &v[1] + &m[2][i] * &v[2])
    }

    /// `R_G v = R_T R_Mᵀ v` (reversed: `R_M R_Tᵀ v`).
    fn dir(&self, v: &V3) -> V3 {
        if self.inverse {
            Self::mat(&self.rm, &Self::mat_t(&self.r, v))
        } else {
            Self::mat(&self.r, &Self::mat_t(&self.rm, v))
        }
    }

    /// `R_Gᵀ v = R_M R_Tᵀ v` (reversed: `R_T R_Mᵀ v`).
    fn dir_inv(&self, v: &V3) -> V3 {
        if self.inverse {
            Self::mat(&self.r, &Self::mat_t(&self.rm, v))
        } else {
            Self::mat(&self.rm, &Self::mat_t(&self.r, v))
        }
    }

    /// `G x = R_T R_Mᵀ (x − t_M) + p` (reversed: `G⁻¹ x = R_M R_Tᵀ (x − p) + t_M`).
    fn point(&self, x: &V3) -> V3 {
        if self.inverse {
            add(&self.dir(&sub(x, &self.p)), &self.tm)
        } else {
            add(&self.dir(&sub(x, &self.tm)), &self.p)
        }
    }
}

fn norm2(v: &V3) -> Scalar {
    dot(v, v)
}

/// A unit-free vector perpendicular to the unit vector `w` (exact).
fn perpendicular(w: &V3) -> V3 {
    let basis = [
        [Scalar::int(1), Scalar::int(0), Scalar::int(0)],
        [Scalar::int(0), Scalar::int(1), Scalar::int(0)],
        [Scalar::int(0), Scalar::int(0), Scalar::int(1)],
    ];
    // The basis vector least aligned with w, when w is numeric; otherwise the first that gives
    // a nonzero cross product.
    let mut best: Option<(f64, V3)> = None;
    for e in &basis {
        let c = cross(w, e);
        if is_zero3(&c) {
            continue;
        }
        let score = dot(w, e).eval(&|_| None).map(f64::abs).unwrap_or(0.5);
        if best.as_ref().is_none_or(|(s, _)| score < *s) {
            best = Some((score, c));
        }
    }
    best.map(|b| b.1).unwrap_or_else(zero3)
}

/// Subproblem 4 (a component of a rotated vector): `k · Rot(ω, q) u = d`, as
/// `a cos q + b sin q = c`.
fn sp4(k: &V3, axis: &Axis, u: &V3, d: &Scalar) -> Formula {
    let w = &axis.dir;
    let wu = dot(w, u);
    let kw = dot(k, w);
    Formula::Trig {
        a: dot(k, u) - &wu * &kw,
        b: dot(k, &cross(w, u)),
        c: d - &(&wu * &kw),
    }
}

/// Subproblem 3 (a distance): `|E(q) x − centre|² = δ²` about a revolute axis.
fn sp3(axis: &Axis, x: &V3, centre: &V3, delta2: &Scalar) -> Formula {
    let u = sub(x, &axis.point);
    let w = sub(centre, &axis.point);
    let d = (norm2(&u) + norm2(&w) - delta2) * <Scalar as crate::Ring>::from_ratio(1, 2);
    sp4(&w, axis, &u, &d)
}

/// Subproblem 1 (a rotation taking `u` to `v` about the axis): `q = atan2(ω·(u×v), u·v −
/// (ω·u)(ω·v))`.
fn sp1(axis: &Axis, u: &V3, v: &V3) -> Formula {
    let w = &axis.dir;
    Formula::Atan2 {
        y: dot(w, &cross(u, v)),
        x: dot(u, v) - dot(w, u) * dot(w, v),
    }
}

struct Builder<'a> {
    axes: &'a [Axis],
    steps: Vec<IkStep>,
    /// `D` when a point is known only as `N / D` (see [`meet`]): the steps on it are
    /// multiplied through by a power of `D`.
    scale: Option<Scalar>,
    /// The part of the target the family controls.
    reach: Reach,
}

const SHOULDER: Branch = Branch {
    part: BranchPart::Shoulder,
    signs: BranchSigns::LeftRight,
};
const ELBOW: Branch = Branch {
    part: BranchPart::Elbow,
    signs: BranchSigns::UpDown,
};
const WRIST: Branch = Branch {
    part: BranchPart::Wrist,
    signs: BranchSigns::NoFlipFlip,
};
const REACH: Branch = Branch {
    part: BranchPart::Reach,
    signs: BranchSigns::FarNear,
};

impl Builder<'_> {
    fn push(
        &mut self,
        j: usize,
        mut formula: Formula,
        method: Phrase,
        branch: Option<Branch>,
        singular: impl Into<Phrase>,
    ) -> Result<(), PlanError> {
        let scaled = parts_mut(&mut formula)
            .iter()
            .any(|p| p.symbols().iter().any(|s| s.name() == INV_SCALE));
        if scaled {
            let d = self
                .scale
                .clone()
                .ok_or(PlanError::NotExact("a point with a symbolic divisor"))?;
            homogenize(&mut formula, &d)?;
        }
        let degenerate = match &formula {
            Formula::Atan2 { y, x } => y.is_zero_value() && x.is_zero_value(),
            Formula::Trig { a, b, .. } => a.is_zero_value() && b.is_zero_value(),
            Formula::Linear { a, .. } => a.is_zero_value(),
            _ => false,
        };
        let all = match &formula {
            Formula::Atan2 { y, x } => vec![y, x],
            Formula::Trig { a, b, c } => vec![a, b, c],
            Formula::Value { v } => vec![v],
            Formula::Linear { a, b } => vec![a, b],
            Formula::Quadratic { beta, gamma } => vec![beta, gamma],
        };
        first_error(all)?;
        if degenerate {
            return Err(PlanError::Degenerate {
                variable: self.axes[j].variable.clone(),
                method: method.to_string(),
            });
        }
        let branch = if formula.branches() == 2 {
            branch
        } else {
            None
        };
        self.steps.push(IkStep {
            joint: j,
            variable: self.axes[j].variable.clone(),
            formula,
            method,
            branch,
            singular: singular.into(),
        });
        Ok(())
    }
}

fn geometry_lines(axes: &[Axis]) -> Result<Vec<Fact>, ScalarError> {
    let mut out = vec![Fact::Joints(axes.iter().map(|a| a.kind).collect())];
    for i in 0..axes.len() {
        for j in i + 1..axes.len().min(i + 3) {
            if axes[i].kind == JointKind::Prismatic || axes[j].kind == JointKind::Prismatic {
                out.push(Fact::Directions {
                    axes: [i + 1, j + 1],
                    parallel: is_zero3(&cross(&axes[i].dir, &axes[j].dir)),
                });
                continue;
            }
            let relation = relation(&axes[i], &axes[j]);
            if let Relation::SkewUnless(r) = &relation {
                first_error([r])?;
            }
            out.push(Fact::Pair {
                axes: [i + 1, j + 1],
                relation,
            });
        }
    }
    let n = axes.len();
    if n >= 3 {
        out.push(Fact::SphericalWrist {
            axes: [n - 2, n - 1, n],
            yes: common_point(&axes[n - 3..]).is_some(),
        });
    }
    Ok(out)
}

/// The point common to three revolute axes, when there is one (exactly).
fn common_point(ax: &[Axis]) -> Option<V3> {
    if ax.iter().any(|a| a.kind != JointKind::Revolute) {
        return None;
    }
    let pairs = [(0, 1), (1, 2), (0, 2)];
    for (i, j) in pairs {
        if relation(&ax[i], &ax[j]) == Relation::Intersecting {
            let p = intersection(&ax[i], &ax[j])?;
            let k = 3 - i - j;
            return on_line(&p, &ax[k]).then_some(p);
        }
    }
    None
}

/// Where axes 1 and 2 meet when they do, else the point of axis 2.
fn shoulder_centre(a1: &Axis, a2: &Axis) -> V3 {
    if relation(a1, a2) == Relation::Intersecting {
        if let Some(o) = intersection(a1, a2) {
            return o;
        }
    }
    a2.point.clone()
}

fn parallel(a: &Axis, b: &Axis) -> bool {
    is_zero3(&cross(&a.dir, &b.dir))
}

fn revolute(ax: &[Axis]) -> bool {
    ax.iter().all(|a| a.kind == JointKind::Revolute)
}

pub(crate) fn derive(robot: &Robot, opts: &IkOptions) -> Result<IkSolution, IkError> {
    let (axes, home) = home_axes(robot);
    derive_axes(
        &robot.name,
        &robot.variables,
        robot.parameters(),
        axes,
        home,
        opts,
    )
}

/// The derivation from the axes and the home pose. A 7-joint chain without `--free` gets the
/// first end joint, else the first inner joint, whose value as a parameter leaves a supported
/// family (said in the geometry); a
/// `--free` that leaves none gets an error naming the joints that would.
pub(crate) fn derive_axes(
    name: &str,
    variables: &[String],
    params: Vec<String>,
    axes: Vec<Axis>,
    home: Matrix4<Scalar>,
    opts: &IkOptions,
) -> Result<IkSolution, IkError> {
    let first = derive_fixed(
        name,
        variables,
        params.clone(),
        axes.clone(),
        home.clone(),
        opts,
    );
    if axes.len() != 7 || !matches!(first, Err(IkError::Unsupported { .. })) {
        return first;
    }
    let try_free = |v: &String| {
        // Families first for every choice of the free joint; the general method below.
        let o = IkOptions {
            free: Some(v.clone()),
            method: IkMethod::Family,
        };
        derive_fixed(
            name,
            variables,
            params.clone(),
            axes.clone(),
            home.clone(),
            &o,
        )
    };
    match &opts.free {
        None => {
            // An end joint first (the other six are then an arm of their own with the whole
            // target), then the inner joints in order.
            let n = variables.len();
            let order = [0, n - 1].into_iter().chain(1..n - 1);
            let order = order.filter(|_| opts.method != IkMethod::General);
            for k in order {
                let v = &variables[k];
                match try_free(v) {
                    Ok(mut sol) => {
                        let which = if k == 0 {
                            FreeChoice::First
                        } else if k == n - 1 {
                            FreeChoice::Last
                        } else {
                            FreeChoice::Inner
                        };
                        sol.geometry.insert(
                            0,
                            Fact::FreeChosen {
                                variable: v.clone(),
                                which,
                            },
                        );
                        return Ok(sol);
                    }
                    Err(IkError::Unsupported { .. }) => {}
                    Err(e) => return Err(e),
                }
            }
            if opts.method != IkMethod::Family {
                // No family with any free joint: the first joint free, the general method.
                let o = IkOptions {
                    free: Some(variables[0].clone()),
                    method: IkMethod::General,
                };
                let g = derive_fixed(
                    name,
                    variables,
                    params.clone(),
                    axes.clone(),
                    home.clone(),
                    &o,
                );
                if let Ok(mut sol) = g {
                    sol.geometry.insert(
                        0,
                        Fact::FreeChosen {
                            variable: variables[0].clone(),
                            which: FreeChoice::First,
                        },
                    );
                    return Ok(sol);
                }
            }
            first.map_err(|e| with_line(e, "no joint given as --free leaves a supported family"))
        }
        Some(f) => {
            let fits: Vec<&str> = variables
                .iter()
                .filter(|v| *v != f && try_free(v).is_ok())
                .map(String::as_str)
                .collect();
            let line = if fits.is_empty() {
                format!("--free {f}: no joint given as --free leaves a supported family")
            } else {
                format!(
                    "--free {f} leaves no supported family; --free {} does",
                    fits.join(" or --free ")
                )
            };
            first.map_err(|e| with_line(e, &line))
        }
    }
}

/// An [`IkError::Unsupported`] with one more geometry line.
fn with_line(e: IkError, line: &str) -> IkError {
    match e {
        IkError::Unsupported {
            robot,
            mut geometry,
            families,
        } => {
            geometry.push_str(&format!("\n  {line}"));
            IkError::Unsupported {
                robot,
                geometry,
                families,
            }
        }
        e => e,
    }
}

#[allow(clippy::needless_range_loop)] // rows and columns of a 3 x 4 block, by index
fn derive_fixed(
    name: &str,
    variables: &[String],
    mut params: Vec<String>,
    mut axes: Vec<Axis>,
    mut home: Matrix4<Scalar>,
    opts: &IkOptions,
) -> Result<IkSolution, IkError> {
    check_target_names(variables, &params)?;
    if let Some(f) = &opts.free {
        fix_free(name, variables, f, &mut axes, &mut home)?;
        params.push(f.clone());
        params.sort();
    }
    let mut geometry = geometry_lines(&axes)?;
    if opts.free.is_some() {
        geometry.insert(
            0,
            Fact::Numbering(axes.iter().map(|a| a.variable.clone()).collect()),
        );
    }
    let target = Target::new(&home);
    let mut b = Builder {
        axes: &axes,
        steps: Vec::new(),
        scale: None,
        reach: Reach::Pose,
    };
    let attempt = if opts.method == IkMethod::General {
        Ok(None)
    } else {
        family(&mut b, &target)
    };
    let unsupported = |why: Option<String>| IkError::Unsupported {
        robot: name.to_string(),
        geometry: {
            let mut g: Vec<String> = geometry.iter().map(Fact::to_string).collect();
            g.extend(why);
            g.iter()
                .map(|l| format!("  {l}"))
                .collect::<Vec<_>>()
                .join("\n")
        },
        families: FAMILIES.into(),
    };
    // A limit reached anywhere on the way (a decision on an error value reads as "no") is the
    // outcome, whatever the family search concluded: the work budget is spent for good once
    // exceeded, and a term limit leaves an error value in the axes or the steps.
    crate::scalar::charge(0)?;
    first_error(axes.iter().flat_map(|a| a.dir.iter().chain(&a.point)))?;
    first_error(home.rows.iter().flatten())?;
    let general = opts.method != IkMethod::Family && super::general::applies(&axes);
    // Why a family that applied stopped: said beside the general method's refusal.
    let family_error = match &attempt {
        Err(m) => Some(m.to_string()),
        _ => None,
    };
    let (family, position_only) = match attempt {
        Ok(Some(f)) => f,
        Err(PlanError::Scalar(e)) => return Err(IkError::Scalar(e)),
        Ok(None) | Err(_) if general => {
            b.steps.clear();
            b.reach = Reach::Pose;
            let name = if super::general::apart_chain(&axes) {
                GENERAL_APART
            } else {
                GENERAL
            };
            (name.into(), false)
        }
        Ok(None) => return Err(unsupported(None)),
        Err(m) => return Err(unsupported(Some(m.to_string()))),
    };
    let conditions = reach_conditions(&b.steps);
    let steps = b.steps;
    let reach = if position_only {
        Reach::Position
    } else {
        b.reach
    };
    let variables = variables
        .iter()
        .filter(|v| Some(*v) != opts.free.as_ref())
        .cloned()
        .collect();
    let sol = IkSolution {
        robot: name.to_string(),
        family,
        geometry,
        conditions,
        steps,
        variables,
        params,
        free: opts.free.clone(),
        position_only,
        reach,
        home,
        end: super::EndFrame::default(),
        axes,
        general: None,
        forms: std::sync::OnceLock::new(),
        degrees: std::sync::OnceLock::new(),
    };
    with_general(sol, family_error)
}

/// Refuses a robot that uses a name of the target pose's entries.
fn check_target_names(variables: &[String], params: &[String]) -> Result<(), IkError> {
    for row in TARGET_SYMBOLS {
        for s in row {
            if variables.iter().any(|v| v == s) || params.iter().any(|v| v == s) {
                return Err(IkError::Option(format!(
                    "the robot uses the name `{s}`, which ik keeps for the target pose"
                )));
            }
        }
    }
    Ok(())
}

/// Fixes the free joint `f` at its (symbolic) value: the axes after it and the home pose
/// moved by its motion `E_k`, its axis removed.
fn fix_free(
    name: &str,
    variables: &[String],
    f: &str,
    axes: &mut Vec<Axis>,
    home: &mut Matrix4<Scalar>,
) -> Result<(), IkError> {
    let k = variables.iter().position(|v| v == f).ok_or_else(|| {
        IkError::Option(format!(
            "--free {f}: not a joint variable of {name} (joint variables: {})",
            variables.join(", ")
        ))
    })?;
    let by = axes[k].clone();
    for a in axes.iter_mut().skip(k + 1) {
        *a = a.moved_by(&by);
    }
    // M' = E_k M.
    let mut rows = home.rows.clone();
    for c in 0..4 {
        let col: V3 = std::array::from_fn(|r| home.rows[r][c].clone());
        let m = if c < 3 {
            by.move_dir(&col, 1)
        } else {
            by.move_point(&col, 1)
        };
        for (row, x) in rows.iter_mut().zip(m) {
            row[c] = x;
        }
    }
    *home = Matrix4::from_rows(rows);
    axes.remove(k);
    Ok(())
}

/// Where each step's roots exist (a trig or quadratic step's radicand), one line each.
fn reach_conditions(steps: &[IkStep]) -> Vec<String> {
    let mut conditions = Vec::new();
    for s in steps {
        match &s.formula {
            Formula::Trig { .. } => conditions.push(format!(
                "{}: exists where a² + b² − c² ≥ 0 (else the target is out of reach)",
                s.variable
            )),
            Formula::Quadratic { .. } => conditions.push(format!(
                "{}: exists where β² − γ ≥ 0 (else the target is out of reach)",
                s.variable
            )),
            _ => {}
        }
    }
    conditions
}

/// A solution by the general method gets its elimination's data; refused where the
/// elimination is degenerate.
fn with_general(mut sol: IkSolution, family_error: Option<String>) -> Result<IkSolution, IkError> {
    let name = sol.robot.clone();
    if sol.steps.is_empty()
        && (sol.family.template == GENERAL || sol.family.template == GENERAL_APART)
    {
        let info = super::general::info(&sol);
        if info.degree == 0 {
            // Every arrangement of the loop is degenerate here (three parallel axes with a
            // spherical wrist, say): the elimination gives no polynomial.
            let mut g: Vec<String> = sol.geometry.iter().map(Fact::to_string).collect();
            g.extend(family_error.map(|e| format!("the family that applies stops: {e}")));
            g.push(
                "the general 6R elimination is degenerate for this geometry in every arrangement"
                    .into(),
            );
            g.extend(super::general::degenerate_reason(&sol.axes));
            return Err(IkError::Unsupported {
                robot: name.to_string(),
                geometry: g
                    .iter()
                    .map(|l| format!("  {l}"))
                    .collect::<Vec<_>>()
                    .join("\n"),
                families: FAMILIES.into(),
            });
        }
        sol.general = Some(info);
    }
    Ok(sol)
}

/// The family line of a solution by the general method.
pub(crate) const GENERAL: &str =
    "general 6R: Raghavan-Roth elimination to one polynomial in tan(theta/2) (Manocha-Canny matrix form)";

/// The family line of a 4R2P with its slides three joints apart, solved by the general
/// method's own elimination for it (`general/apart.rs`), not by Raghavan-Roth's.
pub(crate) const GENERAL_APART: &str = "general 4R2P, slides three joints apart: the four turns fix the orientation, the slides' plane the position; one resultant in tan(theta/2)";

/// Tries every family in turn; `Ok(None)` when none applies.
fn family(b: &mut Builder, t: &Target) -> Result<Option<(Phrase, bool)>, PlanError> {
    let ax = b.axes;
    let n = ax.len();
    if (n == 2 || n == 3) && revolute(ax) && ax.iter().all(|a| parallel(a, &ax[0])) {
        planar(b, t)?;
        let name = if n == 2 { "planar 2R" } else { "planar 3R" };
        return Ok(Some((name.into(), n == 2)));
    }
    if n == 4
        && revolute(&ax[0..2])
        && ax[2].kind == JointKind::Prismatic
        && ax[3].kind == JointKind::Revolute
        && parallel(&ax[0], &ax[1])
        && parallel(&ax[0], &ax[3])
        && parallel(&ax[0], &ax[2])
        && !matches!(
            relation(&ax[0], &ax[1]),
            Relation::Parallel { same_line: true }
        )
    {
        scara(b, t)?;
        return Ok(Some(("SCARA (RRPR)".into(), false)));
    }
    if n == 4 && pitch_arm_axes(ax) {
        pitch_arm(b, t)?;
        return Ok(Some((
            "4R: a base axis, then three parallel axes 2, 3, 4 (base yaw and three pitch joints)"
                .into(),
            false,
        )));
    }
    if n == 5 {
        return five_joints(b, t);
    }
    if n != 6 {
        return Ok(None);
    }
    if let Some(w) = common_point(&ax[3..6]) {
        if !parallel(&ax[3], &ax[4]) && !parallel(&ax[4], &ax[5]) {
            if let Some(pos) = spherical_position(b, t, &w)? {
                wrist_orientation(b, t)?;
                return Ok(Some((
                    Phrase::text("6 joints with a spherical wrist (Pieper): {p}").with_inner(pos),
                    false,
                )));
            }
        }
    }
    // A spherical shoulder (axes 1, 2, 3 through one point): the chain read backwards,
    // G⁻¹ = E6⁻¹ ⋯ E1⁻¹, is a chain of the reversed axes 6, ..., 1 at the same variables
    // with a spherical wrist.
    if let Some(o) = common_point(&ax[0..3]) {
        if !parallel(&ax[0], &ax[1]) && !parallel(&ax[1], &ax[2]) {
            let rev: Vec<Axis> = ax.iter().rev().map(Axis::reversed).collect();
            let tr = t.reversed();
            let mut rb = Builder {
                axes: &rev,
                steps: Vec::new(),
                scale: None,
                reach: Reach::Pose,
            };
            if let Some(pos) = spherical_position(&mut rb, &tr, &o)? {
                wrist_orientation(&mut rb, &tr)?;
                for mut s in rb.steps {
                    s.joint = n - 1 - s.joint;
                    s.method = Phrase {
                        reversed: true,
                        ..s.method.renumbered(n)
                    };
                    s.singular = Phrase {
                        reversed: true,
                        ..s.singular.renumbered(n)
                    };
                    // The reversed chain's shoulder is the arm's wrist and the other way round.
                    if let Some(br) = &mut s.branch {
                        br.part = match br.part {
                            BranchPart::Shoulder => BranchPart::Wrist,
                            BranchPart::Wrist => {
                                // Axes 4' and 6' are axes 3 and 1.
                                s.singular = Phrase::new(
                                    "shoulder singularity (radicand zero, the two branches \
                                     merge): axes {0} and {1} in line",
                                    &[1, 3],
                                );
                                BranchPart::Shoulder
                            }
                            x => x,
                        };
                    }
                    b.steps.push(s);
                }
                return Ok(Some((
                    Phrase::text(
                        "6 joints with a spherical shoulder (axes 1, 2, 3 through one point): \
                         the chain reversed, G⁻¹ = E6⁻¹ ⋯ E1⁻¹ about the reversed axes \
                         1' = 6, ..., 6' = 1, is a spherical-wrist arm (Pieper); in the arm's own \
                         numbering: {p}",
                    )
                    .with_inner(pos.renumbered(n)),
                    false,
                )));
            }
        }
    }
    if revolute(ax)
        && parallel(&ax[1], &ax[2])
        && parallel(&ax[1], &ax[3])
        && !parallel(&ax[0], &ax[1])
        && !parallel(&ax[4], &ax[1])
        && relation(&ax[4], &ax[5]) == Relation::Intersecting
        && !matches!(
            relation(&ax[1], &ax[2]),
            Relation::Parallel { same_line: true }
        )
    {
        three_parallel(b, t)?;
        return Ok(Some((
            "6R with three consecutive parallel axes (2, 3, 4) and axes 5, 6 intersecting".into(),
            false,
        )));
    }
    if slides::applies(ax) {
        return Ok(Some((slides::three_slides(b, t)?, false)));
    }
    Ok(None)
}

fn planar(b: &mut Builder, t: &Target) -> Result<(), PlanError> {
    let ax = b.axes;
    let n = ax.len();
    let w = ax[0].dir.clone();
    // The point carried: the tool origin (2R) or a point of the last axis (3R).
    let (x, y) = if n == 2 {
        (t.tm.clone(), t.p.clone())
    } else {
        (ax[2].point.clone(), t.point(&ax[2].point))
    };
    let p1 = &ax[0].point;
    let perp2 = |v: &V3| norm2(v) - dot(&w, v) * dot(&w, v);
    let delta2 = perp2(&sub(&y, p1)) + dot(&w, &sub(&x, p1)) * dot(&w, &sub(&x, p1));
    b.push(
        1,
        sp3(&ax[1], &x, p1, &delta2),
        if n == 2 {
            "subproblem 3 (distance): joint 2 turns the tool point about axis 2; its distance to \
             axis 1 must equal the target's"
        } else {
            "subproblem 3 (distance): joint 2 turns the point of axis 3 about axis 2; its \
             distance to axis 1 must equal the target's"
        }
        .into(),
        Some(ELBOW),
        "elbow straight or folded (radicand zero)",
    )?;
    let x2 = ax[1].move_point(&x, 1);
    b.push(
        0,
        sp1(&ax[0], &sub(&x2, p1), &sub(&y, p1)),
        "subproblem 1 (rotation): joint 1 turns the point onto the target".into(),
        None,
        "the point on axis 1",
    )?;
    if n == 3 {
        let e = perpendicular(&ax[2].dir);
        let v = ax[1].move_dir(&ax[0].move_dir(&t.dir(&e), -1), -1);
        b.push(
            2,
            sp1(&ax[2], &e, &v),
            "subproblem 1 (rotation): joint 3 completes the orientation, R3 = R2ᵀ R1ᵀ R".into(),
            None,
            "never",
        )?;
    }
    Ok(())
}

fn scara(b: &mut Builder, t: &Target) -> Result<(), PlanError> {
    let ax = b.axes;
    let w = ax[0].dir.clone();
    let x4 = ax[3].point.clone();
    let g4 = t.point(&x4);
    let wv = dot(&w, &ax[2].dir);
    let d = dot(&w, &sub(&g4, &x4)).try_div(&wv)?;
    b.push(
        2,
        Formula::Value { v: d },
        "linear: rotations about axes parallel to the slide keep the component along it; the \
         slide supplies the rest"
            .into(),
        None,
        "never",
    )?;
    let q = sub(&g4, &scale(&Scalar::sym(&ax[2].variable), &ax[2].dir));
    let p1 = &ax[0].point;
    let perp2 = |v: &V3| norm2(v) - dot(&w, v) * dot(&w, v);
    let delta2 = perp2(&sub(&q, p1)) + dot(&w, &sub(&x4, p1)) * dot(&w, &sub(&x4, p1));
    b.push(
        1,
        sp3(&ax[1], &x4, p1, &delta2),
        "subproblem 3 (distance): joint 2 sets the distance of axis 4 from axis 1".into(),
        Some(ELBOW),
        "elbow straight or folded (radicand zero)",
    )?;
    let x2 = ax[1].move_point(&x4, 1);
    b.push(
        0,
        sp1(&ax[0], &sub(&x2, p1), &sub(&q, p1)),
        "subproblem 1 (rotation): joint 1 turns axis 4 onto the target".into(),
        None,
        "axis 4 on axis 1",
    )?;
    let e = perpendicular(&ax[3].dir);
    let v = ax[1].move_dir(&ax[0].move_dir(&t.dir(&e), -1), -1);
    b.push(
        3,
        sp1(&ax[3], &e, &v),
        "subproblem 1 (rotation): joint 4 completes the orientation, R4 = R2ᵀ R1ᵀ R".into(),
        None,
        "never",
    )?;
    Ok(())
}

/// Joints 1-3 of a spherical-wrist arm from the wrist centre; the method in words, or `None`.
fn spherical_position(b: &mut Builder, t: &Target, w: &V3) -> Result<Option<Phrase>, PlanError> {
    let ax = b.axes;
    let pw = t.point(w);
    let (a1, a2, a3) = (&ax[0], &ax[1], &ax[2]);
    if revolute(&ax[0..3])
        && parallel(a2, a3)
        && !parallel(a1, a2)
        && !matches!(relation(a2, a3), Relation::Parallel { same_line: true })
    {
        let p1 = &a1.point;
        b.push(
            0,
            sp4(&sub(&pw, p1), a1, &a2.dir, &dot(&a2.dir, &sub(w, p1))),
            Phrase::new(
                "subproblem 4 (height): rotations about the parallel axes {1} and {2} keep the \
                 wrist centre's component along them, so (Rot(axis {0}, theta) k{1})·(wc − p{0}) \
                 = k{1}·(C − p{0})",
                &[1, 2, 3],
            ),
            Some(SHOULDER),
            Phrase::new(
                "radicand zero (shoulder singularity, left and right merge): the wrist centre's \
                 distance from axis {0} equals the shoulder offset |k{1}·(C − p{0})| = |{v}| (the \
                 wrist centre on axis {0} when it is 0)",
                &[1, 2],
            )
            .with_value(dot(&a2.dir, &sub(w, p1))),
        )?;
        let q = a1.move_point(&pw, -1);
        // The centre: where axes 1 and 2 meet when they do (then |q - O| = |wc - O|), else the
        // point of axis 2. The component of q - centre along k2 equals that of C - centre,
        // by theta1's equation, so the distance from axis 2 is |q - centre|.
        let centre = shoulder_centre(a1, a2);
        let delta2 = norm2(&sub(&q, &centre));
        b.push(
            2,
            sp3(a3, w, &centre, &delta2),
            Phrase::new(
                "subproblem 3 (distance): joint {1} sets the wrist centre's distance from a point \
                 of axis {0}, which joint {0} keeps",
                &[2, 3],
            ),
            Some(ELBOW),
            "elbow straight (radicand zero)",
        )?;
        let p2 = &centre;
        let x3 = a3.move_point(w, 1);
        b.push(
            1,
            sp1(a2, &sub(&x3, p2), &sub(&q, p2)),
            Phrase::new(
                "subproblem 1 (rotation): joint {0} turns the wrist centre onto the target's",
                &[2],
            ),
            None,
            Phrase::new("never (the wrist centre off axis {0})", &[2]),
        )?;
        return Ok(Some(Phrase::new("axes {0} and {1} parallel", &[2, 3])));
    }
    let shoulder = a1.kind == JointKind::Revolute
        && a2.kind == JointKind::Revolute
        && !parallel(a1, a2)
        && relation(a1, a2) == Relation::Intersecting;
    if !shoulder {
        return elbow_point(b, t, w);
    }
    let o = meet(b, a1, a2)?;
    let x3 = match a3.kind {
        JointKind::Revolute => {
            if on_line_scaled(b, &o, a3) {
                return Ok(None);
            }
            b.push(
                2,
                sp3(a3, w, &o, &norm2(&sub(&pw, &o))),
                Phrase::new(
                    "subproblem 3 (distance): joints {0} and {1} turn about the shoulder point O \
                     where axes {0} and {1} meet, so joint {2} alone sets |wc − O|",
                    &[1, 2, 3],
                ),
                Some(ELBOW),
                "elbow straight (radicand zero)",
            )?;
            a3.move_point(w, 1)
        }
        JointKind::Prismatic => {
            let v = &a3.dir;
            b.push(
                2,
                Formula::Quadratic {
                    beta: dot(v, &sub(w, &o)),
                    gamma: norm2(&sub(w, &o)) - norm2(&sub(&pw, &o)),
                },
                Phrase::new(
                    "distance: joints {0} and {1} turn about the shoulder point O, so the slide \
                     alone sets |wc − O|: |C + d v − O|² = |wc − O|²",
                    &[1, 2],
                ),
                Some(REACH),
                "the slide's line through O's nearest point (double root)",
            )?;
            a3.move_point(w, 1)
        }
    };
    let u = sub(&x3, &o);
    let v = sub(&pw, &o);
    b.push(
        1,
        sp4(&a1.dir, a2, &u, &dot(&a1.dir, &v)),
        Phrase::new(
            "subproblem 2, first half (subproblem 4): joint {0} keeps the component along axis \
             {0}, k{0}·Rot(axis {1}, theta) u = k{0}·(wc − O)",
            &[1, 2],
        ),
        Some(SHOULDER),
        Phrase::new(
            "radicand zero (left and right merge): joint {1} at the extreme of the height \
             k{0}·Rot(axis {1}, theta) u, the wrist centre as high along axis {0} as it can be",
            &[1, 2],
        ),
    )?;
    b.push(
        0,
        sp1(a1, &a2.move_dir(&u, 1), &v),
        Phrase::new(
            "subproblem 2, second half (subproblem 1): joint {0} turns the wrist centre onto the \
             target",
            &[1],
        ),
        None,
        Phrase::new(
            "the wrist centre on axis {0}: any theta{0}, 0 is returned",
            &[1],
        ),
    )?;
    let family = if a3.kind == JointKind::Revolute {
        "axes {0} and {1} intersect (shoulder point), joint {2} revolute"
    } else {
        "axes {0} and {1} intersect (shoulder point), joint {2} prismatic"
    };
    Ok(Some(Phrase::new(family, &[1, 2, 3])))
}

/// Joints 1-3 when axes 2 and 3 meet at a point Q off axis 1 (an elbow point): joints 2 and 3
/// keep Q, so joint 1 alone sets the distance of Q from the wrist centre (subproblem 3), then
/// joints 3 and 2 take the wrist centre to its place about Q (subproblem 2).
fn elbow_point(b: &mut Builder, t: &Target, w: &V3) -> Result<Option<Phrase>, PlanError> {
    let ax = b.axes;
    let (a1, a2, a3) = (&ax[0], &ax[1], &ax[2]);
    if !revolute(&ax[0..3]) || parallel(a2, a3) || relation(a2, a3) != Relation::Intersecting {
        return Ok(None);
    }
    let q0 = meet(b, a2, a3)?;
    if on_line_scaled(b, &q0, a1) || on_line_scaled(b, w, a2) {
        return Ok(None);
    }
    let pw = t.point(w);
    b.push(
        0,
        sp3(a1, &q0, &pw, &norm2(&sub(w, &q0))),
        Phrase::new(
            "subproblem 3 (distance): joints {1} and {2} turn about the elbow point Q where axes \
             {1} and {2} meet, so joint {0} alone sets the distance of Q from the wrist centre, \
             |Rot(axis {0}, theta) Q − wc| = |C − Q|",
            &[1, 2, 3],
        ),
        Some(SHOULDER),
        Phrase::new(
            "radicand zero (left and right merge): the wrist centre at its nearest or farthest \
             from the circle joint {0} turns Q on",
            &[1],
        ),
    )?;
    let q = a1.move_point(&pw, -1);
    let u = sub(w, &q0);
    let v = sub(&q, &q0);
    b.push(
        2,
        sp4(&a2.dir, a3, &u, &dot(&a2.dir, &v)),
        Phrase::new(
            "subproblem 2, first half (subproblem 4): joint {0} keeps the component along axis \
             {0}, k{0}·Rot(axis {1}, theta) (C − Q) = k{0}·(R{2}ᵀ wc − Q)",
            &[2, 3, 1],
        ),
        Some(ELBOW),
        Phrase::new(
            "radicand zero (up and down merge): joint {1} at the extreme of the height along \
             axis {0}",
            &[2, 3],
        ),
    )?;
    b.push(
        1,
        sp1(a2, &a3.move_dir(&u, 1), &v),
        Phrase::new(
            "subproblem 2, second half (subproblem 1): joint {0} turns the wrist centre onto \
             the target",
            &[2],
        ),
        None,
        Phrase::new(
            "the wrist centre on axis {0}: any theta{0}, 0 is returned",
            &[2],
        ),
    )?;
    Ok(Some(Phrase::new(
        "axes {0} and {1} intersect (elbow point), off axis {2}",
        &[2, 3, 1],
    )))
}

fn wrist_orientation(b: &mut Builder, t: &Target) -> Result<(), PlanError> {
    let ax = b.axes;
    let back = |v: &V3| -> V3 {
        let v = ax[0].move_dir(&t.dir(v), -1);
        let v = ax[1].move_dir(&v, -1);
        ax[2].move_dir(&v, -1)
    };
    let (a4, a5, a6) = (&ax[3], &ax[4], &ax[5]);
    let r6 = back(&a6.dir);
    b.push(
        4,
        sp4(&a4.dir, a5, &a6.dir, &dot(&a4.dir, &r6)),
        Phrase::new(
            "subproblem 4 (height): R{3} R{4} R{5} = R{2}ᵀ R{1}ᵀ R{0}ᵀ R; joint {3} keeps the \
             component along axis {3} and joint {5} fixes k{5}, so k{3}·Rot(axis {4}, theta) \
             k{5} = k{3}·(R{3}{4}{5} k{5})",
            &[1, 2, 3, 4, 5, 6],
        ),
        Some(WRIST),
        Phrase::new(
            "wrist singularity: axes {0} and {1} in line (radicand zero)",
            &[4, 6],
        ),
    )?;
    b.push(
        3,
        sp1(a4, &a5.move_dir(&a6.dir, 1), &r6),
        Phrase::new(
            "subproblem 1 (rotation): joint {0} turns Rot(axis {1}) k{2} onto R{0}{1}{2} k{2}",
            &[4, 5, 6],
        ),
        None,
        Phrase::new(
            "wrist singularity: axes {0} and {1} in line, only theta{0} + theta{1} is fixed; \
             theta{0} = 0 is returned",
            &[4, 6],
        ),
    )?;
    let e = perpendicular(&a6.dir);
    let v = a5.move_dir(&a4.move_dir(&back(&e), -1), -1);
    b.push(
        5,
        sp1(a6, &e, &v),
        Phrase::new(
            "subproblem 1 (rotation): joint {2} turns a vector normal to axis {2} onto R{1}ᵀ \
             R{0}ᵀ R{0}{1}{2} of it",
            &[4, 5, 6],
        ),
        None,
        "never",
    )?;
    Ok(())
}

fn three_parallel(b: &mut Builder, t: &Target) -> Result<(), PlanError> {
    let ax = b.axes;
    let x56 = intersection(&ax[4], &ax[5])
        .ok_or(PlanError::NotExact("the intersection of axes 5 and 6"))?;
    let p1 = &ax[0].point;
    let k = &ax[1].dir;
    let p56 = t.point(&x56);
    b.push(
        0,
        sp4(&sub(&p56, p1), &ax[0], k, &dot(k, &sub(&x56, p1))),
        "subproblem 4 (height): the point where axes 5 and 6 meet keeps its component along the \
         parallel axes 2, 3, 4 under joints 2-6, so (Rot(axis 1, theta) k2)·(p56 − p1) = \
         k2·(C56 − p1)"
            .into(),
        Some(SHOULDER),
        Phrase::text(
            "radicand zero (shoulder singularity, left and right merge): the point where axes 5 \
             and 6 meet at distance |k2·(C56 − p1)| = |{v}| from axis 1",
        )
        .with_value(dot(k, &sub(&x56, p1))),
    )?;
    let g6 = t.dir(&ax[5].dir);
    b.push(
        4,
        sp4(k, &ax[4], &ax[5].dir, &dot(k, &ax[0].move_dir(&g6, -1))),
        "subproblem 4 (height): R2 R3 R4 keep k2, so k2·Rot(axis 5, theta) k6 = k2·(R1ᵀ R k6)"
            .into(),
        Some(WRIST),
        "wrist singularity: axis 6 parallel to axes 2, 3, 4 (radicand zero)",
    )?;
    let u = t.dir_inv(&ax[0].move_dir(k, 1));
    let v = ax[4].move_dir(k, -1);
    b.push(
        5,
        sp1(&ax[5], &u, &v),
        "subproblem 1 (rotation): R6 (Rᵀ R1 k2) = R5ᵀ k2".into(),
        None,
        "wrist singularity: axis 6 parallel to axes 2, 3, 4; theta6 = 0 is returned",
    )?;
    let x4 = ax[3].point.clone();
    let z = ax[5].move_point(&ax[4].move_point(&x4, -1), -1);
    let q = ax[0].move_point(&t.point(&z), -1);
    elbow_steps(b, &x4, &q)?;
    let e = perpendicular(&ax[3].dir);
    let r = ax[5].move_dir(&ax[4].move_dir(&e, -1), -1);
    let r = ax[2].move_dir(&ax[1].move_dir(&ax[0].move_dir(&t.dir(&r), -1), -1), -1);
    b.push(
        3,
        sp1(&ax[3], &e, &r),
        "subproblem 1 (rotation): R4 = R3ᵀ R2ᵀ R1ᵀ R R6ᵀ R5ᵀ".into(),
        None,
        "never",
    )?;
    Ok(())
}

/// Joints 3 and 2 of an arm whose axes 2, 3 and 4 are parallel: joint 3 sets the distance of
/// axis 4 (its point `x4` at home) from the shoulder centre to that of `q`, the point where axis
/// 4 must be in joint 1's frame (`R1ᵀ` of its target place); joint 2 then turns it there.
fn elbow_steps(b: &mut Builder, x4: &V3, q: &V3) -> Result<(), PlanError> {
    let ax = b.axes;
    let centre = shoulder_centre(&ax[0], &ax[1]);
    b.push(
        2,
        sp3(&ax[2], x4, &centre, &norm2(&sub(q, &centre))),
        "subproblem 3 (distance): joint 3 sets the distance of axis 4 from a point of axis 2 \
         (their components along k2 agree by theta1's equation)"
            .into(),
        Some(ELBOW),
        "elbow straight (radicand zero)",
    )?;
    let x3 = ax[2].move_point(x4, 1);
    b.push(
        1,
        sp1(&ax[1], &sub(&x3, &centre), &sub(q, &centre)),
        "subproblem 1 (rotation): joint 2 turns axis 4 onto its target place".into(),
        None,
        "axis 4 on axis 2",
    )
}
