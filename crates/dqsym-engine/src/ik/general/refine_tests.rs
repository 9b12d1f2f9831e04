//! The refinement's pieces (`core::forward` on the joints' frames, `core::cholesky_solve`,
//! `core::refine`) and the elimination's QR (`core::qr_pivot`) against independent
//! computations written in the tests: a forward kinematics of plain 4 x 4 matrices
//! (`apart_tests`: Rodrigues' formula per joint, the product of exponentials), the residual of
//! the solved system, the definition of a QR factorization.

#![allow(clippy::needless_range_loop)]

use super::apart_tests::{joint, mul, M4};
use super::core::{chain, cholesky_solve, forward, qr_pivot, refine, GenAxis, EXACT_TOL};
use super::det_tests::Rng;

fn unit_vector(rng: &mut Rng) -> [f64; 3] {
    loop {
        let v: [f64; 3] = std::array::from_fn(|_| 2.0 * rng.unit() - 1.0);
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.2 && n < 1.0 {
            return v.map(|x| x / n);
        }
    }
}

/// A random arm (each joint a slide with probability 1/4, lengths below 1) and home pose.
fn random_arm(rng: &mut Rng) -> ([GenAxis; 6], M4) {
    let ax = std::array::from_fn(|_| {
        let w = unit_vector(rng);
        let kind = if rng.unit() < 0.25 { 1.0 } else { 0.0 };
        let p: [f64; 3] = std::array::from_fn(|_| rng.unit() - 0.5);
        [kind, w[0], w[1], w[2], p[0], p[1], p[2]]
    });
    let w = unit_vector(rng);
    let mut home = joint(&[0.0, w[0], w[1], w[2], 0.0, 0.0, 0.0], rng.angle());
    for i in 0..3 {
        home[i][3] = rng.unit() - 0.5;
    }
    (ax, home)
}

fn top(m: &M4) -> [[f64; 4]; 3] {
    [m[0], m[1], m[2]]
}

/// The pose by plain matrices, and each joint's current axis `(w, p)`: its home axis moved by
/// the joints before it.
fn reference(ax: &[GenAxis; 6], home: &M4, q: &[f64; 6]) -> (M4, [[f64; 6]; 6]) {
    let mut t: M4 = std::array::from_fn(|i| std::array::from_fn(|j| (i == j) as u8 as f64));
    let mut cur = [[0.0; 6]; 6];
    for i in 0..6 {
        for r in 0..3 {
            cur[i][r] = (0..3).map(|k| t[r][k] * ax[i][1 + k]).sum();
            cur[i][3 + r] = (0..3).map(|k| t[r][k] * ax[i][4 + k]).sum::<f64>() + t[r][3];
        }
        t = mul(&t, &joint(&ax[i], q[i]));
    }
    (mul(&t, home), cur)
}

/// The forward kinematics on the joints' frames (`F1 Z(q1) L1 ⋯ Z(q6) L6`) is the product of
/// exponentials to rounding, and each current axis is the home axis moved by the joints before
/// it (its point anywhere on that line).
#[test]
fn forward_on_the_joints_frames_is_the_product_of_exponentials() {
    let mut rng = Rng(0x3c6e_f372_fe94_f82b);
    for _ in 0..300 {
        let (ax, home) = random_arm(&mut rng);
        let q: [f64; 6] = std::array::from_fn(|i| {
            if ax[i][0] != 0.0 {
                rng.unit() - 0.5
            } else {
                rng.angle()
            }
        });
        let (want, wcur) = reference(&ax, &home, &q);
        let (got, cur) = forward(&chain(&ax, &top(&home)), &q);
        for r in 0..3 {
            for c in 0..4 {
                assert!(
                    (got[r][c] - want[r][c]).abs() <= 1e-13,
                    "{ax:?} at {q:?}: {got:?} vs {want:?}"
                );
            }
        }
        for i in 0..6 {
            let (w, p) = (&cur[i][..3], &cur[i][3..]);
            let d: Vec<f64> = (0..3).map(|r| p[r] - wcur[i][3 + r]).collect();
            let off = [
                d[1] * w[2] - d[2] * w[1],
                d[2] * w[0] - d[0] * w[2],
                d[0] * w[1] - d[1] * w[0],
            ];
            for r in 0..3 {
                assert!((w[r] - wcur[i][r]).abs() <= 1e-13, "axis {i}: {w:?}");
                assert!(off[r].abs() <= 1e-13, "axis {i}: {p:?} off the line");
            }
        }
    }
}

