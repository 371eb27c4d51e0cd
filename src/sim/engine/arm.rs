//! The modular arm of thesis ch. 4 (§4.1, Fig. 4.1) built from bodies on the
//! engine: an independent computation of the motions that
//! [`crate::sim::Mrr`] integrates from eq. (4.1)–(4.6).
//!
//! # Bodies and joints
//!
//! The arm is read from the same [`ModuleParams`] as [`crate::sim::Mrr`]
//! (the thesis's module data: rotor inertia `I_m = 1.14e-5 kg·m²`, link
//! 0.64 kg and 0.45 m, `M2 = M3 = 1.2 kg`, `N = 100`, Table 4.1, as
//! [`ModuleParams::thesis_joint`] and
//! [`crate::sim::closed_loop::payload_joint`] set them). For module `i`:
//!
//! * **Link `i`** — a body whose frame is the module's link frame: origin
//!   at the joint (`origin`, in the frame of link `i − 1`), and, at
//!   `q_l = 0`, the orientation of link `i − 1`. It turns about `axis`
//!   relative to link `i − 1` (the fixed base for `i = 1`) on a
//!   reduced-coordinate (multibody) revolute joint.
//! * **Rotor `i`** — its own body on its own multibody revolute joint about
//!   the same axis, through the same point, also carried by link `i − 1`
//!   (the housing is part of the carrying link). It is symmetric about its
//!   axis (Assumption 1 of §4.1): axial moment `I_m` (`rotor_inertia`),
//!   transverse moment and mass from [`RotorBody`], centre of mass on the
//!   axis at the joint.
//!
//! [`ModuleParams`] counts the rotor's mass and transverse inertia as part
//! of the carrying link (its `link_mass` "includes the rotors it
//! carries"); here they are taken out of link `i − 1` (mass, centre of mass
//! and inertia by the parallel-axis theorem) and put on the rotor body, so
//! that the bodies together have exactly the mass distribution the model
//! describes, but the engine sees a spinning rotor with its own gyroscopic
//! terms instead of the model's `I_m z_miᵀ ω` couplings. For the base
//! module the rotor is carried by the base, and nothing is taken out.
//!
//! The engine knows nothing of eq. (4.1)–(4.6): it has bodies with mass,
//! joints, gravity as a force `m g` at every centre of mass, and torques.
//!
//! # The drive and the other torques
//!
//! The harmonic drive between rotor `i` and link `i` is ours, behind the
//! [`DriveModel`] hook: from the module's [`DriveState`] (link angle
//! `q_l`, motor angle `q_m`, both relative to link `i − 1`, and their
//! speeds) it returns the generalized forces on `q_l` and `q_m`
//! ([`DriveTorques`]; `τ_t` and `−τ_t/N` for a drive without kinematic
//! error, the right-hand sides of eq. 4.1/4.2). They act on the bodies as
//! torque pairs about the joint axis — on the link (or rotor) and, reversed,
//! on link `i − 1` — which is exactly a generalized force on that one
//! coordinate. The motor torque `τ_m` and an external link torque
//! `τ_ext` (a generalized force on `q_l`, as [`crate::sim::Mrr`] has it)
//! are pairs the same way. Implementations: [`LinearDrives`] (a spring and
//! damper per module), [`PlantDrives`] (the simulated drive
//! [`crate::sim::DrivePlantParams`] with its hysteresis and kinematic
//! error, and optionally the friction of eq. 4.7/4.8 of
//! [`crate::sim::FrictionParams`]; built from the models the library
//! carries, so a comparison), [`super::FamilyDrives`] (members of the
//! independent joint family, the plant the chapter-4 figures run on), or
//! any closure
//! `FnMut(usize, &DriveState) -> DriveTorques`.
//!
//! # Time stepping
//!
//! The hook and the applied torques are evaluated once per engine step
//! `dt` ([`EngineSettings::dt`]) and held over it. Within a step the
//! engine integrates the multibody in `solver_iterations` substeps of
//! `dt / solver_iterations` (semi-implicit Euler on the joint coordinates,
//! gravity, Coriolis and gyroscopic terms re-evaluated every substep, the
//! applied torques not). Run the arm with **one** substep
//! ([`arm_settings`]): a step is then semi-implicit
//! (symplectic) Euler for the drive spring too, and the error is first
//! order in `dt` (halving the step halves every difference to
//! [`crate::sim::Mrr`], measured in `tests/engine_arm.rs`). With several
//! substeps the drive torque is held while the bodies move, which
//! integrates the spring by a scheme whose energy grows: at `dt = 1e-4 s`
//! and 4 substeps a 1 s torque-driven run was 3 rad off, and halving the
//! step cut the error tenfold instead of twofold.
//!
//! The drive is an explicit spring, so `dt ω` must stay well below 1 for
//! the drive's frequency `ω = √(K (1/J_l + 1/(N² I_m)))`: ≈ 650 rad/s for
//! the SHD-17-100's stiffest segment (`K3 = 1.3e4 N·m/rad`) between the
//! thesis's rotor (`N² I_m = 0.114 kg·m²`) and link (`J_l = 0.043 kg·m²`
//! about the joint), `dt ω ≈ 0.065` at [`ARM_DT`] = 1e-4 s. The engine's default joint damping
//! (0.1 N·m·s/rad per revolute joint in rapier 0.27) is set to zero: the
//! only dissipation is the one the drive hook puts in. The motor-spring
//! fields of [`EngineSettings`] are not used by the arm: its motors are
//! torque sources.
//!
//! Angles are read from the bodies' poses (unwrapped step to step), speeds
//! from the engine's joint velocities.
//!
//! # Contacts
//!
//! The arm has no colliders unless one is added: [`EngineArm::add_wall`]
//! puts a frictionless ball ([`TipBall`]) on a link and a fixed box
//! ([`Wall`], e.g. [`Wall::stop_for`]) in the world, and the engine's
//! contact force between them is read back as a force
//! ([`EngineArm::contact_force`], N, base frame) and as a generalized force
//! on the ball's link coordinate ([`EngineArm::contact_torque`], N·m). It is
//! the collision obstacle of `sim::engine::arm_scenarios` that
//! [`crate::sim::Mrr`] cannot have.

