//! Teaching walkthroughs (`dqsym walk`): snapshots of the text and Markdown of the paper's
//! Appendix III RRR arm and sec 6.3 6R robot, their LaTeX through KaTeX, the numeric check,
//! and the web page rendered in headless Chromium.

use crate::common::snapshot_settings;
use crate::tools::katex_all;
use dqsym::{
    closed_form, closed_form_traced, walk_markdown, walk_robot, walk_script, walk_text, Scalar,
    Step, TraceStep, Walkthrough,
};
use std::path::{Path, PathBuf};
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
         l3 c12 c3 - l3 s12 s3 = l3 c123"
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
    assert!(t.contains("l1 c1 + l2 c12 + l3 c123"), "{t}");
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

fn chromium() -> PathBuf {
    let found = std::env::var_os("PATH").and_then(|p| {
        std::env::split_paths(&p)
            .map(|d| d.join("chromium"))
            .find(|c| c.is_file())
    });
    found.unwrap_or_else(|| {
        panic!("chromium is missing: run `bash scripts/test.sh`, which installs Debian's chromium")
    })
}

fn headless(out: &Path) -> Command {
    let profile = crate::tools::temp_dir(&format!(
        "chromium-{}",
        out.file_name().and_then(|n| n.to_str()).unwrap_or("x")
    ));
    let mut c = Command::new(chromium());
    c.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-background-networking",
        "--no-first-run",
        "--disable-component-update",
        "--disable-sync",
    ])
    .arg(format!("--user-data-dir={}", profile.display()));
    c
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
