//! 4×4 homogeneous matrices, and the conversions between them and unit dual quaternions.
//!
//! The elementary matrices here ([`Matrix4::rot_x`], [`Matrix4::trans`], ...) are built
//! from cos and sin directly, never through a dual quaternion: they are the independent
//! oracle the dual-quaternion results are checked against.

use super::quat::forward_binop;
use super::{mul, DualQuat, Quat};
use crate::Ring;
use std::array::from_fn;
use std::ops::Mul;

/// A 4×4 matrix, row-major: `rows[i][j]` is row `i`, column `j`.
///
/// A rigid motion is `[[R, d], [0 0 0 1]]` with `R` a rotation and `d` the translation; it
/// maps the point `v` to `R v + d`.
///
/// # Laws
/// - `*` is the matrix product: associative, [`Matrix4::identity`] neutral, not commutative.
/// - `(A B).transform_point(v) = A.transform_point(B.transform_point(v))` for affine `A`, `B`.
/// - For a unit DQ `q`: `q.to_matrix().transform_point(v) = q.transform_point(v)`, and
///   `(p q).to_matrix() = p.to_matrix() q.to_matrix()`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Matrix4<T> {
    /// The four rows.
    pub rows: [[T; 4]; 4],
}

impl<T: Ring> Matrix4<T> {
    /// The matrix with the given rows.
    pub fn from_rows(rows: [[T; 4]; 4]) -> Self {
        Matrix4 { rows }
    }

    /// The identity matrix.
    pub fn identity() -> Self {
        Matrix4::from_rows(from_fn(|i| {
            from_fn(|j| if i == j { T::one() } else { T::zero() })
        }))
    }

    /// The rigid motion `[[R, d], [0 0 0 1]]` from a 3×3 rotation block and a translation.
    pub fn from_rotation_and_translation(r: [[T; 3]; 3], d: [T; 3]) -> Self {
        let [r0, r1, r2] = r;
        let [d0, d1, d2] = d;
        let row = |[a, b, c]: [T; 3], t: T| [a, b, c, t];
        Matrix4::from_rows([
            row(r0, d0),
            row(r1, d1),
            row(r2, d2),
            [T::zero(), T::zero(), T::zero(), T::one()],
        ])
    }

    /// The upper-left 3×3 block (the rotation of a rigid motion).
    pub fn rotation_block(&self) -> [[T; 3]; 3] {
        from_fn(|i| from_fn(|j| self.rows[i][j].clone()))
    }

    /// The last column's first three entries (the translation of a rigid motion).
    pub fn translation_column(&self) -> [T; 3] {
        from_fn(|i| self.rows[i][3].clone())
    }

    /// The transpose.
    pub fn transpose(&self) -> Self {
        Matrix4::from_rows(from_fn(|i| from_fn(|j| self.rows[j][i].clone())))
    }

    /// The image `R v + d` of the point `v` (homogeneous coordinate 1). The last row is
    /// not used: the matrix is taken to be affine.
    pub fn transform_point(&self, v: &[T; 3]) -> [T; 3] {
        from_fn(|i| {
            let r = &self.rows[i];
            mul(&r[0], &v[0]) + mul(&r[1], &v[1]) + mul(&r[2], &v[2]) + &r[3]
        })
    }

    /// The full matrix product (64 multiplications; see ERRATA item 10 on the paper's count).
    pub fn mul_ref(&self, b: &Self) -> Self {
        Matrix4::from_rows(from_fn(|i| {
            from_fn(|j| {
                let a = &self.rows[i];
                mul(&a[0], &b.rows[0][j])
                    + mul(&a[1], &b.rows[1][j])
                    + mul(&a[2], &b.rows[2][j])
                    + mul(&a[3], &b.rows[3][j])
            })
        }))
    }

