//! The general 6R method's C and JavaScript solvers (`ik/general/core.c`, `core.js`, ports of
//! `core.rs`) against the Rust reference solver (`IkSolution::solve_numeric`): the generated C
//! compiled with `gcc -std=c99 -pedantic -Wall -Wextra -Werror` and run, the IK page's
//! JavaScript run with node and in the page itself (Chromium), on a Jaco-style arm (60-degree
//! wrist), a skew-shoulder offset-wrist 6R and a PUMA with a 0.8 mm shoulder offset (through
//! `--method general`). Every pose is checked by an independent classic-DH 4 x 4 model written
//! here: every solution not flagged approximate reproduces the pose to 1e-9 (rotation entries,
//! positions over the arm's size), the original configuration is among them, and the solution
//! set is the reference's.

use crate::common::Rng;
use dqsym::ik::{solve, IkMethod, IkOptions, IkSolution, NumSolution};
use std::path::Path;
use std::process::Command;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");
const PI: f64 = std::f64::consts::PI;

type M4 = [[f64; 4]; 4];

/// One classic DH row `Rz(q) Tz(d) Tx(a) Rx(alpha)`, `alpha` as robot-file text and as a number.
#[derive(Clone, Copy)]
struct Dh {
    d: f64,
    a: f64,
    alpha: (&'static str, f64),
}

const fn dh(d: f64, a: f64, alpha: (&'static str, f64)) -> Dh {
    Dh { d, a, alpha }
}

const A0: (&str, f64) = ("0", 0.0);
const A90: (&str, f64) = ("pi/2", PI / 2.0);
const AM90: (&str, f64) = ("-pi/2", -PI / 2.0);
const A180: (&str, f64) = ("pi", PI);
const A60: (&str, f64) = ("pi/3", PI / 3.0);

/// Kinova Jaco (the Robotics Toolbox DH table without its joint offsets: 60-degree wrist).
fn jaco() -> Vec<Dh> {
    let k = 1.0 / 3f64.sqrt();
    let (d1, d2, d3, d4, d5, d6, e2) = (0.2755, 0.41, 0.2073, 0.0743, 0.0743, 0.1687, 0.0098);
    vec![
        dh(d1, 0.0, A90),
        dh(0.0, d2, A180),
        dh(-e2, 0.0, A90),
        dh(-(d3 + k * d4), 0.0, A60),
        dh(-(k * d4 + k * d5), 0.0, A60),
        dh(-(k * d5 + d6), 0.0, A180),
    ]
}

/// A skew shoulder (axes 1, 2 at 60 degrees with an offset) and an offset wrist.
fn skew() -> Vec<Dh> {
    vec![
        dh(0.3, 0.05, A60),
        dh(0.02, 0.4, ("pi/6", PI / 6.0)),
        dh(0.05, 0.03, A90),
        dh(0.35, 0.02, AM90),
        dh(0.07, 0.04, ("2*pi/5", 2.0 * PI / 5.0)),
        dh(0.1, 0.0, A0),
    ]
}

/// PUMA 560 at its published lengths with a 0.8 mm shoulder offset `a1`.
fn puma_offset() -> Vec<Dh> {
    vec![
        dh(0.0, 0.0008, A90),
        dh(0.0, 0.4318, A0),
        dh(0.15005, 0.0203, AM90),
        dh(0.4318, 0.0, A90),
        dh(0.0, 0.0, AM90),
        dh(0.0, 0.0, A0),
    ]
}

/// The arms and how each is derived (the PUMA keeps its family unless the general method is
/// forced).
fn arms() -> Vec<(&'static str, Vec<Dh>, IkMethod)> {
    vec![
        ("jaco", jaco(), IkMethod::Auto),
        ("skew", skew(), IkMethod::Auto),
        ("puma a1", puma_offset(), IkMethod::General),
    ]
}

fn mul(a: &M4, b: &M4) -> M4 {
    std::array::from_fn(|r| std::array::from_fn(|c| (0..4).map(|k| a[r][k] * b[k][c]).sum()))
}

/// The independent model: the product of the rows' 4 x 4 matrices.
fn dh_pose(rows: &[Dh], q: &[f64]) -> M4 {
    let mut t: M4 = std::array::from_fn(|r| std::array::from_fn(|c| f64::from(u8::from(r == c))));
    for (r, th) in rows.iter().zip(q) {
        let (st, ct) = th.sin_cos();
        let (sa, ca) = r.alpha.1.sin_cos();
        let m = [
            [ct, -st * ca, st * sa, r.a * ct],
            [st, ct * ca, -ct * sa, r.a * st],
            [0.0, sa, ca, r.d],
            [0.0, 0.0, 0.0, 1.0],
        ];
        t = mul(&t, &m);
    }
    t
}

fn dh_toml(name: &str, rows: &[Dh]) -> String {
    let mut s = format!("name = \"{name}\"\nconvention = \"dh\"\n");
    for (i, r) in rows.iter().enumerate() {
        s.push_str(&format!(
            "\n[[joint]]\ntype = \"revolute\"\ntheta = \"q{}\"\nd = \"{}\"\na = \"{}\"\nalpha = \"{}\"\n",
            i + 1,
            r.d,
            r.a,
            r.alpha.0
        ));
    }
    s
}

fn derive(name: &str, rows: &[Dh], method: IkMethod) -> IkSolution {
    let text = dh_toml(name, rows);
    let robot = dqsym::parse_robot(&text, name, &dqsym::eval_scalar_text).expect("robot");
    let sol =
        solve(&robot, &IkOptions { free: None, method }).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(sol.general.is_some(), "{name}: {}", sol.family);
    sol
}

/// The largest angle difference on the circle.
fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            let d = (x - y).rem_euclid(2.0 * PI);
            d.min(2.0 * PI - d)
        })
        .fold(0.0, f64::max)
}

