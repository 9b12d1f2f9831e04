//! The script language end to end: the evaluator through the library, and the binary's `run`,
//! `-e` and REPL on the examples and on every bad input.

use crate::common::snapshot_settings;
use dqsym::{
    closed_form, lang::BUILTINS, parse, plain, show, DualQuat, PlainOptions, Quat, Scalar, Session,
    ShowOptions, Value,
};
use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_dqsym");

fn sym(n: &str) -> Scalar {
    Scalar::sym(n)
}

/// Runs `src` in a fresh session, panicking with the rendered error.
fn session(src: &str) -> Session {
    let program = parse(src).unwrap_or_else(|e| panic!("{e}"));
    let mut s = Session::new();
    s.run(&program)
        .unwrap_or_else(|e| panic!("{}", e.render(src)));
    s
}

/// The displayed text of the last statement of `src`.
fn shown(src: &str) -> String {
    let program = parse(src).unwrap_or_else(|e| panic!("{e}"));
    let mut s = Session::new();
    let out = s
        .run(&program)
        .unwrap_or_else(|e| panic!("{}", e.render(src)));
    let last = out.last().expect("something displayed");
    show(last, &ShowOptions::default()).unwrap()
}

fn eval_error(src: &str) -> String {
    let program = parse(src).unwrap_or_else(|e| panic!("{e}"));
    Session::new()
        .run(&program)
        .expect_err("should fail")
        .message()
}

fn text(s: &Scalar) -> String {
    plain(&closed_form(s).unwrap(), &PlainOptions::default())
}

fn dq(s: &Session, name: &str) -> DualQuat<Scalar> {
    match s.get(name) {
        Some(Value::DualQuat(d)) => d.clone(),
        other => panic!("{name} is {other:?}"),
    }
}

fn run_bin(args: &[&str], stdin: Option<&str>) -> Output {
    let mut child = Command::new(BIN)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .env("XDG_STATE_HOME", std::env::temp_dir())
        .spawn()
        .expect("runs");
    let mut input = child.stdin.take().expect("stdin");
    input
        .write_all(stdin.unwrap_or("").as_bytes())
        .expect("writes");
    drop(input);
    child.wait_with_output().expect("finishes")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("utf-8")
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).expect("utf-8")
}

#[test]
fn dual_unit_times_vector_is_a_pure_dual_part() {
    let s = session("syms x y z\np = 1 + I*(x, y, z)\nq = eps*(x, y, z)");
    let p = dq(&s, "p");
    assert_eq!(p.real, Quat::identity());
    assert_eq!(p.dual, Quat::vector(sym("x"), sym("y"), sym("z")));
    assert_eq!(dq(&s, "q").dual, p.dual);
}

#[test]
fn appendix2_product_of_dual_numbers() {
    assert_eq!(
        shown("syms q1 I q2 q3 q4\nqa=q1+I*q2\nqb=q3+I*q4\nQ=qa*qb"),
        "Q = q1 q3 + eps (q1 q4 + q2 q3)\n"
    );
}

#[test]
fn products_keep_their_order() {
    let s = session("a = (0, 1, 0, 0)*(0, 0, 1, 0); b = (0, 0, 1, 0)*(0, 1, 0, 0)");
    let k = |w: i64| {
        Value::Quat(Quat::new(
            Scalar::int(0),
            Scalar::int(0),
            Scalar::int(0),
            Scalar::int(w),
        ))
    };
    assert_eq!(s.get("a"), Some(&k(1)));
    assert_eq!(s.get("b"), Some(&k(-1)));
}

#[test]
fn half_angles_print_as_full_angles() {
    assert_eq!(
        shown("halfangle c3, s3 = theta3\nc3^2 - s3^2"),
        "c3^2 - s3^2 = c3\n  where c3 = cos(theta3)\n"
    );
    assert_eq!(
        shown("halfangle c, s = theta\n2*c*s"),
        "2*c*s = sin(theta)\n"
    );
}

#[test]
fn appendix3_syms_lines_keep_half_angle_meanings() {
    let s = session("halfangle c3, s3 = theta3\nsyms c3 s3 c12\nx = c3");
    assert_eq!(
        s.get("x"),
        Some(&Value::Scalar(
            (sym("theta3") * <Scalar as dqsym::Ring>::from_ratio(1, 2)).cos()
        ))
    );
}

