//! Closed-form inverse kinematics (`dqsym ik`).
//!
//! The joint axes are read from the chain as exact Plücker lines in the home pose
//! ([`axes::home_axes`]), so dh, mdh and screw files all become one product of exponentials
//! `FK(q) = E1(q1) ... En(qn) M`. Exact decisions on the axes (parallel, intersecting, a common
//! point) choose a family; each family is a sequence of Paden–Kahan subproblems on the exact
//! axis data, and every joint comes out as one of four closed forms ([`Formula`]) whose
//! coefficients are exact scalars in the target pose (`r11 ... r33`, `px`, `py`, `pz`), the
//! robot's parameters and the joints solved before it (`c1`, `s23`, ...).

pub mod axes;
pub mod check;
mod emit;
pub mod general;
mod plan;
mod report;
mod safe;

pub use axes::{home_axes, intersection, relation, Axis, Relation, V3};
pub use emit::{ik_c, ik_javascript_helpers, ik_python, ik_rust, ik_step_degrees};
pub use general::emit::ik_javascript_general;
pub use report::ik_report;

use crate::kin::Robot;
use crate::{Matrix4, Scalar, ScalarError};
use thiserror::Error;

/// The names of the target pose's entries: `T = [[r11 r12 r13 px] [r21 r22 r23 py] [r31 r32 r33
/// pz] [0 0 0 1]]`.
pub const TARGET_SYMBOLS: [[&str; 4]; 3] = [
    ["r11", "r12", "r13", "px"],
    ["r21", "r22", "r23", "py"],
    ["r31", "r32", "r33", "pz"],
];

/// Why no closed-form solver was derived.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum IkError {
    /// The axes' geometry is not one of the supported families.
    #[error("{}: no closed-form inverse kinematics for this geometry.\n{geometry}\nSupported families: {families}", crate::emit::names::printable(robot))]
    Unsupported {
        /// The robot's name.
        robot: String,
        /// What was found, axis pair by axis pair.
        geometry: String,
        /// The families supported.
        families: String,
    },
    /// A bad option (`--free`) or a name clash.
    #[error("{0}")]
    Option(String),
    /// An exact computation failed (term limit, work budget): the limit with the option that
    /// raises it, never taken for a property of the geometry.
    #[error(transparent)]
    Scalar(#[from] ScalarError),
}

/// Why the numeric reference solver ([`IkSolution::solve_numeric`]) gave no solutions.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum NumericError {
    /// A parameter of the solution has no value.
    #[error("no value for parameter `{0}`")]
    MissingParameter(String),
    /// An exact computation or an evaluation failed.
    #[error(transparent)]
    Scalar(#[from] ScalarError),
    /// The general method's solver failed.
    #[error(transparent)]
    General(#[from] general::GeneralError),
}

/// Which method derives the solver.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum IkMethod {
    /// A special family when one applies, else the general 6R elimination ([`general`]).
    #[default]
    Auto,
    /// The special families only (a geometry outside them is an error naming it).
    Family,
    /// The general 6R elimination, even where a family applies.
    General,
}

impl IkMethod {
    /// `auto`, `family` or `general`.
    pub fn parse(s: &str) -> Option<IkMethod> {
        match s {
            "auto" => Some(IkMethod::Auto),
            "family" => Some(IkMethod::Family),
            "general" => Some(IkMethod::General),
            _ => None,
        }
    }
}

/// What to derive.
#[derive(Clone, Debug, Default)]
pub struct IkOptions {
    /// A joint variable given as a parameter (a 7-joint arm becomes a 6-joint one).
    pub free: Option<String>,
    /// The method.
    pub method: IkMethod,
}

