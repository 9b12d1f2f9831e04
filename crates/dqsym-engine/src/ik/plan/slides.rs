//! Three turns and three slides (3R3P), the slides anywhere in the chain: the orientation from
//! the turns alone, then the slides from a linear system.
//!
//! # The derivation
//!
//! In the product of exponentials `E1 ⋯ E6 = G = T M⁻¹` a slide is a translation `Tr(dᵢ vᵢ)`
//! along its home direction `vᵢ` and turns nothing. A turn `E = Tr(p) R Tr(−p)` moves a
//! translation past itself as `E Tr(v) = Tr(R v) E`, so every slide can be moved to the front:
//!
//! `E1 ⋯ E6 = Tr(Σᵢ dᵢ uᵢ) Eₐ E_b E_c`, `uᵢ = R_{<i} vᵢ`,
//!
//! with `a < b < c` the turns and `R_{<i}` the product of the rotations of the turns before
//! slide `i` (in chain order). Hence:
//!
//! 1. Orientation: `Rₐ R_b R_c = R_G`, three turns about constant home directions `wₐ`, `w_b`,
//!    `w_c` (a wrist, wherever the turns sit). `Rₐ` keeps `wₐ` and `R_c` keeps `w_c`, so
//!    `wₐ · R_b w_c = wₐ · R_G w_c`: subproblem 4, `a cos θ_b + b sin θ_b = c`, at most two
//!    roots (degree 2, the known bound for 3R3P); then `θₐ` turns `R_b w_c` onto `R_G w_c`
//!    and `θ_c` a normal of `w_c` onto `R_bᵀ Rₐᵀ R_G` of it (subproblem 1, `atan2` each).
//!    Degenerate for every target where `w_b` is parallel to `wₐ` or `w_c` (two turns about one
//!    direction: the turns reach a two-parameter family of orientations only): refused.
//! 2. Position: with `p_c` a point of axis `c` (`E_c p_c = p_c`), `G p_c = Σ dᵢ uᵢ + Eₐ E_b
//!    p_c`, three linear equations `U d = r`, `r = G p_c − Eₐ E_b p_c`, `U = (u₁ u₂ u₃)`,
//!    whose entries are polynomials in the sines and cosines of the turns solved in step 1.
//!    By Cramer's rule `det U · dᵢ = det Uᵢ(r)` ([`Formula::Linear`]). `det U` is
//!    dimensionless (unit directions) and `det Uᵢ(r)` a length. Both are written in the frame
//!    of the first slide (`R_{<i₁}ᵀ` applied to every column, which leaves the determinants
//!    unchanged and makes `u₁ = v₁` constant). `det U = 0` where the slides' current
//!    directions fail to span space: a continuum or nothing, the singular set of the step;
//!    `det U ≡ 0` (three slides along coplanar directions whatever the turns) is refused.
//!
//! So a 3R3P arm has at most two solutions, each exact: two branches of `θ_b`, one value of
//! every other joint.

use super::*;

/// Exactly three turns and three slides.
pub(super) fn applies(ax: &[Axis]) -> bool {
    ax.len() == 6
        && ax.iter().filter(|a| a.kind == JointKind::Prismatic).count() == 3
        && ax.iter().filter(|a| a.kind == JointKind::Revolute).count() == 3
}

