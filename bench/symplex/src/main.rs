//! The benchmark workloads of `bench/compare`, done with symplex the way a robotics user would:
//! DH matrices and DH dual quaternions multiplied symbolically, expanded, then simplified.
//! `symplex-bench W2` prints one JSON line per finished stage (flushed), so a caller that
//! kills the process at its time limit still sees the stages that finished.

use std::io::Write;
use std::time::Instant;
use symplex::expr::ExprType;
use symplex::prelude::*;
use symplex::robotics::dh_matrix;

/// `(theta, d, a, alpha)` of one DH link.
type Dh = [Ex; 4];

fn planar(ctx: &Context, n: usize) -> Vec<Dh> {
    (1..=n)
        .map(|i| {
            [
                ctx.symbol(&format!("theta{i}")),
                ctx.int(0),
                ctx.symbol(&format!("l{i}")),
                ctx.int(0),
            ]
        })
        .collect()
}

fn puma(ctx: &Context) -> Vec<Dh> {
    let alpha = [(1, 2), (0, 1), (-1, 2), (1, 2), (-1, 2), (0, 1)];
    let d = ["0", "0", "d3", "d4", "0", "0"];
    let a = ["0", "a2", "a3", "0", "0", "0"];
    let v = |s: &str| if s == "0" { ctx.int(0) } else { ctx.symbol(s) };
    (0..6)
        .map(|i| {
            [
                ctx.symbol(&format!("theta{}", i + 1)),
                v(d[i]),
                v(a[i]),
                &ctx.pi() * &ctx.rational(alpha[i].0, alpha[i].1),
            ]
        })
        .collect()
}

fn generic(ctx: &Context, n: usize) -> Vec<Dh> {
    (1..=n)
        .map(|i| {
            [
                ctx.symbol(&format!("theta{i}")),
                ctx.symbol(&format!("d{i}")),
                ctx.symbol(&format!("a{i}")),
                ctx.symbol(&format!("alpha{i}")),
            ]
        })
        .collect()
}

fn matmul(x: &[Vec<Ex>], y: &[Vec<Ex>]) -> Vec<Vec<Ex>> {
    (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let mut s = &x[i][0] * &y[0][j];
                    for k in 1..4 {
                        s = &s + &(&x[i][k] * &y[k][j]);
                    }
                    s.expand()
                })
                .collect()
        })
        .collect()
}

/// The 4x4 product of the links' DH matrices, expanded after each product.
fn matrix_chain(links: &[Dh]) -> Vec<Vec<Ex>> {
    let mut acc: Option<Vec<Vec<Ex>>> = None;
    for l in links {
        let m = dh_matrix(&l[0], &l[1], &l[2], &l[3]);
        let m: Vec<Vec<Ex>> = (0..4)
            .map(|i| (0..4).map(|j| m.get(i, j).clone()).collect())
            .collect();
        acc = Some(match acc {
            None => m,
            Some(a) => matmul(&a, &m),
        });
    }
    acc.expect("at least one link")
}

type Q = [Ex; 4];

fn qmul(a: &Q, b: &Q) -> Q {
    let [w1, x1, y1, z1] = a;
    let [w2, x2, y2, z2] = b;
    let p = |u: &Ex, v: &Ex| u * v;
    [
        &(&(&p(w1, w2) - &p(x1, x2)) - &p(y1, y2)) - &p(z1, z2),
        &(&(&p(w1, x2) + &p(x1, w2)) + &p(y1, z2)) - &p(z1, y2),
        &(&(&p(w1, y2) - &p(x1, z2)) + &p(y1, w2)) + &p(z1, x2),
        &(&(&p(w1, z2) + &p(x1, y2)) - &p(y1, x2)) + &p(z1, w2),
    ]
}

fn qadd(a: &Q, b: &Q) -> Q {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2], &a[3] + &b[3]]
}

/// One DH link as a unit dual quaternion `r + eps t r / 2`, r = Rz(theta) Rx(alpha),
/// t = (a cos theta, a sin theta, d).
fn dh_dq(ctx: &Context, l: &Dh) -> [Ex; 8] {
    let half = ctx.rational(1, 2);
    let (th, al) = (&l[0] * &half, &l[3] * &half);
    let z = ctx.int(0);
    let rz: Q = [th.cos(), z.clone(), z.clone(), th.sin()];
    let rx: Q = [al.cos(), al.sin(), z.clone(), z.clone()];
    let r = qmul(&rz, &rx);
    let t: Q = [
        z.clone(),
        &(&l[2] * &l[0].cos()) * &half,
        &(&l[2] * &l[0].sin()) * &half,
        &l[1] * &half,
    ];
    let d = qmul(&t, &r);
    let e = |x: &Ex| x.expand();
    [
        e(&r[0]),
        e(&r[1]),
        e(&r[2]),
        e(&r[3]),
        e(&d[0]),
        e(&d[1]),
        e(&d[2]),
        e(&d[3]),
    ]
}

