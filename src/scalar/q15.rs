//! `Q15`: normalized fixed point for the integer-multiplier hot path of
//! FPU-less 32-bit cores (Cortex-M0+).
//!
//! # Why a second fixed representation
//!
//! [`I16F16`](crate::scalar::I16F16) covers the thesis's physical ranges, but
//! every `I16F16` product needs the 64-bit intermediate of a 32 × 32 → 64
//! multiply. A Cortex-M0+ has only `MULS` (32 × 32 → low 32 bits), so that
//! product is a call to `__aeabi_lmul`. A [`Q15`] product is a 16 × 16 → 32
//! multiply, which is *one* `MULS`.
//!
//! [`Q15`] is [`I1F15`](fixed::types::I1F15): range `[-1, 1)`, resolution
//! (one LSB) `2⁻¹⁵ ≈ 3.05e-5`. It does **not** implement
//! [`Scalar`](crate::scalar::Scalar): `1.0` is not representable, so
//! `Scalar::ONE` and everything built on it would be wrong. It is used for
//! *normalized* quantities: a physical value `v` with a known full scale `V`
//! is stored as `v / V` (torsion / maximum torsion, torque / rated torque, a
//! normalized control signal, a velocity over the boundary-layer width…).
//! The scales are applied once, at configuration time, with [`FullScale`];
//! the hot path only uses the integer functions of this module.
//!
//! Angles use [`BinaryAngle`]: one full turn is `2¹⁶` codes
//! (`1 code = 2π/65536 rad ≈ 9.59e-5 rad`), so angle addition and
//! subtraction wrap exactly modulo `2π`.
//!
//! # Formats
//!
//! | format | range | resolution | hot-path product |
//! |---|---|---|---|
//! | [`Q15`] (`I1F15`) | `[-1, 1 - 2⁻¹⁵]` | `2⁻¹⁵ ≈ 3.05e-5` (4.5 significant digits) | 16 × 16 → 32 |
//! | [`BinaryAngle`] | `[-π, π)`, wraps | `2π/2¹⁶ ≈ 9.59e-5 rad` (0.0055°) | — |
//! | `I16F16` | `[-32768, 32768 - 2⁻¹⁶]` | `2⁻¹⁶ ≈ 1.53e-5` | 32 × 32 → 64 |
//!
//! # Cost of one product on a Cortex-M0+ (`thumbv6m-none-eabi`)
//!
//! Measured, not estimated: each operation wrapped in one
//! `#[inline(never)] extern "C"` function, built for `thumbv6m-none-eabi`
//! (release, `opt-level = 3`, fat LTO), linked, and executed in the
//! `unicorn` Cortex-M0+ emulator over 3 000 inputs (edge cases and random
//! values). Counts are *instructions executed*, including the wrapper's
//! frame (`push`, `add r7`, `pop`: 3 instructions).
//!
//! | operation | instructions | what they are |
//! |---|---|---|
//! | [`mul`] (Q15) | 11 | `muls`; `movs`+`lsls`+`adds` (round, +2¹⁴); `asrs #15`; `ldr`+`cmp`+`blt` (saturation; +1 `mov` when it saturates) |
//! | `I16F16` `Scalar::mul` | 66–68 | 37 inside `__aeabi_lmul` (the 32 × 32 → 64 product), ~26 for the 64-bit rounding add, 64-bit shift and 64-bit saturation compares |
//!
//! So one Q15 product is 8 instructions inline against ~63 for `I16F16`
//! (about 8×). Cycles follow the same ratio on a part with the
//! single-cycle multiplier; with the optional 32-cycle iterative
//! multiplier, each `muls` adds 31 cycles, once for Q15 and several times
//! inside `__aeabi_lmul`.
//!
//! Whole kernels, same method (instructions executed, min–max):
//!
//! | kernel | Q15 | `I16F16` (integer kernels of [`kernels::i16f16`](super::kernels::i16f16)) |
//! |---|---|---|
//! | `sin` | 21–40 | 217–267 (3 `__aeabi_lmul`) |
//! | `sin_cos` | 52–81 | — |
//! | `atan` | 15–31 | — |
//! | `atan2` | 25–137 | 486–528 (2 `__aeabi_lmul`) |
//! | `sqrt` | 8–186 | — |
//! | `exp_neg` | 7–35 | — |
//! | `sat` | 19–86 | — |
//!
//! # Arithmetic semantics
//!
//! * Every function is total: no panic, no overflow in debug builds, no
//!   wrapping except [`BinaryAngle`] arithmetic (which is modular by design).
//! * [`mul`] rounds to nearest (ties toward `+∞`) and saturates its single
//!   overflow case `(-1)·(-1)` to [`MAX`]; [`add`], [`sub`], [`neg`] saturate.
//! * `+1` is not representable; where a result is `+1` it saturates to
//!   [`MAX`] `= 1 - 2⁻¹⁵` (one LSB of error, counted in every bound below).
//!   [`sgn`] and [`sat`] return the *odd-symmetric* `±MAX` for `±1`, so that
//!   `sgn(-x) = -sgn(x)` holds exactly (a `-1 = MIN`, `+1 = MAX` pair would
//!   make the sign function, and every friction compensation built on it,
//!   biased by one LSB towards the negative direction).
//!
//! # Kernels
//!
//! All kernels are integer-only: 16 × 16 → 32 products, 32-bit shifts, adds
//! and compares, and three tables totalling 902 bytes (`SIN_Q16` 512 B,
//! `ATAN_Q16` 258 B, `EXP_NEG_Q30` 132 B). The quotients of `atan2` and
//! `sat` use a 15/16-step shift-and-subtract division instead of a divide
//! instruction (the M0+ has none; `__aeabi_uidiv` costs ~190
//! instructions). No kernel uses a 64-bit operation, a float or a call.
//!
//! The bounds are *proven* by exhaustive enumeration of every input (every
//! one of the `2¹⁶` inputs of a unary kernel, every one of the `2³²` input
//! pairs of [`atan2`] and [`sat`]) against the `f64` reference, by the
//! `exhaustive_*_q15` tests in `proofs/kernels_q15.rs`
//! (`cargo test --release --lib -- --ignored exhaustive_ --test-threads 1 --nocapture`).
//!
//! | kernel | algorithm | domain (all checked) | proven bound | measured max error |
//! |---|---|---|---|---|
//! | [`mul`] | one 16 × 16 → 32 product, round, saturate | 2³² pairs | 0.5 LSB; 1 LSB for `(-1)(-1)` | 0.5; 1.0 at `(-1)(-1)` |
//! | [`sgn`] | compares | 2¹⁶ | exact (`±MAX`) | 0 |
//! | [`sat`] | compares + 15-step division | 2³² pairs `(x, y)` | 1 LSB (0.5 LSB where the exact value is not `±1`) | 1.0 where the exact value is `±1` |
//! | [`sin`], [`cos`] | quadrant reduction, 256-segment quarter-wave Q16 table, linear interpolation | 2¹⁶ angles | 1 LSB | 1.0 at `±π/2` (`±1 → ±MAX`); 0.83 elsewhere |
//! | [`sin_cos`] | as `sin`, `cos` | 2¹⁶ angles | bit-equal to `(sin, cos)`; `\|s² + c² - 1\| ≤ 2` LSB | 2.0 (at `0`: `MAX²`) |
//! | [`atan`] | 128-segment Q16 table, linear interpolation | 2¹⁶ | 1 LSB | 0.84 |
//! | [`atan2`] | octant reduction, 16-step ratio, `atan` table, `× 2/π` | 2³² pairs `(y, x)` | 1 code mod 2π | 0.71 code |
//! | [`sqrt`] | digit-by-digit integer root, one rounding | 2¹⁶ | 0.5 LSB (correctly rounded) | 0.5 |
//! | [`exp_neg`] | 33-entry Q30 table `e^{-i/32}` × `(1 - f + f²/2)` | 2¹⁶ (bound on `[-1, 0]`, `MAX` above) | 1 LSB | 1.0 at `0` (`1 → MAX`); 0.90 elsewhere |
//!
//! `atan`, `sqrt` and `exp_neg` are also proven non-decreasing over every
//! input; `sin`, `atan` and `sat` odd. The `2³²`-pair proofs cost, in
//! release, about 155 s of CPU for `atan2` (dominated by the `libm::atan2`
//! reference), 40 s for `sat` and 18 s for `mul`: about half that in wall
//! time on two idle cores (`atan2` took 240 s on the shared 2-core CI
//! machine).

