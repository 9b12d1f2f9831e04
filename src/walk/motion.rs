//! Rigid motions described by their geometry: what a factor means in words, and its 4x4
//! homogeneous matrix built from elementary rotations and translations (never from a dual
//! quaternion), which is the oracle of a walkthrough's check.

use crate::{
    kin::{dh_link_matrix, mdh_link_matrix, screw_parameters},
    DualQuat, Frac, Matrix4, Quat, Scalar, ScalarError,
};
use num_traits::Zero;

/// A rigid motion given by its geometry.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Motion {
    /// A rotation by `angle` about the line through `point` with unit direction `axis`, and a
    /// slide along it (eq 16, 18).
    Screw {
        /// The unit direction.
        axis: [Scalar; 3],
        /// A point of the axis.
        point: [Scalar; 3],
        /// The rotation angle.
        angle: Scalar,
        /// The slide along the axis.
        slide: Scalar,
    },
    /// A translation.
    Translation {
        /// The displacement.
        t: [Scalar; 3],
    },
    /// The classic DH link `Rz(theta) Tz(d) Tx(a) Rx(alpha)`.
    Dh {
        /// Joint angle.
        theta: Scalar,
        /// Link offset.
        d: Scalar,
        /// Link length.
        a: Scalar,
        /// Link twist.
        alpha: Scalar,
    },
    /// Craig's modified DH link `Rx(alpha) Tx(a) Rz(theta) Tz(d)`.
    Mdh {
        /// Link twist.
        alpha: Scalar,
        /// Link length.
        a: Scalar,
        /// Joint angle.
        theta: Scalar,
        /// Link offset.
        d: Scalar,
    },
}

/// A piece of a description: words, or a value to typeset.
#[derive(Clone, Debug, PartialEq)]
pub enum Word {
    /// Plain words.
    Text(String),
    /// A scalar, shown in closed form.
    Scalar(Scalar),
    /// A tuple `(x, y, z)` of scalars.
    Tuple(Vec<Scalar>),
}

/// A description in words with values in it.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Words(pub Vec<Word>);

impl Words {
    pub(crate) fn text(s: &str) -> Words {
        Words(vec![Word::Text(s.to_owned())])
    }

    fn t(mut self, s: &str) -> Words {
        self.0.push(Word::Text(s.to_owned()));
        self
    }

    fn s(mut self, x: &Scalar) -> Words {
        self.0.push(Word::Scalar(x.clone()));
        self
    }

    fn v(mut self, x: &[Scalar]) -> Words {
        self.0.push(Word::Tuple(x.to_vec()));
        self
    }
}

fn zero3(v: &[Scalar; 3]) -> bool {
    v.iter().all(Scalar::is_zero_value)
}

/// `x`, `y`, `z` (or `-x`, ...) for a coordinate axis.
fn axis_name(axis: &[Scalar; 3]) -> Option<String> {
    let nonzero: Vec<usize> = (0..3).filter(|&k| !axis[k].is_zero_value()).collect();
    let [k] = nonzero.as_slice() else {
        return None;
    };
    let name = ["x", "y", "z"][*k];
    if axis[*k] == Scalar::int(1) {
        Some(name.to_owned())
    } else if axis[*k] == Scalar::int(-1) {
        Some(format!("-{name}"))
    } else {
        None
    }
}

impl Motion {
    /// The motion in words: "rotation of theta3 about the x-parallel axis through
    /// (0, l1 + l2, 0)".
    pub fn describe(&self) -> Words {
        match self {
            Motion::Screw {
                axis,
                point,
                angle,
                slide,
            } => {
                let about = |w: Words| match (axis_name(axis), zero3(point)) {
                    (Some(n), true) => w.t(&format!("the {n} axis")),
                    (Some(n), false) => w.t(&format!("the {n}-parallel axis through ")).v(point),
                    (None, true) => w.t("the axis ").v(axis).t(" through the origin"),
                    (None, false) => w.t("the axis ").v(axis).t(" through ").v(point),
                };
                if angle.is_zero_value() {
                    return about(Words::text("translation of ").s(slide).t(" along "));
                }
                let w = if slide.is_zero_value() {
                    Words::text("rotation of ")
                } else {
                    Words::text("screw motion: rotation of ")
                };
                let w = about(w.s(angle).t(" about "));
                if slide.is_zero_value() {
                    w
                } else {
                    w.t(", with a slide of ").s(slide).t(" along it")
                }
            }
            Motion::Translation { t } => Words::text("translation by ").v(t),
            Motion::Dh { theta, d, a, alpha } => Words::text("classic DH link: rotation of ")
                .s(theta)
                .t(" about z, slide of ")
                .s(d)
                .t(" along z, slide of ")
                .s(a)
                .t(" along x, twist of ")
                .s(alpha)
                .t(" about x"),
            Motion::Mdh { alpha, a, theta, d } => {
                Words::text("modified (Craig) DH link: twist of ")
                    .s(alpha)
                    .t(" about x, slide of ")
                    .s(a)
                    .t(" along x, rotation of ")
                    .s(theta)
                    .t(" about z, slide of ")
                    .s(d)
                    .t(" along z")
            }
        }
    }

