//! Automatic multiple-mode control: active (eq. 4.19) ↔ passive (eq. 4.32)
//! on the interaction torque, with hysteresis, debounce and dwell time;
//! bumpless transfer; and the reaction to a detected collision
//! ([`crate::estimation::collision`]). The thesis switches modes by hand
//! (§4.4); this manager is an extension.
//!
//! # Modes
//! * [`JointMode::Active`] — the robust adaptive law tracking the desired
//!   trajectory plus a *rejoin offset* `o` (see below).
//! * [`JointMode::Hold`] — the same law holding the position latched at a
//!   collision (reaction [`CollisionReaction::Stop`]).
//! * [`JointMode::Passive`] — eq. (4.32) with the adapted friction
//!   estimates.
//!
//! # Switching rules
//! With the interaction torque `τ_i = τ̂_t − τ_expected` (link side):
//! * Active → Passive when `|τ_i| > enter` for `debounce` consecutive
//!   samples;
//! * Passive → Active when `|τ_i| < exit` (`exit < enter`: hysteresis)
//!   **and** the motor is at rest, `|q̇_m| ≤ v_rest`, for `n_release ≥
//!   debounce` consecutive samples (the [`ReleaseRule`]);
//!
//! each only once the current mode lasted at least `dwell` samples. A
//! collision onset switches at once to its reaction's mode and latches it
//! until [`ModeConfig::acknowledge_collision`]; after that, Hold returns to
//! Active (debounced) and Passive follows the rules above. An onset in
//! Passive latches too: the joint stays Passive from that sample on (the
//! release rule waits for the acknowledgement), and no onset sample ever
//! switches into Active.
//!
//! *Why the release rule.* Under eq. (4.32)–(4.33) the passive joint is a
//! free body of apparent inertia `K_p⁻¹` driven by the interaction torque:
//! a hand that guides it needs only the small torque that accelerates that
//! inertia, so a small `|τ_i|` does not tell a released joint from a
//! guided one. The torque-only rule then returns to Active in the middle of
//! the guidance; Active starts rejoining the desired trajectory, the hand
//! resists, `|τ_i|` exceeds `enter`, and the joint cycles. In the simulated
//! guidance scenario (`sim::closed_loop::interaction_scenario`, exit 2 N·m)
//! the torque-only rule gives 38 switches between 0.88 s and 3.01 s
//! (36 with the simulator's former speed meter, which extrapolated its
//! first window). What a guided joint does and a released one does not
//! is *move*: requiring `|q̇_m| ≤ v_rest` blocks the return while the hand
//! leads, and holding that for longer than the hand's pauses blocks it
//! while the hand holds still (the same scenario with the rule of
//! `ModeScenarioConfig::interaction`: 2 switches; test
//! `hand_guidance_does_not_cycle_the_modes`). `v_rest` must exceed the
//! speed jitter of the released passive joint (the estimator's error acts
//! on the small apparent inertia: up to 5.1 rad/s motor side in that
//! scenario; see [`super::passive`] for the loop's characteristics) and
//! stay below the guiding speeds; `exit` must exceed the estimator's error
//! (Assumption 5), or the hold is interrupted and the joint stays Passive.
//! [`ModeParams::try_new`] installs the torque-only rule
//! ([`ReleaseRule::torque_only`]) so that existing configurations keep
//! their behaviour; [`ModeParams::with_release`] sets another.
//!
//! # Bumpless transfer, and the bound on the torque jump
//! `τ_before` is the previous command (what the motor is being driven
//! with). At a switching sample the incoming mode is seeded:
//! * entering Active: the rejoin offset is set to `o = q_m − q_m^d`,
//!   `ȯ = q̇_m − q̇_m^d`, so the reference starts at the measured position
//!   and speed (`e = ė = 0`, so `r = 0`); afterwards `o` decays to 0 as a
//!   critically damped second-order system of bandwidth `ω` and the joint
//!   rejoins the desired trajectory smoothly;
//! * entering Hold: the reference is the measured position, at rest;
//! * entering Active or Hold: the integral is re-seeded to
//!   `z = clamp(R₀ − τ_before, ±z_max)` (`R₀` the law with `z = 0`; the law
//!   is affine in `z` with slope −1, so it becomes `R = R₀ − z`), so that
//!   the law itself starts near `τ_before`;
//! * in every case a bias `b = τ_before − clamp(R, ±L)` (`R` the incoming
//!   law) is added to the limited law, and decays by `e^{−T/T_b}`-like
//!   factor `1 − T/T_b` per sample.
//!
//! The output after the switch is `τ_after = clamp(clamp(R, ±L) + b, ±L)`.
//! In exact arithmetic `τ_after = τ_before`. **Bound:** with
//! `|τ_before| ≤ L` and `|clamp(R, ±L)| ≤ L`,
//! * `I16F16`: every operand and sum stays below `2L ≤ 32 000 mN·m`
//!   (`L ≤ 16 N·m` is validated), so the fixed-point additions are exact
//!   and `τ_after = τ_before` **exactly**;
//! * floats with unit roundoff `u` (`RESOLUTION/2`): `b` carries an error
//!   `≤ u|τ_before − clamp(R)| ≤ 2uL`, the sum another `≤ u(|τ_before| +
//!   2uL)`, and the clamp is 1-Lipschitz with `τ_before` inside it, so
//!   `|τ_after − τ_before| ≤ 3uL + 2u²L ≤ 2·RESOLUTION·L`.
//!
//! [`ModeConfig::switch_jump_bound`] returns this bound; the property test
//! `switching_is_bumpless` checks it over random states.
//!
//! # Fixed-point resolution of the manager's slow states
//! The adapted friction estimates carry a sub-LSB residual
//! ([`crate::scalar::Scalar::integrate`]); the manager's own states do not,
//! and on `I16F16` they stop where their increments round to zero:
//! * the rejoin offset when `|ȯ T|` and `|acc T|` are both below ½ LSB, so
//!   `|o| < (1 + 2ω) 2⁻¹⁷/(ω² T)` rad (motor side): 4.0e-4 rad at
//!   `ω = 10 rad/s`, 5.7e-3 rad at `ω = 1 rad/s` with `T = 4 ms` (below
//!   one count of the thesis's 0.01° link encoder at the link for `N =
//!   100`; the bound grows as `1/ω²`, so choose `ω` accordingly). Test
//!   `rejoin_offset_stall_is_within_its_bound`.
//! * the bias when `|b| T/T_b < ½ LSB`, i.e. `|b| < T_b/(2T)` LSB of motor
//!   torque: 12.5 LSB = 1.9e-7 N·m for `T_b = 0.1 s` at 4 ms, a
//!   millionth of the 0.188 N·m limit.
//!
//! The measured position is never overwritten: the manager's position
//! state (offset or hold point) is defined relative to the measured
//! position at the switch, so the reference is continuous with the joint.
//!
//! # Example
//! A push of 2.5 N·m on a joint held at rest (above the 2 N·m entry
//! threshold of [`ModeSettings::table_4_1`]): the switch to Passive waits
//! for the dwell (5 samples) and the debounce (3), so it happens on the
//! 6th sample, and the motor torque moves by no more than
//! [`ModeConfig::switch_jump_bound`] at the switch.
//!
//! ```
//! use mrr_control::control::{ControlInput, JointMode, ModeConfig, ModeParams, ModeSettings};
//! let params = ModeParams::try_new(ModeSettings::table_4_1(2000.0)?)?;
//! let mc = ModeConfig::<f64>::new(&params);
//! let mut st = mc.initial_state();
//! let push = ControlInput { joint_torque: 2.5, ..Default::default() };
//! let mut switched_at = None;
//! for sample in 1..=10 {
//!     let before = st.last_torque();
//!     let o = mc.update(&mut st, &push);
//!     if o.switched {
//!         switched_at = Some(sample);
//!         assert_eq!(o.mode, JointMode::Passive);
//!         assert!((o.torque - before).abs() <= mc.switch_jump_bound());
//!     }
//! }
//! assert_eq!(switched_at, Some(5 + 1)); // dwell + 1
//! # Ok::<(), mrr_control::ParamError>(())
//! ```

