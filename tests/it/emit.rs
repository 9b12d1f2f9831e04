//! Emitters: LaTeX snapshots rendered by KaTeX, SymPy text parsed back by SymPy and compared
//! numerically with `Scalar::eval`.

use crate::paper_support::*;
use crate::tools;
use dqsym::{
    emit::{latex_aligned, latex_dual_quat, latex_matrix, latex_symbol, latex_tuple, sympy},
    latex, DualQuat, Expr, LatexOptions,
};

fn t(i: usize) -> S {
    sym(&format!("theta{i}"))
}

/// The planar RRR arm of sec 6.1: the product q_d1 q_d2 q_d3 and the end effector v0.
pub fn rrr() -> (DualQuat<S>, [S; 3]) {
    let (l1, l2, l3) = (sym("l1"), sym("l2"), sym("l3"));
    let about = |i, y: S| DualQuat::rotation_about_point(&ex(), &t(i), &v3(int(0), y, int(0)));
    let q = about(1, int(0)) * about(2, l1.clone()) * about(3, &l1 + &l2);
    let v0 = q.transform_point(&v3(int(0), &l1 + &l2 + &l3, int(0)));
    (q, v0)
}

/// The matrix [R] of sec 3-A.
fn sec3a() -> [[S; 3]; 3] {
    let h = half(&sym("theta"));
    let s = sin(&h);
    let q = DualQuat::from_real(quat(
        cos(&h),
        int(6).sqrt() * frac(1, 4) * &s,
        int(2).sqrt() * frac(1, 4) * &s,
        int(2).sqrt() * frac(1, 2) * &s,
    ));
    let m = q.to_matrix();
    std::array::from_fn(|i| std::array::from_fn(|j| m.rows[i][j].clone()))
}

fn closed_all(v: &[S]) -> Vec<Expr> {
    v.iter().map(closed).collect()
}

/// Asserts a LaTeX snapshot after KaTeX has rendered it without error.
fn latex_snap(name: &str, tex: &str) {
    tools::katex(tex, name);
    crate::common::snapshot_settings().bind(|| insta::assert_snapshot!(name, tex));
}

const SHORT: LatexOptions = LatexOptions {
    shorthand: true,
    width: 80,
    decimals: false,
};
const EXPLICIT: LatexOptions = LatexOptions {
    shorthand: false,
    width: 80,
    decimals: false,
};

#[test]
fn latex_uses_the_papers_notation() {
    let o = SHORT;
    let e = |x: &S| latex(&closed(x), &o);
    assert_eq!(e(&int(1)), "1");
    assert_eq!(e(&frac(3, 8)), "\\frac{3}{8}");
    assert_eq!(e(&int(2).sqrt()), "\\sqrt{2}");
    assert_eq!(e(&(cos(&(t(1) + t(2))) * sym("l2"))), "l_{2} c_{12}");
    assert_eq!(
        latex(&closed(&(cos(&(t(1) + t(2))) * sym("l2"))), &EXPLICIT),
        "l_{2} \\cos(\\theta_{1} + \\theta_{2})"
    );
    assert_eq!(e(&sin(&half(&t(3)))), "\\sin(\\frac{\\theta_{3}}{2})");
    assert_eq!(latex_symbol("alpha2"), "\\alpha_{2}");
    assert_eq!(latex_symbol("a2"), "a_{2}");
    assert_eq!(latex_symbol("d"), "d");
}

#[test]
fn latex_rrr_end_effector_and_product() {
    let (q, v0) = rrr();
    let c = q.components();
    let real = closed_all(&c[..4]);
    let dual = closed_all(&c[4..]);
    let v = closed_all(&v0);
    let names = ["x", "y", "z"];
    let rows: Vec<(String, Expr)> = names
        .iter()
        .zip(&v)
        .map(|(n, e)| (format!("v_{{0,{n}}}"), e.clone()))
        .collect();
    let tex = format!(
        "\\begin{{gathered}}\nq_{{d1}} q_{{d2}} q_{{d3}} = {}\\\\\nv_0 = {}\\\\\n{}\n\\end{{gathered}}",
        latex_dual_quat(&real, &dual, &SHORT),
        latex_tuple(&v, &SHORT),
        latex_aligned(&rows, &EXPLICIT)
    );
    assert!(tex.contains("l_{1} c_{1} + l_{2} c_{12} + l_{3} c_{123}"));
    latex_snap("latex_rrr", &tex);
}

