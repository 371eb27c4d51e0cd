//! The DAUJ wrist built from its parts on the engine (thesis §5.1, Fig.
//! 5.3–5.4, 5.6), to check the library's kinematics and force mapping
//! ([`crate::wrist`]) against a mechanism that does not use them.
//!
//! # The parts and the modelling choices
//!
//! All joint axes of the wrist pass through one point, the centre of the
//! sphere (Fig. 5.5): the origin here. At the zero configuration (the
//! thesis's initial status `θ1 = θ3 = 0`, `δ = γ = 0`, §5.2) every body's
//! frame coincides with the base frame; `z` is the axis of the link `L1`
//! (the motor-1 axis), and the output link `L2` points along `z` too.
//!
//! * **Lower semi-sphere** — driven by motor 1 about the base `z` axis
//!   (joint `J1`, angle `θ1`; §5.1: "Motor 1 is used to drive the lower
//!   semi-sphere").
//! * **Upper semi-sphere** — meets the lower one in a plane inclined by `φ`
//!   and turns on it (the internal oblique joint `J4`, angle `θ4`,
//!   passive). Its axis is the normal of that plane, `n = (0, −sin φ,
//!   cos φ)` in the lower semi-sphere's frame: the tilt direction of the
//!   matrices printed in eq. (5.5) (`R_z(θ1) R_x(φ) … R_x(−φ)`, errata E5.1).
//!   The thesis fixes the size of the tilt (`φ`, E5.3: 16°), this sets its
//!   direction, which only names the frames.
//! * **Output link `L2`** — turns about its own axis relative to the upper
//!   semi-sphere (joint `J3`, angle `θ3`). Motor 2 reaches `J3` through the
//!   extended shafts and the inner universal joint (§5.1); here `J3` carries
//!   its own motor, i.e. the torque at `θ3` that eq. (5.28) is written for.
//!   The transmission from the motor-2 shaft `θ2` to `θ3`, eq. (5.1)–(5.3),
//!   is the separate bench [`super::UniversalJointBench`] (errata E6.6).
//! * **Outer universal joint** (joints `J5`, `J6`) — a cross between the
//!   base and `L2`: a revolute joint of the cross to the base about the base
//!   `y` axis (pitch `δ`), and a revolute joint of `L2` to the cross about
//!   the cross's `x` axis (yaw `γ`), the order of eq. (5.6),
//!   `R = R_y(δ) R_x(γ)`. It keeps `L2` from rolling about its axis (§5.1).
//!
//! Lower semi-sphere → upper semi-sphere → `L2`, and base → cross, are
//! reduced-coordinate multibody joints on the fixed base (exact joints); one
//! impulse joint, cross → `L2`, closes the loop. The engine's solver, not
//! eq. (5.8)–(5.12), finds the `θ4` that makes the chain and the universal
//! joint agree. (A free cross held by two impulse joints does not work in
//! rapier 0.27: tied to the base that roots the multibody it panics, tied to
//! a second fixed body it left the loop open by up to 3 rad.) The motors are
//! position springs on `J1` and `J3`, torques this module applies to the
//! bodies ([`EngineSettings`]); `J4` and the cross are free. Gravity is
//! off; the masses and inertias only shape the transients.
//!
//! A wrench on the tool is a force at the tool point, `l` along the axis of
//! `L2`, plus a couple, both in the base frame; at rest the motors' springs
//! hold it and their deflection gives the torques the mechanism needs
//! ([`DaujMechanism::motor_torques`]).

use rapier3d_f64::na::UnitQuaternion;
use rapier3d_f64::prelude::*;

use super::dauj::{insert_dauj, DaujOptions, WorldAxis};
use super::world::{angle_about, unwrap_near, EngineSettings, World};
use crate::error::ParamError;
use crate::wrist::WristParams;

