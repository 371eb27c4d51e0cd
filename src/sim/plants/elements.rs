//! The physical elements of the independent drive plant, each written here
//! from its own physics (none of them is a model of `harmonic_drive`).
//!
//! Sign convention (plant side, output-side units throughout): a positive
//! torque `T` twists an element by a positive angle; the chapter-2 mapping
//! is done once in [`drive`](super::drive).

use core::f64::consts::TAU;

use crate::sim::sensors::SplitMix64;

/// `ln cosh z`, without overflow for large `|z|`.
fn ln_cosh(z: f64) -> f64 {
    let a = z.abs();
    a + (-2.0 * a).exp().ln_1p() - core::f64::consts::LN_2
}

/// Integral of a logistic step `σ((u − c)/w) = (1 + tanh((u − c)/w))/2`
/// from `0` to `u`: `(w/2)[g((u − c)/w) − g(−c/w)]` with `g(z) = z + ln cosh z`.
fn smooth_ramp(u: f64, c: f64, w: f64) -> f64 {
    let g = |z: f64| z + ln_cosh(z);
    0.5 * w * (g((u - c) / w) - g(-c / w))
}

/// The elastic backbone of the flexspline: its torque (N·m) as a function
/// of its torsion (rad), odd and strictly increasing.
///
/// Three shapes, none of them eq. (2.10) (cubic), (2.11) (piecewise linear)
/// or (2.26) (arctangent); each is calibrated to the SHD-17-100 catalogue
/// of thesis §2.4 (`K1 = 8.4e3`, `K2 = 9.4e3` N·m/rad, `T1 = 3.9`,
/// `T2 = 12` N·m) and a third slope `K3` the thesis does not give.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FlexsplineBackbone {
    /// Local stiffness `K1 + (K2 − K1) σ((|y| − y1)/w) + (K3 − K2) σ((|y| − y2)/w)`
    /// with `σ = (1 + tanh)/2`: the catalogue's slopes, with its corners at
    /// the knee torsions `y1 = T1/K1`, `y2 = y1 + (T2 − T1)/K2` rounded over
    /// a width `w` (rad). Integrated in closed form (`ln cosh`).
    RoundedKnees {
        /// Slopes `K1, K2, K3`, N·m/rad.
        slopes: [f64; 3],
        /// Knee torsions `y1, y2`, rad.
        knees: [f64; 2],
        /// Corner width `w`, rad.
        width: f64,
    },
    /// A monotone cubic Hermite spline (Fritsch–Carlson slopes) through the
    /// catalogue points `(0, 0)`, `(y1, T1)`, `(y2, T2)`, `(y3, T3)`, slope
    /// `soft_start·K1` at zero, continued linearly with `K3` past `y3`.
    MonotoneSpline {
        /// Node torsions, rad (`0 < y1 < y2 < y3` after the leading zero).
        torsions: [f64; 4],
        /// Node torques, N·m.
        torques: [f64; 4],
        /// Node slopes, N·m/rad.
        slopes: [f64; 4],
    },
    /// Quadratic stiffening `T = K_a y + K_b y|y|` through the two catalogue
    /// knee points `(y1, T1)` and `(y2, T2)`.
    QuadraticStiffening {
        /// Linear stiffness `K_a`, N·m/rad.
        linear: f64,
        /// Quadratic coefficient `K_b`, N·m/rad².
        quadratic: f64,
    },
}

/// The catalogue numbers a backbone is calibrated to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatalogueNumbers {
    /// `K1`, N·m/rad.
    pub k1: f64,
    /// `K2`, N·m/rad.
    pub k2: f64,
    /// `K3`, N·m/rad (not in the thesis).
    pub k3: f64,
    /// `T1`, N·m.
    pub t1: f64,
    /// `T2`, N·m.
    pub t2: f64,
}

impl CatalogueNumbers {
    /// Knee torsions `y1 = T1/K1` and `y2 = y1 + (T2 − T1)/K2`, rad.
    pub fn knees(&self) -> [f64; 2] {
        let y1 = self.t1 / self.k1;
        [y1, y1 + (self.t2 - self.t1) / self.k2]
    }
}

