//! The general 6R method on Rethink's 7-joint arms (Sawyer and Baxter, the Robotics Toolbox's
//! DH tables, one joint free) and an independent count of the real solutions: a multistart
//! Levenberg–Marquardt written here on the plain 4 x 4 DH model finds solutions from many
//! random seeds; every solution it finds is among the general solver's, and every solution the
//! solver returns reproduces the pose.

use crate::common::Rng;
use crate::ik_general::{
    derive, deviation, dh_pose, dh_toml, dist, jaco, mul, row, size, skew_offset, wrapped, Row, M4,
    PI,
};
use dqsym::ik::{solve, IkMethod, IkOptions, IkSolution, NumSolution};

const AM90: (&str, f64) = ("-pi/2", -PI / 2.0);
const A90: (&str, f64) = ("pi/2", PI / 2.0);
const A0: (&str, f64) = ("0", 0.0);

/// Rethink Sawyer: the Robotics Toolbox's DH table (`models.DH.Sawyer`: `a1 = 81 mm`, every
/// twist `-pi/2` but the last, no offsets).
fn sawyer() -> Vec<Row> {
    let d = [0.317, 0.1925, 0.4, 0.1685, 0.4, 0.1363, 0.13375];
    let a = [0.081, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    (0..7)
        .map(|i| row(d[i], a[i], if i == 6 { A0 } else { AM90 }))
        .collect()
}

/// Rethink Baxter's left arm: the Robotics Toolbox's DH table (`models.DH.Baxter`; the
/// `pi/2` offset of joint 2 left out: it only renames the joint's zero).
fn baxter() -> Vec<Row> {
    vec![
        row(0.27, 0.069, AM90),
        row(0.0, 0.0, A90),
        row(0.102 + 0.262, 0.069, AM90),
        row(0.0, 0.0, A90),
        row(0.103 + 0.271, 0.010, AM90),
        row(0.0, 0.0, A90),
        row(0.28, 0.0, A0),
    ]
}

/// The 7-joint arm solved by the general method with joint `free` (from 0) a parameter.
fn derive_free(name: &str, rows: &[Row], free: usize) -> IkSolution {
    let text = dh_toml(name, rows);
    let robot = dqsym::parse_robot(&text, name, &dqsym::eval_scalar_text).expect("robot");
    let opts = IkOptions {
        free: Some(format!("q{}", free + 1)),
        method: IkMethod::General,
    };
    let sol = solve(&robot, &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(sol.general.is_some(), "{name}: {}", sol.family);
    sol
}

/// The full joint vector: the solved six with the free joint's value put back.
fn full(q6: &[f64], free: Option<(usize, f64)>) -> Vec<f64> {
    let mut q = q6.to_vec();
    if let Some((k, v)) = free {
        q.insert(k, v);
    }
    q
}

/// The solver's solutions at the pose of `q` (all joints), checked: at most 16, each one not
/// flagged approximate reproduces the pose to 1e-9 (rotation entries, positions over the
/// arm's size) by the independent model, and the original configuration is among them.
fn solve_checked(
    name: &str,
    sol: &IkSolution,
    rows: &[Row],
    q: &[f64],
    free: Option<usize>,
) -> Vec<NumSolution> {
    let t = dh_pose(rows, q);
    let fv = free.map(|k| (k, q[k]));
    let name_k = free.map(|k| format!("q{}", k + 1));
    let params: Vec<(&str, f64)> = match (&name_k, fv) {
        (Some(n), Some((_, v))) => vec![(n.as_str(), v)],
        _ => vec![],
    };
    let sols = sol.solve_numeric(&t, &params).expect("solve");
    assert!(sols.len() <= 16, "{name}: {} solutions", sols.len());
    let len = size(rows);
    for s in sols.iter().filter(|s| !s.approximate) {
        let dev = deviation(&t, &dh_pose(rows, &full(&s.q, fv)), len);
        assert!(
            dev <= 1e-9,
            "{name}: {:?} misses the pose by {dev} (q {q:?})",
            s.q
        );
    }
    let mut rest = q.to_vec();
    if let Some(k) = free {
        rest.remove(k);
    }
    assert!(
        sols.iter()
            .any(|s| !s.approximate && dist(&s.q, &rest) <= 1e-6),
        "{name}: {q:?} not among {sols:?}"
    );
    sols
}

/// 1,000 random configurations of Sawyer and Baxter, with the first joint free and with an
/// inner one (Sawyer's third, Baxter's fifth) free: every solution reproduces the pose to 1e-9
/// and the original configuration is among them.
#[test]
fn sawyer_and_baxter_round_trip_with_a_free_joint() {
    for (name, rows, frees) in [
        ("sawyer", sawyer(), [0usize, 2]),
        ("baxter", baxter(), [0usize, 4]),
    ] {
        for free in frees {
            let sol = derive_free(name, &rows, free);
            let mut rng = Rng::new(91 + free as u64);
            let n = if free == 0 { 1000 } else { 300 };
            let mut most = 0;
            for _ in 0..n {
                let q: Vec<f64> = (0..7).map(|_| rng.range(-PI, PI)).collect();
                most = most.max(solve_checked(name, &sol, &rows, &q, Some(free)).len());
            }
            eprintln!("{name}, q{} free: at most {most} solutions", free + 1);
            assert!(most >= 4, "{name}: {most}");
        }
    }
}

/// The frames of the DH chain: `T_0 = I`, `T_i = T_{i-1} A_i`; joint `i` turns about the z
/// axis of `T_{i-1}` through its origin. Written out (the same product as `dh_pose`, which
/// `multistart_frames_agree_with_the_model` checks) because the multistart calls it a million
/// times in a debug build.
fn frames(rows: &[Row], q: &[f64]) -> Vec<M4> {
    let mut t: M4 = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0; 4],
    ];
    t[3][3] = 1.0;
    let mut out = Vec::with_capacity(rows.len() + 1);
    out.push(t);
    for (r, th) in rows.iter().zip(q) {
        let (st, ct) = th.sin_cos();
        let (sa, ca) = r.alpha.1.sin_cos();
        let m = [
            [ct, -st * ca, st * sa, r.a * ct],
            [st, ct * ca, -ct * sa, r.a * st],
            [0.0, sa, ca, r.d],
        ];
        let mut n = t;
        for i in 0..3 {
            for j in 0..4 {
                let mut x = t[i][0] * m[0][j] + t[i][1] * m[1][j] + t[i][2] * m[2][j];
                if j == 3 {
                    x += t[i][3];
                }
                n[i][j] = x;
            }
        }
        t = n;
        out.push(t);
    }
    out
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Solves the 6 x 6 system `a x = b` by Gaussian elimination with partial pivoting.
#[allow(clippy::needless_range_loop)]
pub(crate) fn solve6(mut a: [[f64; 6]; 6], mut b: [f64; 6]) -> Option<[f64; 6]> {
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

/// The pose error as a 6-vector (position over `len`, then half the sum of the columns'
/// cross products, the rotation vector to first order) and the Jacobian of the solved joints.
fn error_and_jacobian(
    rows: &[Row],
    q: &[f64],
    solved: &[usize],
    target: &M4,
    len: f64,
) -> ([f64; 6], [[f64; 6]; 6]) {
    let fr = frames(rows, q);
    let end = fr[rows.len()];
    let p = [end[0][3], end[1][3], end[2][3]];
    let mut e = [0.0; 6];
    for r in 0..3 {
        e[r] = (target[r][3] - p[r]) / len;
    }
    for c in 0..3 {
        let x = cross(
            [end[0][c], end[1][c], end[2][c]],
            [target[0][c], target[1][c], target[2][c]],
        );
        for r in 0..3 {
            e[3 + r] += 0.5 * x[r];
        }
    }
    let mut j = [[0.0; 6]; 6];
    for (col, &i) in solved.iter().enumerate() {
        let z = [fr[i][0][2], fr[i][1][2], fr[i][2][2]];
        let o = [fr[i][0][3], fr[i][1][3], fr[i][2][3]];
        let v = cross(z, [p[0] - o[0], p[1] - o[1], p[2] - o[2]]);
        for r in 0..3 {
            j[r][col] = v[r] / len;
            j[3 + r][col] = z[r];
        }
    }
    (e, j)
}

/// Levenberg–Marquardt from `seed` on the solved joints (the others held): the joint vector
/// when it converges to the pose (deviation at most 1e-12), else `None`.
fn levenberg_marquardt(
    rows: &[Row],
    seed: &[f64],
    solved: &[usize],
    target: &M4,
    len: f64,
) -> Option<Vec<f64>> {
    let mut q = seed.to_vec();
    let norm = |e: &[f64; 6]| e.iter().map(|x| x * x).sum::<f64>();
    let (mut e, mut j) = error_and_jacobian(rows, &q, solved, target, len);
    let mut lambda = 1e-3;
    for _ in 0..100 {
        if norm(&e) < 1e-28 {
            break;
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
        let mut trial = q.clone();
        for (c, &i) in solved.iter().enumerate() {
            trial[i] += d[c];
        }
        let (e2, j2) = error_and_jacobian(rows, &trial, solved, target, len);
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
    let dev = deviation(target, &dh_pose(rows, &q), len);
    (dev <= 1e-12).then(|| solved.iter().map(|&i| wrapped(q[i])).collect())
}

/// Distinct solutions found from `seeds` random seeds. Two converged solutions are one when
/// their joints agree to 1e-6 rad: both reproduce the pose to 1e-12, so each is within 1e-12
/// over the smallest singular value of the Jacobian of the exact solution, about 1e-9 at the
/// random (non-singular) poses used here; two distinct solutions of such a pose are further
/// apart than 1e-6 (closer ones would mean a configuration within 1e-6 of a singular set).
fn multistart(
    rows: &[Row],
    t: &M4,
    free: Option<(usize, f64)>,
    seeds: usize,
    rng: &mut Rng,
) -> Vec<Vec<f64>> {
    let n = rows.len();
    let solved: Vec<usize> = (0..n)
        .filter(|i| free.is_none_or(|(k, _)| k != *i))
        .collect();
    let len = size(rows);
    let mut found: Vec<Vec<f64>> = Vec::new();
    for _ in 0..seeds {
        let mut seed: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
        if let Some((k, v)) = free {
            seed[k] = v;
        }
        if let Some(s) = levenberg_marquardt(rows, &seed, &solved, t, len) {
            if !found.iter().any(|f| dist(f, &s) <= 1e-6) {
                found.push(s);
            }
        }
    }
    found
}

/// The independent count: at 30 random poses per arm (the skew 6R, Jaco, Sawyer with its
/// first joint free), 300 Levenberg–Marquardt starts each; every distinct solution they
/// find is one of the general solver's (and every solution of the solver reproduces the
/// pose, `solve_checked`), so the solver's count is at least the multistart's; over all poses
/// the multistart finds at least 98% of the solver's solutions (a random start can miss a
/// small basin; its found-rate is printed).
#[test]
fn solution_sets_agree_with_an_independent_multistart() {
    let arms: Vec<(&str, Vec<Row>, Option<usize>)> = vec![
        ("skew", skew_offset(), None),
        ("jaco", jaco(), None),
        ("sawyer", sawyer(), Some(0)),
    ];
    for (name, rows, free) in arms {
        let sol = match free {
            Some(k) => derive_free(name, &rows, k),
            None => derive(name, &rows, IkMethod::General),
        };
        let mut rng = Rng::new(101);
        let (mut total_solver, mut total_multi) = (0, 0);
        for _ in 0..30 {
            let q: Vec<f64> = (0..rows.len()).map(|_| rng.range(-PI, PI)).collect();
            let exact: Vec<NumSolution> = solve_checked(name, &sol, &rows, &q, free)
                .into_iter()
                .filter(|s| !s.approximate)
                .collect();
            let t = dh_pose(&rows, &q);
            let fv = free.map(|k| (k, q[k]));
            let multi = multistart(&rows, &t, fv, 300, &mut rng);
            for m in &multi {
                assert!(
                    exact.iter().any(|s| dist(&s.q, m) <= 1e-6),
                    "{name}: the multistart's solution {m:?} is not among the solver's {exact:?} (q {q:?})"
                );
            }
            assert!(multi.len() <= exact.len());
            total_solver += exact.len();
            total_multi += multi.len();
        }
        assert!(
            50 * total_multi >= 49 * total_solver,
            "{name}: the multistart found {total_multi} of the solver's {total_solver}"
        );
        eprintln!(
            "{name}: solver {total_solver} solutions at 30 poses, multistart (300 seeds) {total_multi}: found-rate {:.3}",
            total_multi as f64 / total_solver as f64
        );
    }
}

/// The multistart's model is the test's own: a pose it produces from a configuration is the
/// pose `dh_pose` gives (a check of `frames` against the model it differentiates).
#[test]
fn multistart_frames_agree_with_the_model() {
    let rows = sawyer();
    let q: Vec<f64> = (0..7).map(|i| 0.3 * i as f64 - 0.8).collect();
    let fr = frames(&rows, &q);
    let t = dh_pose(&rows, &q);
    assert!(deviation(&t, &fr[7], 1.0) <= 1e-15);
    assert!(deviation(&mul(&fr[6], &dh_pose(&rows[6..], &q[6..])), &t, 1.0) <= 1e-15);
}

/// benches/generated/ik_general_skew6r.rs is what `dqsym ik --format rust` writes for
/// benches/support/skew6r.toml (`DQSYM_BLESS=1` rewrites it).
#[test]
fn generated_bench_solver_is_current() {
    let dir = env!("CARGO_MANIFEST_DIR");
    let file = format!("{dir}/benches/support/skew6r.toml");
    let text = std::fs::read_to_string(&file).expect("robot file");
    let robot = dqsym::parse_robot(&text, &file, &dqsym::eval_scalar_text).expect("robot");
    let sol = solve(&robot, &IkOptions::default()).expect("ik");
    assert_eq!(sol.general.as_ref().map(|g| g.degree), Some(16));
    let want = dqsym::ik::ik_rust(&sol).expect("rust");
    let path = format!("{dir}/benches/generated/ik_general_skew6r.rs");
    if std::env::var_os("DQSYM_BLESS").is_some() {
        std::fs::write(&path, &want).expect("write the bench solver");
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        have == want,
        "{path} is out of date: rerun with DQSYM_BLESS=1 to rewrite it"
    );
}
