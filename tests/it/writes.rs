//! Output and input files (hostile round 3, rows 8, 21-24): a write error on stdout ends every
//! command with `error: cannot write output: ...` and status 1, never a panic; a full stderr
//! keeps the error status; input files have a size cap; `walk --html` never writes over its
//! input or over a file it did not write (unless `--force`); the drawing never holds NaN; a
//! worker thread that cannot get its stack says so.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_dqsym");
const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs the binary in `dir` with `args`, stdin from `input`, stdout into `stdout`.
fn run_into(dir: &Path, args: &[&str], input: &str, stdout: Stdio) -> Output {
    use std::io::Write;
    let mut child = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .env("XDG_STATE_HOME", std::env::temp_dir())
        .env_remove("RUST_BACKTRACE")
        .stdin(Stdio::piped())
        .stdout(stdout)
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    let mut i = child.stdin.take().expect("stdin");
    let _ = i.write_all(input.as_bytes());
    drop(i);
    child.wait_with_output().expect("finishes")
}

fn dev_full() -> Stdio {
    Stdio::from(
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full opens"),
    )
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("dqsym-writes-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch dir");
    d
}

/// A two-joint URDF (the planar 2R arm), for `convert` and URDF `fk`.
const URDF_2R: &str = r#"<robot name="r2"><link name="a"/><link name="b"/><link name="c"/>
<joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
<joint name="j2" type="revolute"><parent link="b"/><child link="c"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/></joint>
</robot>"#;

#[test]
fn every_command_ends_a_full_disk_with_one_message_and_status_1() {
    let dir = scratch("full");
    std::fs::write(dir.join("r2.urdf"), URDF_2R).expect("writes");
    let puma = format!("{ROOT}/examples/robots/puma560.toml");
    let rrr = format!("{ROOT}/examples/robots/rrr.toml");
    let script = format!("{ROOT}/examples/appendix3_rrr.dq");
    let mut cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["-e".into(), "x + 1".into()], ""),
        (vec!["run".into(), script.clone()], ""),
        (vec![], "syms x\ny = (x + 1)^2\n"),
        (vec!["walk".into(), rrr.clone()], ""),
        (vec!["walk".into(), rrr.clone(), "--markdown".into()], ""),
        (vec!["walk".into(), script], ""),
        (vec!["ik".into(), puma.clone()], ""),
        (vec!["convert".into(), "r2.urdf".into()], ""),
        (vec!["fk".into(), "r2.urdf".into()], ""),
        (vec!["ops".into()], ""),
        (vec!["ops".into(), rrr.clone()], ""),
        (vec!["paper".into()], ""),
        // clap's help and version texts (once written with the write's failure ignored: 0).
        (vec!["--help".into()], ""),
        (vec!["fk".into(), "--help".into()], ""),
        (vec!["--version".into()], ""),
    ];
    for format in ["plain", "latex", "sympy", "rust", "c", "python"] {
        cases.push((
            vec![
                "fk".into(),
                rrr.clone(),
                "--jacobian".into(),
                "--format".into(),
                format.into(),
            ],
            "",
        ));
    }
    for (args, input) in &cases {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_into(&dir, &a, input, dev_full());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert_eq!(
            err.trim_end(),
            "error: cannot write output: No space left on device",
            "{args:?}"
        );
    }
}

#[test]
fn a_full_stderr_keeps_the_error_status_and_never_panics() {
    let dir = scratch("stderr");
    for (args, code) in [
        (vec!["-e", "1/0"], 1),
        (vec!["-e", "(x + 1)^2"], 0),
        (vec!["run", "missing.dq"], 1),
    ] {
        let out = Command::new(BIN)
            .args(&args)
            .current_dir(&dir)
            .env_remove("RUST_BACKTRACE")
            .stdout(Stdio::null())
            .stderr(dev_full())
            .output()
            .expect("runs");
        assert_eq!(out.status.code(), Some(code), "{args:?}");
    }
}

#[test]
fn input_files_past_the_size_limit_are_refused_before_they_are_read() {
    let dir = scratch("size");
    // A device never ends: the error comes after the limit's worth of bytes.
    for cmd in ["run", "fk", "walk"] {
        let out = run_into(&dir, &[cmd, "/dev/zero"], "", Stdio::piped());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{cmd}: {err}");
        assert!(
            err.contains("larger than the input size limit of 16777216 bytes (--max-input-size)"),
            "{cmd}: {err}"
        );
    }
    // The limit is exact: a script of n bytes runs under --max-input-size n, not n - 1; and
    // so at ten times the default size (a 160 MB file is not written: the size is what the
    // limit compares).
    let script = "x = 6 * 7\n";
    std::fs::write(dir.join("s.dq"), script).expect("writes");
    let n = script.len();
    let ok = run_into(
        &dir,
        &["run", "s.dq", "--max-input-size", &n.to_string()],
        "",
        Stdio::piped(),
    );
    assert_eq!(String::from_utf8_lossy(&ok.stdout), "x = 42\n");
    let over = run_into(
        &dir,
        &["run", "s.dq", "--max-input-size", &(n - 1).to_string()],
        "",
        Stdio::piped(),
    );
    assert!(stderr(&over).contains(&format!(
        "s.dq: larger than the input size limit of {} bytes (--max-input-size)",
        n - 1
    )));
    let big = run_into(
        &dir,
        &["run", "/dev/zero", "--max-input-size", "167772160"],
        "",
        Stdio::piped(),
    );
    assert!(stderr(&big).contains("limit of 167772160 bytes"));
}

#[test]
fn a_worker_stack_that_cannot_be_had_is_named_as_the_cause() {
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v 250000; exec {BIN} -e '1+1'"))
        .output()
        .expect("sh runs");
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("cannot start the evaluation thread with its 256 MB stack")
            && err.contains("ulimit -v"),
        "{err}"
    );
}

