//! Randomized laws of the arithmetic in cyclotomic fields: sums and products of random
//! elements (constants and symbolic angles offset by rational multiples of pi, square roots,
//! monomials) are canonical (a second canonicalization from scratch changes nothing: the
//! route every result took before sums and products by constants skipped the groups that
//! were canonical already), agree with an independent evaluation in `f64` of the same
//! expression, and do not depend on the order they were formed in.

use super::super::{canonical_terms, Scalar, ScalarError};
use super::{canonicalize, Settled};
use crate::{Ring, SignedProduct};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;

/// A small linear congruential generator: the test needs no dependency and repeats exactly.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        self.0 >> 33
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len() as u64) as usize]
    }
}

const X: f64 = 0.37;
const A: f64 = 0.61;
const B: f64 = -1.3;

/// A value built both exactly and in `f64`, independently.
#[derive(Clone)]
struct Val {
    s: Scalar,
    f: f64,
}

fn ratio(p: i64, q: i64) -> Val {
    Val {
        s: Scalar::rational(BigRational::new(BigInt::from(p), BigInt::from(q))),
        f: p as f64 / q as f64,
    }
}

fn add(a: &Val, b: &Val) -> Val {
    Val {
        s: &a.s + &b.s,
        f: a.f + b.f,
    }
}

fn sub(a: &Val, b: &Val) -> Val {
    Val {
        s: &a.s - &b.s,
        f: a.f - b.f,
    }
}

fn mul(a: &Val, b: &Val) -> Val {
    Val {
        s: &a.s * &b.s,
        f: a.f * b.f,
    }
}

/// `sqrt(d)`.
fn root(d: i64) -> Val {
    Val {
        s: Scalar::int(d).sqrt(),
        f: (d as f64).sqrt(),
    }
}

/// One of the monomials `1, a, b, a b, a^2`.
fn monomial(rng: &mut Rng) -> Val {
    let (a, b) = (
        Val {
            s: Scalar::sym("a"),
            f: A,
        },
        Val {
            s: Scalar::sym("b"),
            f: B,
        },
    );
    match rng.below(5) {
        0 => ratio(1, 1),
        1 => a,
        2 => b,
        3 => mul(&a, &b),
        _ => mul(&a, &a),
    }
}

/// `cos` or `sin` of `j x + k pi / n` (`j` may be zero: a constant).
fn trig(rng: &mut Rng, n: i64) -> Val {
    let j = rng.pick(&[0i64, 0, 1, 2, -1]);
    let k = rng.below(2 * n as u64) as i64 - n / 2;
    let angle = &(&Scalar::sym("x") * &Scalar::int(j))
        + &(&Scalar::pi() * &Scalar::rational(BigRational::new(k.into(), n.into())));
    let t = j as f64 * X + std::f64::consts::PI * k as f64 / n as f64;
    if rng.below(2) == 0 {
        Val {
            s: angle.cos(),
            f: t.cos(),
        }
    } else {
        Val {
            s: angle.sin(),
            f: t.sin(),
        }
    }
}

/// A sum of one to four terms `p/q sqrt(d) monomial trig` at the denominators `dens`.
fn element(rng: &mut Rng, dens: &[i64]) -> Val {
    let mut acc = ratio(0, 1);
    for _ in 0..=rng.below(4) {
        let p = rng.below(9) as i64 - 4;
        let q = rng.pick(&[1i64, 2, 3, 4]);
        let mut t = mul(&ratio(p, q), &root(rng.pick(&[1i64, 1, 2, 3, 5, 6])));
        t = mul(&t, &monomial(rng));
        if rng.below(4) != 0 {
            let n = rng.pick(dens);
            t = mul(&t, &trig(rng, n));
        }
        acc = add(&acc, &t);
    }
    acc
}

/// A constant of the square-root field times one monomial (what products skip the
/// cyclotomic rewrite for), nonzero.
fn scale(rng: &mut Rng) -> Val {
    let mut k = ratio(rng.pick(&[1i64, -1, 2, 3]), rng.pick(&[1i64, 2, 4]));
    if rng.below(2) == 0 {
        let extra = mul(
            &ratio(rng.pick(&[1i64, -1, 5]), 4),
            &root(rng.pick(&[2i64, 3, 6, 7])),
        );
        k = add(&k, &extra);
    }
    mul(&k, &monomial(rng))
}