use core::ops::{Add, Neg, Sub};

use crate::error::ParamError;

/// A normalized quantity in `[-1, 1)`, LSB `2⁻¹⁵` (the Q15 / `I1F15` format).
///
/// Not a [`Scalar`](crate::scalar::Scalar) backend: see the [module
/// docs](self).
pub type Q15 = fixed::types::I1F15;

/// The largest value, `1 - 2⁻¹⁵`; stands for `+1` wherever a result is `+1`.
pub const MAX: Q15 = Q15::MAX;
/// The smallest value, `-1`.
pub const MIN: Q15 = Q15::MIN;
/// Zero.
pub const ZERO: Q15 = Q15::ZERO;
/// One LSB, `2⁻¹⁵`.
pub const LSB: Q15 = Q15::DELTA;

// ---------------------------------------------------------------------------
// Configuration-time conversions (f64; never on the hot path)
// ---------------------------------------------------------------------------

/// Nearest [`Q15`] to `x` (ties to even), saturating to `[MIN, MAX]`;
/// NaN maps to 0. Configuration time only (uses `f64`).
pub fn from_f64(x: f64) -> Q15 {
    if x.is_nan() {
        ZERO
    } else {
        Q15::saturating_from_num(x)
    }
}

/// The exact value of `x` as `f64`.
#[inline]
pub fn to_f64(x: Q15) -> f64 {
    x.to_bits() as f64 / 32768.0
}

/// The full scale `V` of a normalized quantity: a physical value `v` (SI
/// units) is stored as the [`Q15`] `v / V`.
///
/// Built once at configuration time; the hot path never sees `V`.
///
/// ```
/// use mrr_control::scalar::q15::{self, FullScale};
/// // Torque normalized by a 40 N·m rated torque.
/// let rated = FullScale::try_new("rated_torque", 40.0).unwrap();
/// let t = rated.quantize(12.5);
/// assert!((rated.to_si(t) - 12.5).abs() <= 40.0 * 2f64.powi(-16));
/// // Beyond the full scale saturates.
/// assert_eq!(rated.quantize(100.0), q15::MAX);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullScale {
    full_scale: f64,
}

impl FullScale {
    /// A full scale `V > 0` (finite). `name` names the parameter in the
    /// error.
    pub fn try_new(name: &'static str, full_scale: f64) -> Result<Self, ParamError> {
        let full_scale = crate::error::positive(name, full_scale)?;
        if full_scale.is_infinite() {
            return Err(ParamError::NotFinite {
                name,
                value: full_scale,
            });
        }
        Ok(FullScale { full_scale })
    }

    /// The full scale `V`, in the SI unit of the quantity.
    pub fn value(&self) -> f64 {
        self.full_scale
    }

    /// `v / V` rounded to nearest, saturating at `[MIN, MAX]` (NaN → 0).
    pub fn quantize(&self, v: f64) -> Q15 {
        from_f64(v / self.full_scale)
    }

    /// The SI value `q · V` of a normalized quantity.
    pub fn to_si(&self, q: Q15) -> f64 {
        to_f64(q) * self.full_scale
    }
}

// ---------------------------------------------------------------------------
// Hot-path arithmetic
// ---------------------------------------------------------------------------

