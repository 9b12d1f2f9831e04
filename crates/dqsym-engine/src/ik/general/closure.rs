//! The roots of `det M` that are solutions: each complex root `x3` of `det M(x)` at a generic
//! target is back-substituted in complex arithmetic (the null vector of `M(x3)`, `x4` and `x5`
//! from it, `X12` from `Bm X12 = Am(θ3) X45` by the QR of `Bm`) and kept when the fourteen
//! original equations hold and `X12` is the product `(1, c1, s1) ⊗ (1, c2, s2)` with `c² + s² =
//! 1` (a slide's `(1, d, d²)` with the square its square). For special geometry forced through
//! the general method, `det M` has roots that move with the target but are no solutions (the
//! IRB 140: 16 roots, 8 solutions); [`super::degree`] counts these out.

use super::core::{eigenvalues, matrix_poly, Arranged, Elim};

type Cx = (f64, f64);

fn mul(a: Cx, b: Cx) -> Cx {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn div(a: Cx, b: Cx) -> Cx {
    let d = b.0 * b.0 + b.1 * b.1;
    ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
}

fn add(a: Cx, b: Cx) -> Cx {
    (a.0 + b.0, a.1 + b.1)
}

fn sub(a: Cx, b: Cx) -> Cx {
    (a.0 - b.0, a.1 - b.1)
}

fn abs(a: Cx) -> f64 {
    a.0.hypot(a.1)
}

fn re(x: f64) -> Cx {
    (x, 0.0)
}

/// A root is a solution when the original equations and the products of `X12` hold to this
/// fraction of their terms. The roots come from the eigenvalues of a companion matrix, to
/// about `1e-10` relative at a generic target (simple roots, coefficients rounded to `1e-15`
/// of the largest, the matrix balanced); the null vector and the least squares lose at most
/// the condition of `M(x3)` and `Bm` (about `1e3` at the generic targets of the tests), so a
/// solution's defects are below `1e-7` (measured: `2e-9` at most, the IRB 140 and the UR5
/// forced general); a root that is no solution leaves them large (measured on the same arms:
/// the products off by `1e-1` to `8e-1`, the equations by `2e-3` to `1e-2`). `1e-4` lies
/// between, four orders from the first.
pub(crate) const CLOSURE_TOL: f64 = 1e-4;

/// A root whose defects (the larger of the two, relative) lie between [`CLOSURE_TOL`] and this
/// is neither clearly a solution nor clearly none (a nearly special arm, whose roots cluster
/// and come out of the eigenvalues to a few digits only): the count is not trusted and the
/// moving roots' count stands. The spurious roots measured leave `1.7e-1` at least.
pub(crate) const CLOSURE_FAR: f64 = 1e-2;

/// Roots within this distance of `±i` (the spurious factor `(1 + x²)⁴`, whose multiple roots
/// the eigenvalues spread by the fourth root of rounding, about `1e-4`) are not checked: they
/// are the spurious factor's.
const NEAR_I: f64 = 1e-2;

/// How many roots of `p` (ascending coefficients of `det M`, trimmed) back-substitute to a
/// solution of the original equations; `None` when the eigenvalues fail or a root is neither
/// clearly a solution nor clearly none ([`CLOSURE_FAR`]).
pub(crate) fn closing_roots(ar: &Arranged, el: &Elim, p: &[f64]) -> Option<usize> {
    let n = p.len() - 1;
    if n == 0 || n > 24 {
        return None;
    }
    let mut comp = [[0.0; 24]; 24];
    for j in 0..n {
        comp[0][j] = -p[n - 1 - j] / p[n];
    }
    for i in 1..n {
        comp[i][i - 1] = 1.0;
    }
    let roots = eigenvalues(&mut comp, n)?;
    let m = matrix_poly(&el.sig, 0.0);
    let mut count = 0;
    for &x in &roots[..n] {
        if abs(sub(x, (0.0, 1.0))) < NEAR_I || abs(add(x, (0.0, 1.0))) < NEAR_I {
            continue;
        }
        let defect = closes(ar, el, &m, x);
        if defect <= CLOSURE_TOL {
            count += 1;
        } else if defect < CLOSURE_FAR {
            return None;
        }
    }
    Some(count)
}

/// `(1, c, s)` of a turn from its half-angle tangent, or `(1, d, d²)` of a slide.
fn basis(prism: bool, x: Cx) -> [Cx; 3] {
    if prism {
        [re(1.0), x, mul(x, x)]
    } else {
        let x2 = mul(x, x);
        let den = add(re(1.0), x2);
        [
            re(1.0),
            div(sub(re(1.0), x2), den),
            div(mul(re(2.0), x), den),
        ]
    }
}

/// The complex null vector of a 12 x 12 matrix: LU with complete pivoting, the last unknown 1.
#[allow(clippy::needless_range_loop)]
fn null_vector(mut a: [[Cx; 12]; 12]) -> [Cx; 12] {
    let mut col: [usize; 12] = std::array::from_fn(|i| i);
    for k in 0..11 {
        let (mut pr, mut pc, mut best) = (k, k, -1.0);
        for r in k..12 {
            for c in k..12 {
                if abs(a[r][c]) > best {
                    (pr, pc, best) = (r, c, abs(a[r][c]));
                }
            }
        }
        a.swap(k, pr);
        for row in a.iter_mut() {
            row.swap(k, pc);
        }
        col.swap(k, pc);
        if best == 0.0 {
            continue;
        }
        for r in k + 1..12 {
            let f = div(a[r][k], a[k][k]);
            for c in k..12 {
                a[r][c] = sub(a[r][c], mul(f, a[k][c]));
            }
        }
    }
    let mut y = [re(0.0); 12];
    y[11] = re(1.0);
    for i in (0..11).rev() {
        let mut s = re(0.0);
        for k in i + 1..12 {
            s = sub(s, mul(a[i][k], y[k]));
        }
        y[i] = if abs(a[i][i]) == 0.0 {
            re(0.0)
        } else {
            div(s, a[i][i])
        };
    }
    let mut v = [re(0.0); 12];
    for i in 0..12 {
        v[col[i]] = y[i];
    }
    v
}

/// The ratio `v[num] / v[den]` over the pair with the largest denominator.
fn ratio(v: &[Cx; 12], pairs: &[(usize, usize)]) -> Cx {
    let &(n, d) = pairs
        .iter()
        .max_by(|a, b| abs(v[a.1]).total_cmp(&abs(v[b.1])))
        .unwrap_or(&(0, 0));
    div(v[n], v[d])
}

/// How far the root `x3` is from back-substituting to a solution: the larger of the fourteen
/// equations' defect and the products' of `X12`, each relative to its terms (see
/// [`CLOSURE_TOL`]); infinite where the least squares fails.
#[allow(clippy::needless_range_loop)]
fn closes(ar: &Arranged, el: &Elim, m: &[[[f64; 12]; 12]; 3], x3: Cx) -> f64 {
    let x32 = mul(x3, x3);
    let mx: [[Cx; 12]; 12] = std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            add(
                add(re(m[0][r][c]), mul(re(m[1][r][c]), x3)),
                mul(re(m[2][r][c]), x32),
            )
        })
    });
    let v = null_vector(mx);
    let at = |a: usize, b: usize| 3 * a + b;
    let x4 = ratio(
        &v,
        &(0..3)
            .flat_map(|a| (0..3).map(move |b| (at(a + 1, b), at(a, b))))
            .collect::<Vec<_>>(),
    );
    let x5 = ratio(
        &v,
        &(0..4)
            .flat_map(|a| (0..2).map(move |b| (at(a, b + 1), at(a, b))))
            .collect::<Vec<_>>(),
    );
    let pr = ar.prismatic();
    let (f3, f4, f5) = (basis(pr[2], x3), basis(pr[3], x4), basis(pr[4], x5));
    let mut rhs = [re(0.0); 14];
    let mut size = 0.0;
    for e in 0..14 {
        for k in 0..3 {
            for i4 in 0..3 {
                for i5 in 0..3 {
                    let t = mul(
                        re(el.am[e][k][3 * i4 + i5]),
                        mul(f3[k], mul(f4[i4], f5[i5])),
                    );
                    size += abs(t);
                    rhs[e] = add(rhs[e], t);
                }
            }
        }
    }
    // Qᵀ rhs: its last six entries are the equations' defect, its first eight give X12.
    let qr: [Cx; 14] =
        std::array::from_fn(|i| (0..14).fold(re(0.0), |s, e| add(s, mul(re(el.qt[i][e]), rhs[e]))));
    let defect = qr[8..].iter().map(|x| abs(*x)).fold(0.0, f64::max);
    let mut z = [re(0.0); 8];
    for i in (0..8).rev() {
        let mut s = qr[i];
        for k in i + 1..8 {
            s = sub(s, mul(re(el.r[i][k]), z[k]));
        }
        if el.r[i][i] == 0.0 {
            return f64::INFINITY;
        }
        z[i] = div(s, re(el.r[i][i]));
    }
    let mut x12 = [re(0.0); 9];
    x12[0] = re(1.0);
    for i in 0..8 {
        x12[el.piv[i] + 1] = z[i];
    }
    // The products: X[i, j] = X[i, 0] X[0, j], and each joint's own relation.
    let mut bad: f64 = 0.0;
    let mut scale: f64 = 1.0;
    for i in 1..3 {
        for j in 1..3 {
            let want = mul(x12[3 * i], x12[j]);
            scale = scale.max(abs(want)).max(abs(x12[3 * i + j]));
            bad = bad.max(abs(sub(x12[3 * i + j], want)));
        }
    }
    for (k, (one, two)) in [(0, (3, 6)), (1, (1, 2))] {
        let (a, b) = (x12[one], x12[two]);
        let rel = if pr[k] {
            sub(b, mul(a, a))
        } else {
            sub(add(mul(a, a), mul(b, b)), re(1.0))
        };
        scale = scale.max(abs(mul(a, a))).max(abs(b));
        bad = bad.max(abs(rel));
    }
    let d = (defect / size).max(bad / scale);
    if d.is_nan() {
        f64::INFINITY
    } else {
        d
    }
}
