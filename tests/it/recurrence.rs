//! The recurrence form of `dqsym fk` (long symbolic chains): its entries evaluated in f64
//! against the f64 chain and finite differences, and the Rust, C and Python code it generates
//! compiled or run and compared with those entries.

use crate::paper_support::points;
use crate::robots::{load, numeric_chain};
use crate::tools;
use dqsym::{
    app::{fk_recurrence, Quantity},
    emit::sympy,
    fk_report,
    kin::dq_jacobian,
    DualQuat, Expr, FkOptions, Format, Robot, Scalar,
};
use std::collections::HashMap;
use std::process::Command;

const CHAIN20: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/chain20_symbolic.toml"
);

fn example(name: &str) -> String {
    format!("{}/examples/robots/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

/// Options that force the recurrence (no expansion fits in one term), with the Jacobian and a
/// point.
fn forced(format: Format, point: [Scalar; 3]) -> FkOptions {
    FkOptions {
        format,
        shorthand: true,
        point: Some(point),
        jacobian: true,
        max_terms: 1,
    }
}

fn some_point() -> [Scalar; 3] {
    dqsym::lang::eval_point_text("1/2, -1, 2").expect("a point")
}

/// Every entry's value at `env`, in order, each evaluated with the ones before it bound.
/// Values are keyed by the symbol later entries read an entry by (`Q2_3`, `T_1_2`).
pub(crate) fn evaluate(
    entries: &[(Quantity, Expr)],
    env: &[(String, f64)],
) -> HashMap<String, f64> {
    let mut vals: HashMap<String, f64> = env.iter().cloned().collect();
    for (name, e) in entries {
        let bound: Vec<(&str, f64)> = vals.iter().map(|(k, v)| (k.as_str(), *v)).collect();
        let v = e
            .value_at(&bound)
            .unwrap_or_else(|| panic!("{}: a symbol without a value", name.name()));
        vals.insert(name.symbol(), v);
    }
    vals
}

fn symbols(r: &Robot) -> Vec<String> {
    let mut names = r.variables.clone();
    names.extend(r.parameters());
    names
}

fn joint_values(r: &Robot, env: &[(String, f64)]) -> Vec<f64> {
    r.variables
        .iter()
        .map(|v| env.iter().find(|(k, _)| k == v).expect("bound").1)
        .collect()
}

fn near(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

/// The recurrence of `r` at random values of every symbol: `dq` and `T` against the f64
/// chain, `p` against the f64 matrix, `J` against central differences of the f64 chain.
pub(crate) fn check_against_f64_chain(file: &str, r: &Robot, entries: &[(Quantity, Expr)]) {
    let names = symbols(r);
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let pt = [0.5, -1.0, 2.0];
    for env in points(&refs, 2) {
        let vals = evaluate(entries, &env);
        let chain = numeric_chain(r, &env);
        let qs = joint_values(r, &env);
        let dq = chain.forward(&qs).expect("joint count").components();
        let m = chain.forward_matrix(&qs).expect("joint count");
        for (k, want) in dq.iter().enumerate() {
            let got = vals[&format!("dq_{k}")];
            assert!(near(got, *want, 1e-9), "{file}: dq[{k}] {got} != {want}");
        }
        for i in 0..3 {
            for j in 0..4 {
                let got = vals[&format!("T_{i}_{j}")];
                let want = m.rows[i][j];
                assert!(near(got, want, 1e-9), "{file}: T[{i}][{j}] {got} != {want}");
            }
        }
        let image = m.transform_point(&pt);
        for (k, want) in image.iter().enumerate() {
            let got = vals[&format!("p_{k}")];
            assert!(near(got, *want, 1e-9), "{file}: p[{k}] {got} != {want}");
        }
        let h = 1e-6;
        for j in 0..qs.len() {
            let at = |d: f64| {
                let mut q = qs.clone();
                q[j] += d;
                chain.forward(&q).expect("joint count").components()
            };
            let (plus, minus) = (at(h), at(-h));
            for k in 0..8 {
                let fd = (plus[k] - minus[k]) / (2.0 * h);
                let got = vals[&format!("J_{k}_{j}")];
                assert!(near(got, fd, 1e-6), "{file}: J[{k}][{j}] {got} != {fd}");
            }
        }
    }
}

#[test]
fn symbolic_chain_expansion_has_k_times_4_to_the_k_terms() {
    // Why long symbolic chains are reported as a recurrence: the largest DQ component of the
    // first k links of chain20 has k 4^k terms (measured up to k = 7 in release: 114,688).
    let r = load(CHAIN20);
    let mut acc = DualQuat::<Scalar>::identity();
    for (k, f) in r.joint_dqs().into_iter().take(5).enumerate() {
        acc = acc * f;
        let k = k + 1;
        let largest = acc.components().iter().map(Scalar::len).max();
        assert_eq!(largest, Some(k << (2 * k)), "after {k} links");
    }
}

#[test]
fn generic_6r_recurrence_prints_the_matrix_from_its_cos_sin_polynomial() {
    // Every DH parameter symbolic, six joints: the DQ exceeds the term budget, the matrix as a
    // polynomial in the cosines and sines does not, so T is in the robot's own symbols.
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/generic_6r.toml");
    let r = load(file);
    let o = FkOptions {
        format: Format::Plain,
        shorthand: true,
        point: Some(some_point()),
        jacobian: true,
        max_terms: 5_000,
    };
    let entries = fk_recurrence(&r, &o).expect("a recurrence");
    let names = symbols(&r);
    let own: Vec<(&str, f64)> = names.iter().map(|s| (s.as_str(), 0.5)).collect();
    for (name, e) in entries.iter().filter(|(n, _)| matches!(n, Quantity::T(..))) {
        assert!(
            e.value_at(&own).is_some(),
            "{} reads only the robot's own symbols",
            name.name()
        );
    }
    check_against_f64_chain(file, &r, &entries);
    let text = fk_report(&r, &o).expect("report");
    assert!(text.contains("from the cos/sin polynomial"), "{text}");
}

#[test]
fn chain20_recurrence_with_jacobian_matches_the_f64_chain_and_finite_differences() {
    let r = load(CHAIN20);
    let o = forced(Format::Sympy, some_point());
    let entries = fk_recurrence(&r, &o).expect("a recurrence");
    assert_eq!(
        entries
            .iter()
            .filter(|(n, _)| matches!(n, Quantity::J { .. }))
            .count(),
        8 * 20
    );
    check_against_f64_chain("chain20", &r, &entries);
}

#[test]
fn every_example_robot_forced_into_a_recurrence_matches_its_expansion() {
    for name in [
        "rrr",
        "scara",
        "puma560",
        "stanford",
        "ur5",
        "kuka_iiwa7",
        "six_r",
    ] {
        let file = example(name);
        let r = load(&file);
        let o = forced(Format::Sympy, some_point());
        let entries = fk_recurrence(&r, &o).expect("a recurrence");
        // The report prints exactly these entries, one SymPy line each.
        let text = fk_report(&r, &o).expect("a report");
        let lines: String = entries
            .iter()
            .map(|(n, e)| format!("{} = {}\n", n.name(), sympy(e)))
            .collect();
        assert_eq!(text, lines, "{name}");
        check_against_f64_chain(name, &r, &entries);
        // And the Jacobian equals the expanded one at a random point.
        let q = r.forward();
        let vars: Vec<&str> = r.variables.iter().map(String::as_str).collect();
        let jac = dq_jacobian(&q, &vars);
        let names = symbols(&r);
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        let env = &points(&refs, 1)[0];
        let vals = evaluate(&entries, env);
        for (k, row) in jac.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                let want = crate::paper_support::ev(x, env);
                let got = vals[&format!("J_{k}_{j}")];
                assert!(near(got, want, 1e-9), "{name}: J[{k}][{j}] {got} != {want}");
            }
        }
    }
}

/// The names inside the parentheses of the generated function's signature line, without the
/// out-parameters (C) and types.
fn signature_args(code: &str, marker: &str) -> Vec<String> {
    let line = code
        .lines()
        .find(|l| l.starts_with(marker))
        .expect("signature");
    let inner = &line[line.find('(').expect("(") + 1..line.rfind(')').expect(")")];
    inner
        .split(", ")
        .filter(|a| !a.contains('['))
        .map(|a| {
            let a = a.trim_start_matches("double ");
            let a = a.split(':').next().expect("name");
            a.trim_start_matches('_').to_string()
        })
        .collect()
}

/// The returned values in the order dq (8), t (12), p (3), j (8 x n), from the recurrence's
/// own entries evaluated in f64.
fn expected(entries: &[(Quantity, Expr)], env: &[(String, f64)], n: usize) -> Vec<f64> {
    let vals = evaluate(entries, env);
    let mut v: Vec<f64> = (0..8).map(|k| vals[&format!("dq_{k}")]).collect();
    for i in 0..3 {
        for j in 0..4 {
            v.push(vals[&format!("T_{i}_{j}")]);
        }
    }
    v.extend((0..3).map(|k| vals[&format!("p_{k}")]));
    for k in 0..8 {
        v.extend((0..n).map(|j| vals[&format!("J_{k}_{j}")]));
    }
    v
}

/// Runs `bin` on one line of argument values per point and compares its output lines (the
/// values in the order of [`expected`]) with the recurrence.
fn compare_run(
    what: &str,
    out: &str,
    r: &Robot,
    entries: &[(Quantity, Expr)],
    envs: &[Vec<(String, f64)>],
) {
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), envs.len(), "{what}: one line per point");
    for (line, env) in lines.iter().zip(envs) {
        let got: Vec<f64> = line
            .replace(['[', ']', ','], " ")
            .split_whitespace()
            .map(|x| x.parse().expect("a number"))
            .collect();
        let want = expected(entries, env, r.variables.len());
        assert_eq!(got.len(), want.len(), "{what}: one value per entry");
        for (k, (a, b)) in got.iter().zip(&want).enumerate() {
            assert!(near(*a, *b, 1e-9), "{what}: value {k}: {a} != {b}");
        }
    }
}