use super::adaptive::{
    ActiveTerms, RobustAdaptiveConfig, RobustAdaptiveParams, RobustAdaptiveState,
};
use super::passive::{PassiveConfig, PassiveParams};
use super::ControlInput;
use crate::error::{positive, ParamError};
use crate::estimation::collision::{
    CollisionConfig, CollisionParams, CollisionReaction, CollisionState,
};
use crate::scalar::{Coef, CoefRow, Scalar};

/// The operating mode of a joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointMode {
    /// Robust adaptive position control, eq. (4.19).
    Active,
    /// Position hold after a collision (eq. 4.19 with a frozen reference).
    Hold,
    /// Friction compensation with torque feedback, eq. (4.32).
    Passive,
}

/// Parameters of the mode manager, SI; built only by
/// [`try_new`](Self::try_new) from named [`ModeSettings`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeParams {
    active: RobustAdaptiveParams,
    passive: PassiveParams,
    enter_passive: f64,
    exit_passive: f64,
    debounce: u16,
    dwell: u16,
    rejoin_bandwidth: f64,
    bias_time_constant: f64,
    collision: Option<CollisionParams>,
    /// The Passive → Active release rule ([`ModeParams::with_release`]).
    release: ReleaseRule,
}

/// The Passive → Active release rule: besides `|τ_i| < exit`, the motor
/// speed must be at rest, `|q̇_m| ≤ speed`, and both must hold for
/// `samples` consecutive samples (at least the manager's `debounce`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReleaseRule {
    /// Motor-side rest speed, rad/s (`> 0`).
    pub speed: f64,
    /// Consecutive samples the release condition must hold (`≥ debounce`).
    pub samples: u16,
}

/// The settings of the mode manager by name, for [`ModeParams::try_new`]:
/// a struct literal names every value, so two of the same type (`debounce`
/// and `dwell`, or `rejoin_bandwidth` and `bias_time_constant`) cannot be
/// swapped silently.
///
/// ```
/// use mrr_control::control::{ModeParams, ModeSettings};
/// let settings = ModeSettings {
///     debounce: 4,
///     dwell: 50,
///     ..ModeSettings::table_4_1(2000.0)?
/// };
/// let params = ModeParams::try_new(settings)?;
/// assert_eq!((params.settings().debounce, params.settings().dwell), (4, 50));
/// # Ok::<(), mrr_control::ParamError>(())
/// ```
///
/// The positional form, where `debounce` and `dwell` could trade places,
/// no longer compiles:
///
/// ```compile_fail
/// use mrr_control::control::{ModeParams, PassiveParams, RobustAdaptiveParams};
/// let a = RobustAdaptiveParams::table_4_1().unwrap();
/// let p = PassiveParams::table_4_1(2000.0).unwrap();
/// let _ = ModeParams::try_new(a, p, 2.0, 1.0, 5, 3, 10.0, 0.1, None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeSettings {
    /// The robust adaptive law of the Active and Hold modes, eq. (4.19).
    pub active: RobustAdaptiveParams,
    /// The passive law, eq. (4.32); its torque limit must equal the active
    /// one.
    pub passive: PassiveParams,
    /// Interaction torque `|τ_i|` above which Active → Passive, N·m (link
    /// side), `≤ 30 000`.
    pub enter_passive: f64,
    /// Interaction torque `|τ_i|` below which Passive → Active, N·m,
    /// `0 < exit_passive < enter_passive`.
    pub exit_passive: f64,
    /// Consecutive samples a switching condition must hold, `≥ 1`.
    pub debounce: u16,
    /// Samples a mode lasts at least before the torque rules may leave it.
    pub dwell: u16,
    /// Bandwidth `ω` of the rejoin offset's decay, rad/s (`0 < ω T ≤ 0.5`,
    /// `ω ≤ 1e5`).
    pub rejoin_bandwidth: f64,
    /// Time constant `T_b` of the bumpless-transfer bias's decay, s
    /// (`≥ T`).
    pub bias_time_constant: f64,
    /// Collision detection and reaction, or `None`.
    pub collision: Option<CollisionParams>,
}

