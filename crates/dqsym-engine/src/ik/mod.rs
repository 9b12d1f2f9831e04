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
mod emit;
mod plan;
mod report;

pub use axes::{home_axes, intersection, relation, Axis, Relation, V3};
pub use emit::{ik_c, ik_python, ik_rust};
pub use report::ik_report;

use crate::kin::Robot;
use crate::{Matrix4, Scalar};
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
    #[error("{robot}: no closed-form inverse kinematics for this geometry.\n{geometry}\nSupported families: {families}")]
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
    /// An exact computation failed (term limit, work budget).
    #[error("{0}")]
    Scalar(String),
}

/// What to derive.
#[derive(Clone, Debug, Default)]
pub struct IkOptions {
    /// A joint variable given as a parameter (a 7-joint arm becomes a 6-joint one).
    pub free: Option<String>,
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
    /// The subproblem and the identity it uses, in words.
    pub method: String,
    /// The branch's name and the names of its `+` and `−` signs (shoulder left/right, ...).
    pub branch: Option<(String, String, String)>,
    /// Where the step is singular, in words.
    pub singular: String,
}

/// A derived closed-form inverse kinematics.
#[derive(Clone, Debug)]
pub struct IkSolution {
    /// The robot's name.
    pub robot: String,
    /// The family found.
    pub family: String,
    /// The geometry facts decided, one per line.
    pub geometry: Vec<String>,
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
    /// The home pose `M` of the end effector.
    pub home: Matrix4<Scalar>,
    /// The closed forms of every step's parts, computed on first use.
    pub(crate) forms: std::sync::OnceLock<Result<Vec<Parts>, String>>,
}

