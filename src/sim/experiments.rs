//! The experiments of thesis §2.4 and §3.2 on the simulated joint.
//!
//! Conventions: records use the chapter-2 quantities the models are written
//! in — torsion `Δθ = θ_fo + θ_wi/N` (eq. 2.13) from the encoder counts,
//! flexspline torque `τ_f = −τ_t` from the torque sensor, wave-generator
//! torque `τ_w = τ_m` (the motor torque in the chapter-4 sign; see
//! [`transmission`](super::transmission) for the mapping). Every model is
//! the library's: [`HarmonicDriveParams::torsion`] (eq. 2.30),
//! [`CataloguePiecewise::torsion`] (eq. 2.11),
//! [`CubicStiffness::torsion`] (eq. 2.10), [`WaveGeneratorTorqueConfig`]
//! (eq. 2.40) and the estimator [`TorqueEstimatorConfig`] (eq. 3.8–3.10).

use super::mrr::{ModuleParams, Mrr, Sensors};
use super::transmission::{BackboneShape, DrivePlantParams, MeshFrictionPlant, SHD_17_100_K3};
use crate::estimation::torque::{
    TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings, TorqueEstimatorState,
};
use crate::harmonic_drive::kinematic_error::{KinematicErrorFit, KinematicErrorModel};
use crate::harmonic_drive::{
    CatalogueCurve, CatalogueData, CataloguePiecewise, CubicStiffness, HarmonicDriveParams,
    WaveGeneratorTorqueConfig, WaveGeneratorTorqueParams, WaveGeneratorTorqueState,
};
use crate::scalar::{Scalar, I16F16};

use core::f64::consts::TAU;

/// Back-driving friction torque measured in thesis §2.4, `τ_fb = 2.0 N·m`.
pub const BACKDRIVE_FRICTION: f64 = 2.0;

/// The models compared in the experiments, all identified from the
/// SHD-17-100 catalogue data of §2.4.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Models {
    /// The proposed model, eq. (2.30), identified by eq. (2.33)–(2.37).
    pub proposed: HarmonicDriveParams,
    /// The catalogue piecewise model, eq. (2.11).
    pub piecewise: CataloguePiecewise,
    /// The cubic model, eq. (2.10), through the catalogue knees.
    pub cubic: CubicStiffness,
}

impl Models {
    /// Identify all three from [`CatalogueData::SHD_17_100`] (and `K3`).
    pub fn shd_17_100() -> Self {
        let d = CatalogueData::SHD_17_100;
        let piecewise = CataloguePiecewise::try_new(CatalogueCurve {
            k1: d.k1,
            k2: d.k2,
            k3: SHD_17_100_K3,
            t1: d.t1,
            t2: d.t2,
        })
        .expect("valid");
        Models {
            proposed: d.identify().expect("valid"),
            piecewise,
            cubic: CubicStiffness::through_catalogue_knees(&piecewise).expect("valid"),
        }
    }
}

/// Error statistics of a model's torsion (or torque) prediction.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ErrorStats {
    /// Root mean square, same unit as the data.
    pub rms: f64,
    /// Largest (most positive) error.
    pub max: f64,
    /// Smallest (most negative) error.
    pub min: f64,
}

impl ErrorStats {
    /// Statistics of a set of errors (zeros for an empty set).
    pub fn of<I: IntoIterator<Item = f64>>(errors: I) -> Self {
        let (mut n, mut s2) = (0usize, 0.0);
        let (mut max, mut min) = (f64::NEG_INFINITY, f64::INFINITY);
        for e in errors {
            n += 1;
            s2 += e * e;
            max = max.max(e);
            min = min.min(e);
        }
        if n == 0 {
            return ErrorStats::default();
        }
        ErrorStats {
            rms: (s2 / n as f64).sqrt(),
            max,
            min,
        }
    }
}

/// Torsion `Δθ = θ_fo + θ_wi/N` (rad, eq. 2.13) from the counts of module
/// `i` (chapter-2 sign: `θ_wi = −q_m`).
pub fn measured_torsion(m: &ModuleParams, s: &Sensors, i: usize) -> f64 {
    let link = s.link_counts[i] as f64 * m.link_encoder.rad_per_count();
    let motor = -(s.motor_counts[i] as f64) * m.motor_encoder.rad_per_count();
    link + motor / m.drive.ratio
}

