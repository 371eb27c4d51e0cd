//! Multiple-mode joint control of thesis ch. 4.
//!
//! * [`adaptive`] — the robust adaptive law of eq. (4.15)–(4.19) with the
//!   adaptation law of Theorem 1 (projected onto known bounds), the
//!   integral term and joint-torque feedback (active mode).
//! * [`bound`] — the ultimate-bound calculator of eq. (4.28)–(4.31).
//! * [`passive`] — friction compensation with torque feedback, eq. (4.32),
//!   and the free-body behaviour of eq. (4.33) (errata E4.1).
//! * [`mode`] — a mode manager switching active ↔ passive on the
//!   interaction torque, bumplessly, and reacting to collisions detected by
//!   [`crate::estimation::collision`].
//!
//! Every step takes one [`ControlInput`] sample, so a simulator or firmware
//! fills one plain struct per joint and tick.
//!
//! # Sign conventions and units
//! Motor-side angles `q_m` (rad), speeds (rad/s) and accelerations
//! (rad/s²) are positive in the same direction as the motor torque `τ_m`.
//! The joint torque `τ_t` is the torque the transmission applies to the
//! link, as in eq. (4.1)–(4.2): `I_m q̈_m + f_m + τ_t/N = τ_m`, so a positive
//! `τ_t` loads the motor negatively. Values are stored in the units of
//! `S::UNITS` ([`crate::scalar::units`]): on `I16F16` motor torques are in
//! mN·m, joint torques in N·m, angles in rad, speeds in rad/s and
//! accelerations in rad/s² (the speed scale per second).

pub mod adaptive;
pub mod bound;
pub mod design;
pub mod mode;
pub mod passive;
mod si;

pub use adaptive::{
    ActiveOutput, RobustAdaptiveConfig, RobustAdaptiveDesign, RobustAdaptiveParams,
    RobustAdaptiveState, UncertaintyBounds,
};
pub use bound::UltimateBound;
pub use mode::{
    JointMode, ModeConfig, ModeOutput, ModeParams, ModeSettings, ModeState, ReleaseRule,
};
pub use passive::{
    HandContact, PassiveCharacteristics, PassiveConfig, PassiveOutput, PassiveParams,
    PassiveSettings, Pole,
};

/// One control sample of one joint, in stored units of `S::UNITS`.
///
/// Desired values are motor-side (eq. 4.15: `q_m^d`, `q̇_m^d`, `q̈_m^d`,
/// e.g. `N` times a link trajectory). The sampling period is a
/// configuration constant (each rate constant is folded with it into a
/// prepared coefficient, so the step needs no division and no `dt`
/// multiply in fixed point).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ControlInput<S> {
    /// Desired motor position `q_m^d`, stored angle units.
    pub desired_position: S,
    /// Desired motor speed `q̇_m^d`, stored speed units.
    pub desired_velocity: S,
    /// Desired motor acceleration `q̈_m^d`, stored speed units per second.
    pub desired_acceleration: S,
    /// Measured motor position `q_m`, stored angle units.
    pub motor_position: S,
    /// Measured (or observed) motor speed `q̇_m`, stored speed units.
    pub motor_velocity: S,
    /// Estimated (ch. 3) or measured joint torque `τ̂_t`, stored link-torque
    /// units, sign as in eq. (4.1).
    pub joint_torque: S,
    /// Desired joint torque `τ_td` of the passive law, eq. (4.32) (0 for a
    /// free joint), stored link-torque units.
    pub desired_joint_torque: S,
    /// Joint torque expected without interaction (gravity, payload,
    /// model), stored link-torque units; the interaction torque and the
    /// collision residual are `τ̂_t` minus this.
    pub expected_joint_torque: S,
}

impl<S: Scalar> ControlInput<S> {
    /// `true` when every field is a finite number (always for fixed point).
    #[inline]
    pub fn is_finite(&self) -> bool {
        S::all_finite(&[
            self.desired_position,
            self.desired_velocity,
            self.desired_acceleration,
            self.desired_joint_torque,
            self.expected_joint_torque,
            self.motor_position,
            self.motor_velocity,
            self.joint_torque,
        ])
    }

    /// [`is_finite`](Self::is_finite) for a sample whose motor position,
    /// motor speed and joint torque are known to be finite (the joint
    /// step measures them from counts and a finite estimate): the same
    /// test on the other five fields.
    #[inline]
    pub(crate) fn is_finite_but_measured(&self) -> bool {
        S::all_finite(&[
            self.desired_position,
            self.desired_velocity,
            self.desired_acceleration,
            self.desired_joint_torque,
            self.expected_joint_torque,
        ])
    }
}

use crate::scalar::Scalar;

