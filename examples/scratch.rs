use dqsym::*;
use std::time::Instant;
fn q(n: i64, d: i64) -> Scalar {
    <Scalar as Ring>::from_ratio(n, d)
}
fn main() {
    let pi = Scalar::pi();
    let alpha = [q(1, 2), q(0, 1), q(-1, 2), q(1, 2), q(-1, 2), q(0, 1)];
    let a = [
        Scalar::int(0),
        Scalar::int(0),
        Scalar::sym("a2"),
        Scalar::sym("a3"),
        Scalar::int(0),
        Scalar::int(0),
    ];
    let d = [
        Scalar::int(0),
        Scalar::int(0),
        Scalar::sym("d3"),
        Scalar::sym("d4"),
        Scalar::int(0),
        Scalar::int(0),
    ];
    // Standard DH PUMA: a_i of link i: a2 on link 2, a3 on link 3; d3 on link 3, d4 on link 4.
    let links: Vec<_> = (0..6)
        .map(|i| {
            let th = Scalar::sym(&format!("theta{}", i + 1));
            let ai = match i {
                1 => Scalar::sym("a2"),
                2 => Scalar::sym("a3"),
                _ => Scalar::int(0),
            };
            let di = match i {
                2 => Scalar::sym("d3"),
                3 => Scalar::sym("d4"),
                _ => Scalar::int(0),
            };
            dh_link(&th, &di, &ai, &(&pi * &alpha[i]))
        })
        .collect();
    let _ = (a, d);
    for _ in 0..1 {
        let t = Instant::now();
        let mut acc = links[0].clone();
        for l in &links[1..] {
            acc = acc * l;
        }
        let el = t.elapsed();
        let t2 = Instant::now();
        let m = acc.to_matrix();
        let el2 = t2.elapsed();
        let t3 = Instant::now();
        let mut tot = Cost::default();
        let mut outs = vec![];
        for i in 0..3 {
            for j in 0..4 {
                let e = closed_form(&m.rows[i][j]).unwrap();
                let c = e.cost();
                tot.ops += c.ops;
                tot.calls += c.calls;
                outs.push(e);
            }
        }
        let el3 = t3.elapsed();
        let t4 = Instant::now();
        let dqc: Vec<_> = acc
            .components()
            .iter()
            .map(|x| closed_form(x).unwrap())
            .collect();
        let el4 = t4.elapsed();
        println!("product {:?} matrix {:?} closed(matrix) {:?} closed(dq) {:?} total cost {:?} terms {:?}", el, el2, el3, el4, tot, acc.components().iter().map(|x| x.len()).collect::<Vec<_>>());
        if true {
            for (k, e) in outs.iter().enumerate() {
                println!(
                    "T{}{} = {}",
                    k / 4,
                    k % 4,
                    plain(e, &PlainOptions::default())
                );
            }
            for (k, e) in dqc.iter().enumerate() {
                println!(
                    "dq{} = {}  {:?}",
                    k,
                    plain(e, &PlainOptions::default()),
                    e.cost()
                );
            }
        }
    }
}
