//! One joint, wired once: raw encoder readings → joint-torque estimate
//! (ch. 3, eq. 3.8–3.10) → sign conventions → mode manager (ch. 4: active
//! eq. 4.19, passive eq. 4.32, hold, collision reaction) in one
//! [`JointConfig::update`] per servo tick.
//!
//! The component has the crate's shape: [`JointParams`] (SI, validated by
//! [`JointParams::try_new`] from named [`JointSettings`], or a preset:
//! [`JointParams::table_4_1_at`] for the 4 ms servo tick, or the thesis's
//! own [`JointParams::table_4_1`], which does not hold at 4 ms) → [`JointConfig<S>`] (quantized once
//! for backend `S`) → [`JointState<S>`] (estimator, mode manager and speed
//! meter state) → `update(&self, &mut state, &readings, &target)` →
//! [`JointOutput<S>`]. The step never panics, never allocates and never
//! returns NaN: an impossible reading is replaced and flagged
//! ([`JointOutput::invalid_input`]).
//!
//! # Sign conventions, handled here once
//! Users speak the chapter-4 convention throughout: the motor angle
//! `q_m = N q_l` at zero torsion, the motor torque `τ_m` positive driving
//! the link forward, and the joint torque `τ_t` the torque the drive
//! applies to the link (eq. 4.1). The estimator of ch. 3 counts the motor
//! angle `θ_wi` the other way (eq. 2.4, errata E2.10) and returns the
//! torque with the sign of the torsion. So the step
//! * passes the **motor counter negated** to the estimator
//!   ([`TorqueEstimatorConfig::update`]), and starts the estimator state
//!   at the negated position;
//! * gives the estimator the motor torque `τ_w = τ_m` (the same sign in
//!   both conventions): the reading's [`JointReadings::motor_torque`] or,
//!   when it is `None`, the previous command;
//! * feeds the mode manager `τ̂_t = −torque` ([`JointOutput::joint_torque`]).
//!
//! A positive reading of [`JointReadings::motor_counter`] therefore moves
//! the link forward, as a positive [`JointOutput::motor_torque`] drives it.
//!
//! # Motor position and speed from the counts
//! The joint keeps the motor position as a 64-bit count (chapter-4 sign),
//! advanced by the wrapping 32-bit difference of the free-running counter
//! (valid while the motor turns fewer than 2³¹ counts per tick), and the
//! speed as the count difference over a window of `w` ticks,
//! `q̇_m = (c_k − c_{k−w})·2π/(M w T)` (resolution `2π/(M w T)`, lag half
//! the window), both converted once per tick by [`Scalar::from_counts`].
//! [`JointConfig::state`] starts the motor where the estimator reads no
//! torsion: `N` times the link angle in `[−π, π)`, moved by the
//! kinematic error `N·e_k` when a model of it is configured (a motor
//! count started elsewhere is a torque offset on every later estimate).
//!
//! # Multi-turn positions and targets
//! No absolute angle is stored in the backend's number, so a joint turning
//! in one direction keeps its control for any number of turns on every
//! backend (`tests/multi_turn.rs`: 10⁴ output revolutions in closed loop
//! on `I16F16`, `f32` and `f64`, tracking as at the first). A target is
//! whole output revolutions plus the rest, link angle
//! `2π·`[`turns`](JointTarget::turns)` + `[`position`](JointTarget::position)
//! ([`JointTarget::from_si`] splits an SI angle so, the rest in
//! `[−π, π]`), and the step forms the motor position in that target's
//! frame from the 64-bit count, in counts, before it becomes the
//! backend's number:
//!
//! `q_m − 2πN·turns = (c − turns·M·N)·2π/M`, compared with `N·position`
//! (eq. 4.15).
//!
//! The law's error `e = q_m − N q_d` (eq. 4.19) is then a difference of two
//! numbers of the size of one output revolution at the motor (`2πN` rad),
//! exact to the count on every backend. So
//! [`JointOutput::motor_position`] (and the mode manager's
//! `reference_position`) are **in the target's frame**:
//! `q_m − 2πN·turns`, rad at the motor; the absolute position is
//! [`JointState::motor_position_counts`] (64-bit counts,
//! `q_m = counts·2π/M`). When the target's `turns` change, nothing
//! stored moves: the mode manager's hold point keeps the whole turns of
//! the frame it was stored in and is read in the target's frame, moved
//! by the whole output revolutions between the two, `2πN` each (on fixed
//! point by at most the revolutions its angle holds, `⌊32 768/(2πN)⌋` =
//! 52 at `N = 100` on `I16F16`, beyond which the hold point is out of
//! range anyway), so that back in its own frame it is the stored point
//! again; the rejoin offset is a difference and needs no move. A target
//! frame is taken on a usable sample (below).
//!
//! The frame has a range: `|q_m − 2πN·turns|` at most
//! [`JointConfig::frame_limit_counts`] counts — half the stored angle
//! range on fixed point, at most `2³¹ − 1` counts (`I16F16`: 16 384 rad at
//! the motor, 26 output revolutions at `N = 100`), and on floats the counts whose angle still
//! resolves half a count (`f32`: 2²² counts, 13 176 rad at `M = 2000`,
//! 21 output revolutions; `f64`: 2⁵¹ counts). A target whose whole turns
//! leave the motor farther than that (a target given without its turns,
//! as `turns: 0` and a large `position`) is **flagged** `invalid_input`
//! and not used (below), never read as a saturated or rounded error
//! (its reported `motor_position` is still in the target's frame; on
//! `f32` a count beyond `±(2³¹ − 1)` from the frame's origin is reported
//! at that bound).
//! `JointTarget::position` itself is a stored angle: keep it within a
//! revolution (on `I16F16`, `N·position` saturates beyond `±32 768/N` rad).
//!
//! # Plausibility of readings
//! A motor cannot turn faster than [`JointSettings::max_motor_speed`]
//! (from its data sheet; [`TABLE_4_1_MAX_MOTOR_SPEED`] in the presets). A
//! counter that moved more than `⌊max_motor_speed·T·M/(2π)⌋ + 1` counts in
//! one tick (one count of quantization above the speed) is a counter fault
//! — a glitch, a lost or doubled reading, a jump of whole revolutions that
//! the torsion cannot see because it is a multiple of `M·N` counts. Then:
//!
//! * the sample is flagged `invalid_input` (and
//!   [`JointMeasurement::counter_jump`] from [`JointConfig::measure`]);
//! * the joint **holds its last valid state**: the move is left out of the
//!   motor position, the speed meter and the estimator see no motion for
//!   this tick, and the mode manager is not advanced (command 0 N·m, the
//!   last command recorded as 0, as for any invalid sample);
//! * **recovery**: the next tick is measured from the jumped counter, so a
//!   counter that jumped and stays (an offset) costs one flagged tick and
//!   the offset never enters the position; a one-tick spike costs two (out
//!   and back). The position then continues from where it was held
//!   (`tests/plausibility.rs`).
//!
//! The same holding path takes every sample the step cannot use: an
//! impossible torsion or a link count not below `L` (the estimator's
//! flags), and a target outside the frame (above).
//!
//! # Units
//! [`JointTarget`] is link-side: rad, rad/s, rad/s² and N·m — the stored
//! units of every backend (`S::UNITS` scales angles, speeds and link
//! torques by 1; [`JointTarget::from_si`] applies the scales anyway). The
//! step multiplies the trajectory by `N` for the motor-side law (eq. 4.15).
//! [`JointOutput::motor_torque`] is in stored motor-torque units (N·m on
//! floats, mN·m on `I16F16`); the `_si` readers give SI on every backend.
//!
//! # Status flags
//! The flags mean the same on every output of the crate's control steps —
//! the laws ([`ActiveOutput`](crate::control::ActiveOutput),
//! [`PassiveOutput`](crate::control::PassiveOutput)), the mode manager
//! ([`ModeOutput`]), the joint ([`JointOutput`]) and the wrist
//! ([`WristOutput`](crate::wrist::WristOutput)):
//!
//! * **`invalid_input`** — this sample could not be used: an input was NaN
//!   or infinite or an impossible reading (a link count not below `L`, a
//!   torsion no torque can produce, a counter faster than the motor's
//!   maximum speed — [plausibility](self#plausibility-of-readings)), on
//!   the joint a target outside the frame of its whole turns
//!   ([multi-turn](self#multi-turn-positions-and-targets)), or, on floats,
//!   finite inputs so large that the law
//!   overflowed to NaN. The command is the documented fallback (0 N·m from
//!   a law; in the mode manager 0 for a non-finite input, the decaying
//!   bump-transfer bias for an overflow) and the adapted state is not
//!   advanced. The cause is always the sample: the adapted state cannot
//!   hold a NaN or leave its box (its fields are private and
//!   [`RobustAdaptiveConfig::state`](crate::control::RobustAdaptiveConfig::state)
//!   validates), so an invalid flag clears as soon as the inputs are valid.
//! * **`saturated` of one law or of the mode manager** (`ActiveOutput`,
//!   `PassiveOutput`, `ModeOutput`, hence [`JointOutput::control`]) — the
//!   command is not the law's value: it was limited to `±L` (the law or,
//!   after a switch, the law plus the bias), **or** it is the fallback of
//!   an invalid sample. So `invalid_input` implies `saturated` there.
//! * **`torque_saturated`** — a valid law value was limited to `±L`:
//!   `saturated && !invalid_input` of the law. The wrist reports it per
//!   step ([`WristOutput::torque_saturated`](crate::wrist::WristOutput::torque_saturated),
//!   either motor), the joint through [`JointOutput::torque_saturated`]. An
//!   invalid sample never sets it.
//! * **the wrist's `saturated`** — `reference_saturated ||
//!   torque_saturated`: something valid was limited, never an invalid
//!   sample alone.
//!
//! So a NaN target on the joint gives `motor_torque` 0 with
//! `invalid_input`, `control.saturated` and `control.invalid_input` set,
//! and `torque_saturated()` false — as on the wrist, whose
//! `torque_saturated` stays false and whose `laws[i].saturated` is set.
//! (The per-law `saturated` keeps the fallback in its meaning rather than
//! being narrowed to the limit alone, so that the joint step's code is
//! unchanged.)
//!
//! # Example
//! The Table 4.1 joint at rest, then a motor counter that ran ahead of the
//! link by 10 counts (a torsion): the estimate follows eq. (3.9)–(3.10),
//! computed here independently in `f64`.
//!
//! ```
//! use mrr_control::joint::{JointConfig, JointParams, JointReadings, JointTarget};
//! let p = JointParams::table_4_1()?;
//! let cfg = JointConfig::<f64>::new(&p);
//! // The motor at count 0 (`state(0, 0)` would start it where the
//! // kinematic error puts an unloaded motor).
//! let mut st = cfg.state_at(0, 0);
//! let hold = JointTarget::from_si(0.0, 0.0, 0.0);
//! // Motor 10 counts forward of a link at 0, no motor torque applied.
//! let readings = JointReadings { link_count: 0, motor_counter: 10, motor_torque: Some(0.0) };
//! let out = cfg.update(&mut st, &readings, &hold);
//! // Torsion Δθ = θ_fo + θ_wi/N with θ_wi = −10·2π/2000 (the estimator's
//! // sign); minus the kinematic error of Table 3.2 at (0, θ_wi); then
//! // τ_f = tan(c_f K_f0 Δθ_f)/c_f (eq. 3.10) and τ̂_t = −τ_f.
//! let drive = mrr_control::harmonic_drive::CatalogueData::SHD_17_100.identify()?;
//! let ke = mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel::table_3_2();
//! let theta_wi = -10.0 * std::f64::consts::TAU / 2000.0;
//! let dtheta_f = theta_wi / 100.0 - ke.evaluate(0.0, theta_wi);
//! let f = drive.flexspline();
//! let tau_t = -(f.c_f() * f.k_f0() * dtheta_f).tan() / f.c_f();
//! assert!(tau_t > 0.0); // the motor ahead pushes the link forward
//! assert!((out.joint_torque - tau_t).abs() < 1e-3 * tau_t.abs());
//! assert!((out.motor_position - 10.0 * std::f64::consts::TAU / 2000.0).abs() < 1e-12);
//! assert!(!out.invalid_input);
//! # Ok::<(), mrr_control::ParamError>(())
//! ```