impl FlexsplineBackbone {
    /// [`RoundedKnees`](Self::RoundedKnees) with the corner width a share of
    /// the first knee torsion.
    pub fn rounded_knees(c: &CatalogueNumbers, width_share: f64) -> Self {
        let knees = c.knees();
        FlexsplineBackbone::RoundedKnees {
            slopes: [c.k1, c.k2, c.k3],
            knees,
            width: width_share * knees[0],
        }
    }

    /// [`MonotoneSpline`](Self::MonotoneSpline) through the catalogue points
    /// and `T3 = 2 T2`, starting with slope `soft_start·K1`.
    pub fn monotone_spline(c: &CatalogueNumbers, soft_start: f64) -> Self {
        let [y1, y2] = c.knees();
        let t3 = 2.0 * c.t2;
        let y3 = y2 + (t3 - c.t2) / c.k3;
        let torsions = [0.0, y1, y2, y3];
        let torques = [0.0, c.t1, c.t2, t3];
        let secant = |i: usize| (torques[i + 1] - torques[i]) / (torsions[i + 1] - torsions[i]);
        let harmonic = |a: f64, b: f64| 2.0 / (1.0 / a + 1.0 / b);
        let slopes = [
            soft_start * c.k1,
            harmonic(secant(0), secant(1)),
            harmonic(secant(1), secant(2)),
            c.k3,
        ];
        FlexsplineBackbone::MonotoneSpline {
            torsions,
            torques,
            slopes,
        }
    }

    /// [`QuadraticStiffening`](Self::QuadraticStiffening) through the knees.
    pub fn quadratic_stiffening(c: &CatalogueNumbers) -> Self {
        let [y1, y2] = c.knees();
        // K_a + K_b y1 = T1/y1 and K_a + K_b y2 = T2/y2.
        let (s1, s2) = (c.t1 / y1, c.t2 / y2);
        let quadratic = (s2 - s1) / (y2 - y1);
        FlexsplineBackbone::QuadraticStiffening {
            linear: s1 - quadratic * y1,
            quadratic,
        }
    }

    /// Short name for tables.
    pub fn name(&self) -> &'static str {
        match self {
            FlexsplineBackbone::RoundedKnees { .. } => "rounded-knees",
            FlexsplineBackbone::MonotoneSpline { .. } => "spline",
            FlexsplineBackbone::QuadraticStiffening { .. } => "quadratic",
        }
    }

    /// Elastic torque (N·m) at a torsion (rad).
    pub fn torque(&self, torsion: f64) -> f64 {
        let u = torsion.abs();
        let t = match *self {
            FlexsplineBackbone::RoundedKnees {
                slopes,
                knees,
                width,
            } => {
                slopes[0] * u
                    + (slopes[1] - slopes[0]) * smooth_ramp(u, knees[0], width)
                    + (slopes[2] - slopes[1]) * smooth_ramp(u, knees[1], width)
            }
            FlexsplineBackbone::MonotoneSpline {
                torsions,
                torques,
                slopes,
            } => {
                if u >= torsions[3] {
                    torques[3] + slopes[3] * (u - torsions[3])
                } else {
                    let i = if u < torsions[1] {
                        0
                    } else if u < torsions[2] {
                        1
                    } else {
                        2
                    };
                    let h = torsions[i + 1] - torsions[i];
                    let s = (u - torsions[i]) / h;
                    let (s2, s3) = (s * s, s * s * s);
                    (2.0 * s3 - 3.0 * s2 + 1.0) * torques[i]
                        + (s3 - 2.0 * s2 + s) * h * slopes[i]
                        + (-2.0 * s3 + 3.0 * s2) * torques[i + 1]
                        + (s3 - s2) * h * slopes[i + 1]
                }
            }
            FlexsplineBackbone::QuadraticStiffening { linear, quadratic } => {
                linear * u + quadratic * u * u
            }
        };
        t.copysign(torsion)
    }

    /// Torsion (rad) at an elastic torque (N·m): the inverse of
    /// [`torque`](Self::torque) by bisection (the backbone is at least as
    /// stiff as `min_stiffness`, which brackets the root).
    pub fn torsion(&self, torque: f64) -> f64 {
        let target = torque.abs();
        let (mut lo, mut hi) = (0.0, target / self.min_stiffness());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.torque(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-16 * hi.max(1e-300) {
                break;
            }
        }
        (0.5 * (lo + hi)).copysign(torque)
    }

    /// A lower bound of the local stiffness over all torsions, N·m/rad.
    pub fn min_stiffness(&self) -> f64 {
        match *self {
            FlexsplineBackbone::RoundedKnees { slopes, .. } => {
                slopes[0].min(slopes[1]).min(slopes[2])
            }
            FlexsplineBackbone::MonotoneSpline { slopes, .. } => {
                // A Fritsch–Carlson piece is monotone but may dip below its
                // end slopes; a quarter of the smallest is a safe bracket.
                0.25 * slopes.iter().cloned().fold(f64::INFINITY, f64::min)
            }
            FlexsplineBackbone::QuadraticStiffening { linear, .. } => linear,
        }
    }
}

