//! Door opening (thesis §6.4.4, Fig. 6.18–6.20) on the engine: the mobile
//! manipulator, the DAUJ wrist built from its parts and a hinged door, with
//! the library's wrist step and turret passive law in the loop at 4 ms.
//!
//! # The scene
//! One engine world (z up, the knob's height at `z = 0`, gravity off: the
//! shoulder and elbow are locked at the knob's height and the F/T sensor is
//! tared with the gripper hanging, so the weights only add constant loads
//! the thesis's run does not see either). Geometry and the base's random
//! processes are those of [`crate::sim::door`] ([`DoorConfig`]): the door's
//! hinge at the origin, the knob at `(R, 0, 0)` on the closed door, the base
//! at `(R, −l_g − L_a, 0)` on the circle about the hinge, the arm pointing
//! at the knob.
//!
//! * **Door** — a body on a revolute joint to the ground about the vertical
//!   through the hinge. Its mass, hinge friction and closer spring are
//!   assumptions ([`DoorBody`]; the thesis describes "an artificial door"
//!   and gives none of them): drawn per seed from stated ranges, so the
//!   verdicts are over doors as well as over slip and jerk sequences.
//! * **Base** — a free body of 120 kg (the order of the Powerbot AGV's
//!   mass; not in the thesis) that tracks, by a stiff feedback force and
//!   torque (natural frequency 100 rad/s), the pose integrated from the
//!   differential-drive speeds of [`DoorConfig`]'s planned circle with
//!   wheel slip and jerks, and the platform pitch that rocks with its
//!   acceleration. The arm's reaction moves it by micrometres.
//! * **Turret** — the arm (shoulder and elbow locked: one body, 3 kg,
//!   0.35 kg·m² about the turret axis) on a revolute joint to the base, and
//!   its rotor (`I_m = 1.14e-5 kg·m²`, turning at `N = 100` times the link
//!   speed) on its own joint, coupled by member [`TURRET_FAMILY_MEMBER`] of
//!   the independent joint family ([`FamilyDrives`]: spline flexspline
//!   backbone with Maxwell-slip hysteresis, 30 % of the catalogue loss at
//!   the node, wave-generator bearing compliance, a kinematic error drawn
//!   from the run's seed, asymmetric pre-sliding motor friction and
//!   Maxwell-slip link friction; not the library's eq. 3.7 or eq. 4.8
//!   models), the rotor mounted at the member's zero-load motor angle. The link-side torque sensor
//!   reads the drive's transmission torque with ±0.05 N·m uniform noise;
//!   the motor encoder has 2000 counts per turn.
//! * **Wrist** — the DAUJ of [`super::wrist`] (the same parts, axes and
//!   masses: semi-spheres, oblique joint at `φ`, output link `L2`, the
//!   outer universal joint's cross closing the loop through an impulse
//!   joint) mounted on the arm at the reach `L_a`, its base `z` along the
//!   arm and its yaw axis `x` vertical: `γ` swings the tool in the
//!   horizontal plane, `δ` tilts it. Each motor is a rotor body on the arm
//!   (`I_m = 1.05e-6 kg·m²`, `N = 531`, Table 6.1's drive as
//!   [`door_wrist_design`] uses it) coupled to its joint (`J1`, and `J3`
//!   through the inner universal joint taken as 1 : 1) by a stated
//!   stiff-spring drive, `τ_t = k_w (q_m/N − q) + c_w (q̇_m/N − q̇)` with
//!   `k_w = 400 N·m/rad` and `c_w = 2 N·m·s/rad` (the thesis gives no wrist
//!   drive stiffness; 400 N·m/rad is the order of a size-8 harmonic
//!   drive's low-load stiffness, and the explicit spring must stay stable
//!   against the semi-spheres' 1e-3 kg·m² at the engine step), and motor
//!   friction with presliding (`f_c = 8 mN·m`, `f_s = 4 mN·m` at the motor:
//!   a breakaway of 6.4 N·m at the joint). The motor encoders have 2000
//!   counts per turn. The 1 : 1 inner joint ignores the factor of eq. (5.3),
//!   which the library's step applies (errata E6.6): it stays within
//!   `1/cos β − 1 < 0.4 %` for the bends of these runs (below 5°).
//! * **F/T sensor and gripper** — the gripper (0.3 kg, isotropic
//!   5e-4 kg·m²) is its own body on a fixed joint to `L2` at the sensor
//!   origin `l`; the wrench it puts through that joint is read by momentum
//!   balance as in [`super::SensedWrist`], and turned into gauge voltages
//!   by a [`StrainGaugeSensor`] whose matrix is off the certificate by
//!   ±2 % (seeded) with 0.3 mV noise (offsets tared). The wrench is
//!   averaged over each 4 ms tick before it is read (the amplifiers'
//!   anti-aliasing filter): the one-step momentum balance carries the
//!   engine's step-scale content, which a sampled sensor behind a filter
//!   does not see.
//! * **Grasp** — a stiff spring between the gripper's grasp point and the
//!   knob, as in [`crate::sim::door`]: `k_g` (N/m) with 40 N·s/m, and
//!   `k_r` (N·m/rad) with 0.3 N·m·s/rad about every axis.
//!
//! # Control in the loop
//! Every 4 ms (the thesis's TMS320F2812 period) on the backend chosen
//! ([`Backend`], f32 by default as the thesis's DSP firmware would run):
//! * Passive runs: the turret by eq. (4.32) ([`PassiveConfig`],
//!   `K_p = 0.1/I_m`) on its torque reading; the wrist by the library's
//!   public step ([`WristStepConfig`]: F/T gauges → `(τ_δ, τ_γ)`, the mode
//!   manager held Passive with the admittance law of eq. 6.32, inverse
//!   kinematics, both motor laws of eq. 6.15 with [`door_wrist_design`]).
//! * Held-active run (contrast): the turret by the ch. 4 active law holding
//!   its initial angle, the wrist step held Active at the straight pose.
//!
//! # The start pose and the straight pose
//! The wrist's joints are set, before the first step, to the configuration
//! of the library's inverse kinematics for the start pose (pitch
//! `start_pitch`, yaw 0; the branch `θ4 ≥ 0`), the only use of the
//! library's kinematics in the scene; the engine then closes the loop
//! (the loop error is reported, [`EngineDoorRun::loop_error`]). A half
//! second before the grasp lets the wrist settle in Active mode; the grasp
//! spring is attached where the gripper then is.
//!
//! The DAUJ has two assembly modes for the same motor angles (the two
//! roots of eq. 5.10); the library's kinematics describe one, and the two
//! meet at the straight pose, where the mechanism is singular. Grasped at
//! the straight pose (`start_pitch = 0`), the passive wrist leaves it as
//! the knob pulls. The wrist step's motor references stay continuous
//! there (it takes the root of eq. 5.13 nearest the previous motor angle,
//! errata E5.5), yet in the engine the mechanism can still come out in
//! the other assembly mode, where the pose the motors reach is not the
//! one the step assumes, and the admittance loop then pushes against the
//! knob. On seeds 1–3 that gives passive peaks of 46, 12 and 13 N·m (held
//! active: 6.5 N·m; with the root `θ4 ≥ 0` always taken, whose references
//! jumped by up to π there, it was 113, 87 and 13 N·m) —
//! `cargo run --release --features sim --example door_opening -- --straight`.
//! Grasped with the wrist bent (5°–15° of pitch, kept by the knob), the
//! path stays away from the straight pose and the runs are regular: that
//! is the operating point of the claims ([`crate::sim::claims::ch6`]).
//!
//! # The engine step
//! The explicit drive springs and the hooks are evaluated once per engine
//! step and held over it, with one solver substep (as [`super::EngineArm`]
//! explains): [`door_engine_settings`] gives `dt = 0.25 ms` (16 steps per
//! control tick). The fastest explicit mode is a wrist drive spring on the
//! semi-sphere, `√(k_w/1e-3) = 632 rad/s`, `dt ω = 0.16`. Convergence is
//! checked by halving the step (`tests/engine_door.rs`).