use rapier3d_f64::na::{Matrix3, UnitQuaternion};
use rapier3d_f64::prelude::*;

use super::world::{angle_about, unwrap_near, EngineSettings, World};
use crate::error::ParamError;
use crate::sim::mrr::ModuleParams;
use crate::sim::transmission::DrivePlantParams;
use crate::sim::FrictionParams;

/// The state of one module's drive, in the chapter-4 coordinates of
/// [`crate::sim::Mrr`]: angles of link `i` and rotor `i` relative to link
/// `i − 1` about the module's axis (rad, right-handed about the axis), and
/// their rates (rad/s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DriveState {
    /// Link angle `q_l`, rad.
    pub link_angle: f64,
    /// Motor (rotor) angle `q_m`, rad.
    pub motor_angle: f64,
    /// Link speed `q̇_l`, rad/s.
    pub link_speed: f64,
    /// Motor speed `q̇_m`, rad/s.
    pub motor_speed: f64,
}

/// What a drive does to its module: the transmission torque and the
/// generalized forces it puts on the link and motor coordinates (N·m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DriveTorques {
    /// Transmission torque `τ_t` on the link, N·m (what a link-side torque
    /// sensor reads).
    pub transmission: f64,
    /// Generalized force on `q_l`, N·m (`τ_t` for a drive without
    /// kinematic error, minus any link-side friction).
    pub on_link: f64,
    /// Generalized force on `q_m`, N·m (`−τ_t/N` for a drive without
    /// kinematic error, minus any motor-side friction).
    pub on_motor: f64,
}

impl DriveTorques {
    /// An ideal reducer of ratio `ratio` carrying `transmission` (N·m):
    /// `τ_t` on the link, `−τ_t/N` on the rotor (eq. 4.1/4.2).
    pub fn ideal(transmission: f64, ratio: f64) -> Self {
        DriveTorques {
            transmission,
            on_link: transmission,
            on_motor: -transmission / ratio,
        }
    }
}

/// The hook through which a drive model acts on the arm.
///
/// [`EngineArm`] calls [`torques`](Self::torques) for every module before
/// each engine step and holds the result over the step, then
/// [`advance`](Self::advance) with the new state after it (for models with
/// memory: hysteresis anchors, friction presliding).
pub trait DriveModel {
    /// The torques of module `module`'s drive at `state`.
    fn torques(&mut self, module: usize, state: &DriveState) -> DriveTorques;

    /// Update the model's memory after a step ended at `state`.
    fn advance(&mut self, module: usize, state: &DriveState) {
        let _ = (module, state);
    }

    /// Energy stored in module `module`'s drive at `state` (J); zero unless
    /// the model says otherwise (used by [`EngineArm::energy`]).
    fn stored_energy(&self, module: usize, state: &DriveState) -> f64 {
        let _ = (module, state);
        0.0
    }
}

impl<F: FnMut(usize, &DriveState) -> DriveTorques> DriveModel for F {
    fn torques(&mut self, module: usize, state: &DriveState) -> DriveTorques {
        self(module, state)
    }
}

