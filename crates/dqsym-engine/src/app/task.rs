//! Task Jacobians of a robot in closed form (`dqsym fk ROBOT --jacobian=KIND`), with DQ
//! Robotics' names and row layouts (`DQ_Kinematics.cpp`): each is the exact derivative of a task
//! quantity of the pose `x = r + ε (1/2) t r` by the joint variables, so it equals DQ Robotics'
//! chain-rule matrices built from the pose Jacobian (`translation_jacobian = 2 haminus4(P(x)*)
//! J_D + 2 hamiplus4(D(x)) C4 J_P`, ...) entry for entry.
//!
//! The robot's line and plane (of `line`, `plane` and the distances from them) pass through the
//! end effector `t` with the direction `l = r l0 r*` or normal `n = r n0 r*`, `l0`, `n0` given in
//! the end-effector frame (DQ Robotics' `line_jacobian(J, x, l0)`). A workspace line or plane is
//! given by a unit direction (normal) and a point, so it is `l + ε (p × l)` (`n + ε (p · n)`).
//!
//! All of them are polynomials except the line-to-line distance Jacobian: the squared distance
//! of two skew lines is the quotient `D(l · lz)² / |P(l × lz)|²` ([`dqr::line_to_line_squared_distance`]),
//! so its Jacobian is a row of numerators over one denominator ([`TaskMatrix`]); when the robot
//! line is parallel to the workspace line for every configuration (`P(l × lz) = 0` exactly), it is
//! the polynomial `|D(l × lz)|²`, as in DQ Robotics' parallel branch. Where `P(l × lz)` vanishes
//! at some configurations only (the lines become parallel there), the quotient's denominator is
//! zero: DQ Robotics switches to the parallel formula at exactly those points, which is not the
//! limit of the other one (the squared distance is not differentiable there).
//!
//! The time derivative of any of them (`KIND_derivative`, DQ Robotics' `*_jacobian_derivative`)
//! is `sum_k dJ/dq_k qdot_k`, the rates named `<q>_dot`; of a quotient `A/E`, `(A' E - A E')/E²`.

use super::fk::{render, FkOptions, ReportError};
use super::quantity::{Quantity, Section, SectionKind, TaskBase, TaskName};
use crate::algebra::dqr;
use crate::kin::Robot;
use crate::scalar::par_map;
use crate::{closed_form, DualQuat, Expr, Quat, Scalar, ScalarError};
use num_traits::Zero;

