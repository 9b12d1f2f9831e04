//! The numeric edges of the solvers: the tolerances every solver uses (the reference one here
//! and the generated ones, which get these values formatted into their text), each step's
//! scale, and the forward-kinematics check of a solution with its Gauss–Newton refinement.
//!
//! # Tolerances
//!
//! Every tolerance is relative to the robot's scale `L`: the largest sum of absolute
//! coordinates of a joint axis' point, the home position or the target position (every length
//! the solver adds or subtracts is a difference of such points, at most `2 L`). A step's parts (`a`, `b`, `c`; `y`, `x`; `β`, `γ`) are
//! homogeneous polynomials of some degree `d` in lengths (found once per solver,
//! `step_degrees`), so their size is of order `S = L^d` and the rounding of their evaluation
//! (at most a few dozen operations, each adding at most `eps` times the sum of the absolute
//! values of the terms, a handful of terms of size `S`: about 32 eps S, with a factor 2 to
//! spare) is below `σ = ZERO_TOL · S` with `ZERO_TOL = 64 eps`:
//! - a part below `σ` is zero within rounding: an atan2 whose arguments are both below it is
//!   on a singular set (any value; the twelve samples `k π/6`), but the value `atan2(y, x)`
//!   itself is kept beside them where it is not exactly `0/0` (close to the set the arguments
//!   carry a common factor that vanishes there, and their ratio stays accurate);
//! - a radicand `rad = a² + b² − c²` carries the rounding of its parts, `ν = 2σ (|a| + |b| +
//!   |c|) + 4 eps n` to first order: within `ν` of zero the two roots are one double root
//!   (singular); a positive radicand keeps its two roots however small, a negative one within
//!   `ν` is 0, and one down to `−REACH_TOL · n` (beyond rounding, a target slightly out of
//!   reach) is clamped to 0 too, its solutions the closest reach (checked below, so flagged
//!   approximate with their residual); below that the target is out of reach.
//!
//! A step's root then errs by at most `σ / h` (atan2, `h = hypot(y, x)`) or `ν / (2 √(rad ·
//! n))` (a trig equation; `ν / (2 √rad)` over the scale for a quadratic). Where every step of a
//! solution errs by less than `CHECK_TOL` the solution is exact to rounding and is returned as
//! it is (the common case, kept as fast as before); every other solution, and every singular
//! one, is checked by forward kinematics: its residual (the largest deviation of an entry of
//! its pose from the target, rotation entries as they are, positions over `L`) above
//! `REFINE_TOL` (twenty times the rounding of an exact solution's pose, `3 (n + 1) eps`, so
//! that exact solutions are not refined) starts a damped Gauss–Newton refinement on the pose residual, and a residual still above
//! `POSE_TOL` after it (a target out of reach, a sample of a singular set the pose is only
//! near) flags the solution approximate with that residual. Samples of a singular set whose
//! own atan2 value was kept are dropped instead when they stay off the pose: the pose is only
//! near the set, and the kept value is its solution.

/// Rounding of a step's parts, relative to their scale `L^d` (see the module docs).
pub const ZERO_TOL: f64 = 64.0 * f64::EPSILON;
/// How far below zero (relative to `a² + b²`) a radicand is still the closest reach.
pub const REACH_TOL: f64 = 1e-8;
/// The error bound of a step's root (radians, or relative to the scale) above which a
/// solution is checked by forward kinematics (a tenth of `POSE_TOL`).
pub const CHECK_TOL: f64 = 1e-11;
/// The residual (relative) above which a checked solution is refined: twenty times the
/// rounding of an exact solution's pose, `3 (n + 1) eps` for six joints, so that only a
/// solution off its pose is refined (near a singular set the joints beside it may err by the
/// residual over the distance to the set, so it is refined as far as rounding allows).
pub const REFINE_TOL: f64 = 1e-13;
/// The residual (relative) above which a checked solution is flagged approximate.
pub const POSE_TOL: f64 = 1e-10;
/// Gauss–Newton iterations at most.
pub const REFINE_STEPS: usize = 12;

/// The candidates of one step: `(value, singular, checked, sampled)`: `checked` when its error
/// bound exceeds [`CHECK_TOL`]; `sampled` for a sample of a singular set beside the kept
/// atan2 value (dropped when it stays off the pose).
pub(crate) type Cand = (f64, bool, bool, bool);

