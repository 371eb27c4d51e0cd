//! Fixed-point unit scales: how the thesis's physical quantities are placed
//! into the `I16F16` range, and the resolution that leaves.
//!
//! `I16F16` spans `±32768` with a step of `2⁻¹⁶ ≈ 1.53e-5`. Storing every
//! quantity in plain SI units would not work: a harmonic-drive torsion of
//! `1e-5 rad` is below one LSB, a stiffness of `1.4e5 Nm/rad` (SHD-40,
//! Table 3.1) overflows, and a rotor inertia of `1.14e-5 kg·m²` (Table 4.1)
//! is less than one LSB. Each quantity therefore has a **unit scale** `s`:
//! the stored number is `value_SI · s`. Configurations (`XxxConfig<S>`)
//! multiply by the scale once, at build time, with [`quantize`]. Each backend
//! names its scales in `S::UNITS`: floats use [`SI`] (every scale 1) and
//! `I16F16` uses [`FIXED`], so one generic code path serves every backend
//! and a float configuration stores plain SI values.
//!
//! Consequences, computed by [`QUANTITIES`] and printed by
//! `cargo run --release --example kernel_report` (relative error = the
//! quantization error of the thesis value in that unit):
//!
//! | quantity | thesis range | unit (scale) | range in SI | resolution in SI | worst relative quantization of a thesis value |
//! |---|---|---|---|---|---|
//! | link torque | 0.3 – 206 Nm | Nm (1) | ±32 768 Nm | 1.5e-5 Nm | 1.0e-5 (0.3 Nm) |
//! | motor torque | 0.012 – 0.188 Nm | mNm (1e3) | ±32.8 Nm | 1.5e-8 Nm | 0 |
//! | torsion | 1e-5 – 5e-3 rad | mrad (1e3) | ±32.8 rad | 1.5e-8 rad | 5.5e-4 (1e-5 rad) |
//! | link / motor angle | 1.7e-4 – 628 rad | rad (1) | ±32 768 rad | 1.5e-5 rad | 3.8e-2 (0.01°) |
//! | speed | 0.01 – 500 rad/s | rad/s (1) | ±32 768 rad/s | 1.5e-5 rad/s | 5.5e-4 (0.01 rad/s) |
//! | stiffness | 3.7e3 – 1.4e5 Nm/rad | Nm/mrad (1e-3) | ±3.3e7 Nm/rad | 0.015 Nm/rad | 8.3e-7 |
//! | rotor inertia | 1.05e-6 – 1.14e-5 kg·m² | mNm·s²/rad (1e3) | ±32.8 kg·m² | 1.5e-8 kg·m² | 2.7e-3 (Table 6.1) |
//! | gains λ, K_I, μ, ρ_base | 0.1 – 1e4 | SI (1) | ±32 768 | 1.5e-5 | 0 |
//! | boundary layers ε | 1e-4 – 0.1 | SI (1) | ±32 768 | 1.5e-5 | 6.8e-2 (ε_F1 = 1e-4) |
//!
//! Model constants that only ever multiply (`c_f`, `1/(c_f K_f0)`, `1/N`, …)
//! are not stored as `I16F16` values at all but as prepared
//! [`Coef`](super::Coef)s with a 31-bit mantissa, so their relative
//! precision is 2⁻³¹ whatever their magnitude.
//!
//! Two entries deserve care, and the components that use them say so: a
//! link angle at the 0.01° accuracy of the thesis's link encoder is only 11
//! LSB (angles come from encoder *counts*, which the estimators keep as
//! integers), and `ε_F1 = 1e-4` of Table 4.1 quantizes to `7·2⁻¹⁶ = 1.07e-4`
//! — a 7 % wider boundary layer, which is harmless for stability but must be
//! the value the ultimate-bound calculator uses, so configurations expose
//! their quantized values.
//!
//! Where a 16×16→32 multiply matters (Cortex-M0+), normalized Q15 quantities
//! are offered by [`q15`](super::q15).

use super::Scalar;

/// Link-side torque: stored in N·m.
pub const LINK_TORQUE: f64 = 1.0;
/// Motor-side torque: stored in mN·m.
pub const MOTOR_TORQUE: f64 = 1e3;
/// Harmonic-drive torsion and kinematic error: stored in mrad.
pub const TORSION: f64 = 1e3;
/// Joint angles (link or motor side): stored in rad.
pub const ANGLE: f64 = 1.0;
/// Angular speeds: stored in rad/s.
pub const SPEED: f64 = 1.0;
/// Torsional stiffness: stored in N·m/mrad.
pub const STIFFNESS: f64 = 1e-3;
/// Rotor inertia: stored in mN·m·s²/rad (so that inertia × acceleration is
/// a motor torque in mN·m).
pub const INERTIA: f64 = 1e3;

