//! The DAUJ wrist's bodies and joints (thesis §5.1, Fig. 5.3–5.6), built
//! once for every scene that carries the wrist: the kinematics check
//! ([`super::DaujMechanism`]), the finger bench ([`super::wrist_bench`])
//! and the door opening ([`super::door`]).
//!
//! [`insert_dauj`] puts into a [`World`], on a given parent body:
//!
//! * the **lower semi-sphere** on `J1` about the wrist's `z` (motor 1,
//!   `θ1`), 0.1 kg, 1e-3 kg·m² about every axis;
//! * the **upper semi-sphere** on the oblique joint `J4` about
//!   `n = z cos φ − y sin φ` of the lower one (passive, `θ4`), 0.1 kg,
//!   1e-3 kg·m²;
//! * the **output link `L2`** on `J3` about `z` of the upper semi-sphere
//!   (`θ3`), 0.2 kg with its centre of mass 4 cm out along `z`,
//!   1e-3 kg·m²;
//! * the **cross** of the outer universal joint on the parent about `y`
//!   (pitch `δ`), 0.02 kg, 2e-6 kg·m², and `L2` on the cross about its `x`
//!   (yaw `γ`): `R = R_y(δ) R_x(γ)`, eq. (5.6);
//! * optionally the two **rotors** of the motors ([`DaujRotors`]) on the
//!   parent about `z`, and a **tool** on a fixed joint to `L2`
//!   ([`DaujTool`]).
//!
//! The parent → lower → upper → `L2` chain, the parent → cross joint and
//! the rotors' joints are reduced-coordinate multibody joints; one impulse
//! joint, cross → `L2`, closes the loop (why, in [`super::wrist`]). The
//! masses are the same in every scene; the motors and the tool are the
//! scene's.
//!
//! # Frames
//! Every body's frame is the world's at the start (the parent's too:
//! [`insert_dauj`] checks it), and the wrist's own `x`, `y`, `z` axes are
//! world axes (`x` and `y` each one of `+x`, `+y`, `+z`, [`WorldAxis`]; `z = x × y`), so principal moments of inertia written in
//! the wrist's frame are principal moments along the world axes. All joint
//! axes pass through the wrist centre `origin` (m, world).
//!
//! # Insertion order
//! Bodies first (rotors, lower, upper, `L2`, cross, tool), then the
//! multibody joints (rotors, `J1`, `J4`, `J3`, pitch), the start pose, and
//! last the impulse joints (yaw, tool mount). The engine's results depend
//! on this order at the level of its solver's rounding; the three scenes
//! were built in it before they shared this function, and still are.

use rapier3d_f64::prelude::*;

use super::world::{body_at, hinge, unwrap_near, Coord, World};
use crate::error::ParamError;
use crate::sim::FrictionParams;
use crate::wrist::{PitchYaw, WristConfig, WristParams};

/// A world axis: the directions the wrist's `x` and `y` may take (module
/// docs, "Frames").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum WorldAxis {
    /// `+x`.
    X,
    /// `+y`.
    Y,
    /// `+z`.
    Z,
}

impl WorldAxis {
    fn vector(self) -> Vector<Real> {
        match self {
            WorldAxis::X => Vector::x(),
            WorldAxis::Y => Vector::y(),
            WorldAxis::Z => Vector::z(),
        }
    }
}

/// The motors' rotors: one body per motor on the parent, about the wrist's
/// `z` through the wrist centre, set at `ratio` times its joint's start
/// angle. The scene couples each to its joint (`J1`, `J3`) by its drive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct DaujRotors {
    /// Gear ratio `N` (rotor angle / joint angle), finite, ≥ 1.
    pub ratio: f64,
    /// Rotor mass, kg, positive.
    pub mass: f64,
    /// Principal moments of inertia along the wrist's `x`, `y`, `z` (`z`
    /// the rotor's own axis), kg·m², positive.
    pub inertia: [f64; 3],
}

