//! The chapter-4 experiments with the library's joint step in the loop, run
//! on the arm of bodies on the engine ([`EngineArm`]) or, for comparison,
//! on the thesis's own arm model ([`Mrr`], eq. 4.1–4.6): the runners, their
//! set-ups and the traces a figure draws.
//!
//! # Which drives
//! [`ArmPlant::Family`] drives the engine arm's joints with a member of the
//! independent joint family ([`FamilyDrives`]: its own backbone,
//! hysteresis, node friction, drawn kinematic error and pre-sliding
//! friction), the plant the figures' evidence rests on ([`ARM_FAMILY`]
//! names the members and seeds the report runs). [`ArmPlant::Engine`]
//! drives it with the library's drive plant ([`PlantDrives`]: Table 3.2's
//! eq. 3.7 kinematic error, the model the estimator subtracts, and friction
//! of eq. 4.8's form): a plant partly built from the models under test,
//! kept as a comparison. The criteria these runs are held
//! to live in `tests/engine_arm.rs` and `tests/engine_arm_modes.rs`.
//!
//! # The loop
//! Every [`CONTROL_TICK`] (4 ms, the thesis's period) each joint's
//! [`JointConfig::<S>::update`](crate::joint::JointConfig::update) reads
//! counts quantized from the plant's true angles (the estimator's link
//! counts per revolution, 2^17 in Table 4.1's preset, and its motor counts,
//! 2000; no noise), and its motor torque `τ_m` (N·m, positive driving the
//! link forward) is held over the tick. The plant steps in between: the
//! engine at its step ([`super::ARM_DT`] = 0.1 ms in [`super::arm_settings`]),
//! `Mrr` by RK4 at [`CONTROL_TICK`]` / `[`MRR_STEPS_PER_TICK`] (0.1 ms).
//! Angles are in rad, positive right-handed about the joint axis; torques in
//! N·m; an external torque on a link (a hand, an obstacle) is a generalized
//! force on its `q_l`, positive in the joint's positive sense.
//!
//! # Experiments
//! * [`arm_tracking`] — §4.4.1 active tracking (eq. 4.19–4.27, Table 4.1)
//!   on an arm of any modules: joint 1 follows a desired trajectory, the
//!   others hold 0; the joint-torque feedback is the crate's joint step (C,
//!   the estimate of eq. 3.8–3.10, mode manager in the loop) or, for
//!   Fig. 4.3's areas A and B, the same active law fed with no torque or
//!   with the drive's true transmission torque (a noiseless F/T sensor).
//! * [`joint_scenario`] — one joint under a hand or an obstacle: passive
//!   back-driving (§4.3, eq. 4.32/4.33, §4.4.2, Fig. 4.11–4.12,
//!   [`back_driving`]), the mode manager switching Active → Passive →
//!   Active on the interaction torque ([`mode_switching`]), and a
//!   collision detected on the estimated joint torque ([`collision`]).
//!   The mode manager and the detector are this crate's extension; the
//!   thesis switches modes by hand.
//!
//! # Two obstacles
//! [`Obstacle::Spring`] pushes back on the link as a one-sided spring and
//! damper on `q_l` (300 N·m/rad, 2 N·m·s/rad, from 0.15 rad): a torque this
//! crate writes, the same on `Mrr` and on the engine, so the two plants
//! can be compared. [`Obstacle::Contact`] is a rapier contact: a ball at the
//! link's tip ([`TipBall`]) and a fixed box ([`Wall::stop_for`]) placed so
//! that the ball touches it at 0.15 rad; the force is the engine's contact
//! force (its soft, frictionless contact constraint), read back as a
//! generalized force on `q_l` ([`EngineArm::contact_torque`]). `Mrr` has no
//! colliders, so the contact runs on the engine only; its stiffness is the
//! engine's (a few mm of allowed penetration), not a number of this crate.

use std::f64::consts::{PI, TAU};

use super::arm::{
    arm_settings, DriveModel, DriveState, EngineArm, PlantDrives, RotorBody, TipBall, Wall,
};
use super::family_drives::{family_member, FamilyDrives};
use super::world::EngineSettings;
use crate::control::{ControlInput, JointMode, ModeParams, ModeSettings, ReleaseRule};
use crate::error::ParamError;
use crate::estimation::collision::{CollisionParams, CollisionReaction, CollisionSettings};
use crate::joint::{JointConfig, JointParams, JointReadings, JointSettings, JointTarget};
use crate::scalar::units::quantize;
use crate::sim::closed_loop::{raised_cosine, JointTorqueFeedback};
use crate::sim::mrr::ModuleParams;
use crate::sim::Mrr;
use crate::Scalar;

/// The control period of every run here, s (the thesis's 4 ms).
pub const CONTROL_TICK: f64 = 4e-3;
/// `Mrr`'s RK4 steps per tick (0.1 ms steps).
pub const MRR_STEPS_PER_TICK: usize = 40;
/// Gravity of every run, m/s², base frame.
pub const ARM_GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];

