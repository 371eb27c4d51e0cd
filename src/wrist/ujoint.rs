//! The standard (Cardan) universal joint, thesis eq. (5.1)–(5.3): how the
//! inner universal joint of the wrist transmits the motor-2 shaft angle
//! `θ2` to `θ3` when its axles are bent by `β`.
//!
//! Conventions: `θ3` is the input-side (driving) angle, `θ2` the output
//! side, both in rad and zero together; `β` (rad) is the bend between the
//! axles, `|β| < π/2`. Eq. (5.1) is
//! `θ2 = atan2(cos β sin θ3, cos θ3)`; eq. (5.2) is its derivative in time
//! and eq. (5.3) the torque ratio that conserves power, `τ2 ω2 = τ3 ω3`
//! (the joint is lossless).
//!
//! The bend is limited to [`MAX_BEND`] (85°): beyond it `cos β` is too
//! small for a physical joint; larger inputs are clamped and flagged.

use super::kinematics::denan;
use crate::scalar::Scalar;

/// Largest accepted bend of the joint (rad), 85°.
pub const MAX_BEND: f64 = 85.0 * core::f64::consts::PI / 180.0;

/// Output of the universal-joint transmission.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transmission<S> {
    /// Output angle `θ2` (rad), eq. (5.1), in `(−π, π]` plus the whole
    /// turns of the input (so it follows `θ3` without jumps).
    pub angle: S,
    /// Output speed `ω2` (rad/s), eq. (5.2).
    pub speed: S,
    /// Output torque `τ2` (unit of the input torque), eq. (5.3).
    pub torque: S,
    /// The bend was outside `[−MAX_BEND, MAX_BEND]` (or NaN) and was clamped.
    pub saturated: bool,
}

/// Eq. (5.1)–(5.3): the output angle, speed and torque for input angle
/// `theta3` (rad), speed `omega3` (rad/s) and torque `tau3`, bend `beta`
/// (rad). Never NaN (NaN and infinite inputs are read as 0); the speed
/// and torque gains are at most `1/cos(MAX_BEND)` = 11.5.
pub fn transmit<S: Scalar>(beta: S, theta3: S, omega3: S, tau3: S) -> Transmission<S> {
    let lim = S::from_f64(MAX_BEND);
    let b0 = denan(beta);
    let b = b0.clamp(lim.neg(), lim);
    let saturated = b != beta || denan(theta3) != theta3;
    let cb = b.cos();
    let t3 = denan(theta3);
    // The wrapped part goes through atan2, the whole turns are added back.
    let w = wrap_any(t3);
    let (s3, c3) = w.sin_cos();
    // Eq. (5.1).
    let angle = cb.mul(s3).atan2(c3).add(t3.sub(w));
    // Eq. (5.2): ω2 = ω3 cos β / (cos²θ3 + cos²β sin²θ3).
    let den = c3.mul(c3).add(cb.mul(cb).mul(s3).mul(s3));
    let speed = denan(omega3).mul(cb).div(den);
    // Eq. (5.3): τ2 = (cos²β sin²θ3 + cos²θ3)/cos β · τ3.
    let torque = den.div(cb).mul(denan(tau3));
    Transmission {
        angle,
        speed,
        torque,
        saturated,
    }
}

/// `x` reduced to `[−π, π]` for any `x`, through `(sin x, cos x)`.
fn wrap_any<S: Scalar>(x: S) -> S {
    let (s, c) = x.sin_cos();
    s.atan2(c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;
    use proptest::prelude::*;

    /// Reference: the joint's output angle from its geometry (the output
    /// fork stays perpendicular to the input fork), by a different route:
    /// tan θ2 = cos β tan θ3 on the same half-turn.
    fn reference_angle(beta: f64, t3: f64) -> f64 {
        let base = libm::round(t3 / core::f64::consts::PI) * core::f64::consts::PI;
        let r = t3 - base; // (−π/2, π/2]
        base + (beta.cos() * r.tan()).atan()
    }

    proptest! {
        #[test]
        fn angle_speed_and_torque_agree_with_geometry_and_finite_differences(
            beta in -1.4f64..1.4, t3 in -7.0f64..7.0, w3 in -5.0f64..5.0, tau in -3.0f64..3.0,
        ) {
            let r = transmit(beta, t3, w3, tau);
            prop_assert!(!r.saturated);
            let half = core::f64::consts::FRAC_PI_2;
            let near_pole = ((t3 / half).round() as i64 % 2 != 0) && (t3 - (t3 / half).round() * half).abs() < 1e-3;
            if !near_pole {
                prop_assert!((r.angle - reference_angle(beta, t3)).abs() < 1e-12, "{} {}", r.angle, reference_angle(beta, t3));
            }
            // Eq. (5.2) is the derivative of eq. (5.1).
            let h = 1e-6;
            let fd = (transmit(beta, t3 + h, 0.0, 0.0).angle - transmit(beta, t3 - h, 0.0, 0.0).angle) / (2.0 * h);
            prop_assert!((r.speed - w3 * fd).abs() < 1e-6 * (1.0 + w3.abs() * fd.abs()));
            // Eq. (5.3): power is conserved.
            prop_assert!((r.torque * r.speed - tau * w3).abs() < 1e-9 * (1.0 + (tau * w3).abs()));
        }
    }

    #[test]
    fn clamps_the_bend_and_never_returns_nan() {
        let r = transmit(2.0f64, 0.3, 1.0, 1.0);
        assert!(r.saturated);
        let r = transmit(f64::NAN, f64::NAN, f64::NAN, f64::NAN);
        assert!(r.saturated && r.angle == 0.0 && r.speed == 0.0 && r.torque == 0.0);
        let q = |x: f64| I16F16::from_f64(x);
        let r = transmit(q(0.5), q(1.0), q(2.0), q(1.0));
        let e = transmit(0.5f64, 1.0, 2.0, 1.0);
        assert!((r.angle.to_f64() - e.angle).abs() < 4e-4);
        assert!((r.speed.to_f64() - e.speed).abs() < 1e-3);
        assert!((r.torque.to_f64() - e.torque).abs() < 1e-3);
        // Straight joint: identity.
        let r = transmit(0.0f64, 2.5, 1.5, -0.5);
        assert!((r.angle - 2.5).abs() < 1e-15 && (r.speed - 1.5).abs() < 1e-15);
        assert!((r.torque + 0.5).abs() < 1e-15);
    }
}