/// A linear drive per module: `τ_t = K δ + c δ̇` with the torsion
/// `δ = q_m/N − q_l` (rad), stiffness `K` (N·m/rad) and damping `c`
/// (N·m·s/rad); ideal reducer ([`DriveTorques::ideal`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LinearDrives {
    ratio: Vec<f64>,
    stiffness: Vec<f64>,
    damping: Vec<f64>,
}

impl LinearDrives {
    /// One drive per entry `(N, K, c)`: `N ≥ 1`, `K > 0`, `c ≥ 0`, all
    /// finite.
    pub fn try_new(drives: &[(f64, f64, f64)]) -> Result<Self, ParamError> {
        let mut out = LinearDrives {
            ratio: Vec::with_capacity(drives.len()),
            stiffness: Vec::with_capacity(drives.len()),
            damping: Vec::with_capacity(drives.len()),
        };
        for &(n, k, c) in drives {
            crate::error::gear_ratio(n)?;
            crate::error::positive("stiffness", k)?;
            let c = crate::error::finite("damping", c)?;
            if c < 0.0 {
                return Err(ParamError::Negative {
                    name: "damping",
                    value: c,
                });
            }
            out.ratio.push(n);
            out.stiffness.push(k);
            out.damping.push(c);
        }
        Ok(out)
    }

    fn torsion(&self, i: usize, s: &DriveState) -> (f64, f64) {
        let n = self.ratio[i];
        (
            s.motor_angle / n - s.link_angle,
            s.motor_speed / n - s.link_speed,
        )
    }
}

impl DriveModel for LinearDrives {
    fn torques(&mut self, i: usize, s: &DriveState) -> DriveTorques {
        if i >= self.ratio.len() {
            return DriveTorques::default();
        }
        let (d, dd) = self.torsion(i, s);
        DriveTorques::ideal(self.stiffness[i] * d + self.damping[i] * dd, self.ratio[i])
    }

    fn stored_energy(&self, i: usize, s: &DriveState) -> f64 {
        if i >= self.ratio.len() {
            return 0.0;
        }
        let (d, _) = self.torsion(i, s);
        0.5 * self.stiffness[i] * d * d
    }
}

/// The simulated drive plant of each module ([`DrivePlantParams`]: the
/// catalogue backbone, Maxwell-slip hysteresis, the eq. 3.7 kinematic
/// error) and, optionally, its link- and motor-side friction
/// ([`FrictionParams`], eq. 4.7/4.8 with presliding), with the same
/// generalized forces as [`crate::sim::Mrr`]'s: `−τ_t ∂δ_c/∂q_l − f_l`
/// on the link, `−τ_t ∂δ_c/∂q_m − f_m` on the motor.
#[derive(Debug, Clone, PartialEq)]
pub struct PlantDrives {
    drives: Vec<DrivePlantParams>,
    friction: Vec<(FrictionParams, FrictionParams)>,
    slip_anchors: Vec<Vec<f64>>,
    /// Presliding anchors `(link, motor)`, rad.
    friction_anchors: Vec<(f64, f64)>,
}

impl PlantDrives {
    /// The drives of `modules`, with their friction when `with_friction`
    /// (otherwise none). Every element starts relaxed at `state` (one per
    /// module; missing entries are zero).
    pub fn of(modules: &[ModuleParams], with_friction: bool, state: &[DriveState]) -> Self {
        let drives: Vec<DrivePlantParams> = modules.iter().map(|m| m.drive.clone()).collect();
        let friction = modules
            .iter()
            .map(|m| {
                if with_friction {
                    (m.link_friction, m.motor_friction)
                } else {
                    (FrictionParams::NONE, FrictionParams::NONE)
                }
            })
            .collect();
        let mut out = PlantDrives {
            slip_anchors: drives
                .iter()
                .map(|d| vec![0.0; d.slip_elements.len()])
                .collect(),
            friction_anchors: vec![(0.0, 0.0); drives.len()],
            drives,
            friction,
        };
        out.relax(state);
        out
    }

    /// Relax every element at `state` (no stored presliding deflection or
    /// hysteresis), as [`crate::sim::Mrr::set_state`] does.
    pub fn relax(&mut self, state: &[DriveState]) {
        for i in 0..self.drives.len() {
            let s = state.get(i).copied().unwrap_or_default();
            let (dc, _, _) = self.drives[i].compliance_torsion(s.link_angle, s.motor_angle);
            self.slip_anchors[i].iter_mut().for_each(|z| *z = dc);
            self.friction_anchors[i] = (s.link_angle, s.motor_angle);
        }
    }
}