/// Which plant a run steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArmPlant {
    /// The thesis's model, eq. (4.1)–(4.6), RK4 at 0.1 ms.
    Mrr,
    /// The arm of bodies on the engine, at these settings (e.g.
    /// [`arm_settings`] or its half step), its drives the library's drive
    /// plant and friction ([`PlantDrives`]: Table 3.2's eq. 3.7 kinematic
    /// error, the model the estimator subtracts, and friction of eq. 4.8's
    /// form) — kept as a comparison.
    Engine(EngineSettings),
    /// The arm of bodies on the engine, at these settings, its drives
    /// members of the independent joint family ([`FamilyDrives`]): member
    /// `member` of [`joint_family`](crate::sim::plants::joint_family) on every module, module `i`'s
    /// kinematic error drawn from seed `seed + i`.
    Family {
        /// Engine settings.
        settings: EngineSettings,
        /// Index into [`joint_family`](crate::sim::plants::joint_family) (0–23).
        member: usize,
        /// Seed of module 0's kinematic-error draw (odd seeds draw the
        /// large tooth-pass ripple).
        seed: u64,
    },
}

/// The family members and seeds the chapter-4 engine figures run on:
/// `(index into joint_family, seed)`. Member 2: rounded-knee backbone, the
/// loss all at the node, full motor friction; 14: spline backbone, 30 % of
/// the loss at the node, full friction (the quick family's first corner);
/// 17: quadratic backbone, all at the node, half friction (its second
/// corner). Seeds 1–3 (odd ones draw the large tooth-pass ripple). The
/// members' link inertia and payload are not used on the engine (the
/// arm's bodies are the link).
pub const ARM_FAMILY: [(usize, u64); 3] = [(2, 1), (14, 2), (17, 3)];

impl ArmPlant {
    /// The engine at [`arm_settings`] (0.1 ms, one substep).
    pub fn engine() -> Self {
        ArmPlant::Engine(arm_settings())
    }

    /// The engine at [`arm_settings`] on family member `member`
    /// (index into [`joint_family`](crate::sim::plants::joint_family)) with seed `seed`.
    pub fn family(member: usize, seed: u64) -> Self {
        ArmPlant::Family {
            settings: arm_settings(),
            member,
            seed,
        }
    }

    /// A label for tables: `"Mrr"`, `"engine dt 0.1 ms"` or
    /// `"engine dt 0.1 ms, family member 14 seed 2"`.
    pub fn label(&self) -> String {
        match self {
            ArmPlant::Mrr => "Mrr".into(),
            ArmPlant::Engine(s) => format!("engine dt {} ms", s.dt() * 1e3),
            ArmPlant::Family {
                settings,
                member,
                seed,
            } => format!(
                "engine dt {} ms, family member {member} seed {seed}",
                settings.dt() * 1e3
            ),
        }
    }
}

/// A plant the loop drives, one joint per module.
trait TickPlant {
    /// True link and motor angles, rad.
    fn angles(&self) -> (Vec<f64>, Vec<f64>);
    /// Link speed of module `i`, rad/s.
    fn link_speed(&self, i: usize) -> f64;
    /// Transmission torque of module `i`, N·m (a noiseless link-side
    /// torque sensor).
    fn transmission(&self, i: usize) -> f64;
    fn hold(&mut self, torque: &[f64]);
    fn set_external(&mut self, i: usize, torque: f64);
    /// One plant step; returns its length, s.
    fn step(&mut self) -> f64;
    fn steps_per_tick(&self) -> usize;
    /// The engine's contact torque on module 0's link over the last step,
    /// N·m (0 without a contact).
    fn contact_torque(&self) -> f64 {
        0.0
    }
}

impl TickPlant for Mrr {
    fn angles(&self) -> (Vec<f64>, Vec<f64>) {
        (self.link_angles().to_vec(), self.motor_angles().to_vec())
    }
    fn link_speed(&self, i: usize) -> f64 {
        self.link_speeds().get(i).copied().unwrap_or(0.0)
    }
    fn transmission(&self, i: usize) -> f64 {
        self.transmission_torques().get(i).copied().unwrap_or(0.0)
    }
    fn hold(&mut self, torque: &[f64]) {
        self.set_motor_torque(torque);
    }
    fn set_external(&mut self, i: usize, torque: f64) {
        if let Some(t) = self.external_torque.get_mut(i) {
            *t = torque;
        }
    }
    fn step(&mut self) -> f64 {
        Mrr::step(self);
        self.step_size()
    }
    fn steps_per_tick(&self) -> usize {
        MRR_STEPS_PER_TICK
    }
}

impl<D: DriveModel> TickPlant for EngineArm<D> {
    fn angles(&self) -> (Vec<f64>, Vec<f64>) {
        (self.link_angles(), self.motor_angles())
    }
    fn link_speed(&self, i: usize) -> f64 {
        self.drive_states().get(i).map_or(0.0, |s| s.link_speed)
    }
    fn transmission(&self, i: usize) -> f64 {
        self.drive_torques().get(i).map_or(0.0, |d| d.transmission)
    }
    fn hold(&mut self, torque: &[f64]) {
        self.set_motor_torque(torque);
    }
    fn set_external(&mut self, i: usize, torque: f64) {
        let mut t = vec![0.0; self.len()];
        if let Some(x) = t.get_mut(i) {
            *x = torque;
        }
        self.set_external_torque(&t);
    }
    fn step(&mut self) -> f64 {
        EngineArm::step(self);
        self.settings().dt()
    }
    fn steps_per_tick(&self) -> usize {
        (CONTROL_TICK / self.settings().dt()).round() as usize
    }
    fn contact_torque(&self) -> f64 {
        EngineArm::contact_torque(self)
    }
}

