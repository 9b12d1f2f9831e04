// The numeric core of the general 6R solver (Raghavan–Roth elimination in Manocha–Canny's
// matrix form). Plain Rust on `f64` arrays with no dependency and no allocation: the engine
// compiles this file as `ik::general::core`, and the generated Rust solver contains it
// verbatim (`include_str!`), so the reference and the generated solver are one algorithm.
//
// Units: every length is divided by the robot's scale `len` first, so that all the numbers
// below are of order one (the residual is the one of `ik::check`: rotation entries as they
// are, positions over `len`).

/// A joint axis in the home pose: `[kind, wx, wy, wz, px, py, pz]` (kind 1: prismatic).
pub type GenAxis = [f64; 7];

/// The most solutions of a 6R chain.
pub const GEN_MAX: usize = 16;

/// The tolerances (from `ik::check`): the residual above which a solution is flagged
/// approximate, and the largest residual kept at all (a candidate further off is a root of the
/// elimination that is not a solution: a complex root with a small imaginary part, a spurious
/// root of a degenerate arrangement).
#[derive(Clone, Copy, Debug)]
pub struct GenTol {
    /// Flag approximate above this.
    pub pose: f64,
    /// Drop above this.
    pub keep: f64,
}

/// Every solution found: joint vectors in joint order with their residuals.
#[derive(Clone, Copy, Debug)]
pub struct GenOut {
    /// Joint vectors.
    pub q: [[f64; 6]; GEN_MAX],
    /// Residual of each (relative, as `ik::check::residual`).
    pub residual: [f64; GEN_MAX],
    /// How many are valid.
    pub n: usize,
    /// The degree of the univariate polynomial of the first arrangement used (the finite
    /// eigenvalues of the linearisation other than the spurious `±i`); 0 when none was usable.
    pub degree: usize,
    /// The first three arrangements used: `(reversed, shift)` packed as `shift + 6 reversed`.
    pub arrangements: [usize; 3],
    /// How many arrangements were used (at most 12).
    pub n_arr: usize,
}

type V = [f64; 3];
type M3 = [[f64; 3]; 3];
/// A rigid motion as a 3 x 4 block `[R | t]`.
type B34 = [[f64; 4]; 3];

pub(crate) fn dot3(a: &V, b: &V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross3(a: &V, b: &V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Rodrigues: `c I + s [w]x + (1 − c) w wᵀ`.
pub(crate) fn rodrigues(w: &V, s: f64, c: f64) -> M3 {
    let k = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = if i == j { c } else { 0.0 } + s * k[i][j] + (1.0 - c) * w[i] * w[j];
        }
    }
    r
}

pub(crate) fn mv(r: &M3, v: &V) -> V {
    [dot3(&r[0], v), dot3(&r[1], v), dot3(&r[2], v)]
}

/// One joint of an arranged chain: unit direction `w`, point `c` (scaled), whether it slides
/// (`prism`: its variable is the length `d` of a translation along `w`, and `c` is unused), and
/// its motion applied to a point and a direction.
#[derive(Clone, Copy)]
pub(crate) struct J {
    pub(crate) w: V,
    pub(crate) c: V,
    pub(crate) prism: bool,
}

impl J {
    /// The rotations of the joint's three samples (`inv`: of the inverse motion), computed once
    /// for the grid of [`Arranged::elim`]; unused for a slide.
    fn sample_rots(&self, inv: bool) -> [M3; 3] {
        let sg = if inv { -1.0 } else { 1.0 };
        std::array::from_fn(|k| {
            if self.prism {
                [[0.0; 3]; 3]
            } else {
                rodrigues(&self.w, sg * SAMPLE_S[k], SAMPLE_C[k])
            }
        })
    }

    /// `(E x, R d)` at sample `k` of the joint's variable (`inv`: the inverse motion), `rots`
    /// its [`J::sample_rots`]: a revolute joint at the angle `2πk/3`, a prismatic one at the
    /// length `SAMPLE_D[k]`.
    fn sample(&self, rots: &[M3; 3], k: usize, inv: bool, x: &V, d: &V) -> (V, V) {
        let sg = if inv { -1.0 } else { 1.0 };
        if self.prism {
            let t = sg * SAMPLE_D[k];
            let y = [
                x[0] + t * self.w[0],
                x[1] + t * self.w[1],
                x[2] + t * self.w[2],
            ];
            (y, *d)
        } else {
            self.turn(&rots[k], x, d)
        }
    }

    /// The weights that turn the three samples into the coefficients of the joint's basis:
    /// `(1, cos θ, sin θ)` for a revolute joint, `(1, d, d²)` for a prismatic one.
    fn weights(&self) -> &'static [[f64; 3]; 3] {
        if self.prism {
            &VANDER
        } else {
            &DFT
        }
    }

    /// `(E x, R d)` for the rotation `r` about the joint's axis.
    fn turn(&self, r: &M3, x: &V, d: &V) -> (V, V) {
        let y = [x[0] - self.c[0], x[1] - self.c[1], x[2] - self.c[2]];
        let ry = mv(r, &y);
        (
            [ry[0] + self.c[0], ry[1] + self.c[1], ry[2] + self.c[2]],
            mv(r, d),
        )
    }
}

/// The fourteen Raghavan–Roth quantities of a point `p` and a direction `l`: `l`, `p`, `p·p`,
/// `p·l`, `p×l`, `(p·p) l − 2 (p·l) p`. Under a rotation about the origin they transform
/// linearly with coefficients in `(1, cos, sin)`, under a constant translation linearly with
/// constant coefficients (`t × (l × p)` absorbs the products), so along the chain each
/// quantity is of degree at most one in the sine and cosine of every joint.
fn quantities(p: &V, l: &V) -> [f64; 14] {
    let pp = dot3(p, p);
    let pl = dot3(p, l);
    let x = cross3(p, l);
    let mut o = [0.0; 14];
    o[..3].copy_from_slice(l);
    o[3..6].copy_from_slice(p);
    o[6] = pp;
    o[7] = pl;
    o[8..11].copy_from_slice(&x);
    for i in 0..3 {
        o[11 + i] = pp * l[i] - 2.0 * pl * p[i];
    }
    o
}

/// The three sample angles `2πk/3` (sine, cosine) and the weights that turn three samples of
/// `a + b cos θ + c sin θ` into `(a, b, c)` exactly (a three-point DFT).
pub const SAMPLE_S: [f64; 3] = [0.0, 0.866_025_403_784_438_6, -0.866_025_403_784_438_6];
pub const SAMPLE_C: [f64; 3] = [1.0, -0.5, -0.5];
pub const DFT: [[f64; 3]; 3] = [
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [2.0 / 3.0, -1.0 / 3.0, -1.0 / 3.0],
    [0.0, 0.577_350_269_189_625_8, -0.577_350_269_189_625_8],
];

/// The three sample lengths of a prismatic joint's variable `d` (scaled), and the weights that
/// turn three samples of `a + b d + c d²` into `(a, b, c)` exactly (the inverse Vandermonde
/// matrix of `0, 1, −1`): a translation by `d w` acts on the fourteen quantities with entries
/// of degree at most two in `d` (`p·p` gains `2 d w·p + d²`).
pub const SAMPLE_D: [f64; 3] = [0.0, 1.0, -1.0];
pub const VANDER: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 0.5, -0.5], [-1.0, 0.5, 0.5]];

/// The basis change that lets a prismatic joint's `(1, d, d²)` coefficients through the
/// half-angle map [`HALF`] of a revolute joint's `(1, cos, sin)`: `HALF⁻¹`, so that
/// `(coefficients · HALF_INV) · HALF` is the polynomial `a + b x + c x²` in `x = d` itself.
/// Then the hidden joint's shift `φ` (a rotation of `(cos, sin)`) becomes the Möbius map `d =
/// (t + y) / (1 − t y)`, `t = tan(φ/2)` (up to the constant factor `1 + t²`), and `d =
/// tan(θ/2)` for the angle `θ` the revolute formulas give.
pub const HALF_INV: [[f64; 3]; 3] = [[0.5, 0.5, 0.0], [0.0, 0.0, 0.5], [0.5, -0.5, 0.0]];

/// The arranged problem `E1 ⋯ E6 = H` (home pose the identity), its elimination and solution.
pub(crate) struct Arranged {
    pub(crate) j: [J; 6],
    /// `H` with its translation scaled.
    pub(crate) h: B34,
    /// Arranged joint `i` is the arm's joint `perm[i]`.
    pub(crate) perm: [usize; 6],
}

/// The elimination of one arrangement: `Bm X12 = Am(θ3) X45` (14 equations), the left null
/// space `N` of `Bm` (six rows), and `N Am` in the basis `(1, cos θ3, sin θ3)`.
pub(crate) struct Elim {
    /// `Am[e][k][m]`: equation `e`, `k` in `(1, cos θ3, sin θ3)`, monomial `m` of X45.
    pub(crate) am: [[[f64; 9]; 3]; 14],
    /// Householder QR of `Bm` with column pivoting: `qt` is `Qᵀ` (14 x 14), `r` the 8 x 8
    /// triangle, `piv` the column order.
    pub(crate) qt: [[f64; 14]; 14],
    pub(crate) r: [[f64; 8]; 8],
    pub(crate) piv: [usize; 8],
    /// `|r77| / |r00|`: how far `Bm` is from losing rank.
    pub(crate) rank_ratio: f64,
    /// `Σ = N Am` in `(1, cos θ3, sin θ3)`: 6 x 9 each.
    pub(crate) sig: [[[f64; 9]; 6]; 3],
}

/// The left side's coefficients `Am[e][k][m]` ([`Arranged::left`]).
pub(crate) type Left = [[[f64; 9]; 3]; 14];

/// The degree in length of each of the fourteen quantities ([`quantities`]): `l`, `p`, `p·p`,
/// `p·l`, `p×l`, `(p·p) l − 2 (p·l) p`. Computed from lengths in the robot's units, equation
/// `e` of the left side is `len^LEFT_DEG[e]` times the one from lengths over `len`, whatever
/// the turning joints' angles: the products and sums of each quantity are of its degree.
pub const LEFT_DEG: [u8; 14] = [0, 0, 0, 1, 1, 1, 2, 1, 1, 1, 1, 2, 2, 2];

/// The left side of lengths over `len` from the one in the robot's units (see [`LEFT_DEG`]):
/// each equation times `1 / len` to its degree.
#[allow(clippy::needless_range_loop)]
pub(crate) fn scaled_left(robot: &Left, len: f64) -> Left {
    let s = 1.0 / len;
    let f = [1.0, s, s * s];
    let mut out = *robot;
    for e in 0..14 {
        let fe = f[LEFT_DEG[e] as usize];
        for row in out[e].iter_mut() {
            for x in row.iter_mut() {
                *x *= fe;
            }
        }
    }
    out
}

/// Whether the left side of arrangement `arr` ([`Arranged::left`]) is a constant of the arm:
/// the loop read from joint 1 (forwards or backwards, `arr` 0 or 6) leaves the axes as they
/// are (a shifted loop conjugates some by the target), and turning joints 3 to 5 make each
/// equation a multiple of the one in the robot's units ([`LEFT_DEG`]; a slide's samples are
/// lengths of the scaled arm).
pub(crate) fn left_is_constant(ar: &Arranged, arr: usize) -> bool {
    (arr == 0 || arr == 6) && !ar.j[2].prism && !ar.j[3].prism && !ar.j[4].prism
}

/// The left side of arrangement `arr` (0 or 6) of the arm `axes` in the robot's units,
/// computed once per arm and thread (the solver of a fixed arm computes it at its first call):
/// the last arm's two in a thread-local cache keyed by the axes' bits.
pub(crate) fn robot_left(axes: &[GenAxis; 6], arr: usize) -> Left {
    use std::cell::RefCell;
    type Cache = Option<([[u64; 7]; 6], [Option<Left>; 2])>;
    thread_local! {
        static LEFT_CACHE: RefCell<Cache> = const { RefCell::new(None) };
    }
    let key: [[u64; 7]; 6] = std::array::from_fn(|i| std::array::from_fn(|k| axes[i][k].to_bits()));
    let compute = || {
        let js: [J; 6] = std::array::from_fn(|i| J {
            w: [axes[i][1], axes[i][2], axes[i][3]],
            c: [axes[i][4], axes[i][5], axes[i][6]],
            prism: axes[i][0] != 0.0,
        });
        let id: B34 = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        ];
        Arranged::new(&js, &id, arr).left()
    };
    LEFT_CACHE
        .try_with(|cell| {
            let mut cache = cell.borrow_mut();
            if cache.as_ref().map(|c| c.0) != Some(key) {
                *cache = Some((key, [None, None]));
            }
            let slot = &mut cache.as_mut().expect("set above").1[arr / 6];
            *slot.get_or_insert_with(compute)
        })
        .unwrap_or_else(|_| compute())
}

/// The monomial index of `(i, j)` with `i, j` in `(1, cos, sin)`.
fn mono(i: usize, j: usize) -> usize {
    3 * i + j
}

impl Arranged {
    /// `arr = shift + 6 reversed` of the chain `ax` (scaled) with the target `g = T M⁻¹`.
    pub(crate) fn new(ax: &[J; 6], g: &B34, arr: usize) -> Arranged {
        let (rev, shift) = (arr >= 6, arr % 6);
        let mut base = *ax;
        let mut h = *g;
        let mut bperm = [0, 1, 2, 3, 4, 5];
        if rev {
            // E6⁻¹ ⋯ E1⁻¹ = G⁻¹, and Ei⁻¹(q) turns about the reversed axis by q.
            for i in 0..6 {
                let a = ax[5 - i];
                base[i] = J {
                    w: [-a.w[0], -a.w[1], -a.w[2]],
                    c: a.c,
                    prism: a.prism,
                };
                bperm[i] = 5 - i;
            }
            h = inverse(g);
        }
        // E_{s+1} ⋯ E6 (H⁻¹ E1 H) ⋯ (H⁻¹ Es H) = H.
        let hi = inverse(&h);
        let mut j = base;
        let mut perm = [0; 6];
        for i in 0..6 {
            let k = (shift + i) % 6;
            perm[i] = bperm[k];
            j[i] = if k < shift {
                let (c, w) = motion_apply(&hi, &base[k].c, &base[k].w);
                J {
                    w,
                    c,
                    prism: base[k].prism,
                }
            } else {
                base[k]
            };
        }
        Arranged { j, h, perm }
    }

    /// Whether each arranged joint slides.
    pub(crate) fn prismatic(&self) -> [bool; 6] {
        std::array::from_fn(|i| self.j[i].prism)
    }

    /// The equations' coefficients by exact trigonometric interpolation (see [`DFT`]).
    pub(crate) fn elim(&self) -> Option<Elim> {
        self.elim_from(self.left())
    }

    /// The left side's coefficients (`Am` before the right side's constant term is taken
    /// from it): `E3 E4 E5` applied to `(p6, w6)` on a 3 x 3 x 3 grid of samples and turned
    /// into coefficients (see [`DFT`]). A function of the arranged joints 3 to 6 alone.
    #[allow(clippy::needless_range_loop)]
    pub(crate) fn left(&self) -> Left {
        let (p6, w6) = (self.j[5].c, self.j[5].w);
        let rots: [[M3; 3]; 3] = std::array::from_fn(|i| self.j[2 + i].sample_rots(false));
        let mut lhs = [[[[0.0; 14]; 3]; 3]; 3];
        for k5 in 0..3 {
            let (x5, d5) = self.j[4].sample(&rots[2], k5, false, &p6, &w6);
            for k4 in 0..3 {
                let (x4, d4) = self.j[3].sample(&rots[1], k4, false, &x5, &d5);
                for k3 in 0..3 {
                    let (x3, d3) = self.j[2].sample(&rots[0], k3, false, &x4, &d4);
                    lhs[k3][k4][k5] = quantities(&x3, &d3);
                }
            }
        }
        let mut am = [[[0.0; 9]; 3]; 14];
        let wt: [&[[f64; 3]; 3]; 5] = std::array::from_fn(|i| self.j[i].weights());
        // The 3-D transform as three 1-D passes (27 x 3 products each instead of 27 x 27).
        let mut t1 = [[[[0.0; 14]; 3]; 3]; 3];
        for i5 in 0..3 {
            for k3 in 0..3 {
                for k4 in 0..3 {
                    for k5 in 0..3 {
                        let w = wt[4][i5][k5];
                        for e in 0..14 {
                            t1[k3][k4][i5][e] += w * lhs[k3][k4][k5][e];
                        }
                    }
                }
            }
        }
        let mut t2 = [[[[0.0; 14]; 3]; 3]; 3];
        for i4 in 0..3 {
            for k3 in 0..3 {
                for k4 in 0..3 {
                    let w = wt[3][i4][k4];
                    for i5 in 0..3 {
                        for e in 0..14 {
                            t2[k3][i4][i5][e] += w * t1[k3][k4][i5][e];
                        }
                    }
                }
            }
        }
        // (Accumulated along e, then put in am's order: the same sums.)
        let mut t3 = [[[[0.0; 14]; 3]; 3]; 3];
        for i3 in 0..3 {
            for k3 in 0..3 {
                let w = wt[2][i3][k3];
                for i4 in 0..3 {
                    for i5 in 0..3 {
                        for e in 0..14 {
                            t3[i3][i4][i5][e] += w * t2[k3][i4][i5][e];
                        }
                    }
                }
            }
        }
        for i3 in 0..3 {
            for i4 in 0..3 {
                for i5 in 0..3 {
                    for e in 0..14 {
                        am[e][i3][mono(i4, i5)] = t3[i3][i4][i5][e];
                    }
                }
            }
        }
        am
    }

