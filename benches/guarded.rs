//! The guarded cases of issue 33: workloads that once regressed or that the form decision,
//! the thread default and the closed-form memo made fast, each measured in process (one
//! thread, the binary's `fk` limits: 5,000 terms, 3 million units of work).
//! `scripts/bench_guard.sh` compares them (and the same commands' instruction counts) against
//! a saved baseline and names every case slower by more than 10%.
//! Short measurements: `cargo bench --bench guarded [-- FILTER]`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use dqsym::{Context, FkOptions, Robot, Scalar};
use std::time::Duration;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn robot(path: &str) -> Robot {
    let text = std::fs::read_to_string(format!("{ROOT}/{path}")).expect("robot file");
    dqsym::parse_robot(&text, path, &dqsym::eval_scalar_text).expect("robot")
}

/// A revolute DH chain of `n` joints whose every length and twist is a symbol.
fn symbolic_chain(n: usize) -> Robot {
    let mut s = String::from("convention = \"dh\"\n");
    for i in 1..=n {
        s += &format!(
            "[[joint]]\ntype = \"revolute\"\ntheta = \"theta{i}\"\nd = \"d{i}\"\na = \"a{i}\"\nalpha = \"alpha{i}\"\n"
        );
    }
    dqsym::parse_robot(&s, "symbolic.toml", &dqsym::eval_scalar_text).expect("robot")
}

fn scalar(text: &str) -> Scalar {
    dqsym::eval_scalar_text(text).expect("scalar")
}

/// The binary's limits for one command, on one thread.
fn context() -> Context {
    Context::new()
        .with_term_limit(5_000)
        .with_work_budget(3_000_000)
        .with_threads(1)
}

fn fk_jacobian(c: &mut Criterion) {
    let o = FkOptions {
        jacobian: true,
        max_terms: 5_000,
        ..FkOptions::default()
    };
    let robots = [
        ("puma560", robot("examples/robots/puma560.toml")),
        ("symbolic_4r", symbolic_chain(4)),
        ("symbolic_6r", robot("tests/data/generic_6r.toml")),
        ("jaco_style", robot("tests/data/jaco_style.toml")),
    ];
    let mut g = c.benchmark_group("guarded_fk_jacobian");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for (name, r) in &robots {
        g.bench_function(*name, |b| {
            b.iter(|| {
                let _entered = context().enter();
                black_box(dqsym::fk_report(r, &o).expect("report"))
            })
        });
    }
    g.finish();
}

fn closed_forms(c: &mut Criterion) {
    let cases = [
        ("sin1_sin2_sin3", scalar("sin(1)*sin(2)*sin(3)")),
        ("cos1_cos2_cos3_cos4", scalar("cos(1)*cos(2)*cos(3)*cos(4)")),
        ("sin_x_sin_2x_sin_3x", scalar("sin(x)*sin(2*x)*sin(3*x)")),
    ];
    let mut g = c.benchmark_group("guarded_closed_form");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for (name, x) in &cases {
        g.bench_function(*name, |b| {
            b.iter(|| {
                let _entered = context().enter();
                black_box(dqsym::closed_form(x).expect("closed form"))
            })
        });
    }
    g.finish();
}

fn expansion(c: &mut Criterion) {
    let mut g = c.benchmark_group("guarded_expansion");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    let s = scalar("x + y + z");
    g.bench_function("x_plus_y_plus_z_pow_30", |b| {
        b.iter(|| {
            let _entered = Context::new().with_threads(1).enter();
            black_box(s.pow(30))
        })
    });
    g.finish();
}

criterion_group!(benches, fk_jacobian, closed_forms, expansion);
criterion_main!(benches);
