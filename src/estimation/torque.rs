//! The joint-torque estimator of thesis §3.1, eq. (3.8)–(3.10), as a
//! Config/State/update component on every backend.
//!
//! Per sample:
//!
//! 1. torsion from the encoders, eq. (2.13): `Δθ = θ_fo + θ_wi / N`, computed
//!    exactly in integer counts (see below);
//! 2. kinematic error `θ_err` of eq. (3.7) at the link and motor angles
//!    (optional), in the amplitude–phase form
//!    [`KinematicErrorPhaseForm`](crate::harmonic_drive::kinematic_error::KinematicErrorPhaseForm)
//!    from binary angles (see below);
//! 3. flexspline torsion, eq. (3.9):
//!    `Δθ_f = Δθ + sgn(τ_w)(1 − e^{−c_w|τ_w|})/(c_w N K_w0) − θ_err`, with the
//!    wave-generator torque `τ_w` approximated by the motor torque command;
//! 4. joint torque, eq. (3.10): `τ_f = tan(Δθ_f c_f K_f0) / c_f`.
//!
//! **Exact torsion from counts.** With a link encoder of `L` counts per
//! revolution, a motor encoder of `M` counts per motor revolution and an
//! integer ratio `N`, the torsion in units of `2π/(L M N)` is the integer
//! `D = c_l · M N + p · L` (reduced to `[−LMN/2, LMN/2)`), where `c_l` is the
//! link count and `p` the motor position modulo one output revolution
//! (`M N` counts). No rounding happens before the single scaling
//! [`Scalar::from_counts`], so a fixed-point estimate keeps the encoders'
//! full resolution.
//!
//! **Kinematic error from counts.** The link count `c_l` and the motor
//! count within the motor revolution become binary angles (`u32`, units of
//! `2⁻³²` turn) by [`CountToTurn`] (no division at run time); the phases
//! `φ` are prepared as binary angles too, so `θ − φ` and `2θ_wi − φ_2` are
//! exact wrapping integer operations, and eq. (3.7) is
//! `a_0 + R_l·cos_turn(θ_fo − φ_l) + R_1·cos_turn(θ_wi − φ_1) +
//! R_2·cos_turn(2θ_wi − φ_2)`: three [`Scalar::cos_turn`], three
//! [`Scalar::mul`], three additions (fixed point). Float backends take both
//! motor harmonics from one `sin_cos_turn_coarse` ([`kernels::f32::sin_cos_turn_coarse`](crate::scalar::kernels::f32::sin_cos_turn_coarse) on `f32`) of `u = θ_wi − φ_1`
//! by the double angle: with `δ = 2φ_1 − φ_2` (exact in binary angles, so
//! `2u + δ` is exactly `2θ_wi − φ_2`) and `c² + s² = 1`,
//! `R_1 cos u + R_2 cos(2u + δ) = c (R_1 + A c + B s) − R_2 cos δ`,
//! `A = 2R_2 cos δ`, `B = −2R_2 sin δ`, the constant folded into `a_0`.
//!
//! *Error bound* against `f64` eq. (3.7) at the count angles
//! `2π c_l/L`, `2π p/M`, in stored torsion units (`R_j` and `a_0` in
//! stored units, `A = |a_0| + ΣR_j` the amplitude bound):
//!
//! * angles: count conversion `< 1.5` units of `2⁻³²` turn, phase rounding
//!   `≤ 0.5` units, doubled motor angle `< 3` units: `e_θ ≤ 3.5 · 2π/2³²
//!   = 5.1e-9` rad per argument, hence `≤ R_j·e_θ` per term;
//! * `I16F16` (`q = 2⁻¹⁶` stored units): `a_0` and each `R_j` rounded to
//!   `q/2`, `cos_turn` `≤ 2⁻¹⁶` (proven), each product rounded to `q/2`,
//!   additions exact:
//!   `|e| ≤ q/2 + Σ_j [q/2·(1 + 2⁻¹⁶) + R_j·(2⁻¹⁶ + e_θ) + q/2]`
//!   (while no sum saturates, i.e. for `A` far below the range): about
//!   `3.5 q + q·ΣR_j`, below `6.5 q` when every amplitude is below 1
//!   stored unit (1 mrad);
//! * `f32` (relative rounding `u = 2⁻²⁴`): the cosines are
//!   `cos_turn_coarse` ([`kernels::f32::cos_turn_coarse`](crate::scalar::kernels::f32::cos_turn_coarse) on `f32`) and `sin_cos_turn_coarse` ([`kernels::f32::sin_cos_turn_coarse`](crate::scalar::kernels::f32::sin_cos_turn_coarse) on `f32`), a
//!   table interpolation within `ε_c = 4.8e-6` absolute (proven; the
//!   harmonics are arcseconds, so `R_j ε_c` is far below an encoder count,
//!   and it saves about 40 instructions per step on a Cortex-M4F over the
//!   full-accuracy kernels). The link term is within
//!   `R_l(2u + ε_c + e_θ)`; the motor form `M(c, s) = c(R_1 + Ac + Bs)`
//!   has `|∂M/∂c| ≤ R_1 + 6R_2` and `|∂M/∂s| ≤ 2R_2`, so kernel and angle
//!   errors add `≤ (R_1 + 8R_2)(ε_c + e_θ)`, and `A dc² + B dc ds` at most
//!   `4R_2(ε_c + e_θ)²` more; rounding `A`, `B` and `a_0 − R_2 cos δ` adds
//!   `≤ u(|a_0| + 5R_2)`, the products and sums inside the form
//!   `≤ u(2R_1 + 10R_2)`, the two outer sums
//!   `≤ 2u(|a_0| + R_l + R_1 + 3R_2)`: in all `|e| ≤ |a_0|u + R_l(2u + ε_c
//!   + e_θ) + (R_1 + 8R_2)(ε_c + e_θ) + 4R_2(ε_c + e_θ)² + u(2R_1 + 15R_2)
//!   + 2u(|a_0| + R_l + R_1 + 3R_2)`, plus second-order terms in `u`
//!   (bounded by `40 u² A` in the test).
//!
//! `kinematic_error_from_counts_within_bound` (tests below) checks these
//! bounds for both backends over many counts.
//!
//! **Saturation.** `tan` is valid only for `|Δθ_f c_f K_f0| < π/2`. At or
//! beyond it, and whenever the estimate would exceed the configured
//! `max_torque`, the output is `±max_torque` (sign of the torsion) and
//! `saturated` is set; a value from the wrong branch of `tan` is never
//! returned. Both conditions grow with `|Δθ_f|` (every rounding step is
//! monotone and `tan` is proven monotone), so they are tested together, by
//! one comparison of `|Δθ_f|` with the largest torsion that passes both
//! on either sign, found at configuration time on the backend's own
//! arithmetic; the saturated path then skips `tan`.
//!
//! # Example
//! The SHD-17-100 with a 17-bit link encoder and a 2000-count motor
//! encoder, on `f32`: the link encoder 3 counts ahead of a motor at 0 is a
//! torsion `Δθ = 3·2π/2¹⁷` rad, and with no motor torque and no kinematic
//! error the estimate is eq. (3.10), `tan(c_f K_f0 Δθ)/c_f`, here
//! evaluated in `f64`.
//!
//! ```
//! use mrr_control::estimation::torque::{
//!     TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings,
//! };
//! use mrr_control::harmonic_drive::CatalogueData;
//! let drive = CatalogueData::SHD_17_100.identify()?;
//! let p = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
//!     drive,
//!     kinematic_error: None,
//!     link_counts_per_rev: 1 << 17,
//!     motor_counts_per_rev: 2000,
//!     max_torque: 60.0,
//! })?;
//! let est = TorqueEstimatorConfig::<f32>::new(&p);
//! let mut st = est.state(0, 0); // motor at count 0, counter reading 0
//! let e = est.update(&mut st, 3, 0, 0.0);
//! let f = drive.flexspline();
//! let torsion = 3.0 * std::f64::consts::TAU / 131_072.0;
//! let tau = (f.c_f() * f.k_f0() * torsion).tan() / f.c_f();
//! assert!((e.torque_si() - tau).abs() < 1e-5 * tau); // ≈ 1.2 N·m
//! assert!(!e.saturated && !e.invalid_input);
//! # Ok::<(), mrr_control::ParamError>(())
//! ```

