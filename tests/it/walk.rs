//! Teaching walkthroughs (`dqsym walk`): snapshots of the text and Markdown of the paper's
//! Appendix III RRR arm and sec 6.3 6R robot, their LaTeX through KaTeX, the numeric check,
//! and the web page rendered in headless Chromium.

use crate::common::snapshot_settings;
use crate::tools::{chromium, headless, katex_all};
use dqsym::Matrix4;
use dqsym::{
    closed::{closed_form_traced, TraceStep},
    closed_form,
    walk::Step,
    walk_markdown, walk_robot, walk_script, walk_text, Scalar, Walkthrough,
};
use std::path::Path;
use std::process::Command;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn walk(file: &str) -> Walkthrough {
    let src = std::fs::read_to_string(Path::new(ROOT).join(file)).expect("example");
    walk_script(&src, file).expect("walkthrough")
}

#[test]
fn appendix3_rrr_text_walkthrough() {
    let text = walk_text(&walk("examples/appendix3_rrr.dq")).expect("text");
    assert!(text.contains(
        "Factor dq3: rotation of theta3 about the x-parallel axis through (0, l1 + l2, 0)"
    ));
    assert!(text.contains(
        "cos a cos b - sin a sin b = cos(a + b), a = theta1 + theta2, b = theta3, terms 3 and 4: \
         l3 C12 C3 - l3 S12 S3 = l3 C123"
    ));
    snapshot_settings().bind(|| insta::assert_snapshot!("walk_appendix3_rrr_text", text));
}

#[test]
fn appendix3_rrr_markdown_walkthrough() {
    let md = walk_markdown(&walk("examples/appendix3_rrr.dq")).expect("markdown");
    snapshot_settings().bind(|| insta::assert_snapshot!("walk_appendix3_rrr_markdown", md));
}

#[test]
fn sec6_3_6r_text_walkthrough() {
    let text = walk_text(&walk("examples/sec6_3_6r.dq")).expect("text");
    assert!(text.contains(
        "Factor qd5: rotation of theta5 about the z-parallel axis through (0, l1 + l2 + l3, 0)"
    ));
    snapshot_settings().bind(|| insta::assert_snapshot!("walk_sec6_3_6r_text", text));
}

#[test]
fn sec6_3_6r_markdown_walkthrough() {
    let md = walk_markdown(&walk("examples/sec6_3_6r.dq")).expect("markdown");
    snapshot_settings().bind(|| insta::assert_snapshot!("walk_sec6_3_6r_markdown", md));
}

/// Every `$...$` and `$$...$$` formula of a Markdown text.
fn formulas(md: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (i, block) in md.split("$$").enumerate() {
        if i % 2 == 1 {
            out.push(block.trim().to_owned());
        } else {
            out.extend(
                block
                    .split('$')
                    .enumerate()
                    .filter(|(k, _)| k % 2 == 1)
                    .map(|(_, f)| f.to_owned()),
            );
        }
    }
    out
}

#[test]
fn markdown_walkthroughs_render_in_katex() {
    for file in [
        "examples/appendix3_rrr.dq",
        "examples/sec6_3_6r.dq",
        "examples/sec6_4_puma_like.dq",
        "examples/twists.dq",
    ] {
        let md = walk_markdown(&walk(file)).expect("markdown");
        let f = formulas(&md);
        assert!(f.len() > 20, "{file}: only {} formulas", f.len());
        katex_all(&f, file);
    }
    let puma = std::fs::read_to_string(Path::new(ROOT).join("examples/robots/puma560.toml"))
        .expect("robot");
    let w = walk_robot(&puma, "puma560.toml", &dqsym::eval_scalar_text).expect("walk");
    katex_all(&formulas(&walk_markdown(&w).expect("markdown")), "PUMA 560");
    // The Puma-like robot's tool point expands to sums of 17 terms: folded, not dropped.
    let text = std::fs::read_to_string(Path::new(ROOT).join("examples/robots/puma_like.toml"))
        .expect("robot");
    let w = walk_robot(&text, "puma_like.toml", &dqsym::eval_scalar_text).expect("walk");
    let md = walk_markdown(&w).expect("markdown");
    assert!(
        md.contains("<details><summary>expanded sum, terms numbered: 17 terms"),
        "{md}"
    );
    assert!(md.contains("}_{17}"), "the folded sum keeps every term");
    katex_all(&formulas(&md), "Puma-like robot");
}

fn checks(w: &Walkthrough) -> Vec<f64> {
    w.steps
        .iter()
        .filter_map(|s| match s {
            Step::Check { max_deviation, .. } => Some(*max_deviation),
            _ => None,
        })
        .collect()
}