/// A task Jacobian (`--jacobian=KIND`).
#[derive(Clone, Debug, PartialEq)]
pub enum TaskJacobian {
    /// `pose_jacobian`: d vec8(x) / dq, 8 x n (the same as `--jacobian`).
    Pose,
    /// `rotation_jacobian`: d vec4(P(x)) / dq, 4 x n.
    Rotation,
    /// `translation_jacobian`: d vec4(t) / dq with `t = 2 D(x) P(x)*`, 4 x n (row 0 is zero).
    Translation,
    /// `line_jacobian`: d vec8(l + ε t × l) / dq for the line through the end effector with
    /// direction `l = r l0 r*` (`l0` in the end-effector frame), 8 x n.
    Line([Scalar; 3]),
    /// `plane_jacobian`: d vec8(n + ε (t · n)) / dq for the plane through the end effector with
    /// normal `n = r n0 r*`, 8 x n (rows 5..7 zero).
    Plane([Scalar; 3]),
    /// `distance_jacobian`: d |t|² / dq, the squared distance of the end effector from the base
    /// origin, 1 x n.
    Distance,
    /// `point_to_point_distance_jacobian`: d |t - p|² / dq for a workspace point `p`, 1 x n.
    PointToPoint([Scalar; 3]),
    /// `point_to_line_distance_jacobian`: d |t × l - m|² / dq for a workspace line `l + ε m`
    /// (given by its unit direction and a point), 1 x n.
    PointToLine([Scalar; 3], [Scalar; 3]),
    /// `point_to_plane_distance_jacobian`: d (t · n - d) / dq for a workspace plane `n + ε d`
    /// (given by its unit normal and a point), 1 x n.
    PointToPlane([Scalar; 3], [Scalar; 3]),
    /// `line_to_point_distance_jacobian`: d |p × l - m|² / dq, the squared distance of a
    /// workspace point `p` (second) from the robot line `l + ε m` (direction `l0` in the
    /// end-effector frame, first), 1 x n.
    LineToPoint([Scalar; 3], [Scalar; 3]),
    /// `plane_to_point_distance_jacobian`: d (p · n - d) / dq, the signed distance of a workspace
    /// point `p` (second) from the robot plane `n + ε d` (normal `n0` in the end-effector frame,
    /// first), 1 x n.
    PlaneToPoint([Scalar; 3], [Scalar; 3]),
    /// `line_to_line_distance_jacobian`: d of the squared distance between the robot line
    /// (direction `l0` in the end-effector frame) and a workspace line (unit direction, point),
    /// 1 x n, a quotient (module docs).
    LineToLine([Scalar; 3], [Scalar; 3], [Scalar; 3]),
    /// `line_to_line_angle_jacobian`: d |l - lz|² / dq of the directions of the robot line
    /// (`l0` in the end-effector frame) and a workspace line (unit direction, point), 1 x n.
    LineToLineAngle([Scalar; 3], [Scalar; 3], [Scalar; 3]),
    /// The geometric Jacobian, 6 x n: the end-effector origin's linear velocity (x, y, z) over
    /// the angular velocity (x, y, z), both in the base frame, per unit rate of each joint
    /// variable (Siciliano's `J = [J_P; J_O]`; [`crate::kin::geometric_jacobian`]).
    Geometric,
    /// The same velocities in the end-effector frame, 6 x n (`R^T v` over `R^T omega`: the body
    /// twist, [`crate::kin::geometric_jacobian_body`]).
    GeometricBody,
    /// The time derivative `sum_k dJ/dq_k qdot_k` of another task Jacobian (DQ Robotics'
    /// `pose_jacobian_derivative`, `rotation_jacobian_derivative`, ...), a function of `q` and
    /// the joint rates `<q>_dot`.
    Derivative(Box<TaskJacobian>),
}

/// A task Jacobian as exact numerators over one common denominator (1 for every kind but
/// [`TaskJacobian::LineToLine`] and its derivative).
#[derive(Clone, Debug, PartialEq)]
pub struct TaskMatrix {
    /// The numerators, one row per task coordinate, one column per joint variable.
    pub num: Vec<Vec<Scalar>>,
    /// The common denominator.
    pub den: Scalar,
}

impl TaskMatrix {
    /// The entries when the denominator is 1.
    pub fn as_polynomial(&self) -> Option<&Vec<Vec<Scalar>>> {
        (self.den == Scalar::int(1)).then_some(&self.num)
    }
}

const KINDS: &str = "pose, rotation, translation, geometric, geometric_body, line[:X,Y,Z], \
    plane[:X,Y,Z], distance, \
    point_to_point:X,Y,Z, point_to_line:DX,DY,DZ,PX,PY,PZ, point_to_plane:NX,NY,NZ,PX,PY,PZ, \
    line_to_point:[LX,LY,LZ,]PX,PY,PZ, plane_to_point:[NX,NY,NZ,]PX,PY,PZ, \
    line_to_line:[LX,LY,LZ,]DX,DY,DZ,PX,PY,PZ, line_to_line_angle:[LX,LY,LZ,]DX,DY,DZ,PX,PY,PZ, \
    or any of them followed by _derivative (pose_derivative, line_derivative:X,Y,Z, ...)";