/// The largest deviation of `got` from `want`: rotation entries, positions over `len`.
fn deviation(want: &M4, got: &M4, len: f64) -> f64 {
    let mut d: f64 = 0.0;
    for r in 0..3 {
        for c in 0..4 {
            let e = (want[r][c] - got[r][c]).abs();
            d = d.max(if c == 3 { e / len } else { e });
        }
    }
    d
}

fn size(rows: &[Dh]) -> f64 {
    rows.iter().map(|r| r.d.abs() + r.a.abs()).sum()
}

/// The model of an arm whose six solved joints are `q`: its DH rows, the first at the fixed
/// angle `free` when there is one (a 7R arm with its free joint as a parameter).
#[derive(Clone, Copy)]
struct Model<'a> {
    rows: &'a [Dh],
    free: Option<f64>,
}

impl Model<'_> {
    fn pose(&self, q: &[f64]) -> M4 {
        let all: Vec<f64> = self.free.iter().chain(q).copied().collect();
        dh_pose(self.rows, &all)
    }
}

/// Random configurations, and the poses as lines of 16 numbers (row-major, `{:e}` reads back
/// exactly).
fn poses(m: Model, n: usize, seed: u64) -> (Vec<Vec<f64>>, String) {
    let mut rng = Rng::new(seed);
    let qs: Vec<Vec<f64>> = (0..n)
        .map(|_| (0..6).map(|_| rng.range(-PI, PI)).collect())
        .collect();
    let input = qs
        .iter()
        .map(|q| {
            let v: Vec<String> = m
                .pose(q)
                .iter()
                .flatten()
                .map(|x| format!("{x:e}"))
                .collect();
            v.join(" ") + "\n"
        })
        .collect();
    (qs, input)
}

/// Solutions of one set are more than `SAME_TOL = 1e-6` apart (the core merges closer ones),
/// so pairing within half of it is unambiguous: a port's solution within `MATCH` of a
/// reference solution is that solution, and not another of the set. (A port that computes as
/// the reference does lands within rounding of it; the largest distance seen is printed.)
const MATCH: f64 = 0.5e-6;

