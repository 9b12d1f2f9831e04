//! Joint axes as exact Plücker lines in the home pose, and the exact decisions on them
//! (parallel, intersecting, a common point) that choose a closed-form solver.

use crate::kin::{JointGeometry, JointKind, Robot};
use crate::{Matrix4, Scalar};

/// A 3-vector of exact scalars.
pub type V3 = [Scalar; 3];

pub(crate) fn add(a: &V3, b: &V3) -> V3 {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]]
}

pub(crate) fn sub(a: &V3, b: &V3) -> V3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

pub(crate) fn scale(k: &Scalar, a: &V3) -> V3 {
    [k * &a[0], k * &a[1], k * &a[2]]
}

pub(crate) fn dot(a: &V3, b: &V3) -> Scalar {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

pub(crate) fn cross(a: &V3, b: &V3) -> V3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

pub(crate) fn is_zero3(a: &V3) -> bool {
    a.iter().all(Scalar::is_zero_value)
}

pub(crate) fn zero3() -> V3 {
    [Scalar::int(0), Scalar::int(0), Scalar::int(0)]
}

/// `Rot(w, angle) v` by Rodrigues' formula, with `c`, `s` the cosine and sine of the angle
/// (`w` a unit vector).
pub(crate) fn rotate(w: &V3, c: &Scalar, s: &Scalar, v: &V3) -> V3 {
    let wv = dot(w, v);
    let one_c = Scalar::int(1) - c;
    let wxv = cross(w, v);
    let mut out = zero3();
    for i in 0..3 {
        out[i] = &v[i] * c + &wxv[i] * s + &w[i] * &wv * &one_c;
    }
    out
}

/// One joint axis in the home pose: a Plücker line (`dir`, `moment = point × dir`).
#[derive(Clone, Debug)]
pub struct Axis {
    /// Revolute (rotation about the line) or prismatic (slide along `dir`).
    pub kind: JointKind,
    /// The joint variable's name.
    pub variable: String,
    /// Unit direction.
    pub dir: V3,
    /// A point of the line.
    pub point: V3,
    /// `point × dir`.
    pub moment: V3,
}

impl Axis {
    fn new(kind: JointKind, variable: &str, dir: V3, point: V3) -> Axis {
        let moment = cross(&point, &dir);
        Axis {
            kind,
            variable: variable.to_string(),
            dir,
            point,
            moment,
        }
    }

    /// The same line with its direction reversed: its motion at `q` is this axis's motion at
    /// `−q`, so a chain read backwards, `E6⁻¹ ⋯ E1⁻¹`, is a chain of reversed axes at the same
    /// variables.
    pub(crate) fn reversed(&self) -> Axis {
        let neg = Scalar::int(-1);
        Axis::new(
            self.kind,
            &self.variable,
            scale(&neg, &self.dir),
            self.point.clone(),
        )
    }

    /// `cos` and `sin` of the joint variable (`sign` -1 for the inverse motion).
    pub(crate) fn cs(&self, sign: i64) -> (Scalar, Scalar) {
        let q = Scalar::sym(&self.variable);
        (q.cos(), Scalar::int(sign) * q.sin())
    }

    /// The joint's motion applied to a point (`sign` -1: its inverse).
    pub(crate) fn move_point(&self, x: &V3, sign: i64) -> V3 {
        match self.kind {
            JointKind::Revolute => {
                let (c, s) = self.cs(sign);
                add(
                    &self.point,
                    &rotate(&self.dir, &c, &s, &sub(x, &self.point)),
                )
            }
            JointKind::Prismatic => {
                let q = Scalar::int(sign) * Scalar::sym(&self.variable);
                add(x, &scale(&q, &self.dir))
            }
        }
    }

    /// The joint's rotation applied to a direction (`sign` -1: its inverse).
    pub(crate) fn move_dir(&self, v: &V3, sign: i64) -> V3 {
        match self.kind {
            JointKind::Revolute => {
                let (c, s) = self.cs(sign);
                rotate(&self.dir, &c, &s, v)
            }
            JointKind::Prismatic => v.clone(),
        }
    }

    /// This axis carried by the motion of `by` at its (symbolic) variable.
    pub(crate) fn moved_by(&self, by: &Axis) -> Axis {
        Axis::new(
            self.kind,
            &self.variable,
            by.move_dir(&self.dir, 1),
            by.move_point(&self.point, 1),
        )
    }
}

/// How two axes lie, decided exactly.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Relation {
    /// Directions parallel (cross product zero); `same_line` when the lines coincide.
    Parallel {
        /// The lines coincide.
        same_line: bool,
    },
    /// Not parallel, reciprocal product zero.
    Intersecting,
    /// Neither, for every value of the parameters.
    Skew,
    /// Skew, except where the reciprocal product (shown) vanishes.
    SkewUnless(Scalar),
}

/// The relation of two axes: parallel when `d1 × d2 = 0`, intersecting when not parallel and
/// the reciprocal product `d1·m2 + d2·m1` is zero.
pub fn relation(a: &Axis, b: &Axis) -> Relation {
    let c = cross(&a.dir, &b.dir);
    if is_zero3(&c) {
        let same_line = is_zero3(&cross(&sub(&b.point, &a.point), &a.dir));
        return Relation::Parallel { same_line };
    }
    let r = dot(&a.dir, &b.moment) + dot(&b.dir, &a.moment);
    if r.is_zero_value() {
        Relation::Intersecting
    } else if r.is_constant() {
        Relation::Skew
    } else {
        Relation::SkewUnless(r)
    }
}