    /// The elimination from the left side's coefficients `left` ([`Arranged::left`], or its
    /// rows scaled from the robot's units, [`scaled_left`]): the right side `E2⁻¹ E1⁻¹ H`
    /// applied to `(p6, w6)` on a 3 x 3 grid, `Bm`, its QR and `Σ = N Am`.
    #[allow(clippy::needless_range_loop)]
    pub(crate) fn elim_from(&self, left: Left) -> Option<Elim> {
        let (p6, w6) = (self.j[5].c, self.j[5].w);
        let rots: [[M3; 3]; 2] = std::array::from_fn(|i| self.j[i].sample_rots(true));
        let hp = motion_apply(&self.h, &p6, &w6);
        let mut rhs = [[[0.0; 14]; 3]; 3];
        for k1 in 0..3 {
            let (y1, e1) = self.j[0].sample(&rots[0], k1, true, &hp.0, &hp.1);
            for k2 in 0..3 {
                let (y2, e2) = self.j[1].sample(&rots[1], k2, true, &y1, &e1);
                rhs[k1][k2] = quantities(&y2, &e2);
            }
        }
        let mut am = left;
        let mut bm = [[0.0; 8]; 14];
        let wt: [&[[f64; 3]; 3]; 2] = std::array::from_fn(|i| self.j[i].weights());
        // The 2-D transform of each of the 14 quantities, the quantities' sums side by side
        // (each in the order of k1, k2).
        for i1 in 0..3 {
            for i2 in 0..3 {
                let mut s = [0.0; 14];
                for k1 in 0..3 {
                    for k2 in 0..3 {
                        let w = wt[0][i1][k1] * wt[1][i2][k2];
                        for e in 0..14 {
                            s[e] += w * rhs[k1][k2][e];
                        }
                    }
                }
                let m = mono(i1, i2);
                for e in 0..14 {
                    if m == 0 {
                        am[e][0][0] -= s[e];
                    } else {
                        bm[e][m - 1] = s[e];
                    }
                }
            }
        }
        let (qt, r, piv, rank_ratio) = qr_pivot(&bm);
        // Each sum over e in order, the nine monomials side by side.
        let mut sig = [[[0.0; 9]; 6]; 3];
        for k in 0..3 {
            for row in 0..6 {
                let q = &qt[8 + row];
                let out = &mut sig[k][row];
                for e in 0..14 {
                    let (qe, a) = (q[e], &am[e][k]);
                    for m in 0..9 {
                        out[m] += qe * a[m];
                    }
                }
            }
        }
        self.prismatic_basis(&mut sig);
        Some(Elim {
            am,
            qt,
            r,
            piv,
            rank_ratio,
            sig,
        })
    }
}

impl Arranged {
    /// The coefficients of prismatic joints 3, 4, 5 from `(1, d, d²)` into the basis that
    /// [`matrix_poly`]'s half-angle map turns into `(1, d, d²)` again ([`HALF_INV`]).
    #[allow(clippy::needless_range_loop)]
    fn prismatic_basis(&self, sig: &mut [[[f64; 9]; 6]; 3]) {
        let conv = |v: [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|k| (0..3).map(|j| v[j] * HALF_INV[j][k]).sum())
        };
        for row in 0..6 {
            if self.j[2].prism {
                for m in 0..9 {
                    let v = conv([sig[0][row][m], sig[1][row][m], sig[2][row][m]]);
                    for k in 0..3 {
                        sig[k][row][m] = v[k];
                    }
                }
            }
            for k in 0..3 {
                if self.j[3].prism {
                    for i5 in 0..3 {
                        let v = conv(std::array::from_fn(|i4| sig[k][row][mono(i4, i5)]));
                        for i4 in 0..3 {
                            sig[k][row][mono(i4, i5)] = v[i4];
                        }
                    }
                }
                if self.j[4].prism {
                    for i4 in 0..3 {
                        let v = conv(std::array::from_fn(|i5| sig[k][row][mono(i4, i5)]));
                        for i5 in 0..3 {
                            sig[k][row][mono(i4, i5)] = v[i5];
                        }
                    }
                }
            }
        }
    }
}

/// `[R | t]⁻¹ = [Rᵀ | −Rᵀ t]`.
pub(crate) fn inverse(g: &B34) -> B34 {
    let mut o = [[0.0; 4]; 3];
    for i in 0..3 {
        for j in 0..3 {
            o[i][j] = g[j][i];
        }
        o[i][3] = -(g[0][i] * g[0][3] + g[1][i] * g[1][3] + g[2][i] * g[2][3]);
    }
    o
}

/// A motion applied to a point and a direction.
fn motion_apply(g: &B34, x: &V, d: &V) -> (V, V) {
    let mut p = [0.0; 3];
    let mut v = [0.0; 3];
    for i in 0..3 {
        p[i] = g[i][0] * x[0] + g[i][1] * x[1] + g[i][2] * x[2] + g[i][3];
        v[i] = g[i][0] * d[0] + g[i][1] * d[1] + g[i][2] * d[2];
    }
    (p, v)
}

/// Householder QR with column pivoting of the 14 x 8 matrix `b`: `(Qᵀ, R, order, |r77| /
/// |r00|)`; the last six rows of `Qᵀ` span the left null space when the ratio is not small.
#[allow(clippy::needless_range_loop, clippy::type_complexity)]
#[inline(always)]
pub(crate) fn qr_pivot(b: &[[f64; 8]; 14]) -> ([[f64; 14]; 14], [[f64; 8]; 8], [usize; 8], f64) {
    let mut a = *b;
    let mut qt = [[0.0; 14]; 14];
    for i in 0..14 {
        qt[i][i] = 1.0;
    }
    let mut piv = [0, 1, 2, 3, 4, 5, 6, 7];
    // Each step with its column a constant (the loops over its rows unrolled).
    qr_step::<0>(&mut a, &mut qt, &mut piv);
    qr_step::<1>(&mut a, &mut qt, &mut piv);
    qr_step::<2>(&mut a, &mut qt, &mut piv);
    qr_step::<3>(&mut a, &mut qt, &mut piv);
    qr_step::<4>(&mut a, &mut qt, &mut piv);
    qr_step::<5>(&mut a, &mut qt, &mut piv);
    qr_step::<6>(&mut a, &mut qt, &mut piv);
    qr_step::<7>(&mut a, &mut qt, &mut piv);
    let mut r = [[0.0; 8]; 8];
    for i in 0..8 {
        for j in i..8 {
            r[i][j] = a[i][j];
        }
    }
    let ratio = if r[0][0] == 0.0 {
        0.0
    } else {
        (r[7][7] / r[0][0]).abs()
    };
    (qt, r, piv, ratio)
}

/// Step `K` of [`qr_pivot`]: the remaining column of largest norm to column `K`, its
/// Householder reflection applied to the columns from `K` on and to `Qᵀ` (from the left, its
/// rows from `K` on). Each sum runs down a column, over the rows from `K` in order and started
/// at `−0` (as the standard library's `f64` sum of an iterator, which it was), and the sums of
/// all columns are accumulated side by side, row after row: the same operations in the same
/// order as one column at a time, in loops along the rows that the compiler vectorises.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn qr_step<const K: usize>(a: &mut [[f64; 8]; 14], qt: &mut [[f64; 14]; 14], piv: &mut [usize; 8]) {
    // The remaining column of largest norm first.
    let mut norms = [-0.0; 8];
    for r in K..14 {
        for c in K..8 {
            norms[c] += a[r][c] * a[r][c];
        }
    }
    let mut best = K;
    let mut bn = -1.0;
    for c in K..8 {
        if norms[c] > bn {
            bn = norms[c];
            best = c;
        }
    }
    if best != K {
        for r in 0..14 {
            a[r].swap(K, best);
        }
        piv.swap(K, best);
    }
    let norm = f64::max(bn, 0.0).sqrt();
    if norm == 0.0 {
        return;
    }
    let alpha = if a[K][K] > 0.0 { -norm } else { norm };
    let mut v = [0.0; 14];
    for r in K..14 {
        v[r] = a[r][K];
    }
    v[K] -= alpha;
    let mut vn = -0.0;
    for r in K..14 {
        vn += v[r] * v[r];
    }
    if vn == 0.0 {
        return;
    }
    let mut s = [-0.0; 8];
    for r in K..14 {
        for c in K..8 {
            s[c] += v[r] * a[r][c];
        }
    }
    for c in K..8 {
        s[c] = s[c] * 2.0 / vn;
    }
    for r in K..14 {
        for c in K..8 {
            a[r][c] -= s[c] * v[r];
        }
    }
    // Qᵀ ← H Qᵀ: each column's sum down the rows from K, all columns side by side. At the
    // first step Qᵀ is the identity and, with v finite, column c's sum is v[c] itself (its
    // other terms are zeros, which leave it unchanged; where it is a zero the update leaves
    // Qᵀ the identity whatever its sign).
    let mut t = [-0.0; 14];
    if K == 0 && vn.is_finite() {
        t = v;
    } else {
        for r in K..14 {
            for c in 0..14 {
                t[c] += v[r] * qt[r][c];
            }
        }
    }
    for c in 0..14 {
        t[c] = t[c] * 2.0 / vn;
    }
    for r in K..14 {
        for c in 0..14 {
            qt[r][c] -= t[c] * v[r];
        }
    }
}

