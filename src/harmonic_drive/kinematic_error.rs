//! Kinematic error of a harmonic drive and its effect on torque estimation
//! (thesis §3.1, eq. 3.1–3.7, Tables 3.1–3.2).
//!
//! The kinematic error `θ_err` is the difference between the actual and the
//! rigid output angle at zero torque. It repeats once per output revolution
//! (link side) and once and twice per wave-generator revolution (motor side,
//! Nye & Kraml). The thesis models it with a truncated Fourier series,
//! eq. (3.3)–(3.7):
//!
//! ```text
//! θ_err = a_0 + a_l1 cos(w_l θ_fo) + b_l1 sin(w_l θ_fo)
//!             + Σ_{k=1,2} [ a_wk cos(k w_w θ_wi) + b_wk sin(k w_w θ_wi) ]
//! ```
//!
//! (eq. 3.5 and 3.7 print `θ_wo` in the `b_w1` term; it is `θ_wi`, errata E3.2).
//!
//! **Units of Table 3.2.** The table gives no units. Angles are in degrees:
//! `w_l = 0.01731` and `w_w = 0.01734` are within 1 % of `π/180`, i.e. one
//! cycle per 360° of link and of motor rotation, and the coefficients are in
//! degrees too — read as radians, the largest term (`b_l1 = −0.0043`) would
//! be ten times the catalogue's maximum kinematic error for this drive
//! (4.4e-4 rad, Table 3.1), whereas in degrees the modelled peak-to-peak
//! error, 3.33e-4 rad, lies within it (`table_3_2_is_in_degrees` checks both;
//! errata E3.3).
//!
//! [`KinematicErrorModel`] stores SI values (rad) with the harmonic counts as
//! integers per revolution, so the model is exactly periodic;
//! [`KinematicErrorFit`] fits it by linear least squares from samples of one
//! output revolution, without allocation.

use crate::error::{finite, in_range, ParamError};
use crate::scalar::Scalar;
use core::f64::consts::PI;
use nalgebra::{SMatrix, SVector};

/// One row of Table 3.1 (SHD series, Harmonic Drive catalogue data).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveSize {
    /// Size code (14, 17, 20, 25, 32, 40).
    pub size: u32,
    /// Gear ratio.
    pub ratio: u32,
    /// Rated torque, N·m.
    pub rated_torque: f64,
    /// Catalogue stiffness `K2`, N·m/rad.
    pub k2: f64,
    /// Maximum kinematic error, rad.
    pub max_kinematic_error: f64,
}

impl DriveSize {
    /// Eq. (3.1): torque estimation error caused by the kinematic error at
    /// the local stiffness `K2`, `τ_kerr = K2 θ_err` (N·m).
    pub fn kinematic_torque_error(&self) -> f64 {
        self.k2 * self.max_kinematic_error
    }

    /// Eq. (3.2): that error relative to the rated torque, in percent.
    pub fn relative_torque_error_percent(&self) -> f64 {
        self.kinematic_torque_error() / self.rated_torque * 100.0
    }
}

const fn row(size: u32, ratio: u32, rated: f64, k2_e4: f64, err_e4: f64) -> DriveSize {
    DriveSize {
        size,
        ratio,
        rated_torque: rated,
        k2: k2_e4 * 1e4,
        max_kinematic_error: err_e4 * 1e-4,
    }
}

/// The inputs of Table 3.1 (size, ratio, rated torque, `K2`, maximum
/// kinematic error); the table's last two columns are computed by
/// [`DriveSize::kinematic_torque_error`] and
/// [`DriveSize::relative_torque_error_percent`] (the printed ones are
/// truncated, errata E3.1).
pub const TABLE_3_1: [DriveSize; 16] = [
    row(14, 50, 3.7, 0.37, 4.4),
    row(14, 100, 5.4, 0.44, 4.4),
    row(17, 50, 11.0, 0.88, 4.4),
    row(17, 100, 16.0, 0.94, 4.4),
    row(20, 50, 17.0, 1.3, 2.9),
    row(20, 100, 28.0, 1.7, 2.9),
    row(20, 160, 28.0, 1.7, 2.9),
    row(25, 50, 27.0, 2.7, 2.9),
    row(25, 100, 47.0, 3.7, 2.9),
    row(25, 160, 47.0, 3.7, 2.9),
    row(32, 50, 53.0, 6.1, 2.9),
    row(32, 100, 96.0, 7.8, 2.9),
    row(32, 160, 96.0, 7.8, 2.9),
    row(40, 50, 96.0, 11.0, 2.9),
    row(40, 100, 185.0, 14.0, 2.9),
    row(40, 160, 206.0, 14.0, 2.9),
];

