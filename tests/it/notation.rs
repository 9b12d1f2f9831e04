//! Notation that never collides: every example robot, with its joint variables renamed in every
//! style people and URDF exporters use (`q1`, `q_1`, `joint_a1`, `shoulder_pan_joint`, `theta1`)
//! and in the letters of the reports' own notation (`T`, `p_1`, `J`, `w2`, `x`, `r13`, ...),
//! through `fk --format latex` and the walkthrough's Markdown, every formula rendered by KaTeX
//! (no error), and no report entry named with the letter of a robot symbol.

use crate::tools::katex_all;
use dqsym::{
    emit::latex_symbol, eval_scalar_text, fk_report, parse_robot, walk_markdown, walk_robot,
    FkOptions, Format, Robot,
};
use std::collections::BTreeSet;

/// URDF-style joint names (the UR5's and beyond).
const URDF: [&str; 8] = [
    "shoulder_pan_joint",
    "shoulder_lift_joint",
    "elbow_joint",
    "wrist_1_joint",
    "wrist_2_joint",
    "wrist_3_joint",
    "flange_joint",
    "tool_joint",
];

/// The name of joint `i` (from 1) in each style.
fn styled(style: usize, i: usize) -> String {
    match style {
        0 => format!("q{i}"),
        1 => format!("q_{i}"),
        2 => format!("joint_a{i}"),
        3 => URDF[i - 1].to_owned(),
        4 => format!("theta{i}"),
        // The letters the reports name their own entries with (`T`, `p`, `J`, `x` ... `w`
        // components, `r13` rotation entries), bare and with an index.
        _ => COMPONENT_LETTERS[i - 1].to_owned(),
    }
}
const STYLES: usize = 6;

/// Joint names taken from the report's own notation.
const COMPONENT_LETTERS: [&str; 8] = ["T", "p_1", "J", "w2", "x", "r13", "dq", "y_0"];

/// `text` with every identifier equal to a key of `map` replaced by its value.
fn rename(text: &str, map: &[(String, String)]) -> String {
    let mut out = String::new();
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        let w = std::mem::take(word);
        match map.iter().find(|(a, _)| *a == w) {
            Some((_, b)) => out.push_str(b),
            None => out.push_str(&w),
        }
    };
    for c in text.chars() {
        if c.is_ascii_alphanumeric() || c == '_' {
            word.push(c);
        } else {
            flush(&mut word, &mut out);
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
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

/// The `aligned` blocks of a LaTeX report, and the names its rows define (`x_{0}`).
fn latex_blocks(tex: &str) -> (Vec<String>, Vec<String>) {
    let mut blocks = Vec::new();
    let mut names = Vec::new();
    let mut cur: Option<String> = None;
    for line in tex.lines() {
        if line.starts_with("\\begin{aligned}") {
            cur = Some(String::new());
        }
        if let Some(c) = cur.as_mut() {
            c.push_str(line);
            c.push('\n');
            if let Some((name, _)) = line.split_once(" &= ") {
                names.push(name.trim_start_matches("\\begin{aligned}").to_owned());
            }
        }
        if line.starts_with("\\end{aligned}") {
            blocks.extend(cur.take());
        }
    }
    (blocks, names)
}

/// The LaTeX bases of a robot's symbols: `q` of `q_{1}`, `\mathit{joint}` of `joint_a1`.
fn bases(r: &Robot) -> BTreeSet<String> {
    r.variables
        .iter()
        .cloned()
        .chain(r.parameters())
        .map(|n| {
            let t = latex_symbol(&n);
            t.split("_{").next().unwrap_or_default().to_owned()
        })
        .collect()
}

fn robot_files() -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots");
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("examples/robots")
        .map(|e| e.expect("entry").path().display().to_string())
        .filter(|p| p.ends_with(".toml"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_example_robot_in_every_name_style_renders_in_katex_without_collisions() {
    let files = robot_files();
    assert!(files.len() >= 15, "{files:?}");
    let (mut reports, mut walks) = (0, 0);
    // Every formula of every report and page, rendered by KaTeX at the end in one run (an
    // error names the formula).
    let mut all: Vec<String> = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).expect("robot file");
        let original = parse_robot(&text, file, &eval_scalar_text).expect("robot");
        // A 7-joint walkthrough takes seconds in a debug build: those are walked in their own
        // names (the Franka's and the LWR's `q`), every other robot in every style.
        let heavy = original.variables.len() > 6 || file.ends_with("puma_like.toml");
        for style in 0..STYLES {
            let map: Vec<(String, String)> = original
                .variables
                .iter()
                .enumerate()
                .map(|(i, v)| (v.clone(), styled(style, i + 1)))
                .collect();
            let renamed = rename(&text, &map);
            let r = parse_robot(&renamed, file, &eval_scalar_text)
                .unwrap_or_else(|e| panic!("{file} style {style}: {e}"));
            assert_eq!(
                r.variables,
                map.iter().map(|(_, b)| b.clone()).collect::<Vec<_>>()
            );
            let o = FkOptions {
                format: Format::Latex,
                ..FkOptions::default()
            };
            let tex = fk_report(&r, &o).expect("report");
            let (blocks, names) = latex_blocks(&tex);
            assert!(blocks.len() >= 2, "{file}: {tex}");
            let taken = bases(&r);
            for n in &names {
                let base = n.split(['_', '^']).next().unwrap_or_default();
                assert!(
                    !taken.contains(base),
                    "{file} style {style}: entry `{n}` is named like a symbol of the robot ({taken:?})"
                );
            }
            all.extend(blocks);
            reports += 1;
            if heavy && style != 0 {
                continue;
            }
            let w = walk_robot(&renamed, file, &eval_scalar_text).expect("walkthrough");
            let md = walk_markdown(&w).expect("markdown");
            let f = formulas(&md);
            assert!(f.len() > 5, "{file}: {} formulas", f.len());
            all.extend(f);
            walks += 1;
        }
    }
    all.sort();
    all.dedup();
    katex_all(
        &all,
        "fk --format latex and walkthroughs of every example robot in every name style",
    );
    assert_eq!(reports, files.len() * STYLES);
    assert!(walks >= (files.len() - 5) * STYLES, "{walks} walkthroughs");
}