#[test]
fn rrr_arm_end_effector_is_l1c1_l2c12_l3c123() {
    let src = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/appendix3_rrr.dq"
    ))
    .unwrap();
    let s = session(&src);
    let v0 = dq(&s, "v0");
    let (t1, t2, t3) = (sym("theta1"), sym("theta2"), sym("theta3"));
    let (l1, l2, l3) = (sym("l1"), sym("l2"), sym("l3"));
    let y = &l1 * t1.cos() + &l2 * (&t1 + &t2).cos() + &l3 * (&t1 + &t2 + &t3).cos();
    let z = &l1 * t1.sin() + &l2 * (&t1 + &t2).sin() + &l3 * (&t1 + &t2 + &t3).sin();
    assert_eq!(v0.real, Quat::identity());
    assert_eq!(v0.dual, Quat::vector(Scalar::int(0), y.clone(), z));
    assert_eq!(text(&y), "l1 c1 + l2 c12 + l3 c123");
    // The library's own chain agrees.
    let ex = [Scalar::int(1), Scalar::int(0), Scalar::int(0)];
    let at = |y: Scalar| [Scalar::int(0), y, Scalar::int(0)];
    let chain = DualQuat::rotation(&ex, &t1)
        * DualQuat::rotation_about_point(&ex, &t2, &at(l1.clone()))
        * DualQuat::rotation_about_point(&ex, &t3, &at(&l1 + &l2));
    assert_eq!(chain.transform_point(&at(&l1 + &l2 + &l3))[1], y);
}

#[test]
fn sec6_4_example_matches_the_library_and_fixes_the_wrist_centre() {
    let src = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/sec6_4_puma_like.dq"
    ))
    .unwrap();
    let s = session(&src);
    let (d, big_l) = (sym("d"), sym("L"));
    let c4 = [d.clone(), big_l.clone(), Scalar::int(0)];
    let ez = [Scalar::int(0), Scalar::int(0), Scalar::int(1)];
    assert_eq!(
        dq(&s, "qd5"),
        DualQuat::rotation_about_point(&ez, &sym("theta5"), &c4)
    );
    let arm = dq(&s, "T");
    assert_eq!(s.get("C"), Some(&Value::Vector(arm.transform_point(&c4))));
    assert_eq!(
        dq(&s, "W").transform_point(&c4),
        c4,
        "the wrist leaves C4 fixed"
    );
}

#[test]
fn jacobian_is_eight_by_n_derivatives() {
    let s = session("syms theta1 theta2 a1 a2\nq = dh(theta1, 0, a1, 0)*dh(theta2, 0, a2, 0)\nJ = jacobian(q, [theta1, theta2])");
    let q = dq(&s, "q");
    let Some(Value::Matrix(j)) = s.get("J") else {
        panic!("a matrix")
    };
    assert_eq!((j.len(), j[0].len()), (8, 2));
    for (row, c) in j.iter().zip(q.components()) {
        assert_eq!(row[0], c.diff("theta1"));
        assert_eq!(row[1], c.diff("theta2"));
    }
}

#[test]
fn failed_statement_leaves_bindings_intact() {
    let mut s = Session::new();
    let p = parse("syms l\nx = 1 + l\nx = x/0").unwrap();
    assert!(s.run(&p).is_err());
    assert_eq!(s.get("x"), Some(&Value::Scalar(Scalar::int(1) + sym("l"))));
}

#[test]
fn quaternion_plus_scalar_is_an_error_but_dual_quaternion_plus_scalar_promotes() {
    assert!(eval_error("syms l1\n(1, 0, 0, 0) + l1").contains("a 4-tuple is a whole quaternion"));
    let s = session("syms l1\np = l1 + I*(0, 1, 0)");
    assert_eq!(dq(&s, "p").real, Quat::from_scalar(sym("l1")));
}

#[test]
fn transform_and_matrix_require_unit_dual_quaternions() {
    let m = eval_error("syms l\ntransform((1, 1, 0, 0), (0, l, 0))");
    assert!(m.contains("needs a unit dual quaternion"), "{m}");
    let m = eval_error("matrix(2*I + 1)");
    assert!(m.contains("needs a unit dual quaternion"), "{m}");
}

