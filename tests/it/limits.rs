//! Reliability of the binary: every limit is a clear error after a bounded amount of work (the
//! work counter, never the clock: the suite runs on loaded machines); output is byte-identical
//! from run to run; the REPL survives every error class and keeps its bindings.

use dqsym::{parse, Context, Session};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_dqsym");

/// Runs the binary with `args` and `stdin`, returning its output.
fn run(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(BIN)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .env("XDG_STATE_HOME", std::env::temp_dir())
        .spawn()
        .expect("runs");
    let mut input = child.stdin.take().expect("stdin");
    input.write_all(stdin.as_bytes()).expect("writes");
    drop(input);
    child.wait_with_output().expect("finishes")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The peak resident memory of the binary run with `args`, in kilobytes, from GNU time.
fn peak_rss_kb(args: &[&str]) -> u64 {
    let out = Command::new("/usr/bin/time")
        .args(["-f", "maxrss=%M", BIN])
        .args(args)
        .output()
        .expect("/usr/bin/time runs");
    let err = stderr(&out);
    err.lines()
        .find_map(|l| l.strip_prefix("maxrss="))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no maxrss in {err}"))
}

/// Asserts a run failed with status 1 and `message` on stderr.
fn fails_with(args: &[&str], message: &str) {
    let out = run(args, "");
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.contains(message), "{args:?}: {err}");
}

/// Runs the statements of `src` in the library under `ctx` (a one-liner's session: free names
/// are symbols) and shows every result in plain text; returns the first error message, if
/// any, and the work done, in term operations.
fn work_of(src: &str, ctx: &Context) -> (Option<String>, u64) {
    let _in = ctx.enter();
    let before = Context::work_done();
    let mut session = Session::with_implicit_symbols();
    let mut error = None;
    match parse(src) {
        Err(e) => error = Some(e.to_string()),
        Ok(program) => {
            for stmt in &program.statements {
                match session.exec(stmt) {
                    Ok(Some(d)) => {
                        if let Err(e) = dqsym::show(&d, &dqsym::ShowOptions::default()) {
                            error.get_or_insert(e.to_string());
                        }
                    }
                    Ok(None) => {}
                    Err(e) => {
                        error.get_or_insert(e.message());
                    }
                }
            }
        }
    }
    (error, Context::work_done() - before)
}

/// The binary's default limits.
fn cli_context() -> Context {
    Context::new()
        .with_term_limit(20_000)
        .with_work_budget(3_000_000)
}

#[test]
fn huge_power_of_a_sum_is_refused_at_once_without_eating_memory() {
    let expr = "(x + y + z + w)^100000";
    fails_with(&["-e", expr], "exponent 100000 is too large");
    assert!(peak_rss_kb(&["-e", expr]) < 64 * 1024);
    let (err, work) = work_of(expr, &cli_context());
    assert!(err.unwrap().contains("exponent 100000 is too large"));
    assert!(
        work < 100,
        "refused after the sum alone: {work} term operations"
    );
    // Within the exponent limit the term limit refuses it, after a few small products.
    let expr = "(x + y + z + w)^10000";
    fails_with(&["-e", expr], "expression too large");
    assert!(peak_rss_kb(&["-e", expr]) < 64 * 1024);
    let (err, work) = work_of(expr, &cli_context());
    assert!(err.unwrap().contains("expression too large"));
    assert!(work < 2_000_000, "{work} term operations");
}

#[test]
fn twenty_thousand_nested_parentheses_are_an_error_not_a_stack_overflow() {
    let deep = format!("{}x{}", "(".repeat(20_000), ")".repeat(20_000));
    fails_with(&["-e", &deep], "nesting deeper than");
    // Also past a raised limit: the parser counts before it recurses.
    fails_with(&["--max-depth", "4096", "-e", &deep], "nesting deeper than");
}

