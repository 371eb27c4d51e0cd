//! `f32` kernels for single-precision FPUs (Cortex-M4F): the crate's own
//! range reductions and polynomials, in `f32` and integer arithmetic only.
//!
//! # Design
//!
//! * No `libm`, no `f64` (soft-float on a Cortex-M4F), no 64-bit division.
//!   Integer work uses `u32 × u32 → u64` products (one `UMULL`) and
//!   `leading_zeros` (one `CLZ`). Every kernel is straight-line code with a
//!   few forward branches and no loops or calls; the instruction counts
//!   quoted below are the sizes of each kernel compiled alone for
//!   `thumbv7em-none-eabihf` (release, `opt-level = 3`), so they bound the
//!   instructions executed on any path.
//! * No fused multiply-add is used (Rust never contracts `a * b + c`), so the
//!   host and the target compute bit-identical results and the exhaustive
//!   host proofs hold on the target. The proofs assume IEEE-754 binary32
//!   arithmetic with round-to-nearest and gradual underflow (the Cortex-M4F
//!   reset state of `FPSCR`: `FZ = 0`, `RMode = 0`).
//! * A NaN argument is treated as 0; results are never NaN.
//!
//! # Polynomials
//!
//! Each polynomial approximates the *remainder* after the exactly known
//! leading terms (`x + x³·P(x²)`, `1 + r + r²·P(r)`, ...), so its evaluation
//! error is scaled down by the small size of that remainder. The coefficients
//! are Chebyshev (near-minimax) fits of the remainder function on the reduced
//! interval, computed with `mpmath.chebyfit` at 50 digits and rounded to
//! `f32`, except those of [`tan`] and [`exp`]: minimax (Remez) fits for the
//! relative error of the result, one coefficient shorter than the Chebyshev
//! fits they replace and still far below the `f32` rounding (a relative
//! error of a few 1e-9).
//! `proofs/kernels_f32_coefficients.py` regenerates them all. The error
//! bounds do not rely on the fit's own error estimate: each is proven by the
//! exhaustive engine over every `f32` input of the domain against an `f64`
//! reference (see `proofs/kernels_f32.rs`; run with
//! `cargo test --release --lib -- --ignored exhaustive_ --test-threads 1 --nocapture`).
//!
//! Errors are in ulp of the reference's `f32` binade (`ulp_error_f32` in the
//! proofs; subnormal results in ulp `2^-149`); 0.5 ulp is correct rounding.

/// Largest `f32` below π/2: the edge of the principal branch of [`tan`].
pub const TAN_DOMAIN_EDGE: f32 = 1.570_796_2;

/// Largest `f32` whose exponential is finite in `f32` (just below
/// `ln(f32::MAX) = 88.722839…`); [`exp`] returns `f32::MAX` above it.
pub const EXP_MAX_ARG: f32 = f32::from_bits(0x42b1_7217); // 88.722_83

/// Smallest argument for which [`exp`] is not flushed to 0: `e^x` rounds to
/// 0 (is below half the smallest subnormal, `2^-150`) for every `f32` below it.
pub const EXP_MIN_ARG: f32 = f32::from_bits(0xc2cf_f1b4); // -103.972_08

const SIGN: u32 = 0x8000_0000;

/// π/2 = `FRAC_PI_2_HI + FRAC_PI_2_LO` (+ 1.7e-15).
const FRAC_PI_2_HI: f32 = f32::from_bits(0x3fc9_0fdb);
const FRAC_PI_2_LO: f32 = f32::from_bits(0xb33b_bd2e);
/// π = `PI_HI + PI_LO` (+ 3.4e-15).
const PI_HI: f32 = f32::from_bits(0x4049_0fdb);
const PI_LO: f32 = f32::from_bits(0xb3bb_bd2e);
/// π/4 rounded up: below it no reduction is needed.
pub(crate) const FRAC_PI_4_UP: u32 = 0x3f49_0fdb;

#[inline]
fn denan(x: f32) -> f32 {
    if x.is_nan() {
        0.0
    } else {
        x
    }
}

#[inline]
fn with_sign(magnitude: f32, sign: u32) -> f32 {
    f32::from_bits(magnitude.to_bits() ^ sign)
}

/// Horner evaluation of `c[0] + c[1] z + c[2] z² + …`.
#[inline(always)]
fn horner<const N: usize>(z: f32, c: &[f32; N]) -> f32 {
    let mut p = c[N - 1];
    let mut i = N - 1;
    while i > 0 {
        i -= 1;
        p = p * z + c[i];
    }
    p
}

// ---------------------------------------------------------------- atan ----

/// `atan(u) ≈ u + u³·Q(u²)` on `u ∈ [0, 0.6]` (degree 6 in `u²`).
const ATAN_Q: [f32; 7] = [
    -0.333_333_34,
    0.199_999_44,
    -0.142_831_73,
    0.110_673_43,
    -0.087_226_37,
    0.060_235_15,
    -0.024_739_42,
];
/// π/4 = `FRAC_PI_4_HI + FRAC_PI_4_LO` (+ 8.6e-16).
const FRAC_PI_4_HI: f32 = f32::from_bits(0x3f49_0fdb);
const FRAC_PI_4_LO: f32 = f32::from_bits(0xb2bb_bd2e);
/// 0.6 and 1/0.6: the branch points of [`atan_nonneg`].
pub(crate) const ATAN_LOW: f32 = 0.6;
pub(crate) const ATAN_HIGH: f32 = 1.666_666_6;

/// `atan(u)` for `|u| ≤ 0.6` by the polynomial (exact for subnormal `u`).
#[inline(always)]
pub(crate) fn atan_poly(u: f32) -> f32 {
    let z = u * u;
    u + u * z * horner(z, &ATAN_Q)
}

/// Arctangent of a non-negative `u` (`+∞` included) in three branches, each
/// non-decreasing in `u` (every rounding step is monotone and the
/// polynomial's correction term is small against the step of its argument):
///
/// * `u ≤ 0.6`: `atan_poly(u)`;
/// * `0.6 < u ≤ 1/0.6`: `π/4 + atan v` with `v = (u−1)/(u+1) ∈ [−¼, ¼]`
///   (`u − 1` is exact by Sterbenz);
/// * `u > 1/0.6`: `π/2 − atan(1/u)`.
#[inline(always)]
fn atan_nonneg(u: f32) -> f32 {
    if u <= ATAN_LOW {
        atan_poly(u)
    } else if u <= ATAN_HIGH {
        FRAC_PI_4_HI + (atan_poly(atan_mid_ratio(u)) + FRAC_PI_4_LO)
    } else {
        FRAC_PI_2_HI - (atan_poly(recip(u)) - FRAC_PI_2_LO)
    }
}

