//! The operators of DQ Robotics (`DQ.cpp`, `DQ_Geometry.cpp`) over any ring, with its names and
//! its semantics: parts, conjugates, Hamilton matrices, vectorizations, adjoints, products of
//! pure dual quaternions, translation, and Plücker lines and planes.
//!
//! Conventions shared with DQ Robotics: `h = P(h) + ε D(h)`, the whole coefficient of ε is the
//! dual part (our [`DualQuat::dual`]), components `(w, x, y, z, w_ε, x_ε, y_ε, z_ε)` in that
//! order, `conj` conjugates both parts, a pose is `r + ε (1/2) t r`, so
//! `translation(h) = 2 D(h) P(h)*`. The paper writes `(ε/2)(q5..q8)` instead (ERRATA "Two
//! dual-part conventions"); nothing here uses that form. A line is `l + ε m` with unit
//! direction `l` and moment `m = p × l`, a plane `n + ε d` with unit normal `n` and
//! `d = p · n` (DQ Robotics' sign: the plane is `{x : x · n = d}`).
//!
//! Everything here is a polynomial in the components, so it is exact for
//! [`crate::Scalar`]; the operations that are not (`exp`, `log`, `pow`, `norm`, angles) live in
//! `kin/dqexp.rs`.

use super::{cross as cross3, mul, DualQuat, Quat};
use crate::Ring;

/// `P(h)`, the primary (real) part.
pub fn primary<T: Ring>(h: &DualQuat<T>) -> Quat<T> {
    h.real.clone()
}

/// `D(h)`, the dual part.
pub fn dual_part<T: Ring>(h: &DualQuat<T>) -> Quat<T> {
    h.dual.clone()
}

/// `Re(h)`: the scalar parts, `w + ε w_ε`.
pub fn re<T: Ring>(h: &DualQuat<T>) -> DualQuat<T> {
    DualQuat::from_real_and_dual(
        Quat::from_scalar(h.real.w.clone()),
        Quat::from_scalar(h.dual.w.clone()),
    )
}

/// `Im(h)`: the vector parts, `(0, x, y, z) + ε (0, x_ε, y_ε, z_ε)`.
pub fn im<T: Ring>(h: &DualQuat<T>) -> DualQuat<T> {
    DualQuat::from_real_and_dual(
        Quat::from_vector(&h.real.vector_part()),
        Quat::from_vector(&h.dual.vector_part()),
    )
}

/// `sharp(h) = P(h) − ε D(h)` (our [`DualQuat::dual_conjugate`]).
pub fn sharp<T: Ring>(h: &DualQuat<T>) -> DualQuat<T> {
    h.dual_conjugate()
}

/// `tplus(h) = h P(h)*`, the translation part `1 + ε (1/2) t` of a unit DQ.
pub fn tplus<T: Ring>(h: &DualQuat<T>) -> DualQuat<T> {
    h * &DualQuat::from_real(h.real.conjugate())
}

/// `Ad(a, x) = a x conj(a)`: for a unit `a` and a pure `x`, the twist, line or vector `x`
/// expressed in the frame `a` moves to.
pub fn ad<T: Ring>(a: &DualQuat<T>, x: &DualQuat<T>) -> DualQuat<T> {
    a * x * &a.conjugate()
}

/// `Adsharp(a, x) = sharp(a) x conj(a)`: for a unit `a` and a plane `x = n + ε d`, the plane
/// moved by `a`, `n' + ε (d + t · n')` with `n' = r n r*` (see [`transform_plane`]). (`Ad`
/// would give the dual part `d + ε t × n'`, not a plane.)
pub fn adsharp<T: Ring>(a: &DualQuat<T>, x: &DualQuat<T>) -> DualQuat<T> {
    sharp(a) * x * &a.conjugate()
}

/// `cross(a, b) = (a b − b a) / 2`; for pure quaternions, the cross product of the vectors, and
/// for pure dual quaternions (lines) its dual extension.
pub fn cross<T: Ring>(a: &DualQuat<T>, b: &DualQuat<T>) -> DualQuat<T> {
    (a * b - b * a).scale(&T::from_ratio(1, 2))
}

