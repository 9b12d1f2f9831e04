//! Generated Rust, C, Python and JavaScript: compiled (rustc -D warnings, clippy, gcc -Werror)
//! or run (the venv's Python with NumPy, Node in strict mode), then compared at random points
//! with `Scalar::eval`.

use crate::paper_support::*;
use crate::tools;
use dqsym::emit::{
    arguments, c_function, javascript_function, python_function, rust_function, CodegenOptions,
    Output,
};
use std::process::Command;

fn joints(n: usize) -> Vec<String> {
    (1..=n).map(|i| format!("theta{i}")).collect()
}

/// The PUMA 560 pose: the 8 DQ components and the top three rows of the 4x4 matrix.
pub fn puma_outputs() -> Vec<Output> {
    let (q, _) = crate::paper_arms::puma560();
    let m = q.to_matrix();
    vec![
        Output::vector(
            "dq",
            "The pose as a unit dual quaternion (w, x, y, z) + eps (w, x, y, z).",
            q.components().iter().map(closed).collect(),
        ),
        Output::matrix(
            "t",
            "The top three rows of the 4x4 homogeneous matrix.",
            m.rows
                .iter()
                .take(3)
                .map(|r| r.iter().map(closed).collect())
                .collect(),
        ),
    ]
}

fn rrr_outputs() -> Vec<Output> {
    let (q, v0) = crate::emit::rrr();
    vec![
        Output::vector(
            "dq",
            "q_d1 q_d2 q_d3.",
            q.components().iter().map(closed).collect(),
        ),
        Output::vector("v0", "The end effector.", v0.iter().map(closed).collect()),
        Output::scalar(
            "reach",
            "y + z of the end effector.",
            closed(&(&v0[1] + &v0[2])),
        ),
    ]
}

/// Random points for `args`, and the expected returned outputs there from `Scalar::eval`,
/// flattened; an intermediate output's entries are bound to their symbols for the later ones.
fn expected(outputs: &[Output], args: &[String]) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let names: Vec<&str> = args.iter().map(String::as_str).collect();
    let pts = points(&names, 6);
    let want = pts
        .iter()
        .map(|env| {
            let mut env = env.clone();
            let mut want = Vec::new();
            for o in outputs {
                for (k, e) in o.values.iter().enumerate() {
                    let v = ev(&e.to_scalar(), &env);
                    if o.intermediate {
                        env.push((o.entry_symbol(k), v));
                    } else {
                        want.push(v);
                    }
                }
            }
            want
        })
        .collect();
    let pts = pts
        .iter()
        .map(|env| env.iter().map(|(_, v)| *v).collect())
        .collect();
    (pts, want)
}

fn input(pts: &[Vec<f64>]) -> String {
    pts.iter()
        .map(|p| {
            let v: Vec<String> = p.iter().map(|x| format!("{x:?}")).collect();
            v.join(" ") + "\n"
        })
        .collect()
}

fn compare(what: &str, out: &str, want: &[Vec<f64>]) {
    let got: Vec<Vec<f64>> = out
        .lines()
        .map(|l| {
            l.replace(['[', ']', ','], " ")
                .split_whitespace()
                .map(|x| x.parse::<f64>().expect("a number"))
                .collect()
        })
        .collect();
    assert_eq!(got.len(), want.len(), "{what}: one line per point");
    for (g, w) in got.iter().zip(want) {
        assert_eq!(g.len(), w.len(), "{what}: one value per output entry");
        for (k, (a, b)) in g.iter().zip(w).enumerate() {
            assert!(close(*a, *b), "{what}: entry {k}: {a} != {b}");
        }
    }
}

fn check_rust(name: &str, outputs: &[Output], args: &[String], o: &CodegenOptions) {
    let code = rust_function(name, "Generated for a test.", outputs, args, o).expect("codegen");
    let call: Vec<String> = (0..args.len()).map(|i| format!("v[{i}]")).collect();
    let fields: Vec<String> = outputs
        .iter()
        .filter(|o| !o.intermediate)
        .map(|o| format!("r.{}", o.name))
        .collect();
    let fmt = vec!["{:?}"; fields.len()].join(" ");
    let main = format!(
        "\nfn main() {{\n    let mut s = String::new();\n    std::io::Read::read_to_string(&mut std::io::stdin(), &mut s).unwrap();\n    for line in s.lines() {{\n        let v: Vec<f64> = line.split_whitespace().map(|x| x.parse().unwrap()).collect();\n        let r = {name}({});\n        println!(\"{fmt}\", {});\n    }}\n}}\n",
        call.join(", "),
        fields.join(", ")
    );
    let dir = tools::temp_dir(&format!("rust-{name}"));
    let src = dir.join("gen.rs");
    std::fs::write(&src, code + &main).expect("write gen.rs");
    let bin = dir.join("gen");
    tools::compile_rust_clean(&src, &bin, true, &src.display().to_string());
    let (pts, want) = expected(outputs, args);
    let out = tools::run(Command::new(&bin), &input(&pts), "generated Rust");
    compare(&format!("Rust {name}"), &out, &want);
}