/// One recorded sample of the compliance experiments (chapter-2 signs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComplianceSample {
    /// Time, s.
    pub time: f64,
    /// Wave-generator (motor) torque used by the models, N·m.
    pub wave_generator_torque: f64,
    /// Flexspline torque from the torque sensor, N·m.
    pub flexspline_torque: f64,
    /// True flexspline torque `−τ_t`, N·m.
    pub true_flexspline_torque: f64,
    /// Motor angle `θ_wi`, rad (from the motor encoder).
    pub motor_angle: f64,
    /// Torsion measured by the encoders, eq. (2.13), rad.
    pub measured_torsion: f64,
    /// True torsion `θ_fo + θ_wi/N` of the plant, rad.
    pub true_torsion: f64,
    /// Eq. (2.30) at the measured `τ_f` and `τ_w`, rad.
    pub proposed: f64,
    /// Eq. (2.26) alone (the flexspline term of eq. 2.30, the
    /// wave-generator term left out) at the measured `τ_f`, rad.
    pub flexspline: f64,
    /// Eq. (2.11) at the measured `τ_f`, rad.
    pub piecewise: f64,
    /// Eq. (2.10) at the measured `τ_f`, rad.
    pub cubic: f64,
    /// Eq. (2.11) at the input torque `−N τ_w`, rad.
    pub piecewise_input: f64,
}

/// Results of a compliance experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct ComplianceResult {
    /// Recorded samples.
    pub samples: Vec<ComplianceSample>,
    /// Error of eq. (2.30) against the measured torsion, rad.
    pub proposed: ErrorStats,
    /// Error of eq. (2.26) alone (measured `τ_f`), rad.
    pub flexspline: ErrorStats,
    /// Error of eq. (2.11) (measured `τ_f`), rad.
    pub piecewise: ErrorStats,
    /// Error of eq. (2.10) (measured `τ_f`), rad.
    pub cubic: ErrorStats,
    /// Error of eq. (2.11) at the input torque `−N τ_w`, rad.
    pub piecewise_input: ErrorStats,
    /// Energy the plant dissipated in the drive's hysteresis: the loop
    /// integral `∮ τ_t dδ_c` over the run minus the change of stored
    /// energy, J (from the recorded true torque and compliance torsion).
    pub loop_energy: f64,
    /// The same dissipation predicted from the recorded torsion reversals
    /// by the Maxwell-slip law (each element slips `|Δδ| − 2F_i/k_i` per
    /// half cycle), J.
    pub maxwell_slip_energy: f64,
}

/// The plant's true transmission torque and chapter-2 torsion now.
fn truth(r: &Mrr) -> (f64, f64) {
    let n = r.modules()[0].drive.ratio;
    (
        r.transmission_torques()[0],
        r.link_angles()[0] - r.motor_angles()[0] / n,
    )
}

fn record(
    models: &Models,
    r: &Mrr,
    s: &Sensors,
    tau_w: f64,
    (t_true, true_torsion): (f64, f64),
) -> ComplianceSample {
    let m = &r.modules()[0];
    let n = m.drive.ratio;
    let tau_f = -s.link_torque[0];
    ComplianceSample {
        time: s.time,
        wave_generator_torque: tau_w,
        flexspline_torque: tau_f,
        true_flexspline_torque: -t_true,
        motor_angle: -(s.motor_counts[0] as f64) * m.motor_encoder.rad_per_count(),
        measured_torsion: measured_torsion(m, s, 0),
        true_torsion,
        proposed: models.proposed.torsion(tau_f, tau_w),
        flexspline: models.proposed.flexspline().torsion(tau_f),
        piecewise: models.piecewise.torsion(tau_f),
        cubic: models.cubic.torsion(tau_f),
        piecewise_input: models.piecewise.torsion(-n * tau_w),
    }
}

fn finish(samples: Vec<ComplianceSample>, dissipation: (f64, f64)) -> ComplianceResult {
    let stat = |f: &dyn Fn(&ComplianceSample) -> f64| {
        ErrorStats::of(samples.iter().map(|s| f(s) - s.measured_torsion))
    };
    ComplianceResult {
        proposed: stat(&|s| s.proposed),
        flexspline: stat(&|s| s.flexspline),
        piecewise: stat(&|s| s.piecewise),
        cubic: stat(&|s| s.cubic),
        piecewise_input: stat(&|s| s.piecewise_input),
        loop_energy: dissipation.0,
        maxwell_slip_energy: dissipation.1,
        samples,
    }
}

/// Tracks the hysteresis dissipation of module 0 two ways (see
/// [`ComplianceResult::loop_energy`]).
///
/// The second way applies the elasto-plastic law to the sequence of
/// torsion reversals: starting from rest, element `i` slips `|Δ| − x_i` on
/// the first swing and `|Δ| − 2x_i` on every later half cycle of swing
/// `|Δ|` (`x_i = F_i/k_i`), dissipating `F_i` times the slip. A reversal
/// smaller than `2 min x_i` makes no element slip back, and the elements
/// retrace it elastically, so such reversals are skipped exactly.
struct Dissipation {
    prev: Option<(f64, f64)>,
    loop_integral: f64,
    start_energy: f64,
    threshold: f64,
    extremum: f64,
    last_reversal: f64,
    first: bool,
    direction: f64,
    slip_energy: f64,
}