use rapier3d_f64::na::UnitQuaternion;
use rapier3d_f64::prelude::*;

use super::arm::{DriveModel, DriveState};
use super::dauj::{
    insert_dauj, DaujJointAngles, DaujOptions, DaujRotors, DaujTool, WorldAxis, WristDrives,
};
use super::family_drives::{family_member, FamilyDrives};
use super::ft_sensor::{GaugeErrors, StrainGaugeSensor, V_REF};
use super::world::{body_at, hinge, Coord, EngineSettings, World};
use crate::control::{
    ControlInput, PassiveConfig, PassiveParams, RobustAdaptiveConfig, RobustAdaptiveParams,
};
use crate::error::ParamError;
use crate::scalar::{Scalar, I16F16};
use crate::sim::door::{
    door_wrist_design, turret_hold_design, BaseMotion, DoorConfig, DoorControl,
};
use crate::sim::mrr::ModuleParams;
use crate::sim::{FrictionParams, SplitMix64};
use crate::wrist::active::WristActiveParams;
use crate::wrist::admittance::{AdmittanceParams, AdmittanceSettings};
use crate::wrist::ft_sensor::{DecouplingMatrix, FtSensorParams};
use crate::wrist::modes::{WristMode, WristModeParams, WristModeSettings};
use crate::wrist::step::{
    WristReadings, WristStepConfig, WristStepParams, WristStepSettings, WristTarget,
};
use crate::wrist::{MotorAngles, PitchYaw, WristParams};

/// The controllers' period, s (thesis §6.4.1: 4 ms on the TMS320F2812).
pub const CONTROL_PERIOD: f64 = 0.004;

/// The numeric type the library's steps run in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    /// `f32`, as on a DSP or Cortex-M4F.
    F32,
    /// `f64`.
    F64,
    /// `I16F16` fixed point, as on a Cortex-M0+.
    I16F16,
}

/// The door: assumptions the thesis does not state (module docs), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoorBody {
    /// Mass, kg (a uniform leaf of width `width`).
    pub mass: f64,
    /// Leaf width, m (hinge to free edge; the knob is at [`DoorConfig`]'s
    /// radius).
    pub width: f64,
    /// Hinge Coulomb friction, N·m.
    pub hinge_coulomb: f64,
    /// Hinge viscous friction, N·m·s/rad.
    pub hinge_viscous: f64,
    /// Closer spring, N·m/rad of opening.
    pub closer_stiffness: f64,
    /// Closer preload once open, N·m.
    pub closer_preload: f64,
}

impl DoorBody {
    /// The middle of the ranges of [`draw`](Self::draw): 10 kg, 0.85 m,
    /// 0.3 N·m and 0.6 N·m·s/rad at the hinge, a closer of 1 N·m/rad with
    /// 0.5 N·m preload.
    pub fn nominal() -> Self {
        DoorBody {
            mass: 10.0,
            width: 0.85,
            hinge_coulomb: 0.3,
            hinge_viscous: 0.6,
            closer_stiffness: 1.0,
            closer_preload: 0.5,
        }
    }

