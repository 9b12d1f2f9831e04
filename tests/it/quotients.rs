//! Matrices with quotient entries in the language: `screwparams` of every screw the library
//! reads (planar centres divide by sin(theta/2)), checked against plain 4x4 matrices at random
//! points; their arithmetic, their four output formats, and the errors around them.

use crate::paper_support::{get, half, int, mat_rot_about, points, sym};
use crate::tools;
use dqsym::{kin::dh_link_matrix, parse, Frac, Matrix4, Session, Value};
use std::process::Command;

type Env = [(String, f64)];

/// Runs `src` (free names are symbols) and returns the value of `S`.
fn value_of(src: &str) -> Value {
    let program = parse(src).unwrap_or_else(|e| panic!("{e}"));
    let mut s = Session::with_implicit_symbols();
    s.run(&program)
        .unwrap_or_else(|e| panic!("{}", e.render(src)));
    s.get("S").expect("S is bound").clone()
}

/// The rendered error of `src`, which must fail.
fn error_of(src: &str) -> String {
    let program = parse(src).unwrap_or_else(|e| panic!("{e}"));
    Session::new()
        .run(&program)
        .expect_err("should fail")
        .render(src)
}

/// The entries of a matrix value, plain or with quotients, at a point.
fn entries_at(v: &Value, env: &Env) -> Vec<Vec<f64>> {
    let look = |n: &str| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v);
    match v {
        Value::Matrix(rows) => rows
            .iter()
            .map(|r| r.iter().map(|s| s.eval(&look).expect("bound")).collect())
            .collect(),
        Value::QuotientMatrix(rows) => rows
            .iter()
            .map(|r| r.iter().map(|f| f.eval(&look).expect("bound")).collect())
            .collect(),
        other => panic!("a matrix, not {other:?}"),
    }
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Asserts that the rows `(theta, t, 0)`, `n`, `m`, `C` of `screwparams` are the screw of the
/// rigid motion `[R d]`: `R` is the rotation by `theta` about the unit `n` (Rodrigues), the motion
/// is `x -> R (x - C) + C + t n`, i.e. `(I - R) C + t n = d`, with `C . n = 0` (the axis point
/// nearest the origin), and `m = C x n`. For `sin(theta/2) != 0` these determine the screw.
fn assert_screw_of(p: &[Vec<f64>], motion: &Matrix4<f64>, what: &str) {
    let (theta, t) = (p[0][0], p[0][1]);
    let row = |k: usize| [p[k][0], p[k][1], p[k][2]];
    let (n, m, c) = (row(1), row(2), row(3));
    assert_eq!(p[0][2], 0.0, "{what}");
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    assert!(near(dot(n, n), 1.0), "{what}: |n| = 1");
    let r = motion.rotation_block();
    let want = Matrix4::rotation(&n, &theta).rotation_block();
    for i in 0..3 {
        for j in 0..3 {
            assert!(near(r[i][j], want[i][j]), "{what}: R[{i}][{j}]");
        }
    }
    let d = motion.translation_column();
    for i in 0..3 {
        let rc: f64 = (0..3).map(|j| r[i][j] * c[j]).sum();
        assert!(near(c[i] - rc + t * n[i], d[i]), "{what}: d[{i}]");
    }
    assert!(near(dot(c, n), 0.0), "{what}: C . n = 0");
    let cn = cross(c, n);
    for i in 0..3 {
        assert!(near(m[i], cn[i]), "{what}: m[{i}]");
    }
}

/// A unit DQ in the language, its symbols, and the same motion as an f64 matrix built from
/// elementary matrices only.
struct Case {
    src: &'static str,
    names: &'static [&'static str],
    matrix: fn(&Env) -> Matrix4<f64>,
}

fn trans(x: f64, y: f64, z: f64) -> Matrix4<f64> {
    Matrix4::trans(&[x, y, z])
}