/// The arm of `modules` on `plant`, at rest at `q_l = 0`. With
/// `hold_gravity` every drive starts twisted to carry the gravity torque
/// there (motor angles from `Mrr`'s inversion of the drive plant, the same
/// start on both plants; on a family member, its own drive loaded to the
/// same gravity torque, [`FamilyDrives::load`]); otherwise at `q_m = 0`
/// (a family member: its zero-load motor angle), drives relaxed. Full
/// drive plants and their friction on every plant.
fn build(
    modules: &[ModuleParams],
    plant: ArmPlant,
    hold_gravity: bool,
    contact: Option<(&TipBall, &Wall)>,
) -> Result<Box<dyn TickPlant>, ParamError> {
    let n = modules.len();
    let zero = vec![0.0; n];
    let mut model = Mrr::try_new(
        modules.to_vec(),
        ARM_GRAVITY,
        CONTROL_TICK,
        MRR_STEPS_PER_TICK,
        1,
    )?;
    let qm0 = if hold_gravity {
        let g0 = model.gravity_torques();
        model.motor_angles_for_torque(&zero, &g0)
    } else {
        zero.clone()
    };
    match plant {
        ArmPlant::Mrr => {
            if contact.is_some() {
                return Err(ParamError::OutOfRange {
                    name: "plant",
                    value: 0.0,
                    min: 1.0,
                    max: 1.0,
                });
            }
            model.set_state(&zero, &qm0, &zero, &zero);
            Ok(Box::new(model))
        }
        ArmPlant::Engine(settings) => {
            let start: Vec<DriveState> = qm0
                .iter()
                .map(|&q| DriveState {
                    motor_angle: q,
                    ..Default::default()
                })
                .collect();
            let drive = PlantDrives::of(modules, true, &start);
            engine_arm(modules, drive, settings, &qm0, contact)
        }
        ArmPlant::Family {
            settings,
            member,
            seed,
        } => {
            let plant = family_member(member)?;
            let seeds: Vec<u64> = (0..n as u64).map(|i| seed.wrapping_add(i)).collect();
            let mut drive = FamilyDrives::try_new(modules, vec![plant; n], &seeds, &zero)?;
            if hold_gravity {
                let g0 = model.gravity_torques();
                for (i, g) in g0.iter().enumerate() {
                    drive.load(i, *g)?;
                }
            }
            let qm = drive.motor_angles();
            engine_arm(modules, drive, settings, &qm, contact)
        }
    }
}

/// The engine arm of `modules` on `drive`, at rest at `q_l = 0` with the
/// motor angles `qm`, with the contact if any.
fn engine_arm<D: DriveModel + 'static>(
    modules: &[ModuleParams],
    drive: D,
    settings: EngineSettings,
    qm: &[f64],
    contact: Option<(&TipBall, &Wall)>,
) -> Result<Box<dyn TickPlant>, ParamError> {
    let zero = vec![0.0; modules.len()];
    let mut arm = EngineArm::try_new(modules, ARM_GRAVITY, RotorBody::default(), drive, settings)?;
    if let Some((ball, wall)) = contact {
        arm.add_wall(ball, wall)?;
    }
    arm.set_state(&zero, qm, &zero, &zero);
    Ok(Box::new(arm))
}

/// Count readings of true angles (rad) for a joint of `params`: the link's
/// absolute count and the motor's free-running counter.
fn counter(params: &JointParams) -> impl Fn(f64, f64) -> (u32, u32) {
    let lc = params.settings().estimator.link_counts_per_rev() as f64;
    let mc = params.settings().estimator.motor_counts_per_rev() as f64;
    move |ql, qm| {
        (
            (ql / TAU * lc).floor().rem_euclid(lc) as u32,
            ((qm / TAU * mc).floor() as i64) as u32,
        )
    }
}

fn mode_index(m: JointMode) -> usize {
    match m {
        JointMode::Active => 0,
        JointMode::Hold => 1,
        JointMode::Passive => 2,
    }
}

// ---------------------------------------------------------------------------
// Active tracking (§4.4.1).

/// Desired link angle (rad), speed (rad/s) and acceleration (rad/s²) at `t`
/// (s).
pub type Trajectory = fn(f64) -> (f64, f64, f64);

/// An active-tracking run ([`arm_tracking`]).
#[derive(Debug, Clone)]
pub struct ArmTrackingConfig {
    /// The arm, module 0 on the base.
    pub modules: Vec<ModuleParams>,
    /// Every joint's step (the same for all).
    pub joint: JointParams,
    /// Joint 1's torque feedback: [`JointTorqueFeedback::Estimated`] runs
    /// the crate's joint step (`JointConfig::update`, mode manager in the
    /// loop); `None` and `Sensor` run the same joint's measurement
    /// (`JointConfig::measure`) and its active law (eq. 4.19–4.27) with
    /// `τ̂_t` replaced by 0 or by the drive's transmission torque. The
    /// other joints use the same choice.
    pub feedback: JointTorqueFeedback,
    /// Joint 1's desired trajectory; the others hold 0.
    pub desired: Trajectory,
    /// Length of the run, s.
    pub duration: f64,
    /// Errors are counted from this time on, s.
    pub settle: f64,
}

/// Joint 1's reference of the tests' arm runs: at rest until 0.2 s, then
/// `0.2 (1 − cos(π (t − 0.2)))/2` rad.
pub fn half_cosine_from_rest(t: f64) -> (f64, f64, f64) {
    let (q, v, a) = raised_cosine(0.1, 2.0, (t - 0.2).max(0.0));
    (q, v, if t >= 0.2 { a } else { 0.0 })
}