/// Gauss–Newton from a configuration 1e-6 away from a solution ends at the forward
/// kinematics' rounding: the residual it reports is at most `EXACT_TOL`, the pose by plain
/// matrices agrees to 1e-13, and the configuration is a solution near the start (within 1e-5:
/// a random arm can be near a singular configuration, where nearby solutions differ along the
/// Jacobian's near-null direction).
#[test]
fn refine_polishes_a_near_solution_to_the_rounding() {
    let mut rng = Rng(0xa54f_f53a_5f1d_36f1);
    for _ in 0..200 {
        let (ax, home) = random_arm(&mut rng);
        let q0: [f64; 6] = std::array::from_fn(|i| {
            if ax[i][0] != 0.0 {
                rng.unit() - 0.5
            } else {
                rng.angle()
            }
        });
        let target = reference(&ax, &home, &q0).0;
        let mut q: [f64; 6] = std::array::from_fn(|i| q0[i] + 1e-6 * (rng.unit() - 0.5));
        let res = refine(&chain(&ax, &top(&home)), &top(&target), &mut q);
        assert!(res <= EXACT_TOL, "{ax:?} from {q0:?}: residual {res:e}");
        let got = reference(&ax, &home, &q).0;
        for r in 0..3 {
            for c in 0..4 {
                assert!((got[r][c] - target[r][c]).abs() <= 1e-13, "{got:?}");
            }
        }
        for i in 0..6 {
            assert!((q[i] - q0[i]).abs() <= 1e-5, "{q:?} vs {q0:?}");
        }
    }
}

/// Cholesky's solve of a damped Gram matrix leaves a residual at rounding; a matrix that is
/// not positive definite (or not finite) gives `None`.
#[test]
fn cholesky_solves_damped_normal_equations_and_refuses_the_indefinite() {
    let mut rng = Rng(0x1f83_d9ab_fb41_bd6b);
    for k in 0..500 {
        let j: [[f64; 6]; 12] = std::array::from_fn(|_| std::array::from_fn(|_| rng.unit() - 0.5));
        let mut m = [[0.0; 6]; 6];
        for a in 0..6 {
            for b in 0..6 {
                m[a][b] = (0..12).map(|r| j[r][a] * j[r][b]).sum();
            }
        }
        let damp = [1e-12, 1e-6, 1.0][k % 3];
        let tr: f64 = (0..6).map(|i| m[i][i]).sum();
        for i in 0..6 {
            m[i][i] += damp * tr;
        }
        let g: [f64; 6] = std::array::from_fn(|_| rng.unit() - 0.5);
        let d = cholesky_solve(&m, &g).expect("positive definite");
        let size: f64 = m.iter().flatten().map(|x| x.abs()).fold(0.0, f64::max)
            * d.iter().map(|x| x.abs()).sum::<f64>();
        for i in 0..6 {
            let r: f64 = (0..6).map(|c| m[i][c] * d[c]).sum::<f64>() - g[i];
            assert!(r.abs() <= 1e-13 * size.max(1.0), "row {i}: {r:e}");
        }
        let mut bad = m;
        bad[k % 6][k % 6] = -1.0;
        assert!(cholesky_solve(&bad, &g).is_none());
        bad[k % 6][k % 6] = f64::NAN;
        assert!(cholesky_solve(&bad, &g).is_none());
    }
}

/// The QR of a 14 x 8 matrix with column pivoting: `Qᵀ` orthogonal, `Qᵀ B` upper triangular
/// in the pivot order with `R` above, the ratio `|r77 / r00|` near rounding for a matrix of
/// rank 7 and not for a random one.
#[test]
fn qr_pivot_is_an_orthogonal_factorization_and_reveals_the_rank() {
    let mut rng = Rng(0x5be0_cd19_137e_2179);
    for k in 0..300 {
        let mut b: [[f64; 8]; 14] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.unit() - 0.5));
        let deficient = k % 2 == 1;
        if deficient {
            // Column 5 a combination of columns 1 and 2.
            for row in b.iter_mut() {
                row[5] = 0.3 * row[1] - 1.7 * row[2];
            }
        }
        let (qt, r, piv, ratio) = qr_pivot(&b);
        for i in 0..14 {
            for j in 0..14 {
                let x: f64 = (0..14).map(|e| qt[i][e] * qt[j][e]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((x - want).abs() <= 1e-14, "Q^T Q at ({i}, {j}): {x}");
            }
        }
        for i in 0..14 {
            for j in 0..8 {
                let x: f64 = (0..14).map(|e| qt[i][e] * b[e][piv[j]]).sum();
                let want = if i <= j && i < 8 { r[i][j] } else { 0.0 };
                assert!(
                    (x - want).abs() <= 1e-14,
                    "(Q^T B P)[{i}][{j}] = {x}, R {want}"
                );
            }
        }
        if deficient {
            assert!(ratio <= 1e-14, "rank 7: ratio {ratio:e}");
        } else {
            assert!(ratio >= 1e-6, "random: ratio {ratio:e}");
        }
    }
}
