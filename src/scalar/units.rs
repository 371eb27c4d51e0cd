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

    /// Without the scales, the thesis's small and large values do not fit.
    #[test]
    fn plain_si_would_lose_torsion_and_inertia() {
        assert_eq!(quantize::<I16F16>(1e-5 / 2.0, 1.0), I16F16::ZERO);
        assert_eq!(quantize::<I16F16>(1.4e5, 1.0), I16F16::MAX);
        assert!(relative_quantization_error::<I16F16>(1.14e-5, 1.0) > 0.3);
    }
}
