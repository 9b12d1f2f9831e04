//! Inverse kinematics of a general 6-joint chain, revolute or prismatic (no special family
//! applies, or `--method general`), by the Raghavan–Roth elimination in Manocha and Canny's
//! matrix form.
//!
//! # The elimination
//!
//! The chain is the product of exponentials on the exact home-pose axes, `E1(q1) ⋯ E6(q6) M =
//! T`, so with `H = T M⁻¹`:
//!
//! 1. `E3 E4 E5 (p6, w6) = E2⁻¹ E1⁻¹ H (p6, w6)`, for a point `p6` and the direction `w6` of
//!    axis 6 (which `E6` leaves fixed): `θ6` is gone.
//! 2. The fourteen Raghavan–Roth quantities of the point `p` and direction `l` on both sides:
//!    `l`, `p`, `p·p`, `p·l`, `p × l`, `(p·p) l − 2 (p·l) p`. A rotation about the origin acts
//!    on them linearly with entries in `(1, cos, sin)` of its angle; a constant translation
//!    linearly with constant entries (the products are absorbed by `t × (l × p)`), and every
//!    joint motion is a rotation between two constant translations. So each quantity is of
//!    degree at most one in the sine and cosine of each joint: `Bm X12 = Am(θ3) X45`, with
//!    `X12` the eight products `(1, c1, s1) ⊗ (1, c2, s2)` but the constant, `X45` the nine
//!    products `(1, c4, s4) ⊗ (1, c5, s5)`, `Am` linear in `(1, c3, s3)`.
//! 3. The six rows `N` with `N Bm = 0` (the left null space of the 14 x 8 `Bm`, from its
//!    Householder QR) give six equations `N Am(θ3) X45 = 0` free of `θ1`, `θ2`.
//! 4. Half-angle tangents `x4`, `x5` (times `(1 + x4²)(1 + x5²)`) turn them into six equations
//!    in the nine monomials `x4^a x5^b` (`a, b ≤ 2`); with the same six times `x4`: twelve in
//!    twelve, `M(x3) X = 0`, `M(x3) = A x3² + B x3 + C`, `x3 = tan((θ3 − φ)/2)`.
//! 5. `det M(x3) = 0` is the univariate polynomial, of degree 24 with the spurious factor
//!    `(1 + x3²)⁴`: degree 16 for a general 6R. For a turning hidden joint the core finds its
//!    real roots by the determinant route (below); where that route gives up in this
//!    arrangement and again in the next one tried (`core::gen_solve`: a cluster that is an
//!    accident of the target breaks up in another reading of the loop, a structural one
//!    recurs; an arrangement with no conditioned sample of `S(θ)` is nearly degenerate at the
//!    target and waits until the conditioned ones leave the set incomplete, `core::GaveUp`),
//!    and for a sliding hidden joint, they are the eigenvalues of the 24 x 24 companion linearisation
//!    `[[0, I], [−A⁻¹C, −A⁻¹B]]` (the spurious `±i` deflated first from the null vectors of
//!    `M(i)`, 24 → 16 rows; then balancing, Hessenberg reduction, Francis double-shift QR; the
//!    shift `φ` keeps `A` invertible). The degree the solution states
//!    ([`GeneralInfo::degree`]) is the number of roots of `det M` at a generic target that
//!    move with the target (`degree.rs`: the spurious `±i`, roots at infinity and, for special
//!    geometry, roots that stay, such as the wrist singular set `θ5 ∈ {0, π}` of a spherical
//!    wrist, are not counted); special geometry lowers it.
//! 6. Back-substitution: `x4`, `x5` from the null vector of `M(x3)`; `θ1`, `θ2` from `Bm X12 =
//!    Am(θ3) X45` (least squares by the same QR); `θ6` from `E6 = (E1 ⋯ E5)⁻¹ H` about axis 6.
//!    Every candidate is polished by damped Gauss–Newton on the forward kinematics and checked
//!    by it ([`super::check`]'s residual and approximate flag); duplicates are merged: within
//!    `core::SAME_TOL` as they come, then a solution whose residual `r` is above the rounding
//!    into one of smaller residual within `core::FOLD_REACH √r` (near a singular
//!    configuration the refinement stops short along a fold, and the joint vectors within
//!    residual `r` reach about `√r` from the solution: `core::merge_repeats`).
//!
//! # Prismatic joints
//!
//! A prismatic joint's motion is a translation by `d w` (its length `d` along its unit axis
//! `w`). By the translation formulas (see [`exact`]) it acts on the fourteen quantities with
//! entries of degree at most two in `d` (`p·p` gains `2 d w·p + d²`, the last three `d² l −
//! 2 d² (w·l) w`), and on nothing else: so every step above carries over with the basis `(1,
//! d, d²)` of a slide in place of `(1, cos, sin)` of a turn. The core samples a slide at `d =
//! 0, 1, −1` and reads the coefficients by the inverse Vandermonde matrix (exact for degree
//! two), as it samples a turn at three angles.
//!
//! - A slide among joints 1, 2 changes the eight power products of `X12` (`d1`, `d1²`, `d1 c2`,
//!   …): `Bm` keeps its 14 x 8 shape, and `d` is read back as its monomial itself.
//! - A slide among joints 4, 5 needs no half-angle tangent: `d` is already the polynomial
//!   variable. The core converts its coefficients by `HALF⁻¹` so that the half-angle map
//!   of step 4 turns them back into `(1, d, d²)`: `M(x)` keeps its 12 x 12 shape.
//! - A slide at joint 3 gives `M(d) = A d² + B d + C` directly (the same conversion); the shift
//!   `φ` of a turn becomes the Möbius map `d = (t + y) / (1 − t y)`, `t = tan(φ/2)`, which
//!   keeps `A` invertible when `M(d)` has roots at infinity. These (eight for a general 5R1P)
//!   come out at `y = cot(φ/2)` and are not counted in the degree.
//! - Joint 6 must turn: it is eliminated by a point of its axis, which a slide would move. The
//!   arrangements that end with a slide are skipped (and the exact equations read the loop
//!   backwards when the last joint slides).
//!
//! Degree reached at a generic target (measured, `tests/it/ik_general_prismatic.rs`, the slide
//! or slides at every placement in a skew chain): 16 for a 5R1P, 8 for a 4R2P, the known
//! bounds (5R1P ≤ 16, 4R2P ≤ 8). Two slides among joints 1, 2, or among 4, 5, leave power
//! products that never occur (`Bm` loses rank, or `M` has a zero column). A slide among joints
//! 1, 2 together with one among joints 4, 5 makes `det M` vanish identically, for this reason
//! (`degenerate_reason`):
//!
//! - A slide's `d²` enters only four of the fourteen quantities: `p·p` (coefficient 1) and the
//!   last three, `(p·p) l − 2 (p·l) p` (coefficient the reflection `l − 2 (v·l) v` of the
//!   direction in the plane normal to the slide's direction `v`, then carried by the turns
//!   after it). So the `d²` columns are vectors `(α; y)` in those four rows, `y ∈ R³`.
//! - The left slide (joint 1 or 2) gives `Bm` three `d²` columns (times `1, c, s` of the other
//!   left joint): those with `α = 0` span the turn's image of a plane, a 2-plane `Π₁ ⊂ R³`.
//! - The right slide (joint 4 or 5) gives `Am` three `d²` columns (times `1, c, s` of the
//!   other right joint): those with `α = 0` (the `cos`, `sin` ones) span a 2-plane `Π₂ ⊂ R³`,
//!   turned by `θ3`.
//! - Two planes of `R³` through the origin share a line: at every `θ3` a combination of the
//!   right slide's `d² c`, `d² s` columns lies in the column space of `Bm`, so `N` annihilates
//!   it and `M(x)` has a null vector supported on the columns of the slide's highest power
//!   `d³ x5ᵇ` (a solution at `d = ∞`) for every `x`: `det M ≡ 0`.
//!
//! An arm whose two slides are three joints apart (RPRRPR, PRRPRR, RRPRRP) puts one slide on
//! each side in every reading of the loop that ends with a turn, so this elimination cannot
//! serve it; `apart.rs` solves it instead (the loop read from a slide, `Tr(d0 v0) E1 E2 Tr(d3
//! v3) E4 E5 = H`): slides turn nothing, so `R1 R2 = R_H R5ᵀ R4ᵀ =: Q` and `F = w1 · Q w2 −
//! w1 · w2 = 0` (degree one in each of `θ4`, `θ5`); moved past the turns the slides add `d0 v0
//! + d3 Q v3`, so `P = det(v0, Q v3, h − t(E1 E2 E4 E5)) = 0` (degree two in each, with
//! `cos θ1`, `sin θ1` by subproblem 1 linear in `Q`); the Sylvester resultant of `F` and `P`
//! in `tan(θ5/2)` is a trigonometric polynomial `D(θ4)` of degree 8 (17 samples, the core's
//! certified root search; where it gives up in both readings, the eigenvalues of the companion
//! matrix of `D` in `tan((θ4 − φ)/2)`). `D` has degree 6 at a generic arm: 12 roots, of which
//! the four where the common root is `tan(θ5/2) = ±i` are no solutions, so the degree reached
//! is 8 (`degree::apart_degree`). Back-substitution: `θ5` from `F = 0` where `P` vanishes, `θ1`,
//! `θ2` by subproblem 1, `d0`, `d3` by least squares (flagged singular where the slides'
//! current directions are parallel), then the core's refinement and check. A 3R3P arm needs
//! no elimination: the family `ik/plan/slides.rs` solves it in closed form (two solutions).
//!
//! # The degree stated
//!
//! The roots of `det M` that move with the target (`degree.rs`) can still be no solutions for
//! special geometry forced general (the IRB 140: 16 moving roots, 8 solutions). `closure.rs`
//! back-substitutes every complex root at the generic target (the null vector of `M(x3)`, `X12`
//! from the fourteen equations) and keeps those where the equations hold and `X12` is a
//! product of `(1, c, s)` factors with `c² + s² = 1`: the degree stated is the smaller count.
//!
//! Special geometry makes an arrangement degenerate (`Bm` loses rank, or `det M` vanishes
//! identically, as for a spherical wrist) or gives double roots (two solutions sharing `θ3`):
//! the loop `E1 ⋯ E6 H⁻¹ = I` is then read from another joint or backwards (twelve
//! arrangements), and a set with a double root is completed from the next arrangement.
//!
//! # What is exact
//!
//! [`exact`] derives the fourteen equations exactly: every coefficient of `Am(θ3)` and `Bm` a
//! [`crate::Scalar`] in the robot's parameters and the target's entries (through the fourteen
//! quantities `g1 … g14` of the target's point and direction), by the action of a rigid
//! motion on the quantities as a 15 x 15 matrix, one joint at a time in `(1, cos, sin)`; and
//! the half-angle polynomials `P_e(x3, x4, x5) = (1 + x3²)(1 + x4²)(1 + x5²) (Am X45)_e`.
//! The report and the walkthrough print them. Exact arithmetic stops at step 3: the left
//! null space `N` of `Bm` is computed per target in f64 (Householder QR), so `A`, `B`, `C`
//! (`N` times the `P_e`) and everything after are numeric. The exact equations are those of
//! the loop read from joint 1 (forwards or backwards as at the generic target); an
//! arrangement read from another joint conjugates axes by the target and is not printed.
//!
//! The solver itself (`core.rs`) computes the same coefficients numerically from the axes
//! evaluated at the parameters: each of the fourteen quantities is sampled on a 3 x 3 x 3
//! grid of angles `2πk/3` and its coefficients read off by a three-point discrete Fourier
//! transform, exact for degree one ([`sampled_equations`] returns them; a test checks them
//! against [`exact`] at random parameters and targets).
//! The numeric core (`core.rs`) is plain Rust that the generated solver contains verbatim.
//!
//! # The determinant route
//!
//! `M(x) = (1 + x²) S(θ)` row by row, with `S(θ) = T0 + T1 cos θ + T2 sin θ` (12 x 12, `x =
//! tan(θ/2)`), so `det S = det M / (1 + x²)¹²` is a trigonometric polynomial in `θ`, of degree
//! 8 for the spurious factor `(1 + x²)⁴` (lower for arms with more): no division by a factor
//! that vanishes at `±i`, no shift, no root at infinity. The core (`core::det_candidates`)
//! evaluates it at 17 equally spaced real angles (an LU each, the columns in the block order
//! `core::DET_COLS`: the six equations have no `x4³` column and their copies no `x4⁰` one, so
//! each of those blocks is eliminated within its own six rows, 39 row updates instead of 48;
//! only the six distinct rows are assembled, and the zero blocks are never stored: the same
//! pivots and bits as the whole matrix' LU, a test checks),
//! reads its coefficients by the discrete Fourier transform (exact for degree 8, perfectly
//! conditioned on the circle), and checks the interpolant at an 18th angle (content of a
//! higher degree would show there). Its real roots come from a certified interval search
//! (`core::trig_roots`): Taylor's formula to the seventh derivative with the rest bounded by
//! `Σ j⁸ |c_j|` excludes intervals free of roots and proves the others monotone (one root,
//! Halley's method in the bracket from the zero of the Taylor polynomial at the interval's
//! midpoint: cubic convergence, one step and its check, the ends' signs read from Taylor's
//! formula where it certifies them) or
//! convex (two roots or a near-double one, taken twice as a near-real complex pair is) — no
//! real root can fall between the cases. No library sine or cosine: the sample angles are
//! tables (`core::DET_SIN`), and each evaluation turns the nearest multiple of `π/32`
//! (`core::GRID_SIN`) by Taylor polynomials of the rest (`core::unit`, a few units of
//! rounding), with the signs and powers of the derivatives folded into the coefficients once
//! per polynomial (`core::TrigTable`). Each root's null vector is one LU with partial
//! pivoting (the same column order), checked by its residual (complete pivoting otherwise). Where `det S` and its derivative vanish
//! together to rounding (a cluster of roots: the multiple roots of special arms forced
//! general, and a cluster of about six roots within 0.02 rad at one pose in ten of a general
//! arm), the route gives up and the eigenvalue route decides, as it does when no sample is
//! conditioned or the check angle disagrees.
//!
//! Why `det S` has degree 8 at every arm, and why no smaller determinant splits off `S(θ)`
//! (issue #29, session 19; the unit test
//! `det_tests::the_moving_part_of_s_has_rank_eight_in_its_rows_and_no_constant_block` checks
//! each rank below on the skew arm and random arms, all twelve arrangements). The
//! hidden joint is a rotation `Rot(θ)` between two constant translations (step 2), so the left
//! side is `L Rot(θ) u(X45)`, `u` the fourteen quantities of `E4 E5 (p6, w6)` moved by a
//! constant translation: `Rot(θ)` leaves the two scalars and the four vectors' components
//! along the axis alone and turns the eight others, `cos θ Π + sin θ J` (`Π` the projection
//! on the four normal planes, `J` the quarter turn in each). So `T1`, `T2` (the parts of `Σ =
//! N Am` in `cos θ3`, `sin θ3`) are `N L Π U⊥`, `N L J U⊥`, with `U⊥` the 8 x 9 matrix of those
//! eight components in `X45`: stacked (12 x 9) they have rank 8, and their kernel, `U⊥`'s,
//! depends on joints 3 to 6 of the arranged loop alone, so it is the same at every target
//! where those four are all the arm's or all conjugated by the target (a common rigid motion:
//! arrangements 0, 4, 5, forwards or backwards) and moves with it in the others. With `z =
//! e^{iθ}`, `z S(θ) = A⁻ + z T0 + z² A⁺`, `A± = (T1 ∓ i T2) / 2`, and `Π + i J` has complex
//! rank one in each plane: `T1 + i T2` has complex rank 4 in nine columns, so the 12 x 12 `A⁻`
//! (six rows and their copies times `x4`) has rank 8 at most, and so has `A⁺`. Then `det (z
//! S)` has the factor `z⁴` and degree 20 at most: `det S = z⁻⁸ p(z)`, `p` of degree 16, a
//! trigonometric polynomial of degree 8 (the spurious `(1 + x²)⁴` is this), whatever the arm.
//! A general 6R has 16 solutions, so no elimination of this kind has a lower degree and
//! needs fewer samples. A constant block does not split off either: the real parts `T1`,
//! `T2` of the 12 x 12 `S`, stacked (24 x 12) and side by side (12 x 24), have rank 12 at every
//! arm and target tried, so no combination of its columns or of its rows with constant
//! coefficients is free of `θ`. The constant block there is is complex: with `Z` the kernel of
//! `A⁻` and `Y` the left kernel of `A⁺`, `Y S(θ) Z = Y T0 Z` (4 x 4), and its Schur
//! complement is an 8 x 8 matrix quadratic in `z` with complex entries, whose samples cost
//! more than the real 12 x 12 LU on its blocks (about 230 multiplications and additions).
//!
//! Why not the companion matrix of `p(x) = (1 + x²)⁸ det S` in monomials (tried): its QR
//! took 207k instructions (more than the linearisation's) and its roots came out to `1e-6`
//! only (monomials are ill-conditioned for sixteen roots spread on the real line), losing two
//! solutions of the 64 bench poses to near-double roots turned complex.
//!
//! Measured (callgrind, the generated solver of `benches/support/skew6r.toml` at the 64 poses
//! of `benches/ik_general.rs`, instructions of the solves only, 362 solutions before and
//! after): 513k instructions per pose with the eigenvalue route (QR iteration 133k, null
//! vectors 68k, `±i` deflation 66k, the elimination 66k, refinement 60k); 402k with the
//! determinant route as first built (the 18 sampled LUs 86k, the root search 75k of which
//! 36k were library `sincos` calls, null vectors and back-substitution 26k, the eigenvalue
//! route at the 5 poses of 64 where the search gives up 20k); 352k now (issue #29, session
//! 14: no library `sincos` in the search, the back-substitution or the forward kinematics of
//! the refinement, `core::unit` instead, within a few units of rounding, the residuals still
//! below `EXACT_TOL`; Halley; the block column order; the tables; the QR's row layout). What
//! is left, per pose: the 18 sampled LUs about 85k (their row updates are vectorised
//! already; assembling `S(θ)` is a fifth of it), the elimination 70k (the QR of `Bm` 20k of
//! it), the refinement 55k (12 forward kinematics and 6 normal equations for 6 candidates),
//! the search 45k (about 50 evaluations with all derivatives and 60 of three), null vectors
//! and back-substitution 50k, the eigenvalue route 20k. The C port (GCC 12, `-O2`): 607k to
//! 550k. Tried and dropped (no gain or a loss): row updates from the pivot column on
//! (not vectorised), the elimination's arrays built element by element, the 27 products of
//! back-substitution hoisted, a root margin lowered a hundredfold (the eigenvalue route's
//! poses are clusters within `1e-13` of the scale). The 20 µs (about 150k instructions) of
//! issue #29 needs fewer or smaller samples (an LU is 4.7k), the left side of the
//! elimination (`E3 E4 E5` on its grid) hoisted to the arm's constants where the loop is
//! read from joint 1 (it depends on the target only through the length scale), and fewer
//! refinement steps.
//!
//! Session 15 (callgrind as above): 352k to 301k per pose, 362 solutions, the same solutions
//! to the bit (each change keeps every operation and its order; a harness compared all 64
//! poses' joint vectors bit for bit): `det S` and the roots' null vectors from one LU on
//! the nonzero blocks (`core::block_lu`: the six distinct rows assembled, 54 entries not 144;
//! row updates of 9 and 6 entries, not 12; tests check the same bits as the whole matrix'
//! LU), the root search skipping `mono`'s end evaluations where Taylor's formula at the
//! midpoint certifies one sign at both ends, the refinement's trial points without the
//! current axes, the elimination's sample rotations once per joint and its sums along the
//! contiguous index. Measured per pose now (inclusive): the elimination 56k (one arrangement:
//! the QR of `Bm` with `Q` 12k, `Σ = N Am` 4k, the grid transforms 8k, loop overhead the
//! rest), the 18 sampled determinants 52k (about 1k of row updates each at SSE2's two lanes,
//! assembly 0.4k, pivoting and bookkeeping the rest), the root search about 40k (50
//! evaluations with eight derivatives, 60 with three), the refinement's forward kinematics
//! 23k (2.1 per candidate: one Gauss–Newton step reaches `EXACT_TOL` already), the
//! back-substitution 22k (a third of it five library `atan2`), the eigenvalue route 20k and
//! its complete-pivoting null vectors 12k (5 poses of 64). Tried and dropped: a root grid of
//! 16 or 24 intervals (330k: more splits), the back-substitution's sums from a transposed
//! copy of `Am` (more copying than it saved). The 150k of issue #29 is not reached by local
//! changes: what is left is spread over steps near their floor in arithmetic, and needs
//! structure (the left side of the elimination, `E3 E4 E5` on its grid, as per-arm constants
//! where the loop is read from joint 1 or 6; the base grid's evaluations from tables; a forward
//! kinematics shared by the refinement's steps). The C port's determinant on the blocks too
//! (the same bits): GCC 12 `-O2` 551k per pose before and after (it vectorises neither), `-O3`
//! 352k to 324k.
//!
//! Session 16 (callgrind as above): 301k to 237k per pose, 362 solutions. Bit for bit the same
//! solutions (each change keeps every operation and its order; a harness compared the 64 poses'
//! joint vectors): `block_lu`'s row updates only at the columns after the pivot's (the entries
//! before are never read again), each step with its column a constant so that the loops unroll
//! (`core::eq_step`, `copy_step`, `block_step`), 301k to 280k; the null vector's residual check on
//! the six distinct rows of `S` (structural zeros skipped); the QR of `Bm` and the
//! complete-pivoting null vector step by step with constant columns (278k to 261k); the normal
//! matrix of the refinement by its upper triangle; the search's end values by one sum
//! (`core::trig_one`) and its 32 base evaluations from the powers `e^{ijm}` at the grid's midpoints
//! computed once (`core::grid_powers`), the grid indices beside the search's stack (a stack above 2
//! kB took glibc's `rep stosb` to zero, which callgrind counts by the byte). Different bits, the
//! same solutions to `4e-13`: the left side of the elimination (`E3 E4 E5` on its grid and its
//! transform, 16k per pose) is a constant of the arm where the loop is read from joint 1
//! (arrangements 0 and 6, joints 3 to 5 turning): computed in the robot's units once per arm and
//! thread (`core::robot_left`, a cache keyed by the axes' bits) and each equation scaled by `1/len`
//! to its degree in length (`core::LEFT_DEG`, `core::scaled_left`), 261k to 243k. The C port
//! computes the same numbers per call (`ik_gen_robot_left`) and stays bit for bit the Rust
//! solver's; the JavaScript and Python ports keep the left side of the scaled arm (their solutions
//! agree within the ports tests' tolerance). Tried and dropped: the elimination's transforms built
//! block by block without zeroed arrays (283k, worse), `compose` row by row (the same code). What
//! is left per pose, roughly: the 18 sampled determinants 30k, the root search 30k, the elimination
//! 35k (the QR of `Bm` 12k), the refinement 30k, the back-substitution 20k, the eigenvalue route at
//! 5 poses of 64 about 30k. The 150k of issue #29 is not reached.
//!
//! Session 17 (callgrind as above): 236k to 219k per pose, the same 362 solutions (within
//! `5e-14`). Where arrangement 0's determinant route gives up (5 poses of 64: a cluster of
//! roots of `det S(θ3)` within rounding) the next arrangement's determinant route is tried
//! before the eigenvalue route (`core::gen_solve`): its hidden joint is another, where the
//! cluster is not; an extra elimination and 18 samples (about 100k) instead of the eigenvalue
//! route (about 450k). Where the next one gives up too (a structural cluster: a PUMA with
//! `1e-6` offsets forced general gives up in 10 of 12 arrangements), the deferred
//! arrangement's eigenvalue route decides, then that arrangement's own, so the solution set is
//! the one the old order gave (`det_tests`). All four ports take this order; the C port stays
//! bit for bit the Rust solver's on the 64 bench poses. `core::trig_rows` reads its 25 nonzero
//! half-angle products from a table in the loops' order (the same bits; 1.4k). Tried and
//! dropped: the 27 products of the back-substitution hoisted (0.6k, different bits), a root
//! grid of 16, 24 or 48 intervals (all more than 32). What is left per pose (inclusive): the
//! determinant route 136k (18 sampled LUs 38k, search 26k, back-substitution 22k), the
//! refinement 51k (two forward kinematics per root, 1.8k each, and one Gauss–Newton step:
//! 316 of 368 roots need exactly one, the residual after it is about `4e-16`, below
//! `EXACT_TOL` = `1e-14`, which is the rounding of the 7 products of the forward kinematics
//! already, so no earlier stop is safe), the elimination 26k.
//!
//! Session 18 (callgrind as above, the solver's core compiled with `rustc -O` in a harness that
//! calls `gen_solve` at the 64 poses): 218.6k to 204.4k per pose, the same 362 solutions
//! (within `5.2e-14`, largest residual `9.4e-15`); the C port bit for bit the Rust solver's
//! there. The same bits: `wrap` returns an angle already in `(−π, π]` without the remainder
//! (−2.3k), `lu` with comparisons for its largest entry and smallest pivot (−2.1k), the null
//! vector's `U` read with each pivot row's copy looked up once (−0.5k). The search's 32 base
//! evaluations four at a time (`core::grid_values`: `e^{ij(m + rπ/2)} = iʲʳ e^{ijm}`, the sums
//! by `j mod 4` at 8 midpoints; the same values to rounding, the same decisions; −1.5k). Each
//! root's bracket reads an end's sign from Taylor's formula at the interval's midpoint where
//! it is certified and evaluates only the others, and Halley's method starts from the zero of
//! the Taylor polynomial (`core::taylor_start`), one step and its check (−4.3k). The
//! refinement's normal matrix and gradient without the Jacobian's columns: joint `i`'s column
//! is `[w]× [F | t − p]`, so with `F` a rotation its rotation part gives `2 wi·wj` and `wi·u`,
//! `u = Σ_k f_k × e_k` (−3.6k; two solutions move in their last bits). Tried and
//! dropped: the samples' rows in pairs `(T0 + c T1) ± s T2` (the same bits, +0.6k: the LUs
//! inline worse), a library-free `atan2` (no gain: the library's is 4k per pose in all),
//! `block_lu` built in its result (+2k), the base sums class by class (+1.3k). Found: for the
//! bench arm the θ3-dependent parts of `S(θ)` (`T1`, `T2` stacked, 12 x 9) have rank 8, the
//! same kernel at every target (a column of monomials free of `θ3`), not used. Where the 204k
//! goes (inclusive): the determinant route 128k (18 sampled LUs 38.5k, back-substitution
//! 21.5k, the search and null vectors the rest), the refinement 43k (two forward
//! kinematics per root at about 2k each), the elimination 26k (the QR of `Bm` 13.6k). The
//! 157k of the 20 µs target is not reached.
//!
//! Session 19, the determinant route (callgrind as in session 18, the generated solver's core
//! compiled with `rustc -O` in a harness that solves the 64 bench poses): 204.8k to 195.4k per
//! pose, the same 362 solutions (largest change in any joint `2.7e-13`, largest residual
//! `9.8e-15`); the C port changed with it, bit for bit the Rust solver's on the 64 poses (GCC 12
//! `-O2`, the whole program: 570.8k to 549.9k per pose). The lead of a constant block in `S(θ)`
//! does not hold (see the determinant route above: the moving part of `S` has real rank 12).
//! Changes: `θ6` by turning one vector `u` back through joints 5 to 1 (Rodrigues on a vector,
//! no 3 x 3 products; joints 3 to 5 with the cosine and sine their bases have) (−3.2k); the
//! back-substitution's 27 basis products once (−0.6k); the Fourier sums on the samples at `±θ`
//! paired, half the products (−1.2k); the search's base grid eight values at a time (the grid
//! is symmetric and `D`'s cosine part even, its sine part odd: `core::grid_values`) (−2.1k);
//! the same bits: the LU's pivot searches with a running
//! largest (−1.4k), the null vector's back-solve by `U`'s blocks, structural zeros skipped
//! (−0.9k). Tried and dropped: `block_lu` taking its rows by value (+0.2k), the residual check's
//! rows side by side (+0.4k), the search's bounds `r^j / j!` once per interval or only when the
//! one before decided nothing (±0.1k). The JavaScript and Python ports are unchanged (their
//! solutions agree within the ports tests' tolerance).
//!
//! Session 19, the refinement and the elimination's setup (callgrind as above): 204.1k to
//! 190.9k per pose, the same 362 solutions (within `5.6e-14`, largest residual `9.5e-15`);
//! the C port bit for bit the Rust solver's there. The damped normal equations by Cholesky (a
//! Gram matrix plus a positive multiple of the identity: no pivoting; −4.8k, the same bits).
//! The forward kinematics on the joints' frames (`core::Chain`, once per solve): `E1(q1) ⋯
//! E6(q6) M = F1 Z(q1) L1 ⋯ Z(q6) L6` with the link transforms `Li = Fi⁻¹ Fi+1`, `L6 = F6⁻¹ M`
//! constants of the arm, so a joint is a turn of two columns and one product, and the product
//! so far is the next joint's frame, its current axis without work (−7k in three steps, with
//! Rodrigues joints prepared once on the way). The error's largest entry without a branch per
//! entry (−1.3k). Measured and not kept: `Bm`'s `Qᵀ` accumulated backwards from the kept
//! Householder vectors (−1.8k) and the right side's transform as two 1-D passes (−1.1k): their
//! new last bits move which spurious candidates of a nearly special arm (the PUMA with a 0.8 mm
//! shoulder offset) the refinement carries to within `2e-6` of an exact solution at a residual
//! near `1e-7`, kept as an approximate extra (3000 poses: 23,876 solutions, 76 approximate,
//! against 23,881 and 83), and at one pose of the ports test the reference then has two more
//! than the page's solver. The step accepted without its forward kinematics on a bound (the
//! linearised error plus `½ ‖δ‖₁² max(1, |t − pj|)` from the second derivatives `ξi ξj F`): at
//! most −2.9k, and only without a term for the forward kinematics' own rounding, which a
//! priori is about `3e-14` (seven products of rotations), above `EXACT_TOL`, so that with it the
//! check is almost never skipped; the residual stays measured. The cosines at the trial point
//! from the last ones turned by the step (+0.5k), the products four entries side by side and `Σ
//! = N Am` 27 sums side by side (the same code). One candidate (a local minimum at `5e-3`, two
//! of the 368) takes 35 trial steps of the 408. Where the 191k goes: the determinant route
//! 128k, the refinement 28.5k (plus the chain 1.7k), the elimination 29.8k (the QR of `Bm`
//! 13.6k).
//!
//! Session 20 (callgrind as above): 181.5k to 141.6k per pose, the same 362 solutions. The
//! arrangement tried first is chosen at the derivation ([`GeneralInfo::first`]): the bench's
//! skew 6R clusters roots of `θ3` (arrangement 0, the first that serves at the generic
//! target) at 7 of the 64 poses (5 give up, a flat cluster near `θ3 ≈ 4.2`; 2 leave the set
//! incomplete), each paying a second elimination (with a left side computed per target,
//! 23k) and eighteen more samples: those 7 poses cost 230k to 510k each, 18k per pose on
//! average. Reading the loop backwards (arrangement 6, hidden `θ4`, its left side a constant of
//! the arm too) no bench pose gives up: 176.3k to 141.6k, the solutions within `1.3e-12`
//! (the largest change at a pose with two solutions `0.06` rad apart), residuals at most
//! `1.0e-14`; at 5000 poses of the bench's generator the same 29,276 solutions, 93 of them
//! moved by more than `1e-12` (the six largest, `1.9e-11` to `1.2e-9`, at pairs of solutions
//! within `0.003` rad of each other, where the joints are that ill-conditioned; every residual
//! at most `1.0e-14` either way), and 182.2k to 145.4k per pose
//! at 1000 of them (test `det_tests::the_first_arrangement_avoids_the_skew_arms_clusters`).
//! The choice solves 32 poses per candidate at the derivation (the derivation's
//! arrangement, the other of 0 and 6) and keeps the derivation's unless the other serves
//! alone at more of them. Measured first arrangements on the bench (the whole solver): 0
//! 176.3k, 1 161.3k, 2 170.6k, 3 173.4k, 4 171.3k, 5 178.7k, 6 141.7k. The same bits,
//! before that (181.5k to 176.3k): the QR of `Bm` with every column's sums side by side (the
//! norms, the reflection's products, `Qᵀ` updated from the left in place, vectorised; the
//! first step's `Qᵀ` read off the identity) (−2.8k), `qr_pivot` and the refinement's
//! `forward` inlined (no `memcpy` of their results) (−1.8k), the elimination borrowed where
//! it is returned, not moved per arrangement (−0.7k). Tried and dropped: the complete
//! pivoting's largest entry searched after the row updates (+0.1k), `block_lu` built in its
//! result (+1.1k, as in session 18), `Arranged::left`'s transforms entry by entry without
//! zeroed arrays (+0.2k), `elim_from` taking the left side by reference (no change), the
//! cluster's fallback to arrangement 6 instead of 1 at arrangement 0 (−1.1k: dropped for
//! the choice at the derivation, which avoids the give-ups). Where the 141.6k goes
//! (inclusive): the 18 sampled LUs 34k, the elimination 21k (the QR of `Bm` about 10k), the
//! back-substitution 17k, the refinement 16k (two forward kinematics per root), the root
//! search, the null vectors and the rest about 54k.
//!
//! Session 20, repeats at a fold (`core::merge_repeats`, `core::FOLD_REACH`): a solution whose
//! residual `r` is above the rounding and that lies within `30 √r` of one of smaller residual
//! is dropped at the end of the solve (the approximate extras above, refined to `1e-7` within
//! `2e-6` of an exact solution, are such repeats). Callgrind as in session 18 (the generated
//! solver at the 64 bench poses, three rounds less one over 128): 181,369 to 181,408
//! instructions per pose, the same 362 solutions bit for bit; the 39 are the scan of the
//! residuals, every one within `EXACT_TOL` on the bench arm. Tried: the scan as a fold of all
//! 16 slots, the count of exact hits kept as they come, the slides' scaling skipped for a
//! revolute arm (each no better).

