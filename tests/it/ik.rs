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
        "puma560" => &[
            ("a2", 0.4318),
            ("a3", 0.0203),
            ("d3", 0.15005),
            ("d4", 0.4318),
        ],
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
        "six_r" => &[
            ("l1", 0.3),
            ("l2", 0.3),
            ("l3", 0.2),
            ("l4", 0.1),
            ("L", 0.8),
        ],
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
            method: dqsym::ik::IkMethod::Family,
        },
    )
}

/// The plain f64 chain of `file` at its published parameters.
pub(crate) fn chain(file: &str) -> Chain<f64> {
    let r = load(&format!("{ROBOTS}{file}.toml"));
    let env = params(file);
    let mut c = numeric_chain(&r, &env);
    // The end ik solves for is the one fk reports: moved to the tool point, if the file has one.
    if let Some(p) = &r.tool {
        let p = p.clone().map(|x| {
            x.eval(&|n| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))
                .expect("tool point")
        });
        c.tool = &c.tool * &dqsym::DualQuat::translation(&p);
    }
    c
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

/// A derived solver and what checking it needs: the robot, its f64 chain and parameters, and
/// where the free joint sits.
struct Case {
    sol: IkSolution,
    kinds: Vec<JointKind>,
    free_k: Option<usize>,
    env: Vec<(String, f64)>,
    c: Chain<f64>,
}

impl Case {
    fn new(file: &str, free: Option<&str>) -> Case {
        let sol = derive(file, free).unwrap_or_else(|e| panic!("{file}: {e}"));
        let r = load(&format!("{ROBOTS}{file}.toml"));
        let free_k = sol
            .free
            .as_ref()
            .map(|f| r.variables.iter().position(|v| v == f).expect("free"));
        Case {
            sol,
            kinds: r.chain.joints.iter().map(|j| j.kind).collect(),
            free_k,
            env: params(file),
            c: chain(file),
        }
    }

    /// The parameters' values, the free joint's taken from `q`.
    fn params(&self, q: &[f64]) -> Vec<(&str, f64)> {
        let mut p: Vec<(&str, f64)> = self.env.iter().map(|(k, v)| (k.as_str(), *v)).collect();
        if let (Some(k), Some(f)) = (self.free_k, &self.sol.free) {
            p.push((f.as_str(), q[k]));
        }
        p
    }

    /// The engine's solutions for the pose of `q`.
    fn solve(&self, q: &[f64]) -> Vec<NumSolution> {
        self.sol
            .solve_numeric(&pose(&self.c, q), &self.params(q))
            .expect("params")
    }

    /// Checks solutions (the free joint excluded) for the pose of `q`: each is finite and
    /// reproduces the pose to 1e-9. True when `q` is among them (mod 2 pi).
    fn check(&self, what: &str, q: &[f64], sols: &[Vec<f64>]) -> bool {
        let t = pose(&self.c, q);
        let mut found = false;
        for s in sols {
            let mut qq = s.clone();
            if let Some(k) = self.free_k {
                qq.insert(k, q[k]);
            }
            assert_eq!(qq.len(), q.len(), "{what}: joint count");
            assert!(qq.iter().all(|x| x.is_finite()), "{what}: NaN in {qq:?}");
            let dev = max_dev(&t, &pose(&self.c, &qq), self.sol.position_only);
            assert!(
                dev < 1e-9,
                "{what}: solution {qq:?} misses the pose of {q:?} by {dev:e}"
            );
            found |= qq
                .iter()
                .zip(q)
                .zip(&self.kinds)
                .all(|((a, b), k)| match k {
                    JointKind::Revolute => angle_diff(*a, *b) < 1e-6,
                    JointKind::Prismatic => (a - b).abs() < 1e-6,
                });
        }
        found
    }
}