/// `v` is its own canonical form from scratch and agrees with its `f64` value; `false` when
/// the field is past the degree limit (the case is skipped).
fn check(v: &Val, what: &str) -> bool {
    let terms = match v.s.terms() {
        Ok(t) => t,
        Err(ScalarError::CyclotomicDegree { .. }) => return false,
        Err(e) => panic!("{what}: {e}"),
    };
    if let Some(again) = canonicalize(terms, &Settled::Nothing).expect("canonicalize") {
        let again = canonical_terms(again).expect("sorted");
        assert_eq!(again, terms, "{what}: not canonical");
    }
    let f =
        v.s.eval_at(&[("x", X), ("a", A), ("b", B)])
            .expect("a value");
    let tol = 1e-9 * (1.0 + v.f.abs());
    assert!((f - v.f).abs() < tol, "{what}: {f} against {}", v.f);
    true
}

/// Sums (groups from one operand, from both, cancelling) and products (by constants times
/// monomials, and general ones) of random elements of cyclotomic fields: canonical, equal
/// to the `f64` evaluation, and the same whichever way the value is formed.
#[test]
fn random_sums_and_products_are_canonical_and_exact() {
    let mut rng = Rng(0x5eed_c1c0);
    let dens = [5i64, 7, 8, 9, 10, 16, 18, 36];
    let mut checked = 0;
    for trial in 0..120 {
        let pair = [rng.pick(&dens), rng.pick(&dens)];
        let (u, v, w) = (
            element(&mut rng, &pair),
            element(&mut rng, &pair),
            element(&mut rng, &pair),
        );
        let k = scale(&mut rng);
        let cases = [
            ("u + v", add(&u, &v)),
            ("u - v", sub(&u, &v)),
            ("u - u", sub(&u, &u)),
            ("u + u", add(&u, &u)),
            ("u k", mul(&u, &k)),
            ("k u", mul(&k, &u)),
            ("(u + v) k", mul(&add(&u, &v), &k)),
            ("u v", mul(&u, &v)),
            ("u v + w", add(&mul(&u, &v), &w)),
        ];
        for (what, c) in &cases {
            if check(c, &format!("trial {trial}: {what}")) {
                checked += 1;
            }
        }
        // The same values formed another way: through sums whose groups mix.
        let uk = &cases[4].1.s;
        let other = &(&(&u.s + &w.s) * &k.s) - &(&w.s * &k.s);
        if uk.as_error().is_none() && other.as_error().is_none() {
            assert_eq!(*uk, other, "trial {trial}: u k = (u + w) k - w k");
        }
        let sum = &cases[0].1.s;
        let other = &(&(&u.s + &w.s) + &v.s) - &w.s;
        if sum.as_error().is_none() && other.as_error().is_none() {
            assert_eq!(*sum, other, "trial {trial}: u + v = ((u + w) + v) - w");
        }
        assert!(cases[2].1.s.is_zero_value() || cases[2].1.s.as_error().is_some());
    }
    assert!(checked > 800, "{checked}");
}

