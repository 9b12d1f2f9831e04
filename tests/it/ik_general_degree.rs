//! The degree the general method states is the count of roots that are solutions
//! (`ik::general::closure`): arms of a family forced through `--method general` whose `det M`
//! has roots that move with the target yet are no solutions (the IRB 140, the paper's
//! Puma-like robot: 16 moving roots) state the family's solution count, the product of its
//! steps' branch counts, computed independently by the family's closed forms.

use dqsym::ik::{solve, IkMethod, IkOptions};

#[test]
fn forced_general_states_the_roots_that_are_solutions() {
    for file in [
        "irb140",
        "puma_like",
        "puma560",
        "stanford",
        "kuka_kr5",
        "ur5",
        "ur10",
    ] {
        let path = format!("{}/examples/robots/{file}.toml", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).expect("robot file");
        let robot = dqsym::parse_robot(&text, &path, &dqsym::eval_scalar_text).expect("robot");
        let derive = |method| solve(&robot, &IkOptions { free: None, method }).expect("ik");
        let family = derive(IkMethod::Auto);
        assert!(family.general.is_none(), "{file}: {}", family.family);
        let count: usize = family.steps.iter().map(|s| s.formula.branches()).product();
        let degree = derive(IkMethod::General).general.expect("general").degree;
        eprintln!("{file}: forced general, degree {degree}, the family's {count} solutions");
        assert_eq!(degree, count, "{file}");
    }
}
