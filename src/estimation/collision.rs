//! Collision detection on the joint-torque estimate (the use of ch. 3's
//! estimate the thesis names in its conclusions, ch. 7).
//!
//! The residual is `ρ = τ̂_t − τ_expected`: the estimated (or measured)
//! joint torque minus the torque expected without contact (gravity,
//! payload, inverse dynamics; 0 if unknown). A collision is *detected* when
//! `|ρ| > threshold` for `debounce` consecutive samples, and *released*
//! when `|ρ| < release_threshold` (≤ threshold: hysteresis) for `release`
//! consecutive samples. The detector only flags; the reaction
//! ([`CollisionReaction`]) is carried out by the mode manager
//! ([`crate::control::mode`]).

use crate::error::{positive, ParamError};
use crate::scalar::Scalar;

/// What the joint does on a detected collision.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CollisionReaction {
    /// Hold the position at detection (active law, frozen reference).
    Stop,
    /// Switch to the passive mode (eq. 4.32): yield to the contact.
    Passive,
}

/// The detector's parameters by name, SI, for [`CollisionParams::try_new`]
/// (two thresholds and two sample counts of the same types: named so that
/// they cannot be swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionSettings {
    /// Detection threshold on `|ρ|`, N·m (link torque), in
    /// `(0, 30 000]`.
    pub threshold: f64,
    /// Release threshold on `|ρ|`, N·m, in `(0, threshold]` (hysteresis).
    pub release_threshold: f64,
    /// Consecutive samples over `threshold` that detect a collision (≥ 1).
    pub debounce: u16,
    /// Consecutive samples under `release_threshold` that release it
    /// (≥ 1).
    pub release: u16,
    /// What the joint does on detection.
    pub reaction: CollisionReaction,
}

/// Detector parameters, SI; built only by [`try_new`](CollisionParams::try_new).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionParams {
    threshold: f64,
    release_threshold: f64,
    debounce: u16,
    release: u16,
    reaction: CollisionReaction,
}

impl CollisionParams {
    /// Validate: `0 < release_threshold ≤ threshold ≤ 30 000` N·m (link
    /// torque); `debounce, release ≥ 1` samples.
    pub fn try_new(settings: CollisionSettings) -> Result<Self, ParamError> {
        let CollisionSettings {
            threshold,
            release_threshold,
            debounce,
            release,
            reaction,
        } = settings;
        positive("threshold", threshold)?;
        if threshold > 30_000.0 {
            return Err(ParamError::OutOfRange {
                name: "threshold",
                value: threshold,
                min: 0.0,
                max: 30_000.0,
            });
        }
        positive("release_threshold", release_threshold)?;
        if release_threshold > threshold {
            return Err(ParamError::Exceeds {
                lower: "release_threshold",
                lower_value: release_threshold,
                upper: "threshold",
                upper_value: threshold,
            });
        }
        for (name, v) in [("debounce", debounce), ("release", release)] {
            if v == 0 {
                return Err(ParamError::NotPositive { name, value: 0.0 });
            }
        }
        Ok(CollisionParams {
            threshold,
            release_threshold,
            debounce,
            release,
            reaction,
        })
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> CollisionSettings {
        CollisionSettings {
            threshold: self.threshold,
            release_threshold: self.release_threshold,
            debounce: self.debounce,
            release: self.release,
            reaction: self.reaction,
        }
    }

    /// Detection threshold, N·m.
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// Release threshold, N·m.
    pub fn release_threshold(&self) -> f64 {
        self.release_threshold
    }

    /// Samples over the threshold that detect.
    pub fn debounce(&self) -> u16 {
        self.debounce
    }

    /// Samples under the release threshold that release.
    pub fn release(&self) -> u16 {
        self.release
    }

    /// The configured reaction.
    pub fn reaction(&self) -> CollisionReaction {
        self.reaction
    }
}

/// The detector quantized for backend `S` (thresholds in stored link-torque
/// units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionConfig<S> {
    threshold: S,
    release_threshold: S,
    debounce: u16,
    release: u16,
    reaction: CollisionReaction,
}

/// Detector state: the latched flag and the run length of the current
/// condition.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CollisionState {
    detected: bool,
    count: u16,
}

impl CollisionState {
    /// `true` while a collision is latched.
    pub fn detected(&self) -> bool {
        self.detected
    }
}

/// One detector step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionOutput<S> {
    /// `τ̂_t − τ_expected`, stored link-torque units (saturating).
    pub residual: S,
    /// A collision is latched.
    pub detected: bool,
    /// It was detected at this sample (rising edge).
    pub onset: bool,
    /// An input was NaN: treated as a collision (fail safe).
    pub invalid_input: bool,
}

impl<S: Scalar> CollisionConfig<S> {
    /// Quantize validated parameters.
    pub fn new(p: &CollisionParams) -> Self {
        let lt = S::UNITS.link_torque;
        CollisionConfig {
            threshold: S::from_f64(p.threshold * lt),
            release_threshold: S::from_f64(p.release_threshold * lt),
            debounce: p.debounce,
            release: p.release,
            reaction: p.reaction,
        }
    }