/// Fig. 4.2's desired trajectory: `0.25 (1 − cos(2π t/4 s))` rad (the
/// raised cosine of [`crate::sim::closed_loop::TrackingConfig::table_4_1`]).
pub fn raised_cosine_4s(t: f64) -> (f64, f64, f64) {
    raised_cosine(0.25, 4.0, t)
}

/// What [`arm_tracking`] measured. Per-tick traces are sampled at the
/// start of each tick, before the joint step.
#[derive(Debug, Clone, Default)]
pub struct ArmTrackingRun {
    /// Tick times, s.
    pub time: Vec<f64>,
    /// Joint 1's desired link angle, rad.
    pub desired: Vec<f64>,
    /// Link angles per tick, one per module, rad.
    pub link: Vec<Vec<f64>>,
    /// Joint 1's link error `q_l − q_l^d` per tick, rad.
    pub link_error: Vec<f64>,
    /// Motor torques `τ_m` commanded (held over the tick), N·m.
    pub motor_torque: Vec<Vec<f64>>,
    /// Estimated joint torques `τ̂_t` (eq. 3.8–3.10, eq. 4.1 sign), N·m.
    pub estimate: Vec<Vec<f64>>,
    /// Joint 1's mode per tick.
    pub mode: Vec<JointMode>,
    /// Ticks per mode (Active, Hold, Passive) per joint.
    pub modes: Vec<[usize; 3]>,
    /// Largest `|q_l − q_d|` from `settle` on, per joint, rad.
    pub max_error: Vec<f64>,
    /// RMS of `q_l − q_d` from `settle` on, per joint, rad.
    pub rms_error: Vec<f64>,
    /// First tick out of Active, per joint.
    pub left_active: Vec<Option<usize>>,
    /// Largest `|τ̂_t|` per joint, N·m.
    pub max_torque: Vec<f64>,
}

/// §4.4.1 on `plant` ([`ArmTrackingConfig`]): the arm starts at rest at
/// `q_l = 0` with its drives carrying gravity there. Errors: the modules
/// or the engine settings, as [`Mrr::try_new`] and [`EngineArm::try_new`]
/// report them.
pub fn arm_tracking<S: Scalar>(
    plant: ArmPlant,
    cfg: &ArmTrackingConfig,
) -> Result<ArmTrackingRun, ParamError> {
    let mut plant = build(&cfg.modules, plant, true, None)?;
    let p = &cfg.joint;
    let joint = JointConfig::<S>::new(p);
    let law = joint.mode().active();
    let count = counter(p);
    let u = S::UNITS;
    let ratio = p.ratio();
    let (ql, qm) = plant.angles();
    let n = ql.len();
    let mut states: Vec<_> = (0..n)
        .map(|i| {
            let (l, m) = count(ql[i], qm[i]);
            joint.state(l, m)
        })
        .collect();
    let mut law_states: Vec<_> = (0..n).map(|_| law.initial_state()).collect();
    let mut last: Vec<S> = vec![S::ZERO; n];
    let mut out = ArmTrackingRun {
        modes: vec![[0; 3]; n],
        max_error: vec![0.0; n],
        left_active: vec![None; n],
        max_torque: vec![0.0; n],
        ..Default::default()
    };
    let mut sq = vec![0.0; n];
    let mut counted = 0usize;
    let ticks = (cfg.duration / CONTROL_TICK).round() as usize;
    for k in 0..ticks {
        let t = k as f64 * CONTROL_TICK;
        let (ql, qm) = plant.angles();
        let mut torque = vec![0.0; n];
        let mut estimate = vec![0.0; n];
        let mut mode0 = JointMode::Active;
        for i in 0..n {
            let (q, v, a) = if i == 0 {
                (cfg.desired)(t)
            } else {
                (0.0, 0.0, 0.0)
            };
            let (lcount, mcount) = count(ql[i], qm[i]);
            let (mode, tau, est) = match cfg.feedback {
                JointTorqueFeedback::Estimated => {
                    let r = JointReadings::counts(lcount, mcount);
                    let o = joint.update(&mut states[i], &r, &JointTarget::from_si(q, v, a));
                    (o.mode, o.motor_torque_si(), o.joint_torque_si())
                }
                fb => {
                    let r = JointReadings {
                        link_count: lcount,
                        motor_counter: mcount,
                        motor_torque: Some(last[i]),
                    };
                    let m = joint.measure(&mut states[i], &r);
                    let feedback = match fb {
                        JointTorqueFeedback::Sensor => plant.transmission(i),
                        _ => 0.0,
                    };
                    let x = ControlInput {
                        desired_position: quantize::<S>(ratio * q, u.angle),
                        desired_velocity: quantize::<S>(ratio * v, u.speed),
                        desired_acceleration: quantize::<S>(ratio * a, u.speed),
                        motor_position: m.motor_position,
                        motor_velocity: m.motor_velocity,
                        joint_torque: quantize::<S>(feedback, u.link_torque),
                        ..Default::default()
                    };
                    let o = law.update(&mut law_states[i], &x);
                    last[i] = o.torque;
                    (
                        JointMode::Active,
                        o.torque.to_f64() / u.motor_torque,
                        m.joint_torque_si(),
                    )
                }
            };
            let m = mode_index(mode);
            out.modes[i][m] += 1;
            if m != 0 && out.left_active[i].is_none() {
                out.left_active[i] = Some(k);
            }
            out.max_torque[i] = out.max_torque[i].max(est.abs());
            if t >= cfg.settle {
                let e = ql[i] - q;
                out.max_error[i] = out.max_error[i].max(e.abs());
                sq[i] += e * e;
            }
            if i == 0 {
                mode0 = mode;
                out.desired.push(q);
                out.link_error.push(ql[0] - q);
            }
            torque[i] = tau;
            estimate[i] = est;
        }
        if t >= cfg.settle {
            counted += 1;
        }
        out.time.push(t);
        out.link.push(ql);
        out.mode.push(mode0);
        out.motor_torque.push(torque.clone());
        out.estimate.push(estimate);
        plant.hold(&torque);
        for _ in 0..plant.steps_per_tick() {
            plant.step();
        }
    }
    out.rms_error = sq
        .iter()
        .map(|s| (s / counted.max(1) as f64).sqrt())
        .collect();
    Ok(out)
}

