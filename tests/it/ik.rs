//! Closed-form inverse kinematics: for every supported example robot, FK(q) -> IK at random
//! configurations reproduces the pose with every solution and finds q among them; the singular
//! sets give flagged solutions, never NaN; robots outside the families get the clear error.

use crate::common::Rng;
use crate::robots::{load, numeric_chain};
use dqsym::ik::{solve, IkError, IkOptions, IkSolution, NumSolution};
use dqsym::{Chain, JointKind};

const ROBOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/");

/// Published values of each example robot's parameters (m).
pub(crate) fn params(file: &str) -> Vec<(String, f64)> {
    let v: &[(&str, f64)] = match file {
        "puma560" => &[("a2", 0.4318), ("a3", 0.0203), ("d3", 0.15005), ("d4", 0.4318)],
        "puma_like" => &[
            ("l1", 0.3),
            ("l2", 0.4),
            ("d", 0.1),
            ("L", 0.9),
            ("b", 0.15),
        ],
        "ur5" => &[
            ("d1", 0.089159),
            ("a2", -0.425),
            ("a3", -0.39225),
            ("d4", 0.10915),
            ("d5", 0.09465),
            ("d6", 0.0823),
        ],
        "stanford" => &[("d2", 0.154), ("d6", 0.263)],
        "scara" => &[("a1", 0.4), ("a2", 0.3), ("d4", 0.1)],
        "rrr" => &[("l1", 0.5), ("l2", 0.4), ("l3", 0.2)],
        "planar2r" => &[("l1", 0.5), ("l2", 0.35)],
        "irb140" => &[
            ("d1", 0.352),
            ("a1", 0.07),
            ("a2", 0.36),
            ("d4", 0.38),
            ("d6", 0.065),
        ],
        "kuka_kr5" => &[
            ("d1", 0.4),
            ("a1", 0.18),
            ("a2", 0.6),
            ("a3", 0.12),
            ("d4", -0.62),
            ("d6", -0.115),
        ],
        "kuka_iiwa7" => &[("d1", 0.34), ("d3", 0.4), ("d5", 0.4), ("d7", 0.126)],
        "panda" => &[
            ("d1", 0.333),
            ("d3", 0.316),
            ("a3", 0.0825),
            ("a4", -0.0825),
            ("d5", 0.384),
            ("a6", 0.088),
            ("dF", 0.107),
        ],
        "six_r" => &[("l1", 0.3), ("l2", 0.3), ("l3", 0.2), ("l4", 0.1), ("L", 0.8)],
        _ => &[],
    };
    v.iter().map(|(n, x)| (n.to_string(), *x)).collect()
}

pub(crate) fn derive(file: &str, free: Option<&str>) -> Result<IkSolution, IkError> {
    let r = load(&format!("{ROBOTS}{file}.toml"));
    solve(
        &r,
        &IkOptions {
            free: free.map(str::to_string),
        },
    )
}

/// The plain f64 chain of `file` at its published parameters.
pub(crate) fn chain(file: &str) -> Chain<f64> {
    let r = load(&format!("{ROBOTS}{file}.toml"));
    numeric_chain(&r, &params(file))
}

/// The pose of the chain at `q` (all joints, the free one included).
pub(crate) fn pose(c: &Chain<f64>, q: &[f64]) -> [[f64; 4]; 4] {
    c.forward_matrix(q).expect("joints").rows
}

fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

fn max_dev(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4], position_only: bool) -> f64 {
    let mut m: f64 = 0.0;
    for r in 0..3 {
        for c in 0..4 {
            if position_only && c < 3 {
                continue;
            }
            m = m.max((a[r][c] - b[r][c]).abs());
        }
    }
    m
}

