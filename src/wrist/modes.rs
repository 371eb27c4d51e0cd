//! Active ↔ passive switching of the wrist, bumpless, in task space.
//!
//! The wrist runs one position loop in both modes — the robust adaptive law
//! of [`super::active`] on the joint references of the task-space reference
//! `x_r = (δ_r, γ_r)` (through the ch. 5 inverse kinematics, the caller's
//! step) — and the mode only chooses where `x_r` comes from:
//!
//! * [`WristMode::Active`] — the desired trajectory `x_d(t)` plus a rejoin
//!   offset `o` that decays as a critically damped second-order system of
//!   bandwidth `ω`: `ö = −2ω ȯ − ω² o`;
//! * [`WristMode::Passive`] — the admittance law of
//!   [`super::admittance`] (eq. 6.32), driven by the measured interaction
//!   torque.
//!
//! This is the joint mode manager's scheme ([`crate::control::mode`]:
//! rejoin offset, hysteresis, debounce, dwell) generalised to the wrist's
//! two task axes, with one simplification that the shared position loop
//! allows: the reference is *continuous across a switch* — entering
//! Passive seeds the admittance state with the current reference, entering
//! Active seeds `o = x_r − x_d`, `ȯ = ẋ_r − ẋ_d` — so the law's state
//! (integral, adapted friction) carries over and the command has no jump
//! beyond one ordinary sample of reference motion. The wrist's position is
//! never re-initialised from anything but its own reference, so it is
//! never lost.
//!
//! # Switching rules (Remark 6, automated)
//! With `|τ| = max(|τ_δ|, |τ_γ|)` (N·m, eq. 6.3):
//! * Active → Passive when `|τ| > enter` for `debounce` consecutive
//!   samples;
//! * Passive → Active when `|τ| < exit` **and** the passive reference
//!   moves slower than `rest_speed` on both axes, for `debounce`
//!   consecutive samples;
//!
//! each only after the current mode has lasted `dwell` samples. The rest
//! condition is what keeps a guided wrist passive: while a hand or a door
//! moves it, the admittance law is by design keeping `|τ|` small, so a
//! torque-only exit rule would re-enter Active in mid-motion, be loaded
//! again, and cycle (the weakness of the joint manager's torque-only rule,
//! [`crate::control::mode`]). A request in the input
//! ([`WristModeInput::request`]) switches at once (the manual switching of
//! the thesis's experiments).

// Two- and six-element arrays indexed in parallel (axes, rows): index loops
// read better than zipped iterators here.
#![allow(clippy::needless_range_loop)]

use super::admittance::{AdmittanceConfig, AdmittanceParams, AdmittanceState};
use crate::error::{increasing, positive, ParamError};
use crate::scalar::{Coef, CoefRow, Scalar};

/// The wrist's operating mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WristMode {
    /// Position control on the desired task trajectory (eq. 6.15).
    Active,
    /// Admittance (eq. 6.32) with `τ_d = 0`.
    Passive,
}

/// The wrist mode manager's settings by name, SI, for
/// [`WristModeParams::try_new`] (four `f64` and two `u16`: named so that
/// none can be swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristModeSettings {
    /// The admittance law of the passive mode (eq. 6.32).
    pub admittance: AdmittanceParams,
    /// Interaction torque above which Active turns Passive, N·m, in
    /// `(exit_passive, 1000]`.
    pub enter_passive: f64,
    /// Interaction torque below which Passive may return, N·m, `> 0`.
    pub exit_passive: f64,
    /// Reference speed below which the passive wrist counts as at rest,
    /// rad/s, `> 0`.
    pub rest_speed: f64,
    /// Consecutive samples a switching condition must hold (≥ 1).
    pub debounce: u16,
    /// Samples a mode is kept at least after a switch.
    pub dwell: u16,
    /// Bandwidth `ω` of the rejoin filter, rad/s, `0 < ω T ≤ 0.5`.
    pub rejoin_bandwidth: f64,
}

/// Validated parameters of the wrist mode manager, SI; built only by
/// [`try_new`](Self::try_new).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristModeParams {
    admittance: AdmittanceParams,
    enter_passive: f64,
    exit_passive: f64,
    rest_speed: f64,
    debounce: u16,
    dwell: u16,
    rejoin_bandwidth: f64,
}

