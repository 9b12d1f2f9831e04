use dqsym::*;
fn main() {
    let c = |n: &str| Scalar::sym(n).cos();
    let s = |n: &str| Scalar::sym(n).sin();
    let (l1, l2, l3) = (Scalar::sym("l1"), Scalar::sym("l2"), Scalar::sym("l3"));
    // p3 = (l3, 0); p2 = (l2,0) + R3 p3; p1 = (l1,0) + R2 p2; p0 = R1 p1
    let rot = |t: &str, p: (Scalar, Scalar)| (c(t) * &p.0 - s(t) * &p.1, s(t) * &p.0 + c(t) * &p.1);
    let p2 = rot("theta3", (l3.clone(), Scalar::int(0)));
    let p1 = rot("theta2", (l2 + p2.0, p2.1));
    let p0 = rot("theta1", (l1 + p1.0, p1.1));
    for x in [&p0.0, &p0.1] {
        let e = closed_form(x).unwrap();
        println!("{}   [{:?}]", plain(&e, &PlainOptions::default()), e.cost());
        println!("{}", plain(&e, &PlainOptions { shorthand: false }));
    }
    let e = closed_form(&p0.0).unwrap();
    println!("{:?}", legend(&[&e]));
    // half angle
    let h = Scalar::sym("t") * <Scalar as Ring>::from_ratio(1, 2);
    let x = Scalar::int(2) * h.sin().pow(2) * Scalar::sym("y") + Scalar::sym("l") * h.cos();
    println!(
        "{}",
        plain(&closed_form(&x).unwrap(), &PlainOptions::default())
    );
}
