//! Robot files written the way datasheets print them (tests/data/hostile/robot/datasheet_*):
//! angles as decimals (1.5708, 3.14159, 1.571, -0.7854), degrees as bare numbers. The hostile
//! corpus snapshots what `dqsym fk` says of each; here every file that reads is checked
//! against plain 4x4 matrices built in this file with the angles the rule reads (pi/2 for
//! 1.5708, 1.57 for 1.57), at random configurations.

use crate::common::Rng;
use crate::mat4::{mul, rot, trans, M, X, Y, Z};
use dqsym::{eval_scalar_text, kin::RobotOptions, Robot};
use std::f64::consts::PI;

/// Classic DH: `Rz(theta) Tz(d) Tx(a) Rx(alpha)`.
fn dh(theta: f64, d: f64, a: f64, alpha: f64) -> M {
    let m = mul(&rot(Z, theta), &trans([0.0, 0.0, d]));
    mul(&mul(&m, &trans([a, 0.0, 0.0])), &rot(X, alpha))
}

/// Modified DH: `Rx(alpha) Tx(a) Rz(theta) Tz(d)`.
fn mdh(alpha: f64, a: f64, theta: f64, d: f64) -> M {
    let m = mul(&rot(X, alpha), &trans([a, 0.0, 0.0]));
    mul(&mul(&m, &rot(Z, theta)), &trans([0.0, 0.0, d]))
}

/// The URDF-style frame `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)`.
fn frame(xyz: [f64; 3], rpy: [f64; 3]) -> M {
    let r = mul(&rot(Z, rpy[2]), &mul(&rot(Y, rpy[1]), &rot(X, rpy[0])));
    mul(&trans(xyz), &r)
}

/// A turn by `t` about the axis through `p` with direction `u`.
fn screw(u: [f64; 3], p: [f64; 3], t: f64) -> M {
    let m = mul(&trans(p), &rot(u, t));
    mul(&m, &trans([-p[0], -p[1], -p[2]]))
}

fn chain(ms: &[M]) -> M {
    ms.iter()
        .fold(trans([0.0, 0.0, 0.0]), |acc, m| mul(&acc, m))
}

/// The first three rows of `m` at `env` against `want`, entry by entry.
fn assert_close(m: &dqsym::Matrix4<dqsym::Scalar>, env: &[(&str, f64)], want: &M, what: &str) {
    for (i, (row, wrow)) in m.rows.iter().zip(want).take(3).enumerate() {
        for (j, (x, w)) in row.iter().zip(wrow).enumerate() {
            let got = x.eval_at(env).expect("numeric entry");
            assert!(
                (got - w).abs() < 1e-12,
                "{what}: T[{i}][{j}] = {got}, expected {w} at {env:?}"
            );
        }
    }
}