    /// A door drawn uniformly from the ranges the runs sweep: mass 5–15 kg
    /// (a light lab door panel to a hollow-core interior door), width
    /// 0.85 m, hinge Coulomb 0.1–0.5 N·m and viscous 0.2–1.0 N·m·s/rad,
    /// closer 0–2 N·m/rad with 0–1 N·m preload (none to a light spring; a
    /// commercial EN 1154 closer is far stronger, and the thesis's
    /// artificial door shows no closer). The draw uses its own stream of
    /// `seed`, so the base's slip and jerks are those of
    /// [`crate::sim::door`] for the same seed.
    pub fn draw(seed: u64) -> Self {
        let mut rng = SplitMix64::new(seed ^ 0xD00D_F00D_5EED_0001);
        let mut u = |a: f64, b: f64| a + (b - a) * rng.uniform();
        DoorBody {
            mass: u(5.0, 15.0),
            width: 0.85,
            hinge_coulomb: u(0.1, 0.5),
            hinge_viscous: u(0.2, 1.0),
            closer_stiffness: u(0.0, 2.0),
            closer_preload: u(0.0, 1.0),
        }
    }

    /// Moment of inertia about the hinge, kg·m² (`m w²/3`).
    pub fn hinge_inertia(&self) -> f64 {
        self.mass * self.width * self.width / 3.0
    }

    fn validate(&self) -> Result<(), ParamError> {
        crate::error::positive("door.mass", self.mass)?;
        crate::error::positive("door.width", self.width)?;
        for (name, v) in [
            ("door.hinge_coulomb", self.hinge_coulomb),
            ("door.hinge_viscous", self.hinge_viscous),
            ("door.closer_stiffness", self.closer_stiffness),
            ("door.closer_preload", self.closer_preload),
        ] {
            let v = crate::error::finite(name, v)?;
            if v < 0.0 {
                return Err(ParamError::Negative { name, value: v });
            }
        }
        Ok(())
    }
}

/// The engine settings of the door runs: `dt = 0.25 ms`, one solver
/// substep (module docs; the motor-spring fields are not used).
pub fn door_engine_settings() -> EngineSettings {
    EngineSettings::try_new(2.5e-4, 1, 20.0, 0.4).unwrap_or_default()
}

/// One 4 ms sample of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngineDoorSample {
    /// Time, s.
    pub time: f64,
    /// Door opening angle, rad (positive open).
    pub door: f64,
    /// Turret angle from its start, rad.
    pub turret: f64,
    /// Wrist pitch `δ` and yaw `γ` of the mechanism, rad.
    pub wrist: [f64; 2],
    /// The step's pose reference `(δ_r, γ_r)`, rad.
    pub reference: [f64; 2],
    /// `(τ_δ, τ_γ)` the library's step read from the gauges, N·m.
    pub measured: [f64; 2],
    /// `(τ_δ, τ_γ)` the knob puts on the wrist about its pitch and yaw axes
    /// (the engine's, noise-free), N·m; positive tending to increase `δ`
    /// (`γ`).
    pub interaction: [f64; 2],
    /// Base pose `(x, y, heading)`, m, m, rad.
    pub base: [f64; 3],
    /// Motor angles `(θ1, θ3)` as the encoders read them, rad (joint side).
    pub motors: [f64; 2],
    /// The step's motor references `(θ1_r, θ3_r)`, rad.
    pub motor_reference: [f64; 2],
}

/// The result of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineDoorRun {
    /// Samples at 4 ms.
    pub samples: Vec<EngineDoorSample>,
    /// Peak measured `|τ_δ|`, `|τ_γ|`, N·m.
    pub peak_measured: [f64; 2],
    /// Peak true `|τ_δ|`, `|τ_γ|`, N·m.
    pub peak_interaction: [f64; 2],
    /// Peak grasp force, N.
    pub peak_force: f64,
    /// Final door angle, rad.
    pub door_angle: f64,
    /// Largest `|δ|`, `|γ|`, rad.
    pub wrist_range: [f64; 2],
    /// Largest loop-closure error of the DAUJ (module [`super::wrist`]),
    /// rad.
    pub loop_error: f64,
    /// Ticks whose wrist step left the requested mode.
    pub off_mode_ticks: usize,
    /// Ticks with a saturated wrist motor command.
    pub saturated_ticks: usize,
    /// The door of the run.
    pub door: DoorBody,
}

impl EngineDoorRun {
    /// `max(|τ_δ|, |τ_γ|)` measured, N·m.
    pub fn peak(&self) -> f64 {
        self.peak_measured[0].max(self.peak_measured[1])
    }

    /// `max(|τ_δ|, |τ_γ|)` true, N·m.
    pub fn peak_true(&self) -> f64 {
        self.peak_interaction[0].max(self.peak_interaction[1])
    }
}

/// The scene's bodies and the coordinates read from them.
struct Scene {
    world: World,
    base: RigidBodyHandle,
    link: RigidBodyHandle,
    output: RigidBodyHandle,
    gripper: RigidBodyHandle,
    door: RigidBodyHandle,
    turret_link: Coord,
    turret_motor: Coord,
    /// `J1` (lower semi-sphere on the arm) and `J3` (`L2` on the upper).
    wrist_joint: [Coord; 2],
    wrist_motor: [Coord; 2],
    pitch: Coord,
    yaw: Coord,
    door_hinge: Coord,
    /// Wrist centre in the arm's frame, m.
    wrist_centre: Vector<Real>,
    /// Grasp point in the gripper's frame, m.
    grasp_local: Vector<Real>,
    /// Knob in the door's frame, m, and the gripper-to-door rotation the
    /// grasp's rotational spring rests at; `None` before the grasp.
    knob: Option<(Vector<Real>, UnitQuaternion<Real>)>,
    /// Sensor origin in `L2`'s frame, m.
    sensor_local: Vector<Real>,
    gripper_mass: f64,
    gripper_inertia: f64,
}

const BASE_MASS: f64 = 120.0;
const BASE_INERTIA: f64 = 10.0;
const GRIPPER_MASS: f64 = 0.3;
const GRIPPER_INERTIA: f64 = 5e-4;
pub(super) const WRIST_RATIO: f64 = 531.0;
pub(super) const WRIST_ROTOR: f64 = 1.05e-6;
/// Wrist drive stiffness `k_w` (N·m/rad) and damping `c_w` (N·m·s/rad).
pub(super) const WRIST_DRIVE: (f64, f64) = (400.0, 2.0);
/// The time before the grasp, s: the wrist holds its start pose in Active
/// mode, the turret holds, the base stands, the door is free.
const PRE_GRASP: f64 = 0.5;