#[test]
fn every_walkthrough_ends_with_a_passing_matrix_check() {
    for file in ["examples/appendix3_rrr.dq", "examples/sec6_3_6r.dq"] {
        let c = checks(&walk(file));
        assert_eq!(c.len(), 1, "{file}");
        assert!(c[0] < 1e-12, "{file}: {c:?}");
    }
    for robot in [
        "rrr",
        "six_r",
        "puma560",
        "scara",
        "stanford",
        "ur5",
        "kuka_iiwa7",
    ] {
        let path = format!("examples/robots/{robot}.toml");
        let text = std::fs::read_to_string(Path::new(ROOT).join(&path)).expect("robot");
        let w = walk_robot(&text, &path, &dqsym::eval_scalar_text).expect("walk");
        let c = checks(&w);
        assert_eq!(c.len(), 2, "{robot}");
        assert!(c.iter().all(|d| *d < 1e-9), "{robot}: {c:?}");
    }
}

#[test]
fn robot_file_walkthrough_describes_each_joint_in_words() {
    let text =
        std::fs::read_to_string(Path::new(ROOT).join("examples/robots/rrr.toml")).expect("robot");
    let w = walk_robot(&text, "rrr.toml", &dqsym::eval_scalar_text).expect("walk");
    let t = walk_text(&w).expect("text");
    assert!(
        t.contains(
            "Factor q3: rotation of theta3 about the x-parallel axis through (0, l1 + l2, 0)"
        ),
        "{t}"
    );
    assert!(t.contains("p.y:"), "{t}");
    assert!(t.contains("l1 C1 + l2 C12 + l3 C123"), "{t}");
}

#[test]
fn traced_closed_form_is_the_closed_form_and_its_steps_add_up() {
    let w = walk("examples/sec6_3_6r.dq");
    let mut n = 0;
    for s in &w.steps {
        if let Step::Transform { value, .. } = s {
            let scalars: Vec<Scalar> = match value {
                dqsym::Value::DualQuat(d) => d.dual.vector_part().to_vec(),
                dqsym::Value::Vector(v) => v.to_vec(),
                _ => Vec::new(),
            };
            for x in scalars {
                let (e, steps) = closed_form_traced(&x).expect("traced");
                assert_eq!(e, closed_form(&x).expect("closed"));
                // Each sum equals the input, and each identity's result equals its two terms.
                let mut last: Vec<dqsym::Expr> = Vec::new();
                for s in &steps {
                    match s {
                        TraceStep::Sum { terms, .. } => {
                            let sum = terms.iter().fold(Scalar::int(0), |a, t| a + t.to_scalar());
                            assert_eq!(sum, x);
                            last = terms.clone();
                        }
                        TraceStep::Identity { terms, result, .. } => {
                            let pair =
                                last[terms[0] - 1].to_scalar() + last[terms[1] - 1].to_scalar();
                            assert_eq!(pair, result.to_scalar());
                            n += 1;
                        }
                        _ => {}
                    }
                }
            }
        }
    }
    assert!(n > 20, "only {n} identities");
}

#[test]
fn walk_command_prints_text_and_refuses_a_bad_config() {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["walk", "examples/appendix3_rrr.dq"])
        .current_dir(ROOT)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stdout).contains("Check against 4x4"));
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args([
            "walk",
            "examples/robots/rrr.toml",
            "--html",
            "/dev/null",
            "--config",
            "theta1",
        ])
        .current_dir(ROOT)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--config"));
}

#[test]
fn html_walkthrough_renders_in_headless_chromium() {
    let artifacts = Path::new(ROOT).join("artifacts");
    std::fs::create_dir_all(&artifacts).expect("artifacts dir");
    let page = artifacts.join("walk_rrr.html");
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["walk", "examples/appendix3_rrr.dq", "--html"])
        .arg(&page)
        .current_dir(ROOT)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "dqsym walk --html failed (KaTeX comes from `bash scripts/test.sh`): {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(&page).expect("page");
    assert!(
        !html.contains("http://") || !html.contains("src=\"http"),
        "no network sources"
    );
    assert!(!html.contains("url(fonts/"), "fonts are inlined");
    let url = format!("file://{}", page.display());
    let shot = artifacts.join("walk_rrr.png");
    let _ = std::fs::remove_file(&shot);
    let s = headless(&shot)
        .arg(format!("--screenshot={}", shot.display()))
        .arg("--window-size=1200,2000")
        .arg(&url)
        .output()
        .expect("chromium runs");
    assert!(s.status.success(), "{}", String::from_utf8_lossy(&s.stderr));
    assert!(
        shot.is_file(),
        "no screenshot: {}",
        String::from_utf8_lossy(&s.stderr)
    );
    let d = headless(&artifacts.join("dom"))
        .args(["--virtual-time-budget=5000", "--dump-dom"])
        .arg(&url)
        .output()
        .expect("chromium runs");
    assert!(d.status.success(), "{}", String::from_utf8_lossy(&d.stderr));
    let dom = String::from_utf8_lossy(&d.stdout);
    let rendered = dom.matches("class=\"katex\"").count();
    let formulas = html.matches("data-tex=").count();
    assert!(
        rendered >= formulas && formulas > 50,
        "{rendered} of {formulas} rendered"
    );
    assert!(
        !dom.contains("class=\"katex-error\""),
        "a formula failed in KaTeX"
    );
    assert!(dom.contains("<svg"), "no drawing");
    assert!(dom.contains("class=\"mechanism\""), "no mechanism drawing");
}