impl Dissipation {
    fn new(r: &Mrr) -> Self {
        let (d, _) = Self::state(r);
        let threshold = 2.0
            * r.modules()[0]
                .drive
                .slip_elements
                .iter()
                .map(|e| e.slip_torque / e.stiffness)
                .fold(f64::INFINITY, f64::min);
        Dissipation {
            prev: None,
            loop_integral: 0.0,
            start_energy: r.drive_energy(0),
            threshold,
            extremum: d,
            last_reversal: d,
            first: true,
            direction: 0.0,
            slip_energy: 0.0,
        }
    }
    fn state(r: &Mrr) -> (f64, f64) {
        let m = &r.modules()[0];
        let (d, _, _) = m
            .drive
            .compliance_torsion(r.link_angles()[0], r.motor_angles()[0]);
        (d, r.transmission_torques()[0])
    }
    fn add(&mut self, r: &Mrr) {
        let (d, t) = Self::state(r);
        if let Some((d0, t0)) = self.prev {
            self.loop_integral += 0.5 * (t + t0) * (d - d0);
        }
        self.prev = Some((d, t));
        let step = d - self.extremum;
        if self.direction == 0.0 {
            if step.abs() > 0.0 {
                self.direction = step.signum();
                self.extremum = d;
            }
        } else if step * self.direction > 0.0 {
            self.extremum = d;
        } else if step.abs() > self.threshold {
            self.close_half_cycle(r);
            self.direction = -self.direction;
            self.extremum = d;
        }
    }
    fn close_half_cycle(&mut self, r: &Mrr) {
        let swing = (self.extremum - self.last_reversal).abs();
        let factor = if self.first { 1.0 } else { 2.0 };
        for e in &r.modules()[0].drive.slip_elements {
            let slip = swing - factor * e.slip_torque / e.stiffness;
            if slip > 0.0 {
                self.slip_energy += e.slip_torque * slip;
            }
        }
        self.first = false;
        self.last_reversal = self.extremum;
    }
    fn result(mut self, r: &Mrr) -> (f64, f64) {
        self.close_half_cycle(r);
        (
            self.loop_integral - (r.drive_energy(0) - self.start_energy),
            self.slip_energy,
        )
    }
}

/// Configuration of the locked-output experiment (thesis Fig. 2.17–2.20).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LockedOutputConfig {
    /// Initial motor torque amplitude, N·m (0.12 N·m loads the drive to
    /// `T2 = 12 N·m`).
    pub amplitude: f64,
    /// Frequency of the sinusoid, Hz.
    pub frequency: f64,
    /// Duration, s; the amplitude decreases linearly to 0 over it.
    pub duration: f64,
    /// Command (sample) period, s.
    pub control_period: f64,
    /// RK4 steps per sample.
    pub steps_per_period: usize,
    /// Record every `record_every`-th sample.
    pub record_every: usize,
    /// Maxwell-slip elements of the plant's drive (0: the drive's own
    /// hysteresis removed, leaving the motor friction's loop only).
    pub slip_elements: usize,
    /// Shape of the plant's elastic backbone.
    pub backbone: BackboneShape,
    /// Noise seed.
    pub seed: u64,
}

impl Default for LockedOutputConfig {
    fn default() -> Self {
        LockedOutputConfig {
            amplitude: 0.12,
            frequency: 0.5,
            duration: 20.0,
            control_period: 1e-3,
            steps_per_period: 10,
            record_every: 4,
            slip_elements: 8,
            backbone: BackboneShape::CataloguePiecewise,
            seed: 1,
        }
    }
}

/// Experiment 1 of §2.4: output locked, the motor driven open loop with a
/// sinusoidal torque of decreasing amplitude (Fig. 2.17); records torsion
/// versus input torque (Fig. 2.18) and the models' errors (Fig. 2.19–2.20).
pub fn locked_output(cfg: &LockedOutputConfig) -> ComplianceResult {
    let models = Models::shd_17_100();
    let mut module = ModuleParams::thesis_joint();
    module.link_locked = true;
    module.drive = DrivePlantParams::from_catalogue(
        &CatalogueData::SHD_17_100,
        SHD_17_100_K3,
        cfg.backbone,
        cfg.slip_elements,
        Some(KinematicErrorModel::table_3_2()),
    )
    .expect("catalogue constants are valid");
    let mut r = Mrr::try_new(
        vec![module],
        [0.0, 0.0, -9.81],
        cfg.control_period,
        cfg.steps_per_period,
        cfg.seed,
    )
    .expect("valid plant");
    let mut dis = Dissipation::new(&r);
    let samples_total = (cfg.duration / cfg.control_period).round() as usize;
    let mut samples = Vec::new();
    for k in 0..samples_total {
        let t = k as f64 * cfg.control_period;
        let tau = cfg.amplitude * (1.0 - t / cfg.duration) * (TAU * cfg.frequency * t).sin();
        let t_true = truth(&r);
        let mut ctl = |_: &Sensors, out: &mut [f64]| out[0] = tau;
        let s = r.sample(&mut ctl, &mut |_, _| {});
        if k % cfg.record_every == 0 {
            samples.push(record(&models, &r, &s, tau, t_true));
        }
        dis.add(&r);
    }
    let d = dis.result(&r);
    finish(samples, d)
}

