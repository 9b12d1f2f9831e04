//! Products of cosines and sines of one angle whose factors carry different constant offsets
//! (`cos(x) sin(x + 3*pi/7)`, `(cos(x) - cos(pi/7)) (sin(x) + 1)`): the canonical form holds
//! their multiple-angle sums over the offsets' cyclotomic field, and the closed form finds the
//! product again from the roots of the sum as a polynomial in `e^{i x}` (`closed/roots.rs`).
//! Every printed form is parsed back and compared exactly with its input, evaluated in f64 at
//! random points against the product computed here, and is no longer than the input.

use crate::common::Rng;
use dqsym::closed::Angle;
use dqsym::{closed_form, eval_scalar_text, plain, Expr, PlainOptions, Sym, Trig};
use num_rational::{BigRational, Ratio};
use num_traits::Zero;
use std::f64::consts::PI;

/// Operations in the language's text as a CAS counts them (SymPy's `count_ops`, roughly):
/// every operator and every call.
fn ops(text: &str) -> usize {
    text.chars().filter(|c| "+-*/^".contains(*c)).count()
        + ["cos(", "sin(", "sqrt("]
            .iter()
            .map(|f| text.matches(f).count())
            .sum::<usize>()
}

/// A value as a function of `x` and `l`.
type Value<'a> = dyn Fn(f64, f64) -> f64 + 'a;

/// The language's syntax for printed text, which writes products by juxtaposition.
fn source(text: &str) -> String {
    text.replace(' ', "*")
        .replace("*+*", "+")
        .replace("*-*", "-")
}

/// The closed form of `input`: its printed text parsed back equals the input exactly, its
/// value at random points is `value(x, l)`, and it costs no more operations than `cost`.
fn checked(input: &str, value: &Value, rng: &mut Rng) -> String {
    let v = eval_scalar_text(input).unwrap_or_else(|e| panic!("{input}: {e}"));
    let e = closed_form(&v).expect("closed form");
    let text = plain(&e, &PlainOptions::default());
    let back = eval_scalar_text(&source(&text)).unwrap_or_else(|err| panic!("{text}: {err}"));
    assert_eq!(back, v, "{input} => {text}");
    for _ in 0..4 {
        let (x, l) = (rng.range(-3.0, 3.0), rng.range(0.5, 2.0));
        let got = e.value_at(&[("x", x), ("l", l)]).expect("a value");
        let want = value(x, l);
        assert!(
            (got - want).abs() <= 1e-9 * (1.0 + want.abs()),
            "{input} => {text}: {got} against {want} at x = {x}"
        );
    }
    text
}

