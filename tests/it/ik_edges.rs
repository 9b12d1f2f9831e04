//! Inverse kinematics at the edges: round trips at random configurations and at configurations
//! 1e-12 .. 1e-3 rad from a wrist, elbow or shoulder singular set (and on it), for every
//! IK-capable example robot, through the reference solver and the generated Rust, C (C99,
//! pedantic) and Python solvers. Every solution not flagged approximate reproduces the pose to
//! 1e-9 (rotation entries, positions over the robot's size) by an independent 4 x 4 model
//! written here, the original configuration is among the solutions (or, at a singular set, a
//! singular solution with its pose), and no row is returned twice.

use crate::common::Rng;
use crate::ik::{derive, params};
use crate::robots::{load, numeric_chain};
use dqsym::ik::{Formula, IkSolution};
use dqsym::kin::JointGeometry;
use dqsym::{Chain, JointKind};
use std::path::Path;

const ROBOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/");

type M4 = [[f64; 4]; 4];

fn mul(a: &M4, b: &M4) -> M4 {
    std::array::from_fn(|r| std::array::from_fn(|c| (0..4).map(|k| a[r][k] * b[k][c]).sum()))
}

fn eye() -> M4 {
    std::array::from_fn(|r| std::array::from_fn(|c| f64::from(u8::from(r == c))))
}

fn rot(axis: usize, t: f64) -> M4 {
    let (s, c) = t.sin_cos();
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut m = eye();
    m[i][i] = c;
    m[j][j] = c;
    m[i][j] = -s;
    m[j][i] = s;
    m
}

fn trans(x: f64, y: f64, z: f64) -> M4 {
    let mut m = eye();
    m[0][3] = x;
    m[1][3] = y;
    m[2][3] = z;
    m
}

/// Rotation by `t` about the unit axis `w` through `p` (Rodrigues), or a slide `t w`.
fn screw(w: [f64; 3], p: [f64; 3], t: f64, prismatic: bool) -> M4 {
    if prismatic {
        return trans(t * w[0], t * w[1], t * w[2]);
    }
    let (s, c) = t.sin_cos();
    let k = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
    let mut m = eye();
    for r in 0..3 {
        for j in 0..3 {
            m[r][j] = if r == j { c } else { 0.0 } + s * k[r][j] + (1.0 - c) * w[r] * w[j];
        }
    }
    for r in 0..3 {
        m[r][3] = p[r] - (0..3).map(|j| m[r][j] * p[j]).sum::<f64>();
    }
    m
}

/// A unit dual quaternion `(w, x, y, z) + eps (w, x, y, z)` as a matrix.
fn dq_matrix(q: [f64; 8]) -> M4 {
    let [w, x, y, z, a, b, c, d] = q;
    let mut m = eye();
    m[0] = [
        w * w + x * x - y * y - z * z,
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        0.0,
    ];
    m[1] = [
        2.0 * (x * y + w * z),
        w * w - x * x + y * y - z * z,
        2.0 * (y * z - w * x),
        0.0,
    ];
    m[2] = [
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        w * w - x * x - y * y + z * z,
        0.0,
    ];
    m[0][3] = 2.0 * (-a * x + b * w - c * z + d * y);
    m[1][3] = 2.0 * (-a * y + b * z + c * w - d * x);
    m[2][3] = 2.0 * (-a * z - b * y + c * x + d * w);
    m
}

/// The independent model: the joints' numeric fields, read back from the parsed robot, put
/// through plain matrix products (DH: Rz Tz Tx Rx; MDH: Rx Tx Rz Tz; screw: Rodrigues), between
/// the base and tool frames read from the robot file's text here (`Frames`).
struct Model {
    chain: Chain<f64>,
    /// The robot's size: the largest distance of a frame origin from the base at home, at
    /// least 1 mm. Position deviations are measured against it.
    size: f64,
    /// The constant frames: `[base]` before the first joint; `[tool]` and the tool point
    /// (`tool = [x, y, z]`) after the last. The end `fk` reports, and `ik` solves for, is
    /// `base · joints · tool`.
    frames: Frames,
}

impl Model {
    fn new(c: Chain<f64>, frames: Frames) -> Model {
        let mut m = Model {
            chain: c,
            size: 1.0,
            frames,
        };
        let n = m.chain.joints.len();
        let n1 = |t: &M4| t[0][3].abs() + t[1][3].abs() + t[2][3].abs();
        let mut size: f64 = 1e-3;
        let mut t = m.frames.base;
        for j in &m.chain.joints {
            t = mul(&t, &link(j, 0.0));
            size = size.max(n1(&t));
            if let JointGeometry::Screw { point, .. } = &j.geometry {
                size = size.max(point.iter().map(|x| x.abs()).sum());
            }
        }
        m.size = size.max(n1(&m.pose(&vec![0.0; n])));
        m
    }

    fn pose(&self, q: &[f64]) -> M4 {
        let mut t = self.frames.base;
        for (j, qi) in self.chain.joints.iter().zip(q) {
            t = mul(&t, &link(j, *qi));
        }
        mul(&t, &self.frames.tool)
    }

