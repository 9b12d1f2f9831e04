//! Jacobians of a symbolic pose: the paper's 8 x n matrix of DQ-component derivatives (sec 5 B)
//! and the geometric 6 x n Jacobian, both exact.

use crate::{DualQuat, Quat, Scalar};

/// The 8 x n Jacobian `d q_k / d theta_j` of the DQ components (w, x, y, z, w_e, x_e, y_e, z_e),
/// as rows.
pub fn dq_jacobian(q: &DualQuat<Scalar>, vars: &[&str]) -> Vec<Vec<Scalar>> {
    q.components()
        .iter()
        .map(|c| vars.iter().map(|v| c.diff(v)).collect())
        .collect()
}

/// The geometric Jacobian of a unit DQ pose `q = r + eps d`, as 6 rows: linear velocity of the
/// frame origin (x, y, z) over angular velocity (x, y, z), one column per variable.
///
/// With `t = 2 d r*`: `omega = vec(2 r' r*)` and `v = t' = vec(2 d' r* + 2 d r'*)`, so the
/// columns follow from the 8 x n Jacobian by quaternion algebra alone, for any joint type and
/// convention (revolute, prismatic; DH, modified DH, screw).
pub fn geometric_jacobian(q: &DualQuat<Scalar>, vars: &[&str]) -> Vec<Vec<Scalar>> {
    let r = &q.real;
    let d = &q.dual;
    let two = Scalar::int(2);
    let mut rows: Vec<Vec<Scalar>> = (0..6).map(|_| Vec::with_capacity(vars.len())).collect();
    for v in vars {
        let dr = diff_quat(r, v);
        let dd = diff_quat(d, v);
        let omega = (dr.clone() * r.conjugate()).scale(&two);
        let lin = (dd * r.conjugate() + d.clone() * dr.conjugate()).scale(&two);
        let (l, w) = (lin.vector_part(), omega.vector_part());
        for k in 0..3 {
            rows[k].push(l[k].clone());
            rows[k + 3].push(w[k].clone());
        }
    }
    rows
}

/// The body form of [`geometric_jacobian`]: the same velocities, the end-effector origin's
/// linear velocity over the angular velocity, expressed in the end-effector frame (`R^T v`,
/// `R^T omega`; with `q = r + eps d`, `R^T x` is `r* x r`). Its rows are the body twist
/// `(v_b, omega_b)` of `T^-1 dT/dq` (Lynch and Park's `V_b` with its halves swapped).
pub fn geometric_jacobian_body(q: &DualQuat<Scalar>, vars: &[&str]) -> Vec<Vec<Scalar>> {
    let base = geometric_jacobian(q, vars);
    let r = &q.real;
    let back = |v: [Scalar; 3]| (r.conjugate() * Quat::from_vector(&v) * r.clone()).vector_part();
    let mut rows: Vec<Vec<Scalar>> = (0..6).map(|_| Vec::with_capacity(vars.len())).collect();
    let col = |k0: usize, j: usize| {
        [
            base[k0][j].clone(),
            base[k0 + 1][j].clone(),
            base[k0 + 2][j].clone(),
        ]
    };
    let cols: Vec<([Scalar; 3], [Scalar; 3])> = (0..vars.len())
        .map(|j| (back(col(0, j)), back(col(3, j))))
        .collect();
    for (l, w) in cols {
        for k in 0..3 {
            rows[k].push(l[k].clone());
            rows[k + 3].push(w[k].clone());
        }
    }
    rows
}

fn diff_quat(q: &Quat<Scalar>, v: &str) -> Quat<Scalar> {
    Quat::new(q.w.diff(v), q.x.diff(v), q.y.diff(v), q.z.diff(v))
}