impl ModeSettings {
    /// The Table 4.1 laws (active, and passive with `passive_gain`,
    /// 1/(kg·m²)) with this crate's example manager settings — the thesis
    /// switches modes by hand and gives none: passive above 2 N·m
    /// interaction and back below 1 N·m, debounce 3 samples, dwell 5
    /// samples, rejoin bandwidth 10 rad/s, bias time constant 0.1 s, no
    /// collision detection. Change fields by name before
    /// [`ModeParams::try_new`].
    pub fn table_4_1(passive_gain: f64) -> Result<Self, ParamError> {
        Ok(ModeSettings {
            active: RobustAdaptiveParams::table_4_1()?,
            passive: PassiveParams::table_4_1(passive_gain)?,
            enter_passive: 2.0,
            exit_passive: 1.0,
            debounce: 3,
            dwell: 5,
            rejoin_bandwidth: 10.0,
            bias_time_constant: 0.1,
            collision: None,
        })
    }
}

impl ModeParams {
    /// Validate: `0 < exit_passive < enter_passive ≤ 30 000` N·m
    /// (interaction torque, link side); `debounce ≥ 1` sample; the passive
    /// torque limit equal to the active one; a rejoin bandwidth `ω > 0`
    /// rad/s with `ω T ≤ 0.5` (`T` the active law's sample period: the
    /// discrete rejoin filter is then stable and not oscillatory) and
    /// `ω ≤ 1e5` (so `ω²` is an exact coefficient); a bias
    /// time constant `T_b ≥ T` s.
    pub fn try_new(settings: ModeSettings) -> Result<Self, ParamError> {
        let ModeSettings {
            active,
            passive,
            enter_passive,
            exit_passive,
            debounce,
            dwell,
            rejoin_bandwidth,
            bias_time_constant,
            collision,
        } = settings;
        positive("exit_passive", exit_passive)?;
        positive("enter_passive", enter_passive)?;
        crate::error::increasing(
            ("exit_passive", exit_passive),
            ("enter_passive", enter_passive),
        )?;
        if enter_passive > 30_000.0 {
            return Err(ParamError::OutOfRange {
                name: "enter_passive",
                value: enter_passive,
                min: 0.0,
                max: 30_000.0,
            });
        }
        if debounce == 0 {
            return Err(ParamError::NotPositive {
                name: "debounce",
                value: 0.0,
            });
        }
        let d = active.design();
        let t = d.sample_period;
        let pl = passive_limit(&passive);
        if pl != d.torque_limit {
            return Err(ParamError::OutOfRange {
                name: "passive.torque_limit",
                value: pl,
                min: d.torque_limit,
                max: d.torque_limit,
            });
        }
        positive("rejoin_bandwidth", rejoin_bandwidth)?;
        let max_w = f64::min(0.5 / t, 1e5);
        if rejoin_bandwidth > max_w {
            return Err(ParamError::OutOfRange {
                name: "rejoin_bandwidth",
                value: rejoin_bandwidth,
                min: 0.0,
                max: max_w,
            });
        }
        positive("bias_time_constant", bias_time_constant)?;
        if bias_time_constant < t {
            return Err(ParamError::OutOfRange {
                name: "bias_time_constant",
                value: bias_time_constant,
                min: t,
                max: f64::INFINITY,
            });
        }
        let release = ReleaseRule::torque_only(debounce);
        Ok(ModeParams {
            active,
            passive,
            enter_passive,
            exit_passive,
            debounce,
            dwell,
            rejoin_bandwidth,
            bias_time_constant,
            collision,
            release,
        })
    }

    /// The settings this was validated from.
    pub fn settings(&self) -> ModeSettings {
        ModeSettings {
            active: self.active,
            passive: self.passive,
            enter_passive: self.enter_passive,
            exit_passive: self.exit_passive,
            debounce: self.debounce,
            dwell: self.dwell,
            rejoin_bandwidth: self.rejoin_bandwidth,
            bias_time_constant: self.bias_time_constant,
            collision: self.collision,
        }
    }

    /// Replace the Passive → Active release rule (module docs,
    /// "Switching rules"). Validate: `speed > 0` rad/s (motor side, at
    /// most `30 000` so that it is representable on every backend) and
    /// `samples ≥ debounce`.
    pub fn with_release(mut self, rule: ReleaseRule) -> Result<Self, ParamError> {
        let v = positive("rule.speed", rule.speed)?;
        if v > 30_000.0 {
            return Err(ParamError::OutOfRange {
                name: "rule.speed",
                value: v,
                min: 0.0,
                max: 30_000.0,
            });
        }
        if rule.samples < self.debounce {
            return Err(ParamError::OutOfRange {
                name: "rule.samples",
                value: rule.samples as f64,
                min: self.debounce as f64,
                max: u16::MAX as f64,
            });
        }
        self.release = rule;
        Ok(self)
    }

