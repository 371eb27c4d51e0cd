//! The independent drive plant: a flexspline backbone with its own
//! hysteresis, Maxwell-slip mesh friction at the node between the
//! flexspline and the wave-generator bearing, the bearing's compliance, a
//! kinematic error and the bench's sensors; and the two experiments of
//! thesis §2.4 run on it quasi-statically.
//!
//! # Structure and signs (plant side)
//! Angles are output-side radians along one direction: input `a` (the
//! motor angle divided by `N`), node `x` (the flexspline's gear side),
//! output `o`. The wave-generator bearing carries `T_w = W(a − x)`, the
//! flexspline `T_f = B(x − o) + H(x − o)` (backbone `B` plus its own
//! Maxwell-slip hysteresis `H`), and the mesh friction `M(x)` ties the node
//! to the housing: `T_w = T_f + M(x)`. The drive's torsion is
//! `φ = a − o = W⁻¹(T_w) + (x − o)`.
//!
//! Chapter 2 writes the same quantities as `Δθ = −φ` (eq. 2.13 with
//! `θ_wi = −N a`), `τ_f = −T_f` and `τ_w = T_w/N` (motor side); with these,
//! eq. (2.9)'s `τ_w = −(τ_f − τ_fr)/N` is the node balance above with
//! `τ_fr = M`. Every [`Sample`] is in chapter-2 signs.
//!
//! The quasi-static solution is exact for this rate-independent plant: the
//! motor and link inertias and the speed play no part at the slow sine of
//! Fig. 2.17 (a period of seconds against a drive resonance above 50 Hz).

use core::f64::consts::TAU;

use super::elements::{
    illinois, CatalogueNumbers, FlexsplineBackbone, KinematicErrorPlant, MaxwellSlip,
    MaxwellSlipState, QuantizingEncoder, WaveGeneratorCompliance,
};
use crate::sim::sensors::SplitMix64;

/// Gear ratio of the SHD-17-100 (§2.4).
pub const RATIO: f64 = 100.0;
/// Catalogue curve of the SHD-17-100 (§2.4: `K1 = 8.4e3`, `K2 = 9.4e3`
/// N·m/rad, `T1 = 3.9`, `T2 = 12` N·m). `K3` is not in the thesis:
/// `1.3e4` N·m/rad is assumed (the third slope only matters above 12 N·m).
pub const CATALOGUE: CatalogueNumbers = CatalogueNumbers {
    k1: 8.4e3,
    k2: 9.4e3,
    k3: 1.3e4,
    t1: 3.9,
    t2: 12.0,
};
/// Hysteresis loss `Ψ`, rad (catalogue, §2.4).
pub const HYSTERESIS_LOSS: f64 = 2.9e-4;
/// Starting torque on the wave generator `τ_fs = 1.2` N·cm (§2.4), N·m.
pub const STARTING_TORQUE: f64 = 0.012;
/// Back-driving torque on the flexspline `τ_fb = 2.0` N·m (§2.4).
pub const BACKDRIVE_TORQUE: f64 = 2.0;
/// Rated torque of the SHD-17-100, N·m (§2.4); the catalogue's hysteresis
/// loop is taken between `±` this torque.
pub const RATED_TORQUE: f64 = 16.0;
/// Shares of the break-away torque among the four Maxwell-slip elements of
/// each friction law (an assumption: a spread of pre-sliding stiffnesses).
pub const SLIP_SHARES: [f64; 4] = [0.4, 0.3, 0.2, 0.1];
/// Pre-sliding displacements of the mesh-friction elements, output-side
/// rad (an assumption: a few µrad, well inside the 1e-4 rad the node moves).
pub const MESH_PRESLIDING: [f64; 4] = [2e-6, 4e-6, 8e-6, 16e-6];
/// Pre-sliding displacements of the flexspline's own hysteresis elements,
/// rad (an assumption: 1–8 % of the 1.3e-3 rad torsion at `T2`).
pub const FLEXSPLINE_PRESLIDING: [f64; 4] = [1e-5, 2e-5, 4e-5, 8e-5];

