//! URDF files: bytes, UTF-8, `parse_urdf` (both angle readings), the plain forward-kinematics
//! report under small limits, and `convert`'s robot file for the chains it reads.
#![no_main]

use dqsym::{fk_report, parse_urdf, FkOptions, Format};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let ctx = dqsym::Context::new()
        .with_term_limit(1_000)
        .with_work_budget(50_000)
        .with_max_exponent(1_000);
    for snap_angles in [true, false] {
        let _entered = ctx.enter();
        let o = dqsym::kin::UrdfOptions {
            tip: None,
            base: None,
            snap_angles,
        };
        let r = match parse_urdf(text, "fuzz.urdf", &o) {
            Ok(r) => r,
            Err(e) => {
                let _ = e.to_string();
                continue;
            }
        };
        let options = FkOptions {
            format: Format::Plain,
            shorthand: true,
            point: r.robot.tool.clone(),
            jacobian: false,
            max_terms: ctx.term_limit(),
        };
        let _ = fk_report(&r.robot, &options);
        let _ = dqsym::app::robot_toml(&r.robot, "fuzz.urdf");
    }
});
