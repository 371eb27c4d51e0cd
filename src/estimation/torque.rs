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
//! motor harmonics from one [`Scalar::sin_cos_turn_coarse`] of `u = θ_wi − φ_1`
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
//!   [`Scalar::cos_turn_coarse`] and [`Scalar::sin_cos_turn_coarse`], a
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
use crate::scalar::target::inlined_except_on_armv6m;
use crate::scalar::target::own_function_on_armv6m;
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
    if S::RESOLUTION.to_f64() < 1e-6 {
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
/// the domain of [`Scalar::tan_bounded`] (`atan 8`) with a margin far
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
        // With a divide instruction the division is cheaper than the test
        // that skips it (and the static bound pays both); Armv6-M skips it.
        let (q, r) = if HAS_DIVIDE || mag >= m {
            self.m_div.div_rem(mag)
        } else {
            (0, mag)
        };
        let turn = if delta >= 0 {
            // in_turn + r < 2M, compared without overflow.
            let mut carry = q;
            if r >= m - in_turn {
                in_turn = r - (m - in_turn);
                carry += 1;
            } else {
                in_turn += r;
            }
            let c = if HAS_DIVIDE || carry >= n {
                self.n_div.div_rem(carry).1
            } else {
                carry
            };
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
            let b = if HAS_DIVIDE || borrow >= n {
                self.n_div.div_rem(borrow).1
            } else {
                borrow
            };
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

    /// Eq. (3.7) at link and motor angles (rad) given as `(sin, cos)` pairs.
    #[inline]
    fn kinematic_error(&self, link: (S, S), motor: (S, S)) -> S {
        match &self.kinematic_error {
            Some(a) => KinematicErrorModel::series(a, link, motor),
            None => S::ZERO,
        }
    }

    own_function_on_armv6m! {
        /// Eq. (3.7) in phase form from the link count `c_l < L` and the motor
        /// count within the motor revolution `p < M` (stored torsion units; the
        /// error bound is in the module docs).
        pub(crate) fn kinematic_error_from_counts(&self, c_l: u32, p: u32) -> S {
            match &self.kinematic_error_phase {
                Some(k) => {
                    let link = self.link_turn.turn(c_l);
                    let motor = self.motor_turn.turn(p);
                    let (r, phi) = (&k.amplitudes, &k.phases);
                    if S::RESOLUTION.to_f64() < 1e-6 {
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
    }

    own_function_on_armv6m! {
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
    }

    inlined_except_on_armv6m! {
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
        pub fn update(
            &self,
            st: &mut TorqueEstimatorState,
            link_count: u32,
            motor_counter: u32,
            motor_torque: S,
        ) -> TorqueEstimate<S> {
            self.update_with(st, link_count, motor_counter, motor_torque, false)
        }
    }

    inlined_except_on_armv6m! {
        /// [`update`](Self::update), told whether the motor torque is known to
        /// be finite (`torque_finite`: it is then not tested; the joint passes
        /// the mode manager's previous command, which is limited).
        pub(crate) fn update_with(
            &self,
            st: &mut TorqueEstimatorState,
            link_count: u32,
            motor_counter: u32,
            motor_torque: S,
            torque_finite: bool,
        ) -> TorqueEstimate<S> {
            self.advance(st, motor_counter);
            let c_l = if HAS_DIVIDE || link_count >= self.l {
                self.l_div.div_rem(link_count).1
            } else {
                link_count
            };
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

    inlined_except_on_armv6m! {
        /// [`estimate_from_torsion_counts`](Self::estimate_from_torsion_counts)
        /// with `torque_finite` as in [`update_with`](Self::update_with).
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
            let negative = if S::RESOLUTION.to_f64() < 1e-6 {
                Some(d < 0)
            } else {
                None
            };
            self.finish(
                torsion,
                negative,
                kin_err,
                motor_torque,
                torque_finite,
                link_count_invalid,
            )
        }
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
mod tests {
    use super::*;
    use crate::harmonic_drive::CatalogueData;
    use crate::scalar::target::mul_wide_split;
    use crate::scalar::I16F16;
    use proptest::prelude::*;
    use std::string::ToString;

    const L: u32 = 1 << 17;
    const M: u32 = 2000;

    /// The reciprocal division equals `/` and `%` on edges of every kind:
    /// divisors 1, 2, powers of two and their neighbours, the estimator's
    /// M, N and L, the largest `u32`; dividends around multiples of `d`
    /// and at the ends of the `u32` range.
    #[test]
    fn reciprocal_division_is_exact_on_edges() {
        let mut ds = vec![1u32, 2, 3, 7, 100, 160, M, L, u32::MAX, u32::MAX - 1];
        for k in 1..32 {
            ds.extend([(1u32 << k) - 1, 1 << k, (1 << k) + 1]);
        }
        for &d in &ds {
            let mut xs = vec![0u32, 1, d - 1, d, d.wrapping_add(1), u32::MAX, u32::MAX - 1];
            xs.extend([1u32 << 31, (1 << 31) - 1, (1 << 31) + 1]);
            let top = u32::MAX / d;
            for q in [1, 2, top / 2, top - 1, top] {
                let base = q.wrapping_mul(d);
                xs.extend([base, base.wrapping_sub(1), base.wrapping_add(1)]);
            }
            for x in xs {
                assert_eq!(
                    div_rem_reciprocal(x, d, reciprocal(d)),
                    (x / d, x % d),
                    "{x} / {d}"
                );
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(100_000))]
        /// The reciprocal division equals `/` and `%` for random operands.
        #[test]
        fn reciprocal_division_is_exact(x: u32, d in 1u32.., small in 1u32..5000) {
            for d in [d, small] {
                prop_assert_eq!(div_rem_reciprocal(x, d, reciprocal(d)), (x / d, x % d));
            }
        }
    }

    fn params(ke: Option<KinematicErrorModel>) -> TorqueEstimatorParams {
        let drive = CatalogueData::SHD_17_100.identify().unwrap();
        TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: ke,
            link_counts_per_rev: L,
            motor_counts_per_rev: M,
            max_torque: 60.0,
        })
        .unwrap()
    }

    /// The SHD-17-100 estimator with other encoders `L`, `M` and ratio `N`.
    fn params_sized(
        ke: Option<KinematicErrorModel>,
        l: u32,
        m: u32,
        n: u32,
    ) -> TorqueEstimatorParams {
        let d = CatalogueData::SHD_17_100.identify().unwrap();
        let drive =
            HarmonicDriveParams::try_new(d.flexspline(), d.wave_generator(), n as f64).unwrap();
        TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: ke,
            link_counts_per_rev: l,
            motor_counts_per_rev: m,
            max_torque: 60.0,
        })
        .unwrap()
    }

    /// Encoder readings for a joint at link angle `link` (rad) carrying a
    /// flexspline torque `tau` with motor torque `tau_w` (forward model,
    /// eq. 2.30 and 3.8), and the half-width of the torsion quantization.
    fn readings(p: &TorqueEstimatorParams, link: f64, tau: f64, tau_w: f64) -> (u32, i64, f64) {
        let n = p.drive.ratio();
        let base = p.drive.torsion(tau, tau_w);
        let mut torsion = base;
        if let Some(k) = p.kinematic_error {
            // θ_err depends on the measured motor angle θ_wi = N(Δθ − θ_fo),
            // which depends on the torsion: solve Δθ = base + θ_err by
            // fixed-point iteration (a contraction: N·|dθ_err/dθ_wi| < 0.02).
            for _ in 0..30 {
                torsion = base + k.evaluate(link, n * (torsion - link));
            }
        }
        let motor = n * (torsion - link); // eq. (2.13) solved for θ_wi
        let c_l = libm::round(link / TAU * L as f64) as i64;
        let p_m = libm::round(motor / TAU * M as f64) as i64;
        let q = TAU / L as f64 * 0.5 + TAU / (M as f64 * n) * 0.5;
        (c_l.rem_euclid(L as i64) as u32, p_m, q)
    }

    proptest! {
        /// Round trip through the forward model: the estimate lies between
        /// the torques of the flexspline torsions ± the encoder quantization
        /// (plus the kinematic error's change over one count), by
        /// monotonicity of eq. (3.10).
        #[test]
        fn estimate_inverts_the_forward_model(
            link in 0.0f64..TAU, tau in -40.0f64..40.0, tau_w in -0.2f64..0.2, with_ke: bool,
        ) {
            let ke = with_ke.then(KinematicErrorModel::table_3_2);
            let p = params(ke);
            let (c_l, p_m, q) = readings(&p, link, tau, tau_w);
            let cfg = TorqueEstimatorConfig::<f64>::new(&p);
            let mut st = cfg.state(p_m, 12345);
            let est = cfg.update(&mut st, c_l, 12345, tau_w);
            prop_assert!(!est.saturated);
            let ke_slope = ke.map_or(0.0, |k| {
                let c = k.coefficients();
                (c[1].abs() + c[2].abs()) * TAU / L as f64 + (c[3].abs() + c[4].abs() + 2.0 * (c[5].abs() + c[6].abs())) * TAU / M as f64
            });
            let d = q + ke_slope + 1e-12;
            let f = p.drive.flexspline();
            let true_tf = f.torsion(tau);
            let (lo, hi) = (f.torque(true_tf - d).torque, f.torque(true_tf + d).torque);
            prop_assert!(est.torque >= lo - 1e-9 && est.torque <= hi + 1e-9, "{} not in [{lo}, {hi}] (τ = {tau})", est.torque);
        }

        /// The motor position follows a wrapping 32-bit counter through any
        /// sequence of moves (each under 2³¹ counts).
        #[test]
        fn motor_position_follows_wrapping_counter(
            start in any::<u32>(), pos0 in -1_000_000i64..1_000_000,
            moves in proptest::collection::vec(-5_000_000i64..5_000_000, 1..50),
        ) {
            let p = params(None);
            let cfg = TorqueEstimatorConfig::<f64>::new(&p);
            let mut st = cfg.state(pos0, start);
            let (mut counter, mut pos) = (start, pos0);
            let mn = (M * 100) as i64;
            for mv in moves {
                counter = counter.wrapping_add(mv as i32 as u32);
                pos += mv;
                cfg.advance(&mut st, counter);
                let want = pos.rem_euclid(mn);
                prop_assert_eq!(st.motor_turn as i64 * M as i64 + st.motor_in_turn as i64, want);
            }
        }

        /// I16F16 agrees with f64 on the count path (the full-range
        /// exhaustive sweep is in proofs/); here: within 0.5 % of the rated
        /// 16 N·m over the torque range.
        #[test]
        fn fixed_agrees_with_f64(link in 0.0f64..TAU, tau in -40.0f64..40.0, tau_w in -0.2f64..0.2) {
            let p = params(Some(KinematicErrorModel::table_3_2()));
            let (c_l, p_m, _) = readings(&p, link, tau, tau_w);
            let cf = TorqueEstimatorConfig::<f64>::new(&p);
            let cx = TorqueEstimatorConfig::<I16F16>::new(&p);
            let a = cf.update(&mut cf.state(p_m, 0), c_l, 0, tau_w).torque;
            let b = cx.update(&mut cx.state(p_m, 0), c_l, 0, I16F16::from_f64(tau_w * 1e3)).torque.to_f64();
            prop_assert!((a - b).abs() <= 0.005 * 16.0, "{a} vs {b}");
        }
    }

    proptest! {
        /// f32 and I16F16 lie within their documented `AgreementBound` of
        /// f64 on the SHD-17-100 (with and without Table 3.2), over the
        /// torque range and beyond (saturation), on the count path.
        #[test]
        fn backends_within_the_agreement_bound(
            link in 0.0f64..TAU, tau in -80.0f64..80.0, tau_w in -0.2f64..0.2, with_ke: bool,
        ) {
            let p = params(with_ke.then(KinematicErrorModel::table_3_2));
            let (c_l, p_m, _) = readings(&p, link, tau, tau_w);
            let cf = TorqueEstimatorConfig::<f64>::new(&p);
            let a = cf.update(&mut cf.state(p_m, 0), c_l, 0, tau_w);
            fn backend<S: Scalar>(p: &TorqueEstimatorParams, c_l: u32, p_m: i64, tau_w: f64) -> TorqueEstimate<S> {
                let c = TorqueEstimatorConfig::<S>::new(p);
                c.update(&mut c.state(p_m, 0), c_l, 0, S::from_f64(tau_w * S::UNITS.motor_torque))
            }
            for (b, bound) in [
                (backend::<f32>(&p, c_l, p_m, tau_w), p.agreement_bound::<f32>()),
            ].into_iter().map(|(b, bd)| ((b.torque_si(), b.flexspline_torsion_si()), bd))
                .chain([{
                    let b = backend::<I16F16>(&p, c_l, p_m, tau_w);
                    ((b.torque_si(), b.flexspline_torsion_si()), p.agreement_bound::<I16F16>())
                }])
            {
                let (lo, hi) = bound.torque_interval(&p, a.flexspline_torsion);
                prop_assert!(lo <= b.0 && b.0 <= hi, "{} not in [{lo}, {hi}]", b.0);
                prop_assert!((b.1 - a.flexspline_torsion).abs() <= bound.torsion);
            }
        }
    }

    /// f32 stays within its agreement bound with harmonics of millirad
    /// (the `api_params` fuzz target found a drive with a 7.3 mrad one
    /// beyond the bound that ignored the table cosine's error).
    #[test]
    fn f32_agreement_bound_covers_a_large_kinematic_error() {
        let k = KinematicErrorModel::try_new([4.4e-5, 1e-7, 6.4e-5, -6.2e-5, -1e-7, 7.3e-3, 1e-7])
            .unwrap();
        let p = params(Some(k));
        let bound = p.agreement_bound::<f32>();
        let (c64, c32) = (
            TorqueEstimatorConfig::<f64>::new(&p),
            TorqueEstimatorConfig::<f32>::new(&p),
        );
        let rigid = params(None);
        let mut worst = 0.0f64;
        for i in 0..2000 {
            let link = TAU * i as f64 / 2000.0;
            for tau in [-30.0, -3.0, 0.0, 5.0, 40.0] {
                let (c_l, p_m, _) = readings(&rigid, link, tau, 0.0);
                let a = c64.update(&mut c64.state(p_m, 0), c_l, 0, 0.0);
                let b = c32.update(&mut c32.state(p_m, 0), c_l, 0, 0.0);
                let e = (b.flexspline_torsion_si() - a.flexspline_torsion).abs();
                assert!(
                    e <= bound.torsion,
                    "{e} > {} at {c_l}, {p_m}",
                    bound.torsion
                );
                worst = worst.max(e);
            }
        }
        // Above what the full-accuracy cosines allowed (the former bound,
        // `2(8u·range + 8u·A_w + (30u + e_θ)·A)`): the test fails without
        // the table cosine's term.
        let u = libm::exp2(-24.0);
        let e_theta = 3.5 * TAU / 4_294_967_296.0;
        let former = 2.0
            * (8.0 * u * p.torsion_range()
                + 8.0 * u * p.drive.output_wave_generator_torsion()
                + (30.0 * u + e_theta) * k.amplitude_bound());
        std::eprintln!(
            "f32 Δθ_f worst {worst:e}, bound {:e}, former {former:e}",
            bound.torsion
        );
        assert!(worst > former, "{worst:e} <= {former:e}");
    }

    /// The agreement bound is not vacuous: at a loaded torsion the
    /// interval excludes 0 (a silent 0 fails it) and is narrower than
    /// 0.01 N·m on I16F16 and 1e-3 N·m on f32.
    #[test]
    fn agreement_bound_rejects_a_silent_zero() {
        let p = params(Some(KinematicErrorModel::table_3_2()));
        let torsion = p.drive().flexspline().torsion(10.0);
        for (bound, width) in [
            (p.agreement_bound::<I16F16>(), 0.01),
            (p.agreement_bound::<f32>(), 1e-3),
        ] {
            let (lo, hi) = bound.torque_interval(&p, torsion);
            assert!(lo > 0.0 && hi - lo < width, "[{lo}, {hi}]");
            assert!(lo <= 10.0 && 10.0 <= hi);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]
        /// The 32-bit `advance` equals the 64-bit formula from any state
        /// for any counter (moves up to ±2³¹ counts), on the Table 3.2
        /// drive and on encoder/ratio sizes with M, N near the edges.
        #[test]
        fn advance_equals_the_64_bit_formula(
            pos in 0i64..1 << 40, last in any::<u32>(), counter in any::<u32>(), small: bool,
            size in 0usize..4,
        ) {
            let (m, n) = [(M, 100u32), (1, 1), (3, 65535), (1 << 20, 160)][size];
            // The link encoder plays no part in `advance`; L = 1 keeps every
            // size within the validated `L·M·N`.
            let p = params_sized(None, 1, m, n);
            let cfg = TorqueEstimatorConfig::<f64>::new(&p);
            let counter = if small { last.wrapping_add(counter % 8001).wrapping_sub(4000) } else { counter };
            let mut a = cfg.state(pos, last);
            let mut b = a;
            cfg.advance(&mut a, counter);
            cfg.advance_reference(&mut b, counter);
            prop_assert_eq!(a, b);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]
        /// `update` forms the torsion count `D` of eq. (2.13) exactly: equal
        /// to the i128 formula `c_l·MN + p·L` reduced to `[−LMN/2, LMN/2)`.
        #[test]
        fn update_uses_the_exact_torsion_count(
            c_l in 0u32..L, pos in -(1i64 << 40)..(1i64 << 40), tw in -200i32..200,
        ) {
            let cfg = TorqueEstimatorConfig::<I16F16>::new(&params(None));
            let tw = I16F16::from_num(tw);
            let mut st = cfg.state(pos, 7);
            let got = cfg.update(&mut st, c_l, 7, tw);
            let (l, mn) = (L as i128, (M * 100) as i128);
            let p = (pos as i128).rem_euclid(mn);
            let d = (c_l as i128 * mn + p * l + l * mn / 2).rem_euclid(l * mn) - l * mn / 2;
            let want = cfg.estimate_from_torsion_counts(d as i64, I16F16::ZERO, tw, false);
            prop_assert_eq!(got, want);
        }

        /// `mul_wide` is the exact product on both of its paths.
        #[test]
        fn mul_wide_is_exact(a in any::<u32>(), b in 0i64..1 << 48, narrow: bool) {
            // Products below 2⁶⁴, as at the call sites.
            let (a, b) = if narrow { (a >> 1, b & 0xFFFF_FFFF) } else { (a >> 17, b) };
            prop_assert_eq!(mul_wide(a, b) as u128, a as u128 * b as u128);
        }

        /// The Armv6-M form of `mul_wide` is the exact product (bits of the
        /// 64-bit product) for a 32-bit `b` and for every product below
        /// 2⁶³ (the call sites' range).
        #[test]
        fn mul_wide_split_is_exact(a in any::<u32>(), b in 0i64..1 << 48, narrow: bool) {
            let (a, b) = if narrow { (a, b & 0xFFFF_FFFF) } else { (a >> 17, b) };
            prop_assert_eq!(mul_wide_split(a, b) as u64 as u128, a as u128 * b as u128);
        }
    }

    /// The split conversion of a torsion count equals `from_counts` bit
    /// for bit on floats for every `|d| < 2⁴⁷`: the edges, both sides of
    /// every power of two and of the 2²⁴ split, halfway cases, random
    /// counts (`from_counts` on `f32` is the correctly rounded
    /// `count_to_f32`, tested against `as` in `scalar::float`).
    #[test]
    fn torsion_of_counts_equals_from_counts_below_2_47() {
        let mut ds = vec![
            0i64,
            1,
            -1,
            (1 << 47) - 1,
            -(1 << 47),
            (1 << 24) - 1,
            1 << 24,
        ];
        for k in 0..47 {
            for e in [-3i64, -1, 0, 1, 2, 3] {
                ds.extend([(1i64 << k) + e, -(1i64 << k) + e]);
            }
            if k > 25 {
                // Halfway between two f32 values, and one count off it.
                let h = (1i64 << k) + (1 << (k - 24));
                ds.extend([h, h - 1, h + 1, -h, -h + 1, -h - 1]);
            }
        }
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        for _ in 0..200_000 {
            let x = crate::scalar::xorshift64(&mut state);
            ds.push((x as i64) >> (17 + x % 40));
        }
        for c in [
            Coef::new(1.0),
            Coef::new(TAU / 2.62144e10),
            Coef::new(3.7e-7),
        ] {
            for &d in &ds {
                assert!(d.unsigned_abs() <= 1 << 47, "{d}");
                if d == 1 << 47 {
                    continue;
                }
                let (a, b): (f32, f32) = (torsion_of_counts(d, &c), f32::from_counts(d, &c));
                assert_eq!(a.to_bits(), b.to_bits(), "f32 {d}");
                let (a, b): (f64, f64) = (torsion_of_counts(d, &c), f64::from_counts(d, &c));
                assert_eq!(a.to_bits(), b.to_bits(), "f64 {d}");
            }
        }
    }

    /// The error bound of the module docs ("Kinematic error from counts")
    /// for backend `S`, in stored torsion units, plus the `f64`
    /// reference's own rounding (`8 ε A`).
    fn ke_count_bound<S: Scalar>(k: &KinematicErrorModel) -> f64 {
        let f = k.phase_form();
        let t = S::UNITS.torsion;
        let (a0, r) = (f.offset.abs() * t, f.amplitudes.map(|r| r * t));
        let a = a0 + r.iter().sum::<f64>();
        let e_theta = 3.5 * TAU / 4_294_967_296.0;
        let reference = 8.0 * f64::EPSILON * a;
        let bound = if S::NAME == "I16F16" {
            let q = 1.0 / 65536.0;
            q / 2.0
                + r.iter()
                    .map(|&rj| q / 2.0 * (1.0 + q) + rj * (q + e_theta) + q / 2.0)
                    .sum::<f64>()
        } else {
            assert_eq!(S::NAME, "f32");
            // The double-angle form of the motor harmonics (module docs).
            let u = f32::EPSILON as f64 / 2.0; // 2⁻²⁴
                                               // cos_turn_coarse, sin_cos_turn_coarse: 4.8e-6.
            let c = crate::scalar::kernels::f32::COS_TURN_COARSE_BOUND;
            a0 * u
                + r[0] * (2.0 * u + c + e_theta)
                + (r[1] + 8.0 * r[2]) * (c + e_theta)
                + u * (2.0 * r[1] + 15.0 * r[2])
                + 2.0 * u * (a0 + r[0] + r[1] + 3.0 * r[2])
                + 4.0 * r[2] * (c + e_theta) * (c + e_theta)
                + 40.0 * u * u * a
        };
        bound + reference
    }

    /// Counts to test for an encoder of `n` counts: 0, `n − 1`, the
    /// quadrant boundaries and their neighbours, and a stride.
    fn test_counts(n: u32) -> Vec<u32> {
        let mut v = vec![0, 1, n - 1];
        for q in 1..4u32 {
            let b = (n as u64 * q as u64 / 4) as u32;
            v.extend([b.saturating_sub(1), b, b + 1]);
        }
        let step = (n / 157).max(1);
        v.extend((0..n).step_by(step as usize));
        v.retain(|&c| c < n);
        v
    }

    /// The largest error of the count-based eq. (3.7) of backend `S`
    /// against `f64` [`KinematicErrorModel::evaluate`] at the count angles
    /// `2π c_l/L`, `2π p/M` (stored units), over the test counts; panics
    /// beyond [`ke_count_bound`].
    fn ke_count_worst<S: Scalar>(k: KinematicErrorModel, l: u32, m: u32) -> f64 {
        let p = params_sized(Some(k), l, m, 100);
        let cfg = TorqueEstimatorConfig::<S>::new(&p);
        let bound = ke_count_bound::<S>(&k);
        let mut worst = 0.0f64;
        for c in test_counts(l) {
            for q in test_counts(m) {
                let want = k.evaluate(TAU * c as f64 / l as f64, TAU * q as f64 / m as f64)
                    * S::UNITS.torsion;
                let got = cfg.kinematic_error_from_counts(c, q).to_f64();
                let e = (got - want).abs();
                assert!(
                    e <= bound,
                    "{} L = {l}, M = {m}, c_l = {c}, p = {q}: {got} vs {want} (bound {bound})",
                    S::NAME
                );
                worst = worst.max(e / bound);
            }
        }
        worst
    }

    /// The count-based kinematic error (phase form, binary angles,
    /// `cos_turn`) agrees with `f64` eq. (3.7) within the derived bound on
    /// I16F16 and f32, for Table 3.2 and a larger model with an offset,
    /// with power-of-two and other encoder resolutions.
    #[test]
    fn kinematic_error_from_counts_within_bound() {
        let larger =
            KinematicErrorModel::try_new([2e-4, 3e-4, -1e-4, -2e-4, 1.5e-4, 1e-4, -3e-4]).unwrap();
        let mut worst = [0.0f64; 2];
        for k in [KinematicErrorModel::table_3_2(), larger] {
            for (l, m) in [(L, M), (100_000, 4096), (36_000, 1000), (1 << 20, 3)] {
                worst[0] = worst[0].max(ke_count_worst::<I16F16>(k, l, m));
                worst[1] = worst[1].max(ke_count_worst::<f32>(k, l, m));
            }
        }
        std::eprintln!(
            "kinematic error from counts, worst error / bound: I16F16 {:.3}, f32 {:.3}",
            worst[0],
            worst[1]
        );
        // The bound is not vacuous: the errors reach a visible part of it.
        assert!(worst.iter().all(|&w| w > 0.05), "worst / bound: {worst:?}");
    }

    /// `update` subtracts exactly the count-based kinematic error.
    #[test]
    fn update_subtracts_the_count_based_kinematic_error() {
        let p = params(Some(KinematicErrorModel::table_3_2()));
        let cfg = TorqueEstimatorConfig::<I16F16>::new(&p);
        let tw = I16F16::from_num(3);
        // Motor positions near the rigid one, `−c_l·MN/L`, so that the
        // torsion stays inside the model's range.
        let mn = M as i64 * 100;
        for (c_l, off) in [(0u32, 0i64), (L / 4, 5), (L - 1, -3), (77_777, 2)] {
            let pos = -(c_l as i64 * mn / L as i64) + off;
            let with = cfg.update(&mut cfg.state(pos, 0), c_l, 0, tw);
            let ke = cfg.kinematic_error_from_counts(c_l, pos.rem_euclid(M as i64) as u32);
            assert_ne!(ke, I16F16::ZERO);
            assert_eq!(with.flexspline_torsion, {
                let none = TorqueEstimatorConfig::<I16F16>::new(&params(None));
                none.update(&mut none.state(pos, 0), c_l, 0, tw)
                    .flexspline_torsion
                    - ke
            });
        }
    }

    #[test]
    fn out_of_branch_torsion_saturates_at_max_torque_with_flag() {
        let p = params(None);
        let cfg = TorqueEstimatorConfig::<f32>::new(&p);
        let n = 100i64;
        // A link angle of +0.01 rad with the motor at rest: Δθ = 10 mrad,
        // beyond the flexspline's 4.2 mrad maximum.
        let c_l = (0.01 / TAU * L as f64) as u32;
        let mut st = cfg.state(0, 0);
        let e = cfg.update(&mut st, c_l, 0, 0.0);
        assert!(e.saturated && e.torque == 60.0, "{e:?}");
        let mut st = cfg.state(0, 0);
        let e = cfg.update(&mut st, L - c_l, 0, 0.0);
        assert!(e.saturated && e.torque == -60.0, "{e:?}");
        // An invalid link count is reduced and flagged.
        let mut st = cfg.state(0, 0);
        let e = cfg.update(&mut st, L, 0, 0.0);
        assert!(e.link_count_invalid && e.torque == 0.0);
        let _ = n;
    }

    /// The saturation of `finish` by one comparison against the prepared
    /// `torsion_limit` equals the two direct tests it replaces (the `tan`
    /// argument beyond `atan 8`, the domain of `tan_bounded`, then
    /// `|τ| > max_torque`) at every torsion tried: on `I16F16` every code
    /// within twice the branch edge, on the floats a thousand codes either
    /// side of the limit and a log sweep. The limit is tight: the direct
    /// test passes at it and fails at the next code up, and it is set by
    /// `max_torque`, not by the domain. Two set-ups: SHD-17-100 at 60 N·m
    /// and at the largest accepted `max_torque`, `7.5/c_f = 166.9` N·m; a
    /// limit above that is rejected by name.
    #[test]
    fn saturation_by_torsion_limit_equals_the_direct_tests() {
        fn direct<S: Scalar>(cfg: &TorqueEstimatorConfig<S>, ft: S) -> (S, bool) {
            let f = &cfg.flexspline;
            let angle = f.angle_of(ft);
            let bound = S::from_f64(crate::harmonic_drive::compliance::TAN_BOUNDED_ARGUMENT);
            let t = f.torque_in_branch(ft);
            let sat = angle.abs() > bound || t.abs() > cfg.max_torque;
            let m = cfg.max_torque;
            let torque = match (sat, ft < S::ZERO) {
                (false, _) => t,
                (true, true) => m.neg(),
                (true, false) => m,
            };
            (torque, sat)
        }
        fn agree<S: Scalar + core::fmt::Debug>(cfg: &TorqueEstimatorConfig<S>, ft: S) {
            let e = cfg.finish(ft, None, S::ZERO, S::ZERO, false, false);
            assert_eq!((e.torque, e.saturated), direct(cfg, ft), "at {ft:?}");
        }
        /// Whether the torque (not the domain) fails just above the limit.
        fn torque_bound<S: Scalar>(cfg: &TorqueEstimatorConfig<S>, up: S) -> bool {
            let t = |x: S| cfg.flexspline.torque_in_branch(x).abs() > cfg.max_torque;
            t(up) || t(up.neg())
        }
        /// Checks one float configuration; returns whether the next torsion
        /// above the limit fails by its torque.
        fn floats<S: Scalar + core::fmt::Debug>(
            cfg: &TorqueEstimatorConfig<S>,
            step: impl Fn(S, i32) -> S,
        ) -> bool {
            let a = cfg.torsion_limit;
            assert!(!direct(cfg, a).1 && !direct(cfg, a.neg()).1);
            let up = step(a, 1);
            assert!(direct(cfg, up).1 || direct(cfg, up.neg()).1);
            for k in -1000..=1000 {
                let t = step(a, k);
                agree(cfg, t);
                agree(cfg, t.neg());
            }
            let edge = a.to_f64();
            for i in 0..=4000 {
                let t = S::from_f64(edge * 1e-6 * libm::pow(2e6, i as f64 / 4000.0));
                agree(cfg, t);
                agree(cfg, t.neg());
            }
            for t in [S::ZERO, S::MAX, S::MAX.neg()] {
                agree(cfg, t);
            }
            torque_bound(cfg, up)
        }
        let drive = CatalogueData::SHD_17_100.identify().unwrap();
        let c_f = drive.flexspline().c_f();
        let settings = |max_torque: f64| TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: L,
            motor_counts_per_rev: M,
            max_torque,
        };
        let largest = MAX_STIFFENING_TORQUE / c_f;
        for max in [60.0, largest] {
            let p = TorqueEstimatorParams::try_new(settings(max)).unwrap();
            assert!(floats(&TorqueEstimatorConfig::<f32>::new(&p), |x, k| {
                f32::from_bits((x.to_bits() as i32 + k) as u32)
            }));
            assert!(floats(&TorqueEstimatorConfig::<f64>::new(&p), |x, k| {
                f64::from_bits((x.to_bits() as i64 + k as i64) as u64)
            }));
            let cfg = TorqueEstimatorConfig::<I16F16>::new(&p);
            let a = cfg.torsion_limit.to_bits();
            assert!(!direct(&cfg, cfg.torsion_limit).1);
            let up = I16F16::from_bits(a + 1);
            assert!(direct(&cfg, up).1 || direct(&cfg, up.neg()).1);
            assert!(torque_bound(&cfg, up));
            let edge = (drive.flexspline().max_torsion() * I16F16::UNITS.torsion * 65536.0) as i32;
            for b in -2 * edge..=2 * edge {
                agree(&cfg, I16F16::from_bits(b));
            }
            for b in [i32::MIN, i32::MIN + 1, i32::MAX] {
                agree(&cfg, I16F16::from_bits(b));
            }
        }
        let over = largest * (1.0 + 1e-9);
        assert_eq!(
            TorqueEstimatorParams::try_new(settings(over)).unwrap_err(),
            ParamError::CombinationOutOfRange {
                name: "drive.c_f·max_torque",
                value: c_f * over,
                min: 0.0,
                max: MAX_STIFFENING_TORQUE,
            }
        );
    }

    #[test]
    fn rejects_non_integer_ratio_and_coarse_encoders() {
        let d = CatalogueData::SHD_17_100.identify().unwrap();
        let drive =
            HarmonicDriveParams::try_new(d.flexspline(), d.wave_generator(), 100.5).unwrap();
        let e = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: L,
            motor_counts_per_rev: M,
            max_torque: 60.0,
        })
        .unwrap_err();
        assert_eq!(
            e,
            ParamError::NotInteger {
                name: "drive.ratio",
                value: 100.5,
                min: 1.0,
                max: 65535.0
            }
        );
        assert_eq!(
            e.to_string(),
            "parameter `drive.ratio` must be an integer in [1, 65535], got 100.5"
        );
        let drive = CatalogueData::SHD_17_100.identify().unwrap();
        assert!(matches!(
            TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
                drive,
                kinematic_error: None,
                link_counts_per_rev: 0,
                motor_counts_per_rev: M,
                max_torque: 60.0
            }),
            Err(ParamError::NotPositive {
                name: "link_counts_per_rev",
                ..
            })
        ));
        assert!(matches!(
            TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
                drive,
                kinematic_error: None,
                link_counts_per_rev: L,
                motor_counts_per_rev: M,
                max_torque: -1.0
            }),
            Err(ParamError::NotPositive {
                name: "max_torque",
                ..
            })
        ));
        // 2^31 counts must span the torsion range: 2^26 link counts with a
        // 2^16-count motor encoder is too fine.
        assert!(matches!(
            TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
                drive,
                kinematic_error: None,
                link_counts_per_rev: 1 << 26,
                motor_counts_per_rev: 1 << 16,
                max_torque: 60.0
            }),
            Err(ParamError::CombinationOutOfRange { name: LMN_NAME, .. })
        ));
    }

    /// The named encoder resolutions reach their own getters and their own
    /// roles: one link count is a torsion of `2π/L`, one motor count one of
    /// `2π/(M N)` (eq. 2.13, computed here from the definitions). With
    /// positional `u32` arguments `L` and `M` could be swapped and still
    /// validate; swapped, these torsions would be `2π/M` and `2π/(L N)`.
    #[test]
    fn named_encoder_resolutions_reach_their_roles() {
        let drive = CatalogueData::SHD_17_100.identify().unwrap();
        let (l, m) = (1u32 << 17, 2000u32);
        let s = TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: l,
            motor_counts_per_rev: m,
            max_torque: 50.0,
        };
        let p = TorqueEstimatorParams::try_new(s).unwrap();
        assert_eq!(
            (
                p.link_counts_per_rev(),
                p.motor_counts_per_rev(),
                p.max_torque()
            ),
            (l, m, 50.0)
        );
        assert_eq!(p.settings(), s);
        assert_eq!(TorqueEstimatorParams::try_new(p.settings()), Ok(p));
        let cfg = TorqueEstimatorConfig::<f64>::new(&p);
        let one_link = cfg.update(&mut cfg.state(0, 0), 1, 0, 0.0).torsion;
        let want = TAU / l as f64;
        assert!(
            (one_link - want).abs() <= 1e-12 * want,
            "{one_link} vs {want}"
        );
        let one_motor = cfg.update(&mut cfg.state(0, 0), 0, 1, 0.0).torsion;
        let want = TAU / (m as f64 * 100.0);
        assert!(
            (one_motor.abs() - want).abs() <= 1e-12 * want,
            "{one_motor} vs {want}"
        );
    }

    /// A zero motor resolution used to reach `state()` through a struct
    /// literal and divide by zero; now it is rejected by name, as is a zero
    /// link resolution (which used to give a silent 0).
    #[test]
    fn zero_encoder_resolutions_are_rejected_by_name() {
        let drive = CatalogueData::SHD_17_100.identify().unwrap();
        for (l, m, name) in [
            (L, 0, "motor_counts_per_rev"),
            (0, M, "link_counts_per_rev"),
        ] {
            let e = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
                drive,
                kinematic_error: None,
                link_counts_per_rev: l,
                motor_counts_per_rev: m,
                max_torque: 60.0,
            })
            .unwrap_err();
            assert_eq!(e, ParamError::NotPositive { name, value: 0.0 });
            assert_eq!(
                e.to_string(),
                std::format!("parameter `{name}` must be > 0, got 0")
            );
        }
    }

    /// `L = M = u32::MAX` breaks the product rule, and the error names the
    /// whole product `L·M·N` with its value, not `L` alone.
    #[test]
    fn oversized_encoder_product_names_the_product() {
        let drive = CatalogueData::SHD_17_100.identify().unwrap();
        let e = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: u32::MAX,
            motor_counts_per_rev: u32::MAX,
            max_torque: 60.0,
        })
        .unwrap_err();
        let lmn = u32::MAX as f64 * u32::MAX as f64 * 100.0;
        match e {
            ParamError::CombinationOutOfRange {
                name,
                value,
                min,
                max,
            } => {
                assert_eq!(name, "link_counts_per_rev·motor_counts_per_rev·drive.ratio");
                assert_eq!(value, lmn);
                assert_eq!(min, 1.0);
                // The torsion range rule binds before 2⁴⁶ for this drive:
                // 2³¹ counts of 2π/(LMN) must cover twice the range.
                let p = params(None);
                let want = libm::floor(2_147_483_648.0 * TAU / (2.0 * p.torsion_range()));
                assert_eq!(max, want);
                assert!(max < MAX_COUNTS_PER_OUTPUT_REV);
            }
            other => panic!("{other:?}"),
        }
        assert!(e.to_string().starts_with(
            "`link_counts_per_rev·motor_counts_per_rev·drive.ratio` must lie in [1, "
        ));
    }

    /// `update_radians` with NaN or infinite readings: every field finite,
    /// `invalid_input` set, on every backend that has non-finite values;
    /// and a NaN or infinite motor torque on the count path is flagged
    /// (it used to count as 0, or be clamped, silently).
    #[test]
    fn non_finite_readings_are_flagged() {
        fn check<S: Scalar + core::fmt::Debug>(bad: [S; 3]) {
            let p = params(Some(KinematicErrorModel::table_3_2()));
            let cfg = TorqueEstimatorConfig::<S>::new(&p);
            let ok = S::from_f64(0.01);
            let finite = |e: &TorqueEstimate<S>| {
                [e.torque, e.torsion, e.flexspline_torsion]
                    .iter()
                    .all(|v| v.to_f64().is_finite())
            };
            for &x in &bad {
                for (la, ma, tw) in [(x, x, x), (x, ok, ok), (ok, x, ok), (ok, ok, x)] {
                    let e = cfg.update_radians(la, ma, tw);
                    assert!(e.invalid_input && finite(&e), "{la:?} {ma:?} {tw:?}: {e:?}");
                    assert!(e.torque.abs() <= cfg.max_torque);
                }
                let e = cfg.update(&mut cfg.state(0, 0), 5, 0, x);
                assert!(e.invalid_input && finite(&e), "{x:?}: {e:?}");
                // Taken as zero motor torque.
                let zero = cfg.update(&mut cfg.state(0, 0), 5, 0, S::ZERO);
                assert_eq!((e.torque, e.torsion), (zero.torque, zero.torsion));
                assert!(!zero.invalid_input);
            }
            // Finite readings of a small torsion (1 µrad) are not flagged.
            let e = cfg.update_radians(S::from_f64(0.002), S::from_f64(-0.1999), ok);
            assert!(!e.invalid_input && finite(&e));
        }
        check::<f32>([f32::NAN, f32::INFINITY, f32::NEG_INFINITY]);
        check::<f64>([f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
    }

    /// A counter jump that no torque can produce (here half an output
    /// revolution of torsion) is flagged, the torque saturates with its
    /// flag, and the reported torsion is the documented clamp
    /// `±torsion_range` on every backend (it used to be 2.628 rad on f32
    /// and 0.515 rad on I16F16 for the same readings).
    #[test]
    fn impossible_counter_jump_is_flagged_and_agrees_across_backends() {
        fn jump<S: Scalar>(p: &TorqueEstimatorParams, counts: u32) -> TorqueEstimate<S> {
            let cfg = TorqueEstimatorConfig::<S>::new(p);
            let mut st = cfg.state(0, 0);
            cfg.update(&mut st, 0, counts, S::ZERO)
        }
        let p = params(None);
        let range = p.torsion_range();
        // Motor counts (of MN = 200 000 per output revolution) for a torsion
        // of +2.6 rad and of −1.3 rad.
        for (counts, sign) in [(82_761u32, 1.0), (u32::MAX - 41_380, -1.0)] {
            let a = jump::<f32>(&p, counts);
            let b = jump::<f64>(&p, counts);
            let c = jump::<I16F16>(&p, counts);
            for (e, flagged, q) in [
                (a.torsion_si(), a.invalid_input && a.saturated, 1e-7 * range),
                (b.torsion_si(), b.invalid_input && b.saturated, 1e-15),
                (c.torsion_si(), c.invalid_input && c.saturated, 1e-8),
            ] {
                assert!(flagged);
                assert!((e - sign * range).abs() <= q, "{e} vs {}", sign * range);
            }
            assert_eq!(a.torque_si(), sign * 60.0);
            assert_eq!(b.torque_si(), sign * 60.0);
            assert_eq!(c.torque_si(), sign * 60.0);
        }
        // The largest torsion the model can produce is not flagged.
        let cfg = TorqueEstimatorConfig::<f64>::new(&p);
        let edge = (p.drive().flexspline().max_torsion() / TAU * (M as f64 * 100.0)) as u32;
        let e = cfg.update(&mut cfg.state(0, 0), 0, edge, 0.0);
        assert!(!e.invalid_input && e.torsion > 0.0, "{e:?}");
    }
}