/// Compliance of the wave-generator bearing (output-side torsion, rad, for
/// an output-side wave-generator torque `T_w = N τ_w`, N·m): odd,
/// increasing, and *not* the exponential saturation of eq. (2.29).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WaveGeneratorCompliance {
    /// Hyperbolic saturation `δ = δ_m T/(|T| + T_h)` (slow `1/T` tail, where
    /// eq. 2.29 closes exponentially).
    Hyperbolic {
        /// Limit torsion `δ_m`, rad.
        limit: f64,
        /// Half-torsion torque `T_h`, N·m.
        knee: f64,
    },
    /// Bearing play taken up by a soft spring, then a hard stop: slope
    /// `1/k_0` up to `T_c`, `1/k_s` beyond (a corner, no saturation).
    BilinearStop {
        /// Soft stiffness `k_0`, N·m/rad.
        soft: f64,
        /// Corner torque `T_c`, N·m.
        corner: f64,
        /// Stop stiffness `k_s`, N·m/rad.
        stop: f64,
    },
}

impl WaveGeneratorCompliance {
    /// Short name for tables.
    pub fn name(&self) -> &'static str {
        match self {
            WaveGeneratorCompliance::Hyperbolic { .. } => "hyperbolic",
            WaveGeneratorCompliance::BilinearStop { .. } => "bilinear-stop",
        }
    }

    /// The same shape with every torsion multiplied by `s > 0`.
    pub fn scaled(&self, s: f64) -> Self {
        match *self {
            WaveGeneratorCompliance::Hyperbolic { limit, knee } => {
                WaveGeneratorCompliance::Hyperbolic {
                    limit: limit * s,
                    knee,
                }
            }
            WaveGeneratorCompliance::BilinearStop { soft, corner, stop } => {
                WaveGeneratorCompliance::BilinearStop {
                    soft: soft / s,
                    corner,
                    stop: stop / s,
                }
            }
        }
    }

    /// Output-side torsion (rad) for an output-side torque (N·m).
    pub fn torsion(&self, torque: f64) -> f64 {
        let t = torque.abs();
        let d = match *self {
            WaveGeneratorCompliance::Hyperbolic { limit, knee } => limit * t / (t + knee),
            WaveGeneratorCompliance::BilinearStop { soft, corner, stop } => {
                if t <= corner {
                    t / soft
                } else {
                    corner / soft + (t - corner) / stop
                }
            }
        };
        d.copysign(torque)
    }

    /// Output-side torque (N·m) for a torsion (rad); for the hyperbolic
    /// shape torsions at or beyond `±δ_m` map to `±1e6` N·m (a stop).
    pub fn torque(&self, torsion: f64) -> f64 {
        let d = torsion.abs();
        let t = match *self {
            WaveGeneratorCompliance::Hyperbolic { limit, knee } => {
                if d >= limit {
                    1e6
                } else {
                    (knee * d / (limit - d)).min(1e6)
                }
            }
            WaveGeneratorCompliance::BilinearStop { soft, corner, stop } => {
                let dc = corner / soft;
                if d <= dc {
                    d * soft
                } else {
                    corner + (d - dc) * stop
                }
            }
        };
        t.copysign(torsion)
    }
}