/// Link torque sensor: ATI Mini45 (§3.2) resolution 1/376 N·m, noise of
/// half a step (assumption).
pub const TORQUE_SENSOR_RESOLUTION: f64 = 1.0 / 376.0;

/// One member of the plant family.
#[derive(Debug, Clone, PartialEq)]
pub struct DrivePlant {
    /// Elastic backbone of the flexspline.
    pub backbone: FlexsplineBackbone,
    /// The flexspline's own hysteresis (Maxwell-slip, parallel to the
    /// backbone): the mechanism eq. (2.30) does not represent.
    pub flexspline_hysteresis: MaxwellSlip,
    /// Wave-generator bearing compliance.
    pub wave_generator: WaveGeneratorCompliance,
    /// Mesh friction at the node (Maxwell-slip to the housing): with the
    /// bearing compliance, the mechanism eq. (2.30) is built on.
    pub mesh_friction: MaxwellSlip,
    /// Share of the catalogue hysteresis loss `Ψ` produced by the mesh
    /// friction and bearing compliance (the rest by the flexspline).
    pub node_share: f64,
    /// Peak output-side torque `N τ_m` of the Fig. 2.17 command (and of the
    /// Fig. 2.21 external torque), N·m.
    pub amplitude: f64,
    /// Tooth-pass ripple amplitude of the kinematic error, rad.
    pub ripple: f64,
    /// Motor encoder (on the motor shaft).
    pub motor_encoder: QuantizingEncoder,
    /// Link encoder (on the output).
    pub link_encoder: QuantizingEncoder,
    /// Relative torque-constant error bound: each seed draws a gain error
    /// uniform in `±` this.
    pub torque_gain_error: f64,
}

/// One recorded sample, chapter-2 signs (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// Torsion `Δθ = θ_fo + θ_wi/N` from the two encoders, relative to the
    /// first sample (the bench's zero at rest), rad.
    pub torsion: f64,
    /// Flexspline torque `τ_f` from the torque sensor, N·m.
    pub flexspline_torque: f64,
    /// Wave-generator torque `τ_w` (motor side) as the bench knows it: the
    /// command in the locked-output test, `NaN`-free zero in the held-input
    /// test (where the models estimate it by eq. 2.40), N·m.
    pub wave_generator_torque: f64,
    /// True torsion `−φ`, rad.
    pub true_torsion: f64,
    /// True `τ_f`, N·m.
    pub true_flexspline_torque: f64,
    /// True `τ_w` (motor side), N·m.
    pub true_wave_generator_torque: f64,
    /// True motor-side angle `θ_wi` (with the run's random start angle),
    /// rad: the angle the kinematic error repeats with.
    pub motor_angle: f64,
}

/// Mutable state of the plant.
#[derive(Debug, Clone, PartialEq)]
struct State {
    node: f64,
    flexspline: MaxwellSlipState,
    mesh: MaxwellSlipState,
}

/// Root of an increasing function near `x0`: bracket by doubling steps,
/// then Illinois regula falsi.
fn solve_increasing(f: impl Fn(f64) -> f64, x0: f64, step: f64) -> f64 {
    let f0 = f(x0);
    if f0 == 0.0 {
        return x0;
    }
    let dir = if f0 < 0.0 { 1.0 } else { -1.0 };
    let (mut a, mut fa) = (x0, f0);
    let mut h = step;
    let (mut b, mut fb) = (x0 + dir * h, f(x0 + dir * h));
    let mut n = 0;
    while fa.signum() == fb.signum() && n < 200 {
        a = b;
        fa = fb;
        h *= 2.0;
        b = x0 + dir * h;
        fb = f(b);
        n += 1;
    }
    illinois(&f, (a, fa), (b, fb), 200, |a, b, c| {
        (b - a).abs() <= 1e-15 * (1e-12 + c.abs())
    })
}

