//! Tables 1 and 2 of the paper, reproduced by counting the operations products actually do
//! (ERRATA 10: the DQ product is 48 + 40 = 88; the homogeneous product is 48/36 for the top three
//! rows, 36/27 exploiting the constant last row, 64/48 in full; ERRATA 11: a chain of n 3x3
//! rotations costs 27(n - 1) multiplications and 18(n - 1) additions).

use dqsym::emit::{generated_ops, OpCount};

fn ops(c: OpCount) -> (usize, usize) {
    (c.mul, c.add)
}

fn table() -> Vec<(&'static str, OpCount)> {
    dqsym::emit::product_table()
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
    for n in [2usize, 3, 6] {
        let c = dqsym::emit::rotation_chain_ops(n);
        assert_eq!(ops(c), (27 * (n - 1), 18 * (n - 1)), "ERRATA 11, n = {n}");
    }
}

#[test]
fn generated_puma560_pose_costs_fewer_products_than_the_dq_chain() {
    let outs = crate::codegen::puma_outputs();
    let args = dqsym::emit::arguments(
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