/// `(1, cos, sin)` of a half-angle tangent times `1 + x²`, as polynomials in `x`.
pub const HALF: [[f64; 3]; 3] = [[1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [0.0, 2.0, 0.0]];

/// The 12 x 12 matrix polynomial `M(x) = A x² + B x + C` of `x = tan((θ3 − φ)/2)`: the six
/// equations `Σ X45 = 0` with `θ4`, `θ5` by their half-angle tangents (monomials `x4^a x5^b`,
/// `a, b ≤ 2`), and the same times `x4` (`a ≤ 3`): twelve equations in twelve monomials.
#[allow(clippy::needless_range_loop)]
pub(crate) fn matrix_poly(sig: &[[[f64; 9]; 6]; 3], phi: f64) -> [[[f64; 12]; 12]; 3] {
    let (sp, cp) = phi.sin_cos();
    let mut out = [[[0.0; 12]; 12]; 3];
    for row in 0..6 {
        for i4 in 0..3 {
            for i5 in 0..3 {
                let m = mono(i4, i5);
                let s0 = sig[0][row][m];
                let sc = sig[1][row][m] * cp + sig[2][row][m] * sp;
                let ss = sig[2][row][m] * cp - sig[1][row][m] * sp;
                let coef = [s0 + sc, 2.0 * ss, s0 - sc];
                for a in 0..3 {
                    for b in 0..3 {
                        let h = HALF[i4][a] * HALF[i5][b];
                        if h == 0.0 {
                            continue;
                        }
                        for (d, cd) in coef.iter().enumerate() {
                            out[d][row][3 * a + b] += h * cd;
                            out[d][row + 6][3 * (a + 1) + b] += h * cd;
                        }
                    }
                }
            }
        }
    }
    out
}

#[allow(clippy::needless_range_loop)]
/// LU with partial pivoting of an `n x n` block of `a` (in place); `None` when singular.
/// Returns the pivot order and the smallest pivot over the largest entry.
pub(crate) fn lu<const N: usize>(a: &mut [[f64; N]; N]) -> ([usize; N], f64) {
    let mut p: [usize; N] = std::array::from_fn(|i| i);
    // (Comparisons, not `f64::max`/`min`: the same choice, NaN skipped as they skip it.)
    let mut amax: f64 = 0.0;
    for x in a.as_flattened() {
        if x.abs() > amax {
            amax = x.abs();
        }
    }
    let mut minpiv = f64::INFINITY;
    for k in 0..N {
        let mut best = k;
        let mut bv = a[k][k].abs();
        for r in k + 1..N {
            if a[r][k].abs() > bv {
                best = r;
                bv = a[r][k].abs();
            }
        }
        if best != k {
            a.swap(k, best);
            p.swap(k, best);
        }
        let d = a[k][k];
        if d.abs() < minpiv {
            minpiv = d.abs();
        }
        if d == 0.0 {
            continue;
        }
        let (top, rest) = a.split_at_mut(k + 1);
        let pr = &top[k];
        for row in rest.iter_mut() {
            let f = row[k] / d;
            row[k] = f;
            if f != 0.0 {
                for c in k + 1..N {
                    row[c] -= f * pr[c];
                }
            }
        }
    }
    let ratio = if amax > 0.0 { minpiv / amax } else { 0.0 };
    (p, ratio)
}

/// Solves `LU x = b[p]` in place.
fn lu_solve<const N: usize>(lu: &[[f64; N]; N], p: &[usize; N], b: &[f64; N]) -> [f64; N] {
    let mut x = [0.0; N];
    for i in 0..N {
        x[i] = b[p[i]];
    }
    for i in 0..N {
        for k in 0..i {
            x[i] -= lu[i][k] * x[k];
        }
    }
    for i in (0..N).rev() {
        for k in i + 1..N {
            x[i] -= lu[i][k] * x[k];
        }
        x[i] /= lu[i][i];
    }
    x
}

/// The eigenvalues of the 24 x 24 companion linearisation of `A x² + B x + C`:
/// `[[0, I], [−A⁻¹C, −A⁻¹B]]` (`A` invertible, given as its LU `a`, `p`), less the
/// eigenvalues `±i` that [`deflate_spurious`] removes. `(re, im)` pairs and how many; `None`
/// when the QR iteration does not converge.
#[allow(clippy::needless_range_loop)]
pub(crate) fn eigen_quadratic(
    m: &[[[f64; 12]; 12]; 3],
    a: &[[f64; 12]; 12],
    p: &[usize; 12],
) -> Option<([(f64, f64); 24], usize)> {
    let mut k = [[0.0; 24]; 24];
    for i in 0..12 {
        k[i][12 + i] = 1.0;
    }
    for col in 0..12 {
        let cc: [f64; 12] = std::array::from_fn(|r| m[0][r][col]);
        let cb: [f64; 12] = std::array::from_fn(|r| m[1][r][col]);
        let xc = lu_solve(a, p, &cc);
        let xb = lu_solve(a, p, &cb);
        for r in 0..12 {
            k[12 + r][col] = -xc[r];
            k[12 + r][12 + col] = -xb[r];
        }
    }
    let n = deflate_spurious(m, &mut k);
    eigenvalues(&mut k, n).map(|ev| (ev, n))
}

/// Below this pivot (relative to the largest entry) `M(i)` is singular to rounding: a null
/// vector of it. The entries of `M` are of order one and carry rounding errors of a few ulps,
/// and elimination with complete pivoting keeps the growth small, so the pivots of the exact
/// null space come out near 1e-15; a pivot between 1e-10 and 1e-15 would be an eigenvalue
/// within about 1e-10 of `±i`, a complex root, so deflating it loses no real root and moves
/// the others by about 1e-10 times their condition, which the refinement removes.
pub const SPURIOUS_RANK: f64 = 1e-10;

/// Deflates the spurious eigenvalues `±i` of the companion matrix `k` (the factor `(1 + x²)⁴`
/// of `det M`, four pairs for a general 6R): the null vectors `v = a + i b` of `M(i)` give
/// eigenvectors `[v; i v]` of `k`, so the real vectors `[a; −b]`, `[b; a]` span an invariant
/// subspace `Z`. With `Q = [Z W]` orthogonal (Householder QR of `Z`), `Qᵀ k Q` is block upper
/// triangular and its trailing block `Wᵀ k W` has the other eigenvalues; it is left in the
/// leading rows and columns of `k`, and its size is returned (24 when nothing is deflated).
/// For the skew 6R this takes the QR iteration from 24 to 16 rows, a third of its work.
#[allow(clippy::needless_range_loop)]
fn deflate_spurious(m: &[[[f64; 12]; 12]; 3], k: &mut [[f64; 24]; 24]) -> usize {
    // M(i) = C − A + i B by elimination with complete pivoting, complex as (re, im) arrays.
    let mut re = [[0.0; 12]; 12];
    let mut im = m[1];
    for r in 0..12 {
        for c in 0..12 {
            re[r][c] = m[0][r][c] - m[2][r][c];
        }
    }
    let mut cols = [0usize; 12];
    for (i, c) in cols.iter_mut().enumerate() {
        *c = i;
    }
    // The largest entry of the remaining block is tracked while it is updated.
    let (mut br, mut bc, mut bv) = (0, 0, -1.0);
    for r in 0..12 {
        for c in 0..12 {
            let v = re[r][c] * re[r][c] + im[r][c] * im[r][c];
            if v > bv {
                (br, bc, bv) = (r, c, v);
            }
        }
    }
    let first = bv;
    let mut rank = 12;
    for s in 0..12 {
        // Also stops on NaN: no pivot is taken unless it is a number above the threshold.
        let pivot_ok = bv > SPURIOUS_RANK * SPURIOUS_RANK * first;
        if !pivot_ok {
            rank = s;
            break;
        }
        re.swap(s, br);
        im.swap(s, br);
        for r in 0..12 {
            re[r].swap(s, bc);
            im[r].swap(s, bc);
        }
        cols.swap(s, bc);
        let (dr, di, d) = (re[s][s], im[s][s], bv);
        let (pr, pi) = (re[s], im[s]);
        (br, bc, bv) = (s + 1, s + 1, -1.0);
        for r in s + 1..12 {
            // f = a[r][s] / a[s][s]
            let (nr, ni) = (re[r][s], im[r][s]);
            let fr = (nr * dr + ni * di) / d;
            let fi = (ni * dr - nr * di) / d;
            re[r][s] = 0.0;
            im[r][s] = 0.0;
            for c in s + 1..12 {
                let x = re[r][c] - (fr * pr[c] - fi * pi[c]);
                let y = im[r][c] - (fr * pi[c] + fi * pr[c]);
                re[r][c] = x;
                im[r][c] = y;
                let v = x * x + y * y;
                if v > bv {
                    (br, bc, bv) = (r, c, v);
                }
            }
        }
    }
    let nullity = 12 - rank;
    if nullity == 0 || nullity >= 12 || !(first > 0.0 && first.is_finite()) {
        return 24;
    }
    // The null vectors (one per free column) as the columns of Z, stored by columns.
    let mut z = [[0.0; 24]; 24];
    for f in 0..nullity {
        let (mut yr, mut yi) = ([0.0; 12], [0.0; 12]);
        yr[rank + f] = 1.0;
        for i in (0..rank).rev() {
            let (mut sr, mut si) = (-re[i][rank + f], -im[i][rank + f]);
            for c in i + 1..rank {
                sr -= re[i][c] * yr[c] - im[i][c] * yi[c];
                si -= re[i][c] * yi[c] + im[i][c] * yr[c];
            }
            let (dr, di) = (re[i][i], im[i][i]);
            let d = dr * dr + di * di;
            yr[i] = (sr * dr + si * di) / d;
            yi[i] = (si * dr - sr * di) / d;
        }
        for i in 0..12 {
            let c = cols[i];
            z[2 * f][c] = yr[i];
            z[2 * f][12 + c] = -yi[i];
            z[2 * f + 1][c] = yi[i];
            z[2 * f + 1][12 + c] = yr[i];
        }
    }
    // Gaussian elimination with partial pivoting of Z: `Π Z = L U`, `L = [L1; L2]` unit lower
    // trapezoidal with multipliers of size at most one. The similarity `T = Πᵀ [[L1, 0], [L2,
    // I]]` (the stabilised elementary transformations of the Hessenberg reduction) maps the
    // leading coordinates onto span Z, so the trailing block of `T⁻¹ k T` is `k'22 − L2 L1⁻¹
    // k'12` with `k' = Π k Πᵀ`.
    let nz = 2 * nullity;
    let mut perm = [0usize; 24];
    for (i, p) in perm.iter_mut().enumerate() {
        *p = i;
    }
    for j in 0..nz {
        let mut best = j;
        for r in j + 1..24 {
            if z[j][perm[r]].abs() > z[j][perm[best]].abs() {
                best = r;
            }
        }
        perm.swap(j, best);
        let d = z[j][perm[j]];
        if !(d != 0.0 && d.is_finite()) {
            return 24;
        }
        for r in j + 1..24 {
            let pr = perm[r];
            let f = z[j][pr] / d;
            z[j][pr] = f;
            for c in j + 1..nz {
                z[c][pr] -= f * z[c][perm[j]];
            }
        }
    }
    // X = L1⁻¹ k'12 (forward substitution), then k'22 − L2 X into the leading block.
    let n = 24 - nz;
    let mut x = [[0.0; 24]; 24];
    for i in 0..nz {
        let mut row: [f64; 24] =
            std::array::from_fn(|c| if c < n { k[perm[i]][perm[nz + c]] } else { 0.0 });
        for (j, xj) in x[..i].iter().enumerate() {
            let l = z[j][perm[i]];
            for (rc, xc) in row[..n].iter_mut().zip(&xj[..n]) {
                *rc -= l * xc;
            }
        }
        x[i] = row;
    }
    let mut out = [[0.0; 24]; 24];
    for r in 0..n {
        let pr = perm[nz + r];
        let mut row: [f64; 24] =
            std::array::from_fn(|c| if c < n { k[pr][perm[nz + c]] } else { 0.0 });
        for (j, xj) in x[..nz].iter().enumerate() {
            let l = z[j][pr];
            for (rc, xc) in row[..n].iter_mut().zip(&xj[..n]) {
                *rc -= l * xc;
            }
        }
        out[r] = row;
    }
    *k = out;
    n
}

/// A null vector of the 12 x 12 matrix `m` (Gaussian elimination with complete pivoting, the
/// last pivot taken as zero).
#[allow(clippy::needless_range_loop)]
pub(crate) fn null_vector(m: &[[f64; 12]; 12]) -> [f64; 12] {
    let mut a = *m;
    let mut cols = [0usize; 12];
    for (i, c) in cols.iter_mut().enumerate() {
        *c = i;
    }
    // The largest entry of the remaining block, tracked while it is updated (the same choice
    // as a search of the block after each step: the same entries in the same order).
    let (mut br, mut bc, mut bv) = (0, 0, -1.0);
    for (r, row) in a.iter().enumerate() {
        for (c, x) in row.iter().enumerate() {
            if x.abs() > bv {
                (br, bc, bv) = (r, c, x.abs());
            }
        }
    }
    // Each step with its column a constant (the row updates unrolled).
    nv_step::<0>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<1>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<2>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<3>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<4>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<5>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<6>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<7>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<8>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<9>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    nv_step::<10>(&mut a, &mut cols, &mut br, &mut bc, &mut bv);
    let mut y = [0.0; 12];
    y[11] = 1.0;
    for i in (0..11).rev() {
        let mut s = 0.0;
        for c in i + 1..12 {
            s -= a[i][c] * y[c];
        }
        y[i] = if a[i][i] == 0.0 { 0.0 } else { s / a[i][i] };
    }
    let mut v = [0.0; 12];
    for i in 0..12 {
        v[cols[i]] = y[i];
    }
    v
}

/// Step `K` of [`null_vector`]: the pivot `(br, bc)` to `(K, K)`, the rows below less their
/// multiple of it, and the largest entry of the block left tracked.
#[inline(always)]
fn nv_step<const K: usize>(
    a: &mut [[f64; 12]; 12],
    cols: &mut [usize; 12],
    br: &mut usize,
    bc: &mut usize,
    bv: &mut f64,
) {
    a.swap(K, *br);
    for row in a.iter_mut() {
        row.swap(K, *bc);
    }
    cols.swap(K, *bc);
    let pivot = a[K];
    let d = pivot[K];
    (*br, *bc, *bv) = (K + 1, K + 1, -1.0);
    if d == 0.0 {
        // Nothing eliminated: the next pivot is searched in the block as it is.
        for (r, row) in a.iter().enumerate().skip(K + 1) {
            for (c, x) in row.iter().enumerate().skip(K + 1) {
                if x.abs() > *bv {
                    (*br, *bc, *bv) = (r, c, x.abs());
                }
            }
        }
        return;
    }
    for (r, row) in a.iter_mut().enumerate().skip(K + 1) {
        let f = row[K] / d;
        row[K] -= f * pivot[K];
        for c in K + 1..12 {
            let x = row[c] - f * pivot[c];
            row[c] = x;
            if x.abs() > *bv {
                (*br, *bc, *bv) = (r, c, x.abs());
            }
        }
    }
}

/// A null vector of the 12 x 12 matrix `m`, singular to rounding, from its LU with partial
/// pivoting (a quarter of [`null_vector`]'s work): `U` has the rank of `m`, so its smallest
/// pivot `u_kk` is the zero one; `y_k = 1`, `y_j = 0` beyond `k` and the triangle above solved
/// give `U y = 0`, hence `m y = 0`. The rows below a tiny pivot are not used. When the residual
/// is above [`NULL_RESIDUAL`] (partial pivoting did not reveal the rank, or the root is
/// inexact) the vector of complete pivoting ([`null_vector`]) is taken. (The solver takes the
/// same vector of `S(θ)` from its blocks, [`null_vector_trig`]; this is its reference.)
#[cfg(test)]
#[allow(clippy::needless_range_loop)]
pub(crate) fn null_vector_lu(m: &[[f64; 12]; 12]) -> [f64; 12] {
    let mut a = *m;
    let (mut kmin, mut pmin) = (11, f64::INFINITY);
    for k in 0..12 {
        let mut best = k;
        for r in k + 1..12 {
            if a[r][k].abs() > a[best][k].abs() {
                best = r;
            }
        }
        a.swap(k, best);
        let (top, rest) = a.split_at_mut(k + 1);
        let pivot = &top[k];
        let d = pivot[k];
        if d.abs() < pmin {
            (kmin, pmin) = (k, d.abs());
        }
        if d == 0.0 {
            continue;
        }
        eliminate(rest, pivot, k, d);
    }
    let mut y = [0.0; 12];
    y[kmin] = 1.0;
    for i in (0..kmin).rev() {
        let mut s = 0.0;
        for c in i + 1..=kmin {
            s -= a[i][c] * y[c];
        }
        y[i] = if a[i][i] == 0.0 { 0.0 } else { s / a[i][i] };
    }
    checked_null(m, y)
}

/// `y` when it is a null vector of `m` to rounding (the residual `|m y|` at most
/// [`NULL_RESIDUAL`] `|m| |y|`), else the vector of complete pivoting ([`null_vector`]):
/// partial pivoting need not reveal the rank.
#[allow(clippy::needless_range_loop)]
fn checked_null(m: &[[f64; 12]; 12], y: [f64; 12]) -> [f64; 12] {
    let (mut ms, mut ys, mut res) = (0.0, 0.0, 0.0);
    for r in 0..12 {
        let mut s = 0.0;
        for c in 0..12 {
            s += m[r][c] * y[c];
            if m[r][c].abs() > ms {
                ms = m[r][c].abs();
            }
        }
        if s.abs() > res {
            res = s.abs();
        }
        if y[r].abs() > ys {
            ys = y[r].abs();
        }
    }
    if res <= NULL_RESIDUAL * ms * ys {
        y
    } else {
        null_vector(m)
    }
}

/// The residual `|m y|` (largest entry) over `|m| |y|` a null vector from partial pivoting may
/// keep (see [`null_vector_trig`]): rounding of the elimination (`1e-16` times its growth and
/// the condition of `U`'s leading block, up to `1e4` at the bench's poses) with a margin of
/// ten; measured `1e-11` at most where partial pivoting works, `1e-7` where it does not.
pub const NULL_RESIDUAL: f64 = 1e-10;

/// `2 atan2(num, den)` from the pair of monomials of largest size: the half-angle tangent's
/// ratio `num / den`, well-conditioned for any angle.
fn angle_from(pairs: &[(f64, f64)]) -> f64 {
    let mut best = (0.0, 1.0);
    let mut bn = -1.0;
    for &(n, d) in pairs {
        let s = n * n + d * d;
        if s > bn {
            bn = s;
            best = (n, d);
        }
    }
    wrap(2.0 * best.0.atan2(best.1))
}

/// An angle in `(−π, π]`. One already there is returned as it is, without the remainder
/// (which is exact and would return it unchanged: the same bits, a library call fewer).
pub(crate) fn wrap(a: f64) -> f64 {
    if a > -std::f64::consts::PI && a <= std::f64::consts::PI {
        return a;
    }
    let t = std::f64::consts::TAU;
    let mut x = a % t;
    if x > std::f64::consts::PI {
        x -= t;
    } else if x <= -std::f64::consts::PI {
        x += t;
    }
    x
}

/// The joints of the arranged chain at a root of `det M`: `v` is the null vector of `M(x)` (or
/// of any multiple of it, as `S(θ)`) there, and `t3` the hidden joint's angle `φ + 2 atan x` (a
/// slide's through [`HALF_INV`]).
#[allow(clippy::needless_range_loop)]
fn back_substitute(ar: &Arranged, el: &Elim, v: &[f64; 12], t3: f64) -> [f64; 6] {
    let at = |a: usize, b: usize| v[3 * a + b];
    let t4 = angle_from(&[
        (at(1, 0), at(0, 0)),
        (at(1, 1), at(0, 1)),
        (at(1, 2), at(0, 2)),
        (at(2, 0), at(1, 0)),
        (at(2, 1), at(1, 1)),
        (at(2, 2), at(1, 2)),
        (at(3, 0), at(2, 0)),
        (at(3, 1), at(2, 1)),
        (at(3, 2), at(2, 2)),
    ]);
    let t5 = angle_from(&[
        (at(0, 1), at(0, 0)),
        (at(1, 1), at(1, 0)),
        (at(2, 1), at(2, 0)),
        (at(3, 1), at(3, 0)),
        (at(0, 2), at(0, 1)),
        (at(1, 2), at(1, 1)),
        (at(2, 2), at(2, 1)),
        (at(3, 2), at(3, 1)),
    ]);
    // A prismatic joint's variable is the tangent of the half angle these formulas give
    // (`d = tan(θ/2)`, see [`HALF_INV`]).
    let slide = |k: usize, t: f64| if ar.j[k].prism { (0.5 * t).tan() } else { t };
    let (t3, t4, t5) = (slide(2, t3), slide(3, t4), slide(4, t5));
    // θ1, θ2: Bm X12 = Am(θ3) X45 by the QR of Bm.
    let f = |k: usize, t: f64| {
        if ar.j[k].prism {
            [1.0, t, t * t]
        } else {
            // (A few units of rounding more than the library's: the refinement starts here.)
            let (c, s) = unit(t);
            [1.0, c, s]
        }
    };
    let (f3, f4, f5) = (f(2, t3), f(3, t4), f(4, t5));
    // The 27 products of the three joints' bases once, in am's order (k, i4, i5).
    let mut g = [0.0; 27];
    for k in 0..3 {
        for i4 in 0..3 {
            for i5 in 0..3 {
                g[9 * k + mono(i4, i5)] = f3[k] * f4[i4] * f5[i5];
            }
        }
    }
    let mut rhs = [0.0; 14];
    for e in 0..14 {
        let mut s = 0.0;
        for (a, gm) in el.am[e].as_flattened().iter().zip(&g) {
            s += a * gm;
        }
        rhs[e] = s;
    }
    let mut y = [0.0; 8];
    for i in 0..8 {
        y[i] = (0..14).map(|e| el.qt[i][e] * rhs[e]).sum();
    }
    let mut z = [0.0; 8];
    for i in (0..8).rev() {
        let mut s = y[i];
        for k in i + 1..8 {
            s -= el.r[i][k] * z[k];
        }
        z[i] = if el.r[i][i] == 0.0 {
            0.0
        } else {
            s / el.r[i][i]
        };
    }
    let mut x12 = [0.0; 9];
    x12[0] = 1.0;
    for i in 0..8 {
        x12[el.piv[i] + 1] = z[i];
    }
    // A prismatic θ1 or θ2 is its monomial `d` itself.
    let t1 = if ar.j[0].prism {
        x12[mono(1, 0)]
    } else {
        x12[mono(2, 0)].atan2(x12[mono(1, 0)])
    };
    let t2 = if ar.j[1].prism {
        x12[mono(0, 1)]
    } else {
        x12[mono(0, 2)].atan2(x12[mono(0, 1)])
    };
    // θ6 from the rest: E6 = (E1 ⋯ E5)⁻¹ H, read about its axis: R6 u = R5ᵀ ⋯ R1ᵀ R_H u for
    // a unit vector u normal to axis 6, each Rᵀ by Rodrigues applied to the vector.
    let w6 = ar.j[5].w;
    let e = if w6[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let u = cross3(&w6, &e);
    let mut v: V = std::array::from_fn(|i| (0..3).map(|l| ar.h[i][l] * u[l]).sum());
    // (Joints 3 to 5 turning have their cosine and sine in their bases already.)
    let t = [t1, t2, t3, t4, t5];
    let fk = [f3, f4, f5];
    for (k, tk) in t.iter().enumerate() {
        if ar.j[k].prism {
            continue;
        }
        let (c, s) = if k >= 2 {
            (fk[k - 2][1], fk[k - 2][2])
        } else {
            unit(*tk)
        };
        let w = &ar.j[k].w;
        // Rᵀ v = c v − s w × v + (1 − c) (w · v) w.
        let x = cross3(w, &v);
        let f = (1.0 - c) * dot3(w, &v);
        v = std::array::from_fn(|i| c * v[i] - s * x[i] + f * w[i]);
    }
    let t6 = dot3(&w6, &cross3(&u, &v)).atan2(dot3(&u, &v));
    [t1, t2, t3, t4, t5, t6]
}

/// The imaginary part (relative) below which an eigenvalue is taken as a real root: a double
/// root, or two close real roots of a nearly special arm, split into a complex pair by rounding
/// with an imaginary part up to the square root of the perturbation; candidates that are no
/// solution are dropped by the forward-kinematics check after refinement.
pub const NEAR_REAL: f64 = 1e-3;

/// The shifts `φ` of the hidden joint tried in turn, the first that makes the leading matrix
/// `A` conditioned better than [`SHIFT_GOOD`] is taken (else the best of them).
pub const SHIFTS: [f64; 5] = [0.0, 2.1, -1.7, 0.9, -2.9];

/// A shift whose leading matrix has a smallest LU pivot above this (relative) is good enough.
pub const SHIFT_GOOD: f64 = 1e-3;

/// Below this relative pivot the leading matrix is singular to rounding for every shift: `det
/// M` vanishes identically (a degenerate arrangement for this geometry).
pub const SHIFT_SINGULAR: f64 = 1e-10;

/// An eigenvalue within this of `±i` is the spurious factor `1 + x²`, not counted in the degree.
pub const SPURIOUS_TOL: f64 = 1e-6;

/// A prismatic hidden joint's root beyond this (scaled length) is a root at infinity, not a
/// solution. After scaling every length of the arm and the target's distance are at most 1, so
/// a slide that reaches the target travels at most about 7 (six links and the target), or
/// `7 / sin α` where two slides at an angle `α` cancel part of each other's travel: below 100
/// for slides more than 4 degrees from parallel (parallel slides are a special family). The
/// roots at infinity of `det M(d)` (8 for a general 5R1P, 16 for a 4R2P with adjacent
/// slides) come out of the shifted linearisation as a cluster around `y = cot(φ/2)`, spread by
/// rounding as `ε^(1/k)` for a cluster of `k`: up to about `1e-4` measured, that is `|d|`
/// above `1e4`; the margin of 100 covers spreads up to `1e-2`.
pub const PRISM_FAR: f64 = 1e2;

/// An eigenvalue larger than this is a root at infinity (the degree drops), not counted.
pub const INFINITE_ROOT: f64 = 1e8;

/// Below this `|r77| / |r00|` the eight monomials of θ1, θ2 are not independent to rounding:
/// the six eliminated equations would not be the elimination (a degenerate arrangement).
pub const RANK_TOL: f64 = 1e-9;

/// As `ik::check::refine`: below `CHECK_TOL / 1000` the pose is exact to rounding.
pub const EXACT_TOL: f64 = 1e-14;

/// The damping of Gauss–Newton: its start (relative to the normal matrix' trace), its least
/// value and the largest before the refinement gives up.
pub const DAMP_START: f64 = 1e-12;
/// See [`DAMP_START`].
pub const DAMP_MIN: f64 = 1e-15;
/// See [`DAMP_START`].
pub const DAMP_MAX: f64 = 1.0;

/// Gauss–Newton iterations at most.
pub const REFINE_ITERS: usize = 16;

/// Two joint vectors within this (every angle, on the circle) are one solution (candidates
/// are merged as they come, [`add_root`]; above the rounding see [`FOLD_REACH`]).
pub const SAME_TOL: f64 = 1e-6;

/// The radius within which a solution whose residual `r` is above [`EXACT_TOL`] repeats one
/// of smaller residual: `FOLD_REACH √r` ([`merge_repeats`]). Near a singular configuration the
/// pose moves only to second order along the Jacobian's near-null direction (a fold, where
/// two solutions meet), so the joint vectors within residual `r` of the pose reach `√(2r/κ)`
/// from the solution along it, `κ` the curvature of the forward kinematics there; a
/// refinement that stops at residual `r` (Gauss–Newton converges only linearly at a fold) can
/// be anywhere in that set, and two candidates that close are one solution at that residual.
/// At the rounding (`r` = [`EXACT_TOL`]) a constant of `SAME_TOL / √EXACT_TOL = 10` would
/// continue [`SAME_TOL`]; measured on the PUMA 560 forced general, 20 poses at each of `1e-3
/// .. 1e-12` and `0` from its elbow singularity, the candidates stopped at residual `r` lay
/// `1.3 √r` to `16 √r` from the exact solution they repeat, while near its wrist singularity
/// the flagged candidates are `61 √r`
/// and more from any solution; the constant is 30, between the two (a curvature down to
/// `0.002`). There, 1,412 solutions were returned before, 568 after (444 flagged approximate
/// before, 9 after), none of the original configurations lost.
pub const FOLD_REACH: f64 = 30.0;

/// The candidates of one arrangement by the eigenvalue route: its real roots (the real and
/// nearly real eigenvalues of the linearisation of `M(x)` at the best-conditioned shift), each
/// with the arm's joint vector (not yet refined), and the degree reached; `None` when `A` is
/// singular at every shift (the arrangement is degenerate here).
pub(crate) fn eigen_candidates(
    ar: &Arranged,
    el: &Elim,
    roots: &mut [[f64; 6]; 24],
) -> Option<(usize, usize)> {
    // The shift φ of the hidden joint that makes A (θ3 = φ + π) best conditioned; its matrix
    // polynomial and the LU of its A are kept.
    let mut best = (0.0, -1.0);
    let mut mp = [[[0.0; 12]; 12]; 3];
    let mut a = [[0.0; 12]; 12];
    let mut p = [0; 12];
    for phi in SHIFTS {
        let mp_s = matrix_poly(&el.sig, phi);
        let mut a_s = mp_s[2];
        let (p_s, ratio) = lu(&mut a_s);
        if ratio > best.1 {
            best = (phi, ratio);
            (mp, a, p) = (mp_s, a_s, p_s);
        }
        if ratio > SHIFT_GOOD {
            break;
        }
    }
    if best.1 < SHIFT_SINGULAR {
        return None;
    }
    let phi = best.0;
    let (ev, n_ev) = eigen_quadratic(&mp, &a, &p)?;
    let mut n = 0;
    let mut degree = 0;
    for &(re, im) in &ev[..n_ev] {
        // A prismatic hidden joint's roots at infinity (`d = ∞`, the eigenvalues clustered at
        // `y = cot(φ/2)`) are no solutions.
        if ar.j[2].prism && (0.5 * phi + re.atan()).tan().abs() > PRISM_FAR {
            continue;
        }
        let spurious = (re.abs() + (im.abs() - 1.0).abs()) < SPURIOUS_TOL;
        if re.is_finite() && im.is_finite() && !spurious && re.hypot(im) < INFINITE_ROOT {
            degree += 1;
        }
        // A real root, or a pair split by rounding (a double root near a singular set): the
        // refinement and the check by forward kinematics decide.
        if im.abs() <= NEAR_REAL * (1.0 + re.abs()) && re.is_finite() {
            let mut m = [[0.0; 12]; 12];
            for r in 0..12 {
                for c in 0..12 {
                    m[r][c] = (mp[2][r][c] * re + mp[1][r][c]) * re + mp[0][r][c];
                }
            }
            let t = back_substitute(ar, el, &null_vector(&m), wrap(phi + 2.0 * re.atan()));
            let mut q = [0.0; 6];
            for i in 0..6 {
                q[ar.perm[i]] = t[i];
            }
            roots[n] = q;
            n += 1;
        }
    }
    Some((n, degree))
}

/// The samples of the determinant route: `det S(θ)` is a trigonometric polynomial of degree at
/// most [`DET_DEGREE`], so `2 DET_DEGREE + 1` equally spaced angles determine it exactly.
pub const DET_SAMPLES: usize = 17;

/// The degree of `det S(θ)` in `θ` for a turning hidden joint: `det M(x) = (1 + x²)¹² det S(θ)`
/// has degree 24 with the spurious factor `(1 + x²)⁴` of the elimination, so `det S(θ)` is a
/// polynomial of degree 16 over `(1 + x²)⁸`: of degree 8 in `(cos θ, sin θ)`.
pub const DET_DEGREE: usize = 8;

/// `sin(kπ/17)` and `cos(kπ/17)`, `k = 0 … 33` (correctly rounded, from 40 digits): the
/// [`DET_SAMPLES`] angles `2πk/17` at the even `k`, the check angle `π/17` and the
/// interpolant's `jπ/17` at the others; no library call.
pub const DET_SIN: [f64; 34] = [
    0.0,
    0.18374951781657034,
    0.3612416661871529,
    0.5264321628773558,
    0.6736956436465572,
    0.7980172272802395,
    0.8951632913550623,
    0.961825643172819,
    0.9957341762950345,
    0.9957341762950345,
    0.961825643172819,
    0.8951632913550623,
    0.7980172272802395,
    0.6736956436465572,
    0.5264321628773558,
    0.3612416661871529,
    0.18374951781657034,
    0.0,
    -0.18374951781657034,
    -0.3612416661871529,
    -0.5264321628773558,
    -0.6736956436465572,
    -0.7980172272802395,
    -0.8951632913550623,
    -0.961825643172819,
    -0.9957341762950345,
    -0.9957341762950345,
    -0.961825643172819,
    -0.8951632913550623,
    -0.7980172272802395,
    -0.6736956436465572,
    -0.5264321628773558,
    -0.3612416661871529,
    -0.18374951781657034,
];

/// See [`DET_SIN`].
pub const DET_COS: [f64; 34] = [
    1.0,
    0.9829730996839018,
    0.9324722294043558,
    0.8502171357296141,
    0.7390089172206591,
    0.6026346363792564,
    0.44573835577653825,
    0.2736629900720829,
    0.092268359463302,
    -0.092268359463302,
    -0.2736629900720829,
    -0.44573835577653825,
    -0.6026346363792564,
    -0.7390089172206591,
    -0.8502171357296141,
    -0.9324722294043558,
    -0.9829730996839018,
    -1.0,
    -0.9829730996839018,
    -0.9324722294043558,
    -0.8502171357296141,
    -0.7390089172206591,
    -0.6026346363792564,
    -0.44573835577653825,
    -0.2736629900720829,
    -0.092268359463302,
    0.092268359463302,
    0.2736629900720829,
    0.44573835577653825,
    0.6026346363792564,
    0.7390089172206591,
    0.8502171357296141,
    0.9324722294043558,
    0.9829730996839018,
];

/// The largest mismatch (relative to the largest sample) between `det S` at the check angle
/// `π / DET_SAMPLES` (half way between two samples) and the interpolant, before the
/// determinant route gives way to the eigenvalue route. Rounding makes each sample's
/// determinant the exact one of a matrix within a few units of rounding (LU with partial
/// pivoting, growth small at a pivot ratio above [`SHIFT_GOOD`]), that is an absolute error up
/// to about `n ε κ` of the largest sample with `κ` the condition of `S` (below `1e4` where
/// the samples are usable), and the interpolation (Lebesgue constant under 3 for 17 points)
/// adds a factor 3: about `1e-10`. Content of degree 9 to 12 (an elimination with fewer
/// spurious factors) aliases onto degrees 8 to 5 and differs at the check angle by twice its
/// size: above `1e-7` it is not rounding.
pub const DET_CHECK: f64 = 1e-7;

/// A top coefficient of `det S(θ)` below this (relative to the largest sample) is rounding and
/// dropped: the polynomial's degree is then lower (more spurious factors `1 + x²`, as for arms
/// with parallel axes, whose roots `±i` the eigenvalue route deflates). Rounding leaves the
/// coefficients with errors of about `1e-13` of the largest sample (see [`DET_CHECK`]); a
/// dropped coefficient of up to `1e-9` moves a simple root by about as much (restored by the
/// refinement) and splits a double root by at most `1e-4.5` (within [`NEAR_REAL`]).
pub const DET_TRIM: f64 = 1e-9;

/// `S(θ) = T0 + T1 cos θ + T2 sin θ`, the 12 x 12 matrix [`matrix_poly`] builds at `φ = 0`
/// divided by `1 + x²`, `x = tan(θ/2)`, by its six distinct rows: `rows[d][r][3a + b]` is the
/// coefficient (`d`: of `1`, `cos θ`, `sin θ`) of the monomial `x4^a x5^b` in equation `r`.
/// Row `r + 6` of `S` is row `r` times `x4`: the same entries at the columns `3(a + 1) + b`.
pub(crate) type TrigRows = [[[f64; 9]; 6]; 3];

/// The [`TrigRows`] of `S(θ)` from `Σ = N Am` (the same rows with `(1, cos θ3, sin θ3)` kept).
#[allow(clippy::needless_range_loop)]
pub(crate) fn trig_rows(sig: &[[[f64; 9]; 6]; 3]) -> TrigRows {
    let mut out = [[[0.0; 9]; 6]; 3];
    for row in 0..6 {
        // Each entry takes its terms in the order (i4, i5) of the table: the sums of the loops
        // over the half-angle map, bit for bit (the products by 1, 2, 4 are exact).
        for &(o, m, h) in &HALF_TERMS {
            for d in 0..3 {
                out[d][row][o] += h * sig[d][row][m];
            }
        }
    }
    out
}

/// The nonzero products `h = HALF[i4][a] HALF[i5][b]` as `(3a + b, mono(i4, i5), h)`, in the
/// order `(i4, i5, a, b)` (25 of 81; a unit test rebuilds them from [`HALF`]).
pub const HALF_TERMS: [(usize, usize, f64); 25] = [
    (0, 0, 1.0),
    (2, 0, 1.0),
    (6, 0, 1.0),
    (8, 0, 1.0),
    (0, 1, 1.0),
    (2, 1, -1.0),
    (6, 1, 1.0),
    (8, 1, -1.0),
    (1, 2, 2.0),
    (7, 2, 2.0),
    (0, 3, 1.0),
    (2, 3, 1.0),
    (6, 3, -1.0),
    (8, 3, -1.0),
    (0, 4, 1.0),
    (2, 4, -1.0),
    (6, 4, -1.0),
    (8, 4, 1.0),
    (1, 5, 2.0),
    (7, 5, -2.0),
    (3, 6, 2.0),
    (5, 6, 2.0),
    (3, 7, 2.0),
    (5, 7, -2.0),
    (4, 8, 4.0),
];

/// The column order in which [`det_trig`] eliminates `S(θ)`: the
/// monomials `x4^a x5^b` by blocks `a = 0, 3, 1, 2`. The rows of the six equations have no `a = 3` column and their
/// copies times `x4` no `a = 0` column, so with the blocks `a = 0` and `a = 3` first each is
/// eliminated within its six rows (the others' multipliers are exactly zero and skipped),
/// leaving a 6 x 6 block: 39 row updates instead of 48. Moving three columns past six keeps
/// the determinant's sign.
pub const DET_COLS: [usize; 12] = [0, 1, 2, 9, 10, 11, 3, 4, 5, 6, 7, 8];

/// The six rows of `S(θ)` at the angle with sine `s`, cosine `c` (54 entries).
#[allow(clippy::needless_range_loop)]
fn rows_at(t: &TrigRows, s: f64, c: f64) -> [[f64; 9]; 6] {
    let mut m = [[0.0; 9]; 6];
    // (The 54 entries as one run: the loop is vectorised.)
    let (t0, t1, t2) = (
        t[0].as_flattened(),
        t[1].as_flattened(),
        t[2].as_flattened(),
    );
    for (k, x) in m.as_flattened_mut().iter_mut().enumerate() {
        *x = t0[k] + c * t1[k] + s * t2[k];
    }
    m
}

/// `S(θ)` at the angle with sine `s`, cosine `c`, its columns in the order [`DET_COLS`] (the
/// tests' reference for [`block_lu`]).
#[cfg(test)]
pub(crate) fn trig_at_cols(t: &TrigRows, s: f64, c: f64) -> [[f64; 12]; 12] {
    cols_of(&rows_at(t, s, c))
}

/// `S` from its six distinct rows `p`, its columns in the order [`DET_COLS`].
fn cols_of(p: &[[f64; 9]; 6]) -> [[f64; 12]; 12] {
    let mut m = [[0.0; 12]; 12];
    for r in 0..6 {
        // Columns a = 0 | a = 3 | a = 1 | a = 2: the equation, then its copy times x4.
        m[r][..3].copy_from_slice(&p[r][..3]);
        m[r][6..].copy_from_slice(&p[r][3..]);
        m[r + 6][3..6].copy_from_slice(&p[r][6..]);
        m[r + 6][6..].copy_from_slice(&p[r][..6]);
    }
    m
}

/// The LU with partial pivoting of `S(θ)` with its columns in the order [`DET_COLS`], on its
/// nonzero blocks only ([`block_lu`]): the rows by their position in the whole matrix'
/// elimination, each as nine entries.
struct BlockLu {
    /// The equations' rows `[a = 0 | a = 1 | a = 2]` at positions 0-5 (rows 0-2 are `U`'s).
    eq: [[f64; 9]; 6],
    /// The copies' rows `[a = 3 | a = 1 | a = 2]`, copy `i` at position `6 + i` until it is
    /// a pivot row.
    low: [[f64; 9]; 6],
    /// The row at position `6 + i` after columns 3-5: copy `i` (`6 + i`) or the equation's
    /// row `k` that traded places with it when it became the pivot row `k`.
    from: [usize; 6],
    /// `U`'s rows 6-11 at its columns 6-11.
    b: [[f64; 6]; 6],
    /// The pivots `u_kk`.
    piv: [f64; 12],
    /// The determinant.
    det: f64,
}

impl BlockLu {
    /// Which copy became pivot row `i` (`from[j] == i`), for `i` below 6; `usize::MAX` where
    /// none did (an equation's row).
    fn copies(&self) -> [usize; 6] {
        let mut out = [usize::MAX; 6];
        for (j, &f) in self.from.iter().enumerate() {
            if f < 6 {
                out[f] = j;
            }
        }
        out
    }
}

/// The LU of `S` from its six distinct rows `p`, with the same pivots, row swaps, products and
/// row updates (of the entries that are read again) as the elimination with partial pivoting
/// of the whole 12 x 12 matrix in the column order [`DET_COLS`]. An equation's row is `[a = 0 |
/// a = 1 | a = 2]` and its copy's `[a = 3 | a = 1 | a = 2]`, the other block zero: columns 0-2
/// are eliminated within the equations' rows (the copies' multipliers are exactly zero),
/// columns 3-5 within the copies' rows, and the last six columns are a 6 x 6 block. A third of
/// the assembly (54 entries, not 144) and about half of the row updates' length.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn block_lu(p: &[[f64; 9]; 6]) -> BlockLu {
    let mut m = *p;
    // The copies: [a = 3 | a = 1 | a = 2] of the equation's [a = 0 | a = 1 | a = 2].
    let mut low = [[0.0; 9]; 6];
    for r in 0..6 {
        let p = &m[r];
        low[r] = [p[6], p[7], p[8], p[0], p[1], p[2], p[3], p[4], p[5]];
    }
    let mut det = 1.0;
    let mut piv = [0.0; 12];
    // Columns 0-2, among the equations' rows (positions 0-5 of the whole matrix). Each step
    // updates the columns after the pivot's only: the entries of the rows below at the
    // pivot's column and before are never read again (the next pivots are searched further
    // right, `U` is read above its diagonal), so the entries that are read are the whole
    // matrix' to the bit.
    eq_step::<0>(&mut m, &mut det, &mut piv);
    eq_step::<1>(&mut m, &mut det, &mut piv);
    eq_step::<2>(&mut m, &mut det, &mut piv);
    // Columns 3-5, among the copies' rows (positions 6-11; the equations' rows 3-5 at
    // positions 3-5 are zero there). A copy taken as the pivot of column k trades places with
    // the equation's row at position k; the copies left keep their positions, in their order,
    // so the first of the largest is the whole matrix' choice.
    let mut from = [6, 7, 8, 9, 10, 11];
    copy_step::<0>(&mut low, &mut from, &mut det, &mut piv);
    copy_step::<1>(&mut low, &mut from, &mut det, &mut piv);
    copy_step::<2>(&mut low, &mut from, &mut det, &mut piv);
    // The last six columns: a 6 x 6 block.
    let mut b = [[0.0; 6]; 6];
    for i in 0..6 {
        let row = if from[i] >= 6 { &low[i] } else { &m[from[i]] };
        b[i].copy_from_slice(&row[3..]);
    }
    block_step::<0>(&mut b, &mut det, &mut piv);
    block_step::<1>(&mut b, &mut det, &mut piv);
    block_step::<2>(&mut b, &mut det, &mut piv);
    block_step::<3>(&mut b, &mut det, &mut piv);
    block_step::<4>(&mut b, &mut det, &mut piv);
    block_step::<5>(&mut b, &mut det, &mut piv);
    BlockLu {
        eq: m,
        low,
        from,
        b,
        piv,
        det,
    }
}

/// Step `K` (column `K`) of [`block_lu`] among the equations' rows: partial pivoting, the rows
/// below less their multiple of the pivot row at the columns after `K`.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn eq_step<const K: usize>(m: &mut [[f64; 9]; 6], det: &mut f64, piv: &mut [f64; 12]) {
    let (mut best, mut bv) = (K, m[K][K].abs());
    for r in K + 1..6 {
        if m[r][K].abs() > bv {
            (best, bv) = (r, m[r][K].abs());
        }
    }
    if best != K {
        m.swap(K, best);
        *det = -*det;
    }
    let d = m[K][K];
    *det *= d;
    piv[K] = d;
    if d != 0.0 {
        let pr = m[K];
        for row in m[K + 1..].iter_mut() {
            let f = row[K] / d;
            if f != 0.0 {
                for c in K + 1..9 {
                    row[c] -= f * pr[c];
                }
            }
        }
    }
}

