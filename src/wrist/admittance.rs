//! Passive mode of the wrist by the admittance law of thesis §6.2, eq.
//! (6.28)–(6.33), in task space `x = (δ, γ)` (eq. 6.30), sampled.
//!
//! The measured interaction torques `τ = (τ_δ, τ_γ)` (eq. 6.3,
//! [`super::ft_sensor`]) move the task-space reference
//!
//! `x_d[k] = clamp(x_d[k−1] + T K_c (τ[k] − τ_d), workspace)`
//!
//! (eq. 6.32, forward Euler, with `f_d = τ_d`; `τ_d = 0` is the passive
//! mode), and the position loop (the active law of [`super::active`] on
//! the joint references `IK(x_d)`) makes the wrist follow it. The mapping
//! of `x_d` to motor joint references through the inverse kinematics of
//! ch. 5 is the caller's step (or [`super::modes`]'s user's): this module
//! stays in task space, where the thesis's law is written and where the
//! singularity of the joint-space map at `δ = γ = 0` (§6.2) does not
//! appear. With the ch. 5 kinematics of this crate the step is
//! `WristConfig::inverse(PitchYaw { delta, gamma }).motors` (or its
//! continuous `IkState` form) for the joint references of
//! [`super::active::WristJointSample`], and the force mapping of eq. (6.1)
//! for its `interaction_torque`.
//!
//! # Sign (errata E6.2)
//! Here `τ` is the torque the environment applies to the wrist, positive
//! when it tends to increase `δ` (`γ`). A spring-like environment gives
//! `τ = −K_t (x − x_e)` (eq. 6.28 with `f = −τ` the torque the wrist
//! applies to the environment), and the law `ẋ_d = +K_c (τ − τ_d)`
//! yields, with `x = x_d` (eq. 6.29),
//! `d(Δτ)/dt = −K_c K_t Δτ`: eq. (6.33) with its missing time derivative
//! restored, stable for `K_c K_t > 0`. Eq. (6.28) and (6.32) as printed
//! (`f = K_t X`, `ẋ_d = K_c Δf`, both in terms of the force the gripper
//! exerts) give `d(Δf)/dt = +K_c K_t Δf` instead: the printed law is
//! unstable unless `K_c < 0`. Eq. (6.31) should read `Δf(t) → 0`.
//!
//! # Stability in discrete time
//! Let the position loop reach the reference `d` samples after it is set
//! (`d = 0`: eq. 6.29 literally, the wrist is at `x_d[k]` when `τ[k+1]` is
//! sampled). Then `Δτ[k+1] = Δτ[k] − a Δτ[k−d]` with `a = T K_c K_t`,
//! characteristic polynomial `z^{d+1} − z^d + a`. A root on the unit
//! circle `z = e^{iω}` needs `|z − 1| = a` and
//! `dω + (π + ω)/2 ≡ π`, i.e. `ω = π/(2d+1)` and
//!
//! `a_max(d) = 2 sin(π / (2(2d+1)))`:
//!
//! `a_max = 2` for `d = 0` (`|1 − a| < 1`), `1` for `d = 1`, `0.618` for
//! `d = 2`. The loop is stable iff `0 < K_c < a_max(d) / (T K_t)`
//! ([`max_admittance_gain`]), and monotone (no overshoot) for
//! `d = 0, K_c ≤ 1/(T K_t)`. With a stiffness matrix (coupled axes), `K_t`
//! is its largest eigenvalue and the condition holds for the largest of
//! the two gains (the eigenvalues of `diag(K_c) K_t` lie in
//! `(0, max K_c · λ_max(K_t)]`); it is then sufficient, exact for equal
//! gains.
//!
//! At the thesis's `T = 4 ms` and `K_c = 0.1 rad/(s·N·m)` (§6.4.3) the
//! loop tolerates environments up to `K_t = 2/(0.004·0.1) = 5000 N·m/rad`
//! with `d = 0`, 2500 with `d = 1`. [`AdmittanceParams::try_new`] rejects a
//! gain outside `(0, a_max/(T K_t))` for the stated stiffness with
//! [`ParamError::OutOfRange`] named `"gain[0]"` or `"gain[1]"`.

// Two- and six-element arrays indexed in parallel (axes, rows): index loops
// read better than zipped iterators here.
#![allow(clippy::needless_range_loop)]

use crate::error::{finite, non_negative, positive, ParamError};
use crate::scalar::{Coef, Scalar};

/// `a_max(d) = 2 sin(π/(2(2d+1)))`, the largest stable `T K_c K_t` with a
/// position lag of `d` samples (module docs).
pub fn stability_limit(lag_samples: u8) -> f64 {
    2.0 * libm::sin(core::f64::consts::PI / (2.0 * (2.0 * lag_samples as f64 + 1.0)))
}