#[test]
fn max_depth_is_configurable_and_bounded() {
    let nested = |n: usize| format!("{}x{}", "(".repeat(n), ")".repeat(n));
    let out = run(&["-e", &nested(300)], "");
    assert_eq!(out.status.code(), Some(1));
    let out = run(&["--max-depth", "1000", "-e", &nested(300)], "");
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    fails_with(
        &["--max-depth", "10", "-e", &nested(20)],
        "nesting deeper than 10",
    );
    // A limit the stack could not take is refused by the argument parser.
    let out = run(&["--max-depth", "100000", "-e", "x"], "");
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn max_exponent_is_configurable() {
    fails_with(&["--max-exponent", "5", "-e", "x^6"], "the limit is 5");
    let out = run(&["--max-exponent", "5", "-e", "x^5"], "");
    assert_eq!(stdout(&out), "x^5\n");
}

#[test]
fn many_small_operations_run_out_of_the_work_budget() {
    // Each product is small, but there are many: the term limit alone would not stop it.
    let line = format!("a = (x + y + z)^6; b = a*a{}", " + a*a".repeat(1000));
    fails_with(
        &["--work-budget", "500000", "-e", &line],
        "work budget exceeded",
    );
    let (err, work) = work_of(&line, &cli_context().with_work_budget(500_000));
    assert!(err.unwrap().contains("work budget exceeded"));
    // The statement stops at the first charge past its budget: a few products more at most.
    assert!((500_000..700_000).contains(&work), "{work} term operations");
    fails_with(
        &["--work-budget", "1000", "-e", "(x + y + z)^6"],
        "over the budget of 1000 (--work-budget raises it)",
    );
    // The budget is per statement: a script of many cheap statements is fine.
    let script = "syms a b\n".to_owned() + &"x = (a + b)^4;\n".repeat(50);
    let path = std::env::temp_dir().join(format!("dqsym_budget_{}.dq", std::process::id()));
    std::fs::write(&path, script).unwrap();
    let out = run(
        &["--work-budget", "2000", "run", path.to_str().unwrap()],
        "",
    );
    let _ = std::fs::remove_file(&path);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

#[test]
fn twenty_fully_symbolic_dh_joints_are_reported_quickly_in_bounded_memory() {
    let robot =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/robots_huge/dh20_symbolic.toml");
    let robot = robot.to_str().unwrap();
    // The run succeeding means that every unit of it stayed within the work budget (3 million
    // term operations): bounded work, whatever the machine's load.
    let out = Command::new("/usr/bin/time")
        .args(["-f", "maxrss=%M", BIN, "fk", robot, "--jacobian"])
        .output()
        .expect("/usr/bin/time runs");
    let err = stderr(&out);
    // The expansion is exponential: fk notices after a few products and prints the pose
    // exactly as a recurrence over the joint factors instead of running out of memory.
    assert_eq!(out.status.code(), Some(0), "{err}");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("as a recurrence over the joint factors") && text.contains("J[7][19] = "),
        "{text}"
    );
    let rss: u64 = err
        .lines()
        .find_map(|l| l.strip_prefix("maxrss="))
        .and_then(|v| v.trim().parse().ok())
        .expect("maxrss");
    assert!(rss < 256 * 1024, "{rss} kB");
}

fn files(dir: &str, ext: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(dir))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == ext))
        .collect();
    v.sort();
    v
}

/// Every example, in every output format, run twice as separate processes: the bytes agree.
#[test]
fn every_example_prints_byte_identical_output_twice() {
    let mut runs: Vec<Vec<String>> = Vec::new();
    for f in files("examples", "dq") {
        for format in ["plain", "latex", "sympy", "rust"] {
            runs.push(vec![
                "run".into(),
                f.display().to_string(),
                "--format".into(),
                format.into(),
            ]);
        }
    }
    for f in files("examples/robots", "toml") {
        runs.push(vec!["fk".into(), f.display().to_string()]);
        runs.push(vec![
            "fk".into(),
            f.display().to_string(),
            "--format".into(),
            "rust".into(),
        ]);
    }
    assert!(runs.len() >= 30, "{} runs", runs.len());
    for args in &runs {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let a = run(&args, "");
        let b = run(&args, "");
        assert_eq!(a.status.code(), Some(0), "{args:?}: {}", stderr(&a));
        assert!(!a.stdout.is_empty(), "{args:?}");
        assert!(
            a.stdout == b.stdout,
            "{args:?}: output differs between runs"
        );
    }
}

/// A scripted session through the real binary: one bad line of every error class between good
/// ones; every later line still sees the earlier bindings.
#[test]
fn repl_survives_every_error_class_and_keeps_bindings() {
    let deep = format!("{}1{}", "(".repeat(20_000), ")".repeat(20_000));
    let script = [
        "syms l1 l2",
        "halfangle c1, s1 = theta1",
        "q = (c1, s1, 0, 0) + I*(0, 0, -l1*s1)",
        "a = 1 + *",                                 // parse error
        "b = nosuch + 1",                            // unknown name
        "c = frobnicate(1)",                         // unknown function
        "d = dh(1, 2)",                              // arity
        "e = (1, 0, 0, 0) + l1",                     // type error
        "f = q/(l1 - l1)",                           // division by zero
        "g = l1/l2",                                 // symbolic divisor
        "h = (l1 + l2)^100000",                      // huge exponent
        "k = (l1 + l2 + theta1)^5000",               // too large
        &deep,                                       // deep nesting
        "m = transform(2 + I*(1, 0, 0), (1, 0, 0))", // not a unit DQ
        "n = cos(l1*l2)",                            // not an angle
        "o = (1, 2)",                                // tuple size
        "pi = 3",                                    // reserved
        "c1 = 2",                                    // half-angle name
        "p = q*(1 + I*(0, l1 + l2, 0))*cconj(q)",
        "r = p + 0",
        "r",
    ]
    .join("\n");
    let out = run(&[], &(script + "\n"));
    let (text, err) = (stdout(&out), stderr(&out));
    assert_eq!(out.status.code(), Some(0), "{err}");
    for message in [
        "expected",
        "unknown name `nosuch`",
        "unknown function `frobnicate`",
        "`dh` takes",
        "cannot add a scalar and a quaternion",
        "division by zero",
        "cannot divide by a symbolic expression",
        "exponent 100000 is too large",
        "expression too large",
        "nesting deeper than",
        "needs a unit dual quaternion",
        "must be a rational combination",
        "a tuple of 2",
        "cannot be assigned",
        "already declared",
    ] {
        assert!(err.contains(message), "no `{message}` in:\n{err}");
    }
    assert_eq!(err.matches("error: ").count(), 15, "{err}");
    assert!(
        text.contains("p = 1 + eps (0, 0, l1 + l2 c1, l2 s1)"),
        "{text}"
    );
    assert!(
        text.contains("r = 1 + eps (0, 0, l1 + l2 c1, l2 s1)"),
        "{text}"
    );
    assert!(text.contains("r = 1 + eps"), "{text}");
    assert_eq!(
        text.matches("= 1 + eps (0, 0, l1 + l2 c1, l2 s1)").count(),
        3,
        "{text}"
    );
}

