//! Constant coefficients lifted out of the angles (issue 18; closed/coefs.rs): a product of
//! constant cosines and sines beside symbolic angles prints as that product, not as the sum over
//! the field's common denominator (`sin(pi/7) cos(pi/9) cos(q)`, canonically a sum of
//! `cos(q +- k pi/63)`). Every case: the printed text, exact equality with the input, the f64
//! value at random points against a formula written here, and the explicit text read back.

use crate::common::Rng;
use dqsym::{closed_form, eval_scalar_text, plain, PlainOptions};
use std::f64::consts::PI;

type Env<'a> = &'a dyn Fn(&str) -> f64;

/// The closed form of `input`, checked: exact equality, the explicit text read back, and the
/// f64 value at 10 random points against `direct`. Returns the printed text.
fn checked(input: &str, direct: &dyn Fn(Env) -> f64, rng: &mut Rng) -> String {
    let x = eval_scalar_text(input).unwrap_or_else(|e| panic!("{input}: {e}"));
    let e = closed_form(&x).unwrap_or_else(|err| panic!("{input}: {err}"));
    assert_eq!(e.to_scalar(), x, "{input}");
    let explicit = plain(
        &e,
        &PlainOptions {
            shorthand: false,
            decimals: false,
        },
    );
    let back = eval_scalar_text(&explicit).unwrap_or_else(|err| panic!("{explicit}: {err}"));
    assert_eq!(back, x, "{input}: {explicit} reads back to another value");
    for _ in 0..10 {
        let vals: Vec<(String, f64)> = e
            .symbol_names()
            .into_iter()
            .map(|n| (n, rng.range(-2.0, 2.0)))
            .collect();
        // A symbol the closed form does not read (the input's value is zero, say) may have
        // any value.
        let env = |n: &str| vals.iter().find(|(m, _)| m == n).map_or(0.5, |(_, v)| *v);
        let want = direct(&env);
        let pairs: Vec<(&str, f64)> = vals.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let shown = e.value_at(&pairs).expect("value");
        assert!(
            (shown - want).abs() < 1e-9 * (1.0 + want.abs()),
            "{input} -> {explicit}: {shown} vs {want}"
        );
    }
    plain(&e, &PlainOptions::default())
}

fn a(k: f64, n: f64) -> f64 {
    k * PI / n
}

#[test]
fn constant_products_beside_symbolic_angles_print_as_products() {
    let mut rng = Rng::new(18);
    type Case = (&'static str, &'static str, Box<dyn Fn(Env) -> f64>);
    let cases: Vec<Case> = vec![
        (
            "cos(pi/9)*sin(pi/7)*cos(q)",
            "sin(pi/7) cos(pi/9) cos(q)",
            Box::new(|v| a(1., 9.).cos() * a(1., 7.).sin() * v("q").cos()),
        ),
        (
            "cos(pi/9)*sin(pi/7)*cos(q) + sin(q)*cos(pi/7)",
            "sin(pi/7) cos(pi/9) cos(q) + cos(pi/7) sin(q)",
            Box::new(|v| {
                a(1., 9.).cos() * a(1., 7.).sin() * v("q").cos() + v("q").sin() * a(1., 7.).cos()
            }),
        ),
        // The two coefficients of one angle are R cos(phi), R sin(phi): one cosine.
        (
            "cos(pi/9)*sin(pi/7)*cos(q) + sin(q)*cos(pi/7)*cos(pi/9)",
            "cos(pi/9) sin(q + pi/7)",
            Box::new(|v| a(1., 9.).cos() * (v("q") + a(1., 7.)).sin()),
        ),
        (
            "cos(q+pi/7)*cos(pi/9)",
            "cos(pi/9) cos(q + pi/7)",
            Box::new(|v| (v("q") + a(1., 7.)).cos() * a(1., 9.).cos()),
        ),
        (
            "l1*cos(pi/9)*cos(q1 + pi/7) + l2*sin(q2)*cos(pi/5)",
            "l1 cos(pi/9) cos(q1 + pi/7) + 1/4 l2 s2 (1 + sqrt(5))",
            Box::new(|v| {
                v("l1") * a(1., 9.).cos() * (v("q1") + a(1., 7.)).cos()
                    + v("l2") * v("q2").sin() * a(1., 5.).cos()
            }),
        ),
        (
            "sin(4*pi/9)*cos(q1)*sin(q2) + cos(pi/7)*cos(q1)*l",
            // The shared c1 is taken out of the summands in their order (extra.rs), of the
            // same cost as `c1 (l cos(pi/7) + sin(4*pi/9) s2)`.
            "c1 (sin(4*pi/9) s2 + l cos(pi/7))",
            Box::new(|v| {
                a(4., 9.).sin() * v("q1").cos() * v("q2").sin()
                    + a(1., 7.).cos() * v("q1").cos() * v("l")
            }),
        ),
        (
            "cos(pi/9)*cos(q1+q2) + cos(pi/7)*sin(q1)",
            // The sum split by its angles' symbols, part by part (extra.rs), of the same
            // cost as `cos(pi/7) s1 + cos(pi/9) c12`.
            "cos(pi/9) c12 + cos(pi/7) s1",
            Box::new(|v| {
                a(1., 9.).cos() * (v("q1") + v("q2")).cos() + a(1., 7.).cos() * v("q1").sin()
            }),
        ),
        // Without symbolic angles: each monomial's coefficient its own product.
        (
            "cos(pi/5)*cos(pi/7)*x + cos(pi/9)*y*sin(pi/7)",
            "1/4 (x (1 + sqrt(5)) cos(pi/7) + 4 y sin(pi/7) cos(pi/9))",
            Box::new(|v| {
                a(1., 5.).cos() * a(1., 7.).cos() * v("x")
                    + a(1., 9.).cos() * v("y") * a(1., 7.).sin()
            }),
        ),
    ];
    for (input, want, direct) in &cases {
        assert_eq!(checked(input, direct.as_ref(), &mut rng), *want, "{input}");
    }
}