#[allow(clippy::many_single_char_names)]
pub(crate) mod apart;
#[cfg(test)]
mod apart_tests;
mod closure;
#[allow(clippy::many_single_char_names)]
pub(crate) mod core;
#[cfg(test)]
mod deflate_tests;
mod degree;
#[cfg(test)]
mod det_tests;
pub(crate) mod emit;
pub mod exact;
#[cfg(test)]
mod refine_tests;

use super::check::{self, AxisData};
use super::{IkSolution, NumSolution, TARGET_SYMBOLS};
use crate::kin::JointKind;

/// What the general method found about the arm.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GeneralInfo {
    /// The degree of the univariate polynomial reached at a generic target, counting the
    /// roots that move with the target (16 for a general 6R; special geometry lowers it), 0
    /// when no arrangement was usable there.
    pub degree: usize,
    /// The arrangement used at that target: `(reversed, shift)` (the loop read from joint
    /// `shift + 1`, backwards when `reversed`).
    pub arrangement: (bool, usize),
    /// The arrangement the numeric solvers try first, as the core numbers it (`shift + 6
    /// reversed`): the derivation's, or the other reading of the loop from joint 1 where that
    /// gives up less at sample targets.
    pub first: usize,
}

/// The most residual a candidate may keep and still be returned (flagged approximate): a
/// thousand times a pose tolerance of `1e-9`, so that a solution near a singular set, whose
/// refinement stalls at the residual over the distance to the set, is returned flagged rather
/// than dropped, while a root that is no solution (far off the pose) is dropped.
pub const KEEP_TOL: f64 = 1e-6;

