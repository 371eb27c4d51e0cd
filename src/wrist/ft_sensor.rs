//! The wrist's six-axis force/torque sensor, thesis §6.1 and §6.3:
//! the gauge amplifier of eq. (6.34), the decoupling matrix of eq. (6.35)
//! and the map of eq. (6.3) from the measured wrench to the interaction
//! torques `(τ_δ, τ_γ)` about the wrist's pitch and yaw axes.
//!
//! # Signal chain
//! 1. Each of the six half-bridge gauges is read through an instrumentation
//!    amplifier, `V_out = V_ref + G (V_IN+ − V_IN−)` (eq. 6.34), and the
//!    controller forms the gauge signal `SG_i = V_out,i − V_ref,i` (V).
//!    [`GaugeAmplifier`] holds `G` and gives the bridge voltage back.
//! 2. The wrench in the sensor frame is `w = M · SG` (eq. 6.35), with the
//!    6×6 decoupling matrix `M` of the sensor's calibration certificate:
//!    rows 0–2 in N/V (`F_x, F_y, F_z`), rows 3–5 in N·m/V
//!    (`τ_x, τ_y, τ_z`). [`DecouplingMatrix::try_new`] rejects a matrix
//!    with a non-finite entry or a 1-norm condition number above a limit
//!    (a matrix that amplifies gauge noise beyond use, or a transcription
//!    error in the certificate).
//! 3. The interaction torques about the wrist centre (eq. 6.3, corrected —
//!    errata E6.1), with `l` the distance (m) from the wrist centre to the
//!    sensor origin along the sensor's `z` axis:
//!
//!    `τ_δ = cos γ (τ_x − l F_y) − sin γ τ_z`,
//!    `τ_γ = −(τ_y + l F_x)`.
//!
//! # Sign conventions
//! The wrench is the one the environment applies to the tool, expressed in
//! the sensor frame of Fig. 6.1 (ATI convention). The moment about the
//! wrist centre is `m = τ + (l ẑ) × F = (τ_x − l F_y, τ_y + l F_x, τ_z)`.
//! The pitch axis seen from the sensor frame is `(cos γ, 0, −sin γ)`
//! (it stays with the wrist base while the tool yaws by `γ`) and the yaw
//! axis is `−ŷ`; `τ_δ, τ_γ` are the projections of `m` on them, so a
//! positive `τ_δ` (`τ_γ`) tends to increase `δ` (`γ`). Rows read off the
//! printed eq. (6.3) agree with this except the `τ_x` coefficient, printed
//! `1` instead of `cos γ` (errata E6.1).
//!
//! # Units
//! Floats store SI (V, N, N·m). On `I16F16` gauge signals are stored in V,
//! forces in N and torques in N·m (the link-torque unit): ±32 768 N and a
//! resolution of 1.5e-5 N·m, ample for a Mini45 (±580 N, ±20 N·m).

// Two- and six-element arrays indexed in parallel (axes, rows): index loops
// read better than zipped iterators here.
#![allow(clippy::needless_range_loop)]

use crate::error::{finite, in_range, ParamError};
use crate::scalar::{Coef, Scalar};

/// The gauge amplifier of eq. (6.34), `V_out = V_ref + G (V_IN+ − V_IN−)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaugeAmplifier {
    gain: f64,
}

impl GaugeAmplifier {
    /// Validate the gain `G` (dimensionless): finite, in `[1, 10 000]`
    /// (the AD8221's programmable range is 1–1000).
    pub fn try_new(gain: f64) -> Result<Self, ParamError> {
        let g = finite("gain", gain)?;
        if !(1.0..=1e4).contains(&g) {
            return Err(ParamError::OutOfRange {
                name: "gain",
                value: g,
                min: 1.0,
                max: 1e4,
            });
        }
        Ok(GaugeAmplifier { gain: g })
    }

    /// `G`.
    pub fn gain(&self) -> f64 {
        self.gain
    }

    /// Eq. (6.34): the amplifier output (V) for reference `v_ref` (V) and
    /// bridge differential `v_in = V_IN+ − V_IN−` (V).
    pub fn output(&self, v_ref: f64, v_in: f64) -> f64 {
        v_ref + self.gain * v_in
    }