/// Why the text of `--jacobian=KIND` names no task Jacobian.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TaskParseError {
    /// `KIND_derivative` of a derivative.
    #[error("`{0}`: the derivative of a derivative would need the joint accelerations")]
    DerivativeOfDerivative(String),
    /// `line_to_line_derivative`.
    #[error(
        "`{0}`: DQ Robotics has no derivative of the line-to-line distance Jacobian, and that of its quotient is large: not generated"
    )]
    LineToLineDerivative(String),
    /// A `:` argument to a kind that takes none.
    #[error("`{0}` takes no `:` argument")]
    UnexpectedArgument(String),
    /// No `:` argument to a kind that needs one.
    #[error("`{kind}` needs `:{what}`")]
    MissingArgument {
        /// The kind.
        kind: String,
        /// What it needs.
        what: String,
    },
    /// The wrong number of coordinates.
    #[error("`{kind}` needs {count} numbers ({what}), got `{given}`")]
    Count {
        /// The kind.
        kind: String,
        /// How many it takes (`6 or 9`).
        count: String,
        /// What they are.
        what: String,
        /// The argument given.
        given: String,
    },
    /// A vector the caller's reader refused, with its message.
    #[error("{0}")]
    Vector(String),
    /// No such kind.
    #[error("unknown Jacobian `{0}`: expected {KINDS}")]
    Unknown(String),
}

impl TaskJacobian {
    /// Reads `pose`, `rotation`, `translation`, `line`, `line:X,Y,Z`, `plane`, `plane:X,Y,Z`,
    /// `distance`, the distances to workspace primitives (`point_to_point:X,Y,Z`,
    /// `point_to_line:DX,DY,DZ,PX,PY,PZ`, `point_to_plane:NX,NY,NZ,PX,PY,PZ`) and from the robot
    /// line or plane (`line_to_point`, `plane_to_point`, `line_to_line`, `line_to_line_angle`,
    /// with the robot line's direction or plane's normal in the end-effector frame first,
    /// optional: default z), and any of them followed by `_derivative` (`line_derivative:0,1,0`).
    /// `line` and `plane` default to the z axis, DQ Robotics' usual `k_`; the vectors are read by
    /// `parse_vec`.
    pub fn parse<E: std::fmt::Display>(
        s: &str,
        parse_vec: &dyn Fn(&str) -> Result<[Scalar; 3], E>,
    ) -> Result<TaskJacobian, TaskParseError> {
        let parse_vec = |a: &str| parse_vec(a).map_err(|e| TaskParseError::Vector(e.to_string()));
        let (kind, arg) = match s.split_once(':') {
            Some((k, a)) => (k, Some(a)),
            None => (s, None),
        };
        if let Some(inner) = kind.strip_suffix("_derivative") {
            let inner_s = match arg {
                Some(a) => format!("{inner}:{a}"),
                None => inner.to_owned(),
            };
            return match TaskJacobian::parse(&inner_s, &parse_vec)? {
                TaskJacobian::Derivative(_) => {
                    Err(TaskParseError::DerivativeOfDerivative(kind.to_owned()))
                }
                TaskJacobian::LineToLine(..) => {
                    Err(TaskParseError::LineToLineDerivative(kind.to_owned()))
                }
                t => Ok(TaskJacobian::Derivative(Box::new(t))),
            };
        }
        let k = || [Scalar::int(0), Scalar::int(0), Scalar::int(1)];
        let dir = || -> Result<[Scalar; 3], TaskParseError> {
            match arg {
                None => Ok(k()),
                Some(a) => parse_vec(a),
            }
        };
        let plain = |t: TaskJacobian| match arg {
            None => Ok(t),
            Some(_) => Err(TaskParseError::UnexpectedArgument(kind.to_owned())),
        };
        // `n` vectors of three numbers, the first optional when `optional`: (the vectors given,
        // with the default robot direction first when it was left out).
        let missing = |what: &str| TaskParseError::MissingArgument {
            kind: kind.to_owned(),
            what: what.to_owned(),
        };
        let vectors = |n: usize, optional: bool, what: &str| {
            let a = arg.ok_or_else(|| missing(what))?;
            let parts: Vec<&str> = a.split(',').collect();
            let given = parts.len() / 3;
            if !parts.len().is_multiple_of(3) || !(given == n || optional && given == n - 1) {
                return Err(TaskParseError::Count {
                    kind: kind.to_owned(),
                    count: if optional {
                        format!("{} or {}", 3 * (n - 1), 3 * n)
                    } else {
                        (3 * n).to_string()
                    },
                    what: what.to_owned(),
                    given: a.to_owned(),
                });
            }
            let mut out: Vec<[Scalar; 3]> = Vec::with_capacity(n);
            if given < n {
                out.push(k());
            }
            for c in parts.chunks(3) {
                out.push(parse_vec(&c.join(","))?);
            }
            Ok::<_, TaskParseError>(out)
        };
        let two = |what: &str| vectors(2, false, what).map(|v| (v[0].clone(), v[1].clone()));
        let robot_two = |what: &str| vectors(2, true, what).map(|v| (v[0].clone(), v[1].clone()));
        let robot_three =
            |what: &str| vectors(3, true, what).map(|v| (v[0].clone(), v[1].clone(), v[2].clone()));
        match kind {
            "point_to_point" => match arg {
                Some(a) => Ok(TaskJacobian::PointToPoint(parse_vec(a)?)),
                None => Err(missing("X,Y,Z")),
            },
            "point_to_line" => two("a unit direction, then a point")
                .map(|(d, p)| TaskJacobian::PointToLine(d, p)),
            "point_to_plane" => {
                two("a unit normal, then a point").map(|(n, p)| TaskJacobian::PointToPlane(n, p))
            }
            "line_to_point" => robot_two("the robot line's direction (optional), then a point")
                .map(|(l, p)| TaskJacobian::LineToPoint(l, p)),
            "plane_to_point" => robot_two("the robot plane's normal (optional), then a point")
                .map(|(n, p)| TaskJacobian::PlaneToPoint(n, p)),
            "line_to_line" => robot_three(
                "the robot line's direction (optional), the workspace line's unit direction and point",
            )
            .map(|(l, d, p)| TaskJacobian::LineToLine(l, d, p)),
            "line_to_line_angle" => robot_three(
                "the robot line's direction (optional), the workspace line's unit direction and point",
            )
            .map(|(l, d, p)| TaskJacobian::LineToLineAngle(l, d, p)),
            "pose" => plain(TaskJacobian::Pose),
            "rotation" => plain(TaskJacobian::Rotation),
            "translation" => plain(TaskJacobian::Translation),
            "distance" => plain(TaskJacobian::Distance),
            "geometric" => plain(TaskJacobian::Geometric),
            "geometric_body" | "geometric-body" => plain(TaskJacobian::GeometricBody),
            "line" => Ok(TaskJacobian::Line(dir()?)),
            "plane" => Ok(TaskJacobian::Plane(dir()?)),
            other => Err(TaskParseError::Unknown(other.to_owned())),
        }
    }