/// Six joints, at least one revolute (the loop is read so that one ends it): the chains the
/// general method solves.
pub(crate) fn applies(axes: &[super::Axis]) -> bool {
    axes.len() == 6 && axes.iter().any(|a| a.kind == JointKind::Revolute)
}

/// Why the elimination is degenerate in every arrangement, when the kinds of the joints say so
/// (see the module docs): two slides three joints apart.
pub(crate) fn degenerate_reason(axes: &[super::Axis]) -> Option<String> {
    let slides: Vec<usize> = (0..axes.len())
        .filter(|&i| axes[i].kind == JointKind::Prismatic)
        .collect();
    let &[i, j] = slides.as_slice() else {
        return None;
    };
    (axes.len() == 6 && j - i == 3).then(|| {
        format!(
            "the slides {} and {} are three joints apart: every reading of the loop that ends \
             with a turn has one among the eliminated joints 1, 2 and the other among joints \
             4, 5; a slide's d^2 enters only p.p and (p.p) l - 2 (p.l) p, so at every target a \
             combination of the second slide's d^2 columns lies in the column space of Bm and \
             M(x) has a null vector at d = infinity for every x (det M = 0 identically)",
            axes[i].variable, axes[j].variable
        )
    })
}

fn tol() -> core::GenTol {
    core::GenTol {
        pose: check::POSE_TOL,
        keep: KEEP_TOL,
    }
}

