//! Every cost bounded (hostile round 3, rows 9-15, 17-19): computed numbers have a digit
//! limit, big coefficients and the closed-form searches charge the work budget before they
//! spend, a common factor comes out at its whole power, angles have a symbol limit, long
//! chains fall back to the recurrence, `convert` reports a limit as a limit and never writes
//! what `fk` refuses, the REPL's bindings roll back. Assertions are on the work counter and
//! on the errors, never on time; families run at the defaults and at ten times them.

use dqsym::{parse, Context, Scalar, ScalarError, Session};
use num_bigint::BigInt;
use num_rational::BigRational;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_dqsym");

/// Runs `src` statement by statement in a one-liner's session under `ctx`; the index and
/// message of the first failing statement (showing the result included), the session, and
/// the work done.
fn run(src: &str, ctx: &Context) -> (Option<(usize, String)>, Session, u64) {
    let _in = ctx.enter();
    let before = Context::work_done();
    let mut session = Session::with_implicit_symbols();
    let program = parse(src).expect("parses");
    for (i, stmt) in program.statements.iter().enumerate() {
        let r = session
            .exec(stmt)
            .map_err(|e| e.message())
            .and_then(|d| match d {
                Some(d) => dqsym::show(&d, &dqsym::ShowOptions::default())
                    .map(|_| ())
                    .map_err(|e| e.to_string()),
                None => Ok(()),
            });
        if let Err(m) = r {
            return (Some((i, m)), session, Context::work_done() - before);
        }
    }
    (None, session, Context::work_done() - before)
}

fn int(v: &BigInt) -> Scalar {
    Scalar::rational(BigRational::from_integer(v.clone()))
}

/// Decimal digits of `2^e`, computed exactly.
fn digits_of_power_of_two(e: u32) -> usize {
    BigInt::from(2).pow(e).to_string().len()
}

#[test]
fn repeated_squaring_stops_at_the_digit_limit_by_default_and_at_ten_times_it() {
    for limit in [
        dqsym::scalar::DEFAULT_MAX_DIGITS,
        10 * dqsym::scalar::DEFAULT_MAX_DIGITS,
    ] {
        // The budget charges a product of big numbers by their words squared: at ten times
        // the digit limit it must be raised too, or it stops the family first.
        let ctx = Context::new()
            .with_max_digits(limit)
            .with_work_budget(1_000_000_000);
        let mut src = String::from("n = 2^1000;\n");
        src += &"n = n*n;\n".repeat(12);
        let (err, session, _) = run(&src, &ctx);
        // Statement k (k >= 1) makes 2^(1000 * 2^k): the first one past the limit fails.
        let first_over = (1..=12u32)
            .find(|&k| digits_of_power_of_two(1000 << k) as u64 > limit)
            .expect("within the family");
        let (at, message) = err.expect("an error");
        assert_eq!(at, first_over as usize, "{message}");
        assert!(
            message.contains(&format!("over the limit of {limit} digits (--max-digits"))
                && message.contains("number too large"),
            "{message}"
        );
        // The value before it is exact: 2^(1000 * 2^(k - 1)) (built under the same limit).
        let _in = ctx.enter();
        let kept = session.get("n").expect("bound");
        let expected = int(&BigInt::from(2).pow(1000u32 << (first_over - 1)));
        assert_eq!(kept, &dqsym::Value::Scalar(expected));
    }
}

#[test]
fn rationals_that_grow_by_sums_and_reciprocals_stop_at_the_digit_limit() {
    let ctx = Context::new().with_work_budget(3_000_000);
    let mut src = String::from("n = 3/2;\n");
    src += &"n = n*n + 1/n;\n".repeat(30);
    let (err, _, work) = run(&src, &ctx);
    let (_, message) = err.expect("an error");
    assert!(message.contains("--max-digits"), "{message}");
    // Every statement charged its coefficients' words: the whole run stays in one budget.
    assert!(work <= 30 * 3_000_000, "{work}");
}

#[test]
fn a_power_past_the_digit_limit_is_refused_before_it_is_computed() {
    let ctx = Context::new();
    let (_, _, base) = run("2^10000", &ctx);
    let (err, _, work) = run("(2^10000)^4", &ctx);
    let (_, message) = err.expect("an error");
    // 2^40000 has 12,042 digits.
    assert_eq!(digits_of_power_of_two(40_000), 12_042);
    assert!(
        message.contains("about 12042 digits, over the limit of 10000"),
        "{message}"
    );
    assert!(
        work < base + 100,
        "the power was computed: {work} units, {base} for the base"
    );
    // Just under the limit it is computed, exactly.
    let (err, session, _) = run("y = (2^10000)^3", &ctx);
    assert!(err.is_none(), "{err:?}");
    assert_eq!(
        session.get("y"),
        Some(&dqsym::Value::Scalar(int(&BigInt::from(2).pow(30_000u32))))
    );
}

