//! The external tools the emitter tests hand their output to: KaTeX (node), Python with SymPy
//! and NumPy, rustc and gcc. `scripts/test.sh` installs KaTeX and the Python venv when missing
//! and exports `DQSYM_PYTHON`; a missing tool fails the test with a message naming it, never
//! skips it.
#![allow(dead_code)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Runs `cmd` with `input` on stdin; returns stdout, or panics with stderr and `what`.
pub fn run(mut cmd: Command, input: &str, what: &str) -> String {
    let mut child = cmd
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("{what}: cannot start {cmd:?}: {e}"));
    // Write from a thread so a child that fills its stdout pipe cannot deadlock us.
    let mut stdin = child.stdin.take().expect("piped stdin");
    let input = input.to_string();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("child output");
    writer
        .join()
        .expect("stdin writer")
        .unwrap_or_else(|e| panic!("{what}: writing stdin: {e}"));
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr),
        String::from_utf8_lossy(&out.stdout)
    );
    String::from_utf8(out.stdout).expect("utf-8 output")
}

/// The Python interpreter with SymPy and NumPy: `$DQSYM_PYTHON` (set by scripts/test.sh to the
/// repository's .venv), else `python3`.
pub fn python() -> String {
    std::env::var("DQSYM_PYTHON").unwrap_or_else(|_| "python3".to_string())
}

/// Runs a Python script (given as `-c` text) with `input` on stdin. Fails with a clear message
/// when the interpreter lacks `module`.
pub fn run_python(script: &str, input: &str, module: &str) -> String {
    let py = python();
    let probe = Command::new(&py)
        .args(["-c", &format!("import {module}")])
        .output();
    let ok = probe.as_ref().is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "Python module `{module}` is missing for interpreter `{py}` \
         (DQSYM_PYTHON {}): run `bash scripts/test.sh`, which creates .venv with sympy and numpy",
        if std::env::var("DQSYM_PYTHON").is_ok() {
            "set"
        } else {
            "unset, fell back to python3"
        }
    );
    let mut cmd = Command::new(&py);
    cmd.args(["-c", script]);
    run(cmd, input, &format!("{py} ({module})"))
}

/// Renders `tex` with KaTeX in display mode, `throwOnError: true`; panics on any KaTeX error.
pub fn katex(tex: &str, what: &str) {
    assert!(
        Path::new(ROOT).join("node_modules/katex").is_dir(),
        "KaTeX is missing (node_modules/katex): run `bash scripts/test.sh`, which installs it with npm"
    );
    let script = "let s='';process.stdin.on('data',d=>s+=d);process.stdin.on('end',()=>{\
        try{require('katex').renderToString(s,{throwOnError:true,displayMode:true});}\
        catch(e){console.error(String(e));process.exit(1);}});";
    let mut cmd = Command::new("node");
    cmd.args(["-e", script]).current_dir(ROOT);
    run(cmd, tex, &format!("KaTeX on {what}"));
}

/// A fresh directory for one test's generated files, under target/.
pub fn temp_dir(name: &str) -> PathBuf {
    let base = option_env!("CARGO_TARGET_TMPDIR")
        .map(PathBuf::from)
        .unwrap_or_else(std::env::temp_dir);
    let dir = base.join(format!("dqsym-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Renders every formula of `formulas` with KaTeX in one node process, display mode,
/// `throwOnError: true`; panics naming the first formula KaTeX rejects.
pub fn katex_all(formulas: &[String], what: &str) {
    assert!(
        Path::new(ROOT).join("node_modules/katex").is_dir(),
        "KaTeX is missing (node_modules/katex): run `bash scripts/test.sh`, which installs it with npm"
    );
    let script = "let s='';process.stdin.on('data',d=>s+=d);process.stdin.on('end',()=>{\
        const k=require('katex');for(const f of JSON.parse(s)){\
        try{k.renderToString(f,{throwOnError:true,displayMode:true});}\
        catch(e){console.error(String(e)+'\\nin: '+f);process.exit(1);}}});";
    let json: Vec<String> = formulas.iter().map(|f| json_string(f)).collect();
    let mut cmd = Command::new("node");
    cmd.args(["-e", script]).current_dir(ROOT);
    run(
        cmd,
        &format!("[{}]", json.join(",")),
        &format!("KaTeX on {what}"),
    );
}

pub fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Runs the `dqsym` binary with `args`, asserts it exits 0 (showing stderr otherwise) and
/// returns its standard output.
pub fn dqsym_ok(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(args)
        .output()
        .expect("dqsym runs");
    assert_eq!(
        out.status.code(),
        Some(0),
        "dqsym {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 output")
}

/// Compiles the Rust program `src` into `exe` with `rustc -D warnings` (optimized when `opt`)
/// and lints it with `clippy-driver -D warnings`; `what` names it in failure messages.
pub fn compile_rust_clean(src: &Path, exe: &Path, opt: bool, what: &str) {
    let dir = src.parent().expect("a file in a directory");
    let mut rustc = Command::new("rustc");
    rustc.args(["--edition", "2021", "-D", "warnings"]);
    if opt {
        rustc.arg("-O");
    }
    rustc.arg("-o").arg(exe).arg(src);
    run(rustc, "", &format!("rustc -D warnings on {what}"));
    let mut clippy = Command::new("clippy-driver");
    clippy
        .args([
            "--edition",
            "2021",
            "-D",
            "warnings",
            "--emit=metadata",
            "--out-dir",
        ])
        .arg(dir)
        .arg(src);
    run(
        clippy,
        "",
        &format!(
            "clippy-driver -D warnings on {what} (install with `rustup component add clippy`)"
        ),
    );
}

/// Compiles the C99 program `src` into `exe` with `gcc -std=c99 -pedantic -Wall -Wextra
/// -Werror -O2 ... -lm`; `what` names it in failure messages.
pub fn compile_c_clean(src: &Path, exe: &Path, what: &str) {
    let mut gcc = Command::new("gcc");
    gcc.args([
        "-std=c99",
        "-pedantic",
        "-Wall",
        "-Wextra",
        "-Werror",
        "-O2",
        "-o",
    ])
    .arg(exe)
    .arg(src)
    .arg("-lm");
    run(gcc, "", what);
}

/// Debian's chromium on PATH, or a failure saying how to install it.
pub fn chromium() -> PathBuf {
    let found = std::env::var_os("PATH").and_then(|p| {
        std::env::split_paths(&p)
            .map(|d| d.join("chromium"))
            .find(|c| c.is_file())
    });
    found.unwrap_or_else(|| {
        panic!("chromium is missing: run `bash scripts/test.sh`, which installs Debian's chromium")
    })
}

/// A headless chromium with a fresh profile named after `out`, no network services.
pub fn headless(out: &Path) -> Command {
    let profile = crate::tools::temp_dir(&format!(
        "chromium-{}",
        out.file_name().and_then(|n| n.to_str()).unwrap_or("x")
    ));
    let mut c = Command::new(chromium());
    c.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-background-networking",
        "--no-first-run",
        "--disable-component-update",
        "--disable-sync",
    ])
    .arg(format!("--user-data-dir={}", profile.display()));
    c
}
