//! The built-ins with DQ Robotics' names and semantics (`DQ.cpp`, `DQ_Geometry.cpp`), exact:
//! their `:help` table and their implementations. The library functions are in
//! `algebra/dqr.rs` (polynomial ones) and `kin/dqexp.rs` (angles, exp, log, powers, ScLERP).
//!
//! Left out: `pinv` and `dec_mult` (decompositional products, numeric conveniences with no
//! closed-form use), `generalized_jacobian`, `Q4`/`Q8` (derivatives of `exp` divided by
//! `sin(phi/2)/(phi/2)`, which is not a polynomial), and every `is_*` predicate with a
//! threshold (exactness makes them `unit(q)` and the Plücker constraints), the `*_residual`
//! functions (a moving workspace primitive) and the line-segment distances (a numeric choice
//! of the closest elements).

use super::ast::Span;
use super::builtins::{b, dq_like, invalid, symbol_list, type_error, unit_dq, Arg, Builtin};
use super::eval::{op_error, EvalError, Result};
use super::value::{self, Value};
use crate::algebra::dqr;
use crate::kin::dqexp::{self, DqError};
use crate::{app::TaskJacobian, DualQuat, Frac, Quat, Scalar};
use num_traits::Zero;

/// The DQ Robotics built-ins, in the order `:help` lists them (after the core ones).
pub(super) const TABLE: [Builtin; 66] = [
    b("P", "P(h)", 1, 1, "DQ Robotics' primary part P(h) (our real part)", "P(dh(theta1, d1, a1, 0))", run_p),
    b("D", "D(h)", 1, 1, "DQ Robotics' dual part D(h): h = P(h) + eps D(h), as in our q + eps q_eps", "D(trans((l, 0, 0)))", run_d),
    b("Re", "Re(h)", 1, 1, "the scalar parts w + eps w_eps", "Re(dh(theta1, d1, 0, 0))", run_re),
    b("Im", "Im(h)", 1, 1, "the vector parts (0, x, y, z) + eps (0, x_eps, y_eps, z_eps)", "Im(dh(theta1, d1, 0, 0))", run_im),
    b("sharp", "sharp(h)", 1, 1, "P(h) - eps D(h) (our dconj)", "sharp(trans((l, 0, 0)))", run_sharp),
    b("norm", "norm(h)", 1, 1, "DQ Robotics' norm sqrt(h* h) = |P| + eps (P . D)/|P|, exact when |P|^2 is 1 or a rational", "norm(2*trans((l, 0, 0)))", run_norm),
    b("inv", "inv(h)", 1, 1, "DQ Robotics' inverse (the same as inverse)", "inv(rot((0, 0, 1), theta1))", run_inv),
    b("translation", "translation(h)", 1, 1, "the translation 2 D(h) P(h)* of a unit DQ, a pure quaternion (0; t)", "translation(dh(theta1, d1, a1, alpha1))", run_translation),
    b("rotation", "rotation(h)", 1, 1, "the rotation P(h) of a unit DQ", "rotation(dh(theta1, d1, a1, 0))", run_p),
    b("rotation_angle", "rotation_angle(h)", 1, 1, "2 acos(w) of a unit DQ, read exactly (branch: acos in [0, pi] for numbers, the written angle for cos(x))", "rotation_angle(rot((0, 0, 1), theta1))", run_rotation_angle),
    b("rotation_axis", "rotation_axis(h)", 1, 1, "Im(P(h))/sin(phi/2), a pure quaternion; k for no rotation (DQ Robotics' convention)", "rotation_axis(rot((0, 1, 0), theta1, (l, 0, 0)))", run_rotation_axis),
    b("log", "log(h)", 1, 1, "DQ Robotics' log (phi/2) n + eps t/2 of a unit DQ (rotation and translation apart; screwlog is the screw one)", "log(rot((0, 0, 1), theta1) * trans((l, 0, 0)))", run_log),
    b("exp", "exp(h)", 1, 1, "DQ Robotics' exp e^P + eps D e^P of a pure DQ, e^r = cos|r| + sin|r| r/|r| (|r| must be linear in the symbols)", "exp((0, theta1/2, 0, 0) + eps*(0, l, 0, 0))", run_exp),
    b("pow", "pow(h, a) or pow(h, a, psi)", 2, 3, "DQ Robotics' pow exp(a log h): rotation r^a, translation a t; psi names the angle a*phi when it is not linear", "pow(rot((0, 0, 1), theta1) * trans((l, 0, 0)), t, alpha1)", run_pow),
    b("screwlog", "screwlog(q)", 1, 1, "the screw logarithm (theta/2) n + eps ((d/2) n + (theta/2) m), q = exp of it (2 xi is the twist)", "screwlog(screw((0, 0, 1), (l, 0, 0), theta1, d1))", run_screwlog),
    b("screwpow", "screwpow(q, t) or screwpow(q, t, psi)", 2, 3, "the screw power q^t: angle t theta (psi names it when not linear), slide t d about the same axis", "screwpow(screw((0, 0, 1), (l, 0, 0), pi/2, d1), t, alpha1)", run_pow),
    b("sclerp", "sclerp(q0, q1, t) or sclerp(q0, q1, t, psi)", 3, 4, "ScLERP q0 (q0* q1)^t, the screw power (psi = t * rotation_angle(q0* q1) when not linear)", "sclerp(trans((0, 0, 0)), rot((0, 0, 1), pi/2, (l, 0, 0)), t, alpha1)", run_sclerp),
    b("sclerpdot", "sclerpdot(q0, q1, t) or sclerpdot(q0, q1, t, psi)", 3, 4, "d/dt of sclerp: sclerp(q0, q1, t) xi, xi = screwlog(q0* q1); the body twist 2 xi is constant", "sclerpdot(trans((0, 0, 0)), rot((0, 0, 1), pi/2, (l, 0, 0)), t, alpha1)", run_sclerp),
    b("twist", "twist(q, qdot)", 2, 2, "the spatial twist xi = 2 qdot q* (qdot = 1/2 xi q): angular velocity + eps (linear velocity of the point at the origin)", "twist(rot((0, 0, 1), theta1), diff(rot((0, 0, 1), theta1), theta1))", run_twist),
    b("bodytwist", "bodytwist(q, qdot)", 2, 2, "the body twist xi = 2 q* qdot (qdot = 1/2 q xi)", "bodytwist(rot((0, 0, 1), theta1), diff(rot((0, 0, 1), theta1), theta1))", run_twist),
    b("qdot", "qdot(q, xi)", 2, 2, "1/2 xi q, the derivative of q under the spatial twist xi", "qdot(rot((0, 0, 1), theta1), (0, 0, 0, 1))", run_qdot),
    b("normalize", "normalize(h)", 1, 1, "DQ Robotics' normalize h norm(h)^-1, a unit DQ (exact when |P(h)|^2 is a rational)", "normalize(2*trans((l, 0, 0)) + eps*(1, 0, 0, 0))", run_normalize),
    b("C4", "C4()", 0, 0, "the 4x4 matrix with vec4(conj(q)) = C4() vec4(q)", "C4()", run_c4),
    b("C8", "C8()", 0, 0, "the 8x8 matrix with vec8(conj(h)) = C8() vec8(h)", "C8()", run_c8),
    b("crossmatrix4", "crossmatrix4(a)", 1, 1, "the 4x4 matrix with vec4(cross(a, b)) = crossmatrix4(a) vec4(b) for pure a, b", "crossmatrix4((0, l, 0, 1))", run_crossmatrix4),
    b("tplus", "tplus(h)", 1, 1, "h P(h)*, the translation factor 1 + eps t/2 of a unit DQ", "tplus(dh(theta1, d1, a1, alpha1))", run_tplus),
    b("Ad", "Ad(a, x)", 2, 2, "the adjoint a x conj(a) (moves lines, twists and directions by a)", "Ad(rot((0, 0, 1), theta1), (0, 1, 0, 0))", run_ad),
    b("Adsharp", "Adsharp(a, x)", 2, 2, "sharp(a) x conj(a): moves the plane x = n + eps d by a, to n' + eps (d + t . n'), n' = r n r* (Ad moves lines)", "Adsharp(rot((0, 0, 1), theta1, (l, 0, 0)), plane((1, 0, 0), (d1, 0, 0)))", run_ad),
    b("hamiplus4", "hamiplus4(q)", 1, 1, "the 4x4 matrix with vec4(q p) = hamiplus4(q) vec4(p)", "hamiplus4(rot((0, 0, 1), theta1))", run_hamiplus4),
    b("haminus4", "haminus4(q)", 1, 1, "the 4x4 matrix with vec4(p q) = haminus4(q) vec4(p)", "haminus4(rot((0, 0, 1), theta1))", run_haminus4),
    b("hamiplus8", "hamiplus8(h)", 1, 1, "the 8x8 matrix with vec8(h g) = hamiplus8(h) vec8(g)", "hamiplus8(trans((l, 0, 0)))", run_hamiplus8),
    b("haminus8", "haminus8(h)", 1, 1, "the 8x8 matrix with vec8(g h) = haminus8(h) vec8(g)", "haminus8(trans((l, 0, 0)))", run_haminus8),
    b("vec3", "vec3(q)", 1, 1, "the column (x, y, z) of P(q)", "vec3(translation(trans((l, 0, 0))))", run_vec3),
    b("vec4", "vec4(q)", 1, 1, "the column (w, x, y, z) of P(q)", "vec4(rot((0, 0, 1), theta1))", run_vec4),
    b("vec6", "vec6(h)", 1, 1, "the column of the vector parts (x, y, z, x_eps, y_eps, z_eps)", "vec6(log(trans((l, 0, 0))))", run_vec6),
    b("vec8", "vec8(h)", 1, 1, "the column of all eight components", "vec8(dh(theta1, d1, a1, alpha1))", run_vec8),
    b("cross", "cross(a, b)", 2, 2, "(a b - b a)/2: the cross product of pure quaternions, extended to lines", "cross((1, 0, 0), (0, l, 0))", run_cross),
    b("dot", "dot(a, b)", 2, 2, "-(a b + b a)/2: the dot product of pure quaternions (a scalar for vectors), extended to lines", "dot((1, 0, 0), (l, 1, 0))", run_cross),
    b("line", "line(direction, point)", 2, 2, "the Plücker line l + eps (p x l) through point with direction l", "line((0, 0, 1), (l, 0, 0))", run_line),
    b("plane", "plane(normal, point)", 2, 2, "the plane n + eps (p . n) through point with normal n", "plane((0, 0, 1), (0, 0, d1))", run_line),
    b("point_to_point_squared_distance", "point_to_point_squared_distance(p, q)", 2, 2, "|p - q|^2", "point_to_point_squared_distance((l, 0, 0), (0, d1, 0))", run_point_to_point_squared_distance),
    b("point_to_line_squared_distance", "point_to_line_squared_distance(p, line)", 2, 2, "|p x l - m|^2 for the line l + eps m", "point_to_line_squared_distance((l, 0, 0), line((0, 0, 1), (0, 0, d1)))", run_point_to_line_squared_distance),
    b("point_to_plane_distance", "point_to_plane_distance(p, plane)", 2, 2, "the signed distance p . n - d from the plane n + eps d", "point_to_plane_distance((l, 0, d1), plane((0, 0, 1), (0, 0, 1)))", run_point_to_plane_distance),
    b("line_to_line_squared_distance", "line_to_line_squared_distance(l1, l2)", 2, 2, "D(l1 . l2)^2 / |P(l1 x l2)|^2, or |D(l1 x l2)|^2 for parallel lines (a quotient when symbolic)", "line_to_line_squared_distance(line((1, 0, 0), (0, 0, 0)), line((0, 1, 0), (0, 0, d1)))", run_line_to_line_squared_distance),
    b("point_projected_in_line", "point_projected_in_line(p, line)", 2, 2, "the projection l x m + (p . l) l of the point p on the line l + eps m, a pure quaternion", "point_projected_in_line((l, 1, 0), line((1, 0, 0), (0, 0, d1)))", run_point_projected_in_line),
    b("closest_points_between_lines", "closest_points_between_lines(l1, l2)", 2, 2, "the closest points of two non-parallel lines, the rows of a 2x3 matrix (a quotient by |l1 x l2|^2 when symbolic); DQ Robotics returns a pair", "closest_points_between_lines(line((1, 0, 0), (0, 0, 0)), line((0, 1, 0), (l, 0, d1)))", run_closest_points_between_lines),
    b("line_to_line_angle", "line_to_line_angle(l1, l2)", 2, 2, "acos(P(l1 . l2)), read exactly when that is cos of an angle", "line_to_line_angle(line((1, 0, 0), (0, 0, 0)), Ad(rot((0, 0, 1), theta1), line((1, 0, 0), (0, 0, l))))", run_line_to_line_angle),
    b("pose_jacobian", "pose_jacobian(x, [q1, q2, ...])", 2, 2, "d vec8(x) / dq, 8 x n (the same as jacobian)", "pose_jacobian(dh(theta1, 0, l, 0) * dh(t, d1, 0, 0), [theta1, t])", |n, v, _| task_jacobian(n, v, |_, _| Ok(TaskJacobian::Pose), false)),
    b("rotation_jacobian", "rotation_jacobian(x, [q1, ...])", 2, 2, "d vec4(P(x)) / dq of a unit pose, 4 x n", "rotation_jacobian(dh(theta1, 0, l, 0) * dh(t, d1, 0, 0), [theta1, t])", |n, v, _| task_jacobian(n, v, |_, _| Ok(TaskJacobian::Rotation), false)),
    b("translation_jacobian", "translation_jacobian(x, [q1, ...])", 2, 2, "d vec4(translation(x)) / dq of a unit pose, 4 x n", "translation_jacobian(dh(theta1, 0, l, 0) * dh(t, d1, 0, 0), [theta1, t])", |n, v, _| task_jacobian(n, v, |_, _| Ok(TaskJacobian::Translation), false)),
    b("line_jacobian", "line_jacobian(x, [q1, ...], direction)", 3, 3, "d vec8(l + eps t x l) / dq, l = r direction r* (direction in the frame x)", "line_jacobian(dh(theta1, 0, l, 0), [theta1], (0, 0, 1))", |n, v, _| task_jacobian(n, v, |n, v| Ok(TaskJacobian::Line(vec_at(n, v, 2, "the direction")?)), false)),
    b("plane_jacobian", "plane_jacobian(x, [q1, ...], normal)", 3, 3, "d vec8(n + eps t . n) / dq, n = r normal r* (normal in the frame x)", "plane_jacobian(dh(theta1, 0, l, 0), [theta1], (0, 0, 1))", |n, v, _| task_jacobian(n, v, |n, v| Ok(TaskJacobian::Plane(vec_at(n, v, 2, "the normal")?)), false)),
    b("distance_jacobian", "distance_jacobian(x, [q1, ...])", 2, 2, "d |translation(x)|^2 / dq, 1 x n", "distance_jacobian(dh(theta1, 0, l, 0) * dh(t, 0, l, 0), [theta1, t])", |n, v, _| task_jacobian(n, v, |_, _| Ok(TaskJacobian::Distance), false)),
    b("point_to_point_distance_jacobian", "point_to_point_distance_jacobian(x, [q1, ...], p)", 3, 3, "d |t - p|^2 / dq, t = translation(x), p a workspace point, 1 x n", "point_to_point_distance_jacobian(dh(theta1, 0, l, 0), [theta1], (1, 0, 0))", |n, v, _| task_jacobian(n, v, |n, v| Ok(TaskJacobian::PointToPoint(vec_at(n, v, 2, "the point")?)), false)),
    b("point_to_line_distance_jacobian", "point_to_line_distance_jacobian(x, [q1, ...], line)", 3, 3, "d |t x l - m|^2 / dq for the workspace line l + eps m, 1 x n", "point_to_line_distance_jacobian(dh(theta1, 0, l, 0), [theta1], line((0, 1, 0), (1, 0, 0)))", |n, v, _| task_jacobian(n, v, |n, v| {
            let (l, p) = workspace_line(n, v, 2)?;
            Ok(TaskJacobian::PointToLine(l, p))
        }, false)),
    b("point_to_plane_distance_jacobian", "point_to_plane_distance_jacobian(x, [q1, ...], plane)", 3, 3, "d (t . n - d) / dq for the workspace plane n + eps d, 1 x n", "point_to_plane_distance_jacobian(dh(theta1, 0, l, 0), [theta1], plane((1, 0, 0), (1, 0, 0)))", |n, v, _| task_jacobian(n, v, |n, v| {
            let (nn, p) = plane_arg(n, &v[2])?;
            Ok(TaskJacobian::PointToPlane(nn, p))
        }, false)),
    b("line_to_point_distance_jacobian", "line_to_point_distance_jacobian(x, [q1, ...], direction, p)", 4, 4, "d |p x l - m|^2 / dq: the workspace point p from the robot line l + eps t x l, l = r direction r*, 1 x n", "line_to_point_distance_jacobian(dh(theta1, 0, l, 0), [theta1], (0, 1, 0), (1, 0, 0))", |n, v, _| task_jacobian(n, v, |n, v| {
            Ok(TaskJacobian::LineToPoint(vec_at(n, v, 2, "the direction")?, vec_at(n, v, 3, "the point")?))
        }, false)),
    b("plane_to_point_distance_jacobian", "plane_to_point_distance_jacobian(x, [q1, ...], normal, p)", 4, 4, "d (p . n - d) / dq: the workspace point p from the robot plane n + eps t . n, n = r normal r*, 1 x n", "plane_to_point_distance_jacobian(dh(theta1, 0, l, 0), [theta1], (1, 0, 0), (0, 1, 0))", |n, v, _| task_jacobian(n, v, |n, v| {
            Ok(TaskJacobian::PlaneToPoint(vec_at(n, v, 2, "the normal")?, vec_at(n, v, 3, "the point")?))
        }, false)),
    b("line_to_line_distance_jacobian", "line_to_line_distance_jacobian(x, [q1, ...], direction, line)", 4, 4, "d of line_to_line_squared_distance(robot line, line) / dq, the robot line through t along r direction r*: a quotient, 1 x n", "line_to_line_distance_jacobian(dh(theta1, 0, l, 0), [theta1], (1, 0, 0), line((0, 3/5, 4/5), (0, 0, 1)))", |n, v, _| task_jacobian(n, v, |n, v| {
            let l0 = vec_at(n, v, 2, "the direction")?;
            let (l, p) = workspace_line(n, v, 3)?;
            Ok(TaskJacobian::LineToLine(l0, l, p))
        }, false)),
    b("line_to_line_angle_jacobian", "line_to_line_angle_jacobian(x, [q1, ...], direction, line)", 4, 4, "d |P(l) - P(line)|^2 / dq, l = r direction r* the robot line's direction, 1 x n", "line_to_line_angle_jacobian(dh(theta1, 0, l, 0), [theta1], (1, 0, 0), line((0, 1, 0), (0, 0, 0)))", |n, v, _| task_jacobian(n, v, |n, v| {
            let l0 = vec_at(n, v, 2, "the direction")?;
            let (l, p) = workspace_line(n, v, 3)?;
            Ok(TaskJacobian::LineToLineAngle(l0, l, p))
        }, false)),
    b("pose_jacobian_derivative", "pose_jacobian_derivative(x, [q1, ...])", 2, 2, "the time derivative of the pose Jacobian, sum_k dJ/dq_k q_k_dot (rates named q_dot)", "pose_jacobian_derivative(dh(theta1, 0, l, 0) * dh(t, d1, 0, 0), [theta1, t])", |n, v, _| task_jacobian(n, v, |_, _| Ok(TaskJacobian::Pose), true)),
    b("rotation_jacobian_derivative", "rotation_jacobian_derivative(x, [q1, ...])", 2, 2, "the time derivative of rotation_jacobian (rates named q_dot)", "rotation_jacobian_derivative(dh(theta1, 0, l, 0) * dh(t, d1, 0, 0), [theta1, t])", |n, v, _| task_jacobian(n, v, |_, _| Ok(TaskJacobian::Rotation), true)),
    b("translation_jacobian_derivative", "translation_jacobian_derivative(x, [q1, ...])", 2, 2, "the time derivative of translation_jacobian (rates named q_dot)", "translation_jacobian_derivative(dh(theta1, 0, l, 0) * dh(t, d1, 0, 0), [theta1, t])", |n, v, _| task_jacobian(n, v, |_, _| Ok(TaskJacobian::Translation), true)),
    b("line_jacobian_derivative", "line_jacobian_derivative(x, [q1, ...], direction)", 3, 3, "the time derivative of line_jacobian (rates named q_dot)", "line_jacobian_derivative(dh(theta1, 0, l, 0), [theta1], (0, 0, 1))", |n, v, _| task_jacobian(n, v, |n, v| Ok(TaskJacobian::Line(vec_at(n, v, 2, "the direction")?)), true)),
    b("plane_jacobian_derivative", "plane_jacobian_derivative(x, [q1, ...], normal)", 3, 3, "the time derivative of plane_jacobian (rates named q_dot)", "plane_jacobian_derivative(dh(theta1, 0, l, 0), [theta1], (1, 0, 0))", |n, v, _| task_jacobian(n, v, |n, v| Ok(TaskJacobian::Plane(vec_at(n, v, 2, "the normal")?)), true)),
    b("distance_jacobian_derivative", "distance_jacobian_derivative(x, [q1, ...])", 2, 2, "the time derivative of distance_jacobian (rates named q_dot)", "distance_jacobian_derivative(dh(theta1, 0, l, 0) * dh(t, 0, l, 0), [theta1, t])", |n, v, _| task_jacobian(n, v, |_, _| Ok(TaskJacobian::Distance), true)),
];

