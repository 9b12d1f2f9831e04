//! Names never become code: generated families over every name of each language's table of
//! reserved names (used as a symbol, an output, a function, a robot's joint variable and
//! parameter), compiled with `gcc -std=c99 -Wall -Wextra -Werror`, `rustc -D warnings`, run in
//! Python with NumPy and read back by `sympy.sympify`, each value checked at random points
//! against dqsym's own f64 evaluation or an independent DH product; and every comment syntax
//! given hostile robot names (`*/`, `"""`, newlines, `\input`, control characters, code
//! fences), the generated code compiled and checked to hold no code but its own. Each family
//! is one compilation or one Python process.

use crate::tools::{compile_rust_clean, run, run_python, temp_dir};
use dqsym::emit::names::{reserved_names, Lang};
use dqsym::emit::{c_function, python_function, rust_function, sympy, CodegenOptions, Output};
use dqsym::{closed_form, eval_scalar_text, fk_report, parse_robot, FkOptions, Format, Scalar};
use std::process::Command;

/// Deterministic pseudo-random values in [-1.5, 1.5] (a 64-bit LCG).
fn values(seed: u64, n: usize) -> Vec<f64> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 3.0 - 1.5
        })
        .collect()
}

/// A value in the symbol `name` and `x` that reads `name` in a product, a power and an angle.
fn expr_of(name: &str) -> Scalar {
    let (n, x) = (Scalar::sym(name), Scalar::sym("x"));
    n.clone() * (n.clone() + x.clone()).cos() + x * n.pow(2) + Scalar::int(3)
}

/// `value` at `name = a`, `x = b` by dqsym's own f64 evaluation.
fn oracle(name: &str, a: f64, b: f64) -> f64 {
    expr_of(name)
        .eval_at(&[(name, a), ("x", b)])
        .expect("f64 value")
}

/// The name after `marker` up to `(`: the generated function's name.
fn fn_name(code: &str, marker: &str) -> String {
    let line = code
        .lines()
        .find_map(|l| l.strip_prefix(marker))
        .unwrap_or_else(|| panic!("no `{marker}` line in\n{code}"));
    line.split('(').next().unwrap().trim().to_owned()
}

fn close(what: &str, got: f64, want: f64) {
    // The generated code and the oracle evaluate the same few operations in another order:
    // a few ulps of the largest intermediate (|name|^2 |x| <= 3.4, plus 3) suffice.
    assert!(
        (got - want).abs() <= 1e-12 * (1.0 + want.abs()),
        "{what}: generated {got}, dqsym {want}"
    );
}

/// Every C-reserved name (keywords, every `<math.h>` name) as a symbol, an output and the
/// function's name: one C file, compiled with -Werror and run.
#[test]
fn c_reserved_names_are_renamed_compile_and_match_eval() {
    let names = reserved_names(Lang::C);
    assert!(names.len() > 200, "{} C names", names.len());
    let o = CodegenOptions::default();
    let mut src = String::new();
    let mut calls = String::new();
    let pts = values(11, 2 * names.len());
    for (i, n) in names.iter().enumerate() {
        let out = Output::scalar(n, "value", closed_form(&expr_of(n)).unwrap());
        let code = c_function(n, "doc", &[out], &[n.clone(), "x".into()], &o).unwrap();
        let f = fn_name(&code, "void ");
        assert_ne!(&f, n, "{n} kept as the function's name");
        src.push_str(&code);
        calls.push_str(&format!(
            "    {{ double v; {f}({:?}, {:?}, &v); printf(\"%.17g\\n\", v); }}\n",
            pts[2 * i],
            pts[2 * i + 1]
        ));
    }
    src.push_str(&format!(
        "#include <stdio.h>\nint main(void)\n{{\n{calls}    return 0;\n}}\n"
    ));
    let out = compile_and_run_c("reserved", &src);
    let got: Vec<f64> = out.lines().map(|l| l.parse().unwrap()).collect();
    assert_eq!(got.len(), names.len());
    for (i, n) in names.iter().enumerate() {
        close(n, got[i], oracle(n, pts[2 * i], pts[2 * i + 1]));
    }
}

/// Runs a Python program too long for `-c` from a file, `input` on stdin.
fn run_py_file(tag: &str, script: &str, input: &str) -> String {
    run_python("", "", "numpy");
    let file = temp_dir(&format!("names_py_{tag}")).join("gen.py");
    std::fs::write(&file, script).unwrap();
    let mut cmd = Command::new(crate::tools::python());
    cmd.arg(&file);
    run(cmd, input, &format!("python {}", file.display()))
}

fn compile_and_run_c(tag: &str, src: &str) -> String {
    let dir = temp_dir(&format!("names_c_{tag}"));
    let (file, exe) = (dir.join("gen.c"), dir.join("gen"));
    std::fs::write(&file, src).unwrap();
    let mut gcc = Command::new("gcc");
    gcc.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-o"])
        .arg(&exe)
        .arg(&file)
        .arg("-lm");
    run(gcc, "", &format!("gcc -Werror on {}", file.display()));
    run(Command::new(&exe), "", "the compiled C program")
}