/// Sums of signed products formed at once (`Ring::sums_of_products`: every product's terms,
/// one canonical rewrite at the end, as the quaternion and dual quaternion products form their
/// components) of random elements with pi offsets, square roots and monomials: the scalar the
/// products and sums one by one give, canonical, and equal to the `f64` value of the same
/// expression.
#[test]
fn sums_of_products_at_once_are_the_stepwise_scalar() {
    let mut rng = Rng(0x5eed_d0a1);
    let dens = [3i64, 5, 7, 8, 9, 12, 18];
    let mut checked = 0;
    for trial in 0..100 {
        let pair = [rng.pick(&dens), rng.pick(&dens)];
        let n = 1 + rng.below(8) as usize;
        let factors: Vec<(bool, Val, Val)> = (0..n)
            .map(|_| {
                let minus = rng.below(2) == 0;
                (minus, element(&mut rng, &pair), element(&mut rng, &pair))
            })
            .collect();
        let split = rng.below(n as u64 + 1) as usize;
        // The old route: every product canonical, then every partial sum.
        let stepwise = |f: &[(bool, Val, Val)]| {
            f.iter().fold(ratio(0, 1), |acc, (minus, a, b)| {
                let p = mul(a, b);
                if *minus {
                    sub(&acc, &p)
                } else {
                    add(&acc, &p)
                }
            })
        };
        let expected = add(&stepwise(&factors[..split]), &stepwise(&factors[split..]));
        let products: Vec<SignedProduct<'_, Scalar>> =
            factors.iter().map(|(m, a, b)| (*m, &a.s, &b.s)).collect();
        let (first, second) = products.split_at(split);
        let at_once = Val {
            s: <Scalar as Ring>::sums_of_products(&[first, second]),
            f: expected.f,
        };
        if !check(&expected, &format!("trial {trial}: stepwise")) {
            continue;
        }
        assert!(check(&at_once, &format!("trial {trial}: at once")));
        assert_eq!(at_once.s, expected.s, "trial {trial}");
        checked += 1;
    }
    assert!(checked > 80, "{checked}");
}

/// Products of general scalars (the groups a product passes through untouched, a group with
/// pi offsets of one factor times an offset-free group of the other, and the ones it
/// rewrites) at denominators from 5 to 72, with square roots: canonical (a rewrite from
/// scratch changes nothing), equal to the `f64` evaluation, and equal to the same value built
/// another way (distributed, reassociated, through a sum that cancels).
#[test]
fn random_general_products_are_canonical_and_exact() {
    let mut rng = Rng(0x9e37_79b9_7f4a);
    let dens = [5i64, 7, 9, 10, 12, 14, 15, 16, 18, 20, 24, 36, 40, 45, 72];
    // Offset-free factors: their angles are multiples of pi/12.
    let plain = [1i64, 2, 3, 4, 6, 12];
    let mut checked = 0;
    let mut derivatives = 0;
    let mut trials = 0;
    while trials < 90 {
        let pair = [rng.pick(&dens), rng.pick(&dens)];
        // Fields of degree up to 96 keep the debug build's bases quick.
        let w = pair.iter().fold(24u64, |w, d| {
            let d = 2 * *d as u64;
            w / num_integer::gcd(w, d) * d
        });
        if super::level::totient(w) > 96 {
            continue;
        }
        trials += 1;
        let (u, v) = (element(&mut rng, &pair), element(&mut rng, &pair));
        let (p, q) = (element(&mut rng, &plain), element(&mut rng, &plain));
        let up = mul(&u, &p);
        let cases = [
            ("u p", up.clone()),
            ("p u", mul(&p, &u)),
            ("u v", mul(&u, &v)),
            ("u u", mul(&u, &u)),
            ("(u + p) (v + q)", mul(&add(&u, &p), &add(&v, &q))),
            ("(u p) q", mul(&up, &q)),
            ("(u p) v", mul(&up, &v)),
            ("u p - v q", sub(&up, &mul(&v, &q))),
        ];
        for (what, c) in &cases {
            if check(c, &format!("trial {trials}: {what}")) {
                checked += 1;
            }
        }
        let same = |a: &Scalar, b: &Scalar, what: &str| {
            if a.as_error().is_none() && b.as_error().is_none() {
                assert_eq!(*a, *b, "trial {trials}: {what}");
            }
        };
        let (us, vs, ps, qs) = (&u.s, &v.s, &p.s, &q.s);
        same(
            &up.s,
            &(&(&(us + qs) * ps) - &(qs * ps)),
            "u p = (u + q) p - q p",
        );
        same(
            &cases[4].1.s,
            &(&(&(us * vs) + &(us * qs)) + &(&(ps * vs) + &(ps * qs))),
            "(u + p) (v + q) = u v + u q + p v + p q",
        );
        same(&cases[5].1.s, &(us * &(ps * qs)), "(u p) q = u (p q)");
        same(&cases[6].1.s, &(us * &(ps * vs)), "(u p) v = u (p v)");
        // Derivatives (whose groups of one origin pass through): canonical, the numeric
        // derivative, and the product rule.
        for x in ["x", "a"] {
            let d = up.s.diff(x);
            let at = |dx: f64| {
                let (xv, av) = if x == "x" { (X + dx, A) } else { (X, A + dx) };
                up.s.eval_at(&[("x", xv), ("a", av), ("b", B)])
            };
            let h = 1e-4;
            let (Ok(f1), Ok(f2), Ok(g1), Ok(g2)) = (at(h), at(-h), at(2.0 * h), at(-2.0 * h))
            else {
                continue;
            };
            // Richardson's five-point derivative: error of order h^4.
            let numeric = (8.0 * (f1 - f2) - (g1 - g2)) / (12.0 * h);
            let v = Val {
                s: d.clone(),
                f: numeric,
            };
            if d.as_error().is_none() {
                let terms = d.terms().expect("terms");
                if let Some(again) = canonicalize(terms, &Settled::Nothing).expect("canonicalize") {
                    let again = canonical_terms(again).expect("sorted");
                    assert_eq!(again, terms, "trial {trials}: d(u p)/d{x} not canonical");
                }
                let f = d.eval_at(&[("x", X), ("a", A), ("b", B)]).expect("a value");
                assert!(
                    (f - v.f).abs() < 1e-6 * (1.0 + v.f.abs()),
                    "trial {trials}: d/d{x}: {f} against {}",
                    v.f
                );
                derivatives += 1;
            }
            same(
                &d,
                &(&(&us.diff(x) * ps) + &(us * &ps.diff(x))),
                "(u p)' = u' p + u p'",
            );
        }
    }
    assert!(checked > 650, "{checked}");
    assert!(derivatives > 150, "{derivatives}");
}

