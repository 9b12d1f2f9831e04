//! Support for the paper tests: exact closed forms with their re-check, snapshots, and numeric
//! checks at random points against plain 4x4 matrices.
#![allow(dead_code)]

use crate::common::Rng;
use dqsym::{
    closed_form, plain, print::legend, DualQuat, Expr, Matrix4, PlainOptions, Quat, Ring, Scalar,
};

pub type S = Scalar;

pub fn sym(n: &str) -> S {
    Scalar::sym(n)
}
pub fn int(n: i64) -> S {
    Scalar::int(n)
}
pub fn frac(a: i64, b: i64) -> S {
    S::from_ratio(a, b)
}
pub fn half(x: &S) -> S {
    x * frac(1, 2)
}
pub fn cos(x: &S) -> S {
    x.cos().check().expect("cos of an angle")
}
pub fn sin(x: &S) -> S {
    x.sin().check().expect("sin of an angle")
}
pub fn v3(x: S, y: S, z: S) -> [S; 3] {
    [x, y, z]
}
pub fn zero3() -> [S; 3] {
    [int(0), int(0), int(0)]
}
pub fn ex() -> [S; 3] {
    [int(1), int(0), int(0)]
}
pub fn ey() -> [S; 3] {
    [int(0), int(1), int(0)]
}
pub fn ez() -> [S; 3] {
    [int(0), int(0), int(1)]
}

/// The closed form of `x`, checked to re-canonicalize to `x`.
pub fn closed(x: &S) -> Expr {
    let e = closed_form(x).expect("closed form");
    assert_eq!(&e.to_scalar(), x, "closed form must equal its input");
    e
}

/// A report: one line per named value in robotics shorthand, then the legend.
pub struct Report {
    lines: Vec<String>,
    exprs: Vec<Expr>,
    shorthand: bool,
}

impl Report {
    pub fn new(title: &str) -> Report {
        Report {
            lines: vec![title.to_string()],
            exprs: Vec::new(),
            shorthand: true,
        }
    }
    pub fn explicit(title: &str) -> Report {
        Report {
            lines: vec![title.to_string()],
            exprs: Vec::new(),
            shorthand: false,
        }
    }
    pub fn note(&mut self, text: &str) -> &mut Self {
        self.lines.push(format!("# {text}"));
        self
    }
    pub fn value(&mut self, name: &str, x: &S) -> &mut Self {
        let e = closed(x);
        let o = PlainOptions {
            shorthand: self.shorthand,
            decimals: false,
        };
        self.lines.push(format!("{name} = {}", plain(&e, &o)));
        self.exprs.push(e);
        self
    }
    pub fn vector(&mut self, name: &str, v: &[S]) -> &mut Self {
        let o = PlainOptions {
            shorthand: self.shorthand,
            decimals: false,
        };
        let parts: Vec<String> = v
            .iter()
            .map(|x| {
                let e = closed(x);
                let s = plain(&e, &o);
                self.exprs.push(e);
                s
            })
            .collect();
        self.lines.push(format!("{name} = ({})", parts.join(", ")));
        self
    }
    pub fn dq(&mut self, name: &str, q: &DualQuat<S>) -> &mut Self {
        let c = q.components();
        self.vector(&format!("{name} real"), &c[..4]);
        self.vector(&format!("{name} dual"), &c[4..])
    }
    pub fn matrix3(&mut self, name: &str, m: &Matrix4<S>) -> &mut Self {
        for (i, row) in m.rows.iter().take(3).enumerate() {
            self.vector(&format!("{name} row {}", i + 1), &row[..3]);
        }
        self
    }
    pub fn text(&self) -> String {
        let refs: Vec<&Expr> = self.exprs.iter().collect();
        let mut out = self.lines.join("\n");
        let leg = legend(&refs);
        if self.shorthand && !leg.is_empty() {
            out.push_str("\nwhere ");
            out.push_str(&leg.join(", "));
        }
        out.push('\n');
        out
    }
}

/// Asserts a snapshot of the report in the top-level snapshots/ folder.
pub fn snap(name: &str, r: &Report) {
    crate::common::snapshot_settings().bind(|| insta::assert_snapshot!(name, r.text()));
}

/// Random values for the given symbols, in [-2, 2], at a few seeds.
pub fn points(names: &[&str], n: usize) -> Vec<Vec<(String, f64)>> {
    let mut rng = Rng::new(names.len() as u64 * 7919 + n as u64);
    (0..n)
        .map(|_| {
            names
                .iter()
                .map(|s| (s.to_string(), rng.range(-2.0, 2.0)))
                .collect()
        })
        .collect()
}

pub fn ev(x: &S, env: &[(String, f64)]) -> f64 {
    x.eval(&|n| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))
        .expect("every symbol bound")
}

pub fn get(env: &[(String, f64)], name: &str) -> f64 {
    env.iter()
        .find(|(k, _)| k == name)
        .map(|(_, v)| *v)
        .expect("bound")
}

pub fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
}

/// Checks symbolic values against numbers computed without the symbolic code, at random points.
pub fn check_numeric(names: &[&str], sym: &[S], num: impl Fn(&[(String, f64)]) -> Vec<f64>) {
    for env in points(names, 8) {
        let want = num(&env);
        assert_eq!(want.len(), sym.len());
        for (k, (s, w)) in sym.iter().zip(&want).enumerate() {
            let got = ev(s, &env);
            assert!(close(got, *w), "entry {k}: {got} != {w} at {env:?}");
        }
    }
}

/// `T(p) R_axis(theta) T(-p)` as an f64 matrix, from elementary matrices only.
pub fn mat_rot_about(axis: char, theta: f64, p: [f64; 3]) -> Matrix4<f64> {
    let r = match axis {
        'x' => Matrix4::rot_x(&theta),
        'y' => Matrix4::rot_y(&theta),
        _ => Matrix4::rot_z(&theta),
    };
    Matrix4::trans(&p) * r * Matrix4::trans(&[-p[0], -p[1], -p[2]])
}

pub fn quat(w: S, x: S, y: S, z: S) -> Quat<S> {
    Quat::new(w, x, y, z)
}