/// The closed form of `x^n - x^(n-1)` and the work it took.
fn two_term_polynomial(n: u64) -> (String, u64) {
    let ctx = Context::new()
        .with_max_exponent(100_000)
        .with_term_limit(20_000);
    let _in = ctx.enter();
    let x = Scalar::sym("x");
    let p = x.pow(n) - x.pow(n - 1);
    let before = Context::work_done();
    let e = dqsym::closed_form(&p).expect("a closed form");
    let work = Context::work_done() - before;
    // The closed form's value is the polynomial's, at x = 3/2 (exact: the closed form is
    // turned back into a scalar and substituted).
    let at = |s: &Scalar| s.subs("x", &Scalar::rational(BigRational::new(3.into(), 2.into())));
    assert_eq!(at(&e.to_scalar()), at(&p), "n = {n}");
    (dqsym::plain(&e, &dqsym::PlainOptions::default()), work)
}

#[test]
fn a_common_power_comes_out_in_one_step_whatever_its_exponent() {
    let (text_small, work_small) = two_term_polynomial(100);
    assert_eq!(text_small, "x^99 (-1 + x)");
    for n in [10_000, 100_000] {
        let (text, work) = two_term_polynomial(n);
        assert_eq!(text, format!("x^{} (-1 + x)", n - 1));
        // The work does not grow with the exponent (it grew with its square).
        assert!(
            work <= 2 * work_small + 100,
            "n = {n}: {work} vs {work_small}"
        );
    }
}

#[test]
fn products_of_many_constant_cosines_end_within_the_budget() {
    let budget = 200_000;
    for (n, power) in [(512, false), (200, false), (10_000, true)] {
        let src = if power {
            "cos(x)^10000".to_owned()
        } else {
            (1..=n)
                .map(|k| format!("cos({k})"))
                .collect::<Vec<_>>()
                .join("*")
        };
        let ctx = Context::new()
            .with_term_limit(20_000)
            .with_work_budget(budget);
        let (err, _, work) = run(&src, &ctx);
        let (_, message) = err.expect("a limit");
        assert!(
            message.contains("work budget exceeded") || message.contains("expression too large"),
            "{n}: {message}"
        );
        // Charged before it was spent: the run ends at the first charge past the budget. The
        // counter includes that last charge, of a product refused before it was formed (for
        // `cos(x)^10000` a square of 129-term scalars with coefficients of hundreds of digits,
        // some 750,000 units): a few budgets at most, where the products formed before the
        // budget was charged for their coefficients ran to 3,000,000 units and more.
        assert!(
            work <= 5 * budget,
            "{n}: {work} units for a budget of {budget}"
        );
    }
}

/// Products and powers of constants whose coefficients grow (hostile round 3, row 12, and its
/// variants): every product charges its coefficients' words, their reductions included, before
/// it is formed, so each ends on a named limit at a work count of a few budgets, at a budget
/// and at ten times it. (Before the reductions were charged, `cos(1) * ... * cos(512)` ran
/// 1.8 s of release CPU to the default budget's error, now 0.6 s; the counter is what is
/// asserted here.)
#[test]
fn constant_products_and_powers_charge_their_coefficients_before_forming_them() {
    let product =
        |f: &dyn Fn(usize) -> String, n: usize| (1..=n).map(f).collect::<Vec<_>>().join("*");
    let family = [
        product(&|k| format!("sin({k})"), 512),
        product(&|k| format!("cos({k}*x)"), 512),
        product(&|k| format!("cos({k}/7)"), 512),
        product(&|k| format!("(cos({k}) + sin({}))", k + 1), 300),
        "(cos(1) + sin(2))^200".to_owned(),
        "(cos(1) + sin(2) + cos(3))^500".to_owned(),
        "(1/3 + cos(1)/7)^2000".to_owned(),
        "(sin(x) + cos(2*x)/3)^3000".to_owned(),
    ];
    for budget in [100_000u64, 1_000_000] {
        for (i, src) in family.iter().enumerate() {
            // The ten-times budget for the first three only: the rest behave alike, and each
            // run costs its budget of work.
            if budget > 100_000 && i >= 3 {
                continue;
            }
            let ctx = Context::new()
                .with_term_limit(20_000)
                .with_work_budget(budget);
            let (err, _, work) = run(src, &ctx);
            let (_, message) = err.unwrap_or_else(|| panic!("{src}: a limit"));
            assert!(
                (message.contains("work budget exceeded") && message.contains("--work-budget"))
                    || (message.contains("expression too large")
                        && message.contains("--term-limit")),
                "{src}: {message}"
            );
            // The counter includes the last charge, of a product refused before it was formed.
            // A product of many factors grows by one factor a step, so that charge is small: at
            // most one more budget. A power squares its largest scalar: the refused square's
            // charge grows with the square of that scalar's terms and words, up to 30 budgets
            // at the small budget (3 at the default).
            let refused = if src.contains('^') { 40 } else { 2 };
            assert!(
                work <= refused * budget,
                "{src}: {work} units for a budget of {budget}"
            );
        }
    }
}