fn dq_error(name: &str, e: DqError, a: &Arg) -> EvalError {
    invalid(&format!("`{name}`: {e}"), a.span)
}

/// A pure quaternion, a vector or a DQ `(0, v) + eps 0` as a 3-vector (a point, a direction).
fn vec3_arg(func: &str, what: &str, a: &Arg) -> Result<[Scalar; 3]> {
    match &a.value {
        Value::Vector(v) => return Ok(v.clone()),
        Value::Quat(q) if q.w.is_zero() => return Ok(q.vector_part()),
        Value::DualQuat(d) if d.real.w.is_zero() && d.dual.is_zero() => {
            return Ok(d.real.vector_part())
        }
        // A column or row of three, such as `vec3(...)`.
        Value::Matrix(m) => {
            let flat: Vec<&Scalar> = m.iter().flatten().collect();
            if let [x, y, z] = flat.as_slice() {
                if m.len() == 1 || m.len() == 3 {
                    return Ok([(*x).clone(), (*y).clone(), (*z).clone()]);
                }
            }
        }
        _ => {}
    }
    Err(type_error(
        func,
        what,
        "a vector (x, y, z), a pure quaternion (0, x, y, z) or a column of three",
        &a.value,
        a.span,
    ))
}

/// A DQ argument, vectors promoted to pure quaternions.
fn dq_arg(func: &str, a: &Arg) -> Result<DualQuat<Scalar>> {
    match &a.value {
        Value::Vector(v) => Ok(DualQuat::from_real(Quat::from_vector(v))),
        _ => dq_like(func, a),
    }
}