/// A value built under the default cyclotomic degree limit, then combined under a lower one:
/// every result that holds a group past the lower limit is the degree error naming that
/// limit, whichever way it was formed (sums whose groups pass through untouched, products by
/// constants, general products, negation), never a panic and never the group passed through
/// unchecked; results within the lower limit are unaffected.
#[test]
fn a_limit_lowered_after_a_value_was_built_is_still_enforced() {
    use super::super::Context;
    let sym = Scalar::sym;
    let angle = |j: i64, k: i64, n: i64| {
        &(&sym("x") * &Scalar::int(j))
            + &(&Scalar::pi() * &Scalar::rational(BigRational::new(k.into(), n.into())))
    };
    // Sevenths need Q(zeta_168), of degree 48; ninths Q(zeta_72), of degree 24.
    let sevenths = &(&angle(1, 1, 7).cos() * &sym("a")) + &angle(0, 2, 7).cos();
    let ninths = &angle(1, 5, 9).sin() * &Scalar::int(3).sqrt();
    let plain = &sym("b") + &angle(1, 1, 3).cos();
    for v in [&sevenths, &ninths] {
        assert!(v.as_error().is_none(), "built under the default limit: {v}");
    }
    let limit = 12;
    let _in = Context::new().with_max_cyclotomic_degree(limit).enter();
    let k = &(&Scalar::int(3) + &Scalar::int(2).sqrt()) * &sym("c");
    for (name, v, degree) in [("sevenths", &sevenths, 48), ("ninths", &ninths, 24)] {
        let results = [
            ("v + plain", v + &plain),
            ("plain - v", &plain - v),
            ("v + v", v + v),
            ("v k", v * &k),
            ("k v", &k * v),
            ("v plain", v * &plain),
            ("v cos(y)", v * &sym("y").cos()),
            ("-v", -v),
        ];
        for (what, r) in results {
            match r.check() {
                Err(e @ ScalarError::CyclotomicDegree { .. }) => {
                    let ScalarError::CyclotomicDegree {
                        degree: d,
                        limit: l,
                        exact,
                        ..
                    } = e
                    else {
                        unreachable!()
                    };
                    assert_eq!((d, l, exact), (degree, limit, true), "{name}: {what}");
                    let text = e.to_string();
                    assert!(text.contains("--max-cyclotomic-degree"), "{text}");
                }
                other => panic!("{name}: {what}: expected the degree limit, got {other:?}"),
            }
        }
    }
    // Within the lower limit nothing changes.
    let twice = &plain + &plain;
    assert_eq!(twice, &plain * &Scalar::int(2));
    assert!(twice.as_error().is_none());
}

