//! The families: exact decisions on the home-pose axes, then Paden–Kahan subproblems on the
//! exact axis data. Every step is a [`Formula`] in the target symbols, the parameters and the
//! joints solved before it.

use super::axes::{
    add, cross, dot, home_axes, intersection, is_zero3, on_line, relation, scale, sub, zero3, Axis,
    Relation, V3,
};
use super::{Formula, IkError, IkOptions, IkSolution, IkStep, TARGET_SYMBOLS};
use crate::kin::{JointKind, Robot};
use crate::{Matrix4, Scalar};

pub(crate) const FAMILIES: &str = "planar 2R (position) and 3R; SCARA-type RRPR (three parallel \
revolute axes, a prismatic joint along them); 6 joints with a spherical wrist (axes 4, 5, 6 \
through one point) and either axes 2 and 3 parallel, or axes 1 and 2 intersecting (joint 3 \
revolute or prismatic); the same read backwards (a spherical shoulder: axes 1, 2, 3 through one \
point, with axes 4 and 5 parallel or axes 5 and 6 intersecting); 6R with axes 2, 3, 4 parallel \
and axes 5 and 6 intersecting (UR type); 7 joints with one joint given by --free reducing to one of these";

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

/// A step's text written for the reversed chain (axis j' is axis n + 1 − j) in the arm's own
/// numbering: the numbers after `axis`, `axes`, `joint`, `joints` (lists joined by `, `, ` and `,
/// `-`), and the digits of `k2`, `p1`, `R4`, `R456`, `theta4` (each digit one axis).
fn renumber(text: &str, n: usize) -> String {
    let map = |d: usize| if (1..=n).contains(&d) { n + 1 - d } else { d };
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    let word_start = |i: usize| i == 0 || !chars[i - 1].is_alphanumeric();
    let starts = |i: usize, w: &str| {
        chars[i..]
            .iter()
            .take(w.chars().count())
            .copied()
            .eq(w.chars())
    };
    while i < chars.len() {
        if word_start(i) {
            if let Some(w) = ["axis ", "axes ", "joint ", "joints "]
                .into_iter()
                .find(|w| starts(i, w))
            {
                out.push_str(w);
                i += w.len();
                // A list of numbers: 1, 2 and 3; 2-6.
                loop {
                    let j = i;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                    if i == j {
                        break;
                    }
                    let d: String = chars[j..i].iter().collect();
                    out.push_str(&d.parse().map_or(d.clone(), |d| map(d).to_string()));
                    let sep = [", ", " and ", "-"].into_iter().find(|sep| {
                        starts(i, sep) && chars.get(i + sep.len()).is_some_and(char::is_ascii_digit)
                    });
                    match sep {
                        Some(sep) => {
                            out.push_str(sep);
                            i += sep.len();
                        }
                        None => break,
                    }
                }
                continue;
            }
            if let Some(w) = ["theta", "k", "p", "R"]
                .into_iter()
                .find(|w| starts(i, w) && chars.get(i + w.len()).is_some_and(char::is_ascii_digit))
            {
                out.push_str(w);
                i += w.len();
                while i < chars.len() && chars[i].is_ascii_digit() {
                    let d = chars[i].to_digit(10).unwrap_or(0) as usize;
                    out.push_str(&map(d).to_string());
                    i += 1;
                }
                continue;
            }
        }
        out.push(chars[i]);
        i += 1;
    }
    out
}

struct Builder<'a> {
    axes: &'a [Axis],
    steps: Vec<IkStep>,
}

const SHOULDER: (&str, &str, &str) = ("shoulder", "left", "right");
const ELBOW: (&str, &str, &str) = ("elbow", "up", "down");
const WRIST: (&str, &str, &str) = ("wrist", "no flip", "flip");
const REACH: (&str, &str, &str) = ("reach", "far", "near");

impl Builder<'_> {
    fn push(
        &mut self,
        j: usize,
        formula: Formula,
        method: String,
        branch: Option<(&str, &str, &str)>,
        singular: &str,
    ) -> Result<(), String> {
        let degenerate = match &formula {
            Formula::Atan2 { y, x } => y.is_zero_value() && x.is_zero_value(),
            Formula::Trig { a, b, .. } => a.is_zero_value() && b.is_zero_value(),
            _ => false,
        };
        let all = match &formula {
            Formula::Atan2 { y, x } => vec![y, x],
            Formula::Trig { a, b, c } => vec![a, b, c],
            Formula::Value { v } => vec![v],
            Formula::Quadratic { beta, gamma } => vec![beta, gamma],
        };
        if let Some(e) = all.iter().find_map(|x| x.as_error()) {
            return Err(format!("scalar: {e}"));
        }
        if degenerate {
            return Err(format!(
                "the subproblem for {} is degenerate for every target ({method})",
                self.axes[j].variable
            ));
        }
        let branch = if formula.branches() == 2 {
            branch.map(|(n, p, m)| (n.to_string(), p.to_string(), m.to_string()))
        } else {
            None
        };
        self.steps.push(IkStep {
            joint: j,
            variable: self.axes[j].variable.clone(),
            formula,
            method,
            branch,
            singular: singular.to_string(),
        });
        Ok(())
    }
}