/// Reads one pose's solutions (`n`, then `n` lines `q1 .. q6 approximate residual`) from a
/// port's output and checks them against the reference; returns the largest distance of a
/// paired solution.
fn check_port(
    port: &str,
    name: &str,
    m: Model,
    q: &[f64],
    reference: &[NumSolution],
    lines: &mut std::str::Lines,
) -> f64 {
    let t = m.pose(q);
    let len = size(m.rows);
    let n: usize = lines.next().expect("count").parse().expect("n");
    let got: Vec<Vec<f64>> = (0..n)
        .map(|_| {
            lines
                .next()
                .expect("row")
                .split_whitespace()
                .map(|x| x.parse().expect("number"))
                .collect()
        })
        .collect();
    assert_eq!(
        n,
        reference.len(),
        "{port} {name} at {q:?}: {got:?} vs {reference:?}"
    );
    let mut most: f64 = 0.0;
    for r in reference {
        let g = got
            .iter()
            .find(|g| dist(&g[..6], &r.q) <= MATCH)
            .unwrap_or_else(|| panic!("{port} {name}: {:?} not among {got:?} at {q:?}", r.q));
        assert_eq!(g[6] != 0.0, r.approximate, "{port} {name}: flag of {g:?}");
        most = most.max(dist(&g[..6], &r.q));
    }
    for g in got.iter().filter(|g| g[6] == 0.0) {
        let dev = deviation(&t, &m.pose(&g[..6]), len);
        assert!(dev <= 1e-9, "{port} {name}: {g:?} misses the pose by {dev}");
    }
    assert!(
        got.iter().any(|g| g[6] == 0.0 && dist(&g[..6], q) <= 1e-6),
        "{port} {name}: {q:?} not among {got:?}"
    );
    most
}

const C_MAIN: &str = r#"
#include <stdio.h>
#include <time.h>

int main(void) {
    static double ts[1000][4][4];
    int n = 0, i, k, rep, total = 0;
    clock_t start;
    while (n < 1000) {
        for (i = 0; i < 16; i++)
            if (scanf("%lf", &ts[n][i / 4][i % 4]) != 1) break;
        if (i < 16) break;
        n++;
    }
    for (k = 0; k < n; k++) {
        ik_solutions s;
        ik((const double (*)[4])ts[k]ARGS, &s);
        printf("%d\n", s.n);
        for (i = 0; i < s.n; i++) {
            int j;
            for (j = 0; j < 6; j++) printf("%.17g ", s.q[i][j]);
            printf("%d %.17g\n", s.approximate[i], s.residual[i]);
        }
    }
    start = clock();
    for (rep = 0; rep < 5; rep++) {
        for (k = 0; k < n; k++) {
            ik_solutions s;
            ik((const double (*)[4])ts[k]ARGS, &s);
            total += s.n;
        }
    }
    printf("time %g %d\n", 1e6 * (double)(clock() - start) / CLOCKS_PER_SEC / (5.0 * n), total);
    return 0;
}
"#;

/// Compiles the C solver `code` with a main that reads poses and calls `ik(T{args}, &s)`
/// (`gcc -std=c99 -pedantic -Wall -Wextra -Werror -O2`), runs it on `input` and returns its
/// output.
fn run_c(tag: &str, code: &str, args: &str, input: &str) -> String {
    let dir = crate::tools::temp_dir(&format!("ik-general-c-{tag}"));
    let src = dir.join("ik.c");
    let exe = dir.join("ik");
    std::fs::write(&src, format!("{code}{}", C_MAIN.replace("ARGS", args))).expect("write");
    let mut gcc = Command::new("gcc");
    gcc.args([
        "-std=c99",
        "-pedantic",
        "-Wall",
        "-Wextra",
        "-Werror",
        "-O2",
        "-o",
    ])
    .arg(&exe)
    .arg(&src)
    .arg("-lm");
    crate::tools::run(
        gcc,
        "",
        &format!("gcc -Werror on the general solver of {tag}"),
    );
    crate::tools::run(Command::new(&exe), input, "generated C ik")
}