use crate::control::design::{
    design_for_period, table_4_1_known_stribeck_shape, DesignError, SampledJoint,
};
use crate::control::{
    ControlInput, JointMode, ModeConfig, ModeOutput, ModeParams, ModeSettings, ModeState,
    PassiveParams, RobustAdaptiveState,
};
use crate::error::ParamError;
use crate::estimation::torque::{
    TorqueEstimate, TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings,
    TorqueEstimatorState,
};
use crate::harmonic_drive::identification::CatalogueData;
use crate::harmonic_drive::kinematic_error::KinematicErrorModel;
use crate::scalar::target::mul_wide_signed;
use crate::scalar::units::{dequantize, quantize_keep_non_finite};
use crate::scalar::{CountCoef, IntFactor, Scalar};
use core::f64::consts::TAU;

/// Longest speed window, ticks.
pub const MAX_SPEED_WINDOW: u8 = 64;

/// The plausibility limit of the presets' motor speed, rad/s
/// ([`JointSettings::max_motor_speed`] of [`JointParams::table_4_1`] and
/// [`JointParams::table_4_1_at`]): 1000 rad/s (about 9,550 rpm).
///
/// Source: the thesis gives no speed rating for its motor (a Maxon
/// 218014 brushed DC motor, ch. 2.5 and 3.4; only its weight, torque
/// limit and torque constant are printed). The fastest motion it reports
/// on this joint is 1.56 rad/s at the link (Table 3.3), 156 rad/s at the
/// motor through `N = 100`, and the 4 ms design assumes motor speeds up
/// to 100 rad/s ([`JointParams::table_4_1_at`]). The limit is a
/// plausibility bound about 6.4 times the fastest reported speed, not a
/// rating: set [`JointSettings::max_motor_speed`] from your motor's data
/// sheet (its maximum permissible speed). At 4 ms and 2000 counts per
/// revolution it admits up to 1274 counts per tick; one motor revolution
/// (2000 counts) or a whole output revolution (200 000) in one tick is
/// rejected.
pub const TABLE_4_1_MAX_MOTOR_SPEED: f64 = 1000.0;
const _: () = assert!(MAX_SPEED_WINDOW.is_power_of_two());

