//! Short closed forms for constants and the angle text (issue 18): powers of equal symbols,
//! the factorization read in angle sums, products of constant cosines with radical cofactors
//! or beside a constant, and a rational constant shown after the symbols of its angle. Every
//! case: the printed text, exact equality with the input, the f64 value at random points
//! against a formula written here, and the explicit text parsed back to the input.

use crate::common::Rng;
use dqsym::{closed_form, emit::sympy, eval_scalar_text, plain, PlainOptions};
use std::f64::consts::PI;

type F = fn(&dyn Fn(&str) -> f64) -> f64;

/// Checks one case: text, exact value, f64 value at 10 points, explicit text read back.
fn check(input: &str, want: &str, direct: F) {
    let x = eval_scalar_text(input).unwrap_or_else(|e| panic!("{input}: {e}"));
    let e = closed_form(&x).expect("closed form");
    assert_eq!(e.to_scalar(), x, "{input}");
    assert_eq!(plain(&e, &PlainOptions::default()), want, "{input}");
    let explicit = plain(
        &e,
        &PlainOptions {
            shorthand: false,
            decimals: false,
        },
    );
    let back = eval_scalar_text(&explicit).unwrap_or_else(|err| panic!("{explicit}: {err}"));
    assert_eq!(back, x, "{input}: {explicit} reads back to another value");
    let mut g = Rng::new(0x9e37_79b9_7f4a_7c15 ^ input.len() as u64);
    for _ in 0..10 {
        let vals: Vec<(String, f64)> = e
            .symbol_names()
            .into_iter()
            .map(|n| (n, g.range(-2.0, 2.0)))
            .collect();
        let env = |n: &str| {
            vals.iter()
                .find(|(m, _)| m == n)
                .map(|(_, v)| *v)
                .unwrap_or_else(|| panic!("no value for {n}"))
        };
        let want_v = direct(&env);
        let shown = e.to_scalar().eval(&|n| Some(env(n))).expect("value");
        let pairs: Vec<(&str, f64)> = vals.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let display = e.value_at(&pairs).expect("value");
        for v in [shown, display] {
            assert!(
                (v - want_v).abs() < 1e-9 * (1.0 + want_v.abs()),
                "{input}: {v} vs {want_v}"
            );
        }
    }
}

#[test]
fn equal_factors_print_as_powers() {
    check(
        "x^2*cos(a) + x^2*y*sin(a) + x^3",
        "x^2 (cos(a) + y sin(a) + x)",
        |v| v("x").powi(2) * (v("a").cos() + v("y") * v("a").sin() + v("x")),
    );
    // A symbol pulled out of a sum meets its own power inside: `a2^2`, never `a2 a2`.
    for input in [
        "a2^2*cos(a)^2*sin(b) + a2^2*cos(b)*a3",
        "l1^3*cos(t) + l1^2*sin(t)",
    ] {
        let x = eval_scalar_text(input).expect(input);
        let text = plain(
            &closed_form(&x).expect("closed form"),
            &PlainOptions::default(),
        );
        for s in ["a2 a2", "l1 l1"] {
            assert!(!text.contains(s), "{input}: {text}");
        }
    }
}

#[test]
fn squares_of_angle_sums_are_read_as_variables_of_their_own() {
    check(
        "a2^2*cos(a)^2 - a3^2*cos(a+b)^2",
        "a2^2 cos(a)^2 - a3^2 cos(a + b)^2",
        |v| (v("a2") * v("a").cos()).powi(2) - (v("a3") * (v("a") + v("b")).cos()).powi(2),
    );
    check(
        "(l2*cos(t1) - l3*cos(t1 + t2))*(l2*cos(t1) + l3*cos(t1 + t2))",
        "l2^2 c1^2 - l3^2 c12^2",
        |v| (v("l2") * v("t1").cos()).powi(2) - (v("l3") * (v("t1") + v("t2")).cos()).powi(2),
    );
    check(
        "cos(a + b)^2 - x*cos(c - d)^2",
        "cos(a + b)^2 - x cos(c - d)^2",
        |v| (v("a") + v("b")).cos().powi(2) - v("x") * (v("c") - v("d")).cos().powi(2),
    );
}

