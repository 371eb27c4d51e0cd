//! Wave-generator torque under back-driving, eq. (2.40), as a play operator.
//!
//! When the link is back-driven while the motor is held, the drive's
//! friction balances the two torques: `N τ_w + τ_f = τ_fr` with
//! `|τ_fr| ≤ τ_fb`, the back-driving friction torque (eq. 2.9). While the
//! friction can hold the balance, the wave-generator torque does not change
//! (stick); once it cannot, the friction saturates at `±τ_fb` (slip):
//!
//! * `τ_f + N τ_w(t−1) > τ_fb`  → `τ_w(t) = −(τ_f − τ_fb)/N`
//! * `τ_f + N τ_w(t−1) < −τ_fb` → `τ_w(t) = −(τ_f + τ_fb)/N`
//! * otherwise                  → `τ_w(t) = τ_w(t−1)`
//!
//! The printed conditions of eq. (2.40) are garbled (errata E2.5); this is the
//! intended stateful logic. It is the classic play (backlash) operator of
//! width `2 τ_fb` acting on `−τ_f / N`: rate independent, so it produces the
//! hysteresis of Fig. 2.22 without any derivative of a measured signal.

use crate::error::{gear_ratio, positive, ParamError};
use crate::scalar::{Coef, Scalar};

/// The back-driving friction play of eq. (2.40) by name, for [`WaveGeneratorTorqueParams::try_new`]
/// (two `f64`: named so that they cannot be swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveGeneratorTorqueSettings {
    /// Back-driving friction torque at the flexspline `τ_fb`, N·m (> 0).
    pub backdrive_friction: f64,
    /// Gear ratio `N` (≥ 1).
    pub ratio: f64,
}

/// Parameters of the back-driving friction play, eq. (2.40); built only by
/// [`try_new`](Self::try_new).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveGeneratorTorqueParams {
    backdrive_friction: f64,
    ratio: f64,
}

impl WaveGeneratorTorqueParams {
    /// Validates `τ_fb > 0` and `N ≥ 1`.
    pub fn try_new(settings: WaveGeneratorTorqueSettings) -> Result<Self, ParamError> {
        let WaveGeneratorTorqueSettings {
            backdrive_friction,
            ratio,
        } = settings;
        let backdrive_friction = positive("backdrive_friction", backdrive_friction)?;
        let ratio = gear_ratio(ratio)?;
        Ok(WaveGeneratorTorqueParams {
            backdrive_friction,
            ratio,
        })
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> WaveGeneratorTorqueSettings {
        WaveGeneratorTorqueSettings {
            backdrive_friction: self.backdrive_friction,
            ratio: self.ratio,
        }
    }

    /// Back-driving friction torque at the flexspline `τ_fb`, N·m (> 0).
    pub fn backdrive_friction(&self) -> f64 {
        self.backdrive_friction
    }

    /// Gear ratio `N` (≥ 1).
    pub fn ratio(&self) -> f64 {
        self.ratio
    }
}

/// Eq. (2.40) quantized for backend `S`: link torques in
/// `S::UNITS.link_torque`, motor torques in `S::UNITS.motor_torque`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveGeneratorTorqueConfig<S> {
    /// `τ_fb / N` in stored motor-torque units.
    half_width: S,
    /// Stored motor torque per stored link torque, `1/N` with unit scales.
    motor_per_link: Coef,
}

/// State of eq. (2.40): the previous wave-generator torque `τ_w(t−1)`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WaveGeneratorTorqueState<S> {
    /// `τ_w(t−1)` in stored motor-torque units.
    pub torque: S,
}

impl<S: Scalar> WaveGeneratorTorqueConfig<S> {
    /// Quantize validated parameters.
    pub fn new(p: &WaveGeneratorTorqueParams) -> Self {
        let u = S::UNITS;
        WaveGeneratorTorqueConfig {
            half_width: S::from_f64(p.backdrive_friction / p.ratio * u.motor_torque),
            motor_per_link: Coef::new(u.motor_torque / (p.ratio * u.link_torque)),
        }
    }

