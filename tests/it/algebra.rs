//! The algebra and kinematics laws over f64, the numeric oracle: quaternion and dual
//! quaternion identities as properties, every dual-quaternion motion against a product of
//! plain 4×4 elementary matrices, and the paper's worked examples of sec 2–3 and 6.1.

use dqsym::{
    algebra::DualNumber,
    kin::{dh_link, dh_link_matrix, mdh_link, mdh_link_matrix},
    Chain, DualQuat, Joint, Matrix4, Quat,
};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

const TOL: f64 = 1e-9;

/// `|a − b| ≤ TOL · max(1, |a|, |b|)`.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= TOL * a.abs().max(b.abs()).max(1.0)
}

fn assert_close_slice(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len());
    let ok = a.iter().zip(b).all(|(x, y)| close(*x, *y));
    assert!(ok, "{what}:\n left: {a:?}\nright: {b:?}");
}

fn assert_dq_close(a: &DualQuat<f64>, b: &DualQuat<f64>) {
    assert_close_slice(&a.components(), &b.components(), "dual quaternions differ");
}

/// Equal as rigid motions: `q` and `−q` are the same motion.
fn assert_same_motion(a: &DualQuat<f64>, b: &DualQuat<f64>) {
    if a.real.dot(&b.real) < 0.0 {
        assert_dq_close(&-a, b);
    } else {
        assert_dq_close(a, b);
    }
}

fn flat(m: &Matrix4<f64>) -> Vec<f64> {
    m.rows.iter().flatten().copied().collect()
}

fn assert_matrix_close(a: &Matrix4<f64>, b: &Matrix4<f64>) {
    assert_close_slice(&flat(a), &flat(b), "matrices differ");
}

fn assert_point_close(a: &[f64; 3], b: &[f64; 3]) {
    assert_close_slice(a, b, "points differ");
}

fn unit_vector() -> impl Strategy<Value = [f64; 3]> {
    (-1.0..=1.0f64, 0.0..(2.0 * PI)).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    })
}

fn angle() -> impl Strategy<Value = f64> {
    -2.0 * PI..2.0 * PI
}

fn length() -> impl Strategy<Value = f64> {
    -3.0..3.0f64
}

fn vector() -> impl Strategy<Value = [f64; 3]> {
    [length(), length(), length()]
}

/// A random rigid motion: a rotation about a random axis, then a random translation.
fn unit_dq() -> impl Strategy<Value = DualQuat<f64>> {
    (unit_vector(), angle(), vector())
        .prop_map(|(axis, theta, t)| DualQuat::translation(&t) * DualQuat::rotation(&axis, &theta))
}

/// A random dual quaternion, not necessarily unit.
fn any_dq() -> impl Strategy<Value = DualQuat<f64>> {
    prop::array::uniform8(-2.0..2.0f64).prop_map(DualQuat::from_components)
}

fn any_quat() -> impl Strategy<Value = Quat<f64>> {
    prop::array::uniform4(-2.0..2.0f64).prop_map(Quat::from_components)
}

fn assert_unit(q: &DualQuat<f64>) {
    let c = q.unit_constraints();
    assert!(
        c.norm_minus_one.abs() < TOL,
        "|q|² − 1 = {}",
        c.norm_minus_one
    );
    assert!(c.real_dot_dual.abs() < TOL, "q · q_ε = {}", c.real_dot_dual);
}