    /// The configured reaction.
    pub fn reaction(&self) -> CollisionReaction {
        self.reaction
    }

    /// One sample: the estimated and the expected joint torque (stored
    /// link-torque units). A NaN input counts as over the threshold.
    pub fn update(&self, st: &mut CollisionState, estimated: S, expected: S) -> CollisionOutput<S> {
        let residual = estimated.sub(expected);
        let invalid = residual.is_nan();
        let mag = residual.abs();
        let was = st.detected;
        if !st.detected {
            // Over the threshold or NaN, in one comparison (`<=` is false
            // for NaN).
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            let over = !(mag <= self.threshold);
            if over {
                st.count = st.count.saturating_add(1);
                if st.count >= self.debounce {
                    st.detected = true;
                    st.count = 0;
                }
            } else {
                st.count = 0;
            }
        } else if mag < self.release_threshold {
            // Under the release threshold (false for NaN).
            st.count = st.count.saturating_add(1);
            if st.count >= self.release {
                st.detected = false;
                st.count = 0;
            }
        } else {
            st.count = 0;
        }
        CollisionOutput {
            residual: if invalid { S::ZERO } else { residual },
            detected: st.detected,
            onset: st.detected && !was,
            invalid_input: invalid,
        }
    }
}

#[cfg(any(kani, test))]
mod words {
    use super::{CollisionConfig, CollisionReaction};
    #[cfg(test)]
    use crate::scalar::words::Sink;
    use crate::scalar::{words::Words, I16F16};

