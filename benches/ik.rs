//! Closed-form inverse kinematics: the derivation (`dqsym::ik::solve` and the Rust solver
//! text, as `dqsym ik --format rust` does it) on PUMA 560, UR5 and the iiwa with a free joint,
//! and the generated solvers (every branch) per call.
#![allow(clippy::excessive_precision)]

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::time::Duration;

// Not files of their own under benches/: Cargo would take them for bench targets, rustfmt would
// reformat them. A test keeps them equal to what `dqsym ik --format rust` writes.
#[allow(dead_code)]
mod puma {
    include!("generated/ik_puma560.rs");
}
#[allow(dead_code)]
mod ur5 {
    include!("generated/ik_ur5.rs");
}

const ROBOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/");

fn load(file: &str) -> dqsym::Robot {
    let path = format!("{ROBOTS}{file}.toml");
    let text = std::fs::read_to_string(&path).expect("robot file");
    dqsym::parse_robot(&text, &path, &dqsym::eval_scalar_text).expect("robot")
}

fn derive(r: &dqsym::Robot, free: Option<&str>) -> String {
    let sol = dqsym::ik::solve(
        r,
        &dqsym::ik::IkOptions {
            free: free.map(str::to_string),
            ..Default::default()
        },
    )
    .expect("ik");
    dqsym::ik::ik_rust(&sol).expect("rust")
}

/// A PUMA 560 target pose (from q = 0.3, -0.7, 1.1, 0.25, -1.3, 2.0).
fn puma_target() -> [[f64; 4]; 4] {
    let r = load("puma560");
    let sol = dqsym::ik::solve(&r, &dqsym::ik::IkOptions::default()).expect("ik");
    let q = [0.3, -0.7, 1.1, 0.25, -1.3, 2.0];
    let env = [
        ("a2", 0.4318),
        ("a3", 0.0203),
        ("d3", 0.15005),
        ("d4", 0.4318),
    ];
    let t = pose(&sol.home, &q, &r, &env);
    let n = puma::ik(&t, 0.4318, 0.0203, 0.15005, 0.4318);
    assert_eq!(n.n, 8, "PUMA: 8 branches");
    t
}

fn ur5_target() -> [[f64; 4]; 4] {
    let r = load("ur5");
    let sol = dqsym::ik::solve(&r, &dqsym::ik::IkOptions::default()).expect("ik");
    let q = [0.3, -0.7, 1.1, 0.25, -1.3, 2.0];
    let env = [
        ("a2", -0.425),
        ("a3", -0.39225),
        ("d1", 0.089159),
        ("d4", 0.10915),
        ("d5", 0.09465),
        ("d6", 0.0823),
    ];
    let t = pose(&sol.home, &q, &r, &env);
    let n = ur5::ik(&t, -0.425, -0.39225, 0.089159, 0.10915, 0.09465, 0.0823);
    assert_eq!(n.n, 8, "UR5: 8 branches");
    t
}

/// The pose from the robot's symbolic forward matrix evaluated at `q`.
fn pose(
    _home: &dqsym::Matrix4<dqsym::Scalar>,
    q: &[f64],
    r: &dqsym::Robot,
    env: &[(&str, f64)],
) -> [[f64; 4]; 4] {
    let m = r.forward_matrix();
    let mut all: Vec<(&str, f64)> = env.to_vec();
    for (v, x) in r.variables.iter().zip(q) {
        all.push((v.as_str(), *x));
    }
    std::array::from_fn(|i| std::array::from_fn(|j| m.rows[i][j].eval_at(&all).expect("eval")))
}

fn bench(c: &mut Criterion) {
    let puma_robot = load("puma560");
    let ur5_robot = load("ur5");
    let iiwa = load("kuka_iiwa7");
    let mut g = c.benchmark_group("ik_derivation");
    g.sample_size(10);
    g.bench_function("puma560", |b| {
        b.iter(|| derive(black_box(&puma_robot), None))
    });
    g.bench_function("ur5", |b| b.iter(|| derive(black_box(&ur5_robot), None)));
    g.bench_function("iiwa_free_theta3", |b| {
        b.iter(|| derive(black_box(&iiwa), Some("theta3")))
    });
    g.finish();
    let tp = puma_target();
    let tu = ur5_target();
    let mut g = c.benchmark_group("ik_solver_all_branches");
    // The solutions are written into a buffer the caller keeps (`ik_into`), as a controller
    // calling the solver in its loop does.
    let mut out = puma::IkSolutions::default();
    g.bench_function("puma560_generated", |b| {
        b.iter(|| {
            puma::ik_into(&mut out, black_box(&tp), 0.4318, 0.0203, 0.15005, 0.4318);
            out.n
        })
    });
    let mut out = ur5::IkSolutions::default();
    g.bench_function("ur5_generated", |b| {
        b.iter(|| {
            ur5::ik_into(
                &mut out,
                black_box(&tu),
                -0.425,
                -0.39225,
                0.089159,
                0.10915,
                0.09465,
                0.0823,
            );
            out.n
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().measurement_time(Duration::from_secs(3)).warm_up_time(Duration::from_secs(1));
    targets = bench
}
criterion_main!(benches);