proptest! {
    #[test]
    fn quaternion_product_is_associative(a in any_quat(), b in any_quat(), c in any_quat()) {
        let (l, r) = ((&a * &b) * &c, &a * (&b * &c));
        assert_close_slice(&l.components(), &r.components(), "(ab)c != a(bc)");
    }

    #[test]
    fn dual_quaternion_product_is_associative(a in any_dq(), b in any_dq(), c in any_dq()) {
        assert_dq_close(&((&a * &b) * &c), &(&a * (&b * &c)));
    }

    #[test]
    fn dual_quaternion_product_distributes_over_sum(a in any_dq(), b in any_dq(), c in any_dq()) {
        assert_dq_close(&(&a * (&b + &c)), &(&a * &b + &a * &c));
        assert_dq_close(&((&a - &b) * &c), &(&a * &c - &b * &c));
    }

    #[test]
    fn conjugate_of_product_is_product_of_conjugates_reversed(p in any_dq(), q in any_dq()) {
        let pq = &p * &q;
        assert_dq_close(&pq.conjugate(), &(q.conjugate() * p.conjugate()));
        assert_dq_close(
            &pq.combined_conjugate(),
            &(q.combined_conjugate() * p.combined_conjugate()),
        );
    }

    #[test]
    fn dual_conjugate_of_product_keeps_the_order(p in any_dq(), q in any_dq()) {
        assert_dq_close(&(&p * &q).dual_conjugate(), &(p.dual_conjugate() * q.dual_conjugate()));
    }

    #[test]
    fn combined_conjugate_is_dual_conjugate_of_conjugate(q in any_dq()) {
        assert_dq_close(&q.combined_conjugate(), &q.conjugate().dual_conjugate());
    }

    #[test]
    fn dual_quaternion_times_its_inverse_is_identity(q in any_dq()) {
        prop_assume!(q.real.norm_squared() > 0.05);
        let inv = q.try_inverse().expect("invertible real part");
        assert_dq_close(&(&q * &inv), &DualQuat::identity());
        assert_dq_close(&(&inv * &q), &DualQuat::identity());
    }

    #[test]
    fn unit_dual_quaternion_inverse_is_its_conjugate(q in unit_dq()) {
        assert_dq_close(&q.try_inverse().unwrap(), &q.conjugate());
    }

    #[test]
    fn norm_of_product_is_product_of_norms(p in any_dq(), q in any_dq()) {
        let lhs = (&p * &q).norm_squared();
        let rhs = p.norm_squared().mul_ref(&q.norm_squared());
        assert_close_slice(&[lhs.re, lhs.du], &[rhs.re, rhs.du], "norms");
    }

    #[test]
    fn norm_is_dq_times_its_conjugate(q in any_dq()) {
        let DualNumber { re, du } = q.norm_squared();
        let qq = &q * q.conjugate();
        assert_close_slice(&qq.components(), &[re, 0., 0., 0., du, 0., 0., 0.], "q q*");
    }

    #[test]
    fn rigid_motions_are_unit_and_closed_under_product(p in unit_dq(), q in unit_dq()) {
        assert_unit(&p);
        assert_unit(&(&p * &q));
        let n = p.norm_squared();
        assert_close_slice(&[n.re, n.du], &[1.0, 0.0], "unit norm");
    }

    #[test]
    fn transforming_by_a_product_is_transforming_in_turn(
        p in unit_dq(), q in unit_dq(), v in vector()
    ) {
        // Eq 11: q acts first, then p.
        let by_product = (&p * &q).transform_point(&v);
        let in_turn = p.transform_point(&q.transform_point(&v));
        assert_point_close(&by_product, &in_turn);
    }

    #[test]
    fn translation_part_is_where_the_origin_goes(q in unit_dq()) {
        assert_point_close(&q.translation_part(), &q.transform_point(&[0.0; 3]));
    }

    #[test]
    fn dual_quaternion_to_matrix_to_dual_quaternion_round_trips(q in unit_dq()) {
        let back = DualQuat::from_matrix(&q.to_matrix()).expect("a rigid motion");
        assert_same_motion(&back, &q);
    }

    #[test]
    fn matrix_to_dual_quaternion_to_matrix_round_trips(
        a in angle(), b in angle(), c in angle(), t in vector()
    ) {
        let m = Matrix4::trans(&t) * Matrix4::rot_z(&a) * Matrix4::rot_y(&b) * Matrix4::rot_x(&c);
        let q = DualQuat::from_matrix(&m).expect("a rigid motion");
        assert_unit(&q);
        assert_matrix_close(&q.to_matrix(), &m);
    }

    #[test]
    fn matrix_of_a_product_is_the_product_of_matrices(p in unit_dq(), q in unit_dq()) {
        assert_matrix_close(&(&p * &q).to_matrix(), &(p.to_matrix() * q.to_matrix()));
    }

    #[test]
    fn matrix_moves_points_like_the_dual_quaternion(q in unit_dq(), v in vector()) {
        assert_point_close(&q.to_matrix().transform_point(&v), &q.transform_point(&v));
    }

    #[test]
    fn rotation_about_an_axis_matches_rodrigues_matrix(n in unit_vector(), a in angle()) {
        let q = DualQuat::rotation(&n, &a);
        assert_matrix_close(&q.to_matrix(), &Matrix4::rotation(&n, &a));
    }

    #[test]
    fn rotations_about_coordinate_axes_match_elementary_matrices(a in angle()) {
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let elementary = [Matrix4::rot_x(&a), Matrix4::rot_y(&a), Matrix4::rot_z(&a)];
        for (axis, m) in axes.iter().zip(&elementary) {
            assert_matrix_close(&DualQuat::rotation(axis, &a).to_matrix(), m);
        }
    }

    #[test]
    fn rotate_then_translate_matches_matrix_product(
        a in angle(), b in angle(), t in vector()
    ) {
        let q = DualQuat::translation(&t)
            * DualQuat::rotation(&[0.0, 0.0, 1.0], &a)
            * DualQuat::rotation(&[1.0, 0.0, 0.0], &b);
        let m = Matrix4::trans(&t) * Matrix4::rot_z(&a) * Matrix4::rot_x(&b);
        assert_matrix_close(&q.to_matrix(), &m);
        let r = DualQuat::from_rotation_and_translation(Quat::rotation(&[0.0, 0.0, 1.0], &a), &t);
        assert_matrix_close(&r.to_matrix(), &(Matrix4::trans(&t) * Matrix4::rot_z(&a)));
    }

    #[test]
    fn rotation_about_a_point_is_translate_rotate_translate_back(
        n in unit_vector(), a in angle(), p in vector(), v in vector()
    ) {
        let q = DualQuat::rotation_about_point(&n, &a, &p);
        let minus_p = [-p[0], -p[1], -p[2]];
        let m = Matrix4::trans(&p) * Matrix4::rotation(&n, &a) * Matrix4::trans(&minus_p);
        assert_matrix_close(&q.to_matrix(), &m);
        let composed =
            DualQuat::translation(&p) * DualQuat::rotation(&n, &a) * DualQuat::translation(&minus_p);
        assert_dq_close(&q, &composed);
        // Every point of the axis is fixed.
        let on_axis = [p[0] + v[0] * n[0], p[1] + v[0] * n[1], p[2] + v[0] * n[2]];
        assert_point_close(&q.transform_point(&on_axis), &on_axis);
    }

    #[test]
    fn screw_is_rotation_about_the_line_and_slide_along_it(
        n in unit_vector(), p in vector(), a in angle(), slide in length()
    ) {
        // Corrected eq 18 (ERRATA item 6: the moment carries a factor 2).
        let q = DualQuat::screw(&n, &p, &a, &slide);
        let t = [slide * n[0], slide * n[1], slide * n[2]];
        let composed = DualQuat::translation(&t) * DualQuat::rotation_about_point(&n, &a, &p);
        assert_dq_close(&q, &composed);
        let minus_p = [-p[0], -p[1], -p[2]];
        let m = Matrix4::trans(&t)
            * Matrix4::trans(&p)
            * Matrix4::rotation(&n, &a)
            * Matrix4::trans(&minus_p);
        assert_matrix_close(&q.to_matrix(), &m);
        assert_unit(&q);
    }

    #[test]
    fn dh_link_dual_quaternion_matches_rz_tz_tx_rx(
        theta in angle(), d in length(), a in length(), alpha in angle()
    ) {
        let q = dh_link(&theta, &d, &a, &alpha);
        let m = Matrix4::rot_z(&theta)
            * Matrix4::trans(&[0.0, 0.0, d])
            * Matrix4::trans(&[a, 0.0, 0.0])
            * Matrix4::rot_x(&alpha);
        assert_matrix_close(&dh_link_matrix(&theta, &d, &a, &alpha), &m);
        assert_matrix_close(&q.to_matrix(), &m);
        assert_unit(&q);
    }

    #[test]
    fn mdh_link_dual_quaternion_matches_rx_tx_rz_tz(
        alpha in angle(), a in length(), theta in angle(), d in length()
    ) {
        let q = mdh_link(&alpha, &a, &theta, &d);
        let m = mdh_link_matrix(&alpha, &a, &theta, &d);
        assert_matrix_close(&q.to_matrix(), &m);
        // Sec 5 A: q_rot(x, α) q_trans(x, a) q_rot(z, θ) q_trans(z, d).
        let paper = DualQuat::rotation(&[1.0, 0.0, 0.0], &alpha)
            * DualQuat::translation(&[a, 0.0, 0.0])
            * DualQuat::rotation(&[0.0, 0.0, 1.0], &theta)
            * DualQuat::translation(&[0.0, 0.0, d]);
        assert_dq_close(&q, &paper);
    }

    #[test]
    fn chain_dual_quaternion_matches_chain_matrix(
        params in prop::array::uniform4((angle(), length(), length(), angle())),
        q in prop::array::uniform4(angle()),
        axis in unit_vector(), point in vector(), tool in unit_dq(),
    ) {
        let [p0, p1, p2, p3] = params;
        let chain = Chain::new(vec![
            Joint::revolute_dh(p0.0, p0.1, p0.2, p0.3),
            Joint::prismatic_dh(p1.0, p1.1, p1.2, p1.3),
            Joint::revolute_mdh(p2.3, p2.2, p2.0, p2.1),
            Joint::prismatic_mdh(p3.3, p3.2, p3.0, p3.1),
            Joint::revolute_screw(axis, point),
            Joint::prismatic_screw(axis),
        ])
        .with_tool(tool.clone());
        let values = [q[0], q[1], q[2], q[3], q[0] - q[1], q[2] * 0.5];
        for (joint, v) in chain.joints.iter().zip(&values) {
            assert_matrix_close(&joint.dq(v).to_matrix(), &joint.matrix(v));
        }
        let fk = chain.forward(&values).unwrap();
        assert_unit(&fk);
        assert_matrix_close(&fk.to_matrix(), &chain.forward_matrix(&values).unwrap());
        let frames = chain.forward_frames(&values).unwrap();
        assert_dq_close(&(frames.last().unwrap() * &tool), &fk);
    }
}