/// The product of the mechanism's elementary 4x4 matrices (no dual quaternion code) at `env`,
/// up to motion `upto` (exclusive).
fn chain(
    motions: &[dqsym::walk::Motion],
    upto: usize,
    env: &dyn Fn(&str) -> Option<f64>,
) -> Matrix4<f64> {
    let mut m = Matrix4::identity();
    for x in &motions[..upto] {
        m = m * x
            .matrix(&|s: &dqsym::Sym| env(s.name()))
            .expect("evaluates");
    }
    m
}

/// The inverse of a rigid 4x4 matrix: R^T, -R^T p.
fn rigid_inverse(m: &Matrix4<f64>) -> Matrix4<f64> {
    let r = &m.rows;
    let mut out = Matrix4::identity();
    for (i, row) in out.rows.iter_mut().take(3).enumerate() {
        for (j, x) in row.iter_mut().take(3).enumerate() {
            *x = r[j][i];
        }
        row[3] = -r.iter().take(3).map(|rk| rk[i] * rk[3]).sum::<f64>();
    }
    out
}

fn vec3(v: &serde_json::Value) -> [f64; 3] {
    let a: Vec<f64> = v
        .as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect();
    [a[0], a[1], a[2]]
}

fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + b.abs())
}

/// Label boxes (screen rectangles) that overlap, by index pairs.
fn overlapping(labels: &[[f64; 4]]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for i in 0..labels.len() {
        for j in i + 1..labels.len() {
            let (a, b) = (labels[i], labels[j]);
            if a[0] < b[0] + b[2] - 0.5
                && b[0] < a[0] + a[2] - 0.5
                && a[1] < b[1] + b[3] - 0.5
                && b[1] < a[1] + a[3] - 0.5
            {
                out.push((i, j));
            }
        }
    }
    out
}

/// A page for the browser: `dqsym walk FILE [--ik] --html`, and slider values (a hash of the
/// name, inside each slider's range).
struct PageJob {
    file: String,
    ik: bool,
    url: String,
    shots: std::path::PathBuf,
    values: serde_json::Map<String, serde_json::Value>,
}

