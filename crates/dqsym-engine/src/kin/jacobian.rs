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

fn diff_quat(q: &Quat<Scalar>, v: &str) -> Quat<Scalar> {
    Quat::new(q.w.diff(v), q.x.diff(v), q.y.diff(v), q.z.diff(v))
}