    /// One step: the wave-generator torque for the current flexspline torque.
    ///
    /// Written on the motor side as `x = −τ_f/N`: stick while
    /// `|x − τ_w(t−1)| ≤ τ_fb/N`, otherwise `τ_w` follows `x` at the edge of
    /// the play — the same three cases as the module docs.
    ///
    /// A NaN or infinite flexspline torque (floats) leaves the state
    /// unchanged and returns it, so a bad sample never poisons the state.
    #[inline]
    pub fn update(&self, state: &mut WaveGeneratorTorqueState<S>, flexspline_torque: S) -> S {
        if !S::all_finite(&[flexspline_torque]) {
            return state.torque;
        }
        let x = flexspline_torque.mul_coef(&self.motor_per_link).neg();
        let lo = x.sub(self.half_width);
        let hi = x.add(self.half_width);
        state.torque = state.torque.clamp(lo, hi);
        state.torque
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;
    use proptest::prelude::*;

    /// Each named setting reaches its own getter (two `f64` that used to
    /// be positional; `τ_fb = 100`, `N = 2` would have validated swapped).
    #[test]
    fn named_settings_reach_their_getters() {
        let s = WaveGeneratorTorqueSettings {
            backdrive_friction: 2.0,
            ratio: 100.0,
        };
        let p = WaveGeneratorTorqueParams::try_new(s).unwrap();
        assert_eq!((p.backdrive_friction(), p.ratio()), (2.0, 100.0));
        assert_eq!(p.settings(), s);
    }

    /// A NaN or infinite torque used to turn the state into NaN or ±∞ for
    /// good; now it is skipped and the state stays finite.
    #[test]
    fn non_finite_torque_leaves_the_state_unchanged() {
        let p = WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings {
            backdrive_friction: 2.0,
            ratio: 100.0,
        })
        .unwrap();
        let c = WaveGeneratorTorqueConfig::<f32>::new(&p);
        let mut st = WaveGeneratorTorqueState::default();
        let before = c.update(&mut st, 10.0);
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            assert_eq!(c.update(&mut st, bad), before);
            assert_eq!(st.torque, before);
        }
        // And the play goes on from there.
        assert_eq!(c.update(&mut st, -10.0), 0.08);
    }

    /// The cases of eq. (2.40) as written in the module docs, in f64.
    fn reference(prev: f64, tf: f64, tfb: f64, n: f64) -> f64 {
        if tf + n * prev > tfb {
            -(tf - tfb) / n
        } else if tf + n * prev < -tfb {
            -(tf + tfb) / n
        } else {
            prev
        }
    }

    #[test]
    fn rejects_bad_parameters_by_name() {
        assert!(matches!(
            WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings {
                backdrive_friction: 0.0,
                ratio: 100.0
            }),
            Err(ParamError::NotPositive {
                name: "backdrive_friction",
                ..
            })
        ));
        assert!(matches!(
            WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings {
                backdrive_friction: 2.0,
                ratio: 0.5
            }),
            Err(ParamError::OutOfRange { name: "ratio", .. })
        ));
    }

    /// The printed second condition of eq. (2.40) fires inside the stick
    /// region (errata E2.5): at balance τ_w = −τ_f/N with τ_f = 1 N·m and
    /// τ_fb = 2 N·m, τ_f − N τ_w = 2 > −τ_fb, so the printed logic would move
    /// τ_w to −(τ_f + τ_fb)/N although the friction can hold it.
    #[test]
    fn printed_condition_would_slip_in_the_stick_region() {
        let (tf, tfb, n) = (1.0, 2.0, 100.0);
        let prev = -tf / n;
        assert!(tf - n * prev > -tfb); // the printed condition holds
        assert_eq!(reference(prev, tf, tfb, n), prev); // but the drive sticks
        let cfg = WaveGeneratorTorqueConfig::<f64>::new(
            &WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings {
                backdrive_friction: tfb,
                ratio: n,
            })
            .unwrap(),
        );
        let mut st = WaveGeneratorTorqueState { torque: prev };
        assert_eq!(cfg.update(&mut st, tf), prev);
    }

    proptest! {
        /// The clamp form equals the three cases, step by step, for random
        /// back-driving sequences.
        #[test]
        fn clamp_form_equals_the_case_analysis(
            torques in proptest::collection::vec(-40.0f64..40.0, 1..200),
            tfb in 0.1f64..5.0, n in 30.0f64..200.0,
        ) {
            let cfg = WaveGeneratorTorqueConfig::<f64>::new(&WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings { backdrive_friction: tfb, ratio: n }).unwrap());
            let mut st = WaveGeneratorTorqueState::default();
            let mut prev = 0.0;
            for tf in torques {
                let want = reference(prev, tf, tfb, n);
                let got = cfg.update(&mut st, tf);
                prop_assert!((got - want).abs() <= 1e-12 * (1.0 + want.abs()));
                prev = want;
                // The friction balance never exceeds τ_fb.
                prop_assert!((n * got + tf).abs() <= tfb * (1.0 + 1e-12) + 1e-12);
            }
        }

        /// Fixed point follows f64 within the quantization of its inputs.
        #[test]
        fn fixed_follows_f64(torques in proptest::collection::vec(-40.0f64..40.0, 1..100)) {
            let p = WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings { backdrive_friction: 2.0, ratio: 100.0 }).unwrap();
            let (cf, cx) = (WaveGeneratorTorqueConfig::<f64>::new(&p), WaveGeneratorTorqueConfig::<I16F16>::new(&p));
            let (mut sf, mut sx) = (WaveGeneratorTorqueState::default(), WaveGeneratorTorqueState::default());
            for tf in torques {
                let a = cf.update(&mut sf, tf) * 1e3; // mN·m
                let b = cx.update(&mut sx, I16F16::from_f64(tf)).to_f64();
                // Quantizing τ_f costs ½ LSB, scaled by 1/N = 10 mN·m per
                // N·m (exact in I16F16): 5 LSB; the product rounds (½ LSB)
                // and the play half-width τ_fb/N = 20 mN·m is exact; the
                // clamp only selects. So |error| ≤ 5.5 LSB.
                prop_assert!((a - b).abs() <= 5.5 / 65536.0, "{a} vs {b}");
            }
        }
    }
}