/// Table 3.2 exactly as printed (degrees, see the module docs), for
/// reference; [`KinematicErrorModel::table_3_2`] is its SI form.
pub mod table_3_2 {
    /// `a_0`, degrees.
    pub const A0: f64 = 0.0;
    /// `a_l1`, degrees.
    pub const A_L1: f64 = -0.0001476;
    /// `b_l1`, degrees.
    pub const B_L1: f64 = -0.004309;
    /// `w_l`, radians per degree of link angle.
    pub const W_L: f64 = 0.01731;
    /// `a_w1`, degrees.
    pub const A_W1: f64 = 0.001594;
    /// `b_w1`, degrees.
    pub const B_W1: f64 = -0.001891;
    /// `a_w2`, degrees.
    pub const A_W2: f64 = 0.003288;
    /// `b_w2`, degrees.
    pub const B_W2: f64 = 0.0009049;
    /// `w_w`, radians per degree of motor angle.
    pub const W_W: f64 = 0.01734;
}

/// The Fourier kinematic-error model of eq. (3.7), in SI units, with one
/// harmonic per output revolution and two per wave-generator revolution.
///
/// Built only by [`try_new`](Self::try_new), [`table_3_2`](Self::table_3_2)
/// or a [`KinematicErrorFit`], so its coefficients are finite and bounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicErrorModel {
    coefficients: [f64; 7],
}

/// The names of the coefficients of eq. (3.7), in the order of
/// [`KinematicErrorModel::coefficients`].
pub const COEFFICIENT_NAMES: [&str; 7] = ["a0", "a_l1", "b_l1", "a_w1", "b_w1", "a_w2", "b_w2"];

/// Largest accepted [`KinematicErrorModel::amplitude_bound`], rad (0.57°):
/// 23 times the largest catalogue kinematic error of Table 3.1 (4.4e-4
/// rad), and small enough that the fixed-point evaluation keeps the error
/// bound of the torque estimator's module docs below 15 steps of its
/// torsion unit.
pub const MAX_KINEMATIC_ERROR: f64 = 0.01;

impl KinematicErrorModel {
    /// Validates the coefficients `[a0, a_l1, b_l1, a_w1, b_w1, a_w2,
    /// b_w2]` (rad): each finite and in `[−0.01, 0.01]` (named as in
    /// [`COEFFICIENT_NAMES`]), and
    /// the largest error they can produce, `|a0| + Σ √(a² + b²)`, at most
    /// [`MAX_KINEMATIC_ERROR`].
    pub fn try_new(coefficients: [f64; 7]) -> Result<Self, ParamError> {
        // Each coefficient alone is at most the amplitude bound, so a
        // coefficient beyond it is named before the sum is formed (which
        // then cannot overflow).
        for (name, &c) in COEFFICIENT_NAMES.iter().zip(&coefficients) {
            in_range(name, c, -MAX_KINEMATIC_ERROR, MAX_KINEMATIC_ERROR)?;
        }
        let m = KinematicErrorModel { coefficients };
        crate::error::combination(
            "|a0| + √(a_l1² + b_l1²) + √(a_w1² + b_w1²) + √(a_w2² + b_w2²)",
            m.amplitude_bound(),
            0.0,
            MAX_KINEMATIC_ERROR,
        )?;
        Ok(m)
    }

    /// Coefficients `[a0, a_l1, b_l1, a_w1, b_w1, a_w2, b_w2]`, rad.
    pub fn coefficients(&self) -> [f64; 7] {
        self.coefficients
    }