/// One joint's closed form.
#[derive(Clone, Debug)]
pub enum Formula {
    /// `q = atan2(y, x)`; singular where `x = y = 0` (any value, 0 is returned).
    Atan2 {
        /// Numerator-side argument.
        y: Scalar,
        /// Denominator-side argument.
        x: Scalar,
    },
    /// `a cos q + b sin q = c`: `q = atan2(b, a) ± atan2(sqrt(a² + b² − c²), c)`; exists where
    /// the radicand is non-negative, singular where it is zero or `a = b = 0`.
    Trig {
        /// Coefficient of `cos q`.
        a: Scalar,
        /// Coefficient of `sin q`.
        b: Scalar,
        /// Right-hand side.
        c: Scalar,
    },
    /// `q = v` (a prismatic joint read off linearly).
    Value {
        /// The value.
        v: Scalar,
    },
    /// `a q = b`: `q = b / a`, a prismatic joint's length from a linear equation whose
    /// coefficient varies with the joints solved before it (Cramer's rule for several slides
    /// at once). `a` is dimensionless and `b` a length (the step's degree in lengths is `b`'s,
    /// 1): singular where `a = 0` (the slides' directions fail to span; `b / a` is kept while
    /// `a ≠ 0`, else 0).
    Linear {
        /// The coefficient of `q`.
        a: Scalar,
        /// The right-hand side.
        b: Scalar,
    },
    /// `q² + 2 β q + γ = 0`: `q = −β ± sqrt(β² − γ)`.
    Quadratic {
        /// Half the linear coefficient.
        beta: Scalar,
        /// The constant term.
        gamma: Scalar,
    },
}

impl Formula {
    /// How many branches (1 or 2).
    pub fn branches(&self) -> usize {
        match self {
            Formula::Trig { .. } | Formula::Quadratic { .. } => 2,
            _ => 1,
        }
    }
}

/// One step of a derivation: which joint, how, and what it means.
#[derive(Clone, Debug)]
pub struct IkStep {
    /// Index of the joint among the solved variables (0-based; the free joint excluded).
    pub joint: usize,
    /// The joint variable.
    pub variable: String,
    /// The closed form.
    pub formula: Formula,
    /// The subproblem and the identity it uses.
    pub method: Phrase,
    /// The branch's name and the names of its `+` and `−` signs (shoulder left/right, ...).
    pub branch: Option<Branch>,
    /// Where the step is singular.
    pub singular: Phrase,
}

/// A sentence of a derivation whose joint numbers are data: `{0}`, `{1}`, ... in `template`
/// stand for the numbers in `axes` (1-based, among the solved joints), `{v}` for the closed
/// form of `value`, `{p}` for the phrase `inner`. A step derived on the reversed chain maps its
/// numbers ([`Phrase::renumbered`]) instead of rewriting words; `ik/report.rs` writes it out
/// (`Display`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Phrase {
    /// The words with their placeholders.
    pub template: &'static str,
    /// The joint numbers of the placeholders `{0}`, `{1}`, ...
    pub axes: Vec<usize>,
    /// The value of `{v}`.
    pub value: Option<Scalar>,
    /// The phrase of `{p}`.
    pub inner: Option<Box<Phrase>>,
    /// Derived on the chain read backwards (written with the prefix `chain reversed: `).
    pub reversed: bool,
}

impl Phrase {
    /// A phrase with the joint numbers `axes`.
    pub fn new(template: &'static str, axes: &[usize]) -> Phrase {
        Phrase {
            template,
            axes: axes.to_vec(),
            value: None,
            inner: None,
            reversed: false,
        }
    }

    /// Fixed words.
    pub fn text(template: &'static str) -> Phrase {
        Phrase::new(template, &[])
    }

    /// With the value of `{v}`.
    pub fn with_value(mut self, v: Scalar) -> Phrase {
        self.value = Some(v);
        self
    }

    /// With the phrase of `{p}`.
    pub fn with_inner(mut self, p: Phrase) -> Phrase {
        self.inner = Some(Box::new(p));
        self
    }

    /// The phrase of a chain of `n` joints read backwards in the arm's own numbering: joint
    /// `j` of the reversed chain is joint `n + 1 − j`.
    pub fn renumbered(mut self, n: usize) -> Phrase {
        for a in &mut self.axes {
            if (1..=n).contains(a) {
                *a = n + 1 - *a;
            }
        }
        self.inner = self.inner.map(|p| Box::new(p.renumbered(n)));
        self
    }
}

impl From<&'static str> for Phrase {
    fn from(t: &'static str) -> Phrase {
        Phrase::text(t)
    }
}

