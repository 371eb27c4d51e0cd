//! Interactive-force compensation in passive mode, thesis §4.3, eq. (4.32):
//!
//! $$ \tau_m = \hat f^c(\dot q_m) + \frac{\hat\tau_t}{N}
//!    + \frac{\hat I_m K_p (\tau_{td} - \hat\tau_t)}{N} $$
//!
//! Friction is compensated by the nominal model of eq. (4.17) (the
//! estimates passed in, e.g. the adapted ones of the active law, or the
//! configured nominal ones), the joint torque is fed forward, and the
//! proportional term drives the joint torque toward `τ_td` (0 for a free
//! joint).
//!
//! **Eq. (4.33), corrected (errata E4.1).** Substituted into eq. (4.2) with
//! exact friction compensation, `Î_m = I_m` and `τ̂_t = τ_t`:
//! `I_m q̈_m = I_m K_p (τ_td − τ̂_t)/N`, i.e. with `τ_td = 0`
//! `(N/K_p) q̈_m + τ̂_t = 0` — a free body of inertia `N/K_p` at the motor,
//! `N²/K_p` seen from the link. Checked by
//! `closed_loop_is_a_free_body_of_inertia_n_over_kp`.
//!
//! Units: `K_p` in 1/(kg·m²) (so that `Î_m K_p` is a dimensionless torque
//! gain), `Î_m` in kg·m².

use super::ControlInput;
use crate::error::{gear_ratio, positive, ParamError};
use crate::friction::{FrictionConfig, FrictionParams};
use crate::scalar::{Coef, Scalar};

/// Parameters of eq. (4.32), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveParams {
    rotor_inertia: f64,
    gain: f64,
    ratio: f64,
    eps_velocity: f64,
    nominal_friction: FrictionParams,
    torque_limit: f64,
}

impl PassiveParams {
    /// Validate: `Î_m > 0` (kg·m²), `K_p ≥ 0` (1/(kg·m²)), `N ≥ 1`,
    /// `ε_q̇ > 0` (rad/s), valid nominal friction, torque limit in
    /// `(0, 16]` N·m.
    pub fn try_new(
        rotor_inertia: f64,
        gain: f64,
        ratio: f64,
        eps_velocity: f64,
        nominal_friction: FrictionParams,
        torque_limit: f64,
    ) -> Result<Self, ParamError> {
        positive("rotor_inertia", rotor_inertia)?;
        let gain = crate::error::finite("gain", gain)?;
        if gain < 0.0 {
            return Err(ParamError::Negative {
                name: "gain",
                value: gain,
            });
        }
        gear_ratio(ratio)?;
        positive("eps_velocity", eps_velocity)?;
        if eps_velocity < 1.0 / 65536.0 {
            return Err(ParamError::NotRepresentable {
                name: "eps_velocity",
                value: eps_velocity,
            });
        }
        let f = nominal_friction;
        FrictionParams::try_new(f.viscous, f.coulomb, f.stribeck, f.stribeck_shape)?;
        positive("torque_limit", torque_limit)?;
        if torque_limit > 16.0 {
            return Err(ParamError::OutOfRange {
                name: "torque_limit",
                value: torque_limit,
                min: 0.0,
                max: 16.0,
            });
        }
        if rotor_inertia * gain / ratio > 1e6 {
            return Err(ParamError::OutOfRange {
                name: "gain",
                value: gain,
                min: 0.0,
                max: 1e6 * ratio / rotor_inertia,
            });
        }
        Ok(PassiveParams {
            rotor_inertia,
            gain,
            ratio,
            eps_velocity,
            nominal_friction,
            torque_limit,
        })
    }

    /// The passive mode for the Table 4.1 joint: `Î_m = 1.14e-5 kg·m²`,
    /// `N = 100`, `ε_q̇ = 0.01 rad/s`, the nominal friction at the centre of
    /// the Table 4.1 example box
    /// ([`RobustAdaptiveDesign::table_4_1`](super::RobustAdaptiveDesign::table_4_1)),
    /// limit 0.188 N·m, and `K_p` given (the thesis prints no value for
    /// ch. 4).
    pub fn table_4_1(gain: f64) -> Result<Self, ParamError> {
        let d = super::RobustAdaptiveDesign::table_4_1();
        Self::try_new(
            d.rotor_inertia,
            gain,
            d.ratio,
            d.eps_velocity,
            d.initial_friction,
            d.torque_limit,
        )
    }

