//! Errors are typed values (issue 30): the variant says what went wrong, its data where, and
//! the message is the one users always read.

use dqsym::app::{dh_refusal, DhRefusal};
use dqsym::ik::{solve, IkOptions, NumericError};
use dqsym::kin::ExprError;
use dqsym::{eval_scalar_text, parse_robot};

/// Planar 2R in DH form, the lengths symbolic (as `examples/robots/planar2r.toml`).
fn planar2r() -> dqsym::Robot {
    let text = std::fs::read_to_string("examples/robots/planar2r.toml").expect("robot file");
    parse_robot(&text, "planar2r.toml", &eval_scalar_text).expect("robot")
}

/// The pose of the planar 2R arm, written here as plain matrices (the test's own model).
fn planar_pose(l1: f64, l2: f64, t1: f64, t2: f64) -> [[f64; 4]; 4] {
    let (c12, s12) = ((t1 + t2).cos(), (t1 + t2).sin());
    [
        [c12, -s12, 0.0, l1 * t1.cos() + l2 * c12],
        [s12, c12, 0.0, l1 * t1.sin() + l2 * s12],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

#[test]
fn numeric_ik_without_a_parameter_names_it_and_with_it_reaches_the_pose() {
    let sol = solve(&planar2r(), &IkOptions::default()).expect("a solver");
    let (l1, l2, t1, t2) = (0.7, 0.4, 0.3, -1.1);
    let target = planar_pose(l1, l2, t1, t2);
    let err = sol.solve_numeric(&target, &[("l1", l1)]).unwrap_err();
    assert_eq!(err, NumericError::MissingParameter("l2".into()));
    assert_eq!(err.to_string(), "no value for parameter `l2`");
    let found = sol
        .solve_numeric(&target, &[("l1", l1), ("l2", l2)])
        .expect("solutions");
    assert!(!found.is_empty());
    // Two joints reach a position: only the target's position column is used.
    assert!(sol.position_only);
    let mut has_own = false;
    for s in &found {
        let p = planar_pose(l1, l2, s.q[0], s.q[1]);
        for (r, row) in p.iter().enumerate().take(3) {
            assert!((row[3] - target[r][3]).abs() < 1e-9, "{:?}", s.q);
        }
        // The same angle, modulo 2 pi.
        let same = |a: f64, b: f64| (a - b).sin().abs() < 1e-9 && (a - b).cos() > 0.0;
        has_own |= same(s.q[0], t1) && same(s.q[1], t2);
    }
    assert!(has_own, "{found:?}");
}

#[test]
fn field_expression_errors_say_which_text_and_why() {
    match eval_scalar_text("(1, 2, 3, 4)") {
        Err(ExprError::NotScalar { text, .. }) => assert_eq!(text, "(1, 2, 3, 4)"),
        other => panic!("{other:?}"),
    }
    match eval_scalar_text("q1 +") {
        Err(e @ ExprError::Invalid { .. }) => assert!(e.to_string().starts_with("`q1 +`: ")),
        other => panic!("{other:?}"),
    }
    let e = dqsym::lang::eval_point_text("1, 2").unwrap_err();
    assert_eq!(e, ExprError::PointArity { found: 2 });
    assert_eq!(
        e.to_string(),
        "a point needs 3 coordinates separated by commas, found 2"
    );
    // A robot file's field error keeps its words behind the file, joint and field.
    let text = "convention = \"screw\"\n[[joint]]\ntype = \"revolute\"\nvariable = \"q1\"\n\
                axis = [\"0\", \"0\", \"0\"]\npoint = [\"0\", \"0\", \"0\"]\n";
    let e = parse_robot(text, "zero.toml", &eval_scalar_text).unwrap_err();
    assert_eq!(
        e.to_string(),
        "zero.toml: joint 1, field `axis`: the axis is zero"
    );
}

#[test]
fn dh_refusal_is_typed_and_names_the_coupled_joint() {
    // Joint 2 follows joint 1 (a mimic joint): no DH form.
    let text = "convention = \"screw\"\n\
                [[joint]]\ntype = \"revolute\"\nvariable = \"q1\"\naxis = [0, 0, 1]\npoint = [0, 0, 0]\n\
                [[joint]]\ntype = \"revolute\"\nvariable = \"2*q1\"\naxis = [0, 0, 1]\npoint = [1, 0, 0]\n";
    let r = parse_robot(text, "coupled.toml", &eval_scalar_text).expect("robot");
    let why = dh_refusal(&r).expect("a reason");
    assert_eq!(why, DhRefusal::Mimic(2));
    assert_eq!(
        why.to_string(),
        "joint 2 moves with another joint's variable (a mimic joint)"
    );
    // The same axes with a variable each: DH form.
    let free = text.replace("2*q1", "q2");
    let r = parse_robot(&free, "free.toml", &eval_scalar_text).expect("robot");
    assert_eq!(dh_refusal(&r), None);
    // A screw-form reader's refusal of a DH robot is typed too.
    assert_eq!(dh_refusal(&planar2r()), Some(DhRefusal::NotScrew));
}

/// The REPL's `:ik` refuses each bad command with its typed error's message (the usage, an
/// unbound or mistyped chain, `--free` without a variable) and the session goes on.
#[test]
fn repl_ik_errors_say_what_is_wrong_and_the_session_goes_on() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let input = ":ik\n:ik foo q1\nsyms a\n:ik a q1\n:ik a --free\n:ik a\na + 1/2\n:quit\n";
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(input.as_bytes())
        .expect("written");
    let out = child.wait_with_output().expect("it ends");
    let err = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(
        lines,
        [
            "error: usage: :ik NAME q1 q2 ... [--free qk]",
            "error: `foo` is not bound",
            "error: `a` is a scalar, not a dual quaternion",
            "error: --free needs a joint variable",
            "error: usage: :ik NAME q1 q2 ... [--free qk] (name the joint variables)",
        ],
        "{err}"
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("a + 1/2"), "{stdout}");
}