/// The locked-output experiment of [`locked_output`] (same torque
/// schedule: `cfg.amplitude`, `frequency`, `duration`, `control_period`,
/// `record_every`) on the Fig. 2.7 plant [`MeshFrictionPlant`], evaluated
/// quasi-statically: the motor torque `τ_m` loads the wave generator
/// (`T = N τ_m`), the mesh friction passes `τ = clamp(τ, T − F, T + F)` to
/// the locked flexspline, and the encoders read `δ = f(τ) + g_w(T)`
/// exactly (no rotor dynamics, motor friction, kinematic error or sensor
/// noise). Records and errors use the chapter-2 signs of [`locked_output`]
/// (`Δθ = −δ`, `τ_f = −τ`, `τ_w = τ_m`). The dissipation fields are 0.
pub fn locked_output_mesh_friction(
    plant: &MeshFrictionPlant,
    cfg: &LockedOutputConfig,
) -> ComplianceResult {
    let models = Models::shd_17_100();
    let n = plant.ratio;
    let samples_total = (cfg.duration / cfg.control_period).round() as usize;
    let mut flex = 0.0;
    let mut samples = Vec::new();
    for k in 0..samples_total {
        let t = k as f64 * cfg.control_period;
        let tau_m = cfg.amplitude * (1.0 - t / cfg.duration) * (TAU * cfg.frequency * t).sin();
        let wg = n * tau_m;
        flex = plant.flexspline_torque(flex, wg);
        if k % cfg.record_every == 0 {
            let torsion = -plant.torsion(flex, wg);
            let tau_f = -flex;
            samples.push(ComplianceSample {
                time: t,
                wave_generator_torque: tau_m,
                flexspline_torque: tau_f,
                true_flexspline_torque: tau_f,
                motor_angle: 0.0,
                measured_torsion: torsion,
                true_torsion: torsion,
                proposed: models.proposed.torsion(tau_f, tau_m),
                flexspline: models.proposed.flexspline().torsion(tau_f),
                piecewise: models.piecewise.torsion(tau_f),
                cubic: models.cubic.torsion(tau_f),
                piecewise_input: models.piecewise.torsion(-n * tau_m),
            });
        }
    }
    finish(samples, (0.0, 0.0))
}

/// The plant structures of the model-ranking sweep (errata E2.9).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlantStructure {
    /// One compliance (backbone plus Maxwell-slip loop of width `Ψ`
    /// centred on it) between motor and link, simulated with the rotor,
    /// motor friction, kinematic error and sensors ([`locked_output`]).
    Centred(BackboneShape),
    /// Fig. 2.7: wave-generator compliance, mesh friction, flexspline
    /// compliance ([`MeshFrictionPlant::shd_17_100`],
    /// [`locked_output_mesh_friction`]).
    MeshFriction,
}

impl PlantStructure {
    /// A short label for tables.
    pub fn name(self) -> &'static str {
        match self {
            PlantStructure::Centred(shape) => shape.name(),
            PlantStructure::MeshFriction => "Fig. 2.7 mesh friction",
        }
    }
}

/// One row of the model-ranking sweep: RMS torsion error (rad) of each
/// model in the locked-output experiment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RankingRow {
    /// The plant.
    pub structure: PlantStructure,
    /// Initial drive-torque amplitude `N·A` (link side), N·m.
    pub drive_amplitude: f64,
    /// Eq. (2.30), the proposed model.
    pub proposed: f64,
    /// Eq. (2.26) alone.
    pub flexspline: f64,
    /// Eq. (2.11), the catalogue model.
    pub piecewise: f64,
    /// Eq. (2.10), the cubic model.
    pub cubic: f64,
}

impl RankingRow {
    /// Whether eq. (2.30) has a smaller RMS error than both classic
    /// models, (2.11) and (2.10).
    pub fn proposed_beats_classic(&self) -> bool {
        self.proposed < self.piecewise && self.proposed < self.cubic
    }
}

