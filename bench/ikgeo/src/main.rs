//! dqsym's generated closed-form IK solvers (every branch) and the `ik-geo` crate, timed in one
//! criterion run: PUMA 560 (spherical wrist, axes 2 and 3 parallel) beside ik-geo's IRB 6640 (the
//! same family, ik-geo's `spherical_two_parallel`), and UR5 beside ik-geo's UR5
//! (`three_parallel_two_intersecting`). Each solver gets a reachable pose of its robot.
#![allow(clippy::excessive_precision)]

use criterion::{black_box, Criterion};
use nalgebra::{Matrix3, Vector3};
use std::time::Duration;

#[allow(dead_code)]
mod puma {
    include!("../../../benches/generated/ik_puma560.rs");
}
#[allow(dead_code)]
mod ur5 {
    include!("../../../benches/generated/ik_ur5.rs");
}

/// The pose of a standard-DH chain: rows `(theta offset 0, d, a, alpha)`.
fn dh_pose(rows: &[(f64, f64, f64)], q: &[f64]) -> [[f64; 4]; 4] {
    let mut t = [[0.0; 4]; 4];
    for (i, r) in t.iter_mut().enumerate() {
        r[i] = 1.0;
    }
    for ((d, a, alpha), th) in rows.iter().zip(q) {
        let (s, c) = th.sin_cos();
        let (sa, ca) = alpha.sin_cos();
        let l = [
            [c, -s * ca, s * sa, a * c],
            [s, c * ca, -c * sa, a * s],
            [0.0, sa, ca, *d],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let mut n = [[0.0; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                n[i][j] = (0..4).map(|k| t[i][k] * l[k][j]).sum();
            }
        }
        t = n;
    }
    t
}

fn main() {
    let pi2 = std::f64::consts::FRAC_PI_2;
    let q = [0.3, -0.7, 1.1, 0.25, -1.3, 2.0];
    let tp = dh_pose(
        &[
            (0.0, 0.0, pi2),
            (0.0, 0.4318, 0.0),
            (0.15005, 0.0203, -pi2),
            (0.4318, 0.0, pi2),
            (0.0, 0.0, -pi2),
            (0.0, 0.0, 0.0),
        ],
        &q,
    );
    let tu = dh_pose(
        &[
            (0.089159, 0.0, pi2),
            (0.0, -0.425, 0.0),
            (0.0, -0.39225, 0.0),
            (0.10915, 0.0, pi2),
            (0.09465, 0.0, -pi2),
            (0.0823, 0.0, 0.0),
        ],
        &q,
    );
    assert_eq!(puma::ik(&tp, 0.4318, 0.0203, 0.15005, 0.4318).n, 8);
    assert_eq!(
        ur5::ik(&tu, -0.425, -0.39225, 0.089159, 0.10915, 0.09465, 0.0823).n,
        8
    );
    let irb = ik_geo::robot::irb6640();
    let ur = ik_geo::robot::ur5();
    let (ri, ti) = irb.fk(&q);
    let (ru, tu_geo) = ur.fk(&q);
    use ik_geo::robot::IKSolver;
    let n_irb = irb.ik(ri, ti).len();
    let n_ur = ur.ik(ru, tu_geo).len();
    eprintln!("ik-geo solutions: IRB 6640 {n_irb}, UR5 {n_ur}");
    let mut c = Criterion::default()
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_secs(1))
        .configure_from_args();
    let mut g = c.benchmark_group("ik_solver_all_branches");
    // The solutions are written into a buffer the caller keeps (`ik_into`), as a controller
    // calling the solver in its loop does.
    let mut out = puma::IkSolutions::default();
    g.bench_function("dqsym_puma560_generated", |b| {
        b.iter(|| {
            puma::ik_into(&mut out, black_box(&tp), 0.4318, 0.0203, 0.15005, 0.4318);
            out.n
        })
    });
    g.bench_function("ikgeo_irb6640_spherical_two_parallel", |b| {
        b.iter(|| irb.ik(black_box(ri), black_box(ti)))
    });
    let mut out = ur5::IkSolutions::default();
    g.bench_function("dqsym_ur5_generated", |b| {
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
    g.bench_function("ikgeo_ur5_three_parallel_two_intersecting", |b| {
        b.iter(|| ur.ik(black_box(ru), black_box(tu_geo)))
    });
    g.finish();
    let _: (Matrix3<f64>, Vector3<f64>) = (ri, ti);
    c.final_summary();
}
