//! Serial chains: forward kinematics as a product of joint motions.

use super::Joint;
use crate::{DualQuat, Matrix4, Ring};

/// Why a chain could not be evaluated.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ChainError {
    /// The number of joint values differs from the number of joints.
    #[error("expected {expected} joint values, found {found}")]
    WrongJointCount {
        /// The number of joints of the chain.
        expected: usize,
        /// The number of values given.
        found: usize,
    },
}

/// A serial chain: a fixed base motion, joints from the base outwards, then a fixed tool motion.
///
/// Forward kinematics is `base · J₁(q₁) J₂(q₂) … Jₙ(qₙ) · tool`, the paper's `q = q₀₁ q₁₂ … q_{n−1,n}`
/// (sec 5 A). With DH joints each factor is the motion of a link frame relative to the
/// previous one and `tool` is the end effector in the last frame; with screw joints each
/// factor is a motion about a home-pose axis in base coordinates and `tool` is the end
/// effector's home pose (sec 6), both relative to `base` (the robot's mounting in the world;
/// the identity by default). Nothing here needs more than a [`Ring`], so symbolic joint
/// values flow through unchanged.
///
/// # Laws
/// - `forward(q).to_matrix() = forward_matrix(q)` (up to rounding for f64).
/// - `forward(q)` is a unit DQ when every joint's is and `tool` is.
/// - The last entry of `forward_frames(q)` times `tool` is `forward(q)`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Chain<T> {
    /// The fixed motion applied before the first joint (the base frame in the world).
    pub base: DualQuat<T>,
    /// The joints, base first.
    pub joints: Vec<Joint<T>>,
    /// The fixed motion applied after the last joint.
    pub tool: DualQuat<T>,
}

impl<T: Ring> Chain<T> {
    /// The chain of `joints` with no base and no tool (identities).
    pub fn new(joints: Vec<Joint<T>>) -> Self {
        Chain {
            base: DualQuat::identity(),
            joints,
            tool: DualQuat::identity(),
        }
    }

    /// The same chain with `base` applied before the first joint.
    pub fn with_base(self, base: DualQuat<T>) -> Self {
        Chain { base, ..self }
    }

    /// The same chain with `tool` applied after the last joint.
    pub fn with_tool(self, tool: DualQuat<T>) -> Self {
        Chain { tool, ..self }
    }

    /// The number of joints (degrees of freedom).
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    fn check(&self, q: &[T]) -> Result<(), ChainError> {
        if q.len() == self.joints.len() {
            Ok(())
        } else {
            Err(ChainError::WrongJointCount {
                expected: self.joints.len(),
                found: q.len(),
            })
        }
    }

    /// The cumulative motions `base J₁(q₁)`, `base J₁ J₂`, …, `base J₁ … Jₙ` (without the
    /// tool): the pose of every link frame, as a Jacobian needs them.
    ///
    /// # Errors
    /// [`ChainError::WrongJointCount`] when `q` does not hold one value per joint.
    pub fn forward_frames(&self, q: &[T]) -> Result<Vec<DualQuat<T>>, ChainError> {
        self.check(q)?;
        let mut acc = self.base.clone();
        let mut frames = Vec::with_capacity(q.len());
        for (joint, qi) in self.joints.iter().zip(q) {
            acc = acc * joint.dq(qi);
            frames.push(acc.clone());
        }
        Ok(frames)
    }

    /// The end-effector motion `base · J₁(q₁) … Jₙ(qₙ) · tool` as a dual quaternion.
    ///
    /// # Errors
    /// [`ChainError::WrongJointCount`] when `q` does not hold one value per joint.
    pub fn forward(&self, q: &[T]) -> Result<DualQuat<T>, ChainError> {
        self.check(q)?;
        let pose = self
            .joints
            .iter()
            .zip(q)
            .fold(self.base.clone(), |acc, (joint, qi)| acc * joint.dq(qi));
        Ok(pose * &self.tool)
    }

    /// The end-effector motion as a product of the joints' elementary matrices. The base and
    /// the tool are the factors converted from their dual quaternions ([`DualQuat::to_matrix`]).
    ///
    /// # Errors
    /// [`ChainError::WrongJointCount`] when `q` does not hold one value per joint.
    pub fn forward_matrix(&self, q: &[T]) -> Result<Matrix4<T>, ChainError> {
        self.check(q)?;
        let pose = self
            .joints
            .iter()
            .zip(q)
            .fold(self.base.to_matrix(), |acc, (joint, qi)| {
                acc * joint.matrix(qi)
            });
        Ok(pose * self.tool.to_matrix())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrong_number_of_joint_values_is_an_error() {
        let chain = Chain::new(vec![Joint::revolute_dh(0.0, 0.0, 1.0, 0.0)]);
        assert_eq!(
            chain.forward(&[]),
            Err(ChainError::WrongJointCount {
                expected: 1,
                found: 0
            })
        );
    }
}