#[test]
fn every_help_example_runs() {
    for b in BUILTINS {
        let src = format!("syms theta1 d1 a1 alpha1 t l\nx = {}", b.example);
        let program = parse(&src).unwrap_or_else(|e| panic!("{}: {e}", b.name));
        Session::new()
            .run(&program)
            .unwrap_or_else(|e| panic!("{}: {}", b.name, e.render(&src)));
        assert!(b.example.starts_with(b.name), "{}", b.example);
    }
}

#[test]
fn statements_ending_with_semicolon_are_not_displayed() {
    let program = parse("x = 1;\ny = 2\n3;\n4").unwrap();
    let out = Session::new().run(&program).unwrap();
    let labels: Vec<&str> = out.iter().map(|d| d.label.as_str()).collect();
    assert_eq!(labels, ["y", "4"]);
}

/// Every example runs with the binary; its output is a snapshot.
#[test]
fn examples_run_and_print_the_papers_results() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".dq"))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "appendix2_product.dq",
            "appendix3_rrr.dq",
            "sec3b_planar.dq",
            "sec6_2_wrist.dq",
            "sec6_3_6r.dq",
            "sec6_4_puma_like.dq",
            "twists.dq"
        ]
    );
    for name in names {
        let path = dir.join(&name);
        let out = run_bin(&["run", path.to_str().unwrap()], None);
        assert_eq!(out.status.code(), Some(0), "{name}: {}", stderr(&out));
        let snap = format!("example_{}", name.trim_end_matches(".dq"));
        snapshot_settings().bind(|| insta::assert_snapshot!(snap, stdout(&out)));
    }
}

#[test]
fn example_results_agree_with_the_paper() {
    let run = |name: &str| {
        let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
        stdout(&run_bin(&["run", &path], None))
    };
    let rrr = run("appendix3_rrr.dq");
    assert!(
        rrr.contains("v0 = 1 + eps (0, 0, l1 c1 + l2 c12 + l3 c123, l1 s1 + l2 s12 + l3 s123)"),
        "{rrr}"
    );
    let planar = run("sec3b_planar.dq");
    assert!(
        planar.contains("b1 = 1 + eps (0, 0, d1 + l cos(theta), d2 + l sin(theta))"),
        "{planar}"
    );
    let six = run("sec6_3_6r.dq");
    assert!(
        six.contains("v3 = 1 + eps (0, -l4 c4 s5, l1 + l2 + l3 + l4 c5, l4 s4 s5)"),
        "{six}"
    );
    let puma = run("sec6_4_puma_like.dq");
    assert!(
        puma.contains("transform(qd4*qd5*qd6, C4) = (d, L, 0)"),
        "{puma}"
    );
}

#[test]
fn explicit_flag_spells_out_angle_sums() {
    let path = format!("{}/examples/appendix3_rrr.dq", env!("CARGO_MANIFEST_DIR"));
    let out = stdout(&run_bin(&["run", &path, "--explicit"], None));
    assert!(
        out.contains("l1*cos(theta1) + l2*cos(theta1 + theta2) + l3*cos(theta1 + theta2 + theta3)"),
        "{out}"
    );
    assert!(!out.contains("where"), "{out}");
}

#[test]
fn one_liner_prints_the_closed_form() {
    let out = run_bin(&["-e", "cos(t)^2 + sin(t)^2"], None);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(stdout(&out), "1\n");
    let out = run_bin(
        &["-e", "transform(rot((0, 0, 1), theta1), (l, 0, 0))"],
        None,
    );
    assert_eq!(
        stdout(&out),
        "(l c1, l s1, 0)\n  where c1 = cos(theta1), s1 = sin(theta1)\n"
    );
}

#[test]
fn one_liner_errors_exit_with_status_1_and_a_caret() {
    let out = run_bin(&["-e", "1/(t - t)"], None);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        stderr(&out),
        "error: division by zero\n --> 1:3\n  |\n1 | 1/(t - t)\n  |   ^^^^^^^\n"
    );
    let out = run_bin(&["-e", "(1 + "], None);
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn run_reports_a_missing_file_with_status_1() {
    let out = run_bin(&["run", "/nonexistent/x.dq"], None);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).starts_with("error: cannot read"));
}