/// `a · b`, rounded to nearest (ties toward `+∞`), from one 16 × 16 → 32
/// product. The single overflow case `(-1)·(-1) = +1` saturates to [`MAX`].
/// Error ≤ 0.5 LSB (1 LSB for `(-1)·(-1)`).
///
/// ```
/// use mrr_control::scalar::q15::{self, Q15};
/// let half = Q15::from_num(0.5);
/// assert_eq!(q15::mul(half, half), Q15::from_num(0.25));
/// assert_eq!(q15::mul(q15::MIN, q15::MIN), q15::MAX);
/// ```
#[inline]
pub fn mul(a: Q15, b: Q15) -> Q15 {
    Q15::from_bits(mul_bits(a.to_bits(), b.to_bits()))
}

/// [`mul`] on raw bit patterns.
#[inline]
pub const fn mul_bits(a: i16, b: i16) -> i16 {
    // |a·b| ≤ 2³⁰, so a·b + 2¹⁴ fits in i32.
    let p = ((a as i32) * (b as i32) + (1 << 14)) >> 15;
    if p > i16::MAX as i32 {
        i16::MAX
    } else {
        p as i16
    }
}

/// `a + b`, saturating at [`MIN`]/[`MAX`].
#[inline]
pub fn add(a: Q15, b: Q15) -> Q15 {
    a.saturating_add(b)
}

/// `a - b`, saturating at [`MIN`]/[`MAX`].
#[inline]
pub fn sub(a: Q15, b: Q15) -> Q15 {
    a.saturating_sub(b)
}

/// `-a`; `-MIN = +1` saturates to [`MAX`].
#[inline]
pub fn neg(a: Q15) -> Q15 {
    a.saturating_neg()
}

/// Sign function of thesis eq. (2.17): `+1` for `x > 0`, `0` for `x = 0`,
/// `-1` for `x < 0`, with `±1` represented by the odd-symmetric `±MAX`
/// `= ±(1 - 2⁻¹⁵)` (one LSB below the exact magnitude; see the module docs).
///
/// ```
/// use mrr_control::scalar::q15::{self, Q15};
/// assert_eq!(q15::sgn(Q15::from_num(-0.3)), -q15::MAX);
/// assert_eq!(q15::sgn(q15::ZERO), q15::ZERO);
/// ```
#[inline]
pub fn sgn(x: Q15) -> Q15 {
    Q15::from_bits(sgn_bits(x.to_bits()))
}

#[inline]
const fn sgn_bits(x: i16) -> i16 {
    if x > 0 {
        i16::MAX
    } else if x < 0 {
        -i16::MAX
    } else {
        0
    }
}

/// Boundary-layer saturation of thesis eq. (4.18) on normalized values:
///
/// ```text
/// sat(x, y) = x/|x|   if |x| > y
///            x/|y|   if |x| ≤ y
/// ```
///
/// Same semantics as [`Scalar::sat`](crate::scalar::Scalar::sat): for
/// `y ≤ 0` every `x ≠ 0` lies outside the layer and the result is
/// [`sgn`]`(x)`; `sat(0, y) = 0`. Inside the layer `x / y` is rounded to
/// nearest (ties away from zero) by a 15-step shift-and-subtract division
/// (no divide instruction); `±1`
/// is returned as `±MAX` (as by [`sgn`]), so the result lies in
/// `[-MAX, MAX]`.
///
/// Proven over all `2³²` pairs `(x, y)`: error ≤ 1 LSB against the exact
/// eq. (4.18) (≤ 0.5 LSB except where the exact value is `±1`); odd in `x`
/// (`x ≠ MIN`); non-decreasing in `x`; continuous at `|x| = y`.
///
/// ```
/// use mrr_control::scalar::q15::{self, Q15};
/// let eps = Q15::from_num(0.5);
/// assert_eq!(q15::sat(Q15::from_num(0.25), eps), Q15::from_num(0.5));
/// assert_eq!(q15::sat(Q15::from_num(-0.75), eps), -q15::MAX);
/// assert_eq!(q15::sat(Q15::from_num(0.001), q15::ZERO), q15::MAX);
/// ```
#[inline]
pub fn sat(x: Q15, y: Q15) -> Q15 {
    Q15::from_bits(sat_bits(x.to_bits(), y.to_bits()))
}

#[inline]
fn sat_bits(x: i16, y: i16) -> i16 {
    if y <= 0 {
        return sgn_bits(x);
    }
    let ax = (x as i32).unsigned_abs(); // ≤ 2¹⁵
    let y = y as u32; // 1 ..= 2¹⁵ - 1
    if ax >= y {
        // |x| > y is outside the layer; |x| = y gives x/y = ±1 exactly.
        return sgn_bits(x);
    }
    // round(|x| / y · 2¹⁵), ties up, without a divide instruction.
    let q = ratio::<15>(ax, y);
    // |x| ≤ y - 1 gives |x|/y·2¹⁵ ≤ 2¹⁵ - 2¹⁵/y < 2¹⁵ - 1 (y < 2¹⁵), so q
    // fits in i16; the clamp only documents it.
    let q = if q > i16::MAX as u32 {
        i16::MAX
    } else {
        q as i16
    };
    if x < 0 {
        -q
    } else {
        q
    }
}

// ---------------------------------------------------------------------------
// Binary angles
// ---------------------------------------------------------------------------

/// An angle in binary angular measurement: one full turn is `2¹⁶` codes,
/// `1 code = 2π/65536 rad ≈ 9.587e-5 rad`. The code is a two's-complement
/// `i16`, so the principal value is in `[-π, π)`; addition, subtraction and
/// negation wrap, i.e. are exact modulo `2π`.
///
/// ```
/// use mrr_control::scalar::q15::BinaryAngle;
/// let a = BinaryAngle::from_radians(3.0);
/// let b = BinaryAngle::from_radians(0.5);
/// // 3.5 rad wraps to 3.5 - 2π.
/// let c = (a + b).to_radians();
/// assert!((c - (3.5 - 2.0 * core::f64::consts::PI)).abs() <= 2.0 * 9.6e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct BinaryAngle(i16);