fn page_job(file: &str, ik: bool) -> PageJob {
    let artifacts = Path::new(ROOT).join("artifacts");
    std::fs::create_dir_all(&artifacts).expect("artifacts dir");
    let stem = Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .expect("stem")
        .to_owned();
    // `ur5.urdf` beside `ur5.toml`: the URDF's page gets a name of its own.
    let stem = if file.ends_with(".urdf") {
        format!("{stem}_urdf")
    } else {
        stem
    };
    let stem = if ik { format!("ik_{stem}") } else { stem };
    let page = artifacts.join(format!("walk_{stem}.html"));
    let _ = std::fs::remove_file(&page);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_dqsym"));
    cmd.args(["walk", file]);
    if ik {
        cmd.arg("--ik");
    }
    let out = cmd
        .arg("--html")
        .arg(&page)
        .current_dir(ROOT)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "dqsym walk --html {file}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(&page).expect("page");
    assert!(
        html.contains("function dqsym_walk("),
        "{file}: no generated function"
    );
    let names: Vec<String> = html
        .split("data-name=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap_or_default().to_owned())
        .collect();
    assert!(!names.is_empty(), "{file}: no sliders");
    let mut values = serde_json::Map::new();
    for (k, n) in names.iter().enumerate() {
        let joint = html.contains(&format!("data-name=\"{n}\" data-joint"));
        let h = n
            .bytes()
            .fold(7u64, |a, b| a.wrapping_mul(31).wrapping_add(u64::from(b)));
        let u = ((h + k as u64 * 17) % 1000) as f64 / 1000.0;
        let v = if joint { 2.4 * u - 1.2 } else { 0.3 + 0.6 * u };
        let v = if joint {
            v
        } else {
            v.copysign(if html.contains(&format!("data-name=\"{n}\" min=\"-")) {
                -1.0
            } else {
                1.0
            })
        };
        values.insert(n.clone(), serde_json::json!(v));
    }
    PageJob {
        file: file.to_owned(),
        ik,
        url: format!("file://{}", page.display()),
        shots: artifacts.join(format!("walk_{stem}")),
        values,
    }
}

/// The layout at one width: no KaTeX error, every formula rendered, no formula clipped
/// without a scroll container and every scrolling one with its cue, no sideways page scroll,
/// legend and controls text of 12 px or more, labels of 12 px or more on the screen, off one
/// another and off every drawn link, and (IK) the solver's table inside the window.
fn check_layout(job: &PageJob, width: &str, r: &serde_json::Value) {
    let file = &job.file;
    assert_eq!(r["problems"], serde_json::json!([]), "{file} at {width}px");
    assert!(
        job.shots
            .with_file_name(format!(
                "{}-{width}.png",
                job.shots
                    .file_name()
                    .and_then(|s| s.to_str())
                    .expect("name")
            ))
            .is_file(),
        "{file}: no screenshot at {width}px"
    );
    let w: f64 = width.parse().expect("width");
    if !r["orbited"].is_null() {
        // A drag turned the view: the drawing changed, the legend says the new view.
        assert_ne!(
            r["orbited"]["arm"], r["moved"]["arm"],
            "{file} {width}px: dragging the drawing turns the view"
        );
        assert!(
            r["orbited"]["view"]
                .as_str()
                .is_some_and(|v| v.starts_with("view from azimuth")),
            "{file}: {}",
            r["orbited"]["view"]
        );
    }
    for state in ["initial", "home", "moved", "orbited"] {
        let s = &r[state];
        if s.is_null() {
            // Only a drawing that is not planar can be turned.
            continue;
        }
        let at = format!("{file} (ik: {}) {width}px {state}", job.ik);
        assert_eq!(s["katexErrors"], 0, "{at}: KaTeX errors");
        assert_eq!(s["rendered"], s["formulas"], "{at}: every formula renders");
        assert_eq!(
            s["clipped"],
            serde_json::json!([]),
            "{at}: clipped formulas"
        );
        assert_eq!(s["noCue"], 0, "{at}: a formula scrolls without a cue");
        assert!(
            s["pageWidth"].as_f64().expect("width") <= w,
            "{at}: the page scrolls sideways ({} px)",
            s["pageWidth"]
        );
        for f in numbers(&s["fonts"]) {
            assert!(f >= 12.0, "{at}: text of {f} px");
        }
        for f in numbers(&s["labelPx"]) {
            // The label's glyph box on the screen; a 13 px font's digits are about 12 px high.
            assert!(f >= 11.0, "{at}: a joint label {f} px high");
        }
        assert_eq!(
            s["labelHits"],
            serde_json::json!([]),
            "{at}: a joint label crosses a link"
        );
        let labels: Vec<[f64; 4]> = s["labels"]
            .as_array()
            .expect("labels")
            .iter()
            .map(|b| {
                let v = numbers(b);
                [v[0], v[1], v[2], v[3]]
            })
            .collect();
        assert!(
            overlapping(&labels).is_empty(),
            "{at}: joint labels overlap: {:?}",
            overlapping(&labels)
        );
        for t in s["tables"].as_array().expect("tables") {
            assert!(
                t[1].as_f64().expect("right") <= w + 1.0,
                "{at}: table {} ends at {} px",
                t[0],
                t[1]
            );
        }
    }
}

/// The numbers of one width against the mechanism's elementary 4x4 matrices: the sliders,
/// the pose, its dual quaternion, the tool, each joint; on an IK page, each solution's pose
/// against the target, and the sliders' own configuration among the solutions.
fn check_numbers(job: &PageJob, m: &dqsym::walk::Mechanism, r: &serde_json::Value) {
    let file = &job.file;
    let (home, moved) = (&r["home"], &r["moved"]);
    assert_ne!(
        home["arm"], moved["arm"],
        "{file}: moving the sliders redraws the arm"
    );
    assert_ne!(
        home["shown"], moved["shown"],
        "{file}: moving the sliders changes the numbers"
    );
    let at = |state: &serde_json::Value| -> Vec<(String, f64)> {
        state["sliders"]
            .as_object()
            .expect("sliders")
            .iter()
            .map(|(k, v)| (k.clone(), v.as_f64().expect("number")))
            .collect()
    };
    let moved_env = at(moved);
    let home_env = at(home);
    for (n, v) in &moved_env {
        let want = job.values[n].as_f64().expect("number");
        assert!(
            (v - want).abs() < 1e-12,
            "{file}: slider {n} is {v}, set {want}"
        );
    }
    let env_of = |vals: &[(String, f64)]| {
        let vals = vals.to_vec();
        move |n: &str| vals.iter().find(|(k, _)| k == n).map(|(_, v)| *v)
    };
    let (he, me) = (env_of(&home_env), env_of(&moved_env));
    let t = chain(&m.motions, m.motions.len(), &me);
    let page_t = numbers(&moved["numbers"]["T"]);
    for i in 0..4 {
        for j in 0..4 {
            assert!(
                near(page_t[4 * i + j], t.rows[i][j]),
                "{file}: T[{i}][{j}] {} != {}",
                page_t[4 * i + j],
                t.rows[i][j]
            );
        }
    }
    let dq = numbers(&moved["numbers"]["dq"]);
    let q = dqsym::DualQuat::from_real_and_dual(
        dqsym::Quat::new(dq[0], dq[1], dq[2], dq[3]),
        dqsym::Quat::new(dq[4], dq[5], dq[6], dq[7]),
    );
    let qm = q.to_matrix();
    for i in 0..4 {
        for j in 0..4 {
            assert!(
                near(qm.rows[i][j], t.rows[i][j]),
                "{file}: the DQ's matrix [{i}][{j}]"
            );
        }
    }
    let tool_home = match &m.tool {
        Some(p) => [
            p[0].eval(&me).unwrap(),
            p[1].eval(&me).unwrap(),
            p[2].eval(&me).unwrap(),
        ],
        None => [0.0; 3],
    };
    let want_tool = t.transform_point(&tool_home);
    let got_tool = vec3(&moved["tool"]);
    let printed = numbers(&moved["numbers"]["p"]);
    for k in 0..3 {
        assert!(near(got_tool[k], want_tool[k]), "{file}: drawn tool {k}");
        assert!(near(printed[k], want_tool[k]), "{file}: printed tool {k}");
    }
    // Joint k is drawn on the link before it: at F(q) F(0)^-1 applied to its home position.
    let drawn_motions: Vec<usize> = m
        .motions
        .iter()
        .enumerate()
        .filter(|(_, x)| {
            !matches!(x, dqsym::walk::Motion::Translation { .. }) && !x.variables().is_empty()
        })
        .map(|(i, _)| i)
        .collect();
    let hj = home["joints"].as_array().expect("joints");
    let mj = moved["joints"].as_array().expect("joints");
    assert_eq!(
        hj.len(),
        drawn_motions.len(),
        "{file}: one circle per joint"
    );
    for (k, &i) in drawn_motions.iter().enumerate() {
        let f = chain(&m.motions, i, &me) * rigid_inverse(&chain(&m.motions, i, &he));
        let want = f.transform_point(&vec3(&hj[k]));
        let got = vec3(&mj[k]);
        for c in 0..3 {
            assert!(
                near(got[c], want[c]),
                "{file}: joint {} coordinate {c}: {} != {}",
                k + 1,
                got[c],
                want[c]
            );
        }
    }
    if job.ik {
        check_ik_rows(job, m, moved, &moved_env, &t);
    }
}

/// Each solution row of an IK page, put back into the mechanism's 4x4 product, gives the
/// target; the sliders' own joint values are one of the rows (angles modulo a turn).
fn check_ik_rows(
    job: &PageJob,
    m: &dqsym::walk::Mechanism,
    moved: &serde_json::Value,
    env: &[(String, f64)],
    t: &Matrix4<f64>,
) {
    let file = &job.file;
    let rows = moved["ik"].as_array().expect("ik rows");
    assert!(!rows.is_empty(), "{file}: no IK solution on the page");
    // The solved variables: the sliders that are joints, minus a free joint the solver takes
    // as a parameter (its column is absent).
    let joints: Vec<String> = m
        .motions
        .iter()
        .flat_map(|x| x.variables())
        .filter(|v| env.iter().any(|(n, _)| n == v))
        .collect();
    let html = std::fs::read_to_string(job.url.trim_start_matches("file://")).expect("page");
    let vars: Vec<String> = html
        .split("const IK = ")
        .nth(1)
        .and_then(|s| s.split("\"vars\":[").nth(1))
        .and_then(|s| s.split(']').next())
        .expect("IK vars")
        .split(',')
        .map(|v| v.trim_matches('"').to_owned())
        .collect();
    assert!(vars.iter().all(|v| joints.contains(v)), "{file}: {vars:?}");
    let position_only = html.contains("\"position_only\":true");
    let mut own = false;
    for row in rows {
        let q = numbers(&row["q"]);
        let mut at = env.to_vec();
        for (v, x) in vars.iter().zip(&q) {
            at.retain(|(n, _)| n != v);
            at.push((v.clone(), *x));
        }
        let back = chain(&m.motions, m.motions.len(), &move |n: &str| {
            at.iter().find(|(k, _)| k == n).map(|(_, v)| *v)
        });
        for i in 0..3 {
            for j in 0..4 {
                if position_only && j < 3 {
                    continue;
                }
                assert!(
                    (back.rows[i][j] - t.rows[i][j]).abs() < 1e-8,
                    "{file}: IK solution {q:?} gives T[{i}][{j}] = {} for {}",
                    back.rows[i][j],
                    t.rows[i][j]
                );
            }
        }
        own |= vars.iter().zip(&q).all(|(v, x)| {
            let want = env.iter().find(|(n, _)| n == v).expect("slider").1;
            let d = (x - want).abs() % std::f64::consts::TAU;
            d.min(std::f64::consts::TAU - d) < 1e-6
        });
    }
    assert!(
        own,
        "{file}: the sliders' configuration is not among the solutions"
    );
}

#[test]
fn every_example_page_works_at_phone_and_desktop_width_in_chromium() {
    let chromium = chromium();
    assert!(
        Path::new(ROOT)
            .join("node_modules/playwright-core")
            .is_dir(),
        "playwright-core is missing (node_modules/playwright-core): run `bash scripts/test.sh`"
    );
    let mut robots: Vec<String> = std::fs::read_dir(Path::new(ROOT).join("examples/robots"))
        .expect("examples/robots")
        .filter_map(|e| e.ok())
        .map(|e| format!("examples/robots/{}", e.file_name().to_string_lossy()))
        .filter(|p| p.ends_with(".toml"))
        .collect();
    robots.sort();
    let rrr = walk("examples/appendix3_rrr.dq");
    let mut jobs = vec![(
        page_job("examples/appendix3_rrr.dq", false),
        rrr.mechanism.expect("a mechanism"),
    )];
    for file in &robots {
        let text = std::fs::read_to_string(Path::new(ROOT).join(file)).expect("robot");
        let robot = dqsym::parse_robot(&text, file, &dqsym::eval_scalar_text).expect("robot");
        // The mechanism alone (the page's own products are what is checked).
        let m = dqsym::walk::robot_mechanism(&robot);
        jobs.push((page_job(file, false), m.clone()));
        let family = dqsym::ik::IkOptions {
            method: dqsym::ik::IkMethod::Family,
            ..Default::default()
        };
        match dqsym::ik::solve(&robot, &family) {
            Ok(_) => jobs.push((page_job(file, true), m)),
            // A geometry with no closed form has no IK page; the error says so.
            Err(e @ dqsym::ik::IkError::Unsupported { .. }) => {
                assert!(e.to_string().contains("no closed-form"), "{e}")
            }
            Err(e) => panic!("{file}: {e}"),
        }
    }
    // A URDF arm: long joint names in the legend, the sliders and the IK table.
    let urdf = "benches/support/ur5.urdf";
    let text = std::fs::read_to_string(Path::new(ROOT).join(urdf)).expect("urdf");
    let robot = dqsym::parse_urdf(&text, urdf, &dqsym::kin::UrdfOptions::default())
        .expect("urdf")
        .robot;
    let m = dqsym::walk::robot_mechanism(&robot);
    jobs.push((page_job(urdf, false), m.clone()));
    jobs.push((page_job(urdf, true), m));
    assert!(jobs.iter().filter(|(j, _)| j.ik).count() >= 10);
    let spec: Vec<serde_json::Value> = jobs
        .iter()
        .map(|(j, _)| {
            serde_json::json!({"url": j.url, "shots": j.shots.display().to_string(),
                "values": j.values, "ik": j.ik})
        })
        .collect();
    let spec_file = Path::new(ROOT).join("artifacts/walk_pages.json");
    std::fs::write(&spec_file, serde_json::Value::Array(spec).to_string()).expect("jobs");
    let mut node = Command::new("node");
    node.arg(Path::new(ROOT).join("tests/it/walk_page.js"))
        .arg(&spec_file)
        .env("CHROMIUM", &chromium)
        .current_dir(ROOT);
    let text = crate::tools::run(node, "", "playwright on every example page");
    let r: serde_json::Value = serde_json::from_str(&text).expect("json from the pages");
    for (job, m) in &jobs {
        for width in ["390", "1600"] {
            let r = &r[&job.url][width];
            check_layout(job, width, r);
            check_numbers(job, m, r);
        }
    }
}

/// `name="value"` attributes of every element `<tag ... class="class"` in an SVG text.
fn svg_elements<'a>(svg: &'a str, tag: &str, class: &str) -> Vec<&'a str> {
    svg.split(&format!("<{tag} "))
        .skip(1)
        .filter(|e| e.contains(&format!("class=\"{class}\"")))
        .map(|e| e.split('>').next().unwrap_or_default())
        .collect()
}