    /// The Table 4.1 passive mode with a default gain the thesis does not
    /// give: `K_p = 1/Î_m` (`Î_m K_p = 1`, i.e. `K_p ≈ 87 719` 1/(kg·m²)
    /// for `Î_m = 1.14e-5 kg·m²`).
    ///
    /// With `Î_m K_p = 1` the two joint-torque terms of eq. (4.32) cancel,
    /// `τ_m = f̂^c(q̇_m) + τ_td/N`: the law compensates friction and adds
    /// the desired joint torque, and the estimate's noise and sampling
    /// delay do not enter a torque-feedback loop, so the choice is stable
    /// at any sample period. By eq. (4.33) as corrected (errata E4.1) the
    /// joint then moves as a free body of link-side inertia
    /// `N²/K_p = N² Î_m` (0.114 kg·m² here): the rotor's reflected inertia
    /// without its friction. A larger `K_p` makes the joint feel lighter
    /// (eq. 4.33) but closes a loop on the sampled estimate; check it in
    /// simulation before raising it ([`table_4_1`](Self::table_4_1) takes
    /// any gain).
    pub fn table_4_1_default() -> Result<Self, ParamError> {
        let d = super::RobustAdaptiveDesign::table_4_1();
        Self::table_4_1(1.0 / d.rotor_inertia)
    }

    /// `K_p`, 1/(kg·m²).
    pub fn gain(&self) -> f64 {
        self.gain
    }

    /// `N/K_p`: the apparent motor-side inertia of eq. (4.33) as corrected
    /// (errata E4.1), kg·m²; `∞` for `K_p = 0`.
    pub fn apparent_motor_inertia(&self) -> f64 {
        self.ratio / self.gain
    }
}

/// Eq. (4.32) quantized for backend `S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveConfig<S> {
    friction: FrictionConfig<S>,
    nominal: [S; 4],
    /// `1/N` from stored link torque to stored motor torque.
    feedback: Coef,
    /// `Î_m K_p / N` from stored link torque to stored motor torque.
    torque_gain: Coef,
    torque_limit: S,
}

/// One step of the passive law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveOutput<S> {
    /// Motor torque, stored motor-torque units, `|τ| ≤ limit`.
    pub torque: S,
    /// The law's value before the limit.
    pub law_torque: S,
    /// The output was limited (or the input invalid).
    pub saturated: bool,
    /// An input was NaN or infinite: torque 0.
    pub invalid_input: bool,
}