/// The settings of a joint by name, for [`JointParams::try_new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointSettings {
    /// The joint-torque estimator (drive model, kinematic error, encoder
    /// resolutions `L` and `M`, torque limit).
    pub estimator: TorqueEstimatorParams,
    /// The mode manager (active and passive laws, switching, collision);
    /// its gear ratio must be the drive's, and its sample period is the
    /// joint's tick `T`.
    pub mode: ModeParams,
    /// Window of the motor speed's count difference, ticks, in
    /// `[1, MAX_SPEED_WINDOW]`.
    pub speed_window: u8,
    /// The fastest the motor can turn, rad/s (> 0; from the motor's data
    /// sheet, e.g. its maximum permissible speed): a reading whose counter
    /// moved farther in one tick is a counter fault, flagged and not used
    /// ([plausibility of readings](self#plausibility-of-readings)).
    pub max_motor_speed: f64,
}

/// Parameters of one joint, SI; built only by [`try_new`](Self::try_new).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointParams {
    settings: JointSettings,
}

impl JointParams {
    /// Validate: the mode manager's gear ratio (its active law's `N`) equals
    /// the drive's (`ParamError::OutOfRange` naming `mode.active.ratio`,
    /// with the drive's ratio as both bounds); `speed_window` in
    /// `[1, MAX_SPEED_WINDOW]`; the motor speed resolution
    /// `2π/(M·w·T)` at most 32 768 rad/s (named
    /// `2π/(estimator.motor_counts_per_rev·speed_window·mode.active.sample_period)`);
    /// `max_motor_speed` finite and > 0, and the counts it moves in one
    /// tick, `max_motor_speed·T·M/(2π)`, at most 2³⁰ (named
    /// `max_motor_speed·mode.active.sample_period·estimator.motor_counts_per_rev/2π`;
    /// the wrapping 32-bit counter difference must resolve them); and the
    /// motor counts per output revolution `M·N` at most 2³² (named
    /// `estimator.motor_counts_per_rev·estimator.drive.ratio`; whole output
    /// turns of a target, [`JointTarget::turns`], are then exact 64-bit
    /// counts). The estimator and mode parameters were validated by their
    /// own `try_new`.
    pub fn try_new(settings: JointSettings) -> Result<Self, ParamError> {
        let n = settings.estimator.drive().ratio();
        let mode_ratio = settings.mode.settings().active.design().ratio;
        if mode_ratio != n {
            return Err(ParamError::OutOfRange {
                name: "mode.active.ratio",
                value: mode_ratio,
                min: n,
                max: n,
            });
        }
        if settings.speed_window == 0 || settings.speed_window > MAX_SPEED_WINDOW {
            return Err(ParamError::OutOfRange {
                name: "speed_window",
                value: settings.speed_window as f64,
                min: 1.0,
                max: MAX_SPEED_WINDOW as f64,
            });
        }
        crate::error::positive("max_motor_speed", settings.max_motor_speed)?;
        let p = JointParams { settings };
        crate::error::combination(
            "2π/(estimator.motor_counts_per_rev·speed_window·mode.active.sample_period)",
            p.speed_resolution(),
            0.0,
            32_768.0,
        )?;
        crate::error::combination(
            "max_motor_speed·mode.active.sample_period·estimator.motor_counts_per_rev/2π",
            settings.max_motor_speed * p.sample_period() / p.motor_rad_per_count(),
            0.0,
            (1u64 << 30) as f64,
        )?;
        crate::error::combination(
            "estimator.motor_counts_per_rev·estimator.drive.ratio",
            settings.estimator.motor_counts_per_rev() as f64 * p.ratio(),
            1.0,
            (1u64 << 32) as f64,
        )?;
        Ok(p)
    }