/// `(u − 1)/(u + 1)`, the argument of the middle branch of [`atan_nonneg`]
/// (`u − 1` is exact by Sterbenz on `(0.6, 1/0.6]`).
#[inline(always)]
pub(crate) fn atan_mid_ratio(u: f32) -> f32 {
    (u - 1.0) / (u + 1.0)
}

/// Arctangent, in radians, in `[-π/2, π/2]` (thesis eq. 2.26 uses it for the
/// kinematic-error phase).
///
/// * Domain: every `f32` (`±∞ → ±π/2` rounded to nearest, NaN → 0).
/// * Algorithm: odd symmetry; then `atan_nonneg`: the reductions
///   `atan u = π/4 + atan((u−1)/(u+1))` on `(0.6, 1/0.6]` and
///   `atan u = π/2 − atan(1/u)` above bring the argument to `[0, 0.6]`, where
///   `atan u = u + u³·Q(u²)` with `Q` a degree-6 Chebyshev fit; π/4 and π/2
///   are split in two `f32`s.
/// * Proven bound: **2 ulp** over every `f32`, non-decreasing over every pair
///   of adjacent `f32`s, and exactly odd: all three by the exhaustive engine,
///   `exhaustive_atan_f32` (every `x ≥ 0` code, negatives by the proven
///   oddness). Measured maximum error: 1.115 ulp at `x = 1.8235223`.
/// * Cost: ≤ 86 Thumb-2 instructions on a Cortex-M4F (straight-line code,
///   one `VDIV`), vs. ~1,500 for a `libm` call.
#[inline]
pub fn atan(x: f32) -> f32 {
    let bits = x.to_bits();
    let abits = bits & !SIGN;
    if abits > 0x7f80_0000 {
        return 0.0;
    }
    with_sign(atan_nonneg(f32::from_bits(abits)), bits & SIGN)
}

// ----------------------------------------------------------------- tan ----

/// `tan(d) ≈ d + d³·T(d²)` on `d ∈ [0, π/4]` (degree 6 in `d²`, so degree 15
/// in `d`): the minimax fit for the relative error of `tan d` (Remez,
/// 1.3e-9; 3.7e-9 with the coefficients rounded to `f32` and `T[1]` moved
/// one ulp up, which lowers the exhaustively measured maximum of [`tan`]),
/// which is to first order also the relative error of the reflected
/// `1/tan d`.
const TAN_T: [f32; 7] = [
    0.333_333_5,
    0.133_326_65,
    0.054_059_923,
    0.021_282_166,
    0.010_835_859,
    8.948_921e-5,
    0.004_376_292_7,
];

/// Tangent on the principal branch (thesis eq. 3.10, the flexspline
/// pressure-angle term).
///
/// * Domain: `|x| ≤ TAN_DOMAIN_EDGE` (the largest `f32` below π/2). Outside
///   it (and for `±∞`) the result is `±tan(TAN_DOMAIN_EDGE)` with the sign
///   of `x`, so `tan` is non-decreasing over every `f32`; NaN → 0.
/// * Algorithm: odd symmetry; for `|x| < π/4`, `tan x = x + x³·T(x²)` with
///   `T` of degree 6, a minimax fit for the relative error on `[0, π/4]`
///   (the same fit serves the reflection); above, `tan x = 1/tan d`
///   with `d = π/2 − |x|` computed as an unevaluated `f32` pair (the first
///   subtraction is exact by Sterbenz, the rounding error of the second is
///   recovered by Fast2Sum) and folded into the polynomial as `d_lo·(1+d²)`.
/// * Proven bound: **2 ulp** over the domain, non-decreasing over every pair
///   of adjacent `f32`s, exactly odd: all by the exhaustive engine,
///   `exhaustive_tan_f32`. Measured
///   maximum error: 1.612 ulp at `x = 1.1060537`.
/// * Cost: at most 52 Thumb-2 instructions executed on a Cortex-M4F (one
///   `VDIV`; `embedded/count.py`'s worst case over its arguments, less its
///   7-instruction call overhead).
#[inline]
pub fn tan(x: f32) -> f32 {
    let bits = x.to_bits();
    let abits = bits & !SIGN;
    // NaN → 0; beyond the edge (∞ included) → the edge. Integer compares
    // on the magnitude bits (no `fminf` call on targets without VMINNM).
    let ax = if abits > 0x7f80_0000 {
        0.0
    } else if abits > TAN_DOMAIN_EDGE.to_bits() {
        TAN_DOMAIN_EDGE
    } else {
        f32::from_bits(abits)
    };
    tan_of_magnitude(ax, ax.to_bits() >= FRAC_PI_4_UP, bits & SIGN)
}

/// The part of [`tan`] after the argument is limited: `tan ax` for `0 ≤
/// ax ≤ TAN_DOMAIN_EDGE`, given `reflect = ax ≥ π/4` (rounded up, as
/// `FRAC_PI_4_UP`) and the sign bit `sign`.
#[inline(always)]
fn tan_of_magnitude(ax: f32, reflect: bool, sign: u32) -> f32 {
    let (d, d_lo) = if reflect { tan_reflect(ax) } else { (ax, 0.0) };
    let t = tan_poly(d, d_lo);
    let r = if reflect { recip(t) } else { t };
    with_sign(r, sign)
}

/// The largest argument of [`tan_bounded`] (rad): `atan 8` rounded to
/// `f32` (as the estimator converts its bound, `TAN_BOUNDED_ARGUMENT`).
pub const TAN_BOUNDED_MAX: f32 = 1.446_441_332_248_135_f64 as f32;

/// [`tan`] for `|x| ≤ atan 8`, the torque estimator's argument of eq.
/// (3.10) (the `f32` backend's `tan_bounded`):
/// the argument is limited by one floating-point comparison with
/// [`TAN_BOUNDED_MAX`] instead of [`tan`]'s integer tests against the
/// edge of the branch and NaN, and the rest is `tan`'s own code (the
/// M4F joint step's bound is 5 instructions lower with it,
/// `embedded/perfcheck.py joint_f32`).
///
/// * Domain: `|x| ≤ TAN_BOUNDED_MAX`, where the result is **bit for bit**
///   `tan(x)`, so it has `tan`'s proven bound (2 ulp), is non-decreasing
///   and exactly odd. Beyond (`±∞` included) it is `±tan(TAN_BOUNDED_MAX)`
///   (`±8.0000005`) with the sign of `x`, so it is non-decreasing over
///   every number; a NaN is limited the same way (`±8.0000005`, the sign
///   bit of the NaN; the estimator never passes one).
///   `exhaustive_tan_bounded_f32` checks all of it at every magnitude.
#[inline]
pub fn tan_bounded(x: f32) -> f32 {
    let bits = x.to_bits();
    let a = f32::from_bits(bits & !SIGN);
    // One comparison and a select; NaN fails it and takes the bound.
    let ax = if a <= TAN_BOUNDED_MAX {
        a
    } else {
        TAN_BOUNDED_MAX
    };
    // `ax` is a non-negative number: ordered as its bits.
    let reflect = ax >= f32::from_bits(FRAC_PI_4_UP);
    tan_of_magnitude(ax, reflect, bits & SIGN)
}