/// Quasi-static responses of one step (plant signs).
#[derive(Debug, Clone, Copy)]
struct Response {
    /// Torsion `φ = a − o`, rad.
    torsion: f64,
    /// Flexspline torque `T_f`, N·m.
    flexspline_torque: f64,
    /// Bearing torque `T_w`, N·m.
    wave_generator_torque: f64,
    /// Input angle `a`, rad.
    input: f64,
    /// Output angle `o`, rad.
    output: f64,
}

impl DrivePlant {
    fn relaxed(&self) -> State {
        State {
            node: 0.0,
            flexspline: self.flexspline_hysteresis.relaxed(0.0),
            mesh: self.mesh_friction.relaxed(0.0),
        }
    }

    fn flexspline_torque(&self, s: &State, twist: f64) -> f64 {
        self.backbone.torque(twist) + self.flexspline_hysteresis.torque(&s.flexspline, twist)
    }

    /// Output locked (`o = 0`), bearing torque `T_w` applied at the input.
    fn step_locked(&self, s: &mut State, bearing_torque: f64) -> Response {
        let x = solve_increasing(
            |x| {
                self.flexspline_torque(s, x) + self.mesh_friction.torque(&s.mesh, x)
                    - bearing_torque
            },
            s.node,
            1e-7,
        );
        let tf = self.flexspline_torque(s, x);
        self.flexspline_hysteresis.commit(&mut s.flexspline, x);
        self.mesh_friction.commit(&mut s.mesh, x);
        s.node = x;
        let input = x + self.wave_generator.torsion(bearing_torque);
        Response {
            torsion: input,
            flexspline_torque: tf,
            wave_generator_torque: bearing_torque,
            input,
            output: 0.0,
        }
    }

    /// Input held (`a = 0`), flexspline torque `T_f` applied at the output.
    fn step_held(&self, s: &mut State, flexspline_torque: f64) -> Response {
        // Flexspline twist `y = x − o` from its own balance.
        let y0 = self.backbone.torsion(flexspline_torque);
        let y = solve_increasing(
            |y| self.flexspline_torque(s, y) - flexspline_torque,
            y0,
            1e-7,
        );
        self.flexspline_hysteresis.commit(&mut s.flexspline, y);
        // Node lag `u = a − x = −x`: W(u) − M(−u) = T_f.
        let u = solve_increasing(
            |u| {
                self.wave_generator.torque(u)
                    - self.mesh_friction.torque(&s.mesh, -u)
                    - flexspline_torque
            },
            -s.node,
            1e-8,
        );
        self.mesh_friction.commit(&mut s.mesh, -u);
        s.node = -u;
        Response {
            torsion: u + y,
            flexspline_torque,
            wave_generator_torque: self.wave_generator.torque(u),
            input: 0.0,
            output: -u - y,
        }
    }

    /// Width of the catalogue hysteresis loop (rad): input held, output
    /// loaded `0 → +T_r → −T_r → 0` in 0.25 N·m steps with
    /// `T_r` = [`RATED_TORQUE`]; the torsion at zero torque on the way down
    /// minus that on the way up.
    pub fn catalogue_loop_width(&self) -> f64 {
        let mut s = self.relaxed();
        let n = (RATED_TORQUE / 0.25).round() as i32;
        let q = |i: i32| i as f64 * 0.25;
        for i in 0..=n {
            self.step_held(&mut s, q(i));
        }
        let mut down = 0.0;
        for i in (-n..n).rev() {
            let r = self.step_held(&mut s, q(i));
            if i == 0 {
                down = r.torsion;
            }
        }
        let mut up = 0.0;
        for i in (-n + 1)..=0 {
            up = self.step_held(&mut s, q(i)).torsion;
        }
        down - up
    }

    /// The Fig. 2.17 command: output-side torque `A (1 − k/n) sin(2π k/100)`
    /// for `k = 0..n`, `n = 1000` (ten cycles of monotonically decreasing
    /// amplitude, 100 samples each; the plant is rate-independent so the
    /// period does not matter).
    pub fn profile(&self) -> Vec<f64> {
        let n = 1000;
        (0..n)
            .map(|k| {
                let k = k as f64;
                self.amplitude * (1.0 - k / n as f64) * (TAU * k / 100.0).sin()
            })
            .collect()
    }