    /// Table 3.2 in SI units: coefficients converted from degrees to rad,
    /// and the harmonics taken as exactly 1 per link revolution and 1, 2 per
    /// motor revolution (the printed `w_l`, `w_w` are fitted estimates of
    /// `π/180` per degree; see the module docs).
    pub fn table_3_2() -> Self {
        use table_3_2::*;
        let d = PI / 180.0;
        KinematicErrorModel {
            coefficients: [
                A0 * d,
                A_L1 * d,
                B_L1 * d,
                A_W1 * d,
                B_W1 * d,
                A_W2 * d,
                B_W2 * d,
            ],
        }
    }

    /// The regressor of eq. (3.7) at a link angle `θ_fo` and a motor angle
    /// `θ_wi` (both rad, each on its own side of the drive).
    pub fn regressor(link_angle: f64, motor_angle: f64) -> [f64; 7] {
        Self::regressor_from_trig(libm::sincos(link_angle), libm::sincos(motor_angle))
    }

    /// The regressor of eq. (3.7) from `(sin, cos)` of the link and motor
    /// angles, on any backend (the second motor harmonic by the
    /// double-angle identities). The one definition of the model's basis:
    /// the fit, [`evaluate`](Self::evaluate) and the torque estimator's
    /// radian path use it (its count path uses the equivalent
    /// [`phase_form`](Self::phase_form)).
    #[inline]
    pub fn regressor_from_trig<S: Scalar>(link: (S, S), motor: (S, S)) -> [S; 7] {
        let (sl, cl) = link;
        let (s1, c1) = motor;
        let s2 = s1.mul(c1).add(s1.mul(c1));
        let c2 = c1.sub(s1).mul(c1.add(s1));
        [S::ONE, cl, sl, c1, s1, c2, s2]
    }

    /// Eq. (3.7) as the dot product of prepared coefficients (any backend,
    /// stored units) with [`regressor_from_trig`](Self::regressor_from_trig).
    #[inline]
    pub fn series<S: Scalar>(coefficients: &[S; 7], link: (S, S), motor: (S, S)) -> S {
        let r = Self::regressor_from_trig(link, motor);
        let mut sum = S::ZERO;
        for (c, x) in coefficients.iter().zip(r.iter()) {
            sum = sum.add(c.mul(*x));
        }
        sum
    }

    /// Eq. (3.7): the kinematic error (rad).
    pub fn evaluate(&self, link_angle: f64, motor_angle: f64) -> f64 {
        let r = Self::regressor(link_angle, motor_angle);
        r.iter().zip(&self.coefficients).map(|(a, b)| a * b).sum()
    }

    /// Eq. (3.7) in amplitude–phase form (see [`KinematicErrorPhaseForm`]):
    /// each pair `a cos x + b sin x` of the regressor
    /// [`regressor_from_trig`](Self::regressor_from_trig) becomes
    /// `R cos(x − φ)` with `R = √(a² + b²)` and `φ = atan2(b, a)`, since
    /// `R cos(x − φ) = R cos φ cos x + R sin φ sin x`.
    pub fn phase_form(&self) -> KinematicErrorPhaseForm {
        let c = &self.coefficients;
        let pair = |a: f64, b: f64| (libm::hypot(a, b), libm::atan2(b, a));
        let (rl, pl) = pair(c[1], c[2]);
        let (r1, p1) = pair(c[3], c[4]);
        let (r2, p2) = pair(c[5], c[6]);
        KinematicErrorPhaseForm {
            offset: c[0],
            amplitudes: [rl, r1, r2],
            phases: [pl, p1, p2],
        }
    }

    /// Largest |θ_err| bound from the coefficients: `|a0| + Σ √(a² + b²)`.
    pub fn amplitude_bound(&self) -> f64 {
        let c = &self.coefficients;
        c[0].abs() + libm::hypot(c[1], c[2]) + libm::hypot(c[3], c[4]) + libm::hypot(c[5], c[6])
    }
}