/// Derivatives of random elements times `x`, `x + 1` or a monomial, with respect to `x` and
/// to `a`:
/// the variable is in the monomials, in the angles or in both, so the terms with a pi offset
/// of the derivative have one origin (passed through whole by `Scalar::diff`) or two (its
/// mixed groups rewritten). Either way: canonical (a rewrite from scratch changes nothing)
/// and equal to a five-point numeric derivative.
#[test]
fn random_derivatives_of_one_or_two_origins_are_canonical_and_exact() {
    let mut rng = Rng(0xd1ff_0e1e_57a7);
    let dens = [5i64, 7, 9, 10, 18, 36];
    // Derivatives checked whose offset terms had one origin, and two.
    let mut origins = [0usize; 2];
    for trial in 0..150 {
        let den = rng.pick(&dens);
        let u = element(&mut rng, &[den]);
        // `x + 1`: a group of the derivative can hold terms of both origins (`(x + 1)
        // cos(x + phi)` gives `cos(x + phi) - sin(x + phi)`, one group to rewrite).
        let x = Val {
            s: Scalar::sym("x"),
            f: X,
        };
        let factor = match rng.below(3) {
            0 => x,
            1 => add(&x, &ratio(1, 1)),
            _ => monomial(&mut rng),
        };
        let v = mul(&u, &factor);
        let Ok(terms) = v.s.terms() else {
            continue;
        };
        for var in ["x", "a"] {
            let offset = terms.iter().filter(|t| !t.mode.pi.is_zero());
            let in_mono = offset
                .clone()
                .any(|t| t.mono.iter().any(|(s, _)| s.name() == var));
            let in_angle = offset
                .clone()
                .any(|t| t.mode.freq.iter().any(|(s, _)| s.name() == var));
            let d = v.s.diff(var);
            let Ok(dt) = d.terms() else {
                continue;
            };
            if let Some(again) = canonicalize(dt, &Settled::Nothing).expect("canonicalize") {
                let again = canonical_terms(again).expect("sorted");
                assert_eq!(again, dt, "trial {trial}: d/d{var} not canonical");
            }
            let at = |h: f64| {
                let (xv, av) = if var == "x" { (X + h, A) } else { (X, A + h) };
                v.s.eval_at(&[("x", xv), ("a", av), ("b", B)])
                    .expect("a value")
            };
            let h = 1e-4;
            let numeric = (8.0 * (at(h) - at(-h)) - (at(2.0 * h) - at(-2.0 * h))) / (12.0 * h);
            let f = d.eval_at(&[("x", X), ("a", A), ("b", B)]).expect("a value");
            assert!(
                (f - numeric).abs() < 1e-6 * (1.0 + numeric.abs()),
                "trial {trial}: d/d{var}: {f} against {numeric}"
            );
            if in_mono || in_angle {
                origins[usize::from(in_mono && in_angle)] += 1;
            }
        }
    }
    assert!(origins[0] > 100 && origins[1] > 20, "{origins:?}");
}

/// [`super::key_cmp`], the order every sort and search of group keys uses, is the derived
/// order of the key tuple: on every pair of keys of random elements and of angles with
/// fractional frequencies (equal keys shared or allocated apart, coefficients of different
/// denominators), both the order and the equality.
#[test]
fn the_group_key_order_is_the_derived_order() {
    use super::super::Term;
    use super::{key_cmp, GroupKey};
    let mut rng = Rng(0x0bde_4c3a);
    let dens = [5i64, 7, 9, 12, 36];
    let mut vals: Vec<Scalar> = (0..30).map(|_| element(&mut rng, &dens).s).collect();
    let (x, y) = (Scalar::sym("x"), Scalar::sym("y"));
    let q = |p: i64, d: i64| Scalar::rational(BigRational::new(p.into(), d.into()));
    for (p, d) in [(1i64, 2i64), (1, 3), (2, 3), (3, 4), (-5, 6), (7, 2)] {
        let angle = &(&(&x * &q(p, d)) + &(&y * &q(d, p.abs() + 1))) + &(&Scalar::pi() * &q(1, 9));
        vals.push(&(&Scalar::sym("a") * &angle.cos()) + &angle.sin());
    }
    let terms: Vec<&Term> = vals
        .iter()
        .filter_map(|v| v.terms().ok())
        .flatten()
        .collect();
    let keys: Vec<GroupKey> = terms.iter().map(|t| (&*t.mode.freq, &t.mono)).collect();
    let (mut equal, mut apart) = (0, 0);
    for a in &keys {
        for b in &keys {
            assert_eq!(key_cmp(a, b), a.cmp(b), "{a:?} against {b:?}");
            assert_eq!(key_cmp(a, b).is_eq(), a == b);
            if a == b && !std::ptr::eq(a.0, b.0) {
                apart += 1;
            }
            equal += usize::from(a == b);
        }
    }
    assert!(
        keys.len() > 100 && apart > 0 && equal > keys.len(),
        "{} keys",
        keys.len()
    );
}