fn read(file: &str, o: &RobotOptions) -> Robot {
    let path = format!(
        "{}/tests/data/hostile/robot/{file}",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("datasheet file");
    dqsym::kin::parse_robot_with(&text, file, &eval_scalar_text, o)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The robot's exact pose matrix against `oracle` at random configurations.
fn check(file: &str, oracle: &dyn Fn(&[f64]) -> M) -> Robot {
    let r = read(file, &RobotOptions::default());
    let m = r.forward_matrix();
    let mut rng = Rng::new(file.len() as u64 * 7919);
    for _ in 0..5 {
        let q: Vec<f64> = r.variables.iter().map(|_| rng.range(-PI, PI)).collect();
        let env: Vec<(&str, f64)> = r
            .variables
            .iter()
            .map(String::as_str)
            .zip(q.iter().copied())
            .collect();
        assert_close(&m, &env, &oracle(&q), file);
    }
    r
}

#[test]
fn ur5e_from_its_datasheet_reads_alpha_1_5708_as_pi_over_2() {
    let r = check("datasheet_ur5e.toml", &|q| {
        chain(&[
            dh(q[0], 0.1625, 0.0, PI / 2.0),
            dh(q[1], 0.0, -0.425, 0.0),
            dh(q[2], 0.0, -0.3922, 0.0),
            dh(q[3], 0.1333, 0.0, PI / 2.0),
            dh(q[4], 0.0997, 0.0, -PI / 2.0),
            dh(q[5], 0.0996, 0.0, 0.0),
        ])
    });
    assert_eq!(r.notes.len(), 3, "{:?}", r.notes);
    assert!(!r.decimals.is_empty());
    // Exact: no constant angle is left in the pose (1.5708 would leave cos(3927/2500)).
    assert!(r.parameters().is_empty());
    let t = dqsym::fk_report(&r, &dqsym::FkOptions::default()).expect("report");
    assert!(!t.contains("3927"), "{t}");
}

#[test]
fn a_base_yaw_of_3_14159_is_a_half_turn_and_tool_angles_snap() {
    check("datasheet_base_yaw.toml", &|q| {
        chain(&[
            frame([0.0, 0.0, 0.1], [0.0, 0.0, PI]),
            dh(q[0], 0.2, 0.3, -PI / 2.0),
            dh(q[1], 0.0, 0.25, 0.0),
            frame([0.0, 0.0, 0.05], [PI / 2.0, 0.0, -PI / 4.0]),
        ])
    });
}

#[test]
fn decimal_offsets_inside_theta_snap_and_the_prismatic_offset_stays() {
    check("datasheet_theta_offsets.toml", &|q| {
        chain(&[
            dh(q[0] - PI / 2.0, 0.4, 0.05, PI / 4.0),
            dh(q[1] + PI, 0.0, 0.3, 0.0),
            dh(-PI / 2.0, q[2] + 0.1, 0.0, 0.0),
        ])
    });
}

#[test]
fn modified_dh_datasheet_angles_snap() {
    check("datasheet_mdh.toml", &|q| {
        chain(&[
            mdh(0.0, 0.0, q[0], 0.333),
            mdh(-PI / 2.0, 0.0, q[1], 0.0),
            mdh(PI / 2.0, 0.0, q[2], 0.316),
            mdh(PI / 2.0, 0.0825, q[3], 0.0),
        ])
    });
}

#[test]
fn two_decimal_angles_stay_as_written() {
    let r = check("datasheet_short_decimals.toml", &|q| {
        chain(&[dh(q[0], 0.1, 0.0, 1.57), dh(q[1], 0.0, 0.2, 0.3)])
    });
    assert!(r.notes[0].contains("pi/2"), "{:?}", r.notes);
}

/// Angles kept as typed decimals (1.57, 0.3) print as decimals inside the sines and cosines
/// too (`cos(0.935)`, not `cos(187/200)`), in plain text and LaTeX,
/// and the text reads back to the exact pose; the LaTeX renders in KaTeX.
#[test]
fn angles_typed_as_decimals_print_as_decimals_in_every_entry() {
    use dqsym::{fk_report, FkOptions, Format};
    let r = read("datasheet_short_decimals.toml", &RobotOptions::default());
    let report = |format, shorthand| {
        let o = FkOptions {
            format,
            shorthand,
            ..FkOptions::default()
        };
        fk_report(&r, &o).expect("report")
    };
    let explicit = report(Format::Plain, false);
    // (1.57 - 0.3)/2 = 0.635 and (1.57 + 0.3)/2 = 0.935: decimals, never 127/200, 187/200.
    assert!(explicit.contains("cos(0.935)"), "{explicit}");
    for fraction in ["/200", "/100", "/20)", "/10)"] {
        assert!(!explicit.contains(fraction), "{fraction} in\n{explicit}");
    }
    let q = r.forward();
    let m = r.forward_matrix();
    let mut read_back = 0;
    for line in explicit.lines() {
        let Some((name, expr)) = line.split_once(" = ") else {
            continue;
        };
        let want = if let Some(k) = name.strip_prefix("dq[") {
            let k: usize = k.trim_end_matches(']').parse().expect("k");
            q.components()[k].clone()
        } else if name.starts_with("T[") {
            let b = name.as_bytes();
            m.rows[(b[2] - b'0') as usize][(b[5] - b'0') as usize].clone()
        } else {
            continue;
        };
        let back = eval_scalar_text(expr).expect("the text reads back");
        assert_eq!(back, want, "{name}: {expr}");
        read_back += 1;
    }
    assert_eq!(read_back, 20);
    let tex = report(Format::Latex, true);
    assert!(tex.contains("(0.935)") && !tex.contains("{200}"), "{tex}");
    let blocks: Vec<String> = tex
        .split("\\begin{aligned}")
        .skip(1)
        .map(|b| {
            format!(
                "\\begin{{aligned}}{}\\end{{aligned}}",
                b.split("\\end{aligned}").next().unwrap_or_default()
            )
        })
        .collect();
    crate::tools::katex_all(&blocks, "datasheet_short_decimals.toml");
}

#[test]
fn a_coupled_screw_offset_of_0_5236_is_pi_over_6() {
    check("datasheet_screw_offset.toml", &|q| {
        chain(&[
            screw(Z, [0.0; 3], q[0]),
            screw(Y, [0.3, 0.0, 0.2], 2.0 * q[0] + PI / 6.0),
        ])
    });
}

#[test]
fn degrees_are_refused_with_the_deg_suggestion_and_exact_angles_keeps_them() {
    for (file, t) in [
        ("datasheet_degrees.toml", "90"),
        ("datasheet_degrees_in_theta.toml", "180"),
    ] {
        let path = format!(
            "{}/tests/data/hostile/robot/{file}",
            env!("CARGO_MANIFEST_DIR")
        );
        let text = std::fs::read_to_string(&path).expect("file");
        let e = dqsym::parse_robot(&text, file, &eval_scalar_text)
            .expect_err("degrees refused")
            .to_string();
        assert!(e.contains(&format!("\"{t}deg\"")), "{e}");
    }
    // Taken literally, alpha = 90 is 90 rad.
    let o = RobotOptions { exact_angles: true };
    let r = read("datasheet_degrees.toml", &o);
    assert!(r.notes.is_empty());
    let m = r.forward_matrix();
    let q = [0.3, -0.7, 1.1];
    let env = [("q1", q[0]), ("q2", q[1]), ("q3", q[2])];
    let want = chain(&[
        dh(q[0], 0.1625, 0.0, 90.0),
        dh(q[1], 0.0, -0.425, 0.0),
        dh(q[2], 0.0, -0.3922, -90.0),
    ]);
    assert_close(&m, &env, &want, "alpha in degrees");
    // The same file with "90deg" reads as the robot meant.
    let path = format!(
        "{}/tests/data/hostile/robot/datasheet_degrees.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path)
        .expect("file")
        .replace("alpha = 90", "alpha = \"90deg\"")
        .replace("alpha = -90", "alpha = \"-90deg\"");
    let r = dqsym::parse_robot(&text, "deg.toml", &eval_scalar_text).expect("reads");
    let m = r.forward_matrix();
    let want = chain(&[
        dh(q[0], 0.1625, 0.0, PI / 2.0),
        dh(q[1], 0.0, -0.425, 0.0),
        dh(q[2], 0.0, -0.3922, -PI / 2.0),
    ]);
    assert_close(&m, &env, &want, "alpha in degrees");
}

/// The UR5 example with its nominal lengths typed in as decimals, as a datasheet prints them.
fn ur5_with_decimals() -> String {
    let path = format!("{}/examples/robots/ur5.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).expect("ur5.toml");
    let text = text.split("[values]").next().expect("joints").to_owned();
    [
        ("\"d1\"", "0.089159"),
        ("\"a2\"", "-0.425"),
        ("\"a3\"", "-0.39225"),
        ("\"d4\"", "0.10915"),
        ("\"d5\"", "0.09465"),
        ("\"d6\"", "0.0823"),
    ]
    .iter()
    .fold(text, |t, (from, to)| t.replace(from, to))
}

#[test]
fn decimals_print_as_decimals_and_read_back_exactly() {
    use dqsym::{fk_report, FkOptions, Format};
    let ur5e_path = format!(
        "{}/tests/data/hostile/robot/datasheet_ur5e.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let ur5e = std::fs::read_to_string(ur5e_path).expect("ur5e");
    for (file, text, want) in [
        (
            "ur5e.toml",
            ur5e,
            "T[0][3] = c1 (-0.425 c2 - 0.3922 c23 - 0.0996 c234 s5 + 0.0997 s234) + s1 (0.1333 + 0.0996 c5)",
        ),
        (
            "ur5.toml",
            ur5_with_decimals(),
            "T[2][3] = 0.089159 - 0.425 s2 - 0.39225 s23 - 0.09465 c234 - 0.0823 s234 s5",
        ),
    ] {
        let r = dqsym::parse_robot(&text, file, &eval_scalar_text).expect("robot");
        assert!(!r.decimals.is_empty(), "{file}");
        let report = |format, shorthand| {
            let o = FkOptions {
                format,
                shorthand,
                ..FkOptions::default()
            };
            fk_report(&r, &o).expect("report")
        };
        let plain = report(Format::Plain, true);
        assert!(plain.lines().any(|l| l == want), "{file}:\n{plain}");
        assert!(!plain.contains("/10000") && !plain.contains("/20000"), "{plain}");
        // The explicit text reads back, through the language, to the exact pose.
        let explicit = report(Format::Plain, false);
        let m = r.forward_matrix();
        let mut read = 0;
        for line in explicit.lines().filter(|l| l.starts_with("T[")) {
            let (name, expr) = line.split_once(" = ").expect("an entry");
            let (i, j) = (
                name.as_bytes()[2] - b'0',
                name.as_bytes()[5] - b'0',
            );
            let back = eval_scalar_text(expr).expect("the text reads back");
            assert_eq!(back, m.rows[i as usize][j as usize], "{file} {name}: {expr}");
            read += 1;
        }
        assert_eq!(read, 12);
        // LaTeX in decimals too, and KaTeX renders it.
        let tex = report(Format::Latex, true);
        assert!(tex.contains("0.425 c_{2}") && !tex.contains("\\frac{1}{10000}"), "{tex}");
        let blocks: Vec<String> = tex
            .split("\\begin{aligned}")
            .skip(1)
            .map(|b| format!("\\begin{{aligned}}{}", b.split("\\end{aligned}").next().unwrap_or_default()) + "\\end{aligned}")
            .collect();
        crate::tools::katex_all(&blocks, file);
        // SymPy: exact decimals (`(425/1000)`), equal to the fractions of the pose.
        let sympy = report(Format::Sympy, true);
        assert!(sympy.contains("(425/1000)"), "{sympy}");
        let exact: String = m.rows[..3]
            .iter()
            .flatten()
            .enumerate()
            .map(|(c, x)| {
                let e = dqsym::closed_form(x).expect("closed form");
                format!("T[{}][{}] = {}\n", c / 4, c % 4, dqsym::emit::sympy(&e))
            })
            .collect();
        let script = format!(
            "import sympy, sys\n\
             a = dict(l.split(' = ', 1) for l in sys.stdin.read().split('@@')[0].splitlines() if l.startswith('T['))\n\
             b = dict(l.split(' = ', 1) for l in {exact:?}.splitlines())\n\
             for k in b:\n    d = sympy.expand(sympy.expand_trig(sympy.sympify(a[k]) - sympy.sympify(b[k])))\n    assert d == 0, (k, d)\n\
             print(len(b))\n"
        );
        let out = crate::tools::run_python(&script, &format!("{sympy}@@"), "sympy");
        assert_eq!(out.trim(), "12", "{file}");
        // Generated code reads the lengths as typed.
        let py = report(Format::Python, true);
        assert!(py.contains("0.425"), "{py}");
    }
}