fn check_c(name: &str, outputs: &[Output], args: &[String]) {
    let code = c_function(
        name,
        "Generated for a test.",
        outputs,
        args,
        &Default::default(),
    )
    .expect("codegen");
    let mut decl = String::new();
    let mut outs = Vec::new();
    let mut prints = String::new();
    for o in outputs.iter().filter(|o| !o.intermediate) {
        match o.shape {
            None => {
                decl.push_str(&format!("        double {};\n", o.name));
                outs.push(format!("&{}", o.name));
                prints.push_str(&format!("        printf(\"%.17g \", {});\n", o.name));
            }
            Some((r, c)) => {
                decl.push_str(&format!("        double {}[{}];\n", o.name, r * c));
                outs.push(if r == 1 {
                    o.name.clone()
                } else {
                    format!("(double (*)[{c}]){}", o.name)
                });
                prints.push_str(&format!(
                    "        for (int k = 0; k < {}; k++) printf(\"%.17g \", {}[k]);\n",
                    r * c,
                    o.name
                ));
            }
        }
    }
    let n = args.len();
    let main = format!(
        "\n#include <stdio.h>\nint main(void)\n{{\n    double v[{n}];\n    for (;;) {{\n        for (int i = 0; i < {n}; i++)\n            if (scanf(\"%lf\", &v[i]) != 1) return 0;\n{decl}        {name}({}, {});\n{prints}        printf(\"\\n\");\n    }}\n}}\n",
        (0..n).map(|i| format!("v[{i}]")).collect::<Vec<_>>().join(", "),
        outs.join(", ")
    );
    let dir = tools::temp_dir(&format!("c-{name}"));
    let src = dir.join("gen.c");
    std::fs::write(&src, code + &main).expect("write gen.c");
    let bin = dir.join("gen");
    let mut gcc = Command::new("gcc");
    gcc.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "-o"])
        .arg(&bin)
        .arg(&src)
        .arg("-lm");
    tools::run(
        gcc,
        "",
        &format!("gcc -std=c99 -Werror on {}", src.display()),
    );
    let (pts, want) = expected(outputs, args);
    let out = tools::run(Command::new(&bin), &input(&pts), "generated C");
    compare(&format!("C {name}"), &out, &want);
}

pub(crate) fn check_python(name: &str, outputs: &[Output], args: &[String]) {
    let code = python_function(
        name,
        "Generated for a test.",
        outputs,
        args,
        &Default::default(),
    )
    .expect("codegen");
    let names: Vec<String> = outputs
        .iter()
        .filter(|o| !o.intermediate)
        .map(|o| format!("{:?}", o.name))
        .collect();
    // All points in one vectorized call: each argument is the column of its values.
    let driver = format!(
        "\nimport sys\ndata = np.loadtxt(sys.stdin, ndmin=2)\nr = {name}(*data.T)\nfor i in range(data.shape[0]):\n    print(' '.join(repr(float(x)) for k in [{}] for x in np.ravel(r[k][i])))\n",
        names.join(", ")
    );
    let (pts, want) = expected(outputs, args);
    let out = tools::run_python(&(code + &driver), &input(&pts), "numpy");
    compare(&format!("Python {name}"), &out, &want);
}