/// Fig. 4.3's run on `plant`: the §4.4.1 joint
/// ([`crate::sim::closed_loop::payload_joint`] at 20° from the vertical,
/// carrying its link and 2.4 kg at the link's end) under Table 4.1's law at
/// 4 ms with its passive entry out of reach, tracking
/// [`raised_cosine_4s`] for `duration` s, errors counted after `settle` s.
pub fn fig4_3_tracking<S: Scalar>(
    plant: ArmPlant,
    feedback: JointTorqueFeedback,
    duration: f64,
    settle: f64,
) -> Result<ArmTrackingRun, ParamError> {
    let joint = scenario_joint(1e3, 5e2, REST_1S, None)?;
    arm_tracking::<S>(
        plant,
        &ArmTrackingConfig {
            modules: vec![crate::sim::closed_loop::payload_joint(20f64.to_radians())],
            joint,
            feedback,
            desired: raised_cosine_4s,
            duration,
            settle,
        },
    )
}

// ---------------------------------------------------------------------------
// One joint under a hand or an obstacle.

/// `JointParams::table_4_1_at(4 ms)` with the mode manager's passive entry
/// `enter` and exit `exit` (N·m of interaction torque), its release rule
/// and collision detector changed by name. Errors: the values, named as
/// [`ModeParams::try_new`] names them.
pub fn scenario_joint(
    enter: f64,
    exit: f64,
    release: ReleaseRule,
    collision: Option<CollisionParams>,
) -> Result<JointParams, ParamError> {
    // The preset is designed and checked at this tick (its docs); a
    // design failure there is reported against the tick.
    let p = JointParams::table_4_1_at(CONTROL_TICK).map_err(|_| ParamError::OutOfRange {
        name: "sample_period",
        value: CONTROL_TICK,
        min: CONTROL_TICK,
        max: CONTROL_TICK,
    })?;
    let s = p.settings();
    let mode = ModeParams::try_new(ModeSettings {
        enter_passive: enter,
        exit_passive: exit,
        collision,
        ..s.mode.settings()
    })?
    .with_release(release)?;
    JointParams::try_new(JointSettings { mode, ..s })
}

/// `|q̇_m| ≤ 10 rad/s` for 1 s (250 ticks): the release rule of the
/// back-driving and mode-switching runs.
pub const REST_1S: ReleaseRule = ReleaseRule {
    speed: 10.0,
    samples: 250,
};

/// The torque a hand or an obstacle puts on the link (N·m) at time `t`
/// (s), link angle `q_l` (rad) and speed `q̇_l` (rad/s).
pub type Environment<'a> = &'a dyn Fn(f64, f64, f64) -> f64;

/// What the link meets in a [`joint_scenario`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Obstacle {
    /// Nothing but the scenario's environment torque.
    None,
    /// The environment torque is an obstacle from this link angle (rad):
    /// contact is the first plant step that starts with `q_l` beyond it.
    Spring(f64),
    /// The engine's contact between a ball on the link and a wall
    /// ([`Wall::stop_for`]); contact is the first plant step with a
    /// contact force. Engine only.
    Contact(TipBall, Wall),
}

/// One joint scenario (module docs).
#[derive(Clone, Copy)]
pub struct JointScenario<'a> {
    /// The joint's step.
    pub joint: &'a JointParams,
    /// Length, s.
    pub duration: f64,
    /// Desired link angle, speed, acceleration at `t`.
    pub desired: Trajectory,
    /// The hand's or spring obstacle's torque, evaluated at every plant
    /// step.
    pub environment: Environment<'a>,
    /// `false` runs the joint step but applies no motor torque.
    pub powered: bool,
    /// The RMS values are taken from this time on, s.
    pub settle: f64,
    /// What the link runs into.
    pub obstacle: Obstacle,
}

/// A mode switch of the joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeSwitch {
    /// Tick time, s.
    pub time: f64,
    /// Mode before.
    pub from: JointMode,
    /// Mode after.
    pub to: JointMode,
    /// `|Δτ_m|` over the switch, N·m.
    pub jump: f64,
}

