//! 4R2P arms whose two slides are three joints apart (PRRPRR, RPRRPR, RRPRRP): the Raghavan–Roth
//! elimination is degenerate for them in every reading of the loop, so `ik::general::apart`
//! separates the orientation (four turns) from the position (the slides' plane). Checked here
//! at every placement of the slides with random geometry, by the classic-DH 4 x 4 model of
//! `ik_general_prismatic.rs` (independent of the engine's product of exponentials): every
//! unflagged solution reproduces the pose to 1e-9 (rotation entries, positions over the arm's
//! size), the original configuration is among them, the count agrees with an independent
//! Levenberg–Marquardt multistart, near-singular poses return nothing wrong unflagged, and the
//! generated solvers (Rust, C, Python, the IK page's JavaScript) return the reference's
//! solutions.

use crate::common::Rng;
use crate::ik_general_prismatic::{
    check_flagged, derive, dist, frames, multistart_by, pose, pri, random_q, rev, size,
    solve_checked, Row,
};
use dqsym::ik::{IkMethod, IkSolution, NumSolution};

const PI: f64 = std::f64::consts::PI;

/// A number as the robot file's text and its value (rounded to 1e-3, so that both agree).
fn num(x: f64) -> (&'static str, f64) {
    let r = (x * 1000.0).round() / 1000.0;
    (Box::leak(format!("{r}").into_boxed_str()), r)
}

/// A random arm with slides at `first` and `first + 3` (0-based): offsets, lengths and twists
/// random (twists away from 0 and ±pi, so that no two consecutive axes are parallel).
fn random_arm(first: usize, rng: &mut Rng) -> Vec<Row> {
    (0..6)
        .map(|i| {
            let sign = if rng.below(2) == 0 { 1.0 } else { -1.0 };
            let alpha = num(sign * rng.range(0.3, 2.8));
            let a = rng.range(-0.4, 0.4);
            if i == first || i == first + 3 {
                pri(num(rng.range(-PI, PI)), num(a).1, alpha)
            } else {
                rev(num(rng.range(-0.4, 0.4)).1, num(a).1, alpha)
            }
        })
        .collect()
}

/// The arms of the tests: two random ones at each placement of the slides.
fn arms() -> Vec<(String, Vec<Row>)> {
    let mut rng = Rng::new(4242);
    let mut out = Vec::new();
    for first in 0..3 {
        for k in 0..2 {
            let rows = random_arm(first, &mut rng);
            let kinds: String = rows
                .iter()
                .map(|r| if r.prismatic { 'P' } else { 'R' })
                .collect();
            out.push((format!("{kinds} #{k}"), rows));
        }
    }
    out
}

#[test]
fn slides_three_apart_round_trip_at_every_placement() {
    for (name, rows) in arms() {
        let sol = derive(&name, &rows, IkMethod::Auto);
        let info = sol
            .general
            .clone()
            .unwrap_or_else(|| panic!("{name}: {}", sol.family));
        assert_eq!(info.degree, 8, "{name}");
        let mut rng = Rng::new(29);
        let mut most = 0;
        let mut hist = [0usize; 9];
        for _ in 0..1000 {
            let q = random_q(&rows, &mut rng);
            let n = solve_checked(&name, &sol, &rows, &q, 8).len();
            most = most.max(n);
            hist[n] += 1;
        }
        eprintln!(
            "{name}: degree {}, real solutions per pose {hist:?}",
            info.degree
        );
        assert!(most >= 4, "{name}: {most}");
    }
}