pub(crate) fn check_js(name: &str, outputs: &[Output], args: &[String]) {
    let code = javascript_function(
        name,
        "Generated for a test.",
        outputs,
        args,
        &Default::default(),
    )
    .expect("codegen");
    let names: Vec<String> = outputs
        .iter()
        .filter(|o| !o.intermediate)
        .map(|o| format!("{:?}", o.name))
        .collect();
    // Node runs the function as a strict-mode module body; `.flat()` lays a matrix row-major.
    let driver = format!(
        "\nlet s = '';\nprocess.stdin.on('data', d => s += d);\nprocess.stdin.on('end', () => {{\n    for (const line of s.split('\\n').filter(l => l.trim())) {{\n        const v = line.trim().split(/\\s+/).map(Number);\n        const r = {name}(...v);\n        console.log([{}].flatMap(k => [r[k]].flat(2)).map(x => x.toPrecision(17)).join(' '));\n    }}\n}});\n",
        names.join(", ")
    );
    let dir = tools::temp_dir(&format!("js-{name}"));
    let src = dir.join("gen.mjs");
    std::fs::write(&src, code + &driver).expect("write gen.mjs");
    let (pts, want) = expected(outputs, args);
    let mut node = Command::new("node");
    node.arg(&src);
    let out = tools::run(node, &input(&pts), "node (install Node.js)");
    compare(&format!("JavaScript {name}"), &out, &want);
}

#[test]
fn javascript_puma560_and_rrr_run_in_node_and_match_eval() {
    let outs = puma_outputs();
    let args = arguments(
        &outs,
        &["theta1", "theta2", "theta3", "theta4", "theta5", "theta6"],
    );
    check_js("puma560", &outs, &args);
    let outs = rrr_outputs();
    let mut args = arguments(&outs, &["theta1", "theta2", "theta3"]);
    args.push("unused".into());
    check_js("rrr", &outs, &args);
    let code = javascript_function("f", "Doc.", &outs, &args, &Default::default()).unwrap();
    assert!(
        code.contains("Math.sin(") && code.contains("\"use strict\";"),
        "{code}"
    );
    // A reserved word is renamed (`new` -> `new_`), the function called by position.
    let reserved = vec![Output::scalar("x", "X.", closed(&sym("new")))];
    let code = javascript_function(
        "new",
        "",
        &reserved,
        &["new".to_owned()],
        &Default::default(),
    )
    .unwrap();
    assert!(code.contains("function new_(new_) {"), "{code}");
    assert!(code.contains("x: new_,"), "{code}");
}

#[test]
fn rust_puma560_pose_compiles_clean_and_matches_eval() {
    let outs = puma_outputs();
    let args = arguments(
        &outs,
        &["theta1", "theta2", "theta3", "theta4", "theta5", "theta6"],
    );
    assert_eq!(
        args,
        [
            joints(6),
            vec!["a2".into(), "a3".into(), "d3".into(), "d4".into()]
        ]
        .concat()
    );
    check_rust("puma560", &outs, &args, &CodegenOptions::default());
    check_rust(
        "puma560_per_angle",
        &outs,
        &args,
        &CodegenOptions {
            expand_angles: false,
        },
    );
}

#[test]
fn rust_rrr_arm_compiles_clean_and_matches_eval() {
    let outs = rrr_outputs();
    let mut args = arguments(&outs, &["theta1", "theta2", "theta3"]);
    args.push("unused".into());
    check_rust("rrr", &outs, &args, &CodegenOptions::default());
}

#[test]
fn c_puma560_and_rrr_compile_with_werror_and_match_eval() {
    let outs = puma_outputs();
    let args = arguments(
        &outs,
        &["theta1", "theta2", "theta3", "theta4", "theta5", "theta6"],
    );
    check_c("puma560", &outs, &args);
    let outs = rrr_outputs();
    let mut args = arguments(&outs, &["theta1", "theta2", "theta3"]);
    args.push("unused".into());
    check_c("rrr", &outs, &args);
}

#[test]
fn python_puma560_and_rrr_vectorized_match_eval() {
    let outs = puma_outputs();
    let args = arguments(
        &outs,
        &["theta1", "theta2", "theta3", "theta4", "theta5", "theta6"],
    );
    check_python("puma560", &outs, &args);
    let outs = rrr_outputs();
    let args = arguments(&outs, &["theta1", "theta2", "theta3"]);
    check_python("rrr", &outs, &args);
}