/// The steps of a 3R3P arm (see the module docs); the family in words.
pub(super) fn three_slides(b: &mut Builder, t: &Target) -> Result<Phrase, PlanError> {
    let ax = b.axes;
    let turns: Vec<usize> = (0..6)
        .filter(|&i| ax[i].kind == JointKind::Revolute)
        .collect();
    let slides: Vec<usize> = (0..6)
        .filter(|&i| ax[i].kind == JointKind::Prismatic)
        .collect();
    let (ia, ib, ic) = (turns[0], turns[1], turns[2]);
    let (wa, wc) = (&ax[ia].dir, &ax[ic].dir);
    let n = |i: usize| i + 1;
    if parallel(&ax[ia], &ax[ib]) || parallel(&ax[ib], &ax[ic]) {
        return Err(PlanError::Degenerate {
            variable: ax[ib].variable.clone(),
            method: "two consecutive turns about parallel axes: the three turns reach only a \
                     two-parameter set of orientations"
                .into(),
        });
    }
    let gwc = t.dir(wc);
    b.push(
        ib,
        sp4(wa, &ax[ib], wc, &dot(wa, &gwc)),
        Phrase::new(
            "subproblem 4 (height): slides turn nothing, so the turns alone give the \
             orientation, R{0} R{1} R{2} = R; joint {0} keeps k{0} and joint {2} keeps k{2}, so \
             k{0}·Rot(axis {1}, theta) k{2} = k{0}·(R k{2})",
            &[n(ia), n(ib), n(ic)],
        ),
        Some(WRIST),
        Phrase::new(
            "radicand zero (the two orientations of the turns merge): axes {0} and {1} in line \
             after the turns",
            &[n(ia), n(ic)],
        ),
    )?;
    b.push(
        ia,
        sp1(&ax[ia], &ax[ib].move_dir(wc, 1), &gwc),
        Phrase::new(
            "subproblem 1 (rotation): joint {0} turns Rot(axis {1}) k{2} onto R k{2}",
            &[n(ia), n(ib), n(ic)],
        ),
        None,
        Phrase::new(
            "axes {0} and {1} in line after the turns: only theta{0} + theta{1} is fixed; \
             theta{0} = 0 is returned",
            &[n(ia), n(ic)],
        ),
    )?;
    let e = perpendicular(wc);
    let v = ax[ib].move_dir(&ax[ia].move_dir(&t.dir(&e), -1), -1);
    b.push(
        ic,
        sp1(&ax[ic], &e, &v),
        Phrase::new(
            "subproblem 1 (rotation): joint {2} turns a vector normal to axis {2} onto R{1}ᵀ \
             R{0}ᵀ R of it",
            &[n(ia), n(ib), n(ic)],
        ),
        None,
        "never",
    )?;
    slide_steps(b, t, &turns, &slides)?;
    Ok(Phrase::new(
        "3R3P: three turns ({0}, {1}, {2}) and three slides ({3}, {4}, {5}); the turns alone \
         give the orientation (a three-axis wrist, two solutions), then the slides the \
         position by a linear system (Cramer's rule)",
        &[
            n(ia),
            n(ib),
            n(ic),
            n(slides[0]),
            n(slides[1]),
            n(slides[2]),
        ],
    ))
}

/// `R_{<k}ᵀ v`: the inverse rotations of the turns before joint `k` applied to `v` (the first
/// turn's inverse first).
fn back_to(ax: &[Axis], turns: &[usize], k: usize, v: &V3) -> V3 {
    turns
        .iter()
        .filter(|&&j| j < k)
        .fold(v.clone(), |v, &j| ax[j].move_dir(&v, -1))
}

/// The rotations of the turns between joints `from` and `k` applied to `v` (the last one
/// first): `R_{(from, k)} v`.
fn forward_between(ax: &[Axis], turns: &[usize], from: usize, k: usize, v: &V3) -> V3 {
    turns
        .iter()
        .rev()
        .filter(|&&j| j > from && j < k)
        .fold(v.clone(), |v, &j| ax[j].move_dir(&v, 1))
}

/// The three slides by Cramer's rule in the frame of the first slide (see the module docs).
fn slide_steps(
    b: &mut Builder,
    t: &Target,
    turns: &[usize],
    slides: &[usize],
) -> Result<(), PlanError> {
    let ax = b.axes;
    let (ia, ib, ic) = (turns[0], turns[1], turns[2]);
    let first = slides[0];
    let pc = &ax[ic].point;
    let reach = sub(
        &t.point(pc),
        &ax[ia].move_point(&ax[ib].move_point(pc, 1), 1),
    );
    let r = back_to(ax, turns, first, &reach);
    let u: Vec<V3> = slides
        .iter()
        .map(|&k| forward_between(ax, turns, first, k, &ax[k].dir))
        .collect();
    let det = |x: &V3, y: &V3, z: &V3| dot(x, &cross(y, z));
    let d = det(&u[0], &u[1], &u[2]);
    let nums = [
        det(&r, &u[1], &u[2]),
        det(&u[0], &r, &u[2]),
        det(&u[0], &u[1], &r),
    ];
    let n = |i: usize| i + 1;
    for (k, num) in nums.into_iter().enumerate() {
        b.push(
            slides[k],
            Formula::Linear {
                a: d.clone(),
                b: num,
            },
            Phrase::new(
                "linear (Cramer's rule): moved past the turns, the slides add d{0} u{0} + d{1} \
                 u{1} + d{2} u{2} (u the slides' current directions) to the position the turns \
                 give a point of axis {3}: det(u{0} u{1} u{2}) d{4} = det(u{0} u{1} u{2} with u{4} \
                 replaced by G p{3} − E{5} E{6} p{3})",
                &[
                    n(slides[0]),
                    n(slides[1]),
                    n(slides[2]),
                    n(ic),
                    n(slides[k]),
                    n(ia),
                    n(ib),
                ],
            ),
            None,
            Phrase::new(
                "the slides' current directions u{0}, u{1}, u{2} coplanar (det = 0): a line of \
                 solutions or none",
                &[n(slides[0]), n(slides[1]), n(slides[2])],
            ),
        )?;
    }
    Ok(())
}