#[test]
fn angles_hold_at_most_the_limit_of_symbols_by_default_and_at_ten_times_it() {
    for limit in [
        dqsym::scalar::DEFAULT_MAX_ANGLE_SYMBOLS,
        10 * dqsym::scalar::DEFAULT_MAX_ANGLE_SYMBOLS,
    ] {
        let ctx = Context::new().with_max_angle_symbols(limit);
        let _in = ctx.enter();
        // A balanced sum: n log n term operations, not n^2.
        fn sum(lo: usize, hi: usize) -> Scalar {
            match hi - lo {
                0 => Scalar::int(0),
                1 => Scalar::sym(&format!("q{lo}")),
                n => sum(lo, lo + n / 2) + sum(lo + n / 2, hi),
            }
        }
        let sum = |n: usize| sum(0, n);
        let ok = sum(limit).cos();
        assert!(ok.as_error().is_none(), "{limit}");
        // cos(q0 + ... + q(n-1)) at every q = 0 is 1.
        assert_eq!(ok.eval(&|_| Some(0.0)).ok(), Some(1.0));
        assert_eq!(
            sum(limit + 1).cos().as_error(),
            Some(&ScalarError::AngleSymbols {
                symbols: limit + 1,
                limit
            })
        );
    }
}

/// A URDF chain of `n` revolute joints with collinear z axes, 0.1 apart.
fn collinear_urdf(n: usize) -> String {
    let links: String = (0..=n).map(|i| format!("<link name=\"l{i}\"/>")).collect();
    let joints: String = (0..n)
        .map(|i| {
            format!(
                "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/>\
                 <child link=\"l{}\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"0 0 1\"/></joint>",
                i + 1
            )
        })
        .collect();
    format!("<robot name=\"r\">{links}{joints}</robot>")
}

fn scratch(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("dqsym-costs-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch dir");
    d
}

#[test]
fn a_long_collinear_chain_is_a_recurrence_not_a_quadratic_expansion() {
    let dir = scratch("collinear");
    let n = 1_500;
    std::fs::write(dir.join("c.urdf"), collinear_urdf(n)).expect("writes");
    let out = Command::new(BIN)
        .args(["fk", "c.urdf"])
        .current_dir(&dir)
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("as a recurrence over the joint factors"),
        "{text:.400}"
    );
    // The pose is the last prefix product of the recurrence.
    assert!(text.contains(&format!("Q{n}_0")), "no Q{n}");
}

#[test]
fn convert_reports_a_limit_reached_in_a_check_as_a_limit() {
    let dir = scratch("convert");
    std::fs::write(dir.join("c.urdf"), collinear_urdf(2_000)).expect("writes");
    let out = Command::new(BIN)
        .args(["convert", "c.urdf"])
        .current_dir(&dir)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("a size limit was reached while checking"),
        "{err}"
    );
    assert!(!err.contains("mimic"), "{err}");
}

