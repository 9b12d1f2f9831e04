//! Sec 6 of the paper: the RRR arm (and Appendix III), the wrist (sec 6.2, Appendix IV), the 6R
//! robot (sec 6.3) and the Puma-like robot (sec 6.4), plus the PUMA 560 pose in DH form.
#![allow(clippy::needless_range_loop)] // Matrix entries read best as (i, j).

use crate::paper_support::*;
use dqsym::{
    kin::{dh_link, dh_link_matrix},
    DualQuat, Matrix4, Quat,
};

fn t(i: usize) -> S {
    sym(&format!("theta{i}"))
}

/// Rotation of theta_i about the x-parallel axis through (0, y, 0).
fn rx_about(i: usize, y: S) -> DualQuat<S> {
    DualQuat::rotation_about_point(&ex(), &t(i), &v3(int(0), y, int(0)))
}

#[test]
fn sec6_1_rrr_arm_end_effector_is_l1c1_l2c12_l3c123() {
    let (l1, l2, l3) = (sym("l1"), sym("l2"), sym("l3"));
    let qd3 = rx_about(3, &l1 + &l2);
    let qd2 = rx_about(2, l1.clone());
    let qd1 = rx_about(1, int(0));
    // q_d3 as printed: (c3, s3, 0, 0) + eps (0; 0, 0, -(l1 + l2) s3).
    let h3 = half(&t(3));
    assert_eq!(
        qd3.dual,
        quat(int(0), int(0), int(0), -((&l1 + &l2) * sin(&h3)))
    );
    let v3p = v3(int(0), &l1 + &l2 + &l3, int(0));
    let v2 = qd3.transform_point(&v3p);
    let v1 = qd2.transform_point(&v2);
    let v0 = qd1.transform_point(&v1);
    let direct = (qd1.clone() * qd2.clone() * qd3.clone()).transform_point(&v3p);
    assert_eq!(v0, direct, "link by link equals the direct product");
    let mut r = Report::new("sec 6.1: planar RRR arm, link by link and directly");
    r.dq("q_d3", &qd3).dq("q_d2", &qd2);
    r.vector("v2", &v2)
        .vector("v1", &v1)
        .vector("v0", &v0)
        .vector("direct (q_d1 q_d2 q_d3) v3", &direct);
    snap("sec6_1_rrr", &r);
    let o = dqsym::PlainOptions::default();
    assert_eq!(
        dqsym::plain(&closed(&v0[1]), &o),
        "l1 c1 + l2 c12 + l3 c123"
    );
    assert_eq!(
        dqsym::plain(&closed(&v0[2]), &o),
        "l1 s1 + l2 s12 + l3 s123"
    );
    check_numeric(
        &["theta1", "theta2", "theta3", "l1", "l2", "l3"],
        &v0,
        |e| {
            let (a, b, c) = (get(e, "l1"), get(e, "l2"), get(e, "l3"));
            let m = mat_rot_about('x', get(e, "theta1"), [0.0; 3])
                * mat_rot_about('x', get(e, "theta2"), [0.0, a, 0.0])
                * mat_rot_about('x', get(e, "theta3"), [0.0, a + b, 0.0]);
            m.transform_point(&[0.0, a + b + c, 0.0]).to_vec()
        },
    );
}

#[test]
fn appendix3_listing_link_by_link() {
    // The Matlab listing with c_i, s_i = cos, sin(theta_i / 2): dq * v * cq, cq the combined conjugate.
    let (l1, l2, l3) = (sym("l1"), sym("l2"), sym("l3"));
    let dq3 = rx_about(3, &l1 + &l2);
    let cq3 = dq3.combined_conjugate();
    let v3p = DualQuat::point(&v3(int(0), &l1 + &l2 + &l3, int(0)));
    let r3 = dq3.clone() * v3p * cq3;
    let dq2 = rx_about(2, l1.clone());
    let r2 = dq2.clone() * r3.clone() * dq2.combined_conjugate();
    let dq1 = rx_about(1, int(0));
    let r1 = dq1.clone() * r2.clone() * dq1.combined_conjugate();
    let mut r = Report::new("Appendix III: 3R planar manipulator, the listing's products");
    r.dq("dq3*v3*cq3", &r3);
    r.note("ERRATA 7: the listing prints c12, s12 in dq2*v2*cq2; the result has c23, s23 (as its own link(1) uses)");
    r.dq("dq2*v2*cq2", &r2).dq("dq1*v1*cq1", &r1);
    snap("appendix3_listing", &r);
    let pts = [
        r3.dual.vector_part(),
        r2.dual.vector_part(),
        r1.dual.vector_part(),
    ]
    .concat();
    check_numeric(
        &["theta1", "theta2", "theta3", "l1", "l2", "l3"],
        &pts,
        |e| {
            let (a, b, c) = (get(e, "l1"), get(e, "l2"), get(e, "l3"));
            let m3 = mat_rot_about('x', get(e, "theta3"), [0.0, a + b, 0.0]);
            let m2 = mat_rot_about('x', get(e, "theta2"), [0.0, a, 0.0]);
            let m1 = mat_rot_about('x', get(e, "theta1"), [0.0; 3]);
            let p = [0.0, a + b + c, 0.0];
            [
                m3.transform_point(&p),
                (m2.clone() * m3.clone()).transform_point(&p),
                (m1 * m2 * m3).transform_point(&p),
            ]
            .concat()
        },
    );
}

