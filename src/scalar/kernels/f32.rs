//! `f32` kernels (interim: libm single-precision routines).
//!
//! Conventions: a NaN argument is treated as 0; results are never NaN.

/// Largest `f32` below π/2: the edge of the principal branch of [`tan`].
pub const TAN_DOMAIN_EDGE: f32 = 1.570_796_2;

#[inline]
fn denan(x: f32) -> f32 {
    if x.is_nan() {
        0.0
    } else {
        x
    }
}

/// Arctangent in `[-π/2, π/2]`.
#[inline]
pub fn atan(x: f32) -> f32 {
    libm::atanf(denan(x))
}

/// Tangent on the principal branch; saturates outside it.
#[inline]
pub fn tan(x: f32) -> f32 {
    let x = denan(x).clamp(-TAN_DOMAIN_EDGE, TAN_DOMAIN_EDGE);
    libm::tanf(x)
}

/// `e^x`, saturating at `f32::MAX`.
#[inline]
pub fn exp(x: f32) -> f32 {
    let y = libm::expf(denan(x));
    if y.is_finite() {
        y
    } else {
        f32::MAX
    }
}

/// Sine.
#[inline]
pub fn sin(x: f32) -> f32 {
    sin_cos(x).0
}

/// Cosine.
#[inline]
pub fn cos(x: f32) -> f32 {
    sin_cos(x).1
}

/// `(sin x, cos x)`.
#[inline]
pub fn sin_cos(x: f32) -> (f32, f32) {
    let x = if x.is_finite() { x } else { 0.0 };
    libm::sincosf(x)
}

/// Four-quadrant arctangent of `y/x`.
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    libm::atan2f(denan(y), denan(x))
}

/// Arccosine; the argument is clamped to `[-1, 1]`.
#[inline]
pub fn acos(x: f32) -> f32 {
    libm::acosf(denan(x).clamp(-1.0, 1.0))
}

/// Square root; negative arguments return 0.
#[inline]
pub fn sqrt(x: f32) -> f32 {
    let x = denan(x);
    if x <= 0.0 {
        0.0
    } else if x.is_infinite() {
        f32::MAX
    } else {
        libm::sqrtf(x)
    }
}