use crate::error::{combination, integer, positive, ParamError};
use crate::harmonic_drive::{
    kinematic_error::KinematicErrorModel, FlexsplineConfig, HarmonicDriveParams,
    WaveGeneratorConfig,
};
use crate::scalar::target::{mul_add_below, mul_wide, HAS_DIVIDE};
use crate::scalar::{turn_from_radians, Coef, CountToTurn, Scalar};
use core::f64::consts::TAU;
use core::num::NonZeroU32;

/// `S::from_counts(d, c)` bit for bit for a torsion count `|d| < 2⁴⁷`
/// (every reduced count of the estimator: `|D| ≤ LMN/2 ≤ 2⁴⁵`). Floats
/// convert the two exact parts `d = hi·2²⁴ + lo` (`|hi| < 2²³`,
/// `0 ≤ lo < 2²⁴`): `hi·2²⁴` is exact, so their sum rounds once, to the
/// correctly rounded `d`, which is the conversion `from_counts` makes
/// (`f32`: without its branch for counts of 2⁴⁷ and more; `f64`: every
/// step is exact). Fixed point takes `from_counts` itself.
#[inline(always)]
fn torsion_of_counts<S: Scalar>(d: i64, c: &Coef) -> S {
    if S::FLOAT {
        let hi = S::from_i32((d >> 24) as i32);
        let lo = S::from_i32((d & 0xFF_FFFF) as i32);
        hi.mul(S::from_f64(16_777_216.0)).add(lo).mul_coef(c)
    } else {
        S::from_counts(d, c)
    }
}

/// `⌊(2³² − 1)/d⌋` for `d ≥ 1`: the prepared reciprocal of
/// [`Divisor::div_rem`].
const fn reciprocal(d: u32) -> u32 {
    u32::MAX / if d == 0 { 1 } else { d }
}

/// A divisor `d ≥ 1` prepared for [`div_rem`](Self::div_rem): as a
/// `NonZeroU32` (the hardware division then needs no zero test) and as
/// its [`reciprocal`].
#[derive(Debug, Clone, Copy, PartialEq)]
struct Divisor {
    d: NonZeroU32,
    recip: u32,
}

impl Divisor {
    /// `d`, or 1 for `d = 0` (the callers validate `d ≥ 1`).
    const fn new(d: u32) -> Self {
        let d = match NonZeroU32::new(d) {
            Some(d) => d,
            None => NonZeroU32::MIN,
        };
        Divisor {
            d,
            recip: reciprocal(d.get()),
        }
    }

    /// `(⌊x/d⌋, x mod d)` for every `u32` `x`.
    ///
    /// Armv6-M has no divide instruction (`/` is a library loop of about
    /// 250 instructions); there the quotient comes from the reciprocal
    /// ([`div_rem_reciprocal`]), elsewhere from the hardware division.
    #[inline(always)]
    fn div_rem(&self, x: u32) -> (u32, u32) {
        if HAS_DIVIDE {
            return (x / self.d, x % self.d);
        }
        div_rem_reciprocal(x, self.d.get(), self.recip)
    }

    /// [`div_rem`](Self::div_rem), except that without a divide
    /// instruction (`DIVIDE = false`: Armv6-M) an `x < d` skips the
    /// division (quotient 0, remainder `x`), a test cheaper than the
    /// library's division there and dearer than the instruction elsewhere.
    /// The callers pass [`HAS_DIVIDE`]; the tests run both forms on the
    /// host.
    /// `d` is the divisor as the caller already holds it (equal to this
    /// one's), so that the test reads no other field.
    #[inline(always)]
    fn div_rem_or_skip<const DIVIDE: bool>(&self, x: u32, d: u32) -> (u32, u32) {
        if DIVIDE || x >= d {
            self.div_rem(x)
        } else {
            (0, x)
        }
    }
}

/// [`Divisor::div_rem`] from `r = ⌊(2³² − 1)/d⌋`: `q₀ = ⌊x·r/2³²⌋` (one 32×32 → 64
/// product) is `q = ⌊x/d⌋` or `q − 1`, because `r ≤ 2³²/d` gives
/// `q₀ ≤ x/d` and `r ≥ (2³² − d)/d` gives `x·r/2³² ≥ x/d − x/2³² > x/d − 1`.
/// The remainder `x − q₀·d ∈ [0, 2d)` is at most `x`, so its 32-bit
/// difference is exact, and one comparison corrects the quotient.
#[inline(always)]
fn div_rem_reciprocal(x: u32, d: u32, r: u32) -> (u32, u32) {
    let (q, _) = crate::scalar::fixed::wide_mul(x, r);
    let rem = x.wrapping_sub(q.wrapping_mul(d));
    if rem >= d {
        (q + 1, rem - d)
    } else {
        (q, rem)
    }
}

/// The estimator's parameters by name, for [`TorqueEstimatorParams::try_new`]
/// (the two encoder resolutions are both `u32`: named so that they cannot be
/// swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorqueEstimatorSettings {
    /// The identified compliance model, eq. (2.30); its ratio `N` must be an
    /// integer.
    pub drive: HarmonicDriveParams,
    /// Kinematic-error model of eq. (3.7), or `None` to leave it out.
    pub kinematic_error: Option<KinematicErrorModel>,
    /// Link-side absolute encoder counts per revolution `L` (≥ 1).
    pub link_counts_per_rev: u32,
    /// Motor-side incremental counts per motor revolution `M`, after
    /// quadrature decoding (≥ 1).
    pub motor_counts_per_rev: u32,
    /// Largest torque the estimate may report, N·m, in
    /// `[MIN_TORQUE_LIMIT, MAX_TORQUE_LIMIT]`.
    pub max_torque: f64,
}

