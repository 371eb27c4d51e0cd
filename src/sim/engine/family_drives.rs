//! The independent joint family's drives on the engine arm: a
//! [`DriveModel`] whose torques come from members of
//! [`crate::sim::plants::joint_family`] ([`JointPlant`], one per module)
//! instead of the library's own drive and friction models.
//!
//! # What a module's drive is
//! Each module carries one [`JointPlant`] and its state
//! ([`JointPlantState`]: friction and hysteresis anchors, the node's last
//! twist, and the kinematic error drawn from the module's seed). At the
//! engine's [`DriveState`] (`q_m = θ_m`, `q_l = θ_l`, both relative to the
//! carrying link, rad; speeds rad/s) the member solves its node balance
//! ([`JointPlant::forces`]: flexspline backbone and hysteresis, wave-generator
//! bearing compliance, mesh friction at the node, a kinematic error with
//! harmonics and tooth-pass ripple) and returns, by virtual work as its own
//! equations of motion have them (module docs of
//! [`crate::sim::plants::joint`]):
//!
//! ```text
//! on the link   T_f (1 − ∂e_k/∂θ_l) − F_l
//! on the motor  −T_w/N − T_f ∂e_k/∂θ_m − F_m
//! ```
//!
//! with `T_f` the flexspline torque (reported as the transmission torque
//! `τ_t`, what a link-side sensor reads), `T_w` the wave-generator bearing
//! torque, `N = 100`, `F_l` the member's link-bearing friction (Maxwell-slip
//! plus viscous) and `F_m` its asymmetric pre-sliding motor friction. None
//! of it is eq. (3.7)'s kinematic error or eq. (4.8)'s friction form, the
//! models the library's estimator and control law carry (contrast
//! [`super::PlantDrives`]). All in N·m, positive in the joint's positive
//! sense.
//!
//! The member's link inertia and payload are not used: on the engine the
//! link, its payload and gravity are bodies and forces of the arm. After
//! each engine step [`DriveModel::advance`] commits the anchors at the new
//! state as [`JointPlant::advance`] does after each of its own steps.
//!
//! No stored energy is reported ([`DriveModel::stored_energy`] stays zero):
//! the family's backbones and bearing curves are given as torques, without
//! an energy function, and its Maxwell-slip elements dissipate.

use super::arm::{DriveModel, DriveState, DriveTorques};
use crate::error::ParamError;
use crate::sim::mrr::ModuleParams;
use crate::sim::plants::drive::RATIO;
use crate::sim::plants::joint::{joint_family, JointPlant, JointPlantState};

/// Member `index` of [`joint_family`] (0–23), the family calibrated once
/// per process (its drives are fitted to the catalogue when built). An
/// index past the family is `ParamError::OutOfRange` naming `member`.
pub fn family_member(index: usize) -> Result<JointPlant, ParamError> {
    static FAMILY: std::sync::OnceLock<Vec<JointPlant>> = std::sync::OnceLock::new();
    let family = FAMILY.get_or_init(joint_family);
    family.get(index).cloned().ok_or(ParamError::OutOfRange {
        name: "member",
        value: index as f64,
        min: 0.0,
        max: family.len() as f64 - 1.0,
    })
}

/// Members of the joint family driving the modules of an arm (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyDrives {
    members: Vec<JointPlant>,
    states: Vec<JointPlantState>,
    seeds: Vec<u64>,
}