const CASES: &[Case] = &[
    // Sec 4, example 1: [M1] = d [R].
    Case {
        src: "trans((0, d1, d2)) * rot((1, 0, 0), theta)",
        names: &["d1", "d2", "theta"],
        matrix: |e| trans(0.0, get(e, "d1"), get(e, "d2")) * Matrix4::rot_x(&get(e, "theta")),
    },
    // Sec 4, example 2: [M2] = [R] d.
    Case {
        src: "rot((1, 0, 0), theta) * trans((0, d1, d2))",
        names: &["d1", "d2", "theta"],
        matrix: |e| Matrix4::rot_x(&get(e, "theta")) * trans(0.0, get(e, "d1"), get(e, "d2")),
    },
    Case {
        src: "rot((1, 0, 0), theta1, (0, l1, 0))",
        names: &["l1", "theta1"],
        matrix: |e| mat_rot_about('x', get(e, "theta1"), [0.0, get(e, "l1"), 0.0]),
    },
    // Two joints of the planar arm of Appendix III: the composite centre is a quotient.
    Case {
        src: "rot((1, 0, 0), theta1, (0, l1, 0)) * rot((1, 0, 0), theta2, (0, l2, 0))",
        names: &["l1", "l2", "theta1", "theta2"],
        matrix: |e| {
            mat_rot_about('x', get(e, "theta1"), [0.0, get(e, "l1"), 0.0])
                * mat_rot_about('x', get(e, "theta2"), [0.0, get(e, "l2"), 0.0])
        },
    },
    Case {
        src: "dh(theta1, d1, a1, 0)",
        names: &["a1", "d1", "theta1"],
        matrix: |e| dh_link_matrix(&get(e, "theta1"), &get(e, "d1"), &get(e, "a1"), &0.0),
    },
    Case {
        src: "screw((3/5, 4/5, 0), (l, d, 0), theta1, t)",
        names: &["d", "l", "t", "theta1"],
        matrix: |e| {
            let (l, d, t) = (get(e, "l"), get(e, "d"), get(e, "t"));
            let n = [0.6, 0.8, 0.0];
            trans(l, d, 0.0)
                * Matrix4::rotation(&n, &get(e, "theta1"))
                * trans(-l, -d, 0.0)
                * trans(t * n[0], t * n[1], 0.0)
        },
    },
    // A general screw: an oblique axis, and a translation with a part along it.
    Case {
        src: "trans((a, b, c)) * rot((2/3, 1/3, 2/3), theta)",
        names: &["a", "b", "c", "theta"],
        matrix: |e| {
            trans(get(e, "a"), get(e, "b"), get(e, "c"))
                * Matrix4::rotation(&[2.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0], &get(e, "theta"))
        },
    },
    Case {
        src: "rot((0, 0, 1), theta1, (l1, 0, 0)) * trans((0, 0, d)) * rot((0, 0, 1), theta2)",
        names: &["d", "l1", "theta1", "theta2"],
        matrix: |e| {
            mat_rot_about('z', get(e, "theta1"), [get(e, "l1"), 0.0, 0.0])
                * trans(0.0, 0.0, get(e, "d"))
                * Matrix4::rot_z(&get(e, "theta2"))
        },
    },
];

#[test]
fn screwparams_of_every_case_is_the_screw_of_its_matrix() {
    let mut quotients = 0;
    for case in CASES {
        let v = value_of(&format!("S = screwparams({})", case.src));
        quotients += usize::from(matches!(v, Value::QuotientMatrix(_)));
        let mut checked = 0;
        for env in points(case.names, 12) {
            let p = entries_at(&v, &env);
            // Near theta = 0 the axis is ill-conditioned: the quotients divide by sin(theta/2).
            if (p[0][0] / 2.0).sin().abs() < 0.05 {
                continue;
            }
            assert_screw_of(&p, &(case.matrix)(&env), case.src);
            checked += 1;
        }
        assert!(checked >= 8, "{}: {checked} points", case.src);
    }
    assert_eq!(
        quotients, 6,
        "all but the rotation about a point and the screw"
    );
}