fn column(x: &[Scalar]) -> Value {
    Value::Matrix(x.iter().map(|s| vec![s.clone()]).collect())
}

fn square4(m: [[Scalar; 4]; 4]) -> Value {
    Value::Matrix(m.into_iter().map(|r| r.to_vec()).collect())
}

/// A DQ result that is a quaternion (dual part zero) when `quat` holds.
fn dq_value(d: DualQuat<Scalar>, quat: bool) -> Value {
    if quat && d.dual.is_zero() {
        Value::Quat(d.real)
    } else {
        Value::DualQuat(d)
    }
}

/// An optional angle-name argument: a symbol.
fn angle_arg<'v>(func: &str, a: Option<&'v Arg>) -> Result<Option<&'v Scalar>> {
    match a {
        None => Ok(None),
        Some(a) => match &a.value {
            Value::Scalar(s) if matches!(s.symbols().as_slice(), [x] if *s == Scalar::sym(x.name())) => {
                Ok(Some(s))
            }
            other => Err(type_error(
                func,
                "the angle name",
                "a symbol (psi = t * rotation angle)",
                other,
                a.span,
            )),
        },
    }
}

fn scalar_arg(func: &str, what: &str, a: &Arg) -> Result<Scalar> {
    match &a.value {
        Value::Scalar(s) => Ok(s.clone()),
        other => Err(type_error(func, what, "a scalar", other, a.span)),
    }
}