/// The independent count: at 10 random poses per arm, 300 Levenberg–Marquardt starts each
/// (slides seeded in `(−1, 1)`); every distinct solution they find (joints apart by more than
/// 1e-6, each reproducing the pose to 1e-12) is one of the solver's, and over all poses they
/// find at least 95% of the solver's (a random start can miss a small basin).
#[test]
fn slides_three_apart_counts_agree_with_an_independent_multistart() {
    for (name, rows) in arms() {
        let sol = derive(&name, &rows, IkMethod::Auto);
        let len = size(&rows);
        let mut rng = Rng::new(101);
        let (mut total_solver, mut total_multi) = (0, 0);
        for _ in 0..10 {
            let q = random_q(&rows, &mut rng);
            let exact: Vec<NumSolution> = solve_checked(&name, &sol, &rows, &q, 8)
                .into_iter()
                .filter(|s| !s.approximate)
                .collect();
            let t = pose(&rows, &q);
            // Far solutions (slides nearly parallel, lengths of hundreds) are fixed only to
            // about the residual times their length over the arm's: joints compared relative
            // to the largest of them.
            let near = |a: &[f64], b: &[f64]| {
                let big = a.iter().chain(b).fold(1.0f64, |m, x| m.max(x.abs()));
                dist(&rows, a, b) <= 1e-6 * big
            };
            let found = multistart_by(&rows, &t, len, 300, &mut rng, near);
            for m in &found {
                assert!(
                    exact.iter().any(|s| near(&s.q, m)),
                    "{name}: the multistart's {m:?} is not among the solver's {exact:?} (q {q:?})"
                );
            }
            total_solver += exact.len();
            total_multi += found.len();
        }
        assert!(
            20 * total_multi >= 19 * total_solver,
            "{name}: the multistart found {total_multi} of the solver's {total_solver}"
        );
        eprintln!("{name}: solver {total_solver} at 10 poses, multistart {total_multi}");
    }
}

/// The determinant of the DH model's 6 x 6 geometric Jacobian (independent of the engine).
#[allow(clippy::needless_range_loop)]
fn jacobian_det(rows: &[Row], q: &[f64]) -> f64 {
    let fr = frames(rows, q);
    let p = [fr[6][0][3], fr[6][1][3], fr[6][2][3]];
    let mut j = [[0.0; 6]; 6];
    for i in 0..6 {
        let z = [fr[i][0][2], fr[i][1][2], fr[i][2][2]];
        let o = [fr[i][0][3], fr[i][1][3], fr[i][2][3]];
        let col = if rows[i].prismatic {
            [z[0], z[1], z[2], 0.0, 0.0, 0.0]
        } else {
            let d = [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
            [
                z[1] * d[2] - z[2] * d[1],
                z[2] * d[0] - z[0] * d[2],
                z[0] * d[1] - z[1] * d[0],
                z[0],
                z[1],
                z[2],
            ]
        };
        for r in 0..6 {
            j[r][i] = col[r];
        }
    }
    // Gaussian elimination with partial pivoting.
    let mut det = 1.0;
    for k in 0..6 {
        let p = (k..6)
            .max_by(|&a, &b| j[a][k].abs().total_cmp(&j[b][k].abs()))
            .expect("row");
        if j[p][k] == 0.0 {
            return 0.0;
        }
        if p != k {
            j.swap(p, k);
            det = -det;
        }
        det *= j[k][k];
        for r in k + 1..6 {
            let f = j[r][k] / j[k][k];
            for c in k..6 {
                j[r][c] -= f * j[k][c];
            }
        }
    }
    det
}

/// A configuration on the singular set (the Jacobian's determinant zero, two solutions
/// merged): along joint `k` from a random configuration, a sign change of the determinant
/// bisected to rounding; `None` when there is none.
fn singular_configuration(rows: &[Row], rng: &mut Rng) -> Option<(Vec<f64>, usize)> {
    let mut q = random_q(rows, rng);
    let k = (0..6).find(|&i| !rows[i].prismatic).expect("a turn") + rng.below(2) as usize;
    let k = if rows[k].prismatic { k + 1 } else { k };
    let at = |q: &mut Vec<f64>, x: f64| {
        q[k] = x;
        jacobian_det(rows, q)
    };
    let n = 64;
    let step = 2.0 * PI / f64::from(n);
    for i in 0..n {
        let (mut a, mut b) = (-PI + step * f64::from(i), -PI + step * f64::from(i + 1));
        let fa = at(&mut q, a);
        if (fa < 0.0) != (at(&mut q, b) < 0.0) {
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if (at(&mut q, m) < 0.0) == (fa < 0.0) {
                    a = m;
                } else {
                    b = m;
                }
            }
            q[k] = 0.5 * (a + b);
            return Some((q, k));
        }
    }
    None
}