/// `π/2 − ax` as an unevaluated pair `(d, d_lo)` for `π/4 < ax < π/2`: the
/// first subtraction is exact (Sterbenz), the rounding error of the second
/// is recovered by Fast2Sum (`|s| > |LO|`).
#[inline(always)]
pub(crate) fn tan_reflect(ax: f32) -> (f32, f32) {
    let s = FRAC_PI_2_HI - ax; // exact (Sterbenz)
    let d = s + FRAC_PI_2_LO;
    (d, (s - d) + FRAC_PI_2_LO)
}

/// `tan(d + d_lo)` for `0 ≤ d ≤ π/4` and a correction `|d_lo|` below half
/// an ulp of `d` (0 outside [`tan`]'s reflection): `d + d³·T(d²)` with
/// `d_lo·(1 + d²)`, the first-order change of `tan` at `d`, added.
#[inline(always)]
pub(crate) fn tan_poly(d: f32, d_lo: f32) -> f32 {
    let z = d * d;
    d + (d * z * horner(z, &TAN_T) + d_lo * (1.0 + z))
}

/// `1/t`, one correctly rounded division.
#[inline(always)]
pub(crate) fn recip(t: f32) -> f32 {
    1.0 / t
}

// ----------------------------------------------------------------- exp ----

/// `e^r ≈ 1 + r + r²·E(r)` on `|r| ≤ ln2/2` (`E` of degree 4, so degree 6
/// in all): the minimax fit for the relative error of `e^r` (Remez, 3.1e-9;
/// 3.6e-9 with the coefficients rounded to `f32` and `E[2]` moved one ulp
/// down, which lowers the exhaustively measured maximum of [`exp`]).
const EXP_E: [f32; 5] = [
    0.499_999_94,
    0.166_665_21,
    0.041_668_385,
    0.008_368_71,
    0.001_381_461_3,
];
/// ln 2 = `LN2_HI + LN2_LO`; `LN2_HI` has 16 significant bits so `k·LN2_HI`
/// is exact for `|k| ≤ 255`.
const LN2_HI: f32 = 0.693_145_75;
const LN2_LO: f32 = 1.428_606_8e-6;

/// `e^x` (thesis eqs. 2.29 and 4.7: the exponential stiffness and Stribeck
/// terms).
///
/// * Domain: every `f32` up to [`EXP_MAX_ARG`] (≈ 88.72); above it (and for
///   `+∞`) the result saturates at `f32::MAX`. Results in the subnormal range
///   are kept (gradual underflow, one rounding), and below [`EXP_MIN_ARG`]
///   (≈ −103.97, where `e^x < 2^-150`) the result is 0, which is the
///   correctly rounded value there. NaN → 1.
/// * Algorithm (Cody–Waite): `k = round(x·log2 e)`, `r = x − k·ln2` with ln 2
///   split so that `x − k·LN2_HI` is exact, `e^r = 1 + r + r²·E(r)` with `E`
///   of degree 4 (degree 6 in all), a minimax fit for the relative error on
///   `[−ln2/2, ln2/2]`, then `·2^k` as two exact
///   power-of-two factors so that only the last product rounds (once, also
///   into the subnormal range).
/// * Proven bound: **2 ulp** over every `f32 ≤ EXP_MAX_ARG` (subnormal
///   results measured in the subnormal ulp `2^-149`; the saturation above is
///   checked to happen only where `e^x` rounds to `+∞`), non-decreasing over
///   every pair of adjacent `f32`s: both by the exhaustive engine over all
///   2^32 codes, `exhaustive_exp_f32`. Measured maximum error: 0.976 ulp
///   (at `x = −5.8606462`; `exhaustive_exp_f32` prints it).
/// * Cost: at most 53 Thumb-2 instructions executed on a Cortex-M4F, no
///   division (`embedded/count.py`, less its 7-instruction call overhead).
#[inline]
pub fn exp(x: f32) -> f32 {
    if x.is_nan() {
        return 1.0;
    }
    if x > EXP_MAX_ARG {
        return f32::MAX;
    }
    if x < EXP_MIN_ARG {
        return 0.0;
    }
    let (p, k) = exp_reduced(x);
    // 2^k = 2^k1 · 2^k2 with both factors normal; p·2^k1 is exact.
    let k1 = k >> 1;
    let k2 = k - k1;
    let s1 = f32::from_bits(((k1 + 127) as u32) << 23);
    let s2 = f32::from_bits(((k2 + 127) as u32) << 23);
    p * s1 * s2
}

/// The reduction and polynomial shared by [`exp`] and [`exp_neg_abs`]:
/// `e^x ≈ p·2^k` with `k = round(x·log2 e)` and `p = e^r`, `|r| ≲ ln2/2`.
/// For `EXP_MIN_ARG ≤ x ≤ EXP_MAX_ARG`, `k ∈ [-150, 128]`.
#[inline(always)]
pub(crate) fn exp_reduced(x: f32) -> (f32, i32) {
    // Round to nearest integer: |x·log2 e| < 2^22, so adding 1.5·2^23 leaves
    // the integer part in the last bits.
    const ROUNDER: f32 = 12_582_912.0;
    let kf = (x * core::f32::consts::LOG2_E + ROUNDER) - ROUNDER;
    let k = kf as i32;
    let r = (x - kf * LN2_HI) - kf * LN2_LO;
    (1.0 + (r + r * r * horner(r, &EXP_E)), k)
}

/// Largest `|x|` for which [`exp_neg_abs`] is not flushed to 0: the largest
/// `f32` `a` whose reduction `k = round(a·64/ln 2)` (in `f32`, as the
/// kernel rounds it) is at most `8064 = 126·64`, so that the scaled table
/// value `2^{−j/64}·2^{−m}` (`k = 64m + j`) is a normal `f32`. At the next
/// `f32` `k = 8065`. `e^−a` here is `1.169e-38`, below the smallest normal
/// `f32` (`2^-126 = 1.175e-38`): only values that would be subnormal are
/// flushed.
pub const EXP_NEG_ABS_MAX_ARG: f32 = f32::from_bits(0x42ae_af15); // 87.341_96