/// Step `KC` (column `3 + KC`) of [`block_lu`] among the copies' rows not yet pivot rows
/// (`from[i] >= 6`), at the columns after the pivot's.
#[inline(always)]
fn copy_step<const KC: usize>(
    low: &mut [[f64; 9]; 6],
    from: &mut [usize; 6],
    det: &mut f64,
    piv: &mut [f64; 12],
) {
    let mut best = usize::MAX;
    let mut bv = 0.0;
    for i in 0..6 {
        if from[i] >= 6 && low[i][KC].abs() > bv {
            best = i;
            bv = low[i][KC].abs();
        }
    }
    if best == usize::MAX {
        // No copy is nonzero here: the zero pivot of the equation's row 3 + KC.
        *det *= 0.0;
        return;
    }
    *det = -*det;
    from[best] = 3 + KC;
    let pr = low[best];
    let d = pr[KC];
    *det *= d;
    piv[3 + KC] = d;
    for (row, &fr) in low.iter_mut().zip(from.iter()) {
        if fr >= 6 {
            let f = row[KC] / d;
            if f != 0.0 {
                for c in KC + 1..9 {
                    row[c] -= f * pr[c];
                }
            }
        }
    }
}

/// Step `K` of [`block_lu`]'s last 6 x 6 block (column `6 + K`), at the columns after `K`.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn block_step<const K: usize>(b: &mut [[f64; 6]; 6], det: &mut f64, piv: &mut [f64; 12]) {
    let (mut best, mut bv) = (K, b[K][K].abs());
    for r in K + 1..6 {
        if b[r][K].abs() > bv {
            (best, bv) = (r, b[r][K].abs());
        }
    }
    if best != K {
        b.swap(K, best);
        *det = -*det;
    }
    let d = b[K][K];
    *det *= d;
    piv[6 + K] = d;
    if d == 0.0 {
        return;
    }
    let pr = b[K];
    for row in b[K + 1..].iter_mut() {
        let f = row[K] / d;
        if f != 0.0 {
            for c in K + 1..6 {
                row[c] -= f * pr[c];
            }
        }
    }
}

