//! Robot files: every example robot against plain 4x4 matrix products at random configurations,
//! its Jacobian against finite differences, `dqsym fk` output, and malformed files.

use crate::paper_support::{ev, points};
use dqsym::{
    eval_scalar_text,
    kin::{dq_jacobian, JointGeometry},
    parse_robot, Chain, Joint, Robot, Scalar,
};
use std::process::Command;

pub(crate) fn load(path: &str) -> Robot {
    let text = std::fs::read_to_string(path).expect("robot file");
    parse_robot(&text, path, &eval_scalar_text).unwrap_or_else(|e| panic!("{e}"))
}

fn robot_files() -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots");
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("examples/robots")
        .map(|e| e.expect("entry").path().display().to_string())
        .filter(|p| p.ends_with(".toml"))
        .collect();
    v.sort();
    // The Jaco-style arm (offsets outside pi/12; tests/it/offsets.rs) lives with the test data:
    // its closed forms take seconds, too long for every walkthrough and Python test of the
    // examples.
    v.push(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/jaco_style.toml").to_owned());
    v
}

/// The chain with every parameter evaluated at `env`: an f64 chain built without symbols.
pub(crate) fn numeric_chain(r: &Robot, env: &[(String, f64)]) -> Chain<f64> {
    let f = |x: &Scalar| ev(x, env);
    let f3 = |v: &[Scalar; 3]| [f(&v[0]), f(&v[1]), f(&v[2])];
    let joints = r
        .chain
        .joints
        .iter()
        .map(|j| {
            let g = match &j.geometry {
                JointGeometry::Dh { theta, d, a, alpha } => JointGeometry::Dh {
                    theta: f(theta),
                    d: f(d),
                    a: f(a),
                    alpha: f(alpha),
                },
                JointGeometry::Mdh { alpha, a, theta, d } => JointGeometry::Mdh {
                    alpha: f(alpha),
                    a: f(a),
                    theta: f(theta),
                    d: f(d),
                },
                JointGeometry::Screw { axis, point } => JointGeometry::Screw {
                    axis: f3(axis),
                    point: f3(point),
                },
                JointGeometry::Local { frames, axis } => JointGeometry::Local {
                    frames: frames.iter().map(|(x, r)| (f3(x), f3(r))).collect(),
                    axis: f3(axis),
                },
            };
            Joint::new(j.kind, g)
        })
        .collect();
    // The base and tool frames, numerically (identities for most example robots).
    let frame = |q: &dqsym::DualQuat<Scalar>| {
        let c = q.components();
        dqsym::DualQuat::from_components(std::array::from_fn(|k| f(&c[k])))
    };
    Chain::new(joints)
        .with_base(frame(&r.chain.base))
        .with_tool(frame(&r.chain.tool))
}

/// The pose matrix of `r` at `env` from the f64 chain (joints not bound are 0).
pub(crate) fn plain_pose(r: &Robot, env: &[(String, f64)]) -> dqsym::Matrix4<f64> {
    let qs: Vec<f64> = r
        .variables
        .iter()
        .map(|v| {
            env.iter()
                .find(|(k, _)| k == v)
                .map(|(_, x)| *x)
                .unwrap_or(0.0)
        })
        .collect();
    numeric_chain(r, env)
        .forward_matrix(&qs)
        .expect("joint count")
}

#[test]
fn every_example_robot_matches_plain_matrix_products() {
    let files = robot_files();
    assert!(files.len() >= 8, "the example robots: {files:?}");
    for file in files {
        let r = load(&file);
        let q = r.forward();
        assert!(
            q.unit_constraints().hold_exactly(),
            "{file}: forward kinematics is a unit DQ"
        );
        let m = q.to_matrix();
        let mut names: Vec<String> = r.variables.clone();
        names.extend(r.parameters());
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        for env in points(&refs, 4) {
            let want = plain_pose(&r, &env);
            for i in 0..3 {
                for j in 0..4 {
                    let got = ev(&m.rows[i][j], &env);
                    assert!(
                        (got - want.rows[i][j]).abs() < 1e-9,
                        "{file}: T[{i}][{j}] {got} != {}",
                        want.rows[i][j]
                    );
                }
            }
            if let Some(tool) = &r.tool {
                let p = q.transform_point(tool);
                let t = [ev(&tool[0], &env), ev(&tool[1], &env), ev(&tool[2], &env)];
                let wp = want.transform_point(&t);
                for k in 0..3 {
                    assert!((ev(&p[k], &env) - wp[k]).abs() < 1e-9, "{file}: tool point");
                }
            }
        }
    }
}