/// FK(q) -> IK at `n` random configurations: every solution reproduces the pose to 1e-9 and q is
/// among them (mod 2 pi).
fn round_trip(file: &str, free: Option<&str>, n: usize, seed: u64) {
    let case = Case::new(file, free);
    let mut rng = Rng::new(seed);
    let mut total = 0;
    for _ in 0..n {
        let q = random_q(&case.c, &mut rng);
        let sols = case.solve(&q);
        assert!(!sols.is_empty(), "{file}: no solution at q = {q:?}");
        let qs: Vec<Vec<f64>> = sols.iter().map(|s| s.q.clone()).collect();
        assert!(
            case.check(file, &q, &qs),
            "{file}: q = {q:?} is not among the {} solutions {qs:?}",
            sols.len()
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

#[test]
fn a_seven_joint_arm_without_free_gets_a_free_joint_chosen_from_its_geometry() {
    // The Panda reduces only with theta7 given; the iiwa already with theta1.
    for (file, want) in [
        ("panda", "theta7"),
        ("franka_panda", "q7"),
        ("kuka_iiwa7", "theta1"),
    ] {
        let sol = derive(file, None).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(sol.free.as_deref(), Some(want), "{file}");
        assert!(
            sol.geometry[0]
                .to_string()
                .contains(&format!("{want} chosen as the free joint")),
            "{file}: {:?}",
            sol.geometry
        );
    }
    round_trip("panda", None, 200, 15);
}

/// The reversed chain (Franka Panda's spherical shoulder) states its steps in the arm's own
/// joint numbers: the joint a step says turns (or alone sets a distance) is the joint it solves.
#[test]
fn reversed_chain_steps_use_the_arms_joint_numbers() {
    let sol = derive("panda", Some("theta7")).expect("derive");
    let mut checked = 0;
    for st in &sol.steps {
        // The numbers are data: a reversed step is marked, and its words are written once.
        assert!(st.method.reversed, "{}", st.method);
        let method = st.method.to_string();
        assert!(method.starts_with("chain reversed: "), "{method}");
        assert!(!method.contains('\''), "primed numbering left: {method}");
        for verb in ["turns", "alone sets"] {
            for (i, _) in method.match_indices(&format!(" {verb} ")) {
                let head = &method[..i];
                if let Some(n) = head.strip_prefix_last("joint ") {
                    assert_eq!(n, (st.joint + 1).to_string(), "{}: {method}", st.variable);
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 3, "{checked} steps named their joint");
}

trait LastPrefix {
    fn strip_prefix_last(&self, p: &str) -> Option<&str>;
}

impl LastPrefix for str {
    /// What follows the last `p` when it ends the text.
    fn strip_prefix_last(&self, p: &str) -> Option<&str> {
        let k = self.rfind(p)?;
        let rest = &self[k + p.len()..];
        rest.chars()
            .all(|c| c.is_ascii_digit())
            .then_some(rest)
            .filter(|r| !r.is_empty())
    }
}

#[test]
fn panda_with_free_theta7_round_trip() {
    // No spherical wrist: axes 1, 2, 3 meet (a spherical shoulder), so with theta7 given the
    // chain read backwards is a Pieper arm.
    round_trip("panda", Some("theta7"), 1000, 13);
    round_trip("franka_panda", Some("q7"), 1000, 14);
}

/// The value of a formula part with the parameters only (`None` when it needs the target or a
/// joint).
fn constant_part(x: &dqsym::Scalar, env: &[(String, f64)]) -> Option<f64> {
    x.eval(&|n| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))
        .ok()
}

/// At `n` configurations on each singular set whose angle is fixed by the parameters (the
/// wrist and elbow branches: the root of `a cos q + b sin q` at its extreme), the solver
/// returns solutions that reproduce the pose, one flagged singular, none NaN.
fn singular_sets(file: &str, free: Option<&str>, n: usize, seed: u64) -> usize {
    let case = Case::new(file, free);
    let r = load(&format!("{ROBOTS}{file}.toml"));
    let mut rng = Rng::new(seed);
    let mut sets = 0;
    for step in &case.sol.steps {
        let dqsym::ik::Formula::Trig { a, b, .. } = &step.formula else {
            continue;
        };
        let (Some(a), Some(b)) = (constant_part(a, &case.env), constant_part(b, &case.env)) else {
            continue;
        };
        sets += 1;
        let k = r
            .variables
            .iter()
            .position(|v| *v == step.variable)
            .expect("joint");
        for _ in 0..n {
            let mut q = random_q(&case.c, &mut rng);
            q[k] = b.atan2(a);
            let sols = case.solve(&q);
            assert!(!sols.is_empty(), "{file} {}: no solution", step.variable);
            assert!(
                sols.iter().any(|s| s.singular),
                "{file}: {} = {} not flagged singular",
                step.variable,
                q[k]
            );
            let qs: Vec<Vec<f64>> = sols.iter().map(|s| s.q.clone()).collect();
            case.check(&format!("{file}: singular {}", step.variable), &q, &qs);
        }
    }
    sets
}

#[test]
fn singular_sets_give_flagged_solutions_that_reproduce_the_pose() {
    // wrist and elbow of the spherical-wrist arms, wrist and elbow of the UR type, the elbow of
    // the planar and SCARA arms.
    for (file, free, want) in [
        ("puma560", None, 2),
        ("irb140", None, 2),
        ("kuka_kr5", None, 2),
        ("puma_like", None, 2),
        ("ur5", None, 2),
        ("ur10", None, 2),
        ("kuka_iiwa7", Some("theta3"), 2),
        ("panda", Some("theta7"), 2),
        ("stanford", None, 1),
        ("scara", None, 1),
        ("rrr", None, 1),
    ] {
        let sets = singular_sets(file, free, 100, 40);
        assert_eq!(sets, want, "{file}: singular sets checked");
    }
}

#[test]
fn robots_outside_the_families_get_the_clear_error() {
    for (file, free, found) in [
        ("six_r", None, "axes 1 and 2 are parallel"),
        (
            "panda",
            Some("theta3"),
            "--free theta3 leaves no supported family; --free theta4 or --free theta6 or \
             --free theta7 does",
        ),
    ] {
        let e = derive(file, free).expect_err(file).to_string();
        assert!(e.contains(found), "{file}: {e}");
        assert!(e.contains("Supported families:"), "{file}: {e}");
    }
    // Inline robots: a spatial RRR, a 6R whose wrist axes 5 and 6 miss each other, a 5R.
    let joint = |t: &str, d: &str, a: &str, al: &str| {
        format!("[[joint]]\ntype = \"revolute\"\ntheta = \"{t}\"\nd = \"{d}\"\na = \"{a}\"\nalpha = \"{al}\"\n")
    };
    let rrr = format!(
        "name = \"spatial RRR\"\nconvention = \"dh\"\n{}{}{}",
        joint("q1", "0", "1", "pi/2"),
        joint("q2", "0", "1", "pi/3"),
        joint("q3", "0", "1", "0")
    );
    let ur_offset = format!(
        "name = \"UR with offset wrist\"\nconvention = \"dh\"\n{}{}{}{}{}{}",
        joint("q1", "d1", "0", "pi/2"),
        joint("q2", "0", "a2", "0"),
        joint("q3", "0", "a3", "0"),
        joint("q4", "d4", "0", "pi/2"),
        joint("q5", "d5", "a5", "-pi/2"),
        joint("q6", "d6", "0", "0")
    );
    let five = format!(
        "name = \"5R\"\nconvention = \"dh\"\n{}{}{}{}{}",
        joint("q1", "0", "0", "pi/2"),
        joint("q2", "0", "1", "0"),
        joint("q3", "0", "1", "0"),
        joint("q4", "0", "0", "pi/2"),
        joint("q5", "1", "0", "0")
    );
    let skew7: String = std::iter::once("name = \"skew 7R\"\nconvention = \"dh\"\n".to_string())
        .chain((1..=7).map(|i| joint(&format!("q{i}"), "1", "1", "pi/3")))
        .collect();
    for (text, found) in [
        (skew7, "no joint given as --free leaves a supported family"),
        (rrr, "axes 1 and 2 are skew"),
        (ur_offset, "axes 5 and 6 are skew unless"),
        (five, "joints: RRRRR (5)"),
    ] {
        let r = dqsym::parse_robot(&text, "inline", &dqsym::eval_scalar_text).expect("robot");
        let family = IkOptions {
            method: dqsym::ik::IkMethod::Family,
            ..IkOptions::default()
        };
        let e = solve(&r, &family).expect_err("unsupported").to_string();
        assert!(e.contains(found), "{e}");
        assert!(e.contains("no closed-form inverse kinematics"), "{e}");
        // Without --method family, six revolute joints (or seven, one of them free) get the
        // general method; the spatial RRR and the 5R stay errors.
        match solve(&r, &IkOptions::default()) {
            Ok(sol) => assert!(sol.general.is_some() && r.variables.len() >= 6, "{text}"),
            Err(e) => assert!(r.variables.len() < 6, "{e}"),
        }
    }
    // A bad --free names the joint variables.
    let e = derive("kuka_iiwa7", Some("theta9"))
        .expect_err("bad free")
        .to_string();
    assert!(e.contains("theta9") && e.contains("theta7"), "{e}");
}

/// The input lines of the generated-code checks: the 16 entries of T, the 8 DQ components, the
/// parameters in the solver's order; and the configurations.
fn codegen_cases(file: &str, free: Option<&str>, n: usize) -> (String, Vec<Vec<f64>>) {
    let sol = derive(file, free).expect("derive");
    let r = load(&format!("{ROBOTS}{file}.toml"));
    let env = params(file);
    let c = chain(file);
    let mut rng = Rng::new(77);
    let mut text = String::new();
    let mut qs = Vec::new();
    for _ in 0..n {
        let q = random_q(&c, &mut rng);
        let t = pose(&c, &q);
        let m = c.forward_matrix(&q).expect("q");
        let dq = dqsym::DualQuat::from_matrix(&m).expect("dq").components();
        let mut v: Vec<f64> = t.iter().flatten().copied().collect();
        v.extend(dq);
        for p in &sol.params {
            let x = match env.iter().find(|(k, _)| k == p) {
                Some((_, x)) => *x,
                None => q[r.variables.iter().position(|v| v == p).expect("free")],
            };
            v.push(x);
        }
        text.push_str(
            &v.iter()
                .map(|x| format!("{x:e}"))
                .collect::<Vec<_>>()
                .join(" "),
        );
        text.push('\n');
        qs.push(q);
    }
    (text, qs)
}

/// Checks a generated solver's output: per case a line `n n_dq`, then n lines of joint values
/// and two flags; every solution reproduces the pose, q is among them, the count is the
/// engine's and the DQ variant's.
fn check_output(file: &str, free: Option<&str>, what: &str, out: &str, qs: &[Vec<f64>]) {
    let case = Case::new(file, free);
    let mut lines = out.lines();
    for q in qs {
        let head: Vec<usize> = lines
            .next()
            .unwrap_or_else(|| panic!("{what}: output ends early"))
            .split_whitespace()
            .map(|x| x.parse().expect("count"))
            .collect();
        let engine = case.solve(q);
        assert_eq!(head[0], engine.len(), "{what}: solution count at {q:?}");
        assert_eq!(head[1], head[0], "{what}: the DQ variant's count");
        let sols: Vec<Vec<f64>> = (0..head[0])
            .map(|_| {
                let v: Vec<f64> = lines
                    .next()
                    .expect("solution line")
                    .split_whitespace()
                    .map(|x| x.parse().expect("number"))
                    .collect();
                v[..case.sol.variables.len()].to_vec()
            })
            .collect();
        assert!(
            case.check(what, q, &sols),
            "{what}: {q:?} not among the solutions"
        );
    }
}

const CODEGEN_ROBOTS: [(&str, Option<&str>); 7] = [
    ("panda", Some("theta7")),
    ("puma560", None),
    ("ur5", None),
    ("stanford", None),
    ("scara", None),
    ("planar2r", None),
    ("kuka_iiwa7", Some("theta3")),
];

#[test]
fn generated_rust_compiles_clean_and_solves() {
    for (file, free) in CODEGEN_ROBOTS {
        let sol = derive(file, free).expect("derive");
        let code = dqsym::ik::ik_rust(&sol).expect("rust");
        let np = sol.params.len();
        let args: String = (0..np).map(|i| format!(", v[{}]", 24 + i)).collect();
        let main = format!(
            "{code}\nfn main() {{\n    use std::io::BufRead;\n    for line in std::io::stdin().lock().lines() {{\n        \
let v: Vec<f64> = line.expect(\"line\").split_whitespace().map(|x| x.parse().expect(\"number\")).collect();\n        \
let mut t = [[0.0; 4]; 4];\n        for (i, x) in v[..16].iter().enumerate() {{\n            t[i / 4][i % 4] = *x;\n        }}\n        \
let mut dq = [0.0; 8];\n        dq.copy_from_slice(&v[16..24]);\n        let s = ik(&t{args});\n        let d = ik_dq(&dq{args});\n        \
println!(\"{{}} {{}}\", s.n, d.n);\n        for i in 0..s.n {{\n            let q: Vec<String> = s.q[i].iter().map(|x| format!(\"{{x:e}}\")).collect();\n            \
println!(\"{{}} {{}} {{}}\", q.join(\" \"), u8::from(s.singular[i]), u8::from(s.approximate[i]));\n        }}\n    }}\n}}\n"
        );
        let dir = crate::tools::temp_dir(&format!("ik-rust-{file}"));
        let src = dir.join("ik.rs");
        let exe = dir.join("ik");
        std::fs::write(&src, main).expect("write");
        crate::tools::compile_rust_clean(&src, &exe, false, &format!("ik solver of {file}"));
        let (input, qs) = codegen_cases(file, free, 50);
        let out = crate::tools::run(std::process::Command::new(&exe), &input, "generated ik");
        check_output(file, free, &format!("Rust {file}"), &out, &qs);
    }
}

#[test]
fn generated_c_compiles_clean_and_solves() {
    for (file, free) in CODEGEN_ROBOTS {
        let sol = derive(file, free).expect("derive");
        let code = dqsym::ik::ik_c(&sol).expect("c");
        let np = sol.params.len();
        let args: String = (0..np).map(|i| format!(", v[{}]", 24 + i)).collect();
        let main = format!(
            "{code}\n#include <stdio.h>\nint main(void) {{\n    double v[64];\n    for (;;) {{\n        \
for (int i = 0; i < 24 + {np}; i++) if (scanf(\"%lf\", &v[i]) != 1) return 0;\n        \
double T[4][4];\n        for (int i = 0; i < 16; i++) T[i / 4][i % 4] = v[i];\n        \
ik_solutions s, d;\n        ik(T{args}, &s);\n        ik_dq(v + 16{args}, &d);\n        printf(\"%d %d\\n\", s.n, d.n);\n        \
for (int i = 0; i < s.n; i++) {{\n            for (int j = 0; j < IK_DOF; j++) printf(\"%.17e \", s.q[i][j]);\n            \
printf(\"%d %d\\n\", s.singular[i], s.approximate[i]);\n        }}\n    }}\n}}\n"
        );
        let dir = crate::tools::temp_dir(&format!("ik-c-{file}"));
        let src = dir.join("ik.c");
        let exe = dir.join("ik");
        std::fs::write(&src, main).expect("write");
        let mut gcc = std::process::Command::new("gcc");
        gcc.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "-o"])
            .arg(&exe)
            .arg(&src)
            .arg("-lm");
        crate::tools::run(gcc, "", &format!("gcc -Werror on the ik solver of {file}"));
        let (input, qs) = codegen_cases(file, free, 50);
        let out = crate::tools::run(std::process::Command::new(&exe), &input, "generated C ik");
        check_output(file, free, &format!("C {file}"), &out, &qs);
    }
}

#[test]
fn generated_python_runs_and_solves() {
    for (file, free) in CODEGEN_ROBOTS {
        let sol = derive(file, free).expect("derive");
        let code = dqsym::ik::ik_python(&sol).expect("python");
        let names: Vec<String> = sol.params.iter().map(|p| format!("'{p}'")).collect();
        let script = format!(
            "{code}\n\nimport sys\nNAMES = [{}]\nfor line in sys.stdin:\n    v = [float(x) for x in line.split()]\n    \
T = np.array(v[:16]).reshape(4, 4)\n    params = dict(zip(NAMES, v[24:]))\n    sols = ik_full(T, **params)\n    \
plain = ik(T, **params)\n    assert [list(q) for q, _, _, _ in sols] == plain\n    d = ik_dq(v[16:24], **params)\n    \
print(len(sols), len(d))\n    for q, sg, ap, _ in sols:\n        assert all(isinstance(x, float) for x in q)\n        \
print(' '.join(repr(x) for x in q), int(sg), int(ap))\n",
            names.join(", ")
        );
        let (input, qs) = codegen_cases(file, free, 50);
        let out = crate::tools::run_python(&script, &input, "numpy");
        check_output(file, free, &format!("Python {file}"), &out, &qs);
    }
}

#[test]
fn sympy_lines_parse_and_agree_with_the_engine() {
    for (file, free) in [("puma560", None), ("ur5", None), ("stanford", None)] {
        let sol = derive(file, free).expect("derive");
        let text = dqsym::ik::ik_report(&sol, dqsym::Format::Sympy, true).expect("sympy");
        let vars: Vec<String> = sol.variables.iter().map(|v| format!("'{v}'")).collect();
        let names: Vec<String> = sol.params.iter().map(|p| format!("'{p}'")).collect();
        // Evaluates the lines in order; a joint line with sign_q branches on +1, -1; complex
        // values (negative radicands) end the branch.
        let script = format!(
            r#"
import sys, re
from sympy import sympify, Symbol, atan2, sqrt, cos, sin, pi, N, im
lines = [l for l in sys.stdin.read().split('\n') if l and not l.startswith('#')]
VARS = [{vars}]
NAMES = [{names}]
TARGET = ['r11','r12','r13','px','r21','r22','r23','py','r31','r32','r33','pz']
parsed = []
for l in lines:
    name, expr = l.split(' = ', 1)
    syms = set(re.findall(r'[A-Za-z_][A-Za-z_0-9]*', expr)) - {{'atan2','sqrt','cos','sin','pi'}}
    parsed.append((name, sympify(expr, locals={{s: Symbol(s) for s in syms}})))
def run(i, env, out):
    if i == len(parsed):
        out.append([env[v] for v in VARS]); return
    name, e = parsed[i]
    signs = [1, -1] if ('sign_' + name) in [str(s) for s in e.free_symbols] else [None]
    for s in signs:
        env2 = dict(env)
        if s is not None:
            env2['sign_' + name] = s
        v = complex(N(e.subs({{Symbol(k): x for k, x in env2.items()}}), 30))
        if abs(v.imag) > 1e-12:
            continue
        env2[name] = v.real
        run(i + 1, env2, out)
for line in open(sys.argv[1]).read().split('\n'):
    if not line: continue
    v = [float(x) for x in line.split()]
    env = dict(zip(TARGET, [v[i] for i in (0,1,2,3,4,5,6,7,8,9,10,11)]))
    env.update(dict(zip(NAMES, v[24:])))
    out = []
    run(0, env, out)
    print(len(out), len(out))
    for q in out:
        print(' '.join(repr(x) for x in q), 0, 0)
"#,
            vars = vars.join(", "),
            names = names.join(", ")
        );
        let (input, qs) = codegen_cases(file, free, 4);
        let dir = crate::tools::temp_dir(&format!("ik-sympy-{file}"));
        let cases = dir.join("cases.txt");
        std::fs::write(&cases, &input).expect("write");
        let py = crate::tools::python();
        let mut cmd = std::process::Command::new(&py);
        cmd.args(["-c", &script]).arg(&cases);
        let out = crate::tools::run(cmd, &text, "the SymPy lines of ik");
        check_output(file, free, &format!("SymPy {file}"), &out, &qs);
    }
}

#[test]
fn ik_command_prints_the_derivation_and_fails_clearly() {
    let out = crate::tools::dqsym_ok(&["ik", &format!("{ROBOTS}puma560.toml")]);
    assert!(
        out.contains("branches: 8 (shoulder x elbow x wrist)"),
        "{out}"
    );
    assert!(
        out.contains("c = 1/2 (a2^2 + a3^2 + d3^2 + d4^2 - px^2 - py^2 - pz^2)"),
        "{out}"
    );
    let out = crate::tools::dqsym_ok(&["ik", &format!("{ROBOTS}ur5.toml")]);
    assert!(out.contains("branches: 8"), "{out}");
    let out = crate::tools::dqsym_ok(&[
        "ik",
        &format!("{ROBOTS}kuka_iiwa7.toml"),
        "--free",
        "theta3",
    ]);
    assert!(out.contains("free joint (a parameter): theta3"), "{out}");
    // LaTeX: every aligned block renders in KaTeX.
    let tex =
        crate::tools::dqsym_ok(&["ik", &format!("{ROBOTS}puma560.toml"), "--format", "latex"]);
    let blocks: Vec<String> = tex
        .split("\\begin{aligned}")
        .skip(1)
        .map(|b| {
            format!(
                "\\begin{{aligned}}{}",
                b.split("\\end{aligned}").next().unwrap_or("")
            ) + "\\end{aligned}"
        })
        .collect();
    assert_eq!(blocks.len(), 6);
    crate::tools::katex_all(&blocks, "ik --format latex");
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["ik", &format!("{ROBOTS}six_r.toml")])
        .output()
        .expect("run");
    assert_eq!(bad.status.code(), Some(1));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("no closed-form inverse kinematics"), "{err}");
    // Three parallel axes and a spherical wrist: the general method's elimination is
    // degenerate in every arrangement, and the error says so.
    assert!(err.contains("degenerate for this geometry"), "{err}");
    // The PUMA forced through the general method prints the elimination and its degree.
    let general = std::process::Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args([
            "ik",
            &format!("{ROBOTS}puma560.toml"),
            "--method",
            "general",
        ])
        .output()
        .expect("run");
    assert_eq!(general.status.code(), Some(0));
    let out = String::from_utf8_lossy(&general.stdout);
    assert!(
        out.contains("general 6R") && out.contains("det M(x) = 0"),
        "{out}"
    );
}

#[test]
fn generated_bench_solvers_are_current() {
    for file in ["puma560", "ur5"] {
        let path = format!(
            "{}/benches/generated/ik_{file}.rs",
            env!("CARGO_MANIFEST_DIR")
        );
        let want = dqsym::ik::ik_rust(&derive(file, None).expect("derive")).expect("rust");
        if std::env::var_os("DQSYM_BLESS").is_some() {
            std::fs::write(&path, &want).expect("write the bench solver");
        }
        let have = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            have == want,
            "{path} is out of date: rerun with DQSYM_BLESS=1 to rewrite it"
        );
    }
}