    /// The gauge signal `SG = V_out − V_ref` of eq. (6.35), V.
    pub fn gauge_signal(v_out: f64, v_ref: f64) -> f64 {
        v_out - v_ref
    }

    /// The bridge differential `SG / G`, V (eq. 6.34 inverted).
    pub fn bridge_voltage(&self, gauge_signal: f64) -> f64 {
        gauge_signal / self.gain
    }
}

/// Largest accepted 1-norm condition number of a decoupling matrix by
/// default. Calibration matrices of six-axis sensors have a condition
/// number of order 10–10³ in SI (forces and torques differ by the sensor's
/// size, ~30 for a Mini45); 10⁴ leaves room for that and still rejects a
/// matrix whose inverse amplifies a relative gauge error 10⁴ times.
pub const DEFAULT_MAX_CONDITION: f64 = 1e4;

/// A validated 6×6 decoupling matrix `M` of eq. (6.35) (rows 0–2 in N/V,
/// rows 3–5 in N·m/V), with its inverse (for simulation) and its 1-norm
/// condition number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecouplingMatrix {
    matrix: [[f64; 6]; 6],
    inverse: [[f64; 6]; 6],
    condition: f64,
}

/// `‖A‖₁`, the largest column sum of magnitudes.
fn norm1(a: &[[f64; 6]; 6]) -> f64 {
    let mut best = 0.0f64;
    for j in 0..6 {
        let mut s = 0.0;
        for row in a {
            s += libm::fabs(row[j]);
        }
        best = best.max(s);
    }
    best
}

/// Gauss–Jordan inverse with partial pivoting; `None` when a pivot is zero
/// or the result is not finite.
fn invert(a: &[[f64; 6]; 6]) -> Option<[[f64; 6]; 6]> {
    let mut m = *a;
    let mut inv = [[0.0; 6]; 6];
    for (i, row) in inv.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for c in 0..6 {
        let mut p = c;
        for r in c + 1..6 {
            if libm::fabs(m[r][c]) > libm::fabs(m[p][c]) {
                p = r;
            }
        }
        if m[p][c] == 0.0 {
            return None;
        }
        m.swap(c, p);
        inv.swap(c, p);
        let d = m[c][c];
        for j in 0..6 {
            m[c][j] /= d;
            inv[c][j] /= d;
        }
        for r in 0..6 {
            if r != c {
                let f = m[r][c];
                if f != 0.0 {
                    for j in 0..6 {
                        m[r][j] -= f * m[c][j];
                        inv[r][j] -= f * inv[c][j];
                    }
                }
            }
        }
    }
    inv.iter().flatten().all(|v| v.is_finite()).then_some(inv)
}

/// The names of `matrix[r][c]`, row-major.
const MATRIX_ENTRIES: [&str; 36] = [
    "matrix[0][0]",
    "matrix[0][1]",
    "matrix[0][2]",
    "matrix[0][3]",
    "matrix[0][4]",
    "matrix[0][5]",
    "matrix[1][0]",
    "matrix[1][1]",
    "matrix[1][2]",
    "matrix[1][3]",
    "matrix[1][4]",
    "matrix[1][5]",
    "matrix[2][0]",
    "matrix[2][1]",
    "matrix[2][2]",
    "matrix[2][3]",
    "matrix[2][4]",
    "matrix[2][5]",
    "matrix[3][0]",
    "matrix[3][1]",
    "matrix[3][2]",
    "matrix[3][3]",
    "matrix[3][4]",
    "matrix[3][5]",
    "matrix[4][0]",
    "matrix[4][1]",
    "matrix[4][2]",
    "matrix[4][3]",
    "matrix[4][4]",
    "matrix[4][5]",
    "matrix[5][0]",
    "matrix[5][1]",
    "matrix[5][2]",
    "matrix[5][3]",
    "matrix[5][4]",
    "matrix[5][5]",
];