fn build_scene(
    cfg: &DoorConfig,
    door: &DoorBody,
    start: PitchYaw<f64>,
    settings: &EngineSettings,
) -> Result<Scene, ParamError> {
    let mut world = World::new(settings);
    let (r, la, lg, ls) = (
        cfg.door_radius,
        cfg.reach,
        cfg.grasp_offset,
        cfg.sensor_offset,
    );
    let z = Vector::z();
    let b0 = Vector::new(r, -lg - la, 0.0);
    let w0 = Vector::new(r, -lg, 0.0);
    let fail = |name| ParamError::NotFinite {
        name,
        value: f64::NAN,
    };
    // Door on the ground.
    let ground = world.base();
    let w = door.width;
    let door_h = body_at(
        &mut world,
        Vector::zeros(),
        Vector::new(w / 2.0, 0.0, 0.0),
        door.mass,
        Vector::new(
            door.mass * 0.04,
            door.mass * w * w / 12.0,
            door.mass * w * w / 12.0,
        ),
    );
    let dj = world
        .multibody_joints
        .insert(
            ground,
            door_h,
            hinge(z, Vector::zeros(), Vector::zeros()),
            true,
        )
        .ok_or(fail("door hinge"))?;
    if let Some((mb, _)) = world.multibody_joints.get_mut(dj) {
        mb.damping_mut().fill(0.0);
    }
    // The robot: one multibody rooted at the free base.
    let base = body_at(
        &mut world,
        b0,
        Vector::zeros(),
        BASE_MASS,
        Vector::repeat(BASE_INERTIA),
    );
    let (arm_mass, arm_com) = (3.0, 0.25);
    let link = body_at(
        &mut world,
        b0,
        Vector::new(0.0, arm_com, 0.0),
        arm_mass,
        Vector::new(
            0.35 - arm_mass * arm_com * arm_com,
            0.01,
            0.35 - arm_mass * arm_com * arm_com,
        ),
    );
    let t_rotor = body_at(
        &mut world,
        b0,
        Vector::zeros(),
        0.3,
        Vector::new(1e-4, 1e-4, 1.14e-5),
    );
    let mb = &mut world.multibody_joints;
    mb.insert(base, link, hinge(z, Vector::zeros(), Vector::zeros()), true)
        .ok_or(fail("turret joint"))?;
    mb.insert(
        base,
        t_rotor,
        hinge(z, Vector::zeros(), Vector::zeros()),
        true,
    )
    .ok_or(fail("turret rotor joint"))?;
    // The wrist on the arm at the reach: its z along the arm (+y), its yaw
    // axis x vertical, its pitch axis y = z × x = +x. The start pose is
    // the library's inverse kinematics for `start` (the only use of the
    // library's kinematics in the scene); the engine closes the loop.
    let straight = start.delta == 0.0 && start.gamma == 0.0;
    let wrist = insert_dauj(
        &mut world,
        link,
        w0,
        (WorldAxis::Z, WorldAxis::X),
        &DaujOptions {
            kinematics: WristParams::thesis(),
            rotors: Some(DaujRotors {
                ratio: WRIST_RATIO,
                mass: 0.05,
                // Transverse 1e-5 kg·m², axial I_m (written as the excess
                // over the transverse moment, as this scene always has).
                inertia: [1e-5, 1e-5, 1e-5 + (WRIST_ROTOR - 1e-5)],
            }),
            tool: Some(DaujTool {
                mount: ls,
                com: 0.5 * (lg - ls),
                mass: GRIPPER_MASS,
                inertia: GRIPPER_INERTIA,
            }),
            start: (!straight).then(|| DaujJointAngles::from_pose(&WristParams::thesis(), start)),
            undamped: true,
        },
    )?;
    let zw = wrist.axes[2];
    let c = Coord::new;
    Ok(Scene {
        world,
        base,
        link,
        output: wrist.output,
        gripper: wrist.tool.ok_or(fail("gripper"))?,
        door: door_h,
        turret_link: c(base, link, z),
        turret_motor: c(base, t_rotor, z),
        wrist_joint: wrist.joints(),
        wrist_motor: wrist.motors().ok_or(fail("wrist rotors"))?,
        pitch: wrist.pitch(),
        yaw: wrist.yaw(),
        door_hinge: c(ground, door_h, z),
        wrist_centre: w0 - b0,
        grasp_local: zw * (lg - ls),
        knob: None,
        sensor_local: zw * ls,
        gripper_mass: GRIPPER_MASS,
        gripper_inertia: GRIPPER_INERTIA,
    })
}

/// The wrench the gripper puts through the sensor over one step (N, N·m;
/// sensor frame, about its origin), by momentum balance (see
/// [`super::SensedWrist`]). `before` is the gripper's (velocity, angular
/// velocity, centre of mass) at the start of the step; `force` acts at
/// `point`, `couple` besides (both world, known loads on the gripper).
struct MomentumBalance {
    v0: Vector<Real>,
    w0: Vector<Real>,
    com: Vector<Real>,
    point: Vector<Real>,
    force: Vector<Real>,
    couple: Vector<Real>,
    origin: Vector<Real>,
    frame: UnitQuaternion<Real>,
}

/// The state of the run's plant-side elements that have memory.
struct Memory {
    turret: [f64; 2],
    wrist: WristDrives,
    hinge_anchor: f64,
    door_angle: f64,
}