/// The unit scales a backend stores quantities with (`stored = SI · scale`).
///
/// Generic components convert at their boundaries with [`quantize`] /
/// [`dequantize`] using `S::UNITS`, and fold every scale ratio into their
/// configuration coefficients once, so the same code serves every backend.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Units {
    /// Link-side torque.
    pub link_torque: f64,
    /// Motor-side torque.
    pub motor_torque: f64,
    /// Harmonic-drive torsion and kinematic error.
    pub torsion: f64,
    /// Joint angles.
    pub angle: f64,
    /// Angular speeds.
    pub speed: f64,
    /// Torsional stiffness.
    pub stiffness: f64,
    /// Rotor inertia.
    pub inertia: f64,
}

/// Floats store plain SI values.
pub const SI: Units = Units {
    link_torque: 1.0,
    motor_torque: 1.0,
    torsion: 1.0,
    angle: 1.0,
    speed: 1.0,
    stiffness: 1.0,
    inertia: 1.0,
};

/// The scales of the table above, used by `I16F16`.
pub const FIXED: Units = Units {
    link_torque: LINK_TORQUE,
    motor_torque: MOTOR_TORQUE,
    torsion: TORSION,
    angle: ANGLE,
    speed: SPEED,
    stiffness: STIFFNESS,
    inertia: INERTIA,
};

/// `value_si · scale`, rounded to the backend (saturating, NaN → 0).
#[inline]
pub fn quantize<S: Scalar>(value_si: f64, scale: f64) -> S {
    S::from_f64(value_si * scale)
}

/// The SI value a stored number stands for.
#[inline]
pub fn dequantize<S: Scalar>(stored: S, scale: f64) -> f64 {
    stored.to_f64() / scale
}

/// Relative error of storing `value_si` (≠ 0) with `scale` in backend `S`.
pub fn relative_quantization_error<S: Scalar>(value_si: f64, scale: f64) -> f64 {
    let back = dequantize(quantize::<S>(value_si, scale), scale);
    ((back - value_si) / value_si).abs()
}

/// Half a step of backend `S` in the stored unit of `scale`, in SI: the
/// largest error of [`quantize`] for an in-range value (0 for floats,
/// which round relatively: `RESOLUTION/2` of the value).
pub fn half_step_si<S: Scalar>(scale: f64) -> f64 {
    if S::RESOLUTION.to_f64() >= 1e-6 {
        0.5 * S::RESOLUTION.to_f64() / scale
    } else {
        0.0
    }
}

// SI at the API boundary: one conversion per boundary type, applying
// `S::UNITS` (identity on floats), so that user code written once speaks
// N·m, rad and rad/s on every backend. The stored-unit fields stay public
// for firmware that wants them.

/// `value_si · scale` for backend `S` like [`quantize`], except that a
/// NaN or an infinity stays one on the float backends (so the step that
/// reads it flags it); fixed point, which has neither, saturates ±∞ to
/// `±MAX` and maps NaN to 0.
#[inline]
pub fn quantize_keep_non_finite<S: Scalar>(value_si: f64, scale: f64) -> S {
    let v = value_si * scale;
    if v.is_finite() {
        return S::from_f64(v);
    }
    // `MAX + MAX` is +∞ on floats and saturates to MAX on fixed point;
    // `∞ − ∞` is NaN on floats and 0 on fixed point.
    let inf = S::MAX.add(S::MAX);
    if v.is_nan() {
        inf.sub(inf)
    } else if v > 0.0 {
        inf
    } else {
        inf.neg()
    }
}

/// A physical quantity of the thesis, its unit scale and the values the
/// thesis uses (for reports and tests).
#[derive(Debug, Clone, Copy)]
pub struct Quantity {
    /// What it is.
    pub name: &'static str,
    /// The stored unit.
    pub unit: &'static str,
    /// Scale from SI to the stored unit.
    pub scale: f64,
    /// Representative thesis values, in SI units, with their source.
    pub thesis_values: &'static [(f64, &'static str)],
}

