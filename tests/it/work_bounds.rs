//! Work bounds of issue 33 (speed, round 3), asserted on the work counter
//! (`Context::work_done`), never on time: the form an `fk` report takes is decided before the
//! closed forms it would throw away are made, and the closed-form search does not redo the
//! closed forms of its pieces. Each bound is the work measured on this test build when the
//! change was made, plus a quarter for unrelated changes to the search; the work before the
//! change is stated beside it.

use dqsym::{Context, FkOptions, Robot};

fn robot(path: &str) -> Robot {
    let file = format!("{}/{path}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&file).expect("robot file");
    dqsym::parse_robot(&text, &file, &dqsym::eval_scalar_text).expect("robot")
}

/// The `fk --jacobian` report of `r` at the binary's limits (5,000 terms, 3 million units of
/// work) on one thread, and the work it took.
fn fk_jacobian_work(r: &Robot) -> (dqsym::app::FkEntries, u64) {
    let ctx = Context::new()
        .with_term_limit(5_000)
        .with_work_budget(3_000_000)
        .with_threads(1);
    let _in = ctx.enter();
    let o = FkOptions {
        jacobian: true,
        max_terms: 5_000,
        ..FkOptions::default()
    };
    let before = Context::work_done();
    let entries = dqsym::app::fk_entries(r, &o).expect("report");
    (entries, Context::work_done() - before)
}

/// The report of a DH chain with symbols `theta{i}`, `d{i}`, `a{i}`, `alpha{i}` is a
/// recurrence whose matrix rows `T[i][j]` equal, at a point, the product of plain 4x4 DH
/// matrices there (an independent implementation).
fn check_dh_pose_at_point(r: &Robot, e: &dqsym::app::FkEntries) {
    assert!(e.recurrence);
    let n = r.variables.len();
    let mut names: Vec<(String, f64)> = Vec::new();
    let mut rng = 0x9e37_79b9_7f4a_7c15u64;
    for i in 1..=n {
        for s in ["theta", "d", "a", "alpha"] {
            rng = rng
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            names.push((
                format!("{s}{i}"),
                ((rng >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0,
            ));
        }
    }
    let values: Vec<(&str, f64)> = names.iter().map(|(s, v)| (s.as_str(), *v)).collect();
    let v = |s: String| values.iter().find(|(n, _)| *n == s).expect("symbol").1;
    let mut t = [[0.0f64; 4]; 4];
    for (i, row) in t.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for i in 1..=n {
        let (th, d) = (v(format!("theta{i}")), v(format!("d{i}")));
        let (a, al) = (v(format!("a{i}")), v(format!("alpha{i}")));
        let l = [
            [
                th.cos(),
                -th.sin() * al.cos(),
                th.sin() * al.sin(),
                a * th.cos(),
            ],
            [
                th.sin(),
                th.cos() * al.cos(),
                -th.cos() * al.sin(),
                a * th.sin(),
            ],
            [0.0, al.sin(), al.cos(), d],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let mut p = [[0.0f64; 4]; 4];
        for (r_, prow) in p.iter_mut().enumerate() {
            for (c, x) in prow.iter_mut().enumerate() {
                *x = (0..4).map(|k| t[r_][k] * l[k][c]).sum();
            }
        }
        t = p;
    }
    let mut checked = 0;
    for (q, x) in e.sections.iter().flat_map(|s| &s.rows) {
        if let dqsym::app::Quantity::T(i, j) = *q {
            let name = q.name();
            let value = x.value_at(&values).expect("value");
            // Products of n 4x4 matrices of entries of size <= 2 (lengths and cosines in
            // [-1, 1]): rounding of order 1e-15 per operation, far below 1e-9.
            assert!(
                (value - t[i][j]).abs() < 1e-9,
                "{name}: {value} vs {}",
                t[i][j]
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 12, "the recurrence prints T[i][j]");
}

#[test]
fn symbolic_4r_fk_jacobian_is_a_recurrence_without_the_jacobians_closed_forms() {
    // A 4-joint DH chain whose every length and twist is a symbol: its expanded pose prints
    // past 100 kB, so the report is the recurrence. Measured: 968,845 units once the pose's
    // text decides before the Jacobian's closed forms are made (whose closed forms were 45%
    // of the process's instructions before); 608,340 once the pose's closed forms stop as
    // soon as the text of those found is past 100 kB (the process 534 M -> 373 M
    // instructions); 284,303 once the matrix's closed forms come before the DQ product and
    // its largest entries' as the last matrix product makes them (two entries pass 100 kB:
    // neither the DQ nor the matrix's other ten entries are made; the process 305 M -> 119 M
    // instructions).
    let r = robot("benches/support/symbolic_4r.toml");
    let (entries, work) = fk_jacobian_work(&r);
    check_dh_pose_at_point(&r, &entries);
    assert!(work <= 355_000, "work {work}");
}

#[test]
fn symbolic_6r_fk_jacobian_stays_within_its_work() {
    // Every length and twist a symbol: the matrix expansion is abandoned on its growth and
    // the DQ product is never made (it ran beside the matrix on two threads before).
    // Measured: 1,089,005 units.
    let r = robot("tests/data/generic_6r.toml");
    let (entries, work) = fk_jacobian_work(&r);
    check_dh_pose_at_point(&r, &entries);
    assert!(work <= 1_360_000, "work {work}");
}

#[test]
fn constant_sine_product_closed_form_reuses_its_pieces() {
    let ctx = Context::new().with_work_budget(3_000_000).with_threads(1);
    let _in = ctx.enter();
    let x = dqsym::eval_scalar_text("sin(1)*sin(2)*sin(3)").expect("scalar");
    let before = Context::work_done();
    let e = dqsym::closed_form(&x).expect("closed form");
    let work = Context::work_done() - before;
    // Its value is the product's, in f64 (an independent evaluation: std's sine).
    let want = 1f64.sin() * 2f64.sin() * 3f64.sin();
    let got = e.value_at(&[]).expect("value");
    // Both are a few f64 operations on values of size <= 1: within 1e-12.
    assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    assert_eq!(e.to_scalar(), x);
    // Measured: 135,510 units with the memo of `closed/mod.rs` (797 M instructions without
    // it, 131 M with it, in the release binary); 19,204 once `cspoly.rs` finds the closed
    // forms of its factors without factoring them again (106 M to 18 M instructions).
    assert!(work <= 30_000, "work {work}");
}

#[test]
fn constant_cosine_triple_closed_form_skips_hopeless_recombinations() {
    let ctx = Context::new().with_work_budget(3_000_000).with_threads(1);
    let _in = ctx.enter();
    let x = dqsym::eval_scalar_text("cos(1)*cos(2)*cos(3)").expect("scalar");
    let before = Context::work_done();
    let e = dqsym::closed_form(&x).expect("closed form");
    let work = Context::work_done() - before;
    // Its value is the product's, in f64 (std's cosine, independent of dqsym).
    let want = 1f64.cos() * 2f64.cos() * 3f64.cos();
    let got = e.value_at(&[]).expect("value");
    assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    assert_eq!(e.to_scalar(), x);
    // Measured: 241,382 units before `zfactor.rs` tested a subset's constant term before
    // forming its product, 170,935 after (debug build; 42 M to 24 M instructions in release).
    assert!(work <= 200_000, "work {work}");
}

/// The closed form of `(x + y + z)^n` as a Horner-like nesting, and the work it took (at an
/// unlimited budget, one thread).
fn multinomial_closed_form(n: u32) -> (dqsym::Expr, dqsym::Scalar, u64) {
    let ctx = Context::new().with_threads(1);
    let _in = ctx.enter();
    let x = dqsym::eval_scalar_text(&format!("(x + y + z)^{n}")).expect("scalar");
    let before = Context::work_done();
    let e = dqsym::closed_form(&x).expect("closed form");
    (e, x, Context::work_done() - before)
}

/// `(x + y + z)^n` at a point, in f64, by repeated multiplication (an independent evaluation).
fn multinomial_at(n: u32, p: [f64; 3]) -> f64 {
    (0..n).fold(1.0, |acc, _| acc * (p[0] + p[1] + p[2]))
}

#[test]
fn multinomial_display_runs_each_factor_once() {
    // The search below its branching levels pulls `x` out sixty times in a row; it sorts the
    // terms by their power of `x` once instead of copying, counting and dividing the inner
    // group at every level. Measured in the release build (which checks the result
    // numerically): 3,577,351 units before (a visit of every term at every level of the
    // nesting), 872,900 after; in this test build, which also checks it exactly, 2,753,033.
    let (e, _, work) = multinomial_closed_form(60);
    for p in [[0.3, 1.1, 0.7], [1.6, 0.4, 0.9], [0.5, 0.5, 1.5]] {
        let got = e
            .value_at(&[("x", p[0]), ("y", p[1]), ("z", p[2])])
            .expect("value");
        let want = multinomial_at(60, p);
        // Every term is positive (no cancellation): each of the ~4,000 operations of the
        // nested form and the 60 of the power adds at most one rounding of 2^-53 relative to
        // the value, so both agree within 5,000 * 2^-53 < 1e-12 of it; 1e-9 leaves room.
        assert!(
            (got - want).abs() <= 1e-9 * want,
            "{got} vs {want} at {p:?}"
        );
    }
    assert!(work <= 3_440_000, "work {work}");
}

#[test]
fn multinomial_display_is_exact_and_nested() {
    let (e, x, _) = multinomial_closed_form(30);
    assert_eq!(e.to_scalar(), x);
    let text = dqsym::print::plain(&e, &Default::default());
    // Nested thirty levels deep in `x`: the form the search built level by level.
    assert!(text.starts_with(&"x (".repeat(29)), "{}", &text[..120]);
}

#[test]
fn signed_power_past_64_bit_coefficients_displays_exactly() {
    // `(x - 2 y + 3 z)^28`: coefficients up to 6^28 ~ 6e21, past 64 bits and within 128,
    // of both signs: the contents and exact quotients of the display in 128-bit machine
    // arithmetic (`closed/mon.rs`), the runs of splits from their counting-sorted buckets.
    let ctx = Context::new().with_threads(1);
    let _in = ctx.enter();
    let x = dqsym::eval_scalar_text("(x - 2*y + 3*z)^28").expect("scalar");
    let before = Context::work_done();
    let e = dqsym::closed_form(&x).expect("closed form");
    let work = Context::work_done() - before;
    assert_eq!(e.to_scalar(), x);
    for p in [[0.3, 0.2, 0.4], [0.9, 0.1, 0.05], [0.25, 0.5, 0.5]] {
        let got = e
            .value_at(&[("x", p[0]), ("y", p[1]), ("z", p[2])])
            .expect("value");
        let base = p[0] - 2.0 * p[1] + 3.0 * p[2];
        let want = (0..28).fold(1.0, |acc, _| acc * base);
        // The nested form adds terms of both signs: each of its few thousand operations rounds
        // by at most 2^-53 of a partial value, which is at most the power of the sum of the
        // absolute values, (x + 2 y + 3 z)^28; 1e-9 of that bounds 10^4 * 2^-53 with room.
        let scale = (0..28).fold(1.0, |acc, _| acc * (p[0] + 2.0 * p[1] + 3.0 * p[2]));
        assert!(
            (got - want).abs() <= 1e-9 * scale,
            "{got} vs {want} at {p:?}"
        );
    }
    // Measured: 201,108 units (unchanged by the machine arithmetic: the charges are per word).
    assert!(work <= 250_000, "work {work}");
}

/// The closed form of `cos(1) * ... * cos(n)` at the binary's budget on one thread, and the
/// work it took.
fn cosine_product_closed_form(n: i64) -> (Result<dqsym::Expr, dqsym::ScalarError>, u64) {
    let text: Vec<String> = (1..=n).map(|k| format!("cos({k})")).collect();
    let x = dqsym::eval_scalar_text(&text.join("*")).expect("scalar");
    let ctx = Context::new().with_work_budget(3_000_000).with_threads(1);
    let _in = ctx.enter();
    let before = Context::work_done();
    let e = dqsym::closed_form(&x);
    (e, Context::work_done() - before)
}

#[test]
fn constant_cosine_product_peels_with_integer_coefficients() {
    // The cosines are divided off the Fourier sum with Gaussian integer coefficients over one
    // denominator, each step charged by its words (with reduced rationals each step took a
    // gcd and was charged one unit whatever its words). Measured: 203,260 units.
    let (e, work) = cosine_product_closed_form(48);
    let e = e.expect("closed form");
    let want: f64 = (1..=48).map(|k| (k as f64).cos()).product();
    let got = e.value_at(&[]).expect("value");
    // 48 factors of size <= 1, each with a rounding of 2^-53 in std's cosine and in the
    // product: within 100 * 2^-53 of the (tiny) value, relative; 1e-12 leaves room.
    assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
    let text = dqsym::print::plain(&e, &Default::default());
    for k in 1..=48 {
        assert!(text.contains(&format!("cos({k})")), "{text}");
    }
    assert!(work <= 254_000, "work {work}");
}

#[test]
fn signed_radical_power_display_agrees_with_its_value() {
    // Negative terms, rational and radical contents: the sign, content and radical steps of
    // a run of splits, taken from its buckets.
    let ctx = Context::new().with_threads(1);
    let _in = ctx.enter();
    let x = dqsym::eval_scalar_text("(sqrt(2)*x*c - 3*y + z/2)^9 - (x*y - 2*z)^7").expect("scalar");
    let e = dqsym::closed_form(&x).expect("closed form");
    assert_eq!(e.to_scalar(), x);
    for p in [
        [0.3, 1.1, 0.7, 1.3],
        [1.6, 0.4, 0.9, 0.6],
        [0.5, 0.5, 1.5, 0.8],
    ] {
        let got = e
            .value_at(&[("x", p[0]), ("y", p[1]), ("z", p[2]), ("c", p[3])])
            .expect("value");
        let (x, y, z, c) = (p[0], p[1], p[2], p[3]);
        let want = (2f64.sqrt() * x * c - 3.0 * y + z / 2.0).powi(9) - (x * y - 2.0 * z).powi(7);
        // Terms up to ~10^5 in size: a relative 1e-12 of the largest of them bounds the
        // rounding of the few hundred operations of either side.
        let scale = (2f64.sqrt() * x * c + 3.0 * y + z / 2.0).powi(9) + (x * y + 2.0 * z).powi(7);
        assert!(
            (got - want).abs() <= 1e-12 * scale,
            "{got} vs {want} at {p:?}"
        );
    }
}

#[test]
fn puma_fk_jacobian_work_stays_bounded_with_the_mixed_angle_factors() {
    // The candidates of `closed/trigfac.rs` (sinusoids of mixed angles, sums split into
    // parts) are not made for the PUMA's scalars (half-angle series at one step, no offsets,
    // no radicals): its work is the search's without them. Measured: 50,085 units (the bound a quarter more).
    let r = robot("examples/robots/puma560.toml");
    let (_, work) = fk_jacobian_work(&r);
    assert!(work <= 62_600, "work {work}");
}