#[test]
fn translation_dual_quaternion_adds_t_to_a_point() {
    // Sec 2-2: q_T = 1 + (ε/2) t, its combined conjugate is itself, and
    // q_T (1 + ε v) q_T = 1 + ε (v + t).
    let (t, v) = ([1.5, -2.0, 0.25], [0.5, 4.0, -1.0]);
    let q = DualQuat::translation(&t);
    assert_eq!(q.components(), [1.0, 0.0, 0.0, 0.0, 0.0, 0.75, -1.0, 0.125]);
    assert_eq!(q.combined_conjugate(), q);
    let image = &q * DualQuat::point(&v) * &q;
    assert_eq!(image, DualQuat::point(&[2.0, 2.0, -0.75]));
}

#[test]
fn planar_examples_of_sec_3b_match_their_matrices() {
    let (theta, d1, d2, l) = (0.8, 1.25, -0.5, 2.0);
    let (c, s) = (f64::cos(theta), f64::sin(theta));
    let x = [1.0, 0.0, 0.0];
    let r = DualQuat::rotation(&x, &theta);
    let t = DualQuat::translation(&[0.0, d1, d2]);
    let v = [0.0, l, 0.0];
    // (b1): rotate, then translate.
    let b1 = (&t * &r).transform_point(&v);
    assert_point_close(&b1, &[0.0, d1 + l * c, d2 + l * s]);
    // (b2): translate, then rotate. The paper prints a spurious factor 1/2 (ERRATA item 3);
    // this is the corrected value, which its own 4×4 check agrees with.
    let b2 = (&r * &t).transform_point(&v);
    assert_point_close(
        &b2,
        &[0.0, d1 * c + l * c - d2 * s, d1 * s + l * s + d2 * c],
    );
    // (b3): rotate about the axis through C = (0, y, z) parallel to x.
    let (y, z) = (0.75, -1.5);
    let q3 = DualQuat::rotation_about_point(&x, &theta, &[0.0, y, z]);
    let (hc, hs) = (f64::cos(theta / 2.0), f64::sin(theta / 2.0));
    assert_close_slice(
        &q3.components(),
        &[hc, hs, 0.0, 0.0, 0.0, 0.0, z * hs, -y * hs],
        "q3 of sec 3-B 3)",
    );
    let b3 = q3.transform_point(&v);
    assert_point_close(
        &b3,
        &[0.0, l * c + z * s + y - y * c, l * s - y * s + z - z * c],
    );
}

