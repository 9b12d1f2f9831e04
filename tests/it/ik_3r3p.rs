//! The 3R3P family (`ik/plan/slides.rs`: the orientation from the three turns, the slides by
//! Cramer's rule): a skew arm with its three slides at each of the 20 placements, checked by
//! the independent classic-DH 4 x 4 model of `ik_general_prismatic` (every solution not
//! flagged approximate reproduces the pose to 1e-9, rotation entries and positions over the
//! arm's size; the original configuration is among them); the solution count against an
//! independent Levenberg–Marquardt multistart; near-singular poses of both steps (the turns'
//! double root, the slides' directions coplanar); the generated solvers in Rust, C, Python and
//! the page's JavaScript against the reference solver.

use crate::common::Rng;
use crate::ik_general_prismatic::{
    check_flagged, derive, deviation, dh_toml, dist, frames, multistart, pose, pri, random_q, rev,
    size, Row,
};
use dqsym::ik::{IkMethod, IkSolution};

const PI: f64 = std::f64::consts::PI;

/// Every placement of three slides among six joints.
fn placements() -> Vec<[usize; 3]> {
    let mut out = Vec::new();
    for i in 0..6 {
        for j in i + 1..6 {
            for k in j + 1..6 {
                out.push([i, j, k]);
            }
        }
    }
    out
}

/// A skew 3R3P arm with its slides at `slides`: offsets and twists everywhere (twists whose
/// cosines and sines are in Q(sqrt 2, sqrt 3), so that the exact formulas stay small), no two
/// turns about parallel axes, no two slides along one direction at home.
fn arm(slides: [usize; 3]) -> Vec<Row> {
    let turns = [
        rev(0.3, 0.1, ("pi/2", PI / 2.0)),
        rev(0.05, 0.4, ("pi/3", PI / 3.0)),
        rev(0.2, 0.03, ("-pi/2", -PI / 2.0)),
    ];
    let moves = [
        pri(("pi/6", PI / 6.0), 0.07, ("-pi/4", -PI / 4.0)),
        pri(("-pi/4", -PI / 4.0), 0.06, ("pi/2", PI / 2.0)),
        pri(("pi/3", PI / 3.0), 0.09, ("pi/6", PI / 6.0)),
    ];
    let (mut t, mut m) = (turns.iter(), moves.iter());
    (0..6)
        .map(|i| {
            if slides.contains(&i) {
                *m.next().expect("three slides")
            } else {
                *t.next().expect("three turns")
            }
        })
        .collect()
}

fn name(slides: [usize; 3]) -> String {
    let kinds: String = (0..6)
        .map(|i| if slides.contains(&i) { 'P' } else { 'R' })
        .collect();
    format!("3R3P {kinds}")
}

fn derived(slides: [usize; 3]) -> (String, Vec<Row>, IkSolution) {
    let (n, rows) = (name(slides), arm(slides));
    let sol = derive(&n, &rows, IkMethod::Auto);
    assert!(sol.general.is_none(), "{n}: {}", sol.family);
    assert!(
        sol.family.to_string().starts_with("3R3P"),
        "{n}: {}",
        sol.family
    );
    (n, rows, sol)
}

/// The solver's solutions at the pose of `q`: at most two, every unflagged one reproduces the
/// pose to 1e-9 by the model here, the original among them.
fn checked(name: &str, sol: &IkSolution, rows: &[Row], q: &[f64]) -> Vec<Vec<f64>> {
    let t = pose(rows, q);
    let sols = sol.solve_numeric(&t, &[]).expect("solve");
    assert!(sols.len() <= 2, "{name}: {} solutions", sols.len());
    let len = size(rows);
    for s in sols.iter().filter(|s| !s.approximate) {
        let dev = deviation(&t, &pose(rows, &s.q), len);
        assert!(dev <= 1e-9, "{name}: {:?} misses by {dev} (q {q:?})", s.q);
    }
    assert!(
        sols.iter()
            .any(|s| !s.approximate && dist(rows, &s.q, q) <= 1e-6),
        "{name}: {q:?} not among {sols:?}"
    );
    sols.into_iter()
        .filter(|s| !s.approximate)
        .map(|s| s.q)
        .collect()
}

