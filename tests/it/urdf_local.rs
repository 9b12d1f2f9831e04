//! URDF files whose origins hold angles off the pi/12 grid (hostile round 3, row 19): each
//! such angle is a named parameter, and carrying every joint's axis to the base multiplied the
//! frames before it out (each angle doubling the terms of every later axis), so `fk` stopped on
//! a term limit. The reader now keeps each joint in its own frame. Random files (seeded) of 4
//! to 6 moving joints, in five classes (off-grid origins of moving joints, off-grid axis
//! directions, off-grid fixed joints between moving ones, a mimic joint with an off-grid
//! offset, prismatic joints): `fk` at the default limits gets its result, and the pose it
//! reports (expanded or recurrence, evaluated entry by entry) equals a plain f64 4x4 model of
//! the URDF text, parsed here, at random joint values.

use crate::mat4::{ident, mul, rot, trans, M};
use dqsym::{app::fk_entries, kin::UrdfOptions, parse_urdf, Context, FkOptions, Preset};
use std::collections::HashMap;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_dqsym");

/// A deterministic generator (64-bit LCG, high bits).
struct Lcg(u64);

impl Lcg {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    fn below(&mut self, n: usize) -> usize {
        ((self.unit() * n as f64) as usize).min(n - 1)
    }

    /// An angle in (-3, 3), four decimals, at least 0.01 from every multiple of pi/12: the
    /// reader keeps it as a parameter.
    fn off_grid(&mut self) -> String {
        loop {
            let x = (self.range(-3.0, 3.0) * 1e4).round() / 1e4;
            let k = (x / (std::f64::consts::PI / 12.0)).round();
            if (x - k * std::f64::consts::PI / 12.0).abs() > 0.01 {
                return format!("{x:.4}");
            }
        }
    }

    fn on_grid(&mut self) -> String {
        // Full precision: the reader reads them as pi/2, -pi/2, pi exactly, and so does the
        // model (a short decimal such as 1.5708 is read as pi/2 too, 4e-6 away from the
        // model's value).
        [
            "0",
            "0",
            "1.5707963267948966",
            "-1.5707963267948966",
            "3.141592653589793",
        ][self.below(5)]
        .to_owned()
    }

    fn length(&mut self) -> String {
        format!("{:.3}", self.range(-0.5, 0.5))
    }
}

#[derive(Clone, Copy, Debug)]
enum Class {
    /// Off-grid rpy angles on the moving joints' origins.
    Moving,
    /// The same, with axis directions off every grid (not unit, not along x, y or z).
    Axes,
    /// An off-grid fixed joint before each moving joint.
    FixedBetween,
    /// The last joint mimics the first, with an off-grid offset.
    Mimic,
    /// Every second joint prismatic.
    Prismatic,
}

/// A random URDF chain of `n` moving joints of class `class`, with at least three origin
/// angles off the grid.
fn generate(seed: u64, n: usize, class: Class) -> String {
    let mut r = Lcg(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x5DEE_CE66);
    let mut text = format!("<?xml version=\"1.0\"?>\n<robot name=\"gen{seed}\">\n");
    let mut joints = String::new();
    let mut link = 0usize;
    let mut next_link = |joints: &mut String, body: String, name: String, kind: &str| {
        joints.push_str(&format!(
            "  <joint name=\"{name}\" type=\"{kind}\">\n    <parent link=\"l{link}\"/>\n    \
             <child link=\"l{}\"/>\n{body}  </joint>\n",
            link + 1
        ));
        link += 1;
    };
    for i in 0..n {
        if matches!(class, Class::FixedBetween) {
            let body = format!(
                "    <origin xyz=\"{} 0 {}\" rpy=\"{} {} 0\"/>\n",
                r.length(),
                r.length(),
                r.off_grid(),
                r.off_grid()
            );
            next_link(&mut joints, body, format!("f{i}"), "fixed");
        }
        // Off the grid: every angle of the first three joints' origins but one, half of the
        // others (at least three in all).
        let rpy: Vec<String> = (0..3)
            .map(|k| {
                if (i < 3 && k != i) || r.unit() < 0.5 {
                    r.off_grid()
                } else {
                    r.on_grid()
                }
            })
            .collect();
        let axis = match class {
            Class::Axes => format!(
                "{:.3} {:.3} {:.3}",
                r.range(0.1, 1.0),
                r.range(-1.0, 1.0),
                r.range(-1.0, 1.0)
            ),
            _ => ["1 0 0", "0 1 0", "0 0 1", "0 0 -1"][r.below(4)].to_owned(),
        };
        let kind = if matches!(class, Class::Prismatic) && i % 2 == 1 {
            "prismatic"
        } else {
            "revolute"
        };
        let mut body = format!(
            "    <origin xyz=\"{} {} {}\" rpy=\"{}\"/>\n    <axis xyz=\"{axis}\"/>\n",
            r.length(),
            r.length(),
            r.length(),
            rpy.join(" ")
        );
        if matches!(class, Class::Mimic) && i == n - 1 {
            body += &format!(
                "    <mimic joint=\"j0\" multiplier=\"-2\" offset=\"{}\"/>\n",
                r.off_grid()
            );
        }
        next_link(&mut joints, body, format!("j{i}"), kind);
    }
    for l in 0..=link {
        text += &format!("  <link name=\"l{l}\"/>\n");
    }
    text + &joints + "</robot>\n"
}