/// The centres C1, C2 and moments m1, m2 of sec 4, as printed with c, s = cos, sin(theta/2):
/// Y1 = d1/2 - d2/2 c/s, Z1 = d1/2 c/s + d2/2; C2 = (0, -d1/2 - d2/2 c/s, d1/2 c/s - d2/2);
/// m1 = (0, d1/2 c/s + d2/2, -d1/2 + d2/2 c/s); m2 = (0, d1/2 c/s - d2/2, d1/2 + d2/2 c/s).
#[test]
fn sec4_centres_and_moments_are_the_papers() {
    let h = half(&sym("theta"));
    let (c, s) = (h.cos(), h.sin());
    let (d1, d2) = (sym("d1"), sym("d2"));
    // a/2 + b/2 c/s = (a s + b c)/(2 s).
    let q = |a: &dqsym::Scalar, b: &dqsym::Scalar| {
        Frac::new(a * &s + b * &c, &s * int(2)).expect("a quotient")
    };
    let zero = Frac::from(int(0));
    let ex1 = [
        [zero.clone(), q(&d2, &d1), q(&-&d1, &d2)],
        [zero.clone(), q(&d1, &-&d2), q(&d2, &d1)],
    ];
    let ex2 = [
        [zero.clone(), q(&-&d2, &d1), q(&d1, &d2)],
        [zero.clone(), q(&-&d1, &-&d2), q(&-&d2, &d1)],
    ];
    for (src, want) in [
        ("trans((0, d1, d2)) * rot((1, 0, 0), theta)", ex1),
        ("rot((1, 0, 0), theta) * trans((0, d1, d2))", ex2),
    ] {
        let Value::QuotientMatrix(rows) = value_of(&format!("S = screwparams({src})")) else {
            panic!("{src}: quotient entries expected")
        };
        assert_eq!(
            rows[0],
            [Frac::from(sym("theta")), zero.clone(), zero.clone()]
        );
        assert_eq!(rows[1], [Frac::from(int(1)), zero.clone(), zero.clone()]);
        assert_eq!(rows[2], want[0], "{src}: moment");
        assert_eq!(rows[3], want[1], "{src}: centre");
    }
}

const EX1: &str = "S = screwparams(trans((0, d1, d2)) * rot((1, 0, 0), theta))";

#[test]
fn quotient_entries_print_as_numerator_over_denominator() {
    // C1 = (0, d1/2 - d2/2 c/s, d1/2 c/s + d2/2) over the common denominator 2 s.
    assert_eq!(
        tools::dqsym_ok(&["-e", EX1]),
        "S =\n  [theta, 0, 0]\n  [1, 0, 0]\n  \
         [0, (d1 cos(theta/2) + d2 sin(theta/2))/(2 sin(theta/2)), \
         (-d1 sin(theta/2) + d2 cos(theta/2))/(2 sin(theta/2))]\n  \
         [0, (d1 sin(theta/2) - d2 cos(theta/2))/(2 sin(theta/2)), \
         (d1 cos(theta/2) + d2 sin(theta/2))/(2 sin(theta/2))]\n"
    );
    // The reducible cases keep their plain matrix.
    assert_eq!(
        tools::dqsym_ok(&["-e", "screwparams(rot((1, 0, 0), theta1, (0, l1, 0)))"]),
        "[theta1, 0, 0]\n[1, 0, 0]\n[0, 0, -l1]\n[0, l1, 0]\n"
    );
    let out = tools::dqsym_ok(&["-e", "screwparams(dh(theta1, d1, a1, 0))"]);
    assert_eq!(
        out,
        "[theta1, d1, 0]\n[0, 0, 1]\n\
         [(a1 cos(theta1/2))/(2 sin(theta1/2)), a1/2, 0]\n\
         [-a1/2, (a1 cos(theta1/2))/(2 sin(theta1/2)), 0]\n"
    );
}

#[test]
fn quotient_entries_render_in_latex() {
    let tex = tools::dqsym_ok(&["-e", EX1, "--format", "latex"]);
    assert!(
        tex.contains(
            "\\frac{d_{1} \\sin(\\frac{\\theta}{2}) - d_{2} \\cos(\\frac{\\theta}{2})}\
             {2 \\sin(\\frac{\\theta}{2})}"
        ),
        "{tex}"
    );
    let body = tex.strip_prefix("S = ").expect("labelled");
    tools::katex(body, "screwparams with quotient entries");
}