/// Every placement of the slides, 1,000 random configurations each: the family applies, every
/// solution reproduces the pose, the original is among them, and there are two solutions (the
/// turns' two orientations) at all but a few configurations (those within rounding of a
/// singular set, where they may merge).
#[test]
fn every_3r3p_placement_round_trips_with_two_solutions() {
    for slides in placements() {
        let (n, rows, sol) = derived(slides);
        let mut rng = Rng::new(3 + slides.iter().sum::<usize>() as u64);
        let mut two = 0;
        for _ in 0..1000 {
            let q = random_q(&rows, &mut rng);
            two += usize::from(checked(&n, &sol, &rows, &q).len() == 2);
        }
        assert!(two >= 990, "{n}: two solutions at only {two} of 1000");
    }
}

/// The independent count: at 6 random poses per placement, 60 Levenberg–Marquardt starts each
/// (slides seeded in `(−1, 1)`); every distinct solution they find (both reproduce the pose to
/// 1e-12, so each is within about 1e-9 of an exact solution at these non-singular poses) is
/// one of the solver's, and over all poses they find every one of the solver's (two per pose:
/// a 3R3P's solutions are far apart, each basin is large).
#[test]
fn three_slide_solution_sets_agree_with_an_independent_multistart() {
    let (mut total_solver, mut total_multi) = (0, 0);
    for slides in placements() {
        let (n, rows, sol) = derived(slides);
        let len = size(&rows);
        let mut rng = Rng::new(41 + slides.iter().sum::<usize>() as u64);
        for _ in 0..6 {
            let q = random_q(&rows, &mut rng);
            let exact = checked(&n, &sol, &rows, &q);
            let t = pose(&rows, &q);
            let found = multistart(&rows, &t, len, 60, &mut rng);
            for m in &found {
                assert!(
                    exact.iter().any(|s| dist(&rows, s, m) <= 1e-6),
                    "{n}: the multistart's {m:?} is not among the solver's {exact:?} (q {q:?})"
                );
            }
            total_solver += exact.len();
            total_multi += found.len();
        }
    }
    eprintln!("3R3P: solver {total_solver} solutions at 120 poses, multistart {total_multi}");
    assert_eq!(total_multi, total_solver);
}