/// The quantities of the thesis and the scale each is stored with.
pub const QUANTITIES: &[Quantity] = &[
    Quantity {
        name: "link torque",
        unit: "N·m",
        scale: LINK_TORQUE,
        thesis_values: &[
            (0.3, "Table 3.3 error"),
            (16.0, "SHD-17 rated"),
            (206.0, "SHD-40-160 rated"),
        ],
    },
    Quantity {
        name: "motor torque",
        unit: "mN·m",
        scale: MOTOR_TORQUE,
        thesis_values: &[(0.012, "τ_fs"), (0.188, "Maxon 218014 max")],
    },
    Quantity {
        name: "torsion",
        unit: "mrad",
        scale: TORSION,
        thesis_values: &[
            (1e-5, "smallest torsion"),
            (2.9e-4, "Ψ"),
            (5e-3, "largest torsion"),
        ],
    },
    Quantity {
        name: "angle",
        unit: "rad",
        scale: ANGLE,
        thesis_values: &[
            (1.745e-4, "0.01° link encoder"),
            (628.3, "100 motor turns/rev"),
        ],
    },
    Quantity {
        name: "speed",
        unit: "rad/s",
        scale: SPEED,
        thesis_values: &[(0.01, "ε_q̇"), (1.56, "Table 3.3"), (500.0, "motor speed")],
    },
    Quantity {
        name: "stiffness",
        unit: "N·m/mrad",
        scale: STIFFNESS,
        thesis_values: &[
            (3.7e3, "SHD-14-50 K2"),
            (8.2e3, "K_f0"),
            (1.4e5, "SHD-40 K2"),
        ],
    },
    Quantity {
        name: "rotor inertia",
        unit: "mN·m·s²/rad",
        scale: INERTIA,
        thesis_values: &[(1.05e-6, "Table 6.1"), (1.14e-5, "Table 4.1")],
    },
    Quantity {
        name: "gains",
        unit: "SI",
        scale: 1.0,
        thesis_values: &[
            (0.1, "μ, ε_r"),
            (10.0, "K_I"),
            (160.0, "λ"),
            (1e4, "ρ_base"),
        ],
    },
    Quantity {
        name: "boundary layer",
        unit: "SI",
        scale: 1.0,
        thesis_values: &[(1e-4, "ε_F1"), (1e-3, "ε_F2"), (0.01, "ε_q̇")],
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::ControlInput;
    use crate::scalar::I16F16;

    /// The quantization error of each thesis value is at most half an LSB
    /// of the stored unit (computed independently from the LSB size), and
    /// every value fits the range.
    #[test]
    fn every_thesis_value_fits_with_half_lsb_error() {
        let lsb = 1.0 / 65536.0;
        for q in QUANTITIES {
            for &(v, src) in q.thesis_values {
                let stored = v * q.scale;
                assert!(stored.abs() < 32768.0, "{} {src} overflows", q.name);
                let rel = relative_quantization_error::<I16F16>(v, q.scale);
                let half_lsb_rel = 0.5 * lsb / stored.abs();
                assert!(
                    rel <= half_lsb_rel * (1.0 + 1e-9),
                    "{} {src}: {rel} > {half_lsb_rel}",
                    q.name
                );
            }
        }
    }

    /// One generic user function, written once in SI, gives the same SI
    /// numbers on f32, f64 and I16F16: the torque limit (188 mN·m; it used
    /// to read 0.188 on floats and 188 on fixed point), a sample's round
    /// trip through `from_si` (within half a stored step), the active law
    /// for a 1 mrad error (it used to read −0.170 vs −170.17), and a torque
    /// estimate (within its documented `AgreementBound`).
    #[test]
    fn one_generic_function_gives_the_same_si_numbers_on_every_backend() {
        use crate::control::{RobustAdaptiveConfig, RobustAdaptiveParams};
        use crate::estimation::{
            TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings,
        };
        use crate::harmonic_drive::CatalogueData;

        struct Si {
            limit: f64,
            round_trip: ControlInput<f64>,
            law: f64,
            estimate: f64,
        }
        fn user_code<S: Scalar>(x: &ControlInput<f64>, est: &TorqueEstimatorParams) -> Si {
            let law = RobustAdaptiveConfig::<S>::new(&RobustAdaptiveParams::table_4_1().unwrap());
            let mut st = law.initial_state();
            let input = ControlInput::<S>::from_si(x);
            let out = law.update(&mut st, &input);
            let cfg = TorqueEstimatorConfig::<S>::new(est);
            // A link count of 1000 with the motor 12 counts short of rigid.
            let mn = est.motor_counts_per_rev() as i64 * 100;
            let rigid = -(1000 * mn / est.link_counts_per_rev() as i64);
            let mut es = cfg.state(rigid - 12, 0);
            let e = cfg.update(&mut es, 1000, 0, S::from_f64(0.05 * S::UNITS.motor_torque));
            Si {
                limit: law.torque_limit_si(),
                round_trip: input.to_si(),
                law: out.torque_si(),
                estimate: e.torque_si(),
            }
        }
        let x = ControlInput {
            desired_position: 1.0,
            desired_velocity: 0.5,
            desired_acceleration: 2.0,
            motor_position: 1.001,
            motor_velocity: 0.5,
            joint_torque: 0.3,
            desired_joint_torque: 0.0,
            expected_joint_torque: 0.1,
        };
        let drive = CatalogueData::SHD_17_100.identify().unwrap();
        let est = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: 1 << 17,
            motor_counts_per_rev: 2000,
            max_torque: 60.0,
        })
        .unwrap();
        let a = user_code::<f64>(&x, &est);
        assert!((a.limit - 0.188).abs() < 1e-12, "{}", a.limit);
        assert!(
            a.law < -0.1 && a.estimate.abs() > 0.1,
            "{} {}",
            a.law,
            a.estimate
        );
        for (name, b, bound) in [
            (
                "f32",
                user_code::<f32>(&x, &est),
                est.agreement_bound::<f32>(),
            ),
            (
                "I16F16",
                user_code::<I16F16>(&x, &est),
                est.agreement_bound::<I16F16>(),
            ),
        ] {
            let half_mnm = half_step_si::<I16F16>(MOTOR_TORQUE).max(1e-7 * 0.188);
            assert!(
                (b.limit - a.limit).abs() <= half_mnm,
                "{name} limit {}",
                b.limit
            );
            let rt = |c: &ControlInput<f64>| {
                [
                    c.desired_position,
                    c.desired_velocity,
                    c.desired_acceleration,
                    c.motor_position,
                    c.motor_velocity,
                    c.joint_torque,
                    c.desired_joint_torque,
                    c.expected_joint_torque,
                ]
            };
            for (got, want) in rt(&b.round_trip).iter().zip(rt(&x)) {
                // Every scale of these fields is 1: half a step is 2⁻¹⁷.
                let tol = half_step_si::<I16F16>(1.0).max(2f64.powi(-24) * want.abs());
                assert!((got - want).abs() <= tol, "{name}: {got} vs {want}");
            }
            // The active law: 1 % of the limit catches any unit slip (a
            // factor of 1000); the derived per-backend budget is in the
            // law's own tests.
            assert!(
                (b.law - a.law).abs() <= 0.01 * a.limit,
                "{name} law {} vs {}",
                b.law,
                a.law
            );
            // The estimate: within the documented agreement bound.
            let cfg = TorqueEstimatorConfig::<f64>::new(&est);
            let mn = est.motor_counts_per_rev() as i64 * 100;
            let rigid = -(1000 * mn / est.link_counts_per_rev() as i64);
            let e = cfg.update(&mut cfg.state(rigid - 12, 0), 1000, 0, 0.05);
            assert_eq!(e.torque, a.estimate);
            let (lo, hi) = bound.torque_interval(&est, e.flexspline_torsion);
            assert!(
                lo <= b.estimate && b.estimate <= hi,
                "{name} {} not in [{lo}, {hi}]",
                b.estimate
            );
        }
    }

    /// A NaN or infinite SI value reaches a float step as such (so it is
    /// flagged), where `quantize` alone would have made it 0 or `MAX`
    /// silently; fixed point saturates.
    #[test]
    fn from_si_keeps_non_finite_values_on_floats() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let si = ControlInput {
                joint_torque: bad,
                ..Default::default()
            };
            let x = ControlInput::<f32>::from_si(&si);
            assert!(!x.is_finite());
            assert_eq!(x.joint_torque.is_nan(), bad.is_nan());
            assert!(!ControlInput::<f64>::from_si(&si).is_finite());
            let q = ControlInput::<I16F16>::from_si(&si).joint_torque;
            let want = if bad.is_nan() {
                I16F16::ZERO
            } else if bad > 0.0 {
                I16F16::MAX
            } else {
                -I16F16::MAX
            };
            assert_eq!(q, want);
        }
    }

    /// Without the scales, the thesis's small and large values do not fit.
    #[test]
    fn plain_si_would_lose_torsion_and_inertia() {
        assert_eq!(quantize::<I16F16>(1e-5 / 2.0, 1.0), I16F16::ZERO);
        assert_eq!(quantize::<I16F16>(1.4e5, 1.0), I16F16::MAX);
        assert!(relative_quantization_error::<I16F16>(1.14e-5, 1.0) > 0.3);
    }
}