#[test]
fn walk_ik_shows_every_step_and_a_check() {
    let out = crate::tools::dqsym_ok(&["walk", &format!("{ROBOTS}puma560.toml"), "--ik"]);
    assert!(out.contains("The joint axes as Plücker lines"), "{out}");
    assert_eq!(out.matches("Step ").count(), 6, "{out}");
    assert!(out.contains("Branch wrist: + is no flip"), "{out}");
    assert!(
        out.contains("The solver returns 8 distinct solutions"),
        "{out}"
    );
    assert_eq!(
        out.matches("pose deviation below 1e-12").count(),
        8,
        "{out}"
    );
    let md = crate::tools::dqsym_ok(&[
        "walk",
        &format!("{ROBOTS}kuka_iiwa7.toml"),
        "--ik",
        "--free",
        "theta3",
        "--markdown",
    ]);
    assert!(md.contains("## 3. The subproblems"), "{md}");
    assert!(
        md.contains("$\\theta_{4}$") || md.contains("\\theta_{4}"),
        "{md}"
    );
    let formulas: Vec<String> = md
        .split('$')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect();
    assert!(!formulas.is_empty());
    crate::tools::katex_all(&formulas, "walk --ik --markdown");
}

/// The roots of one revolute row `(q, a, b, c, n)` of the language's `ik(...)`, as `:help ik`
/// states them: `a cos q + b sin q = c`, n = 2: both roots; n = 1: `atan2(-a, b)`.
fn row_roots(a: f64, b: f64, c: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![(-a).atan2(b)];
    }
    let rad = a * a + b * b - c * c;
    if rad < -1e-9 {
        return vec![];
    }
    let (phi, w) = (b.atan2(a), rad.max(0.0).sqrt().atan2(c));
    vec![phi + w, phi - w]
}

