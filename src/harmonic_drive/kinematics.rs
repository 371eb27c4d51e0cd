//! Rigid kinematics and statics of a harmonic drive (thesis §2.2.1–2.2.2)
//! and the torsion measured by a motor-side and a link-side encoder.
//!
//! Sign convention (thesis eq. 2.1–2.6): with the circular spline fixed, the
//! wave generator (motor) turns `-N` times the flexspline (link), so
//! `θ_w = -N θ_f`, and the torque balance is `τ_w = -τ_f / N`. Angles in rad,
//! angular speeds in rad/s, torques in N·m.

/// Wave-generator angle from the circular-spline and flexspline angles,
/// eq. (2.1): `θ_w = (N + 1) θ_c − N θ_f`.
pub fn wave_generator_angle(ratio: f64, circular_spline: f64, flexspline: f64) -> f64 {
    (ratio + 1.0) * circular_spline - ratio * flexspline
}

/// Wave-generator speed, eq. (2.2): `ω_w = (N + 1) ω_c − N ω_f` (the time
/// derivative of eq. 2.1; the same function as [`wave_generator_angle`]).
pub fn wave_generator_speed(ratio: f64, circular_spline: f64, flexspline: f64) -> f64 {
    wave_generator_angle(ratio, circular_spline, flexspline)
}

/// Static torques on the three members for a given flexspline torque,
/// eq. (2.3): `τ_w = τ_c / (N + 1) = −τ_f / N`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticTorques {
    /// Wave-generator torque `τ_w`, N·m.
    pub wave_generator: f64,
    /// Circular-spline (reaction) torque `τ_c`, N·m.
    pub circular_spline: f64,
    /// Flexspline torque `τ_f`, N·m.
    pub flexspline: f64,
}

/// Eq. (2.3): the torques that balance a flexspline torque `τ_f`.
pub fn static_torques(ratio: f64, flexspline_torque: f64) -> StaticTorques {
    let tw = -flexspline_torque / ratio;
    StaticTorques {
        wave_generator: tw,
        circular_spline: (ratio + 1.0) * tw,
        flexspline: flexspline_torque,
    }
}

/// Eq. (2.9): wave-generator torque with a friction torque `τ_fr` in the
/// drive, `τ_w = −(τ_f − τ_fr) / N`; with `τ_fr = 0` this is eq. (2.6).
pub fn wave_generator_torque(ratio: f64, flexspline_torque: f64, friction_torque: f64) -> f64 {
    -(flexspline_torque - friction_torque) / ratio
}

/// Ideal flexspline angle for a wave-generator angle with the circular
/// spline fixed, eq. (2.4)/(2.7)/(2.20): `θ_fi = −θ_w / N`.
pub fn ideal_flexspline_angle(ratio: f64, wave_generator: f64) -> f64 {
    -wave_generator / ratio
}

/// Ideal flexspline speed for a wave-generator speed with the circular
/// spline fixed, eq. (2.8): `ω_fi = −ω_w / N` (rad/s; the time derivative of
/// eq. 2.7).
pub fn ideal_flexspline_speed(ratio: f64, wave_generator_speed: f64) -> f64 {
    -wave_generator_speed / ratio
}

/// Harmonic-drive torsion from the two encoders, eq. (2.13)/(2.21):
/// `Δθ = θ_fo + θ_wi / N` (rad, output side), where `θ_fo` is the link-side
/// (flexspline output) angle and `θ_wi` the motor-side (wave-generator
/// input) angle. By eq. (2.22)–(2.23) this equals `Δθ_f − Δθ_w / N`.
pub fn torsion_from_encoders(ratio: f64, link_angle: f64, motor_angle: f64) -> f64 {
    link_angle + motor_angle / ratio
}

