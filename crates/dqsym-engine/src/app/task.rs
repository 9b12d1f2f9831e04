//! Task Jacobians of a robot in closed form (`dqsym fk ROBOT --jacobian=KIND`), with DQ
//! Robotics' names and row layouts (`DQ_Kinematics.cpp`): each is the exact derivative of a task
//! quantity of the pose `x = r + ε (1/2) t r` by the joint variables, so it equals DQ Robotics'
//! chain-rule matrices built from the pose Jacobian (`translation_jacobian = 2 haminus4(P(x)*)
//! J_D + 2 hamiplus4(D(x)) C4 J_P`, ...) entry for entry.

use super::fk::{render, FkOptions, ReportError};
use crate::algebra::dqr;
use crate::kin::Robot;
use crate::scalar::par_map;
use crate::{closed_form, DualQuat, Expr, Quat, Scalar, ScalarError};

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
    /// `pose_jacobian_derivative`: d/dt of the pose Jacobian, `sum_k dJ/dq_k qdot_k`, 8 x n, a
    /// function of `q` and the joint rates `<q>_dot`.
    PoseDerivative,
}

impl TaskJacobian {
    /// Reads `pose`, `rotation`, `translation`, `line`, `line:X,Y,Z`, `plane`, `plane:X,Y,Z`,
    /// `distance`, `pose_derivative` (`line` and `plane` default to the z axis, DQ Robotics'
    /// usual `k_`); the direction is read by `parse_vec`.
    pub fn parse(
        s: &str,
        parse_vec: &dyn Fn(&str) -> Result<[Scalar; 3], String>,
    ) -> Result<TaskJacobian, String> {
        let (kind, arg) = match s.split_once(':') {
            Some((k, a)) => (k, Some(a)),
            None => (s, None),
        };
        let dir = || -> Result<[Scalar; 3], String> {
            match arg {
                None => Ok([Scalar::int(0), Scalar::int(0), Scalar::int(1)]),
                Some(a) => parse_vec(a),
            }
        };
        let plain = |t: TaskJacobian| match arg {
            None => Ok(t),
            Some(_) => Err(format!("`{kind}` takes no `:` argument")),
        };
        let two = || -> Result<([Scalar; 3], [Scalar; 3]), String> {
            let a = arg.ok_or_else(|| format!("`{kind}` needs `:DX,DY,DZ,PX,PY,PZ`"))?;
            let parts: Vec<&str> = a.split(',').collect();
            if parts.len() != 6 {
                return Err(format!(
                    "`{kind}` needs six numbers (a unit direction, then a point), got `{a}`"
                ));
            }
            Ok((
                parse_vec(&parts[..3].join(","))?,
                parse_vec(&parts[3..].join(","))?,
            ))
        };
        match kind {
            "point_to_point" => match arg {
                Some(a) => Ok(TaskJacobian::PointToPoint(parse_vec(a)?)),
                None => Err("`point_to_point` needs `:X,Y,Z`".into()),
            },
            "point_to_line" => two().map(|(d, p)| TaskJacobian::PointToLine(d, p)),
            "point_to_plane" => two().map(|(n, p)| TaskJacobian::PointToPlane(n, p)),
            "pose" => plain(TaskJacobian::Pose),
            "rotation" => plain(TaskJacobian::Rotation),
            "translation" => plain(TaskJacobian::Translation),
            "distance" => plain(TaskJacobian::Distance),
            "pose_derivative" => plain(TaskJacobian::PoseDerivative),
            "line" => Ok(TaskJacobian::Line(dir()?)),
            "plane" => Ok(TaskJacobian::Plane(dir()?)),
            other => Err(format!(
                "unknown Jacobian `{other}`: expected pose, rotation, translation, line[:X,Y,Z], \
                 plane[:X,Y,Z], distance, point_to_point:X,Y,Z, point_to_line:DX,DY,DZ,PX,PY,PZ, \
                 point_to_plane:NX,NY,NZ,PX,PY,PZ or pose_derivative"
            )),
        }
    }