/// `new` if it is a number, else `old` (state updates never store NaN);
/// the reference of [`clamp_or_keep`]'s test.
#[cfg(test)]
fn keep_number<S: Scalar>(new: S, old: S) -> S {
    if new.is_nan() {
        old
    } else {
        new
    }
}

/// `new` limited to `[lo, hi]` (`lo ≤ hi`), or `old` limited to it when
/// `new` is NaN, so a state update never stores NaN: equal to
/// `keep_number(new, old).clamp(lo, hi)` (test below), with two
/// comparisons on the common path instead of three (a NaN fails both
/// `new >= lo` and `new < lo`).
///
/// Kept as the reference of the symmetric form (the adapted estimates are
/// clamped by [`Scalar::integrate`], whose float form is this function of
/// `self + x·c`, checked in `float_integrate_is_clamp_or_keep`).
#[cfg(test)]
#[inline]
pub(crate) fn clamp_or_keep<S: Scalar>(new: S, old: S, lo: S, hi: S) -> S {
    if new >= lo {
        if new > hi {
            hi
        } else {
            new
        }
    } else if new < lo {
        lo
    } else {
        old.clamp(lo, hi)
    }
}

/// [`clamp_or_keep`] for the symmetric range `[−limit, limit]` (`0 ≤ limit <
/// MAX`), with one magnitude comparison on the common path: a NaN fails it
/// and both sign tests, and `|MIN|` saturates to `MAX` on fixed point and
/// takes the negative branch, as the two one-sided tests would.
///
/// A NaN `new` is first replaced by `old` (one select), so the same tests
/// limit both: a NaN `old` then fails all three and gives `−limit`, as
/// `clamp` maps NaN to its lower bound.
#[inline]
pub(crate) fn clamp_or_keep_symmetric<S: Scalar>(new: S, old: S, limit: S) -> S {
    if !S::FLOAT {
        // Fixed point (folded at compile time): no NaN, so no select; the
        // form whose Armv6-M code is the shortest.
        return if new.abs() <= limit {
            new
        } else if new > S::ZERO {
            limit
        } else if new < S::ZERO {
            limit.neg()
        } else {
            old.clamp(limit.neg(), limit)
        };
    }
    let w = if new.is_nan() { old } else { new };
    if w.abs() <= limit {
        w
    } else if w > S::ZERO {
        limit
    } else {
        limit.neg()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;

    /// `is_finite` is exactly "every field is finite", including samples
    /// whose finite fields sum beyond the range (the slow path): every
    /// field position takes each special value among finite neighbours of
    /// either sign and size.
    #[test]
    fn is_finite_but_measured_equals_is_finite_for_finite_measurements() {
        let specials = [
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            -1.0,
            0.0,
        ];
        for fill in [0.0f32, 1.5, f32::MAX, f32::MIN] {
            for i in [0usize, 1, 2, 6, 7] {
                for &sp in &specials {
                    let mut v = [fill; 8];
                    v[i] = sp;
                    let x = sample(v);
                    assert_eq!(x.is_finite_but_measured(), x.is_finite(), "{i} {sp} {fill}");
                }
            }
        }
    }

    /// A control input from its eight fields in declaration order.
    fn sample<S: Scalar + Copy>(v: [S; 8]) -> ControlInput<S> {
        ControlInput {
            desired_position: v[0],
            desired_velocity: v[1],
            desired_acceleration: v[2],
            motor_position: v[3],
            motor_velocity: v[4],
            joint_torque: v[5],
            desired_joint_torque: v[6],
            expected_joint_torque: v[7],
        }
    }

    #[test]
    fn is_finite_is_every_field_finite() {
        let fills = [0.0f32, 1.5, -2.0, f32::MAX, f32::MIN, 3e38];
        let specials = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, f32::MAX, -1.0];
        for &fill in &fills {
            let base = [fill; 8];
            assert!(sample(base).is_finite(), "all {fill}");
            for i in 0..8 {
                for &sp in &specials {
                    let mut v = base;
                    v[i] = sp;
                    let want = v.iter().all(|x| x.is_finite());
                    assert_eq!(sample(v).is_finite(), want, "field {i} = {sp}, fill {fill}");
                    let v64 = v.map(f64::from);
                    assert_eq!(sample(v64).is_finite(), want);
                }
            }
        }
        // Infinities of both signs cancel to NaN, still rejected.
        let mut v = [0.0f64; 8];
        v[0] = f64::INFINITY;
        v[7] = f64::NEG_INFINITY;
        assert!(!sample(v).is_finite());
        assert!(sample([I16F16::MAX; 8]).is_finite());
    }

    /// `I16F16` codes for the clamp tests: the extremes, ±1 LSB, ±1 and
    /// values just beyond ±1.
    const FX_SPECIAL: [i32; 10] = [
        i32::MIN,
        i32::MIN + 1,
        -70_000,
        -65_536,
        -1,
        0,
        1,
        65_536,
        70_000,
        i32::MAX,
    ];

    #[test]
    fn clamp_or_keep_equals_keep_then_clamp() {
        let vals = [
            f32::NAN,
            f32::NEG_INFINITY,
            -3.0,
            -1.0,
            -0.5,
            -0.0,
            0.0,
            0.5,
            1.0,
            3.0,
            f32::INFINITY,
        ];
        for &new in &vals {
            for &old in &vals[1..] {
                for (lo, hi) in [(-1.0f32, 1.0f32), (0.0, 0.0), (-0.0, 2.0), (0.5, 1.0)] {
                    let want = Scalar::clamp(keep_number(new, old), lo, hi);
                    let got = clamp_or_keep(new, old, lo, hi);
                    assert_eq!(got.to_bits(), want.to_bits(), "{new} {old} {lo} {hi}");
                }
            }
        }
        let fx = FX_SPECIAL.map(I16F16::from_bits);
        let b = I16F16::from_bits;
        for &new in &fx {
            for &old in &fx {
                for (lo, hi) in [
                    (b(-65_536), b(65_536)),
                    (b(0), b(0)),
                    (b(i32::MIN), b(i32::MAX)),
                ] {
                    let want = Scalar::clamp(keep_number(new, old), lo, hi);
                    assert_eq!(clamp_or_keep(new, old, lo, hi), want);
                }
            }
        }
    }

    /// The float form of `Scalar::integrate` is `clamp_or_keep` of the
    /// sum (with a unit coefficient the step is `x` exactly), with residual
    /// 0 whenever the sum was clamped or NaN, on the special values (as
    /// numbers: `−0.0` may come out as `+0.0`).
    #[test]
    fn float_integrate_is_clamp_or_keep() {
        let vals = [
            f32::NAN,
            f32::NEG_INFINITY,
            -3.0,
            -1.0,
            -0.5,
            -0.0,
            0.0,
            0.5,
            1.0,
            3.0,
            f32::INFINITY,
        ];
        let one = crate::scalar::Coef::new(1.0);
        for &x in &vals {
            for &old in &vals[1..] {
                for (lo, hi) in [(-1.0f32, 1.0f32), (0.0, 0.0), (-0.0, 2.0), (0.5, 1.0)] {
                    let old = Scalar::clamp(old, lo, hi);
                    let want = clamp_or_keep(old + x, old, lo, hi);
                    let (got, res) = old.integrate(0.0, x, &one, lo, hi);
                    // Equal as numbers (the residual's `+0.0` may turn a
                    // `−0.0` sum into `+0.0`).
                    assert!(got == want, "{x} {old} {lo} {hi}: {got} vs {want}");
                    if !(old + x >= lo && old + x <= hi) {
                        assert_eq!(res, 0.0);
                    }
                    let (got64, ()) =
                        (old as f64).integrate((), x as f64, &one, lo as f64, hi as f64);
                    let want64 =
                        clamp_or_keep(old as f64 + x as f64, old as f64, lo as f64, hi as f64);
                    assert_eq!(got64.to_bits(), want64.to_bits());
                }
            }
        }
    }

    /// The symmetric form equals `clamp_or_keep(new, old, −limit, limit)`
    /// on the same special values, with limits 0, 1 LSB / the smallest
    /// subnormal, 1 and one code below `MAX`.
    #[test]
    fn clamp_or_keep_symmetric_equals_the_two_sided_form() {
        let vals = [
            f32::NAN,
            f32::NEG_INFINITY,
            f32::MIN,
            -3.0,
            -1.0,
            -0.5,
            -f32::from_bits(1),
            -0.0,
            0.0,
            f32::from_bits(1),
            0.5,
            1.0,
            3.0,
            f32::MAX,
            f32::INFINITY,
        ];
        // A NaN `old` too (a state outside its contract): both give `−l`.
        for &new in &vals {
            for &old in &vals {
                for l in [
                    0.0f32,
                    f32::from_bits(1),
                    1.0,
                    f32::from_bits(f32::MAX.to_bits() - 1),
                ] {
                    let want = clamp_or_keep(new, old, -l, l);
                    let got = clamp_or_keep_symmetric(new, old, l);
                    assert_eq!(got.to_bits(), want.to_bits(), "{new} {old} {l}");
                }
            }
        }
        let fx = FX_SPECIAL.map(I16F16::from_bits);
        for &new in &fx {
            for &old in &fx {
                for l in [0, 1, 65_536, i32::MAX - 1].map(I16F16::from_bits) {
                    let want = clamp_or_keep(new, old, l.neg(), l);
                    assert_eq!(
                        clamp_or_keep_symmetric(new, old, l),
                        want,
                        "{new} {old} {l}"
                    );
                }
            }
        }
    }
}