/// The twelve representatives `k π/6`, `k = −5..6`, of a joint free on a singular set.
fn samples(after_true: bool) -> impl Iterator<Item = Cand> {
    (-5..=6).map(move |k| {
        (
            f64::from(k) * std::f64::consts::FRAC_PI_6,
            true,
            true,
            after_true,
        )
    })
}

/// `atan2(y, x)` with the rounding `sigma` of its arguments.
pub(crate) fn atan2_cands(y: f64, x: f64, sigma: f64) -> Vec<Cand> {
    let h2 = y * y + x * x;
    if h2 > sigma * sigma {
        let check = sigma * sigma > CHECK_TOL * CHECK_TOL * h2;
        return vec![(y.atan2(x), false, check, false)];
    }
    let mut v = Vec::new();
    if h2 > 0.0 {
        v.push((y.atan2(x), true, true, false));
    }
    v.extend(samples(h2 > 0.0));
    v
}

/// The radicand `rad` of a root pair of scale `n` with its rounding `nu`: `None` out of reach,
/// else the radicand used (0 for a double root), singular, checked.
pub(crate) fn radicand(rad: f64, n: f64, nu: f64) -> Option<(f64, bool, bool)> {
    if rad < -REACH_TOL * n - nu {
        None
    } else if rad <= nu {
        Some((0.0, true, true))
    } else {
        // The roots err by nu / (2 sqrt(rad n)) (trig) or nu / (2 sqrt(rad)) over the scale.
        Some((rad, false, nu * nu > 4.0 * CHECK_TOL * CHECK_TOL * rad * n))
    }
}

/// `a cos q + b sin q = c` with the rounding `sigma` of its parts.
pub(crate) fn trig_cands(a: f64, b: f64, c: f64, sigma: f64) -> Vec<Cand> {
    let n = a * a + b * b;
    if n <= sigma * sigma {
        // No equation left: any value where c is zero too, none otherwise.
        return if c.abs() <= sigma {
            vec![(0.0, true, true, false)]
        } else {
            vec![]
        };
    }
    let nu = 2.0 * sigma * (a.abs() + b.abs() + c.abs()) + 4.0 * f64::EPSILON * n;
    let Some((rad, sg, ck)) = radicand(n - c * c, n, nu) else {
        return vec![];
    };
    let phi = b.atan2(a);
    if sg {
        // The double root, and the pair at the edge of the rounding, sqrt(nu) (sampled: kept
        // where refinement takes them onto the pose, which the double root may miss by up to
        // sqrt(nu / n) when the pose is only near the set).
        let w = nu.sqrt().atan2(c);
        return vec![
            (phi + rad.sqrt().atan2(c), true, true, false),
            (phi + w, true, true, true),
            (phi - w, true, true, true),
        ];
    }
    let w = rad.sqrt().atan2(c);
    vec![(phi + w, sg, ck, false), (phi - w, sg, ck, false)]
}

/// `a q = b` with the rounding `sigma` of `b` (a length, degree 1: `sigma = ZERO_TOL L`); `a`
/// is dimensionless (degree 0), so its rounding is `ZERO_TOL` itself. Singular where `|a| ≤
/// ZERO_TOL` (the slides' directions dependent within rounding): `b / a` is kept while `a ≠ 0`
/// (near the set `a` and `b` share the vanishing factor, as an atan2's arguments do), else 0,
/// and checked. The root errs by `δq = (sigma + |q| ZERO_TOL) / |a|` (first order), checked
/// where that exceeds `CHECK_TOL L`, `L = sigma / ZERO_TOL`.
pub(crate) fn linear_cand(a: f64, b: f64, sigma: f64) -> Cand {
    let q = if a == 0.0 { 0.0 } else { b / a };
    if a.abs() <= ZERO_TOL {
        return (q, true, true, false);
    }
    let err = (sigma + q.abs() * ZERO_TOL) / a.abs();
    (q, false, err * ZERO_TOL > CHECK_TOL * sigma, false)
}

/// `q² + 2 β q + γ = 0` with the rounding `sigma` of `γ` (the step's degree is that of `γ`,
/// twice that of `β`, whose rounding is then `sqrt(sigma ZERO_TOL)`).
pub(crate) fn quadratic_cands(beta: f64, gamma: f64, sigma: f64) -> Vec<Cand> {
    let s = beta.abs().max(gamma.abs().sqrt());
    let nu = sigma
        + 2.0 * (sigma * ZERO_TOL).sqrt() * (2.0 * beta.abs() + s)
        + 4.0 * f64::EPSILON * (beta * beta + gamma.abs());
    let scale = (beta * beta).max(gamma.abs());
    let Some((rad, sg, ck)) = radicand(beta * beta - gamma, scale, nu) else {
        return vec![];
    };
    let r = rad.sqrt();
    vec![(-beta + r, sg, ck, false), (-beta - r, sg, ck, false)]
}

