//! The deflation of the spurious eigenvalues `±i` (`core::deflate_spurious`) against the
//! undeflated 24 x 24 companion matrix built here, and every eigenvalue it keeps against an
//! independent check: `M(λ)` is singular there (complex elimination written here).

#![allow(clippy::needless_range_loop)]

use super::core::{
    compose, eigen_quadratic, eigenvalues, inverse, lu, matrix_poly, Arranged, GenAxis, J,
    RANK_TOL, SHIFTS, SHIFT_GOOD, SHIFT_SINGULAR,
};

type M4 = [[f64; 4]; 4];

fn mul(a: &M4, b: &M4) -> M4 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// Classic DH frames `T_0 … T_6` at `q` for rows `(d, a, alpha)`.
fn frames(rows: &[(f64, f64, f64); 6], q: &[f64; 6]) -> [M4; 7] {
    let mut out = [[[0.0; 4]; 4]; 7];
    for (i, row) in out[0].iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for (k, &(d, a, al)) in rows.iter().enumerate() {
        let (st, ct) = q[k].sin_cos();
        let (sa, ca) = al.sin_cos();
        let m = [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0.0, sa, ca, d],
            [0.0, 0.0, 0.0, 1.0],
        ];
        out[k + 1] = mul(&out[k], &m);
    }
    out
}

/// The axes at home (axis i: the z axis of frame i − 1 through its origin) and the home pose.
fn axes(rows: &[(f64, f64, f64); 6]) -> ([GenAxis; 6], [[f64; 4]; 3]) {
    let f = frames(rows, &[0.0; 6]);
    let ax = std::array::from_fn(|i| {
        let t = f[i];
        [0.0, t[0][2], t[1][2], t[2][2], t[0][3], t[1][3], t[2][3]]
    });
    (ax, [f[6][0], f[6][1], f[6][2]])
}

struct Rng(u64);

impl Rng {
    fn angle(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * std::f64::consts::TAU
    }
}

type C = (f64, f64);