/// `dot(a, b) = −(a b + b a) / 2`; for pure quaternions, the dot product (in the scalar part).
pub fn dot<T: Ring>(a: &DualQuat<T>, b: &DualQuat<T>) -> DualQuat<T> {
    (a * b + b * a).scale(&T::from_ratio(-1, 2))
}

/// `translation(h) = 2 D(h) P(h)*`, a pure quaternion, for a unit `h`.
pub fn translation<T: Ring>(h: &DualQuat<T>) -> Quat<T> {
    (&h.dual * &h.real.conjugate()).scale(&T::from_ratio(2, 1))
}

/// `hamiplus4(a)`: the matrix with `vec4(a b) = hamiplus4(a) vec4(b)`.
pub fn hamiplus4<T: Ring>(a: &Quat<T>) -> [[T; 4]; 4] {
    let [w, x, y, z] = a.components();
    let n = |v: &T| -v.clone();
    [
        [w.clone(), n(&x), n(&y), n(&z)],
        [x.clone(), w.clone(), n(&z), y.clone()],
        [y.clone(), z.clone(), w.clone(), n(&x)],
        [z.clone(), n(&y), x.clone(), w.clone()],
    ]
}

/// `haminus4(b)`: the matrix with `vec4(a b) = haminus4(b) vec4(a)`.
pub fn haminus4<T: Ring>(b: &Quat<T>) -> [[T; 4]; 4] {
    let [w, x, y, z] = b.components();
    let n = |v: &T| -v.clone();
    [
        [w.clone(), n(&x), n(&y), n(&z)],
        [x.clone(), w.clone(), z.clone(), n(&y)],
        [y.clone(), n(&z), w.clone(), x.clone()],
        [z.clone(), y.clone(), n(&x), w.clone()],
    ]
}

/// The 8 x 8 block matrix `[[A(P), 0], [A(D), A(P)]]` of a 4 x 4 Hamilton operator `A`.
fn ham8<T: Ring>(h: &DualQuat<T>, f: fn(&Quat<T>) -> [[T; 4]; 4]) -> Vec<Vec<T>> {
    let (p, d) = (f(&h.real), f(&h.dual));
    let mut out = vec![vec![T::zero(); 8]; 8];
    for i in 0..4 {
        for j in 0..4 {
            out[i][j] = p[i][j].clone();
            out[i + 4][j + 4] = p[i][j].clone();
            out[i + 4][j] = d[i][j].clone();
        }
    }
    out
}

/// `hamiplus8(a)`: `vec8(a b) = hamiplus8(a) vec8(b)`.
pub fn hamiplus8<T: Ring>(a: &DualQuat<T>) -> Vec<Vec<T>> {
    ham8(a, hamiplus4)
}

/// `haminus8(b)`: `vec8(a b) = haminus8(b) vec8(a)`.
pub fn haminus8<T: Ring>(b: &DualQuat<T>) -> Vec<Vec<T>> {
    ham8(b, haminus4)
}

/// `vec6(h) = (x, y, z, x_ε, y_ε, z_ε)`, the vector parts.
pub fn vec6<T: Ring>(h: &DualQuat<T>) -> [T; 6] {
    let [a, b, c] = h.real.vector_part();
    let [d, e, f] = h.dual.vector_part();
    [a, b, c, d, e, f]
}

/// The Plücker line `l + ε (p × l)` through the point `p` with direction `l` (unit for the
/// distances below to be lengths).
pub fn line<T: Ring>(direction: &[T; 3], point: &[T; 3]) -> DualQuat<T> {
    DualQuat::from_real_and_dual(
        Quat::from_vector(direction),
        Quat::from_vector(&cross3(point, direction)),
    )
}

/// The plane `n + ε (p · n)` through the point `p` with normal `n`.
pub fn plane<T: Ring>(normal: &[T; 3], point: &[T; 3]) -> DualQuat<T> {
    DualQuat::from_real_and_dual(
        Quat::from_vector(normal),
        Quat::from_scalar(dot3(point, normal)),
    )
}