/// Joint angles of the mechanism (rad), read from the bodies' poses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MechanismAngles {
    /// `θ1`: lower semi-sphere about the base `z` axis (motor 1), unwrapped
    /// to within `π` of its motor target.
    pub theta1: f64,
    /// `θ4`: upper semi-sphere about the oblique axis, in `(−π, π]`.
    pub theta4: f64,
    /// `θ3`: `L2` about its own axis relative to the upper semi-sphere
    /// (the `J3` motor), unwrapped to within `π` of its motor target.
    pub theta3: f64,
    /// Pitch `δ` of the outer universal joint (cross about the base `y`).
    pub delta: f64,
    /// Yaw `γ` of the outer universal joint (`L2` about the cross's `x`).
    pub gamma: f64,
    /// How far the loop is from closed: the angle (rad) between `L2`'s
    /// orientation through the chain and through the universal joint,
    /// `R_y(δ) R_x(γ)`.
    pub loop_error: f64,
}

/// The DAUJ wrist as a mechanism on the engine (module docs).
pub struct DaujMechanism {
    world: World,
    settings: EngineSettings,
    phi: f64,
    tool_length: f64,
    lower: RigidBodyHandle,
    upper: RigidBodyHandle,
    output: RigidBodyHandle,
    cross: RigidBodyHandle,
    /// The tool, when it is its own body on `L2` ([`Self::attach_tool`]):
    /// the tool wrench then acts on it.
    tool: Option<RigidBodyHandle>,
    targets: [f64; 2],
    force: Vector<Real>,
    couple: Vector<Real>,
    time: f64,
}

impl DaujMechanism {
    /// The wrist of inclination `params.phi()` with its tool point
    /// `tool_length` (m, finite, in `(0, 1]`) along the output axis, at the
    /// zero configuration.
    pub fn try_new(
        params: &WristParams,
        tool_length: f64,
        settings: EngineSettings,
    ) -> Result<Self, ParamError> {
        if !tool_length.is_finite() {
            return Err(ParamError::NotFinite {
                name: "tool_length",
                value: tool_length,
            });
        }
        if !(tool_length > 0.0 && tool_length <= 1.0) {
            return Err(ParamError::OutOfRange {
                name: "tool_length",
                value: tool_length,
                min: f64::MIN_POSITIVE,
                max: 1.0,
            });
        }
        let phi = params.phi();
        let mut world = World::new(&settings);
        let base = world.base();
        // The parts of [`super::dauj`]: semi-spheres of 0.1 kg, L2 a 0.2 kg
        // link with its centre of mass 4 cm out, a light cross. The moments
        // of inertia (1e-3 kg·m², about the reflected inertia of a small
        // geared motor) set the time scale of the explicit motor springs; a
        // static check does not see them. No rotors (the motors are the
        // springs of `EngineSettings`), no tool until `attach_tool`, the
        // engine's default joint damping.
        let wrist = insert_dauj(
            &mut world,
            base,
            Vector::zeros(),
            (WorldAxis::X, WorldAxis::Y),
            &DaujOptions {
                kinematics: *params,
                rotors: None,
                tool: None,
                start: None,
                undamped: false,
            },
        )?;
        let (lower, upper, output, cross) = (wrist.lower, wrist.upper, wrist.output, wrist.cross);
        Ok(Self {
            world,
            settings,
            phi,
            tool_length,
            lower,
            upper,
            output,
            cross,
            tool: None,
            targets: [0.0; 2],
            force: Vector::zeros(),
            couple: Vector::zeros(),
            time: 0.0,
        })
    }

    /// The settings it runs with.
    pub fn settings(&self) -> &EngineSettings {
        &self.settings
    }