#[test]
fn convert_never_writes_a_file_fk_would_refuse() {
    let dir = scratch("refuse");
    let fixed = "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j0\" \
                 type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/><origin xyz=\"1 0 0\"/>\
                 </joint></robot>";
    std::fs::write(dir.join("fixed.urdf"), fixed).expect("writes");
    let out = Command::new(BIN)
        .args(["convert", "fixed.urdf"])
        .current_dir(&dir)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(out.stdout.is_empty());
    assert!(
        err.contains("no robot file written: fk would not read it back"),
        "{err}"
    );
    // The same with --tip = --base on a chain that has joints.
    std::fs::write(dir.join("c.urdf"), collinear_urdf(3)).expect("writes");
    let out = Command::new(BIN)
        .args(["convert", "c.urdf", "--base", "l2", "--tip", "l2"])
        .current_dir(&dir)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty());
    // And a file it writes, fk reads.
    let out = Command::new(BIN)
        .args(["convert", "c.urdf"])
        .current_dir(&dir)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0));
    std::fs::write(dir.join("c.toml"), &out.stdout).expect("writes");
    let fk = Command::new(BIN)
        .args(["fk", "c.toml"])
        .current_dir(&dir)
        .output()
        .expect("runs");
    assert_eq!(
        fk.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&fk.stderr)
    );
}