#[test]
fn rotation_of_sec_3a_has_the_printed_matrix() {
    let n = [6f64.sqrt() / 4.0, 2f64.sqrt() / 4.0, 2f64.sqrt() / 2.0];
    let theta = 1.1;
    let (c, s) = (f64::cos(theta), f64::sin(theta));
    let (r2, r3, r6) = (2f64.sqrt(), 3f64.sqrt(), 6f64.sqrt());
    let printed = Matrix4::from_rotation_and_translation(
        [
            [
                3.0 / 8.0 + 5.0 * c / 8.0,
                r3 * (1.0 - c) / 8.0 - r2 * s / 2.0,
                r3 * (1.0 - c) / 4.0 + r2 * s / 4.0,
            ],
            [
                r3 * (1.0 - c) / 8.0 + r2 * s / 2.0,
                1.0 / 8.0 + 7.0 * c / 8.0,
                (1.0 - c) / 4.0 - r6 * s / 4.0,
            ],
            [
                r3 * (1.0 - c) / 4.0 - r2 * s / 4.0,
                (1.0 - c) / 4.0 + r6 * s / 4.0,
                0.5 + c / 2.0,
            ],
        ],
        [0.0; 3],
    );
    assert_matrix_close(&DualQuat::rotation(&n, &theta).to_matrix(), &printed);
}