/// Near-singular poses (a configuration on the Jacobian's singular set, one turn moved by
/// `eps` from 1e-12 to 1e-3): every solution returned unflagged reproduces the pose to 1e-9
/// by the model here; the pose is reached (exactly or flagged) at least at 95% of them.
#[test]
fn slides_three_apart_near_singular_return_nothing_wrong_unflagged() {
    let mut rng = Rng::new(77);
    let (mut reached, mut total) = (0, 0);
    for (name, rows) in arms() {
        let sol = derive(&name, &rows, IkMethod::Auto);
        for e in 3..=12 {
            let eps = 10f64.powi(-e);
            let Some((mut q, k)) = (0..20).find_map(|_| singular_configuration(&rows, &mut rng))
            else {
                continue;
            };
            q[k] += eps;
            total += 1;
            if check_flagged(&name, &sol, &rows, &q, &[]) <= 1e-6 {
                reached += 1;
            }
        }
    }
    eprintln!("slides three apart, near singular: reached at {reached} of {total}");
    assert!(total >= 55, "{total}");
    assert!(20 * reached >= 19 * total, "{reached} of {total}");
}

/// The generated Rust solver (the apart core after the core), compiled clean, at 60 poses of
/// each placement: the reference's solutions.
#[test]
fn generated_rust_apart_solver_is_the_reference() {
    for (name, rows) in arms().into_iter().step_by(2) {
        let sol = derive(&name, &rows, IkMethod::Auto);
        let code = dqsym::ik::ik_rust(&sol).expect("rust");
        assert!(code.contains("fn apart_solve("), "{name}");
        let main = format!(
            "{code}\nfn main() {{\n    use std::io::BufRead;\n    \
for line in std::io::stdin().lock().lines() {{\n        \
let v: Vec<f64> = line.expect(\"line\").split_whitespace().map(|x| x.parse().expect(\"number\")).collect();\n        \
let mut t = [[0.0; 4]; 4];\n        for (i, x) in v.iter().enumerate() {{\n            t[i / 4][i % 4] = *x;\n        }}\n        \
let s = ik(&t);\n        println!(\"{{}}\", s.n);\n        for i in 0..s.n {{\n            \
let q: Vec<String> = s.q[i].iter().map(|x| format!(\"{{x:e}}\")).collect();\n            \
println!(\"{{}} {{}}\", q.join(\" \"), u8::from(s.approximate[i]));\n        }}\n    }}\n}}\n"
        );
        let tag: String = name.chars().filter(char::is_ascii_alphanumeric).collect();
        let dir = crate::tools::temp_dir(&format!("ik-apart-rust-{tag}"));
        let (src, exe) = (dir.join("ik.rs"), dir.join("ik"));
        std::fs::write(&src, main).expect("write");
        crate::tools::compile_rust_clean(&src, &exe, true, &format!("the solver of {name}"));
        let (qs, input) = crate::ik_3r3p::poses(&rows, 60, 51);
        let out = crate::tools::run(std::process::Command::new(&exe), &input, "generated ik");
        crate::ik_3r3p::check_output("Rust", &name, &sol, &rows, &qs, &out);
    }
}

/// The generated Python (NumPy) solver (`apart.py` after `core.py`) at 40 poses of each
/// placement: the reference's solutions.
#[test]
fn generated_python_apart_solver_is_the_reference() {
    for (name, rows) in arms().into_iter().step_by(2) {
        let sol = derive(&name, &rows, IkMethod::Auto);
        let code = dqsym::ik::ik_python(&sol).expect("python");
        assert!(code.contains("_apart_gen_solve(ik_ax"), "{name}");
        let script = format!(
            "{code}\n\nimport sys\nfor line in sys.stdin:\n    v = [float(x) for x in line.split()]\n    \
T = np.array(v[:16]).reshape(4, 4)\n    sols = ik_full(T)\n    \
print(len(sols))\n    for q, sg, ap, _ in sols:\n        print(' '.join(repr(float(x)) for x in q), int(ap))\n"
        );
        let (qs, input) = crate::ik_3r3p::poses(&rows, 40, 53);
        let out = crate::tools::run_python(&script, &input, "numpy");
        crate::ik_3r3p::check_output("Python", &name, &sol, &rows, &qs, &out);
    }
}