/// Every solution for a numeric target: the reference solver of a general-method solution.
pub(crate) fn solve_numeric(
    sol: &IkSolution,
    target: &[[f64; 4]; 4],
    params: &[(&str, f64)],
) -> Result<Vec<NumSolution>, super::NumericError> {
    let env = |n: &str| params.iter().find(|(k, _)| *k == n).map(|(_, v)| *v);
    let (axes, home) = check::axis_data(sol, &env)?;
    let len = check::scale(&axes, &home, target);
    let first = sol.general.as_ref().map_or(0, |g| g.first);
    let (out, singular) = run(&axes, &home, target, len, first)?;
    Ok((0..out.n)
        .map(|i| NumSolution {
            q: out.q[i].to_vec(),
            singular: singular[i],
            approximate: out.residual[i] > check::POSE_TOL || out.residual[i].is_nan(),
            residual: out.residual[i],
        })
        .collect())
}

fn run(
    axes: &[AxisData],
    home: &[[f64; 4]; 3],
    target: &[[f64; 4]; 4],
    len: f64,
    first: usize,
) -> Result<(core::GenOut, [bool; core::GEN_MAX]), GeneralError> {
    let ax: [AxisData; 6] = axes
        .try_into()
        .map_err(|_| GeneralError::Joints(axes.len()))?;
    let mut singular = [false; core::GEN_MAX];
    let out = if apart(&ax) {
        apart::apart_solve(&ax, home, target, len, tol(), &mut singular)
    } else {
        core::gen_solve(&ax, home, target, len, tol(), first)
    };
    Ok((out, singular))
}