impl DriveModel for PlantDrives {
    fn torques(&mut self, i: usize, s: &DriveState) -> DriveTorques {
        let (Some(d), Some((fl, fm))) = (self.drives.get(i), self.friction.get(i)) else {
            return DriveTorques::default();
        };
        let (dc, dl, dm) = d.compliance_torsion(s.link_angle, s.motor_angle);
        let tt = d.torque(dc, &self.slip_anchors[i]);
        let (zl, zm) = self.friction_anchors[i];
        DriveTorques {
            transmission: tt,
            on_link: -tt * dl - fl.torque(s.link_angle, s.link_speed, zl),
            on_motor: -tt * dm - fm.torque(s.motor_angle, s.motor_speed, zm),
        }
    }

    fn advance(&mut self, i: usize, s: &DriveState) {
        let (Some(d), Some((fl, fm))) = (self.drives.get(i), self.friction.get(i)) else {
            return;
        };
        let (dc, _, _) = d.compliance_torsion(s.link_angle, s.motor_angle);
        d.update_anchors(dc, &mut self.slip_anchors[i]);
        let (zl, zm) = &mut self.friction_anchors[i];
        fl.update_anchor(s.link_angle, s.link_speed, zl);
        fm.update_anchor(s.motor_angle, s.motor_speed, zm);
    }

    fn stored_energy(&self, i: usize, s: &DriveState) -> f64 {
        let Some(d) = self.drives.get(i) else {
            return 0.0;
        };
        let (dc, _, _) = d.compliance_torsion(s.link_angle, s.motor_angle);
        d.elastic_energy(dc, &self.slip_anchors[i])
    }
}

/// The rotor as a body (module docs): its mass (kg) and its moment of
/// inertia about a transverse axis through its centre (kg·m²), taken out of
/// the carrying link. Neither changes the motion (the model counts both in
/// the carrying link); they decide which body carries them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotorBody {
    mass: f64,
    transverse_inertia: f64,
}

impl RotorBody {
    /// A rotor of `mass` (kg, finite, > 0) and `transverse_inertia`
    /// (kg·m², finite, > 0).
    pub fn try_new(mass: f64, transverse_inertia: f64) -> Result<Self, ParamError> {
        Ok(RotorBody {
            mass: crate::error::positive("rotor_mass", mass)?,
            transverse_inertia: crate::error::positive(
                "rotor_transverse_inertia",
                transverse_inertia,
            )?,
        })
    }

    /// Mass, kg.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Transverse moment of inertia, kg·m².
    pub fn transverse_inertia(&self) -> f64 {
        self.transverse_inertia
    }
}

impl Default for RotorBody {
    /// 0.1 kg and 1.14e-5 kg·m² (transverse moment equal to the thesis
    /// rotor's axial one, Table 4.1: a rotor about as long as it is wide;
    /// an assumption, the thesis gives neither).
    fn default() -> Self {
        RotorBody {
            mass: 0.1,
            transverse_inertia: 1.14e-5,
        }
    }
}

/// Mass, centre of mass (m, body frame) and inertia about it (kg·m², body
/// frame) of one body.
#[derive(Debug, Clone, Copy)]
struct Inertial {
    mass: f64,
    com: Vector<Real>,
    inertia: Matrix3<f64>,
}

#[derive(Debug, Clone, Copy)]
struct Joint {
    /// Axis (unit) in the parent's frame.
    axis: Vector<Real>,
    /// Joint point in the parent's frame, m.
    origin: Vector<Real>,
    handle: MultibodyJointHandle,
}

/// The modular arm on the engine (module docs).
pub struct EngineArm<D: DriveModel> {
    world: World,
    settings: EngineSettings,
    gravity: Vector<Real>,
    base: RigidBodyHandle,
    links: Vec<RigidBodyHandle>,
    rotors: Vec<RigidBodyHandle>,
    link_joints: Vec<Joint>,
    rotor_joints: Vec<Joint>,
    link_inertial: Vec<Inertial>,
    rotor_inertial: Vec<Inertial>,
    max_motor_torque: Vec<f64>,
    state: Vec<DriveState>,
    motor_torque: Vec<f64>,
    external_torque: Vec<f64>,
    last_drive: Vec<DriveTorques>,
    drive: D,
    time: f64,
    /// A ball on a link and the fixed wall it can hit ([`Self::add_wall`]).
    obstacle: Option<contact::Obstacle>,
}

fn matrix(m: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| m[i][j])
}

/// `m (|r|² 1 − r rᵀ)`: the parallel-axis term of a mass `m` at `r`.
fn shift(m: f64, r: &Vector<Real>) -> Matrix3<f64> {
    (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * m
}

fn not_finite(name: &'static str, v: f64) -> Result<(), ParamError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(ParamError::NotFinite { name, value: v })
    }
}

/// The engine step the arm is run at, s (module docs).
pub const ARM_DT: f64 = 1e-4;