#[test]
fn forward_matrix_equals_the_matrix_of_the_forward_dq() {
    // `fk` takes the matrix as the product of the joint factors' matrices (cheaper than
    // converting the product DQ); both must be exactly the same scalars.
    for f in robot_files() {
        let r = load(&f);
        let via_dq = r.forward().to_matrix();
        let chained = r.forward_matrix();
        for i in 0..4 {
            for j in 0..4 {
                assert_eq!(chained.rows[i][j], via_dq.rows[i][j], "{f}: T[{i}][{j}]");
            }
        }
    }
}

#[test]
fn every_example_jacobian_matches_finite_differences() {
    for file in robot_files() {
        let r = load(&file);
        let q = r.forward();
        let vars: Vec<&str> = r.variables.iter().map(String::as_str).collect();
        let jac = dq_jacobian(&q, &vars);
        let comps = q.components();
        let mut names: Vec<String> = r.variables.clone();
        names.extend(r.parameters());
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        let env = &points(&refs, 1)[0];
        let h = 1e-6;
        for (j, v) in vars.iter().enumerate() {
            let shifted = |d: f64| -> Vec<(String, f64)> {
                env.iter()
                    .map(|(k, x)| (k.clone(), if k == v { x + d } else { *x }))
                    .collect()
            };
            let (p, m) = (shifted(h), shifted(-h));
            for (i, c) in comps.iter().enumerate() {
                let fd = (ev(c, &p) - ev(c, &m)) / (2.0 * h);
                assert!(
                    (fd - ev(&jac[i][j], env)).abs() < 1e-6,
                    "{file}: J[{i}][{j}]"
                );
            }
        }
    }
}

#[test]
fn malformed_robot_files_name_the_file_joint_and_field() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/robots_bad");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").path())
        .collect();
    files.sort();
    let mut out = String::new();
    for f in &files {
        let name = format!(
            "robots_bad/{}",
            f.file_name().expect("name").to_string_lossy()
        );
        let text = std::fs::read_to_string(f).expect("read");
        match parse_robot(&text, &name, &eval_scalar_text) {
            Ok(_) => panic!("{name} should be refused"),
            Err(e) => {
                let msg = e.to_string();
                assert!(msg.starts_with(&name), "message names the file: {msg}");
                out.push_str(&format!("{msg}\n"));
            }
        }
    }
    crate::common::snapshot_settings().bind(|| insta::assert_snapshot!("robot_file_errors", out));
}

#[test]
fn fk_command_prints_sympy_lines_and_exits_1_on_bad_files() {
    let bin = env!("CARGO_BIN_EXE_dqsym");
    let puma = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/puma560.toml");
    let text = crate::tools::dqsym_ok(&["fk", puma, "--jacobian", "--format", "sympy"]);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 8 + 12 + 8 * 6, "one line per entry");
    for l in &lines {
        let (name, expr) = l.split_once(" = ").expect("NAME = EXPR");
        let ok = name.starts_with("dq[") || name.starts_with("T[") || name.starts_with("J[");
        assert!(ok && !expr.is_empty(), "{l}");
    }
    assert!(text.contains("T[2][3] = "));
    let bad = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/robots_bad/symbolic_axis.toml"
    );
    let out = Command::new(bin).args(["fk", bad]).output().expect("runs");
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("joint 1, field `axis`"), "{err}");
}