impl BinaryAngle {
    /// Zero.
    pub const ZERO: Self = BinaryAngle(0);
    /// `π/2` (`16384` codes).
    pub const FRAC_PI_2: Self = BinaryAngle(1 << 14);
    /// `±π` (`-32768` codes; the principal value is `-π`).
    pub const PI: Self = BinaryAngle(i16::MIN);
    /// Radians per code, `2π / 65536`.
    pub const RADIANS_PER_CODE: f64 = core::f64::consts::PI / 32768.0;

    /// The angle of `code` codes.
    #[inline]
    pub const fn from_bits(code: i16) -> Self {
        BinaryAngle(code)
    }

    /// The code, in `[-32768, 32767]` (principal value `[-π, π)`).
    #[inline]
    pub const fn to_bits(self) -> i16 {
        self.0
    }

    /// The code as an unsigned position on the turn, `[0, 65535]`
    /// (`[0, 2π)`).
    #[inline]
    pub const fn to_turn_code(self) -> u16 {
        self.0 as u16
    }

    /// A [`Q15`] angle in half turns (`h` stands for `h·π` rad) as a binary
    /// angle; exact (it is the same bit pattern).
    #[inline]
    pub const fn from_half_turns(h: Q15) -> Self {
        BinaryAngle(h.to_bits())
    }

    /// The principal value in half turns, `[-1, 1)` (`-1` is `-π`); exact.
    #[inline]
    pub const fn to_half_turns(self) -> Q15 {
        Q15::from_bits(self.0)
    }

    /// Nearest binary angle to `radians`, reduced modulo `2π`; NaN and
    /// infinities map to zero. Configuration time only (uses `f64`).
    pub fn from_radians(radians: f64) -> Self {
        if !radians.is_finite() {
            return BinaryAngle::ZERO;
        }
        let codes = libm::fmod(radians / Self::RADIANS_PER_CODE, 65536.0);
        let codes = libm::round(codes); // in (-65536, 65536]
        BinaryAngle((codes as i32) as i16)
    }

    /// The principal value in radians, `[-π, π)`.
    #[inline]
    pub fn to_radians(self) -> f64 {
        self.0 as f64 * Self::RADIANS_PER_CODE
    }

    /// `self + rhs` modulo `2π` (exact).
    #[inline]
    pub const fn wrapping_add(self, rhs: Self) -> Self {
        BinaryAngle(self.0.wrapping_add(rhs.0))
    }

    /// `self - rhs` modulo `2π` (exact).
    #[inline]
    pub const fn wrapping_sub(self, rhs: Self) -> Self {
        BinaryAngle(self.0.wrapping_sub(rhs.0))
    }

    /// `-self` modulo `2π` (exact; `-π` maps to itself).
    #[inline]
    pub const fn wrapping_neg(self) -> Self {
        BinaryAngle(self.0.wrapping_neg())
    }
}

impl Add for BinaryAngle {
    type Output = Self;
    /// Modulo `2π` (wrapping).
    #[inline]
    fn add(self, rhs: Self) -> Self {
        self.wrapping_add(rhs)
    }
}

impl Sub for BinaryAngle {
    type Output = Self;
    /// Modulo `2π` (wrapping).
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        self.wrapping_sub(rhs)
    }
}

impl Neg for BinaryAngle {
    type Output = Self;
    /// Modulo `2π` (wrapping).
    #[inline]
    fn neg(self) -> Self {
        self.wrapping_neg()
    }
}

// ---------------------------------------------------------------------------
// Kernels
// ---------------------------------------------------------------------------

/// `floor(a · b / 2¹⁶)` for `b < 2¹⁶` from two 16 × 16 → 32 products
/// (exact as long as the result fits in `u32`).
#[inline]
const fn mulhi_u32_u16(a: u32, b: u32) -> u32 {
    (a >> 16) * b + (((a & 0xFFFF) * b) >> 16)
}

/// `sin(t · π/32768)` for `t ∈ [0, 16384]` (the first quadrant), in Q22
/// (`2²² = 1`), by linear interpolation of [`SIN_Q16`].
#[inline]
fn sin_quadrant_q22(t: u32) -> u32 {
    let i = (t >> 6) as usize; // 0 ..= 256
    let f = t & 63;
    if i >= SIN_Q16.len() {
        return 1 << 22;
    }
    let lo = SIN_Q16[i] as u32;
    let hi = if i + 1 < SIN_Q16.len() {
        SIN_Q16[i + 1] as u32
    } else {
        1 << 16
    };
    // The table is increasing, so hi - lo ≥ 0; (hi - lo)·f ≤ 402·63.
    (lo << 6) + (hi - lo) * f
}

/// `|sin|` in Q15 of a first-quadrant angle `t ∈ [0, 16384]` codes;
/// `sin(π/2) = 1` saturates to `MAX`.
#[inline]
fn sin_quadrant_magnitude(t: u32) -> i16 {
    let m = (sin_quadrant_q22(t) + (1 << 6)) >> 7; // round Q22 → Q15
    if m > i16::MAX as u32 {
        i16::MAX
    } else {
        m as i16
    }
}

/// Quadrant reduction of the angle `u · 2π/65536`: the first-quadrant
/// angle `t` with `|sin u| = sin t` (then `|cos u| = sin(π/2 - t)`), and
/// the quadrant `u >> 14`.
#[inline]
fn reduce_quadrant(u: u16) -> (u32, u16) {
    let quadrant = u >> 14;
    let r = (u & 0x3FFF) as u32;
    let t = if quadrant & 1 == 0 { r } else { (1 << 14) - r };
    (t, quadrant)
}

/// Sine of the angle `u · 2π/65536`.
#[inline]
fn sin_turn_code(u: u16) -> i16 {
    let (t, quadrant) = reduce_quadrant(u);
    let m = sin_quadrant_magnitude(t);
    // sin < 0 in quadrants 2, 3.
    if quadrant >= 2 {
        -m
    } else {
        m
    }
}