/// `det S(θ)` and the smallest LU pivot over the largest ([`block_lu`]).
pub(crate) fn det_trig(t: &TrigRows, s: f64, c: f64) -> (f64, f64) {
    let f = block_lu(&rows_at(t, s, c));
    let (mut minpiv, mut maxpiv) = (f64::INFINITY, 0.0);
    for d in f.piv {
        if d.abs() < minpiv {
            minpiv = d.abs();
        }
        if d.abs() > maxpiv {
            maxpiv = d.abs();
        }
    }
    (f.det, if maxpiv > 0.0 { minpiv / maxpiv } else { 0.0 })
}

/// A null vector of `S(θ)`, singular to rounding, with its entries in the column order
/// [`DET_COLS`]: `null_vector_lu`'s (the same bits) from the blocks' LU ([`block_lu`]).
#[allow(clippy::needless_range_loop)]
pub(crate) fn null_vector_trig(t: &TrigRows, s: f64, c: f64) -> [f64; 12] {
    let p = rows_at(t, s, c);
    let f = block_lu(&p);
    let (mut kmin, mut pmin) = (11, f64::INFINITY);
    for (k, d) in f.piv.iter().enumerate() {
        if d.abs() < pmin {
            (kmin, pmin) = (k, d.abs());
        }
    }
    let copy = f.copies();
    let mut y = [0.0; 12];
    y[kmin] = 1.0;
    // U's rows by their blocks, the structural zeros skipped: their products `0 · y_c` leave a
    // sum started at `+0` unchanged (it is never `−0`), and a vector with an entry that is not
    // finite takes the complete pivoting of `checked_null_rows` whatever its other entries.
    for i in (0..kmin).rev() {
        let mut s = 0.0;
        if i >= 6 {
            let row = &f.b[i - 6];
            for c in i + 1..=kmin {
                s -= row[c - 6] * y[c];
            }
        } else if copy[i] != usize::MAX {
            // [0 | a = 3 | a = 1 | a = 2]
            let row = &f.low[copy[i]];
            for c in (i + 1).max(3)..=kmin {
                s -= row[c - 3] * y[c];
            }
        } else {
            // [a = 0 | 0 | a = 1 | a = 2]
            let row = &f.eq[i];
            for c in i + 1..=kmin.min(2) {
                s -= row[c] * y[c];
            }
            for c in (i + 1).max(6)..=kmin {
                s -= row[c - 3] * y[c];
            }
        }
        y[i] = if f.piv[i] == 0.0 { 0.0 } else { s / f.piv[i] };
    }
    checked_null_rows(&p, y)
}

/// [`checked_null`] of `S` given by its six distinct rows `p` (the columns in the order
/// [`DET_COLS`]) without assembling it: each row's sum skips the structural zeros, whose
/// products `0 · y_c` are zeros that leave a sum started at `+0` unchanged (it is never `−0`),
/// so the residual, the scales and the decision are [`checked_null`]'s to the bit. A vector
/// with an entry that is not finite (`0 · ∞` is NaN) takes [`checked_null`] itself.
#[allow(clippy::needless_range_loop)]
fn checked_null_rows(p: &[[f64; 9]; 6], y: [f64; 12]) -> [f64; 12] {
    if !y.iter().all(|v| v.is_finite()) {
        return checked_null(&cols_of(p), y);
    }
    let (mut ms, mut ys, mut res) = (0.0, 0.0, 0.0);
    for r in 0..6 {
        let q = &p[r];
        // The equation [a = 0 | 0 | a = 1 | a = 2] and its copy [0 | a = 3 | a = 1 | a = 2].
        let mut s = 0.0;
        let mut t = 0.0;
        for c in 0..3 {
            s += q[c] * y[c];
            t += q[6 + c] * y[3 + c];
        }
        for c in 3..9 {
            s += q[c] * y[3 + c];
        }
        for c in 0..6 {
            t += q[c] * y[6 + c];
        }
        for x in q {
            if x.abs() > ms {
                ms = x.abs();
            }
        }
        for v in [s, t] {
            if v.abs() > res {
                res = v.abs();
            }
        }
    }
    for v in y {
        if v.abs() > ys {
            ys = v.abs();
        }
    }
    if res <= NULL_RESIDUAL * ms * ys {
        y
    } else {
        null_vector(&cols_of(p))
    }
}

/// One step of Gaussian elimination: the rows `rest` below the pivot row less their multiple
/// `row[k] / d` of it, over whole rows (see [`null_vector_lu`]).
#[cfg(test)]
fn eliminate(rest: &mut [[f64; 12]], pivot: &[f64; 12], k: usize, d: f64) {
    for row in rest.iter_mut() {
        let f = row[k] / d;
        if f != 0.0 {
            for c in 0..12 {
                row[c] -= f * pivot[c];
            }
        }
    }
}

/// How many derivatives of `det S(θ)` the root search uses: Taylor's formula to the seventh,
/// the rest bounded by `Σ j⁸ |c_j| r⁸ / 8!` (below `1e-5` of `Σ |c_j|` at the grid's half-width
/// `π / 32`).
pub const TAYLOR: usize = 8;

/// `sin(kπ/32)`, `k = 0 … 63` (correctly rounded, from 40 digits); `cos(kπ/32)` is
/// `GRID_SIN[(k + 16) % 64]`. The points [`unit`] turns from: the grid of the root search
/// (intervals of `2π / ROOT_GRID`) has its ends at the even `k` and its midpoints at the odd.
#[allow(clippy::approx_constant)]
pub const GRID_SIN: [f64; 64] = [
    0.0,
    0.0980171403295606,
    0.19509032201612828,
    0.2902846772544624,
    0.3826834323650898,
    0.47139673682599764,
    0.5555702330196022,
    0.6343932841636455,
    0.7071067811865476,
    0.773010453362737,
    0.8314696123025452,
    0.881921264348355,
    0.9238795325112867,
    0.9569403357322088,
    0.9807852804032304,
    0.9951847266721969,
    1.0,
    0.9951847266721969,
    0.9807852804032304,
    0.9569403357322088,
    0.9238795325112867,
    0.881921264348355,
    0.8314696123025452,
    0.773010453362737,
    0.7071067811865476,
    0.6343932841636455,
    0.5555702330196022,
    0.47139673682599764,
    0.3826834323650898,
    0.2902846772544624,
    0.19509032201612828,
    0.0980171403295606,
    0.0,
    -0.0980171403295606,
    -0.19509032201612828,
    -0.2902846772544624,
    -0.3826834323650898,
    -0.47139673682599764,
    -0.5555702330196022,
    -0.6343932841636455,
    -0.7071067811865476,
    -0.773010453362737,
    -0.8314696123025452,
    -0.881921264348355,
    -0.9238795325112867,
    -0.9569403357322088,
    -0.9807852804032304,
    -0.9951847266721969,
    -1.0,
    -0.9951847266721969,
    -0.9807852804032304,
    -0.9569403357322088,
    -0.9238795325112867,
    -0.881921264348355,
    -0.8314696123025452,
    -0.773010453362737,
    -0.7071067811865476,
    -0.6343932841636455,
    -0.5555702330196022,
    -0.47139673682599764,
    -0.3826834323650898,
    -0.2902846772544624,
    -0.19509032201612828,
    -0.0980171403295606,
];

/// The spacing `π/32` of [`GRID_SIN`].
pub const GRID_STEP: f64 = std::f64::consts::PI / 32.0;

/// `π/32` in two parts (Cody and Waite): `GRID_STEP_HI` with 33 significant bits, so that
/// `b · GRID_STEP_HI` is exact for `|b| < 2²⁰`, and the rest `GRID_STEP_LO` (from 50
/// digits). The rest of an angle `θ − b π/32` is then exact to a unit of its own rounding,
/// not of `θ`'s.
pub const GRID_STEP_HI: f64 = 0.098_174_770_420_882_85;
/// See [`GRID_STEP_HI`].
pub const GRID_STEP_LO: f64 = 3.798_187_816_566_37e-12;

/// `(cos d, sin d)` of a small angle, `|d| ≤ π/64` (and rounding), by Taylor's polynomials to
/// `d⁹` and `d¹⁰`: the remainders `|d|¹¹/11!` and `|d|¹²/12!` are below `1e-22`, far under
/// rounding, so the result is as accurate as a library's (a few units of rounding).
fn cos_sin_small(d: f64) -> (f64, f64) {
    let d2 = d * d;
    let s = d
        * (1.0
            + d2 * (-1.0 / 6.0
                + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0 + d2 * (1.0 / 362_880.0)))));
    let c = 1.0
        + d2 * (-0.5
            + d2 * (1.0 / 24.0
                + d2 * (-1.0 / 720.0 + d2 * (1.0 / 40_320.0 + d2 * (-1.0 / 3_628_800.0)))));
    (c, s)
}

/// `(cos θ, sin θ)` without a library call: the nearest multiple `bπ/32` of the table turned
/// by the rest `θ − bπ/32` ([`cos_sin_small`], the rest by [`GRID_STEP_HI`] and
/// [`GRID_STEP_LO`]): within a few units of rounding of the library's. A function of `θ` alone
/// (the same value for an end shared by two intervals: a root there is seen once), and the
/// table's values at its points.
pub(crate) fn unit(th: f64) -> (f64, f64) {
    // The nearest multiple b (by truncation, one less where that rounded up a negative).
    // (0 for a NaN or huge θ, as the C port: its conversion is undefined there.)
    let y = th / GRID_STEP + 0.5;
    let mut b = if y.abs() < 1e15 { y as i64 } else { 0 };
    if b as f64 > y {
        b -= 1;
    }
    let bf = b as f64;
    let (c, s) = cos_sin_small((th - bf * GRID_STEP_HI) - bf * GRID_STEP_LO);
    let k = b.rem_euclid(64) as usize;
    let (sb, cb) = (GRID_SIN[k], GRID_SIN[(k + 16) % 64]);
    (cb * c - sb * s, sb * c + cb * s)
}

/// `D(θ) = Re Σ_j c_j e^{ijθ}` prepared for evaluation with its derivatives: `D⁽ᵏ⁾(θ) = Re Σ_j
/// (i j)ᵏ c_j e^{ijθ} = Σ_j u[j][k] cos jθ + v[j][k] sin jθ`, the signs of `iᵏ` and the powers
/// `jᵏ` (exact integers) taken into the coefficients once per polynomial, so that an
/// evaluation is the powers of `e^{iθ}` and eight independent sums (which the compiler runs
/// side by side).
pub(crate) struct TrigTable {
    u: [[f64; TAYLOR]; DET_DEGREE + 1],
    v: [[f64; TAYLOR]; DET_DEGREE + 1],
}

/// The [`TrigTable`] of `D(θ) = Re Σ_j c_j e^{ijθ}`, `c_j = a_j + i b_j`: `Re(iᵏ c_j z)` is
/// `a cos − b sin`, `−(b cos + a sin)`, `−(a cos − b sin)`, `b cos + a sin` for `k mod 4 = 0,
/// 1, 2, 3`.
pub(crate) fn trig_table(c: &[(f64, f64); DET_DEGREE + 1]) -> TrigTable {
    let mut t = TrigTable {
        u: [[0.0; TAYLOR]; DET_DEGREE + 1],
        v: [[0.0; TAYLOR]; DET_DEGREE + 1],
    };
    for (j, &(a, b)) in c.iter().enumerate() {
        let mut p = 1.0;
        for k in 0..TAYLOR {
            let (u, v) = match k % 4 {
                0 => (a, -b),
                1 => (-b, -a),
                2 => (-a, b),
                _ => (b, a),
            };
            t.u[j][k] = p * u;
            t.v[j][k] = p * v;
            p *= j as f64;
        }
    }
    t
}

/// `D(θ)` and its derivatives to the seventh (see [`TrigTable`]).
#[allow(clippy::needless_range_loop)]
pub(crate) fn trig_eval(t: &TrigTable, th: f64) -> [f64; TAYLOR] {
    let (co, s) = unit(th);
    let (mut zr, mut zi) = (1.0, 0.0);
    let mut out = [0.0; TAYLOR];
    for (u, v) in t.u.iter().zip(&t.v) {
        for k in 0..TAYLOR {
            out[k] += u[k] * zr + v[k] * zi;
        }
        (zr, zi) = (zr * co - zi * s, zr * s + zi * co);
    }
    out
}

/// A quarter of the root search's [`ROOT_GRID`] base intervals: their midpoints `m` and `m +
/// rπ/2` (`r` = 1, 2, 3) are the others' ([`grid_values`]).
pub const GRID_QUARTER: usize = ROOT_GRID / 4;

const _: () = assert!(ROOT_GRID.is_multiple_of(8));

/// `D` and its derivatives to the seventh ([`trig_eval`]) at the midpoints of the
/// [`ROOT_GRID`] base intervals, `[g % GRID_QUARTER][g / GRID_QUARTER]` for interval `g`: eight
/// at a time from the powers `e^{ijm}` at the first half quarter's midpoints ([`grid_powers`]),
/// since `e^{ij(m + rπ/2)} = iʲʳ e^{ijm}` and `D⁽ᵏ⁾ = C + S` with `C = Σ u cos jθ` even and `S =
/// Σ v sin jθ` odd in `θ` (so `D⁽ᵏ⁾(−θ) = C − S`), and the grid is symmetric: `−(m + rπ/2)` is
/// the midpoint `m′ + (3 − r)π/2` of interval `GRID_QUARTER − 1 − g`. With the sums by `j mod
/// 4` of `u zr`, `v zi` and, for odd classes, `u zi`, `v zr`, each the same products as before
/// (no more multiplications per midpoint than one value needs), at half the midpoints. The
/// same values to a few units of rounding of `Σ |c_j| jᵏ` (another order of the sums); the
/// search only compares them with bounds that have a margin far above that
/// ([`ROOT_MARGIN`]), and its roots come from fresh evaluations ([`bracketed`]).
#[allow(clippy::needless_range_loop)]
pub(crate) fn grid_values(t: &TrigTable) -> [[[f64; TAYLOR]; 4]; GRID_QUARTER] {
    let powers = grid_powers();
    let mut out = [[[0.0; TAYLOR]; 4]; GRID_QUARTER];
    for g in 0..GRID_QUARTER / 2 {
        // By j mod 4: Σ u zr (the cosine part) and Σ v zi (the sine part), and for the odd
        // classes Σ u zi and Σ v zr (the parts turned by i).
        let mut p = [[0.0; TAYLOR]; 4];
        let mut r = [[0.0; TAYLOR]; 4];
        let mut q = [[0.0; TAYLOR]; 2];
        let mut w = [[0.0; TAYLOR]; 2];
        for (j, ((u, v), &(zr, zi))) in t.u.iter().zip(&t.v).zip(&powers[g]).enumerate() {
            let c = j % 4;
            for k in 0..TAYLOR {
                p[c][k] += u[k] * zr;
                r[c][k] += v[k] * zi;
            }
            if c % 2 == 1 {
                for k in 0..TAYLOR {
                    q[c / 2][k] += u[k] * zi;
                    w[c / 2][k] += v[k] * zr;
                }
            }
        }
        for k in 0..TAYLOR {
            // The cosine and sine parts at m + rπ/2, r = 0 … 3.
            let (ce, co) = (p[0][k] + p[2][k], p[1][k] + p[3][k]);
            let (cd, cq) = (p[0][k] - p[2][k], q[1][k] - q[0][k]);
            let (se, so) = (r[0][k] + r[2][k], r[1][k] + r[3][k]);
            let (sd, sw) = (r[0][k] - r[2][k], w[0][k] - w[1][k]);
            let parts = [
                (ce + co, se + so),
                (cd + cq, sd + sw),
                (ce - co, se - so),
                (cd - cq, sd - sw),
            ];
            for (i, (c, s)) in parts.iter().enumerate() {
                out[g][i][k] = c + s;
                // −(m + iπ/2) is m′ + (3 − i)π/2 for the midpoint m′ = −m − 3π/2 of
                // interval GRID_QUARTER − 1 − g: the cosine part is even, the sine part odd.
                out[GRID_QUARTER - 1 - g][3 - i][k] = c - s;
            }
        }
    }
    out
}