impl FamilyDrives {
    /// One member per module of `modules`, module `i` with
    /// `members[i]`, its kinematic error drawn from `seeds[i]`, at rest
    /// (no torque in the drive, every element relaxed) with the link at
    /// `link_angles[i]` (rad; missing entries are 0): the motor angles are
    /// then [`motor_angles`](Self::motor_angles), not `N q_l`, because of
    /// the drawn kinematic error.
    ///
    /// Errors, each naming the value: `members` or `seeds` of another
    /// length than `modules` (`ParamError::OutOfRange` with the length as
    /// value and the module count as its range), a module whose gear
    /// `ratio` is not the family's `N = 100` (the family is calibrated to
    /// the SHD-17-100), a non-finite `link_angle`.
    pub fn try_new(
        modules: &[ModuleParams],
        members: Vec<JointPlant>,
        seeds: &[u64],
        link_angles: &[f64],
    ) -> Result<Self, ParamError> {
        let n = modules.len() as f64;
        let count = |name: &'static str, len: usize| {
            if len == modules.len() {
                Ok(())
            } else {
                Err(ParamError::OutOfRange {
                    name,
                    value: len as f64,
                    min: n,
                    max: n,
                })
            }
        };
        count("members", members.len())?;
        count("seeds", seeds.len())?;
        for m in modules {
            if m.drive.ratio != RATIO {
                return Err(ParamError::OutOfRange {
                    name: "ratio",
                    value: m.drive.ratio,
                    min: RATIO,
                    max: RATIO,
                });
            }
        }
        let mut states = Vec::with_capacity(members.len());
        for (i, (p, &seed)) in members.iter().zip(seeds).enumerate() {
            let link =
                crate::error::finite("link_angle", link_angles.get(i).copied().unwrap_or(0.0))?;
            states.push(p.rest(link, seed));
        }
        Ok(FamilyDrives {
            members,
            states,
            seeds: seeds.to_vec(),
        })
    }

    /// The members, one per module.
    pub fn members(&self) -> &[JointPlant] {
        &self.members
    }

    /// The seeds of the modules' kinematic-error draws.
    pub fn seeds(&self) -> &[u64] {
        &self.seeds
    }

    /// The members' states (anchors as of the last committed step; their
    /// `x` is the last state committed, not the engine's).
    pub fn states(&self) -> &[JointPlantState] {
        &self.states
    }

    /// The motor angles `q_m` (rad) of the members' states: after
    /// [`try_new`](Self::try_new) the angles at which each drive carries no
    /// torque, after [`load`](Self::load) the loaded ones.
    pub fn motor_angles(&self) -> Vec<f64> {
        self.states.iter().map(|s| s.x[0]).collect()
    }

    /// Twist module `module`'s drive, link held where it is, until the
    /// drive's torque on the link `T_f (1 − ∂e_k/∂θ_l)` is `torque` (N·m;
    /// e.g. the gravity torque of a link at rest), by bisection on the
    /// motor angle over ±0.05 rad of link-side twist from its zero-load
    /// angle, with the elements as they are (relaxed after `try_new`: the
    /// drive loaded from rest). The motor friction is re-anchored at the
    /// new angle (no pre-sliding load). Returns the motor angle (rad).
    /// Errors: an unknown `module`, a non-finite `torque`, a torque
    /// outside what ±0.05 rad of twist carries (`torque`, with that range).
    pub fn load(&mut self, module: usize, torque: f64) -> Result<f64, ParamError> {
        let torque = crate::error::finite("torque", torque)?;
        let (Some(p), Some(st)) = (self.members.get(module), self.states.get_mut(module)) else {
            return Err(ParamError::OutOfRange {
                name: "module",
                value: module as f64,
                min: 0.0,
                max: self.members.len() as f64 - 1.0,
            });
        };
        let link = st.x[2];
        let zero = p.zero_load_motor_angle(st, link);
        let on_link = |st: &JointPlantState, motor: f64| {
            let f = p.forces(st, &[motor, 0.0, link, 0.0]);
            f.flexspline_torque * (1.0 - f.kinematic_error_slope_link)
        };
        let span = 0.05 * RATIO;
        let (mut lo, mut hi) = (zero - span, zero + span);
        let (t_lo, t_hi) = (on_link(st, lo), on_link(st, hi));
        if !(t_lo..=t_hi).contains(&torque) {
            return Err(ParamError::OutOfRange {
                name: "torque",
                value: torque,
                min: t_lo,
                max: t_hi,
            });
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if on_link(st, mid) < torque {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let motor = 0.5 * (lo + hi);
        st.x = [motor, 0.0, link, 0.0];
        st.motor.iter_mut().for_each(|z| *z = motor);
        // The loaded node, its elements slid as far as loading from rest
        // takes them.
        p.commit(st);
        Ok(motor)
    }
}

impl DriveModel for FamilyDrives {
    fn torques(&mut self, i: usize, s: &DriveState) -> DriveTorques {
        let (Some(p), Some(st)) = (self.members.get(i), self.states.get(i)) else {
            return DriveTorques::default();
        };
        let f = p.forces(
            st,
            &[s.motor_angle, s.motor_speed, s.link_angle, s.link_speed],
        );
        DriveTorques {
            transmission: f.flexspline_torque,
            on_link: f.on_link(),
            on_motor: f.on_motor(),
        }
    }

    fn advance(&mut self, i: usize, s: &DriveState) {
        let (Some(p), Some(st)) = (self.members.get(i), self.states.get_mut(i)) else {
            return;
        };
        st.x = [s.motor_angle, s.motor_speed, s.link_angle, s.link_speed];
        p.commit(st);
    }
}