/// One `<joint>` of the text, as the model reads it.
struct Parsed {
    name: String,
    kind: String,
    parent: String,
    child: String,
    xyz: [f64; 3],
    rpy: [f64; 3],
    axis: [f64; 3],
    mimic: Option<(String, f64, f64)>,
}

/// The value of attribute `attr` of the first `<tag` element in `s`.
fn attribute(s: &str, tag: &str, attr: &str) -> Option<String> {
    let at = s.find(&format!("<{tag} "))?;
    let rest = &s[at..];
    let end = rest.find('>')?;
    let el = &rest[..end];
    let key = format!(" {attr}=\"");
    let v = el.find(&key)? + key.len();
    Some(el[v..v + el[v..].find('"')?].to_owned())
}

fn three(s: Option<String>, default: [f64; 3]) -> [f64; 3] {
    match s {
        None => default,
        Some(s) => {
            let v: Vec<f64> = s.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        }
    }
}

/// The joints of the URDF text, in document order (the generator writes the chain in order).
fn parse(text: &str) -> Vec<Parsed> {
    text.split("<joint ")
        .skip(1)
        .map(|chunk| {
            let s = format!("<joint {}", &chunk[..chunk.find("</joint>").unwrap()]);
            let mimic = attribute(&s, "mimic", "joint").map(|l| {
                let num = |a: &str| attribute(&s, "mimic", a).unwrap().parse().unwrap();
                (l, num("multiplier"), num("offset"))
            });
            Parsed {
                name: attribute(&s, "joint", "name").unwrap(),
                kind: attribute(&s, "joint", "type").unwrap(),
                parent: attribute(&s, "parent", "link").unwrap(),
                child: attribute(&s, "child", "link").unwrap(),
                xyz: three(attribute(&s, "origin", "xyz"), [0.0; 3]),
                rpy: three(attribute(&s, "origin", "rpy"), [0.0; 3]),
                axis: three(attribute(&s, "axis", "xyz"), [1.0, 0.0, 0.0]),
                mimic,
            }
        })
        .collect()
}

/// The model: `origin(xyz, rpy) · motion` per joint, `origin = Trans(xyz) Rz(y) Ry(p) Rx(r)`,
/// the motion a rotation about (or a slide along) the normalized axis by the joint's value.
fn model(joints: &[Parsed], q: &HashMap<String, f64>) -> M {
    let mut m = ident();
    for (k, j) in joints.iter().enumerate() {
        if k > 0 {
            assert_eq!(
                j.parent,
                joints[k - 1].child,
                "the generator writes a chain"
            );
        }
        let [x, y, z] = j.rpy;
        let r = mul(
            &rot([0.0, 0.0, 1.0], z),
            &mul(&rot([0.0, 1.0, 0.0], y), &rot([1.0, 0.0, 0.0], x)),
        );
        m = mul(&m, &mul(&trans(j.xyz), &r));
        let v = match &j.mimic {
            Some((l, mult, off)) => mult * q[l] + off,
            None => q.get(&j.name).copied().unwrap_or(0.0),
        };
        let n = j.axis.iter().map(|c| c * c).sum::<f64>().sqrt();
        let a = j.axis.map(|c| c / n);
        m = match j.kind.as_str() {
            "revolute" | "continuous" => mul(&m, &rot(a, v)),
            "prismatic" => mul(&m, &trans(a.map(|c| c * v))),
            _ => m,
        };
    }
    m
}

/// `fk` of the text at the default limits (`dqsym fk`'s preset), its pose evaluated at random
/// joint values against the model; whether it was a recurrence.
fn check(text: &str, what: &str, seed: u64) -> bool {
    let _limits = Context::preset(Preset::Fk).enter();
    let robot = parse_urdf(text, what, &UrdfOptions::default())
        .unwrap_or_else(|e| panic!("{what}: {e}"))
        .robot;
    let o = FkOptions {
        max_terms: Preset::Fk.term_limit(),
        ..FkOptions::default()
    };
    let entries = fk_entries(&robot, &o).unwrap_or_else(|e| panic!("{what}: {e}\n{text}"));
    let rows: Vec<_> = entries.rows().cloned().collect();
    let joints = parse(text);
    let mut r = Lcg(seed);
    for _ in 0..4 {
        let mut q: HashMap<String, f64> = robot
            .variables
            .iter()
            .map(|v| (v.clone(), r.range(-2.0, 2.0)))
            .collect();
        // The parameters at their nominal values: the decimals of the file.
        let env: Vec<(String, f64)> = q
            .iter()
            .map(|(k, v)| (k.clone(), *v))
            .chain(robot.values.iter().cloned())
            .collect();
        let vals = crate::recurrence::evaluate(&rows, &env);
        q.retain(|k, _| joints.iter().any(|j| &j.name == k));
        assert_eq!(
            q.len(),
            robot.variables.len(),
            "{what}: variables named as the joints"
        );
        let want = model(&joints, &q);
        for (i, row) in want.iter().take(3).enumerate() {
            for (k, w) in row.iter().enumerate() {
                let got = vals[&format!("T_{i}_{k}")];
                // Entries are at most the sum of the lengths (< 6 * 0.87) and the rotations'
                // unit entries; the recurrence evaluates a few hundred f64 operations on
                // exact closed forms, so the rounding is some 1e-13: 1e-9 leaves a margin
                // and still catches any wrong term (its coefficient is at least 1e-3^k).
                assert!(
                    (got - w).abs() < 1e-9,
                    "{what}: T[{i}][{k}] = {got}, the model gives {w}\n{text}"
                );
            }
        }
    }
    entries.recurrence
}