    /// The largest deviation: rotation entries as they are, positions over the size.
    fn dev(&self, a: &M4, b: &M4, position_only: bool) -> f64 {
        let mut d: f64 = 0.0;
        for r in 0..3 {
            for c in 0..4 {
                if c == 3 {
                    d = d.max((a[r][3] - b[r][3]).abs() / self.size);
                } else if !position_only {
                    d = d.max((a[r][c] - b[r][c]).abs());
                }
            }
        }
        d
    }
}

fn link(j: &dqsym::Joint<f64>, q: f64) -> M4 {
    let prismatic = j.kind == JointKind::Prismatic;
    let (dq, tq) = if prismatic { (q, 0.0) } else { (0.0, q) };
    match &j.geometry {
        JointGeometry::Dh { theta, d, a, alpha } => {
            let m = mul(&rot(2, theta + tq), &trans(0.0, 0.0, d + dq));
            mul(&mul(&m, &trans(*a, 0.0, 0.0)), &rot(0, *alpha))
        }
        JointGeometry::Mdh { alpha, a, theta, d } => {
            let m = mul(&rot(0, *alpha), &trans(*a, 0.0, 0.0));
            mul(&mul(&m, &rot(2, theta + tq)), &trans(0.0, 0.0, d + dq))
        }
        JointGeometry::Screw { axis, point } => screw(*axis, *point, q, prismatic),
        // A URDF joint as written: Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll) per frame, then the
        // motion about the axis through the frame's origin.
        JointGeometry::Local { frames, axis } => {
            let origin = frames.iter().fold(eye(), |m, (x, r)| {
                let m = mul(&m, &trans(x[0], x[1], x[2]));
                let m = mul(&mul(&m, &rot(2, r[2])), &rot(1, r[1]));
                mul(&m, &rot(0, r[0]))
            });
            mul(&origin, &screw(*axis, [0.0; 3], q, prismatic))
        }
    }
}

/// A robot the tests solve: its solver, model, and where the free joint sits.
struct Arm {
    file: String,
    sol: IkSolution,
    model: Model,
    env: Vec<(String, f64)>,
    free_k: Option<usize>,
    kinds: Vec<JointKind>,
    variables: Vec<String>,
}

impl Arm {
    /// The example robot `file` (examples/robots), with the free joint the solver picks.
    fn new(file: &str) -> Arm {
        Arm::at(&format!("{ROBOTS}{file}.toml"), file, None)
    }

    /// The robot file at `path`, its parameters those `params` gives for `known` (an example
    /// robot's name), with the free joint `free` or the one the solver picks.
    fn at(path: &str, known: &str, free: Option<&str>) -> Arm {
        let r = load(path);
        // The families' solvers (the general method has its own tests, tests/it/ik_general.rs).
        let opts = dqsym::ik::IkOptions {
            free: free.map(str::to_string),
            method: dqsym::ik::IkMethod::Family,
        };
        let sol = dqsym::ik::solve(&r, &opts).unwrap_or_else(|e| panic!("{path}: {e}"));
        let env = params(known);
        let free_k = sol
            .free
            .as_ref()
            .map(|f| r.variables.iter().position(|v| v == f).expect("free"));
        let text = std::fs::read_to_string(path).expect("robot file");
        let chain = numeric_chain(&r, &env);
        let frames = Frames::of(&text, path, &chain, tool_point(&r, &env), &env);
        let name = Path::new(path).file_stem().expect("name").to_string_lossy();
        Arm {
            file: match free {
                Some(f) => format!("{name} (free {f})"),
                None => name.into_owned(),
            },
            sol,
            model: Model::new(chain, frames),
            env,
            free_k,
            kinds: r.chain.joints.iter().map(|j| j.kind).collect(),
            variables: r.variables.clone(),
        }
    }

    fn random_q(&self, rng: &mut Rng) -> Vec<f64> {
        self.kinds
            .iter()
            .map(|k| match k {
                JointKind::Revolute => rng.range(-3.1, 3.1),
                JointKind::Prismatic => rng.range(0.1, 0.6),
            })
            .collect()
    }

    /// The parameters, the free joint's taken from `q`.
    fn params_at(&self, q: &[f64]) -> Vec<(String, f64)> {
        let mut p = self.env.clone();
        if let (Some(k), Some(f)) = (self.free_k, &self.sol.free) {
            p.push((f.clone(), q[k]));
        }
        p
    }

    /// The full joint vector of a solution (the free joint's value from `q`).
    fn full(&self, s: &[f64], q: &[f64]) -> Vec<f64> {
        let mut v = s.to_vec();
        if let Some(k) = self.free_k {
            v.insert(k, q[k]);
        }
        v
    }

