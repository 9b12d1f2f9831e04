//! Tables 1 and 2 of the paper, reproduced by counting the operations products actually do
//! (ERRATA 10: the DQ product is 48 + 40 = 88; the homogeneous product is 48/36 for the top three
//! rows, 36/27 exploiting the constant last row, 64/48 in full; ERRATA 11: a chain of n 3x3
//! rotations costs 27(n - 1) multiplications and 18(n - 1) additions).

use crate::common::Rng;
use dqsym::{count_ops, generated_ops, Counted, DualQuat, Matrix4, OpCount, Quat};

fn rand(rng: &mut Rng) -> Counted {
    Counted(rng.range(-1.0, 1.0))
}

fn quat(rng: &mut Rng) -> Quat<Counted> {
    Quat::new(rand(rng), rand(rng), rand(rng), rand(rng))
}

fn mat3(rng: &mut Rng) -> [[Counted; 3]; 3] {
    std::array::from_fn(|_| std::array::from_fn(|_| rand(rng)))
}

/// The naive 3x3 product.
fn mul3(a: &[[Counted; 3]; 3], b: &[[Counted; 3]; 3]) -> [[Counted; 3]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

/// The top three rows of a 4x4 product, every entry a sum of four products.
fn mul_top_rows(a: &Matrix4<Counted>, b: &Matrix4<Counted>) -> [[Counted; 4]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..4)
                .map(|k| a.rows[i][k] * b.rows[k][j])
                .reduce(|x, y| x + y)
                .unwrap()
        })
    })
}

/// `(R1, t1)(R2, t2) = (R1 R2, R1 t2 + t1)`: the homogeneous product that knows the last row is
/// `(0, 0, 0, 1)`.
fn mul_rigid(
    (r1, t1): &([[Counted; 3]; 3], [Counted; 3]),
    (r2, t2): &([[Counted; 3]; 3], [Counted; 3]),
) -> ([[Counted; 3]; 3], [Counted; 3]) {
    let r = mul3(r1, r2);
    let t = std::array::from_fn(|i| r1[i][0] * t2[0] + r1[i][1] * t2[1] + r1[i][2] * t2[2] + t1[i]);
    (r, t)
}

fn ops(c: OpCount) -> (usize, usize) {
    (c.mul, c.add)
}

/// Counts of one product each: 3x3, quaternion, DQ, full 4x4, top three rows, rigid.
fn table() -> [(&'static str, OpCount); 6] {
    let mut rng = Rng::new(2);
    let (a3, b3) = (mat3(&mut rng), mat3(&mut rng));
    let (p, q) = (quat(&mut rng), quat(&mut rng));
    let dq = |rng: &mut Rng| DualQuat::from_real_and_dual(quat(rng), quat(rng));
    let (pd, qd) = (dq(&mut rng), dq(&mut rng));
    let m4 = |rng: &mut Rng| {
        Matrix4::from_rows(std::array::from_fn(|_| std::array::from_fn(|_| rand(rng))))
    };
    let (a, b) = (m4(&mut rng), m4(&mut rng));
    let rigid = |rng: &mut Rng| (mat3(rng), [rand(rng), rand(rng), rand(rng)]);
    let (x, y) = (rigid(&mut rng), rigid(&mut rng));
    [
        (
            "3x3 rotation matrix product",
            count_ops(|| mul3(&a3, &b3)).1,
        ),
        ("quaternion product", count_ops(|| &p * &q).1),
        ("dual quaternion product", count_ops(|| &pd * &qd).1),
        ("4x4 product, full", count_ops(|| &a * &b).1),
        (
            "4x4 product, top three rows",
            count_ops(|| mul_top_rows(&a, &b)).1,
        ),
        (
            "4x4 product, constant last row exploited",
            count_ops(|| mul_rigid(&x, &y)).1,
        ),
    ]
}

#[test]
fn table1_rotations_3x3_is_27_18_and_quaternion_16_12() {
    let t = table();
    assert_eq!(ops(t[0].1), (27, 18));
    assert_eq!(ops(t[1].1), (16, 12));
    assert_eq!(t[1].1.neg, 0);
}

#[test]
fn table2_rigid_dq_is_48_40_and_homogeneous_64_48_or_48_36_or_36_27() {
    let t = table();
    assert_eq!(ops(t[2].1), (48, 40), "ERRATA 10: 88 in all, not 84");
    assert_eq!(ops(t[3].1), (64, 48));
    assert_eq!(ops(t[4].1), (48, 36));
    assert_eq!(ops(t[5].1), (36, 27));
}

#[test]
fn sec7_chains_of_n_rotations_cost_27_and_18_per_product() {
    let mut rng = Rng::new(3);
    for n in [2usize, 3, 6] {
        let ms: Vec<_> = (0..n).map(|_| mat3(&mut rng)).collect();
        let (_, c) = count_ops(|| ms[1..].iter().fold(ms[0], |acc, m| mul3(&acc, m)));
        assert_eq!(ops(c), (27 * (n - 1), 18 * (n - 1)), "ERRATA 11, n = {n}");
    }
}

#[test]
fn generated_puma560_pose_costs_fewer_products_than_the_dq_chain() {
    let outs = crate::codegen::puma_outputs();
    let args = dqsym::arguments(
        &outs,
        &["theta1", "theta2", "theta3", "theta4", "theta5", "theta6"],
    );
    let dq_only = &outs[..1];
    let c = generated_ops(dq_only, &args, &Default::default()).unwrap();
    // The chain of six DH links: five DQ products of 88 operations each, six sin_cos.
    assert_eq!(c.trig, 12, "one sin_cos (two calls) per joint: {c:?}");
    assert!(c.mul + c.add < 5 * 88, "{c:?}");
    let all = generated_ops(&outs, &args, &Default::default()).unwrap();
    assert_eq!(
        all.trig, 12,
        "the matrix shares the joints' sin_cos: {all:?}"
    );
    let mut report = String::from("Tables 1 and 2 (ERRATA 10, 11), counted: mult, add\n");
    for (name, c) in table() {
        report.push_str(&format!(
            "{name}: {}, {} (total {})\n",
            c.mul,
            c.add,
            c.mul + c.add
        ));
    }
    for (name, c) in [("DQ", c), ("DQ + 3x4 matrix", all)] {
        report.push_str(&format!(
            "generated PUMA 560 {name}: {} mult, {} add, {} neg, {} sin/cos\n",
            c.mul, c.add, c.neg, c.trig
        ));
    }
    crate::common::snapshot_settings().bind(|| insta::assert_snapshot!("op_counts", report));
}