impl DecouplingMatrix {
    /// Validate a certificate matrix: `max_condition` finite and at least
    /// 1 (checked first, `"max_condition"`; see
    /// [`DEFAULT_MAX_CONDITION`]), every entry finite (named by its
    /// position, e.g. `"matrix[2][3]"`), `‖M‖₁ > 0`, `M` invertible and
    /// `κ₁(M) = ‖M‖₁ ‖M⁻¹‖₁ ≤ max_condition`. A singular or
    /// ill-conditioned matrix gives [`ParamError::CombinationOutOfRange`]
    /// named `"κ₁(matrix)"` carrying `κ₁` (`∞` when singular) and the
    /// range `[1, max_condition]`.
    pub fn try_new(matrix: [[f64; 6]; 6], max_condition: f64) -> Result<Self, ParamError> {
        let max_condition = in_range("max_condition", max_condition, 1.0, f64::INFINITY)?;
        for (k, v) in matrix.iter().flatten().enumerate() {
            finite(MATRIX_ENTRIES[k], *v)?;
        }
        let n = norm1(&matrix);
        if n == 0.0 {
            return Err(ParamError::NotPositive {
                name: "‖matrix‖₁",
                value: 0.0,
            });
        }
        let inverse = invert(&matrix);
        let condition = inverse.map_or(f64::INFINITY, |i| n * norm1(&i));
        let within = condition <= max_condition; // false for NaN and ∞ > max
        if !within {
            return Err(ParamError::CombinationOutOfRange {
                name: "κ₁(matrix)",
                value: condition,
                min: 1.0,
                max: max_condition,
            });
        }
        Ok(DecouplingMatrix {
            matrix,
            inverse: inverse.unwrap_or([[0.0; 6]; 6]),
            condition,
        })
    }

    /// A synthetic calibration matrix with the structure and magnitudes of
    /// an ATI Mini45 certificate (strong coupling between the gauges of
    /// each pair, force rows ≈ 30× the torque rows), for examples, tests
    /// and simulation. **Not a real sensor's certificate**: use your
    /// sensor's.
    pub fn example() -> Self {
        // Rows: F_x, F_y, F_z (N/V), τ_x, τ_y, τ_z (N·m/V).
        let m = [
            [0.51, -0.43, 1.72, 58.30, -2.10, -57.90],
            [-2.35, 67.10, 1.05, -33.60, 1.95, -33.20],
            [99.80, 1.60, 101.20, 0.90, 98.70, -0.40],
            [-0.04, 0.95, -1.82, -0.52, 1.84, 0.47],
            [2.10, 0.02, -1.05, 0.80, -1.03, -0.78],
            [0.03, -1.12, 0.02, -1.10, 0.05, -1.14],
        ];
        // Validity is asserted by `example_matrix_is_valid`.
        match Self::try_new(m, DEFAULT_MAX_CONDITION) {
            Ok(d) => d,
            Err(_) => DecouplingMatrix {
                matrix: m,
                inverse: [[0.0; 6]; 6],
                condition: f64::INFINITY,
            },
        }
    }

    /// `M`.
    pub fn matrix(&self) -> &[[f64; 6]; 6] {
        &self.matrix
    }

    /// `M⁻¹` (V per N and V per N·m): gauge signals of a given wrench.
    pub fn inverse(&self) -> &[[f64; 6]; 6] {
        &self.inverse
    }

    /// `κ₁(M)`.
    pub fn condition(&self) -> f64 {
        self.condition
    }

    /// Eq. (6.35) in `f64`: the wrench `[F_x, F_y, F_z, τ_x, τ_y, τ_z]`
    /// (N, N·m) of gauge signals `SG` (V).
    pub fn wrench(&self, sg: &[f64; 6]) -> [f64; 6] {
        mat_vec(&self.matrix, sg)
    }

    /// `M⁻¹ w`: the gauge signals (V) that read as wrench `w`.
    pub fn gauge_signals(&self, w: &[f64; 6]) -> [f64; 6] {
        mat_vec(&self.inverse, w)
    }
}

fn mat_vec(m: &[[f64; 6]; 6], v: &[f64; 6]) -> [f64; 6] {
    let mut o = [0.0; 6];
    for (oi, row) in o.iter_mut().zip(m.iter()) {
        *oi = row.iter().zip(v.iter()).map(|(a, b)| a * b).sum();
    }
    o
}

/// Eq. (6.3), corrected (errata E6.1), in `f64`: the interaction torques
/// `(τ_δ, τ_γ)` (N·m) about the wrist's pitch and yaw axes from the wrench
/// `w = [F_x, F_y, F_z, τ_x, τ_y, τ_z]` (N, N·m, sensor frame), the yaw
/// angle `γ` (rad) and the sensor offset `l` (m).
pub fn interaction_torques(w: &[f64; 6], gamma: f64, l: f64) -> [f64; 2] {
    let (s, c) = libm::sincos(gamma);
    [c * (w[3] - l * w[1]) - s * w[5], -(w[4] + l * w[0])]
}