    /// Checks the solutions `(q, singular, approximate)` of the pose of `q`, at `dist` rad from
    /// a singular set; true when `q` is among them to the accuracy its pose fixes it, or a
    /// singular exact solution stands for it. Away from the sets that is 1e-6; near one the
    /// joints beside it turn together at a cost of `dist` times their turn in the pose, which
    /// other joints partly absorb: on the elbow sets of the KUKA arms (axes 3 and 5 in line) a
    /// turn of 1.5e-3 at 1e-6 from the set leaves the pose within 4e-16, so the tolerance is
    /// `sqrt(1e-11 / dist)` there.
    fn check(&self, what: &str, q: &[f64], dist: f64, sols: &[(Vec<f64>, bool, bool)]) -> bool {
        let tol = 1e-6 + (1e-11 / dist.max(1e-300)).sqrt();
        let t = self.model.pose(q);
        let mut found = false;
        for (i, (s, sg, ap)) in sols.iter().enumerate() {
            let full = self.full(s, q);
            assert!(
                full.iter().all(|x| x.is_finite()),
                "{what}: NaN in {full:?}"
            );
            for (s2, _, _) in &sols[..i] {
                assert!(s2 != s, "{what}: the row {s:?} twice");
            }
            if *ap {
                continue;
            }
            let dev = self
                .model
                .dev(&t, &self.model.pose(&full), self.sol.position_only);
            assert!(
                dev < 1e-9,
                "{what}: {full:?} (singular {sg}) misses the pose of {q:?} by {dev:e}"
            );
            found |= *sg
                || full
                    .iter()
                    .zip(q)
                    .zip(&self.kinds)
                    .all(|((a, b), k)| match k {
                        JointKind::Revolute => {
                            let d = (a - b).rem_euclid(std::f64::consts::TAU);
                            d.min(std::f64::consts::TAU - d) < tol
                        }
                        JointKind::Prismatic => (a - b).abs() < tol,
                    });
        }
        found
    }

    /// The value of a step's part at configuration `q` (its target, parameters and joints).
    fn part(&self, x: &dqsym::Scalar, q: &[f64]) -> f64 {
        let t = self.model.pose(q);
        let mut env = self.params_at(q);
        for (r, row) in dqsym::ik::TARGET_SYMBOLS.iter().enumerate() {
            for (c, s) in row.iter().enumerate() {
                env.push((s.to_string(), t[r][c]));
            }
        }
        env.extend(self.variables.iter().cloned().zip(q.iter().copied()));
        x.eval(&|n| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))
            .unwrap_or(f64::NAN)
    }

    /// Configurations on the singular sets of the trig steps: where the radicand `a² + b² − c²`
    /// of a step vanishes, found along one joint by bisection on `b cos q − a sin q` (whose
    /// zeros are the double roots), with that joint's index. `None` when the set is not met
    /// along the joints tried.
    fn singular(&self, step: usize, rng: &mut Rng) -> Option<(Vec<f64>, usize)> {
        let st = &self.sol.steps[step];
        let Formula::Trig { a, b, .. } = &st.formula else {
            return None;
        };
        let k = self.variables.iter().position(|v| *v == st.variable)?;
        let signed = |q: &[f64]| {
            let (a, b) = (self.part(a, q), self.part(b, q));
            b * q[k].cos() - a * q[k].sin()
        };
        for attempt in 0..40 {
            let mut q = self.random_q(rng);
            let j = (k + attempt) % q.len();
            if Some(j) == self.free_k || self.kinds[j] == JointKind::Prismatic {
                continue;
            }
            // Off the round angles, where a set may sit exactly on a grid point.
            let grid: Vec<f64> = (0..=24)
                .map(|i| -3.03 + 6.1 * f64::from(i) / 24.0)
                .collect();
            let mut f = |x: f64| {
                q[j] = x;
                signed(&q)
            };
            let Some((lo, hi)) = grid.windows(2).find_map(|w| {
                let (fa, fb) = (f(w[0]), f(w[1]));
                (fa.is_finite() && fb.is_finite() && fa * fb < 0.0).then_some((w[0], w[1]))
            }) else {
                continue;
            };
            let (mut lo, mut hi) = (lo, hi);
            let flo = f(lo);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if f(mid) * flo > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            q[j] = 0.5 * (lo + hi);
            // On the set: the radicand at zero within rounding (a double root, not a miss).
            let Formula::Trig { a, b, c } = &st.formula else {
                return None;
            };
            let (a, b, c) = (self.part(a, &q), self.part(b, &q), self.part(c, &q));
            let n = a * a + b * b;
            if (n - c * c).abs() < 1e-9 * n {
                return Some((q, j));
            }
        }
        None
    }

    /// The reference solver's solutions of the pose of `q`.
    fn solve(&self, q: &[f64]) -> Vec<(Vec<f64>, bool, bool)> {
        let p = self.params_at(q);
        let p: Vec<(&str, f64)> = p.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let sols = self
            .sol
            .solve_numeric(&self.model.pose(q), &p)
            .expect("parameters");
        for s in &sols {
            assert_eq!(
                s.approximate,
                s.residual > dqsym::ik::check::POSE_TOL || s.residual.is_nan(),
                "{}: approximate is the residual above POSE_TOL",
                self.file
            );
        }
        sols.into_iter()
            .map(|s| (s.q, s.singular, s.approximate))
            .collect()
    }
}

