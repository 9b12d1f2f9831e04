//! Rigid motions as unit dual quaternions: rotations, translations, screws, points.
//!
//! Every constructor takes its arguments by reference: the symbolic scalar is expensive to
//! clone, and the formulas below reuse each argument several times.

use super::{cross, mul, scale3, DualQuat, Quat};
use crate::Ring;

impl<T: Ring> Quat<T> {
    /// The unit quaternion of the rotation by `angle` about the unit vector `axis` (eq 5):
    /// `(cos(angle/2), sin(angle/2) axis)`.
    pub fn rotation(axis: &[T; 3], angle: &T) -> Self {
        let (c, s) = half_cos_sin(angle);
        rotation_quat_cs(axis, c, &s)
    }
}

impl<T: Ring> DualQuat<T> {
    /// The identity motion `1 + ε 0`.
    pub fn identity() -> Self {
        DualQuat::from_real(Quat::identity())
    }

    /// The rotation by `angle` about the axis through the origin with direction `axis`
    /// (eq 5): `(cos(angle/2), sin(angle/2) axis) + ε 0`.
    ///
    /// `axis` must be a unit vector; it is not normalized here (that needs a square root the
    /// ring may not have). A non-unit axis gives a DQ that fails [`DualQuat::unit_constraints`].
    pub fn rotation(axis: &[T; 3], angle: &T) -> Self {
        DualQuat::from_real(Quat::rotation(axis, angle))
    }

    /// The rotation by `angle` about the axis with (unit) direction `axis` through `point`:
    /// `T(p) R T(−p) = R + ε (0, sin(angle/2) p × n)` (sec 3-B 3) and sec 4).
    pub fn rotation_about_point(axis: &[T; 3], angle: &T, point: &[T; 3]) -> Self {
        let (c, s) = half_cos_sin(angle);
        let real = rotation_quat_cs(axis, c, &s);
        // (ε/2)(p R − R p) with R = (c, s n): the scalar parts cancel and the vector parts
        // leave 2 s (p × n), so the dual part is s (p × n). The product is written out to
        // avoid two quaternion products and the cancellations a symbolic scalar would pay.
        let m = cross(point, axis);
        let [x, y, z] = scale3(&s, &m);
        DualQuat::from_real_and_dual(real, Quat::vector(x, y, z))
    }

    /// The translation by `t`: `1 + ε t/2` (eq 12; sec 2-3's `1 + ε t` is ERRATA item 1).
    pub fn translation(t: &[T; 3]) -> Self {
        DualQuat::from_real_and_dual(
            Quat::identity(),
            Quat::vector(t[0].half(), t[1].half(), t[2].half()),
        )
    }

    /// The screw motion about the line through `point` with unit direction `axis`: a rotation
    /// by `angle` about that line and a translation by `slide` along it (the two commute).
    ///
    /// With `c, s = cos, sin(angle/2)` and the moment `m = point × axis` this is the
    /// corrected eq 18 (ERRATA item 6; the paper drops the factor 2 on the moment):
    /// `Ŝ = (c, s n) + (ε/2)(−s t, c t n + 2 s m)`.
    pub fn screw(axis: &[T; 3], point: &[T; 3], angle: &T, slide: &T) -> Self {
        let (c, s) = half_cos_sin(angle);
        let real = rotation_quat_cs(axis, c, &s);
        let half_t = slide.half();
        let ct = mul(&real.w, &half_t);
        let m = cross(point, axis);
        let v = |i: usize| mul(&ct, &axis[i]) + mul(&s, &m[i]);
        let dual = Quat::new(-mul(&s, &half_t), v(0), v(1), v(2));
        DualQuat::from_real_and_dual(real, dual)
    }

    /// The unit DQ of the motion "rotate by `rotation`, then translate by `t`":
    /// `R + ε t R / 2` (eq 12, 12 A).
    pub fn from_rotation_and_translation(rotation: Quat<T>, t: &[T; 3]) -> Self {
        let half_t = Quat::vector(t[0].half(), t[1].half(), t[2].half());
        let dual = &half_t * &rotation;
        DualQuat::from_real_and_dual(rotation, dual)
    }

    /// The paper's point (position vector) DQ `1 + ε v` (sec 2-1). Not a motion: it is
    /// what [`DualQuat::transform_point`] conjugates.
    pub fn point(v: &[T; 3]) -> Self {
        DualQuat::from_real_and_dual(Quat::identity(), Quat::from_vector(v))
    }

    /// The image of the point `v` under this motion (eq 10): the vector of the dual part of
    /// `q̂ (1 + ε v) q̂‾*`, with the combined conjugate of eq 9.
    ///
    /// Meaningful for a unit DQ; for a non-unit one the result is scaled and skewed.
    pub fn transform_point(&self, v: &[T; 3]) -> [T; 3] {
        let image = self * &Self::point(v) * &self.combined_conjugate();
        image.dual.vector_part()
    }

    /// The translation `t`, the vector part of `2 q_ε q*` (sec 2-3), of a unit DQ. It is
    /// where the motion takes the origin.
    pub fn translation_part(&self) -> [T; 3] {
        let [x, y, z] = self.dual.mul_vector_part(&self.real.conjugate());
        [x.clone() + &x, y.clone() + &y, z.clone() + &z]
    }
}

/// The rotation quaternion `(c, s n)` from the half-angle cosine and sine.
fn rotation_quat_cs<T: Ring>(axis: &[T; 3], c: T, s: &T) -> Quat<T> {
    let [x, y, z] = scale3(s, axis);
    Quat::new(c, x, y, z)
}

/// `(cos(angle/2), sin(angle/2))`, computed once per constructor.
fn half_cos_sin<T: Ring>(angle: &T) -> (T, T) {
    let half = angle.half();
    (half.cos(), half.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn translation_moves_a_point_by_t() {
        let q = DualQuat::translation(&[1.0, -2.0, 0.5]);
        assert_eq!(q.transform_point(&[3.0, 4.0, 5.0]), [4.0, 2.0, 5.5]);
    }

    #[test]
    fn quarter_turn_about_z_maps_x_to_y() {
        let q = DualQuat::rotation(&[0.0, 0.0, 1.0], &std::f64::consts::FRAC_PI_2);
        let p = q.transform_point(&[1.0, 0.0, 0.0]);
        assert!((p[0]).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12 && p[2].abs() < 1e-12);
    }
}