/// Checks a port's output for the poses of `qs` against the reference at `params`; prints its
/// time line.
fn check_output(
    port: &str,
    name: &str,
    m: Model,
    sol: &IkSolution,
    params: &[(&str, f64)],
    qs: &[Vec<f64>],
    out: &str,
) {
    let mut lines = out.lines();
    let mut most: f64 = 0.0;
    for q in qs {
        let reference = sol.solve_numeric(&m.pose(q), params).expect("reference");
        most = most.max(check_port(port, name, m, q, &reference, &mut lines));
    }
    let time = lines.next().expect("time line");
    eprintln!(
        "{port} general solver, {name}: {time} (us per pose, solutions); largest distance to the reference {most:e}"
    );
}

/// The generated C solver, compiled clean under `-std=c99 -pedantic -Wall -Wextra -Werror`
/// (`-O2`), returns the reference's solution set at 300 random poses of each arm; its time per
/// pose is printed (not asserted).
#[test]
fn generated_c_solver_agrees_with_the_reference() {
    for (k, (name, rows, method)) in arms().into_iter().enumerate() {
        let sol = derive(name, &rows, method);
        let code = dqsym::ik::ik_c(&sol).expect("C");
        assert!(
            code.contains("ik_gen_solve("),
            "{name}: not the general solver"
        );
        let m = Model {
            rows: &rows,
            free: None,
        };
        let (qs, input) = poses(m, 300, 71 + k as u64);
        let out = run_c(&k.to_string(), &code, "", &input);
        check_output("C", name, m, &sol, &[], &qs, &out);
    }
}

/// The skew arm with its lengths as parameters named after C's names and the solver's own
/// (`int`, `fmax`, `NAN`, `memcpy`, `ik_len`, `t0`) and a joint named `sin`: the C solver
/// renames what it must, compiles clean and solves as the reference does at 100 poses.
#[test]
fn generated_c_solver_with_hostile_names_agrees_with_the_reference() {
    let rows = skew();
    let names = [
        ("int", 0, 'd'),
        ("fmax", 1, 'a'),
        ("memcpy", 2, 'd'),
        ("ik_len", 3, 'd'),
        ("t0", 4, 'd'),
        ("NAN", 4, 'a'),
    ];
    let mut text = dh_toml("hostile", &rows);
    for (i, r) in rows.iter().enumerate() {
        let mut block = format!("theta = \"q{}\"\nd = \"{}\"\na = \"{}\"\n", i + 1, r.d, r.a);
        let fresh = block.clone();
        for (n, j, field) in names {
            if j == i {
                let old = format!("{field} = \"{}\"", if field == 'd' { r.d } else { r.a });
                block = block.replace(&old, &format!("{field} = \"{n}\""));
            }
        }
        if i == 5 {
            block = block.replace("theta = \"q6\"", "theta = \"sin\"");
        }
        text = text.replace(&fresh, &block);
    }
    let robot = dqsym::parse_robot(&text, "hostile", &dqsym::eval_scalar_text).expect("robot");
    let sol = solve(&robot, &IkOptions::default()).expect("ik");
    assert!(sol.general.is_some(), "{}", sol.family);
    let value = |n: &str| {
        let (_, j, field) = names.iter().find(|(m, _, _)| *m == n).expect("a parameter");
        if *field == 'd' {
            rows[*j].d
        } else {
            rows[*j].a
        }
    };
    assert_eq!(sol.params.len(), names.len(), "{:?}", sol.params);
    let params: Vec<(&str, f64)> = sol.params.iter().map(|p| (p.as_str(), value(p))).collect();
    let args: String = params.iter().map(|(_, v)| format!(", {v:e}")).collect();
    let code = dqsym::ik::ik_c(&sol).expect("C");
    for renamed in [
        "double int_",
        "double fmax_",
        "double NAN_",
        "double ik_len_",
    ] {
        assert!(code.contains(renamed), "{renamed} missing");
    }
    let m = Model {
        rows: &rows,
        free: None,
    };
    let (qs, input) = poses(m, 100, 79);
    let out = run_c("hostile", &code, &args, &input);
    check_output("C", "hostile", m, &sol, &params, &qs, &out);
}