/// Runs one door opening on the engine with the library's steps on
/// `backend`. Errors: a `door` field negative, non-finite or (mass, width)
/// not positive, named `door.<field>`; an engine step that does not divide
/// the 4 ms control period ([`ParamError::OutOfRange`] named `dt`).
pub fn engine_door_opening(
    cfg: &DoorConfig,
    door: &DoorBody,
    start_pitch: f64,
    engine: &EngineSettings,
    backend: Backend,
) -> Result<EngineDoorRun, ParamError> {
    let limit = 20f64.to_radians();
    let start_pitch = crate::error::in_range("start_pitch", start_pitch, -limit, limit)?;
    match backend {
        Backend::F32 => run::<f32>(cfg, door, start_pitch, engine),
        Backend::F64 => run::<f64>(cfg, door, start_pitch, engine),
        Backend::I16F16 => run::<I16F16>(cfg, door, start_pitch, engine),
    }
}

/// The wrist step of the door runs: the kinematics of the thesis, the F/T
/// certificate [`DecouplingMatrix::example`] at the sensor offset, both
/// motors by [`door_wrist_design`] at 4 ms, the mode manager of
/// [`crate::sim::door`] (admittance `K_c = 0.1`, validated for the grasp's
/// stiffness [`DoorConfig::wrist_stiffness_bound`]).
pub fn door_wrist_step(
    cfg: &DoorConfig,
    initial_mode: WristMode,
) -> Result<WristStepParams, ParamError> {
    wrist_step_params(cfg.wrist_stiffness_bound(), cfg.sensor_offset, initial_mode)
}

/// The wrist step of the engine's wrist scenes (the door's, the bench's):
/// the kinematics of the thesis, the F/T certificate
/// [`DecouplingMatrix::example`] at `sensor_offset` (m), both motors by
/// [`door_wrist_design`] at 4 ms, the mode manager of [`crate::sim::door`]
/// with the admittance `K_c = 0.1` validated for an environment of
/// `stiffness` (N·m/rad).
pub(super) fn wrist_step_params(
    stiffness: f64,
    sensor_offset: f64,
    initial_mode: WristMode,
) -> Result<WristStepParams, ParamError> {
    let limit = 30f64.to_radians();
    let admittance = AdmittanceParams::try_new(AdmittanceSettings {
        gain: [0.1, 0.1],
        stiffness,
        sample_period: CONTROL_PERIOD,
        lag_samples: 1,
        limits: [limit, limit],
        max_rate: 1.0,
        deadband: 0.0,
        desired_torque: [0.0; 2],
    })?;
    WristStepParams::try_new(WristStepSettings {
        kinematics: WristParams::thesis(),
        sensor: FtSensorParams::try_new(DecouplingMatrix::example(), sensor_offset)?,
        active: WristActiveParams::try_new([door_wrist_design(CONTROL_PERIOD); 2])?,
        modes: WristModeParams::try_new(WristModeSettings {
            admittance,
            enter_passive: 1.0,
            exit_passive: 0.5,
            rest_speed: 0.01,
            debounce: 5,
            dwell: 250,
            rejoin_bandwidth: 5.0,
        })?,
        initial_mode,
    })
}

