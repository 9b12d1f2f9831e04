//! The trigonometric identity corpus, `tests/data/trig_identities.txt` (written by
//! `scripts/trig_corpus.py`): textbook, half- and multiple-angle, Chebyshev, regular-polygon,
//! Morrie's-law, exact-constant, offset and robotics identities, one `lhs = rhs` a line with the
//! hand-simplified form on the right. Every line is an exact zero (`lhs - rhs` is the zero
//! scalar), checked numerically by SymPy too; the closed form of `lhs` is compared with the
//! hand form and with SymPy's `trigsimp` and `fu` by `count_ops`.

use crate::tools::{json_string, run_python};
use dqsym::{closed_form, emit::sympy, eval_scalar_text};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

struct Line {
    category: String,
    lhs: String,
    rhs: String,
}

fn corpus() -> Vec<Line> {
    let text = std::fs::read_to_string(format!("{ROOT}/tests/data/trig_identities.txt"))
        .expect("tests/data/trig_identities.txt");
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let (category, rest) = l.split_once(" | ").expect("category | lhs = rhs");
            let (lhs, rhs) = rest.split_once(" = ").expect("lhs = rhs");
            Line {
                category: category.trim().to_owned(),
                lhs: lhs.trim().to_owned(),
                rhs: rhs.trim().to_owned(),
            }
        })
        .collect()
}

#[test]
fn the_corpus_has_every_category_and_at_least_300_identities() {
    let c = corpus();
    assert!(c.len() >= 300, "{} identities", c.len());
    for cat in [
        "textbook",
        "half-angle",
        "multiple-angle",
        "chebyshev",
        "polygon",
        "morrie",
        "constants",
        "offsets",
        "robotics",
        "factorization",
        "sum-to-product",
    ] {
        assert!(c.iter().any(|l| l.category == cat), "no {cat} identity");
    }
}

#[test]
fn every_identity_is_an_exact_zero() {
    for l in corpus() {
        let a = eval_scalar_text(&l.lhs).unwrap_or_else(|e| panic!("{e}"));
        let b = eval_scalar_text(&l.rhs).unwrap_or_else(|e| panic!("{e}"));
        let d = (&a - &b).check().expect("exact difference");
        assert!(d.is_zero_value(), "{} - ({}) = {d}", l.lhs, l.rhs);
        assert_eq!(a, b, "{}", l.lhs);
        // The closed form is exactly the value (closed_form checks it; the round trip here
        // makes sure of it independently of that check).
        let e = closed_form(&a).expect("closed form");
        assert_eq!(e.to_scalar(), a, "{}", l.lhs);
    }
}

/// SymPy checks every identity numerically at random points (independently of dqsym), and
/// `count_ops` of our closed form is at most that of the smaller of SymPy's `trigsimp` and `fu`
/// for at least 95% of the corpus; the others are printed.
#[test]
fn closed_forms_are_as_short_as_sympy_trigsimp_and_fu() {
    let lines = corpus();
    let mut items = Vec::new();
    for l in &lines {
        let a = eval_scalar_text(&l.lhs).unwrap_or_else(|e| panic!("{e}"));
        let ours = sympy(&closed_form(&a).expect("closed form"));
        items.push(format!(
            "[{},{},{}]",
            json_string(&l.lhs),
            json_string(&l.rhs),
            json_string(&ours)
        ));
    }
    let script = r#"
import json, re, random, signal, sys
from sympy import sympify, count_ops, trigsimp, Symbol, N
from sympy.simplify.fu import fu

class Slow(Exception):
    pass

def alarm(*_):
    raise Slow()

signal.signal(signal.SIGALRM, alarm)

def limited(f, e):
    signal.alarm(4)
    try:
        return f(e)
    except Slow:
        return e
    finally:
        signal.alarm(0)

out = []
for lhs, rhs, ours in json.load(sys.stdin):
    text = lhs + " " + rhs + " " + ours
    names = set(re.findall(r"[A-Za-z_][A-Za-z_0-9]*", text)) - {"sin", "cos", "sqrt", "pi"}
    loc = {n: Symbol(n, real=True) for n in names}
    L = sympify(lhs.replace("^", "**"), locals=loc)
    R = sympify(rhs.replace("^", "**"), locals=loc)
    O = sympify(ours, locals=loc)
    rnd = random.Random(lhs)
    for _ in range(3):
        pt = {s: rnd.uniform(-2, 2) for s in loc.values()}
        a, b, c = (complex(N(e.subs(pt), 30)) for e in (L, R, O))
        assert abs(a - b) < 1e-9 * (1 + abs(a)), (lhs, rhs, a, b)
        assert abs(a - c) < 1e-9 * (1 + abs(a)), (lhs, ours, a, c)
    t = limited(trigsimp, L)
    f = limited(fu, L)
    out.append([count_ops(O), count_ops(t), count_ops(f), count_ops(R), str(t), str(f)])
print(json.dumps(out))
"#;
    let answer = run_python(script, &format!("[{}]", items.join(",")), "sympy");
    let rows: Vec<serde_json::Value> = serde_json::from_str(answer.trim()).expect("json");
    assert_eq!(rows.len(), lines.len());
    let mut worse = Vec::new();
    let mut longer_than_hand = 0;
    for (l, r) in lines.iter().zip(&rows) {
        let n = |i: usize| r[i].as_u64().expect("count");
        let (ours, t, f, hand) = (n(0), n(1), n(2), n(3));
        if ours > hand {
            longer_than_hand += 1;
        }
        if ours > t.min(f) {
            worse.push(format!(
                "  {} [{}]: ours {ours} ops, trigsimp {t} ({}), fu {f} ({}), hand {hand}",
                l.lhs, l.category, r[4], r[5]
            ));
        }
    }
    println!(
        "{} identities; ours <= min(trigsimp, fu) for {}; longer than the hand form: {}",
        lines.len(),
        lines.len() - worse.len(),
        longer_than_hand
    );
    println!("where SymPy is shorter:\n{}", worse.join("\n"));
    assert!(
        worse.len() * 20 <= lines.len(),
        "SymPy is shorter on {} of {} identities:\n{}",
        worse.len(),
        lines.len(),
        worse.join("\n")
    );
}

