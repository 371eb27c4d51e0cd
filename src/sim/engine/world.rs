//! The engine's world and the settings shared by the mechanisms.

use core::num::NonZeroUsize;

use rapier3d_f64::na::UnitQuaternion;
use rapier3d_f64::prelude::*;

use crate::error::ParamError;

/// Step and solver settings of the engine, and the stiffness of the motor
/// springs that hold a mechanism (SI units).
///
/// A motor is a position spring on its joint, evaluated by this module
/// from the engine's state before every step and applied to the bodies as
/// a torque pair: `τ = k (θ_target − θ) − c θ̇` (N·m) about the joint axis.
/// (The engine's own joint motors are constraints whose impulses it does not
/// report for multibody joints, so a holding torque could not be read from
/// them.) The spring is explicit: `dt √(k/I)` must stay well below 1 for
/// the inertias `I` it moves, which the defaults do (the check at half the
/// step shows it). At rest the torque is `k (θ_target − θ)`, the torque the
/// mechanism needs to hold its load ([`super::DaujMechanism::motor_torques`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngineSettings {
    dt: f64,
    solver_iterations: usize,
    motor_stiffness: f64,
    motor_damping: f64,
}

impl EngineSettings {
    /// Step `dt` (s), solver iterations per step (1…1000), motor stiffness `k`
    /// (N·m/rad) and damping `c` (N·m·s/rad). `dt`, `k` and `c` must be finite
    /// and positive, `dt ≤ 0.1 s`.
    pub fn try_new(
        dt: f64,
        solver_iterations: usize,
        motor_stiffness: f64,
        motor_damping: f64,
    ) -> Result<Self, ParamError> {
        if !dt.is_finite() {
            return Err(ParamError::NotFinite {
                name: "dt",
                value: dt,
            });
        }
        if !(dt > 0.0 && dt <= 0.1) {
            return Err(ParamError::OutOfRange {
                name: "dt",
                value: dt,
                min: f64::MIN_POSITIVE,
                max: 0.1,
            });
        }
        if !(1..=1000).contains(&solver_iterations) {
            return Err(ParamError::OutOfRange {
                name: "solver_iterations",
                value: solver_iterations as f64,
                min: 1.0,
                max: 1000.0,
            });
        }
        for (name, value) in [
            ("motor_stiffness", motor_stiffness),
            ("motor_damping", motor_damping),
        ] {
            if !value.is_finite() {
                return Err(ParamError::NotFinite { name, value });
            }
            if value <= 0.0 {
                return Err(ParamError::NotPositive { name, value });
            }
        }
        Ok(Self {
            dt,
            solver_iterations,
            motor_stiffness,
            motor_damping,
        })
    }

    /// The step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Solver iterations per step.
    pub fn solver_iterations(&self) -> usize {
        self.solver_iterations
    }

    /// Motor spring stiffness (N·m/rad).
    pub fn motor_stiffness(&self) -> f64 {
        self.motor_stiffness
    }

    /// Motor spring damping (N·m·s/rad).
    pub fn motor_damping(&self) -> f64 {
        self.motor_damping
    }

    /// The same settings with the step halved (the convergence check).
    pub fn with_half_step(&self) -> Self {
        Self {
            dt: self.dt / 2.0,
            ..*self
        }
    }
}

impl Default for EngineSettings {
    /// 1 ms step, 16 solver iterations, motors of 20 N·m/rad and
    /// 0.4 N·m·s/rad (with the mechanisms' inertias of 1e-3 to 2e-3 kg·m²:
    /// `dt √(k/I)` ≤ 0.14, near-critical damping).
    fn default() -> Self {
        Self {
            dt: 1e-3,
            solver_iterations: 16,
            motor_stiffness: 20.0,
            motor_damping: 0.4,
        }
    }
}

/// The rapier sets and pipeline of one mechanism (no gravity; colliders
/// only where a mechanism adds them, e.g. the arm's wall).
pub(crate) struct World {
    pipeline: PhysicsPipeline,
    params: IntegrationParameters,
    islands: IslandManager,
    broad_phase: DefaultBroadPhase,
    pub(crate) narrow_phase: NarrowPhase,
    pub(crate) bodies: RigidBodySet,
    pub(crate) colliders: ColliderSet,
    pub(crate) impulse_joints: ImpulseJointSet,
    pub(crate) multibody_joints: MultibodyJointSet,
    ccd: CCDSolver,
}