    /// The entry base name (`Jt`) and the section title.
    fn names(&self) -> (&'static str, &'static str) {
        match self {
            TaskJacobian::Pose => ("J", "Jacobian d dq[i] / d q[j]"),
            TaskJacobian::Rotation => ("Jr", "rotation Jacobian d r[i] / d q[j] (DQ Robotics' rotation_jacobian)"),
            TaskJacobian::Translation => ("Jt", "translation Jacobian d t[i] / d q[j], t = (0, x, y, z) = 2 D P* (DQ Robotics' translation_jacobian)"),
            TaskJacobian::Line(_) => ("Jl", "line Jacobian d vec8(l + eps t x l)[i] / d q[j] (DQ Robotics' line_jacobian)"),
            TaskJacobian::Plane(_) => ("Jpi", "plane Jacobian d vec8(n + eps t . n)[i] / d q[j] (DQ Robotics' plane_jacobian)"),
            TaskJacobian::Distance => ("Jd", "distance Jacobian d |t|^2 / d q[j] (DQ Robotics' distance_jacobian)"),
            TaskJacobian::PointToPoint(_) => ("Jd", "point-to-point distance Jacobian d |t - p|^2 / d q[j] (DQ Robotics' point_to_point_distance_jacobian)"),
            TaskJacobian::PointToLine(..) => ("Jd", "point-to-line distance Jacobian d |t x l - m|^2 / d q[j] (DQ Robotics' point_to_line_distance_jacobian)"),
            TaskJacobian::PointToPlane(..) => ("Jd", "point-to-plane distance Jacobian d (t . n - d) / d q[j] (DQ Robotics' point_to_plane_distance_jacobian)"),
            TaskJacobian::PoseDerivative => ("Jdot", "pose Jacobian derivative sum_k d J[i][j] / d q[k] q_dot[k] (DQ Robotics' pose_jacobian_derivative)"),
        }
    }
}

/// The name of the rate of the joint variable `q`.
pub fn rate_name(q: &str) -> String {
    format!("{q}_dot")
}

/// The task quantity whose Jacobian is taken, as a list of scalars.
fn task_vector(x: &DualQuat<Scalar>, task: &TaskJacobian) -> Vec<Scalar> {
    let r = &x.real;
    let t = dqr::translation(x);
    let moved = |v: &[Scalar; 3]| -> Quat<Scalar> { r * &Quat::from_vector(v) * r.conjugate() };
    match task {
        TaskJacobian::Pose | TaskJacobian::PoseDerivative => x.components().to_vec(),
        TaskJacobian::Rotation => r.components().to_vec(),
        TaskJacobian::Translation => t.components().to_vec(),
        TaskJacobian::Line(l0) => {
            let l = moved(l0).vector_part();
            dqr::line(&l, &t.vector_part()).components().to_vec()
        }
        TaskJacobian::Plane(n0) => {
            let n = moved(n0).vector_part();
            dqr::plane(&n, &t.vector_part()).components().to_vec()
        }
        TaskJacobian::Distance => vec![t.norm_squared()],
        TaskJacobian::PointToPoint(p) => {
            vec![dqr::point_to_point_squared_distance(&t.vector_part(), p)]
        }
        TaskJacobian::PointToLine(l, p) => vec![dqr::point_to_line_squared_distance(
            &t.vector_part(),
            &dqr::line(l, p),
        )],
        TaskJacobian::PointToPlane(n, p) => vec![dqr::point_to_plane_distance(
            &t.vector_part(),
            &dqr::plane(n, p),
        )],
    }
}

/// The task Jacobian's rows (exact), `vars` the joint variables.
pub fn task_jacobian(x: &DualQuat<Scalar>, vars: &[&str], task: &TaskJacobian) -> Vec<Vec<Scalar>> {
    let v = task_vector(x, task);
    let jac: Vec<Vec<Scalar>> = v
        .iter()
        .map(|c| vars.iter().map(|q| c.diff(q)).collect())
        .collect();
    if *task != TaskJacobian::PoseDerivative {
        return jac;
    }
    jac.iter()
        .map(|row| {
            row.iter()
                .map(|e| {
                    vars.iter().fold(Scalar::int(0), |acc, q| {
                        acc + e.diff(q) * Scalar::sym(&rate_name(q))
                    })
                })
                .collect()
        })
        .collect()
}

/// The report of `dqsym fk ROBOT --jacobian=KIND`: the pose (`dq[k]`) and the task Jacobian,
/// in any format. Needs the expanded pose (within `o.max_terms`).
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
    if let TaskJacobian::PoseDerivative = task {
        for q in &vars {
            let name = rate_name(q);
            if robot.parameters().contains(&name) {
                return Err(ReportError::NameClash(name));
            }
        }
    }
    let jac = task_jacobian(&x, &vars, task);
    let n = vars.len().max(1);
    let comps = x.components();
    let flat: Vec<&Scalar> = comps.iter().chain(jac.iter().flatten()).collect();
    let forms: Vec<Result<Expr, ScalarError>> = par_map(&flat, |s| closed_form(s));
    let mut forms = forms.into_iter();
    let mut pose = Vec::new();
    for k in 0..8 {
        pose.push((format!("dq[{k}]"), forms.next().expect("8 entries")?));
    }
    let (base, title) = task.names();
    let mut rows = Vec::new();
    for i in 0..jac.len() {
        for j in 0..n.min(vars.len()) {
            rows.push((
                format!("{base}[{i}][{j}]"),
                forms.next().expect("an entry")?,
            ));
        }
    }
    let sections = vec![
        (
            "unit dual quaternion (w, x, y, z, w_e, x_e, y_e, z_e)".to_owned(),
            pose,
        ),
        (title.to_owned(), rows),
    ];
    render(robot, &sections, o.format, &[])
}