/// [`info`] of a 4R2P with its slides three joints apart: the first reading (forwards, then
/// backwards) whose resultant is usable at the generic target, and its degree
/// (`degree::apart_degree`).
fn apart_info(axes: &[AxisData], home: &[[f64; 4]; 3], t: &[[f64; 4]; 4], len: f64) -> GeneralInfo {
    let (js, g) = scaled(axes, home, t, len);
    let prismatic: [bool; 6] = std::array::from_fn(|i| js[i].prism);
    for arr in apart::apart_arrangements(&prismatic).unwrap_or_default() {
        let found = apart::ApartChain::new(core::Arranged::new(&js, &g, arr))
            .and_then(|ch| degree::apart_degree(&ch));
        if let Some(degree) = found {
            return GeneralInfo {
                degree,
                arrangement: (arr >= 6, arr % 6),
                first: arr,
            };
        }
    }
    GeneralInfo {
        degree: 0,
        arrangement: (false, 0),
        first: 0,
    }
}

/// Whether the joints make a 4R2P with its slides three joints apart (solved by [`apart`]).
pub(crate) fn apart_chain(axes: &[super::Axis]) -> bool {
    axes.len() == 6
        && apart::apart_arrangements(&std::array::from_fn(|i| {
            axes[i].kind == JointKind::Prismatic
        }))
        .is_some()
}

