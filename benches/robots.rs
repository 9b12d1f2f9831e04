//! Robot descriptions: reading robot files and URDF, converting URDF to a robot file, and
//! `fk --jacobian` (the report `dqsym fk` prints, at its default term limit of 5,000) for the
//! 10-joint numeric DH chains of the Robotics Toolbox (Ball, Coil, the planar Hyper) and the
//! 7-joint arms (Panda, LWR4, iiwa) next to the PUMA 560. Short measurements:
//! `cargo bench --bench robots [-- FILTER]`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::time::Duration;

const ROBOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/robots/");
const UR5_URDF: &str = include_str!("support/ur5.urdf");

fn robot_file(file: &str) -> String {
    std::fs::read_to_string(format!("{ROBOTS}{file}.toml")).expect("robot file")
}

fn parse(text: &str) -> dqsym::Robot {
    dqsym::parse_robot(text, "bench.toml", &dqsym::eval_scalar_text).expect("robot")
}

/// A chain of `n` revolute DH links `a`, `alpha` (RTB's Ball: 0.1, pi/2; Coil: 1/n, 5 pi/n;
/// Hyper: 1/n, 0).
fn dh_chain(n: usize, a: &str, alpha: &str) -> String {
    let mut s = String::from("convention = \"dh\"\n");
    for i in 1..=n {
        s += &format!(
            "[[joint]]\ntype = \"revolute\"\ntheta = \"q{i}\"\nd = 0\na = \"{a}\"\nalpha = \"{alpha}\"\n"
        );
    }
    s
}

fn loading(c: &mut Criterion) {
    let mut g = c.benchmark_group("load");
    g.sample_size(20).measurement_time(Duration::from_secs(2));
    for name in ["puma560", "panda", "ur5"] {
        let text = robot_file(name);
        g.bench_function(format!("robot_file_{name}"), |b| {
            b.iter(|| black_box(parse(&text)))
        });
    }
    let o = dqsym::kin::UrdfOptions::default();
    g.bench_function("urdf_ur5", |b| {
        b.iter(|| black_box(dqsym::parse_urdf(UR5_URDF, "ur5.urdf", &o).expect("urdf")))
    });
    let ur5 = dqsym::parse_urdf(UR5_URDF, "ur5.urdf", &o)
        .expect("urdf")
        .robot;
    g.bench_function("convert_ur5_to_dh", |b| {
        b.iter(|| black_box(dqsym::app::robot_toml(&ur5, "ur5.urdf").expect("toml")))
    });
    g.finish();
}

fn fk_jacobian(c: &mut Criterion) {
    let ctx = dqsym::Context::new().with_term_limit(5_000);
    let _entered = ctx.enter();
    let o = dqsym::FkOptions {
        jacobian: true,
        max_terms: 5_000,
        ..dqsym::FkOptions::default()
    };
    let mut robots: Vec<(String, dqsym::Robot)> = vec![
        ("ball10".into(), parse(&dh_chain(10, "0.1", "pi/2"))),
        ("coil10".into(), parse(&dh_chain(10, "1/10", "5*pi/10"))),
        ("hyper10".into(), parse(&dh_chain(10, "1/10", "0"))),
    ];
    for name in ["panda", "lwr4", "kuka_iiwa7", "puma560"] {
        robots.push((name.into(), parse(&robot_file(name))));
    }
    let mut g = c.benchmark_group("fk_jacobian");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for (name, r) in &robots {
        g.bench_function(name.as_str(), |b| {
            b.iter(|| black_box(dqsym::fk_report(r, &o).expect("report")))
        });
    }
    g.finish();
}

criterion_group!(benches, loading, fk_jacobian);
criterion_main!(benches);