    /// The name of its entries (`Jt`, `Jrdot`).
    pub fn name(&self) -> TaskName {
        let base = match self {
            TaskJacobian::Pose => TaskBase::Pose,
            TaskJacobian::Rotation => TaskBase::Rotation,
            TaskJacobian::Translation => TaskBase::Translation,
            TaskJacobian::Geometric => TaskBase::Geometric,
            TaskJacobian::GeometricBody => TaskBase::GeometricBody,
            TaskJacobian::Line(_) => TaskBase::Line,
            TaskJacobian::Plane(_) => TaskBase::Plane,
            TaskJacobian::Distance
            | TaskJacobian::PointToPoint(_)
            | TaskJacobian::PointToLine(..)
            | TaskJacobian::PointToPlane(..)
            | TaskJacobian::LineToPoint(..)
            | TaskJacobian::PlaneToPoint(..)
            | TaskJacobian::LineToLine(..)
            | TaskJacobian::LineToLineAngle(..) => TaskBase::Distance,
            TaskJacobian::Derivative(inner) => {
                return TaskName {
                    derivative: true,
                    ..inner.name()
                }
            }
        };
        TaskName {
            base,
            derivative: false,
        }
    }

    /// The title of its section of the report.
    pub(super) fn title(&self) -> String {
        let t: &str = match self {
            TaskJacobian::Pose => "Jacobian d dq[i] / d q[j]",
            TaskJacobian::Rotation => "rotation Jacobian d r[i] / d q[j] (DQ Robotics' rotation_jacobian)",
            TaskJacobian::Translation => "translation Jacobian d t[i] / d q[j], t = (0, x, y, z) = 2 D P* (DQ Robotics' translation_jacobian)",
            TaskJacobian::Geometric => "geometric Jacobian: rows 0..2 the end-effector origin's velocity v, rows 3..5 the angular velocity omega, per unit rate of q[j], in the base frame",
            TaskJacobian::GeometricBody => "body geometric Jacobian: rows 0..2 the end-effector origin's velocity R^T v, rows 3..5 the angular velocity R^T omega, per unit rate of q[j], in the end-effector frame",
            TaskJacobian::Line(_) => "line Jacobian d vec8(l + eps t x l)[i] / d q[j] (DQ Robotics' line_jacobian)",
            TaskJacobian::Plane(_) => "plane Jacobian d vec8(n + eps t . n)[i] / d q[j] (DQ Robotics' plane_jacobian)",
            TaskJacobian::Distance => "distance Jacobian d |t|^2 / d q[j] (DQ Robotics' distance_jacobian)",
            TaskJacobian::PointToPoint(_) => "point-to-point distance Jacobian d |t - p|^2 / d q[j] (DQ Robotics' point_to_point_distance_jacobian)",
            TaskJacobian::PointToLine(..) => "point-to-line distance Jacobian d |t x l - m|^2 / d q[j] (DQ Robotics' point_to_line_distance_jacobian)",
            TaskJacobian::PointToPlane(..) => "point-to-plane distance Jacobian d (t . n - d) / d q[j] (DQ Robotics' point_to_plane_distance_jacobian)",
            TaskJacobian::LineToPoint(..) => "line-to-point distance Jacobian d |p x l - m|^2 / d q[j], l + eps m the robot line (DQ Robotics' line_to_point_distance_jacobian)",
            TaskJacobian::PlaneToPoint(..) => "plane-to-point distance Jacobian d (p . n - d) / d q[j], n + eps d the robot plane (DQ Robotics' plane_to_point_distance_jacobian)",
            TaskJacobian::LineToLine(..) => "line-to-line distance Jacobian d (D(l . lz)^2 / |P(l x lz)|^2) / d q[j], l the robot line, lz the workspace line (DQ Robotics' line_to_line_distance_jacobian)",
            TaskJacobian::LineToLineAngle(..) => "line-to-line angle Jacobian d |P(l) - P(lz)|^2 / d q[j], l the robot line, lz the workspace line (DQ Robotics' line_to_line_angle_jacobian)",
            TaskJacobian::Derivative(inner) => {
                return format!(
                    "time derivative of the {}: sum_k d/d q[k] of it times q_dot[k] (its *_derivative)",
                    inner.title()
                );
            }
        };
        t.to_owned()
    }
}

