//! dqsym's side of `bench/compare`: the workloads W1-W5, each timed in-process (median of
//! `--runs N`, default 5), printed as one JSON object per line with the size of the result
//! (operations and trig calls of the closed forms, by `Expr::cost`).
//!
//! `cargo run --release --example bench_workloads [-- --runs N] [--term-limit N] [--trace]
//! [W1 W2 W3 W4 W5 W5full]`
//!
//! W1 planar RRR end effector (DH); W2 PUMA 560 pose, DQ and 4x4, in closed form; W3 a generic
//! 6R with every DH parameter symbolic, expanded (the 4x4 as a polynomial in the cosines and
//! sines, as the expanding peers compute it, then its closed form; the DQ as a Fourier series); W4 the
//! PUMA 560 8x6 Jacobian of the DQ components in closed form; W5 a 20-joint planar chain's end
//! effector in closed form; W5full a 20-joint chain with every DH parameter symbolic, which
//! must stop with a size error.

use dqsym::{
    closed::{closed_form_cos_sin, expanded_form, Cost},
    closed_form,
    kin::dh_link,
    DualQuat, Scalar, ScalarError,
};
use std::time::{Duration, Instant};

#[path = "../benches/support/workloads.rs"]
mod workloads;
use workloads::{chain, generic, jacobian_closed_forms, matrix, matrix_cos_sin, planar, puma, Dh};
/// What one run of a workload produced: the size of the closed forms (or of nothing, for a
/// workload that stops) and the number of canonical terms.
struct Outcome {
    cost: Cost,
    entries: usize,
    terms: usize,
    error: Option<ScalarError>,
}

fn closed(xs: &[&Scalar]) -> Result<Outcome, ScalarError> {
    let mut cost = Cost::default();
    let mut terms = 0;
    for x in xs {
        let x = (*x).clone().check()?;
        terms += x.len();
        let c = closed_form(&x)?.cost();
        cost.ops += c.ops;
        cost.calls += c.calls;
    }
    Ok(Outcome {
        cost,
        entries: xs.len(),
        terms,
        error: None,
    })
}

fn end_effector(links: &[Dh]) -> Result<Outcome, ScalarError> {
    let m = chain(links).to_matrix();
    closed(&[&m.rows[0][3], &m.rows[1][3]])
}

/// W2 reports the 4x4 pose (rows 0..2, the product of the DH matrices, as `dqsym fk` forms it)
/// and the DQ as two results.
fn pose_and_dq(links: &[Dh]) -> Result<(Outcome, Outcome), ScalarError> {
    let q = chain(links);
    let m: Vec<Scalar> = matrix(links).rows[..3].iter().flatten().cloned().collect();
    let comps = q.components();
    Ok((
        closed(&m.iter().collect::<Vec<_>>())?,
        closed(&comps.iter().collect::<Vec<_>>())?,
    ))
}

fn jacobian() -> Result<Outcome, ScalarError> {
    let vars: Vec<String> = (1..=6).map(|i| format!("theta{i}")).collect();
    let vars: Vec<&str> = vars.iter().map(String::as_str).collect();
    let forms = jacobian_closed_forms(&puma(), &vars)?;
    let mut cost = Cost::default();
    for e in &forms {
        let c = e.cost();
        cost.ops += c.ops;
        cost.calls += c.calls;
    }
    Ok(Outcome {
        cost,
        entries: forms.len(),
        terms: 0,
        error: None,
    })
}

/// The 20-joint chain with every DH parameter symbolic: the product is exponential in the
/// number of joints, so the expected outcome is a size error, quickly and in little memory.
/// With `trace`, prints each partial product's time and largest component to stderr.
fn full20(trace: bool) -> Result<Outcome, ScalarError> {
    let t = Instant::now();
    let mut q = DualQuat::identity();
    for (k, [th, d, a, al]) in generic(20).iter().enumerate() {
        q = q * dh_link(th, d, a, al);
        if trace {
            let comps = q.components();
            let big = comps.iter().map(Scalar::len).max().unwrap_or(0);
            let err = comps.iter().find_map(|x| x.as_error().cloned());
            eprintln!(
                "links {}: {:?}, largest component {big} terms, {err:?}",
                k + 1,
                t.elapsed()
            );
        }
    }
    let comps = q.components();
    closed(&comps.iter().collect::<Vec<_>>())
}

/// The size of scalars printed expanded: a Fourier series one cos/sin call per term, a cos/sin
/// polynomial one call per placeholder factor.
fn expanded_sized(xs: &[Scalar]) -> Outcome {
    let mut cost = Cost::default();
    for x in xs {
        if let Ok(e) = expanded_form(x) {
            let c = e.with_placeholders_as_trig().cost();
            cost.ops += c.ops;
            cost.calls += c.calls;
        }
    }
    Outcome {
        cost,
        ..expanded(xs)
    }
}