    /// The Table 4.1 joint: the SHD-17-100 identified from its catalogue
    /// sheet ([`CatalogueData::SHD_17_100`], eq. 2.30), the Table 3.2
    /// kinematic error, a 17-bit link encoder (`L = 2¹⁷`), a 2000-count
    /// motor encoder, ±60 N·m estimate limit; the Table 4.1 active law
    /// (`T = 4 ms`) and passive law with the default gain
    /// ([`PassiveParams::table_4_1_default`]) under the manager settings of
    /// [`ModeSettings::table_4_1`] (no collision detector); speed over one
    /// tick (resolution `2π/(2000·4 ms) = 0.785` rad/s); readings implying
    /// a motor faster than [`TABLE_4_1_MAX_MOTOR_SPEED`] rejected.
    ///
    /// # Does not hold at its own 4 ms
    /// These are the thesis's numbers, kept for reproducing ch. 4, and the
    /// law they give **cannot be run at the 4 ms it is stamped with**:
    /// inside its `ε_r = 0.1 rad/s` layer the robust term is a speed
    /// feedback of slope `K_r/ε_r = 1.70 N·m·s/rad`, and sampled every
    /// `T` it is stable only for `T (K_r/ε_r + I_m λ)/I_m < 2`, i.e.
    /// `T < 13.4 µs`; at 4 ms the factor is 597 (errata E4.4), the
    /// speed meter's one-count resolution (0.785 rad/s) is already 8 times
    /// the layer, and the sampled closed loop on the SHD-17-100's spring
    /// has a pole radius of about 2·10⁷
    /// ([`crate::control::design::sampled_pole_radius`]). On a two-inertia
    /// joint with the catalogue spring the first count of motion puts
    /// `r` outside the layer, each tick then changes the motor speed by
    /// `K_r T/I_m ≈ 60 rad/s`, the torsion estimate swings by ±20 N·m,
    /// and the mode manager leaves Active at the 6th tick (its 5-tick
    /// dwell) on every backend (`tests/preset_4ms.rs`,
    /// `table_4_1_leaves_active_within_ticks_at_4ms`). Use
    /// [`table_4_1_at`](Self::table_4_1_at) for a joint run at a servo
    /// tick; this preset holds only at periods of order 10 µs and below
    /// (the examples run it at 0.1 ms with its own caveats).
    pub fn table_4_1() -> Result<Self, ParamError> {
        let estimator = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive: CatalogueData::SHD_17_100.identify()?,
            kinematic_error: Some(KinematicErrorModel::table_3_2()),
            link_counts_per_rev: 1 << 17,
            motor_counts_per_rev: 2000,
            max_torque: 60.0,
        })?;
        let mode = ModeParams::try_new(ModeSettings {
            passive: PassiveParams::table_4_1_default()?,
            ..ModeSettings::table_4_1(1.0)?
        })?;
        Self::try_new(JointSettings {
            estimator,
            mode,
            speed_window: 1,
            max_motor_speed: TABLE_4_1_MAX_MOTOR_SPEED,
        })
    }

    /// The Table 4.1 joint re-designed for the controller period
    /// `sample_period` (s): the same drive, encoders, estimator, passive
    /// law and mode manager as [`table_4_1`](Self::table_4_1), with the
    /// active law of [`design_for_period`] on
    /// [`table_4_1_known_stribeck_shape`] (Table 4.1's uncertainty bounds,
    /// friction box and limits, the Stribeck shape known) for
    ///
    /// * the SHD-17-100 spring between its catalogue slopes
    ///   `K1 = 8.4e3` and `K2 = 9.4e3 N·m/rad` ([`CatalogueData::SHD_17_100`]);
    /// * rotor inertia `1.14e-5 kg·m²` (Table 4.1), **assumed** link
    ///   inertia `0.03–0.1 kg·m²` (the thesis gives none for this joint;
    ///   the sampled torque feedback makes the design depend on it, so
    ///   re-run [`design_for_period`] for another link);
    /// * the 2000-count motor encoder, motor speeds up to 100 rad/s
    ///   (1 rad/s at the link), pole radius at most 0.9.
    ///
    /// At 4 ms (`table_4_1_at(0.004)`) the design has `λ = 56.8 1/s`,
    /// `ε_r = 525 rad/s`, `ε_q̇ = 66.4 rad/s`,
    /// `ε_F = [3e4, 525, 525, 0.1]`, `K_I = 0` (no integral gain on its
    /// half-decade ladder keeps the pole radius, the integral's slow pole
    /// being the limit), sampled pole radius 0.899, and Theorem 1's bound
    /// `r_S = 317 rad/s`, `|e| ≤ r_S/λ = 5.58 rad` at the motor
    /// (0.0558 rad at the link) — a loose bound: `K_r = 0.170 N·m` of
    /// assumed disturbance acts on a 1.14e-5 kg·m² rotor through gains
    /// the 4 ms tick limits. The returned parameters carry the design in
    /// [`ModeParams::settings`]`().active`, so
    /// `UltimateBound::new(p.settings().mode.settings().active.design())`
    /// recomputes the bound.
    ///
    /// Other periods: the rule asks for a pole radius of 0.9 *per tick*,
    /// and the link's oscillation against the spring, which the law's
    /// joint-torque feedback `τ̂_t/N` leaves to the link's own friction in
    /// continuous time, gets its damping here only from the sampling. The
    /// smallest radius on the design grid is 0.981 at 1 ms, 0.917 at 2 ms,
    /// 0.9986 at 8 ms and 1.020 at 10 ms, so those periods return
    /// [`DesignError::NoSampledDesign`] (test
    /// `table_4_1_at_other_periods_is_a_typed_error`); the preset is made
    /// and checked for the thesis's 4 ms.
    ///
    /// Errors: a period outside `[1e-6, 0.1]` s
    /// ([`DesignError::Param`] naming `sample_period`), or one at which no
    /// design meets the criterion ([`DesignError::NoSampledDesign`]).
    pub fn table_4_1_at(sample_period: f64) -> Result<Self, DesignError> {
        let sheet = CatalogueData::SHD_17_100;
        let base = table_4_1_known_stribeck_shape();
        let joint = SampledJoint {
            sample_period,
            ratio: sheet.ratio,
            stiffness: [sheet.k1, sheet.k2],
            rotor_inertia: base.rotor_inertia,
            link_inertia: [0.03, 0.1],
            motor_counts_per_rev: 2000,
            max_motor_speed: 100.0,
            max_pole_radius: 0.9,
        };
        let design = design_for_period(&base, &joint)?;
        let table = Self::table_4_1()?;
        let mode = ModeParams::try_new(ModeSettings {
            active: design.params,
            ..table.settings.mode.settings()
        })?;
        Ok(Self::try_new(JointSettings {
            mode,
            ..table.settings
        })?)
    }

    /// The settings, by name.
    pub fn settings(&self) -> JointSettings {
        self.settings
    }

    /// The tick `T`, s (the active law's sample period).
    pub fn sample_period(&self) -> f64 {
        self.settings.mode.settings().active.design().sample_period
    }

    /// The gear ratio `N`.
    pub fn ratio(&self) -> f64 {
        self.settings.estimator.drive().ratio()
    }

    /// Motor angle per count `2π/M`, rad.
    pub fn motor_rad_per_count(&self) -> f64 {
        TAU / self.settings.estimator.motor_counts_per_rev() as f64
    }

    /// The motor speed's resolution `2π/(M w T)`, rad/s.
    pub fn speed_resolution(&self) -> f64 {
        self.motor_rad_per_count() / (self.settings.speed_window as f64 * self.sample_period())
    }
}

/// The joint quantized for backend `S`.
///
/// `repr(C)`: the estimator, then the mode manager, whose most read values
/// come first ([`ModeConfig`]), so that they lie within a single-precision
/// load's reach of the configuration's base on the Cortex-M4F.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct JointConfig<S> {
    estimator: TorqueEstimatorConfig<S>,
    mode: ModeConfig<S>,
    /// `N` (a validated integer), link → motor side.
    ratio: IntFactor,
    /// `2π/M` in stored angle units per count.
    angle_per_count: CountCoef,
    /// `2π/(M w T)` in stored speed units per count (the count difference
    /// over the window fits `i32`: the 32-bit count product).
    speed_per_count: CountCoef,
    speed_window: u8,
    link_counts: u32,
    /// `M·N`, motor counts per output revolution.
    motor_counts_per_output_rev: i64,
    /// The most counts the counter may move in one tick:
    /// `⌊max_motor_speed·T·M/(2π)⌋ + 1` (one count of quantization).
    max_counts_per_tick: u32,
    /// The largest `|q_m − 2πN·turns|` in counts that the backend's angle
    /// carries ([`JointConfig::frame_limit_counts`]).
    frame_limit: u64,
    /// `2·frame_limit`: the frame test is one unsigned compare,
    /// `in_frame + frame_limit ≤ frame_span`.
    frame_span: u64,
}

/// The joint's state: the estimator's, the mode manager's, and the motor
/// position and speed meter's.
///
/// `repr(C)`, the joint's own per-tick values first and the 64-word speed
/// history last, so that they lie within a short load's reach of the
/// state's base (124 bytes for a word load on Armv6-M).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct JointState<S: Scalar> {
    /// Motor position, counts, chapter-4 sign.
    motor_count: i64,
    /// Last raw counter (chapter-4 sign).
    last_counter: u32,
    head: u8,
    estimator: TorqueEstimatorState,
    mode: ModeState<S>,
    /// The low 32 bits of the motor position of the last `w` ticks
    /// (a counter without its rejected jumps), oldest at `head`.
    history: [u32; MAX_SPEED_WINDOW as usize],
}

