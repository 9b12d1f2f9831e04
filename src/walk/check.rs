//! The check step: a result evaluated at pseudo-random configurations against the product of
//! the factors' elementary 4x4 matrices ([`Motion::matrix`], built without dual quaternions).

use super::motion::Motion;
use super::Step;
use crate::{Matrix4, Scalar, ScalarError, Sym};

/// How many configurations a check tries.
pub(crate) const SAMPLES: usize = 5;

/// A value in [-1.5, 1.5) for the symbol `s` in configuration `sample`: the same on every
/// run and machine (FNV-1a of the name, then a linear congruential step). `pi` has its value
/// and is never asked for.
pub(crate) fn sample_value(s: &Sym, sample: usize) -> f64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in s.name().bytes().chain((sample as u64).to_le_bytes()) {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h = h
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    let u = (h >> 11) as f64 / (1u64 << 53) as f64;
    3.0 * u - 1.5
}

/// The product of the motions' matrices at configuration `sample`.
pub(crate) fn chain_matrix(motions: &[Motion], sample: usize) -> Result<Matrix4<f64>, ScalarError> {
    let env = |s: &Sym| Some(sample_value(s, sample));
    let mut m = Matrix4::identity();
    for x in motions {
        m = m * x.matrix(&env)?;
    }
    Ok(m)
}

/// The oracle in words: the distinct elementary products, in order of first use.
pub(crate) fn oracle(motions: &[Motion]) -> String {
    let mut kinds: Vec<&str> = Vec::new();
    for m in motions {
        if !kinds.contains(&m.oracle()) {
            kinds.push(m.oracle());
        }
    }
    format!(
        "the product of {} 4x4 matrices, each {}",
        motions.len(),
        kinds.join(" or ")
    )
}

/// The check of the image `image` of the home point `v` under the chain `motions`; `None`
/// when a value cannot be evaluated.
pub(crate) fn check(
    motions: &[Motion],
    v: &[Scalar; 3],
    image: &[Scalar; 3],
    label: &str,
) -> Option<Step> {
    let mut max: f64 = 0.0;
    for k in 0..SAMPLES {
        let env = |s: &Sym| Some(sample_value(s, k));
        let m = chain_matrix(motions, k).ok()?;
        let home = [
            v[0].eval_symbols(&env).ok()?,
            v[1].eval_symbols(&env).ok()?,
            v[2].eval_symbols(&env).ok()?,
        ];
        let want = m.transform_point(&home);
        for (w, x) in want.iter().zip(image) {
            max = max.max((w - x.eval_symbols(&env).ok()?).abs());
        }
    }
    Some(Step::Check {
        what: format!("{label}: the point's coordinates"),
        oracle: format!("{} applied to the home point", oracle(motions)),
        samples: SAMPLES,
        max_deviation: max,
    })
}

/// The check of a whole pose: the DQ's 4x4 matrix (Appendix I) against the product of the
/// elementary matrices, entry by entry.
pub(crate) fn check_pose(
    motions: &[Motion],
    pose: &crate::DualQuat<Scalar>,
    label: &str,
) -> Option<Step> {
    let m = pose.to_matrix();
    let mut max: f64 = 0.0;
    for k in 0..SAMPLES {
        let env = |s: &Sym| Some(sample_value(s, k));
        let want = chain_matrix(motions, k).ok()?;
        for (wr, mr) in want.rows.iter().zip(&m.rows) {
            for (w, x) in wr.iter().zip(mr) {
                max = max.max((w - x.eval_symbols(&env).ok()?).abs());
            }
        }
    }
    Some(Step::Check {
        what: format!("{label}: the pose's 4x4 matrix from the dual quaternion (Appendix I)"),
        oracle: oracle(motions),
        samples: SAMPLES,
        max_deviation: max,
    })
}
