//! Robot files: bytes, UTF-8, `parse_robot` with the language's field evaluator, and the plain
//! forward-kinematics report (without the Jacobian) under small limits.
#![no_main]

use dqsym::{eval_scalar_text, fk_report, parse_robot, FkOptions, Format};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let ctx = dqsym::Context::new()
        .with_term_limit(1_000)
        .with_work_budget(50_000)
        .with_max_exponent(1_000);
    let _entered = ctx.enter();
    let robot = match parse_robot(text, "fuzz.toml", &eval_scalar_text) {
        Ok(r) => r,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    // The fields were evaluated each with its own budget; the derivation gets a whole one.
    let _derivation = ctx.enter();
    let options = FkOptions {
        format: Format::Plain,
        shorthand: true,
        point: robot.tool.clone(),
        jacobian: false,
        max_terms: ctx.term_limit(),
    };
    let _ = fk_report(&robot, &options);
});