impl<S: Scalar> JointState<S> {
    /// The current mode.
    pub fn mode(&self) -> JointMode {
        self.mode.mode()
    }
    /// The mode manager's state (adapted friction, bias, collision latch).
    pub fn mode_state(&self) -> &ModeState<S> {
        &self.mode
    }
    /// The estimator's state (in the estimator's sign).
    pub fn estimator_state(&self) -> &TorqueEstimatorState {
        &self.estimator
    }
    /// The motor position in counts since the state was made, offset by the
    /// start position, chapter-4 sign (`q_m = counts · 2π/M`); a rejected
    /// counter jump is not in it. The absolute position on every backend,
    /// whatever the range of its stored angle: `q_m` in rad is
    /// `counts · 2π/M` (in `f64`, exact below 2⁵³ counts).
    pub fn motor_position_counts(&self) -> i64 {
        self.motor_count
    }

    /// The active law's adapted state (friction estimate and integral;
    /// SI readers [`RobustAdaptiveState::friction_si`] and
    /// [`RobustAdaptiveState::integral_si`]).
    pub fn active_state(&self) -> &RobustAdaptiveState<S> {
        self.mode.active_state()
    }
    /// The last motor torque command, stored motor-torque units.
    pub fn last_command(&self) -> S {
        self.mode.last_torque()
    }
    /// The last motor torque command `τ_m` in N·m, positive driving the
    /// link forward.
    pub fn last_command_si(&self) -> f64 {
        self.mode.last_torque_si()
    }
    /// This state with the mode manager's state replaced by `mode` (one
    /// reached by running the same [`ModeConfig`], e.g. to resume a joint
    /// or to start a test in a given mode); the estimator, the motor
    /// position and the target frame are kept (a hold point in `mode`
    /// keeps its own frame's whole turns and moves to the joint's when it
    /// is read).
    pub fn with_mode_state(mut self, mut mode: ModeState<S>) -> Self {
        mode.set_frame(self.mode.frame());
        self.mode = mode;
        self
    }
}

/// The raw readings of one tick, as the firmware gets them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointReadings<S> {
    /// Link-side absolute encoder count, `[0, L)`, increasing with the link
    /// angle (a larger value is reduced modulo `L` and flagged).
    pub link_count: u32,
    /// Free-running motor counter (wrapping), chapter-4 sign: increasing
    /// as the motor drives the link forward.
    pub motor_counter: u32,
    /// Motor torque `τ_m` being applied (e.g. from the measured current),
    /// stored motor-torque units, positive driving the link forward; `None`
    /// takes the previous command (the wave-generator torque `τ_w` of
    /// eq. 3.9 approximated by the command).
    pub motor_torque: Option<S>,
}

impl<S> JointReadings<S> {
    /// Readings with the motor torque taken as the previous command.
    pub fn counts(link_count: u32, motor_counter: u32) -> Self {
        JointReadings {
            link_count,
            motor_counter,
            motor_torque: None,
        }
    }
}

/// What the joint should do on this tick, link side.
///
/// The desired link angle is `2π·turns + position`: whole output
/// revolutions as an integer and the rest as a number, so that a joint
/// turning in one direction keeps its resolution and its range on every
/// backend ([multi-turn](self#multi-turn-positions-and-targets));
/// [`from_si`](Self::from_si) splits an SI angle so.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointTarget<S> {
    /// Whole output (link) revolutions of the desired link angle, positive
    /// forward: the desired link angle is `2π·turns + position`.
    pub turns: i32,
    /// Desired link angle `q_d` beyond the whole [`turns`](Self::turns),
    /// stored angle units (rad); any value the backend holds, best within
    /// `±π` ([`from_si`](Self::from_si) puts it in `[−π, π]`).
    pub position: S,
    /// Desired link speed `q̇_d`, stored speed units (rad/s).
    pub velocity: S,
    /// Desired link acceleration `q̈_d`, stored speed units per second
    /// (rad/s²).
    pub acceleration: S,
    /// Desired joint torque `τ_td` of the passive law (eq. 4.32; 0 for a
    /// free joint), stored link-torque units (N·m), eq. (4.1) sign.
    pub joint_torque: S,
    /// Joint torque expected without interaction (gravity, payload),
    /// stored link-torque units (N·m), eq. (4.1) sign: the interaction
    /// torque and the collision residual are `τ̂_t` minus this.
    pub expected_joint_torque: S,
}

impl<S: Scalar> JointTarget<S> {
    /// A trajectory point from SI values (rad, rad/s, rad/s²), no desired
    /// or expected joint torque. The link angle is split into whole
    /// revolutions and the rest, `position = 2π·turns + r` with `turns`
    /// the nearest integer to `position/2π` and `r ∈ [−π, π]` (an angle
    /// beyond `±2³¹` revolutions keeps `turns = 0`). A NaN or infinity
    /// stays one on floats (the step then flags it); fixed point saturates
    /// it (see [`quantize_keep_non_finite`]).
    pub fn from_si(position: f64, velocity: f64, acceleration: f64) -> Self {
        let u = S::UNITS;
        let (turns, position) = split_turns(position);
        JointTarget {
            turns,
            position: quantize_keep_non_finite(position, u.angle),
            velocity: quantize_keep_non_finite(velocity, u.speed),
            acceleration: quantize_keep_non_finite(acceleration, u.speed),
            joint_torque: S::ZERO,
            expected_joint_torque: S::ZERO,
        }
    }
}

/// `angle = 2π·turns + rest` with `turns` the nearest integer to
/// `angle/2π` (halves away from zero) and `rest ∈ [−π, π]`; an angle that
/// is not a number or beyond `±2³¹` revolutions gives `(0, angle)`.
fn split_turns(angle: f64) -> (i32, f64) {
    let t = angle / TAU;
    // `as` saturates and takes NaN to 0; the range test keeps the split
    // exact in `i32`.
    if t.abs() < 2_147_483_647.0 {
        let k = (t + if t < 0.0 { -0.5 } else { 0.5 }) as i32;
        (k, angle - k as f64 * TAU)
    } else {
        (0, angle)
    }
}

