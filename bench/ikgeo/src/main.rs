//! dqsym's generated closed-form IK solvers (every branch) and the `ik-geo` crate, timed in one
//! criterion run on the same robots and the same poses: PUMA 560 (spherical wrist, axes 2 and 3
//! parallel; ik-geo's `spherical_two_parallel`) and UR5 (three parallel axes, the last two
//! intersecting; ik-geo's `three_parallel_two_intersecting`), each given to ik-geo as its
//! product-of-exponentials form (`h`, `p`) computed here from the same DH table. Beside them the
//! same solvers as generated before the residual check of issue 28 (`before/`, commit be91e84),
//! so the check's cost is measured on the same machine in the same run.
//!
//! Run: `bash bench/ikgeo/run` (release build; criterion arguments pass through, e.g.
//! `bash bench/ikgeo/run --measurement-time 2`). Each benchmark solves all `POSES` poses per
//! iteration; criterion's throughput line gives poses per second, and the time per iteration
//! over `POSES` is the time per pose.
#![allow(clippy::excessive_precision)]

use criterion::{black_box, Criterion, Throughput};
use ik_geo::robot::IKSolver;
use nalgebra::{Matrix3, Matrix3x6, Vector3};

/// ik-geo's `p` (seven displacements); nalgebra has no alias of this size.
type Matrix3x7 = nalgebra::SMatrix<f64, 3, 7>;
use std::time::Duration;

#[allow(dead_code)]
mod puma {
    include!("../../../benches/generated/ik_puma560.rs");
}
#[allow(dead_code)]
mod ur5 {
    include!("../../../benches/generated/ik_ur5.rs");
}
#[allow(dead_code)]
mod puma_before {
    include!("../before/ik_puma560.rs");
}
#[allow(dead_code)]
mod ur5_before {
    include!("../before/ik_ur5.rs");
}

/// Poses per robot, from random configurations (a fixed seed): every solver gets the same.
const POSES: usize = 1000;

/// Rounds over the poses of `--count`.
const COUNT_ROUNDS: usize = 5;

type M4 = [[f64; 4]; 4];

