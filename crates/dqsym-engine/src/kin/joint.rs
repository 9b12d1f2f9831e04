//! Revolute and prismatic joints in three conventions: classic DH, modified DH, screw.

use super::dh::{dh_link, dh_link_matrix, mdh_link, mdh_link_matrix};
use crate::algebra::{neg3, scale3};
use crate::{DualQuat, Matrix4, Quat, Ring};

/// Whether the joint variable is an angle or a length. A robot file's joint `type`:
/// `"revolute"` or `"prismatic"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    /// The joint variable is an angle (added to `θ`, or the rotation about the screw axis).
    Revolute,
    /// The joint variable is a length (added to `d`, or the slide along the screw axis).
    Prismatic,
}

/// Where a joint sits and how it moves, in one of three conventions.
///
/// The DH parameters hold the constant part of the link; the joint variable is added to
/// `theta` (revolute) or `d` (prismatic). A screw joint instead gives its axis in the home
/// pose of the whole chain, in base coordinates (product-of-exponentials style, as the
/// paper's sec 6 builds `q_d1 … q_d6`).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum JointGeometry<T> {
    /// Classic DH link `Rz(θ) Tz(d) Tx(a) Rx(α)`.
    Dh {
        /// Joint angle (offset, for a revolute joint).
        theta: T,
        /// Link offset (offset, for a prismatic joint).
        d: T,
        /// Link length.
        a: T,
        /// Link twist.
        alpha: T,
    },
    /// Craig's modified DH link `Rx(α) Tx(a) Rz(θ) Tz(d)`.
    Mdh {
        /// Link twist `α_{i−1}`.
        alpha: T,
        /// Link length `a_{i−1}`.
        a: T,
        /// Joint angle `θ_i` (offset, for a revolute joint).
        theta: T,
        /// Link offset `d_i` (offset, for a prismatic joint).
        d: T,
    },
    /// A line with unit direction `axis` through `point`, in the chain's home pose.
    /// A revolute joint rotates about it; a prismatic joint slides along `axis` (the point
    /// then does not matter).
    Screw {
        /// Unit direction of the joint axis.
        axis: [T; 3],
        /// A point on the joint axis.
        point: [T; 3],
    },
    /// A URDF joint as written: the constant frames from the previous joint's frame to this
    /// joint's (each `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)`, in order), then a rotation about
    /// (or a slide along) the unit direction `axis` through the origin of the joint's own
    /// frame. The frames stay a factor of this joint: nothing carries an axis to the base, so
    /// a chain of frames at symbolic angles is never multiplied out (each angle would double
    /// the terms of every later axis).
    Local {
        /// The origin frames `(xyz, [roll, pitch, yaw])`, in order.
        frames: Vec<LocalFrame<T>>,
        /// Unit direction of the joint axis, in the joint's frame.
        axis: [T; 3],
    },
}

/// A constant frame of a [`JointGeometry::Local`] joint: `(xyz, [roll, pitch, yaw])`, the
/// motion `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)`.
pub type LocalFrame<T> = ([T; 3], [T; 3]);

/// The frame `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` as a unit DQ.
pub fn local_frame_dq<T: Ring>((xyz, rpy): &LocalFrame<T>) -> DualQuat<T> {
    let (o, l) = (T::zero(), T::one());
    let rx = Quat::rotation(&[l.clone(), o.clone(), o.clone()], &rpy[0]);
    let ry = Quat::rotation(&[o.clone(), l.clone(), o.clone()], &rpy[1]);
    let rz = Quat::rotation(&[o.clone(), o, l], &rpy[2]);
    DualQuat::from_rotation_and_translation(rz * ry * rx, xyz)
}

/// The frame `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` as a product of elementary matrices.
pub fn local_frame_matrix<T: Ring>((xyz, rpy): &LocalFrame<T>) -> Matrix4<T> {
    Matrix4::trans(xyz)
        * Matrix4::rot_z(&rpy[2])
        * Matrix4::rot_y(&rpy[1])
        * Matrix4::rot_x(&rpy[0])
}

/// A one-degree-of-freedom joint: its kind and its geometry.
///
/// # Laws
/// For every joint variable `q`, `joint.dq(q).to_matrix() = joint.matrix(q)` (up to the
/// scalar's rounding) and `joint.dq(q)` is a unit dual quaternion (for a unit screw axis).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Joint<T> {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// The convention and the constant parameters.
    pub geometry: JointGeometry<T>,
}

impl<T: Ring> Joint<T> {
    /// A joint of the given kind and geometry.
    pub fn new(kind: JointKind, geometry: JointGeometry<T>) -> Self {
        Joint { kind, geometry }
    }