    /// The Passive → Active release rule in force.
    pub fn release(&self) -> ReleaseRule {
        self.release
    }
}

impl ReleaseRule {
    /// The rule [`ModeParams::try_new`] installs: the torque-only rule
    /// (no speed condition — the largest admissible rest speed, 30 000
    /// rad/s — and the manager's `debounce`). It keeps the behaviour of
    /// a manager built without a release rule; a joint that may be guided
    /// by hand needs [`ModeParams::with_release`] (module docs).
    pub fn torque_only(debounce: u16) -> Self {
        ReleaseRule {
            speed: 30_000.0,
            samples: debounce,
        }
    }
}

fn passive_limit(p: &PassiveParams) -> f64 {
    // PassiveConfig<f64> stores the limit in SI.
    PassiveConfig::<f64>::new(p).torque_limit()
}

/// The manager quantized for backend `S`.
///
/// `repr(C)`, the values the step reads most first: its own thresholds,
/// the rejoin filter's gains and integration coefficients, the bias decay
/// and the collision detector, then the two laws (a load instruction
/// reaches a bounded distance past its base register: 1020 bytes for a
/// single-precision load on the Cortex-M4F, so these are read without
/// forming their addresses).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct ModeConfig<S> {
    enter_passive: S,
    exit_passive: S,
    /// Passive → Active: motor rest speed (stored speed) and the samples
    /// the release condition must hold.
    release_speed: S,
    limit: S,
    /// `[2ω, ω²]`: the offset's `2ω ȯ + ω² o` from `(ȯ, o)` (speed →
    /// speed/s, angle → speed/s), one exactly summed row on `I16F16`.
    offset_row: CoefRow<2>,
    active: RobustAdaptiveConfig<S>,
    /// `T`, speed/s → speed.
    step_rate: Coef,
    /// `T`, speed → angle.
    step_position: Coef,
    /// `1 − T/T_b`.
    bias_decay: Coef,
    passive: PassiveConfig<S>,
    collision: Option<CollisionConfig<S>>,
    release_samples: u16,
    debounce: u16,
    dwell: u16,
    /// One output revolution at the motor, `2πN` rad, stored angle units,
    /// and the most whole revolutions whose angle the backend holds
    /// (`⌊MAX/output_rev⌋`): the step and the limit of the hold point's
    /// move between turn frames ([`ModeConfig::with_output_revolution`];
    /// 0 and 0 until the joint sets them).
    output_rev: S,
    max_shift_turns: i32,
}

/// The manager's state.
///
/// `repr(C)`, the byte and half-word fields first: on Armv6-M a byte load
/// reaches 31 bytes past its base register and a half-word load 62, so
/// that the mode, the latch and the sample counters are read without
/// forming their addresses.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct ModeState<S: Scalar> {
    mode: JointMode,
    latched: bool,
    in_mode: u16,
    run: u16,
    collision: CollisionState,
    active: RobustAdaptiveState<S>,
    offset: S,
    offset_rate: S,
    hold: S,
    bias: S,
    last_torque: S,
    /// The whole output turns of the frame the inputs' positions are in
    /// (set by the joint, [`ModeState::set_frame`]; 0 for a manager run on
    /// its own) and of the frame the hold point was stored in.
    frame_turns: i32,
    hold_turns: i32,
}

impl<S: Scalar> ModeState<S> {
    /// The current mode.
    pub fn mode(&self) -> JointMode {
        self.mode
    }
    /// The active law's adapted state (read it in SI with
    /// [`RobustAdaptiveState::friction_si`] and
    /// [`RobustAdaptiveState::integral_si`]). The passive law of this
    /// manager uses the same friction estimate.
    pub fn active_state(&self) -> &RobustAdaptiveState<S> {
        &self.active
    }
    /// The bumpless-transfer bias, stored motor torque (see
    /// [`bias_si`](Self::bias_si)).
    pub fn bias(&self) -> S {
        self.bias
    }
    /// The bumpless-transfer bias in N·m, motor side: the amount added to
    /// the new mode's law after a switch so that the command does not
    /// jump, with the sign of a motor torque (positive driving the link
    /// forward); it decays to 0.
    pub fn bias_si(&self) -> f64 {
        self.bias.to_f64() / S::UNITS.motor_torque
    }
    /// The inputs' positions are from now on in the frame of `turns` whole
    /// output revolutions (`q_m − 2πN·turns`; the joint's target frame): a
    /// stored hold point is read in it, moved by whole revolutions from
    /// the frame it was stored in. The other stored positions are
    /// differences (the rejoin offset) and need no move.
    #[inline(always)]
    pub(crate) fn set_frame(&mut self, turns: i32) {
        self.frame_turns = turns;
    }
    /// The frame of the inputs' positions ([`set_frame`](Self::set_frame)).
    #[inline(always)]
    pub(crate) fn frame(&self) -> i32 {
        self.frame_turns
    }
    /// `true` while a collision reaction is latched.
    pub fn collision_latched(&self) -> bool {
        self.latched
    }
    /// The last motor torque command (the `τ_before` of a switch), stored
    /// motor torque.
    pub fn last_torque(&self) -> S {
        self.last_torque
    }
    /// [`last_torque`](Self::last_torque) in N·m, motor side, positive
    /// driving the link forward.
    pub fn last_torque_si(&self) -> f64 {
        self.last_torque.to_f64() / S::UNITS.motor_torque
    }
    /// The rejoin offset `(o, ȯ)` of the Active reference, stored angle and
    /// speed units.
    pub fn rejoin_offset(&self) -> (S, S) {
        (self.offset, self.offset_rate)
    }
    /// [`rejoin_offset`](Self::rejoin_offset) in SI: `o` in rad and `ȯ` in
    /// rad/s, motor side, added to the desired motor position and speed of
    /// the Active law (the reference the law tracks is `q_m^d + o`).
    pub fn rejoin_offset_si(&self) -> (f64, f64) {
        let u = S::UNITS;
        (
            self.offset.to_f64() / u.angle,
            self.offset_rate.to_f64() / u.speed,
        )
    }
}

