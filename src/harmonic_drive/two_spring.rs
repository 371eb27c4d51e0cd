//! The two-spring system with friction of thesis §2.2.3, eq. (2.14)–(2.16):
//! the mechanism by which a compliant element behind a friction contact
//! produces hysteresis, and the reason the proposed model (eq. 2.27–2.29)
//! needs no rate term.
//!
//! A force `F` (N, or N·m for a torsional pair) acts on spring (a) (`K_a`),
//! which pushes spring (b) (`K_b`) through a contact with static friction
//! `F_fr`. The total displacement is eq. (2.14), `X = F_a/K_a + F_b/K_b`,
//! with `F_a = F`.
//!
//! **Spring (b).** Eq. (2.15) prints `F_b = F − F_fr sgn(Ḟ)`, which holds
//! only while the contact slides. The text's own description — spring (b)
//! stays where it is while `|F − F_b| < F_fr` — is the play operator
//! `F_b ← clamp(F_b, F − F_fr, F + F_fr)` implemented by
//! [`TwoSpringState::apply`]; from rest, the printed form would load
//! spring (b) against the force for `F < F_fr` (errata E2.8). The play form
//! needs no rate, only the previous `F_b`.

use crate::error::{non_negative, positive, ParamError};

/// The two-spring system by name, for [`TwoSpringParams::try_new`] (three `f64`: named so that none
/// can be swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoSpringSettings {
    /// Stiffness of spring (a), `K_a` (N/m or N·m/rad), > 0.
    pub k_a: f64,
    /// Stiffness of spring (b), `K_b`, same unit, > 0.
    pub k_b: f64,
    /// Friction force `F_fr` on spring (b), N or N·m, ≥ 0.
    pub friction: f64,
}

/// Parameters of the two-spring system; built only by
/// [`try_new`](Self::try_new).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoSpringParams {
    k_a: f64,
    k_b: f64,
    friction: f64,
}

impl TwoSpringParams {
    /// Validate: stiffnesses finite and positive, friction finite and not
    /// negative.
    pub fn try_new(settings: TwoSpringSettings) -> Result<Self, ParamError> {
        let TwoSpringSettings { k_a, k_b, friction } = settings;
        let k_a = positive("k_a", k_a)?;
        let k_b = positive("k_b", k_b)?;
        let friction = non_negative("friction", friction)?;
        Ok(TwoSpringParams { k_a, k_b, friction })
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> TwoSpringSettings {
        TwoSpringSettings {
            k_a: self.k_a,
            k_b: self.k_b,
            friction: self.friction,
        }
    }

    /// Stiffness of spring (a), `K_a` (N/m or N·m/rad), > 0.
    pub fn k_a(&self) -> f64 {
        self.k_a
    }

    /// Stiffness of spring (b), `K_b`, > 0.
    pub fn k_b(&self) -> f64 {
        self.k_b
    }

    /// Friction force of the contact behind spring (b), `F_fr` ≥ 0.
    pub fn friction(&self) -> f64 {
        self.friction
    }

    /// Eq. (2.16) as printed, valid while spring (b) slides (`|F_b − F| =
    /// F_fr`): `X = F/K_a + F/K_b − sgn(Ḟ) F_fr/K_b`, with `sgn` of eq. (2.17).
    pub fn sliding_displacement(&self, force: f64, force_rate: f64) -> f64 {
        let s = if force_rate > 0.0 {
            1.0
        } else if force_rate < 0.0 {
            -1.0
        } else {
            0.0
        };
        force / self.k_a + force / self.k_b - s * self.friction / self.k_b
    }
}

/// State of the two-spring system: the force stored in spring (b).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TwoSpringState {
    /// `F_b`, the force in spring (b).
    pub spring_b_force: f64,
}