impl WristModeParams {
    /// Validate: `0 < exit_passive < enter_passive ≤ 1000` N·m;
    /// `rest_speed > 0` rad/s; `debounce ≥ 1`; a rejoin bandwidth `ω > 0`
    /// rad/s with `ω T ≤ 0.5` (`T` the admittance law's period: the
    /// discrete filter is then stable and not oscillatory).
    pub fn try_new(settings: WristModeSettings) -> Result<Self, ParamError> {
        let WristModeSettings {
            admittance,
            enter_passive,
            exit_passive,
            rest_speed,
            debounce,
            dwell,
            rejoin_bandwidth,
        } = settings;
        positive("exit_passive", exit_passive)?;
        positive("enter_passive", enter_passive)?;
        increasing(
            ("exit_passive", exit_passive),
            ("enter_passive", enter_passive),
        )?;
        if enter_passive > 1e3 {
            return Err(ParamError::OutOfRange {
                name: "enter_passive",
                value: enter_passive,
                min: 0.0,
                max: 1e3,
            });
        }
        positive("rest_speed", rest_speed)?;
        if debounce == 0 {
            return Err(ParamError::NotPositive {
                name: "debounce",
                value: 0.0,
            });
        }
        positive("rejoin_bandwidth", rejoin_bandwidth)?;
        let max_w = 0.5 / admittance.sample_period();
        if rejoin_bandwidth > max_w {
            return Err(ParamError::OutOfRange {
                name: "rejoin_bandwidth",
                value: rejoin_bandwidth,
                min: 0.0,
                max: max_w,
            });
        }
        Ok(WristModeParams {
            admittance,
            enter_passive,
            exit_passive,
            rest_speed,
            debounce,
            dwell,
            rejoin_bandwidth,
        })
    }

    /// The admittance parameters.
    pub fn admittance(&self) -> &AdmittanceParams {
        &self.admittance
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> WristModeSettings {
        WristModeSettings {
            admittance: self.admittance,
            enter_passive: self.enter_passive,
            exit_passive: self.exit_passive,
            rest_speed: self.rest_speed,
            debounce: self.debounce,
            dwell: self.dwell,
            rejoin_bandwidth: self.rejoin_bandwidth,
        }
    }
}

/// The manager quantized for backend `S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristModeConfig<S> {
    admittance: AdmittanceConfig<S>,
    enter: S,
    exit: S,
    rest: S,
    debounce: u16,
    dwell: u16,
    /// `[1 − 2ωT, −ω² T]`: the next offset rate from `(ȯ, o)` (speed →
    /// speed, angle → speed), one exactly summed row on `I16F16`.
    rate_row: CoefRow<2>,
    /// `T`, speed → angle.
    step: Coef,
    /// `1/T`, angle → speed.
    inv_step: Coef,
    limits: [S; 2],
}

/// The manager's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristModeState<S> {
    mode: WristMode,
    admittance: AdmittanceState<S>,
    offset: [S; 2],
    offset_rate: [S; 2],
    reference: [S; 2],
    in_mode: u16,
    run: u16,
}

impl<S: Scalar> WristModeState<S> {
    /// The current mode.
    pub fn mode(&self) -> WristMode {
        self.mode
    }
    /// The last reference `x_r`, stored rad.
    pub fn reference(&self) -> [S; 2] {
        self.reference
    }
}

/// One sample of the manager's input (stored units: rad, rad/s, N·m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WristModeInput<S> {
    /// Desired task pose `x_d = [δ_d, γ_d]` of the active mode, rad.
    pub desired: [S; 2],
    /// Its rate `ẋ_d`, rad/s.
    pub desired_rate: [S; 2],
    /// Measured interaction torques `[τ_δ, τ_γ]` (eq. 6.3), N·m,
    /// environment on wrist.
    pub interaction: [S; 2],
    /// `Some(mode)` to switch now (manual switching); `None` for the
    /// automatic rules.
    pub request: Option<WristMode>,
}

/// One step of the manager.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristModeOutput<S> {
    /// The mode after this sample.
    pub mode: WristMode,
    /// The reference `x_r = [δ_r, γ_r]` for the position loop, rad (map it
    /// through the IK to joint references).
    pub reference: [S; 2],
    /// Its rate, rad/s.
    pub reference_rate: [S; 2],
    /// The mode changed at this sample.
    pub switched: bool,
    /// The admittance law or the workspace limited the reference.
    pub saturated: bool,
    /// An input was NaN or infinite: the reference was held.
    pub invalid_input: bool,
}