/// Random values of `args` (the generated function's arguments), as environments and as
/// whitespace-separated input lines.
fn inputs(args: &[String]) -> (Vec<Vec<(String, f64)>>, String) {
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let envs = points(&refs, 3);
    let text = envs
        .iter()
        .map(|e| {
            let v: Vec<String> = e.iter().map(|(_, x)| format!("{x:?}")).collect();
            v.join(" ") + "\n"
        })
        .collect();
    (envs, text)
}

#[test]
fn chain20_recurrence_as_rust_compiles_clean_and_agrees_with_the_recurrence() {
    let code = tools::dqsym_ok(&[
        "fk",
        CHAIN20,
        "--jacobian",
        "--point",
        "1/2, -1, 2",
        "--format",
        "rust",
    ]);
    assert!(
        code.contains("let q20_0 = ") || code.contains("q19_0"),
        "locals named after the entries"
    );
    let r = load(CHAIN20);
    let entries = fk_recurrence(&r, &forced(Format::Sympy, some_point())).expect("entries");
    let args = signature_args(&code, "pub fn ");
    assert_eq!(args.len(), 80, "{args:?}");
    let call: Vec<String> = (0..args.len()).map(|i| format!("v[{i}]")).collect();
    let main = format!(
        "\nfn main() {{\n    let mut s = String::new();\n    std::io::Read::read_to_string(&mut std::io::stdin(), &mut s).unwrap();\n    for line in s.lines() {{\n        let v: Vec<f64> = line.split_whitespace().map(|x| x.parse().unwrap()).collect();\n        let r = chain20_fk({});\n        println!(\"{{:?}} {{:?}} {{:?}} {{:?}}\", r.dq, r.t, r.p, r.j);\n    }}\n}}\n",
        call.join(", ")
    );
    let dir = tools::temp_dir("fk-chain20-rust");
    let src = dir.join("fk.rs");
    std::fs::write(&src, code + &main).expect("write");
    let exe = dir.join("fk");
    tools::compile_rust_clean(&src, &exe, false, "the chain20 recurrence");
    let (envs, input) = inputs(&args);
    let out = tools::run(
        Command::new(&exe),
        &input,
        "the compiled chain20 recurrence",
    );
    compare_run("Rust chain20", &out, &r, &entries, &envs);
}