/// Cosine of the angle `u · 2π/65536`, from the same reduction as
/// [`sin_turn_code`]: `|cos u| = sin(π/2 - t)`.
#[inline]
fn cos_turn_code(u: u16) -> i16 {
    let (t, quadrant) = reduce_quadrant(u);
    let m = sin_quadrant_magnitude((1 << 14) - t);
    // cos < 0 in quadrants 1, 2.
    if quadrant == 1 || quadrant == 2 {
        -m
    } else {
        m
    }
}

/// Sine of a binary angle.
///
/// Quadrant reduction (exact), then linear interpolation in a 256-segment
/// quarter-wave table (`SIN_Q16`, Q16) on a 32-bit accumulator, rounded once
/// to Q15; `sin(±π/2) = ±MAX`. Odd: `sin(-a) = -sin(a)` exactly.
/// Domain: every angle. Proven bound: ≤ 1 LSB (exhaustive over all `2¹⁶`
/// angles).
///
/// ```
/// use mrr_control::scalar::q15::{self, BinaryAngle};
/// let s = q15::sin(BinaryAngle::from_radians(core::f64::consts::FRAC_PI_6));
/// assert!((q15::to_f64(s) - 0.5).abs() <= 2f64.powi(-15));
/// ```
#[inline]
pub fn sin(a: BinaryAngle) -> Q15 {
    Q15::from_bits(sin_turn_code(a.to_turn_code()))
}

/// Cosine of a binary angle: `±sin(π/2 - t)` from [`sin`]'s quadrant
/// reduction, bit-equal to `sin(a + π/2)`; `cos(0) = MAX`. Even:
/// `cos(-a) = cos(a)` exactly. Proven bound: ≤ 1 LSB (exhaustive over all
/// `2¹⁶` angles).
#[inline]
pub fn cos(a: BinaryAngle) -> Q15 {
    Q15::from_bits(cos_turn_code(a.to_turn_code()))
}

/// `(sin a, cos a)`, equal bit for bit to `(sin(a), cos(a))` (proven
/// exhaustively).
#[inline]
pub fn sin_cos(a: BinaryAngle) -> (Q15, Q15) {
    // One quadrant reduction for both; bit-equal to (sin(a), cos(a)).
    let (t, quadrant) = reduce_quadrant(a.to_turn_code());
    let s = sin_quadrant_magnitude(t);
    let c = sin_quadrant_magnitude((1 << 14) - t);
    (
        Q15::from_bits(if quadrant >= 2 { -s } else { s }),
        Q15::from_bits(if quadrant == 1 || quadrant == 2 {
            -c
        } else {
            c
        }),
    )
}

/// `atan(r / 2¹⁶)` for `r ∈ [0, 2¹⁶]`, in Q25 radians, by linear
/// interpolation of the 128-segment table [`ATAN_Q16`].
#[inline]
fn atan_unit_q25(r: u32) -> u32 {
    let i = (r >> 9) as usize; // 0 ..= 128
    let f = r & 511;
    if i + 1 >= ATAN_Q16.len() {
        return (ATAN_Q16[ATAN_Q16.len() - 1] as u32) << 9;
    }
    let lo = ATAN_Q16[i] as u32;
    let hi = ATAN_Q16[i + 1] as u32;
    // Increasing table: hi - lo ∈ [0, 512]; (hi - lo)·f < 2¹⁸.
    (lo << 9) + (hi - lo) * f
}

/// Arctangent in radians, as Q15: `atan(x) ∈ [-π/4, π/4)` for
/// `x ∈ [-1, 1)`.
///
/// `|x|` indexes the 128-segment table `ATAN_Q16` (Q16 radians) directly
/// (no division), linear interpolation on a 32-bit accumulator, one final
/// rounding; odd in `x`. Domain: every input. Proven bound: ≤ 1 LSB
/// (exhaustive over all `2¹⁶` inputs); non-decreasing (exhaustive).
///
/// ```
/// use mrr_control::scalar::q15::{self, Q15};
/// let a = q15::atan(Q15::from_num(0.5));
/// assert!((q15::to_f64(a) - 0.5f64.atan()).abs() <= 2f64.powi(-15));
/// ```
#[inline]
pub fn atan(x: Q15) -> Q15 {
    let b = x.to_bits();
    let r = (b as i32).unsigned_abs() << 1; // Q16, ≤ 2¹⁶
    let m = ((atan_unit_q25(r) + (1 << 9)) >> 10) as i16; // ≤ 25736
    Q15::from_bits(if b < 0 { -m } else { m })
}

/// Four-quadrant arctangent of `y / x` as a [`BinaryAngle`] in `[-π, π)`
/// (`atan2(0, -x) = -π ≡ π`); `atan2(0, 0) = 0`.
///
/// Octant reduction `r = min(|x|,|y|) / max(|x|,|y|)` rounded into Q16
/// by a 16-step shift-and-subtract division (no divide instruction),
/// `atan(r)` from the `ATAN_Q16` table (Q25 radians), conversion to `2⁻¹¹` codes with two 16 × 16 products
/// (`× 2/π`), exact octant reflections, one final rounding.
/// Domain: every pair. Proven bound: ≤ 1 code (`≈ 9.6e-5 rad`) modulo the
/// turn, exhaustive over all `2³²` pairs `(y, x)`.
///
/// ```
/// use mrr_control::scalar::q15::{self, Q15};
/// let a = q15::atan2(Q15::from_num(-0.5), Q15::from_num(-0.5));
/// assert!((a.to_radians() + 0.75 * core::f64::consts::PI).abs() <= 9.6e-5);
/// ```
#[inline]
pub fn atan2(y: Q15, x: Q15) -> BinaryAngle {
    let (yb, xb) = (y.to_bits(), x.to_bits());
    let ax = (xb as i32).unsigned_abs(); // ≤ 2¹⁵
    let ay = (yb as i32).unsigned_abs();
    let steep = ay > ax;
    let (num, den) = if steep { (ax, ay) } else { (ay, ax) };
    if den == 0 {
        // den = max(|x|, |y|): only atan2(0, 0) = 0 (no division-by-zero
        // branch in the generated code).
        return BinaryAngle::ZERO;
    }
    let r = ratio::<16>(num, den);
    // Q25 rad → units of 2⁻¹¹ code: × (2¹¹·32768/π)/2²⁵ = × 2/π.
    let mut a = mulhi_u32_u16(atan_unit_q25(r), TWO_OVER_PI_Q16) as i32; // ≤ 2²⁴
    if steep {
        a = (1 << 25) - a; // π/2 - a
    }
    if xb < 0 {
        a = (1 << 26) - a; // π - a
    }
    if yb < 0 {
        a = -a;
    }
    // a ∈ [-2²⁶, 2²⁶]: round to codes; +π (32768) wraps to -π.
    BinaryAngle(((a + (1 << 10)) >> 11) as i16)
}