/// The built-in `C4`.
fn run_c4(_name: &'static str, _v: &[Arg], _span: Span) -> Result<Value> {
    Ok(square4(dqr::c4()))
}

/// The built-in `C8`.
fn run_c8(_name: &'static str, _v: &[Arg], _span: Span) -> Result<Value> {
    Ok(Value::Matrix(dqr::c8()))
}

/// The built-in `P`, `rotation`.
fn run_p(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let h = if name == "P" {
            dq_like(name, a)?
        } else {
            unit_dq(name, a)?
        };
        Value::Quat(dqr::primary(&h))
    })
}

/// The built-in `D`.
fn run_d(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::Quat(dqr::dual_part(&dq_like(name, a)?)))
}

/// The built-in `Re`.
fn run_re(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(dq_value(
        dqr::re(&dq_like(name, a)?),
        matches!(a.value, Value::Quat(_)),
    ))
}

/// The built-in `Im`.
fn run_im(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(dq_value(
        dqr::im(&dq_like(name, a)?),
        matches!(a.value, Value::Quat(_)),
    ))
}

/// The built-in `sharp`.
fn run_sharp(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::DualQuat(dqr::sharp(&dq_like(name, a)?)))
}

/// The built-in `norm`.
fn run_norm(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let h = dq_like(name, a)?;
        Value::DualQuat(dqexp::norm(&h).map_err(|e| dq_error(name, e, a))?)
    })
}

