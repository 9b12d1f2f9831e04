//! The apart solver's eigenvalue route (`apart::apart_eigen_roots`, the fallback where the
//! certified search gives up in both readings) against independent computations written here:
//! trigonometric polynomials built as products of factors with known roots (`det_tests`'s),
//! including triple roots, where the certified search gives up; and the whole solver forced
//! through that route (`apart_solve_by`) on random 4R2P arms with their slides three joints
//! apart, against the certified route and a forward kinematics of plain 4 x 4 matrices written
//! here.

#![allow(clippy::needless_range_loop)]

use super::apart::{apart_eigen_roots, apart_solve_by};
use super::core::{trig_eval, trig_roots, trig_table, GenAxis, DET_DEGREE, GEN_MAX, NEAR_REAL};
use super::det_tests::{gap, product, random_factors, real_roots, separation, Factor, Rng};

/// Checks `apart_eigen_roots` on the product of `factors`: every real root has a found root
/// within `tol`, and every found root is near a real root or near a complex pair close enough
/// to the axis (`η ≤ NEAR_REAL`).
fn check_eigen(factors: &[Factor], scale: f64, tol: f64) -> Vec<f64> {
    let c = product(factors, scale);
    let mut out = [0.0; 24];
    let n = apart_eigen_roots(&c, &mut out).unwrap_or_else(|| panic!("gave up on {factors:?}"));
    let found = out[..n].to_vec();
    let real = real_roots(factors);
    for &r in &real {
        assert!(
            found.iter().any(|&x| gap(x, r) <= tol),
            "{factors:?}: root {r} not within {tol:e} of {found:?}"
        );
    }
    let tt = trig_table(&c);
    let b0: f64 = c.iter().map(|x| x.0.hypot(x.1)).sum();
    for &x in &found {
        let real_ok = real.iter().any(|&r| gap(x, r) <= tol);
        let pair_ok = factors.iter().any(|f| match *f {
            Factor::Complex { mu, eta } => eta <= 2.0 * NEAR_REAL && gap(x, mu) <= 1e-3,
            Factor::Real { .. } => false,
        });
        assert!(
            real_ok || pair_ok,
            "{factors:?}: {x} is no root (found {found:?}, D = {:e} of {b0:e})",
            trig_eval(&tt, x)[0]
        );
    }
    found
}

#[test]
fn eigen_roots_find_every_real_root_of_random_products() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for _ in 0..300 {
        let deg = 1 + (rng.unit() * DET_DEGREE as f64) as usize;
        let factors = random_factors(&mut rng, deg, 0.6);
        // Roots of different factors that fall close are fixed only to about the rounding
        // over their distance.
        let s = separation(&factors);
        let tol = if s > 1e-3 { 1e-8 } else { 1e-3 };
        check_eigen(&factors, 10f64.powf(6.0 * rng.unit() - 3.0), tol);
    }
}

/// A triple root (a double factor `cos(θ − μ) − 1` and a third root at `μ` from another
/// factor), where the certified search gives up: the eigenvalue route finds it (a cluster of
/// three within the cube root of the rounding) and every other real root; so do roots at `θ =
/// π` (the shift keeps them off `x = ∞`) and at both ends of the circle.
#[test]
fn eigen_roots_take_the_triple_roots_the_certified_search_leaves() {
    for mu in [1.3, -2.2, 0.0, std::f64::consts::PI] {
        let factors = [
            Factor::Real { mu, delta: 0.0 },
            Factor::Real {
                mu: mu + 0.4,
                delta: 0.4,
            },
            Factor::Complex {
                mu: mu - 1.0,
                eta: 0.5,
            },
            Factor::Real {
                mu: mu + 2.5,
                delta: 0.3,
            },
        ];
        let c = product(&factors, 1.0);
        assert!(
            trig_roots(&c, &mut [0.0; 24]).is_none(),
            "the certified search resolved the triple root at {mu}"
        );
        let found = check_eigen(&factors, 1.0, 1e-4);
        let near = found.iter().filter(|&&x| gap(x, mu) <= 1e-4).count();
        assert!(near >= 1, "{mu}: {found:?}");
    }
}

/// A 4 x 4 homogeneous matrix (also the refinement tests' own forward kinematics).
pub(super) type M4 = [[f64; 4]; 4];