/// Physical parameters of the estimator.
///
/// Built only by [`try_new`](Self::try_new): every value a
/// [`TorqueEstimatorConfig`] is built from has been validated, so no
/// configuration can divide by zero or invert an empty domain.
///
/// ```
/// use mrr_control::prelude::*;
/// let drive = CatalogueData::SHD_17_100.identify()?;
/// let p = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
///     drive,
///     kinematic_error: None,
///     link_counts_per_rev: 1 << 17,
///     motor_counts_per_rev: 2000,
///     max_torque: 60.0,
/// })?;
/// let cfg = TorqueEstimatorConfig::<f32>::new(&p);
/// let e = cfg.update(&mut cfg.state(0, 0), 0, 0, 0.0);
/// assert!(e.torque_si().abs() < 1e-9 && !e.invalid_input);
/// // A zero motor resolution is refused by name instead of dividing by 0.
/// let err = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
///     drive,
///     kinematic_error: None,
///     link_counts_per_rev: 1 << 17,
///     motor_counts_per_rev: 0,
///     max_torque: 60.0,
/// }).unwrap_err();
/// assert_eq!(err.to_string(), "parameter `motor_counts_per_rev` must be > 0, got 0");
/// # Ok::<(), ParamError>(())
/// ```
///
/// A struct literal, which used to skip the checks, no longer compiles:
///
/// ```compile_fail
/// use mrr_control::prelude::*;
/// let drive = CatalogueData::SHD_17_100.identify().unwrap();
/// let p = TorqueEstimatorParams {
///     drive,
///     kinematic_error: None,
///     link_counts_per_rev: 1 << 17,
///     motor_counts_per_rev: 0,
///     max_torque: 60.0,
/// };
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorqueEstimatorParams {
    drive: HarmonicDriveParams,
    kinematic_error: Option<KinematicErrorModel>,
    link_counts_per_rev: u32,
    motor_counts_per_rev: u32,
    max_torque: f64,
}

/// Smallest accepted `max_torque`, N·m: 65 steps of the fixed-point
/// link-torque unit, so that no backend rounds the limit to 0.
pub const MIN_TORQUE_LIMIT: f64 = 1e-3;

/// Largest accepted `max_torque`, N·m (representable by every backend with
/// room for the sums of the step).
pub const MAX_TORQUE_LIMIT: f64 = 30_000.0;

/// Largest accepted product `L·M·N` (counts of the torsion unit per output
/// revolution): `2⁴⁶`, so that every product of the count path is exact in
/// 64 bits.
pub const MAX_COUNTS_PER_OUTPUT_REV: f64 = 70_368_744_177_664.0;

/// The name of the product `L·M·N` in errors.
const LMN_NAME: &str = "link_counts_per_rev·motor_counts_per_rev·drive.ratio";

/// Largest accepted `c_f·max_torque` (the flexspline's stiffening
/// coefficient, 1/(N·m), times the estimate's limit, N·m: a pure number):
/// at `max_torque` the model's
/// stiffness `K_f0(1 + (c_f τ)²)` is then at most 57.25 `K_f0`, and the
/// argument of `tan` in eq. (3.10) at most `atan 7.5 = 1.4382` rad, inside
/// the domain of `tan_bounded` ([`kernels::i16f16::tan_bounded`](crate::scalar::kernels::i16f16::tan_bounded) on fixed point) (`atan 8`) with a margin far
/// above any rounding, so the estimator evaluates the inverse without the
/// quotient near the pole. The SHD-17-100 of §2.4 at the 60 N·m of the
/// examples is at 2.70 (identified `c_f = 0.04494` 1/(N·m)); every drive
/// scaled from it keeps `c_f·T_rated = 0.719`, so up to 10.4 times the
/// rated torque. Beyond it one torsion count is worth more than 57 times
/// the torque it is worth at rest.
pub const MAX_STIFFENING_TORQUE: f64 = 7.5;

/// The name of the product `c_f·max_torque` in errors.
const STIFFENING_TORQUE_NAME: &str = "drive.c_f·max_torque";

