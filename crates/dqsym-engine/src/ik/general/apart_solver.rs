// The numeric core of a 4R2P chain whose two slides are three joints apart (RPRRPR, PRRPRR,
// RRPRRP): the Raghavan–Roth elimination of `core.rs` is degenerate for it in every reading of
// the loop (see `mod.rs`), so the orientation and the position are separated instead. Plain
// Rust on `f64` arrays that uses `core.rs`'s helpers; the generated Rust solver contains it
// verbatim after the core (the engine compiles it as `ik::general::apart`).
//
// The loop read from the first slide (or backwards): `Tr(d0 v0) E1 E2 Tr(d3 v3) E4 E5 = H`.
//
// 1. Slides turn nothing: `R1 R2 R4 R5 = R_H`, so `Q := R1 R2 = R_H R5ᵀ R4ᵀ`. `R1` keeps `w1`
//    and `R2` keeps `w2`, so `w1 · Q w2 = w1 · w2`: `F(θ4, θ5) = 0`, of degree one in the
//    sine and cosine of each. Given `Q`, `θ1` turns `w2` onto `Q w2` about `w1` (subproblem 1:
//    `cos θ1`, `sin θ1` linear in `Q`, over the constant `|w2 − (w1·w2) w1|²`) and `R2 = R1ᵀ Q`.
// 2. A turn moves a translation past itself (`E Tr(v) = Tr(R v) E`): the left side is
//    `Tr(d0 v0 + d3 Q v3) E1 E2 E4 E5`, so `h − t(E1 E2 E4 E5) = d0 v0 + d3 Q v3` and
//    `P(θ4, θ5) = det(v0, Q v3, h − t) = 0`, with `t = c1 − R1 c1 + R1 c2 − Q c2 + Q (c4 −
//    R4 c4) + R_H (R5ᵀ c5 − c5)` (`ci` a point of axis `i`): of degree two in each.
// 3. The Sylvester matrix of `(1 + x²) F` (quadratic in `x = tan(θ5/2)`) and `(1 + x²)² P`
//    (quartic): 6 x 6, its determinant `D(θ4)` a trigonometric polynomial of degree at most
//    `4 · 1 + 2 · 2 = 8`. Its coefficients come from 17 samples by the discrete Fourier
//    transform (checked at an 18th angle), its real roots from the core's certified search
//    (`trig_roots`). Degree reached at a generic target: 8 (`D` has degree 6, and the four
//    roots where the common root is `x = ±i` are no solutions: see `mod.rs`).
// 4. Back-substitution: `θ5` from `F = 0` (two roots; the one where `P` vanishes), `θ1`, `θ2`
//    by subproblem 1, `d0`, `d3` by least squares, every candidate polished by the core's
//    Gauss–Newton and checked by forward kinematics. Where `v0 × Q v3` vanishes (the slides'
//    current directions parallel: a line of solutions) or `F` does not depend on `θ5`, the
//    back-substitution degenerates: the solution is flagged singular.

/// The rounding of `P` relative to the size of its terms at a root, with a margin: `θ4` is a
/// root to `BRACKET_TOL` (`1e-10`) and `P`'s derivatives are of the order of its terms (trig
/// degree 2 in unit-sized quantities), so a true common root leaves `|P|` about `1e-9` of that
/// size at most; a second root of `F` that is no solution leaves `P` of the order of its terms.
/// `1e-6` lies three orders above the first.
pub const APART_P_TOL: f64 = 1e-6;

/// `|v0 × Q v3|²` (unit directions) below this: the slides' current directions are parallel to
/// within `1e-4` rad, where `d0`, `d3` are fixed only to about the residual over this sine: the
/// solution is flagged singular.
pub const APART_PARALLEL: f64 = 1e-8;

type Vec3 = [f64; 3];
type Mat3 = [[f64; 3]; 3];

fn apart_mt(r: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| r[j][i]))
}

