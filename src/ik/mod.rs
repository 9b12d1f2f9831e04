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
pub use report::{ik_report, IkFormat};

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
}

/// Derives the closed-form inverse kinematics of `robot`.
///
/// # Errors
/// [`IkError::Unsupported`] naming the geometry found when no family applies;
/// [`IkError::Option`] for a bad `--free`; [`IkError::Scalar`] when a limit is reached.
pub fn solve(robot: &Robot, opts: &IkOptions) -> Result<IkSolution, IkError> {
    plan::derive(robot, opts)
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
const CLAMP_TOL: f64 = 1e-8;

impl IkSolution {
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
        let ev = |x: &Scalar, env: &Vec<(String, f64)>| -> Result<f64, String> {
            x.eval(&|n| env.iter().rev().find(|(k, _)| k == n).map(|(_, v)| *v))
                .map_err(|e| e.to_string())
        };
        let cands = candidates(&step.formula, &|x| ev(x, env))?;
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
    Ok(match f {
        Formula::Atan2 { y, x } => {
            let (y, x) = (ev(y)?, ev(x)?);
            if y.hypot(x) < SINGULAR_TOL {
                vec![(0.0, true, false)]
            } else {
                vec![(y.atan2(x), false, false)]
            }
        }
        Formula::Value { v } => vec![(ev(v)?, false, false)],
        Formula::Trig { a, b, c } => {
            let (a, b, c) = (ev(a)?, ev(b)?, ev(c)?);
            let n = a * a + b * b;
            if n < SINGULAR_TOL * SINGULAR_TOL {
                return Ok(if c.abs() < 1e-9 {
                    vec![(0.0, true, false)]
                } else {
                    vec![]
                });
            }
            let rad = n - c * c;
            let (rad, sing, approx) = if rad < -CLAMP_TOL * n {
                return Ok(vec![]);
            } else if rad < 0.0 {
                (0.0, true, rad < -SINGULAR_TOL * n)
            } else {
                (rad, rad <= SINGULAR_TOL * n, false)
            };
            let phi = b.atan2(a);
            let w = rad.sqrt().atan2(c);
            vec![(phi + w, sing, approx), (phi - w, sing, approx)]
        }
        Formula::Quadratic { beta, gamma } => {
            let (b, g) = (ev(beta)?, ev(gamma)?);
            let rad = b * b - g;
            let scale = (b * b).max(g.abs()).max(1.0);
            let (rad, sing, approx) = if rad < -CLAMP_TOL * scale {
                return Ok(vec![]);
            } else if rad < 0.0 {
                (0.0, true, rad < -SINGULAR_TOL * scale)
            } else {
                (rad, rad <= SINGULAR_TOL * scale, false)
            };
            let r = rad.sqrt();
            vec![(-b + r, sing, approx), (-b - r, sing, approx)]
        }
    })
}
