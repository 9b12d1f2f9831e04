//! A corpus of hostile inputs (tests/data/hostile), each run through the binary the way a user
//! would give it, with its whole answer snapshot-tested: `e/` one-liners (`dqsym -e TEXT`),
//! `run/` scripts (`dqsym run`), `repl/` sessions typed into the REPL, `robot/` robot files
//! (`dqsym fk`), `walk/` files (`dqsym walk`), `args/` command lines, `names/` robot files
//! with hostile names (`fk` in every format, `ik` in code for files named `ik_*`, `convert`
//! for URDF, `walk --markdown`, answers one after another). None may panic, print a
//! backtrace or end with a status other than 0, 1 or 2; every one ends under the default limits.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/hostile");

/// Runs the binary in `dir` with `args` and `stdin`; the answer as text for a snapshot.
fn answer(dir: &Path, args: &[String], stdin: &[u8]) -> String {
    let mut child = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(args)
        .current_dir(dir)
        .env("XDG_STATE_HOME", std::env::temp_dir())
        .env_remove("RUST_BACKTRACE")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    let mut input = child.stdin.take().expect("stdin");
    // A REPL that stops reading early is fine.
    let _ = input.write_all(stdin);
    drop(input);
    let out = child.wait_with_output().expect("finishes");
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    let code = out.status.code();
    assert!(
        matches!(code, Some(0..=2)),
        "{args:?}: status {code:?}\n{stderr}"
    );
    for bad in [
        "panicked",
        "RUST_BACKTRACE",
        "stack backtrace",
        "internal failure",
    ] {
        assert!(!stderr.contains(bad), "{args:?}: {bad}\n{stderr}");
    }
    // Long results are cut: the snapshot is about how the input is answered.
    let mut shown: Vec<&str> = stdout.lines().take(12).collect();
    let more = stdout.lines().count().saturating_sub(shown.len());
    let cut;
    if more > 0 {
        cut = format!("[{more} more lines]");
        shown.push(&cut);
    }
    let shown: Vec<String> = shown
        .iter()
        .map(|l| {
            if l.chars().count() > 200 {
                l.chars().take(200).collect::<String>() + " [cut]"
            } else {
                (*l).to_owned()
            }
        })
        .collect();
    format!(
        "status: {}\n--- stdout\n{}\n--- stderr\n{}",
        code.unwrap_or(-1),
        shown.join("\n"),
        stderr
    )
}

/// The commands a `names/` file is given: `fk` in every format, `walk --markdown`, `ik` in
/// code for `ik_*` files, `convert` for URDF files.
fn names_commands(file: &str) -> Vec<Vec<String>> {
    let mut v: Vec<Vec<String>> = ["plain", "latex", "sympy", "c", "rust", "python"]
        .iter()
        .map(|f| vec!["fk".into(), file.into(), "--format".into(), f.to_string()])
        .collect();
    v.push(vec!["walk".into(), file.into(), "--markdown".into()]);
    if file.starts_with("ik_") {
        for f in ["c", "python", "rust"] {
            v.push(vec!["ik".into(), file.into(), "--format".into(), f.into()]);
        }
    }
    if file.ends_with(".urdf") {
        v.push(vec!["convert".into(), file.into()]);
    }
    v
}

#[test]
fn hostile_inputs_get_clear_answers() {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"));
    settings.set_prepend_module_to_snapshot(false);
    let count = std::cell::Cell::new(0);
    settings.bind(|| {
        insta::glob!(DIR, "*/*", |path| {
            let kind = path
                .parent()
                .and_then(|p| p.file_name())
                .and_then(|n| n.to_str())
                .unwrap_or_default()
                .to_owned();
            let dir = path.parent().unwrap();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let bytes = std::fs::read(path).unwrap();
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let s = |x: &str| x.to_owned();
            if kind == "names" {
                let answers: Vec<String> = names_commands(&name)
                    .iter()
                    .map(|args| format!("=== dqsym {}\n{}", args.join(" "), answer(dir, args, &[])))
                    .collect();
                insta::assert_snapshot!(answers.join("\n"));
                count.set(count.get() + 1);
                return;
            }
            let (args, stdin): (Vec<String>, Vec<u8>) = match kind.as_str() {
                "e" => (vec![s("-e"), text.clone()], Vec::new()),
                "run" => (vec![s("run"), name], Vec::new()),
                "repl" => (Vec::new(), bytes),
                "robot" => (vec![s("fk"), name], Vec::new()),
                "walk" => (vec![s("walk"), name], Vec::new()),
                "args" => (text.split_whitespace().map(s).collect(), Vec::new()),
                other => panic!("unknown hostile kind {other}"),
            };
            insta::assert_snapshot!(answer(dir, &args, &stdin));
            count.set(count.get() + 1);
        });
    });
    assert!(count.get() >= 100, "{} hostile inputs", count.get());
}