/// Eq. (2.23): total torsion from the flexspline torsion `Δθ_f` (2.18) and
/// the wave-generator torsion `Δθ_w` (2.19): `Δθ = Δθ_f − Δθ_w / N`.
pub fn total_torsion(ratio: f64, flexspline_torsion: f64, wave_generator_torsion: f64) -> f64 {
    flexspline_torsion - wave_generator_torsion / ratio
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Eq. (2.22): adding and subtracting θ_fi and θ_wo/N in (2.21),
        /// with θ_wo = −N θ_fi (2.20), gives (2.23) for any member angles.
        #[test]
        fn encoder_torsion_decomposes_into_member_torsions(
            ratio in 30.0f64..200.0, fo in -7.0f64..7.0, fi_off in -5e-3f64..5e-3, wi_off in -0.5f64..0.5,
        ) {
            let fi = fo - fi_off;              // θ_fi
            let wo = -ratio * fi;              // eq. (2.20)
            let wi = wo - wi_off;              // θ_wi
            let d_f = fo - fi;                 // eq. (2.18)
            let d_w = wo - wi;                 // eq. (2.19)
            let lhs = torsion_from_encoders(ratio, fo, wi);
            let rhs = total_torsion(ratio, d_f, d_w);
            prop_assert!((lhs - rhs).abs() <= 1e-12 * (1.0 + fo.abs() + wi.abs() / ratio));
        }

        /// Eq. (2.8) is the derivative of eq. (2.7): a central difference
        /// of the ideal flexspline angle along a wave-generator trajectory
        /// θ_w(t) = a sin(ωt) matches the speed map.
        #[test]
        fn ideal_speed_is_the_derivative_of_the_ideal_angle(
            ratio in 1.0f64..300.0, a in 0.1f64..50.0, w in 0.1f64..20.0, t in 0.0f64..10.0,
        ) {
            let h = 1e-5;
            let angle = |t: f64| ideal_flexspline_angle(ratio, a * (w * t).sin());
            let fd = (angle(t + h) - angle(t - h)) / (2.0 * h);
            let exact = ideal_flexspline_speed(ratio, a * w * (w * t).cos());
            // Central-difference truncation a w³ h² / 6 / N; rounding of
            // t ± h (ulp(t) ≤ ε t) moves the phase, an error of up to
            // a w² ε t / h / N; and the sums' own rounding.
            let eps = f64::EPSILON;
            let tol = (a * w.powi(3) * h * h / 6.0 + a * w * w * eps * (t + 1.0) / h
                + 4.0 * eps * a / h) / ratio;
            prop_assert!((fd - exact).abs() <= tol, "{fd} vs {exact}");
        }

        /// With θ_c = 0, eq. (2.1) reduces to (2.4) and the rigid drive has
        /// zero torsion.
        #[test]
        fn fixed_circular_spline_reduces_to_eq_2_4(ratio in 1.0f64..300.0, f in -10.0f64..10.0) {
            let w = wave_generator_angle(ratio, 0.0, f);
            prop_assert!((w + ratio * f).abs() <= 1e-12 * (1.0 + w.abs()));
            prop_assert!((ideal_flexspline_angle(ratio, w) - f).abs() <= 1e-12 * (1.0 + f.abs()));
            prop_assert!(torsion_from_encoders(ratio, f, w).abs() <= 1e-12 * (1.0 + f.abs()));
        }

        /// Eq. (2.3) with eq. (2.2): τ_w is the torque applied to the wave
        /// generator and τ_c, τ_f the torques the drive delivers, so the
        /// lossless drive conserves power, τ_w ω_w = τ_c ω_c + τ_f ω_f, for
        /// any member speeds — an independent check of the two equations.
        #[test]
        fn static_balance_conserves_power(
            ratio in 1.0f64..300.0, tf in -200.0f64..200.0, wc in -5.0f64..5.0, wf in -5.0f64..5.0,
        ) {
            let t = static_torques(ratio, tf);
            prop_assert!((ratio * t.wave_generator + tf).abs() <= 1e-12 * (1.0 + tf.abs()));
            let ww = wave_generator_speed(ratio, wc, wf);
            let p_in = t.wave_generator * ww;
            let p_out = t.circular_spline * wc + t.flexspline * wf;
            prop_assert!((p_in - p_out).abs() <= 1e-9 * (1.0 + p_in.abs()));
            prop_assert_eq!(wave_generator_torque(ratio, tf, 0.0), t.wave_generator);
        }
    }
}