/// The unit z axis of DH frame `i` (the axis of joint `i + 1`) at `q`.
fn z_axis(rows: &[Row], q: &[f64], i: usize) -> [f64; 3] {
    let f = frames(rows, q)[i];
    [f[0][2], f[1][2], f[2][2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Near the turns' double root: the middle turn `b` at `θ* + eps`, where `θ*` is the extreme
/// of `k_a · Rot(k_b, θ) k_c` (home axes from the model at `q = 0`: `A cos θ + B sin θ + C`,
/// extreme at `atan2(B, A)`), so the two orientations nearly merge; `eps` from 1e-12 to 1e-3,
/// every placement. Every solution returned unflagged reproduces the pose to 1e-9, and the
/// pose is reached (exactly or flagged within 1e-6) at every one.
#[test]
fn near_the_turns_double_root_nothing_wrong_is_returned_unflagged() {
    for slides in placements() {
        let (n, rows, sol) = derived(slides);
        let turns: Vec<usize> = (0..6).filter(|i| !slides.contains(i)).collect();
        let zero = [0.0; 6];
        let k = |i: usize| z_axis(&rows, &zero, i);
        let (ka, kb, kc) = (k(turns[0]), k(turns[1]), k(turns[2]));
        let a = dot(ka, kc) - dot(ka, kb) * dot(kb, kc);
        let b = dot(ka, cross(kb, kc));
        let star = b.atan2(a);
        let mut rng = Rng::new(17);
        for e in 3..=12 {
            let eps = 10f64.powi(-e);
            for _ in 0..3 {
                let mut q = random_q(&rows, &mut rng);
                q[turns[1]] = star + eps;
                let best = check_flagged(&n, &sol, &rows, &q, &[]);
                assert!(
                    best <= 1e-6,
                    "{n}, eps {eps}: not reached ({best}, q {q:?})"
                );
            }
        }
    }
}

/// Near the slides' singular set: the middle turn of the PRPRPR arm (between its first and
/// last slides) set where the slides' current directions (the model's z axes) are coplanar,
/// found by bisection on `det(z1, z3, z5)`, then moved by `eps` from 1e-12 to 1e-3. Every
/// solution returned unflagged reproduces the pose to 1e-9; the pose is reached (exactly or
/// flagged) from `eps = 1e-6` on (closer, the slides are a nearly free line and the original
/// is one point of it; counted and printed).
#[test]
fn near_coplanar_slides_nothing_wrong_is_returned_unflagged() {
    let slides = [0, 2, 4];
    let (n, rows, sol) = derived(slides);
    let det = |q: &[f64]| {
        let z: Vec<[f64; 3]> = slides.iter().map(|&i| z_axis(&rows, q, i)).collect();
        dot(z[0], cross(z[1], z[2]))
    };
    let mut rng = Rng::new(23);
    let (mut tried, mut reached) = (0, 0);
    while tried < 60 {
        let mut q = random_q(&rows, &mut rng);
        // A sign change of det over joint 4's turn (joint index 3), then bisection.
        let at = |q: &mut Vec<f64>, x: f64| {
            q[3] = x;
            det(q)
        };
        let steps = 720;
        let mut root = None;
        for s in 0..steps {
            let (x0, x1) = (
                -PI + 2.0 * PI * s as f64 / steps as f64,
                -PI + 2.0 * PI * (s + 1) as f64 / steps as f64,
            );
            if at(&mut q, x0).signum() != at(&mut q, x1).signum() {
                root = Some((x0, x1));
                break;
            }
        }
        let Some((mut lo, mut hi)) = root else {
            continue;
        };
        let flo = at(&mut q, lo);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if at(&mut q, mid).signum() == flo.signum() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let e = 3 + tried % 10;
        let eps = 10f64.powi(-e);
        q[3] = lo + eps;
        tried += 1;
        let best = check_flagged(&n, &sol, &rows, &q, &[]);
        if best <= 1e-6 {
            reached += 1;
        } else {
            assert!(eps < 1e-6, "{n}, eps {eps}: not reached ({best}, q {q:?})");
        }
    }
    eprintln!("{n}, slides nearly coplanar: the pose reached at {reached} of {tried}");
}

/// Random poses of `rows` as input lines (16 numbers each), with their configurations.
pub(crate) fn poses(rows: &[Row], count: usize, seed: u64) -> (Vec<Vec<f64>>, String) {
    let mut rng = Rng::new(seed);
    let qs: Vec<Vec<f64>> = (0..count).map(|_| random_q(rows, &mut rng)).collect();
    let input = qs
        .iter()
        .map(|q| {
            let v: Vec<String> = pose(rows, q)
                .iter()
                .flatten()
                .map(|x| format!("{x:e}"))
                .collect();
            v.join(" ") + "\n"
        })
        .collect();
    (qs, input)
}

/// A generated solver's output (per pose: the count, then one line of six joints and the
/// approximate flag each) against the reference: the same solutions (paired within 1e-7 times
/// the largest joint, at least 1: the solvers evaluate the same closed forms in another order),
/// the same flags, every unflagged one reproducing the pose by the model here.
pub(crate) fn check_output(
    what: &str,
    name: &str,
    sol: &IkSolution,
    rows: &[Row],
    qs: &[Vec<f64>],
    out: &str,
) {
    let mut lines = out.lines();
    let len = size(rows);
    for q in qs {
        let t = pose(rows, q);
        let reference = sol.solve_numeric(&t, &[]).expect("reference");
        let n: usize = lines.next().expect("count").trim().parse().expect("n");
        let got: Vec<Vec<f64>> = (0..n)
            .map(|_| {
                let row = lines.next().expect("row").split_whitespace();
                row.map(|x| x.parse().expect("number")).collect()
            })
            .collect();
        assert_eq!(
            n,
            reference.len(),
            "{what} {name} at {q:?}: {got:?} vs {reference:?}"
        );
        for r in &reference {
            // A far solution (slides nearly parallel, lengths of hundreds) is fixed only to
            // about the rounding times its length: joints compared relative to the largest.
            let big = r.q.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert!(
                got.iter()
                    .any(|g| dist(rows, &g[..6], &r.q) <= 1e-7 * big
                        && (g[6] != 0.0) == r.approximate),
                "{what} {name}: {:?} not among {got:?}",
                r.q
            );
        }
        for g in got.iter().filter(|g| g[6] == 0.0) {
            let dev = deviation(&t, &pose(rows, &g[..6]), len);
            assert!(dev <= 1e-9, "{what} {name}: {g:?} misses by {dev}");
        }
        assert!(got
            .iter()
            .any(|g| g[6] == 0.0 && dist(rows, &g[..6], q) <= 1e-6));
    }
}

/// The placements the generated solvers are checked on: slides first, last, alternating both
/// ways, and split.
const PORTED: [[usize; 3]; 4] = [[0, 1, 2], [3, 4, 5], [0, 2, 4], [1, 3, 5]];

/// The generated Rust solver, compiled optimised and clean (rustc and clippy `-D warnings`), at
/// 100 poses of four placements: the reference's solutions.
#[test]
fn generated_rust_3r3p_solver_is_the_reference() {
    for slides in PORTED {
        let (n, rows, sol) = derived(slides);
        let code = dqsym::ik::ik_rust(&sol).expect("rust");
        let main = format!(
            "{code}\nfn main() {{\n    use std::io::BufRead;\n    \
for line in std::io::stdin().lock().lines() {{\n        \
let v: Vec<f64> = line.expect(\"line\").split_whitespace().map(|x| x.parse().expect(\"number\")).collect();\n        \
let mut t = [[0.0; 4]; 4];\n        for (i, x) in v.iter().enumerate() {{\n            t[i / 4][i % 4] = *x;\n        }}\n        \
let s = ik(&t);\n        println!(\"{{}}\", s.n);\n        for i in 0..s.n {{\n            \
let q: Vec<String> = s.q[i].iter().map(|x| format!(\"{{x:e}}\")).collect();\n            \
println!(\"{{}} {{}}\", q.join(\" \"), u8::from(s.approximate[i]));\n        }}\n    }}\n}}\n"
        );
        let tag = n.replace(' ', "-");
        let dir = crate::tools::temp_dir(&format!("ik-3r3p-rust-{tag}"));
        let (src, exe) = (dir.join("ik.rs"), dir.join("ik"));
        std::fs::write(&src, main).expect("write");
        crate::tools::compile_rust_clean(&src, &exe, true, &format!("the solver of {n}"));
        let (qs, input) = poses(&rows, 100, 51);
        let out = crate::tools::run(std::process::Command::new(&exe), &input, "generated ik");
        check_output("Rust", &n, &sol, &rows, &qs, &out);
    }
}

pub(crate) const C_MAIN: &str = r#"
#include <stdio.h>

int main(void) {
    double t[4][4];
    int i, j;
    for (;;) {
        ik_solutions s;
        for (i = 0; i < 16; i++)
            if (scanf("%lf", &t[i / 4][i % 4]) != 1) return 0;
        ik((const double (*)[4])t, &s);
        printf("%d\n", s.n);
        for (i = 0; i < s.n; i++) {
            for (j = 0; j < 6; j++) printf("%.17g ", s.q[i][j]);
            printf("%d\n", s.approximate[i]);
        }
    }
}
"#;

/// The generated C solver under `-std=c99 -pedantic -Wall -Wextra -Werror`, at 200 poses of
/// four placements: the reference's solutions.
#[test]
fn generated_c_3r3p_solver_is_the_reference() {
    for slides in PORTED {
        let (n, rows, sol) = derived(slides);
        let code = dqsym::ik::ik_c(&sol).expect("c");
        let tag = n.replace(' ', "-");
        let dir = crate::tools::temp_dir(&format!("ik-3r3p-c-{tag}"));
        let (src, exe) = (dir.join("ik.c"), dir.join("ik"));
        std::fs::write(&src, format!("{code}{C_MAIN}")).expect("write");
        crate::tools::compile_c_clean(&src, &exe, "gcc on the 3R3P solver");
        let (qs, input) = poses(&rows, 200, 52);
        let out = crate::tools::run(std::process::Command::new(&exe), &input, "C ik");
        check_output("C", &n, &sol, &rows, &qs, &out);
    }
}

/// The generated Python (NumPy) solver at 60 poses of four placements: the reference's
/// solutions.
#[test]
fn generated_python_3r3p_solver_is_the_reference() {
    for slides in PORTED {
        let (n, rows, sol) = derived(slides);
        let code = dqsym::ik::ik_python(&sol).expect("python");
        let script = format!(
            "{code}\n\nimport sys\nfor line in sys.stdin:\n    v = [float(x) for x in line.split()]\n    \
T = np.array(v[:16]).reshape(4, 4)\n    sols = ik_full(T)\n    \
print(len(sols))\n    for q, sg, ap, _ in sols:\n        print(' '.join(repr(float(x)) for x in q), int(ap))\n"
        );
        let (qs, input) = poses(&rows, 60, 53);
        let out = crate::tools::run_python(&script, &input, "numpy");
        check_output("Python", &n, &sol, &rows, &qs, &out);
    }
}

/// The page's solver: the IK script of `dqsym walk --ik --html` up to its driver (the chain,
/// the steps, the helpers), with a driver here that walks the branches as the page's does
/// (`ik_cands` per step with its rounding, `ik_push` per complete solution).
const NODE_MAIN: &str = r#"
const lines = require("fs").readFileSync(0, "utf8").trim().split("\n");
const ch = dqsym_ik_chain();
const ax = IK.kinds.map((k, i) => [k].concat([0, 1, 2, 3, 4, 5].map((j) => ch[`ax${i}_${j}`])));
const home = [0, 1, 2].map((r) => [0, 1, 2, 3].map((c) => ch[`home${r}${c}`]));
function solve(T) {
    const len = ik_scale(ax, home, T);
    const out = [];
    const env = {};
    ["r11","r12","r13","px","r21","r22","r23","py","r31","r32","r33","pz"].forEach((n, i) => { env[n] = T[Math.floor(i / 4)][i % 4]; });
    (function go(k, sg, ck, smp) {
        if (k === IK.steps.length) {
            ik_push(out, IK.vars.map((n) => env[n]), sg, ck, smp, ax, home, T, len, IK.position_only);
            return;
        }
        const s = IK.steps[k];
        const r = s.f(...s.args.map((n) => env[n]));
        const sig = IK_ZERO_TOL * Math.pow(len, IK.degrees[k]);
        const n0 = out.length;
        for (const [v, s1, c1, m1] of ik_cands(s.kind, s.parts.map((p) => r[p]), sig)) {
            if (m1 && s.kind === "trig" && out.slice(n0).some((row) => !row[2])) continue;
            env[s.var] = v;
            go(k + 1, sg || s1, ck || c1, smp || m1);
        }
        delete env[s.var];
    })(0, false, false, false);
    return out;
}
let text = "";
for (const l of lines) {
    const v = l.split(" ").map(Number);
    const sols = solve([0, 1, 2, 3].map((r) => v.slice(4 * r, 4 * r + 4)));
    text += sols.length + "\n";
    for (const [q, , ap] of sols) text += q.map(String).join(" ") + " " + (ap ? 1 : 0) + "\n";
}
process.stdout.write(text);
"#;

/// The IK page's JavaScript (its chain, steps and helpers, `ik_cands` with the linear steps) at
/// 100 poses of four placements, run with node: the reference's solutions.
#[test]
fn page_javascript_3r3p_solver_is_the_reference() {
    for slides in PORTED {
        let (n, rows, sol) = derived(slides);
        let tag = n.replace(' ', "-");
        let dir = crate::tools::temp_dir(&format!("ik-3r3p-js-{tag}"));
        let file = dir.join("arm.toml");
        std::fs::write(&file, dh_toml(&n, &rows)).expect("write");
        let page = dir.join("page.html");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_dqsym"))
            .arg("walk")
            .arg(&file)
            .args(["--ik", "--html"])
            .arg(&page)
            .output()
            .expect("runs");
        assert!(
            out.status.success(),
            "dqsym walk --ik --html: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let html = std::fs::read_to_string(&page).expect("page");
        let script = html
            .split("<script>")
            .filter_map(|s| s.split("</script>").next())
            .find(|s| s.contains("function dqsym_ik_chain("))
            .expect("the IK script");
        assert!(
            script.contains("\"kind\":\"linear\""),
            "{n}: no linear step"
        );
        let end = script.find("\n(function () {").expect("the page's driver");
        let js = format!("{}{NODE_MAIN}", &script[..end]);
        let (qs, input) = poses(&rows, 100, 54);
        let mut node = std::process::Command::new("node");
        node.args(["-e", &js]);
        let out = crate::tools::run(node, &input, "node on the 3R3P page solver");
        check_output("JavaScript", &n, &sol, &rows, &qs, &out);
    }
}

/// A 3R3P arm that no closed form serves is refused with the reason, never solved wrongly:
/// two consecutive turns about parallel axes (the turns reach a two-parameter set of
/// orientations), and three slides whose directions stay coplanar whatever the turns (slides
/// first, along directions in one plane: `det U` vanishes identically).
#[test]
fn degenerate_3r3p_arms_are_refused_with_the_reason() {
    let mut parallel = arm([3, 4, 5]);
    parallel[1].alpha = ("0", 0.0);
    let mut coplanar = arm([0, 1, 2]);
    for r in &mut coplanar[..3] {
        r.alpha = ("0", 0.0);
    }
    for (n, rows, why) in [
        (
            "parallel turns",
            parallel,
            "two consecutive turns about parallel axes",
        ),
        ("coplanar slides", coplanar, "linear (Cramer's rule)"),
    ] {
        let text = dh_toml(n, &rows);
        let robot = dqsym::parse_robot(&text, n, &dqsym::eval_scalar_text).expect("robot");
        let err = dqsym::ik::solve(
            &robot,
            &dqsym::ik::IkOptions {
                free: None,
                method: IkMethod::Auto,
            },
        )
        .expect_err("refused")
        .to_string();
        assert!(err.contains("the family that applies stops"), "{n}: {err}");
        assert!(err.contains(why), "{n}: {err}");
    }
}