/// `round(num / den · 2^BITS) ∈ [0, 2^BITS]` (ties up) for `0 ≤ num ≤ den`,
/// `0 < den ≤ 2¹⁵`, `BITS ≤ 16`, by `BITS` steps of restoring long
/// division (shift, compare, subtract) on one register holding the remainder in its high half and the
/// quotient bits in its low half. A Cortex-M0+ has no divide instruction;
/// this is about 5 instructions a step, against ~190 for the generic
/// `__aeabi_uidiv`.
#[inline]
fn ratio<const BITS: u32>(num: u32, den: u32) -> u32 {
    if num >= den {
        return 1 << BITS; // num = den
    }
    // R = rem·2¹⁶ + q, with rem < den ≤ 2¹⁵ so 2·rem fits in the high half.
    let d = den << 16;
    let mut r = num << 16;
    let mut k = 0;
    while k < BITS {
        r <<= 1;
        if r >= d {
            r = r - d + 1;
        }
        k += 1;
    }
    // q = ⌊num·2^BITS/den⌋ (in the low BITS bits), rem = the high half.
    let (q, rem) = (r & 0xFFFF, r >> 16);
    q + ((rem << 1) >= den) as u32
}

/// `2/π` in Q16, rounded (`41721.5…`).
const TWO_OVER_PI_Q16: u32 = 41722;