#[test]
fn the_ik_builtin_gives_equations_whose_roots_reproduce_the_pose() {
    // An elbow manipulator with a spherical wrist, and a 7R with a spherical shoulder whose
    // free joint is chosen, built in the language; the rows' roots are taken as `:help ik`
    // says and fed back through the chain's own matrix.
    let cases = [
        (
            "syms t1 t2 t3 t4 t5 t6 a2 d4 d6\nq = dh(t1, 0, 0, pi/2) * dh(t2, 0, a2, 0) * \
             dh(t3, 0, 0, pi/2) * dh(t4, d4, 0, -pi/2) * dh(t5, 0, 0, pi/2) * dh(t6, d6, 0, 0)\n\
             sol = ik(q, [t1, t2, t3, t4, t5, t6])\nM = matrix(q)",
            6,
            vec![("a2", 0.43), ("d4", 0.41), ("d6", 0.09)],
        ),
        (
            "syms t1 t2 t3 t4 t5 t6 t7 d1 d3 a3 d5 a6\nq = mdh(0, 0, t1, d1) * mdh(-pi/2, 0, t2, 0) \
             * mdh(pi/2, 0, t3, d3) * mdh(pi/2, a3, t4, 0) * mdh(-pi/2, -a3, t5, d5) * \
             mdh(pi/2, 0, t6, 0) * mdh(pi/2, a6, t7, 0)\nsol = ik(q, [t1, t2, t3, t4, t5, t6, t7])\n\
             M = matrix(q)",
            7,
            vec![("d1", 0.333), ("d3", 0.316), ("a3", 0.0825), ("d5", 0.384), ("a6", 0.088)],
        ),
    ];
    for (src, n, params) in cases {
        let program = dqsym::parse(src).expect("parse");
        let mut session = dqsym::Session::new();
        session.run(&program).expect("run");
        let rows = match session.get("sol") {
            Some(dqsym::Value::Matrix(rows)) => rows.clone(),
            other => panic!("ik gave {other:?}"),
        };
        let Some(dqsym::Value::Matrix(m)) = session.get("M").cloned() else {
            panic!("matrix");
        };
        assert_eq!(rows.len(), 6, "{src}");
        let names: Vec<String> = (1..=n).map(|i| format!("t{i}")).collect();
        let mut rng = Rng::new(91);
        for _ in 0..50 {
            let q: Vec<f64> = (0..n).map(|_| rng.range(-3.1, 3.1)).collect();
            let mut env: Vec<(String, f64)> =
                params.iter().map(|(k, v)| (k.to_string(), *v)).collect();
            env.extend(names.iter().cloned().zip(q.iter().copied()));
            let ev = |x: &dqsym::Scalar, env: &[(String, f64)]| {
                x.eval(&|s| env.iter().rev().find(|(k, _)| k == s).map(|(_, v)| *v))
                    .expect("value")
            };
            let t: Vec<Vec<f64>> = m
                .iter()
                .map(|r| r.iter().map(|x| ev(x, &env)).collect())
                .collect();
            // The target, the parameters and (for the free joint) q's own value; the solved joints
            // are pushed over q's.
            let mut base: Vec<(String, f64)> =
                params.iter().map(|(k, v)| (k.to_string(), *v)).collect();
            for (r, row) in dqsym::ik::TARGET_SYMBOLS.iter().enumerate() {
                for (c, s) in row.iter().enumerate() {
                    base.push((s.to_string(), t[r][c]));
                }
            }
            let solved: Vec<String> = rows.iter().map(|r| ev_name(&r[0])).collect();
            for (name, v) in names.iter().zip(&q) {
                if !solved.contains(name) {
                    base.push((name.clone(), *v));
                }
            }
            let mut sols = Vec::new();
            solve_rows(&rows, 0, &mut base, &ev, &mut sols);
            assert!(!sols.is_empty(), "no solution at {q:?}");
            let mut found = false;
            for s in &sols {
                let full: Vec<(String, f64)> = params
                    .iter()
                    .map(|(k, v)| (k.to_string(), *v))
                    .chain(s.iter().cloned())
                    .collect();
                let back: Vec<Vec<f64>> = m
                    .iter()
                    .map(|r| r.iter().map(|x| ev(x, &full)).collect())
                    .collect();
                let dev = (0..3)
                    .flat_map(|r| (0..4).map(move |c| (r, c)))
                    .map(|(r, c)| (back[r][c] - t[r][c]).abs())
                    .fold(0.0, f64::max);
                assert!(dev < 1e-9, "{s:?} misses the pose of {q:?} by {dev:e}");
                found |= names.iter().zip(&q).all(|(nm, v)| {
                    let got = s.iter().rev().find(|(k, _)| k == nm).expect("joint").1;
                    angle_diff(got, *v) < 1e-6
                });
            }
            assert!(found, "{q:?} not among {sols:?}");
        }
    }
}