/// What [`joint_scenario`] measured. Per-tick traces are sampled at the
/// start of each tick; the environment torque is the mean over the tick's
/// plant steps.
#[derive(Debug, Clone, Default)]
pub struct JointRun {
    /// Tick times, s.
    pub time: Vec<f64>,
    /// Link angle, rad.
    pub link: Vec<f64>,
    /// Desired link angle, rad.
    pub desired: Vec<f64>,
    /// Motor torque `τ_m` commanded for the tick, N·m (applied only when
    /// powered).
    pub motor_torque: Vec<f64>,
    /// Estimated joint torque `τ̂_t`, N·m.
    pub estimate: Vec<f64>,
    /// The hand's or obstacle's torque on the link, mean over the tick, N·m.
    pub environment_torque: Vec<f64>,
    /// Mode after the tick's step.
    pub modes: Vec<JointMode>,
    /// The collision detector's flag after the tick's step.
    pub collision_flag: Vec<bool>,
    /// Mode switches.
    pub switches: Vec<ModeSwitch>,
    /// RMS environment torque over the plant steps after `settle`, N·m.
    pub env_rms: f64,
    /// Largest `|environment torque|` over the plant steps, N·m.
    pub env_peak: f64,
    /// RMS of `N τ_m` applied over the ticks after `settle`, N·m.
    pub reflected_motor_rms: f64,
    /// Adapted Coulomb estimate `f̂_c` at the first switch, N·m.
    pub coulomb_at_switch: Option<f64>,
    /// First tick the detector flagged, s.
    pub detection: Option<f64>,
    /// Start of the first plant step in contact, s.
    pub contact: Option<f64>,
    /// Link angle at the start of that step, rad.
    pub link_at_contact: Option<f64>,
    /// Largest `|q_l − q_d|` before contact, rad.
    pub error_before_contact: f64,
    /// The mode manager's bound on `|Δτ_m|` at a switch, N·m.
    pub jump_bound: f64,
}

impl JointRun {
    /// Link error `q_l − q_d` per tick, rad.
    pub fn link_error(&self) -> Vec<f64> {
        self.link
            .iter()
            .zip(&self.desired)
            .map(|(l, d)| l - d)
            .collect()
    }
}

/// The thesis joint ([`ModuleParams::thesis_joint`]: vertical axis, its
/// 0.64 kg, 0.45 m link only, full drive plant and friction) at rest at 0,
/// drives relaxed, under `scenario` on `plant`, with the joint step on
/// backend `S`. Errors: an [`Obstacle::Contact`] on [`ArmPlant::Mrr`]
/// (`ParamError::OutOfRange` naming `plant`, value 0 for `Mrr`, range
/// [1, 1] for the engine: `Mrr` has no colliders), and what the plants'
/// constructors report.
pub fn joint_scenario<S: Scalar>(
    plant: ArmPlant,
    scenario: &JointScenario,
) -> Result<JointRun, ParamError> {
    let contact = match &scenario.obstacle {
        Obstacle::Contact(b, w) => Some((b, w)),
        _ => None,
    };
    let mut plant = build(&[ModuleParams::thesis_joint()], plant, false, contact)?;
    let params = scenario.joint;
    let cfg = JointConfig::<S>::new(params);
    let ratio = params.ratio();
    let count = counter(params);
    let (ql, qm) = plant.angles();
    let (l0, m0) = count(ql[0], qm[0]);
    let mut st = cfg.state(l0, m0);
    let mut out = JointRun {
        jump_bound: cfg.mode().switch_jump_bound().to_f64() / S::UNITS.motor_torque,
        ..Default::default()
    };
    let (mut env_sq, mut env_n, mut mot_sq, mut mot_n) = (0.0, 0usize, 0.0, 0usize);
    let mut time = 0.0;
    let ticks = (scenario.duration / CONTROL_TICK).round() as usize;
    for k in 0..ticks {
        let t = k as f64 * CONTROL_TICK;
        let (ql, qm) = plant.angles();
        let (ql, qm) = (ql[0], qm[0]);
        let (qd, vd, ad) = (scenario.desired)(t);
        if out.contact.is_none() {
            out.error_before_contact = out.error_before_contact.max((ql - qd).abs());
        }
        let from = st.mode();
        let before = st.last_command_si();
        let (lc, mc) = count(ql, qm);
        let r = JointReadings::counts(lc, mc);
        let o = cfg.update(&mut st, &r, &JointTarget::from_si(qd, vd, ad));
        if o.control.switched {
            if out.switches.is_empty() {
                out.coulomb_at_switch = Some(st.mode_state().active_state().friction_si().coulomb);
            }
            out.switches.push(ModeSwitch {
                time: t,
                from,
                to: o.mode,
                jump: (o.motor_torque_si() - before).abs(),
            });
        }
        if o.control.collision && out.detection.is_none() {
            out.detection = Some(t);
        }
        let command = o.motor_torque_si();
        let torque = if scenario.powered { command } else { 0.0 };
        if t >= scenario.settle {
            mot_sq += (ratio * torque).powi(2);
            mot_n += 1;
        }
        plant.hold(&[torque]);
        let steps = plant.steps_per_tick();
        let mut tick_env = 0.0;
        for _ in 0..steps {
            let (ql, _) = plant.angles();
            let ql = ql[0];
            let vl = plant.link_speed(0);
            let h = (scenario.environment)(time, ql, vl);
            if let Obstacle::Spring(wall) = scenario.obstacle {
                if ql > wall && out.contact.is_none() {
                    out.contact = Some(time);
                    out.link_at_contact = Some(ql);
                }
            }
            plant.set_external(0, h);
            let start = time;
            time += plant.step();
            let c = plant.contact_torque();
            if c != 0.0 && out.contact.is_none() {
                out.contact = Some(start);
                out.link_at_contact = Some(ql);
            }
            let total = h + c;
            if start >= scenario.settle {
                env_sq += total * total;
                env_n += 1;
            }
            out.env_peak = out.env_peak.max(total.abs());
            tick_env += total;
        }
        out.time.push(t);
        out.link.push(ql);
        out.desired.push(qd);
        out.motor_torque.push(command);
        out.estimate.push(o.joint_torque_si());
        out.environment_torque.push(tick_env / steps.max(1) as f64);
        out.modes.push(o.mode);
        out.collision_flag.push(o.control.collision);
    }
    out.env_rms = (env_sq / env_n.max(1) as f64).sqrt();
    out.reflected_motor_rms = (mot_sq / mot_n.max(1) as f64).sqrt();
    Ok(out)
}