/// The built-in `inv`.
fn run_inv(_name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    value::inverse(&a.value).map_err(|e| op_error(e, a.span))
}

/// The built-in `translation`.
fn run_translation(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::Quat(dqr::translation(&unit_dq(name, a)?)))
}

/// The built-in `rotation_angle`.
fn run_rotation_angle(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::Scalar(
        dqexp::rotation_angle(&unit_dq(name, a)?).map_err(|e| dq_error(name, e, a))?,
    ))
}

/// The built-in `rotation_axis`.
fn run_rotation_axis(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::Quat(
        dqexp::rotation_axis(&unit_dq(name, a)?).map_err(|e| dq_error(name, e, a))?,
    ))
}

/// The built-in `log`.
fn run_log(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::DualQuat(
        dqexp::log(&unit_dq(name, a)?).map_err(|e| dq_error(name, e, a))?,
    ))
}

/// The built-in `screwlog`.
fn run_screwlog(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::DualQuat(
        dqexp::screw_log(&unit_dq(name, a)?).map_err(|e| dq_error(name, e, a))?,
    ))
}

/// The built-in `exp`.
fn run_exp(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let h = dq_like(name, a)?;
        let quat = matches!(a.value, Value::Quat(_));
        dq_value(dqexp::exp(&h).map_err(|e| dq_error(name, e, a))?, quat)
    })
}