fn ev_name(x: &dqsym::Scalar) -> String {
    x.symbols()[0].name().to_string()
}

type Env = Vec<(String, f64)>;

/// A scalar's value in an environment.
type EvalAt = dyn Fn(&dqsym::Scalar, &[(String, f64)]) -> f64;

fn solve_rows(
    rows: &[Vec<dqsym::Scalar>],
    k: usize,
    env: &mut Env,
    ev: &EvalAt,
    out: &mut Vec<Env>,
) {
    let Some(row) = rows.get(k) else {
        out.push(env.clone());
        return;
    };
    let (a, b, c) = (ev(&row[1], env), ev(&row[2], env), ev(&row[3], env));
    let n = ev(&row[4], env) as usize;
    for v in row_roots(a, b, c, n) {
        env.push((ev_name(&row[0]), v));
        solve_rows(rows, k + 1, env, ev, out);
        env.pop();
    }
}

/// The shoulder singular sets: where a `shoulder` step's two roots merge. At the true
/// configuration the step's equation `a cos q + b sin q = c` holds, and `b cos q − a sin q` is
/// ± the square root of its radicand, with the branch's sign; it changes sign across the set.
/// Configurations on the set are found by scanning another joint for a sign change and bisecting;
/// there the solver flags a singular solution, every solution reproduces the pose and q is among
/// them. `dqsym ik` states the condition.
#[test]
fn shoulder_singular_sets_merge_the_branches_and_are_stated() {
    for (file, free) in [
        ("puma560", None),
        ("irb140", None),
        ("kuka_kr5", None),
        ("ur5", None),
        ("stanford", None),
        ("kuka_iiwa7", Some("theta3")),
        ("panda", Some("theta7")),
    ] {
        let case = Case::new(file, free);
        let r = load(&format!("{ROBOTS}{file}.toml"));
        let (_, step) = case
            .sol
            .steps
            .iter()
            .enumerate()
            .find(|(_, s)| {
                s.branch
                    .is_some_and(|b| b.part == dqsym::ik::BranchPart::Shoulder)
            })
            .unwrap_or_else(|| panic!("{file}: no shoulder step"));
        let singular = step.singular.to_string();
        assert!(
            singular.contains("left and right merge") || singular.contains("shoulder singularity"),
            "{file}: {singular}"
        );
        let k = r
            .variables
            .iter()
            .position(|v| *v == step.variable)
            .expect("joint");
        let dqsym::ik::Formula::Trig { a: sa, b: sb, .. } = &step.formula else {
            panic!("{file}: the shoulder step is not a Trig form");
        };
        // The value of a formula part at configuration q (target, parameters, joints).
        let at = |x: &dqsym::Scalar, q: &[f64]| -> f64 {
            let t = pose(&case.c, q);
            let mut env: Vec<(String, f64)> = case.env.clone();
            for (rr, row) in dqsym::ik::TARGET_SYMBOLS.iter().enumerate() {
                for (cc, s) in row.iter().enumerate() {
                    env.push((s.to_string(), t[rr][cc]));
                }
            }
            env.extend(r.variables.iter().cloned().zip(q.iter().copied()));
            x.eval(&|n| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))
                .unwrap_or(f64::NAN)
        };
        // b cos q - a sin q at configuration q.
        let signed = |q: &[f64]| -> f64 {
            let (a, b) = (at(sa, q), at(sb, q));
            b * q[k].cos() - a * q[k].sin()
        };
        // Some joint turns freely at q (its step's arguments vanish): the solver returns
        // representatives of the family, not q's own value.
        let free_at = |q: &[f64]| {
            case.sol.steps.iter().any(|s| match &s.formula {
                dqsym::ik::Formula::Atan2 { y, x } => at(y, q).hypot(at(x, q)) < 1e-9,
                dqsym::ik::Formula::Trig { a, b, .. } => at(a, q).hypot(at(b, q)) < 1e-9,
                _ => false,
            })
        };
        let mut rng = Rng::new(57);
        let mut hits = 0;
        let mut tries = 0;
        while hits < 100 {
            tries += 1;
            assert!(tries < 2000, "{file}: the shoulder set was not met");
            let mut q = random_q(&case.c, &mut rng);
            let j = (k + tries) % q.len();
            if Some(j) == case.free_k {
                continue;
            }
            let f = |x: f64, q: &mut Vec<f64>| {
                q[j] = x;
                signed(q)
            };
            let grid: Vec<f64> = (0..=25).map(|i| -3.1 + 6.2 * f64::from(i) / 25.0).collect();
            let Some(w) = grid.windows(2).find(|w| {
                let (fa, fb) = (f(w[0], &mut q), f(w[1], &mut q));
                fa.is_finite() && fb.is_finite() && fa * fb < 0.0
            }) else {
                continue;
            };
            let (mut lo, mut hi) = (w[0], w[1]);
            let flo = f(lo, &mut q);
            for _ in 0..56 {
                let mid = 0.5 * (lo + hi);
                if f(mid, &mut q) * flo > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            q[j] = 0.5 * (lo + hi);
            let sols = case.solve(&q);
            assert!(
                !sols.is_empty(),
                "{file}: no solution on the shoulder set at {q:?}"
            );
            assert!(
                sols.iter().any(|s| s.singular),
                "{file}: {q:?} on the shoulder set not flagged singular"
            );
            let qs: Vec<Vec<f64>> = sols.iter().map(|s| s.q.clone()).collect();
            let found = case.check(&format!("{file} shoulder set"), &q, &qs);
            // With a zero shoulder offset the set is the wrist centre on axis 1, where joint 1
            // turns freely; on the Panda's (axes 1 and 3 in line) only theta1 + theta3 is fixed.
            assert!(found || free_at(&q), "{file}: {q:?} not among {qs:?}");
            hits += 1;
        }
    }
}