/// One step of the manager.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeOutput<S> {
    /// Motor torque command, stored motor torque, `|τ| ≤ L`.
    pub torque: S,
    /// The mode that produced it.
    pub mode: JointMode,
    /// The mode changed at this sample.
    pub switched: bool,
    /// The command is not the law's value: the law or the biased sum was
    /// limited, or the sample was invalid (then also `invalid_input`); the
    /// limit alone is `saturated && !invalid_input` ([status
    /// flags](crate::joint#status-flags)).
    pub saturated: bool,
    /// An input was NaN or infinite (torque 0, state unchanged), or the
    /// law overflowed to NaN on absurd finite float inputs (the law counts
    /// as 0; the torque is the decaying bias; the active state is not
    /// advanced).
    pub invalid_input: bool,
    /// `τ̂_t − τ_expected`, stored link torque.
    pub interaction: S,
    /// A collision reaction is latched.
    pub collision: bool,
    /// The position reference used (Active: desired + offset; Hold: the
    /// held position; Passive: the measured position), stored angle. On
    /// invalid input: the measured position, or 0 when it is NaN or
    /// infinite (never NaN).
    pub reference_position: S,
}

impl<S: Scalar> ModeConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &ModeParams) -> Self {
        let u = S::UNITS;
        let t = p.active.design().sample_period;
        let w = p.rejoin_bandwidth;
        let active = RobustAdaptiveConfig::new(&p.active);
        ModeConfig {
            active,
            passive: PassiveConfig::new(&p.passive),
            collision: p.collision.as_ref().map(CollisionConfig::new),
            enter_passive: S::from_f64(p.enter_passive * u.link_torque),
            exit_passive: S::from_f64(p.exit_passive * u.link_torque),
            debounce: p.debounce,
            dwell: p.dwell,
            output_rev: S::ZERO,
            max_shift_turns: 0,
            release_speed: S::from_f64(p.release.speed * u.speed),
            release_samples: p.release.samples,
            offset_row: CoefRow::new([2.0 * w, w * w * u.speed / u.angle]),
            step_rate: Coef::new(t),
            step_position: Coef::new(t * u.angle / u.speed),
            bias_decay: Coef::new(1.0 - t / p.bias_time_constant),
            limit: active.torque_limit(),
        }
    }

    /// The initial state: Active, reference offset 0, the active law's
    /// initial estimates.
    pub fn initial_state(&self) -> ModeState<S> {
        ModeState {
            mode: JointMode::Active,
            active: self.active.initial_state(),
            offset: S::ZERO,
            offset_rate: S::ZERO,
            hold: S::ZERO,
            bias: S::ZERO,
            in_mode: 0,
            run: 0,
            collision: CollisionState::default(),
            latched: false,
            last_torque: S::ZERO,
            frame_turns: 0,
            hold_turns: 0,
        }
    }

    /// The active law's configuration.
    pub fn active(&self) -> &RobustAdaptiveConfig<S> {
        &self.active
    }

    /// The motor torque limit `L`, stored units.
    pub fn torque_limit(&self) -> S {
        self.limit
    }

    /// The bound on `|τ_after − τ_before|` at a switching sample (module
    /// docs): 0 on `I16F16`, `2·RESOLUTION·L` on floats.
    pub fn switch_jump_bound(&self) -> S {
        if S::RESOLUTION.to_f64() >= 1.0 / 65536.0 {
            S::ZERO
        } else {
            S::from_f64(2.0 * S::RESOLUTION.to_f64() * self.limit.to_f64())
        }
    }

    /// Clear a latched collision reaction (the operator acknowledged it).
    pub fn acknowledge_collision(&self, st: &mut ModeState<S>) {
        st.latched = false;
    }

    /// The sample as the active law sees it in the current mode: the
    /// reference replaced by desired + offset (Active) or the hold point.
    /// `seeded` is `2ω ȯ + ω² o` when the caller already has it for the
    /// current offset (the one [`seed`](Self::seed) returns).
    #[inline]
    fn reference(
        &self,
        st: &ModeState<S>,
        x: &ControlInput<S>,
        seeded: Option<S>,
    ) -> (ControlInput<S>, S) {
        let mut xr = *x;
        match st.mode {
            JointMode::Hold => {
                // The hold point in the inputs' frame (moved here, where it
                // is read, and not where the frame changes: the move and
                // the Active reference are then separate paths of the
                // step).
                xr.desired_position = self.hold_in_frame(st);
                xr.desired_velocity = S::ZERO;
                xr.desired_acceleration = S::ZERO;
                (xr, S::ZERO)
            }
            _ => {
                let acc = match seeded {
                    Some(sum) => sum,
                    None => self.offset_sum(st),
                }
                .neg();
                xr.desired_position = x.desired_position.add(st.offset);
                xr.desired_velocity = x.desired_velocity.add(st.offset_rate);
                xr.desired_acceleration = x.desired_acceleration.add(acc);
                (xr, acc)
            }
        }
    }

    /// `v` limited to `±limit` ([`limit_flag`](Self::limit_flag)'s value;
    /// its test checks it against the two-sided clamp).
    #[cfg(test)]
    fn limit(&self, v: S) -> S {
        self.limit_flag(v).0
    }

    /// `v` limited to `±limit`, and whether it was limited: one magnitude
    /// comparison. Equal to `v.clamp(−limit, limit)` for every non-NaN `v`
    /// (the limit is at most 16 N·m, inside every backend's range, so
    /// `|v| > limit` is `v > limit || v < −limit`).
    #[inline(always)]
    fn limit_flag(&self, v: S) -> (S, bool) {
        let l = self.limit;
        if v.abs() > l {
            // `v` is a nonzero number here: on floats `±l` from its sign
            // bit (no second comparison).
            let c = if S::FLOAT {
                l.copysign(v)
            } else if v > S::ZERO {
                l
            } else {
                l.neg()
            };
            (c, true)
        } else {
            (v, false)
        }
    }

    /// The command from the law: the law limited to `±limit` (a NaN law,
    /// an overflow on floats, counts as 0), plus the bias, limited again.
    /// At a switch the bias is first re-seeded so that the command starts
    /// at `before`, the previous one. Returns the torque, whether anything
    /// was limited or overflowed, and whether the law overflowed. One
    /// straight sequence (no common-path attempt with a general fallback,
    /// which the static bound would pay twice).
    #[inline(always)]
    fn command(&self, law: S, before: S, switched: bool, bias: &mut S) -> (S, bool, bool) {
        let overflow = law.is_nan();
        let law = if overflow { S::ZERO } else { law };
        self.command_of_number(law, overflow, before, switched, bias)
    }

    /// [`command`](Self::command) for a law already replaced by 0 where it
    /// overflowed (`overflow`): the active arm of `update` knows it from
    /// the law's own validity test, so the law is not tested twice.
    #[inline(always)]
    fn command_of_number(
        &self,
        law: S,
        overflow: bool,
        before: S,
        switched: bool,
        bias: &mut S,
    ) -> (S, bool, bool) {
        let (limited, cut_law) = self.limit_flag(law);
        if switched {
            *bias = before.sub(limited);
        }
        let (torque, cut_sum) = self.limit_flag(limited.add(*bias));
        (torque, cut_law || cut_sum || overflow, overflow)
    }

    /// What the current mode commands on this sample, without advancing
    /// anything (equal to `update`'s torque when no switch happens).
    pub fn evaluate(&self, st: &ModeState<S>, x: &ControlInput<S>) -> S {
        let law = match st.mode {
            JointMode::Passive => self.passive.law(x, &st.active.friction),
            _ => {
                let (xr, _) = self.reference(st, x, None);
                self.active.law(&st.active, &xr).law
            }
        };
        // The command of `update` without a switch (which leaves the bias
        // alone); a law that overflowed to NaN counts as 0 there too.
        let mut bias = st.bias;
        self.command(law, st.last_torque, false, &mut bias).0
    }

    /// The mode the rules ask for at this sample (before debounce).
    fn wanted(&self, st: &ModeState<S>, interaction: S, speed: S) -> JointMode {
        let mag = interaction.abs();
        match st.mode {
            JointMode::Active => {
                if mag > self.enter_passive {
                    JointMode::Passive
                } else {
                    JointMode::Active
                }
            }
            JointMode::Passive => {
                if !st.latched && mag < self.exit_passive && speed.abs() <= self.release_speed {
                    JointMode::Active
                } else {
                    JointMode::Passive
                }
            }
            JointMode::Hold => {
                if st.latched {
                    JointMode::Hold
                } else {
                    JointMode::Active
                }
            }
        }
    }

    /// On floats, an offset whose next reference acceleration
    /// `−(2ω ȯ + ω² o)` is not a finite number (readings and desired
    /// positions of opposite sign near the float range) is dropped: the
    /// Active reference is then the desired trajectory itself, so the
    /// state never holds an infinity or a NaN. Fixed point saturates
    /// instead (folded at compile time). Returns `2ω ȯ + ω² o` of the
    /// offset kept (`+0` for a dropped one, as `2ω·0 + ω²·0` is with
    /// `ω > 0`) on floats, `None` on fixed point.
    #[inline]
    fn drop_overflowing_offset(&self, st: &mut ModeState<S>) -> Option<S> {
        if !S::FLOAT {
            return None;
        }
        let acc = self.offset_sum(st);
        // `v − v` is 0 exactly when `v` is finite; a finite `acc` proves
        // both terms, and so `o` and `ȯ`, finite.
        if acc.sub(acc) != S::ZERO {
            st.offset = S::ZERO;
            st.offset_rate = S::ZERO;
            Some(S::ZERO)
        } else {
            Some(acc)
        }
    }

    /// `2ω ȯ + ω² o`: the reference acceleration of the offset, negated.
    /// On floats the two products summed in order, on fixed point their
    /// exact sum rounded once.
    #[inline(always)]
    fn offset_sum(&self, st: &ModeState<S>) -> S {
        S::dot_coef(&[st.offset_rate, st.offset], &self.offset_row)
    }

    /// Enter mode `to`: reset the counters and seed the reference
    /// (Active: the rejoin offset; Hold: the hold point) and the integral
    /// (to 0, re-seeded in `update` once the law is known). Returns the
    /// new offset's `2ω ȯ + ω² o` when it has it (entering Active on
    /// floats), for [`reference`](Self::reference).
    fn seed(&self, st: &mut ModeState<S>, to: JointMode, x: &ControlInput<S>) -> Option<S> {
        st.mode = to;
        st.in_mode = 0;
        st.run = 0;
        // (The hold point's frame; outside Hold the hold point is not read
        // before it is stored again.)
        st.hold_turns = st.frame_turns;
        let sum = match to {
            JointMode::Passive => return None,
            JointMode::Active => {
                st.offset = x.motor_position.sub(x.desired_position);
                st.offset_rate = x.motor_velocity.sub(x.desired_velocity);
                self.drop_overflowing_offset(st)
            }
            JointMode::Hold => {
                st.hold = x.motor_position;
                None
            }
        };
        st.active.integral = S::ZERO;
        sum
    }

    /// Enter the mode of a collision `reaction` from Active or Hold
    /// ([`seed`](Self::seed) for Hold or Passive). Returns whether the mode
    /// changed (Hold under [`CollisionReaction::Stop`] stays, its hold
    /// point kept).
    #[inline(always)]
    fn seed_reaction(
        &self,
        st: &mut ModeState<S>,
        reaction: CollisionReaction,
        x: &ControlInput<S>,
    ) -> bool {
        match reaction {
            CollisionReaction::Stop if st.mode == JointMode::Hold => false,
            CollisionReaction::Stop => {
                st.mode = JointMode::Hold;
                st.in_mode = 0;
                st.hold = x.motor_position;
                st.hold_turns = st.frame_turns;
                st.active.integral = S::ZERO;
                true
            }
            CollisionReaction::Passive => {
                st.mode = JointMode::Passive;
                st.in_mode = 0;
                true
            }
        }
    }

    /// One sample: collision detection, mode decision (with seeding at a
    /// switch), the mode's law, and the state updates.
    #[cfg_attr(not(armv6m), inline(always))]
    #[cfg_attr(armv6m, inline)]
    pub fn update(&self, st: &mut ModeState<S>, x: &ControlInput<S>) -> ModeOutput<S> {
        self.update_checked(st, x, x.is_finite())
    }

    /// [`update`](Self::update) for a sample whose measured motor position
    /// and speed and joint torque are finite by construction (the joint
    /// step's: count products and the estimate), so that only the other
    /// five fields are tested ([`ControlInput::is_finite_but_measured`]).
    #[inline(always)]
    pub(crate) fn update_measured(
        &self,
        st: &mut ModeState<S>,
        x: &ControlInput<S>,
    ) -> ModeOutput<S> {
        self.update_checked(st, x, x.is_finite_but_measured())
    }

    /// [`update`](Self::update) given whether the sample is finite.
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    fn update_checked(
        &self,
        st: &mut ModeState<S>,
        x: &ControlInput<S>,
        finite: bool,
    ) -> ModeOutput<S> {
        let interaction = x.joint_torque.sub(x.expected_joint_torque);
        if !finite {
            // Never NaN out of a step: the measured position when it is
            // a number (`v − v` is 0 only for a finite float), else 0.
            let position = if x.motor_position.sub(x.motor_position) == S::ZERO {
                x.motor_position
            } else {
                S::ZERO
            };
            return Self::invalid_sample(st, position);
        }
        let mut reaction = None;
        if let Some(c) = &self.collision {
            if c.update(&mut st.collision, x.joint_torque, x.expected_joint_torque)
                .onset
            {
                st.latched = true;
                reaction = Some(c.reaction());
            }
        }
        st.in_mode = st.in_mode.saturating_add(1);
        let mut switched = false;
        let mut seeded = None;
        if let Some(reaction) = reaction {
            // A collision onset: from Active or Hold at once to the
            // reaction's mode; a Passive joint stays Passive, its release
            // blocked by the latch from this sample on. Never into Active
            // (a separate arm: the seeding of Active is not on its path).
            st.run = 0;
            if st.mode != JointMode::Passive {
                switched = self.seed_reaction(st, reaction, x);
            }
        } else {
            let target = self.wanted(st, interaction, x.motor_velocity);
            if target != st.mode {
                st.run = st.run.saturating_add(1);
                // Passive → Active waits for the release rule's hold.
                let needed = if st.mode == JointMode::Passive {
                    self.release_samples
                } else {
                    self.debounce
                };
                if st.run >= needed && st.in_mode > self.dwell {
                    seeded = self.seed(st, target, x);
                    switched = true;
                }
            } else {
                st.run = 0;
            }
        }
        // τ_before: the previous command.
        let before = st.last_torque;
        // The current mode's law, then its state updates.
        let (law, overflow, reference_position) = match st.mode {
            JointMode::Passive => {
                let law = self.passive.law(x, &st.active.friction);
                let overflow = law.is_nan();
                let law = if overflow { S::ZERO } else { law };
                (law, overflow, x.motor_position)
            }
            mode => {
                let (xr, acc) = self.reference(st, x, seeded);
                // `x` was checked above; `xr` only shifts its reference.
                let mut t: ActiveTerms<S> = self.active.law_of_checked_input(&st.active, &xr);
                // `valid` is false exactly when the law is NaN (a NaN `r`
                // makes the law NaN): that is the overflow the command
                // replaces by 0.
                let overflow = !t.valid;
                if t.valid {
                    if switched {
                        // Re-seed the integral so the law starts near
                        // τ_before (the law is affine in z with slope −1).
                        let zl = self.active.integral_limit();
                        let z = t.law.sub(before).clamp(zl.neg(), zl);
                        st.active.integral = z;
                        t.law = t.law.sub(z);
                    }
                    self.active.commit_valid(&mut st.active, &t);
                }
                if mode == JointMode::Active {
                    // Semi-implicit Euler of ö = −2ω ȯ − ω² o.
                    let rate = st.offset_rate.add(acc.mul_coef(&self.step_rate));
                    st.offset_rate = rate;
                    st.offset = st.offset.add(rate.mul_coef(&self.step_position));
                    let _ = self.drop_overflowing_offset(st);
                }
                (
                    if overflow { S::ZERO } else { t.law },
                    overflow,
                    xr.desired_position,
                )
            }
        };
        let (torque, saturated, overflow) =
            self.command_of_number(law, overflow, before, switched, &mut st.bias);
        st.bias = st.bias.mul_coef(&self.bias_decay);
        st.last_torque = torque;
        ModeOutput {
            torque,
            mode: st.mode,
            switched,
            saturated,
            invalid_input: overflow,
            interaction,
            collision: st.latched,
            reference_position,
        }
    }
}

