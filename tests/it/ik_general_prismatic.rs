//! The general method on chains with prismatic joints (`ik::general`, a slide's length `d`
//! enters the Raghavan–Roth quantities through `(1, d, d²)`): a skew 5R1P and a skew 4R2P arm
//! of no special family, 1,000 random configurations each, checked by an independent classic-DH
//! 4 x 4 model written here (every solution not flagged approximate reproduces the pose to 1e-9,
//! rotation entries and positions over the arm's size; the original configuration is among
//! them); their solution counts against an independent Levenberg–Marquardt multistart; the
//! Stanford arm (a family) forced through the general method against the family's solution
//! set; and near-singular poses, where nothing wrong is returned unflagged.

use crate::common::Rng;
use crate::ik_general_count::{cross, solve6};
use crate::mat4::mul;
use dqsym::ik::{solve, IkMethod, IkOptions, IkSolution, NumSolution};

pub(crate) type M4 = [[f64; 4]; 4];
const PI: f64 = std::f64::consts::PI;

/// One classic DH row `Rz(theta) Tz(d) Tx(a) Rx(alpha)`; a prismatic row's variable adds to
/// `d`, a revolute row's to `theta`. Angles as text for the robot file and as numbers here.
#[derive(Clone, Copy)]
pub(crate) struct Row {
    pub(crate) prismatic: bool,
    pub(crate) theta: (&'static str, f64),
    pub(crate) d: f64,
    pub(crate) a: f64,
    pub(crate) alpha: (&'static str, f64),
}

pub(crate) fn rev(d: f64, a: f64, alpha: (&'static str, f64)) -> Row {
    Row {
        prismatic: false,
        theta: ("0", 0.0),
        d,
        a,
        alpha,
    }
}

pub(crate) fn pri(theta: (&'static str, f64), a: f64, alpha: (&'static str, f64)) -> Row {
    Row {
        prismatic: true,
        theta,
        d: 0.0,
        a,
        alpha,
    }
}

/// The frames `T_0 = I`, `T_i = T_{i-1} A_i(q_i)`: joint `i` moves along or about the z axis of
/// `T_{i-1}`.
pub(crate) fn frames(rows: &[Row], q: &[f64]) -> Vec<M4> {
    let mut t: M4 = std::array::from_fn(|r| std::array::from_fn(|c| f64::from(u8::from(r == c))));
    let mut out = vec![t];
    for (r, x) in rows.iter().zip(q) {
        let (th, d) = if r.prismatic {
            (r.theta.1, r.d + x)
        } else {
            (r.theta.1 + x, r.d)
        };
        let (st, ct) = th.sin_cos();
        let (sa, ca) = r.alpha.1.sin_cos();
        let m = [
            [ct, -st * ca, st * sa, r.a * ct],
            [st, ct * ca, -ct * sa, r.a * st],
            [0.0, sa, ca, d],
            [0.0, 0.0, 0.0, 1.0],
        ];
        t = mul(&t, &m);
        out.push(t);
    }
    out
}

pub(crate) fn pose(rows: &[Row], q: &[f64]) -> M4 {
    frames(rows, q)[rows.len()]
}

pub(crate) fn dh_toml(name: &str, rows: &[Row]) -> String {
    let mut s = format!("name = \"{name}\"\nconvention = \"dh\"\n");
    for (i, r) in rows.iter().enumerate() {
        let (kind, theta, d) = if r.prismatic {
            ("prismatic", r.theta.0.to_string(), format!("q{}", i + 1))
        } else {
            ("revolute", format!("q{}", i + 1), r.d.to_string())
        };
        s.push_str(&format!(
            "\n[[joint]]\ntype = \"{kind}\"\ntheta = \"{theta}\"\nd = \"{d}\"\na = \"{}\"\nalpha = \"{}\"\n",
            r.a, r.alpha.0
        ));
    }
    s
}

pub(crate) fn derive(name: &str, rows: &[Row], method: IkMethod) -> IkSolution {
    let text = dh_toml(name, rows);
    let robot = dqsym::parse_robot(&text, name, &dqsym::eval_scalar_text).expect("robot");
    solve(&robot, &IkOptions { free: None, method }).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn wrapped(a: f64) -> f64 {
    (a + 3.0 * PI).rem_euclid(2.0 * PI) - PI
}

/// The largest joint difference: angles on the circle, slides as lengths.
pub(crate) fn dist(rows: &[Row], a: &[f64], b: &[f64]) -> f64 {
    rows.iter()
        .zip(a.iter().zip(b))
        .map(|(r, (x, y))| {
            if r.prismatic {
                (x - y).abs()
            } else {
                wrapped(x - y).abs()
            }
        })
        .fold(0.0, f64::max)
}

/// Rotation entries as they are, positions over `len`.
pub(crate) fn deviation(want: &M4, got: &M4, len: f64) -> f64 {
    let mut d: f64 = 0.0;
    for r in 0..3 {
        for c in 0..4 {
            let e = (want[r][c] - got[r][c]).abs();
            d = d.max(if c == 3 { e / len } else { e });
        }
    }
    d
}

pub(crate) fn size(rows: &[Row]) -> f64 {
    // A slide's range (at most 0.8 here) counts as its length.
    rows.iter()
        .map(|r| r.d.abs() + r.a.abs() + if r.prismatic { 0.8 } else { 0.0 })
        .sum()
}

/// A random configuration: angles in `(−π, π)`, slides in `(−0.5, 0.5)`.
pub(crate) fn random_q(rows: &[Row], rng: &mut Rng) -> Vec<f64> {
    rows.iter()
        .map(|r| {
            if r.prismatic {
                rng.range(-0.5, 0.5)
            } else {
                rng.range(-PI, PI)
            }
        })
        .collect()
}

/// The solver's solutions at the pose of `q`, checked: at most `most`, each one not flagged
/// approximate reproduces the pose to 1e-9 by the model here, the original is among them.
pub(crate) fn solve_checked(
    name: &str,
    sol: &IkSolution,
    rows: &[Row],
    q: &[f64],
    most: usize,
) -> Vec<NumSolution> {
    let t = pose(rows, q);
    let sols = sol.solve_numeric(&t, &[]).expect("solve");
    assert!(sols.len() <= most, "{name}: {} solutions", sols.len());
    let len = size(rows);
    for s in sols.iter().filter(|s| !s.approximate) {
        let dev = deviation(&t, &pose(rows, &s.q), len);
        assert!(dev <= 1e-9, "{name}: {:?} misses by {dev} (q {q:?})", s.q);
    }
    assert!(
        sols.iter()
            .any(|s| !s.approximate && dist(rows, &s.q, q) <= 1e-6),
        "{name}: {q:?} not among {sols:?}"
    );
    sols
}

const A0: (&str, f64) = ("0", 0.0);

/// A 5R1P arm of no family: skew axes, offsets everywhere, the slide third.
pub(crate) fn skew_5r1p() -> Vec<Row> {
    vec![
        rev(0.3, 0.1, ("pi/3", PI / 3.0)),
        rev(0.05, 0.4, ("pi/5", PI / 5.0)),
        pri(("1/3", 1.0 / 3.0), 0.07, ("-pi/4", -PI / 4.0)),
        rev(0.2, 0.03, ("2*pi/5", 2.0 * PI / 5.0)),
        rev(0.11, 0.06, ("-pi/3", -PI / 3.0)),
        rev(0.09, 0.02, ("pi/7", PI / 7.0)),
    ]
}

/// A 4R2P arm of no family: slides third and fifth (the hidden joint and one of the joints
/// of the null vector in the loop read from joint 1).
pub(crate) fn skew_4r2p() -> Vec<Row> {
    vec![
        rev(0.3, 0.1, ("pi/3", PI / 3.0)),
        rev(0.05, 0.4, ("pi/5", PI / 5.0)),
        pri(("1/3", 1.0 / 3.0), 0.07, ("-pi/4", -PI / 4.0)),
        rev(0.2, 0.03, ("2*pi/5", 2.0 * PI / 5.0)),
        pri(("-2/5", -0.4), 0.06, ("-pi/3", -PI / 3.0)),
        rev(0.09, 0.02, ("pi/7", PI / 7.0)),
    ]
}

/// The same 5R1P with the slide last: the loop must be read so that a turning joint ends it.
pub(crate) fn slide_last_5r1p() -> Vec<Row> {
    let mut rows = skew_5r1p();
    rows.swap(2, 5);
    rows[2] = rev(0.09, 0.02, ("pi/7", PI / 7.0));
    rows
}

#[test]
fn skew_prismatic_arms_round_trip_with_the_degree_of_their_class() {
    for (name, rows, degree, n) in [
        ("skew 5R1P", skew_5r1p(), 16, 1000),
        ("skew 4R2P", skew_4r2p(), 8, 1000),
        ("5R1P slide last", slide_last_5r1p(), 16, 300),
    ] {
        let sol = derive(name, &rows, IkMethod::Auto);
        let info = sol
            .general
            .clone()
            .unwrap_or_else(|| panic!("{name}: {}", sol.family));
        assert_eq!(info.degree, degree, "{name}");
        let mut rng = Rng::new(29);
        let mut most = 0;
        for _ in 0..n {
            let q = random_q(&rows, &mut rng);
            most = most.max(solve_checked(name, &sol, &rows, &q, degree).len());
        }
        eprintln!(
            "{name}: degree {}, at most {most} real solutions",
            info.degree
        );
        assert!(most >= 4, "{name}: {most}");
    }
}

/// The pose error (position over `len`, then the rotation vector to first order) and its
/// Jacobian: a slide's column moves the end along its axis and turns nothing.
fn error_and_jacobian(rows: &[Row], q: &[f64], target: &M4, len: f64) -> ([f64; 6], [[f64; 6]; 6]) {
    let fr = frames(rows, q);
    let end = fr[6];
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
    for i in 0..6 {
        let z = [fr[i][0][2], fr[i][1][2], fr[i][2][2]];
        if rows[i].prismatic {
            for r in 0..3 {
                j[r][i] = z[r] / len;
            }
        } else {
            let o = [fr[i][0][3], fr[i][1][3], fr[i][2][3]];
            let v = cross(z, [p[0] - o[0], p[1] - o[1], p[2] - o[2]]);
            for r in 0..3 {
                j[r][i] = v[r] / len;
                j[3 + r][i] = z[r];
            }
        }
    }
    (e, j)
}

/// Levenberg–Marquardt from `seed`: the configuration when it converges to the pose
/// (deviation at most 1e-12), else `None`.
pub(crate) fn levenberg_marquardt(
    rows: &[Row],
    seed: &[f64],
    target: &M4,
    len: f64,
) -> Option<Vec<f64>> {
    let mut q = seed.to_vec();
    let norm = |e: &[f64; 6]| e.iter().map(|x| x * x).sum::<f64>();
    let (mut e, mut j) = error_and_jacobian(rows, &q, target, len);
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
        let trial: Vec<f64> = q.iter().zip(d).map(|(x, dx)| x + dx).collect();
        let (e2, j2) = error_and_jacobian(rows, &trial, target, len);
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
    let dev = deviation(target, &pose(rows, &q), len);
    (dev <= 1e-12).then(|| {
        rows.iter()
            .zip(q)
            .map(|(r, x)| if r.prismatic { x } else { wrapped(x) })
            .collect()
    })
}

/// The distinct solutions (joints apart by more than 1e-6) that [`levenberg_marquardt`] finds
/// from `starts` random seeds (angles in `(−π, π)`, slides in `(−1, 1)`).
pub(crate) fn multistart(
    rows: &[Row],
    target: &M4,
    len: f64,
    starts: usize,
    rng: &mut Rng,
) -> Vec<Vec<f64>> {
    multistart_by(rows, target, len, starts, rng, |a, b| {
        dist(rows, a, b) <= 1e-6
    })
}

/// [`multistart`], two solutions being the same when `same` says so.
pub(crate) fn multistart_by(
    rows: &[Row],
    target: &M4,
    len: f64,
    starts: usize,
    rng: &mut Rng,
    same: impl Fn(&[f64], &[f64]) -> bool,
) -> Vec<Vec<f64>> {
    let mut found: Vec<Vec<f64>> = Vec::new();
    for _ in 0..starts {
        let seed: Vec<f64> = rows
            .iter()
            .map(|r| {
                if r.prismatic {
                    rng.range(-1.0, 1.0)
                } else {
                    rng.range(-PI, PI)
                }
            })
            .collect();
        if let Some(s) = levenberg_marquardt(rows, &seed, target, len) {
            if !found.iter().any(|f| same(f, &s)) {
                found.push(s);
            }
        }
    }
    found
}

/// The independent count: at 30 random poses per arm, 300 Levenberg–Marquardt starts each
/// (slides seeded in `(−1, 1)`); every distinct solution they find (joints apart by more than
/// 1e-6: both reproduce the pose to 1e-12, so each is within about 1e-9 of its exact solution
/// at these non-singular poses) is one of the solver's, and over all poses they find at least
/// 98% of the solver's solutions (a random start can miss a small basin).
#[test]
fn prismatic_solution_sets_agree_with_an_independent_multistart() {
    for (name, rows, degree) in [
        ("skew 5R1P", skew_5r1p(), 16),
        ("skew 4R2P", skew_4r2p(), 8),
    ] {
        let sol = derive(name, &rows, IkMethod::Auto);
        let len = size(&rows);
        let mut rng = Rng::new(101);
        let (mut total_solver, mut total_multi) = (0, 0);
        for _ in 0..30 {
            let q = random_q(&rows, &mut rng);
            let exact: Vec<NumSolution> = solve_checked(name, &sol, &rows, &q, degree)
                .into_iter()
                .filter(|s| !s.approximate)
                .collect();
            let found = multistart(&rows, &pose(&rows, &q), len, 300, &mut rng);
            for m in &found {
                assert!(
                    exact.iter().any(|s| dist(&rows, &s.q, m) <= 1e-6),
                    "{name}: the multistart's {m:?} is not among the solver's {exact:?} (q {q:?})"
                );
            }
            total_solver += exact.len();
            total_multi += found.len();
        }
        assert!(
            50 * total_multi >= 49 * total_solver,
            "{name}: the multistart found {total_multi} of the solver's {total_solver}"
        );
        eprintln!(
            "{name}: solver {total_solver} solutions at 30 poses, multistart {total_multi}: found-rate {:.3}",
            total_multi as f64 / total_solver as f64
        );
    }
}

/// The Stanford arm (`examples/robots/stanford.toml`, spherical wrist: a family) as rows here.
fn stanford(d2: f64, d6: f64) -> Vec<Row> {
    let (am90, a90) = (("-pi/2", -PI / 2.0), ("pi/2", PI / 2.0));
    vec![
        rev(0.0, 0.0, am90),
        rev(d2, 0.0, a90),
        pri(A0, 0.0, A0),
        rev(0.0, 0.0, am90),
        rev(0.0, 0.0, a90),
        rev(d6, 0.0, A0),
    ]
}

fn stanford_solutions(method: IkMethod) -> IkSolution {
    let file = format!(
        "{}/examples/robots/stanford.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&file).expect("robot file");
    let robot = dqsym::parse_robot(&text, &file, &dqsym::eval_scalar_text).expect("robot");
    solve(&robot, &IkOptions { free: None, method }).expect("ik")
}

/// `--method general` on the Stanford arm gives the family's solution set at 300 random
/// configurations (slides of either sign): each general solution is one of the family's and
/// the other way round, every one reproduces the pose by the model here.
#[test]
fn stanford_arm_forced_general_gives_the_family_solution_set() {
    let (d2, d6) = (0.154, 0.263);
    let rows = stanford(d2, d6);
    let params = [("d2", d2), ("d6", d6)];
    let family = stanford_solutions(IkMethod::Auto);
    assert!(family.general.is_none(), "{}", family.family);
    let general = stanford_solutions(IkMethod::General);
    let info = general.general.clone().expect("general");
    eprintln!("stanford forced general: degree {}", info.degree);
    let len = size(&rows);
    let mut rng = Rng::new(7);
    for _ in 0..300 {
        let mut q = random_q(&rows, &mut rng);
        q[2] = rng.range(0.1, 0.8) * if rng.below(2) == 0 { 1.0 } else { -1.0 };
        let t = pose(&rows, &q);
        let exact = |sol: &IkSolution| -> Vec<Vec<f64>> {
            let s = sol.solve_numeric(&t, &params).expect("solve");
            s.into_iter()
                .filter(|s| !s.approximate && !s.singular)
                .map(|s| {
                    let dev = deviation(&t, &pose(&rows, &s.q), len);
                    assert!(dev <= 1e-9, "{:?} misses by {dev} (q {q:?})", s.q);
                    s.q
                })
                .collect()
        };
        let (f, g) = (exact(&family), exact(&general));
        assert!(g.iter().any(|s| dist(&rows, s, &q) <= 1e-6), "{q:?}: {g:?}");
        for a in &f {
            assert!(
                g.iter().any(|b| dist(&rows, a, b) <= 1e-6),
                "family {a:?} not in {g:?}"
            );
        }
        for b in &g {
            assert!(
                f.iter().any(|a| dist(&rows, a, b) <= 1e-6),
                "general {b:?} not in {f:?}"
            );
        }
    }
}

/// Arms of a family forced through the general method state the family's solution count as
/// their degree (the product of the family's branch counts, 8 for each): the Stanford arm
/// (`det M` has `θ5 = 0` and `θ5 = π`, the wrist singular set, as roots of multiplicity four at
/// every target: not counted), the PUMA 560, the KUKA KR5 and the UR5.
#[test]
fn forced_general_degree_is_the_family_solution_count() {
    for file in ["stanford", "puma560", "kuka_kr5", "ur5"] {
        let path = format!("{}/examples/robots/{file}.toml", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).expect("robot file");
        let robot = dqsym::parse_robot(&text, &path, &dqsym::eval_scalar_text).expect("robot");
        let derive = |method| solve(&robot, &IkOptions { free: None, method }).expect("ik");
        let family = derive(IkMethod::Auto);
        assert!(family.general.is_none(), "{file}: {}", family.family);
        let count: usize = family.steps.iter().map(|s| s.formula.branches()).product();
        let general = derive(IkMethod::General);
        let degree = general.general.expect("general").degree;
        assert_eq!(degree, count, "{file}");
        eprintln!("{file}: forced general, degree {degree} = the family's {count} solutions");
    }
}

/// Near-singular poses of the Stanford arm forced through the general method: its wrist at
/// `theta5 = eps` and its slide at `d3 = eps` (the wrist centre on axis 2: `theta2` nearly a
/// free turn, a nearly continuous family of solutions), `eps` from 1e-12 to 1e-3: every
/// solution returned unflagged reproduces the pose to 1e-9 by the model here; the wrist pose
/// is always reached (exactly or flagged), the shoulder one where the elimination does not
/// nearly vanish identically (counted and printed).
#[test]
fn near_singular_prismatic_poses_return_nothing_wrong_unflagged() {
    let (d2, d6) = (0.154, 0.263);
    let st = stanford(d2, d6);
    let general = stanford_solutions(IkMethod::General);
    let params = [("d2", d2), ("d6", d6)];
    let mut rng = Rng::new(13);
    let mut shoulder = 0;
    for k in 3..=12 {
        let eps = 10f64.powi(-k);
        for _ in 0..10 {
            let mut q = random_q(&st, &mut rng);
            q[2] = rng.range(0.2, 0.8);
            q[4] = eps;
            let best = check_flagged("stanford, theta5 = eps", &general, &st, &q, &params);
            assert!(
                best <= 1e-6,
                "theta5 = {eps}: not reached ({best}, q {q:?})"
            );
            let mut q = random_q(&st, &mut rng);
            q[2] = eps;
            if check_flagged("stanford, d3 = eps", &general, &st, &q, &params) <= 1e-6 {
                shoulder += 1;
            }
        }
    }
    eprintln!("stanford, d3 = eps: the pose reached at {shoulder} of 100");
}

/// Every unflagged solution reproduces the pose to 1e-9; returns the best deviation of any.
pub(crate) fn check_flagged(
    name: &str,
    sol: &IkSolution,
    rows: &[Row],
    q: &[f64],
    params: &[(&str, f64)],
) -> f64 {
    let t = pose(rows, q);
    let len = size(rows);
    let sols = sol.solve_numeric(&t, params).expect("solve");
    let mut best = f64::INFINITY;
    for s in &sols {
        let dev = deviation(&t, &pose(rows, &s.q), len);
        best = best.min(dev);
        if !s.approximate {
            assert!(
                dev <= 1e-9,
                "{name}: unflagged {:?} misses by {dev} (q {q:?})",
                s.q
            );
        }
    }
    best
}

/// The exact equations with slides (`ik::general::exact`, the basis `(1, d, d²)`) equal the
/// numeric core's sampled coefficients at random targets, for the 5R1P, the 4R2P and the
/// 5R1P whose last joint slides (read backwards). The tolerance is the one of
/// `ik_general::exact_equations_equal_the_sampled_coefficients` (some 2,000 roundings of order
/// one numbers, 2.2e-13 relative, twice, with a margin): these arms' lengths are below 1, so a
/// coefficient of `d^j` differs from the core's scaled one by a factor `len^j` of order one.
#[test]
#[allow(clippy::needless_range_loop)]
fn prismatic_exact_equations_equal_the_sampled_coefficients() {
    let mut rng = Rng::new(72);
    // Twists whose cosines and sines are in Q(sqrt 2, sqrt 3), slides at theta 0: the exact
    // coefficients of the arms above (cos(1/3), the seventh roots of unity of pi/7) pass the
    // term limit.
    let plain = |rows: Vec<Row>| -> Vec<Row> {
        let twists = [
            ("pi/3", PI / 3.0),
            ("pi/4", PI / 4.0),
            ("-pi/2", -PI / 2.0),
            ("pi/6", PI / 6.0),
            ("-pi/3", -PI / 3.0),
            ("0", 0.0),
        ];
        rows.into_iter()
            .zip(twists)
            .map(|(r, alpha)| Row {
                alpha,
                theta: A0,
                ..r
            })
            .collect()
    };
    for (name, rows) in [
        ("plain 5R1P", plain(skew_5r1p())),
        ("plain 4R2P", plain(skew_4r2p())),
        ("plain 5R1P slide last", plain(slide_last_5r1p())),
    ] {
        let sol = derive(name, &rows, IkMethod::General);
        let info = sol.general.clone().expect("general");
        let eq = dqsym::ik::general::exact::exact_equations(&sol, &info).expect("exact");
        assert!(
            !rows[eq.order[5]].prismatic,
            "{name}: the loop ends with a slide"
        );
        assert_eq!(
            eq.prismatic.iter().filter(|p| **p).count(),
            rows.iter().filter(|r| r.prismatic).count()
        );
        let arr = usize::from(eq.arrangement.0) * 6;
        for _ in 0..4 {
            let t = pose(&rows, &random_q(&rows, &mut rng));
            let env = |n: &str| -> Option<f64> {
                for (r, row) in dqsym::ik::TARGET_SYMBOLS.iter().enumerate() {
                    if let Some(c) = row.iter().position(|x| *x == n) {
                        return Some(t[r][c]);
                    }
                }
                None
            };
            let (am, bm) = eq.eval(&env).expect("eval");
            let (sam, sbm) =
                dqsym::ik::general::sampled_equations(&sol, &t, &[], arr).expect("sampled");
            for e in 0..14 {
                let exact: Vec<f64> = am[e].iter().flatten().chain(&bm[e]).copied().collect();
                let sampled: Vec<f64> = sam[e].iter().flatten().chain(&sbm[e]).copied().collect();
                let big = exact.iter().fold(1e-300_f64, |m, x| m.max(x.abs()));
                for (i, (x, y)) in exact.iter().zip(&sampled).enumerate() {
                    assert!(
                        (x - y).abs() <= 1e-10 * big,
                        "{name}: equation {e} entry {i}: exact {x} sampled {y} (largest {big})"
                    );
                }
            }
        }
    }
}

/// Every placement of one slide (six 5R1P arms) and of two slides (fifteen 4R2P arms) in the
/// skew chain: each is solved with degree at most 16 (one slide) or 8 (two), and 40 random
/// configurations round-trip (`solve_checked`), or, for two slides three joints apart only,
/// refused as degenerate in every arrangement.
#[test]
fn every_placement_of_one_or_two_slides_round_trips() {
    let base = skew_5r1p();
    let turn = rev(0.12, 0.07, ("-pi/4", -PI / 4.0));
    let slide = |i: usize| {
        let t = [("1/3", 1.0 / 3.0), ("-2/5", -0.4), ("1/5", 0.2)][i % 3];
        pri(t, base[i].a, base[i].alpha)
    };
    let mut sets: Vec<Vec<usize>> = (0..6).map(|i| vec![i]).collect();
    for i in 0..6 {
        for j in i + 1..6 {
            sets.push(vec![i, j]);
        }
    }
    let mut rng = Rng::new(17);
    for set in sets {
        let rows: Vec<Row> = (0..6)
            .map(|i| {
                if set.contains(&i) {
                    slide(i)
                } else if i == 2 {
                    turn
                } else {
                    base[i]
                }
            })
            .collect();
        let name = format!("slides at {set:?}");
        let text = dh_toml(&name, &rows);
        let robot = dqsym::parse_robot(&text, &name, &dqsym::eval_scalar_text).expect("robot");
        let opts = IkOptions {
            free: None,
            method: IkMethod::General,
        };
        let most = if set.len() == 1 { 16 } else { 8 };
        match solve(&robot, &opts) {
            Ok(sol) => {
                let degree = sol.general.as_ref().map_or(0, |g| g.degree);
                assert!(degree > 0 && degree <= most, "{name}: degree {degree}");
                for _ in 0..40 {
                    let q = random_q(&rows, &mut rng);
                    solve_checked(&name, &sol, &rows, &q, most);
                }
                eprintln!("{name}: degree {degree}");
            }
            Err(e) => {
                let apart = set.len() == 2 && set[1] - set[0] == 3;
                assert!(apart, "{name}: {e}");
                assert!(e.to_string().contains("degenerate"), "{name}: {e}");
                eprintln!("{name}: refused (degenerate in every arrangement)");
            }
        }
    }
}

/// Three slides (3R3P, every placement in the skew chain): every reading of the loop that ends
/// with a turn has a slide among joints 1, 2 and another among joints 4, 5 (or two in one of
/// these pairs), where `det M` vanishes identically, so each arm is refused by `--method
/// general` with that reason named: never a panic, never a wrong solution (`dqsym ik` solves
/// them by the 3R3P family, `ik_3r3p.rs`).
#[test]
fn three_slides_are_refused_as_degenerate() {
    let base = skew_5r1p();
    for i in 0..6 {
        for j in i + 1..6 {
            for k in j + 1..6 {
                let rows: Vec<Row> = (0..6)
                    .map(|n| {
                        if [i, j, k].contains(&n) {
                            pri(("1/5", 0.2), base[n].a, base[n].alpha)
                        } else {
                            rev(0.12 + 0.01 * n as f64, base[n].a, base[n].alpha)
                        }
                    })
                    .collect();
                let name = format!("slides at {:?}", [i, j, k]);
                let text = dh_toml(&name, &rows);
                let robot =
                    dqsym::parse_robot(&text, &name, &dqsym::eval_scalar_text).expect("robot");
                let opts = IkOptions {
                    free: None,
                    method: IkMethod::General,
                };
                let err = solve(&robot, &opts).expect_err("refused").to_string();
                assert!(
                    err.contains("degenerate for this geometry in every arrangement"),
                    "{name}: {err}"
                );
            }
        }
    }
}

/// The report of the 5R1P states the slide's basis, the degree the solver computed, and the
/// exact equations in the slide's powers; its LaTeX gives the Möbius map of the sliding hidden
/// joint. The degree printed is the one `sol.general` holds (computed, 16 here).
#[test]
fn report_states_the_slide_basis_and_the_degree() {
    let sol = derive("skew 5R1P", &skew_5r1p(), IkMethod::Auto);
    let degree = sol.general.as_ref().expect("general").degree;
    let plain = dqsym::ik::ik_report(&sol, dqsym::Format::Plain, true).expect("plain");
    assert!(plain.contains("Am linear in (1, d, d^2)(q3)"), "{plain}");
    assert!(
        plain.contains(&format!("degree reached at a generic target: {degree}")),
        "{plain}"
    );
    // Equation 7 is p.p: a slide by d3 w adds d3^2 (w.w) = d3^2, exactly.
    assert!(plain.contains("A7[q3^2] = 1\n"), "{plain}");
    assert!(!plain.contains("not printed"), "{plain}");
    let latex = dqsym::ik::ik_report(&sol, dqsym::Format::Latex, true).expect("latex");
    assert!(latex.contains("d = \\frac{t + x}{1 - t x}"), "{latex}");
    assert!(latex.contains(&format!("\\deg p = {degree}")), "{latex}");
}