impl TorqueEstimatorParams {
    /// Validate, each rule once and naming what broke it:
    /// * `drive.ratio` (the drive's `N`): an integer in `[1, 65535]`
    ///   ([`ParamError::NotInteger`]);
    /// * `link_counts_per_rev` `L` and `motor_counts_per_rev` `M` (after
    ///   quadrature decoding): at least 1;
    /// * `max_torque`: finite, in `[0.001, 30 000]` N·m
    ///   ([`MIN_TORQUE_LIMIT`], [`MAX_TORQUE_LIMIT`]);
    /// * the product `drive.c_f·max_torque` (named as such,
    ///   [`ParamError::CombinationOutOfRange`]): at most 7.5
    ///   ([`MAX_STIFFENING_TORQUE`]);
    /// * the product `L·M·N` (named
    ///   `link_counts_per_rev·motor_counts_per_rev·drive.ratio`,
    ///   [`ParamError::CombinationOutOfRange`]): at most `2⁴⁶`
    ///   ([`MAX_COUNTS_PER_OUTPUT_REV`]), and small enough that 2³¹ counts of
    ///   `2π/(LMN)` cover twice the [`torsion_range`](Self::torsion_range)
    ///   (the count range of [`Scalar::from_counts`]).
    ///
    /// The drive and the kinematic-error model were validated by their own
    /// `try_new`.
    pub fn try_new(settings: TorqueEstimatorSettings) -> Result<Self, ParamError> {
        let TorqueEstimatorSettings {
            drive,
            kinematic_error,
            link_counts_per_rev,
            motor_counts_per_rev,
            max_torque,
        } = settings;
        let n = integer("drive.ratio", drive.ratio(), 1.0, 65535.0)?;
        for (name, v) in [
            ("link_counts_per_rev", link_counts_per_rev),
            ("motor_counts_per_rev", motor_counts_per_rev),
        ] {
            if v == 0 {
                return Err(ParamError::NotPositive { name, value: 0.0 });
            }
        }
        let max_torque = positive("max_torque", max_torque)?;
        if !(MIN_TORQUE_LIMIT..=MAX_TORQUE_LIMIT).contains(&max_torque) {
            return Err(ParamError::OutOfRange {
                name: "max_torque",
                value: max_torque,
                min: MIN_TORQUE_LIMIT,
                max: MAX_TORQUE_LIMIT,
            });
        }
        combination(
            STIFFENING_TORQUE_NAME,
            drive.flexspline().c_f() * max_torque,
            0.0,
            MAX_STIFFENING_TORQUE,
        )?;
        let p = TorqueEstimatorParams {
            drive,
            kinematic_error,
            link_counts_per_rev,
            motor_counts_per_rev,
            max_torque,
        };
        let lmn = link_counts_per_rev as f64 * motor_counts_per_rev as f64 * n;
        let by_range = libm::floor(2_147_483_648.0 * TAU / (2.0 * p.torsion_range()));
        combination(LMN_NAME, lmn, 1.0, by_range.min(MAX_COUNTS_PER_OUTPUT_REV))?;
        Ok(p)
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> TorqueEstimatorSettings {
        TorqueEstimatorSettings {
            drive: self.drive,
            kinematic_error: self.kinematic_error,
            link_counts_per_rev: self.link_counts_per_rev,
            motor_counts_per_rev: self.motor_counts_per_rev,
            max_torque: self.max_torque,
        }
    }

    /// The identified compliance model, eq. (2.30) (integer ratio).
    pub fn drive(&self) -> HarmonicDriveParams {
        self.drive
    }

    /// Kinematic-error model of eq. (3.7), or `None` when it is left out.
    pub fn kinematic_error(&self) -> Option<KinematicErrorModel> {
        self.kinematic_error
    }

    /// Link-side absolute encoder counts per revolution `L`.
    pub fn link_counts_per_rev(&self) -> u32 {
        self.link_counts_per_rev
    }

    /// Motor-side incremental counts per motor revolution `M` (after
    /// quadrature decoding).
    pub fn motor_counts_per_rev(&self) -> u32 {
        self.motor_counts_per_rev
    }

    /// Largest torque the estimate may report, N·m; larger estimates
    /// saturate here and are flagged.
    pub fn max_torque(&self) -> f64 {
        self.max_torque
    }

    /// The agreement of backend `S` with `f64` on the count path, summed
    /// term by term from the kernels' proven bounds and doubled (for the
    /// second-order terms and the rounding of the bound's own inputs):
    ///
    /// * `I16F16` (torsion step `q = 2⁻¹⁶` mrad): the torsion from counts
    ///   `q/2`; the wave-generator term `A_w(2⁻¹⁵ + 2⁻¹⁷(1 + c_w/10³)) + q/2`
    ///   (`A_w` its amplitude in mrad: `exp` error, quantized input and
    ///   product); the kinematic error of the module docs,
    ///   `q/2 + Σ_j [q + R_j(2⁻¹⁶ + 5.1e-9)]`; the `tan` argument's rounding
    ///   to `2⁻¹⁷` rad, `2⁻¹⁷/(c_f K_f0)` rad of torsion. Torque: `tan` ≤ 1
    ///   step (proven), scaled by `1/c_f`, and the last rounding:
    ///   `2⁻¹⁶/c_f + 2⁻¹⁶` N·m, plus `2⁻²⁹` relative (31-bit coefficients).
    /// * `f32` (`u = 2⁻²⁴`): torsion `8u` of the torsion range, `8u A_w`,
    ///   and the kinematic error of the module docs with its table
    ///   cosines (`ε_c = 4.8e-6`, proven): `(30u + 8(ε_c + 5.1e-9))` times
    ///   the kinematic-error bound `A` (the angle and kernel terms there
    ///   are at most `(R_l + R_1 + 8R_2)(ε_c + e_θ) ≤ 8A(ε_c + e_θ)`, the
    ///   roundings below `30uA`); torque `2⁻²⁰` relative (`tan` ≤ 2⁻²²,
    ///   proven, and three roundings).
    /// * `f64`: zero (the reference itself).
    pub fn agreement_bound<S: Scalar>(&self) -> AgreementBound {
        use crate::scalar::kernels::f32::COS_TURN_COARSE_BOUND;
        let ke = self.kinematic_error.map_or(0.0, |k| k.amplitude_bound());
        let wg = self.drive.output_wave_generator_torsion();
        let f = self.drive.flexspline();
        let e_theta = 3.5 * TAU / 4_294_967_296.0;
        if S::NAME == "I16F16" {
            let t = crate::scalar::units::FIXED.torsion;
            let q = 1.0 / 65536.0; // stored torsion step, mrad
            let amp = wg * t;
            let c_w = self.drive.wave_generator().c_w();
            let wave = amp * (2.0 * q + q / 2.0 * (1.0 + c_w / 1e3)) + q / 2.0;
            let kin = self.kinematic_error.map_or(0.0, |k| {
                let r = k.phase_form().amplitudes;
                q / 2.0 + r.iter().map(|rj| q + rj * t * (q + e_theta)).sum::<f64>()
            });
            let angle = q / 2.0 / (f.c_f() * f.k_f0()) * t;
            AgreementBound {
                torsion: 2.0 * (q / 2.0 + wave + kin + angle) / t,
                torque_relative: 2.0 * libm::exp2(-29.0),
                torque_absolute: 2.0 * (q / f.c_f() + q),
            }
        } else if S::NAME == "f32" {
            let u = libm::exp2(-24.0);
            AgreementBound {
                torsion: 2.0
                    * (8.0 * u * self.torsion_range()
                        + 8.0 * u * wg
                        + (30.0 * u + 8.0 * (COS_TURN_COARSE_BOUND + e_theta)) * ke),
                torque_relative: 2.0 * libm::exp2(-20.0),
                torque_absolute: 1e-30,
            }
        } else {
            AgreementBound {
                torsion: 0.0,
                torque_relative: 0.0,
                torque_absolute: 0.0,
            }
        }
    }

    /// The largest total torsion `|Δθ|` (rad) the model can produce with
    /// any torques: the flexspline's `π/(2 c_f K_f0)`, plus the
    /// wave-generator term `1/(c_w N K_w0)`, plus the kinematic-error
    /// bound, widened by 1 % so that the rounding of any backend stays
    /// inside. A reading beyond it is impossible for the modelled drive
    /// (see [`TorqueEstimate::invalid_input`]).
    pub fn torsion_range(&self) -> f64 {
        let ke = self.kinematic_error.map_or(0.0, |k| k.amplitude_bound());
        1.01 * (self.drive.flexspline().max_torsion()
            + self.drive.output_wave_generator_torsion()
            + ke)
    }
}

/// How far the estimate of a backend may lie from the `f64` estimate for
/// the same readings on the count path ([`TorqueEstimatorConfig::update`];
/// the motor torque quantized to the backend's unit, and inside its range:
/// `|τ_w| < 32.7 N·m` on `I16F16`): the backend's
/// flexspline torsion `Δθ_f` within [`torsion`](Self::torsion) of the `f64`
/// one, and its torque inside
/// [`torque_interval`](Self::torque_interval). From
/// [`TorqueEstimatorParams::agreement_bound`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AgreementBound {
    /// Bound on the flexspline-torsion difference, rad.
    pub torsion: f64,
    /// Relative bound on the torque rounding after eq. (3.10)'s `tan`.
    pub torque_relative: f64,
    /// Absolute bound on the torque rounding, N·m.
    pub torque_absolute: f64,
}