/// The arm's engine settings: [`ARM_DT`] with one solver substep per step
/// (module docs; the motor-spring fields, unused by the arm, at their
/// defaults).
pub fn arm_settings() -> EngineSettings {
    let d = EngineSettings::default();
    EngineSettings::try_new(ARM_DT, 1, d.motor_stiffness(), d.motor_damping()).unwrap_or(d)
}

impl<D: DriveModel> EngineArm<D> {
    /// The arm of `modules` (module 0 on the base) under `gravity` (m/s²,
    /// base frame, e.g. `[0, 0, −9.81]`), rotors as `rotor`, drives `drive`,
    /// stepped with `settings` (its `dt` and `solver_iterations`), at rest
    /// at `q_l = q_m = 0`.
    ///
    /// Validated, each error naming the value: at least one module
    /// (`modules`); gravity finite; per module a unit `axis` (within 1e-9),
    /// finite `origin`, `link_com` and `link_inertia`, positive
    /// `rotor_inertia`, a gear `ratio ≥ 1`, a positive `max_motor_torque`,
    /// no `link_locked` (not modelled here), a carrying link that keeps a
    /// positive mass once the rotor it carries is taken out (`link_mass`
    /// above the rotor's mass), and every `link_inertia` symmetric (to
    /// 1e-9 relative) and positive semi-definite once the carried rotor is
    /// taken out (a negative one is reported by its smallest eigenvalue).
    pub fn try_new(
        modules: &[ModuleParams],
        gravity: [f64; 3],
        rotor: RotorBody,
        drive: D,
        settings: EngineSettings,
    ) -> Result<Self, ParamError> {
        if modules.is_empty() {
            return Err(ParamError::NotPositive {
                name: "modules",
                value: 0.0,
            });
        }
        for g in gravity {
            not_finite("gravity", g)?;
        }
        let mut link_inertial = Vec::with_capacity(modules.len());
        let mut rotor_inertial = Vec::with_capacity(modules.len());
        for m in modules {
            let axis = Vector::from(m.axis);
            let norm = axis.norm();
            if norm.is_nan() || (norm - 1.0).abs() > 1e-9 {
                return Err(ParamError::OutOfRange {
                    name: "axis",
                    value: norm,
                    min: 1.0 - 1e-9,
                    max: 1.0 + 1e-9,
                });
            }
            for v in m.origin {
                not_finite("origin", v)?;
            }
            for v in m.link_com {
                not_finite("link_com", v)?;
            }
            for v in m.link_inertia.iter().flatten() {
                not_finite("link_inertia", *v)?;
            }
            crate::error::positive("rotor_inertia", m.rotor_inertia)?;
            crate::error::positive("link_mass", m.link_mass)?;
            crate::error::positive("max_motor_torque", m.max_motor_torque)?;
            crate::error::gear_ratio(m.drive.ratio)?;
            if m.link_locked {
                return Err(ParamError::OutOfRange {
                    name: "link_locked",
                    value: 1.0,
                    min: 0.0,
                    max: 0.0,
                });
            }
            link_inertial.push(Inertial {
                mass: m.link_mass,
                com: Vector::from(m.link_com),
                inertia: matrix(&m.link_inertia),
            });
            // Rotor: on its axis at the joint; axial I_m, transverse I_t.
            let it = rotor.transverse_inertia;
            rotor_inertial.push(Inertial {
                mass: rotor.mass,
                com: Vector::zeros(),
                inertia: Matrix3::identity() * it
                    + axis * axis.transpose() * (m.rotor_inertia - it),
            });
        }
        // Take rotor i (mass and transverse inertia) out of link i − 1.
        for i in 1..modules.len() {
            let p = Vector::from(modules[i].origin);
            let z = Vector::from(modules[i].axis);
            let link = link_inertial[i - 1];
            let rest_mass = link.mass - rotor.mass;
            if rest_mass <= 0.0 {
                return Err(ParamError::OutOfRange {
                    name: "link_mass",
                    value: link.mass,
                    min: rotor.mass,
                    max: f64::INFINITY,
                });
            }
            // Inertia about the link frame's origin, minus the rotor's.
            let about_origin = link.inertia + shift(link.mass, &link.com);
            let rotor_transverse =
                (Matrix3::identity() - z * z.transpose()) * rotor.transverse_inertia;
            let rest_about_origin = about_origin - rotor_transverse - shift(rotor.mass, &p);
            let rest_com = (link.com * link.mass - p * rotor.mass) / rest_mass;
            let rest_inertia = rest_about_origin - shift(rest_mass, &rest_com);
            link_inertial[i - 1] = Inertial {
                mass: rest_mass,
                com: rest_com,
                inertia: (rest_inertia + rest_inertia.transpose()) * 0.5,
            };
        }
        // Every link, rotors taken out, a physical inertia tensor.
        for link in &link_inertial {
            let sym = (link.inertia + link.inertia.transpose()) * 0.5;
            let smallest = sym.symmetric_eigenvalues().min();
            let asymmetry = (link.inertia - link.inertia.transpose()).abs().max();
            if smallest.is_nan() || smallest < 0.0 {
                return Err(ParamError::Negative {
                    name: "link_inertia",
                    value: smallest,
                });
            }
            if asymmetry > 1e-9 * sym.abs().max() {
                return Err(ParamError::OutOfRange {
                    name: "link_inertia",
                    value: asymmetry,
                    min: 0.0,
                    max: 1e-9 * sym.abs().max(),
                });
            }
        }

        let mut world = World::new(&settings);
        let base = world.base();
        let mut links = Vec::with_capacity(modules.len());
        let mut rotors = Vec::with_capacity(modules.len());
        let mut link_joints = Vec::with_capacity(modules.len());
        let mut rotor_joints = Vec::with_capacity(modules.len());
        let mut parent = base;
        for (i, m) in modules.iter().enumerate() {
            let axis = Vector::from(m.axis);
            let origin = Vector::from(m.origin);
            let mut insert = |inertial: &Inertial| -> RigidBodyHandle {
                let rb = RigidBodyBuilder::dynamic()
                    .additional_mass_properties(MassProperties::with_inertia_matrix(
                        inertial.com.into(),
                        inertial.mass,
                        inertial.inertia,
                    ))
                    .can_sleep(false)
                    .build();
                world.bodies.insert(rb)
            };
            let link = insert(&link_inertial[i]);
            let rotor_body = insert(&rotor_inertial[i]);
            let joint = || {
                RevoluteJointBuilder::new(UnitVector::new_normalize(axis))
                    .local_anchor1(Point::from(origin))
                    .local_anchor2(Point::origin())
            };
            let multibody = ParamError::NotFinite {
                name: "multibody",
                value: f64::NAN,
            };
            let lj = world
                .multibody_joints
                .insert(parent, link, joint(), true)
                .ok_or(multibody)?;
            let rj = world
                .multibody_joints
                .insert(parent, rotor_body, joint(), true)
                .ok_or(multibody)?;
            links.push(link);
            rotors.push(rotor_body);
            link_joints.push(Joint {
                axis,
                origin,
                handle: lj,
            });
            rotor_joints.push(Joint {
                axis,
                origin,
                handle: rj,
            });
            parent = link;
        }
        // No joint damping but what the drive model puts in.
        if let Some((mb, _)) = world.multibody_joints.get_mut(link_joints[0].handle) {
            mb.damping_mut().fill(0.0);
        }
        let n = modules.len();
        let mut arm = EngineArm {
            world,
            settings,
            gravity: Vector::from(gravity),
            base,
            links,
            rotors,
            link_joints,
            rotor_joints,
            link_inertial,
            rotor_inertial,
            max_motor_torque: modules.iter().map(|m| m.max_motor_torque).collect(),
            state: vec![DriveState::default(); n],
            motor_torque: vec![0.0; n],
            external_torque: vec![0.0; n],
            last_drive: vec![DriveTorques::default(); n],
            drive,
            time: 0.0,
            obstacle: None,
        };
        let zero = vec![0.0; n];
        arm.set_state(&zero, &zero, &zero, &zero);
        Ok(arm)
    }