/// The largest stable admittance gain `K_c` (rad/(s·N·m)) for an
/// environment stiffness `K_t` (N·m/rad), sampling period `T` (s) and a
/// position lag of `d` samples: `a_max(d)/(T K_t)`. `∞` for `K_t = 0`.
///
/// ```
/// use mrr_control::wrist::admittance::max_admittance_gain;
/// // T = 4 ms, K_t = 250 N·m/rad: K_c < 2/(0.004·250) = 2 rad/(s·N·m).
/// assert!((max_admittance_gain(250.0, 0.004, 0) - 2.0).abs() < 1e-12);
/// assert!((max_admittance_gain(250.0, 0.004, 1) - 1.0).abs() < 1e-12);
/// ```
pub fn max_admittance_gain(stiffness: f64, sample_period: f64, lag_samples: u8) -> f64 {
    stability_limit(lag_samples) / (sample_period * stiffness)
}

/// The admittance law's settings by name, SI (units and rules on
/// [`AdmittanceParams::try_new`]); two of the same type cannot be swapped
/// by position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdmittanceSettings {
    /// `[K_c,δ, K_c,γ]`, rad/(s·N·m).
    pub gain: [f64; 2],
    /// Largest environment stiffness `K_t`, N·m/rad.
    pub stiffness: f64,
    /// Sampling period `T`, s.
    pub sample_period: f64,
    /// Samples `d` by which the wrist reaches its reference late.
    pub lag_samples: u8,
    /// Workspace half-widths `[|δ|, |γ|]`, rad.
    pub limits: [f64; 2],
    /// Largest reference speed, rad/s.
    pub max_rate: f64,
    /// Torque deadband, N·m.
    pub deadband: f64,
    /// `τ_d` (`f_d` of eq. 6.31), N·m.
    pub desired_torque: [f64; 2],
}

/// Validated parameters of the admittance law, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdmittanceParams {
    gain: [f64; 2],
    stiffness: f64,
    sample_period: f64,
    lag_samples: u8,
    limits: [f64; 2],
    max_rate: f64,
    deadband: f64,
    desired_torque: [f64; 2],
}

impl AdmittanceParams {
    /// Validate:
    /// * `gain = [K_c,δ, K_c,γ]` in rad/(s·N·m), each in
    ///   `(0, a_max(d)/(T K_t))` ([`max_admittance_gain`]);
    /// * `stiffness` — the largest environment stiffness `K_t` the wrist
    ///   may meet, N·m/rad, `> 0`: the contact's torque per rad about a
    ///   wrist axis, eq. (6.28); for a gripper `K_r` and an environment
    ///   `K_e` in series, `K_r K_e/(K_r + K_e)` (§6.2's `K_r + K_e` is an
    ///   upper bound, safe here; errata E6.7);
    /// * `sample_period` `T ∈ [1e-6, 1]` s; `lag_samples = d ≤ 16`;
    /// * `limits` — the workspace `|δ| ≤ limits[0]`, `|γ| ≤ limits[1]`,
    ///   rad, in `(0, π/2]` (Remark 3: ±30°, [`AdmittanceParams::thesis`]);
    /// * `max_rate` — the largest reference speed, rad/s, `> 0`;
    /// * `deadband` — torques below it (N·m, `≥ 0`) do not move the
    ///   reference (sensor noise and offset; Remark 4's "small residual
    ///   internal force");
    /// * `desired_torque` — `τ_d` (`f_d` of eq. 6.31), N·m, finite; 0 for
    ///   the passive mode.
    pub fn try_new(settings: AdmittanceSettings) -> Result<Self, ParamError> {
        let AdmittanceSettings {
            gain,
            stiffness,
            sample_period,
            lag_samples,
            limits,
            max_rate,
            deadband,
            desired_torque,
        } = settings;
        let k = positive("stiffness", stiffness)?;
        let t = positive("sample_period", sample_period)?;
        if !(1e-6..=1.0).contains(&t) {
            return Err(ParamError::OutOfRange {
                name: "sample_period",
                value: t,
                min: 1e-6,
                max: 1.0,
            });
        }
        if lag_samples > 16 {
            return Err(ParamError::OutOfRange {
                name: "lag_samples",
                value: lag_samples as f64,
                min: 0.0,
                max: 16.0,
            });
        }
        let kmax = max_admittance_gain(k, t, lag_samples);
        for (i, g) in gain.into_iter().enumerate() {
            let name = ["gain[0]", "gain[1]"][i];
            let g = finite(name, g)?;
            if !(g > 0.0 && g < kmax) {
                return Err(ParamError::OutOfRange {
                    name,
                    value: g,
                    min: 0.0,
                    max: kmax,
                });
            }
        }
        for (i, l) in limits.into_iter().enumerate() {
            let name = ["limits[0]", "limits[1]"][i];
            let l = positive(name, l)?;
            if l > core::f64::consts::FRAC_PI_2 {
                return Err(ParamError::OutOfRange {
                    name,
                    value: l,
                    min: 0.0,
                    max: core::f64::consts::FRAC_PI_2,
                });
            }
        }
        let max_rate = positive("max_rate", max_rate)?;
        if max_rate > 1e3 {
            return Err(ParamError::OutOfRange {
                name: "max_rate",
                value: max_rate,
                min: 0.0,
                max: 1e3,
            });
        }
        let deadband = non_negative("deadband", deadband)?;
        for (i, d) in desired_torque.into_iter().enumerate() {
            let name = ["desired_torque[0]", "desired_torque[1]"][i];
            let d = finite(name, d)?;
            if d.abs() > 1e3 {
                return Err(ParamError::OutOfRange {
                    name,
                    value: d,
                    min: -1e3,
                    max: 1e3,
                });
            }
        }
        if deadband > 1e3 {
            return Err(ParamError::OutOfRange {
                name: "deadband",
                value: deadband,
                min: 0.0,
                max: 1e3,
            });
        }
        Ok(AdmittanceParams {
            gain,
            stiffness: k,
            sample_period: t,
            lag_samples,
            limits,
            max_rate,
            deadband,
            desired_torque,
        })
    }