impl AgreementBound {
    /// The interval (N·m) that holds the backend's torque when the `f64`
    /// flexspline torsion is `flexspline_torsion` (rad): eq. (3.10) in
    /// `f64`, saturated at `±max_torque` and out of the `tan` branch (a
    /// non-decreasing function `T`), taken at `Δθ_f ∓ torsion`, widened by
    /// the relative and absolute torque bounds.
    pub fn torque_interval(
        &self,
        p: &TorqueEstimatorParams,
        flexspline_torsion: f64,
    ) -> (f64, f64) {
        let f = p.drive.flexspline();
        let max = p.max_torque;
        let t = |x: f64| {
            let angle = x * f.c_f() * f.k_f0();
            if angle.abs() >= core::f64::consts::FRAC_PI_2 {
                max.copysign(x)
            } else {
                (libm::tan(angle) / f.c_f()).clamp(-max, max)
            }
        };
        let (lo, hi) = (
            t(flexspline_torsion - self.torsion),
            t(flexspline_torsion + self.torsion),
        );
        (
            lo - self.torque_relative * lo.abs() - self.torque_absolute,
            hi + self.torque_relative * hi.abs() + self.torque_absolute,
        )
    }
}

/// Eq. (3.7) in amplitude–phase form, quantized for backend `S`: offset
/// and amplitudes in stored torsion units, phases as binary angles.
#[derive(Debug, Clone, Copy, PartialEq)]
struct KinematicErrorPhase<S> {
    /// `a_0`.
    offset: S,
    /// `[R_l, R_1, R_2]`.
    amplitudes: [S; 3],
    /// `[φ_l, φ_1, φ_2]`, units of `2⁻³²` turn.
    phases: [u32; 3],
}

/// The estimator quantized for backend `S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorqueEstimatorConfig<S> {
    flexspline: FlexsplineConfig<S>,
    wave_generator: WaveGeneratorConfig<S>,
    /// Eq. (3.7) coefficients for the radian path.
    kinematic_error: Option<[S; 7]>,
    /// Eq. (3.7) in phase form for the count path.
    kinematic_error_phase: Option<KinematicErrorPhase<S>>,
    /// Binary angle per link count (`2³²/L`) and per motor count (`2³²/M`).
    link_turn: CountToTurn,
    motor_turn: CountToTurn,
    max_torque: S,
    /// Stored torsion per count of `D` (`2π/(LMN)` scaled).
    torsion_per_count: Coef,
    /// Stored torsion per stored angle, for the radian path.
    torsion_per_angle: Coef,
    inv_ratio: Coef,
    l: u32,
    m: u32,
    n: u32,
    /// `L`, `M` and `N` prepared for division.
    l_div: Divisor,
    m_div: Divisor,
    n_div: Divisor,
    /// `M·N` and `L·M·N` (counts per output revolution), prepared once.
    mn: i64,
    lmn: i64,
    half_lmn: i64,
    /// Float backends: the two motor harmonics of eq. (3.7) from one
    /// `(sin, cos)` of `u = θ_wi − φ_1` by the double angle,
    /// `R_1 cos u + R_2 cos(2u + δ) = c (R_1 + A c + B s) − R_2 cos δ`
    /// with `δ = 2φ_1 − φ_2`, `A = 2R_2 cos δ`, `B = −2R_2 sin δ`
    /// (`c² + s² = 1`): `[a_0 − R_2 cos δ, A, B]` (zeros without a model).
    /// Last, so that the fixed-point layout of the other fields is the
    /// same with or without it.
    double_angle: [S; 3],
    /// The largest `|Δθ_f|` (stored torsion) whose eq. (3.10) torque is on
    /// the principal branch and within `max_torque`, on both signs
    /// ([`FlexsplineConfig::torsion_within`]): the saturation test of
    /// [`finish`](Self::finish) is one comparison against it, made before
    /// `tan`.
    torsion_limit: S,
    /// [`TorqueEstimatorParams::torsion_range`] in stored torsion units:
    /// a torsion beyond it is an impossible reading, clamped here and
    /// flagged.
    torsion_range: S,
}

/// The estimator's state: the motor position within one output revolution,
/// and the last raw motor counter (to follow a wrapping hardware counter).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorqueEstimatorState {
    /// Motor revolution index within the output revolution, `[0, N)`.
    motor_turn: u32,
    /// Motor count within the motor revolution, `[0, M)`.
    motor_in_turn: u32,
    /// Last raw value of the free-running motor counter.
    last_counter: u32,
}

impl TorqueEstimatorState {
    /// The last raw motor counter given to
    /// [`TorqueEstimatorConfig::update`] (or to
    /// [`TorqueEstimatorConfig::state`]), in the estimator's sign.
    pub fn last_counter(&self) -> u32 {
        self.last_counter
    }
}

/// One torque estimate.
///
/// Every field is finite on every backend, whatever the readings: a bad
/// reading is replaced as documented on each field and flagged by
/// `invalid_input` (or `link_count_invalid`). The fields are in stored
/// units (`S::UNITS`); [`torque_si`](Self::torque_si) and the other `_si`
/// methods give SI values on every backend.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorqueEstimate<S> {
    /// Estimated joint (flexspline) torque `τ_f`, stored link-torque units,
    /// within `±max_torque`.
    pub torque: S,
    /// Total torsion `Δθ` of eq. (2.13), stored torsion units, within
    /// `±torsion_range` ([`TorqueEstimatorParams::torsion_range`]): a
    /// larger (or NaN) torsion is impossible for the drive and is replaced
    /// by `±torsion_range` (its sign; 0 for NaN) with `invalid_input` set.
    pub torsion: S,
    /// Flexspline torsion `Δθ_f` of eq. (3.9), stored torsion units.
    pub flexspline_torsion: S,
    /// The torque was saturated at `±max_torque` (out of the `tan` branch or
    /// beyond the limit).
    pub saturated: bool,
    /// The link count was not below `L`; it was reduced modulo `L`.
    pub link_count_invalid: bool,
    /// A reading was impossible: a torsion beyond `±torsion_range` (a
    /// counter jump or angles no torque can produce; the torque is then
    /// `±max_torque` with `saturated` set), a NaN or infinite angle, or a
    /// NaN or infinite motor torque (taken as 0 in eq. 3.9).
    pub invalid_input: bool,
}

impl<S: Scalar> TorqueEstimate<S> {
    /// [`torque`](Self::torque) in N·m on every backend.
    pub fn torque_si(&self) -> f64 {
        self.torque.to_f64() / S::UNITS.link_torque
    }

    /// [`torsion`](Self::torsion) in rad on every backend.
    pub fn torsion_si(&self) -> f64 {
        self.torsion.to_f64() / S::UNITS.torsion
    }

    /// [`flexspline_torsion`](Self::flexspline_torsion) in rad on every
    /// backend.
    pub fn flexspline_torsion_si(&self) -> f64 {
        self.flexspline_torsion.to_f64() / S::UNITS.torsion
    }
}

