//! The general 6R method (`dqsym ik --method general`): the derivation as a process (the
//! `dqsym` binary on a fully numeric skew 6R and on the same arm with every length a symbol),
//! the generated Rust solver per pose (degree 16, every solution), and beside it a
//! Newton–Raphson (Levenberg–Marquardt) multistart written here with 8, 32 and 128 seeds per
//! pose, whose found-rate (the fraction of the solver's solutions it finds) is printed.
#![allow(clippy::excessive_precision, clippy::needless_range_loop)]

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::time::Duration;

// Not a file of its own under benches/ (Cargo would take it for a bench target); a test
// (`ik_general_count::generated_bench_solver_is_current`) keeps it equal to what `dqsym ik
// --format rust` writes for benches/support/skew6r.toml.
#[allow(dead_code)]
mod skew {
    include!("generated/ik_general_skew6r.rs");
}

const SUPPORT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/support/");

type M4 = [[f64; 4]; 4];

/// benches/support/skew6r.toml as classic DH rows `(d, a, alpha)`.
const ROWS: [(f64, f64, f64); 6] = [
    (0.3, 0.05, std::f64::consts::FRAC_PI_3),
    (0.02, 0.4, std::f64::consts::FRAC_PI_6),
    (0.05, 0.03, std::f64::consts::FRAC_PI_2),
    (0.35, 0.02, -std::f64::consts::FRAC_PI_2),
    (0.07, 0.04, 2.0 * std::f64::consts::PI / 5.0),
    (0.1, 0.0, 0.0),
];
const LEN: f64 = 1.43;

/// The frames `T_0 … T_6` of the DH chain at `q`.
fn frames(q: &[f64; 6]) -> [M4; 7] {
    let mut out = [[[0.0; 4]; 4]; 7];
    for (i, row) in out[0].iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for (k, &(d, a, al)) in ROWS.iter().enumerate() {
        let (st, ct) = q[k].sin_cos();
        let (sa, ca) = al.sin_cos();
        let m = [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0.0, sa, ca, d],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let t = out[k];
        out[k + 1] = std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..4).map(|l| t[i][l] * m[l][j]).sum())
        });
    }
    out
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The pose error (position over the arm's size; half the columns' cross products) and the
/// geometric Jacobian.
fn error_jacobian(q: &[f64; 6], t: &M4) -> ([f64; 6], [[f64; 6]; 6]) {
    let fr = frames(q);
    let end = fr[6];
    let p = [end[0][3], end[1][3], end[2][3]];
    let mut e = [0.0; 6];
    for r in 0..3 {
        e[r] = (t[r][3] - p[r]) / LEN;
    }
    for c in 0..3 {
        let x = cross(
            [end[0][c], end[1][c], end[2][c]],
            [t[0][c], t[1][c], t[2][c]],
        );
        for r in 0..3 {
            e[3 + r] += 0.5 * x[r];
        }
    }
    let mut j = [[0.0; 6]; 6];
    for i in 0..6 {
        let z = [fr[i][0][2], fr[i][1][2], fr[i][2][2]];
        let o = [fr[i][0][3], fr[i][1][3], fr[i][2][3]];
        let v = cross(z, [p[0] - o[0], p[1] - o[1], p[2] - o[2]]);
        for r in 0..3 {
            j[r][i] = v[r] / LEN;
            j[3 + r][i] = z[r];
        }
    }
    (e, j)
}