/// The IK page of `file` written by `dqsym walk --ik --html` (extra arguments `args`); returns
/// its text.
pub(crate) fn ik_page(file: &Path, page: &Path, args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .arg("walk")
        .arg(file)
        .args(["--ik", "--html"])
        .arg(page)
        .args(args)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "dqsym walk --ik --html {}: {}",
        file.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::read_to_string(page).expect("page")
}

/// The page's solver script without its driver (the part that reads the document): the chain,
/// the IK data, the helpers and the general method's core.
pub(crate) fn page_solver(html: &str) -> String {
    let script = html
        .split("<script>")
        .filter_map(|s| s.split("</script>").next())
        .find(|s| s.contains("function dqsym_ik_chain("))
        .expect("the IK script");
    assert!(
        script.contains("\"general\":true"),
        "not the general method"
    );
    let at = script
        .find("function ik_general(")
        .expect("the general method's driver");
    let end = at
        + script[at..]
            .find("\n(function () {")
            .expect("the page's driver");
    script[..end].to_string()
}

const NODE_MAIN: &str = r#"
const lines = require("fs").readFileSync(0, "utf8").trim().split("\n");
const ch = dqsym_ik_chain();
const ax = IK.kinds.map((k, i) => [k].concat([0, 1, 2, 3, 4, 5].map((j) => ch[`ax${i}_${j}`])));
const home = [0, 1, 2].map((r) => [0, 1, 2, 3].map((c) => ch[`home${r}${c}`]));
const ts = lines.map((l) => {
    const v = l.split(" ").map(Number);
    return [0, 1, 2, 3].map((r) => v.slice(4 * r, 4 * r + 4));
});
let out = "";
for (const T of ts) {
    const sols = ik_general(ax, home, T);
    out += sols.length + "\n";
    for (const [q, , ap, res] of sols) out += q.map(String).join(" ") + " " + (ap ? 1 : 0) + " " + res + "\n";
}
const start = process.hrtime.bigint();
let total = 0;
for (const T of ts) total += ik_general(ax, home, T).length;
out += `time ${Number(process.hrtime.bigint() - start) / 1e3 / ts.length} ${total}\n`;
process.stdout.write(out);
"#;

/// The IK page's JavaScript for arms solved by the general method (the page's own script: its
/// chain, helpers and `core.js`), run with node, returns the reference's solution set at 300
/// random poses of each arm.
#[test]
fn page_javascript_solver_agrees_with_the_reference() {
    for (k, (name, rows, method)) in arms().into_iter().enumerate() {
        if method != IkMethod::Auto {
            // `walk --ik` takes the method `dqsym ik` picks: the PUMA keeps its family there,
            // so its general solver's JavaScript is checked through the library below.
            continue;
        }
        let sol = derive(name, &rows, method);
        let dir = crate::tools::temp_dir(&format!("ik-general-js-{k}"));
        let file = dir.join("arm.toml");
        std::fs::write(&file, dh_toml(name, &rows)).expect("write");
        // The skew arm's drawing needs more than the default work budget.
        let html = ik_page(
            &file,
            &dir.join("page.html"),
            &["--work-budget", "100000000"],
        );
        let script = format!("{}{NODE_MAIN}", page_solver(&html));
        run_node_check(name, &rows, None, &sol, &script, 81 + k as u64);
    }
    // The PUMA through --method general: the same pieces the page puts together.
    let (name, rows, method) = arms().pop().expect("puma");
    let sol = derive(name, &rows, method);
    let chain = js_chain(&sol);
    let script = format!(
        "{chain}{}{}{NODE_MAIN}",
        dqsym::ik::ik_javascript_helpers(&sol),
        dqsym::ik::ik_javascript_general(&sol)
    );
    run_node_check(name, &rows, None, &sol, &script, 89);
}