impl<S: Scalar> TorqueEstimatorConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &TorqueEstimatorParams) -> Self {
        let u = S::UNITS;
        let n = p.drive.ratio() as u32;
        let (l, m) = (p.link_counts_per_rev, p.motor_counts_per_rev);
        let lmn = l as f64 * m as f64 * n as f64;
        let flexspline = FlexsplineConfig::new(&p.drive.flexspline());
        let max_torque = S::from_f64(p.max_torque * u.link_torque);
        TorqueEstimatorConfig {
            flexspline,
            wave_generator: WaveGeneratorConfig::new(&p.drive.wave_generator(), p.drive.ratio()),
            kinematic_error: p
                .kinematic_error
                .map(|k| k.coefficients().map(|c| S::from_f64(c * u.torsion))),
            kinematic_error_phase: p.kinematic_error.map(|k| {
                let f = k.phase_form();
                KinematicErrorPhase {
                    offset: S::from_f64(f.offset * u.torsion),
                    amplitudes: f.amplitudes.map(|r| S::from_f64(r * u.torsion)),
                    phases: f.phases.map(turn_from_radians),
                }
            }),
            link_turn: CountToTurn::new(l),
            motor_turn: CountToTurn::new(m),
            max_torque,
            torsion_per_count: Coef::new(TAU / lmn * u.torsion),
            torsion_per_angle: Coef::new(u.torsion / u.angle),
            inv_ratio: Coef::new(1.0 / p.drive.ratio()),
            l,
            m,
            n,
            l_div: Divisor::new(l),
            m_div: Divisor::new(m),
            n_div: Divisor::new(n),
            mn: m as i64 * n as i64,
            lmn: l as i64 * m as i64 * n as i64,
            half_lmn: l as i64 * m as i64 * n as i64 / 2,
            double_angle: p.kinematic_error.map_or([S::ZERO; 3], |k| {
                let f = k.phase_form();
                let phases = f.phases.map(turn_from_radians);
                // δ = 2φ_1 − φ_2 from the binary phases, so that 2u + δ is
                // exactly the count path's 2θ_wi − φ_2.
                let delta = (phases[1] << 1).wrapping_sub(phases[2]) as f64 * TAU / 4_294_967_296.0;
                let (sd, cd) = (libm::sin(delta), libm::cos(delta));
                let r2 = f.amplitudes[2];
                [
                    S::from_f64((f.offset - r2 * cd) * u.torsion),
                    S::from_f64(2.0 * r2 * cd * u.torsion),
                    S::from_f64(-2.0 * r2 * sd * u.torsion),
                ]
            }),
            torsion_limit: flexspline
                .torsion_within(max_torque, p.drive.flexspline().max_torsion() * u.torsion),
            torsion_range: S::from_f64(p.torsion_range() * u.torsion),
        }
    }

    /// A state for a motor at absolute position `motor_position` (motor
    /// counts, e.g. from eq. 2.39 times `M/(2π)`, any integer) while the
    /// free-running hardware counter reads `counter`.
    pub fn state(&self, motor_position: i64, counter: u32) -> TorqueEstimatorState {
        let mn = self.m as i64 * self.n as i64;
        let p = motor_position.rem_euclid(mn);
        TorqueEstimatorState {
            motor_turn: (p / self.m as i64) as u32,
            motor_in_turn: (p % self.m as i64) as u32,
            last_counter: counter,
        }
    }

    /// The motor position the state tracks, in motor counts within one
    /// output revolution, `[0, M·N)`, in the estimator's sign (`θ_wi`;
    /// the chapter-4 `q_m` runs the other way, errata E2.10). Times
    /// `2π/M` it is `θ_wi` modulo `2πN` rad.
    pub fn motor_position_counts(&self, st: &TorqueEstimatorState) -> u64 {
        st.motor_turn as u64 * self.m as u64 + st.motor_in_turn as u64
    }

    /// Advance the motor position by the counter change since the last call
    /// (wrapping 32-bit difference: valid while the motor moves fewer than
    /// 2³¹ counts per sample).
    ///
    /// 32-bit arithmetic only: the new position is `p + δ mod MN` in the
    /// canonical form `(turn, in_turn) ∈ [0, N) × [0, M)`: one `u32`
    /// division by `M` and one by `N` ([`Divisor::div_rem`]; no 64-bit
    /// division on any path). On Armv6-M (a multiply by a prepared
    /// reciprocal) a move of less than one motor revolution skips both,
    /// and a longer one skips the one by `N` when the carry is below `N`;
    /// with a divide instruction the divisions are cheaper than those
    /// tests. Equal to the 64-bit formula [`advance_reference`] for
    /// every state and counter (tests below).
    #[inline]
    fn advance(&self, st: &mut TorqueEstimatorState, counter: u32) {
        let delta = counter.wrapping_sub(st.last_counter) as i32;
        st.last_counter = counter;
        let (m, n) = (self.m, self.n);
        let (mut in_turn, turn) = (st.motor_in_turn, st.motor_turn);
        let mag = delta.unsigned_abs();
        let (q, r) = self.m_div.div_rem_or_skip::<HAS_DIVIDE>(mag, m);
        let turn = if delta >= 0 {
            // in_turn + r < 2M, compared without overflow.
            let mut carry = q;
            if r >= m - in_turn {
                in_turn = r - (m - in_turn);
                carry += 1;
            } else {
                in_turn += r;
            }
            let c = self.n_div.div_rem_or_skip::<HAS_DIVIDE>(carry, n).1;
            if c >= n - turn {
                c - (n - turn)
            } else {
                turn + c
            }
        } else {
            let mut borrow = q;
            if r > in_turn {
                in_turn += m - r;
                borrow += 1;
            } else {
                in_turn -= r;
            }
            let b = self.n_div.div_rem_or_skip::<HAS_DIVIDE>(borrow, n).1;
            if b > turn {
                turn + (n - b)
            } else {
                turn - b
            }
        };
        st.motor_turn = turn;
        st.motor_in_turn = in_turn;
    }

    /// The 64-bit form of [`advance`](Self::advance), the reference of its
    /// tests.
    #[cfg(test)]
    fn advance_reference(&self, st: &mut TorqueEstimatorState, counter: u32) {
        let delta = counter.wrapping_sub(st.last_counter) as i32 as i64;
        st.last_counter = counter;
        let mn = self.m as i64 * self.n as i64;
        let p = st.motor_turn as i64 * self.m as i64 + st.motor_in_turn as i64;
        let p = (p + delta).rem_euclid(mn);
        st.motor_turn = (p / self.m as i64) as u32;
        st.motor_in_turn = (p % self.m as i64) as u32;
    }

    /// Whether a kinematic-error model (eq. 3.7) is configured.
    pub(crate) fn has_kinematic_error(&self) -> bool {
        self.kinematic_error_phase.is_some() || self.kinematic_error.is_some()
    }

    /// Eq. (3.7) at link and motor angles (rad) given as `(sin, cos)` pairs.
    #[inline]
    fn kinematic_error(&self, link: (S, S), motor: (S, S)) -> S {
        match &self.kinematic_error {
            Some(a) => KinematicErrorModel::series(a, link, motor),
            None => S::ZERO,
        }
    }

    /// Eq. (3.7) in phase form from the link count `c_l < L` and the motor
    /// count within the motor revolution `p < M` (stored torsion units; the
    /// error bound is in the module docs).
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    pub(crate) fn kinematic_error_from_counts(&self, c_l: u32, p: u32) -> S {
        match &self.kinematic_error_phase {
            Some(k) => {
                let link = self.link_turn.turn(c_l);
                let motor = self.motor_turn.turn(p);
                let (r, phi) = (&k.amplitudes, &k.phases);
                if S::FLOAT {
                    // Floats (folded at compile time): one sine and cosine
                    // of the motor angle for both motor harmonics.
                    let [o, a, b] = self.double_angle;
                    let (s, c) = S::sin_cos_turn_coarse(motor.wrapping_sub(phi[1]));
                    return o
                        .add(r[0].mul(S::cos_turn_coarse(link.wrapping_sub(phi[0]))))
                        .add(c.mul(r[1].add(a.mul(c).add(b.mul(s)))));
                }
                // |cos| ≤ 1 on every backend: the unit-range product.
                k.offset
                    .add(r[0].mul_unit_range(S::cos_turn(link.wrapping_sub(phi[0]))))
                    .add(r[1].mul_unit_range(S::cos_turn(motor.wrapping_sub(phi[1]))))
                    .add(r[2].mul_unit_range(S::cos_turn((motor << 1).wrapping_sub(phi[2]))))
            }
            None => S::ZERO,
        }
    }

    /// Eq. (3.9)–(3.10) from a torsion, the kinematic error and the motor
    /// torque, with the output saturation and the input checks of
    /// [`TorqueEstimate::invalid_input`]: a torsion beyond `±torsion_range`
    /// (or NaN) is clamped to it (NaN to 0), a non-finite motor torque is
    /// taken as 0, and either sets `invalid_input`. `count_negative` is
    /// `Some(D < 0)` for a torsion converted from a count `D` (finite, with
    /// the sign of `D`: the clamp then takes that sign without comparing
    /// the torsion again), `None` otherwise. `torque_finite` tells that
    /// the motor torque is known to be finite (the previous command of the
    /// mode manager), so that it is not tested.
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    fn finish(
        &self,
        torsion: S,
        count_negative: Option<bool>,
        kin_err: S,
        motor_torque: S,
        torque_finite: bool,
        link_count_invalid: bool,
    ) -> TorqueEstimate<S> {
        // One comparison on the common path; NaN fails it.
        let (torsion, torsion_bad) = if torsion.abs() <= self.torsion_range {
            (torsion, false)
        } else if let Some(negative) = count_negative {
            // From counts: finite, with the sign of the count.
            let r = self.torsion_range;
            (if negative { r.neg() } else { r }, true)
        } else if torsion > S::ZERO {
            (self.torsion_range, true)
        } else if torsion < S::ZERO {
            (self.torsion_range.neg(), true)
        } else {
            (S::ZERO, true)
        };
        let torque_bad = !torque_finite && !S::all_finite(&[motor_torque]);
        let motor_torque = if torque_bad { S::ZERO } else { motor_torque };
        let flexspline_torsion = torsion
            .add(self.wave_generator.output_torsion(motor_torque))
            .sub(kin_err);
        // Out of the branch or beyond `max_torque` exactly when |Δθ_f|
        // exceeds the prepared limit (both tests are monotone in |Δθ_f|):
        // one comparison, and no `tan` on the saturated path. The torsion
        // and the kinematic error are finite here, so `Δθ_f` is too.
        let saturated = flexspline_torsion.abs() > self.torsion_limit;
        let torque = if saturated {
            let limit = self.max_torque;
            if flexspline_torsion < S::ZERO {
                limit.neg()
            } else {
                limit
            }
        } else {
            self.flexspline.torque_in_branch(flexspline_torsion)
        };
        TorqueEstimate {
            torque,
            torsion,
            flexspline_torsion,
            saturated,
            link_count_invalid,
            invalid_input: torsion_bad || torque_bad,
        }
    }

    /// One estimate from raw encoder readings: the link-side absolute count
    /// (`[0, L)`; larger values are reduced modulo `L` and flagged), the
    /// free-running motor counter, and the motor torque command `τ_w` in
    /// stored motor-torque units.
    ///
    /// **Signs** (errata E2.10). The counts follow eq. (2.13): the motor
    /// angle `θ_wi` increases in the direction that, through the gear,
    /// turns the link *backwards* (`θ_w = −N θ_f`, eq. 2.4), so a rigid
    /// motion leaves `Δθ = θ_fo + θ_wi/N` at zero. `τ_w` is the motor torque
    /// positive in the direction that drives the link *forward* (opposite
    /// to increasing `θ_wi`). The estimate has the sign of the torsion: a
    /// motor driving a locked link forward gives `Δθ < 0` and a negative
    /// `torque`. For the chapter-4 convention `q_m = N q_l` pass the motor
    /// counter negated; the transmitted torque `τ_t` of eq. (4.1) is then
    /// `−torque`.
    #[cfg_attr(not(armv6m), inline(always))]
    #[cfg_attr(armv6m, inline)]
    pub fn update(
        &self,
        st: &mut TorqueEstimatorState,
        link_count: u32,
        motor_counter: u32,
        motor_torque: S,
    ) -> TorqueEstimate<S> {
        self.update_with(st, link_count, motor_counter, motor_torque, false)
    }

    /// [`update`](Self::update), told whether the motor torque is known to
    /// be finite (`torque_finite`: it is then not tested; the joint passes
    /// the mode manager's previous command, which is limited).
    #[cfg_attr(not(armv6m), inline(always))]
    #[cfg_attr(armv6m, inline)]
    pub(crate) fn update_with(
        &self,
        st: &mut TorqueEstimatorState,
        link_count: u32,
        motor_counter: u32,
        motor_torque: S,
        torque_finite: bool,
    ) -> TorqueEstimate<S> {
        self.advance(st, motor_counter);
        let c_l = self
            .l_div
            .div_rem_or_skip::<HAS_DIVIDE>(link_count, self.l)
            .1;
        // The kinematic error first: its phases need only `c_l` and the
        // motor position within the revolution, and fewer values are live
        // across it than across the torsion's 64-bit products.
        let kin_err = self.kinematic_error_from_counts(c_l, st.motor_in_turn);
        let (mn, lmn, half) = (self.mn, self.lmn, self.half_lmn);
        // p < MN and every product below are exact in 64 bits (LMN ≤ 2⁴⁶
        // is validated).
        let p = mul_add_below(st.motor_turn, self.m, st.motor_in_turn, mn);
        // D ∈ [0, 2·LMN); reduce to [−LMN/2, LMN/2).
        let mut d = mul_wide(c_l, mn) + mul_wide(self.l, p);
        if d >= half {
            d -= lmn;
        }
        if d >= half {
            d -= lmn;
        }
        // The flag formed where it is used (not kept live across the
        // kinematic error and the products).
        let invalid = link_count >= self.l;
        self.estimate_from_counts(d, kin_err, motor_torque, torque_finite, invalid)
    }

    /// Steps 3–4 from the torsion in counts `D` of `2π/(LMN)` (the reduced
    /// eq. 2.13 torsion [`update`](Self::update) computes, `|D| ≤ LMN/2 ≤
    /// 2⁴⁵`; the conversion needs `|D| < 2⁴⁷`): one scaling, then
    /// eq. (3.9)–(3.10). The per-drive-size proofs sweep this over every
    /// `D`.
    #[cfg(any(kani, test, feature = "proofs"))]
    #[inline]
    pub(crate) fn estimate_from_torsion_counts(
        &self,
        d: i64,
        kin_err: S,
        motor_torque: S,
        link_count_invalid: bool,
    ) -> TorqueEstimate<S> {
        self.estimate_from_counts(d, kin_err, motor_torque, false, link_count_invalid)
    }

    /// [`estimate_from_torsion_counts`](Self::estimate_from_torsion_counts)
    /// with `torque_finite` as in [`update_with`](Self::update_with).
    #[cfg_attr(not(armv6m), inline(always))]
    #[cfg_attr(armv6m, inline)]
    fn estimate_from_counts(
        &self,
        d: i64,
        kin_err: S,
        motor_torque: S,
        torque_finite: bool,
        link_count_invalid: bool,
    ) -> TorqueEstimate<S> {
        let torsion = torsion_of_counts(d, &self.torsion_per_count);
        // Floats: the clamp takes the sign of the count (the torsion is
        // finite). Fixed point keeps the comparisons (folded at compile
        // time).
        let negative = if S::FLOAT { Some(d < 0) } else { None };
        self.finish(
            torsion,
            negative,
            kin_err,
            motor_torque,
            torque_finite,
            link_count_invalid,
        )
    }

    /// One estimate from angles in radians (stored angle units): the link
    /// angle `θ_fo` and the motor angle `θ_wi` of eq. (2.13), and the motor
    /// torque command. A convenience for float backends: in `I16F16` the
    /// torsion then has the resolution of a radian angle (1.5e-5 rad), not
    /// that of the encoders — use [`update`](Self::update) there.
    ///
    /// A NaN or infinite angle gives torsion 0, no kinematic error, and
    /// `invalid_input` (so the torque is that of the motor torque alone);
    /// the torque is finite on every backend.
    pub fn update_radians(
        &self,
        link_angle: S,
        motor_angle: S,
        motor_torque: S,
    ) -> TorqueEstimate<S> {
        let torsion = link_angle
            .add(motor_angle.mul_coef(&self.inv_ratio))
            .mul_coef(&self.torsion_per_angle);
        let angles_bad = !S::all_finite(&[link_angle, motor_angle]);
        if angles_bad {
            let mut e = self.finish(S::ZERO, None, S::ZERO, motor_torque, false, false);
            e.invalid_input = true;
            return e;
        }
        let kin_err = if self.kinematic_error.is_some() {
            self.kinematic_error(link_angle.sin_cos(), motor_angle.sin_cos())
        } else {
            S::ZERO
        };
        self.finish(torsion, None, kin_err, motor_torque, false, false)
    }
}