    /// Record a run: `ideal` leaves out the kinematic error, the sensors and
    /// the gain error (the truth an oracle is fitted to).
    fn record(&self, seed: u64, ideal: bool, held: bool) -> Vec<Sample> {
        let mut rng = SplitMix64::new(seed);
        let ke = KinematicErrorPlant::draw(&mut rng, self.ripple, RATIO);
        let wave_generator_start = TAU * rng.uniform();
        let output_start = TAU * rng.uniform();
        let gain = 1.0 + self.torque_gain_error * (2.0 * rng.uniform() - 1.0);
        let mut s = self.relaxed();
        let mut out = Vec::new();
        let mut zero = None;
        for command in self.profile() {
            let r = if held {
                self.step_held(&mut s, command)
            } else {
                let actual = if ideal { command } else { command * gain };
                self.step_locked(&mut s, actual)
            };
            // θ_wi = −N a, θ_fo = o, both offset by the start angles.
            let motor = wave_generator_start - RATIO * r.input;
            let link = output_start + r.output;
            let (torsion, tau_f) = if ideal {
                (-r.torsion, -r.flexspline_torque)
            } else {
                let e = ke.error(motor, link);
                let m = self.motor_encoder.read(motor + RATIO * e, &mut rng) / RATIO;
                let l = self.link_encoder.read(link, &mut rng);
                let noise = 0.5 * TORQUE_SENSOR_RESOLUTION * rng.gaussian();
                let t = ((-r.flexspline_torque + noise) / TORQUE_SENSOR_RESOLUTION).round()
                    * TORQUE_SENSOR_RESOLUTION;
                // θ_fo + θ_wi/N with the start offsets removed below.
                (l - output_start + m - wave_generator_start / RATIO, t)
            };
            let z = *zero.get_or_insert(torsion);
            out.push(Sample {
                torsion: torsion - z,
                flexspline_torque: tau_f,
                wave_generator_torque: if held { 0.0 } else { command / RATIO },
                true_torsion: -r.torsion,
                true_flexspline_torque: -r.flexspline_torque,
                true_wave_generator_torque: r.wave_generator_torque / RATIO,
                motor_angle: motor,
            });
        }
        out
    }

    /// The first experiment of §2.4 (Fig. 2.17–2.20): output locked, the
    /// [`profile`](Self::profile) commanded at the motor. `ideal` records
    /// the plant's truth without kinematic error, sensors or gain error.
    pub fn locked_output(&self, seed: u64, ideal: bool) -> Vec<Sample> {
        self.record(seed, ideal, false)
    }

    /// The second experiment of §2.4 (Fig. 2.21–2.22): input held, the
    /// [`profile`](Self::profile) applied as external torque at the output.
    pub fn held_input(&self, seed: u64, ideal: bool) -> Vec<Sample> {
        self.record(seed, ideal, true)
    }

    /// A one-line description for tables.
    pub fn label(&self) -> String {
        format!(
            "{}/{}/mesh {:.1} N·m/share {:.1}/A {:.0} N·m/ripple {:.0e}",
            self.backbone.name(),
            self.wave_generator.name(),
            self.mesh_friction.breakaway(),
            self.node_share,
            self.amplitude,
            self.ripple
        )
    }
}

/// Which hand-written wave-generator shape a family member uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BearingShape {
    /// [`WaveGeneratorCompliance::Hyperbolic`] with `T_h` half the mesh
    /// break-away torque.
    Hyperbolic,
    /// [`WaveGeneratorCompliance::BilinearStop`] with the corner at 0.8 of
    /// the mesh break-away torque and a stop 25 times stiffer.
    BilinearStop,
}

/// Open choices of one family member, before calibration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlantChoice {
    /// Backbone shape.
    pub backbone: FlexsplineBackbone,
    /// Bearing shape.
    pub bearing: BearingShape,
    /// Mesh break-away torque (output side), N·m.
    pub mesh_breakaway: f64,
    /// Share of `Ψ` from the mesh/bearing mechanism, in `(0, 1]`.
    pub node_share: f64,
}

