//! The general method's generated solvers on chains with prismatic joints: Rust (`core.rs`
//! verbatim), C (`core.c`), Python (`core.py`) and the IK page's JavaScript (`core.js`), each
//! against the reference solver's solution sets on the 5R1P and 4R2P arms of
//! `ik_general_prismatic` (its independent 4 x 4 model checks the poses).

use crate::common::Rng;
use crate::ik_general_prismatic::{
    derive, deviation, dist, pose, random_q, size, skew_4r2p, skew_5r1p, slide_last_5r1p,
};
use dqsym::ik::IkMethod;

const C_MAIN: &str = r#"
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
            printf("%d %.17g\n", s.approximate[i], s.residual[i]);
        }
    }
}
"#;

/// The generated C solver (`core.c`, the port of the core) on the 5R1P, the 4R2P and the
/// 5R1P whose last joint slides, compiled under `-std=c99 -pedantic -Wall -Wextra -Werror`:
/// at 200 random poses each it returns the reference solver's solution set (paired within
/// rounding: the generated solver evaluates the axes' closed forms in C), slides in the
/// robot's unit.
#[test]
fn generated_c_solver_with_slides_is_the_reference() {
    for (k, (name, rows)) in [
        ("skew 5R1P", skew_5r1p()),
        ("skew 4R2P", skew_4r2p()),
        ("5R1P slide last", slide_last_5r1p()),
    ]
    .into_iter()
    .enumerate()
    {
        let sol = derive(name, &rows, IkMethod::Auto);
        let code = dqsym::ik::ik_c(&sol).expect("c");
        let dir = crate::tools::temp_dir(&format!("ik-general-prismatic-c-{k}"));
        let (src, exe) = (dir.join("ik.c"), dir.join("ik"));
        std::fs::write(&src, format!("{code}{C_MAIN}")).expect("write");
        crate::tools::compile_c_clean(&src, &exe, "gcc on the general solver with slides");
        let mut rng = Rng::new(5 + k as u64);
        let qs: Vec<Vec<f64>> = (0..200).map(|_| random_q(&rows, &mut rng)).collect();
        let input: String = qs
            .iter()
            .map(|q| {
                let v: Vec<String> = pose(&rows, q)
                    .iter()
                    .flatten()
                    .map(|x| format!("{x:e}"))
                    .collect();
                v.join(" ") + "\n"
            })
            .collect();
        let out = crate::tools::run(std::process::Command::new(&exe), &input, "C ik");
        let mut lines = out.lines();
        let mut most: f64 = 0.0;
        for q in &qs {
            let reference = sol.solve_numeric(&pose(&rows, q), &[]).expect("reference");
            let n: usize = lines.next().expect("count").parse().expect("n");
            let got: Vec<Vec<f64>> = (0..n)
                .map(|_| {
                    let row = lines.next().expect("row").split_whitespace();
                    row.map(|x| x.parse().expect("number")).collect()
                })
                .collect();
            assert_eq!(
                n,
                reference.len(),
                "{name} at {q:?}: {got:?} vs {reference:?}"
            );
            // Solutions of one set are more than 1e-6 apart (the core merges closer ones):
            // pairing within half of that is unambiguous.
            for r in &reference {
                let g = got
                    .iter()
                    .find(|g| dist(&rows, &g[..6], &r.q) <= 0.5e-6)
                    .unwrap_or_else(|| panic!("{name}: {:?} not among {got:?}", r.q));
                assert_eq!(g[6] != 0.0, r.approximate, "{name} at {q:?}");
                most = most.max(dist(&rows, &g[..6], &r.q));
            }
        }
        eprintln!("{name}: C solver, largest distance to the reference {most:e}");
    }
}