/// The name of the rate of the joint variable `q`.
pub fn rate_name(q: &str) -> String {
    format!("{q}_dot")
}

/// The task quantity whose Jacobian is taken, as numerators over one denominator (1 but for
/// the line-to-line distance of lines that are not parallel for every configuration).
fn task_quantity(x: &DualQuat<Scalar>, task: &TaskJacobian) -> (Vec<Scalar>, Scalar) {
    let r = &x.real;
    let t = dqr::translation(x);
    let tv = t.vector_part();
    let moved = |v: &[Scalar; 3]| -> [Scalar; 3] {
        (r * &Quat::from_vector(v) * r.conjugate()).vector_part()
    };
    let robot_line = |l0: &[Scalar; 3]| dqr::line(&moved(l0), &tv);
    let robot_plane = |n0: &[Scalar; 3]| dqr::plane(&moved(n0), &tv);
    let poly = |v: Vec<Scalar>| (v, Scalar::int(1));
    match task {
        TaskJacobian::Pose => poly(x.components().to_vec()),
        TaskJacobian::Rotation => poly(r.components().to_vec()),
        TaskJacobian::Translation => poly(t.components().to_vec()),
        TaskJacobian::Line(l0) => poly(robot_line(l0).components().to_vec()),
        TaskJacobian::Plane(n0) => poly(robot_plane(n0).components().to_vec()),
        TaskJacobian::Distance => poly(vec![t.norm_squared()]),
        TaskJacobian::PointToPoint(p) => poly(vec![dqr::point_to_point_squared_distance(&tv, p)]),
        TaskJacobian::PointToLine(l, p) => poly(vec![dqr::point_to_line_squared_distance(
            &tv,
            &dqr::line(l, p),
        )]),
        TaskJacobian::PointToPlane(n, p) => {
            poly(vec![dqr::point_to_plane_distance(&tv, &dqr::plane(n, p))])
        }
        TaskJacobian::LineToPoint(l0, p) => poly(vec![dqr::point_to_line_squared_distance(
            p,
            &robot_line(l0),
        )]),
        TaskJacobian::PlaneToPoint(n0, p) => {
            poly(vec![dqr::point_to_plane_distance(p, &robot_plane(n0))])
        }
        TaskJacobian::LineToLine(l0, d, p) => {
            let (num, den) = dqr::line_to_line_squared_distance(&robot_line(l0), &dqr::line(d, p));
            (vec![num], den)
        }
        TaskJacobian::LineToLineAngle(l0, d, _) => {
            let l = moved(l0);
            let diff = [&l[0] - &d[0], &l[1] - &d[1], &l[2] - &d[2]];
            poly(vec![dqr::dot3(&diff, &diff)])
        }
        TaskJacobian::Derivative(inner) => task_quantity(x, inner),
        // Not the gradient of a quantity: `task_jacobian` builds them from the pose's
        // derivatives, and never asks for a quantity.
        TaskJacobian::Geometric | TaskJacobian::GeometricBody => poly(Vec::new()),
    }
}