/// Scale on a log scale by bisection until `width(scale)` (increasing)
/// equals `target`.
fn calibrate_scale(width: impl Fn(f64) -> f64, target: f64, lo: f64, hi: f64) -> f64 {
    let (mut lo, mut hi) = (lo.ln(), hi.ln());
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if width(mid.exp()) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi)).exp()
}

/// A calibrated drive for one choice: the bearing compliance scaled so the
/// mesh/bearing mechanism alone gives `node_share·Ψ` of catalogue loop
/// width, then the flexspline's hysteresis break-away scaled so the whole
/// drive gives `Ψ` ([`HYSTERESIS_LOSS`]). Amplitude, ripple and sensors
/// are filled in by [`family`].
pub fn calibrate(choice: &PlantChoice) -> DrivePlant {
    let f = choice.mesh_breakaway;
    let bearing = match choice.bearing {
        BearingShape::Hyperbolic => WaveGeneratorCompliance::Hyperbolic {
            limit: 1e-4,
            knee: 0.5 * f,
        },
        BearingShape::BilinearStop => WaveGeneratorCompliance::BilinearStop {
            soft: 0.8 * f / 1e-4,
            corner: 0.8 * f,
            stop: 25.0 * 0.8 * f / 1e-4,
        },
    };
    let mut plant = DrivePlant {
        backbone: choice.backbone,
        flexspline_hysteresis: MaxwellSlip { elements: vec![] },
        wave_generator: bearing,
        mesh_friction: MaxwellSlip::from_shares(f, &SLIP_SHARES, &MESH_PRESLIDING),
        node_share: choice.node_share,
        amplitude: 11.0,
        ripple: 5e-6,
        motor_encoder: QuantizingEncoder {
            counts_per_rev: 2000.0,
            noise_counts: 0.1,
        },
        link_encoder: QuantizingEncoder {
            counts_per_rev: (1u32 << 17) as f64,
            noise_counts: 0.1,
        },
        torque_gain_error: 0.02,
    };
    let node_target = choice.node_share * HYSTERESIS_LOSS;
    let s = calibrate_scale(
        |s| {
            let mut p = plant.clone();
            p.wave_generator = bearing.scaled(s);
            p.catalogue_loop_width()
        },
        node_target,
        1e-3,
        1e2,
    );
    plant.wave_generator = bearing.scaled(s);
    if choice.node_share < 1.0 {
        let shape =
            |total: f64| MaxwellSlip::from_shares(total, &SLIP_SHARES, &FLEXSPLINE_PRESLIDING);
        let total = calibrate_scale(
            |t| {
                let mut p = plant.clone();
                p.flexspline_hysteresis = shape(t);
                p.catalogue_loop_width()
            },
            HYSTERESIS_LOSS,
            1e-3,
            20.0,
        );
        plant.flexspline_hysteresis = shape(total);
    }
    plant
}

/// The open choices swept by the full family: three backbones (rounded
/// knees of width 0.3 `y1`, monotone spline with a 0.8 `K1` start,
/// quadratic stiffening), two bearing shapes, the mesh break-away at the
/// two torques the thesis measures (`N τ_fs = 1.2` and `τ_fb = 2.0` N·m),
/// and three splits of `Ψ` (node share 1.0, 0.6, 0.3).
pub fn choices() -> Vec<PlantChoice> {
    let backbones = [
        FlexsplineBackbone::rounded_knees(&CATALOGUE, 0.3),
        FlexsplineBackbone::monotone_spline(&CATALOGUE, 0.8),
        FlexsplineBackbone::quadratic_stiffening(&CATALOGUE),
    ];
    let mut v = Vec::new();
    for backbone in backbones {
        for bearing in [BearingShape::Hyperbolic, BearingShape::BilinearStop] {
            for mesh_breakaway in [RATIO * STARTING_TORQUE, BACKDRIVE_TORQUE] {
                for node_share in [1.0, 0.6, 0.3] {
                    v.push(PlantChoice {
                        backbone,
                        bearing,
                        mesh_breakaway,
                        node_share,
                    });
                }
            }
        }
    }
    v
}

