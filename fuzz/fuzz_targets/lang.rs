//! The script language end to end: bytes, UTF-8, parse, run every statement as the REPL does
//! (an error does not stop the rest), and show every displayed value in every format.
//!
//! The limits are small so that each input is fast; a timeout or an out-of-memory under them is
//! a finding, fixed in the library.
#![no_main]

use dqsym::{parse, show, Format, Session, ShowOptions};
use libfuzzer_sys::fuzz_target;

const FORMATS: [Format; 4] = [Format::Plain, Format::Latex, Format::Sympy, Format::Rust];

fuzz_target!(|data: &[u8]| {
    let Ok(src) = std::str::from_utf8(data) else {
        return;
    };
    let ctx = dqsym::Context::new()
        .with_term_limit(1_000)
        .with_work_budget(50_000)
        .with_max_exponent(1_000);
    let _entered = ctx.enter();
    let program = match parse(src) {
        Ok(p) => p,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    // Printing the tree must give text that parses again.
    let _ = parse(&program.to_string());
    // Either kind of session, declared names (scripts) or free names as symbols (one-liners),
    // chosen by a bit of the input so that the fuzzer flips it; running both would double the
    // time of every input.
    let mut session = if data.len() % 2 == 0 {
        Session::new()
    } else {
        Session::with_implicit_symbols()
    };
    for stmt in &program.statements {
        match session.exec(stmt) {
            Ok(Some(d)) => {
                for format in FORMATS {
                    for explicit in [false, true] {
                        let _ = show(&d, &ShowOptions { format, explicit });
                    }
                }
            }
            Ok(None) => {}
            Err(e) => {
                let _ = e.render(src);
            }
        }
    }
});