fn solve6(mut a: [[f64; 6]; 6], mut b: [f64; 6]) -> Option<[f64; 6]> {
    for k in 0..6 {
        let p = (k..6).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
        if a[p][k].abs() < 1e-300 {
            return None;
        }
        a.swap(k, p);
        b.swap(k, p);
        for i in k + 1..6 {
            let f = a[i][k] / a[k][k];
            for j in k..6 {
                a[i][j] -= f * a[k][j];
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = [0.0; 6];
    for i in (0..6).rev() {
        let s: f64 = (i + 1..6).map(|j| a[i][j] * x[j]).sum();
        x[i] = (b[i] - s) / a[i][i];
    }
    Some(x)
}

/// Levenberg–Marquardt from `q`: the solution when the error falls below 1e-12 (about the
/// solver's own tolerance), in at most 100 steps.
fn newton(mut q: [f64; 6], t: &M4) -> Option<[f64; 6]> {
    let norm = |e: &[f64; 6]| e.iter().map(|x| x * x).sum::<f64>();
    let (mut e, mut j) = error_jacobian(&q, t);
    let mut lambda = 1e-3;
    for _ in 0..100 {
        if norm(&e) < 1e-24 {
            return Some(q.map(wrap));
        }
        let mut a = [[0.0; 6]; 6];
        let mut b = [0.0; 6];
        for r in 0..6 {
            for c in 0..6 {
                a[r][c] = (0..6).map(|k| j[k][r] * j[k][c]).sum();
            }
            a[r][r] += lambda;
            b[r] = (0..6).map(|k| j[k][r] * e[k]).sum();
        }
        let d = solve6(a, b)?;
        let trial: [f64; 6] = std::array::from_fn(|i| q[i] + d[i]);
        let (e2, j2) = error_jacobian(&trial, t);
        if norm(&e2) < norm(&e) {
            (q, e, j) = (trial, e2, j2);
            lambda = (lambda / 5.0).max(1e-12);
        } else {
            lambda *= 4.0;
            if lambda > 1e8 {
                return None;
            }
        }
    }
    None
}

fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
}

fn dist(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| wrap(x - y).abs())
        .fold(0.0, f64::max)
}

/// A small deterministic generator (xorshift) for seeds and configurations.
struct Rng(u64);

impl Rng {
    fn angle(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * std::f64::consts::PI
            - std::f64::consts::PI
    }
}

/// The distinct solutions `seeds` random starts reach (1e-6 apart, as the test's multistart).
fn multistart(t: &M4, seeds: usize, rng: &mut Rng) -> Vec<[f64; 6]> {
    let mut found: Vec<[f64; 6]> = Vec::new();
    for _ in 0..seeds {
        let q0 = std::array::from_fn(|_| rng.angle());
        if let Some(q) = newton(q0, t) {
            if !found.iter().any(|f| dist(f, &q) <= 1e-6) {
                found.push(q);
            }
        }
    }
    found
}

/// Poses of random configurations.
fn targets(n: usize) -> Vec<M4> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    (0..n)
        .map(|_| frames(&std::array::from_fn(|_| rng.angle()))[6])
        .collect()
}

/// The multistart's found-rate against the generated solver's solution sets.
fn found_rate(ts: &[M4], seeds: usize) -> f64 {
    let mut rng = Rng(12345);
    let (mut found, mut all) = (0, 0);
    for t in ts {
        let s = skew::ik(t);
        let exact: Vec<[f64; 6]> = (0..s.n)
            .filter(|&i| !s.approximate[i])
            .map(|i| s.q[i])
            .collect();
        let m = multistart(t, seeds, &mut rng);
        all += exact.len();
        found += exact
            .iter()
            .filter(|q| m.iter().any(|x| dist(x, q) <= 1e-6))
            .count();
    }
    found as f64 / all as f64
}

fn derivation(file: &str) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["ik", &format!("{SUPPORT}{file}"), "--method", "general"])
        .output()
        .expect("run dqsym");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("ik_general_derivation_process");
    g.sample_size(10);
    g.bench_function("skew6r_numeric", |b| b.iter(|| derivation("skew6r.toml")));
    g.bench_function("skew6r_symbolic", |b| {
        b.iter(|| derivation("skew6r_symbolic.toml"))
    });
    g.finish();
    let ts = targets(64);
    let total: usize = ts.iter().map(|t| skew::ik(t).n).sum();
    eprintln!("generated solver: {total} solutions at {} poses", ts.len());
    for seeds in [8, 32, 128] {
        eprintln!(
            "multistart with {seeds} seeds: found-rate {:.3}",
            found_rate(&ts, seeds)
        );
    }
    let mut g = c.benchmark_group("ik_general_solve_per_pose");
    let mut k = 0;
    g.bench_function("skew6r_generated_all_solutions", |b| {
        b.iter(|| {
            k = (k + 1) % ts.len();
            skew::ik(black_box(&ts[k])).n
        })
    });
    for seeds in [8, 32, 128] {
        let mut rng = Rng(777);
        g.bench_function(format!("newton_multistart_{seeds}_seeds"), |b| {
            b.iter(|| {
                k = (k + 1) % ts.len();
                multistart(black_box(&ts[k]), seeds, &mut rng).len()
            })
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().measurement_time(Duration::from_secs(3)).warm_up_time(Duration::from_secs(1));
    targets = bench
}
criterion_main!(benches);
