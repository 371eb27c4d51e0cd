//! `f64` kernels: thin, NaN-free wrappers over the pure-Rust `libm` crate
//! (a port of musl's libm, accurate to < 1 ulp). These are the design and
//! simulation backend and the reference the other backends are checked
//! against; the embedded paths use the `f32` and `I16F16` kernels instead.
//!
//! Conventions shared by all kernels here: a NaN argument is treated as 0;
//! results are never NaN or infinite.

/// Largest `f64` below π/2 (`FRAC_PI_2` rounds down: 1.5707963267948966 <
/// π/2 = 1.57079632679489661923…): the edge of the principal branch of
/// [`tan`].
pub const TAN_DOMAIN_EDGE: f64 = core::f64::consts::FRAC_PI_2;

#[inline]
fn denan(x: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        x
    }
}

#[inline]
fn finite_or(x: f64, saturated: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        saturated
    }
}

/// Arctangent in `[-π/2, π/2]`. Domain: every `f64`.
#[inline]
pub fn atan(x: f64) -> f64 {
    libm::atan(denan(x))
}

/// Tangent on the principal branch `|x| ≤ TAN_DOMAIN_EDGE`; outside it,
/// `±tan(TAN_DOMAIN_EDGE)` with the sign of `x`.
#[inline]
pub fn tan(x: f64) -> f64 {
    let x = denan(x);
    if x > TAN_DOMAIN_EDGE {
        libm::tan(TAN_DOMAIN_EDGE)
    } else if x < -TAN_DOMAIN_EDGE {
        -libm::tan(TAN_DOMAIN_EDGE)
    } else {
        libm::tan(x)
    }
}

/// `e^x`, saturating at `f64::MAX` (and underflowing to 0).
#[inline]
pub fn exp(x: f64) -> f64 {
    finite_or(libm::exp(denan(x)), f64::MAX)
}

/// `e^{−|x|}` (thesis eqs. (2.29) and (4.7)), in `[0, 1]`: [`exp`] of `−|x|`
/// (NaN → 1, as for [`exp`]). `f64` has no cheaper path worth a kernel of
/// its own.
#[inline]
pub fn exp_neg_abs(x: f64) -> f64 {
    exp(-libm::fabs(x))
}

/// Sine; domain: every finite `f64` (`±∞` returns 0, like NaN).
#[inline]
pub fn sin(x: f64) -> f64 {
    finite_or(libm::sin(denan(x)), 0.0)
}

/// Cosine; domain: every finite `f64` (`±∞` returns 1, like NaN).
#[inline]
pub fn cos(x: f64) -> f64 {
    finite_or(libm::cos(denan(x)), 1.0)
}

/// `(sin x, cos x)`.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    let x = if x.is_finite() { x } else { 0.0 };
    libm::sincos(x)
}

/// Four-quadrant arctangent of `y/x` in `[-π, π]`; `atan2(0, 0) = 0`.
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(denan(y), denan(x))
}

/// Arccosine in `[0, π]`; the argument is clamped to `[-1, 1]`.
#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(denan(x).clamp(-1.0, 1.0))
}

/// Square root; negative arguments return 0, `+∞` returns `f64::MAX`.
#[inline]
pub fn sqrt(x: f64) -> f64 {
    let x = denan(x);
    if x <= 0.0 {
        0.0
    } else {
        finite_or(libm::sqrt(x), f64::MAX)
    }
}

/// Cosine of a binary angle: `cos(2π·turn/2³²)`. Exact integer reduction to
/// the nearest quarter turn (`u = |turn as i32|`, `d = u − k·2³⁰`), then
/// `libm`'s `cos`/`sin` of `d·2π/2³²` (`|d·2π/2³²| ≤ π/4`); error below
/// 1e-15, exactly even, `|result| ≤ 1`.
#[inline]
pub fn cos_turn(turn: u32) -> f64 {
    let u = (turn as i32).unsigned_abs(); // [0, 2³¹]
    let k = (u + (1 << 29)) >> 30; // 0, 1, 2
    let d = (u as i32).wrapping_sub((k << 30) as i32); // [−2²⁹, 2²⁹]
    let r = d as f64 * (core::f64::consts::TAU / 4_294_967_296.0);
    match k {
        0 => libm::cos(r),
        1 => -libm::sin(r),
        _ => -libm::cos(r),
    }
}

/// `(sin, cos)` of a binary angle: exactly the default of
/// [`Scalar::sin_cos_turn`](crate::scalar::Scalar::sin_cos_turn),
/// `(cos_turn(turn − 2³⁰), cos_turn(turn))` (on `f64` the two `libm` calls
/// dominate; sharing the integer reduction would save nothing measurable).
#[inline]
pub fn sin_cos_turn(turn: u32) -> (f64, f64) {
    (cos_turn(turn.wrapping_sub(1 << 30)), cos_turn(turn))
}