/// A fact about the axes, decided exactly; axes numbered from 1 among the solved joints.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Fact {
    /// The joints' kinds in order.
    Joints(Vec<crate::kin::JointKind>),
    /// How two revolute axes lie.
    Pair {
        /// The two axes.
        axes: [usize; 2],
        /// Their relation.
        relation: Relation,
    },
    /// Two axes of which one slides: whether their directions are parallel.
    Directions {
        /// The two axes.
        axes: [usize; 2],
        /// Parallel directions.
        parallel: bool,
    },
    /// Whether the last three axes pass through one point (a spherical wrist).
    SphericalWrist {
        /// The three axes.
        axes: [usize; 3],
        /// They do.
        yes: bool,
    },
    /// The solved joints' variables in order, the free joint left out.
    Numbering(Vec<String>),
    /// The free joint chosen for a 7-joint arm without `--free`.
    FreeChosen {
        /// Its variable.
        variable: String,
        /// Why this one.
        which: FreeChoice,
    },
}

/// Which free joint was chosen: end joints are preferred.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum FreeChoice {
    /// The first joint.
    First,
    /// The last joint (the first leaves no family).
    Last,
    /// An inner joint (neither end joint leaves a family).
    Inner,
}

/// Which part of the arm a two-branch step chooses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BranchPart {
    /// The shoulder.
    Shoulder,
    /// The elbow.
    Elbow,
    /// The wrist.
    Wrist,
    /// The reach of a slide (far or near).
    Reach,
}

/// The names of a branch's `+` and `−` signs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BranchSigns {
    /// Left, right.
    LeftRight,
    /// Up, down.
    UpDown,
    /// No flip, flip.
    NoFlipFlip,
    /// Far, near.
    FarNear,
}

/// A two-branch step's branch: the part it chooses and the names of its signs (a reversed
/// chain's shoulder is the arm's wrist, with the shoulder's sign names).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Branch {
    /// The part.
    pub part: BranchPart,
    /// The signs' names.
    pub signs: BranchSigns,
}

/// A derived closed-form inverse kinematics.
#[derive(Clone, Debug)]
pub struct IkSolution {
    /// The robot's name.
    pub robot: String,
    /// The family found.
    pub family: Phrase,
    /// The geometry facts decided (the report writes one line each).
    pub geometry: Vec<Fact>,
    /// Conditions the derivation assumes on the parameters.
    pub conditions: Vec<String>,
    /// The joints in the order they are solved.
    pub steps: Vec<IkStep>,
    /// The joint variables solved, in joint order.
    pub variables: Vec<String>,
    /// The robot's parameters (and the free joint), sorted.
    pub params: Vec<String>,
    /// The free joint, when one was given.
    pub free: Option<String>,
    /// Only the position of the end effector is solved for (planar 2R).
    pub position_only: bool,
    /// The part of the target pose the arm controls (all of it for six joints).
    pub reach: Reach,
    /// The home pose `M` of the end effector.
    pub home: Matrix4<Scalar>,
    /// The frame solved for: the end `fk` reports.
    pub end: EndFrame,
    /// The solved joints' axes in the home pose, in joint order (`FK = E1 ⋯ En M`): what the
    /// solvers check their solutions with.
    pub axes: Vec<Axis>,
    /// Solved by the general 6R elimination (no steps): what it found at a generic target.
    pub general: Option<general::GeneralInfo>,
    /// The closed forms of every step's parts, computed on first use.
    pub(crate) forms: std::sync::OnceLock<Result<Vec<Parts>, ScalarError>>,
    /// Each step's degree in lengths (`check::step_degrees`), computed on first use.
    pub(crate) degrees: std::sync::OnceLock<Result<Vec<i32>, ScalarError>>,
}

/// The part of a target pose an arm with fewer than six joints controls; the rest of the
/// target must agree with the arm (a pose `fk` gives), else the solutions reproduce only this
/// part.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Reach {
    /// The whole pose.
    #[default]
    Pose,
    /// The position of the end frame's origin (planar 2R).
    Position,
    /// The position and one angle: the rotation about the parallel axes `axes` (numbered from
    /// 1 among the solved joints) after the first joint's turn, `R = Rot(axis 1) Rot(k, φ)`.
    PositionAndAngle {
        /// The parallel axes.
        axes: Vec<usize>,
    },
    /// The position and the approach axis: the direction `approach` of the end frame (in its
    /// own coordinates, `T · approach`); the turn about it is not controlled.
    PositionAndApproach {
        /// The approach direction in the end frame.
        approach: [Scalar; 3],
    },
}

