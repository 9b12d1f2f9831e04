//! `fk --jacobian=geometric` and `geometric_body`: the 6 x n geometric Jacobian (the end
//! effector origin's velocity over the angular velocity) in the base frame and in the end
//! effector frame, checked at random configurations against central differences of plain 4x4
//! matrices built in this file from the robot's joints and frames (never from a dual
//! quaternion): PUMA 560, UR5, the Stanford arm (a prismatic joint), a SCARA, a URDF UR5 and a
//! robot with base and tool frames. The generated NumPy and the SymPy text are run too.

use crate::common::Rng;
use crate::mat4::{mul, rot, trans, M, X, Y, Z};
use crate::tools::run_python;
use dqsym::{
    app::{task_jacobian, task_report, TaskJacobian},
    kin::JointGeometry,
    FkOptions, Format, JointKind, Robot, Scalar,
};

/// The pose at joint values `q` with parameters `env`: base frames, one plain matrix per joint
/// (DH, modified DH or a screw motion about its home-pose axis), tool frames.
fn pose(r: &Robot, env: &[(String, f64)], q: &[f64]) -> M {
    let mut all: Vec<(&str, f64)> = env.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    all.extend(
        r.variables
            .iter()
            .map(String::as_str)
            .zip(q.iter().copied()),
    );
    let f = |x: &Scalar| x.eval_at(&all).expect("numeric");
    let f3 = |v: &[Scalar; 3]| [f(&v[0]), f(&v[1]), f(&v[2])];
    let frame = |fr: &dqsym::kin::Frame| {
        let [roll, pitch, yaw] = f3(&fr.rpy);
        let r = mul(&rot(Z, yaw), &mul(&rot(Y, pitch), &rot(X, roll)));
        mul(&trans(f3(&fr.xyz)), &r)
    };
    let mut m = trans([0.0; 3]);
    for fr in &r.base_frames {
        m = mul(&m, &frame(fr));
    }
    for (j, v) in r.chain.joints.iter().zip(&r.joint_values) {
        let v = f(v);
        let (rv, pv) = match j.kind {
            JointKind::Revolute => (v, 0.0),
            JointKind::Prismatic => (0.0, v),
        };
        let jm = match &j.geometry {
            JointGeometry::Dh { theta, d, a, alpha } => {
                let m = mul(&rot(Z, f(theta) + rv), &trans([0.0, 0.0, f(d) + pv]));
                mul(&mul(&m, &trans([f(a), 0.0, 0.0])), &rot(X, f(alpha)))
            }
            JointGeometry::Mdh { alpha, a, theta, d } => {
                let m = mul(&rot(X, f(alpha)), &trans([f(a), 0.0, 0.0]));
                mul(
                    &mul(&m, &rot(Z, f(theta) + rv)),
                    &trans([0.0, 0.0, f(d) + pv]),
                )
            }
            JointGeometry::Screw { axis, point } => {
                let (u, p) = (f3(axis), f3(point));
                match j.kind {
                    JointKind::Revolute => {
                        let m = mul(&trans(p), &rot(u, v));
                        mul(&m, &trans([-p[0], -p[1], -p[2]]))
                    }
                    JointKind::Prismatic => trans([u[0] * v, u[1] * v, u[2] * v]),
                }
            }
            // A URDF joint as written: its origin frames, then the motion about its axis
            // through the last frame's origin.
            JointGeometry::Local { frames, axis } => {
                let u = f3(axis);
                let origin = frames.iter().fold(trans([0.0; 3]), |m, (xyz, rpy)| {
                    let fr = dqsym::kin::Frame {
                        xyz: xyz.clone(),
                        rpy: rpy.clone(),
                    };
                    mul(&m, &frame(&fr))
                });
                let own = match j.kind {
                    JointKind::Revolute => rot(u, v),
                    JointKind::Prismatic => trans([u[0] * v, u[1] * v, u[2] * v]),
                };
                mul(&origin, &own)
            }
        };
        m = mul(&m, &jm);
    }
    for fr in &r.tool_frames {
        m = mul(&m, &frame(fr));
    }
    m
}