impl World {
    pub(crate) fn new(settings: &EngineSettings) -> Self {
        let mut params = IntegrationParameters {
            dt: settings.dt,
            ..IntegrationParameters::default()
        };
        // `try_new` keeps the count in 1..=1000.
        params.num_solver_iterations =
            NonZeroUsize::new(settings.solver_iterations).unwrap_or(NonZeroUsize::MIN);
        Self {
            pipeline: PhysicsPipeline::new(),
            params,
            islands: IslandManager::new(),
            broad_phase: DefaultBroadPhase::new(),
            narrow_phase: NarrowPhase::new(),
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            ccd: CCDSolver::new(),
        }
    }

    /// A dynamic body at the origin with the given mass (kg) and principal
    /// moments of inertia (kg·m²) about its centre of mass `com` (m, body
    /// frame); it never sleeps.
    pub(crate) fn body(
        &mut self,
        com: Vector<Real>,
        mass: f64,
        inertia: Vector<Real>,
    ) -> RigidBodyHandle {
        let rb = RigidBodyBuilder::dynamic()
            .additional_mass_properties(MassProperties::new(com.into(), mass, inertia))
            .can_sleep(false)
            .build();
        self.bodies.insert(rb)
    }

    /// The fixed base at the origin.
    pub(crate) fn base(&mut self) -> RigidBodyHandle {
        self.bodies.insert(RigidBodyBuilder::fixed().build())
    }

    pub(crate) fn step(&mut self) {
        self.pipeline.step(
            &Vector::zeros(),
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.ccd,
            &(),
            &(),
        );
    }

    /// Whether every body's position and velocities are finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.bodies.iter().all(|(_, b)| {
            b.translation().iter().all(|x| x.is_finite())
                && b.linvel().iter().all(|x| x.is_finite())
                && b.angvel().iter().all(|x| x.is_finite())
        })
    }

    /// Clears the forces and torques the last step's caller applied to
    /// every body.
    pub(crate) fn clear_forces(&mut self) {
        for (_, rb) in self.bodies.iter_mut() {
            rb.reset_forces(false);
            rb.reset_torques(false);
        }
    }

    /// Largest angular speed (rad/s) of any body.
    pub(crate) fn max_angular_speed(&self) -> f64 {
        self.bodies
            .iter()
            .map(|(_, b)| b.angvel().norm())
            .fold(0.0, f64::max)
    }
}

/// A revolute joint through the origin about `axis` (the same vector in both
/// bodies' frames: every body of these mechanisms coincides with the world
/// frame at the zero configuration).
pub(crate) fn revolute(axis: Vector<Real>) -> RevoluteJointBuilder {
    RevoluteJointBuilder::new(UnitVector::new_normalize(axis))
        .local_anchor1(Point::origin())
        .local_anchor2(Point::origin())
}

/// A body at `origin` (m, world) whose frame is the world's at the start,
/// with `mass` (kg), centre of mass `com` (m, body frame) and principal
/// moments `inertia` (kg·m²) along the world axes; it never sleeps.
pub(super) fn body_at(
    world: &mut World,
    origin: Vector<Real>,
    com: Vector<Real>,
    mass: f64,
    inertia: Vector<Real>,
) -> RigidBodyHandle {
    let rb = RigidBodyBuilder::dynamic()
        .translation(origin)
        .additional_mass_properties(MassProperties::new(com.into(), mass, inertia))
        .can_sleep(false)
        .build();
    world.bodies.insert(rb)
}

/// A revolute joint about `axis` (world at the start) through the point
/// `anchor1` of the parent and `anchor2` of the child (body frames).
pub(super) fn hinge(
    axis: Vector<Real>,
    anchor1: Vector<Real>,
    anchor2: Vector<Real>,
) -> RevoluteJointBuilder {
    RevoluteJointBuilder::new(UnitVector::new_normalize(axis))
        .local_anchor1(Point::from(anchor1))
        .local_anchor2(Point::from(anchor2))
}

