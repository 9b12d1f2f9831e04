//! Screw parameters, planar centres and Jacobians, exact and against finite differences.
#![allow(clippy::needless_range_loop)] // Components read best by index.

use crate::paper_support::*;
use dqsym::{
    kin::{dq_jacobian, geometric_jacobian, screw_parameters, ScrewError},
    plain, DualQuat, Frac, PlainOptions,
};

fn frac_text(f: &Frac) -> String {
    let o = PlainOptions::default();
    let num = plain(&closed(f.num()), &o);
    match f.as_scalar() {
        Some(_) => num,
        None => format!("({num}) / ({})", plain(&closed(f.den()), &o)),
    }
}

#[test]
fn screw_parameters_recover_axis_angle_slide_and_point() {
    let axes = [
        [int(1), int(0), int(0)],
        [frac(3, 5), int(0), frac(4, 5)],
        [frac(2, 3), frac(1, 3), frac(2, 3)],
    ];
    let p = v3(sym("px"), sym("py"), sym("pz"));
    for n in axes {
        let q = DualQuat::screw(&n, &p, &sym("theta"), &sym("t"));
        let sp = screw_parameters(&q).expect("a screw");
        assert_eq!(sp.angle, sym("theta"));
        for k in 0..3 {
            assert_eq!(sp.axis[k], Frac::from(n[k].clone()), "axis");
        }
        assert_eq!(sp.slide, Frac::from(sym("t")));
        // The nearest point is p minus its component along n.
        let pn = &p[0] * &n[0] + &p[1] * &n[1] + &p[2] * &n[2];
        for k in 0..3 {
            assert_eq!(sp.point[k], Frac::from(&p[k] - &pn * &n[k]), "point");
        }
    }
}

#[test]
fn sec4_centre_c1_from_the_screw_parameters() {
    let r = DualQuat::rotation(&ex(), &sym("theta"));
    let q1 = DualQuat::translation(&v3(int(0), sym("d1"), sym("d2"))) * r;
    let sp = screw_parameters(&q1).expect("planar");
    let h = half(&sym("theta"));
    let (c, s) = (cos(&h), sin(&h));
    let two_s = &s * int(2);
    // Printed: Y1 = d1/2 - d2/2 c/s, Z1 = d1/2 c/s + d2/2.
    let y1 = Frac::new(sym("d1") * &s - sym("d2") * &c, two_s.clone()).unwrap();
    let z1 = Frac::new(sym("d1") * &c + sym("d2") * &s, two_s.clone()).unwrap();
    assert_eq!(sp.point[0], Frac::from(int(0)));
    assert_eq!(sp.point[1], y1);
    assert_eq!(sp.point[2], z1);
    assert_eq!(sp.slide, Frac::from(int(0)));
    let text = format!(
        "sec 4 example 1: screw parameters of q1 = (1 + eps (0, d1, d2)/2) R_x(theta)\nangle = {}\naxis = ({})\nslide = {}\nC1 = ({})\nm1 = ({})\n",
        plain(&closed(&sp.angle), &PlainOptions::default()),
        sp.axis.iter().map(frac_text).collect::<Vec<_>>().join(", "),
        frac_text(&sp.slide),
        sp.point.iter().map(frac_text).collect::<Vec<_>>().join(", "),
        sp.moment.iter().map(frac_text).collect::<Vec<_>>().join(", "),
    );
    crate::common::snapshot_settings()
        .bind(|| insta::assert_snapshot!("sec4_screw_parameters", text));
    assert_eq!(
        screw_parameters(&DualQuat::translation(&v3(sym("a"), int(0), int(0)))),
        Err(ScrewError::PureTranslation)
    );
}

