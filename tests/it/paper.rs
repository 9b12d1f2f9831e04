//! Every result of the paper (with ERRATA.md), exact, as a snapshot, and checked numerically
//! against 4x4 homogeneous matrices built without the DQ code.
#![allow(clippy::needless_range_loop)] // Matrix entries read best as (i, j).

use crate::paper_support::*;
use dqsym::{DualQuat, Matrix4, Quat};

fn th() -> S {
    sym("theta")
}

#[test]
fn sec2_2_translation_adds_t_to_v() {
    let t = v3(sym("tx"), sym("ty"), sym("tz"));
    let v = v3(sym("vx"), sym("vy"), sym("vz"));
    let qt = DualQuat::translation(&t);
    // "fortunately, using def (9), conj(q_T) = q_T": the combined conjugate of 1 + eps t/2.
    assert_eq!(qt.combined_conjugate(), qt);
    let img = qt.clone() * DualQuat::point(&v) * qt.combined_conjugate();
    let mut r = Report::new("sec 2-2: q_T (1 + eps v) q_T with q_T = 1 + eps t/2");
    r.dq("q_T", &qt).dq("q_v'", &img);
    snap("sec2_2_translation", &r);
    let p = img.dual.vector_part();
    check_numeric(&["tx", "ty", "tz", "vx", "vy", "vz"], &p, |e| {
        let m = Matrix4::trans(&[get(e, "tx"), get(e, "ty"), get(e, "tz")]);
        m.transform_point(&[get(e, "vx"), get(e, "vy"), get(e, "vz")])
            .to_vec()
    });
}

#[test]
fn eq1_eq9_eq10_products_and_conjugates() {
    let p = quat(sym("s1"), sym("x1"), sym("y1"), sym("z1"));
    let q = quat(sym("s2"), sym("x2"), sym("y2"), sym("z2"));
    let pq = p.clone() * q.clone();
    let general = DualQuat::from_real_and_dual(
        quat(sym("s"), sym("x"), sym("y"), sym("z")),
        quat(sym("se"), sym("xe"), sym("ye"), sym("ze")),
    );
    let mut r = Report::new(
        "eq 1: quaternion product; eq 9: combined conjugate; eq 10: rotation of a point",
    );
    r.vector("q1 q2", &pq.components());
    r.dq(
        "combined conjugate of (s,x,y,z)+eps(se,xe,ye,ze)",
        &general.combined_conjugate(),
    );
    let qr = DualQuat::rotation(&ez(), &th());
    r.vector(
        "R_z(theta) (1 + eps v) conj(R_z)",
        &qr.transform_point(&v3(sym("vx"), sym("vy"), sym("vz"))),
    );
    snap("eq1_eq9_eq10", &r);
    let c = general.combined_conjugate().components();
    let want = [
        sym("s"),
        -sym("x"),
        -sym("y"),
        -sym("z"),
        -sym("se"),
        sym("xe"),
        sym("ye"),
        sym("ze"),
    ];
    assert_eq!(c, want);
    let img = qr.transform_point(&v3(sym("vx"), sym("vy"), sym("vz")));
    check_numeric(&["theta", "vx", "vy", "vz"], &img, |e| {
        Matrix4::rot_z(&get(e, "theta"))
            .transform_point(&[get(e, "vx"), get(e, "vy"), get(e, "vz")])
            .to_vec()
    });
}

#[test]
fn eq11_composition_applies_inner_transformation_first() {
    // p: rotation of theta1 about the x-parallel axis through (0, y1, z1); q: translation d.
    let p =
        DualQuat::rotation_about_point(&ex(), &sym("theta1"), &v3(int(0), sym("y1"), sym("z1")));
    let q = DualQuat::translation(&v3(sym("d1"), sym("d2"), sym("d3")));
    let v = v3(sym("vx"), sym("vy"), sym("vz"));
    let both = (p.clone() * q.clone()).transform_point(&v);
    let seq = p.transform_point(&q.transform_point(&v));
    assert_eq!(both, seq);
    let mut r = Report::new("eq 11: (p q) v conj(p q) = p (q v conj(q)) conj(p); q = translation d, p = rotation about an x-parallel axis through (0, y1, z1)");
    r.vector("v'", &both);
    snap("eq11_composition", &r);
    check_numeric(
        &["theta1", "y1", "z1", "d1", "d2", "d3", "vx", "vy", "vz"],
        &both,
        |e| {
            let m = mat_rot_about('x', get(e, "theta1"), [0.0, get(e, "y1"), get(e, "z1")])
                * Matrix4::trans(&[get(e, "d1"), get(e, "d2"), get(e, "d3")]);
            m.transform_point(&[get(e, "vx"), get(e, "vy"), get(e, "vz")])
                .to_vec()
        },
    );
}