/// A random configuration: angles in (-pi, pi), slides in (0.1, 0.6).
pub(crate) fn random_q(c: &Chain<f64>, rng: &mut Rng) -> Vec<f64> {
    c.joints
        .iter()
        .map(|j| match j.kind {
            JointKind::Revolute => rng.range(-3.1, 3.1),
            JointKind::Prismatic => rng.range(0.1, 0.6),
        })
        .collect()
}

/// Inserts the free joint's value back into a solution.
fn full_q(sol: &IkSolution, s: &NumSolution, free_val: Option<(usize, f64)>) -> Vec<f64> {
    let mut q = s.q.clone();
    if let Some((k, v)) = free_val {
        q.insert(k, v);
    }
    assert_eq!(q.len(), sol.variables.len() + usize::from(free_val.is_some()));
    q
}

/// FK(q) -> IK at `n` random configurations: every solution reproduces the pose to 1e-9 and q is
/// among them (mod 2 pi).
fn round_trip(file: &str, free: Option<&str>, n: usize, seed: u64) {
    let sol = derive(file, free).unwrap_or_else(|e| panic!("{file}: {e}"));
    let r = load(&format!("{ROBOTS}{file}.toml"));
    let free_k = free.map(|f| r.variables.iter().position(|v| v == f).expect("free"));
    let env = params(file);
    let c = chain(file);
    let mut rng = Rng::new(seed);
    let mut total = 0;
    for _ in 0..n {
        let q = random_q(&c, &mut rng);
        let t = pose(&c, &q);
        let mut p: Vec<(&str, f64)> = env.iter().map(|(k, v)| (k.as_str(), *v)).collect();
        if let Some(k) = free_k {
            p.push((free.expect("free"), q[k]));
        }
        let sols = sol.solve_numeric(&t, &p).expect("params");
        assert!(!sols.is_empty(), "{file}: no solution at q = {q:?}");
        let mut found = false;
        for s in &sols {
            assert!(s.q.iter().all(|x| x.is_finite()), "{file}: NaN at {q:?}");
            let qq = full_q(&sol, s, free_k.map(|k| (k, q[k])));
            let back = pose(&c, &qq);
            let dev = max_dev(&t, &back, sol.position_only);
            assert!(
                dev < 1e-9,
                "{file}: solution {qq:?} misses the pose of {q:?} by {dev:e}"
            );
            let same = qq.iter().zip(&q).enumerate().all(|(i, (a, b))| {
                match r.chain.joints[i].kind {
                    JointKind::Revolute => angle_diff(*a, *b) < 1e-6,
                    JointKind::Prismatic => (a - b).abs() < 1e-6,
                }
            });
            found |= same;
        }
        assert!(
            found,
            "{file}: q = {q:?} is not among the {} solutions {:?}",
            sols.len(),
            sols.iter().map(|s| &s.q).collect::<Vec<_>>()
        );
        total += sols.len();
    }
    assert!(total >= n);
}

#[test]
fn puma560_round_trip() {
    round_trip("puma560", None, 1000, 1);
}

#[test]
fn puma_like_screw_round_trip() {
    round_trip("puma_like", None, 1000, 2);
}

#[test]
fn ur5_round_trip() {
    round_trip("ur5", None, 1000, 3);
}

#[test]
fn ur3_and_ur10_round_trip() {
    round_trip("ur3", None, 1000, 4);
    round_trip("ur10", None, 1000, 5);
}

#[test]
fn stanford_round_trip() {
    round_trip("stanford", None, 1000, 6);
}

#[test]
fn scara_round_trip() {
    round_trip("scara", None, 1000, 7);
}

#[test]
fn planar_round_trips() {
    round_trip("rrr", None, 1000, 8);
    round_trip("planar2r", None, 1000, 9);
}

#[test]
fn irb140_and_kr5_round_trip() {
    round_trip("irb140", None, 1000, 10);
    round_trip("kuka_kr5", None, 1000, 11);
}

#[test]
fn iiwa_with_free_theta3_round_trip() {
    round_trip("kuka_iiwa7", Some("theta3"), 1000, 12);
}