/// The configurations of the edge tests: `n` random ones, then per singular set found (trig
/// steps: wrist, elbow, shoulder) configurations on it and at 1e-12 .. 1e-3 rad from it along
/// the joint that meets it, on either side; `(q, distance)`.
fn configurations(arm: &Arm, n: usize, near: usize, seed: u64) -> Vec<(Vec<f64>, f64)> {
    let mut rng = Rng::new(seed);
    let mut out: Vec<(Vec<f64>, f64)> = (0..n).map(|_| (arm.random_q(&mut rng), 1.0)).collect();
    let mut sets: Vec<usize> = (0..arm.sol.steps.len())
        .filter(|&k| matches!(arm.sol.steps[k].formula, Formula::Trig { .. }))
        .collect();
    let mut made = 0;
    let mut turn = 0;
    while made < near && !sets.is_empty() {
        let i = turn % sets.len();
        turn += 1;
        // A set not met along any joint from 40 random configurations is left out.
        let Some((q, j)) = arm.singular(sets[i], &mut rng) else {
            sets.remove(i);
            continue;
        };
        out.push((q.clone(), 0.0));
        for e in 3..=12 {
            for sign in [-1.0, 1.0] {
                let mut p = q.clone();
                p[j] += sign * 10f64.powi(-e);
                out.push((p, 10f64.powi(-e)));
                made += 1;
            }
        }
    }
    assert!(
        made >= near,
        "{}: {made} near-singular configurations",
        arm.file
    );
    out
}

/// A robot file's constant frames as 4 x 4 matrices, read from its text here (not through the
/// robot reader): the `[base]` and `[tool]` tables (`xyz`, `rpy`: `Trans(xyz) Rz(yaw) Ry(pitch)
/// Rx(roll)`), then the tool point. Checked against the frames the reader built.
struct Frames {
    base: M4,
    tool: M4,
}

impl Frames {
    fn of(
        text: &str,
        path: &str,
        chain: &Chain<f64>,
        point: [f64; 3],
        env: &[(String, f64)],
    ) -> Frames {
        let [x, y, z] = point;
        let at_point = trans(x, y, z);
        let mut f = Frames {
            base: eye(),
            tool: eye(),
        };
        let mut table: Option<(bool, [f64; 3], [f64; 3])> = None;
        let close = |t: Option<(bool, [f64; 3], [f64; 3])>, f: &mut Frames| {
            if let Some((base, xyz, rpy)) = t {
                let r = mul(&mul(&rot(2, rpy[2]), &rot(1, rpy[1])), &rot(0, rpy[0]));
                let m = mul(&trans(xyz[0], xyz[1], xyz[2]), &r);
                *if base { &mut f.base } else { &mut f.tool } = m;
            }
        };
        for line in text.lines() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.starts_with('[') {
                close(table.take(), &mut f);
                assert!(
                    !matches!(line, "[[base]]" | "[[tool]]"),
                    "{path}: arrays of frames are not read by this test's model"
                );
                table = match line {
                    "[base]" => Some((true, [0.0; 3], [0.0; 3])),
                    "[tool]" => Some((false, [0.0; 3], [0.0; 3])),
                    _ => None,
                };
                continue;
            }
            let (Some((_, xyz, rpy)), Some((key, value))) = (table.as_mut(), line.split_once('='))
            else {
                continue;
            };
            let entries: Vec<&str> = value
                .trim()
                .trim_start_matches('[')
                .trim_end_matches(']')
                .split(',')
                .map(|e| e.trim().trim_matches('"').trim_matches('\''))
                .collect();
            assert_eq!(entries.len(), 3, "{path}: {line}");
            match key.trim() {
                "xyz" => *xyz = std::array::from_fn(|i| length(entries[i], env)),
                "rpy" => *rpy = std::array::from_fn(|i| angle(entries[i])),
                other => panic!("{path}: frame key {other}"),
            }
        }
        close(table, &mut f);
        f.tool = mul(&f.tool, &at_point);
        // The reader's frames, for comparison: the same matrices to rounding.
        let tool = mul(&dq_matrix(chain.tool.components()), &at_point);
        for (what, mine, theirs) in [
            ("base", &f.base, &dq_matrix(chain.base.components())),
            ("tool", &f.tool, &tool),
        ] {
            let d = (0..3)
                .flat_map(|r| (0..4).map(move |c| (mine[r][c] - theirs[r][c]).abs()))
                .fold(0.0, f64::max);
            assert!(
                d < 1e-12,
                "{path}: the {what} frame read two ways differs by {d:e}"
            );
        }
        f
    }
}

/// A frame's length entry: a number, or a parameter's value.
fn length(e: &str, env: &[(String, f64)]) -> f64 {
    e.parse().unwrap_or_else(|_| {
        env.iter()
            .find(|(k, _)| k == e)
            .unwrap_or_else(|| panic!("length {e}"))
            .1
    })
}