#[test]
fn latex_sec3a_rotation_matrix() {
    let m = sec3a();
    let rows: Vec<Vec<Expr>> = m.iter().map(|r| closed_all(r)).collect();
    let tex = format!("[R] = {}", latex_matrix(&rows, &EXPLICIT));
    assert!(tex.contains("\\sqrt{6}"));
    latex_snap("latex_sec3a_matrix", &tex);
}

#[test]
fn latex_puma560_pose_matrix_and_dual_quaternion() {
    let (q, _) = crate::paper_arms::puma560();
    let m = q.to_matrix();
    let rows: Vec<Vec<Expr>> = m.rows.iter().map(|r| closed_all(r)).collect();
    let comps: Vec<(String, Expr)> = q
        .components()
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let name = if k < 4 {
                format!("q_{{{k}}}")
            } else {
                format!("q_{{\\varepsilon {}}}", k - 4)
            };
            (name, closed(c))
        })
        .collect();
    let tex = format!(
        "\\begin{{gathered}}\nT = {}\\\\\n{}\n\\end{{gathered}}",
        latex_matrix(&rows, &SHORT),
        latex_aligned(&comps, &SHORT)
    );
    // The long DQ components are broken over lines, and no line is very long.
    let lines: Vec<&str> = tex
        .lines()
        .filter(|l| l.contains("&=") || l.starts_with('&'))
        .collect();
    assert!(lines.len() > 12, "{} lines", lines.len());
    for line in lines {
        assert!(line.len() < 300, "long line: {line}");
    }
    latex_snap("latex_puma560_pose", &tex);
}

/// Values whose SymPy text is parsed back by `sympify` and compared with `Scalar::eval`.
fn sympy_cases() -> Vec<(String, Expr)> {
    let mut v: Vec<(String, Expr)> = Vec::new();
    let mut push = |name: &str, x: &S| v.push((name.to_string(), closed(x)));
    push("one", &int(1));
    push("minus half", &frac(-1, 2));
    push("3/8 x", &(frac(3, 8) * sym("x")));
    push("sqrt", &(int(8).sqrt() * sin(&half(&sym("theta")))));
    push(
        "pi shift",
        &cos(&(sym("theta") * frac(3, 2) - S::pi() * frac(1, 3))),
    );
    push(
        "square",
        &((sym("l1") + sym("l2")) * (sym("l1") + sym("l2"))),
    );
    let (q, v0) = rrr();
    for (k, c) in q.components().iter().enumerate() {
        push(&format!("rrr q[{k}]"), c);
    }
    for (k, c) in v0.iter().enumerate() {
        push(&format!("rrr v0[{k}]"), c);
    }
    for (i, r) in sec3a().iter().enumerate() {
        for (j, c) in r.iter().enumerate() {
            push(&format!("sec3a R[{i}][{j}]"), c);
        }
    }
    let (q, _) = crate::paper_arms::puma560();
    let m = q.to_matrix();
    for i in 0..3 {
        for j in 0..4 {
            push(&format!("puma T[{i}][{j}]"), &m.rows[i][j]);
        }
    }
    for (k, c) in q.components().iter().enumerate() {
        push(&format!("puma q[{k}]"), c);
    }
    // Shapes the closed forms above may not produce.
    let x = || Box::new(Expr::Sym(dqsym::Sym::new("x")));
    v.push(("neg power".into(), Expr::Neg(Box::new(Expr::Pow(x(), 2)))));
    v.push((
        "power of neg".into(),
        Expr::Pow(Box::new(Expr::Neg(x())), 3),
    ));
    v.push((
        "power of fraction".into(),
        Expr::Pow(Box::new(closed(&frac(1, 2))), 3),
    ));
    v.push((
        "fraction after symbol".into(),
        Expr::Mul(vec![Expr::Sym(dqsym::Sym::new("x")), closed(&frac(1, 3))]),
    ));
    v
}