/// The task Jacobian (exact), `vars` the joint variables: numerators and their common
/// denominator; the derivative of `A/E` is `(A' E - A E') / E²`.
pub fn task_jacobian(x: &DualQuat<Scalar>, vars: &[&str], task: &TaskJacobian) -> TaskMatrix {
    if let TaskJacobian::Derivative(inner) = task {
        let j = task_jacobian(x, vars, inner);
        let rate = |e: &Scalar| {
            vars.iter().fold(Scalar::int(0), |acc, q| {
                acc + e.diff(q) * Scalar::sym(&rate_name(q))
            })
        };
        return over(&j.num, &j.den, rate);
    }
    let velocities = match task {
        TaskJacobian::Geometric => Some(crate::kin::geometric_jacobian(x, vars)),
        TaskJacobian::GeometricBody => Some(crate::kin::geometric_jacobian_body(x, vars)),
        _ => None,
    };
    if let Some(num) = velocities {
        return TaskMatrix {
            num,
            den: Scalar::int(1),
        };
    }
    let (v, den) = task_quantity(x, task);
    gradient(&v, &den, vars)
}

/// The Jacobian of the quotients `v[i] / den` by `vars`.
fn gradient(v: &[Scalar], den: &Scalar, vars: &[&str]) -> TaskMatrix {
    if *den == Scalar::int(1) {
        return TaskMatrix {
            num: v
                .iter()
                .map(|c| vars.iter().map(|q| c.diff(q)).collect())
                .collect(),
            den: den.clone(),
        };
    }
    let dden: Vec<Scalar> = vars.iter().map(|q| den.diff(q)).collect();
    TaskMatrix {
        num: v
            .iter()
            .map(|c| {
                vars.iter()
                    .zip(&dden)
                    .map(|(q, dd)| c.diff(q) * den - c * dd)
                    .collect()
            })
            .collect(),
        den: den * den,
    }
}