/// The generated C solver (`apart.c` after `core.c`, compiled under `-std=c99 -pedantic -Wall
/// -Wextra -Werror`) at `count` poses of `rows`, its roots of `D` by the eigenvalue route only
/// when `eigen_only` (the port's hook `IK_GEN_APART_EIGEN_ONLY`): the reference's solutions.
fn check_c(name: &str, rows: &[Row], eigen_only: bool, count: usize) {
    let sol = derive(name, rows, IkMethod::Auto);
    let code = dqsym::ik::ik_c(&sol).expect("c");
    assert!(code.contains("ik_gen_apart_solve(ik_ax"), "{name}");
    let hook = if eigen_only {
        "#define IK_GEN_APART_EIGEN_ONLY\n"
    } else {
        ""
    };
    let tag: String = name.chars().filter(char::is_ascii_alphanumeric).collect();
    let dir = crate::tools::temp_dir(&format!("ik-apart-c-{tag}-{eigen_only}"));
    let (src, exe) = (dir.join("ik.c"), dir.join("ik"));
    let text = format!("{hook}{code}{}", crate::ik_3r3p::C_MAIN);
    std::fs::write(&src, text).expect("write");
    crate::tools::compile_c_clean(&src, &exe, &format!("gcc on the solver of {name}"));
    let (qs, input) = crate::ik_3r3p::poses(rows, count, 55);
    let out = crate::tools::run(std::process::Command::new(&exe), &input, "C ik");
    crate::ik_3r3p::check_output("C", name, &sol, rows, &qs, &out);
}

/// The IK page's solver (its chain, helpers, `core.js` and `apart.js`: the pieces the page
/// puts together, the chain evaluated by the library), run with node at `count` poses of
/// `rows`, its roots of `D` by the eigenvalue route only when `eigen_only` (the port's hook
/// `ik_gen_apart_eigen_only`): the reference's solutions.
fn check_page(name: &str, rows: &[Row], eigen_only: bool, count: usize) {
    let sol = derive(name, rows, IkMethod::Auto);
    let js = format!(
        "{}{}{}",
        crate::ik_general_ports::js_chain(&sol),
        dqsym::ik::ik_javascript_helpers(&sol),
        dqsym::ik::ik_javascript_general(&sol)
    );
    assert!(js.contains("function ik_gen_apart_solve("), "{name}");
    let hook = if eigen_only {
        "ik_gen_apart_eigen_only = true;\n"
    } else {
        ""
    };
    run_page_solver(name, rows, &sol, &format!("{js}{hook}"), count);
}

/// Runs the page's solver `js` with node at `count` poses of `rows` and checks its output
/// against the reference.
fn run_page_solver(name: &str, rows: &[Row], sol: &IkSolution, js: &str, count: usize) {
    let script = format!("{js}{}", crate::ik_general_prismatic_ports::NODE_MAIN);
    let (qs, input) = crate::ik_3r3p::poses(rows, count, 56);
    let mut node = std::process::Command::new("node");
    node.args(["-e", &script]);
    let out = crate::tools::run(node, &input, "node on the apart page solver");
    crate::ik_3r3p::check_output("JavaScript", name, sol, rows, &qs, &out);
}

/// An RPRRPR arm whose angles are multiples of pi/12 (so that its walkthrough's drawing stays
/// small), slides at joints 2 and 5.
fn page_arm() -> Vec<Row> {
    let n = |t: &'static str, v: f64| (t, v);
    vec![
        rev(0.12, 0.05, n("pi/3", PI / 3.0)),
        pri(n("pi/4", PI / 4.0), 0.1, n("-pi/4", -PI / 4.0)),
        rev(0.07, 0.2, n("2*pi/3", 2.0 * PI / 3.0)),
        rev(-0.05, 0.15, n("pi/6", PI / 6.0)),
        pri(n("-pi/3", -PI / 3.0), 0.03, n("-5*pi/12", -5.0 * PI / 12.0)),
        rev(0.09, 0.1, n("pi/4", PI / 4.0)),
    ]
}