/// The table of [`exp_neg_abs`]: entry `j` (`j = 0..64`) is the encoding
/// of `2^{−j/64}` correctly rounded to `f32`, plus `j·2¹⁷` (loaded into an
/// integer register, from which the kernel subtracts `k·2¹⁷ = m·2²³ +
/// j·2¹⁷`: the exponent field drops by `m` and the added `j·2¹⁷` cancels).
/// Generated by `proofs/gen_f32_exp_table.py`; checked by
/// `exp_neg_abs_edges`.
#[rustfmt::skip]
pub(crate) const EXP_NEG_ABS_TABLE: [u32; 64] = [
    0x3f80_0000, 0x3f7f_3e0c, 0x3f7e_83b3, 0x3f7d_d0df,
    0x3f7d_257d, 0x3f7c_8177, 0x3f7b_e4ba, 0x3f7b_4f30,
    0x3f7a_c0c7, 0x3f7a_396a, 0x3f79_b907, 0x3f79_3f89,
    0x3f78_ccdf, 0x3f78_60f5, 0x3f77_fbb8, 0x3f77_9d16,
    0x3f77_44fd, 0x3f76_f35b, 0x3f76_a81e, 0x3f76_6334,
    0x3f76_248c, 0x3f75_ec15, 0x3f75_b9be, 0x3f75_8d75,
    0x3f75_672a, 0x3f75_46cd, 0x3f75_2c4d, 0x3f75_179a,
    0x3f75_08a4, 0x3f74_ff5b, 0x3f74_fbaf, 0x3f74_fd92,
    0x3f75_04f3, 0x3f75_11c4, 0x3f75_23f6, 0x3f75_3b79,
    0x3f75_583f, 0x3f75_7a3a, 0x3f75_a15b, 0x3f75_cd94,
    0x3f75_fed7, 0x3f76_3516, 0x3f76_7043, 0x3f76_b051,
    0x3f76_f532, 0x3f77_3eda, 0x3f77_8d3a, 0x3f77_e046,
    0x3f78_37f0, 0x3f78_942d, 0x3f78_f4f0, 0x3f79_5a2b,
    0x3f79_c3d3, 0x3f7a_31dc, 0x3f7a_a43a, 0x3f7b_1adf,
    0x3f7b_95c2, 0x3f7c_14d5, 0x3f7c_980f, 0x3f7d_1f62,
    0x3f7d_aac3, 0x3f7e_3a29, 0x3f7e_cd87, 0x3f7f_64d2,
];

/// `64/ln 2` rounded to `f32`.
const EXP_NEG_ABS_STEPS_PER_UNIT: f32 = f32::from_bits(0x42b8_aa3b); // 92.332_48
/// `ln 2/64 = STEP_HI + STEP_LO` (to `1e-13`): `STEP_HI = 1420·2⁻¹⁷` has
/// 11 significant bits, so `k·STEP_HI` is exact for every `k ≤ 8064`.
const EXP_NEG_ABS_STEP_HI: f32 = f32::from_bits(0x3c31_8000); // 0.010_833_740_234_375
const EXP_NEG_ABS_STEP_LO: f32 = f32::from_bits(0xb65e_8083); // -3.315_538_2e-6

/// `e^{−|x|}`, the decaying exponential of the wave-generator torsion
/// (thesis eq. (2.29), `e^{−c_w·|τ_w|}`) and of the Stribeck friction term
/// (eq. (4.7), `e^{−f_lτ·q̇²}`), whose exponents are never positive.
///
/// * Domain: every `f32`; the result is in `[0, 1]` and exactly even in
///   `x`. For `|x| ≤` [`EXP_NEG_ABS_MAX_ARG`] (≈ 87.342) within **2 ulp**
///   of `e^{−|x|}` (subnormal results in units of `2^-149`); above it
///   exactly +0, while `e^{−|x|} < 1.17e-38` (below the smallest normal
///   `f32`). NaN → 1 (the NaN convention of [`exp`]: a NaN argument counts
///   as 0).
/// * Algorithm (a table of 64 values instead of [`exp`]'s degree-6
///   polynomial): `a = |x|` (sign bit cleared) and one comparison `a ≤
///   EXP_NEG_ABS_MAX_ARG` that fails for NaN and the flush range alike;
///   `k = round(a·64/ln 2)` by adding and subtracting `1.5·2²³` (`k` is then
///   the low bits of the sum's encoding, `k ≤ 8064`), `r = k·ln 2/64 − a`
///   (`|r| ≤ ln 2/128 + 8e-6`, the rounded product `a·64/ln 2` being
///   within `6e-4` of the exact one: `k·STEP_HI` exact, its difference
///   with `a` exact — by Sterbenz's lemma, or just above the step to
///   `k = 1`, where `STEP_HI` exceeds `2a` by less than `4e-6`, as a
///   multiple of `a`'s ulp `2⁻³¹` below `2⁻⁷` — then `+ k·STEP_LO`), and
///   `e^{−a} = 2^{−k/64}·e^r ≈ s + s·(r + r²/2)` with `s = 2^{−j/64}·2^{−m}`
///   (`k = 64m + j`): the table value with `m` subtracted from its
///   exponent field in an integer register (a normal `f32`: `m ≤ 126`, and
///   `m = 126` only with `j = 0`). The dropped `r³/6` is at most `2.7e-8`
///   relative, the table's rounding `2⁻²⁵`, the final sum rounds once
///   (subnormal results included).
/// * Proven bound: **2 ulp**, 0 above [`EXP_NEG_ABS_MAX_ARG`] with `e^{−|x|}
///   < 1.17e-38`, 1 for NaN, exact evenness: all by the exhaustive engine
///   over every `f32` magnitude, `exhaustive_exp_neg_abs_f32`, which
///   reports the measured maximum ([kernel bounds](crate::docs::verification#kernel-bounds)).
/// * Cost: no polynomial beyond degree 2, no conversion instruction, no
///   division; the Cortex-M4F count of the joint step that calls it twice
///   is in [`docs::performance`](crate::docs::performance) (`embedded/count.py`).
#[inline]
pub fn exp_neg_abs(x: f32) -> f32 {
    let a = f32::from_bits(x.to_bits() & !SIGN);
    // One comparison, false for NaN and for the flush range.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(a <= EXP_NEG_ABS_MAX_ARG) {
        return if a.is_nan() { 1.0 } else { 0.0 };
    }
    exp_neg_of_magnitude(a)
}