#[test]
fn sec6_2_wrist_zyz_quaternions_and_appendix4_yzy_matrix() {
    let q1 = Quat::rotation(&ez(), &t(1));
    let q2 = Quat::rotation(&ey(), &t(2));
    let q3 = Quat::rotation(&ez(), &t(3));
    let zyz = DualQuat::from_real(q1 * q2 * q3).to_matrix();
    let a1 = Matrix4::rot_y(&t(1));
    let a2 = Matrix4::rot_z(&t(2));
    let a3 = Matrix4::rot_y(&t(3));
    let yzy = a1.clone() * a2.clone() * a3.clone();
    // Appendix IV's printed R.
    let (c, s) = (|i| cos(&t(i)), |i| sin(&t(i)));
    let printed = [
        [
            c(1) * c(2) * c(3) - s(1) * s(3),
            -(c(3) * s(2)),
            c(1) * s(3) + c(2) * c(3) * s(1),
        ],
        [c(1) * s(2), c(2), s(1) * s(2)],
        [
            -(c(3) * s(1)) - c(1) * c(2) * s(3),
            s(2) * s(3),
            c(1) * c(3) - c(2) * s(1) * s(3),
        ],
    ];
    let swapped = a3 * a2 * a1;
    for i in 0..3 {
        for j in 0..3 {
            assert_eq!(
                swapped.rows[i][j], printed[i][j],
                "printed R = Ry(theta3) Rz(theta2) Ry(theta1)"
            );
        }
    }
    assert_ne!(
        yzy.rows[0][2], printed[0][2],
        "ERRATA 8: the printed R is not a1 a2 a3"
    );
    let zyz_mat = Matrix4::rot_z(&t(1)) * Matrix4::rot_y(&t(2)) * Matrix4::rot_z(&t(3));
    for i in 0..3 {
        for j in 0..3 {
            assert_eq!(
                zyz.rows[i][j], zyz_mat.rows[i][j],
                "quaternion product = K(theta1, theta2, theta3)"
            );
        }
    }
    let mut r = Report::new("sec 6.2: the wrist. The listed quaternions q1 = (c1,0,0,s1), q2 = (c2,0,s2,0), q3 = (c3,0,0,s3) are ZYZ");
    r.matrix3("R(q1 q2 q3) = Rz Ry Rz", &zyz);
    r.note("Appendix IV: a1 a2 a3 = Ry(t1) Rz(t2) Ry(t3) (YZY)");
    r.matrix3("a1 a2 a3", &yzy);
    r.note("ERRATA 8: the printed R equals Ry(t3) Rz(t2) Ry(t1) (t1 and t3 swapped)");
    r.matrix3("printed R", &swapped);
    snap("sec6_2_wrist", &r);
}

/// The 6R robot of sec 6.3 with L = l1 + l2 + l3.
fn six_r() -> (Vec<DualQuat<S>>, [S; 3]) {
    let (l1, l2, l3, l4) = (sym("l1"), sym("l2"), sym("l3"), sym("l4"));
    let big_l = &l1 + &l2 + &l3;
    let qd1 = rx_about(1, int(0));
    let qd2 = rx_about(2, l1.clone());
    let qd3 = rx_about(3, &l1 + &l2);
    let q4 = DualQuat::rotation(&ey(), &t(4));
    let qd5 = DualQuat::rotation_about_point(&ez(), &t(5), &v3(int(0), big_l.clone(), int(0)));
    let q6 = DualQuat::rotation(&ey(), &t(6));
    (
        vec![qd1, qd2, qd3, q4, qd5, q6],
        v3(int(0), big_l + l4, int(0)),
    )
}