#[test]
fn jacobians_of_the_puma560_agree_with_finite_differences() {
    let (q, _) = crate::paper_arms::puma560();
    let vars = ["theta1", "theta2", "theta3", "theta4", "theta5", "theta6"];
    let j8 = dq_jacobian(&q, &vars);
    let jg = geometric_jacobian(&q, &vars);
    assert_eq!(j8.len(), 8);
    assert_eq!(jg.len(), 6);
    let names = [
        "theta1", "theta2", "theta3", "theta4", "theta5", "theta6", "a2", "a3", "d3", "d4",
    ];
    let comps = q.components();
    let m = q.to_matrix();
    for env in points(&names, 3) {
        let at = |shift: usize, h: f64| -> Vec<(String, f64)> {
            env.iter()
                .enumerate()
                .map(|(k, (n, v))| (n.clone(), if k == shift { v + h } else { *v }))
                .collect()
        };
        let h = 1e-6;
        for (j, _) in vars.iter().enumerate() {
            let (plus, minus) = (at(j, h), at(j, -h));
            for k in 0..8 {
                let fd = (ev(&comps[k], &plus) - ev(&comps[k], &minus)) / (2.0 * h);
                assert!(
                    (fd - ev(&j8[k][j], &env)).abs() < 1e-6,
                    "dq jacobian ({k}, {j})"
                );
            }
            // Linear part: derivative of the position column.
            for k in 0..3 {
                let fd = (ev(&m.rows[k][3], &plus) - ev(&m.rows[k][3], &minus)) / (2.0 * h);
                assert!((fd - ev(&jg[k][j], &env)).abs() < 1e-6, "linear ({k}, {j})");
            }
            // Angular part: omega^ = R' R^T; compare its (2,1), (0,2), (1,0) entries.
            let rot = |e: &[(String, f64)]| -> Vec<Vec<f64>> {
                (0..3)
                    .map(|a| (0..3).map(|b| ev(&m.rows[a][b], e)).collect())
                    .collect()
            };
            let (rp, rm, r0) = (rot(&plus), rot(&minus), rot(&env));
            let dr: Vec<Vec<f64>> = (0..3)
                .map(|a| (0..3).map(|b| (rp[a][b] - rm[a][b]) / (2.0 * h)).collect())
                .collect();
            let w = |a: usize, b: usize| (0..3).map(|k| dr[a][k] * r0[b][k]).sum::<f64>();
            let omega = [w(2, 1), w(0, 2), w(1, 0)];
            for k in 0..3 {
                assert!(
                    (omega[k] - ev(&jg[k + 3][j], &env)).abs() < 1e-6,
                    "angular ({k}, {j})"
                );
            }
        }
    }
}

#[test]
fn language_screwparams_and_gjacobian_match_the_library() {
    use std::process::Command;
    let run = |e: &str| {
        let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
            .args(["-e", e])
            .output()
            .expect("runs");
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).to_string(),
            String::from_utf8_lossy(&out.stderr).to_string(),
        )
    };
    let (code, text, _) = run("screwparams(screw((3/5, 4/5, 0), (l, d, 0), theta1, t))");
    assert_eq!(code, Some(0));
    // Moment p x n and nearest point p - (p.n) n of the axis through (l, d, 0).
    assert_eq!(text, "[theta1, t, 0]\n[3/5, 4/5, 0]\n[0, 0, 1/5 (-3 d + 4 l)]\n[4/25 (-3 d + 4 l), 3/25 (3 d - 4 l), 0]\n");
    let q = DualQuat::screw(
        &[frac(3, 5), frac(4, 5), int(0)],
        &v3(sym("l"), sym("d"), int(0)),
        &sym("theta1"),
        &sym("t"),
    );
    let sp = screw_parameters(&q).expect("screw");
    assert_eq!(
        sp.moment[2],
        Frac::from((sym("l") * int(4) - sym("d") * int(3)) * frac(1, 5))
    );
    // A planar centre divides by sin(theta/2): the matrix holds the quotients (tests/it/quotients.rs).
    let (code, text, _) = run("screwparams(trans((0, d1, d2)) * rot((1, 0, 0), theta))");
    assert_eq!(code, Some(0));
    assert!(
        text.contains("(d1 sin(theta/2) - d2 cos(theta/2))/(2 sin(theta/2))"),
        "{text}"
    );
    let (code, text, _) = run("gjacobian(rot((0, 0, 1), theta1) * trans((l, 0, 0)), [theta1])");
    assert_eq!(code, Some(0));
    assert_eq!(
        text,
        "[-l s1]\n[l c1]\n[0]\n[0]\n[0]\n[1]\n  where c1 = cos(theta1), s1 = sin(theta1)\n"
    );
}