pub(super) fn mul(a: &M4, b: &M4) -> M4 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// The motion of one joint as a 4 x 4 matrix (the test's own): a turn by `q` about the line
/// through `p` along the unit `w` (`R = exp(q [w]×)` by its series' closed form), or a slide
/// by `q` along `w`.
pub(super) fn joint(a: &GenAxis, q: f64) -> M4 {
    let (w, p) = ([a[1], a[2], a[3]], [a[4], a[5], a[6]]);
    let mut m = [[0.0; 4]; 4];
    m[3][3] = 1.0;
    if a[0] != 0.0 {
        for i in 0..3 {
            m[i][i] = 1.0;
            m[i][3] = q * w[i];
        }
        return m;
    }
    let (s, c) = q.sin_cos();
    let k = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
    for i in 0..3 {
        for j in 0..3 {
            let kk: f64 = (0..3).map(|l| k[i][l] * k[l][j]).sum();
            m[i][j] = f64::from(u8::from(i == j)) + s * k[i][j] + (1.0 - c) * kk;
        }
    }
    for i in 0..3 {
        m[i][3] = p[i] - (0..3).map(|j| m[i][j] * p[j]).sum::<f64>();
    }
    m
}

fn forward(ax: &[GenAxis; 6], home: &M4, q: &[f64; 6]) -> M4 {
    let mut t = joint(&ax[0], q[0]);
    for i in 1..6 {
        t = mul(&t, &joint(&ax[i], q[i]));
    }
    mul(&t, home)
}

fn unit_vector(rng: &mut Rng) -> [f64; 3] {
    loop {
        let v = [
            2.0 * rng.unit() - 1.0,
            2.0 * rng.unit() - 1.0,
            2.0 * rng.unit() - 1.0,
        ];
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.2 && n < 1.0 {
            return [v[0] / n, v[1] / n, v[2] / n];
        }
    }
}

/// The largest difference of two joint vectors (angles on the circle).
fn dist(a: &[f64; 6], b: &[f64; 6], slides: &[bool; 6]) -> f64 {
    (0..6)
        .map(|i| {
            if slides[i] {
                (a[i] - b[i]).abs()
            } else {
                gap(a[i], b[i])
            }
        })
        .fold(0.0, f64::max)
}

/// Random 4R2P arms (random axes, slides at `first` and `first + 3`) at random poses, solved
/// with the roots of `D` by the eigenvalue route only: every solution reproduces the pose by
/// the 4 x 4 model here, the original configuration is among them, and the set is the
/// certified route's.
#[test]
fn apart_solver_through_the_eigenvalue_route_is_the_certified_one() {
    let mut rng = Rng(0x51_7cc1_b727_220a);
    let tol = super::tol();
    let mut compared = 0;
    for arm in 0..9 {
        let first = arm % 3;
        let slides: [bool; 6] = std::array::from_fn(|i| i == first || i == first + 3);
        let ax: [GenAxis; 6] = std::array::from_fn(|i| {
            let w = unit_vector(&mut rng);
            let p: [f64; 3] = std::array::from_fn(|_| rng.unit() - 0.5);
            [
                f64::from(u8::from(slides[i])),
                w[0],
                w[1],
                w[2],
                p[0],
                p[1],
                p[2],
            ]
        });
        let home: M4 = [
            [0.0, -1.0, 0.0, 0.3],
            [1.0, 0.0, 0.0, -0.2],
            [0.0, 0.0, 1.0, 0.4],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let hm: [[f64; 4]; 3] = [home[0], home[1], home[2]];
        for _ in 0..20 {
            let q: [f64; 6] = std::array::from_fn(|i| {
                if slides[i] {
                    rng.unit() - 0.5
                } else {
                    rng.angle()
                }
            });
            let t = forward(&ax, &home, &q);
            let solve = |eigen: bool| {
                let mut sing = [false; GEN_MAX];
                let out = apart_solve_by(&ax, &hm, &t, 1.0, tol, &mut sing, eigen);
                (0..out.n)
                    .map(|i| (out.q[i], out.residual[i]))
                    .collect::<Vec<_>>()
            };
            let (by_eigen, certified) = (solve(true), solve(false));
            for (s, res) in by_eigen.iter().filter(|(_, r)| *r <= tol.pose) {
                let f = forward(&ax, &home, s);
                let dev = (0..3)
                    .flat_map(|r| (0..4).map(move |c| (r, c)))
                    .map(|(r, c)| (f[r][c] - t[r][c]).abs())
                    .fold(0.0, f64::max);
                assert!(
                    dev <= 1e-9,
                    "arm {arm}: {s:?} (residual {res:e}) misses by {dev:e}"
                );
            }
            assert!(
                by_eigen
                    .iter()
                    .any(|(s, r)| *r <= tol.pose && dist(s, &q, &slides) <= 1e-6),
                "arm {arm}: {q:?} not among {by_eigen:?}"
            );
            assert_eq!(
                by_eigen.len(),
                certified.len(),
                "arm {arm} at {q:?}: {by_eigen:?} vs {certified:?}"
            );
            for (s, _) in &certified {
                assert!(
                    by_eigen.iter().any(|(e, _)| dist(e, s, &slides) <= 1e-6),
                    "arm {arm}: {s:?} not among {by_eigen:?}"
                );
            }
            compared += 1;
        }
    }
    assert_eq!(compared, 180);
}