/// The frame `ik` solves for, the same `fk` reports as the end: the base frames, the joints,
/// the tool frames and the tool point, in this order (the report states the parts present).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct EndFrame {
    /// Constant frames before the first joint (`[base]`).
    pub base_frames: usize,
    /// Constant frames after the last joint (`[tool]`, or a URDF tip's joint origins).
    pub tool_frames: usize,
    /// The tool point in the last frame (`tool = [x, y, z]`): the end frame's origin, with the
    /// last frame's axes.
    pub tool_point: Option<[Scalar; 3]>,
}

impl EndFrame {
    /// The end frame of `robot`, as `fk` reads it.
    pub fn of(robot: &Robot) -> EndFrame {
        EndFrame {
            base_frames: robot.base_frames.len(),
            tool_frames: robot.tool_frames.len(),
            tool_point: robot.tool.clone(),
        }
    }

    /// Only the joints' own frames: nothing to state.
    pub fn is_plain(&self) -> bool {
        *self == EndFrame::default()
    }
}

type Parts = Vec<(&'static str, crate::Expr)>;

/// Derives the closed-form inverse kinematics of `robot`.
///
/// # Errors
/// [`IkError::Unsupported`] naming the geometry found when no family applies;
/// [`IkError::Option`] for a bad `--free`; [`IkError::Scalar`] when a limit is reached.
pub fn solve(robot: &Robot, opts: &IkOptions) -> Result<IkSolution, IkError> {
    let end = EndFrame::of(robot);
    let mut sol = solve_end(&with_tool_point(robot), opts)?;
    sol.end = end;
    Ok(sol)
}

/// `robot` with its tool point (if any) folded into the tool motion: the end frame `fk` maps
/// the point with is `forward · Trans(p)`, the last frame moved to the point.
pub(crate) fn with_tool_point(robot: &Robot) -> std::borrow::Cow<'_, Robot> {
    let Some(p) = &robot.tool else {
        return std::borrow::Cow::Borrowed(robot);
    };
    let mut r = robot.clone();
    r.chain.tool = &r.chain.tool * &crate::DualQuat::translation(p);
    r.tool = None;
    std::borrow::Cow::Owned(r)
}

fn solve_end(robot: &Robot, opts: &IkOptions) -> Result<IkSolution, IkError> {
    // A base frame, or joints coupled to another's variable (URDF mimic joints), leave the
    // joints' own geometry: the axes are read from the whole pose instead.
    let plain = robot.chain.base == crate::DualQuat::identity()
        && robot.joint_values.len() == robot.variables.len()
        && robot
            .joint_values
            .iter()
            .zip(&robot.variables)
            .all(|(x, v)| *x == Scalar::sym(v));
    if !plain {
        return solve_dq(&robot.name, &robot.forward(), &robot.variables, opts);
    }
    plan::derive(robot, opts)
}

/// Derives the closed-form inverse kinematics of a chain given as one symbolic unit DQ
/// `q(vars)` (a product of joint motions, as built in the language), named `name`.
///
/// # Errors
/// As [`solve`]; [`IkError::Option`] when a variable's derivative is not a joint axis.
pub fn solve_dq(
    name: &str,
    q: &crate::DualQuat<Scalar>,
    variables: &[String],
    opts: &IkOptions,
) -> Result<IkSolution, IkError> {
    let (axes, home) = axes::dq_axes_checked(q, variables)?.ok_or_else(|| {
        IkError::Option(format!(
            "{name}: not a product of joint motions in {} (each variable must turn about or \
             slide along one line)",
            variables.join(", ")
        ))
    })?;
    let mut params: Vec<String> = q
        .components()
        .iter()
        .flat_map(|c| c.symbols())
        .filter(|s| !s.is_pi())
        .map(|s| s.name().to_string())
        .filter(|n| !variables.contains(n))
        .collect();
    params.sort();
    params.dedup();
    plan::derive_axes(name, variables, params, axes, home, opts)
}

/// One numeric solution.
#[derive(Clone, Debug, PartialEq)]
pub struct NumSolution {
    /// Joint values in joint order (the free joint excluded).
    pub q: Vec<f64>,
    /// A singular set was met (a joint chosen on it, or a double root).
    pub singular: bool,
    /// The solution does not reproduce the target to [`check::POSE_TOL`] (a target out of
    /// reach: the closest reach); its residual says by how much.
    pub approximate: bool,
    /// The largest deviation of the solution's pose from the target (positions over the
    /// robot's scale) where it was checked by forward kinematics; 0 where every step was
    /// well-conditioned (exact to rounding, not checked).
    pub residual: f64,
}