#[test]
fn fk_sympy_output_parses_in_sympy_and_agrees_numerically() {
    let bin = env!("CARGO_BIN_EXE_dqsym");
    let rrr = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/rrr.toml");
    let out = Command::new(bin)
        .args(["fk", rrr, "--format", "sympy"])
        .output()
        .expect("runs");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let script = r#"
import sys, math, sympy
vals = {"theta1": 0.3, "theta2": -1.1, "theta3": 0.8, "l1": 1.5, "l2": 0.7, "l3": 0.4}
for line in sys.stdin:
    name, expr = line.rstrip("\n").split(" = ", 1)
    e = sympy.sympify(expr)
    v = float(e.subs({sympy.Symbol(k): x for k, x in vals.items()}).evalf())
    print(f"{name} {v!r}")
"#;
    let res = crate::tools::run_python(script, &text, "sympy");
    let r = load(rrr);
    let q = r.forward();
    let env: Vec<(String, f64)> = [
        ("theta1", 0.3),
        ("theta2", -1.1),
        ("theta3", 0.8),
        ("l1", 1.5),
        ("l2", 0.7),
        ("l3", 0.4),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), *v))
    .collect();
    let p = q.transform_point(r.tool.as_ref().expect("tool"));
    let mut seen = 0;
    for line in res.lines() {
        let (name, v) = line.split_once(' ').expect("name value");
        let v: f64 = v.parse().expect("number");
        let want = if let Some(k) = name.strip_prefix("p[") {
            ev(&p[k[..1].parse::<usize>().expect("index")], &env)
        } else if let Some(k) = name.strip_prefix("dq[") {
            ev(
                &q.components()[k[..1].parse::<usize>().expect("index")],
                &env,
            )
        } else {
            continue;
        };
        assert!((v - want).abs() < 1e-9, "{name}: {v} != {want}");
        seen += 1;
    }
    assert_eq!(seen, 11, "8 DQ components and 3 point coordinates");
}

#[test]
fn fk_rust_output_compiles_and_agrees_with_the_engine() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/scara.toml");
    let code = crate::tools::dqsym_ok(&["fk", file, "--jacobian", "--format", "rust"]);
    let r = load(file);
    let q = r.forward();
    let vals = [0.4, -0.9, 0.25, 1.3, 0.8, 0.6, 0.35];
    let mut names = r.variables.clone();
    names.extend(r.parameters());
    assert_eq!(names.len(), vals.len(), "{names:?}");
    let env: Vec<(String, f64)> = names.iter().cloned().zip(vals).collect();
    let args: Vec<String> = vals.iter().map(|v| format!("{v:?}")).collect();
    let main = format!(
        "{code}\nfn main() {{\n    let r = scara_fk({});\n    for v in r.dq {{ println!(\"{{v:?}}\"); }}\n}}\n",
        args.join(", ")
    );
    let dir = crate::tools::temp_dir("fk-scara");
    let src = dir.join("fk.rs");
    std::fs::write(&src, main).expect("write");
    let exe = dir.join("fk");
    let mut rustc = Command::new("rustc");
    rustc
        .args(["--edition", "2021", "-D", "warnings", "-o"])
        .arg(&exe)
        .arg(&src);
    crate::tools::run(rustc, "", "rustc -D warnings on the fk output");
    let printed = crate::tools::run(Command::new(&exe), "", "the compiled fk function");
    let got: Vec<f64> = printed.lines().map(|l| l.parse().expect("f64")).collect();
    for (k, c) in q.components().iter().enumerate() {
        assert!((got[k] - ev(c, &env)).abs() < 1e-12, "dq[{k}]");
    }
}