/// The generated Python (NumPy) solver on the 5R1P, the 4R2P and the 5R1P whose last joint
/// slides: at 40 poses each, every solution it returns unflagged reproduces the pose to 1e-9 by
/// the model here, and it has every exact solution of the reference (within 1e-7: NumPy's SVD
/// and eigenvalues round differently from the core's QR), slides in the robot's unit.
#[test]
fn generated_python_solver_with_slides_agrees_with_the_reference() {
    for (name, rows) in [
        ("skew 5R1P", skew_5r1p()),
        ("skew 4R2P", skew_4r2p()),
        ("5R1P slide last", slide_last_5r1p()),
    ] {
        let sol = derive(name, &rows, IkMethod::Auto);
        let code = dqsym::ik::ik_python(&sol).expect("python");
        let script = format!(
            "{code}\n\nimport sys\nfor line in sys.stdin:\n    v = [float(x) for x in line.split()]\n    \
T = np.array(v[:16]).reshape(4, 4)\n    sols = ik_full(T)\n    \
print(len(sols))\n    for q, sg, ap, _ in sols:\n        print(' '.join(repr(float(x)) for x in q), int(ap))\n"
        );
        let mut rng = Rng::new(62);
        let qs: Vec<Vec<f64>> = (0..40).map(|_| random_q(&rows, &mut rng)).collect();
        let input: String = qs
            .iter()
            .map(|q| {
                let v: Vec<String> = pose(&rows, q)
                    .iter()
                    .flatten()
                    .map(|x| format!("{x:e}"))
                    .collect();
                v.join(" ") + "\n"
            })
            .collect();
        let out = crate::tools::run_python(&script, &input, "numpy");
        let mut lines = out.lines();
        let len = size(&rows);
        for q in &qs {
            let t = pose(&rows, q);
            let reference = sol.solve_numeric(&t, &[]).expect("reference");
            let n: usize = lines.next().expect("count").parse().expect("n");
            let mut got = Vec::new();
            for _ in 0..n {
                let v: Vec<f64> = lines
                    .next()
                    .expect("row")
                    .split_whitespace()
                    .map(|x| x.parse().expect("number"))
                    .collect();
                if v[6] == 0.0 {
                    let dev = deviation(&t, &pose(&rows, &v[..6]), len);
                    assert!(dev <= 1e-9, "{name}: Python {v:?} misses by {dev}");
                    got.push(v);
                }
            }
            for r in reference.iter().filter(|r| !r.approximate) {
                assert!(
                    got.iter().any(|g| dist(&rows, &g[..6], &r.q) <= 1e-7),
                    "{name}: {:?} not in the Python solver's {got:?}",
                    r.q
                );
            }
        }
    }
}

pub(crate) const NODE_MAIN: &str = r#"
const lines = require("fs").readFileSync(0, "utf8").trim().split("\n");
const ch = dqsym_ik_chain();
const ax = IK.kinds.map((k, i) => [k].concat([0, 1, 2, 3, 4, 5].map((j) => ch[`ax${i}_${j}`])));
const home = [0, 1, 2].map((r) => [0, 1, 2, 3].map((c) => ch[`home${r}${c}`]));
let out = "";
for (const l of lines) {
    const v = l.split(" ").map(Number);
    const T = [0, 1, 2, 3].map((r) => v.slice(4 * r, 4 * r + 4));
    const sols = ik_general(ax, home, T);
    out += sols.length + "\n";
    for (const [q, , ap] of sols) out += q.map(String).join(" ") + " " + (ap ? 1 : 0) + "\n";
}
process.stdout.write(out);
"#;