type Parts = Vec<(&'static str, crate::Expr)>;

/// Derives the closed-form inverse kinematics of `robot`.
///
/// # Errors
/// [`IkError::Unsupported`] naming the geometry found when no family applies;
/// [`IkError::Option`] for a bad `--free`; [`IkError::Scalar`] when a limit is reached.
pub fn solve(robot: &Robot, opts: &IkOptions) -> Result<IkSolution, IkError> {
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
    let (axes, home) = axes::dq_axes(q, variables).ok_or_else(|| {
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
    /// A singular set was met (a joint chosen as 0 or a double root).
    pub singular: bool,
    /// A radicand slightly below zero was clamped (least-squares closest).
    pub approximate: bool,
}

const SINGULAR_TOL: f64 = 1e-10;

/// A radicand `rad` of scale `n`: `None` below `-1e-8 n` (out of reach); within `1e-12 n` of
/// zero a double root (singular; approximate when beyond rounding, `1e-14 n`, or negative
/// beyond it: the closest reach); otherwise itself.
pub fn radicand(rad: f64, n: f64) -> Option<(f64, bool, bool)> {
    if rad < -1e-8 * n {
        None
    } else if rad <= 1e-12 * n {
        Some((0.0, true, rad.abs() > 1e-14 * n))
    } else {
        Some((rad, false, false))
    }
}

impl IkSolution {
    /// The closed forms of every step's parts (`a`, `b`, `c`; `y`, `x`; ...), computed once.
    ///
    /// # Errors
    /// A closed form that fails (term limit, work budget).
    pub fn forms(&self) -> Result<&[Vec<(&'static str, crate::Expr)>], String> {
        self.forms
            .get_or_init(|| {
                self.steps
                    .iter()
                    .map(|s| report::parts(&s.formula).map_err(|e| e.to_string()))
                    .collect()
            })
            .as_ref()
            .map(|v| v.as_slice())
            .map_err(Clone::clone)
    }

    /// Every solution for a numeric target pose (row-major 4x4), the parameters given by name.
    /// Evaluates the exact formulas in f64 (the reference the generated code is checked
    /// against).
    ///
    /// # Errors
    /// A parameter without a value.
    pub fn solve_numeric(
        &self,
        target: &[[f64; 4]; 4],
        params: &[(&str, f64)],
    ) -> Result<Vec<NumSolution>, String> {
        for p in &self.params {
            if !params.iter().any(|(n, _)| n == p) {
                return Err(format!("no value for parameter `{p}`"));
            }
        }
        let mut env: Vec<(String, f64)> = params.iter().map(|(n, v)| (n.to_string(), *v)).collect();
        for (r, row) in TARGET_SYMBOLS.iter().enumerate() {
            for (c, name) in row.iter().enumerate() {
                env.push((name.to_string(), target[r][c]));
            }
        }
        let mut out = Vec::new();
        let mut q = vec![0.0; self.variables.len()];
        self.branch(0, &mut env, &mut q, false, false, &mut out)?;
        Ok(out)
    }

    fn branch(
        &self,
        k: usize,
        env: &mut Vec<(String, f64)>,
        q: &mut Vec<f64>,
        singular: bool,
        approximate: bool,
        out: &mut Vec<NumSolution>,
    ) -> Result<(), String> {
        let Some(step) = self.steps.get(k) else {
            out.push(NumSolution {
                q: q.clone(),
                singular,
                approximate,
            });
            return Ok(());
        };
        let forms = self.forms()?;
        let mut vals = [0.0; 3];
        for (i, (_, e)) in forms[k].iter().enumerate() {
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
        let cands = from_values(&step.formula, &vals);
        for (v, sing, approx) in cands {
            env.push((step.variable.clone(), v));
            q[step.joint] = v;
            let r = self.branch(k + 1, env, q, singular || sing, approximate || approx, out);
            env.pop();
            r?;
        }
        Ok(())
    }
}

/// The numeric candidates of one formula: `(value, singular, approximate)`; none when the
/// radicand is negative (unreachable).
pub fn candidates(
    f: &Formula,
    ev: &dyn Fn(&Scalar) -> Result<f64, String>,
) -> Result<Vec<(f64, bool, bool)>, String> {
    let v: Vec<f64> = match f {
        Formula::Atan2 { y, x } => vec![ev(y)?, ev(x)?],
        Formula::Trig { a, b, c } => vec![ev(a)?, ev(b)?, ev(c)?],
        Formula::Value { v } => vec![ev(v)?],
        Formula::Quadratic { beta, gamma } => vec![ev(beta)?, ev(gamma)?],
    };
    Ok(from_values(f, &v))
}

/// The candidates of a formula from the values of its parts (in the order of its fields).
fn from_values(f: &Formula, v: &[f64]) -> Vec<(f64, bool, bool)> {
    match f {
        Formula::Atan2 { .. } => {
            let (y, x) = (v[0], v[1]);
            if y.hypot(x) < SINGULAR_TOL {
                // Any value: twelve, k pi/6, so that a later joint can still reach (the
                // generated code does the same).
                (-5..=6)
                    .map(|k| (f64::from(k) * std::f64::consts::FRAC_PI_6, true, false))
                    .collect()
            } else {
                vec![(y.atan2(x), false, false)]
            }
        }
        Formula::Value { .. } => vec![(v[0], false, false)],
        Formula::Trig { .. } => {
            let (a, b, c) = (v[0], v[1], v[2]);
            let n = a * a + b * b;
            if n < SINGULAR_TOL * SINGULAR_TOL {
                return if c.abs() < 1e-9 {
                    vec![(0.0, true, false)]
                } else {
                    vec![]
                };
            }
            let Some((rad, sing, approx)) = radicand(n - c * c, n) else {
                return vec![];
            };
            let phi = b.atan2(a);
            let w = rad.sqrt().atan2(c);
            vec![(phi + w, sing, approx), (phi - w, sing, approx)]
        }
        Formula::Quadratic { .. } => {
            let (b, g) = (v[0], v[1]);
            let scale = (b * b).max(g.abs()).max(1.0);
            let Some((rad, sing, approx)) = radicand(b * b - g, scale) else {
                return vec![];
            };
            let r = rad.sqrt();
            vec![(-b + r, sing, approx), (-b - r, sing, approx)]
        }
    }
}