/// The joint step's hooks into the manager (`crate::joint`): an unusable
/// sample and the turn frame of the joint's positions.
impl<S: Scalar> ModeConfig<S> {
    /// The invalid-sample output of [`update`](Self::update): command 0
    /// with `invalid_input` and `saturated` set, `reference_position` the
    /// finite `position`; the state is not advanced (only the last
    /// command, now 0, is recorded).
    #[inline(always)]
    fn invalid_sample(st: &mut ModeState<S>, position: S) -> ModeOutput<S> {
        st.last_torque = S::ZERO;
        ModeOutput {
            torque: S::ZERO,
            mode: st.mode,
            switched: false,
            saturated: true,
            invalid_input: true,
            interaction: S::ZERO,
            collision: st.latched,
            reference_position: position,
        }
    }

    /// The invalid-sample path of [`update`](Self::update) for a sample the
    /// joint found unusable (a counter jump, a target too far from the
    /// motor, an impossible reading) at the finite measured
    /// `motor_position`: the output of a non-finite sample, without running
    /// the manager's step (so that this rare path and the law's are
    /// separate paths of the joint step).
    #[inline(always)]
    pub(crate) fn reject(&self, st: &mut ModeState<S>, motor_position: S) -> ModeOutput<S> {
        Self::invalid_sample(st, motor_position)
    }

