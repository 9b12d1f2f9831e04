//! Property tests on random inputs: closed forms are exact and numerically right, the f64
//! instance of the DQ algebra obeys its laws, and generated NumPy code computes what `eval` does.
//! With the round trips of `parse.rs` and the symbolic laws of `laws.rs` they make well over
//! 10,000 cases per run.

use crate::paper_support::{closed, int, sym, S};
use dqsym::{
    closed_form,
    emit::{arguments, Output},
    DualQuat, Ring,
};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;

const ENV: [(&str, f64); 5] = [
    ("theta1", 0.7),
    ("theta2", -1.3),
    ("l1", 1.1),
    ("l2", 0.4),
    ("d", -0.6),
];

fn env(n: &str) -> Option<f64> {
    ENV.iter().find(|(k, _)| *k == n).map(|(_, v)| *v)
}

/// A random angle `a theta1 + b theta2 + k pi/12` (half angles of the paper's kind included),
/// exactly and as f64.
fn angle() -> impl Strategy<Value = (S, f64)> {
    (-2i64..3, -2i64..3, 0i64..24, prop::bool::ANY).prop_map(|(a, b, k, halve)| {
        let den = if halve { 2 } else { 1 };
        let s = (sym("theta1") * int(a) + sym("theta2") * int(b)) * S::from_ratio(1, den)
            + S::pi() * S::from_ratio(k, 12);
        let f = (a as f64 * ENV[0].1 + b as f64 * ENV[1].1) / den as f64
            + std::f64::consts::PI * k as f64 / 12.0;
        (s, f)
    })
}

/// A random scalar built from sums and products of cos / sin of random angles, symbols and small
/// rationals, with its f64 value at [`ENV`].
fn scalar() -> impl Strategy<Value = (S, f64)> {
    let leaf = prop_oneof![
        (-3i64..4, 1i64..4).prop_map(|(p, q)| (S::from_ratio(p, q), p as f64 / q as f64)),
        prop::sample::select(vec![2usize, 3, 4]).prop_map(|i| (sym(ENV[i].0), ENV[i].1)),
        angle().prop_map(|(s, f)| (s.cos(), f.cos())),
        angle().prop_map(|(s, f)| (s.sin(), f.sin())),
    ];
    leaf.prop_recursive(3, 12, 3, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 2..4).prop_map(|v| {
                v.into_iter()
                    .fold((int(0), 0.0), |(s, f), (t, g)| (s + t, f + g))
            }),
            prop::collection::vec(inner.clone(), 2..3).prop_map(|v| {
                v.into_iter()
                    .fold((int(1), 1.0), |(s, f), (t, g)| (s * t, f * g))
            }),
            (inner.clone(), inner).prop_map(|((a, f), (b, g))| (a - b, f - g)),
        ]
    })
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9 * (1.0 + a.abs().max(b.abs()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn closed_form_is_exactly_its_input((x, _) in scalar()) {
        let e = closed_form(&x).map_err(|err| TestCaseError::fail(err.to_string()))?;
        prop_assert_eq!(e.to_scalar(), x);
    }

    #[test]
    fn exact_value_and_closed_form_agree_with_f64((x, f) in scalar()) {
        let v = x.eval(&env).map_err(|err| TestCaseError::fail(err.to_string()))?;
        prop_assert!(near(v, f), "eval {} != f64 {}", v, f);
        let c = closed_form(&x).unwrap().to_scalar().eval(&env).unwrap();
        prop_assert!(near(c, f), "closed form {} != f64 {}", c, f);
    }
}

/// A random unit DQ over f64: a rotation about a random axis through a random point, then a
/// translation.
fn unit_dq() -> impl Strategy<Value = DualQuat<f64>> {
    let coord = || -3.0f64..3.0;
    (
        (coord(), coord(), coord()),
        -7.0f64..7.0,
        (coord(), coord(), coord()),
        (coord(), coord(), coord()),
    )
        .prop_filter("a nonzero axis", |((x, y, z), ..)| {
            x * x + y * y + z * z > 1e-3
        })
        .prop_map(|((x, y, z), angle, p, t)| {
            let n = (x * x + y * y + z * z).sqrt();
            DualQuat::translation(&[t.0, t.1, t.2])
                * DualQuat::rotation_about_point(&[x / n, y / n, z / n], &angle, &[p.0, p.1, p.2])
        })
}

fn dq_near(a: &DualQuat<f64>, b: &DualQuat<f64>) -> bool {
    a.components()
        .iter()
        .zip(b.components())
        .all(|(x, y)| (x - y).abs() < 1e-9 * (1.0 + y.abs()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn f64_product_is_associative(p in unit_dq(), q in unit_dq(), r in unit_dq()) {
        prop_assert!(dq_near(&((p.clone() * q.clone()) * r.clone()), &(p * (q * r))));
    }

    #[test]
    fn f64_conjugate_of_a_product_reverses(p in unit_dq(), q in unit_dq()) {
        let lhs = (p.clone() * q.clone()).conjugate();
        prop_assert!(dq_near(&lhs, &(q.conjugate() * p.conjugate())));
    }

    #[test]
    fn f64_unit_dq_times_its_conjugate_is_one(q in unit_dq()) {
        prop_assert!(dq_near(&(q.clone() * q.conjugate()), &DualQuat::identity()));
        let inv = q.try_inverse().expect("a unit DQ is invertible");
        prop_assert!(dq_near(&inv, &q.conjugate()));
    }

    #[test]
    fn f64_transforms_compose(p in unit_dq(), q in unit_dq(), v in (-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0)) {
        let v = [v.0, v.1, v.2];
        let both = (p.clone() * q.clone()).transform_point(&v);
        let one_by_one = p.transform_point(&q.transform_point(&v));
        for (a, b) in both.iter().zip(&one_by_one) {
            prop_assert!((a - b).abs() < 1e-9 * (1.0 + b.abs()));
        }
    }

    #[test]
    fn f64_matrix_of_a_product_is_the_product_of_matrices(p in unit_dq(), q in unit_dq()) {
        let m = (p.clone() * q.clone()).to_matrix();
        let (a, b) = (p.to_matrix(), q.to_matrix());
        for i in 0..4 {
            for j in 0..4 {
                let ab: f64 = (0..4).map(|k| a.rows[i][k] * b.rows[k][j]).sum();
                prop_assert!((m.rows[i][j] - ab).abs() < 1e-9 * (1.0 + ab.abs()));
            }
        }
    }
}

/// How many random expressions go through the NumPy emitter, all in one generated function and
/// one Python run.
const CODEGEN_CASES: usize = 300;

#[test]
fn generated_numpy_agrees_with_eval_on_random_expressions() {
    let mut runner = TestRunner::deterministic();
    let strategy = scalar();
    let values: Vec<_> = (0..CODEGEN_CASES)
        .map(|_| {
            let (x, _) = strategy.new_tree(&mut runner).expect("a value").current();
            closed(&x)
        })
        .collect();
    let outputs = vec![Output::vector("v", "Random expressions.", values)];
    let args = arguments(&outputs, &["theta1", "theta2"]);
    crate::codegen::check_python("random", &outputs, &args);
}