/// The two Plücker constraints of a line `l + ε m`: `|l|² − 1` and `l · m`; both vanish for a
/// line (DQ Robotics' `is_line`).
pub fn line_constraints<T: Ring>(l: &DualQuat<T>) -> (T, T) {
    (
        l.real.norm_squared() - T::one(),
        dot3(&l.real.vector_part(), &l.dual.vector_part()),
    )
}

/// `a · b` of two 3-vectors.
pub fn dot3<T: Ring>(a: &[T; 3], b: &[T; 3]) -> T {
    mul(&a[0], &b[0]) + mul(&a[1], &b[1]) + mul(&a[2], &b[2])
}

/// The squared distance between two points (`point_to_point_squared_distance`).
pub fn point_to_point_squared_distance<T: Ring>(a: &[T; 3], b: &[T; 3]) -> T {
    let d = [
        a[0].clone() - &b[0],
        a[1].clone() - &b[1],
        a[2].clone() - &b[2],
    ];
    dot3(&d, &d)
}

/// The squared distance `|p × l − m|²` of a point from the line `l + ε m`
/// (`point_to_line_squared_distance`).
pub fn point_to_line_squared_distance<T: Ring>(p: &[T; 3], line: &DualQuat<T>) -> T {
    let c = cross3(p, &line.real.vector_part());
    let m = line.dual.vector_part();
    let d = [
        c[0].clone() - &m[0],
        c[1].clone() - &m[1],
        c[2].clone() - &m[2],
    ];
    dot3(&d, &d)
}

/// The signed distance `p · n − d` of a point from the plane `n + ε d`
/// (`point_to_plane_distance`).
pub fn point_to_plane_distance<T: Ring>(p: &[T; 3], plane: &DualQuat<T>) -> T {
    dot3(p, &plane.real.vector_part()) - &plane.dual.w
}

/// The squared distance between two lines as a quotient `(numerator, denominator)`
/// (`line_to_line_squared_distance`): for skew or intersecting lines `D(l1 · l2)² / |P(l1 × l2)|²`,
/// for parallel ones (`P(l1 × l2) = 0`) `|D(l1 × l2)|² / 1`.
pub fn line_to_line_squared_distance<T: Ring>(l1: &DualQuat<T>, l2: &DualQuat<T>) -> (T, T) {
    let c = cross(l1, l2);
    let d = dot(l1, l2);
    let den = c.real.norm_squared();
    if den.is_zero() {
        (c.dual.norm_squared(), T::one())
    } else {
        (mul(&d.dual.w, &d.dual.w), den)
    }
}

/// The cosine `P(l1 · l2)` of the angle between two lines (`line_to_line_angle` is its arccos).
pub fn line_to_line_cos<T: Ring>(l1: &DualQuat<T>, l2: &DualQuat<T>) -> T {
    dot(l1, l2).real.w
}

/// The line `q l q*` (= `Ad(q, l)`): the line `l` carried by the unit DQ `q`.
pub fn transform_line<T: Ring>(q: &DualQuat<T>, l: &DualQuat<T>) -> DualQuat<T> {
    ad(q, l)
}

/// The plane `n + ε d` carried by the unit DQ `q = r + ε (1/2) t r`: `Adsharp(q, π) =
/// n' + ε (d + t · n')`, `n' = r n r*`, the plane through the moved points (DQ Robotics moves
/// planes with `Adsharp`, lines with `Ad`).
pub fn transform_plane<T: Ring>(q: &DualQuat<T>, plane: &DualQuat<T>) -> DualQuat<T> {
    adsharp(q, plane)
}

/// DQ Robotics' `C4`: `vec4(r*) = C4 vec4(r)`.
pub fn c4<T: Ring>() -> [[T; 4]; 4] {
    let mut m: [[T; 4]; 4] = std::array::from_fn(|_| std::array::from_fn(|_| T::zero()));
    m[0][0] = T::one();
    for (k, row) in m.iter_mut().enumerate().skip(1) {
        row[k] = -T::one();
    }
    m
}