/// `walk ROBOT --html OUT` in `dir`, with `extra` options.
fn walk_html(dir: &Path, out: &str, extra: &[&str]) -> Output {
    let mut args = vec!["walk", "p.toml", "--html", out];
    args.extend_from_slice(extra);
    let mut cmd = Command::new(BIN);
    cmd.args(&args).current_dir(dir);
    // KaTeX is looked for in the current directory, then in the source tree.
    cmd.output().expect("runs")
}

#[test]
fn walk_html_never_writes_over_its_input_or_a_file_it_did_not_write() {
    let dir = scratch("html");
    let robot =
        std::fs::read_to_string(format!("{ROOT}/examples/robots/planar2r.toml")).expect("reads");
    std::fs::write(dir.join("p.toml"), &robot).expect("writes");
    std::os::unix::fs::symlink("p.toml", dir.join("link.html")).expect("symlink");
    std::fs::hard_link(dir.join("p.toml"), dir.join("hard.html")).expect("hard link");
    // The input under every name, even with --force.
    for out in ["p.toml", "./p.toml", "link.html", "hard.html"] {
        for force in [&[][..], &["--force"][..]] {
            let o = walk_html(&dir, out, force);
            assert_eq!(o.status.code(), Some(1), "{out}");
            assert!(
                stderr(&o).contains("is the input file"),
                "{out}: {}",
                stderr(&o)
            );
        }
    }
    assert_eq!(
        std::fs::read_to_string(dir.join("p.toml")).expect("reads"),
        robot
    );
    // A file it did not write: refused, then written with --force.
    std::fs::write(dir.join("notes.html"), "my notes\n").expect("writes");
    let o = walk_html(&dir, "notes.html", &[]);
    assert!(stderr(&o).contains("exists and is not a page dqsym wrote; pass --force"));
    assert_eq!(
        std::fs::read_to_string(dir.join("notes.html")).expect("reads"),
        "my notes\n"
    );
    let o = walk_html(&dir, "notes.html", &["--force"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let page = std::fs::read_to_string(dir.join("notes.html")).expect("reads");
    assert!(dqsym::walk::is_walk_page(&page));
    // A page it wrote: written again without --force, through a link to it too (the link
    // stays a link).
    let o = walk_html(&dir, "notes.html", &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    std::os::unix::fs::symlink("notes.html", dir.join("page.html")).expect("symlink");
    let o = walk_html(&dir, "page.html", &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(dir.join("page.html"))
        .expect("exists")
        .file_type()
        .is_symlink());
    // A dangling link: refused without --force.
    std::os::unix::fs::symlink("nowhere.html", dir.join("dangling.html")).expect("symlink");
    let o = walk_html(&dir, "dangling.html", &[]);
    assert!(stderr(&o).contains("does not exist; pass --force"));
    // A full disk: an error, status 1, and no temporary file left behind.
    let o = walk_html(&dir, "/dev/full", &[]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("cannot write /dev/full: No space left on device"));
    let left: Vec<String> = std::fs::read_dir(&dir)
        .expect("lists")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn huge_values_never_put_nan_into_the_drawing() {
    let dir = scratch("nan");
    std::fs::copy(
        format!("{ROOT}/examples/robots/planar2r.toml"),
        dir.join("p.toml"),
    )
    .expect("copies");
    // Past the range where coordinates stay finite: a clear error naming the value.
    for v in ["-1e308", "1e300", "1.7e308"] {
        let o = walk_html(&dir, "p.html", &["--config", &format!("l1={v}")]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{v}: {err}");
        assert!(
            err.contains("the mechanism cannot be drawn") && err.contains("l1 = "),
            "{v}: {err}"
        );
    }
    // Large but drawable: finite coordinates everywhere.
    for v in ["1e100", "-1e12", "3"] {
        let o = walk_html(&dir, "p.html", &["--config", &format!("l1={v}")]);
        assert_eq!(o.status.code(), Some(0), "{v}: {}", stderr(&o));
        let page = std::fs::read_to_string(dir.join("p.html")).expect("reads");
        let start = page.find("<svg").expect("a drawing");
        let svg = &page[start..start + page[start..].find("</svg>").expect("its end")];
        assert!(!svg.contains("NaN") && !svg.contains("inf"), "{v}: {svg}");
    }
}

/// A URDF chain too long to walk product by product (2,000 collinear joints: one angle of
/// 2,000 symbols) ends with the limit's error naming the file and the limit's option, also
/// with the angle limit at 10x its default (then the work budget ends it).
#[test]
fn walk_of_a_urdf_past_a_limit_names_the_file() {
    let dir = scratch("walk_limit");
    let n = 2000;
    let mut urdf = String::from("<robot name=\"r\">");
    for i in 0..=n {
        urdf.push_str(&format!("<link name=\"l{i}\"/>"));
    }
    for i in 0..n {
        urdf.push_str(&format!(
            "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/>\
             <child link=\"l{}\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"0 0 1\"/></joint>",
            i + 1
        ));
    }
    urdf.push_str("</robot>");
    std::fs::write(dir.join("chain.urdf"), urdf).expect("writes");
    for extra in [
        &[][..],
        &["--max-angle-symbols", "10000"][..],
        &["--markdown"][..],
    ] {
        let mut args = vec!["walk", "chain.urdf"];
        args.extend_from_slice(extra);
        let out = run_into(&dir, &args, "", Stdio::piped());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.starts_with("error: chain.urdf: ")
                && (err.contains("--max-angle-symbols") || err.contains("--work-budget")),
            "{args:?}: {err}"
        );
    }
}
