//! The `dqsym` command line. Only this file does I/O.

use clap::{Parser, Subcommand};
use dqsym::{closed_form, dh_link, legend, plain, DualQuat, Expr, PlainOptions, Ring, Scalar};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "dqsym",
    version,
    about = "Exact symbolic dual quaternions for robot kinematics"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Derive and print the paper's worked examples (sec 6) and the PUMA 560 pose.
    Paper {
        /// Print cos(theta1 + theta2) instead of the shorthand c12.
        #[arg(long)]
        explicit: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Paper { explicit } => match paper(&PlainOptions {
            shorthand: !explicit,
        }) {
            Ok(text) => {
                print!("{text}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
    }
}

fn sym(n: &str) -> Scalar {
    Scalar::sym(n)
}

fn rx_about(theta: &str, y: Scalar) -> DualQuat<Scalar> {
    let axis = [Scalar::int(1), Scalar::int(0), Scalar::int(0)];
    DualQuat::rotation_about_point(&axis, &sym(theta), &[Scalar::int(0), y, Scalar::int(0)])
}

/// Closed forms of `values`, one line each, followed by the shorthand legend.
fn block(
    title: &str,
    values: &[(String, Scalar)],
    o: &PlainOptions,
) -> Result<String, dqsym::ScalarError> {
    let mut out = format!("{title}\n");
    let mut exprs: Vec<Expr> = Vec::new();
    for (name, v) in values {
        let e = closed_form(v)?;
        out.push_str(&format!("  {name} = {}\n", plain(&e, o)));
        exprs.push(e);
    }
    let refs: Vec<&Expr> = exprs.iter().collect();
    let leg = legend(&refs);
    if o.shorthand && !leg.is_empty() {
        out.push_str(&format!("  where {}\n", leg.join(", ")));
    }
    Ok(out + "\n")
}

fn paper(o: &PlainOptions) -> Result<String, dqsym::ScalarError> {
    let (l1, l2, l3, l4) = (sym("l1"), sym("l2"), sym("l3"), sym("l4"));
    let mut out = String::new();
    // Sec 6.1: the planar RRR arm.
    let chain = rx_about("theta1", Scalar::int(0))
        * rx_about("theta2", l1.clone())
        * rx_about("theta3", &l1 + &l2);
    let tip = chain.transform_point(&[Scalar::int(0), &l1 + &l2 + &l3, Scalar::int(0)]);
    let named = |p: &str, v: &[Scalar]| -> Vec<(String, Scalar)> {
        ["x", "y", "z"]
            .iter()
            .zip(v)
            .map(|(k, x)| (format!("{p}{k}"), x.clone()))
            .collect()
    };
    out += &block(
        "sec 6.1, planar RRR arm: end effector v0",
        &named("v0.", &tip),
        o,
    )?;
    // Sec 6.3: the 6R robot's tool point.
    let big_l = &l1 + &l2 + &l3;
    let ey = [Scalar::int(0), Scalar::int(1), Scalar::int(0)];
    let ez = [Scalar::int(0), Scalar::int(0), Scalar::int(1)];
    let six = chain
        * DualQuat::rotation(&ey, &sym("theta4"))
        * DualQuat::rotation_about_point(
            &ez,
            &sym("theta5"),
            &[Scalar::int(0), big_l.clone(), Scalar::int(0)],
        )
        * DualQuat::rotation(&ey, &sym("theta6"));
    let tool = six.transform_point(&[Scalar::int(0), big_l + l4, Scalar::int(0)]);
    out += &block(
        "sec 6.3, 6R robot: tool point (0, l1 + l2 + l3 + l4, 0) in the base frame",
        &named("v0.", &tool),
        o,
    )?;
    // PUMA 560, standard DH.
    let alpha = [(1, 2), (0, 1), (-1, 2), (1, 2), (-1, 2), (0, 1)];
    let a = [
        Scalar::int(0),
        sym("a2"),
        sym("a3"),
        Scalar::int(0),
        Scalar::int(0),
        Scalar::int(0),
    ];
    let d = [
        Scalar::int(0),
        Scalar::int(0),
        sym("d3"),
        sym("d4"),
        Scalar::int(0),
        Scalar::int(0),
    ];
    let mut q = DualQuat::identity();
    for i in 0..6 {
        let al = Scalar::pi() * Scalar::from_ratio(alpha[i].0, alpha[i].1);
        q = q * dh_link(&sym(&format!("theta{}", i + 1)), &d[i], &a[i], &al);
    }
    let m = q.to_matrix();
    let mut entries = Vec::new();
    for i in 0..3 {
        for j in 0..4 {
            entries.push((format!("T[{i}][{j}]"), m.rows[i][j].clone()));
        }
    }
    out += &block("PUMA 560 (standard DH): 4x4 pose", &entries, o)?;
    let comps: Vec<(String, Scalar)> = q
        .components()
        .iter()
        .enumerate()
        .map(|(k, c)| (format!("dq[{k}]"), c.clone()))
        .collect();
    out += &block(
        "PUMA 560: unit dual quaternion (w, x, y, z, w_e, x_e, y_e, z_e)",
        &comps,
        o,
    )?;
    Ok(out)
}