/// The tool on `L2`: a body whose frame sits at `mount` along `L2`'s axis,
/// held there by a fixed joint (the F/T sensor's place).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct DaujTool {
    /// Distance of the mount from the wrist centre along `L2`, m, finite,
    /// in `[0, 1]`.
    pub mount: f64,
    /// Its centre of mass beyond the mount along `L2`, m, finite, in
    /// `[0, 1]`.
    pub com: f64,
    /// Mass, kg, positive.
    pub mass: f64,
    /// Moment of inertia about every axis through the centre of mass,
    /// kg·m², positive.
    pub inertia: f64,
}

/// A start pose as joint angles, rad: `θ1`, `θ4`, `θ3` of the chain and
/// the pitch `δ` of the cross; the yaw `γ` follows when the engine closes
/// the loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct DaujJointAngles {
    /// `θ1`, motor 1.
    pub theta1: f64,
    /// `θ4`, the oblique joint.
    pub theta4: f64,
    /// `θ3`, `L2` on the upper semi-sphere.
    pub theta3: f64,
    /// `δ`, the cross on the parent.
    pub delta: f64,
}

impl DaujJointAngles {
    /// The joint angles of the library's inverse kinematics (eq. 5.13–5.14,
    /// the branch `θ4 ≥ 0`, the assembly mode its forward kinematics
    /// describes) for `pose`, the motor angles within `π` of zero.
    pub(super) fn from_pose(params: &WristParams, pose: PitchYaw<f64>) -> Self {
        let inv = WristConfig::<f64>::new(params).inverse(pose);
        DaujJointAngles {
            theta1: unwrap_near(inv.motors.theta1, 0.0),
            theta4: inv.theta4,
            theta3: unwrap_near(inv.motors.theta3, 0.0),
            delta: pose.delta,
        }
    }
}

/// What a scene adds to the DAUJ ([`insert_dauj`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct DaujOptions {
    /// The wrist's kinematics: the inclination `φ` of the oblique joint.
    pub kinematics: WristParams,
    /// The motors' rotors, if the scene drives the joints through them.
    pub rotors: Option<DaujRotors>,
    /// The tool on `L2`, if any.
    pub tool: Option<DaujTool>,
    /// The start pose; `None` leaves every joint at zero (the straight
    /// pose, every body's frame the world's).
    pub start: Option<DaujJointAngles>,
    /// Set the damping of every joint of the multibody the wrist joins
    /// (the parent's, its other joints included) to zero; otherwise each
    /// revolute joint keeps the engine's default of 0.1 N·m·s/rad.
    pub undamped: bool,
}

/// The handles of an inserted DAUJ and the coordinates read from them.
#[derive(Debug, Clone, Copy)]
pub(super) struct Dauj {
    /// The body the wrist is mounted on.
    pub parent: RigidBodyHandle,
    /// The lower semi-sphere (`J1`).
    pub lower: RigidBodyHandle,
    /// The upper semi-sphere (`J4`).
    pub upper: RigidBodyHandle,
    /// The output link `L2`.
    pub output: RigidBodyHandle,
    /// The cross of the outer universal joint.
    pub cross: RigidBodyHandle,
    /// The motors' rotors (motor 1, motor 2), if inserted.
    pub rotors: Option<[RigidBodyHandle; 2]>,
    /// The tool, if inserted.
    pub tool: Option<RigidBodyHandle>,
    /// The wrist's `x`, `y`, `z` (world, at the start).
    pub axes: [Vector<Real>; 3],
}

impl Dauj {
    /// `J1` (lower semi-sphere on the parent) and `J3` (`L2` on the upper
    /// semi-sphere), both about the wrist's `z`.
    pub(super) fn joints(&self) -> [Coord; 2] {
        let z = self.axes[2];
        [
            Coord::new(self.parent, self.lower, z),
            Coord::new(self.upper, self.output, z),
        ]
    }

    /// The rotors on the parent about the wrist's `z`, if inserted.
    pub(super) fn motors(&self) -> Option<[Coord; 2]> {
        let z = self.axes[2];
        self.rotors
            .map(|r| r.map(|h| Coord::new(self.parent, h, z)))
    }

    /// The pitch `δ`: the cross on the parent about the wrist's `y`.
    pub(super) fn pitch(&self) -> Coord {
        Coord::new(self.parent, self.cross, self.axes[1])
    }

    /// The yaw `γ`: `L2` on the cross about the cross's `x`.
    pub(super) fn yaw(&self) -> Coord {
        Coord::new(self.cross, self.output, self.axes[0])
    }
}