fn attr(element: &str, name: &str) -> f64 {
    element
        .split(&format!(" {name}=\""))
        .nth(1)
        .and_then(|s| s.split('"').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no numeric {name} in {element}"))
}

#[test]
fn drawings_are_to_scale_with_labels_apart_for_every_example() {
    let mut robots: Vec<String> = std::fs::read_dir(Path::new(ROOT).join("examples/robots"))
        .expect("examples/robots")
        .filter_map(|e| e.ok())
        .map(|e| format!("examples/robots/{}", e.file_name().to_string_lossy()))
        .filter(|p| p.ends_with(".toml"))
        .collect();
    robots.sort();
    assert!(robots.len() >= 8, "{robots:?}");
    let scripts = ["examples/appendix3_rrr.dq", "examples/sec6_3_6r.dq"];
    for file in robots.iter().map(String::as_str).chain(scripts) {
        let w = if file.ends_with(".toml") {
            let text = std::fs::read_to_string(Path::new(ROOT).join(file)).expect("robot");
            walk_robot(&text, file, &dqsym::eval_scalar_text).expect("walk")
        } else {
            walk(file)
        };
        let m = w.mechanism.as_ref().expect("a mechanism");
        let svg = dqsym::walk::mechanism_svg(
            m,
            &dqsym::walk::Config::default(),
            &dqsym::walk::SvgOptions::default(),
        )
        .expect("svg");
        assert!(svg.contains("class=\"base\""), "{file}: no base marker");
        assert!(svg.contains("class=\"triad\""), "{file}: no triad");
        for axis in [">x</text>", ">y</text>", ">z</text>"] {
            assert!(svg.contains(axis), "{file}: the triad names {axis}");
        }
        // Every symbol's value is stated in the legend.
        for s in m.motions.iter().flat_map(|x| x.variables()) {
            assert!(
                svg.contains(&format!("{s} = ")),
                "{file}: the legend omits {s}"
            );
        }
        if file.ends_with(".toml") {
            let text = std::fs::read_to_string(Path::new(ROOT).join(file)).expect("robot");
            if let Some(values) = text.split("[values]").nth(1) {
                for line in values.lines().filter(|l| l.contains('=')) {
                    let (name, v) = line.split_once('=').expect("name = value");
                    let v: f64 = v.trim().parse().expect("a number");
                    let shown = format!("{} = {v}", name.trim());
                    assert!(svg.contains(&shown), "{file}: the legend omits `{shown}`");
                }
            }
        }
        // Labels: boxes of 8 px per digit and 16 px high around their centres, disjoint,
        // and off every joint circle.
        let labels: Vec<[f64; 4]> = svg_elements(&svg, "text", "dq-label")
            .iter()
            .map(|e| {
                let (x, y) = (attr(e, "x"), attr(e, "y"));
                [x - 5.0, y - 7.5, 10.0, 15.0]
            })
            .collect();
        let joints: Vec<(f64, f64)> = svg_elements(&svg, "circle", "dq-joint")
            .iter()
            .map(|e| (attr(e, "cx"), attr(e, "cy")))
            .collect();
        assert_eq!(labels.len(), joints.len(), "{file}: one label per joint");
        assert!(
            overlapping(&labels).is_empty(),
            "{file}: labels overlap: {:?}",
            overlapping(&labels)
        );
        for (i, b) in labels.iter().enumerate() {
            for (k, (x, y)) in joints.iter().enumerate() {
                let inside = b[0] < x + 6.0
                    && x - 6.0 < b[0] + b[2]
                    && b[1] < y + 6.0
                    && y - 6.0 < b[1] + b[3];
                assert!(!inside, "{file}: label {} covers joint {}", i + 1, k + 1);
            }
        }
    }
}

#[test]
fn the_rrr_drawing_has_the_robot_files_proportions() {
    let text =
        std::fs::read_to_string(Path::new(ROOT).join("examples/robots/rrr.toml")).expect("robot");
    let w = walk_robot(&text, "rrr.toml", &dqsym::eval_scalar_text).expect("walk");
    let svg = dqsym::walk::mechanism_svg(
        w.mechanism.as_ref().expect("mechanism"),
        &dqsym::walk::Config::default(),
        &dqsym::walk::SvgOptions::default(),
    )
    .expect("svg");
    // The home pose's links: joints 1 to 3 (joint 1 at the base), tool; l1, l2, l3 as
    // [values] gives them (1, 0.8, 0.5), in one scale.
    let home = svg
        .split("id=\"dq-home\" points=\"")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .expect("home polyline");
    let pts: Vec<(f64, f64)> = home
        .split(' ')
        .map(|p| {
            let (x, y) = p.split_once(',').expect("x,y");
            (x.parse().expect("x"), y.parse().expect("y"))
        })
        .collect();
    let len = |a: (f64, f64), b: (f64, f64)| ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
    let (l1, l2, l3) = (
        len(pts[0], pts[1]),
        len(pts[1], pts[2]),
        len(pts[2], pts[3]),
    );
    assert!(
        (l2 / l1 - 0.8).abs() < 0.01 && (l3 / l1 - 0.5).abs() < 0.01,
        "{pts:?}"
    );
    assert!(
        svg.contains("l1 = 1, l2 = 0.8, l3 = 0.5 (robot file)"),
        "{svg}"
    );
}

#[test]
fn repl_steps_use_the_pages_notation() {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("runs");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(
            b"syms l1\nhalfangle c1, s1 = theta1\nq = (c1, s1, 0, 0) + I*(0, 0, -l1*s1)\n\
              p = q*(1 + I*(0, l1, 0))*cconj(q)\n:steps\n",
        )
        .expect("writes");
    let out = child.wait_with_output().expect("output");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("Notation (each symbol has one meaning on this page):"),
        "{text}"
    );
    assert!(
        text.contains("c1 = cos(theta1/2)") && text.contains("C1 = cos(theta1)"),
        "{text}"
    );
    assert!(text.contains("c1^2 - s1^2 = C1, 2 s1 c1 = S1"), "{text}");
    assert!(!text.contains("where c1 = cos(theta1)"), "{text}");
}