/// `e^{−a}` for `0 ≤ a ≤ EXP_NEG_ABS_MAX_ARG`: the table and polynomial of
/// [`exp_neg_abs`] (its own function so that a proof of the sign and range
/// logic around it can take it as uninterpreted).
#[inline(always)]
pub(crate) fn exp_neg_of_magnitude(a: f32) -> f32 {
    const ROUNDER: f32 = 12_582_912.0;
    // a·64/ln 2 ≤ 8064.5 < 2²²: the sum's last 22 bits are k.
    let t = a * EXP_NEG_ABS_STEPS_PER_UNIT + ROUNDER;
    let kf = t - ROUNDER;
    let k = t.to_bits();
    let r = (kf * EXP_NEG_ABS_STEP_HI - a) + kf * EXP_NEG_ABS_STEP_LO;
    let p = r + r * r * 0.5;
    // ROUNDER's encoding is 0x4b40_0000 (bits 0..22 clear, all shifted out
    // by 17): `k << 17` is k·2¹⁷ = m·2²³ + j·2¹⁷ with j = k mod 64 and
    // m = ⌊k/64⌋, which the table's j·2¹⁷ turns into m·2²³.
    let s = f32::from_bits(EXP_NEG_ABS_TABLE[(k & 63) as usize] - (k << 17));
    s + s * p
}

// ------------------------------------------------------------- sin/cos ----

/// `sin r ≈ r + r³·S(r²)` on `|r| ≤ π/4` (degree 3 in `r²`).
const SIN_S: [f32; 4] = [
    -0.166_666_67,
    0.008_333_332,
    -0.000_198_400_87,
    2.724_992_6e-6,
];
/// `cos r ≈ 1 − r²/2 + r⁴·C(r²)` on `|r| ≤ π/4` (degree 2 in `r²`).
const COS_C: [f32; 3] = [0.041_666_664, -0.001_388_830_2, 2.454_794_2e-5];

/// `sin r = r + r³·S(r²)` for `|r| ≤ π/4`, given `z = r·r`: the one
/// expression (one operation order) of [`sin_cos`], [`cos_turn`] and
/// [`sin_cos_turn`], so that their bit identities hold by construction.
#[inline(always)]
fn sin_poly(r: f32, z: f32) -> f32 {
    r + r * z * horner(z, &SIN_S)
}

/// `cos r = 1 − (r²/2 − r⁴·C(r²))` for `|r| ≤ π/4`, given `z = r·r`: the one
/// expression of [`sin_cos`], [`cos_turn`] and [`sin_cos_turn`].
#[inline(always)]
fn cos_poly(z: f32) -> f32 {
    1.0 - (0.5 * z - z * z * horner(z, &COS_C))
}

/// `(sin r, cos r)` for `|r| ≤ π/4` by [`sin_poly`] and [`cos_poly`], one
/// `z = r·r` shared: the core of [`sin_cos`] after its reduction (a
/// function of its own so that a Kani harness can take it as an
/// uninterpreted function; inlined, the same code).
#[inline(always)]
fn sin_cos_poly(r: f32) -> (f32, f32) {
    let z = r * r;
    (sin_poly(r, z), cos_poly(z))
}

/// Bits of 2/π after the binary point, preceded by one zero word (the
/// window of a small argument starts before the binary point).
const TWO_OVER_PI: [u32; 8] = [
    0,
    0xa2f9_836e,
    0x4e44_1529,
    0xfc27_57d1,
    0xf534_ddc0,
    0xdb62_9599,
    0x3c43_9041,
    0xfe51_63ab,
];
/// π/2 · 2^30, rounded.
const FRAC_PI_2_Q30: u64 = 0x6487_ed51;

/// Exact quadrant reduction of a finite `|x| ≥ π/4` given by its bits:
/// returns `(r, n)` with `|x| = n·π/2 + r (mod 2π)`, `|r| ≤ π/4`, `n ∈ 0..4`.
///
/// Integer Payne–Hanek: with `|x| = m·2^(e−23)`, the product of the 24-bit
/// `m` with a 96-bit window of 2/π, chosen so that bits of `|x|·2/π` above
/// 2² (whole turns) are never formed, gives `|x|·2/π mod 4` as a Q2.62
/// fixed-point number with an error below 2^-60. The remainder is then
/// multiplied by π/2 in Q30 (also in integers) and rounded to `f32` once.
#[inline(always)]
pub(crate) fn reduce_quadrant(abits: u32) -> (f32, u32) {
    let e = (abits >> 23) as i32 - 127; // -1 ..= 127
    let m = ((abits & 0x007f_ffff) | 0x0080_0000) as u64;
    let j0 = (e + 7) as u32; // first window bit, counted from the zero word
    let q = (j0 >> 5) as usize;
    let s = j0 & 31;
    let word = |i: usize| {
        ((((TWO_OVER_PI[i] as u64) << 32) | TWO_OVER_PI[i + 1] as u64) << s >> 32) as u32 as u64
    };
    let (w0, w1, w2) = (word(q), word(q + 1), word(q + 2));
    // m·W / 2^32 mod 2^64: Q2.62 quarter turns.
    let f = ((m * w0) << 32)
        .wrapping_add(m * w1)
        .wrapping_add((m * w2) >> 32);
    let n = f.wrapping_add(1 << 61) >> 62;
    let rem = f.wrapping_sub(n << 62) as i64; // |rem| ≤ 2^61
    let a = rem.unsigned_abs();
    let lz = a.leading_zeros(); // ≥ 2 (64 for a = 0)
    let top = (a << (lz & 63)) >> 32; // [2^31, 2^32), or 0
    let prod = top * FRAC_PI_2_Q30; // r = prod · 2^(-60-lz)
    let scale = f32::from_bits((127 - 28 - lz) << 23);
    let r = ((prod >> 32) as u32 as f32) * scale;
    let r = if rem < 0 { -r } else { r };
    (r, n as u32)
}

/// `(sin x, cos x)` of one angle in radians, sharing the argument reduction
/// (thesis eq. 3.7 and the wrist kinematics of ch. 5).
///
/// * Domain: every finite `f32` (the reduction is exact, so e.g.
///   `sin(1e30)` is accurate); `±∞` and NaN give `(0, 1)`.
/// * Algorithm: `|x| < π/4` is used as is; otherwise `reduce_quadrant`
///   (integer Payne–Hanek with 224 bits of 2/π) gives `|x| = n·π/2 + r`.
///   `sin r = r + r³·S(r²)`, `cos r = 1 − (r²/2 − r⁴·C(r²))` with `S`, `C`
///   Chebyshev fits on `[0, π/4]`; the quadrant `n` swaps and negates them;
///   the sine takes the sign of `x`.
/// * Proven bound: **2 ulp** for both over every finite `f32`; `sin` exactly
///   odd, `cos` exactly even, and [`sin`]/[`cos`] bit-equal to the two
///   components: by the exhaustive engine, `exhaustive_sin_f32` and
///   `exhaustive_cos_f32` (every `x ≥ 0` code, negatives by the proven
///   symmetry). Measured maximum error: sin 1.522 ulp at `x = 4.738828e12`,
///   cos 1.520 ulp at `x = 2.3830931e36`.
/// * Cost: ≤ 138 Thumb-2 instructions on a Cortex-M4F for both values, no
///   division (`libm`'s `sinf`/`cosf` cost ~1,200–1,900 each).
#[inline]
pub fn sin_cos(x: f32) -> (f32, f32) {
    let bits = x.to_bits();
    let abits = bits & !SIGN;
    if abits >= 0x7f80_0000 {
        return (0.0, 1.0);
    }
    let (r, n) = if abits < FRAC_PI_4_UP {
        (f32::from_bits(abits), 0)
    } else {
        reduce_quadrant(abits)
    };
    let (s, c) = sin_cos_poly(r);
    let (sv, cv) = if n & 1 == 0 { (s, c) } else { (c, s) };
    // n: 0 → ( s,  c), 1 → ( c, −s), 2 → (−s, −c), 3 → (−c,  s)
    let sin_sign = (n & 2) << 30;
    let cos_sign = ((n + 1) & 2) << 30;
    (
        with_sign(sv, sin_sign ^ (bits & SIGN)),
        with_sign(cv, cos_sign),
    )
}