fn dq_chain(ctx: &Context, links: &[Dh]) -> Vec<Ex> {
    let mut acc: Option<[Ex; 8]> = None;
    for l in links {
        let q = dh_dq(ctx, l);
        acc = Some(match acc {
            None => q,
            Some(a) => {
                let (ar, ad): (Q, Q) = (
                    [a[0].clone(), a[1].clone(), a[2].clone(), a[3].clone()],
                    [a[4].clone(), a[5].clone(), a[6].clone(), a[7].clone()],
                );
                let (br, bd): (Q, Q) = (
                    [q[0].clone(), q[1].clone(), q[2].clone(), q[3].clone()],
                    [q[4].clone(), q[5].clone(), q[6].clone(), q[7].clone()],
                );
                let r = qmul(&ar, &br);
                let d = qadd(&qmul(&ar, &bd), &qmul(&ad, &br));
                let e = |x: &Ex| x.expand();
                [
                    e(&r[0]),
                    e(&r[1]),
                    e(&r[2]),
                    e(&r[3]),
                    e(&d[0]),
                    e(&d[1]),
                    e(&d[2]),
                    e(&d[3]),
                ]
            }
        });
    }
    acc.expect("at least one link").to_vec()
}

#[derive(Default, Clone, Copy)]
struct Size {
    ops: usize,
    calls: usize,
}

/// Counts + - * / and calls the way dqsym's `Expr::cost` does: a sum of n terms is n - 1 ops
/// (negative terms free), a product of n factors n - 1, a non-integer rational one division,
/// `x^n` n - 1 multiplications, `sqrt` and each cos/sin call one op and one call, the angle
/// argument of cos/sin not counted.
fn count(e: &Ex, in_sum: bool, s: &mut Size) {
    let args = e.args();
    match e.expr_type() {
        ExprType::Number => {
            let t = e.to_string();
            if t.contains('/') {
                s.ops += 1;
            }
        }
        ExprType::Symbol | ExprType::Constant => {}
        ExprType::Add => {
            s.ops += args.len().saturating_sub(1);
            for a in &args {
                count(a, true, s);
            }
        }
        ExprType::Mul => {
            let mut n: usize = 0;
            let mut neg = false;
            for a in &args {
                if a.expr_type() == ExprType::Number && a.to_string() == "-1" {
                    neg = true;
                    continue;
                }
                n += 1;
                count(a, false, s);
            }
            s.ops += n.saturating_sub(1);
            if neg && !in_sum {
                s.ops += 1;
            }
        }
        ExprType::Neg => {
            if !in_sum {
                s.ops += 1;
            }
            for a in &args {
                count(a, false, s);
            }
        }
        ExprType::Pow => {
            let ex = args[1].to_string();
            match ex.parse::<i64>() {
                Ok(n) if n >= 1 => s.ops += (n - 1) as usize,
                Ok(n) => s.ops += n.unsigned_abs() as usize,
                Err(_) if ex == "1/2" => {
                    s.ops += 1;
                    s.calls += 1;
                }
                Err(_) => {
                    s.ops += 1;
                    s.calls += 1;
                    count(&args[1], false, s);
                }
            }
            count(&args[0], false, s);
        }
        _ => {
            let name = e.to_string();
            s.ops += 1;
            s.calls += 1;
            if !(name.starts_with("sin(") || name.starts_with("cos(")) {
                for a in &args {
                    count(a, false, s);
                }
            }
        }
    }
}

fn size(xs: &[Ex]) -> Size {
    let mut s = Size::default();
    for x in xs {
        count(x, false, &mut s);
    }
    s
}

fn report(stage: &str, t: Instant, xs: &[Ex]) {
    let secs = t.elapsed().as_secs_f64();
    let s = size(xs);
    println!(
        "{{\"stage\": \"{stage}\", \"seconds\": {secs:.6}, \"ops\": {}, \"calls\": {}, \"entries\": {}}}",
        s.ops,
        s.calls,
        xs.len()
    );
    std::io::stdout().flush().ok();
}

fn flat(m: &[Vec<Ex>], rows: usize, cols: &[usize]) -> Vec<Ex> {
    (0..rows)
        .flat_map(|i| cols.iter().map(move |&j| m[i][j].clone()))
        .collect()
}

/// Expands, then tries the two trig simplifiers on every entry (each timed from the start).
fn stages(name: &str, t: Instant, xs: Vec<Ex>) {
    report(&format!("{name}expand"), t, &xs);
    let ys: Vec<Ex> = xs.iter().map(Ex::trig_combine).collect();
    report(&format!("{name}trig_combine"), t, &ys);
    let ys: Vec<Ex> = xs.iter().map(Ex::simplify).collect();
    report(&format!("{name}simplify"), t, &ys);
}

fn main() {
    let w = std::env::args().nth(1).unwrap_or_default();
    let ctx = Context::new();
    let t = Instant::now();
    match w.as_str() {
        "W1" => stages("", t, flat(&matrix_chain(&planar(&ctx, 3)), 2, &[3])),
        "W2" => {
            stages(
                "matrix:",
                t,
                flat(&matrix_chain(&puma(&ctx)), 3, &[0, 1, 2, 3]),
            );
            let t = Instant::now();
            stages("dq:", t, dq_chain(&ctx, &puma(&ctx)));
        }
        "W3" => {
            let m = flat(&matrix_chain(&generic(&ctx, 6)), 3, &[0, 1, 2, 3]);
            report("matrix:expand", t, &m);
            let t = Instant::now();
            report("dq:expand", t, &dq_chain(&ctx, &generic(&ctx, 6)));
        }
        "W4" => {
            let links = puma(&ctx);
            let q = dq_chain(&ctx, &links);
            let j: Vec<Ex> = q
                .iter()
                .flat_map(|c| links.iter().map(|l| c.diff(&l[0]).expand()))
                .collect();
            stages("", t, j);
        }
        "W5" => stages("", t, flat(&matrix_chain(&planar(&ctx, 20)), 2, &[3])),
        _ => {
            eprintln!("usage: symplex-bench W1|W2|W3|W4|W5");
            std::process::exit(2);
        }
    }
}