/// `walk --ik --html`: the page renders every formula with KaTeX in headless Chromium, and its
/// solver, run by the page on the sliders' pose, lists solutions whose own poses (computed by
/// the page) match the target.
#[test]
fn walk_ik_html_page_solves_in_the_browser() {
    let root = env!("CARGO_MANIFEST_DIR");
    let artifacts = std::path::Path::new(root).join("artifacts");
    std::fs::create_dir_all(&artifacts).expect("artifacts dir");
    // puma_like has a tool point: the page solves for it, as fk reports it.
    for (file, free) in [
        ("puma560", None),
        ("ur5", None),
        ("panda", Some("theta7")),
        ("puma_like", None),
    ] {
        let page = artifacts.join(format!("walk_ik_{file}.html"));
        let mut args = vec![
            "walk".to_string(),
            format!("{ROBOTS}{file}.toml"),
            "--ik".into(),
            "--html".into(),
            page.display().to_string(),
        ];
        if let Some(f) = free {
            args.extend(["--free".to_string(), f.to_string()]);
        }
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        crate::tools::dqsym_ok(&refs);
        let html = std::fs::read_to_string(&page).expect("page");
        assert!(html.contains("function dqsym_ik_step0("), "{file}");
        let d = crate::tools::headless(&artifacts.join(format!("ik-{file}")))
            .args(["--virtual-time-budget=5000", "--dump-dom"])
            .arg(format!("file://{}", page.display()))
            .output()
            .expect("chromium runs");
        assert!(d.status.success(), "{}", String::from_utf8_lossy(&d.stderr));
        let dom = String::from_utf8_lossy(&d.stdout);
        let formulas = html.matches("data-tex=").count();
        let rendered = dom.matches("class=\"katex\"").count();
        assert!(
            rendered >= formulas && formulas > 20,
            "{file}: {rendered} of {formulas} rendered"
        );
        assert!(
            !dom.contains("class=\"katex-error\""),
            "{file}: a formula failed in KaTeX"
        );
        let count: usize = dom
            .split("data-count=\"")
            .nth(1)
            .and_then(|s| s.split('"').next())
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("{file}: the page's solver did not run"));
        assert!(count >= 1, "{file}: no solution on the page");
        let devs: Vec<f64> = dom
            .split("data-dev=\"")
            .skip(1)
            // The page's own script holds the template `data-dev="${dev}"`.
            .filter_map(|s| s.split('"').next().unwrap_or("").parse().ok())
            .collect();
        assert_eq!(devs.len(), count, "{file}: one row per solution");
        for d in devs {
            assert!(d < 1e-9, "{file}: a solution on the page misses by {d:e}");
        }
    }
}