/// Sine of an angle in radians; the first component of [`sin_cos`] (same
/// domain and proven 2-ulp bound; `±∞` → 0).
#[inline]
pub fn sin(x: f32) -> f32 {
    sin_cos(x).0
}

/// Cosine of an angle in radians; the second component of [`sin_cos`] (same
/// domain and proven 2-ulp bound; `±∞` → 1).
#[inline]
pub fn cos(x: f32) -> f32 {
    sin_cos(x).1
}

/// `2π / 2³²` rounded to `f32` (radians per unit of a binary angle).
const RAD_PER_TURN_UNIT: f32 = 1.462_918_1e-9;

/// Cosine of a binary angle: `cos(2π·turn/2³²)` (thesis eq. 3.7 in the
/// phase form of the torque estimator).
///
/// * Domain: every `u32`; `|result| ≤ 1`; exactly even
///   (`cos_turn(t) = cos_turn(t.wrapping_neg())`).
/// * Algorithm: exact integer reduction: `u = |turn as i32| ∈ [0, 2³¹]`,
///   `k` = the nearest quarter turn (`0, 1, 2`) and `d = u − k·2³⁰ ∈
///   [−2²⁹, 2²⁹)` (exact in `i32`); `r = d·2π/2³²` (one conversion and one
///   product, each rounded), then `cos r` (`k = 0`), `−sin r` (`k = 1`) or
///   `−cos r` (`k = 2`) with the polynomials of [`sin_cos`] (`S`, `C` on
///   `|r| ≤ π/4`). No floating-point range reduction, no division.
/// * Proven bound: **≤ 2⁻²² absolute** (2 ulp of 1), exactly even and
///   `|result| ≤ 1`: `exhaustive_cos_turn_f32` in `proofs/kernels_turn.rs`
///   (every one of the 2³² inputs); measured max 0.905 ulp of 1
///   (1.08e-7) at `turn = 0x60e4f3d0`.
#[inline]
pub fn cos_turn(turn: u32) -> f32 {
    let u = (turn as i32).unsigned_abs(); // [0, 2³¹]
    let k = (u + (1 << 29)) >> 30; // 0, 1, 2
    let d = (u as i32).wrapping_sub((k << 30) as i32); // [−2²⁹, 2²⁹)
    let r = turn_radians(d);
    let z = r * r;
    if k & 1 == 0 {
        let c = cos_poly(z);
        if k == 0 {
            c
        } else {
            -c
        }
    } else {
        -sin_poly(r, z)
    }
}

/// `d·2π/2³²` in radians for a quarter-turn remainder `d ∈ [−2²⁹, 2²⁹]`
/// (one conversion and one product, each rounded; exactly odd in `d`, as
/// both roundings are symmetric). Shared by [`cos_turn`] and
/// [`sin_cos_turn`].
#[inline(always)]
fn turn_radians(d: i32) -> f32 {
    d as f32 * RAD_PER_TURN_UNIT
}

/// `(sin, cos)` of a binary angle, `(sin 2π·turn/2³², cos 2π·turn/2³²)`,
/// with one range reduction for both (thesis eq. (3.7): the kinematic
/// error of the torque estimator, whose harmonics need a sine and a cosine
/// of the same phase).
///
/// * Domain: every `u32`. The result is **bit for bit**
///   `(cos_turn(turn − 2³⁰), cos_turn(turn))` (wrapping subtraction) at
///   every one of the 2³² angles, signed zeros included, so each component
///   inherits the proven bound of [`cos_turn`]: **≤ 2⁻²² absolute**,
///   `|component| ≤ 1`.
/// * Algorithm: exact integer reduction on the unsigned angle: the nearest
///   quarter turn `k = (turn + 2²⁹) >> 30 ∈ 0..4` (wrapping) and
///   `d = (turn − k·2³⁰) as i32 ∈ [−2²⁹, 2²⁹)`. The sine polynomial is
///   evaluated as `cos_turn` does in its odd quadrant, `−s(e)` with
///   `s(r) = r + r³·S(r²)`, at `e = d` for `k = 1, 2` and `e = −d` for
///   `k = 0, 3` (an integer negation, selected by the sign of
///   `turn + 3·2²⁹`); `r = e·2π/2³²`, `z = r²`,
///   `c = 1 − (z/2 − z²·C(z))` (the polynomials and operation order of
///   [`cos_turn`]). Then the quarter-turn rotation, with `σ = −s(e)`:
///   `k = 0 → (σ, c)`, `1 → (c, σ)`, `2 → (σ, −c)`, `3 → (−c, σ)`.
/// * Why it equals two [`cos_turn`] calls: `cos_turn` reduces
///   `u = |turn as i32|` instead, which for each component gives the same
///   quadrant and the remainder `e` (`r(−e) = −r(e)` exactly, `z` is even
///   and `s` odd, so the cosine does not depend on the sign of `e`). Taking
///   `e` rather than `d` for the sine keeps the signed zero: at `e = 0`
///   both sides give `−s(+0) = −0.0` (with `d` and an odd-symmetry sign
///   flip, `turn = 0` and `3·2³⁰` would give `+0.0`). The only other
///   disagreements of the two reductions are the ties `d = −2²⁹` of a
///   negative signed angle (`turn = 0xA000_0000, 0xE000_0000`, and
///   `0x2000_0000` through the shifted cosine), where one side evaluates
///   `s(π/4)` and the other `c(π/4)`; both round to the same `f32`,
///   `0x3f35_04f3` (√½ correctly rounded), so the results agree there too.
///   `exhaustive_sin_cos_turn_f32` in `proofs/kernels_turn.rs` checks the
///   identity at every `u32`.
/// * Cost: 41 Thumb-2 instructions on a Cortex-M4F, straight-line (no
///   branch, three IT blocks), for both values; two [`cos_turn`] calls take
///   46 to 55 on their executed paths (both counted in the disassembly of
///   `thumbv7em-none-eabihf` release builds, `opt-level = 3`, each without
///   its call overhead and result stores). No division.
#[inline]
pub fn sin_cos_turn(turn: u32) -> (f32, f32) {
    let k = turn.wrapping_add(1 << 29) >> 30; // 0..=3
    let d = turn.wrapping_sub(k << 30) as i32; // [−2²⁹, 2²⁹)
                                               // −d for k = 0, 3: exactly when turn + 3·2²⁹ (wrapping) is below 2³¹.
    let e = if (turn.wrapping_add(3 << 29) as i32) < 0 {
        d
    } else {
        -d
    };
    let r = turn_radians(e);
    let z = r * r;
    let sigma = -sin_poly(r, z);
    // −c where the cosine lands in the negative half: k = 2 (cos), 3 (sin).
    let c = cos_poly(z);
    let c = if k & 2 == 0 { c } else { -c };
    if k & 1 == 0 {
        (sigma, c)
    } else {
        (c, sigma)
    }
}