/// A joint axis in the home pose as numbers: `[kind, wx, wy, wz, px, py, pz]`, kind 1 for a
/// prismatic joint (moving along `w`).
pub type AxisData = [f64; 7];

/// The robot's scale `L` (see the module docs): never 0.
pub fn scale(axes: &[AxisData], home: &[[f64; 4]; 3], target: &[[f64; 4]; 4]) -> f64 {
    let mut l: f64 = 0.0;
    for a in axes {
        l = l.max(a[4].abs() + a[5].abs() + a[6].abs());
    }
    l = l.max(home[0][3].abs() + home[1][3].abs() + home[2][3].abs());
    l = l.max(target[0][3].abs() + target[1][3].abs() + target[2][3].abs());
    if l > 0.0 && l.is_finite() {
        l
    } else {
        1.0
    }
}

/// `a · b` for rigid motions as 3 x 4 blocks.
fn compose(a: &[[f64; 4]; 3], b: &[[f64; 4]; 3]) -> [[f64; 4]; 3] {
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            let t = if c == 3 { a[r][3] } else { 0.0 };
            t + a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c]
        })
    })
}

/// The motion of one joint at `q` about (along) its home axis: `R = c I + s [w]x + (1 − c) w
/// wᵀ`, `t = (I − R) p`.
fn motion(a: &AxisData, q: f64) -> [[f64; 4]; 3] {
    let w = [a[1], a[2], a[3]];
    if a[0] != 0.0 {
        return std::array::from_fn(|r| {
            std::array::from_fn(|c| match c {
                3 => q * w[r],
                _ => f64::from(u8::from(r == c)),
            })
        });
    }
    let (s, c) = q.sin_cos();
    let k = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
    let rot: [[f64; 3]; 3] = std::array::from_fn(|r| {
        std::array::from_fn(|j| {
            (if r == j { c } else { 0.0 }) + s * k[r][j] + (1.0 - c) * w[r] * w[j]
        })
    });
    let p = [a[4], a[5], a[6]];
    std::array::from_fn(|r| {
        std::array::from_fn(|j| {
            if j < 3 {
                rot[r][j]
            } else {
                p[r] - (rot[r][0] * p[0] + rot[r][1] * p[1] + rot[r][2] * p[2])
            }
        })
    })
}

/// The pose `E1(q1) ⋯ En(qn) M` and each joint's current axis `(w, p)`.
pub fn forward(
    axes: &[AxisData],
    home: &[[f64; 4]; 3],
    q: &[f64],
) -> ([[f64; 4]; 3], Vec<[f64; 6]>) {
    let mut p = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ];
    let mut cur = Vec::with_capacity(axes.len());
    for (a, &qi) in axes.iter().zip(q) {
        let w: [f64; 3] = std::array::from_fn(|r| p[r][0] * a[1] + p[r][1] * a[2] + p[r][2] * a[3]);
        let o: [f64; 3] =
            std::array::from_fn(|r| p[r][0] * a[4] + p[r][1] * a[5] + p[r][2] * a[6] + p[r][3]);
        cur.push([w[0], w[1], w[2], o[0], o[1], o[2]]);
        p = compose(&p, &motion(a, qi));
    }
    (compose(&p, home), cur)
}

/// The residual vector `T − F` (rotation entries, then positions over `len`; positions only
/// for a position-only solver).
fn error(f: &[[f64; 4]; 3], t: &[[f64; 4]; 4], len: f64, position_only: bool) -> Vec<f64> {
    let mut e = Vec::with_capacity(12);
    for r in 0..3 {
        for c in 0..4 {
            if c == 3 {
                e.push((t[r][3] - f[r][3]) / len);
            } else if !position_only {
                e.push(t[r][c] - f[r][c]);
            }
        }
    }
    e
}

fn max_abs(e: &[f64]) -> f64 {
    e.iter().fold(0.0, |m, x| {
        if x.abs() > m || x.is_nan() {
            x.abs()
        } else {
            m
        }
    })
}

/// The residual of `q`: the largest entry of `T − F(q)`, positions over `len`.
pub fn residual(
    axes: &[AxisData],
    home: &[[f64; 4]; 3],
    t: &[[f64; 4]; 4],
    len: f64,
    position_only: bool,
    q: &[f64],
) -> f64 {
    max_abs(&error(&forward(axes, home, q).0, t, len, position_only))
}