/// The number of factors of a product (a power counted by its exponent), 1 otherwise.
fn factor_count(e: &dqsym::Expr) -> u32 {
    match e {
        dqsym::Expr::Mul(v) => v.iter().map(factor_count).sum(),
        dqsym::Expr::Neg(x) => factor_count(x),
        dqsym::Expr::Pow(x, n) => match **x {
            dqsym::Expr::Add(_) => *n,
            _ => 1,
        },
        dqsym::Expr::Num(_) => 0,
        _ => 1,
    }
}

/// Polynomials in the cosines and sines of several angles, given expanded (or through their
/// multiple-angle sums), come back as products of their factors over the integers: the
/// closed form has at least the given number of factors (two factors whose product has a
/// shorter closed form of its own are shown as that), equals the input exactly, and agrees at
/// random points with the product evaluated here in floating point (independently of dqsym).
#[test]
fn polynomials_in_several_angles_are_factored_over_the_integers() {
    type F = fn(f64, f64, f64) -> f64;
    let cases: [(&str, u32, F); 8] = [
        (
            "1 + cos(a) - cos(b) - (cos(a - b) + cos(a + b))/2",
            2,
            |a, b, _| (1.0 + a.cos()) * (1.0 - b.cos()),
        ),
        (
            "2 + cos(c) + 2*cos(a) + cos(a)*cos(c) - 2*cos(b) - cos(b)*cos(c) - 2*cos(a)*cos(b) - cos(a)*cos(b)*cos(c)",
            3,
            |a, b, c| (1.0 + a.cos()) * (1.0 - b.cos()) * (2.0 + c.cos()),
        ),
        (
            "cos(a)*cos(b) + cos(a)*sin(c) + sin(b)*cos(b) + sin(b)*sin(c)",
            2,
            |a, b, c| (a.cos() + b.sin()) * (b.cos() + c.sin()),
        ),
        (
            "(cos(2*a) - cos(2*b))*(sin(c) + cos(a))/2",
            2,
            |a, b, c| (a.cos().powi(2) - b.cos().powi(2)) * (c.sin() + a.cos()),
        ),
        (
            "cos(a)^2 + 2*cos(a)*cos(b) + cos(b)^2 - sin(c)*(cos(a)^2 + 2*cos(a)*cos(b) + cos(b)^2)",
            3,
            |a, b, c| (a.cos() + b.cos()).powi(2) * (1.0 - c.sin()),
        ),
        (
            "(cos(2*a) - cos(2*b))*(1 + cos(c))",
            2,
            |a, b, c| ((2.0 * a).cos() - (2.0 * b).cos()) * (1.0 + c.cos()),
        ),
        (
            "(cos(a)*cos(b) + sin(c))*(cos(b) - sin(a))*(2 + cos(c))",
            2,
            |a, b, c| (a.cos() * b.cos() + c.sin()) * (b.cos() - a.sin()) * (2.0 + c.cos()),
        ),
        (
            "(3*cos(a)^2 + cos(b) + 1)*(cos(c) - cos(a) + 2)",
            2,
            |a, b, c| (3.0 * a.cos().powi(2) + b.cos() + 1.0) * (c.cos() - a.cos() + 2.0),
        ),
    ];
    let mut rng = crate::common::Rng::new(0x853c_49e6_748f_ea9b);
    let mut uniform = || rng.range(-3.0, 3.0);
    for (text, factors, direct) in cases {
        let x = eval_scalar_text(text).unwrap_or_else(|e| panic!("{e}"));
        let e = closed_form(&x).expect("closed form");
        assert_eq!(e.to_scalar(), x, "{text}");
        assert!(factor_count(&e) >= factors, "{text}: {}", sympy(&e));
        for _ in 0..20 {
            let (a, b, c) = (uniform(), uniform(), uniform());
            let v = e.value_at(&[("a", a), ("b", b), ("c", c)]).expect("value");
            let w = direct(a, b, c);
            assert!(
                (v - w).abs() < 1e-9 * (1.0 + w.abs()),
                "{text} at {a}, {b}, {c}: {v} vs {w}"
            );
        }
    }
}

/// The factorization is charged to the work budget: a product of three factors in three
/// angles and three lengths, expanded, is factored back within a bounded amount of work, and with a
/// budget too small for it the closed form is still an exact (unfactored) form or a budget
/// error, never a hang.
#[test]
fn the_factorization_stays_within_the_work_budget() {
    let text = "(l1 + l2*cos(a))*(1 - cos(b))*(d3 + sin(c))";
    let x = eval_scalar_text(text).unwrap_or_else(|e| panic!("{e}"));
    let ctx = dqsym::Context::new();
    let entered = ctx.enter();
    let e = closed_form(&x).expect("closed form");
    let used = entered.work_used();
    drop(entered);
    assert_eq!(e.to_scalar(), x);
    assert_eq!(factor_count(&e), 3, "{}", sympy(&e));
    assert!(used < 5_000_000, "closed form used {used} units of work");
    let small = dqsym::Context::new().with_work_budget(used / 4);
    let _in = small.enter();
    match closed_form(&x) {
        Ok(e) => assert_eq!(e.to_scalar(), x),
        Err(err) => assert!(matches!(err, dqsym::ScalarError::Budget { .. }), "{err}"),
    }
}