fn run<S: Scalar>(
    cfg: &DoorConfig,
    door: &DoorBody,
    start_pitch: f64,
    engine: &EngineSettings,
) -> Result<EngineDoorRun, ParamError> {
    door.validate()?;
    let dt = engine.dt();
    let per_tick = (CONTROL_PERIOD / dt).round();
    if per_tick < 1.0 || (per_tick * dt - CONTROL_PERIOD).abs() > 1e-12 {
        return Err(ParamError::OutOfRange {
            name: "dt",
            value: dt,
            min: 1e-6,
            max: CONTROL_PERIOD,
        });
    }
    let per_tick = per_tick as usize;
    let start = PitchYaw {
        delta: start_pitch,
        gamma: 0.0,
    };
    let mut sc = build_scene(cfg, door, start, engine)?;
    let mut rng = SplitMix64::new(cfg.seed);
    // Base path: the processes of `sim::door`, drawn in its order.
    let (r, la, lg) = (cfg.door_radius, cfg.reach, cfg.grasp_offset);
    let b0 = [r, -lg - la];
    let rho = b0[0].hypot(b0[1]);
    let heading_nom = b0[1].atan2(b0[0]) + core::f64::consts::FRAC_PI_2;
    let heading0 = heading_nom + cfg.heading_error;
    let total = cfg.opening_time + 1.5;
    let motion = BaseMotion::draw(cfg, rho, total, &mut rng);
    let mut pose = [b0[0], b0[1], heading0];
    // Sensors and drives.
    let mut gauges = StrainGaugeSensor::try_new(
        DecouplingMatrix::example().matrix(),
        GaugeErrors::try_new(0.02, 0.0, 3e-4, cfg.seed ^ 0x5E45_0000)?,
    )?;
    let turret_module = ModuleParams::thesis_joint();
    let turret_family = FamilyDrives::try_new(
        core::slice::from_ref(&turret_module),
        vec![family_member(TURRET_FAMILY_MEMBER)?],
        &[cfg.seed],
        &[0.0],
    )?;
    let mut turret_drive = TurretDrive {
        motor_offset: turret_family.motor_angles()[0],
        drive: turret_family,
    };
    let wrist_friction = FrictionParams {
        coulomb: 0.008,
        static_excess: 0.004,
        stribeck: 1e-3,
        viscous: 2e-6,
        presliding: 0.1,
        presliding_damping: 0.0,
    };
    let hinge = FrictionParams {
        coulomb: door.hinge_coulomb,
        static_excess: 0.0,
        stribeck: 0.0,
        viscous: door.hinge_viscous,
        presliding: 2e-3,
        presliding_damping: 0.0,
    };
    // Library steps.
    let (mode, request) = match cfg.control {
        DoorControl::Passive => (WristMode::Passive, WristMode::Passive),
        DoorControl::ActiveHold => (WristMode::Active, WristMode::Active),
    };
    let _ = mode;
    let wparams = door_wrist_step(cfg, WristMode::Active)?;
    let wstep = WristStepConfig::<S>::new(&wparams);
    // The joints where the scene starts them (straight: zero).
    let q0 = [0, 1].map(|i| sc.wrist_joint[i].angle(&sc.world.bodies, 0.0));
    let start_motors: MotorAngles<S> = WristReadings::<S>::from_si([0.0; 6], q0, [0.0; 2]).motors;
    let mut wstate = wstep.state(start_motors);
    let passive = PassiveConfig::<S>::new(&PassiveParams::table_4_1(0.1 / 1.14e-5)?);
    let hold =
        RobustAdaptiveConfig::<S>::new(&RobustAdaptiveParams::try_new(turret_hold_design())?);
    let mut hold_state = hold.initial_state();
    let wrist_count = core::f64::consts::TAU / 2000.0;
    let quant = |x: f64, q: f64| (x / q).round() * q;
    // Memory and outputs.
    let mut mem = Memory {
        turret: [0.0; 2],
        wrist: WristDrives::new(
            sc.wrist_joint,
            sc.wrist_motor,
            WRIST_RATIO,
            WRIST_DRIVE,
            wrist_friction,
            q0,
        ),
        hinge_anchor: 0.0,
        door_angle: 0.0,
    };
    let mut last_enc = q0;
    let mut last_turret_enc = 0.0f64;
    let mut wrench = [0.0f64; 6];
    let mut torque_motor: [f64; 2];
    let mut torque_turret: f64;
    let mut transmission = 0.0f64;
    let mut true_tau = [0.0f64; 2];
    let mut force_now = 0.0f64;
    let mut out = EngineDoorRun {
        samples: Vec::new(),
        peak_measured: [0.0; 2],
        peak_interaction: [0.0; 2],
        peak_force: 0.0,
        door_angle: 0.0,
        wrist_range: [0.0; 2],
        loop_error: 0.0,
        off_mode_ticks: 0,
        saturated_ticks: 0,
        door: *door,
    };
    let ticks = (total / CONTROL_PERIOD).round() as usize;
    let pre_ticks = (PRE_GRASP / CONTROL_PERIOD).round() as usize;
    let (kg, kr) = (cfg.grasp_stiffness, cfg.grasp_rotational_stiffness);
    let base_w = 100.0;
    let (kp, kd) = (base_w * base_w, 2.0 * base_w);
    for k in 0..pre_ticks + ticks {
        let pre = k < pre_ticks;
        // Time from the grasp (negative before it).
        let time = (k as f64 - pre_ticks as f64) * CONTROL_PERIOD;
        if k == pre_ticks {
            // The grasp: the knob is where the gripper holds it.
            let b = &sc.world.bodies;
            let grasp = b[sc.gripper].position() * Point::from(sc.grasp_local);
            let knob = b[sc.door].position().inverse() * grasp;
            let rest = b[sc.gripper].rotation().inverse() * b[sc.door].rotation();
            sc.knob = Some((knob.coords, rest));
        }
        let target = WristTarget::<S>::from_si(start_pitch, 0.0, 0.0, 0.0).with_request(if pre {
            WristMode::Active
        } else {
            request
        });
        let turret_passive = !pre && cfg.control == DoorControl::Passive;
        // ---- sensors at the tick ----
        let b = &sc.world.bodies;
        let m_angle = [0, 1].map(|i| mem.wrist.rotor_angle(b, i));
        let enc = [0, 1].map(|i| quant(m_angle[i], wrist_count) / WRIST_RATIO);
        let enc_v = [0, 1].map(|i| (enc[i] - last_enc[i]) / CONTROL_PERIOD);
        last_enc = enc;
        let t_motor = quant(sc.turret_motor.angle(b, mem.turret[1]), wrist_count);
        let t_motor_v = (t_motor - last_turret_enc) / CONTROL_PERIOD;
        last_turret_enc = t_motor;
        let volts = gauges.read(&wrench);
        let sg = volts.map(|v| v - V_REF);
        let readings = WristReadings::<S>::from_si(sg, enc, enc_v);
        let wout = wstep.update(&mut wstate, &readings, &target);
        torque_motor = wout.motor_torque_si();
        if !pre {
            out.off_mode_ticks += (wout.mode != request) as usize;
        }
        out.saturated_ticks += (!pre && wout.saturated) as usize;
        let measured = wout.interaction_si();
        let tau_hat = transmission + 0.05 * (2.0 * rng.uniform() - 1.0);
        let si = ControlInput::<f64> {
            desired_position: 0.0,
            motor_position: t_motor,
            motor_velocity: t_motor_v,
            joint_torque: tau_hat,
            ..Default::default()
        };
        torque_turret = if turret_passive {
            passive.update(&ControlInput::<S>::from_si(&si)).torque_si()
        } else {
            hold.update(&mut hold_state, &ControlInput::<S>::from_si(&si))
                .torque_si()
        };
        // ---- record (from the grasp on) ----
        if !pre {
            let b = &sc.world.bodies;
            let delta = sc.pitch.angle(b, 0.0);
            let gamma = sc.yaw.angle(b, 0.0);
            let door_angle = -sc.door_hinge.angle(b, -mem.door_angle);
            out.samples.push(EngineDoorSample {
                time,
                door: door_angle,
                turret: sc.turret_link.angle(b, mem.turret[0]),
                wrist: [delta, gamma],
                reference: wout.reference_si(),
                measured,
                interaction: true_tau,
                base: pose,
                motors: enc,
                motor_reference: wout.motor_reference_si(),
            });
            for i in 0..2 {
                out.peak_measured[i] = out.peak_measured[i].max(measured[i].abs());
                out.peak_interaction[i] = out.peak_interaction[i].max(true_tau[i].abs());
            }
            out.wrist_range[0] = out.wrist_range[0].max(delta.abs());
            out.wrist_range[1] = out.wrist_range[1].max(gamma.abs());
            out.peak_force = out.peak_force.max(force_now);
            out.loop_error = out.loop_error.max(loop_error(&sc, delta, gamma));
        }
        // ---- engine steps until the next tick ----
        step_ticks(
            &mut sc,
            &mut mem,
            &motion,
            &mut pose,
            time,
            dt,
            per_tick,
            cfg,
            (kp, kd),
            (kg, kr),
            &mut turret_drive,
            (&hinge, door),
            (torque_motor, torque_turret),
            &mut transmission,
            &mut true_tau,
            &mut force_now,
            &mut wrench,
        )?;
    }
    out.door_angle = mem.door_angle;
    Ok(out)
}

