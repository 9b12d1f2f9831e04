//! The degree a general-method solution states: the roots of `det M(x)` that move with the
//! target.
//!
//! `det M(x)` (degree 24) has roots that are no solutions at any target: the spurious `±i`
//! (each of multiplicity four, from the half-angle factors `1 + x²`), roots at infinity (a
//! slide's `d = ∞`), and for special geometry more. The Stanford arm read from its slide, with
//! its wrist's middle joint hidden, has `θ5 = 0` and `θ5 = π` as roots of multiplicity four
//! each at every target (the wrist singular set: axes 4 and 6 in line, where the quantities of
//! the eliminated line no longer fix `θ4` and `θ6` apart, so the six equations have a common
//! solution whatever the target): the core's count of finite roots off `±i` is 16 there, the
//! arm's solutions are 8. A root that is a solution moves with the target; a spurious one
//! stays. So the degree is counted as the roots of `det M` at one generic target that are not
//! roots of `det M` at another generic target (the fewer of two others), with multiplicity:
//! `deg p − deg gcd(p, q)`. Each polynomial is read off by the inverse discrete Fourier
//! transform of the 12 x 12 determinant at 32 points of the unit circle (exact for degree 24
//! up to rounding); `deg gcd` is the rank deficiency of their Sylvester matrix (singular values
//! by one-sided Jacobi rotations, zero below [`COMMON_TOL`] of the largest). No root is
//! computed, so multiple roots (the spurious ones have multiplicity four) cost no accuracy.

use super::core::{matrix_poly, Arranged, J};

type Cx = (f64, f64);