#[test]
fn sec6_3_six_r_robot_tool_point() {
    let (q, v6) = six_r();
    let mut v = v6.clone();
    let mut stages = Vec::new();
    for k in (0..6).rev() {
        v = q[k].transform_point(&v);
        stages.push((k, v.clone()));
    }
    // q_d5 as printed: (c5, 0, 0, s5) + eps (L s5, 0, 0) as the vector of the dual part.
    let big_l = sym("l1") + sym("l2") + sym("l3");
    assert_eq!(
        q[4].dual,
        quat(int(0), big_l * sin(&half(&t(5))), int(0), int(0))
    );
    assert_eq!(
        stages[0].1, v6,
        "v5 = v6: q6 leaves the tool point unchanged"
    );
    let mut r = Report::new("sec 6.3: 6R robot, tool point (0, L + l4, 0) with L = l1 + l2 + l3, transformed joint by joint");
    r.dq("q_d5", &q[4]);
    for (k, p) in &stages {
        r.vector(&format!("v{k}"), p);
    }
    // The dq2 step on a general point (x2, y2, z2).
    let g = q[1].transform_point(&v3(sym("x2"), sym("y2"), sym("z2")));
    r.vector("q_d2 (x2, y2, z2) conj(q_d2)", &g);
    snap("sec6_3_six_r", &r);
    let o = dqsym::PlainOptions::default();
    let y = dqsym::plain(&closed(&stages[5].1[1]), &o);
    let e = closed(&stages[5].1[1]);
    // The target form l1 c1 + l2 c12 + (l3 + l4 c5) c123 - l4 s4 s5 s123 costs 18 operations.
    assert!(
        e.cost().ops <= 18,
        "tool point y = {y} costs {:?}",
        e.cost()
    );
    check_numeric(
        &[
            "theta1", "theta2", "theta3", "theta4", "theta5", "theta6", "l1", "l2", "l3", "l4",
        ],
        &stages[5].1,
        |e| {
            let (a, b, c, d) = (get(e, "l1"), get(e, "l2"), get(e, "l3"), get(e, "l4"));
            let big = a + b + c;
            let m = mat_rot_about('x', get(e, "theta1"), [0.0; 3])
                * mat_rot_about('x', get(e, "theta2"), [0.0, a, 0.0])
                * mat_rot_about('x', get(e, "theta3"), [0.0, a + b, 0.0])
                * Matrix4::rot_y(&get(e, "theta4"))
                * mat_rot_about('z', get(e, "theta5"), [0.0, big, 0.0])
                * Matrix4::rot_y(&get(e, "theta6"));
            m.transform_point(&[0.0, big + d, 0.0]).to_vec()
        },
    );
}

#[test]
fn sec6_4_puma_like_corrected_qd5_keeps_wrist_centre_fixed() {
    let (d, big_l) = (sym("d"), sym("L"));
    let c4 = v3(d.clone(), big_l.clone(), int(0));
    let qd1 = DualQuat::rotation(&ez(), &t(1));
    let qd2 = rx_about(2, sym("l1"));
    let qd3 = rx_about(3, sym("l1") + sym("l2"));
    let qd4 = DualQuat::rotation_about_point(&ey(), &t(4), &c4);
    let qd5 = DualQuat::rotation_about_point(&ez(), &t(5), &c4);
    let qd6 = DualQuat::rotation_about_point(&ey(), &t(6), &c4);
    let (s4, s5, s6) = (sin(&half(&t(4))), sin(&half(&t(5))), sin(&half(&t(6))));
    // As printed: q_d4 = (C4, 0, S4, 0) + eps (0; 0, 0, d S4), q_d6 likewise.
    assert_eq!(qd4.dual, quat(int(0), int(0), int(0), &d * &s4));
    assert_eq!(qd6.dual, quat(int(0), int(0), int(0), &d * &s6));
    // ERRATA 9: q_d5 = (C5, 0, 0, S5) + eps (0; L S5, -d S5, 0), since m = (d, L, 0) x k = (L, -d, 0).
    assert_eq!(qd5.dual, quat(int(0), &big_l * &s5, -(&d * &s5), int(0)));
    let printed5 = DualQuat::from_real_and_dual(
        qd5.real.clone(),
        quat(int(0), &big_l * &s5, int(0), -(&d * &s5)),
    );
    let uc = printed5.unit_constraints();
    assert!(!uc.hold_exactly(), "the printed q_d5 is not a unit DQ");
    let wrist = qd4.clone() * qd5.clone() * qd6.clone();
    assert_eq!(
        wrist.transform_point(&c4),
        c4,
        "C4 is fixed by the last three joints"
    );
    let whole = qd1.clone() * qd2.clone() * qd3.clone() * wrist.clone();
    let centre = whole.transform_point(&c4);
    let oa = whole.transform_point(&v3(d.clone(), big_l.clone(), sym("a")));
    let mut r = Report::new("sec 6.4: Puma-like robot; q_d2, q_d3 as in sec 6.3; C4 = (d, L, 0)");
    r.dq("q_d1", &qd1).dq("q_d4", &qd4);
    r.note("ERRATA 9: q_d5 corrected; the printed (C5,0,0,S5) + eps (L S5, 0, -d S5) is not unit");
    r.dq("q_d5", &qd5).dq("q_d6", &qd6);
    r.vector("q_d4 q_d5 q_d6 C4", &wrist.transform_point(&c4));
    r.vector("wrist centre Q C4", &centre);
    r.vector("point A = Q (d, L, a)", &oa);
    snap("sec6_4_puma_like", &r);
    let pts = [centre, oa].concat();
    check_numeric(
        &[
            "theta1", "theta2", "theta3", "theta4", "theta5", "theta6", "l1", "l2", "d", "L", "a",
        ],
        &pts,
        |e| {
            let (a, b, dd, ll) = (get(e, "l1"), get(e, "l2"), get(e, "d"), get(e, "L"));
            let c = [dd, ll, 0.0];
            let m = Matrix4::rot_z(&get(e, "theta1"))
                * mat_rot_about('x', get(e, "theta2"), [0.0, a, 0.0])
                * mat_rot_about('x', get(e, "theta3"), [0.0, a + b, 0.0])
                * mat_rot_about('y', get(e, "theta4"), c)
                * mat_rot_about('z', get(e, "theta5"), c)
                * mat_rot_about('y', get(e, "theta6"), c);
            [
                m.transform_point(&c),
                m.transform_point(&[dd, ll, get(e, "a")]),
            ]
            .concat()
        },
    );
}