    /// This manager for a joint whose output revolution is `output_rev`
    /// at the motor (`2πN` rad, stored angle units, as the joint's counts
    /// give it): the step by which the hold point moves between turn
    /// frames, at most `⌊MAX/output_rev⌋` revolutions at once (on fixed
    /// point; a larger move is out of the angle's range anyway).
    pub(crate) fn with_output_revolution(mut self, output_rev: S) -> Self {
        self.output_rev = output_rev;
        self.max_shift_turns =
            (S::MAX.to_f64() / output_rev.to_f64().abs()).min(i32::MAX as f64) as i32;
        self
    }

    /// The stored hold point in the inputs' frame: moved from the frame it
    /// was stored in by whole output revolutions,
    /// `hold − 2πN·(frame − hold frame)`, on fixed point by at most
    /// `max_shift_turns` revolutions. The stored point keeps its frame, so
    /// that back in that frame it is the stored point again.
    #[inline(always)]
    fn hold_in_frame(&self, st: &ModeState<S>) -> S {
        if st.hold_turns == st.frame_turns {
            return st.hold;
        }
        let mut whole = st.frame_turns.saturating_sub(st.hold_turns);
        if !S::FLOAT {
            // (`max`/`min`, not `clamp`: no bounds assertion.)
            whole = whole.max(-self.max_shift_turns).min(self.max_shift_turns);
        }
        st.hold.sub(self.output_rev.mul_whole(whole))
    }