/// Damped Gauss–Newton on the pose residual from `q` (updated in place): at most
/// [`REFINE_STEPS`] steps, each kept only when it lowers the residual (else the damping grows
/// a hundredfold). Returns the final residual.
#[allow(clippy::needless_range_loop)] // Jacobian and normal-equation entries by index
pub fn refine(
    axes: &[AxisData],
    home: &[[f64; 4]; 3],
    t: &[[f64; 4]; 4],
    len: f64,
    position_only: bool,
    q: &mut [f64],
) -> f64 {
    let n = q.len();
    let (mut f, mut cur) = forward(axes, home, q);
    let mut e = error(&f, t, len, position_only);
    let mut res = max_abs(&e);
    let mut lambda = 1e-12;
    for _ in 0..REFINE_STEPS {
        if res <= CHECK_TOL * 1e-3 {
            break;
        }
        // Jacobian columns: d(R)/dqi = [wi]x R, d(t)/dqi = wi x (t - pi) (revolute), wi
        // (prismatic); the same entries and scaling as the residual.
        let cols: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                let [wx, wy, wz, px, py, pz] = cur[i];
                let cross = |v: [f64; 3]| {
                    [
                        wy * v[2] - wz * v[1],
                        wz * v[0] - wx * v[2],
                        wx * v[1] - wy * v[0],
                    ]
                };
                let dt = if axes[i][0] != 0.0 {
                    [wx, wy, wz]
                } else {
                    cross([f[0][3] - px, f[1][3] - py, f[2][3] - pz])
                };
                let mut col = Vec::with_capacity(12);
                let dr: [[f64; 3]; 3] = if axes[i][0] != 0.0 {
                    [[0.0; 3]; 3]
                } else {
                    let c: [[f64; 3]; 3] =
                        std::array::from_fn(|k| cross([f[0][k], f[1][k], f[2][k]]));
                    std::array::from_fn(|r| std::array::from_fn(|k| c[k][r]))
                };
                for r in 0..3 {
                    for c in 0..4 {
                        if c == 3 {
                            col.push(dt[r] / len);
                        } else if !position_only {
                            col.push(dr[r][c]);
                        }
                    }
                }
                col
            })
            .collect();
        let mut a = vec![vec![0.0; n]; n];
        let mut g = vec![0.0; n];
        let mut tr = 0.0;
        for i in 0..n {
            for j in 0..n {
                a[i][j] = cols[i].iter().zip(&cols[j]).map(|(x, y)| x * y).sum();
            }
            g[i] = cols[i].iter().zip(&e).map(|(x, y)| x * y).sum();
            tr += a[i][i];
        }
        loop {
            let mut m = a.clone();
            for (i, row) in m.iter_mut().enumerate() {
                row[i] += lambda * tr.max(f64::MIN_POSITIVE);
            }
            let Some(d) = cholesky_solve(m, g.clone()) else {
                lambda *= 100.0;
                if lambda > 1.0 {
                    return res;
                }
                continue;
            };
            let next: Vec<f64> = q.iter().zip(&d).map(|(x, y)| x + y).collect();
            let (f2, cur2) = forward(axes, home, &next);
            let e2 = error(&f2, t, len, position_only);
            let r2 = max_abs(&e2);
            if r2 < res {
                q.copy_from_slice(&next);
                (f, cur, e, res) = (f2, cur2, e2, r2);
                lambda = (lambda * 0.01).max(1e-15);
                break;
            }
            lambda *= 100.0;
            if lambda > 1.0 {
                return res;
            }
        }
    }
    res
}

/// Solves `m x = b` for a symmetric positive definite `m`; `None` when it is not.
#[allow(clippy::needless_range_loop)] // triangular loops over matrix entries by index
fn cholesky_solve(mut m: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for j in 0..n {
        let mut d = m[j][j];
        for k in 0..j {
            d -= m[j][k] * m[j][k];
        }
        if d.is_nan() || d <= 0.0 {
            return None;
        }
        let d = d.sqrt();
        m[j][j] = d;
        for i in j + 1..n {
            let mut s = m[i][j];
            for k in 0..j {
                s -= m[i][k] * m[j][k];
            }
            m[i][j] = s / d;
        }
    }
    for i in 0..n {
        for k in 0..i {
            b[i] -= m[i][k] * b[k];
        }
        b[i] /= m[i][i];
    }
    for i in (0..n).rev() {
        for k in i + 1..n {
            b[i] -= m[k][i] * b[k];
        }
        b[i] /= m[i][i];
    }
    Some(b)
}