    /// The rotation by `angle` about the x axis.
    pub fn rot_x(angle: &T) -> Self {
        let (c, s) = (angle.cos(), angle.sin());
        let (o, l) = (T::zero(), T::one());
        Self::from_rotation_and_translation(
            [
                [l, o.clone(), o.clone()],
                [o.clone(), c.clone(), -s.clone()],
                [o.clone(), s, c],
            ],
            [o.clone(), o.clone(), o],
        )
    }

    /// The rotation by `angle` about the y axis.
    pub fn rot_y(angle: &T) -> Self {
        let (c, s) = (angle.cos(), angle.sin());
        let (o, l) = (T::zero(), T::one());
        Self::from_rotation_and_translation(
            [
                [c.clone(), o.clone(), s.clone()],
                [o.clone(), l, o.clone()],
                [-s, o.clone(), c],
            ],
            [o.clone(), o.clone(), o],
        )
    }

    /// The rotation by `angle` about the z axis.
    pub fn rot_z(angle: &T) -> Self {
        let (c, s) = (angle.cos(), angle.sin());
        let (o, l) = (T::zero(), T::one());
        Self::from_rotation_and_translation(
            [
                [c.clone(), -s.clone(), o.clone()],
                [s, c, o.clone()],
                [o.clone(), o.clone(), l],
            ],
            [o.clone(), o.clone(), o],
        )
    }

    /// The translation by `t`.
    pub fn trans(t: &[T; 3]) -> Self {
        let mut m = Self::identity();
        for (row, ti) in m.rows.iter_mut().zip(t) {
            row[3] = ti.clone();
        }
        m
    }

    /// The rotation by `angle` about the unit vector `axis` through the origin, by Rodrigues'
    /// formula as the paper's Appendix V prints it (`v = 1 − cos θ`).
    pub fn rotation(axis: &[T; 3], angle: &T) -> Self {
        let (c, s) = (angle.cos(), angle.sin());
        let v = T::one() - &c;
        let [nx, ny, nz] = axis;
        let nn = |a: &T, b: &T| mul(&mul(a, b), &v);
        let sn = |a: &T| mul(&s, a);
        Self::from_rotation_and_translation(
            [
                [nn(nx, nx) + &c, nn(nx, ny) - sn(nz), nn(nx, nz) + sn(ny)],
                [nn(nx, ny) + sn(nz), nn(ny, ny) + &c, nn(ny, nz) - sn(nx)],
                [nn(nx, nz) - sn(ny), nn(ny, nz) + sn(nx), nn(nz, nz) + &c],
            ],
            from_fn(|_| T::zero()),
        )
    }
}

forward_binop!(Matrix4, Mul, mul, mul_ref);

impl<T: Ring> DualQuat<T> {
    /// The homogeneous matrix `[R(q), d(q)]` of a unit DQ (Appendix I): `R(q)` as printed,
    /// with `(q1, q2, q3, q4) = (w, x, y, z)`, and `d` the vector part of `2 q_ε q*`, which
    /// is Appendix I's `d(q)` once its `(ε/2)(q5..q8)` is read as `q5..q8 = 2 q_ε`.
    pub fn to_matrix(&self) -> Matrix4<T> {
        let Quat { w, x, y, z } = &self.real;
        let two = |a: T| a.clone() + &a;
        let (ww, xx, yy, zz) = (mul(w, w), mul(x, x), mul(y, y), mul(z, z));
        let (xy, xz, yz) = (mul(x, y), mul(x, z), mul(y, z));
        let (wx, wy, wz) = (mul(w, x), mul(w, y), mul(w, z));
        let r = [
            [
                ww.clone() + &xx - &yy - &zz,
                two(xy.clone() - &wz),
                two(xz.clone() + &wy),
            ],
            [
                two(xy + &wz),
                ww.clone() - &xx + &yy - &zz,
                two(yz.clone() - &wx),
            ],
            [two(xz - &wy), two(yz + &wx), ww - &xx - &yy + &zz],
        ];
        Matrix4::from_rotation_and_translation(r, self.translation_part())
    }

