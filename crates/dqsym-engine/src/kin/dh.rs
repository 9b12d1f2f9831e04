//! Denavit–Hartenberg links: the classic convention and Craig's modified one.
//!
//! The paper's sec 5 calls `rot(x, α) trans(x, a) rot(z, θ) trans(z, d)` "standard" DH; it is
//! Craig's modified DH (ERRATA, "Notation clashes"). Both are provided under their usual
//! names: [`dh_link`] is the classic `Rz Tz Tx Rx`, [`mdh_link`] is Craig's `Rx Tx Rz Tz`.

use crate::algebra::mul;
use crate::{DualQuat, Matrix4, Quat, Ring};

/// The screw along a coordinate axis (`0 = x`, `1 = y`, `2 = z`): rotation by `angle` about
/// it and translation by `slide` along it, which commute.
///
/// `(c, s e) + (ε/2)(−s t, c t e)`, eq 16, with `e` the unit axis vector; written out
/// because the general [`DualQuat::screw`] would multiply by a zero point and axis entries.
fn axis_screw<T: Ring>(axis: usize, angle: &T, slide: &T) -> DualQuat<T> {
    let half = angle.half();
    let (c, s) = (half.cos(), half.sin());
    let half_t = slide.half();
    let mut real = [c.clone(), T::zero(), T::zero(), T::zero()];
    let mut dual = [-mul(&s, &half_t), T::zero(), T::zero(), T::zero()];
    real[axis + 1] = s;
    dual[axis + 1] = mul(&c, &half_t);
    DualQuat::from_real_and_dual(Quat::from_components(real), Quat::from_components(dual))
}

/// The classic (distal) DH link `Rz(θ) Tz(d) Tx(a) Rx(α)` as a unit dual quaternion.
///
/// It is the product of two axis screws, `(z; θ, d)` then `(x; α, a)`.
pub fn dh_link<T: Ring>(theta: &T, d: &T, a: &T, alpha: &T) -> DualQuat<T> {
    axis_screw(2, theta, d) * axis_screw(0, alpha, a)
}

/// Craig's modified (proximal) DH link `Rx(α) Tx(a) Rz(θ) Tz(d)` as a unit dual quaternion:
/// the paper's `q_{i−1,i}` of sec 5 A.
///
/// Arguments in the order the factors appear: `α_{i−1}, a_{i−1}, θ_i, d_i`.
pub fn mdh_link<T: Ring>(alpha: &T, a: &T, theta: &T, d: &T) -> DualQuat<T> {
    axis_screw(0, alpha, a) * axis_screw(2, theta, d)
}

/// The classic DH link `Rz(θ) Tz(d) Tx(a) Rx(α)` as a product of elementary matrices.
pub fn dh_link_matrix<T: Ring>(theta: &T, d: &T, a: &T, alpha: &T) -> Matrix4<T> {
    let o = T::zero();
    Matrix4::rot_z(theta)
        * Matrix4::trans(&[o.clone(), o.clone(), d.clone()])
        * Matrix4::trans(&[a.clone(), o.clone(), o])
        * Matrix4::rot_x(alpha)
}

/// Craig's modified DH link `Rx(α) Tx(a) Rz(θ) Tz(d)` as a product of elementary matrices.
pub fn mdh_link_matrix<T: Ring>(alpha: &T, a: &T, theta: &T, d: &T) -> Matrix4<T> {
    let o = T::zero();
    Matrix4::rot_x(alpha)
        * Matrix4::trans(&[a.clone(), o.clone(), o.clone()])
        * Matrix4::rot_z(theta)
        * Matrix4::trans(&[o.clone(), o, d.clone()])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_screw_is_rotation_then_translation_along_the_axis() {
        let (angle, slide) = (0.7, 1.3);
        let direct = axis_screw(1, &angle, &slide);
        let composed = DualQuat::translation(&[0.0, slide, 0.0])
            * DualQuat::rotation(&[0.0, 1.0, 0.0], &angle);
        for (u, v) in direct.components().iter().zip(composed.components()) {
            assert!((u - v).abs() < 1e-12);
        }
    }
}