/// A frame's angle entry as the robot-file rules read it: `"90deg"`, `"pi"`, `"-pi/6"`,
/// `"5*pi/12"`, or radians, where a decimal with d >= 3 digits after the point within
/// max(10^-d, 1e-6) of a multiple of pi/12 is that multiple (README, angles as datasheets
/// print them).
fn angle(e: &str) -> f64 {
    use std::f64::consts::PI;
    if let Some(deg) = e.strip_suffix("deg") {
        return deg.trim().parse::<f64>().expect("degrees").to_radians();
    }
    if let Some(i) = e.find("pi") {
        let (k, n) = (&e[..i], &e[i + 2..]);
        let k = match k.trim_end_matches('*') {
            "" => 1.0,
            "-" => -1.0,
            k => k.parse().expect("multiple of pi"),
        };
        let n: f64 = n
            .strip_prefix('/')
            .map_or(1.0, |n| n.parse().expect("pi/n"));
        return k * PI / n;
    }
    let v: f64 = e.parse().expect("angle");
    let digits = e.split_once('.').map_or(0, |(_, f)| f.len());
    if digits >= 3 {
        let tol = 10f64.powi(-(digits as i32)).max(1e-6);
        let step = PI / 12.0;
        let near = (v / step).round() * step;
        if (v - near).abs() <= tol {
            return near;
        }
    }
    v
}

/// The robot's tool point at the parameters `env` (zero when it has none).
fn tool_point(r: &dqsym::Robot, env: &[(String, f64)]) -> [f64; 3] {
    r.tool.as_ref().map_or([0.0; 3], |p| {
        let f = |x: &dqsym::Scalar| {
            x.eval(&|n: &str| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))
                .expect("tool point")
        };
        [f(&p[0]), f(&p[1]), f(&p[2])]
    })
}

/// Every IK-capable example robot (a seven-joint arm with the free joint the solver picks).
fn arms() -> Vec<Arm> {
    let mut files: Vec<String> = std::fs::read_dir(ROBOTS)
        .expect("examples/robots")
        .filter_map(|e| {
            let p = e.expect("entry").path();
            let name = p.file_name()?.to_str()?.strip_suffix(".toml")?.to_string();
            Some(name)
        })
        .collect();
    files.sort();
    let mut arms = Vec::new();
    for f in files {
        match derive(&f, None) {
            Ok(_) => arms.push(Arm::new(&f)),
            Err(dqsym::ik::IkError::Unsupported { .. }) => {}
            Err(e) => panic!("{f}: {e}"),
        }
    }
    for want in ["puma560", "kuka_kr5", "irb140", "ur5", "stanford", "panda"] {
        assert!(arms.iter().any(|a| a.file == want), "{want} is IK-capable");
    }
    arms
}

/// Random and near-singular configurations per robot for the reference solver: 1,000 each for
/// the arms the issue names, 300 for the other example robots (the whole file stays near a
/// minute of CPU in a debug build).
fn edge_cases(file: &str) -> usize {
    if GENERATED.contains(&file) {
        1000
    } else {
        300
    }
}

/// Round trips of the reference solver at `n` random configurations and `n` near its singular
/// sets (none when it has no trig step); a failure's description, if any.
fn round_trips(arm: &Arm, n: usize) -> Option<String> {
    let trig = arm
        .sol
        .steps
        .iter()
        .any(|s| matches!(s.formula, Formula::Trig { .. }));
    let near = if trig { n } else { 0 };
    let mut missing = Vec::new();
    for (q, dist) in configurations(arm, n, near, 7) {
        let sols = arm.solve(&q);
        let what = format!("{} at {dist:e} from a singular set", arm.file);
        if !arm.check(&what, &q, dist, &sols) {
            missing.push((q, dist, sols));
        }
    }
    if missing.is_empty() {
        return None;
    }
    let dists: Vec<f64> = missing.iter().map(|m| m.1).collect();
    Some(format!(
        "{}: {} configurations not among their solutions (at {dists:?}), first {:?}",
        arm.file,
        missing.len(),
        missing.first()
    ))
}