impl<S: Scalar> WristModeConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &WristModeParams) -> Self {
        let u = S::UNITS;
        let t = p.admittance.sample_period();
        let w = p.rejoin_bandwidth;
        let lim = p.admittance.limits();
        WristModeConfig {
            admittance: AdmittanceConfig::new(&p.admittance),
            enter: S::from_f64(p.enter_passive * u.link_torque),
            exit: S::from_f64(p.exit_passive * u.link_torque),
            rest: S::from_f64(p.rest_speed * u.speed),
            debounce: p.debounce,
            dwell: p.dwell,
            rate_row: CoefRow::new([1.0 - 2.0 * w * t, -(w * w * t * u.speed / u.angle)]),
            step: Coef::new(t * u.angle / u.speed),
            inv_step: Coef::new(u.speed / (t * u.angle)),
            limits: [S::from_f64(lim[0] * u.angle), S::from_f64(lim[1] * u.angle)],
        }
    }

    /// A state in `mode` whose reference is `pose` (the measured task
    /// pose at start-up, rad), at rest.
    pub fn initial_state(&self, mode: WristMode, pose: [S; 2]) -> WristModeState<S> {
        let adm = self.admittance.state_at(pose);
        WristModeState {
            mode,
            admittance: adm,
            offset: [S::ZERO; 2],
            offset_rate: [S::ZERO; 2],
            reference: adm.reference,
            in_mode: 0,
            run: 0,
        }
    }

    fn enter(&self, st: &mut WristModeState<S>, mode: WristMode, x: &WristModeInput<S>) {
        match mode {
            WristMode::Passive => st.admittance = self.admittance.state_at(st.reference),
            WristMode::Active => {
                for i in 0..2 {
                    // While passive the offset-rate slot holds the
                    // admittance rate: ȯ = ẋ_r − ẋ_d.
                    st.offset[i] = st.reference[i].sub(x.desired[i]);
                    st.offset_rate[i] = st.offset_rate[i].sub(x.desired_rate[i]);
                }
            }
        }
        st.mode = mode;
        st.in_mode = 0;
        st.run = 0;
    }

    /// Whether the sample leaves `mode` (the current one): a request for
    /// the other mode, or, without a request, the mode's rule held for
    /// `debounce` samples after `dwell` samples in the mode (advances the
    /// rule's run counter).
    #[inline(always)]
    fn leaves(
        &self,
        st: &mut WristModeState<S>,
        x: &WristModeInput<S>,
        mode: WristMode,
        torque: S,
    ) -> bool {
        if let Some(m) = x.request {
            return m != mode;
        }
        let want = match mode {
            WristMode::Active => torque > self.enter,
            WristMode::Passive => {
                // The passive reference's last rate is held in the
                // offset-rate slot while passive (see below).
                torque < self.exit
                    && st.offset_rate[0].abs() < self.rest
                    && st.offset_rate[1].abs() < self.rest
            }
        };
        st.run = if want { st.run.saturating_add(1) } else { 0 };
        st.run >= self.debounce && st.in_mode >= self.dwell
    }

    /// The Passive reference of this sample: the admittance law (eq. 6.32)
    /// on the interaction. Its state's reference is always inside the
    /// workspace box (`state_at` and `update` clamp it to the limits
    /// these `limits` are quantized from, the same values), so the
    /// manager's clamp of the Active reference would change nothing here.
    #[inline(always)]
    fn passive_reference(
        &self,
        st: &mut WristModeState<S>,
        x: &WristModeInput<S>,
    ) -> ([S; 2], [S; 2], bool) {
        let o = self.admittance.update(&mut st.admittance, x.interaction);
        // Keep the passive rate for the rest test and for a
        // rate-continuous return to Active.
        st.offset_rate = o.rate;
        (o.reference, o.rate, o.saturated)
    }

    /// The Active reference of this sample: desired plus the decaying
    /// rejoin offset, clamped to the workspace box (`want_rate`: the rate
    /// of a clamped reference by difference, see `update_with`).
    #[inline(always)]
    fn active_reference(
        &self,
        st: &mut WristModeState<S>,
        x: &WristModeInput<S>,
        want_rate: bool,
    ) -> ([S; 2], [S; 2], bool) {
        let mut r = [S::ZERO; 2];
        let mut v = [S::ZERO; 2];
        for i in 0..2 {
            // Semi-implicit Euler of ö = −2ω ȯ − ω² o.
            // ȯ(1 − 2ωT) − o ω²T: on floats the two products summed in
            // order, on fixed point their exact sum rounded once.
            let od = S::dot_coef(&[st.offset_rate[i], st.offset[i]], &self.rate_row);
            let o = st.offset[i].add(od.mul_coef(&self.step));
            // On floats an offset whose next step is not a finite
            // number (desired values near the float range) is
            // dropped: the reference is then the desired
            // trajectory, and the state never holds an infinity
            // or a NaN (`v − v` is 0 exactly when `v` is finite).
            // Fixed point saturates instead (folded at compile
            // time).
            let float = S::FLOAT;
            let (o, od) = if !float || od.sub(od).add(o.sub(o)) == S::ZERO {
                (o, od)
            } else {
                (S::ZERO, S::ZERO)
            };
            st.offset_rate[i] = od;
            st.offset[i] = o;
            r[i] = x.desired[i].add(o);
            // On floats a sum beyond the float range reads as the
            // largest finite value.
            let rate = x.desired_rate[i].add(od);
            v[i] = if float {
                rate.clamp(S::MAX.neg(), S::MAX)
            } else {
                rate
            };
        }
        let mut saturated = false;
        let mut out = r;
        for i in 0..2 {
            let l = self.limits[i];
            let c = out[i].clamp(l.neg(), l);
            saturated |= c != out[i];
            out[i] = c;
        }
        let rate = if want_rate && saturated {
            [
                out[0].sub(st.reference[0]).mul_coef(&self.inv_step),
                out[1].sub(st.reference[1]).mul_coef(&self.inv_step),
            ]
        } else {
            v
        };
        (out, rate, saturated)
    }

    /// One sample: decide the mode (rules in the module docs), then
    /// advance the reference of the mode. Never panics; a non-finite input
    /// holds the reference, flagged.
    pub fn update(&self, st: &mut WristModeState<S>, x: &WristModeInput<S>) -> WristModeOutput<S> {
        self.update_with(st, x, true)
    }

    /// [`update`](Self::update); with `want_rate` false the output's
    /// `reference_rate` is not formed on a clamped Active reference (it
    /// reads the Active rate unclamped): the wrist step, which does not
    /// read it, saves the two products. Everything else is the same.
    #[inline(always)]
    pub(crate) fn update_with(
        &self,
        st: &mut WristModeState<S>,
        x: &WristModeInput<S>,
        want_rate: bool,
    ) -> WristModeOutput<S> {
        // `v − v` is 0 for a finite float and NaN otherwise (always 0 on
        // fixed point); written out, so the step has no loop.
        let d = |v: [S; 2]| v[0].sub(v[0]).add(v[1].sub(v[1]));
        let probe = d(x.desired).add(d(x.desired_rate)).add(d(x.interaction));
        if probe != S::ZERO {
            return WristModeOutput {
                mode: st.mode,
                reference: st.reference,
                reference_rate: [S::ZERO; 2],
                switched: false,
                saturated: false,
                invalid_input: true,
            };
        }
        let torque = x.interaction[0].abs().max(x.interaction[1].abs());
        // Each mode's arm decides whether to leave it (rules in the module
        // docs), enters the other mode when it does, and advances the
        // reference of the mode it ends in: the rules of one mode, the
        // entry into the other and the other's reference form one path
        // (the static bound no longer combines the Passive rule with the
        // entry into Passive).
        let (out, rate, saturated, switched) = match st.mode {
            WristMode::Active => {
                if self.leaves(st, x, WristMode::Active, torque) {
                    self.enter(st, WristMode::Passive, x);
                    st.in_mode = st.in_mode.saturating_add(1);
                    let (r, v, sat) = self.passive_reference(st, x);
                    (r, v, sat, true)
                } else {
                    st.in_mode = st.in_mode.saturating_add(1);
                    let (r, v, sat) = self.active_reference(st, x, want_rate);
                    (r, v, sat, false)
                }
            }
            WristMode::Passive => {
                if self.leaves(st, x, WristMode::Passive, torque) {
                    self.enter(st, WristMode::Active, x);
                    st.in_mode = st.in_mode.saturating_add(1);
                    let (r, v, sat) = self.active_reference(st, x, want_rate);
                    (r, v, sat, true)
                } else {
                    st.in_mode = st.in_mode.saturating_add(1);
                    let (r, v, sat) = self.passive_reference(st, x);
                    (r, v, sat, false)
                }
            }
        };
        st.reference = out;
        WristModeOutput {
            mode: st.mode,
            reference: out,
            reference_rate: rate,
            switched,
            saturated,
            invalid_input: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The named settings reach their getters and roles: with `debounce = 3`
    /// and `dwell = 1` a torque over `enter_passive` switches to Passive at
    /// the third sample; swapped (`debounce = 1`, `dwell = 3`, both `u16`,
    /// as positional arguments allowed) it would switch at the fourth.
    #[test]
    fn named_settings_reach_their_roles() {
        let s = WristModeSettings {
            admittance: AdmittanceParams::thesis(200.0).unwrap(),
            enter_passive: 1.5,
            exit_passive: 0.5,
            rest_speed: 0.01,
            debounce: 3,
            dwell: 1,
            rejoin_bandwidth: 10.0,
        };
        let p = WristModeParams::try_new(s).unwrap();
        assert_eq!(p.settings(), s);
        let switch_at = |p: &WristModeParams| {
            let c = WristModeConfig::<f64>::new(p);
            let mut st = c.initial_state(WristMode::Active, [0.0; 2]);
            let x = WristModeInput {
                desired: [0.0; 2],
                desired_rate: [0.0; 2],
                interaction: [2.0, 0.0],
                request: None,
            };
            (1..=10).find(|_| c.update(&mut st, &x).switched)
        };
        assert_eq!(switch_at(&p), Some(3));
        let swapped = WristModeParams::try_new(WristModeSettings {
            debounce: 1,
            dwell: 3,
            ..s
        })
        .unwrap();
        assert_eq!(switch_at(&swapped), Some(4));
    }

    /// Parameters whose thresholds are exact `f64` values: `T = 0.5` s
    /// (admittance gain limit 1 rad/(s·N·m) for `K_t = 4`, `d = 0`), both
    /// gains `2⁻⁶`, so a torque `τ` moves the passive reference by
    /// `K_c T τ = 2⁻⁷ τ` rad per sample, at `2⁻⁶ τ` rad/s; the rejoin
    /// bandwidth may go up to `0.5/T = 1` rad/s.
    fn exact(enter: f64, exit: f64, rest: f64) -> WristModeSettings {
        WristModeSettings {
            admittance: AdmittanceParams::try_new(crate::wrist::admittance::AdmittanceSettings {
                gain: [1.0 / 64.0; 2],
                stiffness: 4.0,
                sample_period: 0.5,
                lag_samples: 0,
                limits: [1.5, 1.5],
                max_rate: 1.0,
                deadband: 0.0,
                desired_torque: [0.0; 2],
            })
            .unwrap(),
            enter_passive: enter,
            exit_passive: exit,
            rest_speed: rest,
            debounce: 2,
            dwell: 0,
            rejoin_bandwidth: 0.5,
        }
    }

    fn up(x: f64) -> f64 {
        f64::from_bits(x.to_bits() + 1)
    }

    /// The largest `enter_passive` (1000 N·m) and rejoin bandwidth
    /// (`0.5/T`) are accepted, the next `f64` above each is rejected by
    /// name with its range.
    #[test]
    fn enter_and_rejoin_bounds_are_inclusive() {
        let s = exact(2.0, 1.5, 1.0);
        let p = WristModeParams::try_new(WristModeSettings {
            enter_passive: 1e3,
            rejoin_bandwidth: 1.0,
            ..s
        })
        .unwrap();
        assert_eq!(p.settings().enter_passive, 1e3);
        assert_eq!(p.settings().rejoin_bandwidth, 1.0);
        assert_eq!(p.admittance(), &s.admittance);
        assert_eq!(
            WristModeParams::try_new(WristModeSettings {
                enter_passive: up(1e3),
                ..s
            }),
            Err(ParamError::OutOfRange {
                name: "enter_passive",
                value: up(1e3),
                min: 0.0,
                max: 1e3
            })
        );
        assert_eq!(
            WristModeParams::try_new(WristModeSettings {
                rejoin_bandwidth: up(1.0),
                ..s
            }),
            Err(ParamError::OutOfRange {
                name: "rejoin_bandwidth",
                value: up(1.0),
                min: 0.0,
                max: 1.0
            })
        );
    }

    /// The sample (1-based) at which a constant input switches the mode,
    /// within 8 samples, from `mode` at rest at the origin.
    fn switch_at(s: WristModeSettings, mode: WristMode, tau: [f64; 2]) -> Option<usize> {
        let c = WristModeConfig::<f64>::new(&WristModeParams::try_new(s).unwrap());
        let mut st = c.initial_state(mode, [0.0; 2]);
        let x = WristModeInput {
            interaction: tau,
            ..Default::default()
        };
        (1..=8).find(|_| c.update(&mut st, &x).switched)
    }

    /// Every switching threshold is strict, on either axis and sign:
    /// Active leaves above `enter_passive` (a torque of exactly 2 N·m
    /// stays), Passive leaves below `exit_passive` (exactly 1.5 N·m stays)
    /// and only at rest — a reference rate of exactly `rest_speed` on
    /// either axis (`τ = 1` N·m: `2⁻⁶` rad/s) keeps it passive. Debounce
    /// 2: Passive's first sample sees the seeded rate 0, the second the
    /// law's rate.
    #[test]
    fn switching_thresholds_are_strict() {
        let s = exact(2.0, 1.5, 1.0);
        for tau in [[2.0, 0.0], [0.0, -2.0], [-1.0, 2.0]] {
            assert_eq!(switch_at(s, WristMode::Active, tau), None, "{tau:?}");
        }
        for tau in [[up(2.0), 0.0], [0.0, -up(2.0)]] {
            assert_eq!(switch_at(s, WristMode::Active, tau), Some(2), "{tau:?}");
        }
        // Exit: rest_speed 1 rad/s is never the limit here.
        for tau in [[1.5, 0.0], [0.0, -1.5]] {
            assert_eq!(switch_at(s, WristMode::Passive, tau), None, "{tau:?}");
        }
        let below = f64::from_bits(1.5f64.to_bits() - 1);
        for tau in [[below, 0.0], [0.0, -below]] {
            assert_eq!(switch_at(s, WristMode::Passive, tau), Some(2), "{tau:?}");
        }
        // Rest: exactly 2⁻⁶ rad/s on one axis stays, half of it leaves.
        let s = exact(2.0, 1.5, 1.0 / 64.0);
        for tau in [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]] {
            assert_eq!(switch_at(s, WristMode::Passive, tau), None, "{tau:?}");
        }
        for tau in [[0.5, 0.0], [0.0, -0.5], [0.5, 0.5]] {
            assert_eq!(switch_at(s, WristMode::Passive, tau), Some(2), "{tau:?}");
        }
    }

    /// The Active reference is clamped to the workspace (1.5 rad here) per
    /// axis and flagged; its rate is then the clamped reference's change
    /// over `T` (from 0 to ±1.5 in 0.5 s: ±3 rad/s), or, when the step
    /// does not ask for it, the unclamped rate. Unclamped, the reference
    /// is the desired pose (no offset at start) and its rate the desired
    /// rate — not the pose's change over `T`, which differs here.
    #[test]
    fn active_reference_is_clamped_per_axis_and_flagged() {
        let c =
            WristModeConfig::<f64>::new(&WristModeParams::try_new(exact(2.0, 1.5, 1.0)).unwrap());
        for (desired, out, sat, rate) in [
            ([0.25, -0.25], [0.25, -0.25], false, [0.125, 0.5]),
            ([2.0, 0.25], [1.5, 0.25], true, [3.0, 0.5]),
            ([0.25, -2.0], [0.25, -1.5], true, [0.5, -3.0]),
        ] {
            let x = WristModeInput {
                desired,
                desired_rate: [0.125, 0.5],
                ..Default::default()
            };
            let mut st = c.initial_state(WristMode::Active, [0.0; 2]);
            let o = c.update(&mut st, &x);
            assert_eq!(
                (o.reference, o.saturated, o.reference_rate),
                (out, sat, rate),
                "{desired:?}"
            );
            assert_eq!(st.reference(), out);
            assert_eq!(st.mode(), WristMode::Active);
            let mut st = c.initial_state(WristMode::Active, [0.0; 2]);
            let o = c.update_with(&mut st, &x, false);
            assert_eq!(
                (o.reference, o.saturated, o.reference_rate),
                (out, sat, [0.125, 0.5]),
                "{desired:?}"
            );
        }
    }

    fn params() -> WristModeParams {
        let a = AdmittanceParams::thesis(200.0).unwrap();
        WristModeParams::try_new(WristModeSettings {
            admittance: a,
            enter_passive: 1.5,
            exit_passive: 0.5,
            rest_speed: 0.01,
            debounce: 5,
            dwell: 50,
            rejoin_bandwidth: 10.0,
        })
        .unwrap()
    }

    fn cfg() -> WristModeConfig<f64> {
        WristModeConfig::new(&params())
    }

    /// A scripted run: the active wrist follows a sine, a torque pulse
    /// pushes it into Passive, a hand then guides it (torque small but the
    /// wrist moving) and releases it; the wrist returns to Active only
    /// after the release, once, and rejoins the trajectory. At every sample
    /// the reference moves by at most one ordinary step: the larger of the
    /// desired step plus the rejoin filter's step, and the admittance
    /// law's `max_rate·T` — the bumpless property.
    #[test]
    fn switching_is_bumpless_and_does_not_cycle_while_guided() {
        let c = cfg();
        let t = 0.004;
        let mut st = c.initial_state(WristMode::Active, [0.0, 0.0]);
        let mut last = st.reference();
        let mut switches = 0;
        let mut modes = std::vec::Vec::new();
        for k in 0..3000 {
            let time = k as f64 * t;
            let desired = [0.1 * (time).sin(), 0.05 * (0.5 * time).sin()];
            let desired_rate = [0.1 * time.cos(), 0.025 * (0.5 * time).cos()];
            // 1–1.2 s: a 3 N·m push; 1.2–6 s: guided with 0.3–0.45 N·m;
            // after 6 s: released.
            let tau = if (1.0..1.2).contains(&time) {
                [0.0, 3.0]
            } else if (1.2..6.0).contains(&time) {
                [0.15 * (3.0 * time).sin(), 0.3 + 0.15 * (2.0 * time).sin()]
            } else {
                [0.0, 0.0]
            };
            let o = c.update(
                &mut st,
                &WristModeInput {
                    desired,
                    desired_rate,
                    interaction: tau,
                    request: None,
                },
            );
            switches += o.switched as usize;
            modes.push(o.mode);
            // Bound of one step: active ≤ |ẋ_d| T + |ȯ| T (≤ 0.11·T + the
            // offset's rate, itself ≤ 2ω|o| ≤ 20·0.3), passive ≤
            // max_rate·T = 1·T.
            let step = (o.reference[0] - last[0])
                .abs()
                .max((o.reference[1] - last[1]).abs());
            assert!(step <= t * (0.11 + 20.0 * 0.3) + 1e-12, "k={k} step {step}");
            if o.switched {
                // The switching sample itself moves like an ordinary one.
                assert!(step <= t * 1.0 + 1e-12, "k={k} switch step {step}");
            }
            last = o.reference;
        }
        assert_eq!(switches, 2, "one entry into Passive, one return");
        assert_eq!(modes[(1.1 / t) as usize], WristMode::Passive);
        assert_eq!(modes[(5.9 / t) as usize], WristMode::Passive);
        assert_eq!(*modes.last().unwrap(), WristMode::Active);
        // Rejoined: 6 s after the release, the offset has decayed.
        let time = 2999.0 * t;
        assert!((last[0] - 0.1 * time.sin()).abs() < 1e-4, "{last:?}");
    }

    /// A hand (a spring of 20 N·m/rad on γ) guides the wrist at 0.03 rad/s
    /// for 4 s, then lets go. Passive, the admittance law follows it with
    /// `τ = ḣ/K_c = 0.3 N·m`, below a 0.45 N·m exit threshold: a
    /// torque-only exit rule returns to Active in mid-guidance, where the
    /// reference rejoins the trajectory, the hand loads the wrist again and
    /// it re-enters Passive — it cycles. With the rest condition (reference
    /// slower than 0.01 rad/s, while guided it moves at 0.03) the wrist
    /// enters Passive once and returns once, after the release.
    #[test]
    fn rest_condition_stops_cycling_while_guided() {
        let run = |rest: f64| {
            let a = AdmittanceParams::thesis(200.0).unwrap();
            let p = WristModeParams::try_new(WristModeSettings {
                admittance: a,
                enter_passive: 0.5,
                exit_passive: 0.45,
                rest_speed: rest,
                debounce: 5,
                dwell: 25,
                rejoin_bandwidth: 10.0,
            })
            .unwrap();
            let c = WristModeConfig::<f64>::new(&p);
            let mut st = c.initial_state(WristMode::Active, [0.0, 0.0]);
            let (mut guided, mut total) = (0, 0);
            for k in 0..2500 {
                let time = k as f64 * 0.004;
                let held = time < 4.0;
                let h = 0.03 * time;
                let tau = if held {
                    20.0 * (h - st.reference()[1])
                } else {
                    0.0
                };
                let o = c.update(
                    &mut st,
                    &WristModeInput {
                        interaction: [0.0, tau],
                        ..Default::default()
                    },
                );
                total += o.switched as usize;
                if held {
                    guided += o.switched as usize;
                }
            }
            (guided, total, st.mode())
        };
        let (guided, _, _) = run(1e3);
        std::println!("torque-only exit rule: {guided} switches while guided");
        assert!(
            guided >= 4,
            "torque-only rule: {guided} switches while guided"
        );
        let (guided, total, mode) = run(0.01);
        assert_eq!((guided, total, mode), (1, 2, WristMode::Active));
    }

    #[test]
    fn manual_request_and_invalid_input() {
        let c = cfg();
        let mut st = c.initial_state(WristMode::Active, [0.2, -0.1]);
        let o = c.update(
            &mut st,
            &WristModeInput {
                desired: [0.0, 0.0],
                request: Some(WristMode::Passive),
                ..Default::default()
            },
        );
        // Entering Passive keeps the reference where the wrist is.
        assert!(o.switched && o.mode == WristMode::Passive);
        assert_eq!(o.reference, [0.2, -0.1]);
        let o = c.update(
            &mut st,
            &WristModeInput {
                interaction: [f64::NAN, 0.0],
                ..Default::default()
            },
        );
        assert!(o.invalid_input && o.reference == [0.2, -0.1]);
        let a = AdmittanceParams::thesis(200.0).unwrap();
        assert!(WristModeParams::try_new(WristModeSettings {
            admittance: a,
            enter_passive: 0.5,
            exit_passive: 0.6,
            rest_speed: 0.01,
            debounce: 5,
            dwell: 50,
            rejoin_bandwidth: 10.0
        })
        .is_err());
        assert!(WristModeParams::try_new(WristModeSettings {
            admittance: a,
            enter_passive: 1.0,
            exit_passive: 0.5,
            rest_speed: 0.01,
            debounce: 0,
            dwell: 50,
            rejoin_bandwidth: 10.0
        })
        .is_err());
        assert!(WristModeParams::try_new(WristModeSettings {
            admittance: a,
            enter_passive: 1.0,
            exit_passive: 0.5,
            rest_speed: 0.01,
            debounce: 1,
            dwell: 50,
            rejoin_bandwidth: 200.0
        })
        .is_err());
    }

    /// Entering Active from Passive with a desired rate near the `f32`
    /// range: the rejoin offset's rate `ẋ_r − ẋ_d` is finite, but within a
    /// few samples the filter `ȯ ← (1 − 2ωT) ȯ − ω² T o`, `o ← o + T ȯ`
    /// overflows to an infinity, and `∞ − ∞` then makes the offset NaN
    /// (the state was found holding `−∞` by the `wrist_maps` fuzz
    /// target). The offset is dropped (the
    /// reference is the desired trajectory), so the state never holds an
    /// infinity or a NaN and the reference follows the desired pose again
    /// once it is back in range. Before, the NaN offset held the reference
    /// at the workspace edge for as long as the wrist stayed Active.
    #[test]
    fn overflowing_rejoin_offset_is_dropped() {
        let c = WristModeConfig::<f32>::new(&params());
        let finite = |st: &WristModeState<f32>| {
            st.offset
                .iter()
                .chain(st.offset_rate.iter())
                .chain(st.reference.iter())
                .all(|v| v.is_finite())
        };
        let mut st = c.initial_state(WristMode::Passive, [0.1, -0.1]);
        let far = WristModeInput {
            desired: [-3.0e38, 0.0],
            desired_rate: [-3.0e38, 3.0e38],
            interaction: [0.0; 2],
            request: Some(WristMode::Active),
        };
        let o = c.update(&mut st, &far);
        assert!(o.switched && o.mode == WristMode::Active);
        assert!(finite(&st), "{st:?}");
        let o = c.update(
            &mut st,
            &WristModeInput {
                request: None,
                ..far
            },
        );
        assert!(finite(&st), "{st:?}");
        assert!(o.reference_rate.iter().all(|v| v.is_finite()), "{o:?}");
        // Back in range: the reference rejoins the desired pose.
        let home = WristModeInput {
            desired: [0.2, -0.1],
            ..Default::default()
        };
        let mut last = c.update(&mut st, &home);
        // (The finite part of the offset, up to 1e37 rad here, decays by
        // about 1 − ωT = 0.96 per sample: 4000 samples are ample.)
        for _ in 0..4000 {
            last = c.update(&mut st, &home);
            assert!(finite(&st), "{st:?}");
        }
        assert_eq!(last.mode, WristMode::Active);
        assert!((last.reference[0] - 0.2).abs() < 1e-3, "{last:?}");
        assert!((last.reference[1] + 0.1).abs() < 1e-3, "{last:?}");
        // An ordinary offset is kept: entering Active 0.3 rad from the
        // desired pose, the reference starts where the wrist is.
        let mut st2 = c.initial_state(WristMode::Passive, [0.3, 0.0]);
        let o = c.update(
            &mut st2,
            &WristModeInput {
                request: Some(WristMode::Active),
                ..Default::default()
            },
        );
        assert!(o.switched && (o.reference[0] - 0.3).abs() < 0.01, "{o:?}");
    }

    /// The guided scenario of `rest_condition_stops_cycling_while_guided`
    /// on `f32` and `I16F16`: the same switches as `f64` (one in, one out)
    /// and references within the backends' rounding of the `f64` ones.
    #[test]
    fn backends_switch_alike() {
        use crate::scalar::I16F16;
        fn run<S: Scalar>() -> (usize, f64) {
            let a = AdmittanceParams::thesis(200.0).unwrap();
            let p = WristModeParams::try_new(WristModeSettings {
                admittance: a,
                enter_passive: 0.5,
                exit_passive: 0.45,
                rest_speed: 0.01,
                debounce: 5,
                dwell: 25,
                rejoin_bandwidth: 10.0,
            })
            .unwrap();
            let c = WristModeConfig::<S>::new(&p);
            let mut st = c.initial_state(WristMode::Active, [S::ZERO; 2]);
            let mut switches = 0;
            let mut max_ref = 0.0f64;
            for k in 0..2500 {
                let time = k as f64 * 0.004;
                let tau = if time < 4.0 {
                    20.0 * (0.03 * time - st.reference()[1].to_f64())
                } else {
                    0.0
                };
                let o = c.update(
                    &mut st,
                    &WristModeInput {
                        interaction: [S::ZERO, S::from_f64(tau)],
                        ..Default::default()
                    },
                );
                switches += o.switched as usize;
                max_ref = max_ref.max(o.reference[1].to_f64());
            }
            (switches, max_ref)
        }
        let (s64, r64) = run::<f64>();
        let (s32, r32) = run::<f32>();
        let (sfx, rfx) = run::<I16F16>();
        assert_eq!((s64, s32, sfx), (2, 2, 2));
        assert!((r32 - r64).abs() < 1e-4, "{r32} {r64}");
        // ≤ 1000 guided steps, each rounded to ½ LSB (7.6e-6 rad).
        assert!((rfx - r64).abs() < 1000.0 * 7.7e-6, "{rfx} {r64}");
    }
}