/// Index into [`crate::sim::plants::joint_family`] of the turret's drive:
/// the spline backbone, 30 % of the catalogue loss at the node, full motor
/// friction (`F = 0.012` N·m; the quick family's first corner). Its
/// kinematic error is drawn from the run's seed.
pub const TURRET_FAMILY_MEMBER: usize = 14;

/// The turret's drive: a family member, and the motor angle (rad) at which
/// it carries no torque with the link at 0, added to the rotor joint's
/// angle (the scene starts the rotor at 0).
struct TurretDrive {
    drive: FamilyDrives,
    motor_offset: f64,
}

impl TurretDrive {
    /// The member's state for the scene's turret state `ts`.
    fn at(&self, ts: DriveState) -> DriveState {
        DriveState {
            motor_angle: ts.motor_angle + self.motor_offset,
            ..ts
        }
    }
}

/// The engine steps of one control tick; `wrench` becomes the sensor's
/// wrench averaged over the tick (the gauge amplifiers' integrate-and-dump
/// anti-aliasing filter ahead of the 4 ms sampling).
#[allow(clippy::too_many_arguments)]
fn step_ticks(
    sc: &mut Scene,
    mem: &mut Memory,
    motion: &BaseMotion,
    pose: &mut [f64; 3],
    time: f64,
    dt: f64,
    per_tick: usize,
    cfg: &DoorConfig,
    gains: (f64, f64),
    grasp: (f64, f64),
    turret_drive: &mut TurretDrive,
    friction: (&FrictionParams, &DoorBody),
    torques: ([f64; 2], f64),
    transmission: &mut f64,
    true_tau: &mut [f64; 2],
    force_now: &mut f64,
    wrench: &mut [f64; 6],
) -> Result<(), ParamError> {
    let mut sum = [0.0; 6];
    for s in 0..per_tick {
        let t = time + s as f64 * dt;
        let w = step_engine(
            sc,
            mem,
            motion,
            pose,
            t,
            dt,
            cfg,
            gains,
            grasp,
            turret_drive,
            friction,
            torques,
            transmission,
            true_tau,
            force_now,
        )
        .ok_or(ParamError::NotFinite {
            name: "dt (the engine state diverged: the step is too coarse for the drive springs)",
            value: dt,
        })?;
        for (a, b) in sum.iter_mut().zip(w) {
            *a += b;
        }
    }
    *wrench = sum.map(|x| x / per_tick as f64);
    Ok(())
}

/// The angle (rad) between `L2`'s orientation and the one the universal
/// joint's `(δ, γ)` give it relative to the arm.
fn loop_error(sc: &Scene, delta: f64, gamma: f64) -> f64 {
    let b = &sc.world.bodies;
    let rel = b[sc.link].rotation().inverse() * b[sc.output].rotation();
    let uj = UnitQuaternion::from_axis_angle(&UnitVector::new_normalize(sc.pitch.axis), delta)
        * UnitQuaternion::from_axis_angle(&UnitVector::new_normalize(sc.yaw.axis), gamma);
    rel.angle_to(&uj)
}