/// The denominators `n` of the `k*pi/n` in a printed text.
fn pi_denominators(text: &str) -> Vec<i64> {
    text.match_indices("pi/")
        .map(|(i, _)| {
            text[i + 3..]
                .chars()
                .take_while(char::is_ascii_digit)
                .collect::<String>()
                .parse()
                .expect("a denominator")
        })
        .collect()
}

/// Random sums of constant products times cosines and sines of symbolic angles, some with
/// offsets: exact, f64 at random points, read back, no longer than the expanded form, and
/// every constant angle shown at one of the input's own denominators, or twice one
/// (`sin(3*pi/5) = cos(pi/10)`), or a multiple of pi/12: never over their common multiple.
#[test]
fn random_constant_coefficients_print_in_the_input_angles() {
    let mut rng = Rng::new(0x5eed_c0ef);
    let pick = |n: usize, rng: &mut Rng| (rng.range(0.0, n as f64) as usize).min(n - 1);
    let dens = [5i64, 7, 8, 9];
    let monos = ["", "l1*", "l2*", "l1*l2*"];
    let angles = ["q1", "q1 + q2", "2*q1", "q2"];
    for case in 0..24 {
        // Two denominators per case (the field of pi/315 at most).
        let d1 = dens[pick(4, &mut rng)];
        let d2 = dens[pick(4, &mut rng)];
        let nterms = 1 + pick(3, &mut rng);
        let mut text = String::new();
        type Part = Box<dyn Fn(Env) -> f64>;
        let mut parts: Vec<Part> = Vec::new();
        for t in 0..nterms {
            let r = [1i64, 2, -1, 3][pick(4, &mut rng)];
            let nconst = 1 + pick(2, &mut rng);
            let mut consts = Vec::new();
            let mut value = r as f64;
            for c in 0..nconst {
                let d = if c == 0 { d1 } else { d2 };
                let k = 1 + pick((d - 1) as usize, &mut rng) as i64;
                let sin = pick(2, &mut rng) == 1;
                let f = if sin { "sin" } else { "cos" };
                consts.push(format!("{f}({k}*pi/{d})"));
                let ang = a(k as f64, d as f64);
                value *= if sin { ang.sin() } else { ang.cos() };
            }
            let mono = monos[pick(4, &mut rng)];
            let ang = angles[pick(4, &mut rng)];
            let sin = pick(2, &mut rng) == 1;
            let off = if pick(3, &mut rng) == 0 {
                (1 + pick((d1 - 1) as usize, &mut rng)) as i64
            } else {
                0
            };
            let f = if sin { "sin" } else { "cos" };
            if t > 0 {
                text.push_str(" + ");
            }
            text.push_str(&format!(
                "{r}*{}*{mono}{f}({ang} + {off}*pi/{d1})",
                consts.join("*")
            ));
            let (mono, ang) = (mono.to_string(), ang.to_string());
            parts.push(Box::new(move |v| {
                let m = match mono.as_str() {
                    "" => 1.0,
                    "l1*" => v("l1"),
                    "l2*" => v("l2"),
                    _ => v("l1") * v("l2"),
                };
                let x = match ang.as_str() {
                    "q1" => v("q1"),
                    "q1 + q2" => v("q1") + v("q2"),
                    "2*q1" => 2.0 * v("q1"),
                    _ => v("q2"),
                } + a(off as f64, d1 as f64);
                value * m * if sin { x.sin() } else { x.cos() }
            }));
        }
        let direct = |v: Env| parts.iter().map(|p| p(v)).sum::<f64>();
        let shown = checked(&text, &direct, &mut rng);
        let x = eval_scalar_text(&text).expect("input");
        let e = closed_form(&x).expect("closed form");
        let expanded = dqsym::closed::expanded_form(&x).expect("expanded");
        assert!(
            e.cost() <= expanded.cost(),
            "case {case}: {text} -> {shown} costs more than the expanded form"
        );
        for n in pi_denominators(&shown) {
            assert!(
                12 % n == 0 || (2 * d1) % n == 0 || (2 * d2) % n == 0,
                "case {case}: {text} -> {shown} shows pi/{n}"
            );
        }
    }
}