/// The IK page itself (`dqsym walk --ik --html`) of an arm with its slides three joints apart:
/// its script (chain, helpers, `core.js`, `apart.js`) run with node at 100 poses returns the
/// reference's solutions.
#[test]
fn ik_page_of_an_apart_arm_solves_it() {
    let (name, rows) = ("RPRRPR page", page_arm());
    let sol = derive(name, &rows, IkMethod::Auto);
    assert!(sol.general.is_some(), "{}", sol.family);
    let dir = crate::tools::temp_dir("ik-apart-page");
    let file = dir.join("arm.toml");
    std::fs::write(&file, crate::ik_general_prismatic::dh_toml(name, &rows)).expect("write");
    let html = crate::ik_general_ports::ik_page(&file, &dir.join("page.html"), &[]);
    let js = crate::ik_general_ports::page_solver(&html);
    assert!(js.contains("function ik_gen_apart_solve("), "{name}");
    run_page_solver(name, &rows, &sol, &js, 100);
}

/// The generated C solver at 200 poses of each placement: the reference's solutions.
#[test]
fn generated_c_apart_solver_is_the_reference() {
    for (name, rows) in arms().into_iter().step_by(2) {
        check_c(&name, &rows, false, 200);
    }
}

/// The IK page's JavaScript at 100 poses of each placement: the reference's solutions.
#[test]
fn page_javascript_apart_solver_is_the_reference() {
    for (name, rows) in arms().into_iter().step_by(2) {
        check_page(&name, &rows, false, 100);
    }
}

/// The fallback where the certified root search gives up in both readings (the eigenvalues of
/// the companion matrix of `D`), forced by each port's hook: the C solver, the page's
/// JavaScript and the Python solver (`_APART_EIGEN_ONLY`) at 40 poses of each placement return
/// the reference's solutions (found by the certified search).
#[test]
fn apart_ports_through_the_eigenvalue_route_are_the_reference() {
    for (name, rows) in arms().into_iter().skip(1).step_by(2) {
        check_c(&name, &rows, true, 40);
        check_page(&name, &rows, true, 40);
        let sol = derive(&name, &rows, IkMethod::Auto);
        let code = dqsym::ik::ik_python(&sol).expect("python");
        let script = format!(
            "{code}\n\n_APART_EIGEN_ONLY = True\nimport sys\nfor line in sys.stdin:\n    v = [float(x) for x in line.split()]\n    \
T = np.array(v[:16]).reshape(4, 4)\n    sols = ik_full(T)\n    \
print(len(sols))\n    for q, sg, ap, _ in sols:\n        print(' '.join(repr(float(x)) for x in q), int(ap))\n"
        );
        let (qs, input) = crate::ik_3r3p::poses(&rows, 40, 57);
        let out = crate::tools::run_python(&script, &input, "numpy");
        crate::ik_3r3p::check_output("Python", &name, &sol, &rows, &qs, &out);
    }
}

/// The family line and the report name this arm's own elimination (the four turns and the
/// slides' plane), not Raghavan-Roth's, which is degenerate for it; the stated degree is 8.
#[test]
fn apart_arms_name_their_own_elimination() {
    for (name, rows) in arms() {
        let sol = derive(&name, &rows, IkMethod::Auto);
        let family = sol.family.template;
        assert!(
            family.contains("slides three joints apart"),
            "{name}: {family}"
        );
        assert!(!family.contains("Raghavan"), "{name}: {family}");
        assert_eq!(sol.general.as_ref().map(|g| g.degree), Some(8), "{name}");
        let report = dqsym::ik::ik_report(&sol, dqsym::Format::Plain, true).expect("plain");
        assert!(report.contains(family), "{name}: {report}");
    }
}
