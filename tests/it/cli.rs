//! The binary, driven as a user would.

use std::process::Command;

#[test]
fn paper_command_prints_the_rrr_end_effector_in_shorthand() {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .arg("paper")
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(text.contains("v0.y = l1 c1 + l2 c12 + l3 c123"), "{text}");
    assert!(text.contains("T[2][3] = a2 s2 + a3 s23 + d4 c23"), "{text}");
}

#[test]
fn paper_command_explicit_form() {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["paper", "--explicit"])
        .output()
        .expect("runs");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(
        text.contains(
            "l1*cos(theta1) + l2*cos(theta1 + theta2) + l3*cos(theta1 + theta2 + theta3)"
        ),
        "{text}"
    );
}

#[test]
fn unknown_command_exits_with_status_2_not_a_panic() {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .arg("frobnicate")
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn ctrl_c_abandons_a_long_computation_and_keeps_the_bindings() {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["--term-limit", "200000", "--work-budget", "1000000000"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starts the REPL");
    let mut stdin = child.stdin.take().expect("stdin");
    // A result of 6,188 terms: its closed form takes seconds in a debug build, long enough to
    // interrupt.
    stdin
        .write_all(b"a = 5\nsyms x y z w u v\n(x + y + z + w + u + v)^12\n")
        .expect("write");
    stdin.flush().expect("flush");
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(status.success());
    std::thread::sleep(std::time::Duration::from_millis(300));
    stdin
        .write_all(b"b = a + 1\n:quit\n")
        .expect("write after the interrupt");
    drop(stdin);
    let out = child.wait_with_output().expect("exits");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(
        stderr.contains("interrupted; the bindings are unchanged"),
        "{stderr}"
    );
    assert!(
        stdout.contains("b = 6"),
        "later lines see earlier bindings: {stdout}"
    );
}

#[test]
fn ops_command_reproduces_tables_1_and_2_with_the_errata() {
    let puma = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/puma560.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["ops", puma])
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    // ERRATA 10: the DQ product is 48 + 40 = 88; ERRATA 11: 27(n - 1) and 18(n - 1).
    assert!(
        text.contains("dual quaternion product: 48 mult, 40 add, total 88"),
        "{text}"
    );
    assert!(
        text.contains("quaternion product: 16 mult, 12 add"),
        "{text}"
    );
    assert!(
        text.contains("3x3 rotation matrix product: 27 mult, 18 add"),
        "{text}"
    );
    assert!(
        text.contains("chain of 3 3x3 rotations (orientation only): 54 mult, 36 add"),
        "{text}"
    );
    assert!(text.contains("generated code, DQ only:"), "{text}");
}

#[test]
fn fk_output_does_not_depend_on_the_number_of_threads() {
    // Closed forms are computed on worker threads (DQSYM_THREADS, default: the cores); each is
    // a pure function of its input and results keep their order, so the bytes are the same.
    let run = |threads: &str, robot: &str| {
        let file = format!(
            "{}/examples/robots/{robot}.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_dqsym"))
            .env("DQSYM_THREADS", threads)
            .args(["fk", &file, "--jacobian"])
            .output()
            .expect("dqsym runs");
        assert!(out.status.success(), "{robot} with {threads} threads");
        out.stdout
    };
    for robot in ["puma560", "stanford", "six_r"] {
        let one = run("1", robot);
        assert!(!one.is_empty());
        assert_eq!(one, run("2", robot), "{robot}: 1 and 2 threads");
        assert_eq!(one, run("5", robot), "{robot}: 1 and 5 threads");
    }
}

#[test]
fn fk_task_jacobians_from_the_command_line() {
    // `--jacobian` alone keeps its meaning and bytes (= `--jacobian=pose`), before or after the
    // robot; `--jacobian=KIND` adds a task Jacobian of the named kind; a bad kind is an error.
    let file = format!("{}/examples/robots/rrr.toml", env!("CARGO_MANIFEST_DIR"));
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_dqsym"))
            .args(args)
            .output()
            .expect("dqsym runs")
    };
    let plain = run(&["fk", &file, "--jacobian"]);
    assert!(plain.status.success());
    assert_eq!(plain.stdout, run(&["fk", "--jacobian", &file]).stdout);
    assert_eq!(plain.stdout, run(&["fk", &file, "--jacobian=pose"]).stdout);
    for (kind, base, rows) in [
        ("rotation", "Jr", 4),
        ("translation", "Jt", 4),
        ("line:0,1,0", "Jl", 8),
        ("plane", "Jpi", 8),
        ("distance", "Jd", 1),
        ("pose_derivative", "Jdot", 8),
    ] {
        for format in ["plain", "sympy", "latex", "rust"] {
            let out = run(&[
                "--format",
                format,
                "fk",
                &file,
                &format!("--jacobian={kind}"),
            ]);
            assert!(
                out.status.success(),
                "{kind} {format}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            let text = String::from_utf8(out.stdout).expect("utf-8");
            if format == "sympy" {
                let n = text
                    .lines()
                    .filter(|l| l.starts_with(&format!("{base}[")))
                    .count();
                assert_eq!(n, rows * 3, "{kind}: {text}");
            }
            if format == "rust" {
                let field = if rows == 1 {
                    format!("pub {}: [f64; 3]", base.to_lowercase())
                } else {
                    format!("pub {}: [[f64; 3]; {rows}]", base.to_lowercase())
                };
                assert!(text.contains(&field), "{kind}: {text}");
            }
        }
    }
    let bad = run(&["fk", &file, "--jacobian=point_to_plane:1,0"]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("needs six numbers"));
    let bad = run(&["fk", &file, "--jacobian=speed"]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("unknown Jacobian `speed`"));
}