/// The geometric Jacobian by central differences of [`pose`]: column j is (dp/dq_j;
/// vee(dR/dq_j R^T)), or in the end-effector frame (R^T of both) when `body`.
fn numeric_jacobian(r: &Robot, env: &[(String, f64)], q: &[f64], body: bool) -> Vec<[f64; 6]> {
    let h = 1e-6;
    let t = pose(r, env, q);
    (0..q.len())
        .map(|j| {
            let (mut qp, mut qm) = (q.to_vec(), q.to_vec());
            qp[j] += h;
            qm[j] -= h;
            let (tp, tm) = (pose(r, env, &qp), pose(r, env, &qm));
            let d = |a: usize, b: usize| (tp[a][b] - tm[a][b]) / (2.0 * h);
            let v = [d(0, 3), d(1, 3), d(2, 3)];
            // W = dR R^T is skew: omega = (W21, W02, W10).
            let w = |a: usize, b: usize| (0..3).map(|k| d(a, k) * t[b][k]).sum::<f64>();
            let omega = [w(2, 1), w(0, 2), w(1, 0)];
            let back = |x: [f64; 3]| -> [f64; 3] {
                std::array::from_fn(|i| (0..3).map(|k| t[k][i] * x[k]).sum())
            };
            let (v, omega) = if body {
                (back(v), back(omega))
            } else {
                (v, omega)
            };
            [v[0], v[1], v[2], omega[0], omega[1], omega[2]]
        })
        .collect()
}

fn robots() -> Vec<Robot> {
    let root = env!("CARGO_MANIFEST_DIR");
    let mut v: Vec<Robot> = [
        "examples/robots/puma560.toml",
        "examples/robots/ur5.toml",
        "examples/robots/stanford.toml",
        "examples/robots/scara.toml",
        "tests/data/hostile/robot/datasheet_base_yaw.toml",
    ]
    .iter()
    .map(|p| crate::robots::load(&format!("{root}/{p}")))
    .collect();
    let urdf = std::fs::read_to_string(format!("{root}/benches/support/ur5.urdf")).expect("urdf");
    let o = dqsym::kin::UrdfOptions::default();
    v.push(
        dqsym::parse_urdf(&urdf, "ur5.urdf", &o)
            .expect("urdf")
            .robot,
    );
    v
}

/// Nominal parameter values: the file's `[values]`, others drawn at random.
fn parameters(r: &Robot, rng: &mut Rng) -> Vec<(String, f64)> {
    r.parameters()
        .into_iter()
        .map(|p| {
            let v = r
                .values
                .iter()
                .find(|(n, _)| *n == p)
                .map_or_else(|| rng.range(0.1, 0.9), |(_, v)| *v);
            (p, v)
        })
        .collect()
}

#[test]
fn geometric_jacobians_match_differences_of_plain_matrices() {
    let mut rng = Rng::new(61);
    let mut prismatic = 0;
    for r in robots() {
        prismatic += r
            .chain
            .joints
            .iter()
            .filter(|j| j.kind == JointKind::Prismatic)
            .count();
        let x = r.forward();
        let vars: Vec<&str> = r.variables.iter().map(String::as_str).collect();
        for (kind, body) in [
            (TaskJacobian::Geometric, false),
            (TaskJacobian::GeometricBody, true),
        ] {
            let j = task_jacobian(&x, &vars, &kind);
            assert_eq!(j.den, Scalar::int(1));
            assert_eq!(j.num.len(), 6, "{}", r.name);
            for _ in 0..4 {
                let env = parameters(&r, &mut rng);
                let q: Vec<f64> = vars.iter().map(|_| rng.range(-3.0, 3.0)).collect();
                let want = numeric_jacobian(&r, &env, &q, body);
                let mut all: Vec<(&str, f64)> = env.iter().map(|(n, v)| (n.as_str(), *v)).collect();
                all.extend(vars.iter().copied().zip(q.iter().copied()));
                for (i, row) in j.num.iter().enumerate() {
                    assert_eq!(row.len(), vars.len());
                    for (c, e) in row.iter().enumerate() {
                        let got = e.eval_at(&all).expect("numeric");
                        assert!(
                            (got - want[c][i]).abs() < 1e-6,
                            "{} {kind:?} [{i}][{c}]: {got} against {} at {q:?}",
                            r.name,
                            want[c][i]
                        );
                    }
                }
            }
        }
    }
    assert!(prismatic >= 2, "prismatic joints are covered");
}