/// Every bad input fails with status 1 (never 101) and a caret.
#[test]
fn bad_inputs_exit_with_status_1() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bad");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let out = run_bin(&["run", path.to_str().unwrap()], None);
        assert_eq!(out.status.code(), Some(1), "{path:?}: {}", stderr(&out));
        let err = stderr(&out);
        assert!(
            err.starts_with("error: ") && err.contains('^'),
            "{path:?}: {err}"
        );
        count += 1;
    }
    assert!(count >= 50, "{count} bad inputs");
}

#[test]
fn repl_keeps_bindings_across_bad_lines() {
    let script = "\
syms l1 l2
halfangle c1, s1 = theta1
q = (c1, s1, 0, 0) + I*(0, 0, -l1*s1)
q + (1, 0, 0, 0
)
undefined + 1
x = (1, 2)
p = q*(1 + I*(0, l1 + l2, 0))*cconj(q)
1/0
y = q
:vars
:help
:bogus
p
:quit
p
";
    let out = run_bin(&[], Some(script));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = stdout(&out);
    let err = stderr(&out);
    assert!(err.contains("unknown name `undefined`"), "{err}");
    assert!(err.contains("a tuple of 2"), "{err}");
    assert!(err.contains("division by zero"), "{err}");
    assert!(err.contains("unknown command `:bogus`"), "{err}");
    assert!(
        text.contains("p = 1 + eps (0, 0, l1 + l2 c1, l2 s1)"),
        "{text}"
    );
    assert!(text.contains("  theta1: symbol"), "{text}");
    for b in BUILTINS {
        assert!(text.contains(b.example), "help lacks {}", b.name);
    }
    // `:quit` ends the session: the last `p` is not evaluated.
    assert_eq!(text.matches("p = 1 + eps").count(), 2, "{text}");
    snapshot_settings().bind(|| insta::assert_snapshot!("repl_session_stderr", err));
}

#[test]
fn displayed_values_use_the_closed_form_layout() {
    let s = shown("syms l\nmatrix(trans((l, 0, 0)))");
    assert_eq!(
        s,
        "matrix(trans((l, 0, 0))) =\n  [1, 0, 0, l]\n  [0, 1, 0, 0]\n  [0, 0, 1, 0]\n  [0, 0, 0, 1]\n"
    );
}

#[test]
fn sympy_format_is_parsed_by_sympify() {
    let one = run_bin(&["-e", "cos(t)^2 + sin(t)^2", "--format", "sympy"], None);
    assert_eq!(stdout(&one), "1\n");
    let path = format!("{}/examples/appendix3_rrr.dq", env!("CARGO_MANIFEST_DIR"));
    let out = stdout(&run_bin(&["run", &path, "--format", "sympy"], None));
    let v0 = out
        .lines()
        .find_map(|l| l.strip_prefix("v0 = "))
        .expect("v0 shown");
    let script = "import sys\nfrom sympy import sympify, symbols, cos, sin, simplify\n\
        t1, t2, t3, l1, l2, l3 = symbols('theta1 theta2 theta3 l1 l2 l3')\n\
        v = sympify(sys.stdin.read(), locals={str(s): s for s in (t1, t2, t3, l1, l2, l3)})\n\
        want = l1*cos(t1) + l2*cos(t1 + t2) + l3*cos(t1 + t2 + t3)\n\
        print(len(v), v[0], simplify(v[6] - want))\n";
    let got = crate::tools::run_python(script, v0, "sympy");
    assert_eq!(got.trim(), "8 1 0");
}

#[test]
fn latex_format_renders_with_katex() {
    for expr in [
        "rot((0, 0, 1), theta1)*trans((a1, 0, 0))",
        "matrix(dh(theta1, d1, a1, pi/2))",
        "transform(rot((1, 0, 0), theta1), (0, l, 0))",
    ] {
        let out = run_bin(&["-e", expr, "--format", "latex"], None);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        crate::tools::katex(&stdout(&out), expr);
    }
}

#[test]
fn rust_format_generates_a_function_of_the_symbols() {
    let out = stdout(&run_bin(
        &[
            "-e",
            "transform(rot((0, 0, 1), theta1), (l, 0, 0))",
            "--format",
            "rust",
        ],
        None,
    ));
    assert!(
        out.contains("pub fn value(l: f64, theta1: f64) -> Value {"),
        "{out}"
    );
}