    /// One output revolution at the motor, stored angle units
    /// ([`with_output_revolution`](Self::with_output_revolution)).
    #[cfg(any(kani, test))]
    pub(crate) fn output_revolution(&self) -> S {
        self.output_rev
    }

    /// The hold point in the inputs' frame (the joint's frame tests).
    #[cfg(test)]
    pub(crate) fn hold_point(&self, st: &ModeState<S>) -> S {
        self.hold_in_frame(st)
    }
}

#[cfg(any(kani, test))]
mod words {
    use super::ModeConfig;
    use crate::control::adaptive::RobustAdaptiveConfig;
    use crate::control::passive::PassiveConfig;
    use crate::estimation::collision::CollisionConfig;
    #[cfg(test)]
    use crate::scalar::words::Sink;
    use crate::scalar::{words::Words, Coef, CoefRow, I16F16};

    impl ModeConfig<I16F16> {
        pub(crate) const fn take(r: &mut Words) -> Self {
            ModeConfig {
                active: RobustAdaptiveConfig::<I16F16>::take(r),
                passive: PassiveConfig::take(r),
                collision: if r.bool() {
                    Some(CollisionConfig::take(r))
                } else {
                    None
                },
                enter_passive: r.fixed(),
                exit_passive: r.fixed(),
                debounce: r.u16(),
                dwell: r.u16(),
                release_speed: r.fixed(),
                release_samples: r.u16(),
                offset_row: CoefRow::<2>::take(r),
                step_rate: Coef::take(r),
                step_position: Coef::take(r),
                bias_decay: Coef::take(r),
                limit: r.fixed(),
                output_rev: r.fixed(),
                max_shift_turns: r.i32(),
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            self.active.put(s);
            self.passive.put(s);
            s.bool(self.collision.is_some());
            if let Some(c) = &self.collision {
                c.put(s);
            }
            s.fixed(self.enter_passive);
            s.fixed(self.exit_passive);
            s.u32(self.debounce.into());
            s.u32(self.dwell.into());
            s.fixed(self.release_speed);
            s.u32(self.release_samples.into());
            self.offset_row.put(s);
            self.step_rate.put(s);
            self.step_position.put(s);
            self.bias_decay.put(s);
            s.fixed(self.limit);
            s.fixed(self.output_rev);
            s.i32(self.max_shift_turns);
        }
    }
}

#[cfg(test)]
mod tests;
