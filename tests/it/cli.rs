//! The binary, driven as a user would.

use std::process::Command;

#[test]
fn paper_command_prints_the_rrr_end_effector_in_shorthand() {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .arg("paper")
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(text.contains("v0.y = l1 c1 + l2 c12 + l3 c123"), "{text}");
    assert!(text.contains("T[2][3] = a2 s2 + a3 s23 + d4 c23"), "{text}");
}

#[test]
fn paper_command_explicit_form() {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .args(["paper", "--explicit"])
        .output()
        .expect("runs");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(
        text.contains(
            "l1*cos(theta1) + l2*cos(theta1 + theta2) + l3*cos(theta1 + theta2 + theta3)"
        ),
        "{text}"
    );
}

#[test]
fn unknown_command_exits_with_status_2_not_a_panic() {
    let out = Command::new(env!("CARGO_BIN_EXE_dqsym"))
        .arg("frobnicate")
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2));
}
