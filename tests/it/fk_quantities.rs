//! The entries and sections of an fk report are types (`app::Quantity`, `app::SectionKind`):
//! every format's name, the generated outputs and Python's keys come from `app/quantity.rs`,
//! and no reader recognises an entry or a section by its text.

use crate::paper_support::points;
use crate::robots::plain_pose;
use dqsym::app::{
    fk_entries, Family, FkEntries, Letters, Quantity, SectionKind, Step, TaskBase, TaskName,
};
use dqsym::{fk_report, Expr, FkOptions, Format, Robot};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Every `.rs` file under `dir`.
fn sources(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let p = e.expect("an entry").path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The code lines (comments left out) of every source file of the library, the binary and
/// the Python bindings, with their file.
fn code_lines() -> Vec<(String, String)> {
    let mut files = Vec::new();
    for d in ["crates/dqsym-engine/src", "src", "python/src"] {
        sources(&std::path::Path::new(ROOT).join(d), &mut files);
    }
    assert!(files.len() > 50, "the sources were found: {}", files.len());
    let mut out = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(&f).expect("readable");
        let name = f
            .strip_prefix(ROOT)
            .expect("under the root")
            .display()
            .to_string();
        for l in text.lines() {
            if !l.trim_start().starts_with("//") {
                out.push((name.clone(), l.to_owned()));
            }
        }
    }
    out
}

/// What reading an entry's or a section's identity back from its text looks like: the base
/// name split off the indices, a match on base names, a section recognised by its title.
const PARSING: &[&str] = &[
    "split_once('[')",
    "split('[')",
    "replace(\"][\"",
    "starts_with(\"homogeneous",
    "starts_with(\"unit dual",
    "starts_with(\"Jacobian",
    "starts_with(\"dq[",
    "starts_with(\"T[",
    "starts_with(\"J[",
    "strip_prefix(\"dq[",
    "starts_with('J')",
    "\"Jr\" |",
    "\"Jr\" =>",
    "\"dq\" =>",
    "\"T\" =>",
    "ends_with(\"_den\")",
    "strip_suffix(\"dot\")",
    "o.name == \"dq\"",
];

/// Section titles: written once, in `app/quantity.rs`.
const TITLES: &[&str] = &[
    "\"homogeneous matrix (rows",
    "\"image of the point\"",
    "\"unit dual quaternion (w, x",
    "\"joint factors L{i}",
    "\"prefix products Q{i}",
    "\"suffix products P{i}",
    "\"Jacobian d dq[",
    "\"rotation Jacobian d r[i]",
];