fn apart_mm(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn apart_sub(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn apart_add(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The canonical chain: arranged joints 0 and 3 slide, 1, 2, 4, 5 turn; `H` the target.
pub(crate) struct ApartChain {
    pub(crate) ar: Arranged,
    rh: Mat3,
    h: Vec3,
    /// `w1 · w2`, `w2 − (w1·w2) w1` and its squared length.
    k12: f64,
    a: Vec3,
    na: f64,
}

impl ApartChain {
    pub(crate) fn new(ar: Arranged) -> Option<ApartChain> {
        let rh: Mat3 = std::array::from_fn(|i| [ar.h[i][0], ar.h[i][1], ar.h[i][2]]);
        let h = [ar.h[0][3], ar.h[1][3], ar.h[2][3]];
        let (w1, w2) = (ar.j[1].w, ar.j[2].w);
        let k12 = dot3(&w1, &w2);
        let a = apart_sub(&w2, &[k12 * w1[0], k12 * w1[1], k12 * w1[2]]);
        let na = dot3(&a, &a);
        // Turns 1 and 2 about parallel axes fix only θ1 + θ2: this reading cannot serve.
        (na > APART_PARALLEL).then_some(ApartChain {
            ar,
            rh,
            h,
            k12,
            a,
            na,
        })
    }

    fn rot(&self, i: usize, th: f64) -> Mat3 {
        let (s, c) = th.sin_cos();
        rodrigues(&self.ar.j[i].w, s, c)
    }

    /// `Q = R_H R5ᵀ R4ᵀ`.
    fn q(&self, t4: f64, t5: f64) -> Mat3 {
        apart_mm(
            &apart_mm(&self.rh, &apart_mt(&self.rot(5, t5))),
            &apart_mt(&self.rot(4, t4)),
        )
    }

    fn f(&self, q: &Mat3) -> f64 {
        let (w1, w2) = (self.ar.j[1].w, self.ar.j[2].w);
        dot3(&w1, &mv(q, &w2)) - self.k12
    }

    /// `(cos θ1, sin θ1)` as subproblem 1 gives them, linear in `Q` (exact where `F = 0`).
    fn cs1(&self, q: &Mat3) -> (f64, f64) {
        let (w1, w2) = (self.ar.j[1].w, self.ar.j[2].w);
        let qw = mv(q, &w2);
        let b = apart_sub(&qw, &[self.k12 * w1[0], self.k12 * w1[1], self.k12 * w1[2]]);
        (
            dot3(&self.a, &b) / self.na,
            dot3(&w1, &cross3(&self.a, &b)) / self.na,
        )
    }

    /// `h − t(E1 E2 E4 E5)` and `Q v3` with `R1` from `(c1, s1)`.
    fn reach(&self, t4: f64, t5: f64, q: &Mat3, c1: f64, s1: f64) -> (Vec3, Vec3) {
        let j = &self.ar.j;
        let r1 = rodrigues(&j[1].w, s1, c1);
        let r4 = self.rot(4, t4);
        let r5 = self.rot(5, t5);
        let t1 = apart_sub(&j[1].c, &mv(&r1, &j[1].c));
        let t2 = apart_sub(&mv(&r1, &j[2].c), &mv(q, &j[2].c));
        let t4v = mv(q, &apart_sub(&j[4].c, &mv(&r4, &j[4].c)));
        let t5v = mv(&self.rh, &apart_sub(&mv(&apart_mt(&r5), &j[5].c), &j[5].c));
        let t = apart_add(&apart_add(&t1, &t2), &apart_add(&t4v, &t5v));
        (apart_sub(&self.h, &t), mv(q, &j[3].w))
    }

    /// `(F, P, size of P's terms)` at `(θ4, θ5)`, `P` in its polynomial form.
    pub(crate) fn fp(&self, t4: f64, t5: f64) -> (f64, f64, f64) {
        let q = self.q(t4, t5);
        let (c1, s1) = self.cs1(&q);
        let (r, u) = self.reach(t4, t5, &q, c1, s1);
        let v0 = self.ar.j[0].w;
        let n = cross3(&v0, &u);
        let p = dot3(&n, &r);
        let size = dot3(&n, &n).sqrt() * dot3(&r, &r).sqrt() + f64::MIN_POSITIVE;
        (self.f(&q), p, size)
    }

    /// `(1 + x²) F` and `(1 + x²)² P` in `x = tan(θ5/2)` at `θ4` (ascending coefficients), from
    /// three and five samples of `θ5` (exact for degrees one and two).
    fn polys(&self, t4: f64) -> ([f64; 3], [f64; 5]) {
        let tau = std::f64::consts::TAU;
        let (mut f0, mut fc, mut fs) = (0.0, 0.0, 0.0);
        for k in 0..3 {
            let th = tau * k as f64 / 3.0;
            let v = self.fp(t4, th).0;
            f0 += v / 3.0;
            fc += 2.0 * v * th.cos() / 3.0;
            fs += 2.0 * v * th.sin() / 3.0;
        }
        let mut pc = [0.0; 5];
        for k in 0..5 {
            let th = tau * k as f64 / 5.0;
            let v = self.fp(t4, th).1;
            pc[0] += v / 5.0;
            for m in 1..3 {
                let (s, c) = (m as f64 * th).sin_cos();
                pc[2 * m - 1] += 2.0 * v * c / 5.0;
                pc[2 * m] += 2.0 * v * s / 5.0;
            }
        }
        let [p0, c1, s1, c2, s2] = pc;
        (
            [f0 + fc, 2.0 * fs, f0 - fc],
            [
                p0 + c1 + c2,
                2.0 * s1 + 4.0 * s2,
                2.0 * p0 - 6.0 * c2,
                2.0 * s1 - 4.0 * s2,
                p0 - c1 + c2,
            ],
        )
    }

    /// `D(θ4)`: the determinant of the Sylvester matrix, and how well its LU is conditioned.
    fn resultant(&self, t4: f64) -> (f64, f64) {
        let (f, p) = self.polys(t4);
        let mut s = [[0.0; 6]; 6];
        for i in 0..4 {
            s[i][i..i + 3].copy_from_slice(&f);
        }
        for i in 0..2 {
            s[4 + i][i..i + 5].copy_from_slice(&p);
        }
        let (perm, ratio) = lu(&mut s);
        let mut d = 1.0;
        for (i, row) in s.iter().enumerate() {
            d *= row[i];
        }
        // The sign of the row permutation.
        let mut seen = [false; 6];
        for i in 0..6 {
            if seen[i] {
                continue;
            }
            let (mut k, mut len) = (i, 0);
            while !seen[k] {
                seen[k] = true;
                k = perm[k];
                len += 1;
            }
            if len % 2 == 0 {
                d = -d;
            }
        }
        (d, ratio)
    }

    /// The trigonometric coefficients of `D` (as `det_coefficients`), `None` when the check
    /// angle disagrees or no sample is conditioned.
    #[allow(clippy::needless_range_loop)]
    pub(crate) fn coefficients(&self) -> Option<[(f64, f64); DET_DEGREE + 1]> {
        let step = std::f64::consts::TAU / DET_SAMPLES as f64;
        let mut d = [0.0; DET_SAMPLES];
        let (mut scale, mut good) = (0.0f64, 0.0f64);
        for k in 0..DET_SAMPLES {
            let (v, ratio) = self.resultant(k as f64 * step);
            d[k] = v;
            scale = scale.max(v.abs());
            good = good.max(ratio);
        }
        if !(good > SHIFT_GOOD && scale.is_finite()) {
            return None;
        }
        let mut c = [(0.0, 0.0); DET_DEGREE + 1];
        for j in 0..=DET_DEGREE {
            let (mut a, mut b) = (0.0, 0.0);
            for k in 0..DET_SAMPLES {
                let (s, co) = ((j * k) as f64 * step).sin_cos();
                a += d[k] * co;
                b += d[k] * s;
            }
            let w = if j == 0 { 1.0 } else { 2.0 } / DET_SAMPLES as f64;
            c[j] = (w * a, -(w * b));
        }
        let half = 0.5 * step;
        let interp: f64 = (0..=DET_DEGREE)
            .map(|j| {
                let (s, co) = (j as f64 * half).sin_cos();
                c[j].0 * co - c[j].1 * s
            })
            .sum();
        ((self.resultant(half).0 - interp).abs() <= DET_CHECK * scale).then_some(c)
    }

    /// The joints (arranged order) at a root `θ4`: one or two candidates (the roots of `F = 0`
    /// in `θ5` where `P` vanishes), each with whether its back-substitution degenerates.
    fn back(&self, t4: f64, out: &mut [([f64; 6], bool); 2]) -> usize {
        let tau = std::f64::consts::TAU;
        let (mut f0, mut fc, mut fs) = (0.0, 0.0, 0.0);
        for k in 0..3 {
            let th = tau * k as f64 / 3.0;
            let v = self.fp(t4, th).0;
            f0 += v / 3.0;
            fc += 2.0 * v * th.cos() / 3.0;
            fs += 2.0 * v * th.sin() / 3.0;
        }
        let rho = fc.hypot(fs);
        let flat = rho <= APART_PARALLEL.sqrt() * (rho + f0.abs() + f64::MIN_POSITIVE);
        let base = fs.atan2(fc);
        let spread = if flat {
            0.0
        } else {
            (-f0 / rho).clamp(-1.0, 1.0).acos()
        };
        let cands = [base + spread, base - spread];
        let ps: [(f64, f64, f64); 2] = std::array::from_fn(|i| self.fp(t4, cands[i]));
        let best = usize::from(ps[1].1.abs() < ps[0].1.abs());
        let mut n = 0;
        for i in [best, 1 - best] {
            let ok = i == best || ps[i].1.abs() <= APART_P_TOL * ps[i].2;
            if ok && (n == 0 || spread > 0.0) {
                out[n] = self.joints(t4, cands[i]);
                out[n].1 |= flat;
                n += 1;
            }
        }
        n
    }

    /// Every joint from `θ4`, `θ5` (arranged order) and whether the slides' least squares
    /// degenerates.
    fn joints(&self, t4: f64, t5: f64) -> ([f64; 6], bool) {
        let q = self.q(t4, t5);
        let (c1, s1) = self.cs1(&q);
        let t1 = s1.atan2(c1);
        let (w1, w2) = (self.ar.j[1].w, self.ar.j[2].w);
        let qt = apart_mt(&q);
        let a2 = apart_sub(
            &mv(&qt, &w1),
            &[self.k12 * w2[0], self.k12 * w2[1], self.k12 * w2[2]],
        );
        let b2 = apart_sub(&w1, &[self.k12 * w2[0], self.k12 * w2[1], self.k12 * w2[2]]);
        let t2 = dot3(&w2, &cross3(&a2, &b2)).atan2(dot3(&a2, &b2));
        let (r, u) = self.reach(t4, t5, &q, t1.cos(), t1.sin());
        let v0 = self.ar.j[0].w;
        // Least squares of r = d0 v0 + d3 u (unit directions): the normal equations.
        let k = dot3(&v0, &u);
        let det = 1.0 - k * k;
        let (r0, ru) = (dot3(&v0, &r), dot3(&u, &r));
        let singular = det.is_nan() || det <= APART_PARALLEL;
        let (d0, d3) = if singular {
            // A line of solutions: the one with d3 = 0.
            (r0, 0.0)
        } else {
            ((r0 - k * ru) / det, (ru - k * r0) / det)
        };
        ([d0, t1, t2, d3, t4, t5], singular)
    }
}

/// The real roots of `D(θ) = Re Σ_j c_j e^{ijθ}` (as [`trig_roots`] returns them) where the
/// certified search gives up (a root of multiplicity three or more to rounding, `D` and `D′`
/// both zero there): the eigenvalues of the companion matrix of `D` in `x = tan((θ − φ)/2)`,
/// as the core takes `det M`'s where its search gives up. With `e^{iθ'} = (1 + ix)² / (1 +
/// x²)` (`θ' = θ − φ`), `(1 + x²)ⁿ D = Re Σ_j c_j e^{ijφ} (1 + ix)ⁿ⁺ʲ (1 − ix)ⁿ⁻ʲ` is a real
/// polynomial of degree `2n` (`n` the degree of `D` less its top coefficients that are
/// rounding, [`DET_TRIM`]) whose leading coefficient is `D(φ + π)`: the shift `φ` is the first
/// of [`SHIFTS`] where that is above [`SHIFT_GOOD`] of `Σ |c_j|` (else the best), so that no
/// root lies at `x = ∞`. An eigenvalue within [`NEAR_REAL`] of the real axis is a root `θ = φ +
/// 2 atan x` (a multiple root splits into such a cluster; the refinement and the check by
/// forward kinematics decide). `None` when `D` vanishes identically to rounding or the QR
/// iteration does not converge.
#[allow(clippy::needless_range_loop)]
pub(crate) fn apart_eigen_roots(
    c: &[(f64, f64); DET_DEGREE + 1],
    out: &mut [f64; 24],
) -> Option<usize> {
    let mut b0 = 0.0;
    for cj in c {
        b0 += cj.0.hypot(cj.1);
    }
    let mut n = DET_DEGREE;
    while n > 0 && c[n].0.hypot(c[n].1) <= DET_TRIM * b0 {
        n -= 1;
    }
    if !(b0 > 0.0 && b0.is_finite()) {
        return None;
    }
    if n == 0 {
        // A nonzero constant: no root.
        return Some(0);
    }
    // The shift: |D(φ + π)| = |Σ_j (−1)ʲ Re(c_j e^{ijφ})| large.
    let mut best = (0.0, -1.0);
    for phi in SHIFTS {
        let mut lead = 0.0;
        for j in 0..=n {
            let (s, co) = (j as f64 * phi).sin_cos();
            let re = c[j].0 * co - c[j].1 * s;
            lead += if j % 2 == 0 { re } else { -re };
        }
        let ratio = lead.abs() / b0;
        if ratio > best.1 {
            best = (phi, ratio);
        }
        if ratio > SHIFT_GOOD {
            break;
        }
    }
    // (No NaN: `b0` is finite.)
    if best.1 <= 0.0 {
        return None;
    }
    let phi = best.0;
    // The polynomial's coefficients (ascending): each (1 + ix)ⁿ⁺ʲ (1 − ix)ⁿ⁻ʲ expanded as a
    // complex polynomial, its product with c_j e^{ijφ} taken real.
    let m = 2 * n;
    let mut p = [0.0; 2 * DET_DEGREE + 1];
    for j in 0..=n {
        let (s, co) = (j as f64 * phi).sin_cos();
        let (a, b) = (c[j].0 * co - c[j].1 * s, c[j].0 * s + c[j].1 * co);
        let mut pr = [0.0; 2 * DET_DEGREE + 1];
        let mut pi = [0.0; 2 * DET_DEGREE + 1];
        pr[0] = 1.0;
        for k in 0..m {
            // Times (1 + i sg x), the highest power first.
            let sg = if k < n + j { 1.0 } else { -1.0 };
            for l in (1..=k + 1).rev() {
                let (r0, i0) = (pr[l], pi[l]);
                pr[l] = r0 - sg * pi[l - 1];
                pi[l] = i0 + sg * pr[l - 1];
            }
        }
        for l in 0..=m {
            p[l] += a * pr[l] - b * pi[l];
        }
    }
    // The companion matrix of the monic polynomial.
    let mut k = [[0.0; 24]; 24];
    for col in 0..m {
        k[0][col] = -p[m - 1 - col] / p[m];
    }
    for r in 1..m {
        k[r][r - 1] = 1.0;
    }
    let ev = eigenvalues(&mut k, m)?;
    let mut count = 0;
    for &(re, im) in &ev[..m] {
        if im.abs() <= NEAR_REAL * (1.0 + re.abs()) && re.is_finite() {
            out[count] = phi + 2.0 * re.atan();
            count += 1;
        }
    }
    Some(count)
}

/// The two slides three joints apart: the arrangements (`shift + 6 reversed`) that put them
/// at arranged joints 0 and 3, forwards and backwards; `None` for any other chain.
pub fn apart_arrangements(prismatic: &[bool; 6]) -> Option<[usize; 2]> {
    let mut found = [0usize; 2];
    let mut n = 0;
    for (i, &p) in prismatic.iter().enumerate() {
        if p {
            if n == 2 {
                return None;
            }
            found[n] = i;
            n += 1;
        }
    }
    (n == 2 && found[1] - found[0] == 3).then_some([found[0], 6 + (5 - found[1])])
}

/// Every solution of a 4R2P chain with its slides three joints apart (see the file's notes),
/// as [`gen_solve`] returns them, and whether each one's back-substitution degenerated
/// (`singular`). The forward reading first; when a root gave no new exact solution (a
/// double root: two solutions sharing `θ4`), the backward one too. The roots of `D` by the
/// certified search ([`trig_roots`]); where it gives up in both readings, by the companion
/// matrix ([`apart_eigen_roots`]).
pub fn apart_solve(
    axes: &[GenAxis; 6],
    home: &[[f64; 4]; 3],
    target: &[[f64; 4]; 4],
    len: f64,
    tol: GenTol,
    singular: &mut [bool; GEN_MAX],
) -> GenOut {
    apart_solve_by(axes, home, target, len, tol, singular, false)
}

/// [`apart_solve`], with the companion matrix's route only when `eigen_only` (the tests' way
/// to reach the route the certified search rarely leaves to it).
#[allow(clippy::needless_range_loop)]
pub(crate) fn apart_solve_by(
    axes: &[GenAxis; 6],
    home: &[[f64; 4]; 3],
    target: &[[f64; 4]; 4],
    len: f64,
    tol: GenTol,
    singular: &mut [bool; GEN_MAX],
    eigen_only: bool,
) -> GenOut {
    let mut out = GenOut {
        q: [[0.0; 6]; GEN_MAX],
        residual: [0.0; GEN_MAX],
        n: 0,
        degree: 0,
        arrangements: [0; 3],
        n_arr: 0,
    };
    let mut ax = *axes;
    for a in ax.iter_mut() {
        for k in 4..7 {
            a[k] /= len;
        }
    }
    let mut hm = *home;
    let mut tg = [[0.0; 4]; 3];
    tg.copy_from_slice(&target[..3]);
    for r in 0..3 {
        hm[r][3] /= len;
        tg[r][3] /= len;
    }
    let prismatic: [bool; 6] = std::array::from_fn(|i| ax[i][0] != 0.0);
    let Some(arrs) = apart_arrangements(&prismatic) else {
        return out;
    };
    // The forward kinematics' chain (the refinement's).
    let fk = chain(&ax, &hm);
    let g = compose(&tg, &inverse(&hm));
    let js: [J; 6] = std::array::from_fn(|i| J {
        w: [ax[i][1], ax[i][2], ax[i][3]],
        c: [ax[i][4], ax[i][5], ax[i][6]],
        prism: prismatic[i],
    });
    // Both readings by the certified search, then (where it gave up in both) by the
    // eigenvalues.
    let routes = [
        (false, arrs[0]),
        (false, arrs[1]),
        (true, arrs[0]),
        (true, arrs[1]),
    ];
    let mut searched = false;
    for (eigen, arr) in routes {
        if (eigen && searched) || (eigen_only && !eigen) {
            continue;
        }
        let Some(ch) = ApartChain::new(Arranged::new(&js, &g, arr)) else {
            continue;
        };
        let Some(c) = ch.coefficients() else { continue };
        let mut th = [0.0; 24];
        let found = if eigen {
            apart_eigen_roots(&c, &mut th)
        } else {
            trig_roots(&c, &mut th)
        };
        let Some(count) = found else {
            continue;
        };
        searched |= !eigen;
        if out.n_arr == 0 {
            out.degree = 2 * DET_DEGREE;
        }
        if out.n_arr < 3 {
            out.arrangements[out.n_arr] = arr;
        }
        out.n_arr += 1;
        let mut hit = [false; GEN_MAX];
        let mut roots = 0;
        for &t4 in &th[..count] {
            let mut cands = [([0.0; 6], false); 2];
            let m = ch.back(t4, &mut cands);
            roots += m;
            for (qa, sing) in &cands[..m] {
                let mut q = [0.0; 6];
                for i in 0..6 {
                    q[ch.ar.perm[i]] = qa[i];
                }
                if let Some((i, exact, appended)) = add_root(&mut out, q, &fk, &tg, &tol) {
                    if appended {
                        singular[i] = *sing;
                    } else {
                        singular[i] |= *sing;
                    }
                    hit[i] |= exact;
                }
            }
        }
        if hit.iter().filter(|h| **h).count() == roots {
            break;
        }
    }
    for q in out.q.iter_mut().take(out.n) {
        for (v, p) in q.iter_mut().zip(prismatic) {
            if p {
                *v *= len;
            }
        }
    }
    out
}

/// [`apart_solve`] with the signature of [`gen_solve`] (the generated Rust solver's driver
/// calls it so; its `singular` flags are not returned).
#[allow(dead_code)]
pub fn apart_gen_solve(
    axes: &[GenAxis; 6],
    home: &[[f64; 4]; 3],
    target: &[[f64; 4]; 4],
    len: f64,
    tol: GenTol,
    _first: usize,
) -> GenOut {
    let mut singular = [false; GEN_MAX];
    apart_solve(axes, home, target, len, tol, &mut singular)
}