/// The SymPy text parses, and agrees with the exact entries at random points.
#[test]
fn quotient_entries_in_sympy_agree_numerically() {
    let names = ["d1", "d2", "theta"];
    let text = tools::dqsym_ok(&["-e", EX1, "--format", "sympy"]);
    let text = text.trim().strip_prefix("S = ").expect("labelled");
    let v = value_of(EX1);
    let envs = points(&names, 4);
    let mut input = format!("{text}\n");
    let mut want = Vec::new();
    for env in &envs {
        let vals: Vec<String> = env.iter().map(|(_, x)| format!("{x:?}")).collect();
        input += &(vals.join(" ") + "\n");
        want.extend(entries_at(&v, env).into_iter().flatten());
    }
    let script = "import sys\nfrom sympy import Matrix, sympify, symbols, cos, sin\n\
        lines = sys.stdin.read().splitlines()\n\
        names = symbols('d1 d2 theta')\n\
        m = sympify(lines[0], locals={'Matrix': Matrix, **{str(s): s for s in names}})\n\
        for line in lines[1:]:\n\
        \x20   vals = [float(x) for x in line.split()]\n\
        \x20   e = m.subs(dict(zip(names, vals))).evalf(30)\n\
        \x20   print(' '.join(repr(float(x)) for x in e))\n";
    let out = tools::run_python(script, &input, "sympy");
    let got: Vec<f64> = out
        .split_whitespace()
        .map(|x| x.parse().expect("a number"))
        .collect();
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert!(near(*g, *w), "{g} != {w}");
    }
}

/// The Rust function returns numerators and denominators; their quotients are the entries.
#[test]
fn quotient_entries_in_rust_compile_and_agree_numerically() {
    let code = tools::dqsym_ok(&["-e", EX1, "--format", "rust"]);
    assert!(code.contains("pub s_num: [[f64; 3]; 4],"), "{code}");
    assert!(code.contains("pub s_den: [[f64; 3]; 4],"), "{code}");
    let main = "\nfn main() {\n    let mut input = String::new();\n    \
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut input).unwrap();\n    \
        for line in input.lines() {\n        \
        let v: Vec<f64> = line.split_whitespace().map(|x| x.parse().unwrap()).collect();\n        \
        let r = s(v[0], v[1], v[2]);\n        \
        for i in 0..4 {\n            for j in 0..3 {\n                \
        print!(\"{:?} \", r.s_num[i][j] / r.s_den[i][j]);\n            }\n        }\n        \
        println!();\n    }\n}\n";
    let dir = tools::temp_dir("rust-quotients");
    let src = dir.join("gen.rs");
    std::fs::write(&src, code + main).expect("write gen.rs");
    let bin = dir.join("gen");
    let mut rustc = Command::new("rustc");
    rustc
        .args(["--edition", "2021", "-D", "warnings", "-o"])
        .arg(&bin)
        .arg(&src);
    tools::run(rustc, "", "rustc -D warnings on the screw parameters");
    let v = value_of(EX1);
    let envs = points(&["d1", "d2", "theta"], 4);
    let input: String = envs
        .iter()
        .map(|env| {
            let vals: Vec<String> = env.iter().map(|(_, x)| format!("{x:?}")).collect();
            vals.join(" ") + "\n"
        })
        .collect();
    let out = tools::run(Command::new(&bin), &input, "generated Rust");
    for (line, env) in out.lines().zip(&envs) {
        let got: Vec<f64> = line
            .split_whitespace()
            .map(|x| x.parse().expect("a number"))
            .collect();
        let want: Vec<f64> = entries_at(&v, env).into_iter().flatten().collect();
        assert_eq!(got.len(), 12);
        for (g, w) in got.iter().zip(&want) {
            assert!(near(*g, *w), "{g} != {w}");
        }
    }
}