/// The powers `e^{ijm}`, `j = 0 … DET_DEGREE`, at the midpoint `m` of each of the first
/// [`GRID_QUARTER`] base intervals of the root search (as [`trig_eval`] computes them there:
/// the same [`unit`] and products), computed once: every search evaluates there first.
pub(crate) fn grid_powers() -> &'static [[(f64, f64); DET_DEGREE + 1]; GRID_QUARTER] {
    static POWERS: std::sync::OnceLock<[[(f64, f64); DET_DEGREE + 1]; GRID_QUARTER]> =
        std::sync::OnceLock::new();
    POWERS.get_or_init(|| {
        let h = std::f64::consts::TAU / ROOT_GRID as f64;
        std::array::from_fn(|k| {
            let (a, b) = (k as f64 * h, (k + 1) as f64 * h);
            let (co, s) = unit(0.5 * (a + b));
            let (mut zr, mut zi) = (1.0, 0.0);
            std::array::from_fn(|_| {
                let z = (zr, zi);
                (zr, zi) = (zr * co - zi * s, zr * s + zi * co);
                z
            })
        })
    })
}

/// `(D⁽ᵏ⁾(θ), D⁽ᵏ⁺¹⁾(θ), D⁽ᵏ⁺²⁾(θ))` for `k` 0 or 1 only (the sums of [`trig_eval`] the
/// root search's brackets read): half its work.
#[allow(clippy::needless_range_loop)]
pub(crate) fn trig_low(t: &TrigTable, k: usize, th: f64) -> (f64, f64, f64) {
    let (co, s) = unit(th);
    let (mut zr, mut zi) = (1.0, 0.0);
    let mut out = [0.0; 4];
    for (u, v) in t.u.iter().zip(&t.v) {
        for l in 0..4 {
            out[l] += u[l] * zr + v[l] * zi;
        }
        (zr, zi) = (zr * co - zi * s, zr * s + zi * co);
    }
    (out[k], out[k + 1], out[k + 2])
}

/// `D⁽ᵏ⁾(θ)` alone (the one sum of [`trig_low`] that the search's end values read; the same
/// sum to the bit).
pub(crate) fn trig_one(t: &TrigTable, k: usize, th: f64) -> f64 {
    let (co, s) = unit(th);
    let (mut zr, mut zi) = (1.0, 0.0);
    let mut out = 0.0;
    for (u, v) in t.u.iter().zip(&t.v) {
        out += u[k] * zr + v[k] * zi;
        (zr, zi) = (zr * co - zi * s, zr * s + zi * co);
    }
    out
}

/// Grid of the real-root search of `det S(θ)`: intervals of `2π / ROOT_GRID`.
pub const ROOT_GRID: usize = 32;

// (The search keeps each interval's index in the grid in a byte.)
const _: () = assert!(ROOT_GRID < 256);

/// The rounding of `D(θ)` relative to `Σ |c_j|` (see [`DET_CHECK`]: the samples' error is
/// about `1e-15` of the largest, measured; a margin of four orders): an interval is free of
/// roots only when `|D|` stays above it.
pub const ROOT_MARGIN: f64 = 1e-11;

/// The smallest half-width of an interval the search splits further (an interval where neither
/// `D′` nor `D″` is certified nonzero at this width is a triple root to rounding: the search
/// gives up).
pub const ROOT_LEAF: f64 = 1e-9;

/// Evaluations of `D` at most before the search gives way to the eigenvalue route (60 to 120
/// at the bench's poses).
pub const ROOT_EVALS: usize = 600;

/// The step of Halley's method (an angle) at which [`bracketed`] stops. The error after a step
/// `s` is about `K s³` (cubic convergence, `K = |D‴/6D′ − (D″/2D′)²|` at the root): up to
/// the degree squared for a simple root on the scale of the coefficients, so that `1e-6`
/// would do there, but `K` grows as the inverse square of the distance to a nearly double
/// root's partner, and such roots are where the refinement needs the root most exactly (the
/// Jacobian nearly singular: a Baxter pose with its fifth joint free stalled `1e-4` from the
/// solution at a residual of `1e-11` from a root to `1e-6`). So the root to `1e-10`, as with
/// Newton's method before: the last step costs one evaluation of three sums.
pub const BRACKET_TOL: f64 = 1e-10;

/// The bracket's width at which bisection in [`bracketed`] stops (where Halley's steps keep
/// leaving the bracket: a root of `D⁽ᵏ⁾` with its derivative nearly zero too), as exact as
/// the refinement needs (it starts from the back-substituted joints anyway).
pub const BRACKET_WIDTH: f64 = 1e-10;

/// The zero of `D⁽ᵏ⁾` in `[a, b]` (`fa` its value or certified sign at `a`, of the opposite
/// sign at `b`, 0 counted as positive), `D⁽ᵏ⁾` monotone there: Halley's method from `start`
/// ([`taylor_start`]), kept inside the bracket (bisection when a step leaves it), to
/// rounding.
fn bracketed(c: &TrigTable, k: usize, mut a: f64, mut b: f64, fa: f64, start: f64) -> f64 {
    let neg_a = fa < 0.0;
    let mut x = start;
    for _ in 0..60 {
        let (v, dv, ddv) = trig_low(c, k, x);
        if v == 0.0 {
            return x;
        }
        if (v < 0.0) == neg_a {
            a = x;
        } else {
            b = x;
        }
        let next = x - 2.0 * v * dv / (2.0 * dv * dv - v * ddv);
        // A Halley step inside the bracket, small enough: the root (see BRACKET_TOL).
        // Bisection where it leaves the bracket, to a bracket of BRACKET_WIDTH.
        if next > a && next < b {
            if (next - x).abs() <= BRACKET_TOL {
                return next;
            }
            x = next;
        } else {
            x = 0.5 * (a + b);
        }
        if b - a <= BRACKET_WIDTH {
            return x;
        }
    }
    x
}

/// `1 / j!`, `j = 0 … 7`.
const INV_FACT: [f64; TAYLOR] = [
    1.0,
    1.0,
    0.5,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5040.0,
];

/// Where [`bracketed`] starts on `[a, b]` inside an interval of the search with midpoint `m`
/// and Taylor data `v` there (`fa`, `fb`: `D⁽ᵏ⁾` at the ends): the zero of `D⁽ᵏ⁾`'s Taylor
/// polynomial at `m`, by Newton's method on it from the secant's zero (no evaluation of `D`).
/// It is within the rest `B₈ r⁸⁻ᵏ / (8 − k)!` over `|D⁽ᵏ⁺¹⁾|` of the root (about `1e-6` at the
/// base grid's width), so that Halley's method takes one step and its check where it took
/// two or three from the secant's zero. The secant's zero where Newton's leaves the bracket.
fn taylor_start(v: &[f64; TAYLOR], k: usize, m: f64, a: f64, b: f64, fa: f64, fb: f64) -> f64 {
    let mut x = a + (b - a) * (fa / (fa - fb));
    if !(x > a && x < b) {
        x = 0.5 * (a + b);
    }
    let mut h = x - m;
    for _ in 0..8 {
        let (mut p, mut dp) = (v[TAYLOR - 1] * INV_FACT[TAYLOR - 1 - k], 0.0);
        for j in (0..TAYLOR - 1 - k).rev() {
            dp = dp * h + p;
            p = p * h + v[k + j] * INV_FACT[j];
        }
        let step = p / dp;
        if !step.is_finite() {
            return x;
        }
        h -= step;
        if step.abs() <= 1e-15 {
            break;
        }
    }
    let y = m + h;
    if y > a && y < b {
        y
    } else {
        x
    }
}

/// The real roots in `θ ∈ [0, 2π)` of `D(θ) = Re Σ_j c_j e^{ijθ}` into `out` (a near-double
/// root twice), by interval search from [`ROOT_GRID`] intervals. On `[m − r, m + r]`, Taylor's
/// formula at `m` to the seventh derivative, with the rest bounded by `B₈ r⁸ / 8!` (`B₈ = Σ j⁸
/// |c_j|` bounds `|D⁽⁸⁾|`), bounds how far `D`, `D′`, `D″` move: `|D(m)|` above it (and the
/// rounding margin) excludes a root; `|D′(m)|` above it makes `D` monotone (a root where its
/// ends differ in sign, by Newton in the bracket); `|D″(m)|` above it makes `D` convex or
/// concave: the extremum (the zero of `D′`) splits it into two monotone parts, and an extremum
/// that does not reach zero but comes within [`NEAR_REAL`] of it (the imaginary part of the
/// complex pair, `√(2 |D| / |D″|)`) is a near-double root, taken twice as the eigenvalue route
/// takes a complex pair with a small imaginary part (so that `gen_solve` sees an incomplete
/// set and reads the next arrangement when both are one solution). Otherwise the interval is
/// halved. An end's sign is read from Taylor's formula where it is certified (beyond the rest
/// and the rounding margin), else evaluated; each root is polished from the zero of the
/// Taylor polynomial ([`taylor_start`]). No real root is lost: every interval that can hold one is resolved or split, and
/// the search gives up (`None`: the eigenvalue route decides) where `D` and `D′` are both zero
/// to rounding (a root of multiplicity three or more, as the special arms forced through the
/// general method have), where an interval reaches [`ROOT_LEAF`] undecided, after
/// [`ROOT_EVALS`] evaluations, or with more roots than fit.
#[allow(clippy::needless_range_loop)]
pub(crate) fn trig_roots(c: &[(f64, f64); DET_DEGREE + 1], out: &mut [f64; 24]) -> Option<usize> {
    // B0 (the scale of D) and B8 (a bound of |D⁽⁸⁾|).
    let (mut b0, mut b8) = (0.0, 0.0);
    for (j, cj) in c.iter().enumerate() {
        let a = cj.0.hypot(cj.1);
        b0 += a;
        let j2 = (j * j) as f64;
        b8 += j2 * j2 * j2 * j2 * a;
    }
    let margin = ROOT_MARGIN * b0;
    let nd = DET_DEGREE as f64;
    let h = std::f64::consts::TAU / ROOT_GRID as f64;
    // The end 2π is the start 0, so that a root there is seen the same from both sides.
    let top = ROOT_GRID as f64 * h;
    let tt = trig_table(c);
    let c = &tt;
    let end = |x: f64| if x >= top { 0.0 } else { x };
    let at = |x: f64| trig_eval(c, end(x));
    // (Each interval with its index in the base grid beside it, ROOT_GRID for the halves.)
    let mut stack = [(0.0, 0.0); 96];
    let mut grid = [0u8; 96];
    let mut depth = 0;
    for k in (0..ROOT_GRID).rev() {
        stack[depth] = (k as f64 * h, (k + 1) as f64 * h);
        grid[depth] = k as u8;
        depth += 1;
    }
    let base = grid_values(c);
    let mut n = 0;
    let mut evals = 0;
    // `D⁽ˡ⁾` at `m + h` by Taylor's formula at `m` (`v`), `|h|` at most the interval's
    // half-width, when its sign is certified: the value beyond the rest `B₈ |h|⁸⁻ˡ / (8 − l)!`
    // (`B₈` bounds `|D⁽⁸⁾|`) and the rounding margin `tol`.
    let certified = |v: &[f64; TAYLOR], l: usize, h: f64, tol: f64| -> Option<f64> {
        let (mut val, mut term) = (0.0, 1.0);
        for k in l..TAYLOR {
            if k > l {
                term *= h / (k - l) as f64;
            }
            val += v[k] * term;
        }
        let rest = b8 * (term * h / (TAYLOR - l) as f64).abs() + tol;
        (val > rest || val < -rest).then_some(val)
    };
    // A root of the monotone part `[a, b]` of `D` (`k = 0`) or `D′` (`k = 1`) inside the
    // interval with midpoint `m` and Taylor data `v` there (`a`, `b` at `m + ha`, `m + hb`), if
    // its ends differ in sign (0 counted as positive, so a root at a shared end is seen once).
    // An end's sign certified by Taylor's formula is not evaluated (it is `D`'s: the margin is
    // far above the evaluation's rounding); two evaluations are counted either way, so that
    // the search takes the same course.
    let mono = |a: f64,
                b: f64,
                (ha, hb): (f64, f64),
                k: usize,
                m: f64,
                v: &[f64; TAYLOR],
                evals: &mut usize| {
        let tol = if k == 0 { margin } else { nd * margin };
        let fa = certified(v, k, ha, tol).unwrap_or_else(|| trig_one(c, k, end(a)));
        let fb = certified(v, k, hb, tol).unwrap_or_else(|| trig_one(c, k, end(b)));
        *evals += 2;
        if (fa < 0.0) == (fb < 0.0) {
            None
        } else {
            let start = taylor_start(v, k, m, a, b, fa, fb);
            Some(bracketed(c, k, a, b, fa, start))
        }
    };
    while depth > 0 {
        depth -= 1;
        let (a, b) = stack[depth];
        let g = grid[depth] as usize;
        let (m, r) = (0.5 * (a + b), 0.5 * (b - a));
        let v = if g < ROOT_GRID {
            base[g % GRID_QUARTER][g / GRID_QUARTER]
        } else {
            at(m)
        };
        evals += 1;
        if evals > ROOT_EVALS || n + 2 > out.len() {
            return None;
        }
        // How far D, D′, D″ can move on the interval: Taylor's formula at m, the rest
        // bounded by B8.
        let mut moves = [0.0; 3];
        for (l, mv) in moves.iter_mut().enumerate() {
            let mut term = 1.0;
            for k in l + 1..TAYLOR {
                term *= r / (k - l) as f64;
                *mv += v[k].abs() * term;
            }
            *mv += b8 * term * r / (TAYLOR - l) as f64;
        }
        if v[0].abs() > moves[0] + margin {
            continue;
        }
        if v[1].abs() > moves[1] + nd * margin {
            if let Some(x) = mono(a, b, (-r, r), 0, m, &v, &mut evals) {
                out[n] = x;
                n += 1;
            }
            continue;
        }
        if v[2].abs() > moves[2] + nd * nd * margin {
            let Some(e) = mono(a, b, (-r, r), 1, m, &v, &mut evals) else {
                // D′ keeps its sign: D is monotone after all.
                if let Some(x) = mono(a, b, (-r, r), 0, m, &v, &mut evals) {
                    out[n] = x;
                    n += 1;
                }
                continue;
            };
            let left = mono(a, e, (-r, e - m), 0, m, &v, &mut evals);
            let right = mono(e, b, (e - m, r), 0, m, &v, &mut evals);
            for x in [left, right].iter().flatten() {
                out[n] = *x;
                n += 1;
            }
            if left.is_none() && right.is_none() {
                let w = at(e);
                if 2.0 * w[0].abs() <= NEAR_REAL * NEAR_REAL * w[2].abs() {
                    out[n] = e;
                    out[n + 1] = e;
                    n += 2;
                }
            }
            continue;
        }
        // D and D′ both zero to rounding (a root of multiplicity three or more: the special
        // arms forced general), or nothing certified at the finest width: the eigenvalue route
        // decides.
        let flat = v[0].abs() <= margin && v[1].abs() <= nd * margin;
        if flat || r <= ROOT_LEAF || depth + 2 > stack.len() {
            return None;
        }
        stack[depth] = (m, b);
        stack[depth + 1] = (a, m);
        grid[depth] = ROOT_GRID as u8;
        grid[depth + 1] = ROOT_GRID as u8;
        depth += 2;
    }
    Some(n)
}