#[test]
fn eq12_12a_12b_and_their_inverses() {
    // ERRATA item 1: the unit translation is 1 + eps t/2 (sec 2-3 prints 1 + eps t).
    let rq = Quat::rotation(&ez(), &th());
    let r = DualQuat::from_real(rq.clone());
    let t = v3(sym("tx"), sym("ty"), sym("tz"));
    let tq = Quat::from_vector(&t);
    let qt = DualQuat::translation(&t);
    let a = qt.clone() * r.clone(); // eq 12 / 12A: rotation first, then translation
    let b = r.clone() * qt.clone(); // eq 12B: translation first
    let half_s = frac(1, 2);
    assert_eq!(
        a,
        DualQuat::from_real_and_dual(rq.clone(), (tq.clone() * rq.clone()).scale(&half_s))
    );
    assert_eq!(
        b,
        DualQuat::from_real_and_dual(rq.clone(), (rq.clone() * tq.clone()).scale(&half_s))
    );
    // Inverses as printed: R* - eps R* T / 2 and R* - eps T R* / 2.
    let inv_a = DualQuat::from_real_and_dual(
        rq.conjugate(),
        -(rq.conjugate() * tq.clone()).scale(&half_s),
    );
    let inv_b = DualQuat::from_real_and_dual(
        rq.conjugate(),
        -(tq.clone() * rq.conjugate()).scale(&half_s),
    );
    assert_eq!(a.try_inverse().expect("unit"), inv_a);
    assert_eq!(b.try_inverse().expect("unit"), inv_b);
    assert_eq!(a.clone() * inv_a.clone(), DualQuat::identity());
    // 2 q_eps q* recovers t (sec 2-3).
    assert_eq!(a.translation_part(), t);
    let mut rep = Report::new("eq 12, 12A (R + eps T R / 2), 12B (R + eps R T / 2) and inverses, R = R_z(theta); ERRATA 1: q_T = 1 + eps t/2");
    rep.dq("12A", &a)
        .dq("12A inverse", &inv_a)
        .dq("12B", &b)
        .dq("12B inverse", &inv_b);
    snap("eq12_12a_12b", &rep);
    let m = a.to_matrix();
    let flat: Vec<S> = m
        .rows
        .iter()
        .take(3)
        .flat_map(|r| r.iter().cloned())
        .collect();
    check_numeric(&["theta", "tx", "ty", "tz"], &flat, |e| {
        let m = Matrix4::trans(&[get(e, "tx"), get(e, "ty"), get(e, "tz")])
            * Matrix4::rot_z(&get(e, "theta"));
        m.rows
            .iter()
            .take(3)
            .flat_map(|r| r.iter().cloned())
            .collect()
    });
}

#[test]
fn sec3a_rotation_matrix_with_sqrt2_sqrt3_sqrt6_as_printed() {
    let h = half(&th());
    let (c, s) = (cos(&h), sin(&h));
    let q = DualQuat::from_real(quat(
        c,
        int(6).sqrt() * frac(1, 4) * &s,
        int(2).sqrt() * frac(1, 4) * &s,
        int(2).sqrt() * frac(1, 2) * &s,
    ));
    let m = q.to_matrix();
    let (ct, st) = (cos(&th()), sin(&th()));
    let one_c = int(1) - &ct;
    let (r2, r3, r6) = (int(2).sqrt(), int(3).sqrt(), int(6).sqrt());
    let printed = [
        [
            frac(3, 8) + frac(5, 8) * &ct,
            &r3 * &one_c * frac(1, 8) - &r2 * &st * frac(1, 2),
            &r3 * &one_c * frac(1, 4) + &r2 * &st * frac(1, 4),
        ],
        [
            &r3 * &one_c * frac(1, 8) + &r2 * &st * frac(1, 2),
            frac(1, 8) + frac(7, 8) * &ct,
            &one_c * frac(1, 4) - &r6 * &st * frac(1, 4),
        ],
        [
            &r3 * &one_c * frac(1, 4) - &r2 * &st * frac(1, 4),
            &one_c * frac(1, 4) + &r6 * &st * frac(1, 4),
            frac(1, 2) + &ct * frac(1, 2),
        ],
    ];
    for i in 0..3 {
        for j in 0..3 {
            assert_eq!(m.rows[i][j], printed[i][j], "[R] entry ({i}, {j})");
        }
        assert_eq!(m.rows[i][3], int(0));
    }
    let mut r = Report::explicit(
        "sec 3-A: [R] of the rotation (cos(theta/2), sqrt(6)/4 s, sqrt(2)/4 s, sqrt(2)/2 s)",
    );
    r.matrix3("[R]", &m);
    snap("sec3a_rotation_matrix", &r);
    let flat: Vec<S> = m
        .rows
        .iter()
        .take(3)
        .flat_map(|r| r[..3].to_vec())
        .collect();
    check_numeric(&["theta"], &flat, |e| {
        let n = [6f64.sqrt() / 4.0, 2f64.sqrt() / 4.0, 2f64.sqrt() / 2.0];
        let m = Matrix4::rotation(&n, &get(e, "theta"));
        m.rows
            .iter()
            .take(3)
            .flat_map(|r| r[..3].to_vec())
            .collect()
    });
}