/// The locked-output model comparison on `structure` with an initial drive
/// torque amplitude of `drive_amplitude` N·m (motor amplitude
/// `drive_amplitude/N`), the other settings of [`LockedOutputConfig::default`].
pub fn model_ranking(structure: PlantStructure, drive_amplitude: f64) -> RankingRow {
    let cfg = LockedOutputConfig {
        amplitude: drive_amplitude / CatalogueData::SHD_17_100.ratio,
        ..LockedOutputConfig::default()
    };
    let r = match structure {
        PlantStructure::Centred(backbone) => locked_output(&LockedOutputConfig { backbone, ..cfg }),
        PlantStructure::MeshFriction => {
            locked_output_mesh_friction(&MeshFrictionPlant::shd_17_100(), &cfg)
        }
    };
    RankingRow {
        structure,
        drive_amplitude,
        proposed: r.proposed.rms,
        flexspline: r.flexspline.rms,
        piecewise: r.piecewise.rms,
        cubic: r.cubic.rms,
    }
}

/// Configuration of the back-driven experiment (thesis Fig. 2.21–2.22).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BackDrivenConfig {
    /// Initial external torque amplitude on the link, N·m.
    pub amplitude: f64,
    /// Frequency, Hz.
    pub frequency: f64,
    /// Duration, s (amplitude decreasing linearly to 0).
    pub duration: f64,
    /// Controller sample period, s.
    pub control_period: f64,
    /// RK4 steps per sample.
    pub steps_per_period: usize,
    /// Record every `record_every`-th sample.
    pub record_every: usize,
    /// Motor position-hold gains: stiffness (N·m/rad) and damping
    /// (N·m·s/rad), motor side.
    pub hold_gains: (f64, f64),
    /// Noise seed.
    pub seed: u64,
}

impl Default for BackDrivenConfig {
    fn default() -> Self {
        BackDrivenConfig {
            amplitude: 10.0,
            frequency: 0.25,
            duration: 20.0,
            control_period: 1e-3,
            steps_per_period: 10,
            record_every: 4,
            hold_gains: (0.5, 3.3e-3),
            seed: 2,
        }
    }
}

/// Results of the back-driven experiment: the compliance comparison with
/// `τ_w` from eq. (2.40) (`proposed`), and with `τ_w` the actual motor
/// command (`proposed_command`).
#[derive(Debug, Clone, PartialEq)]
pub struct BackDrivenResult {
    /// Models with `τ_w` from eq. (2.40) (`τ_fb` = 2.0 N·m).
    pub compliance: ComplianceResult,
    /// Error of eq. (2.30) with `τ_w` = the holding controller's command.
    pub proposed_command: ErrorStats,
}

/// Experiment 2 of §2.4: the motor held by a position controller, a
/// bidirectional torque of decreasing amplitude applied to the link
/// (Fig. 2.21); the wave-generator torque for eq. (2.30) comes from the
/// back-driving friction play of eq. (2.40) (library
/// [`WaveGeneratorTorqueConfig`]).
pub fn back_driven(cfg: &BackDrivenConfig) -> BackDrivenResult {
    let models = Models::shd_17_100();
    let module = ModuleParams::thesis_joint();
    let (kp, kd) = cfg.hold_gains;
    let q_m = module.motor_encoder.rad_per_count();
    let mut r = Mrr::try_new(
        vec![module],
        [0.0, 0.0, -9.81],
        cfg.control_period,
        cfg.steps_per_period,
        cfg.seed,
    )
    .expect("valid plant");
    let n = r.modules()[0].drive.ratio;
    let play = WaveGeneratorTorqueConfig::<f64>::new(
        &WaveGeneratorTorqueParams::try_new(crate::harmonic_drive::WaveGeneratorTorqueSettings {
            backdrive_friction: BACKDRIVE_FRICTION,
            ratio: n,
        })
        .expect("valid"),
    );
    let mut play_state = WaveGeneratorTorqueState::default();
    let mut dis = Dissipation::new(&r);
    let mut prev_counts: Option<i64> = None;
    let samples_total = (cfg.duration / cfg.control_period).round() as usize;
    let mut samples = Vec::new();
    let mut cmd_err = Vec::new();
    let (amp, f, dur, dt) = (
        cfg.amplitude,
        cfg.frequency,
        cfg.duration,
        cfg.control_period,
    );
    for k in 0..samples_total {
        let t_true = truth(&r);
        let mut ctl = |s: &Sensors, out: &mut [f64]| {
            let c = s.motor_counts[0];
            let speed = prev_counts.map_or(0.0, |p| (c - p) as f64 * q_m / dt);
            prev_counts = Some(c);
            out[0] = -kp * c as f64 * q_m - kd * speed;
        };
        let mut ext = |t: f64, m: &mut Mrr| {
            m.external_torque[0] = amp * (1.0 - t / dur) * (TAU * f * t).sin();
        };
        let s = r.sample(&mut ctl, &mut ext);
        let tau_f = -s.link_torque[0];
        let tau_w = play.update(&mut play_state, tau_f);
        let applied = r.applied_motor_torque()[0];
        if k % cfg.record_every == 0 {
            let rec = record(&models, &r, &s, tau_w, t_true);
            cmd_err.push(models.proposed.torsion(tau_f, applied) - rec.measured_torsion);
            samples.push(rec);
        }
        dis.add(&r);
    }
    let d = dis.result(&r);
    BackDrivenResult {
        compliance: finish(samples, d),
        proposed_command: ErrorStats::of(cmd_err),
    }
}

