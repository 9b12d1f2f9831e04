//! The DH tables of the benchmark workloads, shared by `benches/core.rs` and
//! `examples/bench_workloads.rs` (which `bench/compare` runs), so both measure the same thing.

use dqsym::{
    closed::{closed_form_of_derivative, closed_form_prepared},
    kin::{dh_link, dh_link_matrix, dq_jacobian},
    DualQuat, Expr, Matrix4, Ring, Scalar, ScalarError,
};

/// `(theta, d, a, alpha)` of one DH link.
pub type Dh = [Scalar; 4];

pub fn planar(n: usize) -> Vec<Dh> {
    (1..=n)
        .map(|i| {
            [
                Scalar::sym(&format!("theta{i}")),
                Scalar::int(0),
                Scalar::sym(&format!("l{i}")),
                Scalar::int(0),
            ]
        })
        .collect()
}

pub fn puma() -> Vec<Dh> {
    let alpha = [(1, 2), (0, 1), (-1, 2), (1, 2), (-1, 2), (0, 1)];
    let d = ["0", "0", "d3", "d4", "0", "0"];
    let a = ["0", "a2", "a3", "0", "0", "0"];
    let v = |s: &str| {
        if s == "0" {
            Scalar::int(0)
        } else {
            Scalar::sym(s)
        }
    };
    (0..6)
        .map(|i| {
            let (n, m) = alpha[i];
            [
                Scalar::sym(&format!("theta{}", i + 1)),
                v(d[i]),
                v(a[i]),
                Scalar::pi() * <Scalar as Ring>::from_ratio(n, m),
            ]
        })
        .collect()
}

pub fn generic(n: usize) -> Vec<Dh> {
    (1..=n)
        .map(|i| {
            [
                Scalar::sym(&format!("theta{i}")),
                Scalar::sym(&format!("d{i}")),
                Scalar::sym(&format!("a{i}")),
                Scalar::sym(&format!("alpha{i}")),
            ]
        })
        .collect()
}

pub fn chain(links: &[Dh]) -> DualQuat<Scalar> {
    links
        .iter()
        .fold(DualQuat::identity(), |acc, [t, d, a, al]| {
            acc * dh_link(t, d, a, al)
        })
}

/// The 4x4 product of the links' DH matrices as polynomials in the cosines and sines of the
/// angles (`Scalar::to_cos_sin_polynomial`): what an expanding CAS computes, in the form in
/// which a product of distinct angles stays one monomial. `None` if a link angle is not a
/// plain symbol plus a constant.
#[allow(dead_code)]
pub fn matrix_cos_sin(links: &[Dh]) -> Option<Matrix4<Scalar>> {
    let mut acc: Option<Matrix4<Scalar>> = None;
    for [t, d, a, al] in links {
        let mut rows = dh_link_matrix(t, d, a, al).rows;
        for x in rows.iter_mut().flatten() {
            *x = x.to_cos_sin_polynomial()?;
        }
        let m = Matrix4::from_rows(rows);
        acc = Some(match acc {
            None => m,
            Some(p) => p.mul_ref(&m),
        });
    }
    acc
}

/// The 8 x n Jacobian of the chain's DQ in closed form, rows first, the way `dqsym fk
/// --jacobian` computes it: each DQ component put in closed form, then each entry from its
/// component's regrouped monomials (`closed_form_of_derivative`).
#[allow(dead_code)]
pub fn jacobian_closed_forms(links: &[Dh], vars: &[&str]) -> Result<Vec<Expr>, ScalarError> {
    let q = chain(links);
    let j = dq_jacobian(&q, vars);
    let mut out = Vec::with_capacity(8 * vars.len());
    for (row, c) in j.iter().zip(q.components()) {
        let (_, prepared) = closed_form_prepared(&c);
        for (x, v) in row.iter().zip(vars) {
            out.push(closed_form_of_derivative(&prepared, v, x)?);
        }
    }
    Ok(out)
}

/// The 4x4 product of the links' DH matrices (each built from elementary matrices), in the
/// canonical form: how `dqsym fk` forms the pose matrix (`Robot::forward_matrix`).
#[allow(dead_code)]
pub fn matrix(links: &[Dh]) -> Matrix4<Scalar> {
    links
        .iter()
        .fold(Matrix4::identity(), |acc, [t, d, a, al]| {
            acc.mul_ref(&dh_link_matrix(t, d, a, al))
        })
}