/// `dqsym_ik_chain()` and `IK` as the page defines them, for an arm without parameters, from
/// its axes, their kinds and its home pose evaluated by the library.
pub(crate) fn js_chain(sol: &IkSolution) -> String {
    let num = |x: &dqsym::Scalar| {
        x.eval(&|_: &str| None)
            .unwrap_or_else(|e| panic!("a numeric axis entry: {e}"))
    };
    let mut entries = Vec::new();
    for (i, a) in sol.axes.iter().enumerate() {
        for (k, x) in a.dir.iter().chain(&a.point).enumerate() {
            entries.push(format!("ax{i}_{k}: {:e}", num(x)));
        }
    }
    for (r, row) in sol.home.rows.iter().take(3).enumerate() {
        for (c, x) in row.iter().enumerate() {
            entries.push(format!("home{r}{c}: {:e}", num(x)));
        }
    }
    let kinds: Vec<&str> = sol
        .axes
        .iter()
        .map(|a| {
            if a.kind == dqsym::JointKind::Prismatic {
                "1"
            } else {
                "0"
            }
        })
        .collect();
    format!(
        "function dqsym_ik_chain() {{ return {{{}}}; }}\nconst IK = {{ kinds: [{}] }};\n",
        entries.join(", "),
        kinds.join(", ")
    )
}

/// Runs `script` (the page's solver and [`NODE_MAIN`]) with node on 300 random poses of `rows`
/// (the first joint at `free` when given) and checks its output against the reference.
fn run_node_check(
    name: &str,
    rows: &[Dh],
    free: Option<f64>,
    sol: &IkSolution,
    script: &str,
    seed: u64,
) {
    let m = Model { rows, free };
    let (qs, input) = poses(m, 300, seed);
    let mut node = Command::new("node");
    node.args(["-e", script]);
    let out = crate::tools::run(node, &input, &format!("node on the page solver of {name}"));
    let params: Vec<(&str, f64)> = sol
        .free
        .iter()
        .zip(free)
        .map(|(n, v)| (n.as_str(), v))
        .collect();
    check_output("page JavaScript", name, m, sol, &params, &qs, &out);
}