/// Every Python-reserved name (keywords, builtins, `np`, `shape`) as a symbol and the
/// function's name: one module, run with NumPy arrays (a symbol `shape` once overwrote the
/// broadcast shape).
#[test]
fn python_reserved_names_are_renamed_and_match_eval_on_arrays() {
    let names = reserved_names(Lang::Python);
    assert!(names.len() > 100, "{} Python names", names.len());
    let o = CodegenOptions::default();
    let mut module = String::new();
    let mut calls = Vec::new();
    let pts = values(12, 6 * names.len());
    for (i, n) in names.iter().enumerate() {
        let out = Output::scalar(n, "value", closed_form(&expr_of(n)).unwrap());
        let code = python_function(n, "doc", &[out], &[n.clone(), "x".into()], &o).unwrap();
        let f = fn_name(&code, "def ");
        assert_ne!(&f, n, "{n} kept as the function's name");
        module.push_str(&code);
        module.push('\n');
        let (a, b) = (&pts[6 * i..6 * i + 3], &pts[6 * i + 3..6 * i + 6]);
        calls.push(format!(
            "print(' '.join(repr(float(v)) for v in {f}(np.array({a:?}), np.array({b:?}))[{n:?}]))"
        ));
    }
    let script = format!("{module}\n{}\n", calls.join("\n"));
    let out = run_py_file("reserved", &script, "");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), names.len());
    for (i, n) in names.iter().enumerate() {
        let got: Vec<f64> = lines[i].split(' ').map(|v| v.parse().unwrap()).collect();
        for k in 0..3 {
            close(n, got[k], oracle(n, pts[6 * i + k], pts[6 * i + 3 + k]));
        }
    }
}

/// Every Rust-reserved name (keywords strict and reserved, `None`, `std`, `f64`) as a symbol
/// and a field: one crate, compiled with -D warnings and run.
#[test]
fn rust_reserved_names_are_renamed_compile_clean_and_match_eval() {
    let names = reserved_names(Lang::Rust);
    assert!(names.len() > 50, "{} Rust names", names.len());
    let o = CodegenOptions::default();
    let mut src = String::new();
    let mut calls = String::new();
    let pts = values(13, 2 * names.len());
    for (i, n) in names.iter().enumerate() {
        // Fields are snake case: an output is named as `show` names it, lowercase.
        let field = n.to_lowercase();
        let out = Output::scalar(&field, "value", closed_form(&expr_of(n)).unwrap());
        let f = format!("f{i}");
        let code = rust_function(&f, "doc", &[out], &[n.clone(), "x".into()], &o).unwrap();
        src.push_str(&code);
        src.push('\n');
        calls.push_str(&format!(
            "    println!(\"{{:?}}\", {f}({:?}, {:?}));\n",
            pts[2 * i],
            pts[2 * i + 1]
        ));
    }
    src.push_str(&format!("fn main() {{\n{calls}}}\n"));
    let dir = temp_dir("names_rust");
    let (file, exe) = (dir.join("gen.rs"), dir.join("gen"));
    std::fs::write(&file, &src).unwrap();
    compile_rust_clean(&file, &exe, false, "reserved Rust names");
    let out = run(Command::new(&exe), "", "the compiled Rust program");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), names.len());
    for (i, n) in names.iter().enumerate() {
        // `F3 { fn_: 1.25 }`
        let v = lines[i].rsplit(": ").next().unwrap().trim_end_matches(" }");
        close(n, v.parse().unwrap(), oracle(n, pts[2 * i], pts[2 * i + 1]));
    }
}