/// The trigonometric polynomial `det S(θ) = Re Σ_j c_j e^{ijθ}` of `S` as [`trig_rows`]
/// gives it: `(c, scale, degree)` with `scale` the largest of the samples and `degree` its
/// degree less the top coefficients that are rounding ([`DET_TRIM`]). `det S` at
/// [`DET_SAMPLES`] angles (an LU each), the `c_j` by the discrete Fourier transform (exact for
/// the degree [`DET_DEGREE`]), checked at one more angle. [`GaveUp::Unconditioned`] when no
/// sample is conditioned, [`GaveUp::Disagrees`] when the check angle disagrees with the
/// interpolant.
#[allow(clippy::needless_range_loop, clippy::type_complexity)]
pub(crate) fn det_coefficients(
    tm: &TrigRows,
) -> Result<([(f64, f64); DET_DEGREE + 1], f64, usize), GaveUp> {
    let mut d = [0.0; DET_SAMPLES];
    let (mut scale, mut good) = (0.0, 0.0);
    for k in 0..DET_SAMPLES {
        // The angle 2πk/17 is (2k)π/17 of the tables.
        let (det, ratio) = det_trig(tm, DET_SIN[2 * k], DET_COS[2 * k]);
        d[k] = det;
        if det.abs() > scale {
            scale = det.abs();
        }
        if ratio > good {
            good = ratio;
        }
    }
    if !(good > SHIFT_GOOD && scale.is_finite()) {
        return Err(GaveUp::Unconditioned(good));
    }
    // c_j = a_j − i b_j of D(θ) = a_0 + Σ a_j cos jθ + b_j sin jθ = Re Σ c_j e^{ijθ}.
    // The samples at ±θ paired: cos jθ is even, sin jθ odd.
    let mut even = [0.0; DET_DEGREE + 1];
    let mut odd = [0.0; DET_DEGREE + 1];
    for k in 1..=DET_DEGREE {
        even[k] = d[k] + d[DET_SAMPLES - k];
        odd[k] = d[k] - d[DET_SAMPLES - k];
    }
    let mut c = [(0.0, 0.0); DET_DEGREE + 1];
    for j in 0..=DET_DEGREE {
        let (mut a, mut b) = (d[0], 0.0);
        // i = j k mod 17, stepped (no division).
        let mut i = 0;
        for k in 1..=DET_DEGREE {
            i += j;
            if i >= DET_SAMPLES {
                i -= DET_SAMPLES;
            }
            a += even[k] * DET_COS[2 * i];
            b += odd[k] * DET_SIN[2 * i];
        }
        let w = if j == 0 { 1.0 } else { 2.0 } / DET_SAMPLES as f64;
        c[j] = (w * a, -(w * b));
    }
    // The check angle π/17, half way between two samples: jπ/17 of the tables.
    let mut interp = 0.0;
    for j in 0..=DET_DEGREE {
        interp += c[j].0 * DET_COS[j] - c[j].1 * DET_SIN[j];
    }
    let check = det_trig(tm, DET_SIN[1], DET_COS[1]).0;
    // A NaN mismatch fails too.
    let agrees = (check - interp).abs() <= DET_CHECK * scale;
    if !agrees {
        return Err(GaveUp::Disagrees);
    }
    let mut n = DET_DEGREE;
    while n > 0 && c[n].0.hypot(c[n].1) <= DET_TRIM * scale {
        n -= 1;
    }
    Ok((c, scale, n))
}

/// Why a determinant route gave up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum GaveUp {
    /// No sample of `S(θ)` has a relative pivot above [`SHIFT_GOOD`]; the best one's is given.
    /// `S(θ)` is then near a matrix singular at every `θ`: the arrangement is nearly
    /// degenerate at this target (as those of a special arm that are degenerate are, when it
    /// is perturbed by less than about the square root of the rounding), and its eigenvalue
    /// route is used only where no conditioned arrangement gives a complete set (see
    /// [`gen_solve`]).
    Unconditioned(f64),
    /// The interpolant disagrees with `det S` at the check angle ([`DET_CHECK`]).
    Disagrees,
    /// The root search gave up ([`trig_roots`]: a flat cluster of roots).
    Cluster,
}

/// The candidates of one arrangement by the determinant route (the hidden joint turns): `det
/// S(θ)` by [`det_coefficients`], its real roots by [`trig_roots`], then one null vector of
/// `S(θ)` per root ([`null_vector_trig`]). Why it gave up (the eigenvalue route decides, see
/// [`gen_solve`]) when either gives up.
#[allow(clippy::needless_range_loop)]
pub(crate) fn det_candidates(
    ar: &Arranged,
    el: &Elim,
    roots: &mut [[f64; 6]; 24],
) -> Result<(usize, usize), GaveUp> {
    let tm = trig_rows(&el.sig);
    let (c, _, n) = det_coefficients(&tm)?;
    let mut th = [0.0; 24];
    let count = trig_roots(&c, &mut th).ok_or(GaveUp::Cluster)?;
    for (k, &t3) in th[..count].iter().enumerate() {
        // The null vector of S(θ) with its columns in the order DET_COLS (the elimination
        // then skips the same zero blocks as det_trig's), put back in monomial order.
        let (co, s) = unit(t3);
        let y = null_vector_trig(&tm, s, co);
        let mut v = [0.0; 12];
        for (yk, &j) in y.iter().zip(&DET_COLS) {
            v[j] = *yk;
        }
        let t = back_substitute(ar, el, &v, wrap(t3));
        for i in 0..6 {
            roots[k][ar.perm[i]] = t[i];
        }
    }
    // A trigonometric polynomial of degree n has 2n complex roots, none at infinity.
    Ok((count, 2 * n))
}

/// The chain prepared for the forward kinematics (once per solve): with `Fi` a frame of joint
/// `i` in the home pose (its `z` axis the joint's axis, its origin the axis' point),
/// `E1(q1) ⋯ E6(q6) M = F1 Z(q1) L1 Z(q2) L2 ⋯ Z(q6) L6`, where `Z(q)` turns by `q` about `z`
/// (a slide moves by `q` along it), `Li = Fi⁻¹ Fi+1` and `L6 = F6⁻¹ M` (`Ei(q) = Fi Z(q)
/// Fi⁻¹`). The link transforms `Li` are constants of the arm, so a joint costs the turn of two
/// columns and one product, the cosine and sine once, and the product so far is joint `i + 1`'s
/// frame: its current axis with no work.
pub(crate) struct Chain {
    /// `F1`.
    base: B34,
    /// `L1 … L6`.
    link: [B34; 6],
    /// Whether each joint slides.
    prism: [bool; 6],
}

/// A frame of the axis through `c` along `w`: `z` the unit direction, `x` a unit normal (away
/// from the coordinate axis nearest `z`), `y = z × x`, origin `c`.
fn axis_frame(w: &V, c: &V) -> B34 {
    let n = dot3(w, w).sqrt();
    let z = [w[0] / n, w[1] / n, w[2] / n];
    let e = if z[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let x0 = cross3(&z, &e);
    let m = dot3(&x0, &x0).sqrt();
    let x = [x0[0] / m, x0[1] / m, x0[2] / m];
    let y = cross3(&z, &x);
    [
        [x[0], y[0], z[0], c[0]],
        [x[1], y[1], z[1], c[1]],
        [x[2], y[2], z[2], c[2]],
    ]
}

/// The [`Chain`] of the axes `ax` and the home pose `home` (scaled).
pub(crate) fn chain(ax: &[GenAxis; 6], home: &B34) -> Chain {
    let fr: [B34; 6] = std::array::from_fn(|i| {
        let x = &ax[i];
        axis_frame(&[x[1], x[2], x[3]], &[x[4], x[5], x[6]])
    });
    Chain {
        base: fr[0],
        link: std::array::from_fn(|i| {
            compose(&inverse(&fr[i]), if i < 5 { &fr[i + 1] } else { home })
        }),
        prism: std::array::from_fn(|i| ax[i][0] != 0.0),
    }
}

/// `a b` for rigid motions (no term for the zero bottom row of `b`'s rotation columns).
#[inline(always)]
fn then(a: &B34, b: &B34) -> B34 {
    std::array::from_fn(|r| {
        let x = &a[r];
        let mut o = [0.0; 4];
        for c in 0..3 {
            o[c] = x[0] * b[0][c] + x[1] * b[1][c] + x[2] * b[2][c];
        }
        o[3] = x[0] * b[0][3] + x[1] * b[1][3] + x[2] * b[2][3] + x[3];
        o
    })
}

/// The pose `E1(q1) ⋯ E6(q6) M` and each joint's current axis `(w, p)` (scaled lengths).
#[inline(always)]
pub(crate) fn forward(ch: &Chain, q: &[f64; 6]) -> (B34, [[f64; 6]; 6]) {
    forward_with::<true>(ch, q)
}

/// [`forward`], the current axes only when `AXES` (else zero): the refinement's trial points
/// need the pose alone unless another step follows.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
fn forward_with<const AXES: bool>(ch: &Chain, q: &[f64; 6]) -> (B34, [[f64; 6]; 6]) {
    let mut cur = [[0.0; 6]; 6];
    let mut p = ch.base;
    for i in 0..6 {
        if AXES {
            cur[i] = [p[0][2], p[1][2], p[2][2], p[0][3], p[1][3], p[2][3]];
        }
        if ch.prism[i] {
            for row in p.iter_mut() {
                row[3] += q[i] * row[2];
            }
        } else {
            let (c, s) = unit(q[i]);
            for row in p.iter_mut() {
                let (x, y) = (row[0], row[1]);
                row[0] = c * x + s * y;
                row[1] = c * y - s * x;
            }
        }
        p = then(&p, &ch.link[i]);
    }
    (p, cur)
}

pub(crate) fn compose(a: &B34, b: &B34) -> B34 {
    let mut o = [[0.0; 4]; 3];
    for r in 0..3 {
        for c in 0..4 {
            let t = if c == 3 { a[r][3] } else { 0.0 };
            o[r][c] = t + a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        }
    }
    o
}

/// `T − F` entry by entry and its largest size (NaN when any entry is): the maximum by
/// comparisons (a NaN never wins one) and the NaN by a flag, without a branch per entry.
fn error(f: &B34, t: &B34) -> ([f64; 12], f64) {
    let mut e = [0.0; 12];
    let mut m: f64 = 0.0;
    let mut nan = false;
    for r in 0..3 {
        for c in 0..4 {
            let d = t[r][c] - f[r][c];
            e[4 * r + c] = d;
            let a = d.abs();
            if a > m {
                m = a;
            }
            nan |= d.is_nan();
        }
    }
    (e, if nan { f64::NAN } else { m })
}

/// Damped Gauss–Newton from `q` on the pose residual (as `ik::check::refine`, on scaled
/// lengths); returns the final residual.
#[allow(clippy::needless_range_loop)]
pub(crate) fn refine(ch: &Chain, t: &B34, q: &mut [f64; 6]) -> f64 {
    let (mut f, mut cur) = forward(ch, q);
    let (mut e, mut res) = error(&f, t);
    let mut lambda = DAMP_START;
    // The axes of `cur` belong to an earlier `q` (a step was taken without them).
    let mut stale = false;
    for _ in 0..REFINE_ITERS {
        if res <= EXACT_TOL || res.is_nan() {
            break;
        }
        if stale {
            cur = forward(ch, q).1;
        }
        // The Jacobian's column of joint i is `[w]× [F | t − p]` (revolute; `[0 | w]` for a
        // slide), so its normal matrix and gradient need no column: with `F` a rotation (to
        // rounding), `Σ_k (wi × f_k)·(wj × f_k) = 3 wi·wj − wiᵀ F Fᵀ wj = 2 wi·wj` and
        // `Σ_k (wi × f_k)·e_k = wi·u`, `u = Σ_k f_k × e_k`; the translation column adds
        // `(wi × (t − pi))·(wj × (t − pj))` and its product with `e_t`.
        let col = |k: usize| [f[0][k], f[1][k], f[2][k]];
        let mut u = [0.0; 3];
        for k in 0..3 {
            let x = cross3(&col(k), &[e[k], e[4 + k], e[8 + k]]);
            for r in 0..3 {
                u[r] += x[r];
            }
        }
        let et = [e[3], e[7], e[11]];
        let mut rot = [[0.0; 3]; 6];
        let mut tra = [[0.0; 3]; 6];
        for i in 0..6 {
            let [wx, wy, wz, px, py, pz] = cur[i];
            let w = [wx, wy, wz];
            if ch.prism[i] {
                tra[i] = w;
            } else {
                rot[i] = w;
                tra[i] = cross3(&w, &[f[0][3] - px, f[1][3] - py, f[2][3] - pz]);
            }
        }
        let mut a = [[0.0; 6]; 6];
        let mut g = [0.0; 6];
        let mut tr = 0.0;
        for i in 0..6 {
            for j in i..6 {
                let x = 2.0 * dot3(&rot[i], &rot[j]) + dot3(&tra[i], &tra[j]);
                a[i][j] = x;
                a[j][i] = x;
            }
            g[i] = dot3(&rot[i], &u) + dot3(&tra[i], &et);
            tr += a[i][i];
        }
        loop {
            let mut m = a;
            for i in 0..6 {
                m[i][i] += lambda * tr.max(f64::MIN_POSITIVE);
            }
            if let Some(d) = cholesky_solve(&m, &g) {
                let next: [f64; 6] = std::array::from_fn(|i| q[i] + d[i]);
                let (f2, _) = forward_with::<false>(ch, &next);
                let (e2, r2) = error(&f2, t);
                if r2 < res {
                    *q = next;
                    (f, e, res) = (f2, e2, r2);
                    stale = true;
                    lambda = (lambda * 0.01).max(DAMP_MIN);
                    break;
                }
            }
            lambda *= 100.0;
            if lambda > DAMP_MAX {
                return res;
            }
        }
    }
    res
}

/// Solves `m d = g` by Cholesky's factorization `m = L Lᵀ`: the refinement's damped normal
/// matrix is symmetric and positive definite (the Gram matrix of the Jacobian's columns plus a
/// positive multiple of the identity), so no pivoting is needed and the factorization is
/// backward stable; half the work of an LU with partial pivoting. `None` where a pivot is not
/// positive and finite (rounding made the matrix indefinite: more damping).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
pub(crate) fn cholesky_solve(m: &[[f64; 6]; 6], g: &[f64; 6]) -> Option<[f64; 6]> {
    // The lower triangle `l` and its diagonal's reciprocals.
    let mut l = [[0.0; 6]; 6];
    let mut inv = [0.0; 6];
    for j in 0..6 {
        let mut s = m[j][j];
        for k in 0..j {
            s -= l[j][k] * l[j][k];
        }
        // (Not NaN, not infinite.)
        if !(s > 0.0 && s < f64::INFINITY) {
            return None;
        }
        let ir = 1.0 / s.sqrt();
        inv[j] = ir;
        for i in j + 1..6 {
            let mut t = m[i][j];
            for k in 0..j {
                t -= l[i][k] * l[j][k];
            }
            l[i][j] = t * ir;
        }
    }
    // `L y = g`, then `Lᵀ d = y`.
    let mut y = [0.0; 6];
    for i in 0..6 {
        let mut t = g[i];
        for k in 0..i {
            t -= l[i][k] * y[k];
        }
        y[i] = t * inv[i];
    }
    let mut d = [0.0; 6];
    for i in (0..6).rev() {
        let mut t = y[i];
        for k in i + 1..6 {
            t -= l[k][i] * d[k];
        }
        d[i] = t * inv[i];
    }
    Some(d)
}

/// Two joint vectors within `radius` of each other in every joint (angles compared on the
/// circle). Inlined into [`add_root`]'s loop, which runs once per candidate and solution held.
#[inline(always)]
pub(crate) fn same(a: &[f64; 6], b: &[f64; 6], prismatic: &[bool; 6], radius: f64) -> bool {
    (0..6).all(|i| {
        let d = if prismatic[i] {
            a[i] - b[i]
        } else {
            wrap(a[i] - b[i])
        };
        d.abs() <= radius
    })
}

/// Drops each solution of `out` that repeats another at its residual: one whose residual `r`
/// is above [`EXACT_TOL`] and that lies within `FOLD_REACH √r` ([`FOLD_REACH`]) of a solution
/// of smaller residual (of equal residual and earlier). The candidates are merged within
/// [`SAME_TOL`] as they come ([`add_root`]); this pass once per solve, after the last, costs a
/// comparison per solution where every residual is exact to rounding.
pub(crate) fn merge_repeats(out: &mut GenOut, prismatic: &[bool; 6]) {
    if out.residual[..out.n].iter().all(|&r| r <= EXACT_TOL) {
        return;
    }
    let mut i = out.n;
    while i > 0 {
        i -= 1;
        let r = out.residual[i];
        if r <= EXACT_TOL {
            continue;
        }
        let radius = FOLD_REACH * r.sqrt();
        let repeats = (0..out.n).any(|j| {
            let rj = out.residual[j];
            j != i
                && (rj < r || (rj == r && j < i))
                && same(&out.q[j], &out.q[i], prismatic, radius)
        });
        if repeats {
            for k in i..out.n - 1 {
                out.q[k] = out.q[k + 1];
                out.residual[k] = out.residual[k + 1];
            }
            out.n -= 1;
        }
    }
}

/// Refines the candidates of arrangement `arr` (roots of degree `degree`), adds the solutions
/// to `out`; whether the set is complete (every root gave its own exact solution: a double
/// root, two solutions sharing the hidden joint, gives one of them twice or neither).
#[allow(clippy::too_many_arguments)]
fn take_roots(
    out: &mut GenOut,
    roots: &[[f64; 6]],
    degree: usize,
    arr: usize,
    ch: &Chain,
    tg: &B34,
    tol: &GenTol,
) -> bool {
    if out.n_arr == 0 {
        out.degree = degree;
    }
    if out.n_arr < 3 {
        out.arrangements[out.n_arr] = arr;
    }
    out.n_arr += 1;
    // The solutions this arrangement's roots reached (exactly).
    let mut hit = [false; GEN_MAX];
    for root in roots {
        if let Some((i, exact, _)) = add_root(out, *root, ch, tg, tol) {
            hit[i] |= exact;
        }
    }
    hit.iter().filter(|h| **h).count() == roots.len()
}

/// Refines the candidate `q` ([`refine`]) and adds it to `out`, its angles wrapped: merged
/// with a solution within [`SAME_TOL`] of it (the smaller residual kept) or appended. Returns
/// the index it took, whether it is exact (residual within `tol.pose`) and whether it was
/// appended; `None` when it is no solution (residual above `tol.keep`) or the set is full.
/// The root loop of [`take_roots`] and of the 4R2P solver (`apart_solver.rs`).
pub(crate) fn add_root(
    out: &mut GenOut,
    mut q: [f64; 6],
    ch: &Chain,
    tg: &B34,
    tol: &GenTol,
) -> Option<(usize, bool, bool)> {
    let prismatic = ch.prism;
    let res = refine(ch, tg, &mut q);
    if res.is_nan() || res > tol.keep {
        return None;
    }
    for (v, p) in q.iter_mut().zip(prismatic) {
        if !p {
            *v = wrap(*v);
        }
    }
    let exact = res <= tol.pose;
    if let Some(i) = (0..out.n).find(|&i| same(&out.q[i], &q, &prismatic, SAME_TOL)) {
        if res < out.residual[i] {
            out.q[i] = q;
            out.residual[i] = res;
        }
        Some((i, exact, false))
    } else if out.n < GEN_MAX {
        out.q[out.n] = q;
        out.residual[out.n] = res;
        out.n += 1;
        Some((out.n - 1, exact, true))
    } else {
        None
    }
}

/// Every solution of `E1 ⋯ E6 M = T` for a 6R chain: the arrangements (a cyclic shift of the
/// loop, read forwards or backwards) are tried in order; one whose elimination is
/// nondegenerate gives its real roots, each is back-substituted, refined and checked by
/// forward kinematics. When a root gave no new solution (a double root: two solutions
/// sharing the hidden joint), the next arrangement adds its solutions too (at most three).
///
/// A determinant route gives up where `det S`, `D′` and `D″` are all near zero (a flat
/// cluster of roots) or its check fails. Such a cluster is either an accident of the target in
/// one arrangement (the roots of `det S(θ)` are the values of the hidden joint, which differs
/// from one arrangement to the next: two solutions close in `θ3` are rarely close in the next
/// arrangement's hidden joint) or structural (an arm near special geometry, where two
/// solutions share a joint angle for every target; the cluster then recurs in every
/// arrangement whose hidden joint is that joint or moves with it). So the eigenvalue route of
/// the first arrangement to give up is deferred by one arrangement: the next usable
/// arrangement's determinant route is tried, and if it gives up too (the cluster recurs), the
/// deferred arrangement's eigenvalue route decides, then that arrangement's own. Its cost when
/// structural: one more elimination and determinant route than before.
///
/// A determinant route that gives up because no sample of `S(θ)` is conditioned
/// ([`GaveUp::Unconditioned`]) marks an arrangement that is nearly degenerate at this target:
/// the arrangements of a special arm whose `det M` vanishes identically stay within about the
/// perturbation of that when the arm is perturbed (a UR5 whose twists are off by `1e-9`: the
/// best sample's relative pivot about `1e-9`, its smallest singular values about `1e-12`,
/// two of them). Its eigenvalue route divides by a leading matrix as ill-conditioned, so its
/// rounding (about `ε κ`, relative) swamps the perturbation that makes `det M` nonzero
/// wherever `ε κ ≳ 1/κ`: roots are lost or made up, and the null vectors at the roots mix
/// with the near-null direction (garbage that the refinement carries to some other solution:
/// the set looks complete and misses the original configuration, or is empty). Such an
/// arrangement is kept for the end and used only when the conditioned ones leave the set
/// incomplete, the best conditioned first. The bound is the determinant route's own
/// [`SHIFT_GOOD`]: the pivot ratio overstates the smallest singular value by up to a few
/// hundred (measured on these arrangements), so at `1e-3` the smallest singular value is
/// above about `3e-6` and the null vectors' mixing, `24 ε / σ²`, below `6e-4`, under
/// [`NEAR_REAL`].
#[allow(clippy::needless_range_loop)]
pub fn gen_solve(
    axes: &[GenAxis; 6],
    home: &[[f64; 4]; 3],
    target: &[[f64; 4]; 4],
    len: f64,
    tol: GenTol,
    first: usize,
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
    let mut tg: B34 = [[0.0; 4]; 3];
    tg.copy_from_slice(&target[..3]);
    for r in 0..3 {
        hm[r][3] /= len;
        tg[r][3] /= len;
    }
    let prismatic: [bool; 6] = std::array::from_fn(|i| ax[i][0] != 0.0);
    let ch = chain(&ax, &hm);
    let g = compose(&tg, &inverse(&hm));
    let js: [J; 6] = std::array::from_fn(|i| J {
        w: [ax[i][1], ax[i][2], ax[i][3]],
        c: [ax[i][4], ax[i][5], ax[i][6]],
        prism: prismatic[i],
    });
    let mut roots = [[0.0; 6]; 24];
    // An arrangement whose determinant route gave up, its eigenvalue route deferred (see
    // above).
    let mut deferred: Option<(Arranged, Elim, usize)> = None;
    // The arrangements whose determinant route found no conditioned sample (nearly
    // degenerate here, see above): the best sample's pivot ratio and the arrangement.
    let mut unconditioned = [(0.0, 0); 12];
    let mut n_unc = 0;
    // The left side from the arm's constants where it is one (scaled to this target's
    // length scale), else from the arranged joints.
    let elim_of = |ar: &Arranged, arr: usize| {
        if left_is_constant(ar, arr) {
            ar.elim_from(scaled_left(&robot_left(axes, arr), len))
        } else {
            ar.elim()
        }
    };
    let mut complete = false;
    // The arrangement chosen at the derivation first (one that served at its generic target,
    // or the other reading from joint 1 where that gives up less at sample targets: special
    // geometry makes the same ones degenerate at every target, and the hidden joint whose
    // roots cluster is a property of the arm), then the others in order.
    for k in 0..12 {
        let arr = if k == 0 {
            first % 12
        } else if k <= first % 12 {
            k - 1
        } else {
            k
        };
        // Incomplete sets try every usable arrangement (a nearly special arm has nearly double
        // roots in several of them).
        if out.n_arr == 12 {
            break;
        }
        let ar = Arranged::new(&js, &g, arr);
        // The last arranged joint is eliminated by a point of its axis, which a slide moves.
        if prismatic[ar.perm[5]] {
            continue;
        }
        // (Borrowed where it was returned, moved only when it waits: no copy of it per
        // arrangement.)
        let elo = elim_of(&ar, arr);
        let Some(el) = elo.as_ref() else {
            continue;
        };
        if el.rank_ratio < RANK_TOL {
            continue;
        }
        // A turning hidden joint: the determinant route first.
        let det = if ar.j[2].prism {
            None
        } else {
            Some(det_candidates(&ar, el, &mut roots))
        };
        let found = match det {
            Some(Ok(found)) => Some(found),
            // Nearly degenerate here: kept for the end.
            Some(Err(GaveUp::Unconditioned(good))) => {
                unconditioned[n_unc] = (good, arr);
                n_unc += 1;
                continue;
            }
            // The first to give up waits for the next arrangement's determinant route.
            Some(Err(_)) if deferred.is_none() => {
                deferred = elo.map(|el| (ar, el, arr));
                continue;
            }
            // A second gave up (a cluster in every arrangement) or the hidden joint slides:
            // the deferred eigenvalue route decides first, then this arrangement's.
            _ => {
                if let Some((da, de, darr)) = deferred.take() {
                    if let Some((n, degree)) = eigen_candidates(&da, &de, &mut roots) {
                        complete = take_roots(&mut out, &roots[..n], degree, darr, &ch, &tg, &tol);
                        if complete || out.n_arr == 12 {
                            break;
                        }
                    }
                }
                eigen_candidates(&ar, el, &mut roots)
            }
        };
        let Some((n, degree)) = found else { continue };
        complete = take_roots(&mut out, &roots[..n], degree, arr, &ch, &tg, &tol);
        if complete {
            break;
        }
    }
    // The loop ended with an arrangement deferred and the set incomplete: its eigenvalue route.
    if let Some((da, de, darr)) = deferred {
        if !complete && out.n_arr < 12 {
            if let Some((n, degree)) = eigen_candidates(&da, &de, &mut roots) {
                complete = take_roots(&mut out, &roots[..n], degree, darr, &ch, &tg, &tol);
            }
        }
    }
    // Still incomplete: the nearly degenerate arrangements' eigenvalue routes, the best
    // conditioned first (in the order tried among equals).
    let unc = &mut unconditioned[..n_unc];
    for i in 1..unc.len() {
        let mut k = i;
        while k > 0 && unc[k - 1].0 < unc[k].0 {
            unc.swap(k - 1, k);
            k -= 1;
        }
    }
    for &(_, arr) in unc.iter() {
        if complete || out.n_arr == 12 {
            break;
        }
        let ar = Arranged::new(&js, &g, arr);
        let Some(el) = elim_of(&ar, arr) else {
            continue;
        };
        if let Some((n, degree)) = eigen_candidates(&ar, &el, &mut roots) {
            complete = take_roots(&mut out, &roots[..n], degree, arr, &ch, &tg, &tol);
        }
    }
    merge_repeats(&mut out, &prismatic);
    // Prismatic variables back in the robot's length unit.
    for q in out.q.iter_mut().take(out.n) {
        for (v, p) in q.iter_mut().zip(prismatic) {
            if p {
                *v *= len;
            }
        }
    }
    out
}

/// Balancing (Parlett–Reinsch, powers of two): similar matrix with rows and columns of
/// comparable norm, so that the QR iteration's rounding is relative to the eigenvalues' size.
#[allow(clippy::needless_range_loop)]
fn balance(a: &mut [[f64; 24]; 24], n: usize) {
    const RADIX: f64 = 2.0;
    let mut done = false;
    let mut sweeps = 0;
    while !done && sweeps < 100 {
        done = true;
        sweeps += 1;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for j in 0..n {
                if j != i {
                    c += a[j][i].abs();
                    r += a[i][j].abs();
                }
            }
            if c == 0.0 || r == 0.0 || !(c + r).is_finite() {
                continue;
            }
            let s = c + r;
            let mut f = 1.0;
            let mut g = r / RADIX;
            while c < g {
                f *= RADIX;
                c *= RADIX * RADIX;
            }
            g = r * RADIX;
            while c > g {
                f /= RADIX;
                c /= RADIX * RADIX;
            }
            if (c + r) / f < 0.95 * s {
                done = false;
                let gi = 1.0 / f;
                for j in 0..n {
                    a[i][j] *= gi;
                }
                for j in 0..n {
                    a[j][i] *= f;
                }
            }
        }
    }
}