fn cmul(a: C, b: C) -> C {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn cdiv(a: C, b: C) -> C {
    let d = b.0 * b.0 + b.1 * b.1;
    ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
}

fn cabs(a: C) -> f64 {
    a.0.hypot(a.1)
}

/// The smallest pivot of `M(λ) = A λ² + B λ + C` by complex elimination with complete pivoting,
/// over `‖A‖ |λ|² + ‖B‖ |λ| + ‖C‖` (largest entries): about its distance to singularity.
fn singularity(mp: &[[[f64; 12]; 12]; 3], lam: C) -> f64 {
    let l2 = cmul(lam, lam);
    let mut m = [[(0.0, 0.0); 12]; 12];
    let mut size = [0.0f64; 3];
    for r in 0..12 {
        for c in 0..12 {
            let a = cmul((mp[2][r][c], 0.0), l2);
            let b = cmul((mp[1][r][c], 0.0), lam);
            m[r][c] = (a.0 + b.0 + mp[0][r][c], a.1 + b.1);
            for d in 0..3 {
                size[d] = size[d].max(mp[d][r][c].abs());
            }
        }
    }
    let scale = size[2] * cabs(l2) + size[1] * cabs(lam) + size[0];
    let mut smallest = f64::INFINITY;
    for k in 0..12 {
        let (mut br, mut bc) = (k, k);
        for r in k..12 {
            for c in k..12 {
                if cabs(m[r][c]) > cabs(m[br][bc]) {
                    (br, bc) = (r, c);
                }
            }
        }
        m.swap(k, br);
        for row in m.iter_mut() {
            row.swap(k, bc);
        }
        let d = m[k][k];
        smallest = smallest.min(cabs(d));
        if cabs(d) == 0.0 {
            break;
        }
        for r in k + 1..12 {
            let f = cdiv(m[r][k], d);
            for c in k..12 {
                let p = cmul(f, m[k][c]);
                m[r][c] = (m[r][c].0 - p.0, m[r][c].1 - p.1);
            }
        }
    }
    smallest / scale
}

/// `A⁻¹ X` by Gauss–Jordan with partial pivoting (written here, not the solver's LU).
fn solve_columns(a: &[[f64; 12]; 12], x: &[[f64; 12]; 12]) -> [[f64; 12]; 12] {
    let (mut a, mut x) = (*a, *x);
    for k in 0..12 {
        let p = (k..12)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .expect("rows");
        a.swap(k, p);
        x.swap(k, p);
        for r in 0..12 {
            if r != k {
                let f = a[r][k] / a[k][k];
                for c in 0..12 {
                    a[r][c] -= f * a[k][c];
                    x[r][c] -= f * x[k][c];
                }
            }
        }
    }
    for r in 0..12 {
        for c in 0..12 {
            x[r][c] /= a[r][r];
        }
    }
    x
}

/// For random poses of the arm: the eigenvalues kept by the deflation are those of the full
/// companion matrix less `±i`, each a point where `M` is singular; returns the sizes seen.
fn check_arm(rows: &[(f64, f64, f64); 6], seed: u64, poses: usize) -> Vec<usize> {
    let (ax, home) = axes(rows);
    let mut rng = Rng(seed);
    let mut sizes = Vec::new();
    for _ in 0..poses {
        let q: [f64; 6] = std::array::from_fn(|_| rng.angle());
        let t = frames(rows, &q)[6];
        let tg = [t[0], t[1], t[2]];
        let g = compose(&tg, &inverse(&home));
        let js: [J; 6] = std::array::from_fn(|i| J {
            w: [ax[i][1], ax[i][2], ax[i][3]],
            c: [ax[i][4], ax[i][5], ax[i][6]],
            prism: false,
        });
        // The first usable arrangement and shift, as the solver chooses them.
        let usable = (0..12).find_map(|arr| {
            let el = Arranged::new(&js, &g, arr).elim()?;
            if el.rank_ratio < RANK_TOL {
                return None;
            }
            let mut best = None;
            for phi in SHIFTS {
                let mp = matrix_poly(&el.sig, phi);
                let mut a = mp[2];
                let (p, ratio) = lu(&mut a);
                if best.as_ref().is_none_or(|b: &(_, _, _, f64)| ratio > b.3) {
                    best = Some((mp, a, p, ratio));
                }
                if ratio > SHIFT_GOOD {
                    break;
                }
            }
            best.filter(|b| b.3 >= SHIFT_SINGULAR)
                .map(|(mp, a, p, _)| (mp, a, p))
        });
        let (mp, a, p) = usable.expect("a usable arrangement");
        let (kept, n) = eigen_quadratic(&mp, &a, &p).expect("eigenvalues");
        sizes.push(n);
        // The full companion matrix [[0, I], [−A⁻¹C, −A⁻¹B]].
        let (xc, xb) = (solve_columns(&mp[2], &mp[0]), solve_columns(&mp[2], &mp[1]));
        let mut k = [[0.0; 24]; 24];
        for i in 0..12 {
            k[i][12 + i] = 1.0;
            for j in 0..12 {
                k[12 + i][j] = -xc[i][j];
                k[12 + i][12 + j] = -xb[i][j];
            }
        }
        let full = eigenvalues(&mut k, 24).expect("full eigenvalues");
        // Matched within a millionth relative: eigenvalues of a random pose are far apart by
        // comparison, and both sets carry rounding errors near 1e-12 (condition times 1e-16).
        let mut used = [false; 24];
        for &(re, im) in &kept[..n] {
            let at = (0..24).find(|&j| {
                !used[j] && (full[j].0 - re).hypot(full[j].1 - im) <= 1e-6 * (1.0 + re.hypot(im))
            });
            let j = at.unwrap_or_else(|| panic!("{re} + {im} i not among {full:?}"));
            used[j] = true;
            // A finite eigenvalue makes M singular: its smallest pivot is rounding (1e-16
            // relative) times the growth of the elimination and the eigenvalue's condition.
            if re.hypot(im) < 1e6 {
                let s = singularity(&mp, (re, im));
                assert!(s < 1e-9, "M({re} + {im} i) is not singular: {s:e}");
            }
        }
        for j in (0..24).filter(|&j| !used[j]) {
            let (re, im) = full[j];
            assert!(
                re.abs() + (im.abs() - 1.0).abs() < 1e-6,
                "a deflated eigenvalue {re} + {im} i is not ±i"
            );
        }
    }
    sizes
}

#[test]
fn deflation_keeps_every_eigenvalue_but_the_spurious_of_a_skew_6r() {
    let rows = super::det_tests::skew_rows();
    let sizes = check_arm(&rows, 0x9e37_79b9_7f4a_7c15, 40);
    // A general 6R: the factor (1 + x²)⁴ gives four null vectors of M(i), eight eigenvalues.
    assert!(sizes.iter().all(|&n| n == 16), "{sizes:?}");
}

#[test]
fn deflation_keeps_every_eigenvalue_but_the_spurious_of_special_arms() {
    let h = std::f64::consts::FRAC_PI_2;
    // PUMA 560 (two parallel axes, spherical wrist) and UR5 (three parallel axes): the
    // elimination degenerates further; whatever the deflation removes must be ±i.
    let puma = [
        (0.0, 0.0, h),
        (0.0, 0.4318, 0.0),
        (0.15, 0.0203, -h),
        (0.4318, 0.0, h),
        (0.0, 0.0, -h),
        (0.0, 0.0, 0.0),
    ];
    let ur5 = [
        (0.089159, 0.0, h),
        (0.0, -0.425, 0.0),
        (0.0, -0.39225, 0.0),
        (0.10915, 0.0, h),
        (0.09465, 0.0, -h),
        (0.0823, 0.0, 0.0),
    ];
    for (name, rows) in [("puma", puma), ("ur5", ur5)] {
        let sizes = check_arm(&rows, 12345, 20);
        assert!(
            sizes.iter().all(|&n| n < 24),
            "{name}: nothing deflated {sizes:?}"
        );
    }
}