    /// The thesis's passive mode (§6.4.3): `K_c = 0.1 rad/(s·N·m)` on both
    /// axes, `T = 4 ms`, the ±30° workspace (Remark 3), `τ_d = 0`, for an
    /// environment of stiffness up to `stiffness` N·m/rad with a one-sample
    /// position lag (`K_c < 1/(T K_t)`: `K_t < 2500 N·m/rad`), reference
    /// speed ≤ 1 rad/s, no deadband.
    pub fn thesis(stiffness: f64) -> Result<Self, ParamError> {
        let l = 30f64.to_radians();
        Self::try_new(AdmittanceSettings {
            gain: [0.1, 0.1],
            stiffness,
            sample_period: 0.004,
            lag_samples: 1,
            limits: [l, l],
            max_rate: 1.0,
            deadband: 0.0,
            desired_torque: [0.0; 2],
        })
    }

    /// `[K_c,δ, K_c,γ]`, rad/(s·N·m).
    pub fn gain(&self) -> [f64; 2] {
        self.gain
    }

    /// The stiffness the gains were validated for, N·m/rad.
    pub fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// `T`, s.
    pub fn sample_period(&self) -> f64 {
        self.sample_period
    }

    /// `d`, samples.
    pub fn lag_samples(&self) -> u8 {
        self.lag_samples
    }

    /// Workspace half-ranges `[δ, γ]`, rad.
    pub fn limits(&self) -> [f64; 2] {
        self.limits
    }
}

/// The admittance law quantized for backend `S` (angles in rad, torques
/// in N·m: `S::UNITS.angle`, `S::UNITS.link_torque`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdmittanceConfig<S> {
    /// `K_c T`, stored torque → stored angle.
    step: [Coef; 2],
    /// `1/T`, stored angle → stored speed (for the reported rate).
    rate: Coef,
    max_step: [S; 2],
    limits: [S; 2],
    deadband: S,
    desired: [S; 2],
    params: AdmittanceParams,
}

/// The state: the task-space reference `x_d = (δ_d, γ_d)`, rad.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AdmittanceState<S> {
    /// `[δ_d, γ_d]`, stored angle units, always inside the workspace.
    pub reference: [S; 2],
}

/// One step of the admittance law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdmittanceOutput<S> {
    /// `x_d[k] = [δ_d, γ_d]`, stored angle units.
    pub reference: [S; 2],
    /// `ẋ_d` of eq. (6.32) as applied (after the rate and workspace
    /// limits), stored speed units.
    pub rate: [S; 2],
    /// The rate limit or the workspace boundary was active.
    pub saturated: bool,
    /// A torque was NaN or infinite: the reference did not move.
    pub invalid_input: bool,
}

