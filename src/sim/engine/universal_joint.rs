//! The inner universal joint of the wrist on the engine: the standard
//! (Cardan) joint of thesis eq. (5.1)–(5.3), built from its parts to check
//! [`crate::wrist::ujoint::transmit`] and the motor-2 factor of errata E6.6.
//!
//! # The parts
//!
//! * **Driving shaft** (motor 2's, angle `θ2`) — turns about the base `z`
//!   axis; its yoke pin lies along its `x` axis. Motor 2 is a position
//!   spring on this joint, a torque applied by this module
//!   ([`EngineSettings`]).
//! * **Cross** — turns about the driving yoke's pin (`x`) and carries the
//!   driven yoke's pin along its `y` axis.
//! * **Driven shaft** (angle `θ3`) — turns about `d = (sin β, 0, cos β)`,
//!   the `z` axis bent by `β` about `y`; its yoke pin lies along `y` at
//!   `θ3 = 0`.
//!
//! The cross keeps the two pins perpendicular, which for these frames is
//! `tan θ2 = cos β tan θ3`, eq. (5.1) with both angles zero together. The
//! base → driving shaft → cross and base → driven shaft joints are a
//! multibody; the cross → driven shaft joint is an impulse joint that
//! closes the loop. A load torque on the driven shaft is held by motor 2;
//! at rest its spring gives the torque it needs.

use rapier3d_f64::prelude::*;

use super::world::{angle_about, revolute, unwrap_near, EngineSettings, World};
use crate::error::ParamError;

/// A universal joint bent by `β` between a motor-driven shaft and a loaded
/// one (module docs).
pub struct UniversalJointBench {
    world: World,
    settings: EngineSettings,
    bend: f64,
    driving: RigidBodyHandle,
    driven: RigidBodyHandle,
    target: f64,
    load: f64,
}

impl UniversalJointBench {
    /// The joint bent by `bend` (rad, finite, `0 ≤ β ≤ 60°`) at `θ2 = θ3 =
    /// 0`.
    pub fn try_new(bend: f64, settings: EngineSettings) -> Result<Self, ParamError> {
        if !bend.is_finite() {
            return Err(ParamError::NotFinite {
                name: "bend",
                value: bend,
            });
        }
        let max = 60f64.to_radians();
        if !(0.0..=max).contains(&bend) {
            return Err(ParamError::OutOfRange {
                name: "bend",
                value: bend,
                min: 0.0,
                max,
            });
        }
        let mut world = World::new(&settings);
        let base = world.base();
        // Inertias as in the wrist (they set the explicit motor spring's
        // time scale only).
        let driving = world.body(Vector::zeros(), 0.05, Vector::repeat(1e-3));
        let cross = world.body(Vector::zeros(), 0.01, Vector::repeat(1e-6));
        let driven = world.body(Vector::zeros(), 0.05, Vector::repeat(1e-3));
        let d = Vector::new(bend.sin(), 0.0, bend.cos());
        let err = ParamError::NotFinite {
            name: "multibody",
            value: f64::NAN,
        };
        let mb = &mut world.multibody_joints;
        mb.insert(base, driving, revolute(Vector::z()), true)
            .ok_or(err)?;
        mb.insert(driving, cross, revolute(Vector::x()), true)
            .ok_or(err)?;
        mb.insert(base, driven, revolute(d), true).ok_or(err)?;
        world
            .impulse_joints
            .insert(cross, driven, revolute(Vector::y()), true);
        Ok(Self {
            world,
            settings,
            bend,
            driving,
            driven,
            target: 0.0,
            load: 0.0,
        })
    }

    /// The bend `β` (rad).
    pub fn bend(&self) -> f64 {
        self.bend
    }

    /// The axis `d` of the driven shaft (base frame).
    fn driven_axis(&self) -> Vector<Real> {
        Vector::new(self.bend.sin(), 0.0, self.bend.cos())
    }

    /// Sets motor 2's target `θ2` (rad; non-finite is ignored).
    pub fn set_target(&mut self, theta2: f64) {
        if !theta2.is_finite() {
            return;
        }
        self.target = theta2;
    }

    /// The load torque (N·m) on the driven shaft about its axis `d`
    /// (non-finite clears it).
    pub fn set_load(&mut self, torque: f64) {
        self.load = if torque.is_finite() { torque } else { 0.0 };
    }

    /// Ramps the target to `theta2` over `ramp` s, then runs at least
    /// `min_seconds` and until both shafts turn slower than `speed_tol`
    /// (rad/s), for at most `max_seconds`; returns the largest body angular
    /// speed at the end (rad/s).
    pub fn move_and_settle(
        &mut self,
        theta2: f64,
        ramp: f64,
        speed_tol: f64,
        min_seconds: f64,
        max_seconds: f64,
    ) -> f64 {
        let start = self.target;
        let dt = self.settings.dt();
        let n = (ramp / dt).ceil().clamp(1.0, 1e9) as u64;
        for i in 1..=n {
            self.set_target(start + (theta2 - start) * i as f64 / n as f64);
            self.step();
        }
        let (min, max) = ((min_seconds / dt).ceil(), (max_seconds / dt).ceil());
        let mut k = 0.0;
        while k < max.min(1e9) && (k < min || self.world.max_angular_speed() > speed_tol) {
            self.step();
            k += 1.0;
        }
        self.world.max_angular_speed()
    }

    /// One engine step.
    pub fn step(&mut self) {
        let torque = self.driven_axis() * self.load;
        let motor = Vector::z() * self.motor_torque();
        let b = &mut self.world.bodies[self.driven];
        b.reset_torques(false);
        b.add_torque(torque, true);
        let d = &mut self.world.bodies[self.driving];
        d.reset_torques(false);
        d.add_torque(motor, true);
        self.world.step();
    }

    /// `(θ2, θ3)` (rad) read from the shafts' poses, unwrapped to within `π`
    /// of the motor target.
    pub fn angles(&self) -> [f64; 2] {
        let b = &self.world.bodies;
        let t2 = unwrap_near(
            angle_about(b[self.driving].rotation(), &Vector::z()),
            self.target,
        );
        let t3 = angle_about(b[self.driven].rotation(), &self.driven_axis());
        [t2, unwrap_near(t3, self.target)]
    }

    /// Motor 2's torque (N·m about the base `z`): `k (θ_target − θ2) − c θ̇2`.
    pub fn motor_torque(&self) -> f64 {
        let [t2, _] = self.angles();
        let w = self.world.bodies[self.driving].angvel().z;
        self.settings.motor_stiffness() * (self.target - t2) - self.settings.motor_damping() * w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bend_is_validated_by_name() {
        let s = EngineSettings::default();
        assert!(matches!(
            UniversalJointBench::try_new(f64::NAN, s),
            Err(ParamError::NotFinite { name: "bend", .. })
        ));
        assert!(matches!(
            UniversalJointBench::try_new(1.2, s),
            Err(ParamError::OutOfRange { name: "bend", .. })
        ));
    }

    #[test]
    fn straight_joint_passes_the_load_one_to_one() {
        // At β = 0 both shafts are one: motor 2 holds exactly the load.
        let mut b = UniversalJointBench::try_new(0.0, EngineSettings::default()).unwrap();
        b.set_load(0.5);
        let speed = b.move_and_settle(0.3, 0.05, 1e-6, 0.05, 2.0);
        assert!(speed <= 1e-6);
        assert!(
            (b.motor_torque() + 0.5).abs() < 1e-5,
            "{}",
            b.motor_torque()
        );
        let [t2, t3] = b.angles();
        assert!((t2 - t3).abs() < 1e-6);
    }
}