// ---------------------------------------------------------------------------
// The three experiments' set-ups.

/// The back-driving hand's path `q_h = 0.5 sin(2π t/4 s)`, rad, and its
/// speed, rad/s.
pub fn hand_path(t: f64) -> (f64, f64) {
    let w = TAU / 4.0;
    (0.5 * (w * t).sin(), 0.5 * w * (w * t).cos())
}

/// The back-driving hand: an impedance of 200 N·m/rad and 5 N·m·s/rad
/// following [`hand_path`] (as `closed_loop::back_drive`), N·m on the link.
pub fn back_driving_hand(t: f64, ql: f64, vl: f64) -> f64 {
    let (qh, vh) = hand_path(t);
    200.0 * (qh - ql) + 5.0 * (vh - vl)
}

/// Holding `q_l = 0`.
pub fn hold_zero(_t: f64) -> (f64, f64, f64) {
    (0.0, 0.0, 0.0)
}

/// Back-driving (§4.4.2, Fig. 4.11–4.12): [`back_driving_hand`] leads the
/// joint for 6 s, RMS values over the last 4 s; the manager enters
/// Passive above 1 N·m (exit 0.5 N·m, release [`REST_1S`]); `powered =
/// false` is Fig. 4.11's area A (motor torque 0), `true` the passive law
/// of eq. (4.32) on the estimate.
pub fn back_driving<S: Scalar>(plant: ArmPlant, powered: bool) -> Result<JointRun, ParamError> {
    let joint = scenario_joint(1.0, 0.5, REST_1S, None)?;
    joint_scenario::<S>(
        plant,
        &JointScenario {
            joint: &joint,
            duration: 6.0,
            desired: hold_zero,
            environment: &back_driving_hand,
            powered,
            settle: 2.0,
            obstacle: Obstacle::None,
        },
    )
}

/// The hand of the mode-switching run: from 0.5 s it leads the link to
/// 0.4 rad along a raised cosine over 2 s (200 N·m/rad, 5 N·m·s/rad),
/// holds it there and lets go at 3 s. N·m on the link.
pub fn leading_hand(t: f64, ql: f64, vl: f64) -> f64 {
    if !(0.5..3.0).contains(&t) {
        return 0.0;
    }
    let (qh, vh) = if t < 2.5 {
        let (q, v, _) = raised_cosine(0.2, 4.0, t - 0.5);
        (q, v)
    } else {
        (0.4, 0.0)
    };
    200.0 * (qh - ql) + 5.0 * (vh - vl)
}

/// Mode switching: the joint holds 0 Active while [`leading_hand`] leads
/// it; manager enter 4 N·m, exit 2 N·m, release [`REST_1S`]; 6 s.
pub fn mode_switching<S: Scalar>(plant: ArmPlant) -> Result<JointRun, ParamError> {
    let joint = scenario_joint(4.0, 2.0, REST_1S, None)?;
    joint_scenario::<S>(
        plant,
        &JointScenario {
            joint: &joint,
            duration: 6.0,
            desired: hold_zero,
            environment: &leading_hand,
            powered: true,
            settle: 6.0,
            obstacle: Obstacle::None,
        },
    )
}

/// The obstacle's angle, rad.
pub const WALL_ANGLE: f64 = 0.15;

/// The spring obstacle: from [`WALL_ANGLE`] on it pushes back with
/// 300 N·m/rad and 2 N·m·s/rad (never pulling), N·m on the link.
pub fn spring_wall(_t: f64, ql: f64, vl: f64) -> f64 {
    if ql > WALL_ANGLE {
        -(300.0 * (ql - WALL_ANGLE) + 2.0 * vl.max(0.0))
    } else {
        0.0
    }
}

/// No environment torque.
pub fn no_torque(_t: f64, _ql: f64, _vl: f64) -> f64 {
    0.0
}

/// The collision run's reference, `0.2 (1 − cos(π t/4))` rad towards
/// 0.4 rad, then held.
pub fn towards_wall(t: f64) -> (f64, f64, f64) {
    let w = PI / 4.0;
    if t >= 4.0 {
        (0.4, 0.0, 0.0)
    } else {
        (
            0.2 * (1.0 - (w * t).cos()),
            0.2 * w * (w * t).sin(),
            0.2 * w * w * (w * t).cos(),
        )
    }
}

/// The time [`towards_wall`] passes `q` (rad), s.
pub fn reference_passes(q: f64) -> f64 {
    4.0 / PI * (1.0 - q / 0.2).clamp(-1.0, 1.0).acos()
}