impl TwoSpringState {
    /// Apply force `F`: update `F_b` by the play operator (spring (b) moves
    /// only when the friction is overcome) and return the displacement of
    /// eq. (2.14). A non-finite force leaves the state unchanged and is
    /// treated as the previous force would be (returns the displacement at
    /// `F_b`).
    pub fn apply(&mut self, p: &TwoSpringParams, force: f64) -> f64 {
        if !force.is_finite() {
            return self.spring_b_force / p.k_a + self.spring_b_force / p.k_b;
        }
        let lo = force - p.friction;
        let hi = force + p.friction;
        self.spring_b_force = self.spring_b_force.max(lo).min(hi);
        force / p.k_a + self.spring_b_force / p.k_b
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Each named setting reaches its own getter (three `f64` that used to
    /// be positional).
    #[test]
    fn named_settings_reach_their_getters() {
        let s = TwoSpringSettings {
            k_a: 3.0,
            k_b: 5.0,
            friction: 0.7,
        };
        let p = TwoSpringParams::try_new(s).unwrap();
        assert_eq!((p.k_a(), p.k_b(), p.friction()), (3.0, 5.0, 0.7));
        assert_eq!(p.settings(), s);
    }

    proptest! {
        /// While the contact slides (loading past `F_fr` from rest, then
        /// unloading past `2 F_fr` below the turning point; `F_fr < peak/4`
        /// so that both passes slide at half the peak), the play form
        /// equals the printed eq. (2.16); the loop's width at equal force is
        /// `2 F_fr / K_b`, independent of the rate.
        #[test]
        fn play_form_matches_eq_2_16_while_sliding(
            k_a in 10.0f64..1e4, k_b in 10.0f64..1e4, fr in 0.1f64..6.0, peak in 25.0f64..100.0,
        ) {
            let p = TwoSpringParams::try_new(TwoSpringSettings { k_a, k_b, friction: fr }).unwrap();
            let mut st = TwoSpringState::default();
            let steps = 400;
            let mut rising_at_half = 0.0;
            for i in 0..=steps {
                let f = peak * i as f64 / steps as f64;
                let x = st.apply(&p, f);
                if f > fr {
                    let printed = p.sliding_displacement(f, 1.0);
                    prop_assert!((x - printed).abs() <= 1e-12 * (1.0 + printed.abs()));
                }
                if i == steps / 2 { rising_at_half = x; }
            }
            let mut falling_at_half = 0.0;
            for i in (0..=steps).rev() {
                let f = peak * i as f64 / steps as f64;
                let x = st.apply(&p, f);
                if f < peak - 2.0 * fr {
                    let printed = p.sliding_displacement(f, -1.0);
                    prop_assert!((x - printed).abs() <= 1e-12 * (1.0 + printed.abs()));
                }
                if i == steps / 2 { falling_at_half = x; }
            }
            prop_assert!((falling_at_half - rising_at_half - 2.0 * fr / k_b).abs() <= 1e-12 * (1.0 + peak / k_a));
        }
    }

    /// Below the friction force, from rest, spring (b) does not move (the
    /// text's statement); the printed eq. (2.16) would instead give a
    /// displacement below `F/K_a`.
    #[test]
    fn spring_b_rests_below_the_friction_force() {
        let p = TwoSpringParams::try_new(TwoSpringSettings {
            k_a: 100.0,
            k_b: 50.0,
            friction: 4.0,
        })
        .unwrap();
        let mut st = TwoSpringState::default();
        let x = st.apply(&p, 2.0);
        assert_eq!(st.spring_b_force, 0.0);
        assert!((x - 2.0 / 100.0).abs() < 1e-15);
        assert!(p.sliding_displacement(2.0, 1.0) < 2.0 / 100.0);
    }

    #[test]
    fn invalid_parameters_are_named() {
        assert!(matches!(
            TwoSpringParams::try_new(TwoSpringSettings {
                k_a: 0.0,
                k_b: 1.0,
                friction: 1.0
            }),
            Err(ParamError::NotPositive { name: "k_a", .. })
        ));
        assert!(matches!(
            TwoSpringParams::try_new(TwoSpringSettings {
                k_a: 1.0,
                k_b: f64::NAN,
                friction: 1.0
            }),
            Err(ParamError::NotFinite { name: "k_b", .. })
        ));
        assert!(matches!(
            TwoSpringParams::try_new(TwoSpringSettings {
                k_a: 1.0,
                k_b: 1.0,
                friction: -1.0
            }),
            Err(ParamError::Negative {
                name: "friction",
                ..
            })
        ));
        let p = TwoSpringParams::try_new(TwoSpringSettings {
            k_a: 1.0,
            k_b: 1.0,
            friction: 1.0,
        })
        .unwrap();
        let mut st = TwoSpringState::default();
        assert!(st.apply(&p, f64::NAN).is_finite());
    }
}