/// The estimator variants evaluated in the Table 3.3 experiment.
///
/// The last entry feeds `τ_w = 0`, which switches off the wave-generator
/// term of eq. (3.9) and leaves the flexspline model of eq. (2.26) alone:
/// it isolates that term's contribution.
pub const ESTIMATORS: [&str; 7] = [
    "f64, no KE",
    "f64, KE Table 3.2",
    "f64, KE fitted",
    "I16F16, no KE",
    "I16F16, KE Table 3.2",
    "I16F16, KE fitted",
    "f64, KE fitted, tau_w = 0",
];

/// One row of the Table 3.3 reproduction.
#[derive(Debug, Clone, PartialEq)]
pub struct TorqueLevelResult {
    /// Motor torque command, N·m.
    pub motor_torque: f64,
    /// Largest link speed magnitude reached (signed), rad/s.
    pub max_speed: f64,
    /// Error statistics (estimate − true `τ_f`, N·m) per entry of
    /// [`ESTIMATORS`].
    pub errors: Vec<ErrorStats>,
    /// Largest |I16F16 − f64| difference with the fitted KE model, N·m.
    pub fixed_vs_float: f64,
    /// Any estimate saturated.
    pub saturated: bool,
}

/// Configuration of the Table 3.3 experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct TorqueEstimationConfig {
    /// Motor torque levels, N·m (thesis: 0, ±3, ±5, ±10 N·cm).
    pub motor_torques: Vec<f64>,
    /// Duration per level, s.
    pub duration: f64,
    /// Samples ignored at the start of each level (transient), s.
    pub settle: f64,
    /// Estimator (controller) sample period, s (the 4 ms servo tick).
    pub control_period: f64,
    /// RK4 steps per sample.
    pub steps_per_period: usize,
    /// Link speed of the kinematic-error calibration runs, rad/s.
    pub calibration_speed: f64,
    /// Shape of the plant's elastic backbone (calibration and runs).
    pub backbone: BackboneShape,
    /// Noise seed.
    pub seed: u64,
}

impl Default for TorqueEstimationConfig {
    fn default() -> Self {
        TorqueEstimationConfig {
            motor_torques: vec![0.0, 0.03, -0.03, 0.05, -0.05, 0.10, -0.10],
            duration: 8.0,
            settle: 0.5,
            control_period: 4e-3,
            steps_per_period: 40,
            calibration_speed: 0.5,
            backbone: BackboneShape::CataloguePiecewise,
            seed: 3,
        }
    }
}

/// Results of the Table 3.3 experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct TorqueEstimationResult {
    /// One row per motor torque level.
    pub levels: Vec<TorqueLevelResult>,
    /// The kinematic-error model fitted from the calibration runs.
    pub fitted_kinematic_error: KinematicErrorModel,
    /// Error statistics over all levels per entry of [`ESTIMATORS`].
    pub overall: Vec<ErrorStats>,
    /// What the wave-generator term of eq. (3.9) adds to the estimate:
    /// statistics over all levels of `"f64, KE fitted"` minus
    /// `"f64, KE fitted, tau_w = 0"`, N·m.
    pub wave_generator_shift: ErrorStats,
}

/// The thesis joint with its drive built on a backbone of `shape`.
fn joint_on(shape: BackboneShape) -> ModuleParams {
    let mut module = ModuleParams::thesis_joint();
    module.drive = DrivePlantParams::shd_17_100_on(shape);
    module
}

/// Estimator readings from the sensors (chapter-2 convention): link count
/// reduced to `[0, L)`, motor counter `θ_wi` counts as a wrapping `u32`.
pub fn estimator_counts(m: &ModuleParams, s: &Sensors, i: usize) -> (u32, u32) {
    let l = m.link_encoder.counts_per_rev as i64;
    (
        s.link_counts[i].rem_euclid(l) as u32,
        (-s.motor_counts[i]) as u32,
    )
}