/// A group of one term `p/q sqrt(d) monomial trig(j x + k pi/n)` rewritten from the
/// per-thread template of its mode (`canonical_term`) is the group rewritten from scratch
/// (`rewritten_group`), on seeded random terms at many denominators, constants and
/// symbolic angles, sines and cosines, with radicands inside the fields and outside them;
/// each asked for twice, so the second answer comes from the template.
#[test]
fn a_one_term_group_from_its_template_is_the_group_rewritten() {
    use super::{canonical_term, rewritten_group};
    let mut rng = Rng(0x0e7e_c1a5_05e5);
    let dens = [5i64, 7, 8, 9, 10, 15, 16, 18, 20, 36];
    let (mut checked, mut constants) = (0, 0);
    for _ in 0..2000 {
        let n = rng.pick(&dens);
        let v = trig(&mut rng, n);
        let Ok([mode_term]) = v.s.terms() else {
            continue;
        };
        if mode_term.mode.pi.is_zero() {
            continue;
        }
        let mono = monomial(&mut rng);
        let Ok([mono_term]) = mono.s.terms() else {
            panic!("a monomial is one term");
        };
        let p = rng.pick(&[1i64, -1, 2, -3, 5]);
        let q = rng.pick(&[1i64, 2, 3, 7]);
        let t = super::Term {
            mode: mode_term.mode.clone(),
            mono: mono_term.mono.clone(),
            rad: rng.pick(&[1u64, 2, 3, 5, 6, 7, 15, 21]),
            coef: &super::Q::new(p, q) * &mode_term.coef,
        };
        let want = canonical_terms(rewritten_group(&[&t]).expect("rewritten")).expect("sorted");
        for _ in 0..2 {
            let got =
                canonical_terms(canonical_term(&t).expect("from the template")).expect("sorted");
            assert_eq!(got, want, "{t:?}");
        }
        checked += 1;
        constants += usize::from(t.mode.freq.is_empty());
    }
    assert!(
        checked > 300 && constants > 80,
        "{checked} terms, {constants} constants"
    );
}