#[test]
fn products_with_different_offsets_print_as_products() {
    let mut rng = Rng::new(18);
    let c = |a: f64| a.cos();
    let s = |a: f64| a.sin();
    let cases: [(&str, &Value<'_>, &str); 5] = [
        (
            "cos(x + 5*pi/8)^2",
            &|x, _| c(x + 5.0 * PI / 8.0).powi(2),
            "sin(x + pi/8)^2",
        ),
        (
            "cos(x)*sin(x+3*pi/7)*l",
            &|x, l| c(x) * s(x + 3.0 * PI / 7.0) * l,
            "l cos(x) cos(x - pi/14)",
        ),
        (
            "cos(x+pi/7)*cos(x-2*pi/9)",
            &|x, _| c(x + PI / 7.0) * c(x - 2.0 * PI / 9.0),
            "cos(x - 2*pi/9) cos(x + pi/7)",
        ),
        (
            "sin(x+pi/5)^2*cos(x-pi/3)",
            &|x, _| s(x + PI / 5.0).powi(2) * c(x - PI / 3.0),
            "sin(x + pi/5)^2 cos(x - pi/3)",
        ),
        (
            "(cos(x)-cos(pi/7))*(sin(x)+1)",
            &|x, _| (c(x) - c(PI / 7.0)) * (s(x) + 1.0),
            "(cos(x) - cos(pi/7)) (sin(x) + 1)",
        ),
    ];
    for (input, value, want) in cases {
        let text = checked(input, value, &mut rng);
        assert_eq!(text, want, "{input}");
        assert!(ops(&source(&text)) <= ops(input), "{input} => {text}");
    }
}

/// `cos` or `sin` of `k x + (p/q) pi`.
fn trig(sin: bool, k: i64, p: i64, q: i64) -> Expr {
    Expr::Trig {
        f: if sin { Trig::Sin } else { Trig::Cos },
        angle: Angle::new(
            vec![(Sym::new("x"), Ratio::from_integer(k))],
            Ratio::zero(),
            Ratio::new(p, q),
        ),
    }
}

/// A random factor: `cos`/`sin(k x + p pi/q)` to a small power, or `cos(x) - cos(p pi/q)`; its
/// expression and its value at `x`.
fn factor(rng: &mut Rng) -> (Expr, Box<dyn Fn(f64) -> f64>) {
    let pick = |rng: &mut Rng, n: usize| (rng.range(0.0, n as f64) as usize).min(n - 1);
    let q = [5, 7, 8, 9, 10, 12, 16, 24][pick(rng, 8)];
    // An offset in (-1, 1), not 0, as p/q.
    let mut p = pick(rng, 2 * q as usize - 1) as i64 - (q - 1);
    if p == 0 {
        p = 1;
    }
    let r = Ratio::new(p, q);
    let (p, q) = (*r.numer(), *r.denom());
    let phase = PI * p as f64 / q as f64;
    if pick(rng, 5) == 0 {
        // cos(x) - cos(|p| pi/q).
        let (p, phase) = (p.abs(), phase.abs());
        let e = Expr::Add(vec![
            trig(false, 1, 0, 1),
            Expr::Neg(Box::new(Expr::Trig {
                f: Trig::Cos,
                angle: Angle::new(Vec::new(), Ratio::zero(), Ratio::new(p, q)),
            })),
        ]);
        return (e, Box::new(move |x: f64| x.cos() - phase.cos()));
    }
    let sin = pick(rng, 2) == 1;
    let k = 1 + pick(rng, 3) as i64;
    let power = 1 + pick(rng, 2) as u32;
    let base = trig(sin, k, p, q);
    let e = if power == 1 {
        base
    } else {
        Expr::Pow(Box::new(base), power)
    };
    let f = move |x: f64| {
        let a = k as f64 * x + phase;
        (if sin { a.sin() } else { a.cos() }).powi(power as i32)
    };
    (e, Box::new(f))
}

#[test]
fn random_products_of_offset_factors_come_back_no_longer() {
    let mut rng = Rng::new(1801);
    let mut longer = Vec::new();
    for _ in 0..40 {
        // Two to four factors (one alone is the offsets' business, `offsets.rs`).
        let count = 2 + (rng.range(0.0, 3.0) as usize).min(2);
        let mut factors: Vec<Expr> = Vec::new();
        let mut values: Vec<Box<dyn Fn(f64) -> f64>> = Vec::new();
        // Times `l` or a rational.
        let by_symbol = rng.range(0.0, 1.0) < 0.5;
        let r = (
            1 + (rng.range(0.0, 5.0) as i64),
            1 + (rng.range(0.0, 3.0) as i64),
        );
        factors.push(if by_symbol {
            Expr::Sym(Sym::new("l"))
        } else {
            Expr::Num(BigRational::new(r.0.into(), r.1.into()))
        });
        for _ in 0..count {
            let (e, v) = factor(&mut rng);
            factors.push(e);
            values.push(v);
        }
        let input = Expr::Mul(factors);
        let text = plain(&input, &PlainOptions::default());
        let value = |x: f64, l: f64| {
            let m = if by_symbol {
                l
            } else {
                r.0 as f64 / r.1 as f64
            };
            values.iter().map(|f| f(x)).product::<f64>() * m
        };
        let input = source(&text);
        // Offsets whose field is past the cyclotomic degree limit are an error, not a form.
        if eval_scalar_text(&input).is_err() {
            continue;
        }
        let out = checked(&input, &value, &mut rng);
        if ops(&source(&out)) > ops(&input) {
            longer.push(format!("{input} => {out}"));
        }
    }
    // The text count differs from the closed forms' own cost (which counts an angle over a
    // common denominator as one division, a power once): a few forms may read one operation
    // longer by it; they are printed.
    assert!(
        longer.len() <= 2,
        "longer than the input:\n{}",
        longer.join("\n")
    );
}

/// A value as a function of `x`, `y` and `z`.
type Value3<'a> = dyn Fn(f64, f64, f64) -> f64 + 'a;

/// [`checked`] for a scalar in `x`, `y` and `z`: the printed text parsed back equals the input
/// exactly, and its value at random points is `value(x, y, z)`.
fn checked_xyz(input: &str, value: &Value3, rng: &mut Rng) -> String {
    let v = eval_scalar_text(input).unwrap_or_else(|e| panic!("{input}: {e}"));
    let e = closed_form(&v).expect("closed form");
    let text = plain(&e, &PlainOptions::default());
    let back = eval_scalar_text(&source(&text)).unwrap_or_else(|err| panic!("{text}: {err}"));
    assert_eq!(back, v, "{input} => {text}");
    for _ in 0..4 {
        let (x, y, z) = (
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        );
        let got = e
            .value_at(&[("x", x), ("y", y), ("z", z)])
            .expect("a value");
        let want = value(x, y, z);
        assert!(
            (got - want).abs() <= 1e-9 * (1.0 + want.abs()),
            "{input} => {text}: {got} against {want} at x = {x}, y = {y}, z = {z}"
        );
    }
    text
}

#[test]
fn products_in_two_symbols_print_as_products() {
    // No common shift of the offsets exists (the modes x - y and x + y both appear), so
    // only the parts' roots find the product.
    let mut rng = Rng::new(1802);
    let c = |a: f64| a.cos();
    let s = |a: f64| a.sin();
    let cases: [(&str, &Value3<'_>, &str); 4] = [
        (
            "sin(x - 5*pi/8)*cos(y + 3*pi/8)",
            &|x, y, _| s(x - 5.0 * PI / 8.0) * c(y + 3.0 * PI / 8.0),
            "cos(x - pi/8) sin(y - pi/8)",
        ),
        (
            "cos(x+pi/7)*cos(y-2*pi/9)*sin(x)",
            &|x, y, _| c(x + PI / 7.0) * c(y - 2.0 * PI / 9.0) * s(x),
            "sin(x) cos(x + pi/7) cos(y - 2*pi/9)",
        ),
        // Three parts; two, one of them in the angle x + z.
        (
            "cos(x+pi/7)*sin(y-2*pi/9)*sin(z+pi/5)",
            &|x, y, z| c(x + PI / 7.0) * s(y - 2.0 * PI / 9.0) * s(z + PI / 5.0),
            "cos(x + pi/7) sin(y - 2*pi/9) sin(z + pi/5)",
        ),
        (
            "cos(x+z-pi/7)*sin(y+3*pi/8)",
            &|x, y, z| c(x + z - PI / 7.0) * s(y + 3.0 * PI / 8.0),
            "cos(x + z - pi/7) cos(y - pi/8)",
        ),
    ];
    for (input, value, want) in cases {
        let text = checked_xyz(input, value, &mut rng);
        assert_eq!(text, want, "{input}");
        assert!(ops(&source(&text)) <= ops(input), "{input} => {text}");
    }
}

/// `cos` or `sin` of `k v + (p/q) pi`.
fn trig_in(v: &str, sin: bool, k: i64, p: i64, q: i64) -> Expr {
    Expr::Trig {
        f: if sin { Trig::Sin } else { Trig::Cos },
        angle: Angle::new(
            vec![(Sym::new(v), Ratio::from_integer(k))],
            Ratio::zero(),
            Ratio::new(p, q),
        ),
    }
}

#[test]
fn random_products_in_two_symbols_come_back_no_longer() {
    let mut rng = Rng::new(1803);
    let pick = |rng: &mut Rng, n: usize| (rng.range(0.0, n as f64) as usize).min(n - 1);
    let (mut tried, mut longer) = (0, Vec::new());
    for _ in 0..40 {
        let mut factors: Vec<Expr> = Vec::new();
        // (symbol index, sine, multiple, offset in pi).
        let mut parts: Vec<(usize, bool, i64, f64)> = Vec::new();
        for (i, v) in ["x", "y"].into_iter().enumerate() {
            for _ in 0..1 + pick(&mut rng, 2) {
                // An offset p pi/q in (-pi, pi) in lowest terms (offsets in pi/12 are the
                // offsets' business, `offsets.rs`).
                let q: i64 = [5, 7, 8, 9, 16][pick(&mut rng, 5)];
                let p = loop {
                    let p = pick(&mut rng, 2 * q as usize - 1) as i64 - (q - 1);
                    if *Ratio::new(p, q).denom() == q {
                        break p;
                    }
                };
                let sin = pick(&mut rng, 2) == 1;
                let k = 1 + pick(&mut rng, 2) as i64;
                factors.push(trig_in(v, sin, k, p, q));
                parts.push((i, sin, k, p as f64 / q as f64));
            }
        }
        let input = source(&plain(&Expr::Mul(factors), &PlainOptions::default()));
        // Offsets whose field is past the cyclotomic degree limit are an error, not a form.
        if eval_scalar_text(&input).is_err() {
            continue;
        }
        tried += 1;
        let value = |x: f64, y: f64, _: f64| {
            parts
                .iter()
                .map(|&(i, sin, k, p)| {
                    let a = k as f64 * [x, y][i] + p * PI;
                    if sin {
                        a.sin()
                    } else {
                        a.cos()
                    }
                })
                .product::<f64>()
        };
        let out = checked_xyz(&input, &value, &mut rng);
        if ops(&source(&out)) > ops(&input) {
            longer.push(format!("{input} => {out}"));
        }
    }
    assert!(tried >= 16, "only {tried} products in the cyclotomic limit");
    assert!(
        longer.is_empty(),
        "longer than the input:\n{}",
        longer.join("\n")
    );
}