/// Angles at offsets that are multiples of pi/12 (which the canonical form holds as radicals)
/// print as angles again: each `l cos(F + k pi/12)` of its own monomial is one call, no
/// square root.
#[test]
fn offsets_at_twelfths_print_as_angles_not_radicals() {
    let mut rng = Rng::new(0x7e1f);
    type Case = (&'static str, &'static str, Box<dyn Fn(Env) -> f64>);
    let cases: Vec<Case> = vec![
        (
            "l1*sin(x + pi/6) + l2*sin(x + y - pi/6)",
            "l1 cos(x - pi/3) + l2 sin(x + y - pi/6)",
            Box::new(|v| {
                v("l1") * (v("x") + a(1., 6.)).sin() + v("l2") * (v("x") + v("y") - a(1., 6.)).sin()
            }),
        ),
        (
            "l1*cos(x - pi/4) + l2*cos(x + y - 11*pi/5) + l3*cos(x + y + t - pi/4)",
            "l1 cos(x - pi/4) + l2 cos(x + y - pi/5) + l3 cos(t + x + y - pi/4)",
            Box::new(|v| {
                v("l1") * (v("x") - a(1., 4.)).cos()
                    + v("l2") * (v("x") + v("y") - a(11., 5.)).cos()
                    + v("l3") * (v("x") + v("y") + v("t") - a(1., 4.)).cos()
            }),
        ),
        (
            "sqrt(5)*sin(t/2 + 3*pi/4) - 3",
            "-3 + sqrt(5) cos(t/2 + pi/4)",
            Box::new(|v| 5f64.sqrt() * (v("t") / 2. + a(3., 4.)).sin() - 3.),
        ),
    ];
    for (input, want, direct) in &cases {
        assert_eq!(checked(input, direct.as_ref(), &mut rng), *want, "{input}");
    }
    // Generated: one monomial per angle, offsets k pi/12 off the multiples of pi/2.
    let angles = ["x", "x + y", "2*x - y", "x/2 + t"];
    let value = |i: usize, v: Env| match i {
        0 => v("x"),
        1 => v("x") + v("y"),
        2 => 2. * v("x") - v("y"),
        _ => v("x") / 2. + v("t"),
    };
    for case in 0..16 {
        let n = 1 + rng.below(3) as usize;
        let mut text = Vec::new();
        let mut parts: Vec<(usize, bool, i64, i64)> = Vec::new();
        for (i, angle) in angles.iter().enumerate().take(n) {
            let k = loop {
                let k = rng.below(23) as i64 - 11;
                if k % 6 != 0 {
                    break k;
                }
            };
            let sin = rng.chance(0.5);
            let r = [1i64, 2, -3][rng.below(3) as usize];
            let f = if sin { "sin" } else { "cos" };
            text.push(format!("{r}*l{}*{f}({angle} + {k}*pi/12)", i + 1));
            parts.push((i, sin, k, r));
        }
        let text = text.join(" + ");
        let direct = |v: Env| {
            parts
                .iter()
                .map(|&(i, sin, k, r)| {
                    let g = value(i, v) + a(k as f64, 12.);
                    r as f64 * v(&format!("l{}", i + 1)) * if sin { g.sin() } else { g.cos() }
                })
                .sum::<f64>()
        };
        let shown = checked(&text, &direct, &mut rng);
        assert!(
            !shown.contains("sqrt"),
            "case {case}: {text} -> {shown} keeps a radical"
        );
        let x = eval_scalar_text(&text).expect("input");
        let e = closed_form(&x).expect("closed form");
        let expanded = dqsym::closed::expanded_form(&x).expect("expanded");
        assert!(
            e.cost() <= expanded.cost(),
            "case {case}: {text} -> {shown}"
        );
    }
}