// ------------------------------------------------- coarse cos of a turn ----

#[path = "f32_cos_table.rs"]
mod cos_table;
use cos_table::COS_TURN_TABLE;
/// The knots and slopes of [`cos_turn_coarse`] (for the tests of the
/// table).
#[cfg(test)]
pub(crate) const COS_TURN_COARSE_TABLE: &[[f32; 2]; 1024] = &COS_TURN_TABLE;

/// Proven absolute error bound of [`cos_turn_coarse`] and of both
/// components of [`sin_cos_turn_coarse`]: the linear-interpolation
/// remainder `h²/8` with `h = 2π/1024` (4.7059e-6, as `|cos''| ≤ 1`), the
/// rounding of a knot to `f32` (`≤ 2⁻²⁵`), of the prepared difference to
/// the next knot and of the product (each below `4e-10`: `|b − a| ≤ h`)
/// and of the sum (`≤ 2⁻²⁵`), rounded up.
pub const COS_TURN_COARSE_BOUND: f64 = 4.8e-6;

/// Knot and offset of a binary angle: `turn = i·2²² + f`, `i ∈ 0..1024`,
/// `f ∈ 0..2²²` (exact in `f32`: 22 bits).
#[inline(always)]
fn coarse_knot(turn: u32) -> (usize, f32) {
    ((turn >> 22) as usize, (turn & 0x3f_ffff) as f32)
}

/// Linear interpolation from knot `i` (`i < 1024`, so no bounds check is
/// emitted): `a + f·s` with the slope `s = (b − a)·2⁻²²` prepared in the
/// table, `b` the next knot. The same value as `a + (f·2⁻²²)·(b − a)`
/// with `b − a` rounded to `f32`: both products are the exact `f·(b −
/// a)·2⁻²²` (scalings by powers of two, no underflow) rounded once.
#[inline(always)]
fn coarse_at(i: usize, f: f32) -> f32 {
    let [a, s] = COS_TURN_TABLE[i];
    a + f * s
}

/// `cos(2π·turn/2³²)` at the accuracy a small model term needs (thesis
/// eq. (3.7), the harmonics of the kinematic error, whose amplitudes are
/// arcseconds): linear interpolation between 1024 correctly rounded knots
/// `cos(2π i/1024)`, each stored with its slope (8 KiB, generated by
/// `proofs/gen_f32_cos_table.py`).
///
/// * Domain: every `u32` (a binary angle in units of `2⁻³²` turn).
/// * Proven bound: **≤ [`COS_TURN_COARSE_BOUND`] = 4.8e-6 absolute**
///   (derivation at the constant; the full-accuracy [`cos_turn`] is within
///   `2⁻²²` = 2.4e-7), checked against `f64` `cos` at all 2³² angles by
///   `exhaustive_cos_turn_coarse_f32` (max 4.748e-6), and in the plain
///   suite at every knot and midpoint, a stride and random angles
///   (`cos_turn_coarse_within_its_bound`).
/// * Algorithm: knot `i = turn >> 22`, offset `f = turn mod 2²²` (exact),
///   `a_i + f·s_i` with the prepared slope `s_i = (a_{i+1} − a_i)·2⁻²²`.
/// * Cost: no branch, no division, two loads from the table.
#[inline]
pub fn cos_turn_coarse(turn: u32) -> f32 {
    let (i, f) = coarse_knot(turn);
    coarse_at(i, f)
}

/// `(sin, cos)` of a binary angle by [`cos_turn_coarse`]: **bit for bit**
/// `(cos_turn_coarse(turn − 2³⁰), cos_turn_coarse(turn))` (the quarter
/// turn moves the knot by 256 and leaves the offset alone, so the
/// offset is computed once), each within [`COS_TURN_COARSE_BOUND`].
#[inline]
pub fn sin_cos_turn_coarse(turn: u32) -> (f32, f32) {
    let (i, f) = coarse_knot(turn);
    (coarse_at(i.wrapping_sub(256) & 1023, f), coarse_at(i, f))
}

// --------------------------------------------------------------- atan2 ----

/// Four-quadrant arctangent of `y/x`, in `[-π, π]` (`|result| ≤` π rounded
/// to `f32`).
///
/// * Domain: every pair of `f32`s, including zeros, subnormals and `±∞`
///   (`atan2(±∞, ±∞) = ±π/4, ±3π/4`). `atan2(±0, ±0) = 0`; otherwise signed
///   zeros follow IEEE-754 (`atan2(±0, x<0) = ±π`). NaN is treated as 0.
/// * Algorithm: `a = atan(min/max)` of the magnitudes (the non-negative
///   branch of [`atan`]), then `a`, `π/2 − a`, `π − a` or `π/2 + a`
///   (constants split in two `f32`s) and the sign of `y`.
/// * Proven bound: **2 ulp** on a 4096 × 4096 grid of codes spanning every
///   exponent, both signs, zeros, subnormals and `±∞` (the exhaustive
///   engine over the grid, `exhaustive_atan2_f32`), plus random pairs of
///   forces (`atan2_within_bound_on_forces`). A grid is not every pair: the
///   bound off the grid rests on the same code paths as [`atan`], whose
///   bound is proven for every `f32`. Measured maximum error on the grid:
///   1.495 ulp.
/// * Cost: ≤ 134 Thumb-2 instructions on a Cortex-M4F (two `VDIV`s).
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    let y = denan(y);
    let x = denan(x);
    let ybits = y.to_bits();
    let xbits = x.to_bits();
    let ay = f32::from_bits(ybits & !SIGN);
    let ax = f32::from_bits(xbits & !SIGN);
    if ay == 0.0 && ax == 0.0 {
        return 0.0;
    }
    let swap = ay > ax;
    let (num, den) = if swap { (ax, ay) } else { (ay, ax) };
    // num == den also covers ∞/∞.
    let ratio = if num == den { 1.0 } else { num / den };
    let a = atan_nonneg(ratio);
    let (hi, lo, a) = match (swap, xbits & SIGN != 0) {
        (false, false) => (0.0, 0.0, a),
        (true, false) => (FRAC_PI_2_HI, FRAC_PI_2_LO, -a),
        (false, true) => (PI_HI, PI_LO, -a),
        (true, true) => (FRAC_PI_2_HI, FRAC_PI_2_LO, a),
    };
    with_sign((hi + a) + lo, ybits & SIGN)
}