/// The built-in `pow`, `screwpow`.
fn run_pow(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let h = unit_dq(name, a)?;
        let t = scalar_arg(name, "the exponent", &v[1])?;
        let psi = angle_arg(name, v.get(2))?;
        let r = if name == "pow" {
            dqexp::pow(&h, &t, psi)
        } else {
            dqexp::screw_pow(&h, &t, psi)
        };
        Value::DualQuat(r.map_err(|e| dq_error(name, e, a))?)
    })
}

/// The built-in `sclerp`, `sclerpdot`.
fn run_sclerp(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let q0 = unit_dq(name, a)?;
        let q1 = unit_dq(name, &v[1])?;
        let t = scalar_arg(name, "t", &v[2])?;
        let psi = angle_arg(name, v.get(3))?;
        let r = if name == "sclerp" {
            dqexp::sclerp(&q0, &q1, &t, psi)
        } else {
            dqexp::sclerp_derivative(&q0, &q1, &t, psi)
        };
        Value::DualQuat(r.map_err(|e| dq_error(name, e, a))?)
    })
}

/// The built-in `twist`, `bodytwist`.
fn run_twist(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let q = unit_dq(name, a)?;
        let qd = dq_like(name, &v[1])?;
        Value::DualQuat(dqexp::twist(&q, &qd, name == "bodytwist"))
    })
}

/// The built-in `qdot`.
fn run_qdot(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let q = unit_dq(name, a)?;
        let xi = dq_arg(name, &v[1])?;
        Value::DualQuat(dqexp::from_twist(&q, &xi, false))
    })
}

/// The built-in `tplus`.
fn run_tplus(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::DualQuat(dqr::tplus(&unit_dq(name, a)?)))
}

/// The built-in `normalize`.
fn run_normalize(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::DualQuat(
        dqexp::normalize(&dq_like(name, a)?).map_err(|e| dq_error(name, e, a))?,
    ))
}

/// The built-in `crossmatrix4`.
fn run_crossmatrix4(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(square4(dqr::crossmatrix4(&Quat::from_vector(&vec3_arg(
        name,
        "the argument",
        a,
    )?))))
}

