//! Helpers shared by the unit tests of several modules.

use crate::scalar::{Scalar, I16F16};

/// A backend's stored number read without the crate's unit tables:
/// floats store SI; `I16F16` stores `bits · 2^-FRAC_NBITS` of its
/// documented unit (mN·m for motor torque; N·m, rad and rad/s otherwise:
/// the table of `scalar::units`).
pub(crate) trait Stored: Scalar {
    /// The stored number as `f64`, exactly.
    fn stored(self) -> f64;
    /// SI per stored unit (`motor`: a motor torque).
    fn unit(motor: bool) -> f64;
}
impl Stored for f64 {
    fn stored(self) -> f64 {
        self
    }
    fn unit(_: bool) -> f64 {
        1.0
    }
}
impl Stored for f32 {
    fn stored(self) -> f64 {
        self as f64
    }
    fn unit(_: bool) -> f64 {
        1.0
    }
}
impl Stored for I16F16 {
    fn stored(self) -> f64 {
        self.to_bits() as f64 * libm::exp2(-(I16F16::FRAC_NBITS as f64))
    }
    fn unit(motor: bool) -> f64 {
        if motor {
            1e-3
        } else {
            1.0
        }
    }
}
