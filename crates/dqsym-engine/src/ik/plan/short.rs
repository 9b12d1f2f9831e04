//! Arms of fewer than six joints, solved for what they reach: a base joint with three
//! parallel pitch joints (position and one angle), and five joints with a two-axis wrist
//! (position and approach axis).

use super::*;

/// Axis 1, then axes 2, 3, 4 parallel to one another and not to axis 1, none two on one line.
pub(super) fn pitch_arm_axes(ax: &[Axis]) -> bool {
    let apart =
        |a: &Axis, b: &Axis| !matches!(relation(a, b), Relation::Parallel { same_line: true });
    revolute(ax)
        && !parallel(&ax[0], &ax[1])
        && parallel(&ax[1], &ax[2])
        && parallel(&ax[1], &ax[3])
        && apart(&ax[1], &ax[2])
        && apart(&ax[2], &ax[3])
}

/// A base joint and three parallel pitch joints (an AL5D): the reach is the position and the
/// angle about the pitch axes. Joint 1 from the direction of the pitch axes, joints 3 and 2 a
/// planar 2R to axis 4's place, joint 4 the rest of the angle.
pub(super) fn pitch_arm(b: &mut Builder, t: &Target) -> Result<(), PlanError> {
    let ax = b.axes;
    let k = &ax[1].dir;
    b.reach = Reach::PositionAndAngle {
        axes: vec![2, 3, 4],
    };
    // The position alone leaves theta1 and theta1 + pi (the arm reaching over backwards),
    // only one of which turns the pitch axes as the target does: theta1 is read from the
    // direction of the pitch axes, R k2 = Rot(axis 1, theta1) k2.
    b.push(
        0,
        sp1(&ax[0], k, &t.dir(k)),
        "subproblem 1 (rotation): rotations about the parallel axes 2, 3, 4 keep their \
         direction, so joint 1 turns k2 onto R k2"
            .into(),
        None,
        "never (the pitch axes are not parallel to axis 1)",
    )?;
    let x4 = ax[3].point.clone();
    // Joint 4 keeps the points of its axis: G x4 = E1 E2 E3 x4.
    let q = ax[0].move_point(&t.point(&x4), -1);
    super::elbow_steps(b, &x4, &q)?;
    let e = perpendicular(&ax[3].dir);
    let v = ax[2].move_dir(&ax[1].move_dir(&ax[0].move_dir(&t.dir(&e), -1), -1), -1);
    b.push(
        3,
        sp1(&ax[3], &e, &v),
        "subproblem 1 (rotation): joint 4 completes the angle, R4 = R3ᵀ R2ᵀ R1ᵀ R".into(),
        None,
        "never",
    )
}

/// Five joints: a position group (joints 1-3 as in a spherical-wrist arm) and a two-axis
/// wrist (axes 4 and 5 meeting at W). The reach is the position and the approach axis: the
/// direction `e` from W to the end's origin (the end frame's z axis when the origin is W),
/// which the wrist turns with two joints; the turn about it is not controlled.
pub(super) fn five_joints(
    b: &mut Builder,
    t: &Target,
) -> Result<Option<(Phrase, bool)>, PlanError> {
    let ax = b.axes;
    let (a4, a5) = (&ax[3], &ax[4]);
    if !revolute(&ax[3..5]) || parallel(a4, a5) || relation(a4, a5) != Relation::Intersecting {
        return Ok(None);
    }
    let Some(w) = intersection(a4, a5) else {
        return Ok(None);
    };
    let from_w = sub(&t.tm, &w);
    let e = if is_zero3(&from_w) {
        std::array::from_fn(|i| t.rm[i][2].clone())
    } else {
        from_w
    };
    if is_zero3(&cross(&e, &a5.dir)) {
        return Ok(None);
    }
    let Some(pos) = spherical_position(b, t, &w)? else {
        return Ok(None);
    };
    let back = |v: &V3| -> V3 {
        let v = ax[0].move_dir(&t.dir(v), -1);
        let v = ax[1].move_dir(&v, -1);
        ax[2].move_dir(&v, -1)
    };
    let v = back(&e);
    b.push(
        4,
        sp4(&a4.dir, a5, &e, &dot(&a4.dir, &v)),
        "subproblem 2, first half (subproblem 4): joint 4 keeps the approach's component along \
         axis 4, k4·Rot(axis 5, theta) e = k4·(R3ᵀ R2ᵀ R1ᵀ R e)"
            .into(),
        Some(WRIST),
        "radicand zero (the two wrist branches merge)",
    )?;
    b.push(
        3,
        sp1(a4, &a5.move_dir(&e, 1), &v),
        "subproblem 2, second half (subproblem 1): joint 4 turns the approach onto the target's"
            .into(),
        None,
        "the approach along axis 4: any theta4, 0 is returned",
    )?;
    // The approach in the end frame's own coordinates: R_Mᵀ e.
    b.reach = Reach::PositionAndApproach {
        approach: Target::mat_t(&t.rm, &e),
    };
    Ok(Some((
        Phrase::text(
            "5 joints, a two-axis wrist (axes 4 and 5 intersect) reaching a position and an \
             approach axis: {p}",
        )
        .with_inner(pos),
        false,
    )))
}