/// Kinematic-error calibration as in §3.1: the joint is turned one output
/// revolution each way at constant speed with no load, and the torsion
/// left after subtracting the compliance model (eq. 2.30 at the measured
/// `τ_f` and the motor command) is fitted by eq. (3.7)
/// ([`KinematicErrorFit`]). Turning both ways cancels the hysteresis
/// offset of each direction, as eq. (2.38) does for the encoder offset.
pub fn calibrate_kinematic_error(cfg: &TorqueEstimationConfig) -> KinematicErrorModel {
    let models = Models::shd_17_100();
    let module = joint_on(cfg.backbone);
    let (qm, n) = (module.motor_encoder.rad_per_count(), module.drive.ratio);
    let mut r = Mrr::try_new(
        vec![module],
        [0.0, 0.0, -9.81],
        cfg.control_period,
        cfg.steps_per_period / 4,
        cfg.seed ^ 0xCA1,
    )
    .expect("valid plant");
    let mut fit = KinematicErrorFit::new();
    let dt = cfg.control_period;
    for dir in [1.0, -1.0] {
        let speed = dir * cfg.calibration_speed;
        let t_rev = TAU / cfg.calibration_speed;
        let ramp = 0.5;
        let total = ((t_rev + 2.0 * ramp) / dt).round() as usize;
        let start_q = r.motor_angles()[0];
        let mut prev: Option<i64> = None;
        let mut pos_ref = start_q;
        for k in 0..total {
            let t = k as f64 * dt;
            let v_ref = n * speed * (t / ramp).min(1.0);
            pos_ref += v_ref * dt;
            let mut cmd = 0.0;
            let mut ctl = |s: &Sensors, out: &mut [f64]| {
                let c = s.motor_counts[0];
                let v = prev.map_or(0.0, |p| (c - p) as f64 * qm / dt);
                prev = Some(c);
                out[0] = 0.05 * (pos_ref - c as f64 * qm) + 2e-3 * (v_ref - v);
                cmd = out[0];
            };
            let s = r.sample(&mut ctl, &mut |_, _| {});
            if t > ramp && t < ramp + t_rev {
                let m = &r.modules()[0];
                let torsion = measured_torsion(m, &s, 0);
                let link = s.link_counts[0] as f64 * m.link_encoder.rad_per_count();
                let motor = -(s.motor_counts[0] as f64) * qm;
                let model = models.proposed.torsion(-s.link_torque[0], cmd);
                fit.add_sample(link, motor, torsion - model)
                    .expect("finite samples");
            }
        }
        // Coast to rest before turning back.
        for _ in 0..(0.5 / dt) as usize {
            let mut ctl = |_: &Sensors, out: &mut [f64]| out[0] = 0.0;
            r.sample(&mut ctl, &mut |_, _| {});
        }
    }
    fit.solve().expect("a revolution determines the fit")
}

/// The hand of the thesis's operator, modelled as an impedance pulling the
/// link towards a slowly varying speed: `τ_ext = −B (q̇_l − v_h(t))`,
/// limited to ±15 N·m (B = 10 N·m·s/rad,
/// `v_h = 0.5 sin(2π·0.3 t) + 0.2 sin(2π·0.71 t + 1)` rad/s).
pub fn hand_torque(t: f64, link_speed: f64) -> f64 {
    let v_h = 0.5 * (TAU * 0.3 * t).sin() + 0.2 * (TAU * 0.71 * t + 1.0).sin();
    (-10.0 * (link_speed - v_h)).clamp(-15.0, 15.0)
}