/// Square root of a normalized value: `√x ∈ [0, 1)` for `x ∈ [0, 1)`;
/// `x < 0` returns 0.
///
/// Digit-by-digit integer square root of `x·2¹⁵` (15 iterations of 32-bit
/// shift/subtract/compare, no multiply), then one correct rounding. Proven
/// bound: ≤ 0.5 LSB, i.e. correctly rounded (exhaustive over all `2¹⁶`
/// inputs; also an integer property for Kani); non-decreasing.
///
/// ```
/// use mrr_control::scalar::q15::{self, Q15};
/// assert_eq!(q15::sqrt(Q15::from_num(0.25)), Q15::from_num(0.5));
/// assert_eq!(q15::sqrt(Q15::from_num(-0.25)), q15::ZERO);
/// ```
#[inline]
pub fn sqrt(x: Q15) -> Q15 {
    let b = x.to_bits();
    if b <= 0 {
        return ZERO;
    }
    let n = (b as u32) << 15; // < 2³⁰
    let mut rem = n;
    let mut root = 0u32;
    let mut bit = 1u32 << 28; // highest power of 4 ≤ n's bound
    while bit != 0 {
        if rem >= root + bit {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    // root = ⌊√n⌋, rem = n - root²; round up when n > root² + root,
    // i.e. n ≥ (root + ½)² + ¾.
    if rem > root {
        root += 1;
    }
    Q15::from_bits(if root > i16::MAX as u32 {
        i16::MAX
    } else {
        root as i16
    })
}

/// `e^x` for a normalized non-positive argument `x ∈ [-1, 0]`, in
/// `[e⁻¹, 1]`: the exponentials of the thesis are all of this kind
/// (`e^{-c_w|τ_w|}` of eq. 2.29, `e^{-f_τ q̇²}` of eq. 4.7), with the
/// argument scaled once at configuration time so that it lies in `[-1, 0]`.
/// `x ≥ 0` returns [`MAX`] (`e⁰ = 1` saturated; positive arguments are
/// outside the domain and saturate the same way).
///
/// `e^x = e^{-i/32} · e^{-f}` with `i = ⌊-x·32⌋` from the 33-entry table
/// `EXP_NEG_Q30` and `e^{-f} ≈ 1 - f + f²/2` (`0 ≤ f < 2⁻⁵`) in Q16, one
/// 32 × 16 product from two 16 × 16 products, one final rounding.
/// Proven bound: ≤ 1 LSB over `[-1, 0]` (exhaustive over all `2¹⁵ + 1`
/// inputs of the domain, and `MAX` for every positive input);
/// non-decreasing over all `2¹⁶` inputs.
///
/// ```
/// use mrr_control::scalar::q15::{self, Q15};
/// let e = q15::exp_neg(Q15::from_num(-0.5));
/// assert!((q15::to_f64(e) - (-0.5f64).exp()).abs() <= 2f64.powi(-15));
/// assert_eq!(q15::exp_neg(Q15::from_num(0.5)), q15::MAX);
/// ```
#[inline]
pub fn exp_neg(x: Q15) -> Q15 {
    let b = x.to_bits();
    if b >= 0 {
        return MAX;
    }
    let m = (b as i32).unsigned_abs(); // -x in Q15: 1 ..= 2¹⁵
    let i = (m >> 10) as usize; // 0 ..= 32
    let f = m & 1023; // < 2⁻⁵ in Q15
    let e = EXP_NEG_Q30[i];
    let v = if f == 0 {
        e
    } else {
        // 1 - f + f²/2 in Q16; f ≥ 1 keeps it ≤ 65534 (16 bits).
        let q = (1 << 16) - (f << 1) + ((f * f + (1 << 14)) >> 15);
        mulhi_u32_u16(e, q)
    };
    let r = (v + (1 << 14)) >> 15; // Q30 → Q15, ≤ 2¹⁵
    Q15::from_bits(if r > i16::MAX as u32 {
        i16::MAX
    } else {
        r as i16
    })
}

// ---------------------------------------------------------------------------
// Tables (generated with f64 `sin`, `atan`, `exp`, rounded to nearest; the
// unit tests below regenerate and compare them)
// ---------------------------------------------------------------------------

/// `round(sin(i·π/512) · 2¹⁶)`, `i = 0..256` (the entry for `i = 256`,
/// `2¹⁶`, is implicit).
const SIN_Q16: [u16; 256] = [
    0, 402, 804, 1206, 1608, 2010, 2412, 2814, 3216, 3617, 4019, 4420, 4821, 5222, 5623, 6023,
    6424, 6824, 7224, 7623, 8022, 8421, 8820, 9218, 9616, 10014, 10411, 10808, 11204, 11600, 11996,
    12391, 12785, 13180, 13573, 13966, 14359, 14751, 15143, 15534, 15924, 16314, 16703, 17091,
    17479, 17867, 18253, 18639, 19024, 19409, 19792, 20175, 20557, 20939, 21320, 21699, 22078,
    22457, 22834, 23210, 23586, 23961, 24335, 24708, 25080, 25451, 25821, 26190, 26558, 26925,
    27291, 27656, 28020, 28383, 28745, 29106, 29466, 29824, 30182, 30538, 30893, 31248, 31600,
    31952, 32303, 32652, 33000, 33347, 33692, 34037, 34380, 34721, 35062, 35401, 35738, 36075,
    36410, 36744, 37076, 37407, 37736, 38064, 38391, 38716, 39040, 39362, 39683, 40002, 40320,
    40636, 40951, 41264, 41576, 41886, 42194, 42501, 42806, 43110, 43412, 43713, 44011, 44308,
    44604, 44898, 45190, 45480, 45769, 46056, 46341, 46624, 46906, 47186, 47464, 47741, 48015,
    48288, 48559, 48828, 49095, 49361, 49624, 49886, 50146, 50404, 50660, 50914, 51166, 51417,
    51665, 51911, 52156, 52398, 52639, 52878, 53114, 53349, 53581, 53812, 54040, 54267, 54491,
    54714, 54934, 55152, 55368, 55582, 55794, 56004, 56212, 56418, 56621, 56823, 57022, 57219,
    57414, 57607, 57798, 57986, 58172, 58356, 58538, 58718, 58896, 59071, 59244, 59415, 59583,
    59750, 59914, 60075, 60235, 60392, 60547, 60700, 60851, 60999, 61145, 61288, 61429, 61568,
    61705, 61839, 61971, 62101, 62228, 62353, 62476, 62596, 62714, 62830, 62943, 63054, 63162,
    63268, 63372, 63473, 63572, 63668, 63763, 63854, 63944, 64031, 64115, 64197, 64277, 64354,
    64429, 64501, 64571, 64639, 64704, 64766, 64827, 64884, 64940, 64993, 65043, 65091, 65137,
    65180, 65220, 65259, 65294, 65328, 65358, 65387, 65413, 65436, 65457, 65476, 65492, 65505,
    65516, 65525, 65531, 65535,
];

/// `round(atan(i/128) · 2¹⁶)`, `i = 0..=128` (Q16 radians).
const ATAN_Q16: [u16; 129] = [
    0, 512, 1024, 1536, 2047, 2559, 3070, 3580, 4091, 4600, 5110, 5618, 6126, 6633, 7140, 7645,
    8150, 8653, 9156, 9657, 10158, 10657, 11155, 11652, 12147, 12641, 13133, 13624, 14114, 14601,
    15088, 15572, 16055, 16536, 17015, 17492, 17968, 18441, 18913, 19382, 19850, 20315, 20779,
    21240, 21699, 22156, 22610, 23062, 23512, 23960, 24406, 24849, 25289, 25727, 26163, 26597,
    27028, 27456, 27882, 28306, 28727, 29145, 29561, 29975, 30386, 30794, 31200, 31603, 32003,
    32401, 32797, 33190, 33580, 33968, 34353, 34735, 35115, 35492, 35867, 36239, 36608, 36975,
    37340, 37701, 38060, 38417, 38771, 39123, 39472, 39818, 40162, 40503, 40842, 41178, 41512,
    41844, 42172, 42499, 42823, 43145, 43464, 43780, 44095, 44407, 44716, 45024, 45328, 45631,
    45931, 46229, 46525, 46818, 47109, 47398, 47685, 47969, 48251, 48531, 48809, 49085, 49359,
    49630, 49899, 50167, 50432, 50695, 50956, 51215, 51472,
];
/// `round(e^{-i/32} · 2³⁰)`, `i = 0..=32` (Q30).
const EXP_NEG_Q30: [u32; 33] = [
    1073741824, 1040706261, 1008687096, 977653056, 947573834, 918420052, 890163238, 862775794,
    836230973, 810502851, 785566300, 761396966, 737971244, 715266256, 693259826, 671930464,
    651257337, 631220255, 611799650, 592976553, 574732583, 557049920, 539911296, 523299971,
    507199724, 491594829, 476470046, 461810604, 447602185, 433830914, 420483340, 407546428,
    395007542,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_match_their_generators() {
        for (i, &v) in SIN_Q16.iter().enumerate() {
            let r = ((i as f64) * core::f64::consts::PI / 512.0).sin() * 65536.0;
            assert_eq!(v as f64, r.round(), "SIN_Q16[{i}]");
        }
        for (i, &v) in ATAN_Q16.iter().enumerate() {
            let r = (i as f64 / 128.0).atan() * 65536.0;
            assert_eq!(v as f64, r.round(), "ATAN_Q16[{i}]");
        }
        for (i, &v) in EXP_NEG_Q30.iter().enumerate() {
            let r = (-(i as f64) / 32.0).exp() * 2f64.powi(30);
            assert_eq!(v as f64, r.round(), "EXP_NEG_Q30[{i}]");
        }
        assert_eq!(
            TWO_OVER_PI_Q16 as f64,
            (2.0 / core::f64::consts::PI * 65536.0).round()
        );
        let tables = core::mem::size_of_val(&SIN_Q16)
            + core::mem::size_of_val(&ATAN_Q16)
            + core::mem::size_of_val(&EXP_NEG_Q30);
        assert_eq!(tables, 902);
    }

    #[test]
    fn ratio_matches_rounded_integer_division() {
        // Every denominator; numerators on a stride plus the edges (the
        // exhaustive atan2 proof covers every pair through the kernel).
        for den in 1..=32768u32 {
            let mut nums: std::vec::Vec<u32> = (0..=den).step_by(97).collect();
            nums.extend([den, den - 1, den / 2, den.div_ceil(2)]);
            for num in nums {
                let expected = ((num << 16) + (den >> 1)) / den;
                assert_eq!(ratio::<16>(num, den), expected, "{num}/{den}");
                if den < 32768 {
                    let expected = ((num << 15) + (den >> 1)) / den;
                    assert_eq!(ratio::<15>(num, den), expected, "{num}/{den} Q15");
                }
            }
        }
    }

    #[test]
    fn mul_rounds_and_saturates() {
        assert_eq!(mul_bits(1 << 14, 1 << 14), 1 << 13); // ½·½ = ¼
        assert_eq!(mul_bits(1, 1 << 14), 1); // ½ LSB rounds up
        assert_eq!(mul_bits(-1, 1 << 14), 0); // -½ LSB rounds toward +∞
        assert_eq!(mul_bits(i16::MIN, i16::MIN), i16::MAX);
        assert_eq!(mul_bits(i16::MIN, i16::MAX), -i16::MAX);
        assert_eq!(mul_bits(i16::MAX, i16::MAX), i16::MAX - 1);
    }

    #[test]
    fn saturating_add_sub_neg() {
        assert_eq!(add(MAX, LSB), MAX);
        assert_eq!(sub(MIN, LSB), MIN);
        assert_eq!(neg(MIN), MAX);
    }

    #[test]
    fn binary_angle_conversions() {
        use core::f64::consts::PI;
        assert_eq!(BinaryAngle::from_radians(PI / 2.0), BinaryAngle::FRAC_PI_2);
        assert_eq!(BinaryAngle::from_radians(PI), BinaryAngle::PI);
        assert_eq!(BinaryAngle::from_radians(-PI), BinaryAngle::PI);
        assert_eq!(BinaryAngle::from_radians(2.0 * PI), BinaryAngle::ZERO);
        assert_eq!(BinaryAngle::from_radians(-5.0 * PI / 2.0).to_bits(), -16384);
        assert_eq!(BinaryAngle::from_radians(f64::NAN), BinaryAngle::ZERO);
        assert_eq!(BinaryAngle::from_radians(f64::INFINITY), BinaryAngle::ZERO);
        for code in [-32768i16, -1, 0, 1, 12345, 32767] {
            let a = BinaryAngle::from_bits(code);
            assert_eq!(BinaryAngle::from_radians(a.to_radians()), a);
            assert_eq!(BinaryAngle::from_half_turns(a.to_half_turns()), a);
        }
        let a = BinaryAngle::from_bits(30000);
        let b = BinaryAngle::from_bits(10000);
        assert_eq!((a + b).to_bits(), 40000i32.wrapping_sub(65536) as i16);
        assert_eq!((-a - b).to_bits(), -40000i32.wrapping_add(65536) as i16);
        assert_eq!(-BinaryAngle::PI, BinaryAngle::PI);
        assert_eq!(BinaryAngle::PI.to_turn_code(), 32768);
    }

    #[test]
    fn full_scale_rejects_bad_scales() {
        assert!(FullScale::try_new("v", 0.0).is_err());
        assert!(FullScale::try_new("v", -1.0).is_err());
        assert!(FullScale::try_new("v", f64::NAN).is_err());
        assert!(FullScale::try_new("v", f64::INFINITY).is_err());
        let s = FullScale::try_new("v", 2.0).unwrap();
        assert_eq!(s.quantize(1.0), Q15::from_num(0.5));
        assert_eq!(s.quantize(-3.0), MIN);
        assert_eq!(s.quantize(f64::NAN), ZERO);
        assert_eq!(s.to_si(Q15::from_num(0.25)), 0.5);
    }

    #[test]
    fn kernel_hand_values() {
        let q = |v: f64| from_f64(v);
        assert_eq!(sin(BinaryAngle::ZERO), ZERO);
        assert_eq!(sin(BinaryAngle::FRAC_PI_2), MAX);
        assert_eq!(sin(-BinaryAngle::FRAC_PI_2), -MAX);
        assert_eq!(cos(BinaryAngle::ZERO), MAX);
        assert_eq!(cos(BinaryAngle::PI), -MAX);
        assert_eq!(sin(BinaryAngle::PI), ZERO);
        assert_eq!(atan2(ZERO, ZERO), BinaryAngle::ZERO);
        assert_eq!(atan2(ZERO, q(0.5)), BinaryAngle::ZERO);
        assert_eq!(atan2(ZERO, q(-0.5)), BinaryAngle::PI);
        assert_eq!(atan2(q(0.5), ZERO), BinaryAngle::FRAC_PI_2);
        assert_eq!(atan2(q(-0.5), ZERO), -BinaryAngle::FRAC_PI_2);
        assert_eq!(atan2(q(0.5), q(0.5)).to_bits(), 8192);
        assert_eq!(atan2(MIN, MIN).to_bits(), -3 * 8192);
        assert_eq!(atan(ZERO), ZERO);
        assert_eq!(atan(MIN), q(-core::f64::consts::FRAC_PI_4));
        assert_eq!(sqrt(MIN), ZERO);
        assert_eq!(sqrt(MAX), MAX);
        assert_eq!(sqrt(LSB).to_bits(), 181); // √(2⁻¹⁵) = 181.02 LSB
        assert_eq!(exp_neg(ZERO), MAX);
        assert_eq!(exp_neg(MAX), MAX);
        assert_eq!(exp_neg(MIN), q((-1.0f64).exp()));
    }
}