    /// Number of modules.
    pub fn len(&self) -> usize {
        self.links.len()
    }

    /// Always `false`: an arm has at least one module.
    pub fn is_empty(&self) -> bool {
        self.links.is_empty()
    }

    /// The settings it runs with.
    pub fn settings(&self) -> &EngineSettings {
        &self.settings
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The drive model.
    pub fn drive(&self) -> &D {
        &self.drive
    }

    /// The drive model, to change it between steps.
    pub fn drive_mut(&mut self) -> &mut D {
        &mut self.drive
    }

    /// The state of every module's drive (angles rad, speeds rad/s).
    pub fn drive_states(&self) -> &[DriveState] {
        &self.state
    }

    /// Link angles `q_l` (rad).
    pub fn link_angles(&self) -> Vec<f64> {
        self.state.iter().map(|s| s.link_angle).collect()
    }

    /// Motor angles `q_m` (rad).
    pub fn motor_angles(&self) -> Vec<f64> {
        self.state.iter().map(|s| s.motor_angle).collect()
    }

    /// Link speeds (rad/s).
    pub fn link_speeds(&self) -> Vec<f64> {
        self.state.iter().map(|s| s.link_speed).collect()
    }

    /// Motor speeds (rad/s).
    pub fn motor_speeds(&self) -> Vec<f64> {
        self.state.iter().map(|s| s.motor_speed).collect()
    }

    /// The drive torques applied over the last step (before the first
    /// step: zero).
    pub fn drive_torques(&self) -> &[DriveTorques] {
        &self.last_drive
    }

    /// Set the motor torques `τ_m` (N·m), saturated at each module's
    /// `max_motor_torque`; non-finite entries become 0, missing ones stay.
    pub fn set_motor_torque(&mut self, torque: &[f64]) {
        for ((t, out), lim) in torque
            .iter()
            .zip(self.motor_torque.iter_mut())
            .zip(&self.max_motor_torque)
        {
            *out = if t.is_finite() {
                t.clamp(-lim, *lim)
            } else {
                0.0
            };
        }
    }

    /// Motor torques applied now (after saturation), N·m.
    pub fn applied_motor_torque(&self) -> &[f64] {
        &self.motor_torque
    }

    /// Set the external link torques `τ_ext` (N·m, generalized forces on
    /// `q_l`); non-finite entries become 0.
    pub fn set_external_torque(&mut self, torque: &[f64]) {
        for (t, out) in torque.iter().zip(self.external_torque.iter_mut()) {
            *out = if t.is_finite() { *t } else { 0.0 };
        }
    }

    /// Put the arm at link angles `q_l`, motor angles `q_m` (rad) and speeds
    /// `v_l`, `v_m` (rad/s) — one entry per module, non-finite entries read
    /// as 0. The drive model is not touched (relax it separately if it has
    /// memory, e.g. [`PlantDrives::relax`]).
    pub fn set_state(&mut self, q_l: &[f64], q_m: &[f64], v_l: &[f64], v_m: &[f64]) {
        let get = |v: &[f64], i: usize| v.get(i).copied().filter(|x| x.is_finite()).unwrap_or(0.0);
        let Some((mb, _)) = self
            .world
            .multibody_joints
            .get_mut(self.link_joints[0].handle)
        else {
            return;
        };
        // Joint coordinates are displaced to the target; the assembly index
        // of a link is the number of degrees of freedom before it.
        let mut assembly = Vec::with_capacity(mb.num_links());
        let mut acc = 0;
        for l in mb.links() {
            assembly.push(acc);
            acc += l.joint().ndofs();
        }
        let mut velocities = vec![0.0; mb.ndofs()];
        for i in 0..self.links.len() {
            let targets = [
                (
                    self.links[i],
                    get(q_l, i),
                    get(v_l, i),
                    self.state[i].link_angle,
                ),
                (
                    self.rotors[i],
                    get(q_m, i),
                    get(v_m, i),
                    self.state[i].motor_angle,
                ),
            ];
            for (body, q, v, now) in targets {
                let Some(id) = self
                    .world
                    .multibody_joints
                    .rigid_body_link(body)
                    .map(|l| l.id)
                else {
                    continue;
                };
                let Some((mb, _)) = self
                    .world
                    .multibody_joints
                    .get_mut(self.link_joints[0].handle)
                else {
                    return;
                };
                if let Some(link) = mb.link_mut(id) {
                    link.joint.apply_displacement(&[q - now]);
                }
                if let Some(slot) = assembly.get(id).and_then(|&a| velocities.get_mut(a)) {
                    *slot = v;
                }
            }
            self.state[i] = DriveState {
                link_angle: get(q_l, i),
                motor_angle: get(q_m, i),
                link_speed: get(v_l, i),
                motor_speed: get(v_m, i),
            };
        }
        if let Some((mb, _)) = self
            .world
            .multibody_joints
            .get_mut(self.link_joints[0].handle)
        {
            mb.generalized_velocity_mut().copy_from_slice(&velocities);
            mb.forward_kinematics(&self.world.bodies, false);
            mb.update_rigid_bodies(&mut self.world.bodies, true);
        }
    }

    fn rotation(&self, body: RigidBodyHandle) -> UnitQuaternion<Real> {
        *self.world.bodies[body].rotation()
    }

    fn parent_of(&self, i: usize) -> RigidBodyHandle {
        if i == 0 {
            self.base
        } else {
            self.links[i - 1]
        }
    }

    /// Angles from the poses (unwrapped near the last reading) and speeds
    /// from the engine's joint velocities.
    fn read_state(&mut self) {
        for i in 0..self.links.len() {
            let rp = self.rotation(self.parent_of(i));
            let rl = self.rotation(self.links[i]);
            let rr = self.rotation(self.rotors[i]);
            let axis = self.link_joints[i].axis;
            let prev = self.state[i];
            let speed = |h: MultibodyJointHandle| {
                self.world
                    .multibody_joints
                    .get(h)
                    .and_then(|(mb, id)| mb.link(id).map(|l| mb.joint_velocity(l)))
                    .and_then(|v| v.get(0).copied())
                    .unwrap_or(0.0)
            };
            self.state[i] = DriveState {
                link_angle: unwrap_near(angle_about(&(rp.inverse() * rl), &axis), prev.link_angle),
                motor_angle: unwrap_near(
                    angle_about(&(rp.inverse() * rr), &axis),
                    prev.motor_angle,
                ),
                link_speed: speed(self.link_joints[i].handle),
                motor_speed: speed(self.rotor_joints[i].handle),
            };
        }
    }

    /// One engine step: the drive torques at the current state, the motor
    /// and external torques and gravity, held over `dt`. Non-finite
    /// torques from the drive hook are applied as zero.
    pub fn step(&mut self) {
        let n = self.links.len();
        for h in self.links.iter().chain(&self.rotors) {
            let b = &mut self.world.bodies[*h];
            b.reset_forces(false);
            b.reset_torques(false);
        }
        for (h, inertial) in self
            .links
            .iter()
            .zip(&self.link_inertial)
            .chain(self.rotors.iter().zip(&self.rotor_inertial))
        {
            self.world.bodies[*h].add_force(self.gravity * inertial.mass, true);
        }
        for i in 0..n {
            let d = self.drive.torques(i, &self.state[i]);
            // A hook that returns a non-finite torque acts with zero
            // instead, so the engine state stays finite.
            let finite_or_zero = |x: f64| if x.is_finite() { x } else { 0.0 };
            let d = DriveTorques {
                transmission: finite_or_zero(d.transmission),
                on_link: finite_or_zero(d.on_link),
                on_motor: finite_or_zero(d.on_motor),
            };
            self.last_drive[i] = d;
            let parent = self.parent_of(i);
            let z = self.rotation(parent) * self.link_joints[i].axis;
            let on_link = z * (d.on_link + self.external_torque[i]);
            let on_rotor = z * (d.on_motor + self.motor_torque[i]);
            let bodies = &mut self.world.bodies;
            bodies[self.links[i]].add_torque(on_link, true);
            bodies[self.rotors[i]].add_torque(on_rotor, true);
            if parent != self.base {
                bodies[parent].add_torque(-(on_link + on_rotor), true);
            }
        }
        self.world.step();
        self.time += self.settings.dt();
        self.read_state();
        for i in 0..n {
            let s = self.state[i];
            self.drive.advance(i, &s);
        }
    }

    /// Runs for `seconds` of simulated time (whole steps, rounded up).
    pub fn run(&mut self, seconds: f64) {
        let n = (seconds / self.settings.dt()).ceil().clamp(0.0, 1e9) as u64;
        for _ in 0..n {
            self.step();
        }
    }

    /// Total mechanical energy (J): kinetic energy of every body, gravity
    /// potential `−m g·c`, and the energy the drive model stores. The body
    /// velocities are composed here from the engine's poses and joint
    /// speeds (`ω = ω_parent + z q̇`, `v = v_parent + ω_parent × r + z q̇ × r'`).
    pub fn energy(&self) -> f64 {
        let mut e = 0.0;
        // (ω, v of the parent's frame origin) per link; the base is at rest.
        let (mut w_p, mut v_p) = (Vector::zeros(), Vector::zeros());
        let mut parent_pose = *self.world.bodies[self.base].position();
        for i in 0..self.links.len() {
            for (body, joint, inertial, speed) in [
                (
                    self.rotors[i],
                    &self.rotor_joints[i],
                    &self.rotor_inertial[i],
                    self.state[i].motor_speed,
                ),
                (
                    self.links[i],
                    &self.link_joints[i],
                    &self.link_inertial[i],
                    self.state[i].link_speed,
                ),
            ] {
                let pose = self.world.bodies[body].position();
                let z = parent_pose.rotation * joint.axis;
                let anchor = parent_pose * Point::from(joint.origin);
                let w = w_p + z * speed;
                let v_origin = v_p + w_p.cross(&(anchor - parent_pose.translation.vector).coords);
                let com = pose * Point::from(inertial.com);
                let v_com = v_origin + w.cross(&(com - anchor));
                let iw = pose.rotation.to_rotation_matrix().matrix()
                    * inertial.inertia
                    * pose.rotation.to_rotation_matrix().matrix().transpose();
                e += 0.5 * inertial.mass * v_com.norm_squared() + 0.5 * w.dot(&(iw * w));
                e -= inertial.mass * self.gravity.dot(&com.coords);
                if body == self.links[i] {
                    w_p = w;
                    v_p = v_origin;
                    parent_pose = *pose;
                }
            }
            e += self.drive.stored_energy(i, &self.state[i]);
        }
        e
    }
}

mod contact;
pub use contact::{TipBall, Wall};

#[cfg(test)]
mod tests;