/// Reduction to upper Hessenberg form by stabilised elementary similarity transformations
/// (of the leading `n x n` block).
#[allow(clippy::needless_range_loop)]
fn hessenberg(a: &mut [[f64; 24]; 24], n: usize) {
    for m in 1..n - 1 {
        let mut x: f64 = 0.0;
        let mut i = m;
        for j in m..n {
            if a[j][m - 1].abs() > x.abs() {
                x = a[j][m - 1];
                i = j;
            }
        }
        if i != m {
            for j in m - 1..n {
                let t = a[i][j];
                a[i][j] = a[m][j];
                a[m][j] = t;
            }
            for j in 0..n {
                a[j].swap(i, m);
            }
        }
        if x != 0.0 {
            for i in m + 1..n {
                let mut y = a[i][m - 1];
                if y != 0.0 {
                    y /= x;
                    a[i][m - 1] = 0.0;
                    let (top, rest) = a.split_at_mut(i);
                    for (ai, am) in rest[0][m..n].iter_mut().zip(&top[m][m..n]) {
                        *ai -= y * am;
                    }
                    for row in a[..n].iter_mut() {
                        row[m] += y * row[i];
                    }
                }
            }
        }
    }
}

/// The eigenvalues of the leading `n x n` block of a real matrix (destroyed): balancing,
/// Hessenberg reduction and the Francis double-shift QR iteration (the classical `hqr`); the
/// first `n` pairs are set. `None` when an eigenvalue takes more than 60 iterations.
#[allow(clippy::needless_range_loop, clippy::many_single_char_names)]
pub(crate) fn eigenvalues(a0: &mut [[f64; 24]; 24], size: usize) -> Option<[(f64, f64); 24]> {
    balance(a0, size);
    hessenberg(a0, size);
    // 1-based indices as in the classical formulation: a[i][j] = a0[i - 1][j - 1].
    let n = size as isize;
    macro_rules! a {
        ($i:expr, $j:expr) => {
            a0[($i - 1) as usize][($j - 1) as usize]
        };
    }
    let mut wr = [0.0; 24];
    let mut wi = [0.0; 24];
    let mut anorm = 0.0;
    for i in 1..=n {
        for j in (i - 1).max(1)..=n {
            anorm += a!(i, j).abs();
        }
    }
    if !anorm.is_finite() {
        return None;
    }
    let mut nn = n;
    let mut t = 0.0;
    let (mut p, mut q, mut r, mut s, mut w, mut x, mut y, mut z): (
        f64,
        f64,
        f64,
        f64,
        f64,
        f64,
        f64,
        f64,
    );
    (p, q, r) = (0.0, 0.0, 0.0);
    while nn >= 1 {
        let mut its = 0;
        loop {
            let mut l = nn;
            while l >= 2 {
                s = a!(l - 1, l - 1).abs() + a!(l, l).abs();
                if s == 0.0 {
                    s = anorm;
                }
                if a!(l, l - 1).abs() + s == s {
                    a!(l, l - 1) = 0.0;
                    break;
                }
                l -= 1;
            }
            x = a!(nn, nn);
            if l == nn {
                wr[(nn - 1) as usize] = x + t;
                wi[(nn - 1) as usize] = 0.0;
                nn -= 1;
                break;
            }
            y = a!(nn - 1, nn - 1);
            w = a!(nn, nn - 1) * a!(nn - 1, nn);
            if l == nn - 1 {
                p = 0.5 * (y - x);
                q = p * p + w;
                z = q.abs().sqrt();
                x += t;
                let (i1, i2) = ((nn - 2) as usize, (nn - 1) as usize);
                if q >= 0.0 {
                    z = p + if p >= 0.0 { z } else { -z };
                    wr[i1] = x + z;
                    wr[i2] = x + z;
                    if z != 0.0 {
                        wr[i2] = x - w / z;
                    }
                    wi[i1] = 0.0;
                    wi[i2] = 0.0;
                } else {
                    wr[i1] = x + p;
                    wr[i2] = x + p;
                    wi[i1] = -z;
                    wi[i2] = z;
                }
                nn -= 2;
                break;
            }
            if its == 60 {
                return None;
            }
            if its == 10 || its == 20 || its == 40 {
                // An exceptional shift.
                t += x;
                for i in 1..=nn {
                    a!(i, i) -= x;
                }
                s = a!(nn, nn - 1).abs() + a!(nn - 1, nn - 2).abs();
                x = 0.75 * s;
                y = x;
                w = -0.4375 * s * s;
            }
            its += 1;
            let mut m = nn - 2;
            while m >= l {
                z = a!(m, m);
                r = x - z;
                s = y - z;
                p = (r * s - w) / a!(m + 1, m) + a!(m, m + 1);
                q = a!(m + 1, m + 1) - z - r - s;
                r = a!(m + 2, m + 1);
                s = p.abs() + q.abs() + r.abs();
                p /= s;
                q /= s;
                r /= s;
                if m == l {
                    break;
                }
                let u = a!(m, m - 1).abs() * (q.abs() + r.abs());
                let v = p.abs() * (a!(m - 1, m - 1).abs() + z.abs() + a!(m + 1, m + 1).abs());
                if u + v == v {
                    break;
                }
                m -= 1;
            }
            for i in m + 2..=nn {
                a!(i, i - 2) = 0.0;
                if i != m + 2 {
                    a!(i, i - 3) = 0.0;
                }
            }
            let mut k = m;
            while k < nn {
                if k != m {
                    p = a!(k, k - 1);
                    q = a!(k + 1, k - 1);
                    r = 0.0;
                    if k != nn - 1 {
                        r = a!(k + 2, k - 1);
                    }
                    x = p.abs() + q.abs() + r.abs();
                    if x != 0.0 {
                        p /= x;
                        q /= x;
                        r /= x;
                    }
                }
                let norm = (p * p + q * q + r * r).sqrt();
                s = if p >= 0.0 { norm } else { -norm };
                if s != 0.0 {
                    if k == m {
                        if l != m {
                            a!(k, k - 1) = -a!(k, k - 1);
                        }
                    } else {
                        a!(k, k - 1) = -s * x;
                    }
                    p += s;
                    x = p / s;
                    y = q / s;
                    z = r / s;
                    q /= p;
                    r /= p;
                    // Rows k, k + 1 (and k + 2) over columns k..=nn, and columns k, k + 1
                    // (and k + 2) over rows l..=min(nn, k + 3), as row slices.
                    let (k0, n0) = ((k - 1) as usize, nn as usize);
                    let (row0, rest) = a0[k0..].split_first_mut().expect("row k");
                    let (row1, rest) = rest.split_first_mut().expect("row k + 1");
                    if k != nn - 1 {
                        let row2 = &mut rest[0];
                        for j in k0..n0 {
                            let p = row0[j] + q * row1[j] + r * row2[j];
                            row2[j] -= p * z;
                            row1[j] -= p * y;
                            row0[j] -= p * x;
                        }
                    } else {
                        for j in k0..n0 {
                            let p = row0[j] + q * row1[j];
                            row1[j] -= p * y;
                            row0[j] -= p * x;
                        }
                    }
                    let mmin = if nn < k + 3 { nn } else { k + 3 };
                    for row in a0[(l - 1) as usize..mmin as usize].iter_mut() {
                        let c = &mut row[k0..k0 + if k != nn - 1 { 3 } else { 2 }];
                        let mut p = x * c[0] + y * c[1];
                        if k != nn - 1 {
                            p += z * c[2];
                            c[2] -= p * r;
                        }
                        c[1] -= p * q;
                        c[0] -= p;
                    }
                }
                k += 1;
            }
            if l >= nn - 1 {
                break;
            }
        }
    }
    let mut out = [(0.0, 0.0); 24];
    for i in 0..size {
        out[i] = (wr[i], wi[i]);
    }
    Some(out)
}
