//! The dual-quaternion laws on random symbolic inputs, checked exactly by canonical equality and
//! numerically against the f64 instance of the same algebra.

use crate::paper_support::{ev, int, sym, S};
use dqsym::{DualQuat, Ring};
use proptest::prelude::*;

/// A unit DQ: rotation about one of a few exact unit axes by `a theta1 + b theta2 + k pi/6`
/// (half angles stay multiples of pi/12, which have exact radical values),
/// about a point with symbolic or rational coordinates, then a translation.
fn unit_dq() -> impl Strategy<Value = (DualQuat<S>, DualQuat<f64>)> {
    (
        0usize..5,
        -2i64..3,
        -2i64..3,
        0i64..12,
        0usize..4,
        0usize..4,
        -3i64..4,
    )
        .prop_map(|(ax, a, b, k, pc, tc, n)| {
            let axes: [[(i64, i64); 3]; 5] = [
                [(1, 1), (0, 1), (0, 1)],
                [(0, 1), (1, 1), (0, 1)],
                [(0, 1), (0, 1), (1, 1)],
                [(3, 5), (4, 5), (0, 1)],
                [(2, 3), (-1, 3), (2, 3)],
            ];
            let axis_s: [S; 3] = axes[ax].map(|(p, q)| S::from_ratio(p, q));
            let axis_f: [f64; 3] = axes[ax].map(|(p, q)| p as f64 / q as f64);
            let angle_s =
                sym("theta1") * int(a) + sym("theta2") * int(b) + S::pi() * S::from_ratio(k, 6);
            let angle_f = a as f64 * T1 + b as f64 * T2 + std::f64::consts::PI * k as f64 / 6.0;
            let names = ["l1", "l2", "d", "a2"];
            let (ps, pf) = (sym(names[pc]), VALS[pc]);
            let (ts, tf) = (sym(names[tc]) * int(n), VALS[tc] * n as f64);
            let qs = DualQuat::translation(&[ts.clone(), int(n), int(0)])
                * DualQuat::rotation_about_point(&axis_s, &angle_s, &[int(0), ps.clone(), int(1)]);
            let qf = DualQuat::translation(&[tf, n as f64, 0.0])
                * DualQuat::rotation_about_point(&axis_f, &angle_f, &[0.0, pf, 1.0]);
            (qs, qf)
        })
}

const T1: f64 = 0.7;
const T2: f64 = -1.3;
const VALS: [f64; 4] = [1.1, 0.4, -0.6, 2.3];

fn env(n: &str) -> Option<f64> {
    match n {
        "theta1" => Some(T1),
        "theta2" => Some(T2),
        "l1" => Some(VALS[0]),
        "l2" => Some(VALS[1]),
        "d" => Some(VALS[2]),
        "a2" => Some(VALS[3]),
        _ => None,
    }
}

fn agrees(s: &DualQuat<S>, f: &DualQuat<f64>) -> bool {
    s.components().iter().zip(f.components()).all(|(a, b)| {
        let v = a.eval(&env).expect("bound");
        (v - b).abs() < 1e-9 * (1.0 + b.abs())
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn product_is_associative((p, pf) in unit_dq(), (q, qf) in unit_dq(), (r, rf) in unit_dq()) {
        let left = (p.clone() * q.clone()) * r.clone();
        prop_assert_eq!(&left, &(p * (q * r)));
        prop_assert!(agrees(&left, &(pf * qf * rf)));
    }

    #[test]
    fn conjugate_of_a_product_reverses((p, pf) in unit_dq(), (q, qf) in unit_dq()) {
        let pq = p.clone() * q.clone();
        prop_assert_eq!(pq.conjugate(), q.conjugate() * p.conjugate());
        prop_assert_eq!(pq.combined_conjugate(), q.combined_conjugate() * p.combined_conjugate());
        prop_assert!(agrees(&pq.conjugate(), &(pf * qf).conjugate()));
    }

    #[test]
    fn inverse_of_a_unit_dq_is_its_conjugate((q, qf) in unit_dq()) {
        let inv = q.try_inverse().expect("unit DQs are invertible");
        prop_assert_eq!(&inv, &q.conjugate());
        prop_assert_eq!(q.clone() * inv.clone(), DualQuat::identity());
        prop_assert!(q.unit_constraints().hold_exactly());
        prop_assert!(agrees(&inv, &qf.try_inverse().expect("f64 inverse")));
    }

    #[test]
    fn norm_of_a_product_is_the_product_of_norms((p, _pf) in unit_dq(), (q, _qf) in unit_dq()) {
        let n = (p.clone() * q.clone()).norm_squared();
        let (a, b) = (p.norm_squared(), q.norm_squared());
        prop_assert_eq!(n.re, a.re.clone() * b.re.clone());
        prop_assert_eq!(n.du, a.re * b.du + a.du * b.re);
    }

    #[test]
    fn transform_composition_eq11((p, pf) in unit_dq(), (q, qf) in unit_dq()) {
        let v = [sym("vx"), sym("vy"), int(2)];
        let both = (p.clone() * q.clone()).transform_point(&v);
        prop_assert_eq!(&both, &p.transform_point(&q.transform_point(&v)));
        let vf = [0.3, -0.8, 2.0];
        let bf = (pf * qf).transform_point(&vf);
        for k in 0..3 {
            let e = [("vx".to_string(), 0.3), ("vy".to_string(), -0.8), ("theta1".to_string(), T1), ("theta2".to_string(), T2),
                ("l1".to_string(), VALS[0]), ("l2".to_string(), VALS[1]), ("d".to_string(), VALS[2]), ("a2".to_string(), VALS[3])];
            prop_assert!((ev(&both[k], &e) - bf[k]).abs() < 1e-9);
        }
    }

    #[test]
    fn matrix_round_trip_of_numeric_dqs((_q, qf) in unit_dq()) {
        let m = qf.to_matrix();
        let back = DualQuat::from_matrix(&m).expect("rigid motion");
        // q and -q are the same motion.
        let same = back.components().iter().zip(qf.components()).all(|(a, b)| (a - b).abs() < 1e-9);
        let opposite = back.components().iter().zip(qf.components()).all(|(a, b)| (a + b).abs() < 1e-9);
        prop_assert!(same || opposite);
    }
}

#[test]
fn symbolic_dq_matrix_round_trip_at_exact_angles() {
    // from_matrix takes square roots of numbers: exact when the squared quaternion components
    // are rational, as at multiples of pi/2 and pi/3.
    for k in [0, 2, 3, 4, 6, 8, 9, 10] {
        let q = DualQuat::translation(&[sym("a2"), int(1), int(0)])
            * DualQuat::rotation(&[int(0), int(0), int(1)], &(S::pi() * S::from_ratio(k, 6)));
        let m = q.to_matrix();
        if let Some(back) = DualQuat::from_matrix(&m) {
            assert!(back == q || back == -q.clone(), "round trip at k = {k}");
        } else {
            panic!("from_matrix failed at k = {k}");
        }
    }
}
