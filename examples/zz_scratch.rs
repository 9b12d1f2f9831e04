use dqsym::*;
fn main() {
    let text = std::fs::read_to_string("examples/robots/puma560.toml").unwrap();
    let robot = parse_robot(&text, "p", &eval_scalar_text).unwrap();
    let q = robot.forward_within(5000).unwrap();
    let vars: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
    let m = robot.forward_matrix();
    let j = dq_jacobian(&q, &vars);
    let mut all: Vec<Scalar> = Vec::new();
    for c in q.components() {
        all.push(c);
    }
    for i in 0..3 {
        for k in 0..4 {
            all.push(m.rows[i][k].clone());
        }
    }
    for r in j.iter() {
        for x in r.iter() {
            all.push(x.clone());
        }
    }
    let mut d: Vec<Scalar> = vec![];
    let mut ds: Vec<Scalar> = vec![];
    for x in &all {
        if !d.contains(x) {
            d.push(x.clone());
        }
        let nx = -x.clone();
        if !ds.contains(x) && !ds.contains(&nx) {
            ds.push(x.clone());
        }
    }
    println!(
        "all {} distinct {} up to sign {}",
        all.len(),
        d.len(),
        ds.len()
    );
}