fn name(i: usize) -> usize {
    i + 1
}

/// A scalar in closed form, plain text.
fn scalar_text(x: &Scalar) -> String {
    crate::closed_form(x)
        .map(|e| crate::plain(&e, &crate::PlainOptions::default()))
        .unwrap_or_else(|_| x.to_string())
}

fn rel_text(rel: &Relation) -> String {
    match rel {
        Relation::Parallel { same_line: true } => "coincide".into(),
        Relation::Parallel { .. } => "are parallel".into(),
        Relation::Intersecting => "intersect".into(),
        Relation::Skew => "are skew (neither parallel nor intersecting)".into(),
        Relation::SkewUnless(r) => format!(
            "are skew unless {} = 0 (their reciprocal product)",
            crate::closed_form(r)
                .map(|e| crate::plain(&e, &crate::PlainOptions::default()))
                .unwrap_or_else(|_| r.to_string())
        ),
    }
}

fn geometry_lines(axes: &[Axis]) -> Vec<String> {
    let mut out = Vec::new();
    let kinds: Vec<&str> = axes
        .iter()
        .map(|a| match a.kind {
            JointKind::Revolute => "R",
            JointKind::Prismatic => "P",
        })
        .collect();
    out.push(format!("joints: {} ({})", kinds.concat(), axes.len()));
    for i in 0..axes.len() {
        for j in i + 1..axes.len().min(i + 3) {
            if axes[i].kind == JointKind::Prismatic || axes[j].kind == JointKind::Prismatic {
                let par = is_zero3(&cross(&axes[i].dir, &axes[j].dir));
                out.push(format!(
                    "axes {} and {}: directions {}",
                    name(i),
                    name(j),
                    if par { "parallel" } else { "not parallel" }
                ));
                continue;
            }
            out.push(format!(
                "axes {} and {} {}",
                name(i),
                name(j),
                rel_text(&relation(&axes[i], &axes[j]))
            ));
        }
    }
    let n = axes.len();
    if n >= 3 {
        let w = common_point(&axes[n - 3..]);
        out.push(format!(
            "axes {}, {}, {} through one point (spherical wrist): {}",
            n - 2,
            n - 1,
            n,
            if w.is_some() { "yes" } else { "no" }
        ));
    }
    out
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
/// first joint whose value as a parameter leaves a supported family (said in the geometry); a
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
        let o = IkOptions {
            free: Some(v.clone()),
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
            for v in variables {
                match try_free(v) {
                    Ok(mut sol) => {
                        sol.geometry.insert(
                            0,
                            format!(
                                "7 joints, no --free given: {v} chosen as the free joint (a \
                                 parameter), the first joint whose value leaves a supported family"
                            ),
                        );
                        return Ok(sol);
                    }
                    Err(IkError::Unsupported { .. }) => {}
                    Err(e) => return Err(e),
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
    for row in TARGET_SYMBOLS {
        for s in row {
            if variables.iter().any(|v| v == s) || params.iter().any(|v| v == s) {
                return Err(IkError::Option(format!(
                    "the robot uses the name `{s}`, which ik keeps for the target pose"
                )));
            }
        }
    }
    if let Some(f) = &opts.free {
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
        home = Matrix4::from_rows(rows);
        axes.remove(k);
        params.push(f.clone());
        params.sort();
    }
    let mut geometry = geometry_lines(&axes);
    if opts.free.is_some() {
        geometry.insert(
            0,
            format!(
                "axes numbered without the free joint: {}",
                axes.iter()
                    .enumerate()
                    .map(|(i, a)| format!("{} = {}", i + 1, a.variable))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        );
    }
    let target = Target::new(&home);
    let mut b = Builder {
        axes: &axes,
        steps: Vec::new(),
    };
    let attempt = family(&mut b, &target);
    let unsupported = |why: Option<String>| IkError::Unsupported {
        robot: name.to_string(),
        geometry: {
            let mut g = geometry.clone();
            if let Some(w) = why {
                g.push(w);
            }
            g.iter()
                .map(|l| format!("  {l}"))
                .collect::<Vec<_>>()
                .join("\n")
        },
        families: FAMILIES.into(),
    };
    let (family, position_only) = match attempt {
        Ok(Some(f)) => f,
        Ok(None) => return Err(unsupported(None)),
        Err(m) if m.starts_with("scalar: ") => return Err(IkError::Scalar(m[8..].to_string())),
        Err(m) => return Err(unsupported(Some(m))),
    };
    let mut conditions = Vec::new();
    for s in &b.steps {
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
    let steps = b.steps;
    let variables = variables
        .iter()
        .filter(|v| Some(*v) != opts.free.as_ref())
        .cloned()
        .collect();
    Ok(IkSolution {
        robot: name.to_string(),
        family,
        geometry,
        conditions,
        steps,
        variables,
        params,
        free: opts.free.clone(),
        position_only,
        home,
        axes,
        forms: std::sync::OnceLock::new(),
        degrees: std::sync::OnceLock::new(),
    })
}

/// Tries every family in turn; `Ok(None)` when none applies.
fn family(b: &mut Builder, t: &Target) -> Result<Option<(String, bool)>, String> {
    let ax = b.axes;
    let n = ax.len();
    if (n == 2 || n == 3) && revolute(ax) && ax.iter().all(|a| parallel(a, &ax[0])) {
        planar(b, t)?;
        return Ok(Some((format!("planar {n}R"), n == 2)));
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
    if n != 6 {
        return Ok(None);
    }
    if let Some(w) = common_point(&ax[3..6]) {
        if !parallel(&ax[3], &ax[4]) && !parallel(&ax[4], &ax[5]) {
            if let Some(pos) = spherical_position(b, t, &w)? {
                wrist_orientation(b, t)?;
                return Ok(Some((
                    format!("6 joints with a spherical wrist (Pieper): {pos}"),
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
            };
            if let Some(pos) = spherical_position(&mut rb, &tr, &o)? {
                wrist_orientation(&mut rb, &tr)?;
                for mut s in rb.steps {
                    s.joint = n - 1 - s.joint;
                    s.method = format!("chain reversed: {}", renumber(&s.method, n));
                    s.singular = format!("chain reversed: {}", renumber(&s.singular, n));
                    // The reversed chain's shoulder is the arm's wrist and the other way round.
                    if let Some(br) = &mut s.branch {
                        br.0 = match br.0.as_str() {
                            "shoulder" => "wrist".into(),
                            "wrist" => {
                                // Axes 4' and 6' are axes 3 and 1.
                                s.singular = "shoulder singularity (radicand zero, the two \
                                              branches merge): axes 1 and 3 in line"
                                    .into();
                                "shoulder".into()
                            }
                            x => x.into(),
                        };
                    }
                    b.steps.push(s);
                }
                return Ok(Some((
                    format!(
                        "6 joints with a spherical shoulder (axes 1, 2, 3 through one point): \
                         the chain reversed, G⁻¹ = E6⁻¹ ⋯ E1⁻¹ about the reversed axes \
                         1' = 6, ..., 6' = 1, is a spherical-wrist arm (Pieper); in the arm's own \
                         numbering: {}",
                        renumber(&pos, n)
                    ),
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
    Ok(None)
}

fn planar(b: &mut Builder, t: &Target) -> Result<(), String> {
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
        format!(
            "subproblem 3 (distance): joint 2 turns the {} about axis 2; its distance to axis 1 \
             must equal the target's",
            if n == 2 {
                "tool point"
            } else {
                "point of axis 3"
            }
        ),
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

fn scara(b: &mut Builder, t: &Target) -> Result<(), String> {
    let ax = b.axes;
    let w = ax[0].dir.clone();
    let x4 = ax[3].point.clone();
    let g4 = t.point(&x4);
    let wv = dot(&w, &ax[2].dir);
    let d = dot(&w, &sub(&g4, &x4))
        .try_div(&wv)
        .map_err(|e| format!("scalar: {e}"))?;
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
fn spherical_position(b: &mut Builder, t: &Target, w: &V3) -> Result<Option<String>, String> {
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
            "subproblem 4 (height): rotations about the parallel axes 2 and 3 keep the wrist \
             centre's component along them, so (Rot(axis 1, theta) k2)·(wc − p1) = k2·(C − p1)"
                .into(),
            Some(SHOULDER),
            &format!(
                "radicand zero (shoulder singularity, left and right merge): the wrist centre's \
                 distance from axis 1 equals the shoulder offset |k2·(C − p1)| = |{}| (the \
                 wrist centre on axis 1 when it is 0)",
                scalar_text(&dot(&a2.dir, &sub(w, p1)))
            ),
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
            "subproblem 3 (distance): joint 3 sets the wrist centre's distance from a point of \
             axis 2, which joint 2 keeps"
                .into(),
            Some(ELBOW),
            "elbow straight (radicand zero)",
        )?;
        let p2 = &centre;
        let x3 = a3.move_point(w, 1);
        b.push(
            1,
            sp1(a2, &sub(&x3, p2), &sub(&q, p2)),
            "subproblem 1 (rotation): joint 2 turns the wrist centre onto the target's".into(),
            None,
            "never (the wrist centre off axis 2)",
        )?;
        return Ok(Some("axes 2 and 3 parallel".into()));
    }
    if a1.kind != JointKind::Revolute
        || a2.kind != JointKind::Revolute
        || parallel(a1, a2)
        || relation(a1, a2) != Relation::Intersecting
    {
        return Ok(None);
    }
    let o = intersection(a1, a2).ok_or("the intersection of axes 1 and 2 is not exact")?;
    let x3 = match a3.kind {
        JointKind::Revolute => {
            if on_line(&o, a3) {
                return Ok(None);
            }
            b.push(
                2,
                sp3(a3, w, &o, &norm2(&sub(&pw, &o))),
                "subproblem 3 (distance): joints 1 and 2 turn about the shoulder point O where \
                 axes 1 and 2 meet, so joint 3 alone sets |wc − O|"
                    .into(),
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
                "distance: joints 1 and 2 turn about the shoulder point O, so the slide alone \
                 sets |wc − O|: |C + d v − O|² = |wc − O|²"
                    .into(),
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
        "subproblem 2, first half (subproblem 4): joint 1 keeps the component along axis 1, \
         k1·Rot(axis 2, theta) u = k1·(wc − O)"
            .into(),
        Some(SHOULDER),
        "radicand zero (left and right merge): joint 2 at the extreme of the height \
         k1·Rot(axis 2, theta) u, the wrist centre as high along axis 1 as it can be",
    )?;
    b.push(
        0,
        sp1(a1, &a2.move_dir(&u, 1), &v),
        "subproblem 2, second half (subproblem 1): joint 1 turns the wrist centre onto the target"
            .into(),
        None,
        "the wrist centre on axis 1: any theta1, 0 is returned",
    )?;
    Ok(Some(format!(
        "axes 1 and 2 intersect (shoulder point), joint 3 {}",
        if a3.kind == JointKind::Revolute {
            "revolute"
        } else {
            "prismatic"
        }
    )))
}

fn wrist_orientation(b: &mut Builder, t: &Target) -> Result<(), String> {
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
        "subproblem 4 (height): R4 R5 R6 = R3ᵀ R2ᵀ R1ᵀ R; joint 4 keeps the component along \
         axis 4 and joint 6 fixes k6, so k4·Rot(axis 5, theta) k6 = k4·(R456 k6)"
            .into(),
        Some(WRIST),
        "wrist singularity: axes 4 and 6 in line (radicand zero)",
    )?;
    b.push(
        3,
        sp1(a4, &a5.move_dir(&a6.dir, 1), &r6),
        "subproblem 1 (rotation): joint 4 turns Rot(axis 5) k6 onto R456 k6".into(),
        None,
        "wrist singularity: axes 4 and 6 in line, only theta4 + theta6 is fixed; theta4 = 0 \
         is returned",
    )?;
    let e = perpendicular(&a6.dir);
    let v = a5.move_dir(&a4.move_dir(&back(&e), -1), -1);
    b.push(
        5,
        sp1(a6, &e, &v),
        "subproblem 1 (rotation): joint 6 turns a vector normal to axis 6 onto R5ᵀ R4ᵀ R456 \
         of it"
            .into(),
        None,
        "never",
    )?;
    Ok(())
}

fn three_parallel(b: &mut Builder, t: &Target) -> Result<(), String> {
    let ax = b.axes;
    let x56 = intersection(&ax[4], &ax[5]).ok_or("the intersection of axes 5 and 6")?;
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
        &format!(
            "radicand zero (shoulder singularity, left and right merge): the point where axes 5 \
             and 6 meet at distance |k2·(C56 − p1)| = |{}| from axis 1",
            scalar_text(&dot(k, &sub(&x56, p1)))
        ),
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
    let centre = shoulder_centre(&ax[0], &ax[1]);
    let p2 = &centre;
    let delta2 = norm2(&sub(&q, p2));
    b.push(
        2,
        sp3(&ax[2], &x4, p2, &delta2),
        "subproblem 3 (distance): joint 3 sets the distance of axis 4 from a point of axis 2 \
         (their components along k2 agree by theta1's equation)"
            .into(),
        Some(ELBOW),
        "elbow straight (radicand zero)",
    )?;
    let x3 = ax[2].move_point(&x4, 1);
    b.push(
        1,
        sp1(&ax[1], &sub(&x3, p2), &sub(&q, p2)),
        "subproblem 1 (rotation): joint 2 turns axis 4 onto its target place".into(),
        None,
        "axis 4 on axis 2",
    )?;
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