/// Inserts the DAUJ into `world` on `parent` with its centre at `origin`
/// (m, world) and its axes `x`, `y` (world axes; `z = x × y`), as the
/// module docs describe. Errors: `x` parallel to `y` (named `frame.x·frame.y`),
/// a non-finite `origin` (`origin`), a parent not in the world or not at
/// the world's orientation (`parent`), an option outside its range (named
/// by its field, e.g. `rotors.ratio`), or a joint the engine refuses.
pub(super) fn insert_dauj(
    world: &mut World,
    parent: RigidBodyHandle,
    origin: Vector<Real>,
    (x, y): (WorldAxis, WorldAxis),
    options: &DaujOptions,
) -> Result<Dauj, ParamError> {
    let (xw, yw) = (x.vector(), y.vector());
    let dot = xw.dot(&yw);
    if dot != 0.0 {
        return Err(ParamError::CombinationOutOfRange {
            name: "frame.x·frame.y",
            value: dot,
            min: 0.0,
            max: 0.0,
        });
    }
    let zw = xw.cross(&yw);
    validate(origin, options)?;
    let parent_frame = *world
        .bodies
        .get(parent)
        .ok_or(ParamError::NotFinite {
            name: "parent (not a body of the world)",
            value: f64::NAN,
        })?
        .position();
    let turned = parent_frame.rotation.angle();
    if turned != 0.0 {
        return Err(ParamError::OutOfRange {
            name: "parent rotation angle",
            value: turned,
            min: 0.0,
            max: 0.0,
        });
    }
    let anchor = origin - parent_frame.translation.vector;
    let fail = |name| ParamError::NotFinite {
        name,
        value: f64::NAN,
    };
    let phi = options.kinematics.phi();
    let oblique = zw * phi.cos() - yw * phi.sin();
    let axes = [xw, yw, zw];
    let o = Vector::zeros();
    // Bodies.
    let rotors = options.rotors.map(|r| {
        // The moments along the world axes: each world axis is one of the
        // wrist's (module docs, "Frames").
        let along = Vector::from_fn(|k, _| {
            let i = (0..3).find(|&i| axes[i][k] != 0.0).unwrap_or(k);
            r.inertia[i]
        });
        [0, 1].map(|_| body_at(world, origin, o, r.mass, along))
    });
    let lower = body_at(world, origin, o, 0.1, Vector::repeat(1e-3));
    let upper = body_at(world, origin, o, 0.1, Vector::repeat(1e-3));
    let output = body_at(world, origin, zw * 0.04, 0.2, Vector::repeat(1e-3));
    let cross = body_at(world, origin, o, 0.02, Vector::repeat(2e-6));
    let tool = options.tool.map(|t| {
        body_at(
            world,
            origin + zw * t.mount,
            zw * t.com,
            t.mass,
            Vector::repeat(t.inertia),
        )
    });
    // Multibody joints.
    let mb = &mut world.multibody_joints;
    let mut rotor_joints = Vec::new();
    for h in rotors.iter().flatten() {
        rotor_joints.push(
            mb.insert(parent, *h, hinge(zw, anchor, o), true)
                .ok_or(fail("rotor joint"))?,
        );
    }
    let j1 = mb
        .insert(parent, lower, hinge(zw, anchor, o), true)
        .ok_or(fail("J1"))?;
    let j4 = mb
        .insert(lower, upper, hinge(oblique, o, o), true)
        .ok_or(fail("J4"))?;
    let j3 = mb
        .insert(upper, output, hinge(zw, o, o), true)
        .ok_or(fail("J3"))?;
    let jp = mb
        .insert(parent, cross, hinge(yw, anchor, o), true)
        .ok_or(fail("pitch joint"))?;
    // The start pose: the joints set, the rotors at N times their joints,
    // the tool to its place on L2; the engine closes the loop from there.
    if let Some(s) = options.start {
        let mut set = vec![
            (j1, s.theta1),
            (j4, s.theta4),
            (j3, s.theta3),
            (jp, s.delta),
        ];
        if let (Some(r), [r1, r3]) = (options.rotors, rotor_joints.as_slice()) {
            set.push((*r1, r.ratio * s.theta1));
            set.push((*r3, r.ratio * s.theta3));
        }
        let ids: Vec<_> = set
            .iter()
            .map(|&(h, q)| (world.multibody_joints.get(h).map(|(_, id)| id), q))
            .collect();
        let (m, _) = world
            .multibody_joints
            .get_mut(j1)
            .ok_or(fail("start pose"))?;
        let mut disp = vec![0.0; m.ndofs()];
        for (id, q) in ids {
            let id = id.ok_or(fail("start pose"))?;
            let at: usize = (0..id)
                .filter_map(|k| m.link(k).map(|l| l.joint().ndofs()))
                .sum();
            *disp.get_mut(at).ok_or(fail("start pose"))? = q;
        }
        m.apply_displacements(&disp);
        m.forward_kinematics(&world.bodies, true);
        m.update_rigid_bodies(&mut world.bodies, false);
        if let (Some(h), Some(t)) = (tool, options.tool) {
            let pose = *world.bodies[output].position()
                * Isometry::translation(zw.x * t.mount, zw.y * t.mount, zw.z * t.mount);
            world.bodies[h].set_position(pose, true);
        }
    }
    if options.undamped {
        if let Some((m, _)) = world.multibody_joints.get_mut(j1) {
            m.damping_mut().fill(0.0);
        }
    }
    // Impulse joints: the loop, and the tool's mount.
    world
        .impulse_joints
        .insert(cross, output, hinge(xw, o, o), true);
    if let (Some(h), Some(t)) = (tool, options.tool) {
        let mount = FixedJointBuilder::new()
            .local_anchor1(Point::from(zw * t.mount))
            .local_anchor2(Point::origin());
        world.impulse_joints.insert(output, h, mount, true);
    }
    Ok(Dauj {
        parent,
        lower,
        upper,
        output,
        cross,
        rotors,
        tool,
        axes,
    })
}