/// Maxwell-slip friction (Lampaert, Al-Bender & Swevers 2003): elements of
/// stiffness `k_i` (N·m/rad) that stick up to a break-away torque `F_i`
/// (N·m) and then slide — rate-independent pre-sliding hysteresis with
/// nonlocal memory.
#[derive(Debug, Clone, PartialEq)]
pub struct MaxwellSlip {
    /// `(k_i, F_i)` per element.
    pub elements: Vec<(f64, f64)>,
}

/// Anchor positions of the elements of a [`MaxwellSlip`], rad.
#[derive(Debug, Clone, PartialEq)]
pub struct MaxwellSlipState {
    /// Where each element's spring is relaxed, rad.
    pub anchors: Vec<f64>,
}

impl MaxwellSlip {
    /// Elements sharing a total break-away torque `total` (N·m) by `shares`
    /// (summing to 1), element `i` sliding after a displacement
    /// `presliding[i]` (rad).
    pub fn from_shares(total: f64, shares: &[f64], presliding: &[f64]) -> Self {
        MaxwellSlip {
            elements: shares
                .iter()
                .zip(presliding)
                .map(|(s, d)| (s * total / d, s * total))
                .collect(),
        }
    }

    /// Total break-away torque `Σ F_i`, N·m.
    pub fn breakaway(&self) -> f64 {
        self.elements.iter().map(|e| e.1).sum()
    }

    /// A state with every element relaxed at `position`.
    pub fn relaxed(&self, position: f64) -> MaxwellSlipState {
        MaxwellSlipState {
            anchors: vec![position; self.elements.len()],
        }
    }

    /// Friction torque (N·m) at `position` without moving the anchors.
    pub fn torque(&self, state: &MaxwellSlipState, position: f64) -> f64 {
        self.elements
            .iter()
            .zip(&state.anchors)
            .map(|(&(k, f), z)| (k * (position - z)).clamp(-f, f))
            .sum()
    }

    /// Accept `position`: every element pushed past its break-away slides.
    pub fn commit(&self, state: &mut MaxwellSlipState, position: f64) {
        for (&(k, f), z) in self.elements.iter().zip(state.anchors.iter_mut()) {
            let stretch = position - *z;
            if k * stretch > f {
                *z = position - f / k;
            } else if k * stretch < -f {
                *z = position + f / k;
            }
        }
    }
}

/// Kinematic error of the plant, output-side rad, as a function of the
/// wave-generator angle `θ_w` and the output angle `θ_o`: harmonics 1–4 of
/// the wave generator (eq. 3.7 has only 1 and 2), a tooth-pass ripple of
/// order `2(N + 1)` per wave-generator turn, and an output eccentricity.
#[derive(Debug, Clone, PartialEq)]
pub struct KinematicErrorPlant {
    /// `(amplitude rad, phase rad)` of wave-generator harmonics 1..=4.
    pub wave_generator: [(f64, f64); 4],
    /// Tooth-pass ripple `(amplitude, phase)`.
    pub ripple: (f64, f64),
    /// Ripple order per wave-generator turn.
    pub ripple_order: f64,
    /// Output eccentricity (once per output turn) `(amplitude, phase)`.
    pub output: (f64, f64),
}

/// Catalogue bound on the kinematic error of the SHD-17-100, peak to peak,
/// rad (thesis Table 3.1: 4.4e-4 rad).
pub const KINEMATIC_ERROR_PEAK_TO_PEAK: f64 = 4.4e-4;

