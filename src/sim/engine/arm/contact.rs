//! A contact the engine computes: a ball fixed to one link of the arm and a
//! fixed box (the wall) it can run into.
//!
//! The ball and the wall are rapier colliders; the force between them is
//! the engine's contact force (its soft contact constraint, the solver's
//! impulse over the step), not a torque this crate writes. Both colliders
//! are frictionless, so the force is along the contact normal, which for a
//! ball passes through its centre; the generalized force it puts on the
//! ball's link coordinate `q_l` is `((c − o) × F) · z` with `c` the ball's
//! centre, `o` the joint point and `z` the joint axis (all in the base
//! frame). The ball has no mass (density 0): the arm's mass distribution is
//! the one [`EngineArm::try_new`] built.

use rapier3d_f64::prelude::*;

use super::{DriveModel, EngineArm};
use crate::error::ParamError;

/// A ball fixed to a link of the arm: which module's link (0-based), its
/// centre in that link's frame (m) and its radius (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TipBall {
    module: usize,
    center: [f64; 3],
    radius: f64,
}

impl TipBall {
    /// A ball of `radius` (m, finite, > 0) on module `module`'s link, its
    /// centre at `center` (m, finite, the link's frame).
    pub fn try_new(module: usize, center: [f64; 3], radius: f64) -> Result<Self, ParamError> {
        for c in center {
            crate::error::finite("ball_center", c)?;
        }
        Ok(TipBall {
            module,
            center,
            radius: crate::error::positive("ball_radius", radius)?,
        })
    }

    /// The module whose link carries it.
    pub fn module(&self) -> usize {
        self.module
    }

    /// Centre in the link's frame, m.
    pub fn center(&self) -> [f64; 3] {
        self.center
    }

    /// Radius, m.
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

/// A fixed box in the base frame: half extents along its own axes (m), its
/// centre (m) and its rotation about the base's `z` axis (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    half_extents: [f64; 3],
    center: [f64; 3],
    yaw: f64,
}

impl Wall {
    /// A box of `half_extents` (m, finite, > 0) centred at `center` (m,
    /// finite, base frame), turned by `yaw` (rad, finite) about the base's
    /// `z` axis.
    pub fn try_new(half_extents: [f64; 3], center: [f64; 3], yaw: f64) -> Result<Self, ParamError> {
        for h in half_extents {
            crate::error::positive("wall_half_extents", h)?;
        }
        for c in center {
            crate::error::finite("wall_center", c)?;
        }
        Ok(Wall {
            half_extents,
            center,
            yaw: crate::error::finite("wall_yaw", yaw)?,
        })
    }

    /// The wall that `ball` touches when its link, turning about the base's
    /// `z` axis through the origin, reaches `contact_angle` (rad, positive
    /// right-handed about `z`), and that stops it from going further.
    ///
    /// The ball's centre is at distance `R` from the axis (its link frame
    /// coincides with the base frame at `q_l = 0`); the wall's face is the
    /// half-plane through the axis at `φ₀ + contact_angle + asin(r/R)`
    /// (`φ₀` the centre's azimuth at `q_l = 0`, `r` the radius), so that
    /// the ball's surface reaches it at `contact_angle`; the box lies on
    /// the far side of the face, `thickness` (m) thick, spanning the
    /// ball's radius ± 0.1 m along the face and ± max(2r, 0.05 m)
    /// vertically about the ball's height. Errors name the value:
    /// `contact_angle` and `thickness` finite, `thickness > 0`, and the
    /// ball's centre farther than its radius (plus 0.01 m) from the axis
    /// (`ball_center`).
    pub fn stop_for(
        ball: &TipBall,
        contact_angle: f64,
        thickness: f64,
    ) -> Result<Self, ParamError> {
        let contact_angle = crate::error::finite("contact_angle", contact_angle)?;
        let thickness = crate::error::positive("thickness", thickness)?;
        let [cx, cy, cz] = ball.center;
        let reach = (cx * cx + cy * cy).sqrt();
        let r = ball.radius;
        // Finite: the centre and the radius are validated.
        if reach <= r + 0.01 {
            return Err(ParamError::OutOfRange {
                name: "ball_center",
                value: reach,
                min: r + 0.01,
                max: f64::INFINITY,
            });
        }
        let face = cy.atan2(cx) + contact_angle + (r / reach).asin();
        let (s, c) = face.sin_cos();
        // Box centre in the face's frame (x along the face, y away from
        // the ball), turned into the base frame.
        let (lx, ly) = (reach, 0.5 * thickness);
        Wall::try_new(
            [0.1, 0.5 * thickness, (2.0 * r).max(0.05)],
            [c * lx - s * ly, s * lx + c * ly, cz],
            face,
        )
    }

