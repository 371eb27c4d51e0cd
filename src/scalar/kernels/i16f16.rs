//! `I16F16` kernels (interim: evaluated through the `f64` kernels).

use crate::scalar::{Scalar, I16F16};

fn via_f64(x: I16F16, f: fn(f64) -> f64) -> I16F16 {
    <I16F16 as Scalar>::from_f64(f(x.to_f64()))
}

/// Arctangent.
pub fn atan(x: I16F16) -> I16F16 {
    via_f64(x, super::f64::atan)
}
/// Tangent on the principal branch, saturating.
pub fn tan(x: I16F16) -> I16F16 {
    via_f64(x, super::f64::tan)
}
/// `e^x`, saturating.
pub fn exp(x: I16F16) -> I16F16 {
    via_f64(x, super::f64::exp)
}
/// Sine.
pub fn sin(x: I16F16) -> I16F16 {
    via_f64(x, super::f64::sin)
}
/// Cosine.
pub fn cos(x: I16F16) -> I16F16 {
    via_f64(x, super::f64::cos)
}
/// `(sin x, cos x)`.
pub fn sin_cos(x: I16F16) -> (I16F16, I16F16) {
    (sin(x), cos(x))
}
/// Four-quadrant arctangent.
pub fn atan2(y: I16F16, x: I16F16) -> I16F16 {
    <I16F16 as Scalar>::from_f64(super::f64::atan2(y.to_f64(), x.to_f64()))
}
/// Arccosine.
pub fn acos(x: I16F16) -> I16F16 {
    via_f64(x, super::f64::acos)
}
/// Square root.
pub fn sqrt(x: I16F16) -> I16F16 {
    via_f64(x, super::f64::sqrt)
}