/// Eq. (6.3) exactly as printed (the `τ_x` coefficient 1 instead of
/// `cos γ`), for comparison only (errata E6.1).
pub fn interaction_torques_as_printed(w: &[f64; 6], gamma: f64, l: f64) -> [f64; 2] {
    let (s, c) = libm::sincos(gamma);
    [-l * c * w[1] + w[3] - s * w[5], -l * w[0] - w[4]]
}

/// Validated parameters of the wrist's sensing chain: the decoupling
/// matrix and the offset `l` (m) of the sensor origin from the wrist
/// centre along the tool axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FtSensorParams {
    decoupling: DecouplingMatrix,
    offset: f64,
}

impl FtSensorParams {
    /// Validate: `l` finite, in `[0, 1]` m.
    pub fn try_new(decoupling: DecouplingMatrix, offset: f64) -> Result<Self, ParamError> {
        let l = finite("offset", offset)?;
        if !(0.0..=1.0).contains(&l) {
            return Err(ParamError::OutOfRange {
                name: "offset",
                value: l,
                min: 0.0,
                max: 1.0,
            });
        }
        Ok(FtSensorParams {
            decoupling,
            offset: l,
        })
    }

    /// The decoupling matrix.
    pub fn decoupling(&self) -> &DecouplingMatrix {
        &self.decoupling
    }

    /// `l`, m.
    pub fn offset(&self) -> f64 {
        self.offset
    }
}

/// The sensing chain quantized for backend `S` (each entry of `M` and `l`
/// as a prepared [`Coef`], so small entries keep 31 significant bits).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FtSensorConfig<S> {
    matrix: [[Coef; 6]; 6],
    offset: Coef,
    params: FtSensorParams,
    _s: core::marker::PhantomData<S>,
}

/// One reading of the sensing chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FtReading<S> {
    /// `[F_x, F_y, F_z, τ_x, τ_y, τ_z]`, N and N·m (stored link-torque
    /// units), sensor frame, the wrench of the environment on the tool.
    pub wrench: [S; 6],
    /// `[τ_δ, τ_γ]` of eq. (6.3) (corrected), N·m, positive when tending
    /// to increase `δ`, `γ`.
    pub interaction: [S; 2],
    /// An input was NaN or infinite, or finite but so large that the
    /// wrench overflows the backend's range (floats only; gauge signals
    /// of order `f32::MAX / ‖M‖`, far beyond any amplifier's output):
    /// every output is 0.
    pub invalid_input: bool,
}