/// The term count of expanded scalars (no closed form), or their first error.
fn expanded(xs: &[Scalar]) -> Outcome {
    Outcome {
        cost: Cost::default(),
        entries: xs.len(),
        terms: xs.iter().map(Scalar::len).sum(),
        error: xs.iter().find_map(|x| x.as_error().cloned()),
    }
}

fn median(mut v: Vec<Duration>) -> f64 {
    v.sort();
    v[v.len() / 2].as_secs_f64()
}

fn print(workload: &str, part: &str, secs: f64, runs: usize, o: &Outcome) {
    let error = match &o.error {
        Some(e) => format!("\"{e}\""),
        None => "null".into(),
    };
    println!(
        "{{\"workload\": \"{workload}\", \"part\": \"{part}\", \"seconds\": {secs:.6}, \"runs\": {runs}, \"ops\": {}, \"calls\": {}, \"entries\": {}, \"terms\": {}, \"error\": {error}}}",
        o.cost.ops, o.cost.calls, o.entries, o.terms
    );
}

fn timed<R>(runs: usize, f: impl Fn() -> R) -> (f64, R) {
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs {
        let t = Instant::now();
        let r = f();
        times.push(t.elapsed());
        last = Some(r);
    }
    (median(times), last.expect("runs >= 1"))
}

fn failed(e: ScalarError) -> Outcome {
    Outcome {
        cost: Cost::default(),
        entries: 0,
        terms: 0,
        error: Some(e),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut runs = 5;
    let mut ctx = dqsym::Context::new();
    let trace = args.iter().any(|a| a == "--trace");
    let mut picked = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        if a == "--term-limit" {
            if let Some(n) = it.next().and_then(|s| s.parse().ok()) {
                ctx = ctx.with_term_limit(n);
            }
        } else if a == "--runs" {
            runs = it
                .next()
                .and_then(|s| s.parse().ok())
                .unwrap_or(runs)
                .max(1);
        } else if a != "--trace" {
            picked.push(a.as_str());
        }
    }
    if picked.is_empty() {
        picked = vec!["W1", "W2", "W3", "W4", "W5"];
    }
    let _entered = ctx.enter();
    for w in picked {
        match w {
            "W1" => {
                let (s, r) = timed(runs, || end_effector(&planar(3)));
                print(w, "end effector", s, runs, &r.unwrap_or_else(failed));
            }
            "W2" => {
                let (s, r) = timed(runs, || pose_and_dq(&puma()));
                match r {
                    Ok((m, q)) => {
                        print(w, "4x4 + DQ (4x4)", s, runs, &m);
                        print(w, "4x4 + DQ (DQ)", s, runs, &q);
                    }
                    Err(e) => print(w, "4x4 + DQ", s, runs, &failed(e)),
                }
            }
            "W3" => {
                // The 4x4 pose as a polynomial in the cosines and sines (the expanding CAS's
                // form), then its closed form; the DQ (half angles) as a Fourier series.
                let links = generic(6);
                let (s, m) = timed(runs, || matrix_cos_sin(&links));
                let rows: Vec<Scalar> = m
                    .map(|m| m.rows[..3].iter().flatten().cloned().collect())
                    .unwrap_or_default();
                print(w, "expand (4x4)", s, runs, &expanded_sized(&rows));
                let (s2, r) = timed(runs, || {
                    rows.iter()
                        .map(|x| closed_form_cos_sin(x).map(|e| e.cost()))
                        .collect::<Result<Vec<Cost>, _>>()
                });
                let o = r.map(|cs| Outcome {
                    cost: cs.iter().fold(Cost::default(), |a, c| Cost {
                        ops: a.ops + c.ops,
                        calls: a.calls + c.calls,
                    }),
                    entries: rows.len(),
                    terms: rows.iter().map(Scalar::len).sum(),
                    error: None,
                });
                print(
                    w,
                    "closed form (4x4)",
                    s + s2,
                    runs,
                    &o.unwrap_or_else(failed),
                );
                let (s3, q) = timed(1, || chain(&links));
                // Sized as printed expanded (outside the timing): each Fourier term one
                // product with one cos/sin call.
                print(w, "expand (DQ)", s3, 1, &expanded_sized(&q.components()));
            }
            "W4" => {
                let (s, r) = timed(runs, jacobian);
                print(w, "8x6 Jacobian", s, runs, &r.unwrap_or_else(failed));
            }
            "W5" => {
                let (s, r) = timed(runs, || end_effector(&planar(20)));
                print(w, "20-joint planar", s, runs, &r.unwrap_or_else(failed));
            }
            "W5full" => {
                let (s, r) = timed(1, || full20(trace));
                print(w, "20-joint all symbolic", s, 1, &r.unwrap_or_else(failed));
            }
            other => {
                eprintln!("unknown workload {other}");
                std::process::exit(2);
            }
        }
    }
}