impl KinematicErrorPlant {
    /// One random draw. Magnitudes: harmonic 1 about 4.3e-5 rad and
    /// harmonic 2 about 6.0e-5 rad (the sizes of thesis Table 3.2's `a_w1,
    /// b_w1` and `a_w2, b_w2`, converted from degrees), each scaled by a
    /// uniform factor in [0.5, 1.5]; harmonics 3 and 4 uniform up to 1.5e-5
    /// and 2e-5 rad (content eq. 3.7 lacks); the ripple `ripple` rad; the
    /// output term 7.5e-5 rad (Table 3.2's `a_l1, b_l1`). If the sum of
    /// amplitudes exceeds half of [`KINEMATIC_ERROR_PEAK_TO_PEAK`], all are
    /// scaled down to it.
    pub fn draw(rng: &mut SplitMix64, ripple: f64, ratio: f64) -> Self {
        let mut phase = || TAU * rng.uniform();
        let p = [phase(), phase(), phase(), phase(), phase(), phase()];
        let mut u = || rng.uniform();
        let mut a = [
            4.3e-5 * (0.5 + u()),
            6.0e-5 * (0.5 + u()),
            1.5e-5 * u(),
            2.0e-5 * u(),
            ripple,
            7.5e-5,
        ];
        let sum: f64 = a.iter().sum();
        let cap = 0.5 * KINEMATIC_ERROR_PEAK_TO_PEAK;
        if sum > cap {
            a.iter_mut().for_each(|x| *x *= cap / sum);
        }
        KinematicErrorPlant {
            wave_generator: [(a[0], p[0]), (a[1], p[1]), (a[2], p[2]), (a[3], p[3])],
            ripple: (a[4], p[4]),
            ripple_order: 2.0 * (ratio + 1.0),
            output: (a[5], p[5]),
        }
    }

    /// The error (rad) at wave-generator angle `θ_w` and output angle `θ_o`.
    pub fn error(&self, wave_generator_angle: f64, output_angle: f64) -> f64 {
        let mut e = 0.0;
        for (h, &(a, p)) in self.wave_generator.iter().enumerate() {
            e += a * ((h as f64 + 1.0) * wave_generator_angle + p).sin();
        }
        e += self.ripple.0 * (self.ripple_order * wave_generator_angle + self.ripple.1).sin();
        e + self.output.0 * (output_angle + self.output.1).sin()
    }

    /// Upper bound of `|error|`: the sum of the amplitudes, rad.
    pub fn amplitude_sum(&self) -> f64 {
        self.wave_generator.iter().map(|x| x.0).sum::<f64>() + self.ripple.0 + self.output.0
    }
}

/// A quantizing angle sensor: Gaussian noise of `noise_counts` counts, then
/// rounding to whole counts of `2π/counts_per_rev` rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuantizingEncoder {
    /// Counts per revolution of the shaft it reads.
    pub counts_per_rev: f64,
    /// Noise standard deviation, counts.
    pub noise_counts: f64,
}

impl QuantizingEncoder {
    /// A reading (rad) of `angle` (rad).
    pub fn read(&self, angle: f64, rng: &mut SplitMix64) -> f64 {
        let step = TAU / self.counts_per_rev;
        (angle / step + self.noise_counts * rng.gaussian()).round() * step
    }
}