/// What [`JointConfig::measure`] read from one tick's readings (the inputs
/// the mode manager gets), chapter-4 signs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointMeasurement<S> {
    /// The estimated joint torque `τ̂_t` (eq. 4.1 sign: the torque the drive
    /// applies to the link), stored link-torque units; `−estimate.torque`.
    pub joint_torque: S,
    /// The measured motor position `q_m` (from the state's 64-bit count,
    /// [`JointState::motor_position_counts`]), stored angle units: it
    /// saturates on `I16F16` beyond ±32 768 rad and rounds on floats
    /// (on `f32` to coarser than half a count beyond 2²² counts).
    pub motor_position: S,
    /// The measured motor speed `q̇_m` (count difference over the window),
    /// stored speed units.
    pub motor_velocity: S,
    /// The estimator's output, in the estimator's sign (errata E2.10); its
    /// `invalid_input` and `link_count_invalid` flag impossible readings.
    pub estimate: TorqueEstimate<S>,
    /// The motor counter moved farther than
    /// [`JointSettings::max_motor_speed`] allows in one tick: the reading
    /// was rejected (the position, the speed meter and the estimator's
    /// motor position hold; [plausibility](self#plausibility-of-readings)).
    pub counter_jump: bool,
}

impl<S: Scalar> JointMeasurement<S> {
    /// [`joint_torque`](Self::joint_torque) in N·m.
    pub fn joint_torque_si(&self) -> f64 {
        dequantize(self.joint_torque, S::UNITS.link_torque)
    }
    /// [`motor_position`](Self::motor_position) in rad.
    pub fn motor_position_si(&self) -> f64 {
        dequantize(self.motor_position, S::UNITS.angle)
    }
    /// [`motor_velocity`](Self::motor_velocity) in rad/s.
    pub fn motor_velocity_si(&self) -> f64 {
        dequantize(self.motor_velocity, S::UNITS.speed)
    }
}

/// One tick of the joint.
///
/// Every field is finite on every backend.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointOutput<S> {
    /// The motor torque command `τ_m`, stored motor-torque units, positive
    /// driving the link forward, within the torque limit.
    pub motor_torque: S,
    /// The mode that produced it.
    pub mode: JointMode,
    /// The estimated joint torque `τ̂_t` (eq. 4.1 sign: the torque the drive
    /// applies to the link), stored link-torque units; `−estimate.torque`.
    pub joint_torque: S,
    /// The measured motor position in the target's frame,
    /// `q_m − 2πN·turns` (chapter-4 sign; `turns` the target's
    /// [`JointTarget::turns`]), stored angle units
    /// ([multi-turn](self#multi-turn-positions-and-targets); the absolute
    /// position is [`JointState::motor_position_counts`]).
    pub motor_position: S,
    /// The measured motor speed `q̇_m` (count difference over the window),
    /// stored speed units.
    pub motor_velocity: S,
    /// An input was impossible, at either stage (the meaning is shared with
    /// the wrist: [status flags](self#status-flags)): a link count not below
    /// `L`, a torsion no torque can produce, a NaN or infinite motor torque
    /// (estimator), a counter faster than the motor's maximum speed
    /// ([plausibility](self#plausibility-of-readings)), a target outside
    /// its turns' frame ([multi-turn](self#multi-turn-positions-and-targets)),
    /// a NaN or infinite target, or a law that overflowed (mode manager).
    /// The command is then 0 N·m from the mode manager's invalid-sample
    /// path (an overflow: the decaying bias) and the state holds.
    pub invalid_input: bool,
    /// The estimator's output, in the estimator's sign (errata E2.10).
    pub estimate: TorqueEstimate<S>,
    /// The mode manager's output (switch, saturation, collision, reference);
    /// its `saturated` is also set on an invalid sample
    /// ([status flags](self#status-flags); the limit alone is
    /// [`torque_saturated`](Self::torque_saturated)).
    pub control: ModeOutput<S>,
}

impl<S: Scalar> JointOutput<S> {
    /// A valid law value was limited to the torque limit:
    /// `control.saturated && !control.invalid_input` (the meaning of the
    /// wrist's [`torque_saturated`](crate::wrist::WristOutput::torque_saturated);
    /// see [the flags](self#status-flags)). `false` on an invalid sample.
    pub fn torque_saturated(&self) -> bool {
        self.control.saturated && !self.control.invalid_input
    }
    /// [`motor_torque`](Self::motor_torque) in N·m.
    pub fn motor_torque_si(&self) -> f64 {
        dequantize(self.motor_torque, S::UNITS.motor_torque)
    }
    /// [`joint_torque`](Self::joint_torque) in N·m.
    pub fn joint_torque_si(&self) -> f64 {
        dequantize(self.joint_torque, S::UNITS.link_torque)
    }
    /// [`motor_position`](Self::motor_position) in rad, in the target's
    /// frame (`q_m − 2πN·turns`).
    pub fn motor_position_si(&self) -> f64 {
        dequantize(self.motor_position, S::UNITS.angle)
    }
    /// [`motor_velocity`](Self::motor_velocity) in rad/s.
    pub fn motor_velocity_si(&self) -> f64 {
        dequantize(self.motor_velocity, S::UNITS.speed)
    }
}