#[test]
fn recurrences_as_c_compile_with_werror_and_agree_with_the_recurrence() {
    for file in [CHAIN20.to_string(), example("puma560")] {
        let r = load(&file);
        let entries = fk_recurrence(&r, &forced(Format::Sympy, some_point())).expect("entries");
        let code = fk_report(&r, &forced(Format::C, some_point())).expect("C code");
        let name = code
            .lines()
            .find_map(|l| l.strip_prefix("void "))
            .and_then(|l| l.split('(').next())
            .expect("function name")
            .to_string();
        let args = signature_args(&code, "void ");
        let n = args.len();
        let main = format!(
            "\n#include <stdio.h>\nint main(void)\n{{\n    double v[{n}];\n    for (;;) {{\n        for (int i = 0; i < {n}; i++)\n            if (scanf(\"%lf\", &v[i]) != 1) return 0;\n        double dq[8], t[3][4], p[3], j[8][{}];\n        {name}({}, dq, t, p, j);\n        for (int k = 0; k < 8; k++) printf(\"%.17g \", dq[k]);\n        for (int k = 0; k < 12; k++) printf(\"%.17g \", t[k / 4][k % 4]);\n        for (int k = 0; k < 3; k++) printf(\"%.17g \", p[k]);\n        for (int k = 0; k < {}; k++) printf(\"%.17g \", j[k / {m}][k % {m}]);\n        printf(\"\\n\");\n    }}\n}}\n",
            r.variables.len(),
            (0..n).map(|i| format!("v[{i}]")).collect::<Vec<_>>().join(", "),
            8 * r.variables.len(),
            m = r.variables.len(),
        );
        let dir = tools::temp_dir(&format!("fk-c-{name}"));
        let src = dir.join("gen.c");
        std::fs::write(&src, code + &main).expect("write gen.c");
        let bin = dir.join("gen");
        let mut gcc = Command::new("gcc");
        gcc.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-o"])
            .arg(&bin)
            .arg(&src)
            .arg("-lm");
        tools::run(
            gcc,
            "",
            &format!("gcc -std=c99 -Werror on {}", src.display()),
        );
        let (envs, input) = inputs(&args);
        let out = tools::run(Command::new(&bin), &input, "generated C");
        compare_run(&format!("C {name}"), &out, &r, &entries, &envs);
    }
}