    /// Half extents, m.
    pub fn half_extents(&self) -> [f64; 3] {
        self.half_extents
    }

    /// Centre, m, base frame.
    pub fn center(&self) -> [f64; 3] {
        self.center
    }

    /// Rotation about the base's `z` axis, rad.
    pub fn yaw(&self) -> f64 {
        self.yaw
    }
}

/// The colliders of [`EngineArm::add_wall`].
#[derive(Debug, Clone, Copy)]
pub(super) struct Obstacle {
    module: usize,
    center: Vector<Real>,
    ball: ColliderHandle,
    wall: ColliderHandle,
}

impl<D: DriveModel> EngineArm<D> {
    /// Put `ball` on its link and `wall` in the world, both as frictionless
    /// colliders (module docs); from the next step on the engine computes
    /// their contact. Errors: `ball`'s module beyond the arm
    /// (`ball_module`); a second obstacle (`obstacles`: one per arm).
    pub fn add_wall(&mut self, ball: &TipBall, wall: &Wall) -> Result<(), ParamError> {
        let Some(&link) = self.links.get(ball.module) else {
            return Err(ParamError::OutOfRange {
                name: "ball_module",
                value: ball.module as f64,
                min: 0.0,
                max: self.links.len().saturating_sub(1) as f64,
            });
        };
        if self.obstacle.is_some() {
            return Err(ParamError::OutOfRange {
                name: "obstacles",
                value: 2.0,
                min: 0.0,
                max: 1.0,
            });
        }
        let center = Vector::from(ball.center);
        let ball_collider = ColliderBuilder::ball(ball.radius)
            .translation(center)
            .density(0.0)
            .friction(0.0)
            .build();
        let [hx, hy, hz] = wall.half_extents;
        let wall_body = self.world.bodies.insert(
            RigidBodyBuilder::fixed()
                .translation(Vector::from(wall.center))
                .rotation(Vector::z() * wall.yaw)
                .build(),
        );
        let wall_collider = ColliderBuilder::cuboid(hx, hy, hz).friction(0.0).build();
        let w = &mut self.world;
        let ball_handle = w
            .colliders
            .insert_with_parent(ball_collider, link, &mut w.bodies);
        let wall_handle = w
            .colliders
            .insert_with_parent(wall_collider, wall_body, &mut w.bodies);
        self.obstacle = Some(Obstacle {
            module: ball.module,
            center,
            ball: ball_handle,
            wall: wall_handle,
        });
        Ok(())
    }

    /// The force of the wall on the ball over the last step (N, base
    /// frame): the contact impulses the engine's solver applied, over the
    /// step. Zero without an obstacle or out of contact.
    pub fn contact_force(&self) -> [f64; 3] {
        let Some(o) = self.obstacle else {
            return [0.0; 3];
        };
        let Some(pair) = self.world.narrow_phase.contact_pair(o.ball, o.wall) else {
            return [0.0; 3];
        };
        // The manifold normal points out of the pair's first collider;
        // the impulse along it acts on the second one.
        let on_second = pair.total_impulse() / self.settings.dt();
        let f = if pair.collider1 == o.ball {
            -on_second
        } else {
            on_second
        };
        [f.x, f.y, f.z]
    }

    /// The generalized force of the contact on the ball's link coordinate
    /// `q_l` over the last step (N·m, positive in the joint's positive
    /// sense): `((c − o) × F) · z` (module docs). Zero without an
    /// obstacle or out of contact.
    pub fn contact_torque(&self) -> f64 {
        let Some(o) = self.obstacle else {
            return 0.0;
        };
        let f = Vector::from(self.contact_force());
        if f == Vector::zeros() {
            return 0.0;
        }
        let link = self.links[o.module];
        let parent = self.world.bodies[self.parent_of(o.module)].position();
        let joint = &self.link_joints[o.module];
        let origin = parent * Point::from(joint.origin);
        let axis = parent.rotation * joint.axis;
        let c = self.world.bodies[link].position() * Point::from(o.center);
        (c - origin).cross(&f).dot(&axis)
    }

