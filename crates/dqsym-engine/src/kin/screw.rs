//! Screw parameters of a unit dual quaternion (sec 4 and the corrected eq 18): the rigid motion
//! as a rotation of `theta` about an axis `n` through a point, with a slide `t` along it.

use crate::{DualQuat, Frac, Scalar, ScalarError};
use thiserror::Error;

/// The screw of a unit DQ `(c, s n) + eps (1/2)(-s t, c t n + 2 s m)`, `c, s = cos, sin(theta/2)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ScrewParams {
    /// The rotation angle `theta`.
    pub angle: Scalar,
    /// The unit axis direction `n`.
    pub axis: [Frac; 3],
    /// The slide `t` along the axis.
    pub slide: Frac,
    /// The moment `m = p x n` of the axis about the origin.
    pub moment: [Frac; 3],
    /// The point of the axis nearest the origin, `n x m`; for a planar displacement, its centre.
    pub point: [Frac; 3],
}

/// Why screw parameters could not be read.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ScrewError {
    /// The motion is a pure translation (or the identity): it has no screw axis.
    #[error("a pure translation has no screw axis")]
    PureTranslation,
    /// The scalar part of the rotation is not visibly `cos(theta/2)`.
    #[error("cannot read the rotation angle: the scalar part {0} is not cos of an angle")]
    Angle(String),
    /// An exact operation failed.
    #[error(transparent)]
    Scalar(#[from] ScalarError),
}

/// The screw parameters of a unit DQ, exact. Divisions by `sin(theta/2)` are kept as quotients
/// ([`Frac`]), so the centres of sec 4 come out with their `cos/sin` of half angles.
pub fn screw_parameters(q: &DualQuat<Scalar>) -> Result<ScrewParams, ScrewError> {
    let half = q
        .real
        .w
        .as_cos_of_angle()
        .ok_or_else(|| ScrewError::Angle(q.real.w.to_string()))?;
    let (c, s) = (half.cos().check()?, half.sin().check()?);
    if s.is_zero_value() {
        return Err(ScrewError::PureTranslation);
    }
    let v = q.real.vector_part();
    let ve = q.dual.vector_part();
    let axis = [
        Frac::new(v[0].clone(), s.clone())?,
        Frac::new(v[1].clone(), s.clone())?,
        Frac::new(v[2].clone(), s.clone())?,
    ];
    let slide = Frac::new(-(&q.dual.w * Scalar::int(2)), s.clone())?;
    // m = (2 v_e - c t n) / (2 s).
    let ct = Frac::from(c).mul(&slide)?;
    let two_s = Frac::from(&s * Scalar::int(2));
    let mut moment = Vec::with_capacity(3);
    for k in 0..3 {
        let num = Frac::from(&ve[k] * Scalar::int(2)).sub(&ct.mul(&axis[k])?)?;
        moment.push(num.div(&two_s)?);
    }
    let moment: [Frac; 3] = [moment[0].clone(), moment[1].clone(), moment[2].clone()];
    let cross = |a: &[Frac; 3], b: &[Frac; 3], i: usize, j: usize| -> Result<Frac, ScalarError> {
        a[i].mul(&b[j])?.sub(&a[j].mul(&b[i])?)
    };
    let point = [
        cross(&axis, &moment, 1, 2)?,
        cross(&axis, &moment, 2, 0)?,
        cross(&axis, &moment, 0, 1)?,
    ];
    Ok(ScrewParams {
        angle: half * Scalar::int(2),
        axis,
        slide,
        moment,
        point,
    })
}