#[test]
fn sympy_prints_one_as_1_and_fractions_in_parentheses() {
    assert_eq!(sympy(&closed(&int(1))), "1");
    assert_eq!(sympy(&closed(&frac(3, 8))), "3/8");
    assert_eq!(sympy(&closed(&(frac(3, 8) * sym("x")))), "(3/8)*x");
    assert_eq!(
        sympy(&closed(&(sym("l2") * cos(&(t(1) + t(2)))))),
        "l2*cos(theta1 + theta2)"
    );
}

#[test]
fn sympy_text_round_trips_through_sympify() {
    let cases = sympy_cases();
    let mut names: Vec<String> = cases
        .iter()
        .flat_map(|(_, e)| e.to_scalar().symbols())
        .map(|s| s.name().to_string())
        .filter(|n| n != "pi")
        .collect();
    names.sort();
    names.dedup();
    let points = points(&names.iter().map(String::as_str).collect::<Vec<_>>(), 3);
    // Input: the names, then one line per point, then one expression per line.
    let mut input = format!("{}\n{}\n", names.join(" "), points.len());
    for p in &points {
        let vals: Vec<String> = p.iter().map(|(_, v)| format!("{v:?}")).collect();
        input.push_str(&vals.join(" "));
        input.push('\n');
    }
    for (_, e) in &cases {
        input.push_str(&sympy(e));
        input.push('\n');
    }
    let script = r#"
import sys, sympy
lines = sys.stdin.read().splitlines()
names = lines[0].split()
n = int(lines[1])
pts = [[float(x) for x in l.split()] for l in lines[2:2 + n]]
syms = {k: sympy.Symbol(k) for k in names}
for text in lines[2 + n:]:
    e = sympy.sympify(text, locals=syms)
    for p in pts:
        print(repr(float(e.evalf(30, subs={syms[k]: v for k, v in zip(names, p)}))))
"#;
    let out = tools::run_python(script, &input, "sympy");
    let mut got = out.lines().map(|l| l.parse::<f64>().expect("a number"));
    for (name, e) in &cases {
        let x = e.to_scalar();
        for p in &points {
            let want = ev(&x, p);
            let g = got.next().expect("one value per case and point");
            assert!(
                (g - want).abs() <= 1e-9 * (1.0 + want.abs()),
                "{name}: sympy {g} != {want} for `{}`",
                sympy(e)
            );
        }
    }
    assert!(got.next().is_none());
}

#[test]
fn latex_of_jacobians_renders_in_katex() {
    let tex = tools::dqsym_ok(&[
        "-e",
        "jacobian(dh(theta1, d1, a1, pi/2) * dh(theta2, 0, a2, 0), [theta1, theta2])",
        "--format",
        "latex",
    ]);
    assert!(tex.contains("\\begin{pmatrix}"), "{tex}");
    tools::katex(&tex, "the LaTeX of an 8 x 2 Jacobian");
    let rrr = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/rrr.toml");
    let report = tools::dqsym_ok(&["fk", rrr, "--jacobian", "--format", "latex"]);
    // Each aligned block is one formula; the % lines are comments.
    let body: String = report
        .lines()
        .filter(|l| !l.starts_with('%'))
        .collect::<Vec<_>>()
        .join("\n");
    for block in body
        .split("\\end{aligned}")
        .filter(|b| b.contains("\\begin{aligned}"))
    {
        tools::katex(
            &format!("{block}\\end{{aligned}}"),
            "an fk --jacobian LaTeX block",
        );
    }
    assert!(report.contains("J_{"), "{report}");
}