/// Every name `sympify` reads as something else (SymPy's namespace, Python's keywords and
/// builtins) as a symbol: plain `sympify` reads the text back to the same value. `pi` is the
/// constant in dqsym too.
#[test]
fn sympy_names_read_back_by_plain_sympify_as_symbols() {
    // The table, and every name the installed SymPy binds (a newer SymPy's new names too).
    let live = run_python(
        "import keyword, sympy\ng = {}\nexec('from sympy import *', g)\n\
         print('\\n'.join(sorted(set(g) | set(keyword.kwlist))))",
        "",
        "sympy",
    );
    let mut names: Vec<String> = reserved_names(Lang::Sympy)
        .into_iter()
        .chain(live.lines().map(str::to_owned))
        .filter(|n| n != "pi" && n != "x")
        .filter(|n| n.starts_with(|c: char| c.is_ascii_alphabetic()))
        .filter(|n| n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
        .collect();
    names.sort();
    names.dedup();
    assert!(names.len() > 900, "{} SymPy names", names.len());
    let pts = values(14, 2 * names.len());
    let mut input = String::new();
    for (i, n) in names.iter().enumerate() {
        let text = sympy(&closed_form(&expr_of(n)).unwrap());
        input.push_str(&format!(
            "{n}\t{}\t{}\t{text}\n",
            pts[2 * i],
            pts[2 * i + 1]
        ));
    }
    let script = "import sys, sympy\n\
        for line in sys.stdin.read().splitlines():\n\
        \x20   n, a, b, text = line.split('\\t')\n\
        \x20   e = sympy.sympify(text)\n\
        \x20   assert {s.name for s in e.free_symbols} == {n, 'x'}, (n, text, e.free_symbols)\n\
        \x20   v = e.subs({sympy.Symbol(n): sympy.Float(a, 30), sympy.Symbol('x'): sympy.Float(b, 30)})\n\
        \x20   print(repr(float(sympy.N(v, 20))))\n";
    let out = run_python(script, &input, "sympy");
    let got: Vec<f64> = out.lines().map(|l| l.parse().unwrap()).collect();
    assert_eq!(got.len(), names.len());
    for (i, n) in names.iter().enumerate() {
        close(n, got[i], oracle(n, pts[2 * i], pts[2 * i + 1]));
    }
}

/// Names the language reads as symbols (a robot file's fields go through it), from `lang`'s
/// table.
fn robot_names(lang: Lang) -> Vec<String> {
    let all = reserved_names(lang);
    let ok: Vec<String> = all
        .iter()
        .filter(|n| eval_scalar_text(n).is_ok_and(|v| v == Scalar::sym(n)) && *n != "q2")
        .cloned()
        .collect();
    // The language's own built-ins (`cos`, `sqrt`, `pi`) cannot name a joint; the rest must.
    assert!(
        ok.len() * 10 >= all.len() * 7,
        "{lang:?}: only {} of {} names reach a robot file",
        ok.len(),
        all.len()
    );
    ok
}

/// A two-joint DH robot whose first joint's variable is `v` and whose first link length is
/// the parameter `p`.
fn dh_robot(i: usize, v: &str, p: &str) -> dqsym::Robot {
    let text = format!(
        "name = \"r{i}\"\nconvention = \"dh\"\n\
         [[joint]]\ntype = \"revolute\"\ntheta = \"{v}\"\nd = \"0\"\na = \"{p}\"\nalpha = \"0\"\n\
         [[joint]]\ntype = \"revolute\"\ntheta = \"q2\"\nd = \"1/2\"\na = \"1\"\nalpha = \"pi/2\"\n"
    );
    parse_robot(&text, &format!("r{i}.toml"), &eval_scalar_text).expect("robot")
}

/// The pose of [`dh_robot`] by plain 4x4 DH matrices, rows 0..2.
fn dh_pose(v: f64, p: f64, q2: f64) -> [[f64; 4]; 3] {
    let link = |th: f64, d: f64, a: f64, al: f64| {
        let (s, c, sa, ca) = (th.sin(), th.cos(), al.sin(), al.cos());
        [
            [c, -s * ca, s * sa, a * c],
            [s, c * ca, -c * sa, a * s],
            [0.0, sa, ca, d],
            [0.0, 0.0, 0.0, 1.0],
        ]
    };
    let (a, b) = (
        link(v, 0.0, p, 0.0),
        link(q2, 0.5, 1.0, std::f64::consts::FRAC_PI_2),
    );
    let mut t = [[0.0; 4]; 3];
    for (r, row) in t.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    t
}

fn fk_code(robot: &dqsym::Robot, format: Format) -> String {
    let o = FkOptions {
        format,
        ..FkOptions::default()
    };
    fk_report(robot, &o).expect("fk code")
}

/// Pairs of the table's names: each once a joint variable and once a parameter.
fn pairs(names: &[String]) -> Vec<(String, String)> {
    (0..names.len())
        .map(|i| (names[i].clone(), names[(i + 1) % names.len()].clone()))
        .collect()
}

/// Every name of C's table the language reads as a symbol, as a joint variable and as a
/// parameter of a robot: `fk --format c`, one file, -Werror, against plain DH matrices.
#[test]
fn c_fk_with_reserved_joint_and_parameter_names_matches_dh_matrices() {
    let pairs = pairs(&robot_names(Lang::C));
    let pts = values(21, 3 * pairs.len());
    let mut src = String::new();
    let mut calls = String::new();
    for (i, (v, p)) in pairs.iter().enumerate() {
        let code = fk_code(&dh_robot(i, v, p), Format::C);
        src.push_str(&code);
        let (a, b, c) = (pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
        calls.push_str(&format!(
            "    {{ double dq[8], t[3][4]; r{i}_fk({a:?}, {c:?}, {b:?}, dq, t); \
             for (int r = 0; r < 3; r++) for (int k = 0; k < 4; k++) printf(\"%.17g \", t[r][k]); \
             printf(\"\\n\"); }}\n"
        ));
    }
    src.push_str(&format!(
        "#include <stdio.h>\nint main(void)\n{{\n{calls}    return 0;\n}}\n"
    ));
    let out = compile_and_run_c("fk", &src);
    check_poses(&out, &pairs, &pts);
}

fn check_poses(out: &str, pairs: &[(String, String)], pts: &[f64]) {
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), pairs.len());
    for (i, (v, p)) in pairs.iter().enumerate() {
        let got: Vec<f64> = lines[i]
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        let want = dh_pose(pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
        for (k, w) in want.iter().flatten().enumerate() {
            close(&format!("{v}, {p}: T entry {k}"), got[k], *w);
        }
    }
}

/// The same for `fk --format python`, called by position with arrays, and `fk --format
/// rust`, one crate with -D warnings.
#[test]
fn python_and_rust_fk_with_reserved_joint_and_parameter_names_match_dh_matrices() {
    let pairs_py = pairs(&robot_names(Lang::Python));
    let pts = values(22, 3 * pairs_py.len());
    let mut module = String::new();
    let mut calls = Vec::new();
    for (i, (v, p)) in pairs_py.iter().enumerate() {
        module.push_str(&fk_code(&dh_robot(i, v, p), Format::Python));
        module.push('\n');
        let (a, b, c) = (pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
        calls.push(format!(
            "print(' '.join(repr(float(x)) for x in r{i}_fk(np.array([{a:?}]), {c:?}, {b:?})['t'][0].ravel()))"
        ));
    }
    let out = run_py_file("fk", &format!("{module}\n{}\n", calls.join("\n")), "");
    check_poses(&out, &pairs_py, &pts);

    let pairs_rs = pairs(&robot_names(Lang::Rust));
    let pts = values(23, 3 * pairs_rs.len());
    let mut src = String::new();
    let mut calls = String::new();
    for (i, (v, p)) in pairs_rs.iter().enumerate() {
        src.push_str(&fk_code(&dh_robot(i, v, p), Format::Rust));
        src.push('\n');
        let (a, b, c) = (pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
        calls.push_str(&format!(
            "    let t = r{i}_fk({a:?}, {c:?}, {b:?}).t;\n    \
             println!(\"{{}}\", t.iter().flatten().map(|x| format!(\"{{x:?}}\")).collect::<Vec<_>>().join(\" \"));\n"
        ));
    }
    src.push_str(&format!("fn main() {{\n{calls}}}\n"));
    let dir = temp_dir("names_rust_fk");
    let (file, exe) = (dir.join("gen.rs"), dir.join("gen"));
    std::fs::write(&file, &src).unwrap();
    compile_rust_clean(&file, &exe, false, "fk with reserved Rust names");
    let out = run(Command::new(&exe), "", "the compiled Rust program");
    check_poses(&out, &pairs_rs, &pts);
}

/// Robot names that end or escape every comment syntax we write.
const HOSTILE_NAMES: &[&str] = &[
    "x */ int evil_c(void){return 1;} /* ",
    "/* nested */ */ int evil_c2(void){return 2;}",
    "\"\"\"; import os; evil_py = 1; \"\"\"",
    "end\"",
    "back\\",
    "arm\n\\input{secret.tex}\nevil_line = 1",
    "crlf\r\nevil_cr = 1\rx",
    "trigraph ??/\nint evil_tri;",
    "\u{1b}[2J\u{1b}[31mRED\u{7}",
    "bidi \u{202e}evil\u{2066} \u{2028}sep",
    "```\nfn evil_doc() {}\n```",
    "\n    indented_doctest();",
    "<script>alert(1)</script> & [link](x)",
    "coding: utf-7 +AGMAbwBk-",
    "# not a heading %\ttab",
];

fn hostile_robot(i: usize, name: &str) -> dqsym::Robot {
    let text = format!(
        "name = {}\nconvention = \"dh\"\n\
         [[joint]]\ntype = \"revolute\"\ntheta = \"theta1\"\nd = \"0\"\na = \"l1\"\nalpha = \"0\"\n",
        dqsym::emit::names::toml_string(name)
    );
    let r = parse_robot(&text, &format!("h{i}.toml"), &eval_scalar_text).expect("robot");
    assert_eq!(r.name, name);
    r
}

/// Every comment syntax with every hostile name: C (one file, -Werror; its only functions are
/// the generated ones), Python (one module: each function's only statements are its own, the
/// docstring holds the name), Rust (one crate, -D warnings; rustdoc finds no doctest),
/// LaTeX, plain text and TOML (every line the name spans is a comment).
#[test]
fn hostile_robot_names_stay_inside_comments_in_every_syntax() {
    let robots: Vec<dqsym::Robot> = HOSTILE_NAMES
        .iter()
        .enumerate()
        .map(|(i, n)| hostile_robot(i, n))
        .collect();
    let fns: Vec<String> = robots
        .iter()
        .map(|r| fn_name(&fk_code(r, Format::C), "void "))
        .collect();
    // C: compiled; the object file defines exactly the generated functions.
    let c: String = robots.iter().map(|r| fk_code(r, Format::C)).collect();
    let dir = temp_dir("names_hostile");
    std::fs::write(dir.join("h.c"), &c).unwrap();
    let mut gcc = Command::new("gcc");
    gcc.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-c", "-o"])
        .arg(dir.join("h.o"))
        .arg(dir.join("h.c"));
    run(gcc, "", "gcc -Werror on hostile names");
    let mut nm = Command::new("nm");
    nm.args(["--defined-only", "-P"]).arg(dir.join("h.o"));
    let mut defined: Vec<String> = run(nm, "", "nm")
        .lines()
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .collect();
    let mut want = fns.clone();
    defined.sort();
    want.sort();
    assert_eq!(defined, want, "the object file's symbols");
    // Python: each function's body is what the emitter writes; the docstring holds the name.
    let py: String = robots.iter().map(|r| fk_code(r, Format::Python)).collect();
    let hex: Vec<String> = HOSTILE_NAMES
        .iter()
        .map(|n| n.bytes().map(|b| format!("{b:02x}")).collect())
        .collect();
    let script = format!(
        "import ast, sys\nsrc = sys.stdin.read()\ntree = ast.parse(src)\n\
         names = [bytes.fromhex(h).decode() for h in {hex:?}]\n\
         top = [type(s).__name__ for s in tree.body]\n\
         assert set(top) == {{'Import', 'FunctionDef'}}, top\n\
         defs = [s for s in tree.body if isinstance(s, ast.FunctionDef)]\n\
         assert len(defs) == len(names)\n\
         for d, n in zip(defs, names):\n\
         \x20   doc = ast.get_docstring(d, clean=False)\n\
         \x20   for s in d.body[1:]:\n\
         \x20       assert isinstance(s, (ast.Assign, ast.Return)), ast.dump(s)\n\
         \x20       if isinstance(s, ast.Assign):\n\
         \x20           assert all(isinstance(t, ast.Name) for t in s.targets)\n\
         \x20           assert not any(t.id.startswith('evil') for t in s.targets), ast.dump(s)\n\
         \x20   for line in n.split('\\n'):\n\
         \x20       if line.isprintable():\n\
         \x20           assert line.strip() in doc, (line, doc)\n\
         ns = {{}}\nexec(compile(tree, 'h', 'exec'), ns)\n\
         assert not any(k.startswith('evil') for k in ns), sorted(ns)\n\
         print(len(defs))\n"
    );
    let out = run_py_file("hostile", &script, &py);
    assert_eq!(out.trim(), HOSTILE_NAMES.len().to_string());
    // Rust: compiles clean; rustdoc runs no doctest (a name's code fence would be one).
    let rs: String = robots
        .iter()
        .map(|r| fk_code(r, Format::Rust) + "\n")
        .collect();
    let lib = dir.join("hlib.rs");
    std::fs::write(&lib, format!("#![allow(dead_code)]\n{rs}")).unwrap();
    let mut rustc = Command::new("rustc");
    rustc
        .args([
            "--edition",
            "2021",
            "-D",
            "warnings",
            "--crate-type",
            "lib",
            "-o",
        ])
        .arg(dir.join("libh.rlib"))
        .arg(&lib);
    run(rustc, "", "rustc -D warnings on hostile names");
    let mut rustdoc = Command::new("rustdoc");
    rustdoc
        .args(["--edition", "2021", "--test", "--crate-name", "h"])
        .arg(&lib);
    let doc = run(rustdoc, "", "rustdoc --test on hostile names");
    assert!(doc.contains("running 0 tests"), "{doc}");
    // LaTeX, plain and TOML (convert): every line before the first entry is a comment.
    for r in &robots {
        for (format, prefix) in [(Format::Latex, "%"), (Format::Plain, "#")] {
            let text = fk_code(r, format);
            let head: Vec<&str> = text
                .lines()
                .take_while(|l| !l.contains("unit dual quaternion"))
                .collect();
            assert!(!head.is_empty());
            for l in head {
                assert!(
                    l.starts_with(prefix),
                    "{format:?} line {l:?} of {:?}",
                    r.name
                );
                assert!(!l.chars().any(|c| c.is_control()), "{l:?}");
            }
        }
    }
    // TOML (convert, from a URDF: XML carries every name but most control characters): the
    // header's every line a comment, the file read back with the same name.
    for name in HOSTILE_NAMES.iter().filter(|n| {
        n.chars()
            .all(|c| !c.is_control() || matches!(c, '\n' | '\r' | '\t'))
    }) {
        let attr: String = name
            .chars()
            .map(|c| match c {
                '&' => "&amp;".into(),
                '<' => "&lt;".into(),
                '>' => "&gt;".into(),
                '"' => "&quot;".into(),
                c if c.is_control() => format!("&#{};", c as u32),
                c => c.to_string(),
            })
            .collect();
        let urdf = format!(
            "<robot name=\"{attr}\"><link name=\"a\"/><link name=\"b\"/>\
             <joint name=\"j0\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\
             <origin xyz=\"0 0 1\"/><axis xyz=\"0 0 1\"/></joint></robot>"
        );
        let r = dqsym::parse_urdf(&urdf, "h.urdf", &Default::default())
            .expect("urdf")
            .robot;
        let toml_text = dqsym::app::robot_toml(&r, "h.urdf").expect("convert");
        let header: Vec<&str> = toml_text
            .lines()
            .take_while(|l| !l.starts_with("name = "))
            .collect();
        assert!(header.iter().all(|l| l.starts_with('#')), "{header:?}");
        let back = parse_robot(&toml_text, "back.toml", &eval_scalar_text).expect("reads back");
        assert_eq!(back.name, r.name);
        assert!(r.name.starts_with(name), "{:?} from {name:?}", r.name);
        assert_eq!(back.variables, r.variables);
    }
}

#[test]
fn python_function_names_are_available_for_keyword_callers() {
    let args: Vec<String> = ["shape", "x", "shape_", "lambda"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let names = dqsym::emit::python_names(&args);
    assert_eq!(names, ["shape__", "x", "shape_", "lambda_"]);
}

/// Names the solver code writes itself, besides each language's table.
const IK_OWN: &[&str] = &[
    "T", "q", "ik", "ik_out", "ik_t0", "IK_MAX", "IkMemo", "math", "np",
];

/// Planar 2R robots whose joint variables and link lengths take the names of `lang`'s table
/// (four names each) and the solver's own names.
fn ik_robots(lang: Lang) -> Vec<(dqsym::Robot, [String; 4])> {
    let mut names = robot_names(lang);
    names.extend(IK_OWN.iter().map(|s| s.to_string()));
    names.sort();
    names.dedup();
    names
        .chunks(4)
        .filter(|c| c.len() == 4)
        .enumerate()
        .map(|(i, c)| {
            let [v1, v2, p1, p2] = [&c[0], &c[1], &c[2], &c[3]];
            let text = format!(
                "name = \"k{i} */ x\"\nconvention = \"dh\"\n\
                 [[joint]]\ntype = \"revolute\"\ntheta = \"{v1}\"\nd = \"0\"\na = \"{p1}\"\nalpha = \"0\"\n\
                 [[joint]]\ntype = \"revolute\"\ntheta = \"{v2}\"\nd = \"0\"\na = \"{p2}\"\nalpha = \"0\"\n"
            );
            let r = parse_robot(&text, "k.toml", &eval_scalar_text).expect("robot");
            (r, [v1.clone(), v2.clone(), p1.clone(), p2.clone()])
        })
        .collect()
}

fn ik_solution(r: &dqsym::Robot) -> dqsym::ik::IkSolution {
    dqsym::ik::solve(r, &Default::default()).expect("planar 2R solves")
}

/// The IK solvers' parameters and joint variables named after every name of C's and Rust's
/// tables (and the solver's own names): each solver compiles (-Werror, -D warnings).
#[test]
fn ik_code_with_reserved_parameter_and_joint_names_compiles() {
    let dir = temp_dir("names_ik");
    for (k, (r, _)) in ik_robots(Lang::C).iter().enumerate() {
        let file = dir.join(format!("k{k}.c"));
        std::fs::write(&file, dqsym::ik::ik_c(&ik_solution(r)).unwrap()).unwrap();
        let mut gcc = Command::new("gcc");
        gcc.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-c", "-o"])
            .arg(dir.join(format!("k{k}.o")))
            .arg(&file);
        run(gcc, "", &format!("gcc -Werror on {}", file.display()));
    }
    // One crate, a module per robot.
    let mut src = String::from("#![allow(dead_code)]\n");
    for (k, (r, _)) in ik_robots(Lang::Rust).iter().enumerate() {
        let code = dqsym::ik::ik_rust(&ik_solution(r)).unwrap();
        src.push_str(&format!("pub mod k{k} {{\n{code}\n}}\n"));
    }
    let lib = dir.join("k.rs");
    std::fs::write(&lib, &src).unwrap();
    let mut rustc = Command::new("rustc");
    rustc
        .args([
            "--edition",
            "2021",
            "-D",
            "warnings",
            "--crate-type",
            "lib",
            "-o",
        ])
        .arg(dir.join("libk.rlib"))
        .arg(&lib);
    run(rustc, "", "rustc -D warnings on IK with reserved names");
}

/// The Python solvers for every name of Python's table: each solution reaches the target
/// (planar 2R: the position `l1 (cos q1, sin q1) + l2 (cos q12, sin q12)`).
#[test]
fn ik_python_with_reserved_names_reaches_the_target() {
    let robots = ik_robots(Lang::Python);
    let pts = values(31, 4 * robots.len());
    let mut script = String::from("import importlib.util, math, sys\nimport numpy as np\n");
    let dir = temp_dir("names_ik_py");
    for (k, (r, [_, _, p1, p2])) in robots.iter().enumerate() {
        let code = dqsym::ik::ik_python(&ik_solution(r)).unwrap();
        let file = dir.join(format!("k{k}.py"));
        std::fs::write(&file, &code).unwrap();
        // The keyword parameters in sorted order of the names they stand for.
        let def = code.lines().find(|l| l.starts_with("def ik(")).unwrap();
        let params: Vec<&str> = def.trim_end_matches("):").split(", ").skip(2).collect();
        let mut sorted = [p1, p2];
        sorted.sort();
        let (l1, l2) = (0.5 + pts[4 * k].abs(), 0.5 + pts[4 * k + 1].abs());
        let value = |p: &String| if p == p1 { l1 } else { l2 };
        let kw: Vec<String> = params
            .iter()
            .zip(sorted)
            .map(|(name, p)| format!("{name}={:?}", value(p)))
            .collect();
        let (q1, q2) = (pts[4 * k + 2], pts[4 * k + 3]);
        // Each solution's position within 1e-9 of the target: the atan2 forms are accurate
        // to a few ulps of the lengths (< 2.5); near the straight elbow an angle may be off
        // by sqrt(ulp) ~ 1e-8, which moves the tip only to second order.
        script.push_str(&format!(
            "spec = importlib.util.spec_from_file_location('k{k}', {file:?})\n\
             m = importlib.util.module_from_spec(spec)\nspec.loader.exec_module(m)\n\
             px = {l1:?} * math.cos({q1:?}) + {l2:?} * math.cos({q1:?} + {q2:?})\n\
             py = {l1:?} * math.sin({q1:?}) + {l2:?} * math.sin({q1:?} + {q2:?})\n\
             T = np.eye(4)\nT[0, 3], T[1, 3] = px, py\n\
             sols = m.ik(T, {kw})\nassert sols, {k}\n\
             for a, b in sols:\n\
             \x20   x = {l1:?} * math.cos(a) + {l2:?} * math.cos(a + b)\n\
             \x20   y = {l1:?} * math.sin(a) + {l2:?} * math.sin(a + b)\n\
             \x20   assert abs(x - px) < 1e-9 and abs(y - py) < 1e-9, ({k}, a, b, x, y, px, py)\n",
            kw = kw.join(", "),
            file = file.display().to_string(),
        ));
    }
    script.push_str(&format!("print({})\n", robots.len()));
    let out = run_py_file("ik", &script, "");
    assert_eq!(out.trim(), robots.len().to_string());
}

/// A URDF's joint names become its variables without the language in between: every name of
/// C's table (`cos`, `sqrt`, `int`, `M_PI`) names a joint of a planar 2R URDF, `fk --format c`
/// of each in one file (-Werror), against `Tx(1) Rz(q1) Tx(1) Rz(q2)` by plain matrices.
#[test]
fn c_fk_of_urdf_joints_named_after_c_names_matches_matrices() {
    let names = reserved_names(Lang::C);
    let pts = values(41, names.len() + 1);
    let mut src = String::new();
    let mut calls = String::new();
    let mut want = Vec::new();
    for (i, pair) in names.chunks(2).enumerate() {
        let (j1, j2) = (&pair[0], pair.get(1).unwrap_or(&names[0]));
        let urdf = format!(
            "<robot name=\"u{i}\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\
             <joint name=\"{j1}\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\
             <origin xyz=\"1 0 0\"/><axis xyz=\"0 0 1\"/></joint>\
             <joint name=\"{j2}\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/>\
             <origin xyz=\"1 0 0\"/><axis xyz=\"0 0 1\"/></joint></robot>"
        );
        let r = dqsym::parse_urdf(&urdf, "u.urdf", &Default::default())
            .expect("urdf")
            .robot;
        let code = fk_code(&r, Format::C);
        let f = fn_name(&code, "void ");
        src.push_str(&code);
        let (q1, q2) = (pts[2 * i], pts[2 * i + 1]);
        calls.push_str(&format!(
            "    {{ double dq[8], t[3][4]; {f}({q1:?}, {q2:?}, dq, t); \
             printf(\"%.17g %.17g %.17g\\n\", t[0][3], t[1][3], t[0][0]); }}\n"
        ));
        // Tx(1) Rz(q1) Tx(1) Rz(q2): the tip (1 + cos q1, sin q1), T[0][0] = cos(q1 + q2).
        want.push([1.0 + q1.cos(), q1.sin(), (q1 + q2).cos()]);
    }
    src.push_str(&format!(
        "#include <stdio.h>\nint main(void)\n{{\n{calls}    return 0;\n}}\n"
    ));
    let out = compile_and_run_c("urdf", &src);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), want.len());
    for (l, w) in lines.iter().zip(&want) {
        let got: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
        for k in 0..3 {
            close(l, got[k], w[k]);
        }
    }
}

/// Reads a Markdown heading's text as CommonMark does for these characters: a backslash before
/// ASCII punctuation is that character; the HTML entities of `html_text` decoded. `None` when a
/// character that opens inline Markdown (a link, an image, emphasis, a code span, a GFM table
/// cell or strikethrough) or raw HTML stands unescaped.
fn markdown_heading_text(md: &str) -> Option<String> {
    let mut out = String::new();
    let all: Vec<char> = md.chars().collect();
    let mut chars = all.iter().copied().enumerate();
    // An underscore inside a word opens no emphasis (CommonMark's flanking rules).
    let word = |j: Option<usize>| {
        j.and_then(|j| all.get(j))
            .is_some_and(|c| c.is_alphanumeric())
    };
    while let Some((i, c)) = chars.next() {
        match c {
            '_' if word(i.checked_sub(1)) && word(Some(i + 1)) => out.push(c),
            '\\' => match chars.next().map(|(_, n)| n) {
                Some(n) if n.is_ascii_punctuation() => out.push(n),
                Some(n) => {
                    out.push('\\');
                    out.push(n);
                }
                None => out.push('\\'),
            },
            '[' | ']' | '*' | '_' | '`' | '!' | '|' | '~' | '<' | '>' => return None,
            c => out.push(c),
        }
    }
    Some(
        out.replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&#39;", "'")
            .replace("&amp;", "&"),
    )
}

/// `walk --markdown` writes a robot's name into its first heading as inert text: no link,
/// image, emphasis, code span or HTML forms, and the name reads back whole (hostile round 3,
/// row 20, and names written as Markdown).
#[test]
fn walk_markdown_heading_shows_any_robot_name_as_text() {
    let dir = temp_dir("names-markdown");
    let names = [
        "<img src=x onerror=alert(1)>",
        "[x](javascript:alert(1))",
        "![i](http://e/x.png) *a* _b_ `c` | ~~d~~",
        "back\\slash \\[not a link\\] & <b>bold</b>",
        "plain name 2",
        "file_name_with_underscores.toml _emphasis_ a_ _b",
    ];
    for (i, name) in names.iter().enumerate() {
        let toml = format!(
            "name = {}\nconvention = \"dh\"\n[[joint]]\ntype = \"revolute\"\ntheta = \"theta1\"\n\
             d = \"0\"\na = \"l1\"\nalpha = \"0\"\n",
            dqsym::emit::names::toml_string(name)
        );
        let path = dir.join(format!("m{i}.toml"));
        std::fs::write(&path, toml).expect("writes");
        let md = crate::tools::dqsym_ok(&["walk", &path.display().to_string(), "--markdown"]);
        let heading = md.lines().next().expect("heading");
        let title = heading
            .strip_prefix("# Walkthrough: ")
            .unwrap_or_else(|| panic!("{heading}"));
        assert_eq!(
            markdown_heading_text(title).as_deref(),
            Some(*name),
            "{name:?} as {title:?}"
        );
    }
}

/// Values whose closed form is a sum times a rational past f64's range (`(3^700 + x)/3^700`):
/// the generated C and NumPy code gives the value (here `1 + x y / 2^1100`-sized terms that
/// round to their own size), never `(inf + x) * 0` = NaN. The oracle is the test's own f64
/// arithmetic of the expanded value, each term rounded on its own.
#[test]
fn sums_times_constants_past_f64_keep_their_value_in_c_and_numpy() {
    let cases = [
        "(3^700 + x)*y/3^700",
        "(2^1100 + x)*(3^700 + y)/(2^1100*3^700)",
        "(5^600 - x)/5^600 + y",
    ];
    // The x / 3^700-sized terms underflow to 0 in f64 (3^-700 ~ 1e-334): the f64 values are
    // y, 1 and 1 + y exactly.
    let oracle = |k: usize, _a: f64, b: f64| match k {
        0 => b,
        1 => 1.0,
        _ => 1.0 + b,
    };
    let o = CodegenOptions::default();
    let pts = values(21, 2 * cases.len());
    let (mut c_src, mut c_calls, mut py, mut py_calls) =
        (String::new(), String::new(), String::new(), String::new());
    for (k, e) in cases.iter().enumerate() {
        let e = eval_scalar_text(e).expect("exact value");
        let out = Output::scalar("v", "value", closed_form(&e).unwrap());
        let f = format!("f{k}");
        let args = ["x".to_string(), "y".to_string()];
        c_src.push_str(&c_function(&f, "doc", std::slice::from_ref(&out), &args, &o).unwrap());
        py.push_str(&python_function(&f, "doc", &[out], &args, &o).unwrap());
        py.push('\n');
        let (a, b) = (pts[2 * k], pts[2 * k + 1]);
        c_calls.push_str(&format!(
            "    {{ double v; {f}({a:?}, {b:?}, &v); printf(\"%.17g\\n\", v); }}\n"
        ));
        py_calls.push_str(&format!("print(repr(float({f}({a:?}, {b:?})['v'])))\n"));
    }
    c_src.push_str(&format!(
        "#include <stdio.h>\nint main(void)\n{{\n{c_calls}    return 0;\n}}\n"
    ));
    let c_out = compile_and_run_c("past_f64", &c_src);
    let py_out = run_py_file("past_f64", &format!("{py}\n{py_calls}"), "");
    for (lang, out) in [("C", c_out), ("NumPy", py_out)] {
        let got: Vec<f64> = out.lines().map(|l| l.parse().unwrap()).collect();
        assert_eq!(got.len(), cases.len(), "{lang}: {out}");
        for (k, g) in got.iter().enumerate() {
            close(
                &format!("{lang} case {k}"),
                *g,
                oracle(k, pts[2 * k], pts[2 * k + 1]),
            );
        }
    }
}

/// A robot whose name has no letter or digit (`robot_fk`, not `robot__fk`) and whose joint
/// variable and parameter hold double underscores (a URDF joint `j*/0` becomes `j__0`):
/// the Rust fk compiles with `-D warnings` (rustc's snake-case lint) and gives the DH pose.
#[test]
fn rust_fk_of_names_rustc_calls_not_snake_case_compiles_clean_and_matches_dh() {
    let mut src = String::new();
    let mut calls = String::new();
    let pts = values(22, 6);
    for (i, (name, v, p)) in [("!!!", "q__1", "l__a"), ("", "q__", "a__b")]
        .into_iter()
        .enumerate()
    {
        let text = format!(
            "name = \"{name}\"\nconvention = \"dh\"\n\
             [[joint]]\ntype = \"revolute\"\ntheta = \"{v}\"\nd = \"0\"\na = \"{p}\"\nalpha = \"0\"\n\
             [[joint]]\ntype = \"revolute\"\ntheta = \"q2\"\nd = \"1/2\"\na = \"1\"\nalpha = \"pi/2\"\n"
        );
        let robot = parse_robot(&text, "r.toml", &eval_scalar_text).expect("robot");
        let code = fk_code(&robot, Format::Rust);
        let f = fn_name(&code, "pub fn ");
        assert_eq!(f, "robot_fk", "{code}");
        // Each function in its own module: both are named `robot_fk`.
        src.push_str(&format!("mod m{i} {{\n{code}\n}}\n"));
        let args = robot.parameters();
        assert!(args.len() == 1, "{args:?}");
        // Arguments in the order the doc comment lists them.
        let order = code
            .lines()
            .find_map(|l| l.strip_prefix("/// Arguments, in order: "))
            .expect("argument list")
            .trim_end_matches('.')
            .replace('`', "");
        let vals: Vec<String> = order
            .split(", ")
            .map(|a| match a {
                a if a == v => format!("{:?}", pts[3 * i]),
                a if a == p => format!("{:?}", pts[3 * i + 1]),
                _ => format!("{:?}", pts[3 * i + 2]),
            })
            .collect();
        calls.push_str(&format!(
            "    println!(\"{{:?}}\", m{i}::robot_fk({}).t);\n",
            vals.join(", ")
        ));
    }
    src.push_str(&format!("fn main() {{\n{calls}}}\n"));
    let dir = temp_dir("names_rust_snake");
    let (file, exe) = (dir.join("gen.rs"), dir.join("gen"));
    std::fs::write(&file, &src).unwrap();
    compile_rust_clean(&file, &exe, false, "non-snake-case names");
    let out = run(Command::new(&exe), "", "the compiled Rust program");
    for (i, line) in out.lines().enumerate() {
        let got: Vec<f64> = line
            .replace(['[', ']'], "")
            .split(", ")
            .map(|x| x.parse().unwrap())
            .collect();
        let want = dh_pose(pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
        for (k, g) in got.iter().enumerate() {
            close(&format!("robot {i} t[{k}]"), *g, want[k / 4][k % 4]);
        }
    }
}