// ---------------------------------------------------------------- acos ----

/// `asin s ≈ s + s³·A(s²)` on `s ∈ [0, 1/2]` (degree 6 in `s²`).
const ASIN_A: [f32; 7] = [
    0.166_666_67,
    0.074_999_92,
    0.044_647_664,
    0.030_269_139,
    0.023_611_818,
    0.010_574_415,
    0.030_974_54,
];

/// Arccosine, in radians, in `[0, π]`.
///
/// * Domain: `[-1, 1]`; arguments outside are clamped to it (NaN → 0, so
///   `acos(NaN) = π/2`).
/// * Algorithm: `|x| ≤ 1/2`: `π/2 − asin x`; `|x| > 1/2`: `acos|x| =
///   2·asin √((1−|x|)/2)` (the halving is exact, the square root is the
///   correctly rounded [`sqrt`]) and `π − acos|x|` for `x < 0`. `asin s = s +
///   s³·A(s²)` with `A` a degree-6 Chebyshev fit on `[0, 1/2]`; π/2 and π are
///   split in two `f32`s.
/// * Proven bound: **2 ulp** over every `f32` in `[-1, 1]`, by the exhaustive
///   engine, `exhaustive_acos_f32`. Measured maximum error: 1.106 ulp at
///   `x = 0.5449175`.
/// * Cost: ≤ 154 Thumb-2 instructions on a Cortex-M4F, [`sqrt`] included.
#[inline]
pub fn acos(x: f32) -> f32 {
    let x = denan(x).clamp(-1.0, 1.0);
    let neg = x < 0.0;
    let ax = if neg { -x } else { x };
    if ax <= 0.5 {
        let z = x * x;
        FRAC_PI_2_HI - (x - (FRAC_PI_2_LO - x * z * horner(z, &ASIN_A)))
    } else {
        let w = (1.0 - ax) * 0.5;
        let s = sqrt(w);
        let a = 2.0 * (s + s * w * horner(w, &ASIN_A));
        if neg {
            PI_HI - (a - PI_LO)
        } else {
            a
        }
    }
}

// ---------------------------------------------------------------- sqrt ----

/// Square root, correctly rounded.
///
/// * Domain: every `f32 ≥ 0`; negative arguments (and NaN) return 0, `+∞`
///   returns `f32::MAX`.
/// * Algorithm: scale to `t ∈ [1, 4)` by an even power of two (subnormals
///   normalized with one `CLZ`); three Newton steps in `f32` from a bit-level
///   estimate give `√t` within one ulp; the 24-bit candidate `q` is then
///   fixed exactly in integers: `q² ≤ M < (q+1)²` by one `u32 × u32 → u64`
///   product, and rounding up iff `M − q² > q` (the midpoint `(q + ½)²` is
///   never an integer, so there are no ties).
/// * Proven bound: **0.5 ulp** (correctly rounded, bit-equal to the rounded
///   `f64` square root) over every `f32`, and non-decreasing: by the
///   exhaustive engine over all 2^32 codes, `exhaustive_sqrt_f32`.
/// * Cost: ≤ 85 Thumb-2 instructions on a Cortex-M4F (three `VDIV`s).
#[inline]
pub fn sqrt(x: f32) -> f32 {
    let bits = x.to_bits();
    if bits == 0 || bits >= SIGN {
        return 0.0; // +0, negatives, -0 and negative NaNs
    }
    if bits >= 0x7f80_0000 {
        return if bits == 0x7f80_0000 { f32::MAX } else { 0.0 };
    }
    // x = m · 2^(e - 23) with m ∈ [2^23, 2^24).
    let (m, e) = if bits < 0x0080_0000 {
        let sh = bits.leading_zeros() - 8;
        (bits << sh, -126 - sh as i32)
    } else {
        (
            (bits & 0x007f_ffff) | 0x0080_0000,
            (bits >> 23) as i32 - 127,
        )
    };
    // Make the exponent even: x = mm · 2^(2h - 23), mm ∈ [2^23, 2^25).
    let odd = (e & 1) as u32;
    let mm = m << odd;
    let h = (e - odd as i32) >> 1;
    // √x = √(mm · 2^23) · 2^(h - 23).
    let q = sqrt_mantissa(mm);
    // q ∈ [2^23, 2^24]: adding it to the exponent field carries at 2^24.
    f32::from_bits((((h + 126) as u32) << 23) + q)
}

/// `round(√(mm · 2²³))` for `mm ∈ [2²³, 2²⁴)` and even `mm ∈ [2²⁴, 2²⁵)`
/// (the scaled mantissas [`sqrt`] passes), the 24-bit root of [`sqrt`]:
/// the integer `q ∈ [2²³, 2²⁴]` with `q² − q < mm · 2²³ ≤ q² + q` (the
/// midpoints `(q ± ½)²` are never integers). Correct rounding is what
/// makes `sqrt` non-decreasing: `round(√·)` of a larger integer is never
/// smaller. Checked at every such `mm` by `exhaustive_sqrt_f32`.
#[inline(always)]
pub(crate) fn sqrt_mantissa(mm: u32) -> u32 {
    // t = mm · 2^-23 ∈ [1, 4), exact; √(mm · 2^23) = √t · 2^23.
    let t = mm as f32 * (1.0 / 8_388_608.0);
    let mut y = f32::from_bits((t.to_bits() >> 1) + 0x1fbb_4f2e);
    y = 0.5 * (y + t / y);
    y = 0.5 * (y + t / y);
    y = 0.5 * (y + t / y);
    // Integer candidate q ≈ √(mm · 2^23) = √t · 2^23 ∈ [2^23, 2^24].
    let mut q = (y * 8_388_608.0) as u32;
    let big_m = (mm as u64) << 23;
    let sq = q as u64 * q as u64;
    if sq > big_m {
        q -= 1;
    } else if big_m - sq > 2 * q as u64 {
        q += 1;
    }
    let sq = q as u64 * q as u64;
    if big_m - sq > q as u64 {
        q += 1; // round to nearest
    }
    q
}
