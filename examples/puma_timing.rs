//! PUMA 560 forward kinematics as dual quaternions: timing of the product, the matrix and the
//! closed forms. `cargo run --release --example puma_timing [-- --dump]`; `--dump` prints every
//! result (canonical forms and closed forms) so two builds can be compared textually.

use dqsym::{closed_form, kin::dh_link, plain, DualQuat, PlainOptions, Ring, Scalar};
use std::time::{Duration, Instant};

fn links() -> Vec<DualQuat<Scalar>> {
    let pi = Scalar::pi();
    let alpha = [(1, 2), (0, 1), (-1, 2), (1, 2), (-1, 2), (0, 1)];
    (0..6)
        .map(|i| {
            let th = Scalar::sym(&format!("theta{}", i + 1));
            let a = match i {
                1 => Scalar::sym("a2"),
                2 => Scalar::sym("a3"),
                _ => Scalar::int(0),
            };
            let d = match i {
                2 => Scalar::sym("d3"),
                3 => Scalar::sym("d4"),
                _ => Scalar::int(0),
            };
            let (n, m) = alpha[i];
            dh_link(&th, &d, &a, &(&pi * &<Scalar as Ring>::from_ratio(n, m)))
        })
        .collect()
}

fn product(links: &[DualQuat<Scalar>]) -> DualQuat<Scalar> {
    let mut acc = links[0].clone();
    for l in &links[1..] {
        acc = acc * l;
    }
    acc
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn main() {
    let dump = std::env::args().any(|a| a == "--dump");
    let runs: usize = std::env::args()
        .skip_while(|a| a != "--runs")
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(if dump { 1 } else { 15 });
    let links = links();
    let (mut tp, mut tm, mut tcm, mut tcd) = (vec![], vec![], vec![], vec![]);
    for _ in 0..runs {
        let t = Instant::now();
        let acc = product(&links);
        tp.push(t.elapsed());

        let t = Instant::now();
        let m = acc.to_matrix();
        tm.push(t.elapsed());

        let t = Instant::now();
        let mut mat_forms = vec![];
        for row in &m.rows[..3] {
            for e in row {
                mat_forms.push(closed_form(e).expect("closed form"));
            }
        }
        tcm.push(t.elapsed());

        let t = Instant::now();
        let dq_forms: Vec<_> = acc
            .components()
            .iter()
            .map(|x| closed_form(x).expect("closed form"))
            .collect();
        tcd.push(t.elapsed());

        if dump {
            let opts = PlainOptions::default();
            for (k, x) in acc.components().iter().enumerate() {
                println!("dq{k} = {x}");
            }
            for (k, row) in m.rows.iter().enumerate() {
                for (j, x) in row.iter().enumerate() {
                    println!("T{k}{j} = {x}");
                }
            }
            for (k, e) in mat_forms.iter().enumerate() {
                println!("closed T{}{} = {}", k / 4, k % 4, plain(e, &opts));
            }
            for (k, e) in dq_forms.iter().enumerate() {
                println!("closed dq{k} = {}", plain(e, &opts));
            }
        }
    }
    let terms: Vec<usize> = product(&links)
        .components()
        .iter()
        .map(Scalar::len)
        .collect();
    eprintln!(
        "median of {runs}: product {:?}  to_matrix {:?}  closed(matrix) {:?}  closed(dq) {:?}  terms {terms:?}",
        median(tp),
        median(tm),
        median(tcm),
        median(tcd)
    );
}