#[test]
fn no_reader_recognises_an_fk_entry_or_section_by_its_text() {
    let mut found = Vec::new();
    for (file, line) in code_lines() {
        for p in PARSING {
            if line.contains(p) {
                found.push(format!("{file}: `{p}` in {}", line.trim()));
            }
        }
        let home = file.ends_with("app/quantity.rs") || file.ends_with("app/task.rs");
        for t in TITLES {
            if line.contains(t) && !home {
                found.push(format!("{file}: title {t} in {}", line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

fn load(name: &str) -> Robot {
    let path = format!("{ROOT}/examples/robots/{name}.toml");
    crate::robots::load(&path)
}

fn options(format: Format) -> FkOptions {
    FkOptions {
        format,
        jacobian: true,
        point: Some(dqsym::lang::eval_point_text("1/2, -1, 2").expect("a point")),
        ..FkOptions::default()
    }
}

fn names(e: &FkEntries) -> Vec<String> {
    e.rows().map(|(q, _)| q.name()).collect()
}

fn value(e: &Expr, env: &[(String, f64)]) -> f64 {
    let vals: Vec<(&str, f64)> = env.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    e.value_at(&vals).expect("a value")
}

/// Each entry's value is what its `Quantity` says, checked against an f64 product of the
/// joints' matrices (T, p), the rotation of the DQ (dq) and central differences of the DQ
/// entries (J); and every format prints the names `Quantity` writes, in the entries' order.
#[test]
fn fk_quantities_name_the_values_they_hold_in_every_format() {
    for robot in ["puma560", "scara", "stanford"] {
        let r = load(robot);
        let e = fk_entries(&r, &options(Format::Sympy)).expect("entries");
        assert!(!e.recurrence, "{robot}");
        let mut names_of_vars: Vec<&str> = r.variables.iter().map(String::as_str).collect();
        let params = r.parameters();
        names_of_vars.extend(params.iter().map(String::as_str));
        for env in points(&names_of_vars, 2) {
            let m = plain_pose(&r, &env);
            let pt = [0.5, -1.0, 2.0];
            let dq = |env: &[(String, f64)]| -> [f64; 8] {
                let mut v = [0.0; 8];
                for (q, x) in e.rows() {
                    if let Quantity::Dq(k) = q {
                        v[*k] = value(x, env);
                    }
                }
                v
            };
            let [w, x, y, z, ..] = dq(&env);
            // The rotation of the unit quaternion (w, x, y, z), written out.
            let rot = [
                [
                    1.0 - 2.0 * (y * y + z * z),
                    2.0 * (x * y - w * z),
                    2.0 * (x * z + w * y),
                ],
                [
                    2.0 * (x * y + w * z),
                    1.0 - 2.0 * (x * x + z * z),
                    2.0 * (y * z - w * x),
                ],
                [
                    2.0 * (x * z - w * y),
                    2.0 * (y * z + w * x),
                    1.0 - 2.0 * (x * x + y * y),
                ],
            ];
            let close = |a: f64, b: f64, what: String| {
                assert!(
                    (a - b).abs() <= 1e-6 * (1.0 + b.abs()),
                    "{robot} {what}: {a} != {b}"
                )
            };
            for (q, ex) in e.rows() {
                let got = value(ex, &env);
                match *q {
                    Quantity::T(i, j) => close(got, m.rows[i][j], q.name()),
                    Quantity::Point(i) => {
                        let want = (0..3).map(|j| m.rows[i][j] * pt[j]).sum::<f64>() + m.rows[i][3];
                        close(got, want, q.name())
                    }
                    Quantity::Dq(_) => {}
                    Quantity::J { row, col } => {
                        // h ~ eps^(1/3) for central differences of values of size ~1.
                        let h = 1e-5;
                        let at = |d: f64| {
                            let mut env = env.clone();
                            let v = env
                                .iter_mut()
                                .find(|(k, _)| *k == r.variables[col])
                                .expect("a joint");
                            v.1 += d;
                            dq(&env)[row]
                        };
                        close(got, (at(h) - at(-h)) / (2.0 * h), q.name())
                    }
                    other => panic!("{robot}: unexpected entry {}", other.name()),
                }
            }
            for (i, row) in rot.iter().enumerate() {
                for (j, want) in row.iter().enumerate() {
                    close(m.rows[i][j], *want, format!("rotation of dq [{i}][{j}]"));
                }
            }
        }
        // SymPy and plain text print these names, in this order.
        let sympy = fk_report(&r, &options(Format::Sympy)).expect("sympy");
        let printed: Vec<&str> = sympy
            .lines()
            .map(|l| l.split_once(" = ").expect("NAME = EXPR").0)
            .collect();
        assert_eq!(printed, names(&e), "{robot}");
        let plain = fk_report(&r, &options(Format::Plain)).expect("plain");
        let printed: Vec<&str> = plain
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(|l| l.split_once(" = ").expect("NAME = EXPR").0)
            .collect();
        assert_eq!(printed, names(&e), "{robot}");
        // The titles are the sections'.
        let titles: Vec<String> = e.sections.iter().map(|s| s.kind.title()).collect();
        for t in &titles {
            assert!(plain.contains(&format!("# {t}\n")), "{robot}: {t}");
        }
        // LaTeX: one row per entry, named by `Quantity::latex`.
        let latex = fk_report(&r, &options(Format::Latex)).expect("latex");
        let letters = Letters::avoiding(r.variables.iter().cloned().chain(r.parameters()));
        for (q, _) in e.rows() {
            assert!(
                latex.contains(&format!("{} &=", q.latex(&letters))),
                "{robot}: {}",
                q.name()
            );
        }
        // The generated code has one output per family.
        let rust = fk_report(&r, &options(Format::Rust)).expect("rust");
        let mut families: Vec<Family> = e.rows().map(|(q, _)| q.family()).collect();
        families.dedup();
        assert_eq!(families.len(), 4, "{robot}: dq, T, p, J");
        for f in families {
            let out = f.output(vec![Expr::Sym(dqsym::Sym::new("x")); 1], r.variables.len());
            assert!(
                rust.contains(&format!("pub {}:", out.name)),
                "{robot}: {}",
                out.name
            );
        }
    }
}

/// Names written for each kind of entry in each notation.
#[test]
fn fk_quantity_names_per_format() {
    let none = Letters::avoiding(std::iter::empty());
    let q_joints = Letters::avoiding(["q1".to_owned(), "q2".to_owned()].into_iter());
    let cases = [
        (Quantity::Dq(3), "dq[3]", "dq_3", "q_{3}", "x_{3}"),
        (Quantity::T(1, 2), "T[1][2]", "T_1_2", "T_{1,2}", "T_{1,2}"),
        (Quantity::Point(0), "p[0]", "p_0", "p_{0}", "p_{0}"),
        (
            Quantity::J { row: 7, col: 5 },
            "J[7][5]",
            "J_7_5",
            "J_{7,5}",
            "J_{7,5}",
        ),
        (
            Quantity::Step {
                step: Step::Prefix,
                joint: 2,
                k: 3,
            },
            "Q2[3]",
            "Q2_3",
            "\\mathit{Q2}_{3}",
            "\\mathit{Q2}_{3}",
        ),
    ];
    for (q, name, symbol, latex, latex_q) in cases {
        assert_eq!(q.name(), name);
        assert_eq!(q.symbol(), symbol);
        assert_eq!(q.latex(&none), latex, "{name}");
        assert_eq!(q.latex(&q_joints), latex_q, "{name}");
    }
    let rot = TaskName {
        base: TaskBase::Rotation,
        derivative: false,
    };
    let jr = Quantity::task(rot, false, 0, 1);
    assert_eq!(
        (jr.name(), jr.latex(&none)),
        ("Jr[0][1]".into(), "J^{r}_{0,1}".into())
    );
    let jrdot = Quantity::task(
        TaskName {
            derivative: true,
            ..rot
        },
        false,
        0,
        1,
    );
    assert_eq!(jrdot.name(), "Jrdot[0][1]");
    let pose = TaskName {
        base: TaskBase::Pose,
        derivative: false,
    };
    assert_eq!(
        Quantity::task(pose, false, 2, 3),
        Quantity::J { row: 2, col: 3 }
    );
    let jdot = Quantity::task(
        TaskName {
            derivative: true,
            ..pose
        },
        false,
        2,
        3,
    );
    assert_eq!(
        (jdot.name(), jdot.latex(&q_joints)),
        ("Jdot[2][3]".into(), "\\dot{J}_{2,3}".into())
    );
    let distance = TaskName {
        base: TaskBase::Distance,
        derivative: false,
    };
    let num = Quantity::task(distance, true, 0, 4);
    assert_eq!(
        (num.name(), num.symbol()),
        ("Jd_num[0][4]".into(), "Jd_num_0_4".into())
    );
    assert_eq!(Quantity::TaskDenominator(distance).name(), "Jd_den");
    let out = num
        .family()
        .output(vec![Expr::Sym(dqsym::Sym::new("x")); 6], 6);
    assert_eq!((out.name.as_str(), out.shape), ("jd_num", Some((1, 6))));
    let out = Quantity::TaskDenominator(distance)
        .family()
        .output(vec![Expr::Sym(dqsym::Sym::new("x"))], 6);
    assert_eq!((out.name.as_str(), out.shape), ("jd_den", None));
    let out = Quantity::DistanceB(0)
        .family()
        .output(vec![Expr::Sym(dqsym::Sym::new("x")); 7], 6);
    assert_eq!((out.name.as_str(), out.intermediate), ("Jd_b", true));
    let base = |q: Quantity| q.family().base();
    assert_eq!(
        base(Quantity::Step {
            step: Step::FactorDerivative,
            joint: 4,
            k: 0
        }),
        "dL4"
    );
    assert!(matches!(
        SectionKind::Matrix(dqsym::app::MatrixFrom::Expanded)
            .title()
            .as_str(),
        "homogeneous matrix (rows 0..2)"
    ));
}

/// `--jacobian=KIND` errors are a typed enum, each with its message.
#[test]
fn fk_task_jacobian_kinds_are_refused_with_typed_errors() {
    use dqsym::app::{TaskJacobian, TaskParseError};
    let parse = |s: &str| TaskJacobian::parse(s, &|v| dqsym::lang::eval_point_text(v));
    assert!(matches!(
        parse("pose_derivative_derivative"),
        Err(TaskParseError::DerivativeOfDerivative(_))
    ));
    assert!(matches!(
        parse("line_to_line_derivative:1,0,0,0,0,1"),
        Err(TaskParseError::LineToLineDerivative(_))
    ));
    let e = parse("rotation:1,2,3").unwrap_err();
    assert_eq!(e.to_string(), "`rotation` takes no `:` argument");
    let e = parse("point_to_line:1,2,3").unwrap_err();
    assert_eq!(
        e.to_string(),
        "`point_to_line` needs 6 numbers (a unit direction, then a point), got `1,2,3`"
    );
    assert!(matches!(
        parse("point_to_point"),
        Err(TaskParseError::MissingArgument { .. })
    ));
    assert!(matches!(parse("line:1,2"), Err(TaskParseError::Vector(_))));
    assert!(matches!(parse("wobble"), Err(TaskParseError::Unknown(_))));
    assert_eq!(
        parse("plane_to_point:1,2,3").expect("a kind"),
        TaskJacobian::PlaneToPoint(
            [0, 0, 1].map(dqsym::Scalar::int),
            [1, 2, 3].map(dqsym::Scalar::int)
        )
    );
}

/// What choosing code by searching generated (or template) text looks like: a test for a
/// fragment of code, splitting a text into blocks at blank lines.
const SEARCHING: &[&str] = &[
    ".contains(\"",
    ".find(\"",
    ".split(\"\\n",
    ".starts_with(\"",
    ".ends_with(\"",
    ".matches(\"",
];

/// The code writers (`emit/`, the IK solvers' writers) decide what to write from data: the
/// runtime helpers a solver keeps from its formulas (`emit/helpers.rs`, declared in the
/// runtime files), its parts from the plan; none of them searches text for code. (The one
/// place that reads the runtime files' marker lines is `emit/helpers.rs`, which parses
/// declarations, not code.)
#[test]
fn no_writer_chooses_code_by_searching_generated_text() {
    let writer = |f: &str| {
        (f.contains("/src/emit/") || f.contains("/src/ik/")) && !f.ends_with("emit/helpers.rs")
    };
    let mut found = Vec::new();
    let mut files = std::collections::BTreeSet::new();
    for (file, line) in code_lines() {
        if !writer(&file) {
            continue;
        }
        files.insert(file.clone());
        for p in SEARCHING {
            if line.contains(p) {
                found.push(format!("{file}: `{p}` in {}", line.trim()));
            }
        }
    }
    assert!(
        files.iter().any(|f| f.ends_with("ik/emit.rs"))
            && files.iter().any(|f| f.ends_with("ik/general/emit.rs"))
            && files.iter().any(|f| f.ends_with("emit/syntax.rs")),
        "the writers were read: {files:?}"
    );
    assert!(found.is_empty(), "{}", found.join("\n"));
}