#[test]
fn constants_print_as_products_with_radicals_and_beside_constants() {
    check(
        "sin(pi/11)^2*cos(pi/5)",
        "1/4 (1 + sqrt(5)) sin(pi/11)^2",
        |_| (PI / 11.).sin().powi(2) * (PI / 5.).cos(),
    );
    check("1 - cos(pi/7)*cos(pi/9)", "1 - cos(pi/7) cos(pi/9)", |_| {
        1. - (PI / 7.).cos() * (PI / 9.).cos()
    });
    check(
        "sqrt(2)*sin(pi/7)^2*cos(pi/9) - 3/4",
        "sqrt(2) sin(pi/7)^2 cos(pi/9) - 3/4",
        |_| 2f64.sqrt() * (PI / 7.).sin().powi(2) * (PI / 9.).cos() - 0.75,
    );
    check(
        "x*sqrt(3)*cos(pi/7)*sin(pi/11)",
        "sqrt(3) x cos(pi/7) sin(pi/11)",
        |v| 3f64.sqrt() * v("x") * (PI / 7.).cos() * (PI / 11.).sin(),
    );
    check(
        "2 + sqrt(5)*cos(pi/7)*cos(pi/16)",
        "2 + sqrt(5) cos(pi/7) cos(pi/16)",
        |_| 2. + 5f64.sqrt() * (PI / 7.).cos() * (PI / 16.).cos(),
    );
}

#[test]
fn an_angles_constant_prints_after_its_symbols() {
    check("sin(1/3 - t/2)", "-sin(t/2 - 1/3)", |v| {
        (1. / 3. - v("t") / 2.).sin()
    });
    check("cos(1/3 - t/2)", "cos(t/2 - 1/3)", |v| {
        (1. / 3. - v("t") / 2.).cos()
    });
    check("cos(t + 2)", "cos(t + 2)", |v| (v("t") + 2.).cos());
    check("x*sin(2 - u)", "-x sin(u - 2)", |v| {
        v("x") * (2. - v("u")).sin()
    });
    // Every emitter writes the same angle.
    let x = eval_scalar_text("sin(1/3 - t/2)").expect("value");
    let e = closed_form(&x).expect("closed form");
    assert_eq!(sympy(&e), "-sin(t/2 - 1/3)");
    let tex = dqsym::latex(&e, &dqsym::LatexOptions::default());
    assert!(tex.contains(r"\frac{t}{2} - \frac{1}{3}"), "{tex}");
}

/// Random products of one to three constant cosines and sines at denominators 5, 7, 8, 9,
/// 11, 12, 16, times a radical, plus a rational constant: the closed form equals the input,
/// agrees with the product in f64, and is no longer than the expanded form.
#[test]
fn random_constant_products_are_exact_and_no_longer_than_expanded() {
    let mut g = Rng::new(0x2545_f491_4f6c_dd1d);
    let dens = [5i64, 7, 8, 9, 11, 12, 16];
    let roots = [1u64, 1, 2, 3, 5];
    let consts = [(0i64, 1i64), (0, 1), (1, 1), (-3, 4), (1, 2)];
    for _ in 0..24 {
        let n = 1 + g.below(3) as usize;
        let mut text = String::new();
        let mut value = 1.0;
        let mut chosen: Vec<i64> = Vec::new();
        for i in 0..n {
            // At most two denominators: three distinct primes may pass the field's degree limit.
            let d = if chosen.len() == 2 {
                g.pick(&chosen)
            } else {
                g.pick(&dens)
            };
            chosen.push(d);
            let k = 1 + g.below(d as u64 - 1) as i64;
            let sin = g.below(2) == 0;
            if i > 0 {
                text.push('*');
            }
            let f = if sin { "sin" } else { "cos" };
            text.push_str(&format!("{f}({k}*pi/{d})"));
            let a = k as f64 * PI / d as f64;
            value *= if sin { a.sin() } else { a.cos() };
        }
        let r = g.pick(&roots);
        if r != 1 {
            text = format!("sqrt({r})*{text}");
            value *= (r as f64).sqrt();
        }
        let (p, q) = g.pick(&consts);
        if p != 0 {
            text = format!("{text} + ({p})/{q}");
            value += p as f64 / q as f64;
        }
        let x = eval_scalar_text(&text).unwrap_or_else(|e| panic!("{text}: {e}"));
        let e = closed_form(&x).expect("closed form");
        assert_eq!(e.to_scalar(), x, "{text}");
        let v = e.value_at(&[]).expect("value");
        assert!((v - value).abs() < 1e-9, "{text}: {v} vs {value}");
        let expanded = dqsym::closed::expanded_form(&x).expect("expanded");
        assert!(
            e.cost() <= expanded.cost(),
            "{text}: {} ({:?}) longer than {} ({:?})",
            plain(&e, &PlainOptions::default()),
            e.cost(),
            plain(&expanded, &PlainOptions::default()),
            expanded.cost()
        );
    }
}