/// The collision detector of the collision runs: threshold 3 N·m, release
/// 1.5 N·m, debounce 3 ticks, release after 50 ticks, `reaction`.
pub fn collision_detector(reaction: CollisionReaction) -> Result<CollisionParams, ParamError> {
    CollisionParams::try_new(CollisionSettings {
        threshold: 3.0,
        release_threshold: 1.5,
        debounce: 3,
        release: 50,
        reaction,
    })
}

/// The ball at the tip of the thesis joint's 0.45 m link (radius 2 cm,
/// centre on the link's axis at 0.45 m) and the wall it touches at
/// [`WALL_ANGLE`] (5 cm thick, [`Wall::stop_for`]).
pub fn tip_contact() -> Result<(TipBall, Wall), ParamError> {
    let ball = TipBall::try_new(0, [0.45, 0.0, 0.0], 0.02)?;
    let wall = Wall::stop_for(&ball, WALL_ANGLE, 0.05)?;
    Ok((ball, wall))
}

/// Which obstacle a [`collision`] run meets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CollisionObstacle {
    /// [`spring_wall`], on either plant.
    Spring,
    /// The engine contact of [`tip_contact`] (engine only).
    Contact,
}

/// The collision run: the joint tracks [`towards_wall`] for 5 s into the
/// obstacle at [`WALL_ANGLE`]; manager passive entry out of reach
/// (1000 N·m, exit 500 N·m), detector [`collision_detector`] with
/// `reaction`. Errors: [`CollisionObstacle::Contact`] on
/// [`ArmPlant::Mrr`] (`plant`).
pub fn collision<S: Scalar>(
    plant: ArmPlant,
    obstacle: CollisionObstacle,
    reaction: CollisionReaction,
) -> Result<JointRun, ParamError> {
    let joint = scenario_joint(1000.0, 500.0, REST_1S, Some(collision_detector(reaction)?))?;
    let (environment, obstacle): (Environment, Obstacle) = match obstacle {
        CollisionObstacle::Spring => (&spring_wall, Obstacle::Spring(WALL_ANGLE)),
        CollisionObstacle::Contact => {
            let (ball, wall) = tip_contact()?;
            (&no_torque, Obstacle::Contact(ball, wall))
        }
    };
    joint_scenario::<S>(
        plant,
        &JointScenario {
            joint: &joint,
            duration: 5.0,
            desired: towards_wall,
            environment,
            powered: true,
            settle: 5.0,
            obstacle,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Speed and acceleration of a trajectory against central differences
    /// of its angle and speed.
    fn consistent(f: Trajectory, times: &[f64]) {
        let h = 1e-6;
        for &t in times {
            let (_, v, a) = f(t);
            let dq = (f(t + h).0 - f(t - h).0) / (2.0 * h);
            let dv = (f(t + h).1 - f(t - h).1) / (2.0 * h);
            assert!((dq - v).abs() < 1e-6, "t {t}: {dq} vs {v}");
            assert!((dv - a).abs() < 1e-5, "t {t}: {dv} vs {a}");
        }
    }

    #[test]
    fn trajectories_are_their_own_derivatives() {
        consistent(raised_cosine_4s, &[0.3, 1.0, 2.7, 5.5]);
        consistent(half_cosine_from_rest, &[0.1, 0.5, 1.3, 2.9]);
        consistent(towards_wall, &[0.2, 1.7, 3.3]);
        // Peaks: 0.5 rad at 2 s; 0.2 rad at 1.2 s; 0.4 rad from 4 s.
        assert!((raised_cosine_4s(2.0).0 - 0.5).abs() < 1e-12);
        assert!((half_cosine_from_rest(1.2).0 - 0.2).abs() < 1e-12);
        assert_eq!(towards_wall(4.5), (0.4, 0.0, 0.0));
    }

    #[test]
    fn reference_passes_inverts_the_collision_reference() {
        for q in [0.01, 0.15, 0.3, 0.39] {
            let t = reference_passes(q);
            assert!((towards_wall(t).0 - q).abs() < 1e-12, "{q}");
        }
        // The obstacle's nominal contact: (4/π) acos(0.25).
        let nominal = 4.0 / PI * 0.25f64.acos();
        assert!((reference_passes(WALL_ANGLE) - nominal).abs() < 1e-12);
    }

    #[test]
    fn a_contact_on_the_model_is_a_typed_error() {
        let r = collision::<f32>(
            ArmPlant::Mrr,
            CollisionObstacle::Contact,
            CollisionReaction::Stop,
        );
        assert!(matches!(
            r,
            Err(ParamError::OutOfRange { name: "plant", .. })
        ));
    }

    #[test]
    fn the_environments_push_as_documented() {
        // The spring obstacle: nothing before 0.15 rad, 300 N·m/rad and
        // 2 N·m·s/rad beyond, never pulling.
        assert_eq!(spring_wall(0.0, 0.149, 1.0), 0.0);
        assert!((spring_wall(0.0, 0.16, 0.1) + (3.0 + 0.2)).abs() < 1e-12);
        assert!((spring_wall(0.0, 0.16, -0.1) + 3.0).abs() < 1e-12);
        // The back-driving hand at t = 1 s (q_h = 0.5, q̇_h = 0) on a link
        // at rest at 0: 200 × 0.5 N·m.
        assert!((back_driving_hand(1.0, 0.0, 0.0) - 100.0).abs() < 1e-9);
        // The leading hand lets go at 3 s.
        assert_eq!(leading_hand(3.0, 0.1, 0.0), 0.0);
        assert!((leading_hand(2.75, 0.3, 0.0) - 20.0).abs() < 1e-9);
    }
}