/// Eq. (3.7) in amplitude–phase form:
///
/// ```text
/// θ_err = a_0 + R_l cos(θ_fo − φ_l)
///             + R_1 cos(θ_wi − φ_1) + R_2 cos(2 θ_wi − φ_2)
/// ```
///
/// with `R_l = √(a_l1² + b_l1²)`, `φ_l = atan2(b_l1, a_l1)` and likewise
/// for the first and second motor harmonics (`a_w1, b_w1`, `a_w2, b_w2`).
/// The same function as [`KinematicErrorModel::evaluate`] (a trigonometric
/// identity), evaluated with three cosines and three products and no
/// double-angle terms: the form the torque estimator computes per sample
/// from binary angles ([`Scalar::cos_turn`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicErrorPhaseForm {
    /// Constant term `a_0`, rad.
    pub offset: f64,
    /// Amplitudes `[R_l, R_1, R_2]`, rad, `≥ 0`.
    pub amplitudes: [f64; 3],
    /// Phases `[φ_l, φ_1, φ_2]`, rad, in `[−π, π]` (`φ_2` is a phase of
    /// the doubled motor angle `2θ_wi`).
    pub phases: [f64; 3],
}

impl KinematicErrorPhaseForm {
    /// Eq. (3.7) in this form at a link angle `θ_fo` and a motor angle
    /// `θ_wi` (rad); the kinematic error in rad.
    pub fn evaluate(&self, link_angle: f64, motor_angle: f64) -> f64 {
        let (r, p) = (&self.amplitudes, &self.phases);
        self.offset
            + r[0] * libm::cos(link_angle - p[0])
            + r[1] * libm::cos(motor_angle - p[1])
            + r[2] * libm::cos(2.0 * motor_angle - p[2])
    }
}

/// Streaming least-squares fit of [`KinematicErrorModel`] (normal equations
/// of the 7-term regressor, accumulated sample by sample; no allocation).
///
/// Record one output revolution at zero (or known and compensated) load:
/// link angle, motor angle and measured kinematic error (the torsion of
/// eq. 2.21 minus the modelled compliance). Over a full revolution the
/// regressor columns are nearly orthogonal, so the normal equations are well
/// conditioned.
#[derive(Debug, Clone, Default)]
pub struct KinematicErrorFit {
    ata: SMatrix<f64, 7, 7>,
    atb: SVector<f64, 7>,
    samples: usize,
}

impl KinematicErrorFit {
    /// An empty fit.
    pub fn new() -> Self {
        Self::default()
    }

    /// Add one sample (rad, rad, rad); non-finite samples are rejected.
    pub fn add_sample(
        &mut self,
        link_angle: f64,
        motor_angle: f64,
        kinematic_error: f64,
    ) -> Result<(), ParamError> {
        let r = KinematicErrorModel::regressor(
            finite("link_angle", link_angle)?,
            finite("motor_angle", motor_angle)?,
        );
        let e = finite("kinematic_error", kinematic_error)?;
        let r = SVector::<f64, 7>::from(r);
        self.ata += r * r.transpose();
        self.atb += r * e;
        self.samples += 1;
        Ok(())
    }