/// `d(a / e)` entry by entry for a linear derivation `d`: `d a` over `e` when `e` is 1, else
/// `(d a e - a d e) / e²`.
fn over(a: &[Vec<Scalar>], e: &Scalar, d: impl Fn(&Scalar) -> Scalar) -> TaskMatrix {
    if *e == Scalar::int(1) {
        return TaskMatrix {
            num: a.iter().map(|r| r.iter().map(&d).collect()).collect(),
            den: e.clone(),
        };
    }
    let de = d(e);
    TaskMatrix {
        num: a
            .iter()
            .map(|r| r.iter().map(|x| d(x) * e - x * &de).collect())
            .collect(),
        den: e * e,
    }
}

/// The report of `dqsym fk ROBOT --jacobian=KIND`: the pose (`dq[k]`) and the task Jacobian,
/// in any format; a quotient as its numerators `{base}_num[i][j]` and its common denominator
/// `{base}_den`. Needs the expanded pose (within `o.max_terms`).
pub fn task_report(
    robot: &Robot,
    o: &FkOptions,
    task: &TaskJacobian,
) -> Result<String, ReportError> {
    task_report_inner(robot, o, task).map_err(|e| match e {
        ReportError::Scalar(
            ScalarError::TooLarge { limit, .. } | ScalarError::TooManyPairs { limit, .. },
        ) => ReportError::TaskTooLarge(limit),
        other => other,
    })
}

fn task_report_inner(
    robot: &Robot,
    o: &FkOptions,
    task: &TaskJacobian,
) -> Result<String, ReportError> {
    let x = robot
        .forward_within(o.max_terms)
        .ok_or(ReportError::TaskTooLarge(o.max_terms))?;
    let vars: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
    if let TaskJacobian::Derivative(_) = task {
        for q in &vars {
            let name = rate_name(q);
            if robot.parameters().contains(&name) {
                return Err(ReportError::NameClash(name));
            }
        }
    }
    if let Some((b, a)) = line_to_line_parts(&x, task) {
        return line_to_line_report(robot, o, &x, &vars, (b, a));
    }
    let jac = task_jacobian(&x, &vars, task);
    let quotient = jac.as_polynomial().is_none();
    let n = vars.len().max(1);
    let comps = x.components();
    let flat: Vec<&Scalar> = comps
        .iter()
        .chain(jac.num.iter().flatten())
        .chain(quotient.then_some(&jac.den))
        .collect();
    let forms: Vec<Result<Expr, ScalarError>> = par_map(&flat, |s| closed_form(s));
    let mut forms = forms.into_iter();
    let mut pose = Vec::new();
    for k in 0..8 {
        pose.push((Quantity::Dq(k), forms.next().expect("8 entries")?));
    }
    let name = task.name();
    let mut rows = Vec::new();
    for i in 0..jac.num.len() {
        for j in 0..n.min(vars.len()) {
            rows.push((
                Quantity::task(name, quotient, i, j),
                forms.next().expect("an entry")?,
            ));
        }
    }
    let mut sections = vec![
        Section {
            kind: SectionKind::Pose { last_q: false },
            rows: pose,
        },
        Section {
            kind: SectionKind::Task {
                task: Box::new(task.clone()),
                quotient,
            },
            rows,
        },
    ];
    if quotient {
        sections.push(Section {
            kind: SectionKind::TaskDenominator(name),
            rows: vec![(
                Quantity::TaskDenominator(name),
                forms.next().expect("the denominator")?,
            )],
        });
    }
    render(robot, &robot.parameters(), &sections, o, &[])
}

/// `D(l . lz)` and `|P(l x lz)|^2` of the line-to-line distance (`b` and `a`: the squared
/// distance is `b^2 / a`), `None` for other tasks and for lines parallel at every
/// configuration (`a = 0`, a polynomial Jacobian).
fn line_to_line_parts(x: &DualQuat<Scalar>, task: &TaskJacobian) -> Option<(Scalar, Scalar)> {
    let TaskJacobian::LineToLine(l0, d, p) = task else {
        return None;
    };
    let r = &x.real;
    let l = (r * &Quat::from_vector(l0) * r.conjugate()).vector_part();
    let robot = dqr::line(&l, &dqr::translation(x).vector_part());
    let workspace = dqr::line(d, p);
    let a = dqr::cross(&robot, &workspace).real.norm_squared();
    (!a.is_zero()).then(|| (dqr::dot(&robot, &workspace).dual.w, a))
}

