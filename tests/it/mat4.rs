//! Plain f64 4x4 homogeneous matrices, the independent model the robot tests compare dqsym's
//! dual quaternions with: products, translations and Rodrigues rotations, nothing else.

/// A homogeneous matrix, row-major.
pub(crate) type M = [[f64; 4]; 4];

/// The x, y and z unit vectors.
pub(crate) const X: [f64; 3] = [1.0, 0.0, 0.0];
pub(crate) const Y: [f64; 3] = [0.0, 1.0, 0.0];
pub(crate) const Z: [f64; 3] = [0.0, 0.0, 1.0];

pub(crate) fn ident() -> M {
    std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }))
}

pub(crate) fn mul(a: &M, b: &M) -> M {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// The translation by `v`.
pub(crate) fn trans(v: [f64; 3]) -> M {
    let mut m = ident();
    for (row, x) in m.iter_mut().zip(v) {
        row[3] = x;
    }
    m
}

/// The rotation by `t` about the unit vector `u` (Rodrigues).
pub(crate) fn rot(u: [f64; 3], t: f64) -> M {
    let (s, c) = t.sin_cos();
    let v = 1.0 - c;
    let [x, y, z] = u;
    [
        [c + x * x * v, x * y * v - z * s, x * z * v + y * s, 0.0],
        [y * x * v + z * s, c + y * y * v, y * z * v - x * s, 0.0],
        [z * x * v - y * s, z * y * v + x * s, c + z * z * v, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}