/// DQ Robotics' `C8`: `vec8(conj(h)) = C8 vec8(h)`.
pub fn c8<T: Ring>() -> Vec<Vec<T>> {
    let mut m = vec![vec![T::zero(); 8]; 8];
    for (k, row) in m.iter_mut().enumerate() {
        row[k] = if k % 4 == 0 { T::one() } else { -T::one() };
    }
    m
}

/// DQ Robotics' `crossmatrix4(a)`: `vec4(cross(a, b)) = crossmatrix4(a) vec4(b)` for pure `a`,
/// `b`.
pub fn crossmatrix4<T: Ring>(a: &Quat<T>) -> [[T; 4]; 4] {
    let [x, y, z] = a.vector_part();
    let o = T::zero;
    [
        [o(), o(), o(), o()],
        [o(), o(), -z.clone(), y.clone()],
        [o(), z, o(), -x.clone()],
        [o(), -y, x, o()],
    ]
}

/// The projection `l × m + (p · l) l` of the point `p` on the line `l + ε m` (unit `l`;
/// `point_projected_in_line`).
pub fn point_projected_in_line<T: Ring>(p: &[T; 3], line: &DualQuat<T>) -> [T; 3] {
    let l = line.real.vector_part();
    let c = cross3(&l, &line.dual.vector_part());
    let k = dot3(p, &l);
    [
        c[0].clone() + &mul(&k, &l[0]),
        c[1].clone() + &mul(&k, &l[1]),
        c[2].clone() + &mul(&k, &l[2]),
    ]
}

/// The closest points of two lines that are not parallel (`closest_points_between_lines`), as
/// numerators over the common denominator `|l1 × l2|²`: with `c = l1 × l2`,
/// `p1 = ((l2 × c) × m1 + (m2 · c) l1) / |c|²` and
/// `p2 = (m2 × (l1 × c) - (m1 · c) l2) / |c|²`. `None` for parallel lines (`c = 0`), whose
/// closest points are not unique.
pub fn closest_points_between_lines<T: Ring>(
    l1: &DualQuat<T>,
    l2: &DualQuat<T>,
) -> Option<([T; 3], [T; 3], T)> {
    let (a, m1) = (l1.real.vector_part(), l1.dual.vector_part());
    let (b, m2) = (l2.real.vector_part(), l2.dual.vector_part());
    let c = cross3(&a, &b);
    let den = dot3(&c, &c);
    if den.is_zero() {
        return None;
    }
    let (k1, k2) = (dot3(&m2, &c), dot3(&m1, &c));
    let q1 = cross3(&cross3(&b, &c), &m1);
    let q2 = cross3(&m2, &cross3(&a, &c));
    let p1 = std::array::from_fn(|i| q1[i].clone() + &mul(&k1, &a[i]));
    let p2 = std::array::from_fn(|i| q2[i].clone() - &mul(&k2, &b[i]));
    Some((p1, p2, den))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dq(c: [f64; 8]) -> DualQuat<f64> {
        DualQuat::from_components(c)
    }

    #[test]
    fn hamilton_matrices_reproduce_the_product() {
        let a = dq([1., 2., -3., 4., 0.5, -1., 2., 3.]);
        let b = dq([-2., 1., 0.5, 3., 1., 1., -2., 0.25]);
        let ab = (&a * &b).components();
        let (hp, hm) = (hamiplus8(&a), haminus8(&b));
        let (va, vb) = (a.components(), b.components());
        for i in 0..8 {
            let p: f64 = (0..8).map(|j| hp[i][j] * vb[j]).sum();
            let m: f64 = (0..8).map(|j| hm[i][j] * va[j]).sum();
            assert!((p - ab[i]).abs() < 1e-12 && (m - ab[i]).abs() < 1e-12);
        }
    }

    #[test]
    fn cross_and_dot_of_pure_quaternions_are_the_vector_products() {
        let a = DualQuat::from_real(Quat::vector(1., 2., 3.));
        let b = DualQuat::from_real(Quat::vector(-1., 0.5, 2.));
        assert_eq!(cross(&a, &b).real.vector_part(), [2.5, -5., 2.5]);
        assert_eq!(dot(&a, &b).real.w, 6.);
    }
}