fn mul(a: Cx, b: Cx) -> Cx {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn div(a: Cx, b: Cx) -> Cx {
    let d = b.0 * b.0 + b.1 * b.1;
    ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
}

fn sub(a: Cx, b: Cx) -> Cx {
    (a.0 - b.0, a.1 - b.1)
}

fn abs(a: Cx) -> f64 {
    a.0.hypot(a.1)
}

/// A singular value of the Sylvester matrix of two targets' polynomials below this fraction of
/// the largest is zero: a common root. The coefficients are the inverse DFT of 12 x 12
/// determinants, rounded to about `1e-15` of the largest, so a zero singular value comes out
/// at most about `1e-14` of the largest (measured: `2e-15` at most on the arms of the tests);
/// the nonzero ones are the separation of the two targets' moving roots, measured at `1e-8` or
/// more where the roots are of moderate size. `1e-11` lies three orders of magnitude from both.
pub(crate) const COMMON_TOL: f64 = 1e-11;

/// The smallest nonzero singular value (relative) that makes the rank clear: two orders of
/// magnitude above [`COMMON_TOL`]. Below it (polynomials with roots over many orders of
/// magnitude, whose Sylvester matrix has singular values all the way down) the count is not
/// trusted and the core's count of finite roots off `±i` stands.
pub(crate) const GAP_TOL: f64 = 1e-9;

/// `det M(x)` of an elimination's `Σ` (no shift), ascending coefficients (degree ≤ 24).
fn det_poly(sig: &[[[f64; 9]; 6]; 3]) -> Option<[f64; 25]> {
    const K: usize = 32;
    let m = matrix_poly(sig, 0.0);
    let mut vals = [(0.0, 0.0); K];
    for (k, v) in vals.iter_mut().enumerate() {
        let z = (std::f64::consts::TAU * k as f64 / K as f64).sin_cos();
        let z = (z.1, z.0);
        let z2 = mul(z, z);
        let mut a = [[(0.0, 0.0); 12]; 12];
        for r in 0..12 {
            for c in 0..12 {
                a[r][c] = (
                    m[0][r][c] + m[1][r][c] * z.0 + m[2][r][c] * z2.0,
                    m[1][r][c] * z.1 + m[2][r][c] * z2.1,
                );
            }
        }
        *v = det(&mut a);
    }
    let mut out = [0.0; 25];
    for (j, c) in out.iter_mut().enumerate() {
        // c_j = (1/K) Σ p(z_k) z_k^(−j): real for a real polynomial.
        *c = (0..K)
            .map(|k| {
                let a = -std::f64::consts::TAU * (j * k) as f64 / K as f64;
                mul(vals[k], (a.cos(), a.sin())).0
            })
            .sum::<f64>()
            / K as f64;
    }
    out.iter().all(|c| c.is_finite()).then_some(out)
}

/// The determinant of a complex matrix by elimination with partial pivoting.
fn det(a: &mut [[Cx; 12]; 12]) -> Cx {
    let mut d = (1.0, 0.0);
    for k in 0..12 {
        let p = (k..12)
            .max_by(|&i, &j| abs(a[i][k]).total_cmp(&abs(a[j][k])))
            .unwrap_or(k);
        if abs(a[p][k]) == 0.0 {
            return (0.0, 0.0);
        }
        if p != k {
            a.swap(p, k);
            d = (-d.0, -d.1);
        }
        d = mul(d, a[k][k]);
        let pivot = a[k];
        for row in a.iter_mut().skip(k + 1) {
            let f = div(row[k], pivot[k]);
            for (x, p) in row.iter_mut().zip(&pivot).skip(k) {
                *x = sub(*x, mul(f, *p));
            }
        }
    }
    d
}

/// `p` over its largest coefficient, trimmed to its degree (coefficients below `1e-11` of the
/// largest are rounding: a root at infinity each).
fn trimmed(p: &[f64; 25]) -> Option<Vec<f64>> {
    let big = p.iter().fold(0.0, |m: f64, c| m.max(c.abs()));
    if big == 0.0 {
        return None;
    }
    let deg = (0..25).rev().find(|&k| p[k].abs() > 1e-11 * big)?;
    Some(p[..=deg].iter().map(|c| c / big).collect())
}

/// The Sylvester matrix of `p` (degree `n`) and `q` (degree `m`): `m` shifted copies of `p`
/// and `n` of `q`, `(n + m)` square. Its rank is `n + m − deg gcd(p, q)`.
fn sylvester(p: &[f64], q: &[f64]) -> Vec<Vec<f64>> {
    let (n, m) = (p.len() - 1, q.len() - 1);
    let mut s = vec![vec![0.0; n + m]; n + m];
    for i in 0..m {
        for (k, c) in p.iter().enumerate() {
            s[i][i + k] = *c;
        }
    }
    for i in 0..n {
        for (k, c) in q.iter().enumerate() {
            s[m + i][i + k] = *c;
        }
    }
    s
}

/// The singular values of `a` (square), by one-sided Jacobi rotations of its columns.
fn singular_values(mut a: Vec<Vec<f64>>) -> Vec<f64> {
    let n = a.len();
    for _ in 0..60 {
        let mut off: f64 = 0.0;
        for i in 0..n {
            for j in i + 1..n {
                let (mut alpha, mut beta, mut gamma) = (0.0, 0.0, 0.0);
                for row in &a {
                    alpha += row[i] * row[i];
                    beta += row[j] * row[j];
                    gamma += row[i] * row[j];
                }
                if gamma == 0.0 {
                    continue;
                }
                off = off.max(gamma.abs() / (alpha * beta).sqrt());
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                let t = if zeta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                for row in a.iter_mut() {
                    let (x, y) = (row[i], row[j]);
                    row[i] = c * x - s * y;
                    row[j] = s * x + c * y;
                }
            }
        }
        if off < 1e-15 {
            break;
        }
    }
    (0..n)
        .map(|j| a.iter().map(|r| r[j] * r[j]).sum::<f64>().sqrt())
        .collect()
}

/// `deg gcd(p, q)`: the singular values of their Sylvester matrix below [`COMMON_TOL`] of the
/// largest, when the next one is above [`GAP_TOL`] of it (else `None`: the rank is not clear,
/// as for polynomials whose roots spread over many orders of magnitude).
fn common_degree(p: &[f64], q: &[f64]) -> Option<usize> {
    let mut sv = singular_values(sylvester(p, q));
    sv.sort_by(f64::total_cmp);
    let top = *sv.last()?;
    let k = sv.iter().filter(|x| **x <= COMMON_TOL * top).count();
    sv.get(k).is_some_and(|x| *x >= GAP_TOL * top).then_some(k)
}

/// The number of roots of `det M` at the target of `arranged[0]` that are not roots at the
/// targets of the others (the same arrangement at other generic targets), with multiplicity:
/// the degree that counts solutions. `None` when a determinant vanishes identically or a rank
/// is not clear.
pub(crate) fn moving_roots(arranged: &[Arranged]) -> Option<usize> {
    let polys: Vec<Vec<f64>> = arranged
        .iter()
        .map(|a| {
            a.elim()
                .and_then(|e| det_poly(&e.sig))
                .and_then(|p| trimmed(&p))
        })
        .collect::<Option<_>>()?;
    let deg = polys[0].len() - 1;
    let common = polys[1..]
        .iter()
        .map(|q| common_degree(&polys[0], q))
        .collect::<Option<Vec<usize>>>()?;
    Some(deg.saturating_sub(common.into_iter().min().unwrap_or(0)))
}

/// The roots of `det M` at the target of `ar` that back-substitute to a solution
/// (`closure.rs`): fewer than the moving ones for special geometry whose moving roots include
/// spurious ones. `None` when the determinant or the eigenvalues fail.
pub(crate) fn closing_roots(ar: &Arranged) -> Option<usize> {
    let el = ar.elim()?;
    let p = trimmed(&det_poly(&el.sig)?)?;
    super::closure::closing_roots(ar, &el, &p)
}

/// The same chain `js` at the targets `g` in arrangement `arr`.
pub(crate) fn arranged(js: &[J; 6], g: &[[[f64; 4]; 3]], arr: usize) -> Vec<Arranged> {
    g.iter().map(|g| Arranged::new(js, g, arr)).collect()
}

/// `a + b` of complex numbers.
fn add(a: Cx, b: Cx) -> Cx {
    (a.0 + b.0, a.1 + b.1)
}

/// The principal square root of a complex number.
fn csqrt(a: Cx) -> Cx {
    let r = abs(a);
    let re = (0.5 * (r + a.0)).max(0.0).sqrt();
    let im = (0.5 * (r - a.0)).max(0.0).sqrt();
    (re, if a.1 < 0.0 { -im } else { im })
}

/// A root of `D(θ4)` is spurious below this fraction of the size of its terms (`Σ |c_j|
/// |z|^±j`): the spurious roots are roots of `D` by its structure, so `D` vanishes there to the
/// rounding of its coefficients (about `1e-15` of the samples, measured `1e-14` at most),
/// while at a root of `fc ± i fs` that is no root of `D` it is of the order of its terms.
pub(crate) const APART_SPURIOUS: f64 = 1e-8;

/// The degree a 4R2P with its slides three apart reaches at the generic target of `ch`: the
/// `2 n` roots of the resultant `D(θ4)` (trigonometric degree `n`, in `z = e^{iθ4}`) less the
/// spurious ones, where the common root of `(1 + x²) F` and `(1 + x²)² P` is `x = ±i` (`θ5`
/// at infinity: no solution). `(1 + x²) F` at `x = ±i` is `2 (fc ± i fs)`, with `fc`, `fs`
/// the coefficients of `cos θ5`, `sin θ5` in `F`, of degree one in `θ4`: so the spurious roots
/// are among the two roots in `z` of each of `fc ± i fs`, and each that is a root of `D`
/// counts once. `None` when the resultant is not usable there.
pub(crate) fn apart_degree(ch: &super::apart::ApartChain) -> Option<usize> {
    let c = ch.coefficients()?;
    let size: f64 = c.iter().map(|x| abs(*x)).sum();
    let n = (0..c.len()).rev().find(|&j| abs(c[j]) > 1e-9 * size)?;
    // F's coefficients of (1, cos θ5, sin θ5), each as (1, cos θ4, sin θ4) by 3 x 3 samples.
    let tau = std::f64::consts::TAU;
    let mut fcoef = [[0.0; 3]; 3];
    for k4 in 0..3 {
        let t4 = tau * k4 as f64 / 3.0;
        for k5 in 0..3 {
            let t5 = tau * k5 as f64 / 3.0;
            let v = ch.fp(t4, t5).0;
            let w5 = [1.0 / 3.0, 2.0 * t5.cos() / 3.0, 2.0 * t5.sin() / 3.0];
            let w4 = [1.0 / 3.0, 2.0 * t4.cos() / 3.0, 2.0 * t4.sin() / 3.0];
            for a in 0..3 {
                for b in 0..3 {
                    fcoef[a][b] += v * w5[a] * w4[b];
                }
            }
        }
    }
    // D at complex z: (Σ c_j z^j + Σ conj(c_j) z^-j) / 2, and the size of its terms.
    let d_at = |z: Cx| {
        let zi = div((1.0, 0.0), z);
        let (mut p, mut q) = ((1.0, 0.0), (1.0, 0.0));
        let (mut sum, mut size) = ((0.0, 0.0), 0.0);
        for cj in &c {
            sum = add(sum, add(mul(*cj, p), mul((cj.0, -cj.1), q)));
            size += abs(*cj) * (abs(p) + abs(q));
            p = mul(p, z);
            q = mul(q, zi);
        }
        (abs(sum) * 0.5, size * 0.5)
    };
    let mut spurious = 0;
    for sign in [1.0, -1.0] {
        // g = fc + i sign fs = g0 + g1 z + g_1 / z, with a + b cos θ + e sin θ = a + (b − i e)/2
        // z + (b + i e)/2 z⁻¹.
        let lin = |k: usize| -> [Cx; 3] {
            let [a, b, e] = fcoef[k];
            [(a, 0.0), (0.5 * b, -0.5 * e), (0.5 * b, 0.5 * e)]
        };
        let (fc, fs) = (lin(1), lin(2));
        let g: [Cx; 3] = std::array::from_fn(|i| add(fc[i], mul((0.0, sign), fs[i])));
        // g1 z² + g0 z + g_1 = 0.
        let (qa, qb, qc) = (g[1], g[0], g[2]);
        if abs(qa) == 0.0 {
            continue;
        }
        let disc = csqrt(sub(mul(qb, qb), mul((4.0, 0.0), mul(qa, qc))));
        for r in [add((-qb.0, -qb.1), disc), sub((-qb.0, -qb.1), disc)] {
            let z = div(r, mul((2.0, 0.0), qa));
            let (v, s) = d_at(z);
            if abs(z) > 0.0 && v <= APART_SPURIOUS * s {
                spurious += 1;
            }
        }
    }
    Some((2 * n).saturating_sub(spurious))
}