/// The built-in `point_projected_in_line`.
fn run_point_projected_in_line(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let p = vec3_arg(name, "the point", a)?;
        let l = line_arg(name, &v[1])?;
        Value::Quat(Quat::from_vector(&dqr::point_projected_in_line(&p, &l)))
    })
}

/// The built-in `closest_points_between_lines`.
fn run_closest_points_between_lines(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let (l1, l2) = (line_arg(name, a)?, line_arg(name, &v[1])?);
        let (p1, p2, den) = dqr::closest_points_between_lines(&l1, &l2).ok_or_else(|| {
            invalid(
                &format!(
                    "`{name}`: the lines are parallel, so their closest points are not unique"
                ),
                a.span,
            )
        })?;
        let mut rows = Vec::with_capacity(2);
        for p in [p1, p2] {
            let mut row = Vec::with_capacity(3);
            for x in p {
                row.push(
                    Frac::new(x, den.clone()).map_err(|e| super::eval::scalar_error(e, a.span))?,
                );
            }
            rows.push(row);
        }
        value::quotient_matrix(rows)
    })
}

/// The built-in `Ad`, `Adsharp`.
fn run_ad(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let g = dq_like(name, a)?;
        let x = dq_arg(name, &v[1])?;
        let quat =
            !matches!(v[1].value, Value::DualQuat(_)) && !matches!(a.value, Value::DualQuat(_));
        let r = if name == "Ad" {
            dqr::ad(&g, &x)
        } else {
            dqr::adsharp(&g, &x)
        };
        dq_value(r, quat)
    })
}

/// The built-in `hamiplus4`.
fn run_hamiplus4(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(square4(dqr::hamiplus4(&dq_like(name, a)?.real)))
}

/// The built-in `haminus4`.
fn run_haminus4(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(square4(dqr::haminus4(&dq_like(name, a)?.real)))
}

/// The built-in `hamiplus8`.
fn run_hamiplus8(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::Matrix(dqr::hamiplus8(&dq_like(name, a)?)))
}

/// The built-in `haminus8`.
fn run_haminus8(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(Value::Matrix(dqr::haminus8(&dq_like(name, a)?)))
}

/// The built-in `vec3`.
fn run_vec3(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(column(&dq_arg(name, a)?.real.vector_part()))
}

/// The built-in `vec4`.
fn run_vec4(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(column(&dq_arg(name, a)?.real.components()))
}

/// The built-in `vec6`.
fn run_vec6(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(column(&dqr::vec6(&dq_arg(name, a)?)))
}

/// The built-in `vec8`.
fn run_vec8(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok(column(&dq_arg(name, a)?.components()))
}

/// The built-in `cross`, `dot`.
fn run_cross(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let (x, y) = (dq_arg(name, a)?, dq_arg(name, &v[1])?);
        let vectors = matches!(
            (&a.value, &v[1].value),
            (Value::Vector(_), Value::Vector(_))
        );
        let quats =
            !matches!(a.value, Value::DualQuat(_)) && !matches!(v[1].value, Value::DualQuat(_));
        if name == "cross" {
            let r = dqr::cross(&x, &y);
            if vectors {
                Value::Vector(r.real.vector_part())
            } else {
                dq_value(r, quats)
            }
        } else {
            let r = dqr::dot(&x, &y);
            if vectors {
                Value::Scalar(r.real.w)
            } else {
                dq_value(r, quats)
            }
        }
    })
}

/// The built-in `line`, `plane`.
fn run_line(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let d = vec3_arg(name, "the direction", a)?;
        let p = vec3_arg(name, "the point", &v[1])?;
        Value::DualQuat(if name == "line" {
            dqr::line(&d, &p)
        } else {
            dqr::plane(&d, &p)
        })
    })
}

/// The built-in `point_to_point_squared_distance`.
fn run_point_to_point_squared_distance(
    name: &'static str,
    v: &[Arg],
    _span: Span,
) -> Result<Value> {
    let a = &v[0];
    Ok({
        let p = vec3_arg(name, "the first point", a)?;
        let q = vec3_arg(name, "the second point", &v[1])?;
        Value::Scalar(dqr::point_to_point_squared_distance(&p, &q))
    })
}

/// The built-in `point_to_line_squared_distance`.
fn run_point_to_line_squared_distance(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let p = vec3_arg(name, "the point", a)?;
        let l = line_arg(name, &v[1])?;
        Value::Scalar(dqr::point_to_line_squared_distance(&p, &l))
    })
}

/// The built-in `point_to_plane_distance`.
fn run_point_to_plane_distance(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let p = vec3_arg(name, "the point", a)?;
        let pl = dq_like(name, &v[1])?;
        Value::Scalar(dqr::point_to_plane_distance(&p, &pl))
    })
}

/// The built-in `line_to_line_squared_distance`.
fn run_line_to_line_squared_distance(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let (l1, l2) = (line_arg(name, a)?, line_arg(name, &v[1])?);
        let (num, den) = dqr::line_to_line_squared_distance(&l1, &l2);
        let f = Frac::new(num, den).map_err(|e| super::eval::scalar_error(e, a.span))?;
        match f.as_scalar() {
            Some(s) => Value::Scalar(s.clone()),
            None => value::quotient_matrix(vec![vec![f]]),
        }
    })
}