/// Two joint vectors equal to a few units in the last place (angles as they are): one of them
/// is a duplicate.
pub fn same_row(a: &[f64], b: &[f64]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= 4.0 * f64::EPSILON * x.abs().max(y.abs()).max(1.0))
}

/// The degree in lengths of each step's parts (their scale is `L^d`): found by evaluating the
/// parts at one point and again with every length doubled (target position, length
/// parameters, prismatic joints; a parameter the parts are 2π-periodic in is an angle).
pub(crate) fn step_degrees(sol: &super::IkSolution) -> Result<Vec<i32>, crate::ScalarError> {
    let forms = sol.forms()?;
    let mut env: Vec<(String, f64, bool)> = Vec::new();
    let rot = [0.36, -0.48, 0.8, 0.64, 0.6, 0.0, -0.68, 0.64, 0.36];
    for (r, row) in super::TARGET_SYMBOLS.iter().enumerate() {
        for (c, name) in row.iter().enumerate() {
            let v = if c == 3 {
                [0.41, -0.23, 0.37][r]
            } else {
                rot[3 * r + c]
            };
            env.push((name.to_string(), v, c == 3));
        }
    }
    for (i, p) in sol.params.iter().enumerate() {
        env.push((p.clone(), 0.55 + 0.13 * i as f64, true));
    }
    for (i, (v, a)) in sol.variables.iter().zip(&sol.axes).enumerate() {
        let prismatic = a.kind == crate::kin::JointKind::Prismatic;
        env.push((v.clone(), 0.31 + 0.17 * i as f64, prismatic));
    }
    let eval = |e: &crate::Expr, env: &[(String, f64, bool)], k: f64, shift: Option<&str>| {
        e.eval_f64(&|s: &crate::Sym| {
            if s.is_pi() {
                return std::f64::consts::PI;
            }
            env.iter()
                .find(|(n, _, _)| n == s.name())
                .map_or(f64::NAN, |(n, v, len)| {
                    let v = if Some(n.as_str()) == shift {
                        v + std::f64::consts::TAU
                    } else {
                        *v
                    };
                    if *len {
                        v * k
                    } else {
                        v
                    }
                })
        })
        .0
    };
    // A parameter the parts do not change under a 2 pi shift of is an angle (a free joint).
    let all: Vec<&crate::Expr> = forms.iter().flatten().map(|(_, e)| e).collect();
    let angles: Vec<String> = sol
        .params
        .iter()
        .filter(|p| {
            all.iter().all(|e| {
                let (a, b) = (eval(e, &env, 1.0, None), eval(e, &env, 1.0, Some(p)));
                (a - b).abs() <= 1e-9 * a.abs().max(1.0)
            })
        })
        .cloned()
        .collect();
    for (n, _, len) in env.iter_mut() {
        if angles.contains(n) {
            *len = false;
        }
    }
    Ok(forms
        .iter()
        .map(|parts| {
            parts
                .iter()
                .filter_map(|(_, e)| {
                    let (a, b) = (eval(e, &env, 1.0, None), eval(e, &env, 2.0, None));
                    (a.abs() > 1e-12 && b.is_finite()).then(|| (b / a).abs().log2().round() as i32)
                })
                .max()
                .unwrap_or(0)
                .max(0)
        })
        .collect())
}

/// The axes and home pose as numbers at the parameters `env`.
pub(crate) fn axis_data(
    sol: &super::IkSolution,
    env: &dyn Fn(&str) -> Option<f64>,
) -> Result<(Vec<AxisData>, [[f64; 4]; 3]), super::NumericError> {
    let ev = |x: &crate::Scalar| x.eval(env);
    let mut axes = Vec::new();
    for a in &sol.axes {
        let kind = f64::from(u8::from(a.kind == crate::kin::JointKind::Prismatic));
        axes.push([
            kind,
            ev(&a.dir[0])?,
            ev(&a.dir[1])?,
            ev(&a.dir[2])?,
            ev(&a.point[0])?,
            ev(&a.point[1])?,
            ev(&a.point[2])?,
        ]);
    }
    let mut home = [[0.0; 4]; 3];
    for (r, row) in home.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = ev(&sol.home.rows[r][c])?;
        }
    }
    Ok((axes, home))
}