/// PUMA 560 in standard DH: alpha = (pi/2, 0, -pi/2, pi/2, -pi/2, 0), a2 a3 d3 d4 symbolic.
pub fn puma560() -> (DualQuat<S>, Vec<[S; 4]>) {
    let alpha = [
        frac(1, 2),
        int(0),
        frac(-1, 2),
        frac(1, 2),
        frac(-1, 2),
        int(0),
    ];
    let a = [int(0), sym("a2"), sym("a3"), int(0), int(0), int(0)];
    let d = [int(0), int(0), sym("d3"), sym("d4"), int(0), int(0)];
    let mut q = DualQuat::identity();
    for i in 0..6 {
        q = q * dh_link(&t(i + 1), &d[i], &a[i], &(S::pi() * &alpha[i]));
    }
    let params = (0..6)
        .map(|i| [t(i + 1), d[i].clone(), a[i].clone(), alpha[i].clone()])
        .collect();
    (q, params)
}

#[test]
fn puma560_pose_in_c23_groupings_below_315_operations() {
    let (q, _) = puma560();
    let m = q.to_matrix();
    let mut r = Report::new(
        "PUMA 560 (standard DH, Craig's parameters a2 a3 d3 d4): pose as a 4x4 matrix and as a DQ",
    );
    let mut ops = 0;
    for i in 0..3 {
        for j in 0..4 {
            let e = closed(&m.rows[i][j]);
            ops += e.cost().ops;
            r.value(&format!("T[{i}][{j}]"), &m.rows[i][j]);
        }
    }
    for (k, c) in q.components().iter().enumerate() {
        r.value(&format!("dq[{k}]"), c);
    }
    snap("puma560_pose", &r);
    assert!(ops <= 250, "PUMA 560 matrix: {ops} operations");
    let text = r.text();
    let matrix_part = text.split("dq[0]").next().unwrap_or_default();
    assert!(!matrix_part.contains("/2"), "no half angles in the matrix");
    assert!(matrix_part.contains("c23") && matrix_part.contains("s23"));
    let flat: Vec<S> = m.rows.iter().take(3).flat_map(|r| r.to_vec()).collect();
    let names = [
        "theta1", "theta2", "theta3", "theta4", "theta5", "theta6", "a2", "a3", "d3", "d4",
    ];
    check_numeric(&names, &flat, |e| {
        let al = [0.5, 0.0, -0.5, 0.5, -0.5, 0.0];
        let a = [0.0, get(e, "a2"), get(e, "a3"), 0.0, 0.0, 0.0];
        let d = [0.0, 0.0, get(e, "d3"), get(e, "d4"), 0.0, 0.0];
        let mut m = Matrix4::identity();
        for i in 0..6 {
            let th = get(e, &format!("theta{}", i + 1));
            m = m * dh_link_matrix(&th, &d[i], &a[i], &(std::f64::consts::PI * al[i]));
        }
        m.rows.iter().take(3).flat_map(|r| r.to_vec()).collect()
    });
}