/// A group found rewritten on this thread before (`rewritten_before`, through
/// `rewritten_group`) is the group rewritten by exact linear algebra (`canonical_group_exact`,
/// the independent route), on its own frequency vector and monomial and relabelled onto
/// others, and it charges the work the fast path charges once its bases are made: seeded
/// random groups of one to four terms `p/q sqrt(d) m trig(j x + k pi/n)` (one `j` a group,
/// zero for constants) at many denominators, mixed denominators in a group included (past
/// the degree limit, the same error). A group found under a lower limit than it was
/// rewritten at (its remembered level checked) is the exact rewrite or its degree error.
#[test]
fn a_group_rewritten_before_is_the_group_rewritten_exactly() {
    use super::super::{with_own_budget, work_used, Context, Term};
    use super::{exact::canonical_group_exact, fast::canonical_group_fast};
    use super::{rewritten_before, rewritten_group, value_hash};
    let mut rng = Rng(0x0d16_9e0c_ac4e);
    let dens = [5i64, 7, 8, 9, 10, 15, 16, 18, 20, 36];
    let monos: Vec<Term> = ["1", "a", "b"]
        .iter()
        .map(|s| {
            let v = if *s == "1" {
                Scalar::int(1)
            } else {
                Scalar::sym(s)
            };
            v.terms().expect("terms")[0].clone()
        })
        .collect();
    let sorted = |g: Vec<Term>| canonical_terms(g).expect("sorted");
    let (mut checked, mut constants, mut relabelled, mut refused) = (0, 0, 0, 0);
    let mut limited = 0;
    for _ in 0..600 {
        let j = rng.pick(&[0i64, 1, 2]);
        let x = &Scalar::sym("x") * &Scalar::int(j);
        let mono = rng.pick(&[0usize, 1, 2]);
        let mut g: Vec<Term> = Vec::new();
        for _ in 0..=rng.below(4) {
            let n = rng.pick(&dens);
            let k = rng.below(2 * n as u64) as i64;
            let angle =
                &x + &(&Scalar::pi() * &Scalar::rational(BigRational::new(k.into(), n.into())));
            let v = if rng.below(2) == 0 {
                angle.cos()
            } else {
                angle.sin()
            };
            let p = rng.pick(&[1i64, -1, 2, -3, 5]);
            let q = rng.pick(&[1i64, 2, 3, 7]);
            let rad = rng.pick(&[1u64, 1, 2, 3, 5, 6, 7]);
            for t in v.terms().expect("terms") {
                let fresh = g
                    .iter()
                    .all(|u| (u.mode.sin, u.mode.pi, u.rad) != (t.mode.sin, t.mode.pi, rad));
                if t.mode.pi.is_zero() || !fresh {
                    continue;
                }
                g.push(Term {
                    mode: t.mode.clone(),
                    mono: monos[mono].mono.clone(),
                    rad,
                    coef: &super::Q::new(p, q) * &t.coef,
                });
            }
        }
        g.sort_by(Term::key_cmp);
        let refs: Vec<&Term> = g.iter().collect();
        if refs.is_empty() {
            continue;
        }
        let want = match canonical_group_exact(&refs) {
            Ok(want) => sorted(want),
            Err(e) => {
                // Past the degree limit (mixed denominators): the same error, found or not.
                for _ in 0..2 {
                    assert_eq!(rewritten_group(&refs).err(), Some(e.clone()));
                }
                refused += 1;
                continue;
            }
        };
        for _ in 0..2 {
            assert_eq!(
                sorted(rewritten_group(&refs).expect("rewritten")),
                want,
                "{g:?}"
            );
        }
        let fast = canonical_group_fast(&refs).expect("fast").is_some();
        // A group the fast path rewrote is remembered: the calls above found it.
        let found = |g: &[&Term]| {
            rewritten_before(g, value_hash(g))
                .expect("within the limit")
                .is_some()
        };
        assert_eq!(found(&refs), fast, "{g:?}");
        if fast {
            let charged = |f: &dyn Fn()| {
                with_own_budget(u64::MAX / 4, || {
                    f();
                    work_used()
                })
            };
            let direct = charged(&|| drop(canonical_group_fast(&refs)));
            let again = charged(&|| drop(rewritten_group(&refs)));
            assert!(
                direct > 0 && again == direct,
                "{again} against {direct}: {g:?}"
            );
            // Found under other limits (its remembered level checked against each): the
            // exact route's rewrite, or its degree error.
            for limit in [4, 8, 12, 16, 24, 48, 96] {
                let _in = Context::new().with_max_cyclotomic_degree(limit).enter();
                let want = canonical_group_exact(&refs).map(|w| Some(sorted(w)));
                let hit = rewritten_before(&refs, value_hash(&refs)).map(|o| o.map(sorted));
                assert_eq!(hit, want, "limit {limit}: {g:?}");
                limited += usize::from(want.is_err());
            }
        }
        // The same values on another monomial (and another angle, for symbolic groups).
        let other = (mono + 1) % monos.len();
        let freq = (&Scalar::sym("y") * &Scalar::int(3)).cos();
        let moved: Vec<Term> = g
            .iter()
            .map(|t| {
                let mut t = t.clone();
                t.mono = monos[other].mono.clone();
                if !t.mode.freq.is_empty() {
                    t.mode.freq = freq.terms().expect("terms")[0].mode.freq.clone();
                }
                t
            })
            .collect();
        let moved_refs: Vec<&Term> = moved.iter().collect();
        // Relabelled: the same value was rewritten before, on other labels.
        assert_eq!(found(&moved_refs), fast, "{moved:?}");
        let want = sorted(canonical_group_exact(&moved_refs).expect("exact"));
        assert_eq!(
            sorted(rewritten_group(&moved_refs).expect("rewritten")),
            want
        );
        checked += 1;
        constants += usize::from(j == 0);
        relabelled += usize::from(fast);
    }
    assert!(
        checked > 400 && constants > 100 && relabelled > 350 && refused > 0 && limited > 100,
        "{checked} groups, {constants} constant, {relabelled} through the fast path, \
         {refused} past the degree limit, {limited} found past a lower limit"
    );
}