#[test]
fn appendix_i_translation_formulas_hold_with_q5_to_q8_twice_the_dual_part() {
    let q = DualQuat::translation(&[0.3, -1.2, 2.0]) * DualQuat::rotation(&[0.0, 0.6, 0.8], &0.9);
    let [q1, q2, q3, q4, e1, e2, e3, e4] = q.components();
    let [q5, q6, q7, q8] = [2.0 * e1, 2.0 * e2, 2.0 * e3, 2.0 * e4];
    // d(q) of Appendix I.
    let d = [
        -q5 * q2 + q8 * q3 - q7 * q4 + q6 * q1,
        -q8 * q2 - q5 * q3 + q6 * q4 + q7 * q1,
        q7 * q2 - q6 * q3 - q5 * q4 + q8 * q1,
    ];
    assert_point_close(&q.translation_part(), &d);
    assert_point_close(&d, &[0.3, -1.2, 2.0]);
    // q0 of Appendix I, from the matrix's d: (q5..q8) = G(q) d.
    let g = [[-q2, -q3, -q4], [q1, q4, -q3], [-q4, q1, q2], [q3, -q2, q1]];
    let q0: Vec<f64> = g
        .iter()
        .map(|row| row[0] * d[0] + row[1] * d[1] + row[2] * d[2])
        .collect();
    let back = DualQuat::from_matrix(&q.to_matrix()).unwrap();
    let twice_dual: Vec<f64> = back.dual.components().iter().map(|x| 2.0 * x).collect();
    assert_close_slice(&twice_dual, &q0, "Appendix I q0");
}

#[test]
fn half_turns_about_each_axis_convert_to_dual_quaternions() {
    // tr R = −1: Shepperd's method must leave the w branch.
    for m in [
        Matrix4::rot_x(&PI),
        Matrix4::rot_y(&PI),
        Matrix4::rot_z(&PI),
    ] {
        let q = DualQuat::from_matrix(&m).expect("a rotation");
        assert_unit(&q);
        assert_matrix_close(&q.to_matrix(), &m);
    }
}

#[test]
fn rrr_arm_end_effector_is_l1c1_l2c12_l3c123() {
    // Sec 6.1: three revolute joints about axes parallel to x through (0, 0, 0),
    // (0, l1, 0) and (0, l1 + l2, 0); the wrist starts at (0, l1 + l2 + l3, 0).
    let (l1, l2, l3) = (1.0, 0.7, 0.4);
    let x = [1.0, 0.0, 0.0];
    let chain = Chain::new(vec![
        Joint::revolute_screw(x, [0.0; 3]),
        Joint::revolute_screw(x, [0.0, l1, 0.0]),
        Joint::revolute_screw(x, [0.0, l1 + l2, 0.0]),
    ]);
    let (t1, t2, t3) = (0.3, -1.1, FRAC_PI_2);
    let fk = chain.forward(&[t1, t2, t3]).unwrap();
    let v0 = fk.transform_point(&[0.0, l1 + l2 + l3, 0.0]);
    let expected = [
        0.0,
        l1 * t1.cos() + l2 * (t1 + t2).cos() + l3 * (t1 + t2 + t3).cos(),
        l1 * t1.sin() + l2 * (t1 + t2).sin() + l3 * (t1 + t2 + t3).sin(),
    ];
    assert_point_close(&v0, &expected);
    let m = chain.forward_matrix(&[t1, t2, t3]).unwrap();
    assert_point_close(&m.transform_point(&[0.0, l1 + l2 + l3, 0.0]), &expected);
}