impl IkSolution {
    /// How far the pose `got` is from `target` (row-major 4x4 matrices) in what the solution
    /// controls ([`IkSolution::reach`]): the largest difference of a position entry or of an
    /// entry of the rotation (all of it, or the approach direction's image), absolute.
    pub fn deviation(&self, target: &[[f64; 4]; 4], got: &[[f64; 4]; 4]) -> f64 {
        let mut dev: f64 = (0..3)
            .map(|r| (target[r][3] - got[r][3]).abs())
            .fold(0.0, f64::max);
        match &self.reach {
            Reach::Position => {}
            Reach::PositionAndApproach { approach } => {
                let a: Vec<f64> = approach
                    .iter()
                    .map(|x| x.eval(&|_| None).unwrap_or(f64::NAN))
                    .collect();
                let norm = a.iter().map(|x| x * x).sum::<f64>().sqrt();
                for r in 0..3 {
                    let image = |m: &[[f64; 4]; 4]| (0..3).map(|k| m[r][k] * a[k]).sum::<f64>();
                    dev = dev.max((image(target) - image(got)).abs() / norm);
                }
            }
            _ => {
                for r in 0..3 {
                    for c in 0..3 {
                        dev = dev.max((target[r][c] - got[r][c]).abs());
                    }
                }
            }
        }
        dev
    }

    /// The closed forms of every step's parts (`a`, `b`, `c`; `y`, `x`; ...), computed once.
    ///
    /// # Errors
    /// A closed form that fails (term limit, work budget).
    pub fn forms(&self) -> Result<&[Vec<(&'static str, crate::Expr)>], ScalarError> {
        self.forms
            .get_or_init(|| {
                self.steps
                    .iter()
                    .map(|s| report::parts(&s.formula))
                    .collect()
            })
            .as_ref()
            .map(|v| v.as_slice())
            .map_err(Clone::clone)
    }

    /// Each step's degree in lengths, computed once.
    ///
    /// # Errors
    /// A closed form that fails.
    pub fn degrees(&self) -> Result<&[i32], ScalarError> {
        self.degrees
            .get_or_init(|| check::step_degrees(self))
            .as_ref()
            .map(|v| v.as_slice())
            .map_err(Clone::clone)
    }

    /// Every solution for a numeric target pose (row-major 4x4), the parameters given by name.
    /// Evaluates the exact formulas in f64 (the reference the generated code is checked
    /// against), with the tolerances, checks and refinement of [`check`].
    ///
    /// # Errors
    /// A parameter without a value.
    pub fn solve_numeric(
        &self,
        target: &[[f64; 4]; 4],
        params: &[(&str, f64)],
    ) -> Result<Vec<NumSolution>, NumericError> {
        for p in &self.params {
            if !params.iter().any(|(n, _)| n == p) {
                return Err(NumericError::MissingParameter(p.clone()));
            }
        }
        if self.general.is_some() {
            return general::solve_numeric(self, target, params);
        }
        let mut env: Vec<(String, f64)> = params.iter().map(|(n, v)| (n.to_string(), *v)).collect();
        let (axes, home) =
            check::axis_data(self, &|n| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))?;
        let len = check::scale(&axes, &home, target);
        for (r, row) in TARGET_SYMBOLS.iter().enumerate() {
            for (c, name) in row.iter().enumerate() {
                env.push((name.to_string(), target[r][c]));
            }
        }
        let sigma: Vec<f64> = self
            .degrees()?
            .iter()
            .map(|d| check::ZERO_TOL * len.powi(*d))
            .collect();
        let mut b = Branching {
            sol: self,
            sigma,
            env,
            q: vec![0.0; self.variables.len()],
            out: Vec::new(),
            axes,
            home,
            target: *target,
            len,
        };
        b.branch(0, (false, false, false))?;
        Ok(b.out)
    }
}

/// The reference solver's walk through the branches.
struct Branching<'a> {
    sol: &'a IkSolution,
    sigma: Vec<f64>,
    env: Vec<(String, f64)>,
    q: Vec<f64>,
    out: Vec<NumSolution>,
    axes: Vec<check::AxisData>,
    home: [[f64; 4]; 3],
    target: [[f64; 4]; 4],
    len: f64,
}

