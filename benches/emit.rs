//! The generated PUMA 560 forward kinematics against a hand-written chain of nalgebra
//! `UnitDualQuaternion` products, side by side.
#![allow(clippy::excessive_precision)]

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use nalgebra::{Translation3, UnitDualQuaternion, UnitQuaternion, Vector3};
use std::f64::consts::FRAC_PI_2;

// Not a file of its own under benches/: Cargo would take it for a bench target, rustfmt would
// reformat it.
include!("generated/puma560_dq.rs");

const A2: f64 = 0.4318;
const A3: f64 = 0.0203;
const D3: f64 = 0.15005;
const D4: f64 = 0.4318;

/// The constant part of each DH link, `Trans_x(a) Rot_x(alpha)`, built once.
fn constant_parts() -> [UnitDualQuaternion<f64>; 6] {
    let alpha = [FRAC_PI_2, 0.0, -FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2, 0.0];
    let a = [0.0, A2, A3, 0.0, 0.0, 0.0];
    std::array::from_fn(|i| {
        UnitDualQuaternion::from_parts(
            Translation3::new(a[i], 0.0, 0.0),
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), alpha[i]),
        )
    })
}

/// The chain `prod Rot_z(theta_i) Trans_z(d_i) C_i`, as one would write it with nalgebra.
fn nalgebra_chain(q: &[f64; 6], c: &[UnitDualQuaternion<f64>; 6]) -> UnitDualQuaternion<f64> {
    let d = [0.0, 0.0, D3, D4, 0.0, 0.0];
    let mut t = UnitDualQuaternion::identity();
    for i in 0..6 {
        let screw = UnitDualQuaternion::from_parts(
            Translation3::new(0.0, 0.0, d[i]),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), q[i]),
        );
        t = t * screw * c[i];
    }
    t
}

fn generated(q: &[f64; 6]) -> [f64; 8] {
    puma560_dq(q[0], q[1], q[2], q[3], q[4], q[5], A2, A3, D3, D4).dq
}

fn agree(q: &[f64; 6], c: &[UnitDualQuaternion<f64>; 6]) {
    let n = nalgebra_chain(q, c);
    let (r, d) = (n.as_ref().real, n.as_ref().dual);
    let theirs = [r.w, r.i, r.j, r.k, d.w, d.i, d.j, d.k];
    let ours = generated(q);
    // A unit DQ and its negative are the same pose.
    let sign = if (ours[0] - theirs[0]).abs() < (ours[0] + theirs[0]).abs() {
        1.0
    } else {
        -1.0
    };
    for k in 0..8 {
        assert!(
            (ours[k] - sign * theirs[k]).abs() < 1e-12,
            "component {k}: {ours:?} vs {theirs:?}"
        );
    }
}

fn bench(cr: &mut Criterion) {
    let c = constant_parts();
    let q = [0.3, -0.7, 1.1, 0.25, -1.3, 2.0];
    agree(&q, &c);
    agree(&[-2.0, 0.1, 0.4, -0.9, 0.6, 1.5], &c);
    let mut g = cr.benchmark_group("puma560_fk_dq");
    g.bench_function("generated", |b| b.iter(|| generated(black_box(&q))));
    g.bench_function("nalgebra_chain", |b| {
        b.iter(|| nalgebra_chain(black_box(&q), black_box(&c)))
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(std::time::Duration::from_secs(1))
        .measurement_time(std::time::Duration::from_secs(3));
    targets = bench
}
criterion_main!(benches);