#[test]
fn generated_numpy_and_sympy_geometric_jacobians_match_plain_matrices() {
    let mut rng = Rng::new(62);
    let root = env!("CARGO_MANIFEST_DIR");
    let cases = [
        crate::robots::load(&format!("{root}/examples/robots/stanford.toml")),
        crate::robots::load(&format!(
            "{root}/tests/data/hostile/robot/datasheet_base_yaw.toml"
        )),
    ];
    for r in &cases {
        for (kind, key, body) in [
            (TaskJacobian::Geometric, "jg", false),
            (TaskJacobian::GeometricBody, "jb", true),
        ] {
            let code = |format| {
                let o = FkOptions {
                    format,
                    ..FkOptions::default()
                };
                task_report(r, &o, &kind).expect("report")
            };
            let (py, sympy) = (code(Format::Python), code(Format::Sympy));
            let env = parameters(r, &mut rng);
            let q: Vec<f64> = r.variables.iter().map(|_| rng.range(-3.0, 3.0)).collect();
            let want = numeric_jacobian(r, &env, &q, body);
            let values: Vec<String> = env
                .iter()
                .map(|(n, v)| (n.as_str(), *v))
                .chain(
                    r.variables
                        .iter()
                        .map(String::as_str)
                        .zip(q.iter().copied()),
                )
                .map(|(n, v)| format!("'{n}': {v:e}"))
                .collect();
            let base = if body { "Jb" } else { "Jg" };
            let script = format!(
                "{py}\nimport inspect, sympy\nvals = {{{}}}\nf = [v for k, v in list(globals().items()) if k.endswith('_fk')][0]\n\
                 args = [vals[p] for p in inspect.signature(f).parameters]\n\
                 out = f(*args)['{key}']\n\
                 print(' '.join(repr(float(x)) for x in out.reshape(-1)))\n\
                 ent = {{}}\n\
                 for line in open(0).read().splitlines():\n    name, expr = line.split(' = ', 1)\n    ent[name] = expr\n\
                 syms = {{k: sympy.Symbol(k) for k in vals}}\n\
                 n = len(out[0])\n\
                 print(' '.join(repr(float(sympy.sympify(ent['{base}[%d][%d]' % (i, j)], locals=syms).subs({{syms[k]: v for k, v in vals.items()}}).evalf())) for i in range(6) for j in range(n)))\n",
                values.join(", ")
            );
            let out = run_python(&script, &sympy, "sympy");
            let lines: Vec<&str> = out.lines().collect();
            assert_eq!(lines.len(), 2, "{out}");
            for (which, line) in ["numpy", "sympy"].iter().zip(&lines) {
                let got: Vec<f64> = line
                    .split_whitespace()
                    .map(|x| x.parse().expect("a number"))
                    .collect();
                let n = q.len();
                assert_eq!(got.len(), 6 * n, "{which}: {line}");
                for i in 0..6 {
                    for c in 0..n {
                        assert!(
                            (got[i * n + c] - want[c][i]).abs() < 1e-6,
                            "{} {which} {key}[{i}][{c}]: {} against {}",
                            r.name,
                            got[i * n + c],
                            want[c][i]
                        );
                    }
                }
            }
        }
    }
}