/// Sums, products with matrices and scalars, division by numbers, transpose and diff of a
/// matrix with quotient entries agree with the same operations on its values; results whose
/// entries all reduce are plain matrices again.
#[test]
fn quotient_matrix_arithmetic_agrees_numerically() {
    let src = format!(
        "syms d1 d2 theta k\n{EX1}\n\
         A = S + S\nB = 3*S - k*S\nC = [0, 0, 0, 1]*S\nD = transpose(S)*[1, 0; 0, 1; 0, 0; 0, 0]\n\
         E = S/2\nF = diff(S, theta)\nG = diff(S, d1)\nZ = S - S\nP = transpose(S)*S\n\
         R = [1, 0, 0, 0]*S"
    );
    let program = parse(&src).unwrap();
    let mut s = Session::new();
    s.run(&program)
        .unwrap_or_else(|e| panic!("{}", e.render(&src)));
    let get_v = |n: &str| s.get(n).expect("bound").clone();
    let (a, b, c, d) = (get_v("A"), get_v("B"), get_v("C"), get_v("D"));
    let (e, f, g, z, p) = (get_v("E"), get_v("F"), get_v("G"), get_v("Z"), get_v("P"));
    // Results whose entries all reduce are plain matrices.
    assert_eq!(
        get_v("R"),
        Value::Matrix(vec![vec![sym("theta"), int(0), int(0)]])
    );
    assert_eq!(z, Value::Matrix(vec![vec![int(0); 3]; 4]));
    assert!(matches!(g, Value::QuotientMatrix(_)), "{g:?}");
    let sv = get_v("S");
    for env in points(&["d1", "d2", "theta", "k"], 6) {
        let m = entries_at(&sv, &env);
        let k = get(&env, "k");
        let h = 1e-6;
        let shifted = |name: &str, by: f64| -> Vec<(String, f64)> {
            env.iter()
                .map(|(n, x)| (n.clone(), if n == name { x + by } else { *x }))
                .collect()
        };
        let (mp, mm) = (
            entries_at(&sv, &shifted("theta", h)),
            entries_at(&sv, &shifted("theta", -h)),
        );
        let (gp, gm) = (
            entries_at(&sv, &shifted("d1", h)),
            entries_at(&sv, &shifted("d1", -h)),
        );
        let (av, bv, cv, dv) = (
            entries_at(&a, &env),
            entries_at(&b, &env),
            entries_at(&c, &env),
            entries_at(&d, &env),
        );
        let (ev_, fv, gv, zv, pv) = (
            entries_at(&e, &env),
            entries_at(&f, &env),
            entries_at(&g, &env),
            entries_at(&z, &env),
            entries_at(&p, &env),
        );
        for i in 0..4 {
            for j in 0..3 {
                let x = m[i][j];
                assert!(near(av[i][j], 2.0 * x), "A");
                assert!(near(bv[i][j], (3.0 - k) * x), "B");
                assert!(near(ev_[i][j], x / 2.0), "E");
                assert_eq!(zv[i][j], 0.0, "Z");
                let fd = (mp[i][j] - mm[i][j]) / (2.0 * h);
                assert!((fv[i][j] - fd).abs() < 1e-5 * (1.0 + fd.abs()), "F {fd}");
                let gd = (gp[i][j] - gm[i][j]) / (2.0 * h);
                assert!((gv[i][j] - gd).abs() < 1e-5, "G {gd}");
                if i < 2 {
                    assert!(near(dv[j][i], x), "D = the first two rows, transposed");
                }
            }
        }
        assert_eq!(cv.len(), 1);
        for j in 0..3 {
            assert!(near(cv[0][j], m[3][j]), "C is the last row");
            for l in 0..3 {
                let want: f64 = (0..4).map(|r| m[r][j] * m[r][l]).sum();
                assert!(near(pv[j][l], want), "P");
            }
        }
    }
}

/// Operations a matrix with quotient entries does not support fail with a message, a line and
/// a column, never a panic.
#[test]
fn quotient_matrix_misuse_is_a_clear_error() {
    let pre = "syms d1 d2 theta l\nS = screwparams(trans((0, d1, d2)) * rot((1, 0, 0), theta))\n";
    for (line, want) in [
        (
            "S*rot((1, 0, 0), theta)",
            "cannot multiply a 4x3 matrix with quotient entries by a dual quaternion",
        ),
        (
            "S + 1",
            "cannot add a 4x3 matrix with quotient entries and a scalar",
        ),
        ("S + [1, 2]", "the shapes differ"),
        ("S*S", "the inner sizes differ"),
        ("1/S", "cannot divide by a 4x3 matrix with quotient entries"),
        ("S/l", "cannot divide by a symbolic expression (l)"),
        (
            "S^2",
            "cannot raise a 4x3 matrix with quotient entries to a power",
        ),
        ("S'", "the quaternion conjugate needs a quaternion"),
        ("inverse(S)", "found a 4x3 matrix with quotient entries"),
        ("frommatrix(S)", "must be a 4x4 matrix"),
        ("[S]", "a matrix entry must be a scalar"),
        ("jacobian(rot((1, 0, 0), theta), S)", "a list of symbols"),
        (
            "screwparams(trans((0, d1, d2)))",
            "a pure translation has no screw axis",
        ),
    ] {
        let err = error_of(&format!("{pre}{line}"));
        assert!(err.contains(want), "{line}: {err}");
        assert!(err.contains(" --> 3:"), "{line}: {err}");
    }
}