#[test]
fn sec3b_planar_displacements_eq13_14_15_b1_b2_b3() {
    let t = v3(int(0), sym("d1"), sym("d2"));
    let r = DualQuat::rotation(&ex(), &th());
    let qt = DualQuat::translation(&t);
    let v = v3(int(0), sym("l"), int(0));
    let q1 = qt.clone() * r.clone(); // eq 13: rotate, then translate
    let q2 = r.clone() * qt.clone(); // eq 14: translate, then rotate
    let p = v3(int(0), sym("y"), sym("z"));
    let q3 = DualQuat::rotation_about_point(&ex(), &th(), &p); // eq 15
    let h = half(&th());
    let (c, s) = (cos(&h), sin(&h));
    // Eq 13 and 14 as printed, in the eps/2 convention: dual = (1/2)(0; 0, ...).
    let d13 = quat(
        int(0),
        int(0),
        &c * sym("d1") + &s * sym("d2"),
        &c * sym("d2") - &s * sym("d1"),
    )
    .scale(&frac(1, 2));
    let d14 = quat(
        int(0),
        int(0),
        &c * sym("d1") - &s * sym("d2"),
        &c * sym("d2") + &s * sym("d1"),
    )
    .scale(&frac(1, 2));
    assert_eq!(q1.dual, d13);
    assert_eq!(q2.dual, d14);
    // Eq 15: (c, s, 0, 0) + eps (0, 0, z s, -y s).
    assert_eq!(
        q3.dual,
        quat(int(0), int(0), sym("z") * &s, -(sym("y") * &s))
    );
    // ERRATA 4: the inverse of q3 is R* + (eps/2)(d R* - R* d), not R^T + (eps/2)(R^T d - d R^T).
    let dq = Quat::from_vector(&p);
    let rs = r.real.conjugate();
    let inv3 = DualQuat::from_real_and_dual(
        rs.clone(),
        (dq.clone() * rs.clone() - rs.clone() * dq.clone()).scale(&frac(1, 2)),
    );
    assert_eq!(q3.try_inverse().expect("unit"), inv3);
    let b1 = q1.transform_point(&v);
    let b2 = q2.transform_point(&v);
    let b3 = q3.transform_point(&v);
    let (ct, st) = (cos(&th()), sin(&th()));
    assert_eq!(
        b1,
        [
            int(0),
            sym("d1") + sym("l") * &ct,
            sym("d2") + sym("l") * &st
        ]
    );
    // ERRATA 3: (b2) prints a spurious factor 1/2 in front; the 4x4 check printed beside it is right.
    assert_eq!(
        b2,
        [
            int(0),
            sym("d1") * &ct + sym("l") * &ct - sym("d2") * &st,
            sym("d1") * &st + sym("l") * &st + sym("d2") * &ct
        ]
    );
    let mut rep = Report::new("sec 3-B: planar displacements about the x axis (c, s = cos, sin of theta/2 in the factors)");
    rep.dq("eq 13 q1 = (1 + eps t/2) R", &q1)
        .vector("(b1) v'", &b1);
    rep.dq("eq 14 q2 = R (1 + eps t/2)", &q2);
    rep.note("(b2) corrected (ERRATA 3): the paper prints 1 + (eps/2)(...) with the same entries; the factor 1/2 is spurious");
    rep.vector("(b2) v'", &b2);
    rep.dq("eq 15 q3 = rotation about C = (0, y, z)", &q3)
        .vector("(b3) v'", &b3);
    rep.note(
        "ERRATA 4: inverse of q3 is R* + (eps/2)(d R* - R* d) (the paper prints the opposite sign)",
    );
    rep.dq("q3 inverse", &inv3);
    // The planar image-space coordinates q5..q8 = 2 q_eps (the eps/2 convention of the list).
    rep.vector(
        "example 1 (q7, q8)",
        &[q1.dual.y.clone() * int(2), q1.dual.z.clone() * int(2)],
    );
    rep.vector(
        "example 2 (q7, q8)",
        &[q2.dual.y.clone() * int(2), q2.dual.z.clone() * int(2)],
    );
    rep.vector(
        "example 3 (q7, q8)",
        &[q3.dual.y.clone() * int(2), q3.dual.z.clone() * int(2)],
    );
    snap("sec3b_planar", &rep);
    let all: Vec<S> = [b1, b2, b3].concat();
    check_numeric(&["theta", "d1", "d2", "l", "y", "z"], &all, |e| {
        let (t, d1, d2, l) = (get(e, "theta"), get(e, "d1"), get(e, "d2"), get(e, "l"));
        let m1 = Matrix4::trans(&[0.0, d1, d2]) * Matrix4::rot_x(&t);
        let m2 = Matrix4::rot_x(&t) * Matrix4::trans(&[0.0, d1, d2]);
        let m3 = mat_rot_about('x', t, [0.0, get(e, "y"), get(e, "z")]);
        let v = [0.0, l, 0.0];
        [
            m1.transform_point(&v),
            m2.transform_point(&v),
            m3.transform_point(&v),
        ]
        .concat()
    });
}

