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

/// The REPL in a pseudo-terminal, as a user has it: rustyline in raw mode, Ctrl-C as the byte
/// 0x03 that the terminal turns into SIGINT.
struct Pty {
    child: std::process::Child,
    master: std::fs::File,
    out: std::sync::mpsc::Receiver<u8>,
    seen: String,
}

impl Pty {
    fn spawn(args: &[&str]) -> Pty {
        use std::os::fd::{FromRawFd, OwnedFd};
        use std::os::unix::process::CommandExt;
        let (mut master, mut slave) = (0, 0);
        // SAFETY: openpty writes two new descriptors into the given integers.
        let r = unsafe {
            libc::openpty(
                &mut master,
                &mut slave,
                std::ptr::null_mut(),
                std::ptr::null(),
                std::ptr::null(),
            )
        };
        assert_eq!(r, 0, "openpty");
        // SAFETY: both descriptors were just opened and are owned here.
        let (master, slave) =
            unsafe { (OwnedFd::from_raw_fd(master), OwnedFd::from_raw_fd(slave)) };
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_dqsym"));
        cmd.args(args)
            .env("XDG_STATE_HOME", std::env::temp_dir())
            .env("TERM", "xterm")
            .stdin(slave.try_clone().unwrap())
            .stdout(slave.try_clone().unwrap())
            .stderr(slave);
        // SAFETY: setsid and ioctl are async-signal-safe; the child gets its own session with
        // the pseudo-terminal as controlling terminal, so 0x03 becomes SIGINT for it.
        unsafe {
            cmd.pre_exec(|| {
                if libc::setsid() < 0 || libc::ioctl(0, libc::TIOCSCTTY, 0) < 0 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
        let child = cmd.spawn().expect("starts the REPL");
        let master = std::fs::File::from(master);
        let mut reader = master.try_clone().unwrap();
        let (tx, out) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            use std::io::Read;
            let mut buf = [0u8; 4096];
            while let Ok(n) = reader.read(&mut buf) {
                if n == 0 {
                    break;
                }
                for &b in &buf[..n] {
                    if tx.send(b).is_err() {
                        return;
                    }
                }
            }
        });
        Pty {
            child,
            master,
            out,
            seen: String::new(),
        }
    }

    fn send(&mut self, bytes: &[u8]) {
        use std::io::Write;
        self.master.write_all(bytes).unwrap();
        self.master.flush().unwrap();
    }

    /// Reads until `text` has appeared since the last call; fails after two minutes, which
    /// only a broken REPL takes.
    fn expect(&mut self, text: &str) {
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
        loop {
            if let Some(i) = self.seen.find(text) {
                self.seen.drain(..i + text.len());
                return;
            }
            let left = deadline.saturating_duration_since(std::time::Instant::now());
            match self.out.recv_timeout(left) {
                Ok(b) => self.seen.push(char::from(b)),
                Err(_) => panic!("no `{text}` from the REPL; it printed:\n{}", self.seen),
            }
        }
    }

    fn pid(&self) -> u32 {
        self.child.id()
    }
}

impl Drop for Pty {
    /// A failed test must not leave its REPL computing.
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The threads of process `pid`.
fn threads_of(pid: u32) -> usize {
    std::fs::read_dir(format!("/proc/{pid}/task"))
        .map(|d| d.count())
        .unwrap_or(0)
}

/// The resident memory of process `pid`, in kilobytes.
fn rss_kb(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap_or(0)
}

/// Reads `/proc` until `done` holds or `bound` has passed (no sleeping: the state is read again
/// at once); the caller asserts what it waited for.
fn wait_for_at_most(bound: std::time::Duration, mut done: impl FnMut() -> bool) {
    let deadline = std::time::Instant::now() + bound;
    while !done() && std::time::Instant::now() < deadline {
        std::thread::yield_now();
    }
}

/// Looks at `/proc` until `done` holds (no sleeping: the state is read again at once), for at
/// most two minutes, which only a broken REPL takes.
fn wait_for(what: &str, mut done: impl FnMut() -> bool) {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while !done() {
        assert!(
            std::time::Instant::now() < deadline,
            "{what} never happened"
        );
        std::thread::yield_now();
    }
}

#[test]
fn ctrl_c_stops_the_computation_and_keeps_the_bindings() {
    let mut repl = Pty::spawn(&["--term-limit", "10000000", "--work-budget", "100000000000"]);
    repl.expect("dq> ");
    repl.send(b"a = 5\r");
    repl.expect("a = 5");
    repl.send(b"syms x y z\r");
    repl.expect("dq> ");
    let pid = repl.pid();
    let (threads, rss) = (threads_of(pid), rss_kb(pid));
    // 20,301 terms with coefficients of up to 95 digits, then their closed form: some 15 s
    // of release CPU since powers of sums are expanded term by term (`(x + y + z)^100`, the
    // case before, took 1.8 s in a debug build: too close to the interrupt); the interrupt
    // comes once it holds 32 MB more than before.
    repl.send(b"(x + y + z)^200\r");
    wait_for("the computation's memory", || rss_kb(pid) > rss + 32 * 1024);
    let peak = rss_kb(pid);
    let start = std::time::Instant::now();
    repl.send(b"\x03");
    repl.expect("interrupted; the bindings are unchanged");
    let latency = start.elapsed();
    // The REPL joins the worker before it answers: no thread of the computation is left.
    wait_for("the worker's exit", || threads_of(pid) <= threads);
    // And its memory is handed back (the REPL trims the allocator before it answers; the
    // kernel's count is read until it agrees): back within 4 MB of what the REPL held
    // before the computation, from 32 MB or more above it.
    let mut after = rss_kb(pid);
    wait_for_at_most(std::time::Duration::from_secs(10), || {
        after = rss_kb(pid);
        after <= rss + 4 * 1024
    });
    eprintln!(
        "Ctrl-C: answered after {latency:?}; memory {rss} kB before, at least {peak} kB at \
         the interrupt, {after} kB after"
    );
    assert!(
        after <= rss + 4 * 1024,
        "the computation's memory was not returned: {rss} kB before, {peak} kB at the \
         interrupt, {after} kB after"
    );
    repl.send(b"b = a + 1\r");
    repl.expect("b = 6");
    repl.send(b":vars\r");
    repl.expect("x: symbol");
    let later = rss_kb(pid);
    assert!(
        later <= rss + 4 * 1024,
        "memory grows again after the interrupt: {rss} kB before, {later} kB later"
    );
    repl.send(b":quit\r");
    let status = repl.child.wait().expect("exits");
    assert_eq!(status.code(), Some(0));
}

#[test]
fn pasted_lines_run_one_by_one_with_or_without_bracketed_paste() {
    let mut repl = Pty::spawn(&[]);
    repl.expect("dq> ");
    // Bracketed paste: one input holding several lines, one of them continued.
    repl.send(b"\x1b[200~syms l1 l2\ra = (l1 +\r l2)\rb = 2*a\r\x1b[201~\r");
    repl.expect("b = 2 (l1 + l2)");
    // Typed ahead without bracketed paste: every line arrives before the first result.
    repl.send(b"c = b + 1\rd = c + 1\re = d + 1\r");
    repl.expect("e = 3 + 2 l1 + 2 l2");
    repl.send(b":quit\r");
    assert_eq!(repl.child.wait().expect("exits").code(), Some(0));
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
        ("geometric", "Jg", 6),
        ("geometric_body", "Jb", 6),
        ("geometric_derivative", "Jgdot", 6),
        ("line:0,1,0", "Jl", 8),
        ("plane", "Jpi", 8),
        ("distance", "Jd", 1),
        ("pose_derivative", "Jdot", 8),
        ("rotation_derivative", "Jrdot", 4),
        ("translation_derivative", "Jtdot", 4),
        ("line_derivative:0,1,0", "Jldot", 8),
        ("plane_derivative", "Jpidot", 8),
        ("distance_derivative", "Jddot", 1),
        ("line_to_point:1,0,0,1/2,1/3,0", "Jd", 1),
        ("plane_to_point:1/2,1/3,0", "Jd", 1),
        ("line_to_line_angle:0,3/5,4/5,1/2,0,0", "Jd", 1),
        ("point_to_line_derivative:0,3/5,4/5,1/2,0,0", "Jddot", 1),
    ] {
        for format in ["plain", "sympy", "latex", "rust", "c", "python"] {
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
    // The line-to-line distance Jacobian is a quotient: its numerators over one denominator,
    // built from b = D(l . lz), a = |P(l x lz)|^2 and their gradients (intermediate entries).
    let out = run(&[
        "--format",
        "sympy",
        "fk",
        &file,
        "--jacobian=line_to_line:0,3/5,4/5,1/2,0,0",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("utf-8");
    for (prefix, count) in [
        ("Jd_b[", 4),
        ("Jd_a[", 4),
        ("Jd_num[0][", 3),
        ("Jd_den =", 1),
    ] {
        let n = text.lines().filter(|l| l.starts_with(prefix)).count();
        assert_eq!(n, count, "{prefix}: {text}");
    }
    let out = run(&[
        "--format",
        "rust",
        "fk",
        &file,
        "--jacobian=line_to_line:0,3/5,4/5,1/2,0,0",
    ]);
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(
        text.contains("pub jd_num: [f64; 3]") && text.contains("pub jd_den: f64"),
        "{text}"
    );
    for (kind, message) in [
        ("line_to_line:1,0,0", "needs 6 or 9 numbers"),
        (
            "line_to_line_derivative:0,0,1,1,0,0",
            "no derivative of the line-to-line",
        ),
        ("pose_derivative_derivative", "joint accelerations"),
        ("plane_to_point", "needs `:"),
    ] {
        let bad = run(&["fk", &file, &format!("--jacobian={kind}")]);
        assert_eq!(bad.status.code(), Some(1), "{kind}");
        let err = String::from_utf8_lossy(&bad.stderr);
        assert!(err.contains(message), "{kind}: {err}");
    }
    let bad = run(&["fk", &file, "--jacobian=point_to_plane:1,0"]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("needs 6 numbers"));
    let bad = run(&["fk", &file, "--jacobian=speed"]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("unknown Jacobian `speed`"));
}

/// Writing into a pipe whose reader is gone ends the process as it ends `cat`: by SIGPIPE,
/// with nothing on stderr (no panic, no "internal failure"). The read end is closed before the
/// binary starts, so its first write meets the closed pipe.
#[test]
fn output_into_a_closed_pipe_ends_quietly() {
    use std::os::fd::{FromRawFd, OwnedFd};
    use std::os::unix::process::ExitStatusExt;
    let rrr = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/rrr.toml");
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/appendix3_rrr.dq");
    for args in [
        vec!["fk", rrr, "--jacobian"],
        vec!["run", script],
        vec!["-e", "(x + y)^3"],
    ] {
        let mut fds = [0; 2];
        // SAFETY: pipe writes two new descriptors into the array.
        assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0, "pipe");
        // SAFETY: both descriptors were just opened and are owned here.
        let (read, write) = unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) };
        drop(read);
        let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
            .args(&args)
            .stdout(write)
            .output()
            .expect("runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.signal(),
            Some(libc::SIGPIPE),
            "{args:?}: {:?}\n{stderr}",
            out.status
        );
        assert!(stderr.is_empty(), "{args:?} wrote to stderr:\n{stderr}");
    }
}

/// `ops` works on every robot file `fk` accepts: the examples (`fk` runs on each of them in
/// `every_example_prints_byte_identical_output_twice`) and the generic 6R chain whose fully
/// symbolic links once failed with "symbol 'alpha1' is not an argument".
#[test]
fn ops_works_on_every_robot_file_fk_accepts() {
    let root = env!("CARGO_MANIFEST_DIR");
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(format!("{root}/examples/robots"))
        .expect("a directory")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml" || x == "urdf"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "{files:?}");
    files.push(format!("{root}/tests/data/generic_6r.toml").into());
    for f in &files {
        let ops = Command::new(env!("CARGO_BIN_EXE_dqsym"))
            .args([std::ffi::OsStr::new("ops"), f.as_os_str()])
            .output()
            .expect("runs");
        let text = String::from_utf8_lossy(&ops.stdout);
        assert!(
            ops.status.success(),
            "ops {f:?}: {}",
            String::from_utf8_lossy(&ops.stderr)
        );
        assert!(
            text.contains("generated code, all outputs:"),
            "{f:?}: {text}"
        );
    }
}

/// `--format c` and `--format python` on the command line for `-e`, `run` and `fk`: the C is
/// compiled with gcc -Werror and run, the Python run with NumPy, and both agree with the
/// planar formulas computed here at a random point.
#[test]
fn formats_c_and_python_on_the_command_line_compute_the_pose() {
    let dir = crate::tools::temp_dir("cli_formats");
    let script = dir.join("p.dq");
    std::fs::write(
        &script,
        "syms theta1 l\np = transform(rot((0, 0, 1), theta1), (l, 0, 0))\n",
    )
    .unwrap();
    let planar2r = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/planar2r.toml");
    let (t1, t2, l1, l2): (f64, f64, f64, f64) = (0.7137, -1.2214, 0.43, 0.91);
    // The point (l, 0, 0) turned by theta1 about z; the planar 2R pose's first two rows.
    let point = [l1 * t1.cos(), l1 * t1.sin(), 0.0];
    let (c1, s1, c12, s12) = (t1.cos(), t1.sin(), (t1 + t2).cos(), (t1 + t2).sin());
    let pose = [
        [c12, -s12, 0.0, l1 * c1 + l2 * c12],
        [s12, c12, 0.0, l1 * s1 + l2 * s12],
        [0.0, 0.0, 1.0, 0.0],
    ];
    let expected_pose: Vec<f64> = pose.iter().flatten().copied().collect();
    let script_s = script.to_str().unwrap();
    let cases: [(&[&str], &str, &str, Vec<f64>); 3] = [
        (
            &["-e", "transform(rot((0, 0, 1), theta1), (l, 0, 0))"],
            "value",
            "value",
            point.to_vec(),
        ),
        (&["run", script_s], "p", "p", point.to_vec()),
        (&["fk", planar2r], "planar_2r_fk", "t", expected_pose),
    ];
    let close = |got: &[f64], want: &[f64], what: &str| {
        assert_eq!(got.len(), want.len(), "{what}: {got:?}");
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{what}: {got:?}, expected {want:?}");
        }
    };
    for (k, (args, function, output, want)) in cases.iter().enumerate() {
        let with = |format: &str| {
            let mut a = args.to_vec();
            a.extend(["--format", format]);
            crate::tools::dqsym_ok(&a)
        };
        // Python: the arguments by name (the order is the function's own).
        let code = with("python");
        let call = format!(
            "import numpy as np, sys\n{code}\nv = dict(theta1={t1}, theta2={t2}, l={l1}, \
             l1={l1}, l2={l2})\nimport inspect\nargs = [v[a] for a in \
             inspect.signature({function}).parameters]\nprint(' '.join(repr(float(x)) for x in \
             np.asarray({function}(*args)['{output}']).ravel()))\n"
        );
        let got: Vec<f64> = crate::tools::run_python(&call, "", "numpy")
            .split_whitespace()
            .map(|x| x.parse().expect("a number"))
            .collect();
        close(&got, want, &format!("{args:?} --format python"));
        // C: the function's signature names its arguments; a main calls it and prints the
        // output array.
        let code = with("c");
        let sig = code
            .lines()
            .find(|l| l.starts_with("void ") && l.contains(&format!("{function}(")))
            .expect("the C function")
            .to_owned();
        let params = &sig[sig.find('(').unwrap() + 1..sig.rfind(')').unwrap()];
        let mut decls = String::new();
        let mut call = Vec::new();
        for p in params.split(", ") {
            let name = p.trim_start_matches("double ");
            let bare = name.split('[').next().unwrap();
            if let Some(dims) = name.find('[').map(|i| &name[i..]) {
                decls += &format!("    double o_{bare}{dims};\n");
            }
            call.push(match bare {
                "theta1" => t1.to_string(),
                "theta2" => t2.to_string(),
                "l" | "l1" => l1.to_string(),
                "l2" => l2.to_string(),
                other => format!("o_{other}"),
            });
        }
        let n = want.len();
        let src = dir.join(format!("f{k}.c"));
        std::fs::write(
            &src,
            format!(
                "#include <stdio.h>\n{code}\nint main(void)\n{{\n{decls}    {function}({});\n    \
                 const double *o = (const double *)o_{output};\n    for (int i = 0; i < {n}; i++) \
                 printf(\"%.17g \", o[i]);\n    return 0;\n}}\n",
                call.join(", ")
            ),
        )
        .unwrap();
        let exe = dir.join(format!("f{k}"));
        let mut gcc = Command::new("gcc");
        gcc.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-o"])
            .arg(&exe)
            .arg(&src)
            .arg("-lm");
        crate::tools::run(gcc, "", &format!("gcc -Werror on {}", src.display()));
        let got: Vec<f64> = crate::tools::run(Command::new(&exe), "", "the compiled function")
            .split_whitespace()
            .map(|x| x.parse().expect("a number"))
            .collect();
        close(&got, want, &format!("{args:?} --format c"));
    }
}