impl<S: Scalar> PassiveConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &PassiveParams) -> Self {
        let u = S::UNITS;
        let mt = u.motor_torque;
        PassiveConfig {
            friction: FrictionConfig::new(p.eps_velocity),
            nominal: FrictionConfig::<S>::quantize(&p.nominal_friction),
            feedback: Coef::new(mt / (p.ratio * u.link_torque)),
            torque_gain: Coef::new(p.rotor_inertia * p.gain * mt / (p.ratio * u.link_torque)),
            torque_limit: S::from_f64(p.torque_limit * mt),
        }
    }

    /// The configured nominal friction estimates, stored units.
    pub fn nominal_friction(&self) -> [S; 4] {
        self.nominal
    }

    /// The motor torque limit, stored units.
    pub fn torque_limit(&self) -> S {
        self.torque_limit
    }

    /// Eq. (4.32) with the configured nominal friction.
    ///
    /// ```
    /// use mrr_control::control::{ControlInput, PassiveConfig, PassiveParams};
    /// use mrr_control::I16F16;
    /// let p = PassiveParams::table_4_1(2000.0)?;
    /// let cfg = PassiveConfig::<I16F16>::new(&p);
    /// // At rest with τ̂_t = 1 N·m: τ_m = 1/100 − 1.14e-5·2000·1/100
    /// // = 0.01 − 0.000228 = 0.009772 N·m = 9.772 mN·m.
    /// let x = ControlInput { joint_torque: I16F16::from_num(1), ..Default::default() };
    /// let tau = cfg.update(&x).torque.to_num::<f64>();
    /// assert!((tau - 9.772).abs() < 1e-3);
    /// # Ok::<(), mrr_control::ParamError>(())
    /// ```
    pub fn update(&self, x: &ControlInput<S>) -> PassiveOutput<S> {
        self.update_with_friction(x, &self.nominal)
    }

    /// Eq. (4.32) with given friction estimates (stored units, e.g. the
    /// adapted `F̂^c` of the active law). Uses `motor_velocity`,
    /// `joint_torque` and `desired_joint_torque` of the sample.
    #[inline]
    pub fn update_with_friction(&self, x: &ControlInput<S>, friction: &[S; 4]) -> PassiveOutput<S> {
        let law = self.law(x, friction);
        if !x.is_finite() || law.is_nan() {
            return PassiveOutput {
                torque: S::ZERO,
                law_torque: S::ZERO,
                saturated: true,
                invalid_input: true,
            };
        }
        let l = self.torque_limit;
        let torque = law.clamp(l.neg(), l);
        PassiveOutput {
            torque,
            law_torque: law,
            saturated: torque != law,
            invalid_input: false,
        }
    }

    /// The unlimited law value.
    #[inline]
    pub(crate) fn law(&self, x: &ControlInput<S>, friction: &[S; 4]) -> S {
        let f = self.friction.evaluate(friction, x.motor_velocity).torque;
        f.add(x.joint_torque.mul_coef(&self.feedback)).add(
            x.desired_joint_torque
                .sub(x.joint_torque)
                .mul_coef(&self.torque_gain),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;
    use proptest::prelude::*;

    fn params(kp: f64) -> PassiveParams {
        PassiveParams::table_4_1(kp).unwrap()
    }

    /// Errata E4.1: simulate eq. (4.2) under eq. (4.32) with exact friction
    /// compensation and `τ_td = 0`; the motor acceleration is
    /// `−K_p τ̂_t / N` (the corrected eq. 4.33), not `−K_p τ̂_t` (printed).
    #[test]
    fn closed_loop_is_a_free_body_of_inertia_n_over_kp() {
        let kp = 2000.0;
        let p = params(kp);
        let cfg = PassiveConfig::<f64>::new(&p);
        let f = p.nominal_friction;
        let i_m = 1.14e-5;
        for &(qd, tau) in &[(0.3, 0.5), (-2.0, -0.2), (0.001, 1.0), (5.0, -0.05)] {
            let x = ControlInput {
                motor_velocity: qd,
                joint_torque: tau,
                ..Default::default()
            };
            let tau_m = cfg.update(&x).torque;
            // Eq. (4.2): I_m q̈ = τ_m − f(q̇) − τ_t/N, with the model's own
            // boundary-layer friction (the "uncertain part" neglected).
            let qdd = (tau_m - f.nominal(qd, 0.01) - tau / 100.0) / i_m;
            let corrected = -kp * tau / 100.0;
            assert!(
                (qdd - corrected).abs() <= 1e-9 * corrected.abs(),
                "{qdd} vs {corrected}"
            );
            assert!((qdd - (-kp * tau)).abs() > 0.5 * (kp * tau).abs());
        }
        assert_eq!(p.apparent_motor_inertia(), 100.0 / kp);
    }

    #[test]
    fn try_new_names_the_bad_value() {
        assert!(matches!(
            PassiveParams::table_4_1(-1.0),
            Err(ParamError::Negative { name: "gain", .. })
        ));
        let f = RobustFriction::nominal();
        assert!(matches!(
            PassiveParams::try_new(1e-5, 1.0, 0.5, 0.01, f, 0.1),
            Err(ParamError::OutOfRange { name: "ratio", .. })
        ));
        assert!(matches!(
            PassiveParams::try_new(1e-5, 1.0, 100.0, 0.01, f, 17.0),
            Err(ParamError::OutOfRange {
                name: "torque_limit",
                ..
            })
        ));
    }

    struct RobustFriction;
    impl RobustFriction {
        fn nominal() -> FrictionParams {
            super::super::RobustAdaptiveDesign::table_4_1().initial_friction
        }
    }

    proptest! {
        /// Output bounded and NaN-free; backends agree with f64 on the same
        /// (quantized) inputs: I16F16 within 4 LSB of mN·m per stored
        /// product (friction ≤ 8 products, feedback 2) plus the exp kernel
        /// on `f_s` (≤ 2 LSB relative to f_s = 6 mN·m); f32 within
        /// 16 ulp of the largest term.
        #[test]
        fn bounded_and_backends_agree(qd in -100.0f64..100.0, tau in -30.0f64..30.0, kp in 0.0f64..5000.0) {
            let p = params(kp);
            let c64 = PassiveConfig::<f64>::new(&p);
            let cx = PassiveConfig::<I16F16>::new(&p);
            let c32 = PassiveConfig::<f32>::new(&p);
            let xq = ControlInput { motor_velocity: I16F16::from_f64(qd), joint_torque: I16F16::from_f64(tau), ..Default::default() };
            let x64 = ControlInput { motor_velocity: xq.motor_velocity.to_f64(), joint_torque: xq.joint_torque.to_f64(), ..Default::default() };
            let x32 = ControlInput { motor_velocity: qd as f32, joint_torque: tau as f32, ..Default::default() };
            let a = c64.update(&x64);
            let b = cx.update(&xq);
            let c = c32.update(&x32);
            prop_assert!(b.torque.abs() <= cx.torque_limit() && c.torque.abs() <= c32.torque_limit());
            let lsb = 1.0 / 65536.0;
            let tol_x = (4.0 * 10.0 * lsb + 6.0 * 2.0 * lsb) / 1e3;
            prop_assert!((b.torque.to_f64() / 1e3 - a.torque).abs() <= tol_x, "{} vs {}", b.torque, a.torque);
            let a32 = c64.update(&ControlInput { motor_velocity: x32.motor_velocity as f64, joint_torque: x32.joint_torque as f64, ..Default::default() });
            let big = a32.law_torque.abs() + (tau / 100.0).abs() * (1.0 + 1.14e-5 * kp) + 0.03;
            prop_assert!((c.torque as f64 - a32.torque).abs() <= 16.0 * f32::EPSILON as f64 * big);
        }
    }
}
