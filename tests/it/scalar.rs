//! The canonical form: the identities that must hold by construction (issue: exact core).

use crate::common::{n, q, s};
use dqsym::{Scalar, ScalarError};

fn cos(x: &Scalar) -> Scalar {
    x.cos().check().unwrap()
}
fn sin(x: &Scalar) -> Scalar {
    x.sin().check().unwrap()
}

#[test]
fn pythagoras_holds_by_construction() {
    let t = s("t");
    assert_eq!(cos(&t).pow(2) + sin(&t).pow(2), n(1));
    let u = s("a") * q(1, 3) - s("b") + Scalar::pi() * q(1, 7);
    assert_eq!(cos(&u).pow(2) + sin(&u).pow(2), n(1));
}

#[test]
fn cosine_of_a_sum_expands() {
    let (a, b) = (s("t1"), s("t2"));
    assert_eq!(cos(&(&a + &b)), cos(&a) * cos(&b) - sin(&a) * sin(&b));
    assert_eq!(sin(&(&a + &b)), sin(&a) * cos(&b) + cos(&a) * sin(&b));
}

#[test]
fn double_angle_identities_hold() {
    let t = s("t");
    let h = &t * q(1, 2);
    assert_eq!(n(2) * sin(&h) * cos(&h), sin(&t));
    assert_eq!(cos(&h).pow(2) - sin(&h).pow(2), cos(&t));
    assert_eq!(n(2) * sin(&h).pow(2), n(1) - cos(&t));
}

#[test]
fn pi_offsets_and_negation_reduce() {
    let t = s("t");
    assert_eq!(cos(&(&t + Scalar::pi() * q(1, 2))), -sin(&t));
    assert_eq!(sin(&(-&t)), -sin(&t));
    assert_eq!(cos(&(-&t)), cos(&t));
    assert_eq!(sin(&(&t + Scalar::pi())), -sin(&t));
}

#[test]
fn exact_values_at_twelfths_of_pi() {
    let pi = Scalar::pi();
    assert_eq!(cos(&(&pi * q(1, 2))), n(0));
    assert_eq!(cos(&pi), n(-1));
    assert_eq!(sin(&(&pi * q(1, 4))), n(2).sqrt() * q(1, 2));
    assert_eq!(cos(&(&pi * q(1, 6))), n(3).sqrt() * q(1, 2));
    assert_eq!(
        cos(&(&pi * q(1, 12))),
        (n(6).sqrt() + n(2).sqrt()) * q(1, 4)
    );
    assert_eq!(sin(&(&pi * q(7, 6))), q(-1, 2));
}

#[test]
fn radicals_reduce() {
    assert_eq!(n(8).sqrt(), n(2) * n(2).sqrt());
    assert_eq!(n(2).sqrt() * n(3).sqrt(), n(6).sqrt());
    assert_eq!(n(2).sqrt().pow(2), n(2));
    assert_eq!(n(1).try_div(&n(2).sqrt()).unwrap(), n(2).sqrt() * q(1, 2));
    assert_eq!(q(1, 2).sqrt(), n(2).sqrt() * q(1, 2));
    let x = n(1) + n(2).sqrt() + n(3).sqrt();
    assert_eq!(x.recip() * &x, n(1));
}

#[test]
fn division_by_symbols_and_zero_is_refused() {
    assert!(matches!(
        n(1).try_div(&n(0)),
        Err(ScalarError::DivisionByZero)
    ));
    assert!(matches!(
        n(1).try_div(&s("x")),
        Err(ScalarError::SymbolicDivisor(_))
    ));
    assert!(matches!(
        s("x").pow(2).cos().check(),
        Err(ScalarError::NotAnAngle { .. })
    ));
}

#[test]
fn size_limit_is_an_error_not_a_hang() {
    let _in = dqsym::Context::new().enter();
    let x = s("x") + s("y") + s("z") + s("w");
    let before = dqsym::Context::work_done();
    assert!(matches!(
        x.pow(100_000).check(),
        Err(ScalarError::TooLarge { .. } | ScalarError::TooManyPairs { .. })
    ));
    // Refused after a few squarings, not after the 100,000th power's worth of work.
    let work = dqsym::Context::work_done() - before;
    assert!(work < 50_000_000, "{work} term operations");
    assert!(n(2).pow(1 << 40).check().is_err());
}

#[test]
fn derivative_of_trig_and_polynomials() {
    let t = s("t");
    let l = s("l");
    let e = &l * cos(&(&t * q(1, 2))) + l.pow(2) * &t;
    let d = e.diff("t");
    assert_eq!(d, -(&l * sin(&(&t * q(1, 2))) * q(1, 2)) + l.pow(2));
}

#[test]
fn substitution_into_trig_arguments() {
    let e = cos(&s("t")) * s("l");
    let r = e.subs("t", &(s("a") + s("b")));
    assert_eq!(r, s("l") * cos(&(s("a") + s("b"))));
    assert_eq!(e.subs("t", &Scalar::pi()), -s("l"));
}

#[test]
fn evaluation_agrees_with_f64() {
    let e =
        s("l") * cos(&(s("t") * q(1, 2))) + n(2).sqrt() * sin(&(s("t") + Scalar::pi() * q(1, 3)));
    let v = e.eval_at(&[("l", 1.5), ("t", 0.7)]).unwrap();
    let want = 1.5 * (0.35f64).cos() + 2f64.sqrt() * (0.7 + std::f64::consts::PI / 3.0).sin();
    assert!((v - want).abs() < 1e-12);
}