/// Inputs the fuzzers found slow or crashing (`fuzz/`), run as the fuzz targets run them: under
/// small limits, in every format; each ends with status 0 or 1, and in the library each
/// statement stops within its work budget (the counter, not the clock).
#[test]
fn fuzz_findings_end_within_their_budget_under_small_limits() {
    let small = ["--term-limit", "1000", "--work-budget", "50000"];
    let ctx = Context::new()
        .with_term_limit(1_000)
        .with_work_budget(50_000)
        .with_max_exponent(1_000);
    let mut count = 0;
    for f in files("tests/data/fuzz", "dq") {
        let src = std::fs::read_to_string(&f).unwrap();
        for format in ["plain", "latex", "sympy", "rust"] {
            let mut args = small.to_vec();
            args.extend(["--format", format, "-e", &src]);
            let out = run(&args, "");
            assert!(
                matches!(out.status.code(), Some(0 | 1)),
                "{f:?}: {}",
                stderr(&out)
            );
        }
        let statements = parse(&src).map_or(1, |p| p.statements.len() as u64);
        let (_, work) = work_of(&src, &ctx);
        // Each statement and each shown result has a budget of its own; the overshoot is at
        // most one operation under the term limit.
        assert!(
            work <= statements * 2 * (50_000 + 2 * 1_000 * 1_000),
            "{f:?}: {work} term operations for {statements} statements"
        );
        count += 1;
    }
    for f in files("tests/data/fuzz", "toml") {
        let mut args = small.to_vec();
        args.extend(["fk", f.to_str().unwrap()]);
        let out = run(&args, "");
        assert!(
            matches!(out.status.code(), Some(0 | 1)),
            "{f:?}: {}",
            stderr(&out)
        );
        count += 1;
    }
    assert!(count >= 2);
}

/// The command line's default limits are the presets of `Context`: `fk` switches to the
/// recurrence past `Preset::Fk`'s term limit (and says so), `run` refuses a scalar past
/// `Preset::Script`'s, and `--help` states both.
#[test]
fn command_line_defaults_are_the_context_presets() {
    use dqsym::Preset;
    let (fk, script) = (Preset::Fk.term_limit(), Preset::Script.term_limit());
    let help = crate::tools::dqsym_ok(&["--help"]);
    assert!(
        help.contains(&format!("[default: {script}, and {fk} for fk]")),
        "{help}"
    );
    let chain20 = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/chain20_symbolic.toml"
    );
    let out = crate::tools::dqsym_ok(&["fk", chain20]);
    assert!(
        out.contains(&format!("the expanded pose exceeds {fk} terms per entry")),
        "{out}"
    );
    // (x1 + ... + x8)^5 has C(12, 5) = 792 terms, ^6 has C(13, 6) = 1,716: the default limit
    // of scripts passes both, a limit of 1,000 (counted by the library) refuses the second.
    let sum = (1..=8)
        .map(|i| format!("x{i}"))
        .collect::<Vec<_>>()
        .join("+");
    let expr = format!("({sum})^6");
    let ctx = dqsym::Context::preset(Preset::Script);
    assert_eq!(ctx.term_limit(), script);
    assert_eq!(ctx.work_budget(), Preset::Script.work_budget());
    let big = {
        let _in = ctx.enter();
        dqsym::eval_scalar_text(&expr).expect("within the script preset")
    };
    assert_eq!(big.len(), 1716);
    let small = dqsym::Context::preset(Preset::Script).with_term_limit(1_000);
    let _in = small.enter();
    assert!(dqsym::eval_scalar_text(&expr).is_err());
}