#[cfg(any(kani, test))]
mod words {
    use super::{Divisor, KinematicErrorPhase, TorqueEstimatorConfig};
    use crate::harmonic_drive::compliance::{FlexsplineConfig, WaveGeneratorConfig};
    #[cfg(test)]
    use crate::scalar::words::Sink;
    use crate::scalar::{words::Words, Coef, CountToTurn, I16F16};
    use core::num::NonZeroU32;

    impl Divisor {
        const fn take(r: &mut Words) -> Self {
            Divisor {
                d: match NonZeroU32::new(r.u32()) {
                    Some(d) => d,
                    None => NonZeroU32::MIN,
                },
                recip: r.u32(),
            }
        }

        #[cfg(test)]
        fn put(&self, s: &mut Sink) {
            s.u32(self.d.get());
            s.u32(self.recip);
        }
    }

    impl TorqueEstimatorConfig<I16F16> {
        pub(crate) const fn take(r: &mut Words) -> Self {
            TorqueEstimatorConfig {
                flexspline: FlexsplineConfig::take(r),
                wave_generator: WaveGeneratorConfig::take(r),
                kinematic_error: if r.bool() {
                    Some([
                        r.fixed(),
                        r.fixed(),
                        r.fixed(),
                        r.fixed(),
                        r.fixed(),
                        r.fixed(),
                        r.fixed(),
                    ])
                } else {
                    None
                },
                kinematic_error_phase: if r.bool() {
                    Some(KinematicErrorPhase {
                        offset: r.fixed(),
                        amplitudes: [r.fixed(), r.fixed(), r.fixed()],
                        phases: [r.u32(), r.u32(), r.u32()],
                    })
                } else {
                    None
                },
                link_turn: CountToTurn::take(r),
                motor_turn: CountToTurn::take(r),
                max_torque: r.fixed(),
                torsion_per_count: Coef::take(r),
                torsion_per_angle: Coef::take(r),
                inv_ratio: Coef::take(r),
                l: r.u32(),
                m: r.u32(),
                n: r.u32(),
                l_div: Divisor::take(r),
                m_div: Divisor::take(r),
                n_div: Divisor::take(r),
                mn: r.i64(),
                lmn: r.i64(),
                half_lmn: r.i64(),
                double_angle: [r.fixed(), r.fixed(), r.fixed()],
                torsion_limit: r.fixed(),
                torsion_range: r.fixed(),
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            self.flexspline.put(s);
            self.wave_generator.put(s);
            s.bool(self.kinematic_error.is_some());
            if let Some(k) = &self.kinematic_error {
                s.fixeds(k);
            }
            s.bool(self.kinematic_error_phase.is_some());
            if let Some(k) = &self.kinematic_error_phase {
                s.fixed(k.offset);
                s.fixeds(&k.amplitudes);
                k.phases.iter().for_each(|&p| s.u32(p));
            }
            self.link_turn.put(s);
            self.motor_turn.put(s);
            s.fixed(self.max_torque);
            self.torsion_per_count.put(s);
            self.torsion_per_angle.put(s);
            self.inv_ratio.put(s);
            s.u32(self.l);
            s.u32(self.m);
            s.u32(self.n);
            self.l_div.put(s);
            self.m_div.put(s);
            self.n_div.put(s);
            s.i64(self.mn);
            s.i64(self.lmn);
            s.i64(self.half_lmn);
            s.fixeds(&self.double_angle);
            s.fixed(self.torsion_limit);
            s.fixed(self.torsion_range);
        }
    }
}

#[cfg(test)]
mod tests;