impl<S: Scalar> JointConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &JointParams) -> Self {
        let u = S::UNITS;
        let s = &p.settings;
        let m = s.estimator.motor_counts_per_rev();
        let motor_counts_per_output_rev = m as i64 * p.ratio() as i64;
        let angle_per_count = CountCoef::new(p.motor_rad_per_count() * u.angle);
        let frame_limit = Self::frame_limit_counts(p.motor_rad_per_count());
        // One output revolution at the motor, `2πN` rad, from its `M·N`
        // counts: the hold point's step between turn frames.
        let output_rev = S::from_counts_prepared(motor_counts_per_output_rev, &angle_per_count);
        JointConfig {
            estimator: TorqueEstimatorConfig::new(&s.estimator),
            mode: ModeConfig::new(&s.mode).with_output_revolution(output_rev),
            ratio: IntFactor::new(p.ratio()),
            angle_per_count,
            speed_per_count: CountCoef::new(p.speed_resolution() * u.speed),
            speed_window: s.speed_window,
            link_counts: s.estimator.link_counts_per_rev(),
            motor_counts_per_output_rev,
            // Validated: at most 2³⁰ + 1.
            max_counts_per_tick: (s.max_motor_speed * p.sample_period() / p.motor_rad_per_count())
                as u32
                + 1,
            frame_limit,
            frame_span: 2 * frame_limit,
        }
    }

    /// The largest motor-side distance from the target's whole turns,
    /// `|q_m − 2πN·turns|` in counts, that the step accepts on backend `S`
    /// for a motor of `rad_per_count` (`2π/M`) rad per count: on fixed
    /// point the counts whose angle is within half the backend's range
    /// (`I16F16`: 16 384 rad, so that the error to a target within `±π`
    /// at the link cannot saturate), and at most `2³¹ − 1` counts (the
    /// fixed-point count product takes 32-bit counts; the cap binds above
    /// about 823 000 counts per motor revolution on `I16F16`); on floats
    /// the counts whose angle the
    /// backend still resolves to half a count, `1/(2ε)` (`f32`: 2²²
    /// counts, 13 176 rad at `M = 2000`; `f64`: 2⁵¹).
    pub fn frame_limit_counts(rad_per_count: f64) -> u64 {
        if S::FLOAT {
            (0.5 / S::RESOLUTION.to_f64()) as u64
        } else {
            ((S::MAX.to_f64() / S::UNITS.angle / 2.0 / rad_per_count) as u64).min(i32::MAX as u64)
        }
    }

    /// The estimator's configuration.
    pub fn estimator(&self) -> &TorqueEstimatorConfig<S> {
        &self.estimator
    }

    /// The mode manager's configuration.
    pub fn mode(&self) -> &ModeConfig<S> {
        &self.mode
    }

    /// A state for a joint at rest and unloaded whose encoders read
    /// `link_count` and `motor_counter` (chapter-4 sign): the motor
    /// position is taken where the estimator reads no torsion. Without a
    /// kinematic-error model that is `N` times the link angle in `[−π, π)`,
    /// in counts `⌊c·M·N/L⌋` with `c` the link count in `[−L/2, L/2)`.
    /// With one, the unloaded motor stands `N·e_k` away from `Nθ_l`
    /// (eq. 3.7): the count is moved from `⌊c·M·N/L⌋` until the
    /// estimator's flexspline torsion (eq. 3.9: the torsion less the
    /// kinematic error, at zero motor torque) is zero to within half a
    /// motor count (a few chord steps on the count, each one
    /// [`measure`](Self::measure) of a scratch state; the error's slope
    /// in the motor angle is far below the drive ratio's, so the steps
    /// converge at once). The first estimates then read no torque that is
    /// not there; without the move they read `K·|e_k(θ_l)|` (Table 3.2
    /// with a 2¹⁶-count motor encoder: up to 8.2e-5 rad of flexspline
    /// torsion over the 64 link angles of its unit test; more than
    /// 0.5 N·m on some drives of the `sim::plants` joint family).
    ///
    /// Where the motor's absolute position is known, start from it with
    /// [`state_at`](Self::state_at).
    pub fn state(&self, link_count: u32, motor_counter: u32) -> JointState<S> {
        let l = self.link_counts as i64;
        let mut c = link_count as i64 % l;
        if c >= l - l / 2 {
            c -= l;
        }
        let motor = (c * self.motor_counts_per_output_rev).div_euclid(l);
        if !self.estimator.has_kinematic_error() {
            return self.state_at(motor, motor_counter);
        }
        let link_count = (link_count as i64 % l) as u32;
        let torsion = |m: i64| -> Option<f64> {
            let mut st = self.state_at(m, motor_counter);
            let readings = JointReadings {
                link_count,
                motor_counter,
                motor_torque: Some(S::ZERO),
            };
            let e = self.measure(&mut st, &readings).estimate;
            (!e.invalid_input).then(|| e.flexspline_torsion_si())
        };
        // The chord's slope from a step of one output milliradian.
        let h = ((self.motor_counts_per_output_rev as f64 * 1e-3 / core::f64::consts::TAU) as i64)
            .max(1);
        let (Some(t0), Some(t1)) = (torsion(motor), torsion(motor + h)) else {
            return self.state_at(motor, motor_counter);
        };
        let slope = (t1 - t0) / h as f64;
        if !slope.is_finite() || slope == 0.0 {
            return self.state_at(motor, motor_counter);
        }
        let (mut m, mut t) = (motor, t0);
        for _ in 0..4 {
            let step = libm::round(t / slope);
            if step == 0.0 || step.abs() > h as f64 {
                break;
            }
            let next = m - step as i64;
            match torsion(next) {
                Some(tn) if tn.abs() <= t.abs() => (m, t) = (next, tn),
                _ => break,
            }
        }
        self.state_at(m, motor_counter)
    }

    /// A state for a motor at `motor_position` counts (chapter-4 sign,
    /// `q_m = counts · 2π/M`) while its counter reads `motor_counter`.
    ///
    /// The estimator and the speed meter are given the joint's own count
    /// (the counter without its rejected jumps), so the estimator state's
    /// [`last_counter`](TorqueEstimatorState::last_counter) is the low 32
    /// bits of the negated motor position, not the raw counter.
    pub fn state_at(&self, motor_position: i64, motor_counter: u32) -> JointState<S> {
        let own = motor_position as u32;
        JointState {
            estimator: self
                .estimator
                .state(motor_position.wrapping_neg(), own.wrapping_neg()),
            mode: self.mode.initial_state(),
            motor_count: motor_position,
            last_counter: motor_counter,
            history: [own; MAX_SPEED_WINDOW as usize],
            head: 0,
        }
    }

    /// Clear a latched collision reaction (the operator acknowledged it).
    pub fn acknowledge_collision(&self, st: &mut JointState<S>) {
        self.mode.acknowledge_collision(&mut st.mode);
    }

    /// The measuring half of [`update`](Self::update): estimate the joint
    /// torque from the readings (eq. 3.8–3.10, motor counter negated,
    /// `τ̂_t = −estimate`) and measure the motor position and speed,
    /// advancing the estimator and the speed meter, not the mode manager.
    /// For a loop that runs its own law on the measured joint (a
    /// simulator comparing feedback variants, a test bench); call it once
    /// per tick instead of `update`, never both.
    // Inlined into its caller: the joint step is then one function,
    // without call and argument-struct overhead, also in a firmware that
    // builds several joint configurations.
    ///
    /// A counter that moved farther than
    /// [`JointSettings::max_motor_speed`] allows is rejected
    /// ([`JointMeasurement::counter_jump`]; module docs).
    #[inline(always)]
    pub fn measure(
        &self,
        st: &mut JointState<S>,
        readings: &JointReadings<S>,
    ) -> JointMeasurement<S> {
        let (estimate, motor_count, moved, counter_jump) = self.measure_counts(st, readings);
        JointMeasurement {
            joint_torque: estimate.torque.neg(),
            motor_position: S::from_counts_prepared(motor_count, &self.angle_per_count),
            motor_velocity: S::from_counts_i32(moved, &self.speed_per_count),
            estimate,
            counter_jump,
        }
    }

    /// The counting half of [`measure`](Self::measure): the plausibility
    /// test of the counter, the motor position (64-bit count), the
    /// estimate and the speed meter's count difference over the window.
    /// Returns `(estimate, motor count, counts moved over the window,
    /// counter jump)`.
    #[inline(always)]
    fn measure_counts(
        &self,
        st: &mut JointState<S>,
        readings: &JointReadings<S>,
    ) -> (TorqueEstimate<S>, i64, i32, bool) {
        let counter = readings.motor_counter;
        // Position: wrapping 32-bit difference, exact 64-bit sum; a move
        // faster than the motor can turn is a counter fault, not motion:
        // it is left out, and the next tick is measured from this reading.
        let raw = counter.wrapping_sub(st.last_counter) as i32;
        st.last_counter = counter;
        // |raw| > max as one unsigned compare (2·max ≤ 2³¹ + 2, validated).
        let max = self.max_counts_per_tick;
        let counter_jump = (raw as u32).wrapping_add(max) > max << 1;
        let delta = if counter_jump { 0 } else { raw };
        let motor_count = st.motor_count.wrapping_add(delta as i64);
        st.motor_count = motor_count;
        // The joint's own counter: the position's low 32 bits, which the
        // estimator and the speed meter follow (a rejected jump is in
        // neither).
        let own = motor_count as u32;
        // The previous command is finite (the mode manager limits it): the
        // estimator then does not test it.
        let (motor_torque, torque_finite) = match readings.motor_torque {
            Some(t) => (t, false),
            None => (st.mode.last_torque(), true),
        };
        let estimate = self.estimator.update_with(
            &mut st.estimator,
            readings.link_count,
            own.wrapping_neg(),
            motor_torque,
            torque_finite,
        );
        // Speed: difference to the count `w` ticks ago (`w` is validated
        // in [1, MAX_SPEED_WINDOW]; the ring index is taken modulo its
        // power-of-two length anyway, one mask and no bounds test, so no
        // reading can index past it).
        let w = self.speed_window;
        let head = if st.head < w { st.head } else { 0 };
        let slot = &mut st.history[head as usize % MAX_SPEED_WINDOW as usize];
        let old = core::mem::replace(slot, own);
        st.head = if head + 1 >= w { 0 } else { head + 1 };
        let moved = own.wrapping_sub(old) as i32;
        (estimate, motor_count, moved, counter_jump)
    }

    /// One tick: [`measure`](Self::measure) (estimate the joint torque from
    /// the readings, eq. 3.8–3.10, motor counter negated; measure the motor
    /// position and speed), then run the mode manager on
    /// `τ̂_t = −estimate` and the target times `N` (module docs).
    #[inline]
    pub fn update(
        &self,
        st: &mut JointState<S>,
        readings: &JointReadings<S>,
        target: &JointTarget<S>,
    ) -> JointOutput<S> {
        self.step(st, readings, target)
    }

    /// [`update`](Self::update)'s body.
    #[inline(always)]
    fn step(
        &self,
        st: &mut JointState<S>,
        readings: &JointReadings<S>,
        target: &JointTarget<S>,
    ) -> JointOutput<S> {
        let (estimate, motor_count, moved, counter_jump) = self.measure_counts(st, readings);
        // The motor position in the target's turn frame, formed in counts:
        // `q_m − 2πN·turns`, from the frame's origin `turns·M·N` (exact
        // modulo 2⁶⁴, so `in_frame` is exact whenever it is within the
        // frame's limit). Formed on every tick, without a sign test: the
        // bound counts the product on any path that has it, and a stored
        // origin costs its test, load and store besides.
        let turns = target.turns;
        let origin = mul_wide_signed(turns, self.motor_counts_per_output_rev);
        let in_frame = motor_count.wrapping_sub(origin);
        // |in_frame| ≤ frame_limit as one unsigned compare; where the limit
        // is below 2³¹ (a constant of the backend), of the limit's and the
        // span's low words.
        let frame_ok = if Self::frame_fits_i32() {
            in_frame.wrapping_add(self.frame_limit as u32 as i64) as u64
                <= self.frame_span as u32 as u64
        } else {
            in_frame.wrapping_add(self.frame_limit as i64) as u64 <= self.frame_span
        };
        let joint_torque = estimate.torque.neg();
        let motor_velocity = S::from_counts_i32(moved, &self.speed_per_count);
        // An unusable sample (a rejected counter jump, a target too far
        // from the motor for the backend, an impossible torsion or link
        // count): the command is the fallback and the state holds, the
        // frame included (a new target frame is taken on the next usable
        // sample; the hold point is not read before).
        if counter_jump || !frame_ok || estimate.invalid_input || estimate.link_count_invalid {
            let motor_position = self.position_beyond_frame(in_frame);
            let control = self.mode.reject(&mut st.mode, motor_position);
            return JointOutput {
                motor_torque: control.torque,
                mode: control.mode,
                joint_torque,
                motor_position,
                motor_velocity,
                invalid_input: true,
                estimate,
                control,
            };
        }
        // The mode manager's inputs are in the target's frame (stored on
        // every usable sample, unchanged but on a new frame: no branch);
        // its hold point is read in that frame (`ModeState::set_frame`).
        st.mode.set_frame(turns);
        // In the frame (`|in_frame| ≤ frame_limit`): on fixed point and
        // `f32` the limit is below 2³¹, so the count is one 32-bit
        // conversion.
        let motor_position = if Self::frame_fits_i32() {
            S::from_counts_i32(in_frame as i32, &self.angle_per_count)
        } else {
            S::from_counts_prepared(in_frame, &self.angle_per_count)
        };
        let x = ControlInput {
            desired_position: target.position.mul_int(&self.ratio),
            desired_velocity: target.velocity.mul_int(&self.ratio),
            desired_acceleration: target.acceleration.mul_int(&self.ratio),
            motor_position,
            motor_velocity,
            joint_torque,
            desired_joint_torque: target.joint_torque,
            expected_joint_torque: target.expected_joint_torque,
        };
        // The measured fields are finite (count products, the estimate):
        // only the other five are tested. The estimate's flags are clear
        // here.
        let control = self.mode.update_measured(&mut st.mode, &x);
        JointOutput {
            motor_torque: control.torque,
            mode: control.mode,
            joint_torque,
            motor_position,
            motor_velocity,
            invalid_input: control.invalid_input,
            estimate,
            control,
        }
    }

    /// The reported motor position of an unusable sample, `in_frame`
    /// counts from the target's frame (possibly beyond its limit): on
    /// `f32` the count clamped to `±(2³¹ − 1)` and converted from 32 bits,
    /// elsewhere [`Scalar::from_counts_prepared`] (`I16F16` saturates).
    #[inline(always)]
    fn position_beyond_frame(&self, in_frame: i64) -> S {
        if S::FLOAT && Self::frame_fits_i32() {
            let c = in_frame.max(i32::MIN as i64).min(i32::MAX as i64) as i32;
            S::from_counts_i32(c, &self.angle_per_count)
        } else {
            S::from_counts_prepared(in_frame, &self.angle_per_count)
        }
    }
}

impl<S: Scalar> JointConfig<S> {
    /// Whether every frame limit of backend `S`
    /// ([`frame_limit_counts`](Self::frame_limit_counts)) is below 2³¹
    /// counts: on fixed point always (the limit is capped there), on
    /// floats when `1/(2ε)` is (`f32`, not `f64`). A constant of the
    /// backend.
    #[inline(always)]
    fn frame_fits_i32() -> bool {
        !S::FLOAT || 0.5 / S::RESOLUTION.to_f64() <= i32::MAX as f64
    }
}

#[cfg(any(kani, test))]
mod prepared;
#[cfg(any(kani, test))]
pub(crate) use prepared::TABLE_4_1_I16F16;

#[cfg(test)]
mod tests;