#[test]
fn chain_of_20_symbolic_joints_is_reported_as_an_exact_recurrence() {
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/chain20_symbolic.toml"
    );
    let r = load(file);
    // A small term limit keeps the debug-build test quick; the default (20,000) behaves alike.
    let o = dqsym::FkOptions {
        format: dqsym::Format::Sympy,
        max_terms: 2_000,
        jacobian: true,
        ..dqsym::FkOptions::default()
    };
    let text = dqsym::fk_report(&r, &o).expect("a report");
    // Evaluate the recurrence line by line in SymPy at one configuration.
    let mut names: Vec<String> = r.variables.clone();
    names.extend(r.parameters());
    assert_eq!(names.len(), 80, "every DH parameter is a symbol");
    let env: Vec<(String, f64)> = names
        .iter()
        .enumerate()
        .map(|(i, n)| (n.clone(), ((i * 37 % 101) as f64) / 50.0 - 1.0))
        .collect();
    let vals: Vec<String> = env.iter().map(|(k, v)| format!("{k:?}: {v:?}")).collect();
    let script = format!(
        r#"
import sys, sympy
env = {{{}}}
for line in sys.stdin:
    name, expr = line.rstrip("\n").split(" = ", 1)
    e = sympy.sympify(expr)
    v = float(e.xreplace({{s: sympy.Float(env[s.name], 30) for s in e.free_symbols}}).evalf(30))
    env[name.replace("[", "_").replace("]", "")] = v
    if name.startswith(("T[", "J[")):
        print(name, repr(v))
"#,
        vals.join(", ")
    );
    let out = crate::tools::run_python(&script, &text, "sympy");
    let want = plain_pose(&r, &env);
    // The Jacobian against the recurrence's own entries in f64 (which a test checks against
    // finite differences).
    let vals =
        crate::recurrence::evaluate(&dqsym::app::fk_recurrence(&r, &o).expect("entries"), &env);
    let mut seen = 0;
    for line in out.lines() {
        let (name, v) = line.split_once(' ').expect("name value");
        let v: f64 = v.parse().expect("f64");
        if name.starts_with("J[") {
            let key = name.replace("][", "_").replace('[', "_").replace(']', "");
            let want = vals[&key];
            assert!(
                (v - want).abs() <= 1e-9 * (1.0 + want.abs()),
                "{name}: {v} != {want}"
            );
            seen += 1;
            continue;
        }
        let i: usize = name[2..3].parse().expect("row");
        let j: usize = name[5..6].parse().expect("column");
        assert!(
            (v - want.rows[i][j]).abs() < 1e-9,
            "{name}: {v} != {}",
            want.rows[i][j]
        );
        seen += 1;
    }
    assert_eq!(seen, 12 + 8 * 20);
}

#[test]
fn generic_6r_pose_as_a_cos_sin_polynomial_matches_plain_matrix_products() {
    // Every DH parameter symbolic: the Fourier form of the pose has about 300,000 terms, the
    // cos/sin polynomial 1,595 monomials (the form SymEngine expands to; bench W3).
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/generic_6r.toml");
    let r = load(file);
    assert!(
        r.forward_within(5_000).is_none(),
        "the Fourier form explodes"
    );
    let m = r
        .forward_matrix_cos_sin(5_000)
        .expect("the cos/sin polynomial fits");
    let monomials: usize = m.rows[..3].iter().flatten().map(Scalar::len).sum();
    assert!(monomials < 2_000, "{monomials} monomials");
    let forms: Vec<Vec<dqsym::Expr>> = (0..3)
        .map(|i| {
            (0..4)
                .map(|j| dqsym::closed::closed_form_cos_sin(&m.rows[i][j]).expect("closed form"))
                .collect()
        })
        .collect();
    let ops: usize = forms.iter().flatten().map(|e| e.cost().ops).sum();
    let expanded: usize = m.rows[..3]
        .iter()
        .flatten()
        .map(|x| {
            dqsym::closed::expanded_form(x)
                .expect("expanded")
                .with_placeholders_as_trig()
                .cost()
                .ops
        })
        .sum();
    assert!(
        ops * 2 < expanded,
        "closed form {ops} ops, expanded {expanded}"
    );
    let mut names: Vec<String> = r.variables.clone();
    names.extend(r.parameters());
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    for env in points(&refs, 3) {
        let want = plain_pose(&r, &env);
        let value = |n: &str| -> Option<f64> {
            if let Some((x, f)) = dqsym::scalar::parse_trig_placeholder(n) {
                let v = env.iter().find(|(k, _)| k == x)?.1;
                return Some(f.f64(v));
            }
            env.iter().find(|(k, _)| k == n).map(|(_, v)| *v)
        };
        let pairs: Vec<(&str, f64)> = env.iter().map(|(k, v)| (k.as_str(), *v)).collect();
        for (i, row) in forms.iter().enumerate() {
            for (j, form) in row.iter().enumerate() {
                let poly = m.rows[i][j].eval(&value).expect("bound");
                let closed = form.value_at(&pairs).expect("bound");
                let w = want.rows[i][j];
                assert!(
                    (poly - w).abs() < 1e-9,
                    "T[{i}][{j}] polynomial {poly} != {w}"
                );
                assert!(
                    (closed - w).abs() < 1e-9,
                    "T[{i}][{j}] closed form {closed} != {w}"
                );
            }
        }
    }
}

