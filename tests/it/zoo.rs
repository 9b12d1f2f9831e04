//! Numeric 10-joint chains at `dqsym fk`'s default settings (term limit 5,000, work budget 3
//! million): RTB's Ball, Coil and Hyper (`examples/robots/rtb/`) and random DH and modified-DH
//! tables each give a report (the expansion or the recurrence), under 100 kB, whose every entry
//! matches the f64 chain of 4x4 matrices and central differences at random points.

use crate::recurrence::check_against_f64_chain;
use crate::robots::load;
use dqsym::{
    app::fk_entries, app::Quantity, eval_scalar_text, fk_report, parse_robot, Context, FkOptions,
    Robot,
};
use std::process::Command;

const RTB: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/rtb/");

/// The options and context of `dqsym fk FILE --jacobian` (with a point, so `p` is checked too).
fn fk_defaults() -> (Context, FkOptions) {
    let ctx = Context::new()
        .with_term_limit(5_000)
        .with_work_budget(3_000_000);
    let o = FkOptions {
        jacobian: true,
        max_terms: 5_000,
        point: Some(dqsym::lang::eval_point_text("1/2, -1, 2").expect("a point")),
        ..FkOptions::default()
    };
    (ctx, o)
}

/// The report and its entries at the default settings, checked numerically; the report's size.
fn check(name: &str, r: &Robot) -> usize {
    let (ctx, o) = fk_defaults();
    let _entered = ctx.enter();
    let text = fk_report(r, &o).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(text.len() <= 100_000, "{name}: {} bytes", text.len());
    let entries = fk_entries(r, &o).unwrap_or_else(|e| panic!("{name}: {e}"));
    let rows: Vec<(Quantity, dqsym::Expr)> = entries.rows().cloned().collect();
    assert!(
        rows.iter()
            .any(|(n, _)| *n == Quantity::J { row: 7, col: 9 }),
        "{name}"
    );
    check_against_f64_chain(name, r, &rows);
    text.len()
}

#[test]
fn rtb_ten_joint_chains_give_small_reports_that_match_matrix_products() {
    for name in ["ball", "coil", "hyper"] {
        let file = format!("{RTB}{name}.toml");
        let r = load(&file);
        assert_eq!(r.variables.len(), 10, "{name}");
        check(name, &r);
    }
    // Through the binary, at its own defaults.
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["fk", &format!("{RTB}ball.toml"), "--jacobian"])
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.stdout.len() <= 100_000, "{} bytes", out.stdout.len());
    assert!(String::from_utf8_lossy(&out.stdout).contains("as a recurrence"));
}

/// A random numeric table of `n` links: lengths 0 or three-decimal numbers, twists among the
/// multiples of pi that DH tables use, one joint in ten prismatic.
fn random_table(seed: u64, n: usize, mdh: bool) -> String {
    let mut s = seed;
    let mut next = move |k: u64| {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 33) % k
    };
    let alphas = [
        "0", "pi/2", "-pi/2", "pi", "pi/3", "pi/4", "-pi/6", "2*pi/3",
    ];
    let convention = if mdh { "mdh" } else { "dh" };
    let mut text = format!("name = \"random {seed}\"\nconvention = \"{convention}\"\n");
    let length = |next: &mut dyn FnMut(u64) -> u64| match next(2) {
        0 => "0".to_string(),
        _ => format!("0.{:03}", 1 + next(999)),
    };
    for i in 1..=n {
        let (a, d) = (length(&mut next), length(&mut next));
        let alpha = alphas[next(alphas.len() as u64) as usize];
        let (theta, d) = if next(10) == 0 {
            ("0".to_string(), format!("\"q{i}\""))
        } else {
            (format!("\"q{i}\""), d)
        };
        text +=
            &format!(
            "[[joint]]\ntype = \"{}\"\ntheta = {theta}\nd = {d}\na = {a}\nalpha = \"{alpha}\"\n",
            if d.starts_with('"') { "prismatic" } else { "revolute" }
        );
    }
    text
}

#[test]
fn random_ten_joint_numeric_chains_give_small_reports_at_the_default_settings() {
    for (seed, mdh) in [(1, false), (2, true)] {
        let text = random_table(seed, 10, mdh);
        let r = parse_robot(&text, "random.toml", &eval_scalar_text)
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(r.variables.len(), 10);
        check(&format!("random {seed}:\n{text}"), &r);
    }
}
