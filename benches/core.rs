use criterion::{criterion_group, criterion_main, Criterion};
use dqsym::{closed_form, DualQuat, Expr, Scalar};
use std::hint::black_box;

/// The six standard-DH links of the PUMA 560, as dual quaternions (the table is the one the
/// workloads share).
fn puma_links() -> Vec<DualQuat<Scalar>> {
    puma()
        .iter()
        .map(|l| chain(std::slice::from_ref(l)))
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

// The workloads of `bench/compare` (W1-W5) and the hot paths under them, so that a regression
// shows here before it shows in the README's table. The DH tables are shared with
// examples/bench_workloads.rs.

#[path = "support/workloads.rs"]
mod workloads;

use workloads::{chain, generic, jacobian_closed_forms, matrix, matrix_cos_sin, planar, puma, Dh};

/// Closed forms of the end effector (px, py) of a DH chain.
fn end_effector(links: &[Dh]) -> Vec<Expr> {
    let m = chain(links).to_matrix();
    vec![
        closed_form(&m.rows[0][3]).expect("closed form"),
        closed_form(&m.rows[1][3]).expect("closed form"),
    ]
}

fn w1_rrr_end_effector(c: &mut Criterion) {
    let links = planar(3);
    c.bench_function("w1_rrr_end_effector", |b| {
        b.iter(|| black_box(end_effector(&links)))
    });
}

fn w2_puma560_pose_closed_form(c: &mut Criterion) {
    let links = puma();
    c.bench_function("w2_puma560_pose_closed_form", |b| {
        b.iter(|| {
            // As `dqsym fk` forms them: the DQ product, the product of the DH matrices.
            let q = chain(&links);
            let m = matrix(&links);
            let forms: Vec<Expr> = m.rows[..3]
                .iter()
                .flatten()
                .chain(q.components().iter())
                .map(|x| closed_form(x).expect("closed form"))
                .collect();
            black_box(forms)
        })
    });
}

fn w3_generic_6r_dq_expand(c: &mut Criterion) {
    // The 4x4 matrix of this chain exceeds the default term limit; the DQ product is the part
    // dqsym completes (about 1e5 canonical terms), so that is what is timed.
    let links = generic(6);
    let mut g = c.benchmark_group("w3");
    g.sample_size(10);
    g.bench_function("w3_generic_6r_dq_expand", |b| {
        b.iter(|| black_box(chain(&links)))
    });
    g.bench_function("w3_generic_6r_matrix_cos_sin_expand", |b| {
        b.iter(|| black_box(matrix_cos_sin(&links)))
    });
    g.finish();
}

fn w4_puma560_jacobian_closed_form(c: &mut Criterion) {
    let links = puma();
    let vars: Vec<String> = (1..=6).map(|i| format!("theta{i}")).collect();
    let vars: Vec<&str> = vars.iter().map(String::as_str).collect();
    let mut g = c.benchmark_group("w4");
    g.sample_size(20);
    g.bench_function("w4_puma560_jacobian_closed_form", |b| {
        b.iter(|| black_box(jacobian_closed_forms(&links, &vars).expect("closed forms")))
    });
    g.finish();
}

fn w5_planar20_end_effector(c: &mut Criterion) {
    let links = planar(20);
    let mut g = c.benchmark_group("w5");
    g.sample_size(20);
    g.bench_function("w5_planar20_end_effector", |b| {
        b.iter(|| black_box(end_effector(&links)))
    });
    g.finish();
}

/// The factors of the PUMA 560's last product: the first three links and the last three.
fn puma_halves() -> (DualQuat<Scalar>, DualQuat<Scalar>) {
    let links = puma();
    (chain(&links[..3]), chain(&links[3..]))
}

fn hot_scalar_product(c: &mut Criterion) {
    let (a, b) = puma_halves();
    let (x, y) = (a.dual.x.clone(), b.real.w.clone());
    c.bench_function("hot_scalar_product", |bch| bch.iter(|| black_box(&x * &y)));
}

fn hot_canonical_merge(c: &mut Criterion) {
    // The four products that make up the w component of a quaternion product, summed: the
    // sort-and-merge of overlapping terms, with cancellation.
    let (a, b) = puma_halves();
    let (p, q) = (&a.real, &b.real);
    let parts = [&p.w * &q.w, &p.x * &q.x, &p.y * &q.y, &p.z * &q.z];
    c.bench_function("hot_canonical_merge", |bch| {
        bch.iter(|| black_box(&(&(&parts[0] - &parts[1]) - &parts[2]) - &parts[3]))
    });
}

fn hot_closed_form_puma_t00(c: &mut Criterion) {
    let m = chain(&puma()).to_matrix();
    let t00 = m.rows[0][0].clone();
    c.bench_function("hot_closed_form_puma_t00", |b| {
        b.iter(|| black_box(closed_form(&t00).expect("closed form")))
    });
}

criterion_group!(
    workloads_and_hot_paths,
    w1_rrr_end_effector,
    w2_puma560_pose_closed_form,
    w3_generic_6r_dq_expand,
    w4_puma560_jacobian_closed_form,
    w5_planar20_end_effector,
    hot_scalar_product,
    hot_canonical_merge,
    hot_closed_form_puma_t00
);
criterion_main!(benches, workloads_and_hot_paths);