#[test]
fn cos_sin_polynomial_of_the_puma_pose_is_the_fourier_pose() {
    // Both forms of the same matrix: the polynomial, read back with cos/sin of the angles,
    // is exactly the canonical Fourier form.
    let r = load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/robots/puma560.toml"
    ));
    let fourier = r.forward_matrix();
    let poly = r.forward_matrix_cos_sin(5_000).expect("fits");
    for i in 0..3 {
        for j in 0..4 {
            let e = dqsym::closed::closed_form_cos_sin(&poly.rows[i][j]).expect("closed form");
            assert_eq!(e.to_scalar(), fourier.rows[i][j], "T[{i}][{j}]");
        }
    }
}

#[test]
fn jacobian_rows_taken_from_a_multiple_equal_the_jacobian() {
    // `fk --jacobian` puts each class of rational multiples among the Jacobian's entries in
    // closed form once and gives the others that form times their factor: every row must
    // still be its derivative exactly. The multiples are found here independently (a row
    // equal to -1, 2, 1/2, ... times an earlier one), so the test knows it covers them.
    let factors: Vec<Scalar> = [(-1, 1), (2, 1), (-2, 1), (1, 2), (-1, 2)]
        .iter()
        .map(|&(n, d)| Scalar::rational(num_rational::BigRational::new(n.into(), d.into())))
        .collect();
    let mut multiples = 0;
    for f in robot_files() {
        let r = load(&f);
        let vars: Vec<&str> = r.variables.iter().map(String::as_str).collect();
        let jac = dq_jacobian(&r.forward(), &vars);
        let o = dqsym::FkOptions {
            jacobian: true,
            ..dqsym::FkOptions::default()
        };
        let entries = dqsym::app::fk_entries(&r, &o).expect("report");
        assert!(!entries.recurrence, "{f}");
        let rows: Vec<&dqsym::Expr> = entries
            .rows()
            .filter(|(q, _)| q.name().starts_with("J["))
            .map(|(_, e)| e)
            .collect();
        let flat: Vec<&Scalar> = jac.iter().flatten().collect();
        assert_eq!(rows.len(), flat.len(), "{f}");
        for (k, (e, x)) in rows.iter().zip(&flat).enumerate() {
            assert_eq!(e.to_scalar(), **x, "{f}: J entry {k}");
            let earlier = &flat[..k];
            if !earlier.contains(x)
                && factors
                    .iter()
                    .any(|c| earlier.iter().any(|y| (*y).clone() * c.clone() == **x))
            {
                multiples += 1;
            }
        }
    }
    assert!(
        multiples >= 10,
        "{multiples} rows are multiples of earlier rows"
    );
}

#[test]
fn jacobian_closed_forms_from_the_prepared_components_equal_the_jacobian() {
    // `fk --jacobian` puts each entry in closed form by differentiating the regrouped
    // monomials of its DQ component; every such form must be the derivative exactly.
    for f in robot_files() {
        let r = load(&f);
        let q = r.forward();
        let vars: Vec<&str> = r.variables.iter().map(String::as_str).collect();
        let jac = dqsym::kin::dq_jacobian(&q, &vars);
        for (i, c) in q.components().iter().enumerate() {
            let (form, prepared) = dqsym::closed::closed_form_prepared(c);
            assert_eq!(form.expect("closed form").to_scalar(), *c, "{f}: dq[{i}]");
            for (k, v) in vars.iter().enumerate() {
                let e = dqsym::closed::closed_form_of_derivative(&prepared, v, &jac[i][k])
                    .expect("closed form");
                assert_eq!(e.to_scalar(), jac[i][k], "{f}: J[{i}][{k}]");
            }
        }
    }
}