/// `a x b`.
fn cross(a: &[S; 3], b: &[S; 3]) -> [S; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

#[test]
fn sec4_centres_c1_c2_and_moments_m1_m2() {
    let t = v3(int(0), sym("d1"), sym("d2"));
    let r = DualQuat::rotation(&ex(), &th());
    let qt = DualQuat::translation(&t);
    let q1 = qt.clone() * r.clone();
    let q2 = r * qt;
    let h = half(&th());
    let (c, s) = (cos(&h), sin(&h));
    let (d1, d2) = (sym("d1"), sym("d2"));
    // sin(theta/2) C, from the printed C1 = (0, d1/2 - d2/2 c/s, d1/2 c/s + d2/2) and C2.
    let sc1 = [
        int(0),
        (&d1 * &s - &d2 * &c) * frac(1, 2),
        (&d1 * &c + &d2 * &s) * frac(1, 2),
    ];
    let sc2 = [
        int(0),
        -(&d1 * &s + &d2 * &c) * frac(1, 2),
        (&d1 * &c - &d2 * &s) * frac(1, 2),
    ];
    // C is fixed: R C + t = C, i.e. (times s) image(sC) - sC = (1 - s) t, with image(v) = R v + t.
    for (q, sc) in [(&q1, &sc1), (&q2, &sc2)] {
        let img = q.transform_point(sc);
        let tt = q.translation_part();
        for k in 0..3 {
            assert_eq!(
                &img[k] - &sc[k],
                (int(1) - &s) * &tt[k],
                "centre component {k}"
            );
        }
        // m sin(theta/2) = (sC x i) is exactly the dual part's vector of the planar DQ.
        let sm = cross(sc, &ex());
        assert_eq!(sm.to_vec(), q.dual.vector_part().to_vec());
    }
    let mut rep =
        Report::new("sec 4: centres and moments; C = (sin(theta/2) C) / sin(theta/2), m = OC x i");
    rep.vector("sin(theta/2) C1", &sc1)
        .vector("sin(theta/2) m1", &cross(&sc1, &ex()));
    rep.vector("sin(theta/2) C2", &sc2)
        .vector("sin(theta/2) m2", &cross(&sc2, &ex()));
    rep.note(
        "sin(theta/2) m equals the vector of the dual part of q1 (resp. q2), as the paper states",
    );
    snap("sec4_centres_moments", &rep);
    // Numerically: C1 is the fixed point of the matrix [M1] = T(d) R (theta != 0).
    for env in points(&["theta", "d1", "d2"], 8) {
        let (tv, a, b) = (get(&env, "theta"), get(&env, "d1"), get(&env, "d2"));
        let cot = (tv / 2.0).cos() / (tv / 2.0).sin();
        let c1 = [0.0, a / 2.0 - b / 2.0 * cot, a / 2.0 * cot + b / 2.0];
        let m1 = Matrix4::trans(&[0.0, a, b]) * Matrix4::rot_x(&tv);
        let img = m1.transform_point(&c1);
        for k in 0..3 {
            assert!(close(img[k], c1[k]), "C1 fixed by M1");
        }
        let c2 = [0.0, -a / 2.0 - b / 2.0 * cot, a / 2.0 * cot - b / 2.0];
        let m2 = Matrix4::rot_x(&tv) * Matrix4::trans(&[0.0, a, b]);
        let img = m2.transform_point(&c2);
        for k in 0..3 {
            assert!(close(img[k], c2[k]), "C2 fixed by M2");
        }
    }
}

#[test]
fn eq16_screw_and_corrected_eq18() {
    let n = v3(sym("nx"), sym("ny"), sym("nz"));
    let t = sym("t");
    let h = half(&th());
    let (c, s) = (cos(&h), sin(&h));
    // Corrected eq 18 (ERRATA 6): (c, s n) + (eps/2)(-s t, c t n + 2 s m), m = OC x n.
    let p = v3(sym("px"), sym("py"), sym("pz"));
    let tn = [&n[0] * &t, &n[1] * &t, &n[2] * &t];
    let m = cross(&p, &n);
    let d18 = quat(
        -(&s * &t),
        &c * &tn[0] + int(2) * &s * &m[0],
        &c * &tn[1] + int(2) * &s * &m[1],
        &c * &tn[2] + int(2) * &s * &m[2],
    )
    .scale(&frac(1, 2));
    let mut rep = Report::new("eq 16: screw (c, s n)(1 + (eps/2) t n), axis n through O; eq 18 corrected (ERRATA 6): axis through C, m = OC x n");
    rep.dq(
        "eq 16 S (axis z)",
        &(DualQuat::rotation(&ez(), &th()) * DualQuat::translation(&v3(int(0), int(0), t.clone()))),
    );
    rep.note("eq 18 as printed lacks the factor 2 on s m; corrected: (c, s n) + (eps/2)(-s t, c t n + 2 s m)");
    rep.vector("eq 18 dual (general n, C)", &d18.components());
    snap("eq16_eq18_screw", &rep);
    // With a unit axis, the screw constructor equals the corrected eq 18 exactly.
    let unit_axes = [
        ex(),
        ey(),
        ez(),
        [frac(3, 5), frac(4, 5), int(0)],
        [frac(2, 3), frac(1, 3), frac(2, 3)],
    ];
    for axis in unit_axes {
        let tn = [&axis[0] * &t, &axis[1] * &t, &axis[2] * &t];
        let m = cross(&p, &axis);
        let sc = DualQuat::screw(&axis, &p, &th(), &t);
        let d18 = quat(
            -(&s * &t),
            &c * &tn[0] + int(2) * &s * &m[0],
            &c * &tn[1] + int(2) * &s * &m[1],
            &c * &tn[2] + int(2) * &s * &m[2],
        )
        .scale(&frac(1, 2));
        assert_eq!(sc.dual, d18, "corrected eq 18 for axis {axis:?}");
        let s16 = DualQuat::rotation(&axis, &th()) * DualQuat::translation(&tn);
        assert_eq!(
            s16.dual,
            quat(-(&s * &t), &c * &tn[0], &c * &tn[1], &c * &tn[2]).scale(&frac(1, 2)),
            "eq 16"
        );
        let img = sc.transform_point(&v3(sym("vx"), sym("vy"), sym("vz")));
        let a = [
            axis[0].to_f64_value(),
            axis[1].to_f64_value(),
            axis[2].to_f64_value(),
        ];
        check_numeric(
            &["theta", "t", "px", "py", "pz", "vx", "vy", "vz"],
            &img,
            |e| {
                let p = [get(e, "px"), get(e, "py"), get(e, "pz")];
                let tt = get(e, "t");
                let m = Matrix4::trans(&[a[0] * tt, a[1] * tt, a[2] * tt])
                    * Matrix4::trans(&p)
                    * Matrix4::rotation(&a, &get(e, "theta"))
                    * Matrix4::trans(&[-p[0], -p[1], -p[2]]);
                m.transform_point(&[get(e, "vx"), get(e, "vy"), get(e, "vz")])
                    .to_vec()
            },
        );
    }
}

trait F64Value {
    fn to_f64_value(&self) -> f64;
}
impl F64Value for S {
    fn to_f64_value(&self) -> f64 {
        self.eval(&|_| None).expect("a number")
    }
}