/// A relative rotation coordinate: `child` about `axis` (fixed in
/// `parent`'s frame, world at the start).
#[derive(Debug, Clone, Copy)]
pub(super) struct Coord {
    pub(super) parent: RigidBodyHandle,
    pub(super) child: RigidBodyHandle,
    pub(super) axis: Vector<Real>,
}

impl Coord {
    pub(super) fn new(parent: RigidBodyHandle, child: RigidBodyHandle, axis: Vector<Real>) -> Self {
        Coord {
            parent,
            child,
            axis,
        }
    }
    /// The angle (rad) of `child` about the axis relative to `parent`,
    /// unwrapped to within `π` of `near`.
    pub(super) fn angle(&self, b: &RigidBodySet, near: f64) -> f64 {
        let q = b[self.parent].rotation().inverse() * b[self.child].rotation();
        unwrap_near(angle_about(&q, &self.axis), near)
    }
    /// The axis in the world frame now.
    pub(super) fn world_axis(&self, b: &RigidBodySet) -> Vector<Real> {
        b[self.parent].rotation() * self.axis
    }
    /// The relative angular speed about the axis, rad/s.
    pub(super) fn speed(&self, b: &RigidBodySet) -> f64 {
        (b[self.child].angvel() - b[self.parent].angvel()).dot(&self.world_axis(b))
    }
    /// A generalized force `tau` (N·m) on this coordinate: a torque pair.
    pub(super) fn push(&self, b: &mut RigidBodySet, tau: f64) {
        let t = self.world_axis(b) * tau;
        b[self.child].add_torque(t, true);
        b[self.parent].add_torque(-t, true);
    }
}

/// The signed angle (rad, in `(−π, π]`) of the rotation `q` about the unit
/// `axis`, for a `q` that is a rotation about that axis.
pub(crate) fn angle_about(q: &UnitQuaternion<Real>, axis: &Vector<Real>) -> f64 {
    let v = q.imag();
    unwrap_near(2.0 * v.dot(axis).atan2(q.scalar()), 0.0)
}

/// `x` moved by a whole number of turns to within `π` of `near`.
pub(crate) fn unwrap_near(x: f64, near: f64) -> f64 {
    let tau = core::f64::consts::TAU;
    x - tau * ((x - near) / tau).round()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_reject_bad_values_by_name() {
        assert!(matches!(
            EngineSettings::try_new(f64::NAN, 16, 20.0, 0.4),
            Err(ParamError::NotFinite { name: "dt", .. })
        ));
        assert!(matches!(
            EngineSettings::try_new(0.0, 16, 20.0, 0.4),
            Err(ParamError::OutOfRange { name: "dt", .. })
        ));
        assert!(matches!(
            EngineSettings::try_new(1e-3, 0, 20.0, 0.4),
            Err(ParamError::OutOfRange {
                name: "solver_iterations",
                ..
            })
        ));
        assert!(matches!(
            EngineSettings::try_new(1e-3, 16, -1.0, 0.4),
            Err(ParamError::NotPositive {
                name: "motor_stiffness",
                ..
            })
        ));
        assert!(matches!(
            EngineSettings::try_new(1e-3, 16, 20.0, f64::INFINITY),
            Err(ParamError::NotFinite {
                name: "motor_damping",
                ..
            })
        ));
        let s = EngineSettings::try_new(1e-3, 16, 20.0, 0.4).unwrap();
        assert_eq!(s, EngineSettings::default());
        assert_eq!(s.with_half_step().dt(), 5e-4);
    }

    #[test]
    fn angle_about_reads_a_rotation_about_the_axis() {
        let axis = Vector::new(0.0, -0.3f64.sin(), 0.3f64.cos());
        for a in [-3.0, -1.0, 0.0, 0.5, 2.5, 3.1] {
            let q = UnitQuaternion::from_axis_angle(&UnitVector::new_normalize(axis), a);
            assert!((angle_about(&q, &axis) - a).abs() < 1e-12, "{a}");
        }
        assert!((unwrap_near(0.1, 6.3) - (0.1 + core::f64::consts::TAU)).abs() < 1e-12);
    }
}