#[test]
fn constants_and_pi_shifts_compile_to_std_consts() {
    // sqrt(2) = SQRT_2, pi = PI, a quarter-turn shift, a pi/3 shift.
    let th = sym("theta");
    let x = int(2).sqrt() * frac(1, 2) * cos(&(&th + S::pi() * frac(1, 2)))
        + sym("pi_weight") * S::pi()
        + sin(&(&th * frac(3, 2) - S::pi() * frac(1, 3)));
    let outs = vec![Output::scalar("x", "A test value.", closed(&x))];
    let args = arguments(&outs, &["theta"]);
    let code = rust_function("consts", "Constants.", &outs, &args, &Default::default()).unwrap();
    // `sqrt(2)/2` is `FRAC_1_SQRT_2` where the closed form keeps the half with the radical.
    assert!(
        code.contains("std::f64::consts::SQRT_2")
            || code.contains("std::f64::consts::FRAC_1_SQRT_2"),
        "{code}"
    );
    assert!(code.contains("std::f64::consts::PI"), "{code}");
    check_rust("consts", &outs, &args, &CodegenOptions::default());
    check_c("consts", &outs, &args);
    check_python("consts", &outs, &args);
    check_js("consts", &outs, &args);
}

#[test]
fn rust_puma560_calls_sin_cos_once_per_joint_and_shares_subexpressions() {
    let outs = puma_outputs();
    let args = arguments(
        &outs,
        &["theta1", "theta2", "theta3", "theta4", "theta5", "theta6"],
    );
    let code = rust_function("puma560", "PUMA 560.", &outs, &args, &Default::default()).unwrap();
    assert_eq!(code.matches(".sin_cos()").count(), 6, "{code}");
    assert!(code.matches("\n    let t").count() > 10, "{code}");
    let per_angle = rust_function(
        "puma560",
        "PUMA 560.",
        &outs,
        &args,
        &CodegenOptions {
            expand_angles: false,
        },
    )
    .unwrap();
    let lets = per_angle.matches(".sin_cos()").count();
    assert_eq!(lets, 13, "one per distinct angle: {per_angle}");
}

/// The PUMA 560 forward kinematics (DQ) the benchmark includes, as `rust_function` writes it.
fn bench_source() -> String {
    let outs = puma_outputs();
    let dq = &outs[..1];
    let args = arguments(
        dq,
        &["theta1", "theta2", "theta3", "theta4", "theta5", "theta6"],
    );
    let code = rust_function(
        "puma560_dq",
        "PUMA 560 forward kinematics (standard DH, Craig's a2 a3 d3 d4) as a unit dual quaternion.",
        dq,
        &args,
        &CodegenOptions::default(),
    )
    .expect("codegen");
    format!("// Generated by dqsym (tests/it/codegen.rs, bench_source); do not edit.\n\n{code}")
}

#[test]
fn bench_generated_puma560_is_up_to_date() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/benches/generated/puma560_dq.rs"
    );
    let want = bench_source();
    if std::env::var_os("DQSYM_BLESS").is_some() {
        std::fs::write(path, &want).expect("write benches/generated/puma560_dq.rs");
    }
    let have = std::fs::read_to_string(path).unwrap_or_default();
    assert!(
        have == want,
        "benches/generated/puma560_dq.rs is out of date: rerun with DQSYM_BLESS=1 to rewrite it"
    );
}

#[test]
fn intermediate_outputs_are_locals_that_later_outputs_read_by_symbol() {
    // A two-step recurrence: A from the arguments, B from A's entries, the results from both.
    let th = sym("theta");
    let a = vec![
        closed(&(cos(&th) * sym("x"))),
        closed(&(sin(&th) + sym("x") * sym("y"))),
    ];
    let b = vec![
        closed(&(sym("A_0") * sym("A_1") + sym("A_0"))),
        closed(&(sym("A_0") - sym("A_1"))),
    ];
    let r = vec![
        closed(&(sym("B_0") * sym("B_1") + sym("A_0"))),
        closed(&(sym("B_0") * sym("B_0"))),
    ];
    let outs = vec![
        Output::intermediate("A", "First step.", a),
        Output::intermediate("B", "Second step.", b),
        Output::vector("r", "The results.", r),
    ];
    let args = arguments(&outs, &["theta"]);
    assert_eq!(
        args,
        ["theta", "x", "y"],
        "entries of A and B are not arguments"
    );
    let code = rust_function("steps", "Steps.", &outs, &args, &Default::default()).unwrap();
    assert!(
        code.contains("    let a_0 = ") && code.contains("    let b_0 = "),
        "{code}"
    );
    assert!(!code.contains("pub a:") && !code.contains("A_0"), "{code}");
    check_rust("steps", &outs, &args, &CodegenOptions::default());
    check_c("steps", &outs, &args);
    check_python("steps", &outs, &args);
    check_js("steps", &outs, &args);
}