impl<S: Scalar> FtSensorConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &FtSensorParams) -> Self {
        let u = S::UNITS.link_torque;
        let mut matrix = [[Coef::new(0.0); 6]; 6];
        for (mr, pr) in matrix.iter_mut().zip(p.decoupling.matrix.iter()) {
            for (m, v) in mr.iter_mut().zip(pr.iter()) {
                *m = Coef::new(*v * u);
            }
        }
        FtSensorConfig {
            matrix,
            offset: Coef::new(p.offset),
            params: *p,
            _s: core::marker::PhantomData,
        }
    }

    /// The validated parameters.
    pub fn params(&self) -> &FtSensorParams {
        &self.params
    }

    /// Eq. (6.35) then eq. (6.3): gauge signals `SG` (V, stored as plain
    /// volts) and the current yaw `γ` (rad) to the wrench and
    /// `(τ_δ, τ_γ)`. A NaN or infinite input, or a wrench that overflows
    /// the backend's range, gives zeros, flagged.
    ///
    /// ```
    /// use mrr_control::wrist::ft_sensor::{DecouplingMatrix, FtSensorConfig, FtSensorParams};
    /// let p = FtSensorParams::try_new(DecouplingMatrix::example(), 0.05)?;
    /// let cfg = FtSensorConfig::<f64>::new(&p);
    /// // The gauge signals of a pure 2 N·m torque about −y_sensor read as
    /// // τ_γ = +2 N·m, τ_δ = 0, at any yaw.
    /// let sg = p.decoupling().gauge_signals(&[0.0, 0.0, 0.0, 0.0, -2.0, 0.0]);
    /// let r = cfg.update(&sg, 0.3);
    /// assert!((r.interaction[1] - 2.0).abs() < 1e-9 && r.interaction[0].abs() < 1e-9);
    /// # Ok::<(), mrr_control::ParamError>(())
    /// ```
    pub fn update(&self, sg: &[S; 6], gamma: S) -> FtReading<S> {
        let mut w = [S::ZERO; 6];
        for (wi, row) in w.iter_mut().zip(self.matrix.iter()) {
            let mut acc = S::ZERO;
            for (g, m) in sg.iter().zip(row.iter()) {
                acc = acc.add(g.mul_coef(m));
            }
            *wi = acc;
        }
        let (s, c) = gamma.sin_cos();
        // m_x = τ_x − l F_y, m_y = τ_y + l F_x (moment about the wrist
        // centre, module docs).
        let mx = w[3].sub(w[1].mul_coef(&self.offset));
        let my = w[4].add(w[0].mul_coef(&self.offset));
        let interaction = [c.mul(mx).sub(s.mul(w[5])), my.neg()];
        // `v − v` is 0 for a finite value and NaN for NaN and ±∞ (always 0
        // on fixed point): one test covers every input and output.
        let d = |v: S| v.sub(v);
        let mut probe = d(gamma).add(d(interaction[0])).add(d(interaction[1]));
        for v in sg.iter().chain(w.iter()) {
            probe = probe.add(d(*v));
        }
        let bad = probe != S::ZERO;
        if bad {
            return FtReading {
                wrench: [S::ZERO; 6],
                interaction: [S::ZERO; 2],
                invalid_input: true,
            };
        }
        FtReading {
            wrench: w,
            interaction,
            invalid_input: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;

    #[test]
    fn example_matrix_is_valid() {
        let d = DecouplingMatrix::try_new(*DecouplingMatrix::example().matrix(), 1e4).unwrap();
        assert!(
            d.condition() > 1.0 && d.condition() < 1e4,
            "{}",
            d.condition()
        );
        // M M⁻¹ = I.
        for i in 0..6 {
            let mut e = [0.0; 6];
            e[i] = 1.0;
            let back = d.wrench(&d.gauge_signals(&e));
            for j in 0..6 {
                assert!((back[j] - e[j]).abs() < 1e-12, "{i} {j} {back:?}");
            }
        }
    }

    /// κ₁ by a second route: the largest column sum of `M⁻¹` found by
    /// solving `M x = e_j` column by column through the round trip, and a
    /// diagonal matrix whose condition is known exactly.
    #[test]
    fn condition_number_by_hand_and_rejection() {
        let mut m = [[0.0; 6]; 6];
        for (i, row) in m.iter_mut().enumerate() {
            row[i] = [1.0, 2.0, 4.0, 0.5, 1.0, 1.0][i];
        }
        // ‖M‖₁ = 4, ‖M⁻¹‖₁ = 2: κ₁ = 8.
        let d = DecouplingMatrix::try_new(m, 10.0).unwrap();
        assert!((d.condition() - 8.0).abs() < 1e-12);
        assert_eq!(
            DecouplingMatrix::try_new(m, 7.9),
            Err(ParamError::CombinationOutOfRange {
                name: "κ₁(matrix)",
                value: 8.0,
                min: 1.0,
                max: 7.9
            })
        );
        // Singular: two equal rows.
        let mut s = *DecouplingMatrix::example().matrix();
        s[5] = s[4];
        assert!(matches!(
            DecouplingMatrix::try_new(s, 1e4),
            Err(ParamError::CombinationOutOfRange { name: "κ₁(matrix)", value, .. }) if value > 1e4
        ));
        // Nearly singular: a row perturbed toward another by 1e-9.
        let mut n = *DecouplingMatrix::example().matrix();
        for j in 0..6 {
            n[5][j] = n[4][j] + 1e-9 * (j as f64 + 1.0);
        }
        assert!(DecouplingMatrix::try_new(n, 1e4).is_err());
        let mut nan = m;
        nan[2][3] = f64::NAN;
        assert!(matches!(
            DecouplingMatrix::try_new(nan, 1e4),
            Err(ParamError::NotFinite {
                name: "matrix[2][3]",
                ..
            })
        ));
        assert!(DecouplingMatrix::try_new([[0.0; 6]; 6], 1e4).is_err());
        assert!(FtSensorParams::try_new(d, -0.1).is_err());
        assert!(GaugeAmplifier::try_new(0.5).is_err());
    }

    #[test]
    fn amplifier_round_trip() {
        let a = GaugeAmplifier::try_new(100.0).unwrap();
        let v = a.output(2.5, 1.2e-3);
        assert!((v - 2.62).abs() < 1e-12);
        let sg = GaugeAmplifier::gauge_signal(v, 2.5);
        assert!((a.bridge_voltage(sg) - 1.2e-3).abs() < 1e-15);
        // The reader returns the validated gain, the ends of its range
        // included; beyond them the gain is rejected by name.
        for g in [1.0, 100.0, 1e4] {
            assert_eq!(GaugeAmplifier::try_new(g).unwrap().gain(), g);
        }
        for g in [1.0 - 1e-12, 1e4 * (1.0 + 1e-12), f64::NAN] {
            assert!(matches!(
                GaugeAmplifier::try_new(g),
                Err(ParamError::OutOfRange { name: "gain", .. }
                    | ParamError::NotFinite { name: "gain", .. })
            ));
        }
    }

    /// A matrix whose diagonal is zero needs the row exchanges of partial
    /// pivoting: a cyclic permutation with scaled entries (force rows 80,
    /// torque rows 2.5) is valid, its inverse is the transposed
    /// permutation with the reciprocal scales, and `κ₁ = 80/2.5 = 32`.
    #[test]
    fn zero_diagonal_is_inverted_by_row_exchanges() {
        let d = [80.0, 80.0, 80.0, 2.5, 2.5, 2.5];
        let mut m = [[0.0; 6]; 6];
        for i in 0..6 {
            m[i][(i + 1) % 6] = d[i];
        }
        let dm = DecouplingMatrix::try_new(m, DEFAULT_MAX_CONDITION).unwrap();
        for i in 0..6 {
            for j in 0..6 {
                let expected = if i == (j + 1) % 6 { 1.0 / d[j] } else { 0.0 };
                assert_eq!(dm.inverse()[i][j], expected, "[{i}][{j}]");
            }
        }
        assert_eq!(dm.condition(), 32.0);
    }

    /// Errata E6.1. A force whose line of action passes through the wrist
    /// centre exerts no moment about it, so it must give `τ_δ = τ_γ = 0`
    /// whatever the yaw. At the sensor, such a force `F` reads with the
    /// moment `τ = −(l ẑ) × F = (l F_y, −l F_x, 0)`. The corrected map
    /// gives zero; the printed eq. (6.3) gives `l F_y (1 − cos γ)`.
    #[test]
    fn force_through_the_wrist_centre_gives_no_torque() {
        let l = 0.06;
        for &(fx, fy, fz) in &[(3.0, -7.0, 2.0), (-20.0, 15.0, -4.0), (0.0, 40.0, 0.0)] {
            let w = [fx, fy, fz, l * fy, -l * fx, 0.0];
            for k in -6..=6 {
                let g = k as f64 * 0.1;
                let t = interaction_torques(&w, g, l);
                assert!(t[0].abs() < 1e-12 && t[1].abs() < 1e-12, "{t:?}");
                let p = interaction_torques_as_printed(&w, g, l);
                let want = l * fy * (1.0 - libm::cos(g));
                assert!((p[0] - want).abs() < 1e-12, "{p:?} {want}");
            }
        }
        // At γ = 0.5 rad and F_y = 40 N, l = 6 cm the printed form reports
        // 0.294 N·m of pitch torque that does not exist.
        let w = [0.0, 40.0, 0.0, l * 40.0, 0.0, 0.0];
        let p = interaction_torques_as_printed(&w, 0.5, l);
        assert!((p[0] - 2.4 * (1.0 - 0.5f64.cos())).abs() < 1e-12);
        assert!(p[0] > 0.29);
    }

    /// The printed eq. (6.3) differs from the corrected map in the `τ_x`
    /// coefficient alone (errata E6.1): for any wrench, printed − corrected
    /// = `(τ_x (1 − cos γ), 0)`. Every wrench component is nonzero here,
    /// so each term of the printed form is checked.
    #[test]
    fn printed_form_differs_only_in_the_tau_x_coefficient() {
        let l = 0.05;
        for w in [
            [3.0, -7.0, 2.0, 0.4, -0.3, 0.25],
            [-20.0, 15.0, -4.0, -1.1, 0.7, -0.9],
            [0.5, 40.0, 9.0, 2.2, 1.3, 0.6],
        ] {
            for k in -6..=6 {
                let g = k as f64 * 0.1;
                let c = interaction_torques(&w, g, l);
                let p = interaction_torques_as_printed(&w, g, l);
                let d0 = w[3] * (1.0 - libm::cos(g));
                assert!((p[0] - c[0] - d0).abs() < 1e-12, "{w:?} {g}: {p:?} {c:?}");
                assert!((p[1] - c[1]).abs() < 1e-12, "{w:?} {g}: {p:?} {c:?}");
            }
        }
    }

    /// The corrected map is the projection of the moment about the wrist
    /// centre on the pitch axis `(cos γ, 0, −sin γ)` and the yaw axis
    /// `−ŷ`: checked against the moment computed from a force applied at a
    /// point `p` (relative to the wrist centre) plus a free couple.
    #[test]
    fn map_is_the_moment_about_the_wrist_centre_projected() {
        let l = 0.045;
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let p = [0.01, -0.02, 0.11];
        let f = [4.0, -3.0, 9.0];
        let couple = [0.3, -0.2, 0.5];
        let m_centre = {
            let c = cross(p, f);
            [c[0] + couple[0], c[1] + couple[1], c[2] + couple[2]]
        };
        // At the sensor origin (0, 0, l): τ = (p − lẑ) × F + couple.
        let ts = {
            let c = cross([p[0], p[1], p[2] - l], f);
            [c[0] + couple[0], c[1] + couple[1], c[2] + couple[2]]
        };
        let w = [f[0], f[1], f[2], ts[0], ts[1], ts[2]];
        for g in [-0.5, 0.0, 0.2, 0.52] {
            let t = interaction_torques(&w, g, l);
            let (s, c) = (libm::sin(g), libm::cos(g));
            assert!((t[0] - (c * m_centre[0] - s * m_centre[2])).abs() < 1e-12);
            assert!((t[1] + m_centre[1]).abs() < 1e-12);
        }
    }

    /// Every backend agrees with the `f64` chain within its resolution,
    /// and a NaN gauge signal is flagged with zero outputs.
    #[test]
    fn backends_agree_and_nan_is_flagged() {
        let p = FtSensorParams::try_new(DecouplingMatrix::example(), 0.05).unwrap();
        let d = p.decoupling();
        let w = [12.0, -8.0, 30.0, 0.7, -1.1, 0.4];
        let sg = d.gauge_signals(&w);
        let g = 0.25;
        let want = interaction_torques(&w, g, 0.05);
        let c64 = FtSensorConfig::<f64>::new(&p).update(&sg, g);
        assert!((c64.interaction[0] - want[0]).abs() < 1e-10);
        assert!((c64.interaction[1] - want[1]).abs() < 1e-10);
        let c32 = FtSensorConfig::<f32>::new(&p).update(&sg.map(|v| v as f32), g as f32);
        for i in 0..2 {
            assert!(
                (c32.interaction[i] as f64 - want[i]).abs() < 2e-4,
                "{c32:?}"
            );
        }
        // I16F16: each SG quantized to 2⁻¹⁷ V at most; the error is at most
        // Σ_j |M_ij| 2⁻¹⁷ per wrench entry (≤ 200 N/V → 1.6e-3 N) plus the
        // sin/cos kernels' error; 0.01 N·m bounds the torque error.
        let fx = FtSensorConfig::<I16F16>::new(&p)
            .update(&sg.map(I16F16::from_f64), I16F16::from_f64(g));
        for i in 0..2 {
            assert!(
                (fx.interaction[i].to_f64() - want[i]).abs() < 0.01,
                "{fx:?}"
            );
        }
        let mut bad = sg;
        bad[2] = f64::NAN;
        let o = FtSensorConfig::<f64>::new(&p).update(&bad, g);
        assert!(o.invalid_input && o.interaction == [0.0, 0.0]);
        let o = FtSensorConfig::<f64>::new(&p).update(&sg, f64::INFINITY);
        assert!(o.invalid_input);
    }
}