fn validate(origin: Vector<Real>, options: &DaujOptions) -> Result<(), ParamError> {
    use crate::error::{finite, in_range, positive};
    for x in origin.iter() {
        finite("origin", *x)?;
    }
    if let Some(r) = options.rotors {
        in_range("rotors.ratio", r.ratio, 1.0, 1e6)?;
        positive("rotors.mass", r.mass)?;
        for i in r.inertia {
            positive("rotors.inertia", i)?;
        }
    }
    if let Some(t) = options.tool {
        in_range("tool.mount", t.mount, 0.0, 1.0)?;
        in_range("tool.com", t.com, 0.0, 1.0)?;
        positive("tool.mass", t.mass)?;
        positive("tool.inertia", t.inertia)?;
    }
    if let Some(s) = options.start {
        for (name, v) in [
            ("start.theta1", s.theta1),
            ("start.theta4", s.theta4),
            ("start.theta3", s.theta3),
            ("start.delta", s.delta),
        ] {
            finite(name, v)?;
        }
    }
    Ok(())
}

/// The wrist's two drives, each motor's rotor to its joint (`J1`, and `J3`
/// through the inner universal joint taken as 1 : 1), as the door scene
/// and the bench model them: a stiff spring
/// `τ_t = k_w (q_m/N − q) + c_w (q̇_m/N − q̇)` (N·m) between the rotor
/// (angle `q_m`, rad) and the joint (`q`), and the motor friction with
/// presliding on the rotor. Applied as torque pairs before each engine
/// step ([`Self::push`]); its memory (unwrapping, presliding anchors) moves
/// on after it ([`Self::advance`]).
pub(super) struct WristDrives {
    joint: [Coord; 2],
    motor: [Coord; 2],
    ratio: f64,
    spring: (f64, f64),
    friction: FrictionParams,
    /// Joint and rotor angles after the last step, rad.
    angles: [[f64; 2]; 2],
    /// The motor friction's presliding anchors, rad (rotor side).
    anchor: [f64; 2],
}