impl<S: Scalar> AdmittanceConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &AdmittanceParams) -> Self {
        let u = S::UNITS;
        let t = p.sample_period;
        let q = |a: [f64; 2], s: f64| [S::from_f64(a[0] * s), S::from_f64(a[1] * s)];
        AdmittanceConfig {
            step: [
                Coef::new(p.gain[0] * t * u.angle / u.link_torque),
                Coef::new(p.gain[1] * t * u.angle / u.link_torque),
            ],
            rate: Coef::new(u.speed / (t * u.angle)),
            max_step: q([p.max_rate * t; 2], u.angle),
            limits: q(p.limits, u.angle),
            deadband: S::from_f64(p.deadband * u.link_torque),
            desired: q(p.desired_torque, u.link_torque),
            params: *p,
        }
    }

    /// The validated parameters.
    pub fn params(&self) -> &AdmittanceParams {
        &self.params
    }

    /// A state whose reference is `reference` (stored rad) clamped to the
    /// workspace: seed it with the measured task pose `(δ, γ)` when the
    /// passive mode starts, so that the wrist is not moved (bumpless).
    pub fn state_at(&self, reference: [S; 2]) -> AdmittanceState<S> {
        let mut r = [S::ZERO; 2];
        for i in 0..2 {
            let l = self.limits[i];
            r[i] = if reference[i].is_nan() {
                S::ZERO
            } else {
                reference[i].clamp(l.neg(), l)
            };
        }
        AdmittanceState { reference: r }
    }

    /// Eq. (6.32) for one sample: the measured `τ = [τ_δ, τ_γ]` (stored
    /// N·m, environment on wrist) moves the reference by
    /// `T K_c (τ − τ_d)` (minus the deadband), limited to `max_rate·T` and
    /// to the workspace. Never panics; a NaN or infinite torque leaves the
    /// reference unchanged, flagged.
    ///
    /// ```
    /// use mrr_control::wrist::admittance::{AdmittanceConfig, AdmittanceParams};
    /// let cfg = AdmittanceConfig::<f64>::new(&AdmittanceParams::thesis(200.0)?);
    /// let mut st = cfg.state_at([0.0, 0.1]);
    /// // 2 N·m about γ: γ_d grows by T K_c τ = 0.004·0.1·2 = 8e-4 rad.
    /// let o = cfg.update(&mut st, [0.0, 2.0]);
    /// assert!((o.reference[1] - 0.1008).abs() < 1e-12 && o.reference[0] == 0.0);
    /// assert!((o.rate[1] - 0.2).abs() < 1e-9 && !o.saturated);
    /// # Ok::<(), mrr_control::ParamError>(())
    /// ```
    pub fn update(&self, st: &mut AdmittanceState<S>, torque: [S; 2]) -> AdmittanceOutput<S> {
        let d = |v: S| v.sub(v);
        if d(torque[0]).add(d(torque[1])) != S::ZERO {
            return AdmittanceOutput {
                reference: st.reference,
                rate: [S::ZERO; 2],
                saturated: false,
                invalid_input: true,
            };
        }
        let mut saturated = false;
        let mut rate = [S::ZERO; 2];
        for i in 0..2 {
            let e = torque[i].sub(self.desired[i]);
            // Deadband: e − clamp(e, ±band).
            let e = e.sub(e.clamp(self.deadband.neg(), self.deadband));
            let mut dx = e.mul_coef(&self.step[i]);
            let m = self.max_step[i];
            if dx.abs() > m {
                dx = if dx > S::ZERO { m } else { m.neg() };
                saturated = true;
            }
            let old = st.reference[i];
            let l = self.limits[i];
            let x = old.add(dx);
            let x = if x > l {
                saturated = true;
                l
            } else if x < l.neg() {
                saturated = true;
                l.neg()
            } else {
                x
            };
            st.reference[i] = x;
            rate[i] = x.sub(old).mul_coef(&self.rate);
        }
        AdmittanceOutput {
            reference: st.reference,
            rate,
            saturated,
            invalid_input: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;

    /// Simulate the sampled loop of the module docs on one axis with the
    /// library's law: the environment is `τ = −K_t (x − x_e)`, the wrist
    /// reaches each reference `d` samples after it is set. Returns
    /// `|Δτ|` over the last 50 samples divided by the initial `|Δτ|`.
    fn loop_decay(kc: f64, kt: f64, t: f64, d: u8, n: usize) -> f64 {
        // Validate against a slack stiffness so that unstable gains can be
        // simulated with the library's own law.
        let p = AdmittanceParams::try_new(AdmittanceSettings {
            gain: [kc, kc],
            stiffness: 1e-9,
            sample_period: t,
            lag_samples: d,
            limits: [1.5, 1.5],
            max_rate: 1e3,
            deadband: 0.0,
            desired_torque: [0.0; 2],
        })
        .unwrap();
        let cfg = AdmittanceConfig::<f64>::new(&p);
        let xe = 1e-3;
        let mut st = cfg.state_at([0.0, 0.0]);
        let mut history = std::vec![0.0f64; d as usize + 1]; // references set, oldest first
        let tau0 = kt * xe;
        let mut last = 0.0f64;
        for k in 0..n {
            let x = history[0];
            let tau = -kt * (x - xe);
            let o = cfg.update(&mut st, [0.0, tau]);
            history.remove(0);
            history.push(o.reference[1]);
            if k + 50 >= n {
                last = last.max((tau).abs());
            }
        }
        last / tau0
    }

    /// Errata E6.7: §6.2 calls `K_r`, `K_e` compliances and adds them,
    /// `K_t = K_r + K_e`, then uses `K_t` as a stiffness in eq. (6.28),
    /// `f = K_t X`. A gripper spring `K_r` and an environment spring `K_e`
    /// (both stiffnesses, N·m/rad) in series between the wrist and the
    /// surface give the wrist the torque `τ = −K_r (x − y)`, with the tip
    /// `y` where the two balance, `K_r (x − y) = K_e (y − x_e)`: solved
    /// here for `y` on every sample, without any `K_t`. The library's law
    /// (lag `d = 0`) then contracts `Δτ` by `1 − T K_c K_t` per sample with
    /// `K_t = K_r K_e/(K_r + K_e)` (the compliances add), not with
    /// `K_r + K_e`; and a gain that is stable for the series stiffness is
    /// rejected when validated for the sum: the sum is a safe upper bound.
    #[test]
    fn series_springs_set_the_loop_rate_not_their_sum() {
        let (kr, ke, t, kc) = (1000.0, 1000.0, 0.004, 0.9);
        let p = AdmittanceParams::try_new(AdmittanceSettings {
            gain: [kc, kc],
            stiffness: 1e-9,
            sample_period: t,
            lag_samples: 0,
            limits: [1.5, 1.5],
            max_rate: 1e3,
            deadband: 0.0,
            desired_torque: [0.0; 2],
        })
        .unwrap();
        let cfg = AdmittanceConfig::<f64>::new(&p);
        let xe = 1e-3;
        let mut st = cfg.state_at([0.0, 0.0]);
        let torque = |x: f64| {
            let y = (kr * x + ke * xe) / (kr + ke);
            -kr * (x - y)
        };
        let mut x = 0.0;
        let mut taus = std::vec::Vec::new();
        for _ in 0..6 {
            let tau = torque(x);
            taus.push(tau);
            x = cfg.update(&mut st, [0.0, tau]).reference[1];
        }
        let series = kr * ke / (kr + ke);
        for k in 1..taus.len() {
            let ratio = taus[k] / taus[k - 1];
            let k_loop = (1.0 - ratio) / (t * kc);
            assert!(
                (k_loop - series).abs() < 1e-6 * series,
                "{k_loop} vs {series}"
            );
        }
        // Stable (|1 − T K_c K_t| = 0.8 < 1) and converging ...
        assert!(taus[5].abs() < 0.5 * taus[0].abs(), "{taus:?}");
        // ... at a gain that validation against K_r + K_e rejects
        // (max 2/(T (K_r + K_e)) = 0.25) and against K_t accepts (max 1).
        let validate = |stiffness: f64| {
            AdmittanceParams::try_new(AdmittanceSettings {
                gain: [kc, kc],
                stiffness,
                sample_period: t,
                lag_samples: 0,
                limits: [1.5, 1.5],
                max_rate: 1e3,
                deadband: 0.0,
                desired_torque: [0.0; 2],
            })
        };
        assert!(validate(kr + ke).is_err());
        assert!(validate(series).is_ok());
    }

    /// The closed-form range, checked by simulating the discrete loop just
    /// inside (0.97 a_max: the error decays) and just outside (1.03 a_max:
    /// it grows) for `d = 0, 1, 2, 3` at `T = 4 ms`, and `K_c = a_max/(T
    /// K_t)` rejected by `try_new` while 0.99 of it is accepted.
    #[test]
    fn discrete_stability_range_is_exact() {
        let (t, kt) = (0.004, 300.0);
        for d in 0..=3u8 {
            let kmax = max_admittance_gain(kt, t, d);
            // Near the limit the decay per sample is |z| ≈ 1 − O(margin):
            // 4000 samples make inside ≪ 1 and outside ≫ 1.
            let inside = loop_decay(0.97 * kmax, kt, t, d, 4000);
            let outside = loop_decay(1.03 * kmax, kt, t, d, 4000);
            assert!(inside < 1e-2, "d={d}: inside {inside}");
            assert!(outside > 1e2, "d={d}: outside {outside}");
            let ok = AdmittanceParams::try_new(AdmittanceSettings {
                gain: [0.99 * kmax; 2],
                stiffness: kt,
                sample_period: t,
                lag_samples: d,
                limits: [0.5; 2],
                max_rate: 1.0,
                deadband: 0.0,
                desired_torque: [0.0; 2],
            });
            assert!(ok.is_ok());
            let bad = AdmittanceParams::try_new(AdmittanceSettings {
                gain: [kmax, 0.1],
                stiffness: kt,
                sample_period: t,
                lag_samples: d,
                limits: [0.5; 2],
                max_rate: 1.0,
                deadband: 0.0,
                desired_torque: [0.0; 2],
            });
            assert!(
                matches!(bad, Err(ParamError::OutOfRange { name: "gain[0]" | "gain[1]", max, .. }) if (max - kmax).abs() < 1e-12)
            );
        }
        // Hand values of a_max: 2, 1, 2 sin(π/10) = 0.618034.
        assert!((stability_limit(0) - 2.0).abs() < 1e-15);
        assert!((stability_limit(1) - 1.0).abs() < 1e-15);
        assert!((stability_limit(2) - 0.6180339887).abs() < 1e-9);
        // Negative and zero gains are rejected too.
        assert!(AdmittanceParams::try_new(AdmittanceSettings {
            gain: [0.0, 0.1],
            stiffness: kt,
            sample_period: t,
            lag_samples: 0,
            limits: [0.5; 2],
            max_rate: 1.0,
            deadband: 0.0,
            desired_torque: [0.0; 2]
        })
        .is_err());
        assert!(AdmittanceParams::try_new(AdmittanceSettings {
            gain: [-0.1, 0.1],
            stiffness: kt,
            sample_period: t,
            lag_samples: 0,
            limits: [0.5; 2],
            max_rate: 1.0,
            deadband: 0.0,
            desired_torque: [0.0; 2]
        })
        .is_err());
    }

    /// Errata E6.2: the printed sign. With `f = K_t x` (eq. 6.28, the
    /// force the wrist exerts) and `ẋ_d = +K_c Δf` (eq. 6.32) the sampled
    /// loop diverges for any `K_c > 0`; the law here (reaction torque
    /// `τ = −f`) converges at the same gain.
    #[test]
    fn printed_sign_diverges_corrected_converges() {
        let (t, kt, kc, xe) = (0.004, 300.0, 0.1, 1e-3);
        let mut x = 0.0;
        let mut f = 0.0;
        for _ in 0..2000 {
            f = kt * (x - xe); // eq. 6.28 about the contact point x_e
            x += t * kc * f; // eq. 6.32 as printed, x = x_d (eq. 6.29)
        }
        assert!(f.abs() > 1e3 * kt * xe, "{f}");
        assert!(loop_decay(kc, kt, t, 0, 2000) < 1e-6);
    }

    /// Settings on every validated boundary, chosen so that each bound is
    /// an exact `f64`: `T = 0.5` s and `K_t = 4` N·m/rad with `d = 0` give
    /// `K_c,max = 2 sin(π/2)/(0.5·4) = 1` rad/(s·N·m).
    fn edge() -> AdmittanceSettings {
        AdmittanceSettings {
            gain: [0.5, 0.5],
            stiffness: 4.0,
            sample_period: 0.5,
            lag_samples: 0,
            limits: [1.0, 1.0],
            max_rate: 1.0,
            deadband: 0.0,
            desired_torque: [0.0; 2],
        }
    }

    /// The next `f64` above and below `x > 0`.
    fn up(x: f64) -> f64 {
        f64::from_bits(x.to_bits() + 1)
    }
    fn down(x: f64) -> f64 {
        f64::from_bits(x.to_bits() - 1)
    }

    /// Every validated range: the largest and smallest accepted values are
    /// accepted and reach their getters, the next ones are rejected with
    /// the field's name, the value and the range. The closed bounds (`T ∈
    /// [1e-6, 1]`, `d ≤ 16`, `limits ≤ π/2`, `max_rate ≤ 1000`,
    /// `|desired_torque| ≤ 1000`, `deadband ≤ 1000`) accept the bound
    /// itself; the gain's open interval `(0, K_c,max)` rejects both ends.
    #[test]
    fn every_range_is_accepted_to_its_bound_and_rejected_past_it() {
        let ok = |s: AdmittanceSettings| AdmittanceParams::try_new(s).unwrap();
        let range = |name, value, min, max| {
            Err(ParamError::OutOfRange {
                name,
                value,
                min,
                max,
            })
        };
        let s = edge();
        // Getters: the settings as given.
        let p = ok(AdmittanceSettings {
            gain: [0.125, 0.2],
            limits: [0.5, 1.25],
            lag_samples: 3,
            ..s
        });
        assert_eq!(
            (
                p.gain(),
                p.stiffness(),
                p.sample_period(),
                p.lag_samples(),
                p.limits()
            ),
            ([0.125, 0.2], 4.0, 0.5, 3, [0.5, 1.25])
        );
        // The gain: (0, 1) here, either axis.
        let g = down(1.0);
        for i in 0..2 {
            let name = ["gain[0]", "gain[1]"][i];
            let with = |v: f64| {
                let mut gain = [0.5; 2];
                gain[i] = v;
                AdmittanceParams::try_new(AdmittanceSettings { gain, ..s })
            };
            assert_eq!(with(g).unwrap().gain()[i], g);
            assert_eq!(with(1e-300).unwrap().gain()[i], 1e-300);
            assert_eq!(with(1.0), range(name, 1.0, 0.0, 1.0));
            assert_eq!(with(0.0), range(name, 0.0, 0.0, 1.0));
            assert_eq!(with(-0.5), range(name, -0.5, 0.0, 1.0));
        }
        // The sample period, with gains well inside their range.
        let small = AdmittanceSettings {
            gain: [1e-9; 2],
            ..s
        };
        for t in [1e-6, 1.0] {
            assert_eq!(
                ok(AdmittanceSettings {
                    sample_period: t,
                    ..small
                })
                .sample_period(),
                t
            );
        }
        for t in [down(1e-6), up(1.0)] {
            assert_eq!(
                AdmittanceParams::try_new(AdmittanceSettings {
                    sample_period: t,
                    ..small
                }),
                range("sample_period", t, 1e-6, 1.0)
            );
        }
        // The lag: 16 accepted (a_max(16) = 2 sin(π/66) ≈ 0.095 > 1e-9·2).
        assert_eq!(
            ok(AdmittanceSettings {
                lag_samples: 16,
                ..small
            })
            .lag_samples(),
            16
        );
        assert_eq!(
            AdmittanceParams::try_new(AdmittanceSettings {
                lag_samples: 17,
                ..small
            }),
            range("lag_samples", 17.0, 0.0, 16.0)
        );
        // The workspace half-widths: up to π/2, either axis.
        let h = core::f64::consts::FRAC_PI_2;
        for i in 0..2 {
            let name = ["limits[0]", "limits[1]"][i];
            let with = |v: f64| {
                let mut limits = [1.0; 2];
                limits[i] = v;
                AdmittanceParams::try_new(AdmittanceSettings { limits, ..s })
            };
            assert_eq!(with(h).unwrap().limits()[i], h);
            assert_eq!(with(up(h)), range(name, up(h), 0.0, h));
        }
        // The rate, the deadband and the desired torque: up to 1000.
        assert!(AdmittanceParams::try_new(AdmittanceSettings { max_rate: 1e3, ..s }).is_ok());
        assert_eq!(
            AdmittanceParams::try_new(AdmittanceSettings {
                max_rate: up(1e3),
                ..s
            }),
            range("max_rate", up(1e3), 0.0, 1e3)
        );
        assert!(AdmittanceParams::try_new(AdmittanceSettings { deadband: 1e3, ..s }).is_ok());
        assert_eq!(
            AdmittanceParams::try_new(AdmittanceSettings {
                deadband: up(1e3),
                ..s
            }),
            range("deadband", up(1e3), 0.0, 1e3)
        );
        for i in 0..2 {
            let name = ["desired_torque[0]", "desired_torque[1]"][i];
            for sign in [1.0, -1.0] {
                let mut d = [0.0; 2];
                d[i] = sign * 1e3;
                assert!(AdmittanceParams::try_new(AdmittanceSettings {
                    desired_torque: d,
                    ..s
                })
                .is_ok());
                d[i] = sign * up(1e3);
                assert_eq!(
                    AdmittanceParams::try_new(AdmittanceSettings {
                        desired_torque: d,
                        ..s
                    }),
                    range(name, sign * up(1e3), -1e3, 1e3)
                );
            }
        }
    }

    /// `a_max(d) = 2 sin(π/(2(2d+1)))` and `K_c,max = a_max/(T K_t)`
    /// against hand values: `a_max(0) = 2`, `a_max(1) = 2 sin(π/6) = 1`,
    /// `a_max(4) = 2 sin(π/18) = 0.347296355333861`; `T = 0.25`,
    /// `K_t = 8` divide by 2.
    #[test]
    fn stability_limit_and_max_gain_hand_values() {
        for (d, a) in [(0u8, 2.0), (1, 1.0), (4, 0.347_296_355_333_860_7)] {
            assert!((stability_limit(d) - a).abs() < 1e-15, "{d}");
            assert!(
                (max_admittance_gain(8.0, 0.25, d) - a / 2.0).abs() < 1e-15,
                "{d}"
            );
        }
        // Not symmetric in its arguments' roles: T K_t = 0.5·3 = 1.5.
        assert!((max_admittance_gain(3.0, 0.5, 0) - 2.0 / 1.5).abs() < 1e-15);
    }

    /// The rate limit and the workspace are strict: a step of exactly
    /// `max_rate·T` and a reference landing exactly on a limit are not
    /// saturated; one LSB of torque past them is. With [`edge`] and
    /// `K_c = 0.5`: `K_c T = 0.25` rad/(N·m), `max_rate·T = 0.5` rad, so
    /// 2 N·m steps by exactly 0.5 rad.
    #[test]
    fn rate_limit_and_workspace_are_strict() {
        let c = AdmittanceConfig::<f64>::new(&AdmittanceParams::try_new(edge()).unwrap());
        assert_eq!(c.params(), &AdmittanceParams::try_new(edge()).unwrap());
        for sign in [1.0, -1.0] {
            // From 0.5·sign by exactly 0.5 onto the limit ±1: nothing saturated.
            let mut st = c.state_at([0.5 * sign, 0.0]);
            let o = c.update(&mut st, [2.0 * sign, 0.0]);
            assert_eq!(o.reference, [sign, 0.0]);
            assert_eq!(o.rate, [sign, 0.0]); // 0.5 rad in 0.5 s
            assert!(!o.saturated && !o.invalid_input, "{sign}: {o:?}");
            // From 0 by exactly 0.5 on the other axis: not saturated.
            let mut st = c.state_at([0.0, 0.0]);
            let o = c.update(&mut st, [0.0, 2.0 * sign]);
            assert_eq!(o.reference, [0.0, 0.5 * sign]);
            assert!(!o.saturated, "{sign}: {o:?}");
            // A larger torque is limited to the same step, flagged.
            let mut st = c.state_at([0.0, 0.0]);
            let o = c.update(&mut st, [0.0, 3.0 * sign]);
            assert_eq!(o.reference, [0.0, 0.5 * sign]);
            assert_eq!(o.rate, [0.0, sign]);
            assert!(o.saturated, "{sign}: {o:?}");
            // Past the limit: held on it, flagged, with the rate applied.
            let mut st = c.state_at([0.75 * sign, 0.0]);
            let o = c.update(&mut st, [2.0 * sign, 0.0]);
            assert_eq!(o.reference, [sign, 0.0]);
            assert_eq!(o.rate, [0.5 * sign, 0.0]);
            assert!(o.saturated, "{sign}: {o:?}");
        }
        // An infinite torque is invalid (not only NaN), either axis.
        for tau in [[f64::INFINITY, 0.0], [0.0, f64::NEG_INFINITY]] {
            let mut st = c.state_at([0.25, -0.25]);
            let o = c.update(&mut st, tau);
            assert!(o.invalid_input && !o.saturated, "{tau:?}");
            assert_eq!((o.reference, o.rate), ([0.25, -0.25], [0.0; 2]));
        }
        // A state seeded at a NaN pose is at 0 on that axis, clamped on
        // the other.
        assert_eq!(c.state_at([f64::NAN, -3.0]).reference, [0.0, -1.0]);
    }

    #[test]
    fn limits_deadband_and_backends() {
        let p = AdmittanceParams::try_new(AdmittanceSettings {
            gain: [0.1, 0.2],
            stiffness: 200.0,
            sample_period: 0.004,
            lag_samples: 1,
            limits: [0.5, 0.5],
            max_rate: 0.5,
            deadband: 0.3,
            desired_torque: [0.0; 2],
        })
        .unwrap();
        let c = AdmittanceConfig::<f64>::new(&p);
        let mut st = c.state_at([0.49, -7.0]);
        assert_eq!(st.reference, [0.49, -0.5]);
        // Inside the deadband nothing moves.
        let o = c.update(&mut st, [0.29, -0.25]);
        assert_eq!(o.reference, [0.49, -0.5]);
        // 10 N·m − 0.3 band at K_c = 0.1: 3.88e-3 rad > 0.5·0.004 = 2e-3:
        // rate-limited, then the workspace stops it at 0.5.
        let o = c.update(&mut st, [10.0, 0.0]);
        assert!(o.saturated && (o.reference[0] - 0.492).abs() < 1e-12);
        for _ in 0..10 {
            c.update(&mut st, [10.0, 0.0]);
        }
        assert_eq!(st.reference[0], 0.5);
        let o = c.update(&mut st, [f64::NAN, 0.0]);
        assert!(o.invalid_input && o.reference == st.reference);
        // Fixed point and f32 follow f64 over a torque sequence.
        let cf = AdmittanceConfig::<I16F16>::new(&p);
        let c3 = AdmittanceConfig::<f32>::new(&p);
        let (mut a, mut b, mut s3) = (
            c.state_at([0.0; 2]),
            cf.state_at([I16F16::ZERO; 2]),
            c3.state_at([0.0; 2]),
        );
        for k in 0..500 {
            let tau = [
                3.0 * (k as f64 * 0.05).sin(),
                -2.0 * (k as f64 * 0.03).cos(),
            ];
            c.update(&mut a, tau);
            cf.update(&mut b, tau.map(I16F16::from_f64));
            c3.update(&mut s3, tau.map(|v| v as f32));
        }
        for i in 0..2 {
            // ≤ 500 steps × ½ LSB of rounding each (7.6e-6 rad per step).
            assert!((b.reference[i].to_f64() - a.reference[i]).abs() < 500.0 * 7.7e-6);
            assert!((s3.reference[i] as f64 - a.reference[i]).abs() < 1e-5);
        }
    }
}