/// The line-to-line distance Jacobian of lines that are not always parallel, as DQ Robotics
/// builds it (`line_to_line_distance_jacobian`): the intermediate entries `Jd_b[0] = b =
/// D(l . lz)`, `Jd_b[1 + j] = d b / d q[j]`, `Jd_a[0] = a = |P(l x lz)|^2`, `Jd_a[1 + j] = d a /
/// d q[j]`, each in closed form, then `Jd_num[0][j] = 2 b b_j a - b^2 a_j` and `Jd_den = a^2` in
/// their symbols `Jd_b_k`, `Jd_a_k`: the expanded quotient of a 6R arm is far too large, these
/// entries are each about the size of a line Jacobian entry.
fn line_to_line_report(
    robot: &Robot,
    o: &FkOptions,
    x: &DualQuat<Scalar>,
    vars: &[&str],
    (b, a): (Scalar, Scalar),
) -> Result<String, ReportError> {
    let n = vars.len();
    for k in 0..=n {
        for name in [
            Quantity::DistanceB(k).symbol(),
            Quantity::DistanceA(k).symbol(),
        ] {
            if robot.variables.contains(&name) || robot.parameters().contains(&name) {
                return Err(ReportError::NameClash(name));
            }
        }
    }
    let with_gradient = |s: &Scalar| -> Vec<Scalar> {
        std::iter::once(s.clone())
            .chain(vars.iter().map(|q| s.diff(q)))
            .collect()
    };
    let (bs, as_) = (with_gradient(&b), with_gradient(&a));
    let sym = |q: Quantity| Scalar::sym(&q.symbol());
    let (b_, a_) = (Quantity::DistanceB, Quantity::DistanceA);
    let (b0, a0) = (sym(b_(0)), sym(a_(0)));
    let nums: Vec<Scalar> = (1..=n)
        .map(|k| &b0 * sym(b_(k)) * &a0 * Scalar::int(2) - &b0 * &b0 * sym(a_(k)))
        .collect();
    let den = &a0 * &a0;
    let comps = x.components();
    let flat: Vec<&Scalar> = comps
        .iter()
        .chain(&bs)
        .chain(&as_)
        .chain(&nums)
        .chain(std::iter::once(&den))
        .collect();
    let forms: Vec<Result<Expr, ScalarError>> = par_map(&flat, |s| closed_form(s));
    let mut forms = forms.into_iter();
    let mut take = |kind: SectionKind, names: Vec<Quantity>| -> Result<Section, ScalarError> {
        let rows = names
            .into_iter()
            .map(|nm| Ok((nm, forms.next().expect("an entry")?)))
            .collect::<Result<_, ScalarError>>()?;
        Ok(Section { kind, rows })
    };
    let distance = task_name_of_line_to_line();
    let sections = vec![
        take(
            SectionKind::Pose { last_q: false },
            (0..8).map(Quantity::Dq).collect(),
        )?,
        take(SectionKind::DistanceB, (0..=n).map(b_).collect())?,
        take(SectionKind::DistanceA, (0..=n).map(a_).collect())?,
        take(
            SectionKind::DistanceQuotient,
            (0..n)
                .map(|j| Quantity::task(distance, true, 0, j))
                .collect(),
        )?,
        take(
            SectionKind::DistanceDenominator,
            vec![Quantity::TaskDenominator(distance)],
        )?,
    ];
    render(robot, &robot.parameters(), &sections, o, &[])
}

/// The name of the line-to-line distance Jacobian's entries (`Jd`).
fn task_name_of_line_to_line() -> TaskName {
    TaskName {
        base: TaskBase::Distance,
        derivative: false,
    }
}