impl Branching<'_> {
    /// Step `k` on; `flags` are (singular, checked, sampled) of the steps before.
    fn branch(&mut self, k: usize, flags: (bool, bool, bool)) -> Result<(), ScalarError> {
        let Some(step) = self.sol.steps.get(k) else {
            self.finish(flags);
            return Ok(());
        };
        let forms = self.sol.forms()?;
        let mut vals = [0.0; 3];
        for (i, (_, e)) in forms[k].iter().enumerate() {
            let env = &self.env;
            vals[i] = e
                .eval_f64(&|s: &crate::Sym| {
                    if s.is_pi() {
                        return std::f64::consts::PI;
                    }
                    let n = s.name();
                    env.iter()
                        .rev()
                        .find(|(k, _)| k == n)
                        .map_or(f64::NAN, |(_, v)| *v)
                })
                .0;
        }
        let before = self.out.len();
        let trig = matches!(step.formula, Formula::Trig { .. });
        for (v, sg, ck, smp) in from_values(&step.formula, &vals, self.sigma[k]) {
            // The pair beside a double root is for poses only near the singular set: skipped
            // where the double root gave a solution on the pose.
            if trig && smp && self.out[before..].iter().any(|s| !s.approximate) {
                continue;
            }
            self.env.push((step.variable.clone(), v));
            self.q[step.joint] = v;
            let r = self.branch(k + 1, (flags.0 || sg, flags.1 || ck, flags.2 || smp));
            self.env.pop();
            r?;
        }
        Ok(())
    }

    /// A complete solution: checked (and refined) where a step asks for it, dropped when it
    /// is a sample off the pose or a duplicate.
    fn finish(&mut self, (singular, checked, sampled): (bool, bool, bool)) {
        let mut q = self.q.clone();
        let mut residual = 0.0;
        if singular || checked {
            let po = self.sol.position_only;
            residual = check::residual(&self.axes, &self.home, &self.target, self.len, po, &q);
            if residual > check::REFINE_TOL {
                let mut r = q.clone();
                let res = check::refine(&self.axes, &self.home, &self.target, self.len, po, &mut r);
                if res < residual {
                    (q, residual) = (r, res);
                }
            }
            if sampled && residual > check::POSE_TOL {
                return;
            }
            if singular
                && self
                    .out
                    .iter()
                    .any(|s| s.singular && check::same_row(&s.q, &q))
            {
                return;
            }
        }
        self.out.push(NumSolution {
            q,
            singular,
            approximate: residual > check::POSE_TOL || residual.is_nan(),
            residual,
        });
    }
}

/// The numeric candidates of one formula: `(value, singular, checked, sampled)` (see
/// [`check`]); none when the radicand is negative (unreachable). `sigma` is the rounding of
/// the formula's parts.
///
/// # Errors
/// A part that cannot be evaluated.
pub fn candidates(
    f: &Formula,
    ev: &dyn Fn(&Scalar) -> Result<f64, ScalarError>,
    sigma: f64,
) -> Result<Vec<(f64, bool, bool, bool)>, ScalarError> {
    let v: Vec<f64> = match f {
        Formula::Atan2 { y, x } => vec![ev(y)?, ev(x)?],
        Formula::Trig { a, b, c } => vec![ev(a)?, ev(b)?, ev(c)?],
        Formula::Value { v } => vec![ev(v)?],
        Formula::Linear { a, b } => vec![ev(a)?, ev(b)?],
        Formula::Quadratic { beta, gamma } => vec![ev(beta)?, ev(gamma)?],
    };
    Ok(from_values(f, &v, sigma))
}

/// The candidates of a formula from the values of its parts (in the order of its fields).
fn from_values(f: &Formula, v: &[f64], sigma: f64) -> Vec<check::Cand> {
    match f {
        Formula::Atan2 { .. } => check::atan2_cands(v[0], v[1], sigma),
        Formula::Value { .. } => vec![(v[0], false, false, false)],
        Formula::Linear { .. } => vec![check::linear_cand(v[0], v[1], sigma)],
        Formula::Trig { .. } => check::trig_cands(v[0], v[1], v[2], sigma),
        Formula::Quadratic { .. } => check::quadratic_cands(v[0], v[1], sigma),
    }
}