/// One standard-DH link: `Rz(theta) Tz(d) Tx(a) Rx(alpha)`.
fn dh_link(d: f64, a: f64, alpha: f64, th: f64) -> M4 {
    let (s, c) = th.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    [
        [c, -s * ca, s * sa, a * c],
        [s, c * ca, -c * sa, a * s],
        [0.0, sa, ca, d],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn mul(a: &M4, b: &M4) -> M4 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// The frames `F_0 = I, F_i = F_{i-1} A_i(q_i)` of a DH chain `(d, a, alpha)`.
fn dh_frames(rows: &[(f64, f64, f64)], q: &[f64]) -> Vec<M4> {
    let mut t: M4 = std::array::from_fn(|i| std::array::from_fn(|j| f64::from(u8::from(i == j))));
    let mut out = vec![t];
    for ((d, a, alpha), th) in rows.iter().zip(q) {
        t = mul(&t, &dh_link(*d, *a, *alpha, *th));
        out.push(t);
    }
    out
}

/// The product-of-exponentials form ik-geo takes: axis `h_i` the z axis of `F_{i-1}` at home,
/// `p_{i-1,i}` from the point of axis i-1 to the point of axis i, `p_{6T}` from the last axis's
/// point to the end; and the home rotation `M`, since ik-geo's end rotation is `R_1 ... R_6`
/// (the identity at home) where DH's is `R_1 ... R_6 M`. The point of axis i is the origin of
/// `F_{points[i]}` (a frame origin on that axis): ik-geo's spherical-wrist solvers take the
/// wrist centre as the point of the last three axes (`p_45 = p_56 = 0`).
fn poe(rows: &[(f64, f64, f64)], points: [usize; 6]) -> (Matrix3x6<f64>, Matrix3x7, Matrix3<f64>) {
    let f = dh_frames(rows, &[0.0; 6]);
    let origin = |m: &M4| Vector3::new(m[0][3], m[1][3], m[2][3]);
    let h: Vec<Vector3<f64>> = (0..6)
        .map(|i| Vector3::new(f[i][0][2], f[i][1][2], f[i][2][2]))
        .collect();
    let pt: Vec<Vector3<f64>> = points.iter().map(|&k| origin(&f[k])).collect();
    let mut p = vec![pt[0]];
    for i in 1..6 {
        p.push(pt[i] - pt[i - 1]);
    }
    p.push(origin(&f[6]) - pt[5]);
    let m = Matrix3::from_fn(|i, j| f[6][i][j]);
    (Matrix3x6::from_columns(&h), Matrix3x7::from_columns(&p), m)
}

/// A 64-bit LCG in [-3, 3].
fn angles(seed: &mut u64) -> [f64; 6] {
    std::array::from_fn(|_| {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 3.0
    })
}

struct Robot {
    name: &'static str,
    rows: [(f64, f64, f64); 6],
}

/// The poses of `POSES` random configurations: DH matrices for dqsym, (R, p) for ik-geo.
fn poses(r: &Robot, m: &Matrix3<f64>, seed: u64) -> Vec<(M4, Matrix3<f64>, Vector3<f64>)> {
    let mut s = seed;
    (0..POSES)
        .map(|_| {
            let q = angles(&mut s);
            let t = *dh_frames(&r.rows, &q).last().expect("end");
            let rot = Matrix3::from_fn(|i, j| t[i][j]) * m.transpose();
            (t, rot, Vector3::new(t[0][3], t[1][3], t[2][3]))
        })
        .collect()
}

/// ik-geo's model is the DH chain's: its forward kinematics gives the same pose, and its
/// solutions include the configuration (to 1e-6) for most poses.
fn check_ikgeo(r: &Robot, geo: &ik_geo::robot::Robot, m: &Matrix3<f64>) {
    let mut s = 99;
    let mut found = 0;
    for _ in 0..100 {
        let q = angles(&mut s);
        let t = *dh_frames(&r.rows, &q).last().expect("end");
        let (rg, pg) = geo.fk(&q);
        let rd = Matrix3::from_fn(|i, j| t[i][j]) * m.transpose();
        let pd = Vector3::new(t[0][3], t[1][3], t[2][3]);
        assert!(
            (rg - rd).norm() < 1e-12 && (pg - pd).norm() < 1e-12,
            "{}: fk",
            r.name
        );
        let wrap = |x: f64| (x + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU);
        found += usize::from(geo.ik(rd, pd).iter().any(|(s, _)| {
            (0..6).all(|k| {
                (wrap(s[k]) - wrap(q[k]))
                    .abs()
                    .min(std::f64::consts::TAU - (wrap(s[k]) - wrap(q[k])).abs())
                    < 1e-6
            })
        }));
    }
    eprintln!(
        "ik-geo {}: the configuration among the solutions for {found} of 100 poses",
        r.name
    );
    assert!(found >= 95, "{}: ik-geo solves another robot", r.name);
}

/// The poses of both robots and ik-geo's solvers for them, checked.
struct Setup {
    tp: Vec<(M4, Matrix3<f64>, Vector3<f64>)>,
    tu: Vec<(M4, Matrix3<f64>, Vector3<f64>)>,
    geo_puma: ik_geo::robot::Robot,
    geo_ur5: ik_geo::robot::Robot,
}

/// PUMA 560 lengths (a2, a3, d3, d4) and UR5's (a2, a3, d1, d4, d5, d6), as the solvers take them.
const PUMA: (f64, f64, f64, f64) = (0.4318, 0.0203, 0.15005, 0.4318);
const UR: (f64, f64, f64, f64, f64, f64) = (-0.425, -0.39225, 0.089159, 0.10915, 0.09465, 0.0823);

fn setup() -> Setup {
    let pi2 = std::f64::consts::FRAC_PI_2;
    let puma_robot = Robot {
        name: "PUMA 560",
        rows: [
            (0.0, 0.0, pi2),
            (0.0, 0.4318, 0.0),
            (0.15005, 0.0203, -pi2),
            (0.4318, 0.0, pi2),
            (0.0, 0.0, -pi2),
            (0.0, 0.0, 0.0),
        ],
    };
    let ur5_robot = Robot {
        name: "UR5",
        rows: [
            (0.089159, 0.0, pi2),
            (0.0, -0.425, 0.0),
            (0.0, -0.39225, 0.0),
            (0.10915, 0.0, pi2),
            (0.09465, 0.0, -pi2),
            (0.0823, 0.0, 0.0),
        ],
    };
    // The wrist centre, origin of F_4 (= F_5 = F_6), is the point of axes 4, 5, 6.
    let (hp, pp, mp) = poe(&puma_robot.rows, [0, 1, 2, 4, 4, 4]);
    let (hu, pu, mu) = poe(&ur5_robot.rows, [0, 1, 2, 3, 4, 5]);
    let geo_puma = ik_geo::robot::spherical_two_parallel(hp, pp);
    let geo_ur5 = ik_geo::robot::three_parallel_two_intersecting(hu, pu);
    check_ikgeo(&puma_robot, &geo_puma, &mp);
    check_ikgeo(&ur5_robot, &geo_ur5, &mu);
    let tp = poses(&puma_robot, &mp, 1);
    let tu = poses(&ur5_robot, &mu, 2);
    Setup {
        tp,
        tu,
        geo_puma,
        geo_ur5,
    }
}

fn main() {
    let s = setup();
    // `--count NAME` (no criterion run): NAME's solver on every pose `COUNT_ROUNDS` times, for
    // instruction counts under valgrind, which a loaded machine does not disturb; `none` is the
    // set-up alone, to subtract (bench/ikgeo/count).
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--count") {
        count(&s, args.get(i + 1).map_or("none", String::as_str));
        return;
    }
    bench(&s);
}

/// Solves every pose with solver `name` `COUNT_ROUNDS` times and prints the solutions' count.
fn count(s: &Setup, name: &str) {
    let (tp, tu, geo_puma, geo_ur5) = (&s.tp, &s.tu, &s.geo_puma, &s.geo_ur5);
    let (pa, pb, pc, pd) = PUMA;
    let ur = UR;
    let mut total = 0usize;
    let (mut op, mut ob) = (
        puma::IkSolutions::default(),
        puma_before::IkSolutions::default(),
    );
    let (mut ou, mut oub) = (
        ur5::IkSolutions::default(),
        ur5_before::IkSolutions::default(),
    );
    for _ in 0..COUNT_ROUNDS {
        for ((t, r, p), (tu, ru, pu)) in tp.iter().zip(tu.iter()) {
            total += match name {
                "puma560_dqsym_checked" => {
                    puma::ik_into(&mut op, black_box(t), pa, pb, pc, pd);
                    op.n
                }
                "puma560_dqsym_before_check" => {
                    puma_before::ik_into(&mut ob, black_box(t), pa, pb, pc, pd);
                    ob.n
                }
                "puma560_ikgeo" => geo_puma.ik(black_box(*r), black_box(*p)).len(),
                "ur5_dqsym_checked" => {
                    ur5::ik_into(&mut ou, black_box(tu), ur.0, ur.1, ur.2, ur.3, ur.4, ur.5);
                    ou.n
                }
                "ur5_dqsym_before_check" => {
                    ur5_before::ik_into(
                        &mut oub,
                        black_box(tu),
                        ur.0,
                        ur.1,
                        ur.2,
                        ur.3,
                        ur.4,
                        ur.5,
                    );
                    oub.n
                }
                "ur5_ikgeo" => geo_ur5.ik(black_box(*ru), black_box(*pu)).len(),
                "none" => 0,
                other => panic!("--count {other}: unknown"),
            };
        }
    }
    println!("{name}: {total} solutions");
}

/// The criterion run: every solver on every pose.
fn bench(s: &Setup) {
    let (tp, tu, geo_puma, geo_ur5) = (&s.tp, &s.tu, &s.geo_puma, &s.geo_ur5);
    let (pa, pb, pc, pd) = PUMA;
    let ur = UR;
    // The solutions are written into a buffer the caller keeps (`ik_into`), as a controller
    // calling the solver in its loop does; the sum of the counts keeps the work observable.
    let mut c = Criterion::default()
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_secs(1))
        .configure_from_args();
    let mut g = c.benchmark_group(format!("ik_{POSES}_poses"));
    g.throughput(Throughput::Elements(POSES as u64));
    let mut out = puma::IkSolutions::default();
    g.bench_function("puma560_dqsym_checked", |b| {
        b.iter(|| {
            tp.iter()
                .map(|(t, _, _)| {
                    puma::ik_into(&mut out, black_box(t), pa, pb, pc, pd);
                    out.n
                })
                .sum::<usize>()
        })
    });
    let mut out = puma_before::IkSolutions::default();
    g.bench_function("puma560_dqsym_before_check", |b| {
        b.iter(|| {
            tp.iter()
                .map(|(t, _, _)| {
                    puma_before::ik_into(&mut out, black_box(t), pa, pb, pc, pd);
                    out.n
                })
                .sum::<usize>()
        })
    });
    g.bench_function("puma560_ikgeo_spherical_two_parallel", |b| {
        b.iter(|| {
            tp.iter()
                .map(|(_, r, p)| geo_puma.ik(black_box(*r), black_box(*p)).len())
                .sum::<usize>()
        })
    });
    let mut out = ur5::IkSolutions::default();
    g.bench_function("ur5_dqsym_checked", |b| {
        b.iter(|| {
            tu.iter()
                .map(|(t, _, _)| {
                    ur5::ik_into(&mut out, black_box(t), ur.0, ur.1, ur.2, ur.3, ur.4, ur.5);
                    out.n
                })
                .sum::<usize>()
        })
    });
    let mut out = ur5_before::IkSolutions::default();
    g.bench_function("ur5_dqsym_before_check", |b| {
        b.iter(|| {
            tu.iter()
                .map(|(t, _, _)| {
                    ur5_before::ik_into(&mut out, black_box(t), ur.0, ur.1, ur.2, ur.3, ur.4, ur.5);
                    out.n
                })
                .sum::<usize>()
        })
    });
    g.bench_function("ur5_ikgeo_three_parallel_two_intersecting", |b| {
        b.iter(|| {
            tu.iter()
                .map(|(_, r, p)| geo_ur5.ik(black_box(*r), black_box(*p)).len())
                .sum::<usize>()
        })
    });
    g.finish();
    c.final_summary();
}