/// Experiment 1 of §3.2 (Table 3.3): the joint open loop in torque mode at
/// several motor torques, a hand disturbing the link ([`hand_torque`]);
/// the estimator (eq. 3.8–3.10, library [`TorqueEstimatorConfig`]) runs
/// every sample on f64 and I16F16, without and with the kinematic-error
/// model (Table 3.2, and fitted by [`calibrate_kinematic_error`]); errors
/// are against the plant's true flexspline torque.
pub fn torque_estimation(cfg: &TorqueEstimationConfig) -> TorqueEstimationResult {
    let models = Models::shd_17_100();
    let fitted = calibrate_kinematic_error(cfg);
    let module = joint_on(cfg.backbone);
    let (l, m) = (
        module.link_encoder.counts_per_rev,
        module.motor_encoder.counts_per_rev,
    );
    let params = |ke: Option<KinematicErrorModel>| {
        TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive: models.proposed,
            kinematic_error: ke,
            link_counts_per_rev: l,
            motor_counts_per_rev: m,
            max_torque: 60.0,
        })
        .expect("valid")
    };
    let kes = [None, Some(KinematicErrorModel::table_3_2()), Some(fitted)];
    let f64_cfg: Vec<TorqueEstimatorConfig<f64>> = kes
        .iter()
        .map(|k| TorqueEstimatorConfig::new(&params(*k)))
        .collect();
    let fx_cfg: Vec<TorqueEstimatorConfig<I16F16>> = kes
        .iter()
        .map(|k| TorqueEstimatorConfig::new(&params(*k)))
        .collect();
    let mut levels = Vec::new();
    let mut all: Vec<Vec<f64>> = vec![Vec::new(); ESTIMATORS.len()];
    let mut shift = Vec::new();
    for (li, &tau_m) in cfg.motor_torques.iter().enumerate() {
        let mut r = Mrr::try_new(
            vec![module.clone()],
            [0.0, 0.0, -9.81],
            cfg.control_period,
            cfg.steps_per_period,
            cfg.seed.wrapping_add(li as u64),
        )
        .expect("valid plant");
        // Start at a different link angle per level (the thesis's runs did
        // not start at the encoder zero).
        let q0 = 0.9 * li as f64;
        r.set_state(&[q0], &[q0 * 100.0], &[0.0], &[0.0]);
        let s0 = r.read_sensors();
        let (_, c0) = estimator_counts(&module, &s0, 0);
        // Four f64 states: the three models, and the fitted one again for
        // the τ_w = 0 variant.
        let mut st_f: Vec<TorqueEstimatorState> = f64_cfg
            .iter()
            .chain(core::iter::once(&f64_cfg[2]))
            .map(|c| c.state(-s0.motor_counts[0], c0))
            .collect();
        let mut st_x: Vec<TorqueEstimatorState> = fx_cfg
            .iter()
            .map(|c| c.state(-s0.motor_counts[0], c0))
            .collect();
        let mut errs: Vec<Vec<f64>> = vec![Vec::new(); ESTIMATORS.len()];
        let (mut max_speed, mut fixed_vs_float, mut saturated) = (0.0f64, 0.0f64, false);
        let total = (cfg.duration / cfg.control_period).round() as usize;
        for k in 0..total {
            let truth = -r.transmission_torques()[0];
            let ext = |t: f64, m: &mut Mrr| {
                let v = m.link_speeds()[0];
                m.external_torque[0] = hand_torque(t, v);
            };
            // The estimator sees the readings of this sample and the
            // command it is about to apply.
            let s = r.read_sensors();
            let (cl, cm) = estimator_counts(&module, &s, 0);
            let mut est = [0.0; 7];
            for j in 0..3 {
                let e = f64_cfg[j].update(&mut st_f[j], cl, cm, tau_m);
                let x = fx_cfg[j].update(&mut st_x[j], cl, cm, I16F16::from_f64(tau_m * 1e3));
                saturated |= e.saturated || x.saturated;
                est[j] = e.torque;
                est[3 + j] = x.torque.to_f64();
            }
            est[6] = f64_cfg[2].update(&mut st_f[3], cl, cm, 0.0).torque;
            if k as f64 * cfg.control_period >= cfg.settle {
                for j in 0..7 {
                    errs[j].push(est[j] - truth);
                }
                fixed_vs_float = fixed_vs_float.max((est[5] - est[2]).abs());
                shift.push(est[2] - est[6]);
                let v = r.link_speeds()[0];
                if v.abs() > max_speed.abs() {
                    max_speed = v;
                }
            }
            r.set_motor_torque(&[tau_m]);
            for _ in 0..r.steps_per_period {
                let t = r.time();
                ext(t, &mut r);
                r.step();
            }
        }
        for j in 0..7 {
            all[j].extend_from_slice(&errs[j]);
        }
        levels.push(TorqueLevelResult {
            motor_torque: tau_m,
            max_speed,
            errors: errs.into_iter().map(ErrorStats::of).collect(),
            fixed_vs_float,
            saturated,
        });
    }
    TorqueEstimationResult {
        levels,
        fitted_kinematic_error: fitted,
        overall: all.into_iter().map(ErrorStats::of).collect(),
        wave_generator_shift: ErrorStats::of(shift),
    }
}

/// Loop width of a recorded torsion–torque loop at zero of `torque`:
/// the mean torsion at downward zero crossings minus that at upward ones
/// (linear interpolation), over the crossings in `[from, to)` s.
pub fn width_at_zero(
    samples: &[ComplianceSample],
    torque: impl Fn(&ComplianceSample) -> f64,
    torsion: impl Fn(&ComplianceSample) -> f64,
    from: f64,
    to: f64,
) -> f64 {
    // Samples are in time order: the windows inside `[from, to)` are those
    // of the slice of samples timed in it.
    let start = samples.partition_point(|s| s.time < from);
    let end = samples.partition_point(|s| s.time < to).max(start);
    loop_width(&samples[start..end], torque, torsion)
}

/// Width of a hysteresis loop where `torque` crosses zero, for samples of
/// any type in time order: the mean `torsion` at downward zero crossings
/// minus that at upward ones (linear interpolation between samples).
pub fn loop_width<T>(
    samples: &[T],
    torque: impl Fn(&T) -> f64,
    torsion: impl Fn(&T) -> f64,
) -> f64 {
    let (mut down, mut up) = (Vec::new(), Vec::new());
    for w in samples.windows(2) {
        let (t0, t1) = (torque(&w[0]), torque(&w[1]));
        if (t0 > 0.0) != (t1 > 0.0) && t0 != t1 {
            let a = t0 / (t0 - t1);
            let x = torsion(&w[0]) + a * (torsion(&w[1]) - torsion(&w[0]));
            if t1 < t0 {
                down.push(x);
            } else {
                up.push(x);
            }
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    mean(&down) - mean(&up)
}