/// [`super::groups_of`] finds the groups the search of every term's key among the sorted
/// keys of the terms with an offset finds (the route it replaced, written out here): the
/// same keys in the same order, every term in the same group or in none, on the terms of
/// seeded random sums and products at many denominators (with monomials, constants and
/// symbolic angles, several groups and terms without an offset outside them). The groups
/// [`super::group_ids`] finds by hashing are the classes of equal keys ([`super::key_cmp`],
/// every pair of terms compared), numbered as first met, each marked exactly when one of its
/// terms has a pi offset.
#[test]
fn the_groups_of_a_term_vector_are_the_groups_searched_by_key() {
    use super::super::Term;
    use super::{group_ids, groups_of, key_cmp, GroupKey};
    let mut rng = Rng(0x0016_d9a0_5eed);
    let dens = [5i64, 7, 8, 9, 10, 18, 20];
    let (mut checked, mut grouped, mut outside) = (0, 0, 0);
    for _ in 0..300 {
        let n = rng.pick(&dens);
        let v = mul(&element(&mut rng, &[n]), &element(&mut rng, &[n, 12]));
        let v = add(&v, &element(&mut rng, &[n]));
        let Ok(terms) = v.s.terms() else {
            continue;
        };
        let mut keys: Vec<GroupKey> = terms
            .iter()
            .filter(|t| !t.mode.pi.is_zero())
            .map(|t| (&*t.mode.freq, &t.mono))
            .collect();
        keys.sort_unstable_by(key_cmp);
        keys.dedup_by(|a, b| key_cmp(a, b).is_eq());
        let at: Vec<Option<usize>> = terms
            .iter()
            .map(|t: &Term| {
                keys.binary_search_by(|x| key_cmp(x, &(&*t.mode.freq, &t.mono)))
                    .ok()
            })
            .collect();
        let got = groups_of(terms);
        assert_eq!(got.0, keys);
        assert_eq!(got.1, at);
        // Every term's group by hashing: its own key, the same group exactly for equal keys
        // (every pair of terms compared), numbered as first met.
        let (all, ids, offset) = group_ids(terms);
        for (i, t) in terms.iter().enumerate() {
            let k: GroupKey = (&*t.mode.freq, &t.mono);
            assert!(key_cmp(&all[ids[i] as usize], &k).is_eq());
            for (j, u) in terms.iter().enumerate() {
                let same = key_cmp(&k, &(&*u.mode.freq, &u.mono)).is_eq();
                assert_eq!(ids[i] == ids[j], same);
            }
        }
        let mut next = 0;
        for &g in &ids {
            assert!(g <= next, "group {g} numbered before group {next}");
            next += u32::from(g == next);
        }
        assert_eq!(next as usize, all.len());
        let held: Vec<bool> = (0..all.len())
            .map(|g| {
                terms
                    .iter()
                    .zip(&ids)
                    .any(|(t, &h)| h as usize == g && !t.mode.pi.is_zero())
            })
            .collect();
        assert_eq!(offset, held);
        checked += 1;
        grouped += usize::from(keys.len() > 1);
        outside += usize::from(at.contains(&None) && !keys.is_empty());
    }
    assert!(
        checked > 250 && grouped > 100 && outside > 30,
        "{checked} vectors, {grouped} of several groups, {outside} with terms outside them"
    );
}