    impl CollisionConfig<I16F16> {
        pub(crate) const fn take(r: &mut Words) -> Self {
            CollisionConfig {
                threshold: r.fixed(),
                release_threshold: r.fixed(),
                debounce: r.u16(),
                release: r.u16(),
                reaction: if r.bool() {
                    CollisionReaction::Passive
                } else {
                    CollisionReaction::Stop
                },
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            s.fixed(self.threshold);
            s.fixed(self.release_threshold);
            s.u32(self.debounce.into());
            s.u32(self.release.into());
            s.bool(self.reaction == CollisionReaction::Passive);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;
    use proptest::prelude::*;

    /// Thresholds 2 and 1 N·m, the given counts.
    fn settings(debounce: u16, release: u16, reaction: CollisionReaction) -> CollisionSettings {
        CollisionSettings {
            threshold: 2.0,
            release_threshold: 1.0,
            debounce,
            release,
            reaction,
        }
    }

    fn det(debounce: u16, release: u16) -> CollisionConfig<I16F16> {
        CollisionConfig::new(
            &CollisionParams::try_new(settings(debounce, release, CollisionReaction::Stop))
                .unwrap(),
        )
    }

    /// Each named setting reaches its own getter and its own role in the
    /// detector: with debounce 3 and release 1 (the old positional order
    /// swapped would give 1 and 3) detection takes three samples and the
    /// release one. (Thresholds are ordered by validation; the counts, both
    /// `u16`, were not.)
    #[test]
    fn named_settings_reach_their_getters_and_roles() {
        let s = CollisionSettings {
            threshold: 5.0,
            release_threshold: 2.5,
            debounce: 3,
            release: 1,
            reaction: CollisionReaction::Passive,
        };
        let p = CollisionParams::try_new(s).unwrap();
        assert_eq!(
            (
                p.threshold(),
                p.release_threshold(),
                p.debounce(),
                p.release()
            ),
            (5.0, 2.5, 3, 1)
        );
        assert_eq!(p.reaction(), CollisionReaction::Passive);
        assert_eq!(p.settings(), s);
        let c = CollisionConfig::<f64>::new(&p);
        let mut st = CollisionState::default();
        let seq = [6.0, 6.0, 6.0, 4.0, 2.0];
        let got: Vec<bool> = seq
            .iter()
            .map(|&r| c.update(&mut st, r, 0.0).detected)
            .collect();
        // Over 5 three times: detected on the third; 4 is between the
        // thresholds (stays); 2 < 2.5 once releases.
        assert_eq!(got, [false, false, true, true, false]);
    }

    #[test]
    fn debounce_and_hysteresis() {
        let c = det(3, 2);
        let mut st = CollisionState::default();
        let f = I16F16::from_f64;
        // Two samples over the threshold, then one under: no detection.
        for (tau, want) in [(2.5, false), (2.5, false), (0.0, false)] {
            assert_eq!(c.update(&mut st, f(tau), f(0.0)).detected, want);
        }
        // Three in a row (negative residual counts too): detected on the 3rd.
        let outs: Vec<_> = [-2.5, -3.0, -2.1]
            .iter()
            .map(|&t| c.update(&mut st, f(t), f(0.0)))
            .collect();
        assert!(!outs[1].detected && outs[2].detected && outs[2].onset);
        // Between the thresholds it stays latched; below the release
        // threshold for two samples it releases.
        assert!(c.update(&mut st, f(1.5), f(0.0)).detected);
        assert!(c.update(&mut st, f(0.5), f(0.0)).detected);
        assert!(!c.update(&mut st, f(0.5), f(0.0)).detected);
        // The expected torque is subtracted.
        let mut st = CollisionState::default();
        for _ in 0..5 {
            assert!(!c.update(&mut st, f(10.0), f(9.0)).detected);
        }
    }

    #[test]
    fn rejects_inverted_thresholds_and_zero_counts() {
        assert!(matches!(
            CollisionParams::try_new(CollisionSettings {
                threshold: 1.0,
                release_threshold: 2.0,
                ..settings(1, 1, CollisionReaction::Passive)
            }),
            Err(ParamError::Exceeds { .. })
        ));
        assert!(matches!(
            CollisionParams::try_new(settings(0, 1, CollisionReaction::Passive)),
            Err(ParamError::NotPositive {
                name: "debounce",
                ..
            })
        ));
    }

    #[test]
    fn nan_is_a_collision() {
        let c = CollisionConfig::<f32>::new(
            &CollisionParams::try_new(settings(1, 1, CollisionReaction::Stop)).unwrap(),
        );
        let mut st = CollisionState::default();
        let o = c.update(&mut st, f32::NAN, 0.0);
        assert!(o.detected && o.invalid_input && o.residual == 0.0);
        // While detected, a NaN does not count towards the release: it
        // restarts the run of samples under the release threshold.
        let c = CollisionConfig::<f32>::new(
            &CollisionParams::try_new(settings(1, 2, CollisionReaction::Stop)).unwrap(),
        );
        let mut st = CollisionState::default();
        let seq = [f32::NAN, 0.0, f32::NAN, 0.0, 0.0];
        let detected: Vec<bool> = seq
            .iter()
            .map(|&r| c.update(&mut st, r, 0.0).detected)
            .collect();
        assert_eq!(detected, [true, true, true, true, false]);
    }

    /// The validated ranges at their edges: the largest threshold,
    /// 30 000 N·m, and a release threshold equal to the threshold are
    /// accepted; the next `f64` above either is rejected by name.
    #[test]
    fn threshold_ranges_are_closed_at_their_edges() {
        let with = |threshold: f64, release_threshold: f64| {
            CollisionParams::try_new(CollisionSettings {
                threshold,
                release_threshold,
                ..settings(1, 1, CollisionReaction::Stop)
            })
        };
        let above = |x: f64| f64::from_bits(x.to_bits() + 1);
        assert_eq!(with(30_000.0, 1.0).unwrap().threshold(), 30_000.0);
        for t in [above(30_000.0), 1e6] {
            assert_eq!(
                with(t, 1.0),
                Err(ParamError::OutOfRange {
                    name: "threshold",
                    value: t,
                    min: 0.0,
                    max: 30_000.0,
                })
            );
        }
        assert_eq!(with(2.0, 2.0).unwrap().release_threshold(), 2.0);
        assert_eq!(
            with(2.0, above(2.0)),
            Err(ParamError::Exceeds {
                lower: "release_threshold",
                lower_value: above(2.0),
                upper: "threshold",
                upper_value: 2.0,
            })
        );
    }

    /// `release` reaches its getter (a value other than 1), and the
    /// state's `detected` follows the latch: false at rest, true from
    /// detection, false again after release. A residual exactly at the
    /// release threshold is not under it and keeps the latch; one LSB
    /// below it releases.
    #[test]
    fn release_count_and_latched_state_are_visible() {
        let p = CollisionParams::try_new(settings(1, 4, CollisionReaction::Stop)).unwrap();
        assert_eq!(p.release(), 4);
        let c = det(1, 1);
        let f = I16F16::from_f64;
        let mut st = CollisionState::default();
        assert!(!st.detected());
        c.update(&mut st, f(2.5), f(0.0));
        assert!(st.detected());
        for _ in 0..3 {
            assert!(c.update(&mut st, f(1.0), f(0.0)).detected);
            assert!(st.detected());
        }
        let just_under = I16F16::from_bits(f(1.0).to_bits() - 1);
        assert!(!c.update(&mut st, just_under, f(0.0)).detected);
        assert!(!st.detected());
    }

    proptest! {
        /// Against a direct model of the specification over random
        /// residual sequences: detection exactly after `debounce`
        /// consecutive samples over the threshold, release after `release`
        /// consecutive samples under the release threshold.
        #[test]
        fn matches_the_specification(seq in proptest::collection::vec(-4.0f64..4.0, 1..200),
                                     debounce in 1u16..5, release in 1u16..5) {
            let c = CollisionConfig::<f64>::new(
                &CollisionParams::try_new(settings(debounce, release, CollisionReaction::Passive)).unwrap());
            let mut st = CollisionState::default();
            let (mut latched, mut run_hi, mut run_lo) = (false, 0u16, 0u16);
            for r in seq {
                let o = c.update(&mut st, r, 0.0);
                if latched {
                    run_lo = if r.abs() < 1.0 { run_lo + 1 } else { 0 };
                    if run_lo >= release { latched = false; run_lo = 0; }
                } else {
                    run_hi = if r.abs() > 2.0 { run_hi + 1 } else { 0 };
                    if run_hi >= debounce { latched = true; run_hi = 0; }
                }
                prop_assert_eq!(o.detected, latched);
            }
        }
    }
}