#[test]
fn recurrences_as_numpy_agree_with_the_recurrence() {
    for file in [CHAIN20.to_string(), example("puma560")] {
        let r = load(&file);
        let entries = fk_recurrence(&r, &forced(Format::Sympy, some_point())).expect("entries");
        let code = fk_report(&r, &forced(Format::Python, some_point())).expect("Python code");
        let name = code
            .lines()
            .find_map(|l| l.strip_prefix("def "))
            .and_then(|l| l.split('(').next())
            .expect("function name")
            .to_string();
        let args = signature_args(&code, "def ");
        // All points in one vectorized call: each argument is the column of its values.
        let driver = format!(
            "\nimport sys\ndata = np.loadtxt(sys.stdin, ndmin=2)\nr = {name}(*data.T)\nfor i in range(data.shape[0]):\n    print(' '.join(repr(float(x)) for k in ['dq', 't', 'p', 'j'] for x in np.ravel(r[k][i])))\n"
        );
        let (envs, input) = inputs(&args);
        let out = tools::run_python(&(code + &driver), &input, "numpy");
        compare_run(&format!("Python {name}"), &out, &r, &entries, &envs);
    }
}

#[test]
fn recurrence_latex_renders_in_katex() {
    let r = load(&example("rrr"));
    let o = forced(Format::Latex, some_point());
    let report = fk_report(&r, &o).expect("a report");
    assert!(report.contains("\\mathit{Q2}_{0} &="), "{report}");
    let body: String = report
        .lines()
        .filter(|l| !l.starts_with('%'))
        .collect::<Vec<_>>()
        .join("\n");
    let blocks: Vec<String> = body
        .split("\\end{aligned}")
        .filter(|b| b.contains("\\begin{aligned}"))
        .map(|b| format!("{b}\\end{{aligned}}"))
        .collect();
    tools::katex_all(&blocks, "the LaTeX of a recurrence");
}

#[test]
fn a_robot_symbol_named_like_a_recurrence_entry_is_refused() {
    let text = "name = \"clash\"\nconvention = \"dh\"\n[[joint]]\ntype = \"revolute\"\ntheta = \"theta1\"\nd = \"Q2_3\"\na = \"1\"\nalpha = \"0\"\n[[joint]]\ntype = \"revolute\"\ntheta = \"theta2\"\nd = \"0\"\na = \"1\"\nalpha = \"0\"\n";
    let r = dqsym::parse_robot(text, "clash.toml", &dqsym::eval_scalar_text).expect("a robot");
    let err = fk_recurrence(&r, &forced(Format::Sympy, some_point())).unwrap_err();
    assert_eq!(
        err.to_string(),
        "symbol `Q2_3` is also an entry of the recurrence; rename it"
    );
}

#[test]
fn rrr_forced_into_a_recurrence_reads_as_a_recurrence() {
    // The shape of the report: factors, derivatives, prefix products, the pose, suffix
    // products, matrix, point and Jacobian, each line over the symbols of the lines before.
    let r = load(&example("rrr"));
    let o = forced(Format::Plain, some_point());
    let text = fk_report(&r, &o).expect("a report");
    crate::common::snapshot_settings()
        .bind(|| insta::assert_snapshot!("fk_recurrence_rrr_plain", text));
}