/// Peak torques swept for the Fig. 2.17/2.21 profiles, N·m (the thesis does
/// not state them; the Maxon 218014's 18.8 N·cm is 18.8 N·m at the output).
pub const AMPLITUDES: [f64; 3] = [6.0, 11.0, 16.0];
/// Tooth-pass ripple amplitudes swept, rad (not in the thesis).
pub const RIPPLES: [f64; 2] = [5e-6, 4e-5];

/// The plant family: every calibrated [`choices`] member at every
/// [`AMPLITUDES`] and [`RIPPLES`] value (216 plants).
pub fn family() -> Vec<DrivePlant> {
    expand(&choices(), &AMPLITUDES, &RIPPLES)
}

/// A small family for quick checks: the two extreme splits (node share 1.0
/// and 0.3) on the spline and quadratic backbones, hyperbolic bearing,
/// `τ_fb` mesh friction, at 11 N·m and the small ripple (4 plants).
pub fn quick_family() -> Vec<DrivePlant> {
    let c: Vec<PlantChoice> = choices()
        .into_iter()
        .filter(|c| {
            c.backbone.name() != "rounded-knees"
                && c.bearing == BearingShape::Hyperbolic
                && c.mesh_breakaway == BACKDRIVE_TORQUE
                && c.node_share != 0.6
        })
        .collect();
    expand(&c, &[11.0], &[5e-6])
}

fn expand(choices: &[PlantChoice], amplitudes: &[f64], ripples: &[f64]) -> Vec<DrivePlant> {
    let mut v = Vec::new();
    for c in choices {
        let base = calibrate(c);
        for &amplitude in amplitudes {
            for &ripple in ripples {
                v.push(DrivePlant {
                    amplitude,
                    ripple,
                    ..base.clone()
                });
            }
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Calibration hits the catalogue's `Ψ` (total) for every choice.
    #[test]
    fn calibrated_loops_have_the_catalogue_width() {
        for c in choices().iter().step_by(5) {
            let p = calibrate(c);
            let w = p.catalogue_loop_width();
            assert!(
                (w / HYSTERESIS_LOSS - 1.0).abs() < 0.02,
                "{}: {w}",
                p.label()
            );
        }
    }

    /// With the output locked and no mesh friction, the torsion is the
    /// backbone's plus the bearing's at the same torque (a hand check of
    /// the node balance).
    #[test]
    fn locked_step_without_friction_is_the_series_sum() {
        let c = &choices()[0];
        let mut p = calibrate(c);
        p.mesh_friction = MaxwellSlip { elements: vec![] };
        let mut s = p.relaxed();
        for t in [1.0, 5.0, -7.0] {
            let r = p.step_locked(&mut s, t);
            let expect = p.backbone.torsion(t) + p.wave_generator.torsion(t);
            assert!((r.torsion - expect).abs() < 1e-12, "{t}");
        }
    }

    /// Held input, no flexspline hysteresis: after loading past the mesh
    /// break-away and back to zero, the node is held by the friction, so
    /// the torsion is the bearing's at `±F` (the loop of eq. 2.35's story).
    #[test]
    fn held_input_loop_is_twice_the_bearing_torsion_at_breakaway() {
        let c = PlantChoice {
            node_share: 1.0,
            ..choices()[0]
        };
        let p = calibrate(&c);
        let f = p.mesh_friction.breakaway();
        let w = p.catalogue_loop_width();
        let by_hand = 2.0 * p.wave_generator.torsion(f);
        // Pre-sliding leaves the elements short of full slip by at most
        // their largest pre-sliding displacement.
        assert!(
            (w - by_hand).abs() < 2.0 * MESH_PRESLIDING[3],
            "{w} vs {by_hand}"
        );
    }
}