    /// Number of samples added.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Solve the normal equations (Cholesky). Fails with
    /// [`ParamError::NotRepresentable`] (`name = "samples"`) when the samples
    /// do not determine all seven coefficients (fewer than 7, or angles that
    /// do not cover the revolution).
    pub fn solve(&self) -> Result<KinematicErrorModel, ParamError> {
        let chol = self.ata.cholesky().ok_or(ParamError::NotRepresentable {
            name: "samples",
            value: self.samples as f64,
        })?;
        let x = chol.solve(&self.atb);
        if x.iter().any(|v| !v.is_finite()) {
            return Err(ParamError::NotRepresentable {
                name: "samples",
                value: self.samples as f64,
            });
        }
        let mut coefficients = [0.0; 7];
        coefficients.copy_from_slice(x.as_slice());
        KinematicErrorModel::try_new(coefficients)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// All-NaN and all-infinite tables (accepted before, and giving a
    /// constant −64 N·m estimate) are rejected naming the first bad
    /// coefficient; a finite table too large to be a kinematic error is
    /// rejected naming the amplitude bound; Table 3.2 is accepted.
    #[test]
    fn non_finite_or_huge_tables_are_rejected() {
        extern crate std;
        use std::string::ToString;
        let e = KinematicErrorModel::try_new([f64::NAN; 7]).unwrap_err();
        assert_eq!(e.to_string(), "parameter `a0` must be finite, got NaN");
        let mut c = [0.0; 7];
        c[4] = f64::NEG_INFINITY;
        let e = KinematicErrorModel::try_new(c).unwrap_err();
        assert_eq!(e.to_string(), "parameter `b_w1` must be finite, got -inf");
        // A coefficient alone above the bound is named before the sum.
        let e = KinematicErrorModel::try_new([0.0, 0.0, 0.0, 0.03, 0.0, 0.0, 0.0]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "parameter `a_w1` must lie in [-0.01, 0.01], got 0.03"
        );
        // 3-4-5: the first motor harmonic has amplitude 0.0125 rad, each
        // coefficient within the bound.
        let e = KinematicErrorModel::try_new([0.0, 0.0, 0.0, 0.0075, 0.01, 0.0, 0.0]).unwrap_err();
        match e {
            ParamError::CombinationOutOfRange { value, max, .. } => {
                assert!((value - 0.0125).abs() < 1e-15);
                assert_eq!(max, MAX_KINEMATIC_ERROR);
            }
            other => panic!("{other:?}"),
        }
        let t = KinematicErrorModel::table_3_2();
        assert_eq!(KinematicErrorModel::try_new(t.coefficients()), Ok(t));
    }

    /// Table 3.1 recomputed from its inputs (eq. 3.1, 3.2) against hand
    /// products, and the printed (truncated) values within their truncation.
    #[test]
    fn table_3_1_recomputed() {
        // (printed torque error N·m, printed relative error %)
        let printed = [
            (1.6, 43.0),
            (1.9, 35.0),
            (3.8, 35.0),
            (4.1, 25.0),
            (3.7, 21.0),
            (4.9, 17.0),
            (4.9, 17.0),
            (7.8, 29.0),
            (10.7, 23.0),
            (10.7, 23.0),
            (17.7, 33.0),
            (22.6, 24.0),
            (22.6, 24.0),
            (31.0, 32.0),
            (40.0, 22.0),
            (40.0, 19.0),
        ];
        // SHD-14-50 by hand: 3700 · 4.4e-4 = 1.628 N·m, / 3.7 = 44.0 %.
        assert!((TABLE_3_1[0].kinematic_torque_error() - 1.628).abs() < 1e-12);
        assert!((TABLE_3_1[0].relative_torque_error_percent() - 44.0).abs() < 1e-9);
        for (d, &(t, r)) in TABLE_3_1.iter().zip(&printed) {
            let (te, re) = (
                d.kinematic_torque_error(),
                d.relative_torque_error_percent(),
            );
            // Printed torques are the computed ones truncated or rounded to
            // 0.1 N·m (to 1 N·m above 30 N·m) ...
            let step = if t >= 30.0 { 1.0 } else { 0.1 };
            assert!(
                t <= te + step / 2.0 && te - t < step,
                "size {} ratio {}: {te} vs {t}",
                d.size,
                d.ratio
            );
            // ... and the printed percentages come from the printed torques,
            // truncated or rounded to a whole percent.
            let from_printed = t / d.rated_torque * 100.0;
            assert!(
                (from_printed - r).abs() < 1.0,
                "size {} ratio {}: {from_printed} vs {r}",
                d.size,
                d.ratio
            );
            // Against the exact torque the deviation reaches 1.23 points
            // (SHD-40-50: 33.2 % printed as 32 %), errata E3.1.
            assert!((re - r).abs() < 1.25);
        }
    }

    #[test]
    fn table_3_2_is_in_degrees() {
        use table_3_2::*;
        let deg = KinematicErrorModel::table_3_2();
        // Catalogue maximum kinematic error of SHD-17 (Table 3.1), rad.
        let catalogue = TABLE_3_1[3].max_kinematic_error;
        // In degrees: the peak-to-peak error fits the catalogue figure.
        assert!(2.0 * deg.amplitude_bound() < 1.2 * catalogue);
        // Read as radians, one coefficient alone is ten times the figure.
        assert!(B_L1.abs() > 9.0 * catalogue);
        // The printed frequencies are π/180 per degree within 1 %.
        for w in [W_L, W_W] {
            assert!((w / (PI / 180.0) - 1.0).abs() < 0.01);
        }
    }

    proptest! {
        /// A model sampled over one output revolution (N motor turns) with
        /// small noise is recovered by the fit.
        #[test]
        fn fit_recovers_model_from_one_revolution(
            coeffs in proptest::array::uniform7(-1e-4f64..1e-4), n in 30u32..160,
            noise in proptest::collection::vec(-1e-7f64..1e-7, 4000),
        ) {
            let truth = KinematicErrorModel { coefficients: coeffs };
            let mut fit = KinematicErrorFit::new();
            let m = noise.len();
            for (j, e) in noise.iter().enumerate() {
                let link = 2.0 * PI * j as f64 / m as f64;
                let motor = -(n as f64) * link; // eq. (2.4)
                fit.add_sample(link, motor, truth.evaluate(link, motor) + e).unwrap();
            }
            let got = fit.solve().unwrap();
            // Over m equally spaced samples of whole harmonics the basis is
            // orthogonal (AᵀA = diag(m, m/2, …)), so each coefficient's error
            // is (2/m)·Σ nⱼ·basisⱼ ≤ 2·max|n| = 2e-7 (a0: 1e-7), whatever
            // the noise; 1e-9 covers the rounding of the normal equations.
            for (g, t) in got.coefficients.iter().zip(&coeffs) {
                prop_assert!((g - t).abs() <= 2e-7 + 1e-9, "{g} vs {t}");
            }
        }
    }

    proptest! {
        /// The phase form is the same function as the regressor form (a
        /// trigonometric identity): equal to rounding at any angles, for
        /// coefficients of either sign, including Table 3.2.
        #[test]
        fn phase_form_equals_evaluate(
            c in proptest::array::uniform7(-1e-3f64..1e-3),
            link in -10.0f64..10.0, motor in -1e3f64..1e3, table: bool,
        ) {
            let m = if table { KinematicErrorModel::table_3_2() } else { KinematicErrorModel { coefficients: c } };
            let p = m.phase_form();
            let (a, b) = (m.evaluate(link, motor), p.evaluate(link, motor));
            // |θ_err| ≤ 3.2e-3 rad; both sides round a few f64 operations
            // on angles up to 2e3 rad (argument error ≈ 2e3 · 2⁻⁵³).
            prop_assert!((a - b).abs() <= 1e-15, "{a} vs {b}");
            prop_assert!(p.amplitudes.iter().all(|&r| r >= 0.0));
        }
    }

    /// Hand-derived phase form of one pair: `−1·cos x + 1·sin x =
    /// √2 cos(x − 3π/4)`.
    #[test]
    fn phase_form_of_a_known_pair() {
        let m = KinematicErrorModel {
            coefficients: [0.5, -1.0, 1.0, 0.0, 2.0, 3.0, 0.0],
        };
        let p = m.phase_form();
        assert_eq!(p.offset, 0.5);
        assert!((p.amplitudes[0] - 2f64.sqrt()).abs() < 1e-15);
        assert!((p.phases[0] - 3.0 * PI / 4.0).abs() < 1e-15);
        // 2 sin w = 2 cos(w − π/2); 3 cos 2w: R = 3, φ = 0.
        assert_eq!((p.amplitudes[1], p.phases[1]), (2.0, PI / 2.0));
        assert_eq!((p.amplitudes[2], p.phases[2]), (3.0, 0.0));
    }

    #[test]
    fn fit_rejects_degenerate_data() {
        let mut fit = KinematicErrorFit::new();
        for _ in 0..100 {
            fit.add_sample(0.3, 1.0, 1e-5).unwrap();
        }
        assert!(matches!(
            fit.solve(),
            Err(ParamError::NotRepresentable {
                name: "samples",
                ..
            })
        ));
        assert!(matches!(
            KinematicErrorFit::new().add_sample(f64::NAN, 0.0, 0.0),
            Err(ParamError::NotFinite {
                name: "link_angle",
                ..
            })
        ));
    }
}