#[test]
fn random_urdfs_with_angles_off_the_grid_get_their_pose_at_the_default_limits() {
    let classes = [
        Class::Moving,
        Class::Axes,
        Class::FixedBetween,
        Class::Mimic,
        Class::Prismatic,
    ];
    let mut recurrences = 0;
    for (c, class) in classes.into_iter().enumerate() {
        for s in 0..3u64 {
            let seed = 100 * c as u64 + s;
            let n = 4 + (s as usize % 3);
            let text = generate(seed, n, class);
            let what = format!("{class:?} seed {seed} ({n} joints)");
            recurrences += usize::from(check(&text, &what, seed));
        }
    }
    // Most of these exceed the term limit when expanded: the recurrence is what they test.
    assert!(recurrences >= 8, "{recurrences} of 15 as a recurrence");
}

/// The command line, at its defaults, on the same files: `fk` (with the Jacobian) succeeds;
/// `convert`, `ik` and `walk`, which carry the axes to the base, succeed or stop on a named
/// limit, never a panic (`ik` and `walk` at a tenth of the default budget, to stay short).
#[test]
fn commands_on_off_grid_urdfs_succeed_or_name_their_limit() {
    let dir = std::env::temp_dir().join(format!("dqsym-urdf-local-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (seed, class) in [
        (7, Class::Moving),
        (8, Class::FixedBetween),
        (9, Class::Mimic),
    ] {
        let file = dir.join(format!("gen{seed}.urdf"));
        std::fs::write(&file, generate(seed, 5, class)).unwrap();
        let f = file.to_str().unwrap();
        let run = |args: &[&str]| {
            let out = Command::new(BIN).args(args).arg(f).output().unwrap();
            let err = String::from_utf8_lossy(&out.stderr).into_owned();
            assert!(!err.contains("panicked"), "{args:?} {f}: {err}");
            (out.status.code(), err)
        };
        let (code, err) = run(&["fk", "--jacobian"]);
        assert_eq!(code, Some(0), "fk {f}: {err}");
        for args in [
            &["convert"][..],
            &["--work-budget", "300000", "ik"][..],
            &["--work-budget", "300000", "walk", "--markdown"][..],
        ] {
            // A result, or one error message: a limit (named with its option), or for `ik`
            // a geometry no solver covers.
            let (code, err) = run(args);
            let error = err.lines().find(|l| l.starts_with("error: "));
            let named = error.is_some_and(|e| {
                [
                    "--term-limit",
                    "--work-budget",
                    "size limit",
                    "no closed-form",
                ]
                .iter()
                .any(|k| err.contains(k) && !e.is_empty())
            });
            assert!(
                code == Some(0) || (code == Some(1) && named),
                "{args:?} {f}: {code:?} {err}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A URDF whose origins are numbers stays in screw form (its report unchanged); one angle off
/// the grid makes it local.
#[test]
fn only_files_with_parameters_in_their_origins_are_read_in_local_frames() {
    let text = |rpy: &str| {
        format!(
            "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\
             <joint name=\"j0\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\
             <origin xyz=\"0 0 0.3\" rpy=\"{rpy}\"/><axis xyz=\"0 0 1\"/></joint>\
             <joint name=\"j1\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/>\
             <origin xyz=\"0.4 0 0\"/><axis xyz=\"0 1 0\"/></joint></robot>"
        )
    };
    for (rpy, local) in [("1.5707963267948966 0 0", false), ("0.9350 0 0", true)] {
        let t = text(rpy);
        let r = parse_urdf(&t, "r.urdf", &UrdfOptions::default())
            .unwrap()
            .robot;
        assert_eq!(
            r.convention == dqsym::kin::Convention::Local,
            local,
            "{rpy}"
        );
        check(&t, rpy, 3);
        // The screw form carries the same pose.
        let s = r.screw_form().unwrap();
        assert_eq!(s.convention, dqsym::kin::Convention::Screw);
        assert_eq!(s.forward_matrix(), r.forward_matrix(), "{rpy}");
    }
}