#[allow(clippy::too_many_arguments)]
fn step_engine(
    sc: &mut Scene,
    mem: &mut Memory,
    motion: &BaseMotion,
    pose: &mut [f64; 3],
    t: f64,
    dt: f64,
    cfg: &DoorConfig,
    (kp, kd): (f64, f64),
    (kg, kr): (f64, f64),
    turret_drive: &mut TurretDrive,
    (hinge, door): (&FrictionParams, &DoorBody),
    (torque_motor, torque_turret): ([f64; 2], f64),
    transmission: &mut f64,
    true_tau: &mut [f64; 2],
    force_now: &mut f64,
) -> Option<[f64; 6]> {
    if !sc.world.is_finite() {
        return None;
    }
    sc.world.clear_forces();
    let bodies = &mut sc.world.bodies;
    // ---- base: track the planned pose ----
    let (v, w) = motion.velocity(t);
    let h = 1e-4;
    let vel = |t: f64| motion.velocity(t.max(0.0));
    let (vp, wp) = vel(t + h);
    let (vm, wm) = vel(t - h);
    let (vdot, wdot) = ((vp - vm) / (2.0 * h), (wp - wm) / (2.0 * h));
    let vddot = (vel(t + 2.0 * h).0 - 2.0 * v + vel(t - 2.0 * h).0) / (4.0 * h * h);
    let heading = pose[2];
    let fwd = Vector::new(heading.cos(), heading.sin(), 0.0);
    let lat = Vector::new(-heading.sin(), heading.cos(), 0.0);
    let pitch = cfg.rocking * vdot;
    let pitch_rate = cfg.rocking * vddot;
    let heading0 = sc_heading0(cfg);
    let r_des = UnitQuaternion::from_axis_angle(&UnitVector::new_normalize(lat), pitch)
        * UnitQuaternion::from_axis_angle(&Vector::z_axis(), heading - heading0);
    let p_des = Vector::new(pose[0], pose[1], 0.0);
    let v_des = fwd * v;
    let w_des = Vector::z() * w + lat * pitch_rate;
    let a_des = fwd * vdot + lat * (v * w);
    let base = &mut bodies[sc.base];
    let p_b = base.translation();
    let e_rot = (r_des * base.rotation().inverse()).scaled_axis();
    let force = BASE_MASS * (a_des + (v_des - base.linvel()) * kd + (p_des - p_b) * kp);
    let torque = BASE_INERTIA * (Vector::z() * wdot + (w_des - base.angvel()) * kd + e_rot * kp);
    base.add_force(force, true);
    base.add_torque(torque, true);
    // ---- turret drive ----
    let tl = sc.turret_link;
    let tm = sc.turret_motor;
    let ts = DriveState {
        link_angle: tl.angle(bodies, mem.turret[0]),
        motor_angle: tm.angle(bodies, mem.turret[1]),
        link_speed: tl.speed(bodies),
        motor_speed: tm.speed(bodies),
    };
    let d = turret_drive.drive.torques(0, &turret_drive.at(ts));
    *transmission = d.transmission;
    tl.push(bodies, d.on_link);
    tm.push(bodies, d.on_motor + torque_turret);
    // ---- wrist drives ----
    mem.wrist.push(bodies, torque_motor);
    // ---- door hinge and closer ----
    let dh = sc.door_hinge;
    let qd = dh.angle(bodies, -mem.door_angle);
    let opening = -qd;
    let f_hinge = hinge.torque(qd, dh.speed(bodies), mem.hinge_anchor);
    let closer = if opening > 0.0 {
        door.closer_stiffness * opening + door.closer_preload * (opening / 0.01).min(1.0)
    } else {
        0.0
    };
    dh.push(bodies, -f_hinge + closer);
    // ---- grasp spring (from the grasp on) ----
    let g = &bodies[sc.gripper];
    let grasp = g.position() * Point::from(sc.grasp_local);
    let (f_grip, c_grip, knob) = match sc.knob {
        Some((knob_local, rest)) => {
            let dr = &bodies[sc.door];
            let knob = dr.position() * Point::from(knob_local);
            let vg = g.velocity_at_point(&grasp);
            let vk = dr.velocity_at_point(&knob);
            let f = (knob - grasp) * kg + (vk - vg) * 40.0;
            let rel = g.rotation().inverse() * dr.rotation() * rest.inverse();
            let e = g.rotation() * rel.scaled_axis();
            let c = e * kr + (dr.angvel() - g.angvel()) * 0.3;
            (f, c, knob)
        }
        None => (Vector::zeros(), Vector::zeros(), grasp),
    };
    // True interaction about the wrist centre.
    let link_pose = *bodies[sc.link].position();
    let centre = link_pose * Point::from(sc.wrist_centre);
    let moment = (grasp - centre).cross(&f_grip) + c_grip;
    let pitch_axis = sc.pitch.world_axis(bodies);
    let yaw_axis = sc.yaw.world_axis(bodies);
    *true_tau = [moment.dot(&pitch_axis), moment.dot(&yaw_axis)];
    *force_now = f_grip.norm();
    // Sensor frame and the momentum balance's start.
    let o = &bodies[sc.output];
    let origin = (o.position() * Point::from(sc.sensor_local)).coords;
    let frame = o.rotation()
        * UnitQuaternion::from_axis_angle(&Vector::x_axis(), -core::f64::consts::FRAC_PI_2);
    let g = &bodies[sc.gripper];
    let mb = MomentumBalance {
        v0: *g.linvel(),
        w0: *g.angvel(),
        com: g.center_of_mass().coords,
        point: grasp.coords,
        force: f_grip,
        couple: c_grip,
        origin,
        frame,
    };
    let g = &mut bodies[sc.gripper];
    g.add_force_at_point(f_grip, grasp, true);
    g.add_torque(c_grip, true);
    let dr = &mut bodies[sc.door];
    dr.add_force_at_point(-f_grip, knob, true);
    dr.add_torque(-c_grip, true);
    // ---- step ----
    sc.world.step();
    // ---- after the step: memories, pose, sensor wrench ----
    let bodies = &sc.world.bodies;
    let ts = DriveState {
        link_angle: tl.angle(bodies, mem.turret[0]),
        motor_angle: tm.angle(bodies, mem.turret[1]),
        link_speed: tl.speed(bodies),
        motor_speed: tm.speed(bodies),
    };
    turret_drive.drive.advance(0, &turret_drive.at(ts));
    mem.turret = [ts.link_angle, ts.motor_angle];
    mem.wrist.advance(bodies);
    let qd = dh.angle(bodies, -mem.door_angle);
    hinge.update_anchor(qd, dh.speed(bodies), &mut mem.hinge_anchor);
    mem.door_angle = -qd;
    pose[0] += v * heading.cos() * dt;
    pose[1] += v * heading.sin() * dt;
    pose[2] += w * dt;
    let g = &bodies[sc.gripper];
    let (v1, w1) = (*g.linvel(), *g.angvel());
    let alpha = (w1 - mb.w0) / dt;
    let f_joint = sc.gripper_mass * (v1 - mb.v0) / dt - mb.force;
    let m_joint = sc.gripper_inertia * alpha - mb.couple - (mb.point - mb.com).cross(&mb.force);
    let f_s = -f_joint;
    let m_s = -(m_joint + (mb.com - mb.origin).cross(&f_joint));
    let f = mb.frame.inverse() * f_s;
    let m = mb.frame.inverse() * m_s;
    Some([f.x, f.y, f.z, m.x, m.y, m.z])
}

/// The base's heading at the start, rad.
fn sc_heading0(cfg: &DoorConfig) -> f64 {
    let b0 = [cfg.door_radius, -cfg.grasp_offset - cfg.reach];
    b0[1].atan2(b0[0]) + core::f64::consts::FRAC_PI_2 + cfg.heading_error
}