/// The `points="x,y x,y ..."` of an element with the given id.
fn polyline(svg: &str, id: &str) -> Vec<(f64, f64)> {
    svg.split(&format!("id=\"{id}\" points=\""))
        .nth(1)
        .and_then(|s| s.split('"').next())
        .expect("polyline")
        .split(' ')
        .map(|p| {
            let (x, y) = p.split_once(',').expect("x,y");
            (x.parse().expect("x"), y.parse().expect("y"))
        })
        .collect()
}

/// The chosen view shows every link of every example robot at its default configuration at
/// least 0.55 of its true length (the fixed isometric view drew a UR5's upper arm, pointing
/// at the viewer, as a point); the lengths are measured from the drawing against the joints'
/// 3D positions it carries and the scale its legend states.
#[test]
fn no_link_of_an_example_is_drawn_foreshortened() {
    let mut robots: Vec<String> = std::fs::read_dir(Path::new(ROOT).join("examples/robots"))
        .expect("examples/robots")
        .filter_map(|e| e.ok())
        .map(|e| format!("examples/robots/{}", e.file_name().to_string_lossy()))
        .filter(|p| p.ends_with(".toml"))
        .collect();
    robots.sort();
    for file in &robots {
        let text = std::fs::read_to_string(Path::new(ROOT).join(file)).expect("robot");
        let robot = dqsym::parse_robot(&text, file, &dqsym::eval_scalar_text).expect("robot");
        let svg = dqsym::walk::mechanism_svg(
            &dqsym::walk::robot_mechanism(&robot),
            &dqsym::walk::Config::default(),
            &dqsym::walk::SvgOptions::default(),
        )
        .expect("svg");
        let scale: f64 = svg
            .split(", to scale: ")
            .nth(1)
            .and_then(|s| s.split(' ').next())
            .and_then(|s| s.parse().ok())
            .expect("the legend states the scale");
        let mut xyz: Vec<[f64; 3]> = svg_elements(&svg, "circle", "dq-joint")
            .iter()
            .map(|e| {
                let v: Vec<f64> = e
                    .split("data-xyz=\"")
                    .nth(1)
                    .and_then(|s| s.split('"').next())
                    .expect("xyz")
                    .split(',')
                    .map(|x| x.parse().expect("number"))
                    .collect();
                [v[0], v[1], v[2]]
            })
            .collect();
        let tool: Vec<f64> = svg
            .split("id=\"dq-tool\" data-xyz=\"")
            .nth(1)
            .and_then(|s| s.split('"').next())
            .expect("tool")
            .split(',')
            .map(|x| x.parse().expect("number"))
            .collect();
        xyz.push([tool[0], tool[1], tool[2]]);
        let drawn = polyline(&svg, "dq-arm");
        assert_eq!(
            drawn.len(),
            xyz.len(),
            "{file}: one point per joint and the tool"
        );
        let total: f64 = xyz
            .windows(2)
            .map(|w| {
                (0..3)
                    .map(|k| (w[1][k] - w[0][k]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .sum();
        for k in 1..xyz.len() {
            let true_len = (0..3)
                .map(|c| (xyz[k][c] - xyz[k - 1][c]).powi(2))
                .sum::<f64>()
                .sqrt();
            // Links shorter than 2% of the arm are a few pixels whatever the view.
            if true_len < 0.02 * total {
                continue;
            }
            let (a, b) = (drawn[k - 1], drawn[k]);
            let px = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
            // The drawing rounds to 0.1 px.
            let ratio = (px + 0.15) / (true_len * scale);
            assert!(
                ratio >= 0.55,
                "{file}: link {k} drawn at {ratio:.2} of its length"
            );
        }
    }
}

/// Long joint names (as URDF files have) are never cut from the drawing's legend: the legend
/// wraps at the drawing's width between values, and every `name = value` stays whole.
#[test]
fn long_joint_names_wrap_in_the_drawings_legend() {
    let mut text = String::from("name = \"long names\"\nconvention = \"dh\"\n");
    let names: Vec<String> = (1..=6)
        .map(|i| format!("shoulder_and_elbow_revolute_joint_number_{i}"))
        .collect();
    for n in &names {
        text += &format!(
            "[[joint]]\ntype = \"revolute\"\ntheta = \"{n}\"\nd = \"0.1\"\na = \"0.3\"\nalpha = \"pi/2\"\n"
        );
    }
    let w = walk_robot(&text, "long.toml", &dqsym::eval_scalar_text).expect("walk");
    let svg = dqsym::walk::mechanism_svg(
        w.mechanism.as_ref().expect("mechanism"),
        &dqsym::walk::Config::default(),
        &dqsym::walk::SvgOptions::default(),
    )
    .expect("svg");
    let lines: Vec<&str> = svg
        .split("<tspan ")
        .skip(1)
        .map(|s| {
            s.split('>')
                .nth(1)
                .and_then(|t| t.split('<').next())
                .unwrap_or_default()
        })
        .collect();
    for l in &lines {
        // 12 px sans-serif averages under 7 px a character; the text starts 14 px in.
        assert!(
            14.0 + 7.0 * l.chars().count() as f64 <= 600.0,
            "a legend line wider than the drawing: {l}"
        );
    }
    for n in &names {
        assert!(
            lines.iter().any(|l| l.contains(&format!("{n} = "))),
            "{n} is cut from the legend: {lines:?}"
        );
    }
}