impl WristDrives {
    /// The drives of `joint` (`J1`, `J3`) and `motor` (their rotors) with
    /// gear ratio `ratio`, spring `(k_w, c_w)` (N·m/rad, N·m·s/rad) and
    /// motor `friction`, at rest with the joints at `start` (rad) and the
    /// rotors at `ratio` times them.
    pub(super) fn new(
        joint: [Coord; 2],
        motor: [Coord; 2],
        ratio: f64,
        spring: (f64, f64),
        friction: FrictionParams,
        start: [f64; 2],
    ) -> Self {
        WristDrives {
            joint,
            motor,
            ratio,
            spring,
            friction,
            angles: start.map(|q| [q, ratio * q]),
            anchor: start.map(|q| ratio * q),
        }
    }

    /// Rotor `i`'s angle now, rad (motor side), unwrapped near the last.
    pub(super) fn rotor_angle(&self, bodies: &RigidBodySet, i: usize) -> f64 {
        self.motor[i].angle(bodies, self.angles[i][1])
    }

    /// The rotors' angles after the last step, rad (motor side).
    pub(super) fn rotor_angles(&self) -> [f64; 2] {
        [self.angles[0][1], self.angles[1][1]]
    }

    /// Applies the drives' torques, with `motor_torque` (N·m, motor side)
    /// on the rotors.
    pub(super) fn push(&self, bodies: &mut RigidBodySet, motor_torque: [f64; 2]) {
        let ((kw, cw), n) = (self.spring, self.ratio);
        for i in 0..2 {
            let (j, m) = (self.joint[i], self.motor[i]);
            let q = j.angle(bodies, self.angles[i][0]);
            let qm = m.angle(bodies, self.angles[i][1]);
            let (vq, vm) = (j.speed(bodies), m.speed(bodies));
            let tt = kw * (qm / n - q) + cw * (vm / n - vq);
            let fm = self.friction.torque(qm, vm, self.anchor[i]);
            j.push(bodies, tt);
            m.push(bodies, -tt / n + motor_torque[i] - fm);
        }
    }