/// The built-in `line_to_line_angle`.
fn run_line_to_line_angle(name: &'static str, v: &[Arg], _span: Span) -> Result<Value> {
    let a = &v[0];
    Ok({
        let (l1, l2) = (line_arg(name, a)?, line_arg(name, &v[1])?);
        let c = dqr::line_to_line_cos(&l1, &l2);
        let phi = c.as_cos_of_angle().ok_or_else(|| {
            invalid(
                &format!(
                    "`{name}`: P(dot(l1, l2)) = {} is not visibly cos of an angle; it is the cosine of the angle",
                    super::builtins::text(&c)
                ),
                a.span,
            )
        })?;
        Value::Scalar(phi)
    })
}

/// How a task-Jacobian built-in reads its kind from its arguments (after the pose and the
/// variables).
type TaskKind = fn(&'static str, &[Arg]) -> Result<TaskJacobian>;

/// Argument `k` as a vector.
fn vec_at(name: &'static str, v: &[Arg], k: usize, what: &str) -> Result<[Scalar; 3]> {
    vec3_arg(name, what, &v[k])
}

/// Argument `k` as a workspace line: its direction and a point on it.
fn workspace_line(name: &'static str, v: &[Arg], k: usize) -> Result<([Scalar; 3], [Scalar; 3])> {
    let l = line_arg(name, &v[k])?;
    Ok((l.real.vector_part(), point_on_line(&l)))
}

/// The task Jacobian built-ins: `x`, the variables, then what `kind` reads; its time
/// derivative when `derivative`.
fn task_jacobian(name: &'static str, v: &[Arg], kind: TaskKind, derivative: bool) -> Result<Value> {
    let a = &v[0];
    let x = unit_dq(name, a)?;
    let vars = symbol_list(name, &v[1])?;
    let task = kind(name, v)?;
    let task = if derivative {
        TaskJacobian::Derivative(Box::new(task))
    } else {
        task
    };
    let refs: Vec<&str> = vars.iter().map(String::as_str).collect();
    let m = crate::app::task_jacobian(&x, &refs, &task);
    Ok(match m.as_polynomial() {
        Some(rows) => Value::Matrix(rows.clone()),
        None => {
            let mut rows = Vec::with_capacity(m.num.len());
            for r in &m.num {
                let mut row = Vec::with_capacity(r.len());
                for e in r {
                    row.push(
                        Frac::new(e.clone(), m.den.clone())
                            .map_err(|e| super::eval::scalar_error(e, a.span))?,
                    );
                }
                rows.push(row);
            }
            value::quotient_matrix(rows)
        }
    })
}

/// A Plücker line: a DQ with pure parts whose constraints hold exactly.
fn line_arg(func: &str, a: &Arg) -> Result<DualQuat<Scalar>> {
    let l = dq_like(func, a)?;
    let (n, o) = dqr::line_constraints(&l);
    if !l.real.w.is_zero() || !l.dual.w.is_zero() || !n.is_zero() || !o.is_zero() {
        return Err(invalid(
            &format!(
                "`{func}` needs a line l + eps m (pure, |l| = 1, l . m = 0), but |l|^2 - 1 = {} and l . m = {}",
                super::builtins::text(&n),
                super::builtins::text(&o)
            ),
            a.span,
        ));
    }
    Ok(l)
}

/// A point of the line `l + eps m` (unit `l`): `l x m`, the point nearest the origin.
fn point_on_line(l: &DualQuat<Scalar>) -> [Scalar; 3] {
    crate::algebra::cross(&l.real.vector_part(), &l.dual.vector_part())
}

/// A plane `n + eps d` (pure primary part, unit `n`, scalar dual part) as its normal and the
/// point `d n` on it.
fn plane_arg(func: &str, a: &Arg) -> Result<([Scalar; 3], [Scalar; 3])> {
    let pl = dq_like(func, a)?;
    let n = pl.real.vector_part();
    let unit = dqr::dot3(&n, &n) - Scalar::int(1);
    let problem = if !pl.real.w.is_zero() {
        Some(format!(
            "P(plane) has the scalar part {}",
            super::builtins::text(&pl.real.w)
        ))
    } else if !pl.dual.vector_part().iter().all(Zero::is_zero) {
        Some("D(plane) has a vector part".to_owned())
    } else if !unit.is_zero() {
        Some(format!("|n|^2 - 1 = {}", super::builtins::text(&unit)))
    } else {
        None
    };
    if let Some(p) = problem {
        return Err(invalid(
            &format!("`{func}` needs a plane n + eps d (n pure and unit, d a scalar), but {p}"),
            a.span,
        ));
    }
    let d = pl.dual.w.clone();
    Ok((n.clone(), [&n[0] * &d, &n[1] * &d, &n[2] * &d]))
}