    /// The inclination `φ` (rad).
    pub fn phi(&self) -> f64 {
        self.phi
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The motor targets `(θ1, θ3)` (rad).
    pub fn targets(&self) -> [f64; 2] {
        self.targets
    }

    /// Sets the motor targets `θ1`, `θ3` (rad; non-finite values are
    /// ignored). Jumps are taken as steps by the springs: use
    /// [`Self::move_to`] for large moves.
    pub fn set_targets(&mut self, theta1: f64, theta3: f64) {
        if !(theta1.is_finite() && theta3.is_finite()) {
            return;
        }
        self.targets = [theta1, theta3];
    }

    /// The wrench on the tool: `force` (N) at the tool point and a `couple`
    /// (N·m), both in the base frame; it stays until replaced (non-finite
    /// input clears it).
    pub fn set_tool_wrench(&mut self, force: [f64; 3], couple: [f64; 3]) {
        let ok = force.iter().chain(couple.iter()).all(|x| x.is_finite());
        self.force = if ok {
            Vector::from(force)
        } else {
            Vector::zeros()
        };
        self.couple = if ok {
            Vector::from(couple)
        } else {
            Vector::zeros()
        };
    }

    /// The tool point (m, base frame).
    pub fn tool_point(&self) -> [f64; 3] {
        let loaded = self.tool.unwrap_or(self.output);
        let p = self.world.bodies[loaded].position() * Point::new(0.0, 0.0, self.tool_length);
        [p.x, p.y, p.z]
    }

    /// Splits the tool off `L2`: a body of `mass` (kg), centre of mass `com`
    /// and principal moments `inertia` (kg·m², along its frame's axes), both
    /// in `L2`'s frame, held to `L2` by a fixed joint whose frames sit at
    /// `mount` (m, on the output axis). From then on the tool wrench acts on
    /// this body, and `L2` carries it only through the joint. Called at the
    /// zero configuration, before the first step (every body's frame is then
    /// the base frame); returns the tool's handle, or `None` once stepped or
    /// attached.
    pub(super) fn attach_tool(
        &mut self,
        mount: f64,
        mass: f64,
        com: Vector<Real>,
        inertia: Vector<Real>,
    ) -> Option<RigidBodyHandle> {
        if self.time != 0.0 || self.tool.is_some() {
            return None;
        }
        let tool = self.world.body(com, mass, inertia);
        let anchor = Point::new(0.0, 0.0, mount);
        let joint = FixedJointBuilder::new()
            .local_anchor1(anchor)
            .local_anchor2(anchor);
        self.world
            .impulse_joints
            .insert(self.output, tool, joint, true);
        self.tool = Some(tool);
        Some(tool)
    }

    /// A body of the mechanism's world.
    pub(super) fn body(&self, handle: RigidBodyHandle) -> &RigidBody {
        &self.world.bodies[handle]
    }

    /// The output link `L2`'s handle.
    pub(super) fn output_handle(&self) -> RigidBodyHandle {
        self.output
    }

    /// The force (N, at the tool point) and couple (N·m) on the tool, base
    /// frame.
    pub(super) fn tool_wrench(&self) -> (Vector<Real>, Vector<Real>) {
        (self.force, self.couple)
    }

    /// One engine step.
    pub fn step(&mut self) {
        let tool = Point::from(self.tool_point());
        let (force, couple) = (self.force, self.couple);
        let [tau1, tau3] = self.motor_torques();
        let axis3 = self.world.bodies[self.output].rotation() * Vector::z();
        let bodies = &mut self.world.bodies;
        let out = &mut bodies[self.output];
        out.reset_forces(false);
        out.reset_torques(false);
        match self.tool {
            None => {
                out.add_force_at_point(force, tool, true);
                out.add_torque(couple + axis3 * tau3, true);
            }
            Some(t) => {
                out.add_torque(axis3 * tau3, true);
                let loaded = &mut bodies[t];
                loaded.reset_forces(false);
                loaded.reset_torques(false);
                loaded.add_force_at_point(force, tool, true);
                loaded.add_torque(couple, true);
            }
        }
        let upper = &mut bodies[self.upper];
        upper.reset_torques(false);
        upper.add_torque(-axis3 * tau3, true);
        let lower = &mut bodies[self.lower];
        lower.reset_torques(false);
        lower.add_torque(Vector::z() * tau1, true);
        self.world.step();
        self.time += self.settings.dt();
    }

    /// Runs for `seconds` (s) of simulated time.
    pub fn run(&mut self, seconds: f64) {
        let n = (seconds / self.settings.dt()).ceil().clamp(0.0, 1e9) as u64;
        for _ in 0..n {
            self.step();
        }
    }

    /// Moves the motor targets linearly from where they are to
    /// `(theta1, theta3)` (rad) over `ramp` seconds.
    pub fn move_to(&mut self, theta1: f64, theta3: f64, ramp: f64) {
        let [a1, a3] = self.targets;
        let n = (ramp / self.settings.dt()).ceil().clamp(1.0, 1e9) as u64;
        for i in 1..=n {
            let s = i as f64 / n as f64;
            self.set_targets(a1 + s * (theta1 - a1), a3 + s * (theta3 - a3));
            self.step();
        }
    }

    /// Runs at least `min_seconds` and then until every body turns slower
    /// than `speed_tol` (rad/s), for at most `max_seconds` in all; returns
    /// the largest body angular speed at the end (rad/s).
    pub fn settle(&mut self, speed_tol: f64, min_seconds: f64, max_seconds: f64) -> f64 {
        let start = self.time;
        self.run(min_seconds);
        while self.time - start < max_seconds && self.world.max_angular_speed() > speed_tol {
            self.run(10.0 * self.settings.dt());
        }
        self.world.max_angular_speed()
    }

    /// Largest angular speed of any body (rad/s).
    pub fn max_angular_speed(&self) -> f64 {
        self.world.max_angular_speed()
    }

    /// The orientation of the output link `L2` (base frame).
    pub fn output_rotation(&self) -> UnitQuaternion<Real> {
        *self.world.bodies[self.output].rotation()
    }

    /// The joint angles read from the bodies' poses.
    pub fn angles(&self) -> MechanismAngles {
        let b = &self.world.bodies;
        let ql = *b[self.lower].rotation();
        let qu = *b[self.upper].rotation();
        let qo = *b[self.output].rotation();
        let qc = *b[self.cross].rotation();
        let oblique = Vector::new(0.0, -self.phi.sin(), self.phi.cos());
        let theta1 = unwrap_near(angle_about(&ql, &Vector::z()), self.targets[0]);
        let theta4 = angle_about(&(ql.inverse() * qu), &oblique);
        let theta3 = unwrap_near(
            angle_about(&(qu.inverse() * qo), &Vector::z()),
            self.targets[1],
        );
        let delta = angle_about(&qc, &Vector::y());
        let gamma = angle_about(&(qc.inverse() * qo), &Vector::x());
        let through_joint = UnitQuaternion::from_axis_angle(&Vector::y_axis(), delta)
            * UnitQuaternion::from_axis_angle(&Vector::x_axis(), gamma);
        MechanismAngles {
            theta1,
            theta4,
            theta3,
            delta,
            gamma,
            loop_error: qo.angle_to(&through_joint),
        }
    }

    /// The torques the two motors apply (N·m) on `J1` (about the base `z`)
    /// and on `J3` (on `L2` about its axis, against the upper
    /// semi-sphere): `k (θ_target − θ) − c θ̇` of their springs. At rest
    /// these are the torques the mechanism needs to hold its load.
    pub fn motor_torques(&self) -> [f64; 2] {
        let a = self.angles();
        let b = &self.world.bodies;
        let (k, c) = (
            self.settings.motor_stiffness(),
            self.settings.motor_damping(),
        );
        let w1 = b[self.lower].angvel().z;
        let axis3 = b[self.output].rotation() * Vector::z();
        let w3 = (b[self.output].angvel() - b[self.upper].angvel()).dot(&axis3);
        [
            k * (self.targets[0] - a.theta1) - c * w1,
            k * (self.targets[1] - a.theta3) - c * w3,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tool_length_is_validated_by_name() {
        let p = WristParams::thesis();
        let s = EngineSettings::default();
        assert!(matches!(
            DaujMechanism::try_new(&p, f64::NAN, s),
            Err(ParamError::NotFinite {
                name: "tool_length",
                ..
            })
        ));
        assert!(matches!(
            DaujMechanism::try_new(&p, 0.0, s),
            Err(ParamError::OutOfRange {
                name: "tool_length",
                ..
            })
        ));
        assert!(DaujMechanism::try_new(&p, 0.06, s).is_ok());
    }

    #[test]
    fn straight_at_rest_and_non_finite_input_is_ignored() {
        let p = WristParams::thesis();
        let mut m = DaujMechanism::try_new(&p, 0.06, EngineSettings::default()).unwrap();
        m.run(0.05);
        let a = m.angles();
        assert!(a.delta.abs() < 1e-12 && a.gamma.abs() < 1e-12 && a.theta4.abs() < 1e-12);
        // NaN input is ignored, not propagated.
        m.set_targets(f64::NAN, 0.0);
        assert_eq!(m.targets(), [0.0, 0.0]);
        m.set_tool_wrench([0.0; 3], [f64::NAN, 0.0, 0.0]);
        m.run(0.01);
        assert!(m.angles().delta.is_finite());
    }
}