    /// Whether the ball and the wall are in contact after the last step
    /// (the engine's contact pair has an active contact).
    pub fn in_contact(&self) -> bool {
        self.obstacle.is_some_and(|o| {
            self.world
                .narrow_phase
                .contact_pair(o.ball, o.wall)
                .is_some_and(|p| p.has_any_active_contact)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Signed distance (m) from a ball centre `c` to the wall's face on the
    /// ball's side: the face is the box's side at `−half_extents[1]` along
    /// its own `y` axis.
    fn gap(w: &Wall, c: [f64; 3]) -> f64 {
        let n = [-w.yaw.sin(), w.yaw.cos()];
        let h = w.half_extents[1];
        let face = [w.center[0] - h * n[0], w.center[1] - h * n[1]];
        (face[0] - c[0]) * n[0] + (face[1] - c[1]) * n[1]
    }

    #[test]
    fn the_wall_meets_the_ball_at_the_contact_angle() {
        let ball = TipBall::try_new(0, [0.45, 0.0, 0.0], 0.02).unwrap();
        let wall = Wall::stop_for(&ball, 0.15, 0.05).unwrap();
        let at = |q: f64| [0.45 * q.cos(), 0.45 * q.sin(), 0.0];
        // Touching at 0.15 rad (distance = radius), clear before it,
        // overlapping after it.
        assert!((gap(&wall, at(0.15)) - 0.02).abs() < 1e-12);
        assert!(gap(&wall, at(0.14)) > 0.02 + 4e-3);
        assert!(gap(&wall, at(0.16)) < 0.02 - 4e-3);
        // The ball's centre at contact lies along the face (within its
        // half length of 0.1 m from the box's middle).
        let along = [wall.yaw.cos(), wall.yaw.sin()];
        let c = at(0.15);
        let d = (c[0] - wall.center[0]) * along[0] + (c[1] - wall.center[1]) * along[1];
        assert!(d.abs() < wall.half_extents[0], "{d}");
    }

    #[test]
    fn bad_obstacles_are_typed_errors_naming_the_value() {
        assert!(matches!(
            TipBall::try_new(0, [f64::NAN, 0.0, 0.0], 0.02),
            Err(ParamError::NotFinite {
                name: "ball_center",
                ..
            })
        ));
        assert!(matches!(
            TipBall::try_new(0, [0.45, 0.0, 0.0], 0.0),
            Err(ParamError::NotPositive {
                name: "ball_radius",
                ..
            })
        ));
        let near = TipBall::try_new(0, [0.02, 0.0, 0.0], 0.02).unwrap();
        assert!(matches!(
            Wall::stop_for(&near, 0.15, 0.05),
            Err(ParamError::OutOfRange {
                name: "ball_center",
                ..
            })
        ));
        let ball = TipBall::try_new(0, [0.45, 0.0, 0.0], 0.02).unwrap();
        assert!(matches!(
            Wall::stop_for(&ball, f64::INFINITY, 0.05),
            Err(ParamError::NotFinite {
                name: "contact_angle",
                ..
            })
        ));
        assert!(matches!(
            Wall::stop_for(&ball, 0.15, -0.05),
            Err(ParamError::NotPositive {
                name: "thickness",
                ..
            })
        ));
        assert!(matches!(
            Wall::try_new([0.1, 0.1, 0.1], [0.0; 3], f64::NAN),
            Err(ParamError::NotFinite {
                name: "wall_yaw",
                ..
            })
        ));
    }

    #[test]
    fn a_pressed_link_reads_the_contact_torque_that_holds_it() {
        use crate::sim::engine::arm::{arm_settings, DriveState, DriveTorques, RotorBody};
        use crate::sim::mrr::ModuleParams;
        let m = [ModuleParams::thesis_joint()];
        // No drive: the link is free on its joint (vertical axis, so no
        // gravity torque), pushed towards the wall by 2 N·m.
        let free = |_: usize, _: &DriveState| DriveTorques::default();
        let mut arm = EngineArm::try_new(
            &m,
            [0.0, 0.0, -9.81],
            RotorBody::default(),
            free,
            arm_settings(),
        )
        .unwrap();
        let ball = TipBall::try_new(0, [0.45, 0.0, 0.0], 0.02).unwrap();
        let wall = Wall::stop_for(&ball, 0.15, 0.05).unwrap();
        assert!(matches!(
            arm.add_wall(&TipBall::try_new(1, [0.45, 0.0, 0.0], 0.02).unwrap(), &wall),
            Err(ParamError::OutOfRange {
                name: "ball_module",
                ..
            })
        ));
        arm.add_wall(&ball, &wall).unwrap();
        assert!(matches!(
            arm.add_wall(&ball, &wall),
            Err(ParamError::OutOfRange {
                name: "obstacles",
                ..
            })
        ));
        arm.set_state(&[0.14], &[0.0], &[0.0], &[0.0]);
        arm.set_external_torque(&[2.0]);
        arm.step();
        assert!(!arm.in_contact() && arm.contact_torque() == 0.0);
        arm.run(0.5);
        let q = arm.link_angles()[0];
        // At rest on the wall: the contact holds the 2 N·m, no more.
        assert!(arm.in_contact());
        assert!(
            (arm.contact_torque() + 2.0).abs() < 1e-3,
            "{}",
            arm.contact_torque()
        );
        assert!(arm.link_speeds()[0].abs() < 1e-3);
        assert!((q - 0.15).abs() < 3e-3, "{q}");
    }
}