#[test]
fn a_long_numeric_dh_chain_meets_a_small_budget_at_once() {
    let dir = scratch("dh");
    let mut toml = String::from("convention = \"dh\"\n");
    for i in 0..2_000 {
        toml += &format!(
            "[[joint]]\ntype = \"revolute\"\ntheta = \"q{i}\"\nd = \"0\"\na = \"1/2\"\nalpha = \"pi/2\"\n"
        );
    }
    std::fs::write(dir.join("dh.toml"), toml).expect("writes");
    // fk, its Jacobian and ops: the derivation's limit error names the file, as a field's does.
    for args in [&["fk"][..], &["fk", "--jacobian"][..], &["ops"][..]] {
        let out = Command::new(BIN)
            .args(args)
            .args(["dh.toml", "--work-budget", "1000"])
            .current_dir(&dir)
            .output()
            .expect("runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.starts_with("error: dh.toml: work budget exceeded")
                && err.contains("--work-budget"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn a_rolled_back_statement_leaves_the_bindings_as_before_it() {
    let mut s = Session::with_implicit_symbols();
    let p = parse("a = 1\nb = x + 1\na = 2\nc = 3\n").expect("parses");
    s.exec(&p.statements[0]).expect("runs");
    s.checkpoint();
    s.exec(&p.statements[1]).expect("runs");
    s.exec(&p.statements[2]).expect("runs");
    s.rollback();
    assert_eq!(s.get("a"), Some(&dqsym::Value::Scalar(Scalar::int(1))));
    assert!(s.get("b").is_none());
    // A committed statement stays; commit names what it bound anew.
    s.checkpoint();
    s.exec(&p.statements[3]).expect("runs");
    s.exec(&p.statements[2]).expect("runs");
    assert_eq!(s.commit(), vec!["c".to_owned()]);
    s.rollback();
    assert_eq!(s.get("c"), Some(&dqsym::Value::Scalar(Scalar::int(3))));
    assert_eq!(s.get("a"), Some(&dqsym::Value::Scalar(Scalar::int(2))));
}

#[test]
fn define_refuses_the_keywords_as_assignment_does() {
    let mut s = Session::new();
    for k in dqsym::lang::KEYWORDS {
        let e = s
            .define(k, dqsym::Value::Scalar(Scalar::int(1)))
            .expect_err(k);
        assert!(e.message().contains("keyword"), "{k}: {}", e.message());
        // The language refuses the same name.
        assert!(parse(&format!("{k} = 1")).is_err(), "{k}");
    }
}

#[test]
fn the_repl_keeps_every_binding_of_a_long_session() {
    // Each statement moves the session to its worker and back (no copy): 3,000 assignments
    // and then every one of them read back.
    let mut input = String::new();
    for i in 0..3_000 {
        input += &format!("v{i} = {i};\n");
    }
    input += "v0 + v1234 + v2999\n";
    let mut child = Command::new(BIN)
        .env("XDG_STATE_HOME", std::env::temp_dir())
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("runs");
    use std::io::Write;
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(input.as_bytes())
        .expect("writes");
    let out = child.wait_with_output().expect("finishes");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains(&format!("= {}", 1234 + 2999)), "{text}");
}

/// A small deterministic generator (SplitMix64): the mutations are the same on every run.
struct Mix(u64);

impl Mix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One mutation of `text`: a cut, a copied stretch, a hostile number, a swapped word, or a
/// truncation (always at a character boundary).
fn mutate(text: &str, r: &mut Mix) -> String {
    let chars: Vec<char> = text.chars().collect();
    let (a, b) = {
        let x = r.below(chars.len());
        (x, (x + 1 + r.below(40)).min(chars.len()))
    };
    let s = |v: &[char]| v.iter().collect::<String>();
    const NUMBERS: [&str; 9] = [
        "1e309",
        "-0",
        "nan",
        "1e-400",
        "0.30000000000000004",
        "99999999999999999999999",
        "1.5707963",
        "",
        "3 4",
    ];
    const WORDS: [&str; 8] = [
        "revolute",
        "prismatic",
        "fixed",
        "continuous",
        "mimic",
        "axis",
        "origin",
        "joint",
    ];
    match r.below(6) {
        0 => s(&chars[..a]) + &s(&chars[b..]),
        1 => s(&chars[..b]) + &s(&chars[a..]),
        2 => {
            // A number attribute's value replaced.
            let quoted: Vec<usize> = text.match_indices("=\"").map(|(i, _)| i + 2).collect();
            let Some(&at) = quoted.get(r.below(quoted.len())) else {
                return text.to_owned();
            };
            let end = at + text[at..].find('"').unwrap_or(0);
            format!(
                "{}{}{}",
                &text[..at],
                NUMBERS[r.below(NUMBERS.len())],
                &text[end..]
            )
        }
        3 => {
            let w = WORDS[r.below(WORDS.len())];
            let v = WORDS[r.below(WORDS.len())];
            text.replacen(w, v, 1)
        }
        4 => s(&chars[..a]),
        _ => s(&chars[..a]) + "<joint name=\"x\" type=\"revolute\">" + &s(&chars[a..]),
    }
}

#[test]
fn random_urdf_mutations_end_in_a_result_or_a_typed_error_within_their_limits() {
    // The bounded in-suite stand-in for the `urdf` fuzz target (cargo-fuzz needs a nightly
    // toolchain the test command does not use): 600 mutated files, each read both ways and
    // derived under small limits; a panic fails the test, every error has a message.
    let seeds = [
        collinear_urdf(3),
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\
         <joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\
         <origin xyz=\"0.1 0.2 0.3\" rpy=\"0.3 0.7 0\"/><axis xyz=\"0 1 0\"/></joint>\
         <joint name=\"j2\" type=\"prismatic\"><parent link=\"b\"/><child link=\"c\"/>\
         <origin xyz=\"0.4 0 0.1\" rpy=\"0 1.5708 0\"/><axis xyz=\"1 0 0\"/>\
         <limit lower=\"0\" upper=\"1\"/></joint></robot>"
            .to_owned(),
        "<robot name=\"m\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\
         <joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\
         <axis xyz=\"0 0 1\"/></joint><joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/>\
         <child link=\"c\"/><origin xyz=\"1 0 0\"/><axis xyz=\"0 0 1\"/>\
         <mimic joint=\"j1\" multiplier=\"2\" offset=\"0.5\"/></joint></robot>"
            .to_owned(),
    ];
    let ctx = Context::new()
        .with_term_limit(1_000)
        .with_work_budget(50_000)
        .with_max_exponent(1_000);
    let mut r = Mix(31);
    let (mut read, mut refused) = (0, 0);
    for case in 0..600 {
        let mut text = seeds[case % seeds.len()].clone();
        for _ in 0..1 + r.below(3) {
            text = mutate(&text, &mut r);
        }
        for snap_angles in [true, false] {
            let _in = ctx.enter();
            let o = dqsym::kin::UrdfOptions {
                tip: None,
                base: None,
                snap_angles,
            };
            match dqsym::parse_urdf(&text, "m.urdf", &o) {
                Err(e) => {
                    refused += 1;
                    assert!(!e.to_string().is_empty(), "{text}");
                }
                Ok(u) => {
                    read += 1;
                    let options = dqsym::FkOptions {
                        point: u.robot.tool.clone(),
                        max_terms: ctx.term_limit(),
                        ..dqsym::FkOptions::default()
                    };
                    if let Err(e) = dqsym::fk_report(&u.robot, &options) {
                        assert!(!e.to_string().is_empty(), "{text}");
                    }
                    if let Err(e) = dqsym::app::robot_toml(&u.robot, "m.urdf") {
                        assert!(!e.to_string().is_empty(), "{text}");
                    }
                }
            }
        }
    }
    // Both outcomes occur: the mutations are neither all harmless nor all fatal.
    assert!(read > 40 && refused > 100, "{read} read, {refused} refused");
}

/// A product of sums whose terms carry long angles (`cos(q0 + ... + qk)`, as a chain of joints
/// about one axis gives) charges each angle's symbols past the eight a term pair covers: the
/// work counted is at least `n * sum over terms of (symbols - 8)` for each factor. Uncharged,
/// `fk` of a 1,000-joint chain about one axis with offsets off it ran 77 s and 1.3 GB at the
/// default budget (hostile round 3, a variant of row 9).
#[test]
fn long_angles_are_charged_symbol_by_symbol_in_products() {
    let n: u64 = 60;
    let names: Vec<String> = (0..n).map(|i| format!("q{i}")).collect();
    let angle = |k: usize| names[..=k].join(" + ");
    let sum = |f: &str| -> String {
        (0..n as usize)
            .map(|k| format!("{f}({})", angle(k)))
            .collect::<Vec<_>>()
            .join(" + ")
    };
    let src = format!(
        "syms {}\nx = {}\ny = {}\nz = x*y\n",
        names.join(" "),
        sum("cos"),
        sum("sin")
    );
    // Only the product is measured: the sums are formed first.
    let setup = src.rsplit_once("z = ").expect("product").0.to_string();
    let ctx = Context::new()
        .with_term_limit(1_000_000)
        .with_work_budget(u64::MAX);
    let (e0, _, before) = run(&setup, &ctx);
    assert!(e0.is_none(), "{e0:?}");
    let (e1, session, all) = run(&src, &ctx);
    assert!(e1.is_none(), "{e1:?}");
    let excess: u64 = (1..=n).map(|len| len.saturating_sub(8)).sum();
    let floor = n * n + 2 * n * excess;
    assert!(
        all - before >= floor,
        "the product charged {} units, under {floor}",
        all - before
    );
    // And it is the product: x*y at a point is cos-sum times sin-sum.
    let z = session.get("z").expect("z bound");
    let dqsym::Value::Scalar(z) = z else {
        panic!("z is a scalar")
    };
    let q: Vec<f64> = (0..n).map(|i| 0.1 + 0.37 * i as f64).collect();
    let partial = |k: usize| q[..=k].iter().sum::<f64>();
    let (c, s): (f64, f64) = (0..n as usize)
        .map(|k| (partial(k).cos(), partial(k).sin()))
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let got = z
        .eval(&|v: &str| {
            v.strip_prefix('q')
                .and_then(|i| i.parse::<usize>().ok())
                .map(|i| q[i])
        })
        .expect("numeric");
    assert!(
        (got - c * s).abs() < 1e-9 * (1.0 + (c * s).abs()),
        "{got} vs {}",
        c * s
    );
}

/// `convert` reads its file back at fk's term limit (its own default is four times higher):
/// a URDF whose angles are off the pi/12 grid and whose axis is oblique gives symbolic axes
/// that fk's unit-length check cannot confirm at its limit, so nothing is written; whatever
/// convert does write, fk reads (hostile round 3, row 17).
#[test]
fn convert_writes_only_what_fk_reads_at_its_own_limits() {
    let dir = scratch("readback");
    let urdf = "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\
        <joint name=\"j0\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\
        <origin xyz=\"0.1 0.2 0.3\" rpy=\"0.3 0.7 -0.4\"/><axis xyz=\"0.6 0 0.8\"/></joint>\
        <joint name=\"j1\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/>\
        <origin xyz=\"0.3 -0.1 0.2\" rpy=\"1.1 -0.2 0.5\"/><axis xyz=\"0 1 0\"/></joint></robot>";
    std::fs::write(dir.join("r.urdf"), urdf).expect("writes");
    for extra in [&[][..], &["--term-limit", "100000"][..]] {
        let out = Command::new(BIN)
            .args(["convert", "r.urdf"])
            .args(extra)
            .current_dir(&dir)
            .output()
            .expect("runs");
        let err = String::from_utf8_lossy(&out.stderr);
        if out.status.code() != Some(0) {
            assert!(out.stdout.is_empty(), "{extra:?}");
            assert!(
                err.contains("fk would not read it back"),
                "{extra:?}: {err}"
            );
            assert!(err.contains("--term-limit"), "{extra:?}: {err}");
            continue;
        }
        std::fs::write(dir.join("r.toml"), &out.stdout).expect("writes");
        let fk = Command::new(BIN)
            .args(["fk", "r.toml"])
            .args(extra)
            .current_dir(&dir)
            .output()
            .expect("runs");
        assert_eq!(
            fk.status.code(),
            Some(0),
            "{extra:?}: convert wrote a file fk refuses: {}",
            String::from_utf8_lossy(&fk.stderr)
        );
    }
}