    /// The unit DQ of a rigid-motion matrix, or `None` when the ring cannot take the square
    /// root or reciprocal the conversion needs, or the last row is not exactly `0 0 0 1`.
    ///
    /// The rotation block is assumed orthogonal with determinant 1 (not checked: an f64
    /// matrix would need a tolerance). The rotation quaternion comes from Shepperd's method:
    /// of `4w² = 1 + tr R`, `4x² = 1 + R₀₀ − R₁₁ − R₂₂`, ..., the largest is square-rooted
    /// when the scalars have f64 values (numerically stable); otherwise the first the ring
    /// can square-root and invert is used. The translation enters as eq 12: `R + ε t R / 2`.
    /// The sign of the result is the one with a non-negative chosen component.
    pub fn from_matrix(m: &Matrix4<T>) -> Option<Self> {
        let last = &m.rows[3];
        let affine = last[0].is_zero() && last[1].is_zero() && last[2].is_zero();
        if !affine || last[3] != T::one() {
            return None;
        }
        let real = rotation_from_block(&m.rotation_block())?;
        Some(Self::from_rotation_and_translation(
            real,
            &m.translation_column(),
        ))
    }
}

/// Shepperd's method for the unit quaternion of a rotation matrix.
fn rotation_from_block<T: Ring>(r: &[[T; 3]; 3]) -> Option<Quat<T>> {
    let one = T::one();
    let (r00, r11, r22) = (&r[0][0], &r[1][1], &r[2][2]);
    // 4w², 4x², 4y², 4z², in that order.
    let squares = [
        one.clone() + r00 + r11 + r22,
        one.clone() + r00 - r11 - r22,
        one.clone() - r00 + r11 - r22,
        one - r00 - r11 + r22,
    ];
    let mut order = [0usize, 1, 2, 3];
    let approx: Option<Vec<f64>> = squares.iter().map(Ring::to_f64).collect();
    if let Some(values) = approx {
        order.sort_by(|&a, &b| values[b].total_cmp(&values[a]));
    }
    let sum = |i: usize, j: usize| r[i][j].clone() + &r[j][i];
    let diff = |i: usize, j: usize| r[i][j].clone() - &r[j][i];
    for k in order {
        // root = 2 |component|; every other component is (an off-diagonal sum or
        // difference, which is 4 × component × chosen) / (2 root).
        let Some(root) = squares[k].try_sqrt() else {
            continue;
        };
        let Some(inv) = (root.clone() + &root).try_recip() else {
            continue;
        };
        let chosen = root.half();
        let f = |v: T| v * &inv;
        let [w, x, y, z] = match k {
            0 => [chosen, f(diff(2, 1)), f(diff(0, 2)), f(diff(1, 0))],
            1 => [f(diff(2, 1)), chosen, f(sum(0, 1)), f(sum(0, 2))],
            2 => [f(diff(0, 2)), f(sum(0, 1)), chosen, f(sum(1, 2))],
            _ => [f(diff(1, 0)), f(sum(0, 2)), f(sum(1, 2)), chosen],
        };
        return Some(Quat::new(w, x, y, z));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn translation_matrix_moves_points() {
        let m = Matrix4::trans(&[1.0, 2.0, 3.0]);
        assert_eq!(m.transform_point(&[1.0, 1.0, 1.0]), [2.0, 3.0, 4.0]);
    }

    #[test]
    fn non_affine_matrix_has_no_dual_quaternion() {
        let mut m = Matrix4::<f64>::identity();
        m.rows[3][0] = 1.0;
        assert_eq!(DualQuat::from_matrix(&m), None);
    }

    #[test]
    fn half_turn_is_recovered_through_a_vector_branch() {
        // tr R = −1 here, so the w branch (4w² = 0) must be skipped.
        let m = Matrix4::rot_x(&std::f64::consts::PI);
        let q = DualQuat::from_matrix(&m).expect("a rotation matrix");
        assert!((q.real.x.abs() - 1.0).abs() < 1e-12);
    }
}