#[test]
fn reference_solver_round_trips_at_random_and_near_singular_configurations() {
    let failures: Vec<String> = arms()
        .iter()
        .filter_map(|arm| round_trips(arm, edge_cases(&arm.file)))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

const FRAMES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ik_frames/");

/// The robots of tests/data/ik_frames: PUMA 560 and UR5 with a tool point, a `[tool]` frame, a
/// `[base]` frame; each file named after the example robot whose parameters it takes.
fn framed_arms() -> Vec<Arm> {
    let mut files: Vec<String> = std::fs::read_dir(FRAMES)
        .expect("tests/data/ik_frames")
        .map(|e| e.expect("entry").path().display().to_string())
        .filter(|p| p.ends_with(".toml"))
        .collect();
    files.sort();
    let arms: Vec<Arm> = files
        .iter()
        .map(|path| {
            let stem = Path::new(path).file_stem().expect("name").to_string_lossy();
            let known = GENERATED
                .iter()
                .find(|k| stem.starts_with(&format!("{k}_")))
                .unwrap_or_else(|| panic!("{path}: named after none of {GENERATED:?}"));
            Arm::at(path, known, None)
        })
        .collect();
    for want in ["tool_point", "tool_frame", "base_frame"] {
        assert!(
            arms.iter().any(|a| a.file.contains(want)),
            "no robot with a {want} in {FRAMES}"
        );
    }
    arms
}

/// Random and near-singular configurations per framed robot and per free joint of the Panda:
/// 1,000 each, as for the plain arms (the issue asks the same of robots with a tool point, a
/// tool frame and a base frame).
const VARIANT_CASES: usize = 1000;

#[test]
fn robots_with_a_tool_point_a_tool_frame_or_a_base_frame_round_trip_at_the_edges() {
    let failures: Vec<String> = framed_arms()
        .iter()
        .filter_map(|arm| round_trips(arm, VARIANT_CASES))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The Panda's joints that, taken as the free parameter, leave a six-joint arm of a supported
/// family (each tried: the family is found from the axes, not only for the first such joint).
fn panda_free_joints() -> Vec<Arm> {
    let path = format!("{ROBOTS}panda.toml");
    let r = load(&path);
    let mut arms = Vec::new();
    for v in &r.variables {
        let opts = dqsym::ik::IkOptions {
            free: Some(v.clone()),
            method: dqsym::ik::IkMethod::Family,
        };
        match dqsym::ik::solve(&r, &opts) {
            Ok(_) => arms.push(Arm::at(&path, "panda", Some(v))),
            Err(dqsym::ik::IkError::Unsupported { .. }) => {}
            Err(e) => panic!("panda, free {v}: {e}"),
        }
    }
    // The joints whose removal leaves a spherical shoulder or wrist (axes 1-3 or 5-7 meet).
    for want in ["theta4", "theta6", "theta7"] {
        assert!(
            arms.iter().any(|a| a.sol.free.as_deref() == Some(want)),
            "the Panda with {want} free is solved"
        );
    }
    arms
}

#[test]
fn panda_round_trips_with_each_free_joint_that_leaves_a_supported_family() {
    let failures: Vec<String> = panda_free_joints()
        .iter()
        .filter_map(|arm| round_trips(arm, VARIANT_CASES))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The robots whose generated solvers are compiled and run (one program per language).
const GENERATED: [&str; 6] = ["puma560", "kuka_kr5", "irb140", "ur5", "stanford", "panda"];

/// A generated solver's input: per configuration the 16 entries of the target and the
/// parameters in the solver's order.
fn inputs(arm: &Arm, qs: &[(Vec<f64>, f64)]) -> String {
    let mut text = String::new();
    for (q, _) in qs {
        let t = arm.model.pose(q);
        let mut v: Vec<f64> = t.iter().flatten().copied().collect();
        let p = arm.params_at(q);
        for name in &arm.sol.params {
            v.push(p.iter().find(|(k, _)| k == name).expect("parameter").1);
        }
        let line: Vec<String> = v.iter().map(|x| format!("{x:e}")).collect();
        text.push_str(&line.join(" "));
        text.push('\n');
    }
    text
}

/// Reads a generated solver's output (per configuration a count, then rows of joint values and
/// the flags singular, approximate) and checks it as the reference solver's.
fn check_generated(arm: &Arm, lang: &str, out: &str, qs: &[(Vec<f64>, f64)]) {
    let mut lines = out.lines();
    let dof = arm.sol.variables.len();
    for (q, dist) in qs {
        let n: usize = lines
            .next()
            .and_then(|l| l.trim().parse().ok())
            .unwrap_or_else(|| panic!("{lang} {}: output ends early", arm.file));
        let sols: Vec<(Vec<f64>, bool, bool)> = (0..n)
            .map(|_| {
                let v: Vec<f64> = lines
                    .next()
                    .expect("row")
                    .split_whitespace()
                    .map(|x| x.parse().expect("number"))
                    .collect();
                (v[..dof].to_vec(), v[dof] != 0.0, v[dof + 1] != 0.0)
            })
            .collect();
        let what = format!("{lang} {} at {dist:e}", arm.file);
        assert!(
            arm.check(&what, q, *dist, &sols),
            "{what}: {q:?} not among {sols:?}"
        );
        // The same solutions as the reference solver away from the singular sets (on and near
        // them, rounding decides which samples stay).
        if *dist > 1e-3 {
            assert_eq!(n, arm.solve(q).len(), "{what}: solution count");
        }
    }
}

fn generated_cases(arm: &Arm) -> Vec<(Vec<f64>, f64)> {
    configurations(arm, 60, 60, 11)
}

#[test]
fn generated_c_is_pedantic_c99_and_round_trips_at_the_edges() {
    // The named arms, the framed ones and the Panda with each free joint: C compiles fast.
    let arms = GENERATED
        .iter()
        .map(|f| Arm::new(f))
        .chain(framed_arms())
        .chain(panda_free_joints());
    for arm in arms {
        let file: String = arm
            .file
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        let code = dqsym::ik::ik_c(&arm.sol).expect("c");
        let np = arm.sol.params.len();
        let args: String = (0..np).map(|i| format!(", v[{}]", 16 + i)).collect();
        let main = format!(
            "{code}\n#include <stdio.h>\nint main(void) {{\n    double v[64];\n    for (;;) {{\n        \
int i, j;\n        double T[4][4];\n        ik_solutions s;\n        \
for (i = 0; i < 16 + {np}; i++) if (scanf(\"%lf\", &v[i]) != 1) return 0;\n        \
for (i = 0; i < 16; i++) T[i / 4][i % 4] = v[i];\n        \
ik((const double (*)[4])T{args}, &s);\n        printf(\"%d\\n\", s.n);\n        \
for (i = 0; i < s.n; i++) {{\n            for (j = 0; j < IK_DOF; j++) printf(\"%.17e \", s.q[i][j]);\n            \
printf(\"%d %d %.3e\\n\", s.singular[i], s.approximate[i], s.residual[i]);\n        }}\n    }}\n}}\n"
        );
        let dir = crate::tools::temp_dir(&format!("ik-edges-c-{file}"));
        let (src, exe) = (dir.join("ik.c"), dir.join("ik"));
        std::fs::write(&src, main).expect("write");
        let mut gcc = std::process::Command::new("gcc");
        gcc.args([
            "-std=c99",
            "-pedantic",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-O1",
            "-o",
        ])
        .arg(&exe)
        .arg(&src)
        .arg("-lm");
        crate::tools::run(gcc, "", &format!("gcc -std=c99 -pedantic on {file}"));
        let qs = generated_cases(&arm);
        let out = crate::tools::run(std::process::Command::new(&exe), &inputs(&arm, &qs), "C");
        check_generated(&arm, "C", &out, &qs);
    }
}

#[test]
fn generated_rust_round_trips_at_the_edges() {
    // One program: each robot's solver in a module of its own.
    let mut prog = String::new();
    let mut calls = String::new();
    let arms: Vec<Arm> = GENERATED.iter().map(|f| Arm::new(f)).collect();
    for (i, arm) in arms.iter().enumerate() {
        let code = dqsym::ik::ik_rust(&arm.sol).expect("rust");
        prog.push_str(&format!("#[allow(dead_code)]\nmod r{i} {{\n{code}\n}}\n"));
        let args: String = (0..arm.sol.params.len())
            .map(|k| format!(", v[{}]", 16 + k))
            .collect();
        calls.push_str(&format!(
            "        {i} => {{\n            let s = r{i}::ik(&t{args});\n            println!(\"{{}}\", s.n);\n            \
for ((q, sg), ap) in s.q.iter().zip(&s.singular).zip(&s.approximate).take(s.n) {{\n                \
let q: Vec<String> = q.iter().map(|x| format!(\"{{x:e}}\")).collect();\n                \
println!(\"{{}} {{}} {{}}\", q.join(\" \"), u8::from(*sg), u8::from(*ap));\n            }}\n        }}\n"
        ));
    }
    let main = format!(
        "{prog}\nfn main() {{\n    use std::io::BufRead;\n    for line in std::io::stdin().lock().lines() {{\n        \
let v: Vec<f64> = line.expect(\"line\").split_whitespace().map(|x| x.parse().expect(\"number\")).collect();\n        \
let robot = v[0] as usize;\n        let v = &v[1..];\n        let mut t = [[0.0; 4]; 4];\n        \
for (i, x) in v[..16].iter().enumerate() {{\n            t[i / 4][i % 4] = *x;\n        }}\n        \
match robot {{\n{calls}        _ => unreachable!(),\n        }}\n    }}\n}}\n"
    );
    let dir = crate::tools::temp_dir("ik-edges-rust");
    let (src, exe) = (dir.join("ik.rs"), dir.join("ik"));
    std::fs::write(&src, main).expect("write");
    crate::tools::compile_rust_clean(&src, &exe, false, "the generated ik solvers");
    let mut input = String::new();
    let mut cases = Vec::new();
    for (i, arm) in arms.iter().enumerate() {
        let qs = generated_cases(arm);
        for l in inputs(arm, &qs).lines() {
            input.push_str(&format!("{i} {l}\n"));
        }
        cases.push(qs);
    }
    let out = crate::tools::run(std::process::Command::new(&exe), &input, "Rust");
    let mut lines = out.lines().peekable();
    for (arm, qs) in arms.iter().zip(&cases) {
        // This robot's share of the output: its counts and rows.
        let mut part = String::new();
        for _ in qs {
            let head = lines.next().expect("count");
            part.push_str(head);
            part.push('\n');
            for _ in 0..head.trim().parse::<usize>().expect("count") {
                part.push_str(lines.next().expect("row"));
                part.push('\n');
            }
        }
        check_generated(arm, "Rust", &part, qs);
    }
}

#[test]
fn generated_python_round_trips_at_the_edges() {
    for file in ["puma560", "ur5", "stanford"] {
        let arm = Arm::new(file);
        let code = dqsym::ik::ik_python(&arm.sol).expect("python");
        let names: Vec<String> = arm.sol.params.iter().map(|p| format!("'{p}'")).collect();
        let script = format!(
            "{code}\n\nimport sys\nNAMES = [{}]\nfor line in sys.stdin:\n    v = [float(x) for x in line.split()]\n    \
T = np.array(v[:16]).reshape(4, 4)\n    sols = ik_full(T, **dict(zip(NAMES, v[16:])))\n    print(len(sols))\n    \
for q, sg, ap, res in sols:\n        print(' '.join(repr(x) for x in q), int(sg), int(ap))\n",
            names.join(", ")
        );
        let qs = generated_cases(&arm);
        let out = crate::tools::run_python(&script, &inputs(&arm, &qs), "numpy");
        check_generated(&arm, "Python", &out, &qs);
    }
}

/// The IK page at a wrist singularity (PUMA 560's theta5 slider at 0): the live table lists
/// the singular family once (no two rows alike to the three decimals shown), every row's own
/// pose on the target.
#[test]
fn ik_page_at_a_wrist_singularity_lists_each_solution_once() {
    let dir = crate::tools::temp_dir("ik-edges-page");
    let page = dir.join("walk_ik_puma560.html");
    let robot = format!("{ROBOTS}puma560.toml");
    crate::tools::dqsym_ok(&[
        "walk",
        &robot,
        "--ik",
        "--html",
        &page.display().to_string(),
    ]);
    let html = std::fs::read_to_string(&page).expect("page");
    let slider = "data-name=\"theta5\" data-joint=\"1\" min=\"-3.141592653589793\" \
                  max=\"3.141592653589793\" step=\"any\" value=\"";
    let at = html.find(slider).expect("the theta5 slider") + slider.len();
    let end = at + html[at..].find('"').expect("value");
    let singular = format!("{}0{}", &html[..at], &html[end..]);
    let sing = dir.join("singular.html");
    std::fs::write(&sing, singular).expect("write");
    let d = crate::tools::headless(&dir.join("chromium"))
        .args(["--virtual-time-budget=5000", "--dump-dom"])
        .arg(format!("file://{}", sing.display()))
        .output()
        .expect("chromium runs");
    assert!(d.status.success(), "{}", String::from_utf8_lossy(&d.stderr));
    let dom = String::from_utf8_lossy(&d.stdout);
    let table = dom.split("id=\"ik-solutions\"").nth(1).expect("the table");
    let table = table.split("</table>").next().expect("table end");
    let mut rows = Vec::new();
    let mut singular_rows = 0;
    for row in table.split("<tr data-dev=\"").skip(1) {
        let dev: f64 = row.split('"').next().expect("dev").parse().expect("dev");
        assert!(dev < 1e-9, "a row misses the target by {dev:e}");
        let cells: Vec<&str> = row
            .split("<td>")
            .skip(2)
            .map(|c| c.split("</td>").next().unwrap_or(""))
            .collect();
        // The joints (six), then the branches that give it (`*` singular, `~` approximate),
        // the deviation.
        let joints: Vec<String> = cells[..6]
            .iter()
            .map(|c| c.replace("-0.000", "0.000"))
            .collect();
        singular_rows += usize::from(cells[6].contains('*'));
        assert!(!rows.contains(&joints), "the row {joints:?} twice");
        rows.push(joints);
    }
    // The family k pi/6 of theta4 (with theta6 following), once.
    assert!(singular_rows >= 12, "{singular_rows} singular rows");
    assert!(rows.len() <= 24, "{} rows", rows.len());
}

/// A `[base]` frame at angles off the pi/12 grid (roll, pitch and yaw kept as exact decimals):
/// the axes are read from the whole pose, whose terms the base multiplies. At the default
/// limits that reaches a limit, which `ik` names as the limit (never "not a product of joint
/// motions", the geometry error it was relabelled as); if it is solved, it round trips.
#[test]
fn a_base_frame_off_the_angle_grid_is_solved_or_named_as_a_limit() {
    let text = std::fs::read_to_string(format!("{FRAMES}puma560_base_frame.toml"))
        .expect("robot file")
        .replace("rpy = [0, 0, \"pi/6\"]", "rpy = [0.3, -0.2, 0.5]");
    assert!(text.contains("[0.3, -0.2, 0.5]"), "the base line moved");
    let dir = crate::tools::temp_dir("ik-edges-base-off-grid");
    let path = dir.join("puma560_base_off_grid.toml");
    std::fs::write(&path, text).expect("write");
    let path = path.display().to_string();
    let r = load(&path);
    match dqsym::ik::solve(&r, &dqsym::ik::IkOptions::default()) {
        Err(dqsym::ik::IkError::Scalar(e)) => {
            let m = e.to_string();
            assert!(m.contains("limit") || m.contains("budget"), "{m}");
        }
        Err(e) => panic!("{path}: {e}"),
        Ok(_) => {
            let arm = Arm::at(&path, "puma560", None);
            assert!(round_trips(&arm, 20).is_none());
        }
    }
}
