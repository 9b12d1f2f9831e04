//! URDF import and robot files with decimals, TOML numbers, base and tool frames: every robot
//! against an independent chain of plain f64 4x4 matrices built here from the origins and axes
//! as written (pose at random configurations, and its derivatives by finite differences), the
//! conversion back to a robot file, and malformed files.

use crate::mat4::{ident, mul, rot, trans, M};
use dqsym::{
    app::robot_toml, eval_scalar_text, fk_report, kin::UrdfOptions, parse_robot, parse_urdf,
    DualQuat, FkOptions, Robot,
};

/// The URDF origin `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)`.
fn origin(xyz: [f64; 3], rpy: [f64; 3]) -> M {
    let r = mul(
        &rot([0.0, 0.0, 1.0], rpy[2]),
        &mul(&rot([0.0, 1.0, 0.0], rpy[1]), &rot([1.0, 0.0, 0.0], rpy[0])),
    );
    mul(&trans(xyz), &r)
}

/// A joint as the test writes it into the URDF and into the oracle.
#[derive(Clone)]
struct J {
    name: &'static str,
    kind: &'static str,
    parent: &'static str,
    child: &'static str,
    xyz: [&'static str; 3],
    rpy: [&'static str; 3],
    axis: [&'static str; 3],
    mimic: Option<(&'static str, &'static str, &'static str)>,
}

fn j(
    name: &'static str,
    kind: &'static str,
    parent: &'static str,
    child: &'static str,
    xyz: [&'static str; 3],
    rpy: [&'static str; 3],
    axis: [&'static str; 3],
) -> J {
    J {
        name,
        kind,
        parent,
        child,
        xyz,
        rpy,
        axis,
        mimic: None,
    }
}

fn urdf_text(name: &str, joints: &[J]) -> String {
    let mut links: Vec<&str> = Vec::new();
    for x in joints {
        for l in [x.parent, x.child] {
            if !links.contains(&l) {
                links.push(l);
            }
        }
    }
    let mut s = format!("<?xml version=\"1.0\"?>\n<robot name=\"{name}\">\n");
    for l in &links {
        s += &format!("  <link name=\"{l}\"/>\n");
    }
    for x in joints {
        s += &format!(
            "  <joint name=\"{}\" type=\"{}\">\n    <parent link=\"{}\"/>\n    <child link=\"{}\"/>\n    <origin xyz=\"{}\" rpy=\"{}\"/>\n    <axis xyz=\"{}\"/>\n",
            x.name, x.kind, x.parent, x.child, x.xyz.join(" "), x.rpy.join(" "), x.axis.join(" ")
        );
        if let Some((l, m, o)) = x.mimic {
            s += &format!("    <mimic joint=\"{l}\" multiplier=\"{m}\" offset=\"{o}\"/>\n");
        }
        s += "  </joint>\n";
    }
    s + "</robot>\n"
}

fn f(x: &str) -> f64 {
    x.parse().unwrap()
}

fn f3(v: [&str; 3]) -> [f64; 3] {
    [f(v[0]), f(v[1]), f(v[2])]
}

/// The oracle: the product of the joints' origins and motions from the first joint to the
/// last, with the values of `q` by joint name (a mimic joint: multiplier * leader + offset).
fn oracle(joints: &[J], q: &dyn Fn(&str) -> f64) -> M {
    let mut m = ident();
    for x in joints {
        m = mul(&m, &origin(f3(x.xyz), f3(x.rpy)));
        let v = match x.mimic {
            Some((l, mult, off)) => f(mult) * q(l) + f(off),
            None => q(x.name),
        };
        let a = f3(x.axis);
        let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        let a = [a[0] / n, a[1] / n, a[2] / n];
        m = match x.kind {
            "revolute" | "continuous" => mul(&m, &rot(a, v)),
            "prismatic" => mul(&m, &trans([a[0] * v, a[1] * v, a[2] * v])),
            _ => m,
        };
    }
    m
}

/// A deterministic pseudo-random number in [-2, 2).
fn rnd(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 4.0 - 2.0
}

/// The robot's pose matrix at `env` (every variable bound), entries evaluated from the exact
/// matrix.
fn pose_at(m: &dqsym::Matrix4<dqsym::Scalar>, env: &[(String, f64)]) -> M {
    let mut out = [[0.0; 4]; 4];
    for (row, exact) in out.iter_mut().zip(&m.rows) {
        for (x, e) in row.iter_mut().zip(exact) {
            *x = e
                .eval(&|n| env.iter().find(|(a, _)| a == n).map(|(_, v)| *v))
                .expect("bound");
        }
    }
    out
}

/// Checks `r` (whose variables are the joints named in `names`, URDF order) against the
/// oracle at random configurations: the pose, the DQ's matrix, and each column of the pose's
/// derivative by central differences of the oracle.
fn check_against_oracle(r: &Robot, joints: &[J], seed: u64) {
    let m = r.forward_matrix();
    let from_dq = r.forward().to_matrix();
    let mut seed = seed;
    for _ in 0..5 {
        // The joint variables at random, the parameters (angles kept as names) at their
        // nominal values, which are the file's decimals.
        let env: Vec<(String, f64)> = r
            .variables
            .iter()
            .map(|v| (v.clone(), rnd(&mut seed)))
            .chain(r.values.iter().cloned())
            .collect();
        let q = |name: &str| {
            let v = name.replace('-', "_");
            env.iter().find(|(a, _)| *a == v).map_or(0.0, |(_, x)| *x)
        };
        let want = oracle(joints, &q);
        for got in [pose_at(&m, &env), pose_at(&from_dq, &env)] {
            for i in 0..4 {
                for k in 0..4 {
                    assert!(
                        (got[i][k] - want[i][k]).abs() < 1e-6,
                        "{}: T[{i}][{k}] = {} against {}",
                        r.name,
                        got[i][k],
                        want[i][k]
                    );
                }
            }
        }
        // Each variable's column: d T / d v, exact derivative against finite differences.
        for (vi, v) in r.variables.iter().enumerate() {
            let h = 1e-6;
            let shifted = |d: f64| {
                let q = |name: &str| {
                    let n = name.replace('-', "_");
                    env.iter()
                        .find(|(a, _)| *a == n)
                        .map_or(0.0, |(a, x)| if *a == *v { x + d } else { *x })
                };
                oracle(joints, &q)
            };
            let (p, mm) = (shifted(h), shifted(-h));
            for i in 0..3 {
                for k in 0..4 {
                    let exact = m.rows[i][k]
                        .diff(v)
                        .eval(&|n| env.iter().find(|(a, _)| a == n).map(|(_, x)| *x))
                        .unwrap();
                    let fd = (p[i][k] - mm[i][k]) / (2.0 * h);
                    assert!(
                        (exact - fd).abs() < 1e-5,
                        "{}: d T[{i}][{k}] / d {v} (column {vi}) = {exact} against {fd}",
                        r.name
                    );
                }
            }
        }
    }
}

fn read(name: &str, joints: &[J], o: &UrdfOptions) -> dqsym::kin::UrdfRobot {
    parse_urdf(&urdf_text(name, joints), name, o).unwrap_or_else(|e| panic!("{e}"))
}

/// Reads the URDF, checks it against the oracle, prints its report, and converts it to a
/// robot file that reads back to the same pose, exactly.
fn full_check(name: &str, joints: &[J], o: &UrdfOptions) -> Robot {
    let r = read(name, joints, o).robot;
    check_against_oracle(&r, joints, 7);
    let report = fk_report(
        &r,
        &FkOptions {
            jacobian: true,
            max_terms: 5_000,
            ..FkOptions::default()
        },
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(report.contains("T[2][3] = "), "{report}");
    let toml = robot_toml(&r, name).unwrap();
    let back =
        parse_robot(&toml, name, &eval_scalar_text).unwrap_or_else(|e| panic!("{e}\n{toml}"));
    assert_eq!(back.variables, r.variables, "{toml}");
    assert_eq!(back.forward_matrix(), r.forward_matrix(), "{toml}");
    r
}

const Z: [&str; 3] = ["0", "0", "0"];
const AZ: [&str; 3] = ["0", "0", "1"];
const HALF_PI: &str = "1.570796325";

fn ur5() -> Vec<J> {
    vec![
        j(
            "shoulder_pan_joint",
            "revolute",
            "base_link",
            "shoulder_link",
            ["0.0", "0.0", "0.089159"],
            ["0.0", "0.0", "0.0"],
            AZ,
        ),
        j(
            "shoulder_lift_joint",
            "revolute",
            "shoulder_link",
            "upper_arm_link",
            ["0.0", "0.13585", "0.0"],
            ["0.0", HALF_PI, "0.0"],
            ["0", "1", "0"],
        ),
        j(
            "elbow_joint",
            "revolute",
            "upper_arm_link",
            "forearm_link",
            ["0.0", "-0.1197", "0.425"],
            ["0.0", "0.0", "0.0"],
            ["0", "1", "0"],
        ),
        j(
            "wrist_1_joint",
            "revolute",
            "forearm_link",
            "wrist_1_link",
            ["0.0", "0.0", "0.39225"],
            ["0.0", HALF_PI, "0.0"],
            ["0", "1", "0"],
        ),
        j(
            "wrist_2_joint",
            "revolute",
            "wrist_1_link",
            "wrist_2_link",
            ["0.0", "0.093", "0.0"],
            ["0.0", "0.0", "0.0"],
            AZ,
        ),
        j(
            "wrist_3_joint",
            "revolute",
            "wrist_2_link",
            "wrist_3_link",
            ["0.0", "0.0", "0.09465"],
            ["0.0", "0.0", "0.0"],
            ["0", "1", "0"],
        ),
        j(
            "ee_fixed_joint",
            "fixed",
            "wrist_3_link",
            "ee_link",
            ["0.0", "0.0823", "0.0"],
            ["0.0", "0.0", HALF_PI],
            AZ,
        ),
    ]
}

/// PUMA 560 in Craig's modified DH, each link `Tx(a) Rx(alpha) Tz(d) Rz(theta)` as a URDF
/// origin with xyz = (a, -sin(alpha) d, cos(alpha) d) and rpy = (alpha, 0, 0).
fn puma560() -> Vec<J> {
    vec![
        j("j1", "revolute", "base", "l1", Z, Z, AZ),
        j(
            "j2",
            "revolute",
            "l1",
            "l2",
            Z,
            ["-1.5707963268", "0", "0"],
            AZ,
        ),
        j(
            "j3",
            "revolute",
            "l2",
            "l3",
            ["0.4318", "0", "0.15005"],
            Z,
            AZ,
        ),
        j(
            "j4",
            "revolute",
            "l3",
            "l4",
            ["0.0203", "0.4318", "0"],
            ["-1.5707963268", "0", "0"],
            AZ,
        ),
        j(
            "j5",
            "revolute",
            "l4",
            "l5",
            Z,
            ["1.5707963268", "0", "0"],
            AZ,
        ),
        j(
            "j6",
            "revolute",
            "l5",
            "l6",
            Z,
            ["-1.5707963268", "0", "0"],
            AZ,
        ),
    ]
}

/// The Franka Panda arm of franka_description (panda_arm.urdf), flange included.
fn panda() -> Vec<J> {
    let hp = "1.5707963267948966";
    let mhp = "-1.5707963267948966";
    vec![
        j(
            "panda_joint1",
            "revolute",
            "panda_link0",
            "panda_link1",
            ["0", "0", "0.333"],
            Z,
            AZ,
        ),
        j(
            "panda_joint2",
            "revolute",
            "panda_link1",
            "panda_link2",
            Z,
            [mhp, "0", "0"],
            AZ,
        ),
        j(
            "panda_joint3",
            "revolute",
            "panda_link2",
            "panda_link3",
            ["0", "-0.316", "0"],
            [hp, "0", "0"],
            AZ,
        ),
        j(
            "panda_joint4",
            "revolute",
            "panda_link3",
            "panda_link4",
            ["0.0825", "0", "0"],
            [hp, "0", "0"],
            AZ,
        ),
        j(
            "panda_joint5",
            "revolute",
            "panda_link4",
            "panda_link5",
            ["-0.0825", "0.384", "0"],
            [mhp, "0", "0"],
            AZ,
        ),
        j(
            "panda_joint6",
            "revolute",
            "panda_link5",
            "panda_link6",
            Z,
            [hp, "0", "0"],
            AZ,
        ),
        j(
            "panda_joint7",
            "revolute",
            "panda_link6",
            "panda_link7",
            ["0.088", "0", "0"],
            [hp, "0", "0"],
            AZ,
        ),
        j(
            "panda_joint8",
            "fixed",
            "panda_link7",
            "panda_link8",
            ["0", "0", "0.107"],
            Z,
            AZ,
        ),
        j(
            "panda_hand_joint",
            "fixed",
            "panda_link8",
            "panda_hand",
            Z,
            ["0", "0", "-0.7853981633974483"],
            AZ,
        ),
    ]
}

#[test]
fn ur5_urdf_with_its_real_offsets_matches_plain_matrices() {
    let r = full_check("ur5", &ur5(), &UrdfOptions::default());
    assert_eq!(r.variables.len(), 6);
    assert_eq!(r.variables[0], "shoulder_pan_joint");
    // The three rpy values near pi/2 are reported.
    let notes = read("ur5", &ur5(), &UrdfOptions::default()).notes;
    assert_eq!(notes.len(), 3, "{notes:?}");
    assert!(notes[0].contains("1.570796325 read as pi/2"), "{notes:?}");
}

#[test]
fn puma560_urdf_matches_plain_matrices() {
    full_check("puma560", &puma560(), &UrdfOptions::default());
}

#[test]
fn panda_urdf_matches_plain_matrices() {
    let r = full_check("panda", &panda(), &UrdfOptions::default());
    assert_eq!(r.variables.len(), 7);
}

#[test]
fn fixed_and_mimic_joints_fold_into_constants_and_coupled_variables() {
    let mut joints = vec![
        j(
            "base_yaw",
            "continuous",
            "world",
            "a",
            ["0.1", "0", "0.25"],
            Z,
            AZ,
        ),
        j(
            "bracket",
            "fixed",
            "a",
            "b",
            ["0", "0.05", "0.1"],
            ["0.5235987756", "0", "0"],
            AZ,
        ),
        j(
            "lift",
            "revolute",
            "b",
            "c",
            ["0.3", "0", "0"],
            Z,
            ["1", "0", "0"],
        ),
        j(
            "follow",
            "revolute",
            "c",
            "d",
            ["0", "0.2", "0"],
            ["0", "0", "3.14159265"],
            ["0", "1", "0"],
        ),
        j(
            "tool-mount",
            "fixed",
            "d",
            "tool",
            ["0", "0", "0.12"],
            Z,
            AZ,
        ),
    ];
    joints[3].mimic = Some(("lift", "-2", "0.785398163"));
    let r = full_check("coupled", &joints, &UrdfOptions::default());
    // Two independent variables; the mimic joint moves with `lift`.
    assert_eq!(r.variables, ["base_yaw", "lift"]);
    assert_eq!(r.chain.joints.len(), 3);
}

#[test]
fn prismatic_joints_and_non_unit_axes() {
    let joints = vec![
        j(
            "slide_z",
            "prismatic",
            "base",
            "a",
            ["0", "0", "0.5"],
            Z,
            AZ,
        ),
        j("turn", "revolute", "a", "b", ["0.2", "0", "0"], Z, AZ),
        j(
            "reach",
            "prismatic",
            "b",
            "c",
            ["0.1", "0", "0"],
            Z,
            ["1", "1", "0"],
        ),
        j(
            "wrist",
            "revolute",
            "c",
            "d",
            Z,
            ["0", "1.5707963", "0"],
            ["0", "0", "2"],
        ),
    ];
    let r = full_check("cartesian", &joints, &UrdfOptions::default());
    assert_eq!(r.variables.len(), 4);
}

#[test]
fn tip_and_base_choose_the_chain_of_a_tree() {
    let mut joints = panda();
    joints.push(j(
        "finger_joint1",
        "prismatic",
        "panda_hand",
        "leftfinger",
        ["0", "0", "0.0584"],
        Z,
        ["0", "1", "0"],
    ));
    let mut right = j(
        "finger_joint2",
        "prismatic",
        "panda_hand",
        "rightfinger",
        ["0", "0", "0.0584"],
        Z,
        ["0", "-1", "0"],
    );
    right.mimic = Some(("finger_joint1", "1", "0"));
    joints.push(right);
    let text = urdf_text("panda_hand", &joints);
    let err = parse_urdf(&text, "panda_hand.urdf", &UrdfOptions::default()).unwrap_err();
    assert!(err.to_string().contains("--tip"), "{err}");
    let o = UrdfOptions {
        tip: Some("rightfinger".into()),
        ..UrdfOptions::default()
    };
    let r = parse_urdf(&text, "panda_hand.urdf", &o).unwrap().robot;
    // The right finger follows the left one's variable, which is not in the chain.
    assert_eq!(
        r.variables.last().map(String::as_str),
        Some("finger_joint1")
    );
    let mut chain: Vec<J> = panda();
    chain.push(joints.last().unwrap().clone());
    check_against_oracle(&r, &chain, 11);
    let o = UrdfOptions {
        tip: Some("panda_link4".into()),
        base: Some("panda_link2".into()),
        ..UrdfOptions::default()
    };
    let r = parse_urdf(&text, "panda_hand.urdf", &o).unwrap().robot;
    assert_eq!(r.variables, ["panda_joint3", "panda_joint4"]);
    check_against_oracle(&r, &panda()[2..4], 13);
}

#[test]
fn snapping_can_be_turned_off() {
    let o = UrdfOptions {
        snap_angles: false,
        ..UrdfOptions::default()
    };
    // Every nonzero angle is then a parameter named after its joint, at the file's decimal.
    let u = parse_urdf(&urdf_text("ur5", &ur5()), "ur5.urdf", &o).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = u.robot.values.iter().map(|(n, _)| n.as_str()).collect();
    assert!(names.contains(&"shoulder_lift_joint_pitch"), "{names:?}");
    assert!(
        u.notes
            .iter()
            .any(|n| n.contains("kept as the parameter `shoulder_lift_joint_pitch`")),
        "{:?}",
        u.notes
    );
    assert!(
        !u.notes.iter().any(|n| n.contains("read as")),
        "{:?}",
        u.notes
    );
    assert!(u
        .robot
        .values
        .iter()
        .all(|(n, _)| !u.robot.variables.contains(n)));
    check_against_oracle(&u.robot, &ur5(), 17);
}

/// Angles that are no multiple of pi/12 (atan 7 = 1.42889927219074, 10 degrees)
/// become parameters named after their joint and axis, their decimals the robot's nominal
/// values; a mimic offset likewise. Pose and Jacobian against the oracle, and the converted
/// robot file reads back to the same matrix, with the values under `[values]`.
#[test]
fn angles_off_pi_over_12_become_named_parameters() {
    let mut joints = vec![
        j("yaw", "revolute", "w", "a", ["0", "0", "0.14"], Z, AZ),
        j(
            "shoulder",
            "revolute",
            "a",
            "b",
            ["0", "0", "0.1"],
            ["-1.5707963267949", "0", "0"],
            AZ,
        ),
        j(
            "elbow",
            "revolute",
            "b",
            "c",
            ["0.05", "0.35", "0"],
            ["0", "0", "-1.42889927219074"],
            AZ,
        ),
        j(
            "wrist",
            "revolute",
            "c",
            "d",
            ["0.25", "0", "0"],
            ["0", "-0.17453", "0.7853981634"],
            ["0", "1", "0"],
        ),
        j("coupled", "revolute", "d", "e", ["0", "0.02", "0.1"], Z, AZ),
        j("tip", "fixed", "e", "f", ["0.1", "0", "0"], Z, AZ),
    ];
    joints[4].mimic = Some(("wrist", "-1", "0.3"));
    let u = read("odd_angles", &joints, &UrdfOptions::default());
    let params: Vec<(&str, f64)> = u
        .robot
        .values
        .iter()
        .map(|(n, v)| (n.as_str(), *v))
        .collect();
    assert_eq!(
        params,
        [
            ("elbow_yaw", -1.42889927219074),
            ("wrist_pitch", -0.17453),
            ("coupled_offset", 0.3)
        ]
    );
    assert_eq!(u.robot.variables, ["yaw", "shoulder", "elbow", "wrist"]);
    let notes = u.notes.join("\n");
    assert!(notes.contains("0.7853981634 read as pi/4"), "{notes}");
    assert!(
        notes.contains("-1.42889927219074 kept as the parameter `elbow_yaw`"),
        "{notes}"
    );
    let r = full_check("odd_angles", &joints, &UrdfOptions::default());
    let toml = robot_toml(&r, "odd_angles").unwrap();
    assert!(
        toml.contains("[values]\nelbow_yaw = -1.42889927219074\n"),
        "{toml}"
    );
    // The report names them as parameters, not joint variables.
    let report = fk_report(&r, &FkOptions::default()).unwrap();
    assert!(
        report.contains("parameters: coupled_offset, elbow_yaw, wrist_pitch)"),
        "{report}"
    );
}

/// A robot file with decimals, plain TOML numbers (integers and floats, read from their
/// text), degrees, and base and tool frames, against the same oracle.
#[test]
fn robot_file_with_decimals_numbers_base_and_tool_frames_matches_plain_matrices() {
    let text = r#"
name = "framed"
convention = "screw"
[base]
xyz = [0.1, -2, "0.333"]
rpy = ["90deg", 0, "pi/4"]
[tool]
xyz = [0, 0.0825, 1e-1]
rpy = [0, "-pi/2", 0.0]

[[joint]]
type = "revolute"
variable = "q1"
axis = [0, 0, 1]
point = [0, 0, 0]

[[joint]]
type = "revolute"
variable = "q2"
axis = [0, 1, 0]
point = [0.4318, 0, 0.15005]

[[joint]]
type = "prismatic"
variable = "d3"
axis = [1, 0, 0]
"#;
    let r = parse_robot(text, "framed.toml", &eval_scalar_text).unwrap_or_else(|e| panic!("{e}"));
    // The same chain as URDF joints: base, joints about home-pose axes, tool.
    let joints = vec![
        j(
            "base",
            "fixed",
            "w",
            "b",
            ["0.1", "-2", "0.333"],
            [HALF_PI, "0", "0.785398163397"],
            AZ,
        ),
        j("q1", "revolute", "b", "l1", Z, Z, AZ),
        j("to2", "fixed", "l1", "x", ["0.4318", "0", "0.15005"], Z, AZ),
        j("q2", "revolute", "x", "y", Z, Z, ["0", "1", "0"]),
        j(
            "back",
            "fixed",
            "y",
            "l2",
            ["-0.4318", "0", "-0.15005"],
            Z,
            AZ,
        ),
        j("d3", "prismatic", "l2", "l3", Z, Z, ["1", "0", "0"]),
        j(
            "tool",
            "fixed",
            "l3",
            "t",
            ["0", "0.0825", "0.1"],
            ["0", "-1.570796326795", "0"],
            AZ,
        ),
    ];
    check_against_oracle(&r, &joints, 3);
    // Exact: 0.4318 is 2159/5000, not the nearest binary float.
    let x = r.chain.joints[1].geometry.clone();
    let dqsym::kin::JointGeometry::Screw { point, .. } = x else {
        panic!()
    };
    assert_eq!(point[0], eval_scalar_text("2159/5000").unwrap());
}

#[test]
fn bad_urdf_files_have_clear_messages() {
    crate::common::snapshot_settings().bind(|| {
        insta::glob!(
            concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data"),
            "urdf_bad/*.urdf",
            |path| {
                let text = std::fs::read_to_string(path).unwrap();
                let name = path.file_name().unwrap().to_string_lossy().into_owned();
                let err =
                    parse_urdf(&text, &name, &UrdfOptions::default()).expect_err("must be refused");
                insta::assert_snapshot!(err.to_string());
            }
        );
    });
}

/// The recurrence (forced with a term limit of 1) of robots with base and tool frames and with
/// coupled joints: every DQ component, matrix entry and Jacobian entry equals the expanded one.
#[test]
fn recurrence_with_frames_and_coupled_joints_matches_the_expansion() {
    let mut joints = vec![
        j("a1", "revolute", "w", "a", ["0.1", "0", "0.25"], Z, AZ),
        j(
            "a2",
            "revolute",
            "a",
            "b",
            ["0.3", "0", "0"],
            ["1.5707963268", "0", "0"],
            AZ,
        ),
        j(
            "a3",
            "revolute",
            "b",
            "c",
            ["0", "0.2", "0"],
            Z,
            ["0", "1", "0"],
        ),
        j(
            "flange",
            "fixed",
            "c",
            "t",
            ["0", "0", "0.12"],
            ["0", "0", "0.7853981634"],
            AZ,
        ),
    ];
    joints[2].mimic = Some(("a1", "3", "0"));
    let coupled = read("coupled", &joints, &UrdfOptions::default()).robot;
    let framed = parse_robot(
        "convention = \"dh\"\n[base]\nxyz = [0.5, 0, 0.1]\nrpy = [0, 0, \"pi/3\"]\n[tool]\nxyz = [0, 0, 0.107]\nrpy = [\"pi/2\", 0, 0]\n\
         [[joint]]\ntype = \"revolute\"\ntheta = \"q1\"\nd = 0.333\na = 0\nalpha = \"-pi/2\"\n\
         [[joint]]\ntype = \"prismatic\"\ntheta = 0\nd = \"d2\"\na = 0.0825\nalpha = 0\n",
        "framed.toml",
        &eval_scalar_text,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    for r in [&coupled, &framed] {
        let o = FkOptions {
            format: dqsym::Format::Sympy,
            jacobian: true,
            max_terms: 1,
            ..FkOptions::default()
        };
        let entries = dqsym::app::fk_recurrence(r, &o).expect("a recurrence");
        let q = r.forward();
        let m = r.forward_matrix();
        let vars: Vec<&str> = r.variables.iter().map(String::as_str).collect();
        let jac = dqsym::kin::dq_jacobian(&q, &vars);
        let mut seed = 5;
        // The joint variables at random, the parameters (angles kept as names) at their
        // nominal values, which are the file's decimals.
        let env: Vec<(String, f64)> = r
            .variables
            .iter()
            .map(|v| (v.clone(), rnd(&mut seed)))
            .chain(r.values.iter().cloned())
            .collect();
        let vals = crate::recurrence::evaluate(&entries, &env);
        let ev = |x: &dqsym::Scalar| {
            x.eval(&|n| env.iter().find(|(a, _)| a == n).map(|(_, v)| *v))
                .unwrap()
        };
        let close = |got: f64, want: f64, what: &str| {
            assert!(
                (got - want).abs() < 1e-9,
                "{}: {what} {got} != {want}",
                r.name
            )
        };
        for (k, c) in q.components().iter().enumerate() {
            close(vals[&format!("dq_{k}")], ev(c), &format!("dq[{k}]"));
        }
        for i in 0..3 {
            for k in 0..4 {
                close(
                    vals[&format!("T_{i}_{k}")],
                    ev(&m.rows[i][k]),
                    &format!("T[{i}][{k}]"),
                );
            }
        }
        for (k, row) in jac.iter().enumerate() {
            for (c, x) in row.iter().enumerate() {
                close(vals[&format!("J_{k}_{c}")], ev(x), &format!("J[{k}][{c}]"));
            }
        }
    }
}

/// RTB's 10-joint chains (Ball, Coil, Hyper3d class: DH links with a = d = 1, alpha = pi/2)
/// at the default fk limit: the report is the recurrence, small.
#[test]
fn ten_joint_numeric_chain_reports_a_small_recurrence_at_the_default_limit() {
    let mut text = String::from("name = \"coil\"\nconvention = \"dh\"\n");
    for i in 1..=10 {
        text += &format!(
            "[[joint]]\ntype = \"revolute\"\ntheta = \"q{i}\"\nd = 1\na = 1\nalpha = \"pi/2\"\n"
        );
    }
    let r = parse_robot(&text, "coil.toml", &eval_scalar_text).unwrap();
    let report = fk_report(
        &r,
        &FkOptions {
            jacobian: true,
            max_terms: 5_000,
            ..FkOptions::default()
        },
    )
    .expect("a report at the default limit");
    assert!(report.contains("as a recurrence"), "{}", &report[..200]);
    assert!(report.len() <= 100_000, "{} bytes", report.len());
}

/// Axes in odd directions: skew at 60 degrees with offsets, a prismatic joint tilted by 30 and
/// 45 degrees, a revolute axis parallel to it, one collinear with that, one perpendicular and
/// skew, and a tilted tool. Every angle between consecutive axes is a multiple of pi/12 with
/// a rational square sine, so DH form exists.
fn odd_axes() -> Vec<J> {
    vec![
        j("j1", "revolute", "base", "l1", ["0", "0", "0.3"], Z, AZ),
        j(
            "j2",
            "revolute",
            "l1",
            "l2",
            ["0.1", "0.05", "0.2"],
            ["0.5235987756", "0", "0"],
            ["0", "1", "0"],
        ),
        j(
            "j3",
            "prismatic",
            "l2",
            "l3",
            ["0.2", "0", "0"],
            ["0", "0", "0.785398163"],
            ["1", "0", "0"],
        ),
        j(
            "j4",
            "revolute",
            "l3",
            "l4",
            ["0", "0", "0.15"],
            Z,
            ["1", "0", "0"],
        ),
        j(
            "j5",
            "revolute",
            "l4",
            "l5",
            ["0.1", "0", "0"],
            Z,
            ["2", "0", "0"],
        ),
        j("j6", "revolute", "l5", "l6", ["0", "0.2", "0.1"], Z, AZ),
        j(
            "flange",
            "fixed",
            "l6",
            "tool",
            ["0.05", "0", "0.1"],
            ["0", "1.5707963", "0"],
            AZ,
        ),
    ]
}

/// `convert --to toml` writes DH when the axes allow it and screw form otherwise, saying why;
/// either way the file read back has exactly the URDF's pose (DQ up to sign, and matrix) and
/// matches the independent chain of matrices.
#[test]
fn convert_writes_dh_when_the_axes_allow_it_with_the_same_pose() {
    let mut coupled = ur5();
    coupled[4].mimic = Some(("elbow_joint", "1", "0"));
    let mut tilted = odd_axes();
    // 15 degrees between axes 1 and 2: its sine is a nested radical.
    tilted[1].rpy = ["0.2617993878", "0", "0"];
    let cases: Vec<(&str, Vec<J>, Option<&str>)> = vec![
        ("puma560", puma560(), None),
        ("ur5", ur5(), None),
        ("panda", panda(), None),
        ("odd_axes", odd_axes(), None),
        ("tilted", tilted, Some("axes 1 and 2")),
        ("coupled", coupled, Some("mimic")),
    ];
    for (name, joints, refusal) in cases {
        let r = read(name, &joints, &UrdfOptions::default()).robot;
        let toml = robot_toml(&r, name).unwrap();
        match refusal {
            None => {
                assert!(toml.contains("convention = \"dh\""), "{name}:\n{toml}");
                assert_eq!(dqsym::app::dh_refusal(&r), None);
            }
            Some(why) => {
                assert!(toml.contains("convention = \"screw\""), "{name}:\n{toml}");
                let said = dqsym::app::dh_refusal(&r).expect("a reason").to_string();
                assert!(said.contains(why), "{name}: {said}");
                assert!(toml.contains(&format!("# Not DH: {said}.")), "{toml}");
            }
        }
        let back = parse_robot(&toml, name, &eval_scalar_text)
            .unwrap_or_else(|e| panic!("{name}: {e}\n{toml}"));
        assert_eq!(back.variables, r.variables, "{toml}");
        assert_eq!(back.forward_matrix(), r.forward_matrix(), "{name}:\n{toml}");
        // The DQs, up to sign: exactly when no angle is an odd multiple of pi/8 (whose
        // relations the canonical form does not normalize), else at random points.
        let (a, b) = (back.forward(), r.forward());
        let neg = DualQuat::from_components(b.components().map(|x| -x));
        if a != b && a != neg {
            let mut seed = 23;
            for _ in 0..5 {
                let env: Vec<(String, f64)> = r
                    .variables
                    .iter()
                    .map(|v| (v.clone(), rnd(&mut seed)))
                    .collect();
                let ev = |x: &dqsym::Scalar| {
                    x.eval(&|n| env.iter().find(|(a, _)| a == n).map(|(_, v)| *v))
                        .unwrap()
                };
                let (ca, cb) = (a.components(), b.components());
                let same = |s: f64| (0..8).all(|k| (ev(&ca[k]) - s * ev(&cb[k])).abs() < 1e-9);
                assert!(same(1.0) || same(-1.0), "{name}: the DQs differ\n{toml}");
            }
        }
        check_against_oracle(&back, &joints, 17);
    }
}

/// `dqsym convert` through the binary: the UR5 URDF (`benches/support/ur5.urdf`) becomes a DH
/// file that `fk` reads to the same report as the URDF; a mimic joint gives screw form and a
/// note on stderr saying why.
#[test]
fn convert_command_writes_a_file_fk_reads_to_the_same_pose() {
    let bin = env!("CARGO_BIN_EXE_dqsym");
    let dir = std::env::temp_dir().join(format!("dqsym-convert-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let urdf = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/support/ur5.urdf");
    let run = |args: &[&str]| {
        let out = std::process::Command::new(bin).args(args).output().unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        (
            String::from_utf8(out.stdout).unwrap(),
            String::from_utf8(out.stderr).unwrap(),
        )
    };
    let (toml, err) = run(&["convert", urdf, "--to", "toml"]);
    assert!(toml.contains("convention = \"dh\""), "{toml}");
    assert!(!err.contains("screw form"), "{err}");
    let file = dir.join("ur5.toml");
    std::fs::write(&file, &toml).unwrap();
    let body = |report: &str| report.lines().skip(1).collect::<Vec<_>>().join("\n");
    let (from_urdf, _) = run(&["fk", urdf, "--format", "sympy"]);
    let (from_toml, _) = run(&["fk", file.to_str().unwrap(), "--format", "sympy"]);
    // The matrix rows are the same closed forms (the DQ may differ in sign).
    let rows = |r: &str| -> Vec<String> {
        r.lines()
            .filter(|l| l.starts_with("T["))
            .map(str::to_string)
            .collect()
    };
    assert_eq!(rows(&from_urdf), rows(&from_toml), "{}", body(&from_toml));
    assert_eq!(rows(&from_urdf).len(), 12);

    let mut coupled = ur5();
    coupled[2].mimic = Some(("shoulder_lift_joint", "-1", "0"));
    let path = dir.join("coupled.urdf");
    std::fs::write(&path, urdf_text("coupled", &coupled)).unwrap();
    let (toml, err) = run(&["convert", path.to_str().unwrap(), "--to", "toml"]);
    assert!(toml.contains("convention = \"screw\""), "{toml}");
    assert!(
        err.contains(
            "note: written in screw form, not DH: joint 3 moves with another joint's variable"
        ),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