/// Whether the chain is a 4R2P with its slides three joints apart: solved by [`apart`] (the
/// elimination of `core.rs` is degenerate for it).
fn apart(ax: &[AxisData]) -> bool {
    ax.len() == 6 && apart::apart_arrangements(&std::array::from_fn(|i| ax[i][0] != 0.0)).is_some()
}

/// What the general method cannot solve.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum GeneralError {
    /// An arm that is not six joints.
    #[error("the general method needs 6 joints, not {0}")]
    Joints(usize),
    /// The arrangement's elimination is not usable at the target.
    #[error("no elimination")]
    NoElimination,
}

/// What [`sampled_equations`] could not do.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SampleError {
    /// A parameter without a value, or an entry that does not evaluate.
    #[error(transparent)]
    Input(#[from] super::NumericError),
    /// Not six joints, or no elimination at the target.
    #[error(transparent)]
    General(#[from] GeneralError),
}

/// The numeric core's sampled equations of arrangement `arr` (`shift + 6 reversed`) at a
/// numeric target: `(am, bm)` as [`exact::ExactEquations`] lays them out, with lengths back in
/// the robot's units (the core divides them by the arm's scale; a slide's coefficient of `d^j`
/// has `j` lengths less), a slide's entries in its basis `(1, d, d²)`. `bm` is read back from the
/// core's QR factors (`Bm = Q R Pᵀ`), so it carries their rounding too.
///
/// # Errors
/// A parameter without a value, or not six joints.
#[allow(clippy::type_complexity)]
pub fn sampled_equations(
    sol: &IkSolution,
    target: &[[f64; 4]; 4],
    params: &[(&str, f64)],
    arr: usize,
) -> Result<([[[f64; 9]; 3]; 14], [[f64; 8]; 14]), SampleError> {
    let env = |n: &str| params.iter().find(|(k, _)| *k == n).map(|(_, v)| *v);
    let (axes, home) = check::axis_data(sol, &env)?;
    if axes.len() != 6 {
        return Err(GeneralError::Joints(axes.len()).into());
    }
    let len = check::scale(&axes, &home, target);
    let (js, g) = scaled(&axes, &home, target, len);
    let ar = core::Arranged::new(&js, &g, arr % 12);
    let slides = ar.prismatic();
    let el = ar.elim().ok_or(GeneralError::NoElimination)?;
    let mut am = el.am;
    let mut bm = [[0.0; 8]; 14];
    for (j, &col) in el.piv.iter().enumerate() {
        for (e, row) in bm.iter_mut().enumerate() {
            row[col] = (0..8).map(|i| el.qt[i][e] * el.r[i][j]).sum();
        }
    }
    // A coefficient of `d^j` (a slide's variable, scaled in the core) has `j` lengths less.
    let power = |i: usize, k: usize| if slides[i] { k as i32 } else { 0 };
    for e in 0..14 {
        let k = |j: i32| len.powi(exact::LENGTH_DEGREE[e] - j);
        for (i3, row) in am[e].iter_mut().enumerate() {
            for (m, x) in row.iter_mut().enumerate() {
                *x *= k(power(2, i3) + power(3, m / 3) + power(4, m % 3));
            }
        }
        for (m, x) in bm[e].iter_mut().enumerate() {
            *x *= k(power(0, (m + 1) / 3) + power(1, (m + 1) % 3));
        }
    }
    Ok((am, bm))
}

/// The chain and the target `G = T M⁻¹` as the core takes them: lengths over `len`.
fn scaled(
    axes: &[AxisData],
    home: &[[f64; 4]; 3],
    target: &[[f64; 4]; 4],
    len: f64,
) -> ([core::J; 6], [[f64; 4]; 3]) {
    let js: [core::J; 6] = std::array::from_fn(|i| core::J {
        w: [axes[i][1], axes[i][2], axes[i][3]],
        c: [axes[i][4] / len, axes[i][5] / len, axes[i][6] / len],
        prism: axes[i][0] != 0.0,
    });
    let mut hm = *home;
    let mut tg = [[0.0; 4]; 3];
    tg.copy_from_slice(&target[..3]);
    for r in 0..3 {
        hm[r][3] /= len;
        tg[r][3] /= len;
    }
    (js, core::compose(&tg, &core::inverse(&hm)))
}

/// The degree reached and the arrangement at a generic target: the parameters at `0.55 +
/// 0.13 i` (as `check::step_degrees`), the target the pose at joint values `0.31 + 0.17 i`.
pub(crate) fn info(sol: &IkSolution) -> GeneralInfo {
    let none = GeneralInfo {
        degree: 0,
        arrangement: (false, 0),
        first: 0,
    };
    let vals: Vec<(String, f64)> = sol
        .params
        .iter()
        .enumerate()
        .map(|(i, p)| (p.clone(), 0.55 + 0.13 * i as f64))
        .collect();
    let env = |n: &str| vals.iter().find(|(k, _)| k == n).map(|(_, v)| *v);
    let Ok((axes, home)) = check::axis_data(sol, &env) else {
        return none;
    };
    // The generic target, and two more for the roots that stay (see `degree.rs`).
    let targets: Vec<[[f64; 4]; 4]> = [(0.31, 0.17), (0.53, -0.11), (-0.27, 0.19)]
        .iter()
        .map(|&(a, b)| {
            let q: Vec<f64> = (0..axes.len()).map(|i| a + b * i as f64).collect();
            let f = check::forward(&axes, &home, &q).0;
            let mut t = [[0.0; 4]; 4];
            t[..3].copy_from_slice(&f);
            t[3][3] = 1.0;
            t
        })
        .collect();
    let t = targets[0];
    let len = check::scale(&axes, &home, &t);
    if apart(&axes) {
        return apart_info(&axes, &home, &t, len);
    }
    match run(&axes, &home, &t, len, 0) {
        Ok((o, _)) if o.n_arr > 0 => {
            let arr = o.arrangements[0];
            let gs: Vec<[[f64; 4]; 3]> = targets
                .iter()
                .map(|t| scaled(&axes, &home, t, len).1)
                .collect();
            let js = scaled(&axes, &home, &t, len).0;
            let ars = degree::arranged(&js, &gs, arr);
            let moving = degree::moving_roots(&ars).unwrap_or(o.degree);
            // Of those, the ones that are solutions (`closure.rs`).
            let closing = degree::closing_roots(&ars[0]).unwrap_or(moving);
            GeneralInfo {
                degree: moving.min(closing),
                arrangement: (arr >= 6, arr % 6),
                first: first_arrangement(&axes, &home, arr),
            }
        }
        _ => none,
    }
}

/// How many sample targets [`first_arrangement`] solves at.
const FIRST_SAMPLES: usize = 32;

/// The arrangement the numeric solvers try first: the derivation's `arr`, or the other of the
/// arrangements whose left side is a constant of the arm (the loop read from joint 1, forwards
/// or backwards: `core::left_is_constant`, computed once per arm) when its determinant route
/// alone gives the whole solution set at more of [`FIRST_SAMPLES`] sample targets (poses of
/// configurations from a fixed sequence). Each target where the first arrangement gives up (a
/// cluster of roots of its hidden joint) or leaves the set incomplete costs the solver another
/// elimination and its eighteen samples; which hidden joint clusters is a property of the arm
/// (the bench's skew 6R: `θ3` at about one pose in ten, `θ4` not).
fn first_arrangement(axes: &[AxisData], home: &[[f64; 4]; 3], arr: usize) -> usize {
    let mut id = [[0.0; 4]; 4];
    for (i, row) in id.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    id[..3].copy_from_slice(home);
    let len0 = check::scale(axes, home, &id);
    // A small deterministic generator (xorshift) for the configurations: angles in (−π, π),
    // slides within half the arm's size.
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let targets: Vec<[[f64; 4]; 4]> = (0..FIRST_SAMPLES)
        .map(|_| {
            let q: Vec<f64> = axes
                .iter()
                .map(|a| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    let u = (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
                    if a[0] != 0.0 {
                        0.5 * len0 * u
                    } else {
                        std::f64::consts::PI * u
                    }
                })
                .collect();
            let mut t = id;
            t[..3].copy_from_slice(&check::forward(axes, home, &q).0);
            t
        })
        .collect();
    let (js, g) = scaled(
        axes,
        home,
        &targets[0],
        check::scale(axes, home, &targets[0]),
    );
    let clean = |first: usize| {
        targets
            .iter()
            .filter(|t| {
                let len = check::scale(axes, home, t);
                matches!(run(axes, home, t, len, first),
                    Ok((o, _)) if o.n_arr == 1 && o.arrangements[0] == first)
            })
            .count()
    };
    let mut best = (arr, clean(arr));
    for other in [0, 6] {
        // (None is better than one that serves alone at every sample.)
        if best.1 == FIRST_SAMPLES {
            break;
        }
        if other != arr && core::left_is_constant(&core::Arranged::new(&js, &g, other), other) {
            let n = clean(other);
            if n > best.1 {
                best = (other, n);
            }
        }
    }
    best.0
}

/// What the exact equations cover, in words: the arrangement they are derived for, and the
/// step that leaves exact arithmetic.
pub fn exact_scope_text(sol: &IkSolution, eq: &exact::ExactEquations) -> String {
    let first = sol.variables.get(eq.order[0]).map_or("?", String::as_str);
    let dir = if eq.arrangement.0 {
        "backwards"
    } else {
        "forwards"
    };
    let used = sol.general.as_ref().map_or((false, 0), |g| g.arrangement);
    let note = if used.1 == 0 {
        String::new()
    } else {
        format!(
            "; at a generic target the solver reads the loop from {} instead (this arrangement is degenerate for the arm)",
            used_first(sol, used)
        )
    };
    format!(
        "the loop read {dir} from {first}{note}; Am, Bm and the half-angle polynomials P are exact in the parameters and the target's entries; the left null space N of Bm is computed per target in f64 (Householder QR), so A, B, C = N P (12 x 12) are numeric"
    )
}

fn used_first(sol: &IkSolution, (rev, shift): (bool, usize)) -> String {
    let k = if rev { 5 - shift } else { shift };
    sol.variables.get(k).cloned().unwrap_or_default()
}

/// Whether the hidden joint (arranged joint 3, whose variable the polynomial is in) slides in
/// the arrangement of `info`.
pub fn hidden_slides(sol: &IkSolution, info: &GeneralInfo) -> bool {
    let (rev, shift) = info.arrangement;
    let k = (shift + 2) % 6;
    let k = if rev { 5 - k } else { k };
    sol.axes
        .get(k)
        .is_some_and(|a| a.kind == JointKind::Prismatic)
}

/// The elimination in words, one line each (the report and the walkthrough).
pub fn elimination_lines(sol: &IkSolution, info: &GeneralInfo) -> Vec<String> {
    if apart_chain(&sol.axes) {
        return apart_lines(sol, info);
    }
    let v = &sol.variables;
    let (rev, shift) = info.arrangement;
    let arm = |i: usize| {
        let k = (shift + i) % 6;
        if rev {
            5 - k
        } else {
            k
        }
    };
    let order: Vec<&str> = (0..6)
        .map(|i| v.get(arm(i)).map_or("?", String::as_str))
        .collect();
    let slides: Vec<bool> = (0..6)
        .map(|i| {
            sol.axes
                .get(arm(i))
                .is_some_and(|a| a.kind == JointKind::Prismatic)
        })
        .collect();
    if slides.iter().any(|p| *p) {
        return prismatic_lines(info, &order, &slides, rev);
    }
    let t = TARGET_SYMBOLS
        .iter()
        .flatten()
        .copied()
        .collect::<Vec<_>>()
        .join(" ");
    let mut out = vec![
        format!(
            "loop read as {} (joint order{}), target G = T M^-1 from {t}",
            order.join(", "),
            if rev { ", reversed" } else { "" }
        ),
        format!(
            "1. E({}) E({}) E({}) (p, w) = E({})^-1 E({})^-1 G (p, w) for a point p and the direction w of the axis of {}: {} eliminated",
            order[2], order[3], order[4], order[1], order[0], order[5], order[5]
        ),
        "2. the 14 Raghavan-Roth quantities of both sides: l, p, p.p, p.l, p x l, (p.p) l - 2 (p.l) p; each of degree one in the sine and cosine of every joint: Bm X12 = Am X45".into(),
        format!(
            "   X12 = (1, c, s)({}) x (1, c, s)({}) without 1 (8 monomials), X45 = (1, c, s)({}) x (1, c, s)({}) (9), Am linear in (1, c, s)({})",
            order[0], order[1], order[3], order[4], order[2]
        ),
        "3. the left null space N of Bm (14 x 8, Householder QR in f64 at the numeric target: where exact arithmetic stops; Am, Bm and the half-angle polynomials are exact): 6 equations N Am X45 = 0".into(),
        format!(
            "4. half-angle tangents of {} and {}, and the same equations times x({}): M(x) X = 0, M(x) = A x^2 + B x + C (12 x 12), x = tan(({} - phi)/2)",
            order[3], order[4], order[3], order[2]
        ),
        format!(
            "5. det M(x) = 0: degree 24 with the spurious factor (1 + x^2)^4; degree reached at a generic target: {} (det M / (1 + x^2)^12 is a trigonometric polynomial of degree 8 in the angle: 17 samples, its real roots by a certified interval search; the eigenvalues of the 24 x 24 companion matrix where that search gives up)",
            info.degree
        ),
        format!(
            "6. back-substitution: {}, {} from the null vector of M(x); {}, {} from Bm X12 = Am X45; {} from E({})^-1 ... E({})^-1 G; each solution refined by Gauss-Newton and checked by forward kinematics",
            order[3], order[4], order[0], order[1], order[5], order[4], order[0]
        ),
        "special geometry (a degenerate arrangement, a double root) reads the loop from another joint".into(),
    ];
    if info.degree == 0 {
        out.push("no arrangement was usable at the generic target".into());
    }
    out
}

/// [`elimination_lines`] for a chain with prismatic joints: a slide's variable `d` enters the
/// quantities through `(1, d, d²)` where a turn's enters through `(1, cos, sin)`.
fn prismatic_lines(info: &GeneralInfo, order: &[&str], slides: &[bool], rev: bool) -> Vec<String> {
    let basis = |i: usize| {
        let b = if slides[i] {
            "(1, d, d^2)"
        } else {
            "(1, c, s)"
        };
        format!("{b}({})", order[i])
    };
    let tangent = |i: usize| {
        if slides[i] {
            format!("x({0}) = {0}", order[i])
        } else {
            format!("x({0}) = tan({0}/2)", order[i])
        }
    };
    let hidden = if slides[2] {
        format!("{} = (t + x)/(1 - t x), t = tan(phi/2)", order[2])
    } else {
        format!("x = tan(({} - phi)/2)", order[2])
    };
    let spurious = if slides[2] {
        format!("the roots at {} = infinity", order[2])
    } else {
        "the spurious factor (1 + x^2)^4".into()
    };
    let mut out = vec![
        format!(
            "loop read as {} (joint order{}; the last joint turns), target G = T M^-1",
            order.join(", "),
            if rev { ", reversed" } else { "" }
        ),
        format!(
            "1. E({}) E({}) E({}) (p, w) = E({})^-1 E({})^-1 G (p, w) for a point p and the direction w of the axis of {}: {} eliminated",
            order[2], order[3], order[4], order[1], order[0], order[5], order[5]
        ),
        "2. the 14 Raghavan-Roth quantities of both sides: l, p, p.p, p.l, p x l, (p.p) l - 2 (p.l) p; each of degree one in the sine and cosine of every revolute joint, of degree two in the length d of every prismatic one (a slide by d w adds 2 d w.p + d^2 to p.p): Bm X12 = Am X45".into(),
        format!(
            "   X12 = {} x {} without 1 (8 monomials), X45 = {} x {} (9), Am linear in {}",
            basis(0), basis(1), basis(3), basis(4), basis(2)
        ),
        "3. the left null space N of Bm (14 x 8, Householder QR in f64 at the numeric target): 6 equations N Am X45 = 0".into(),
        format!(
            "4. {}, {}, and the same equations times x({}): M(x) X = 0, M(x) = A x^2 + B x + C (12 x 12), {hidden}",
            tangent(3), tangent(4), order[3]
        ),
        format!(
            "5. det M(x) = 0: degree 24 with {spurious}; degree reached at a generic target: {} (known bounds: 16 for 5R1P, 8 for 4R2P, 2 for 3R3P)",
            info.degree
        ),
        format!(
            "6. back-substitution: {}, {} from the null vector of M(x); {}, {} from Bm X12 = Am X45 (a slide's d is its monomial); {} from E({})^-1 ... E({})^-1 G; each solution refined by Gauss-Newton and checked by forward kinematics",
            order[3], order[4], order[0], order[1], order[5], order[4], order[0]
        ),
        "special geometry (a degenerate arrangement, a double root) reads the loop from another joint that turns".into(),
    ];
    if info.degree == 0 {
        out.push("no arrangement was usable at the generic target".into());
    }
    out
}

/// [`elimination_lines`] for a 4R2P with its slides three joints apart (`apart.rs`).
fn apart_lines(sol: &IkSolution, info: &GeneralInfo) -> Vec<String> {
    let (rev, shift) = info.arrangement;
    let order: Vec<&str> = (0..6)
        .map(|i| {
            let k = (shift + i) % 6;
            let k = if rev { 5 - k } else { k };
            sol.variables.get(k).map_or("?", String::as_str)
        })
        .collect();
    let o = |i: usize| order[i];
    let mut out = vec![
        format!(
            "loop read as {} (joint order{}; slides {} and {} three joints apart: the Raghavan-Roth elimination is degenerate for them), target G = T M^-1",
            order.join(", "),
            if rev { ", reversed" } else { "" },
            o(0),
            o(3)
        ),
        format!(
            "1. orientation: slides turn nothing, so R({}) R({}) = R_G R({})^T R({})^T =: Q; R({}) keeps w({}) and R({}) keeps w({}): F = w({}) . Q w({}) - w({}) . w({}) = 0, of degree one in the sine and cosine of {} and of {}",
            o(1), o(2), o(5), o(4), o(1), o(1), o(2), o(2), o(1), o(2), o(1), o(2), o(4), o(5)
        ),
        format!(
            "2. position: moved past the turns the slides add {} v + {} Q v', so P = det(v, Q v', g - t(E({}) E({}) E({}) E({}))) = 0, with cos, sin of {} from subproblem 1 (linear in Q): of degree two in each of {}, {}",
            o(0), o(3), o(1), o(2), o(4), o(5), o(1), o(4), o(5)
        ),
        format!(
            "3. the Sylvester resultant of (1 + x^2) F and (1 + x^2)^2 P in x = tan({}/2): D({}), a trigonometric polynomial of degree at most 8 (17 samples, its real roots by a certified interval search); degree reached at a generic target: {} (the roots where the common x is +-i are no solutions)",
            o(5), o(4), info.degree
        ),
        format!(
            "4. back-substitution: {} from F = 0 where P vanishes; {}, {} by subproblem 1; {}, {} by least squares (singular where the slides' current directions are parallel); each solution refined by Gauss-Newton and checked by forward kinematics",
            o(5), o(1), o(2), o(0), o(3)
        ),
        "a double root (two solutions sharing the hidden joint) reads the loop backwards too".into(),
    ];
    if info.degree == 0 {
        out.push("no reading was usable at the generic target".into());
    }
    out
}