    /// A revolute classic-DH joint; `theta` is the angle offset added to the variable.
    pub fn revolute_dh(theta: T, d: T, a: T, alpha: T) -> Self {
        Joint::new(
            JointKind::Revolute,
            JointGeometry::Dh { theta, d, a, alpha },
        )
    }

    /// A prismatic classic-DH joint; `d` is the offset added to the variable.
    pub fn prismatic_dh(theta: T, d: T, a: T, alpha: T) -> Self {
        Joint::new(
            JointKind::Prismatic,
            JointGeometry::Dh { theta, d, a, alpha },
        )
    }

    /// A revolute modified-DH joint; `theta` is the angle offset added to the variable.
    pub fn revolute_mdh(alpha: T, a: T, theta: T, d: T) -> Self {
        Joint::new(
            JointKind::Revolute,
            JointGeometry::Mdh { alpha, a, theta, d },
        )
    }

    /// A prismatic modified-DH joint; `d` is the offset added to the variable.
    pub fn prismatic_mdh(alpha: T, a: T, theta: T, d: T) -> Self {
        Joint::new(
            JointKind::Prismatic,
            JointGeometry::Mdh { alpha, a, theta, d },
        )
    }

    /// A revolute joint about the line through `point` with unit direction `axis`.
    pub fn revolute_screw(axis: [T; 3], point: [T; 3]) -> Self {
        Joint::new(JointKind::Revolute, JointGeometry::Screw { axis, point })
    }

    /// A prismatic joint sliding along the unit direction `axis`.
    pub fn prismatic_screw(axis: [T; 3]) -> Self {
        let point = [T::zero(), T::zero(), T::zero()];
        Joint::new(JointKind::Prismatic, JointGeometry::Screw { axis, point })
    }

    /// `(θ, d)` of a DH link with the joint variable `q` added to the right one.
    fn theta_d(&self, theta: &T, d: &T, q: &T) -> (T, T) {
        match self.kind {
            JointKind::Revolute => (theta.clone() + q, d.clone()),
            JointKind::Prismatic => (theta.clone(), d.clone() + q),
        }
    }

    /// The motion of the joint at variable `q`, as a unit dual quaternion.
    pub fn dq(&self, q: &T) -> DualQuat<T> {
        match &self.geometry {
            JointGeometry::Dh { theta, d, a, alpha } => {
                let (theta, d) = self.theta_d(theta, d, q);
                dh_link(&theta, &d, a, alpha)
            }
            JointGeometry::Mdh { alpha, a, theta, d } => {
                let (theta, d) = self.theta_d(theta, d, q);
                mdh_link(alpha, a, &theta, &d)
            }
            JointGeometry::Screw { axis, point } => match self.kind {
                JointKind::Revolute => DualQuat::rotation_about_point(axis, q, point),
                JointKind::Prismatic => DualQuat::translation(&scale3(q, axis)),
            },
            JointGeometry::Local { frames, axis } => {
                let motion = match self.kind {
                    JointKind::Revolute => DualQuat::rotation(axis, q),
                    JointKind::Prismatic => DualQuat::translation(&scale3(q, axis)),
                };
                match frames.split_first() {
                    None => motion,
                    Some((first, rest)) => {
                        let origin = rest
                            .iter()
                            .fold(local_frame_dq(first), |acc, f| acc * local_frame_dq(f));
                        origin * motion
                    }
                }
            }
        }
    }

    /// The motion of the joint at variable `q`, as a product of elementary matrices
    /// (no dual quaternion involved).
    pub fn matrix(&self, q: &T) -> Matrix4<T> {
        match &self.geometry {
            JointGeometry::Dh { theta, d, a, alpha } => {
                let (theta, d) = self.theta_d(theta, d, q);
                dh_link_matrix(&theta, &d, a, alpha)
            }
            JointGeometry::Mdh { alpha, a, theta, d } => {
                let (theta, d) = self.theta_d(theta, d, q);
                mdh_link_matrix(alpha, a, &theta, &d)
            }
            JointGeometry::Screw { axis, point } => match self.kind {
                // T(p) R T(−p): the TMT⁻¹ conjugation of sec 3-B 3).
                JointKind::Revolute => {
                    Matrix4::trans(point)
                        * Matrix4::rotation(axis, q)
                        * Matrix4::trans(&neg3(point))
                }
                JointKind::Prismatic => Matrix4::trans(&scale3(q, axis)),
            },
            JointGeometry::Local { frames, axis } => {
                let motion = match self.kind {
                    JointKind::Revolute => Matrix4::rotation(axis, q),
                    JointKind::Prismatic => Matrix4::trans(&scale3(q, axis)),
                };
                frames
                    .iter()
                    .rev()
                    .fold(motion, |acc, f| local_frame_matrix(f) * acc)
            }
        }
    }
}