/// The common point of two intersecting, non-parallel axes, or `None` when the parameters
/// would need a division by a symbolic expression.
pub fn intersection(a: &Axis, b: &Axis) -> Option<V3> {
    let n = cross(&a.dir, &b.dir);
    let n2 = dot(&n, &n);
    let t = dot(&cross(&sub(&b.point, &a.point), &b.dir), &n)
        .try_div(&n2)
        .ok()?;
    let p = add(&a.point, &scale(&t, &a.dir));
    p.iter().all(|x| x.as_error().is_none()).then_some(p)
}

/// True when the point lies on the axis's line.
pub fn on_line(p: &V3, a: &Axis) -> bool {
    is_zero3(&cross(&sub(p, &a.point), &a.dir))
}

/// The joint axes of a robot in its home pose (every joint variable zero), and the home pose
/// `M` of the end effector: `FK(q) = E1(q1) ... En(qn) M`, `Ei` the motion about axis `i`.
pub fn home_axes(robot: &Robot) -> (Vec<Axis>, Matrix4<Scalar>) {
    let zero = Scalar::int(0);
    let mut frame = Matrix4::identity();
    let mut axes = Vec::new();
    let col = |m: &Matrix4<Scalar>, c: usize| -> V3 {
        [
            m.rows[0][c].clone(),
            m.rows[1][c].clone(),
            m.rows[2][c].clone(),
        ]
    };
    for (j, var) in robot.chain.joints.iter().zip(&robot.variables) {
        let home = j.matrix(&zero);
        match &j.geometry {
            JointGeometry::Dh { .. } => {
                axes.push(Axis::new(j.kind, var, col(&frame, 2), col(&frame, 3)));
                frame = frame.mul_ref(&home);
            }
            JointGeometry::Mdh { .. } => {
                frame = frame.mul_ref(&home);
                axes.push(Axis::new(j.kind, var, col(&frame, 2), col(&frame, 3)));
            }
            JointGeometry::Screw { axis, point } => {
                axes.push(Axis::new(j.kind, var, axis.clone(), point.clone()));
                frame = frame.mul_ref(&home);
            }
            JointGeometry::Local { axis, .. } => {
                // The joint's frames carried to the base: the axis is the frame's rotation of
                // the local direction, through the frame's origin (frames at symbolic angles
                // reach a size limit here, an error value the callers report).
                frame = frame.mul_ref(&home);
                let r = |i: usize| -> Scalar {
                    (0..3)
                        .map(|k| &frame.rows[i][k] * &axis[k])
                        .fold(Scalar::int(0), |a, b| a + b)
                };
                axes.push(Axis::new(j.kind, var, [r(0), r(1), r(2)], col(&frame, 3)));
            }
        }
    }
    let m = frame.mul_ref(&robot.chain.tool.to_matrix());
    (axes, m)
}

/// The joint axes and home pose of a chain given as one symbolic unit DQ `Q(q1, ..., qn)`
/// (a product of joint motions): with every variable 0, `Q = M` and `2 (dQ/dqi) M*` is the
/// pure dual quaternion `k + eps m` of joint i's line (revolute), or `eps v` (prismatic).
/// `None` when a derivative is not a line of that form.
pub fn dq_axes(
    q: &crate::DualQuat<Scalar>,
    variables: &[String],
) -> Option<(Vec<Axis>, Matrix4<Scalar>)> {
    dq_axes_checked(q, variables).ok().flatten()
}

/// The joint axes of a chain and its home pose.
pub type AxesAndHome = (Vec<Axis>, Matrix4<Scalar>);

/// [`dq_axes`], with a limit reached while reading the axes (a base frame at angles off the
/// pi/12 grid multiplies every component's terms) as that limit, not as "not a line".
///
/// # Errors
/// The [`ScalarError`](crate::ScalarError) of the first component or check that reached a limit.
pub fn dq_axes_checked(
    q: &crate::DualQuat<Scalar>,
    variables: &[String],
) -> Result<Option<AxesAndHome>, crate::ScalarError> {
    let zero = Scalar::int(0);
    let at_home = |x: &Scalar| -> Scalar {
        let mut y = x.clone();
        for v in variables {
            y = y.subs(v, &zero);
        }
        y
    };
    let comps = q.components();
    let home: Vec<Scalar> = comps.iter().map(at_home).collect();
    let m = crate::DualQuat::from_components(std::array::from_fn(|i| home[i].clone()));
    let mut axes = Vec::new();
    for v in variables {
        let d: [Scalar; 8] = std::array::from_fn(|i| at_home(&comps[i].diff(v)));
        let d = crate::DualQuat::from_components(d);
        let xi = (d * m.conjugate()).components();
        let two = Scalar::int(2);
        let xi: Vec<Scalar> = xi.iter().map(|x| &two * x).collect();
        for x in &xi {
            x.try_is_zero()?;
        }
        if !xi[0].is_zero_value() || !xi[4].is_zero_value() {
            return Ok(None);
        }
        let w: V3 = [xi[1].clone(), xi[2].clone(), xi[3].clone()];
        let e: V3 = [xi[5].clone(), xi[6].clone(), xi[7].clone()];
        if is_zero3(&w) {
            let ee = dot(&e, &e);
            ee.try_is_zero()?;
            if is_zero3(&e) || !ee.is_constant() {
                return Ok(None);
            }
            axes.push(Axis::new(JointKind::Prismatic, v, e, zero3()));
        } else {
            let (ww, we) = (dot(&w, &w), dot(&w, &e));
            ww.try_is_zero()?;
            if ww != Scalar::int(1) || !we.try_is_zero()? {
                return Ok(None);
            }
            let p = cross(&w, &e);
            axes.push(Axis::new(JointKind::Revolute, v, w, p));
        }
    }
    Ok(Some((axes, m.to_matrix())))
}
