use criterion::{criterion_group, criterion_main, Criterion};
use dqsym::{closed_form, dh_link, DualQuat, Expr, Ring, Scalar};
use std::hint::black_box;

/// The six standard-DH links of the PUMA 560.
fn puma_links() -> Vec<DualQuat<Scalar>> {
    let pi = Scalar::pi();
    let alpha = [(1, 2), (0, 1), (-1, 2), (1, 2), (-1, 2), (0, 1)];
    (0..6)
        .map(|i| {
            let th = Scalar::sym(&format!("theta{}", i + 1));
            let a = match i {
                1 => Scalar::sym("a2"),
                2 => Scalar::sym("a3"),
                _ => Scalar::int(0),
            };
            let d = match i {
                2 => Scalar::sym("d3"),
                3 => Scalar::sym("d4"),
                _ => Scalar::int(0),
            };
            let (n, m) = alpha[i];
            dh_link(&th, &d, &a, &(&pi * &<Scalar as Ring>::from_ratio(n, m)))
        })
        .collect()
}

fn puma560_fk_dq_product(c: &mut Criterion) {
    let links = puma_links();
    c.bench_function("puma560_fk_dq_product", |b| {
        b.iter(|| {
            let mut acc = links[0].clone();
            for l in &links[1..] {
                acc = acc * l;
            }
            black_box(acc)
        })
    });
}

/// The PUMA 560 pose as a dual quaternion.
fn puma_pose() -> DualQuat<Scalar> {
    let links = puma_links();
    let mut acc = links[0].clone();
    for l in &links[1..] {
        acc = acc * l;
    }
    acc
}

/// Closed forms of the 8 components and of the 12 top entries of the matrix.
fn closed_forms(pose: &DualQuat<Scalar>, rows: &[[Scalar; 4]]) -> Vec<Expr> {
    pose.components()
        .iter()
        .chain(rows[..3].iter().flatten())
        .map(|x| closed_form(x).expect("closed form"))
        .collect()
}

fn puma560_closed_form(c: &mut Criterion) {
    let pose = puma_pose();
    c.bench_function("puma560_closed_form", |b| {
        b.iter(|| {
            let m = black_box(&pose).to_matrix();
            black_box(closed_forms(&pose, &m.rows))
        })
    });
    let m = pose.to_matrix();
    c.bench_function("puma560_closed_form_only", |b| {
        b.iter(|| black_box(closed_forms(black_box(&pose), &m.rows)))
    });
}

criterion_group!(benches, puma560_fk_dq_product, puma560_closed_form);
criterion_main!(benches);