/// Illinois regula falsi on a bracket `(a, f(a))`, `(b, f(b))` of opposite
/// signs: at most `iterations` steps, stopping at a zero or when
/// `converged(a, b, c)` holds for the bracket and the new point `c`.
pub(crate) fn illinois(
    f: impl Fn(f64) -> f64,
    (mut a, mut fa): (f64, f64),
    (mut b, mut fb): (f64, f64),
    iterations: usize,
    converged: impl Fn(f64, f64, f64) -> bool,
) -> f64 {
    let mut side = 0;
    for _ in 0..iterations {
        let c = (a * fb - b * fa) / (fb - fa);
        let fc = f(c);
        if fc == 0.0 || converged(a, b, c) {
            return c;
        }
        if fc.signum() == fb.signum() {
            b = c;
            fb = fc;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            fa = fc;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    (a * fb - b * fa) / (fb - fa)
}

#[cfg(test)]
mod tests {
    use super::*;

    const CAT: CatalogueNumbers = CatalogueNumbers {
        k1: 8.4e3,
        k2: 9.4e3,
        k3: 1.3e4,
        t1: 3.9,
        t2: 12.0,
    };

    fn shapes() -> [FlexsplineBackbone; 3] {
        [
            FlexsplineBackbone::rounded_knees(&CAT, 0.3),
            FlexsplineBackbone::monotone_spline(&CAT, 0.8),
            FlexsplineBackbone::quadratic_stiffening(&CAT),
        ]
    }

    /// Each backbone is odd, increasing, inverted by `torsion`, and passes
    /// within 4 % of the catalogue knee torques (the rounded corners move
    /// the knee points; the spline and quadratic pass through them).
    #[test]
    fn backbones_are_monotone_and_near_the_catalogue() {
        let [y1, y2] = CAT.knees();
        for b in shapes() {
            let mut prev = f64::NEG_INFINITY;
            for i in -400..=400 {
                let y = i as f64 * 6e-6;
                let t = b.torque(y);
                assert!(t > prev, "{} not increasing at {y}", b.name());
                prev = t;
                assert!((b.torque(-y) + t).abs() < 1e-9);
                assert!((b.torsion(t) - y).abs() < 1e-12, "{}", b.name());
            }
            assert!((b.torque(y1) / CAT.t1 - 1.0).abs() < 0.04, "{}", b.name());
            assert!((b.torque(y2) / CAT.t2 - 1.0).abs() < 0.04, "{}", b.name());
        }
        // The spline and the quadratic go through the knees exactly.
        for b in &shapes()[1..] {
            assert!((b.torque(y1) - CAT.t1).abs() < 1e-9);
            assert!((b.torque(y2) - CAT.t2).abs() < 1e-9);
        }
    }

    /// Far from the corners the rounded backbone has the catalogue slopes.
    #[test]
    fn rounded_knees_have_catalogue_slopes_between_corners() {
        let b = FlexsplineBackbone::rounded_knees(&CAT, 0.1);
        let [y1, y2] = CAT.knees();
        let slope = |y: f64| (b.torque(y + 1e-8) - b.torque(y - 1e-8)) / 2e-8;
        assert!((slope(0.2 * y1) / CAT.k1 - 1.0).abs() < 1e-3);
        assert!((slope(0.5 * (y1 + y2)) / CAT.k2 - 1.0).abs() < 1e-3);
        assert!((slope(3.0 * y2) / CAT.k3 - 1.0).abs() < 1e-3);
    }

    #[test]
    fn wave_generator_shapes_invert() {
        let shapes = [
            WaveGeneratorCompliance::Hyperbolic {
                limit: 1e-4,
                knee: 0.6,
            },
            WaveGeneratorCompliance::BilinearStop {
                soft: 1e4,
                corner: 1.2,
                stop: 2.5e5,
            },
        ];
        for w in shapes {
            for i in -50..=50 {
                let t = i as f64 * 0.4;
                assert!((w.torque(w.torsion(t)) - t).abs() < 1e-9 * (1.0 + t.abs()));
            }
        }
    }

    /// A Maxwell-slip element loaded past break-away and back: the torque
    /// saturates at `Σ F_i` and the loop width at zero position is what the
    /// elastic-plastic law gives by hand.
    #[test]
    fn maxwell_slip_saturates_and_remembers() {
        let m = MaxwellSlip::from_shares(2.0, &[0.5, 0.5], &[1e-6, 4e-6]);
        let mut s = m.relaxed(0.0);
        for i in 0..=100 {
            m.commit(&mut s, i as f64 * 1e-6);
        }
        assert!((m.torque(&s, 100e-6) - 2.0).abs() < 1e-12);
        // Back to 98 µrad: element 1 (k = 1e6) is at 1 - 2 = -1 (saturated),
        // element 2 (k = 2.5e5) at 1 - 0.5 = 0.5.
        assert!((m.torque(&s, 98e-6) - (-1.0 + 0.5)).abs() < 1e-9);
    }

    #[test]
    fn kinematic_error_respects_the_catalogue_bound() {
        let mut rng = SplitMix64::new(7);
        for _ in 0..200 {
            let k = KinematicErrorPlant::draw(&mut rng, 4e-5, 100.0);
            assert!(k.amplitude_sum() <= 0.5 * KINEMATIC_ERROR_PEAK_TO_PEAK * (1.0 + 1e-12));
        }
    }
}