    /// The elementary matrices this motion is built of, in words, for the check.
    pub fn oracle(&self) -> &'static str {
        match self {
            Motion::Screw { .. } => "T(p) R(n, angle) T(-p) T(slide n)",
            Motion::Translation { .. } => "T(t)",
            Motion::Dh { .. } => "Rz(theta) Tz(d) Tx(a) Rx(alpha)",
            Motion::Mdh { .. } => "Rx(alpha) Tx(a) Rz(theta) Tz(d)",
        }
    }

    /// The 4x4 homogeneous matrix at the symbol values `env`, from elementary matrices.
    ///
    /// # Errors
    /// When a parameter names a symbol `env` has no value for.
    pub fn matrix(&self, env: &dyn Fn(&str) -> Option<f64>) -> Result<Matrix4<f64>, ScalarError> {
        let f = |x: &Scalar| x.eval(env);
        let f3 = |v: &[Scalar; 3]| -> Result<[f64; 3], ScalarError> {
            Ok([f(&v[0])?, f(&v[1])?, f(&v[2])?])
        };
        Ok(match self {
            Motion::Screw {
                axis,
                point,
                angle,
                slide,
            } => {
                let (n, p, a, t) = (f3(axis)?, f3(point)?, f(angle)?, f(slide)?);
                Matrix4::trans(&p)
                    * Matrix4::rotation(&n, &a)
                    * Matrix4::trans(&[-p[0], -p[1], -p[2]])
                    * Matrix4::trans(&[t * n[0], t * n[1], t * n[2]])
            }
            Motion::Translation { t } => Matrix4::trans(&f3(t)?),
            Motion::Dh { theta, d, a, alpha } => {
                dh_link_matrix(&f(theta)?, &f(d)?, &f(a)?, &f(alpha)?)
            }
            Motion::Mdh { alpha, a, theta, d } => {
                mdh_link_matrix(&f(alpha)?, &f(a)?, &f(theta)?, &f(d)?)
            }
        })
    }

    /// The symbols of the motion's angle (a revolute joint) or slide (a prismatic one).
    pub fn variables(&self) -> Vec<String> {
        let of = |x: &Scalar| -> Vec<String> {
            x.symbols()
                .into_iter()
                .filter(|s| !s.is_pi())
                .map(|s| s.name().to_owned())
                .collect()
        };
        match self {
            Motion::Screw { angle, slide, .. } => {
                let v = of(angle);
                if v.is_empty() {
                    of(slide)
                } else {
                    v
                }
            }
            Motion::Translation { t } => t.iter().flat_map(of).collect(),
            Motion::Dh { theta, d, .. } | Motion::Mdh { theta, d, .. } => {
                let v = of(theta);
                if v.is_empty() {
                    of(d)
                } else {
                    v
                }
            }
        }
    }

    /// The motion of a unit dual quaternion, read from its screw parameters (sec 4): `None`
    /// when they are not exact scalars (a general motion whose axis needs a quotient).
    pub fn of_dual_quat(q: &DualQuat<Scalar>) -> Option<Motion> {
        if !q.unit_constraints().hold_exactly() {
            return None;
        }
        if q.real == Quat::identity() {
            let t = q.translation_part();
            return (!zero3(&t)).then_some(Motion::Translation { t });
        }
        if let Some(m) = joint_screw(q) {
            return Some(m);
        }
        let p = screw_parameters(q).ok()?;
        let sc = |f: &Frac| f.as_scalar().cloned();
        let v3 =
            |v: &[Frac; 3]| -> Option<[Scalar; 3]> { Some([sc(&v[0])?, sc(&v[1])?, sc(&v[2])?]) };
        Some(Motion::Screw {
            axis: v3(&p.axis)?,
            point: v3(&p.point)?,
            angle: p.angle,
            slide: sc(&p.slide)?,
        })
    }
}

/// The screw of a joint factor whose angle is one symbol: every division by `sin(theta/2)`
/// is exact there, and reading the parts at `theta = pi` (where `sin(theta/2) = 1` and
/// `cos(theta/2) = 0`) gives the quotients, each verified by multiplying back.
fn joint_screw(q: &DualQuat<Scalar>) -> Option<Motion> {
    let half = q.real.w.as_cos_of_angle()?;
    let angle = &half + &half;
    let syms: Vec<String> = angle
        .symbols()
        .into_iter()
        .filter(|s| !s.is_pi())
        .map(|s| s.name().to_owned())
        .collect();
    let [theta] = syms.as_slice() else {
        return None;
    };
    if angle != Scalar::sym(theta) {
        return None;
    }
    let (c, s) = (half.cos(), half.sin());
    let at_pi = |x: &Scalar| x.subs(theta, &Scalar::pi());
    let v = q.real.vector_part();
    let axis = [at_pi(&v[0]), at_pi(&v[1]), at_pi(&v[2])];
    let slide = -(at_pi(&q.dual.w) * Scalar::int(2));
    let ve = q.dual.vector_part();
    let m = [at_pi(&ve[0]), at_pi(&ve[1]), at_pi(&ve[2])];
    let half_t =
        slide.clone() * Scalar::rational(num_rational::BigRational::new(1.into(), 2.into()));
    for k in 0..3 {
        if &s * &axis[k] != v[k] || &s * &m[k] + &c * &half_t * &axis[k] != ve[k] {
            return None;
        }
    }
    if -(&s * &half_t) != q.dual.w {
        return None;
    }
    let point = [
        &axis[1] * &m[2] - &axis[2] * &m[1],
        &axis[2] * &m[0] - &axis[0] * &m[2],
        &axis[0] * &m[1] - &axis[1] * &m[0],
    ];
    Some(Motion::Screw {
        axis,
        point,
        angle,
        slide,
    })
}

/// Whether `q` is a point DQ `1 + eps (0, v)`.
pub(crate) fn is_point(q: &DualQuat<Scalar>) -> bool {
    q.real == Quat::identity() && q.dual.w.is_zero()
}