/// The IK page of the Jaco-style arm in Chromium (the page driver of `walk.rs`'s page test):
/// with the sliders at a configuration, the live table lists the reference's solutions, each
/// reproducing the pose by the model here, the sliders' configuration among them, and the
/// page reports no script error.
#[test]
fn ik_page_of_a_general_arm_lists_every_solution_in_chromium() {
    let chromium = crate::tools::chromium();
    assert!(
        Path::new(ROOT)
            .join("node_modules/playwright-core")
            .is_dir(),
        "playwright-core is missing (node_modules/playwright-core): run `bash scripts/test.sh`"
    );
    let rows = jaco();
    let sol = derive("jaco", &rows, IkMethod::Auto);
    let dir = crate::tools::temp_dir("ik-general-page");
    let file = dir.join("jaco.toml");
    std::fs::write(&file, dh_toml("jaco", &rows)).expect("write");
    let page = dir.join("page.html");
    ik_page(&file, &page, &[]);
    let mut rng = Rng::new(91);
    let q: Vec<f64> = (0..6).map(|_| rng.range(-PI, PI)).collect();
    let values: serde_json::Map<String, serde_json::Value> = q
        .iter()
        .enumerate()
        .map(|(i, v)| (format!("q{}", i + 1), serde_json::json!(v)))
        .collect();
    let url = format!("file://{}", page.display());
    let spec = serde_json::json!([{"url": url, "shots": dir.join("shot").display().to_string(),
        "values": values, "ik": true}]);
    let spec_file = dir.join("jobs.json");
    std::fs::write(&spec_file, spec.to_string()).expect("jobs");
    let mut node = Command::new("node");
    node.arg(Path::new(ROOT).join("tests/it/walk_page.js"))
        .arg(&spec_file)
        .env("CHROMIUM", &chromium)
        .current_dir(ROOT);
    let text = crate::tools::run(node, "", "playwright on the general IK page");
    let r: serde_json::Value = serde_json::from_str(&text).expect("json from the page");
    let len = size(&rows);
    for width in ["390", "1600"] {
        let moved = &r[&url][width]["moved"];
        assert_eq!(
            r[&url][width]["problems"],
            serde_json::json!([]),
            "{width}: {}",
            r[&url][width]["problems"]
        );
        let at: Vec<f64> = (1..=6)
            .map(|i| moved["sliders"][format!("q{i}")].as_f64().expect("slider"))
            .collect();
        let t = dh_pose(&rows, &at);
        let reference = sol.solve_numeric(&t, &[]).expect("reference");
        let shown: Vec<Vec<f64>> = moved["ik"]
            .as_array()
            .expect("rows")
            .iter()
            .map(|row| {
                row["q"]
                    .as_array()
                    .expect("q")
                    .iter()
                    .map(|x| x.as_f64().expect("number"))
                    .collect()
            })
            .collect();
        assert_eq!(
            shown.len(),
            reference.len(),
            "{width}: {shown:?} vs {reference:?}"
        );
        for s in &reference {
            assert!(
                shown.iter().any(|g| dist(g, &s.q) <= MATCH),
                "{width}: {:?} not in the page's table {shown:?}",
                s.q
            );
            if !s.approximate {
                let g = shown.iter().find(|g| dist(g, &s.q) <= MATCH).expect("row");
                let dev = deviation(&t, &dh_pose(&rows, g), len);
                assert!(dev <= 1e-9, "{width}: the page's {g:?} misses by {dev}");
            }
        }
        assert!(
            shown.iter().any(|g| dist(g, &at) <= 1e-6),
            "{width}: the sliders' {at:?} not among {shown:?}"
        );
    }
}

/// A skew 7R arm (no family for any free joint): the first joint is the free parameter, the
/// other six are solved by the general method.
fn skew7() -> Vec<Dh> {
    (0..7)
        .map(|i| dh(0.1 + 0.05 * f64::from(i), 0.2, A60))
        .collect()
}

/// The 7R arm's C solver takes the free joint as a parameter (`ik(T, q1, &s)`) and returns the
/// reference's solution set at 200 poses with `q1 = 0.7`; so does the IK page's JavaScript,
/// whose `dqsym_ik_chain(q1)` reads the free joint's slider.
#[test]
fn seven_joint_arm_with_a_free_joint_in_c_and_on_the_page() {
    let rows = skew7();
    let free = 0.7;
    let text = dh_toml("skew 7R", &rows);
    let robot = dqsym::parse_robot(&text, "skew 7R", &dqsym::eval_scalar_text).expect("robot");
    let sol = solve(&robot, &IkOptions::default()).expect("7R");
    assert!(sol.general.is_some(), "{}", sol.family);
    assert_eq!(sol.free.as_deref(), Some("q1"));
    assert_eq!(sol.params, ["q1"]);
    let m = Model {
        rows: &rows,
        free: Some(free),
    };
    let (qs, input) = poses(m, 200, 97);
    let out = run_c(
        "7r",
        &dqsym::ik::ik_c(&sol).expect("C"),
        &format!(", {free:e}"),
        &input,
    );
    check_output("C", "skew 7R", m, &sol, &[("q1", free)], &qs, &out);
    let dir = crate::tools::temp_dir("ik-general-js-7r");
    let file = dir.join("arm.toml");
    std::fs::write(&file, &text).expect("write");
    let html = ik_page(
        &file,
        &dir.join("page.html"),
        &["--work-budget", "100000000"],
    );
    let script = format!(
        "{}{}",
        page_solver(&html),
        NODE_MAIN.replace("dqsym_ik_chain()", &format!("dqsym_ik_chain({free:e})"))
    );
    run_node_check("skew 7R", &rows, Some(free), &sol, &script, 98);
}