/// The page's JavaScript general solver (`core.js` with the page's helpers and driver) on the
/// 5R1P, the 4R2P and the 5R1P whose last joint slides, the joints' kinds as the page passes
/// them: at 100 poses each it returns the reference's solution set (paired within rounding).
#[test]
fn javascript_solver_with_slides_agrees_with_the_reference() {
    for (k, (name, rows)) in [
        ("skew 5R1P", skew_5r1p()),
        ("skew 4R2P", skew_4r2p()),
        ("5R1P slide last", slide_last_5r1p()),
    ]
    .into_iter()
    .enumerate()
    {
        let sol = derive(name, &rows, IkMethod::Auto);
        let num = |x: &dqsym::Scalar| x.eval(&|_: &str| None).expect("a numeric axis entry");
        let mut entries = Vec::new();
        for (i, a) in sol.axes.iter().enumerate() {
            for (c, x) in a.dir.iter().chain(&a.point).enumerate() {
                entries.push(format!("ax{i}_{c}: {:e}", num(x)));
            }
        }
        for (r, row) in sol.home.rows.iter().take(3).enumerate() {
            for (c, x) in row.iter().enumerate() {
                entries.push(format!("home{r}{c}: {:e}", num(x)));
            }
        }
        let kinds: Vec<&str> = rows
            .iter()
            .map(|r| if r.prismatic { "1" } else { "0" })
            .collect();
        let script = format!(
            "function dqsym_ik_chain() {{ return {{{}}}; }}\nconst IK = {{ kinds: [{}] }};\n{}{}{NODE_MAIN}",
            entries.join(", "),
            kinds.join(", "),
            dqsym::ik::ik_javascript_helpers(&sol),
            dqsym::ik::ik_javascript_general(&sol)
        );
        let mut rng = Rng::new(40 + k as u64);
        let qs: Vec<Vec<f64>> = (0..100).map(|_| random_q(&rows, &mut rng)).collect();
        let input: String = qs
            .iter()
            .map(|q| {
                let v: Vec<String> = pose(&rows, q)
                    .iter()
                    .flatten()
                    .map(|x| format!("{x:e}"))
                    .collect();
                v.join(" ") + "\n"
            })
            .collect();
        let mut node = std::process::Command::new("node");
        node.args(["-e", &script]);
        let out = crate::tools::run(node, &input, "node on the general solver with slides");
        let mut lines = out.lines();
        let mut most: f64 = 0.0;
        for q in &qs {
            let reference = sol.solve_numeric(&pose(&rows, q), &[]).expect("reference");
            let n: usize = lines.next().expect("count").parse().expect("n");
            let got: Vec<Vec<f64>> = (0..n)
                .map(|_| {
                    let row = lines.next().expect("row").split_whitespace();
                    row.map(|x| x.parse().expect("number")).collect()
                })
                .collect();
            assert_eq!(
                n,
                reference.len(),
                "{name} at {q:?}: {got:?} vs {reference:?}"
            );
            for r in &reference {
                let g = got
                    .iter()
                    .find(|g| dist(&rows, &g[..6], &r.q) <= 0.5e-6)
                    .unwrap_or_else(|| panic!("{name}: {:?} not among {got:?}", r.q));
                assert_eq!(g[6] != 0.0, r.approximate, "{name} at {q:?}");
                most = most.max(dist(&rows, &g[..6], &r.q));
            }
        }
        eprintln!("{name}: JavaScript solver, largest distance to the reference {most:e}");
    }
}

/// The generated Rust solver (`core.rs` verbatim) of the 5R1P and the 4R2P, compiled
/// optimised and clean (rustc and clippy `-D warnings`): at 100 poses each it returns the
/// reference's solution set (paired within rounding: it evaluates the axes' closed forms
/// itself), slides in the robot's unit.
#[test]
fn generated_rust_solver_with_slides_agrees_with_the_reference() {
    for (name, rows) in [("skew 5R1P", skew_5r1p()), ("skew 4R2P", skew_4r2p())] {
        let sol = derive(name, &rows, IkMethod::Auto);
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
        let tag = name.replace(' ', "-");
        let dir = crate::tools::temp_dir(&format!("ik-general-prismatic-rust-{tag}"));
        let (src, exe) = (dir.join("ik.rs"), dir.join("ik"));
        std::fs::write(&src, main).expect("write");
        crate::tools::compile_rust_clean(&src, &exe, true, &format!("general solver of {name}"));
        let mut rng = Rng::new(33);
        let qs: Vec<Vec<f64>> = (0..100).map(|_| random_q(&rows, &mut rng)).collect();
        let input: String = qs
            .iter()
            .map(|q| {
                let v: Vec<String> = pose(&rows, q)
                    .iter()
                    .flatten()
                    .map(|x| format!("{x:e}"))
                    .collect();
                v.join(" ") + "\n"
            })
            .collect();
        let out = crate::tools::run(std::process::Command::new(&exe), &input, "generated ik");
        let mut lines = out.lines();
        for q in &qs {
            let reference = sol.solve_numeric(&pose(&rows, q), &[]).expect("reference");
            let n: usize = lines.next().expect("count").parse().expect("n");
            let got: Vec<Vec<f64>> = (0..n)
                .map(|_| {
                    let row = lines.next().expect("row").split_whitespace();
                    row.map(|x| x.parse().expect("number")).collect()
                })
                .collect();
            assert_eq!(
                n,
                reference.len(),
                "{name} at {q:?}: {got:?} vs {reference:?}"
            );
            for r in &reference {
                assert!(
                    got.iter()
                        .any(|g| dist(&rows, &g[..6], &r.q) <= 0.5e-6
                            && (g[6] != 0.0) == r.approximate),
                    "{name}: {:?} not in the generated solver's {got:?}",
                    r.q
                );
            }
            assert!(got
                .iter()
                .any(|g| g[6] == 0.0 && dist(&rows, &g[..6], q) <= 1e-6));
        }
    }
}