    /// Moves the memory on after an engine step.
    pub(super) fn advance(&mut self, bodies: &RigidBodySet) {
        for i in 0..2 {
            let (j, m) = (self.joint[i], self.motor[i]);
            self.angles[i] = [
                j.angle(bodies, self.angles[i][0]),
                m.angle(bodies, self.angles[i][1]),
            ];
            self.friction
                .update_anchor(self.angles[i][1], m.speed(bodies), &mut self.anchor[i]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::engine::world::EngineSettings;
    use rapier3d_f64::na::UnitQuaternion;

    fn options(start: Option<DaujJointAngles>) -> DaujOptions {
        DaujOptions {
            kinematics: WristParams::thesis(),
            rotors: Some(DaujRotors {
                ratio: 50.0,
                mass: 0.05,
                inertia: [1e-5, 2e-5, 3e-6],
            }),
            tool: Some(DaujTool {
                mount: 0.05,
                com: 0.02,
                mass: 0.3,
                inertia: 5e-4,
            }),
            start,
            undamped: true,
        }
    }

    /// A fixed parent away from the origin, so that the anchors are
    /// checked too.
    fn world_with_parent() -> (World, RigidBodyHandle) {
        let mut world = World::new(&EngineSettings::default());
        let parent = world.bodies.insert(
            RigidBodyBuilder::fixed()
                .translation(Vector::new(0.3, -0.2, 0.1))
                .build(),
        );
        (world, parent)
    }

    #[test]
    fn the_start_pose_puts_every_part_where_the_joint_angles_say() {
        // A frame that is not the world's: x → world z, y → world x,
        // z = x × y → world y (the door's).
        let (mut world, parent) = world_with_parent();
        let origin = Vector::new(0.5, 0.4, -0.1);
        let (delta, gamma) = (0.2, -0.15);
        let start = DaujJointAngles::from_pose(&WristParams::thesis(), PitchYaw { delta, gamma });
        let opts = options(Some(start));
        let w = insert_dauj(
            &mut world,
            parent,
            origin,
            (WorldAxis::Z, WorldAxis::X),
            &opts,
        )
        .expect("valid wrist");
        assert_eq!(w.axes, [Vector::z(), Vector::x(), Vector::y()]);
        let b = &world.bodies;
        // The chain's joints read the angles they were set to.
        let [j1, j3] = w.joints();
        assert!((j1.angle(b, 0.0) - start.theta1).abs() < 1e-9);
        assert!((j3.angle(b, 0.0) - start.theta3).abs() < 1e-9);
        assert!((w.pitch().angle(b, 0.0) - delta).abs() < 1e-9);
        // The loop is closed where the library's pose says: L2's
        // orientation through the chain is R_y(δ) R_x(γ) about the wrist's
        // axes (world z for x, world x for y), so the yaw joint reads γ.
        let uj = UnitQuaternion::from_axis_angle(&Vector::x_axis(), delta)
            * UnitQuaternion::from_axis_angle(&Vector::z_axis(), gamma);
        assert!(b[w.output].rotation().angle_to(&uj) < 1e-9);
        assert!((w.yaw().angle(b, 0.0) - gamma).abs() < 1e-9);
        // Every part turns about the wrist centre: their origins stay there.
        for h in [w.lower, w.upper, w.output, w.cross] {
            assert!((b[h].translation() - origin).norm() < 1e-12);
        }
        // The rotors at N times their joints.
        let [m1, m3] = w.motors().expect("rotors");
        assert!((m1.angle(b, 50.0 * start.theta1) - 50.0 * start.theta1).abs() < 1e-9);
        assert!((m3.angle(b, 50.0 * start.theta3) - 50.0 * start.theta3).abs() < 1e-9);
        // The tool 5 cm out along L2's axis.
        let tool = b[w.tool.expect("tool")].translation();
        let along = uj * Vector::y();
        assert!((tool - (origin + along * 0.05)).norm() < 1e-12);
    }

    #[test]
    fn rotor_inertia_is_given_in_the_wrist_frame() {
        let (mut world, parent) = world_with_parent();
        let w = insert_dauj(
            &mut world,
            parent,
            Vector::zeros(),
            (WorldAxis::Z, WorldAxis::X),
            &options(None),
        )
        .expect("valid wrist");
        // Wrist x, y, z are world z, x, y: the moments [1e-5, 2e-5, 3e-6]
        // along the wrist's axes are [2e-5, 3e-6, 1e-5] along the world's.
        // (The engine computes the bodies' mass properties in its step.)
        world.step();
        let r = w.rotors.expect("rotors")[0];
        let m = world.bodies[r].mass_properties().local_mprops;
        let want = Vector::new(2e-5, 3e-6, 1e-5);
        let got = m.principal_inertia();
        assert!((got - want).norm() < 1e-12 * want.norm(), "{got:?}");
    }

    #[test]
    fn bad_inputs_are_named() {
        let name = |origin: Vector<Real>, axes, opts: &DaujOptions| {
            let (mut world, parent) = world_with_parent();
            insert_dauj(&mut world, parent, origin, axes, opts)
                .err()
                .map(|e| e.name())
        };
        let o = Vector::zeros();
        let xy = (WorldAxis::X, WorldAxis::Y);
        assert_eq!(
            name(o, (WorldAxis::Y, WorldAxis::Y), &options(None)),
            Some("frame.x·frame.y")
        );
        assert_eq!(
            name(Vector::new(0.0, f64::NAN, 0.0), xy, &options(None)),
            Some("origin")
        );
        let mut bad = options(None);
        bad.rotors = bad.rotors.map(|r| DaujRotors { ratio: 0.5, ..r });
        assert_eq!(name(o, xy, &bad), Some("rotors.ratio"));
        let mut bad = options(None);
        bad.tool = bad.tool.map(|t| DaujTool { mass: -1.0, ..t });
        assert_eq!(name(o, xy, &bad), Some("tool.mass"));
        let mut bad = options(None);
        bad.start = Some(DaujJointAngles {
            theta1: 0.0,
            theta4: f64::INFINITY,
            theta3: 0.0,
            delta: 0.0,
        });
        assert_eq!(name(o, xy, &bad), Some("start.theta4"));
        // A turned parent.
        let mut world = World::new(&EngineSettings::default());
        let parent = world.bodies.insert(
            RigidBodyBuilder::fixed()
                .rotation(Vector::new(0.0, 0.0, 0.3))
                .build(),
        );
        let e = insert_dauj(&mut world, parent, o, xy, &options(None)).err();
        assert_eq!(e.map(|e| e.name()), Some("parent rotation angle"));
        assert_eq!(name(o, xy, &options(None)), None);
    }
}
