//! Differential kinematics and force mapping of the wrist, thesis
//! eq. (5.22)–(5.29) and (6.1)–(6.2).
//!
//! A Jacobian here maps motor speeds `(θ̇1, θ̇3)` (rad/s) to output speeds
//! `(δ̇, γ̇)` (rad/s): rows `δ, γ`, columns `θ1, θ3`. By virtual work the
//! motor torques that balance output torques `(τ_δ, τ_γ)` are
//! `(τ1, τ3) = Jᵀ (τ_δ, τ_γ)`, eq. (5.28) and (6.1)–(6.2), in the unit of
//! the output torques (the map is dimensionless).
//!
//! # Two Jacobians
//!
//! * [`JacobianKind::Exact`] (the default of [`ForceMapping`] and the one
//!   the wrist controllers use): the derivative of the forward kinematics
//!   of [`super::kinematics`]. Equating the angular velocity of the chain,
//!   `θ̇1 e_z + θ̇4 m + θ̇3 z`, with that of the universal joint,
//!   `δ̇ e_y + γ̇ g` (`m = R_z(θ1)(0, −Sφ, Cφ)` the oblique axis,
//!   `g = R_y(δ) e_x`, `z` the output axis), and solving by Cramer's rule
//!   with `D = Sδ Sφ S1 + Cδ Cφ ≥ cos 2φ cos φ − sin 2φ sin φ = cos 3φ > 0`
//!   (`|δ| ≤ 2φ`, `φ ≤ 30°`):
//!
//!   ```text
//!   J = (1/D) [ Cδ Sφ C1     Sφ C1 Cγ − Sγ D          ]
//!             [ −Sφ S1       Cγ (Sδ Cφ − Cδ Sφ S1)     ],
//!   det J = Sφ (C1 Sδ Cγ − S1 Sγ) / D.
//!   ```
//!
//! * [`JacobianKind::Thesis`]: the thesis's chain `J = J_2 J_c`,
//!   eq. (5.23)–(5.27), with `J_c` the derivative of Ryew–Choi's
//!   approximation (eq. 5.21 as corrected in [`super::alpha_beta`], errata
//!   E5.8) and `J_2` the exact derivative of `(α, β) ↦ (δ, γ)` (errata
//!   E5.9). Its force mapping differs from the exact one by up to 8.96 %
//!   of `‖J‖` over the workspace (`tests::thesis_force_mapping_error`).
//!
//! # Singular configurations
//!
//! `det J = 0` exactly at the straight pose (`θ1 + θ3 = 0`: every motor
//! motion with `θ̇1 = −θ̇3` leaves the wrist straight, so the bend can
//! start only in the direction set by `θ1 − θ3`) and on the workspace
//! boundary (bend `2φ`, `θ4 = π`, where the oblique axis lies in the
//! bending plane). The thesis states none of this: eq. (5.25) and (5.29)
//! invert `J_c` and `J_2` unconditionally, and they are singular at the
//! same two places (`Ω = 0` on the boundary, `β = 0` in `J_2`).
//! [`ForceMapping::motor_torques`] (eq. 5.28) is bounded everywhere
//! (`|J_ij| ≤ 1.4` for `φ = 16°`); [`ForceMapping::task_torques`]
//! (eq. 5.29) uses `1/det` for `|det| ≥ DET_MIN` and `det/DET_MIN²`
//! below (bounded by `1/DET_MIN`, continuous) and flags it.

use super::alpha_beta::AlphaBeta;
use super::kinematics::{denan, MotorAngles, WristConfig, WristParams};
use crate::scalar::Scalar;

/// Below this `|det J|` the mapping of eq. (5.29) is flagged singular and
/// regularized (see the module docs). For `φ = 16°` it is reached within
/// about 2° of the straight pose and of the workspace boundary.
pub const DET_MIN: f64 = 0.01;

/// Torques beyond `±MAX_TORQUE` (in the caller's unit; N·m at the API
/// boundary) are clamped and flagged: no wrist torque comes near it, and
/// it keeps every product finite on every backend.
pub const MAX_TORQUE: f64 = 1e4;

/// Which Jacobian a [`ForceMapping`] uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum JacobianKind {
    /// The derivative of the library's forward kinematics (default).
    #[default]
    Exact,
    /// The thesis's chain `J_2 J_c` of eq. (5.24)–(5.27), corrected.
    Thesis,
}

/// A 2×2 Jacobian `∂(δ, γ)/∂(θ1, θ3)` (dimensionless) and its determinant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobian<S> {
    /// Rows `δ̇, γ̇`; columns `θ̇1, θ̇3`.
    pub m: [[S; 2]; 2],
    /// `det J`.
    pub det: S,
    /// `|det J| < DET_MIN`: near the straight pose or the boundary.
    pub singular: bool,
}

impl<S: Scalar> Jacobian<S> {
    fn from_matrix(m: [[S; 2]; 2]) -> Self {
        let det = m[0][0].mul(m[1][1]).sub(m[0][1].mul(m[1][0]));
        Jacobian {
            m,
            det,
            singular: det.abs() < S::from_f64(DET_MIN),
        }
    }
}

impl<S: Scalar> WristConfig<S> {
    /// The exact Jacobian at the motor angles (rad); see the module docs.
    pub fn jacobian(&self, motors: MotorAngles<S>) -> Jacobian<S> {
        let f = self.forward(motors);
        let (s1, c1) = denan(motors.theta1).sin_cos();
        let (sd, cd) = f.pose.delta.sin_cos();
        let (sg, cg) = f.pose.gamma.sin_cos();
        let (sp, cp) = (self.sin_phi, self.cos_phi);
        let d = sd.mul(sp).mul(s1).add(cd.mul(cp));
        let m = [
            [
                cd.mul(sp).mul(c1).div(d),
                sp.mul(c1).mul(cg).sub(sg.mul(d)).div(d),
            ],
            [
                sp.mul(s1).neg().div(d),
                cg.mul(sd.mul(cp).sub(cd.mul(sp).mul(s1))).div(d),
            ],
        ];
        Jacobian::from_matrix(m)
    }

    /// `J_c = ∂(α, β)/∂(θ1, θ3)` of Ryew–Choi's approximation, eq. (5.22)–
    /// (5.24) corrected (E5.8): `[[−½, ½], [−Ω, −Ω]]` with
    /// `Ω = tan φ cos(u/2) / (1 + tan²φ sin²(u/2))`, `u = θ1 + θ3`, for the
    /// signed `β` of [`super::alpha_beta`].
    pub fn jc_approx(&self, motors: MotorAngles<S>) -> [[S; 2]; 2] {
        let two = S::ONE.add(S::ONE);
        let half = S::ONE.div(two);
        let u = denan(motors.theta1).add(denan(motors.theta3));
        let (s, c) = u.mul(half).sin_cos();
        let t = self.tan_phi;
        let omega = t.mul(c).div(S::ONE.add(t.mul(t).mul(s).mul(s)));
        [[half.neg(), half], [omega.neg(), omega.neg()]]
    }

    /// `J_2 = ∂(δ, γ)/∂(α, β)`, eq. (5.26)–(5.27) corrected (E5.9): the
    /// derivative of `sin δ = cos α sin β`, `tan γ = sin α tan β`, for a
    /// signed bend `β` in the workspace's `[−2φ, 2φ]`; a bend beyond it
    /// (not a pose of the wrist; at `β = ±π/2`, `α = 0` the map is
    /// singular) is limited to it, and NaN is read as 0. Every entry is
    /// then at most `1/cos²(2φ)` in magnitude (`cos δ ≥ cos β`,
    /// `cos²β + sin²α sin²β ≥ cos²β`).
    pub fn j2(&self, ab: AlphaBeta<S>) -> [[S; 2]; 2] {
        let (sa, ca) = denan(ab.alpha).sin_cos();
        let b = denan(ab.beta).clamp(self.max_bend.neg(), self.max_bend);
        let (sb, cb) = b.sin_cos();
        // cos δ = √(1 − cos²α sin²β) ≥ cos β > 0 in the workspace.
        let x = ca.mul(sb);
        let cd = S::ONE.sub(x.mul(x)).sqrt();
        // γ = atan2(sin α sin β, cos β): denominator q = cos²β + sin²α sin²β.
        let y = sa.mul(sb);
        let q = cb.mul(cb).add(y.mul(y));
        [
            [sa.mul(sb).neg().div(cd), ca.mul(cb).div(cd)],
            [ca.mul(sb).mul(cb).div(q), sa.div(q)],
        ]
    }

    /// The thesis's chain `J_2(α, β) J_c` at the motor angles, with
    /// `(α, β)` from the corrected eq. (5.21) (signed `β`).
    pub fn jacobian_thesis(&self, motors: MotorAngles<S>) -> Jacobian<S> {
        let two = S::ONE.add(S::ONE);
        let (t1, t3) = (denan(motors.theta1), denan(motors.theta3));
        let beta = two
            .mul(self.tan_phi.mul(t1.add(t3).div(two).sin()).atan())
            .neg();
        let alpha = t3.sub(t1).div(two).add(S::PI);
        let j2 = self.j2(AlphaBeta { alpha, beta });
        let jc = self.jc_approx(motors);
        let mut m = [[S::ZERO; 2]; 2];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = j2[i][0].mul(jc[0][j]).add(j2[i][1].mul(jc[1][j]));
            }
        }
        Jacobian::from_matrix(m)
    }
}

/// Torques from [`ForceMapping`], with the singularity flag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MappedTorques<S> {
    /// `(τ1, τ3)` or `(τ_δ, τ_γ)`, in the unit of the input torques.
    pub torque: [S; 2],
    /// The Jacobian was singular (`|det J| < DET_MIN`); for
    /// [`ForceMapping::task_torques`] the result is regularized.
    pub singular: bool,
    /// An input torque was outside `±MAX_TORQUE` (or NaN) and was clamped.
    pub saturated: bool,
}

/// The force mapping between output torques `(τ_δ, τ_γ)` and motor torques
/// `(τ1, τ3)`, eq. (5.28)–(5.29) and (6.1)–(6.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceMapping<S> {
    cfg: WristConfig<S>,
    kind: JacobianKind,
    det_min: S,
    inv_det_min_sq: S,
    max_torque: S,
}

impl<S: Scalar> ForceMapping<S> {
    /// The mapping for a wrist with the chosen Jacobian
    /// ([`JacobianKind::Exact`] unless the thesis's chain is wanted).
    pub fn new(p: &WristParams, kind: JacobianKind) -> Self {
        ForceMapping {
            cfg: WristConfig::new(p),
            kind,
            det_min: S::from_f64(DET_MIN),
            inv_det_min_sq: S::from_f64(1.0 / (DET_MIN * DET_MIN)),
            max_torque: S::from_f64(MAX_TORQUE),
        }
    }

    /// The kinematics this mapping evaluates.
    pub fn config(&self) -> &WristConfig<S> {
        &self.cfg
    }

    /// Clamp an input torque pair; `true` when anything was changed.
    fn clamp_torques(&self, t: [S; 2]) -> ([S; 2], bool) {
        let l = self.max_torque;
        let a = denan(t[0]).clamp(l.neg(), l);
        let b = denan(t[1]).clamp(l.neg(), l);
        (
            [a, b],
            a != t[0] || b != t[1] || t[0].is_nan() || t[1].is_nan(),
        )
    }

    /// The Jacobian used, at the motor angles (rad).
    pub fn jacobian(&self, motors: MotorAngles<S>) -> Jacobian<S> {
        match self.kind {
            JacobianKind::Exact => self.cfg.jacobian(motors),
            JacobianKind::Thesis => self.cfg.jacobian_thesis(motors),
        }
    }

    /// Eq. (5.28), (6.1)–(6.2): the motor torques `(τ1, τ3) = Jᵀ (τ_δ, τ_γ)`
    /// at the motor angles (rad). Bounded everywhere (`|τ_i| ≤ 1.4 (|τ_δ| + |τ_γ|)`
    /// for `φ = 16°`); `singular` only reports the configuration. Inputs are
    /// clamped to `±MAX_TORQUE` (NaN read as 0) and flagged.
    pub fn motor_torques(&self, motors: MotorAngles<S>, task: [S; 2]) -> MappedTorques<S> {
        let j = self.jacobian(motors);
        let ([td, tg], saturated) = self.clamp_torques(task);
        MappedTorques {
            torque: [
                j.m[0][0].mul(td).add(j.m[1][0].mul(tg)),
                j.m[0][1].mul(td).add(j.m[1][1].mul(tg)),
            ],
            singular: j.singular,
            saturated,
        }
    }

    /// Eq. (5.29): the output torques `(τ_δ, τ_γ) = J⁻ᵀ (τ1, τ3)` at the
    /// motor angles (rad). For the thesis chain `J = J_2 J_c` this is
    /// `(J_2ᵀ)⁻¹ (J_cᵀ)⁻¹ (τ1, τ3)`, the inverse of eq. (5.28); eq. (5.29)
    /// prints the two inverses in the other order (errata E5.13). Regularized and flagged where
    /// `|det J| < DET_MIN` (the factor `1/det` becomes `det/DET_MIN²`, so
    /// `|τ| ≤ ‖adj J‖ |τ_motor| / DET_MIN`).
    pub fn task_torques(&self, motors: MotorAngles<S>, motor: [S; 2]) -> MappedTorques<S> {
        let j = self.jacobian(motors);
        let ([t1, t3], saturated) = self.clamp_torques(motor);
        let factor = if j.det.abs() >= self.det_min {
            S::ONE.div(j.det)
        } else {
            j.det.mul(self.inv_det_min_sq)
        };
        // (Jᵀ)⁻¹ = adj(Jᵀ)/det, adj(Jᵀ) = [[d, −c], [−b, a]].
        let [[a, b], [c, d]] = j.m;
        MappedTorques {
            torque: [
                d.mul(t1).sub(c.mul(t3)).mul(factor),
                a.mul(t3).sub(b.mul(t1)).mul(factor),
            ],
            singular: j.singular,
            saturated,
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::kinematics::PitchYaw;
    use super::*;
    use crate::scalar::I16F16;
    use core::f64::consts::PI;
    use proptest::prelude::*;

    fn cfg() -> WristConfig<f64> {
        WristConfig::new(&WristParams::thesis())
    }

    /// Central differences of a map R² → R², step h.
    fn fd<F: Fn(f64, f64) -> [f64; 2]>(f: F, x: f64, y: f64, h: f64) -> [[f64; 2]; 2] {
        let (a, b) = (f(x + h, y), f(x - h, y));
        let (c, d) = (f(x, y + h), f(x, y - h));
        [
            [(a[0] - b[0]) / (2.0 * h), (c[0] - d[0]) / (2.0 * h)],
            [(a[1] - b[1]) / (2.0 * h), (c[1] - d[1]) / (2.0 * h)],
        ]
    }

    fn max_diff(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> f64 {
        let mut m: f64 = 0.0;
        for i in 0..2 {
            for j in 0..2 {
                m = m.max((a[i][j] - b[i][j]).abs());
            }
        }
        m
    }

    proptest! {
        #[test]
        fn exact_jacobian_is_the_derivative_of_the_forward_kinematics(t1 in -4.0f64..4.0, t3 in -4.0f64..4.0) {
            let c = cfg();
            let fk = |a: f64, b: f64| {
                let p = c.forward(MotorAngles { theta1: a, theta3: b }).pose;
                [p.delta, p.gamma]
            };
            let j = c.jacobian(MotorAngles { theta1: t1, theta3: t3 });
            let f = fd(fk, t1, t3, 1e-6);
            prop_assert!(max_diff(&j.m, &f) < 1e-7, "{:?} vs {:?}", j.m, f);
            // The closed-form determinant of the module docs.
            let p = c.forward(MotorAngles { theta1: t1, theta3: t3 }).pose;
            let (sp, cp) = c.phi().sin_cos();
            let d = p.delta.sin() * sp * t1.sin() + p.delta.cos() * cp;
            let det = sp * (t1.cos() * p.delta.sin() * p.gamma.cos() - t1.sin() * p.gamma.sin()) / d;
            prop_assert!((det - j.det).abs() < 1e-12);
            prop_assert!(d >= (2.0 * c.phi()).cos() * cp - (2.0 * c.phi()).sin() * sp - 1e-12);
        }

        #[test]
        fn corrected_jc_and_j2_are_derivatives_of_their_maps(t1 in -4.0f64..4.0, t3 in -4.0f64..4.0, a in -3.1f64..3.1, b in -0.55f64..0.55) {
            let c = cfg();
            let approx = |x: f64, y: f64| {
                let beta = -2.0 * (c.phi().tan() * ((x + y) / 2.0).sin()).atan();
                [(y - x) / 2.0 + PI, beta]
            };
            let jc = c.jc_approx(MotorAngles { theta1: t1, theta3: t3 });
            prop_assert!(max_diff(&jc, &fd(approx, t1, t3, 1e-6)) < 1e-8);
            let pose = |x: f64, y: f64| {
                let p = c.pose_of_alpha_beta(AlphaBeta { alpha: x, beta: y });
                [p.delta, p.gamma]
            };
            let j2 = c.j2(AlphaBeta { alpha: a, beta: b });
            prop_assert!(max_diff(&j2, &fd(pose, a, b, 1e-6)) < 1e-8);
        }

        #[test]
        fn force_mapping_does_virtual_work_and_inverts(t1 in -4.0f64..4.0, t3 in -4.0f64..4.0, td in -3.0f64..3.0, tg in -3.0f64..3.0, w1 in -1.0f64..1.0, w3 in -1.0f64..1.0) {
            let fm = ForceMapping::<f64>::new(&WristParams::thesis(), JacobianKind::Exact);
            let m = MotorAngles { theta1: t1, theta3: t3 };
            let j = fm.jacobian(m);
            let tm = fm.motor_torques(m, [td, tg]);
            // Power: τ_motor · θ̇ = τ_task · (J θ̇).
            let out = [j.m[0][0] * w1 + j.m[0][1] * w3, j.m[1][0] * w1 + j.m[1][1] * w3];
            prop_assert!((tm.torque[0] * w1 + tm.torque[1] * w3 - (td * out[0] + tg * out[1])).abs() < 1e-12);
            let back = fm.task_torques(m, tm.torque);
            if !back.singular {
                prop_assert!((back.torque[0] - td).abs() < 1e-9 * (1.0 + 1.0 / j.det.abs()));
                prop_assert!((back.torque[1] - tg).abs() < 1e-9 * (1.0 + 1.0 / j.det.abs()));
            }
            let bound = 2.0 * 1.4 * (td.abs() + tg.abs()) * 1.4 / DET_MIN;
            prop_assert!(back.torque[0].abs() <= bound && back.torque[1].abs() <= bound);
            prop_assert!(tm.torque[0].abs() <= 1.4 * (td.abs() + tg.abs()));
        }
    }

    #[test]
    fn printed_jc_and_j2_are_not_derivatives_of_the_printed_maps() {
        let c = cfg();
        let tp = c.phi().tan();
        // Printed eq. (5.21) and its printed derivative eq. (5.22)/(5.24).
        let map = |x: f64, y: f64| [(x - y) / 2.0, 2.0 * (tp * ((y + x) / 2.0).cos()).atan()];
        let printed_jc = |x: f64, y: f64| {
            let h = (x - y) / 2.0;
            let om = h.sin() * tp / (1.0 + h.cos().powi(2) * tp * tp);
            [[0.5, 0.5], [-om, om]]
        };
        let (t1, t3) = (0.4, -1.3);
        assert!(max_diff(&printed_jc(t1, t3), &fd(map, t1, t3, 1e-6)) > 0.4);
        // Printed eq. (5.27) against the derivative of (α, β) ↦ (δ, γ).
        let printed_j2 = |a: f64, b: f64| {
            let t = b.tan();
            [
                [
                    -t * a.sin() / (1.0 + t * t * a.cos()),
                    -(1.0 / b.cos().powi(2)) * a.cos() / (1.0 + t * t * a.cos().powi(2)),
                ],
                [
                    t * a.cos() / (1.0 + t * t * a.sin()),
                    (1.0 / b.cos().powi(2)) * a.sin() / (1.0 + t * t * a.sin().powi(2)),
                ],
            ]
        };
        let pose = |x: f64, y: f64| {
            let p = c.pose_of_alpha_beta(AlphaBeta { alpha: x, beta: y });
            [p.delta, p.gamma]
        };
        let (a, b) = (0.7, 0.4);
        let fdj = fd(pose, a, b, 1e-6);
        let pj = printed_j2(a, b);
        assert!((pj[0][1] - fdj[0][1]).abs() > 0.5, "{pj:?} {fdj:?}");
        assert!((pj[1][0] - fdj[1][0]).abs() > 1e-3);
        // Row 2, column 2 prints correctly.
        assert!((pj[1][1] - fdj[1][1]).abs() < 1e-8);
    }

    #[test]
    fn singular_at_the_straight_pose_and_on_the_boundary_only() {
        let c = cfg();
        let p = WristParams::thesis();
        // Straight: det 0 for every θ1 = −θ3.
        for t in [0.0, 1.0, -2.0, 3.0] {
            let j = c.jacobian(MotorAngles {
                theta1: t,
                theta3: -t,
            });
            assert!(j.det.abs() < 1e-15 && j.singular);
        }
        // Boundary: the IK of a pose of bend 2φ.
        let mut min_inside = f64::MAX;
        for k in 0..64 {
            let tau = 2.0 * PI * k as f64 / 64.0;
            for (bend, on_edge) in [(p.max_bend(), true), (0.3, false), (0.1, false)] {
                let (d, g) = ((bend * tau.cos()).asin(), 0.0);
                let _ = g;
                // A pose of the given bend in direction τ: z = (sin b cos τ, sin b sin τ, cos b).
                let z = [bend.sin() * tau.cos(), bend.sin() * tau.sin(), bend.cos()];
                let delta = z[0].atan2(z[2]);
                let gamma = (-z[1]).atan2(z[0].hypot(z[2]));
                let _ = d;
                let r = c.inverse(PitchYaw { delta, gamma });
                let j = c.jacobian(r.motors);
                if on_edge {
                    assert!(j.det.abs() < 1e-6, "{tau} {}", j.det);
                } else {
                    min_inside = min_inside.min(j.det.abs());
                }
            }
        }
        assert!(min_inside > DET_MIN, "{min_inside}");
        // The flagged, regularized inverse stays bounded at the singularity.
        let fm = ForceMapping::<f64>::new(&p, JacobianKind::Exact);
        let r = fm.task_torques(
            MotorAngles {
                theta1: 0.5,
                theta3: -0.5,
            },
            [1.0, 1.0],
        );
        assert!(r.singular && r.torque[0].is_finite() && r.torque[0].abs() < 1e3);
    }

    /// Errata E5.13: eq. (5.28) is `τ13 = J_cᵀ J_2ᵀ τ`, so its inverse is
    /// `τ = (J_2ᵀ)⁻¹ (J_cᵀ)⁻¹ τ13`; eq. (5.29) prints the factors in the
    /// other order, `(J_cᵀ)⁻¹ (J_2ᵀ)⁻¹`. With `J_c`, `J_2` of the library
    /// (each checked against finite differences of its map) and 2×2
    /// inverses written out here, over the workspace away from the
    /// singular set: `task_torques` (thesis chain) equals the correct
    /// order and inverts eq. (5.28); the printed order misses by more than
    /// the torque itself somewhere.
    #[test]
    fn eq_5_29_inverts_eq_5_28_only_in_the_reverse_order() {
        let c = cfg();
        let p = WristParams::thesis();
        let fm = ForceMapping::<f64>::new(&p, JacobianKind::Thesis);
        let inv = |m: [[f64; 2]; 2]| {
            let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
            [
                [m[1][1] / det, -m[0][1] / det],
                [-m[1][0] / det, m[0][0] / det],
            ]
        };
        let tr = |m: [[f64; 2]; 2]| [[m[0][0], m[1][0]], [m[0][1], m[1][1]]];
        let app = |m: [[f64; 2]; 2], v: [f64; 2]| {
            [
                m[0][0] * v[0] + m[0][1] * v[1],
                m[1][0] * v[0] + m[1][1] * v[1],
            ]
        };
        let norm = |v: [f64; 2]| v[0].hypot(v[1]);
        let (mut worst_lib, mut worst_printed, mut checked) = (0.0f64, 0.0f64, 0);
        let n = 41;
        for i in 0..n {
            for j in 0..n {
                let d = -p.max_bend() + 2.0 * p.max_bend() * i as f64 / (n - 1) as f64;
                let g = -p.max_bend() + 2.0 * p.max_bend() * j as f64 / (n - 1) as f64;
                if !p.is_reachable(d, g) {
                    continue;
                }
                let m = c.inverse(PitchYaw { delta: d, gamma: g }).motors;
                let u = m.theta1 + m.theta3;
                let beta = -2.0 * (p.phi().tan() * (u / 2.0).sin()).atan();
                let alpha = (m.theta3 - m.theta1) / 2.0 + PI;
                let jc = c.jc_approx(m);
                let j2 = c.j2(AlphaBeta { alpha, beta });
                let det = |a: [[f64; 2]; 2]| a[0][0] * a[1][1] - a[0][1] * a[1][0];
                if det(jc).abs() < 0.05 || det(j2).abs() < 0.05 {
                    continue; // near the singular set (E5.10)
                }
                for t13 in [[1.0, 0.0], [0.0, 1.0], [0.6, -0.8]] {
                    let right = app(inv(tr(j2)), app(inv(tr(jc)), t13));
                    let printed = app(inv(tr(jc)), app(inv(tr(j2)), t13));
                    let lib = fm.task_torques(m, t13);
                    assert!(!lib.singular);
                    // The correct order inverts eq. (5.28).
                    let back = app(tr(jc), app(tr(j2), right));
                    assert!(norm([back[0] - t13[0], back[1] - t13[1]]) < 1e-12);
                    let e = [lib.torque[0] - right[0], lib.torque[1] - right[1]];
                    worst_lib = worst_lib.max(norm(e) / norm(right));
                    let e = [printed[0] - right[0], printed[1] - right[1]];
                    worst_printed = worst_printed.max(norm(e) / norm(right));
                }
                checked += 1;
            }
        }
        std::println!(
            "{checked} poses: library vs (J2^T)^-1 (Jc^T)^-1 {worst_lib:.1e}; printed order off by {:.0} % of |tau|",
            100.0 * worst_printed
        );
        assert!(checked > 500, "{checked}");
        assert!(worst_lib < 1e-12, "{worst_lib}");
        assert!(worst_printed > 1.0, "{worst_printed}");
    }

    /// How far the thesis's force mapping is from the exact one over the
    /// workspace: max of ‖J_thesisᵀ − J_exactᵀ‖_F / ‖J_exactᵀ‖_F.
    #[test]
    fn thesis_force_mapping_error() {
        let c = cfg();
        let p = WristParams::thesis();
        let mut worst: f64 = 0.0;
        let mut at = (0.0, 0.0);
        let n = 81;
        for i in 0..n {
            for j in 0..n {
                let d = -p.max_bend() + 2.0 * p.max_bend() * i as f64 / (n - 1) as f64;
                let g = -p.max_bend() + 2.0 * p.max_bend() * j as f64 / (n - 1) as f64;
                if !p.is_reachable(d, g) {
                    continue;
                }
                let m = c.inverse(PitchYaw { delta: d, gamma: g }).motors;
                let je = c.jacobian(m).m;
                let jt = c.jacobian_thesis(m).m;
                let mut num = 0.0;
                let mut den = 0.0;
                for r in 0..2 {
                    for s in 0..2 {
                        num += (je[r][s] - jt[r][s]).powi(2);
                        den += je[r][s].powi(2);
                    }
                }
                let e = (num / den).sqrt();
                if e > worst {
                    worst = e;
                    at = (d, g);
                }
            }
        }
        std::println!("thesis vs exact force mapping: max relative Frobenius error {:.2} % at (delta, gamma) = ({:.3}, {:.3}) rad", 100.0 * worst, at.0, at.1);
        assert!(worst < 0.10 && worst > 0.005, "{worst}");
    }

    /// `J_2` (eq. 5.27 corrected) at any `(α, β)`: finite on every
    /// backend, also where `(α, β) ↦ (δ, γ)` itself is singular
    /// (`β = ±π/2` with `α = 0`: `cos δ = 0`), bounded by
    /// `1/cos²(2φ)` per entry, and unchanged inside the workspace.
    #[test]
    fn j2_is_finite_and_bounded_everywhere() {
        fn check<S: Scalar>() {
            let p = WristParams::thesis();
            let c = WristConfig::<S>::new(&p);
            let bound = 1.0 / (2.0 * p.phi()).cos().powi(2) * (1.0 + 1e-3);
            for &(a, b) in &[
                (0.0, PI / 2.0),
                (0.0, -PI / 2.0),
                (PI, PI / 2.0),
                (PI / 2.0, PI),
                (0.3, 1.5),
                (0.0, 1e30),
                (f64::NAN, 0.2),
            ] {
                let ab = AlphaBeta {
                    alpha: S::from_f64(a),
                    beta: S::from_f64(b),
                };
                let j = c.j2(ab);
                for x in j.iter().flatten() {
                    assert!(x.to_f64().is_finite(), "{} {ab:?} {j:?}", S::NAME);
                    assert!(x.to_f64().abs() <= bound, "{} {ab:?} {j:?}", S::NAME);
                }
            }
        }
        check::<f64>();
        check::<f32>();
        check::<I16F16>();
    }

    /// `singular` is `|det J| < DET_MIN`, strict and blind to the sign:
    /// diagonal and anti-diagonal matrices whose determinant is exactly
    /// `±DET_MIN` (one product with 1, so no rounding) are regular, half of
    /// it is singular.
    #[test]
    fn singular_is_strict_at_det_min_for_either_sign() {
        for (m, det, singular) in [
            ([[DET_MIN, 0.0], [0.0, 1.0]], DET_MIN, false),
            ([[0.0, DET_MIN], [1.0, 0.0]], -DET_MIN, false),
            ([[0.5 * DET_MIN, 0.0], [0.0, 1.0]], 0.5 * DET_MIN, true),
            ([[0.0, 0.5 * DET_MIN], [1.0, 0.0]], -0.5 * DET_MIN, true),
            ([[1.0, 2.0], [3.0, 4.0]], -2.0, false),
        ] {
            let j = Jacobian::<f64>::from_matrix(m);
            assert_eq!(j.m, m);
            assert_eq!(j.det, det, "{m:?}");
            assert_eq!(j.singular, singular, "{m:?}");
        }
    }

    /// `saturated` is set by each clamped or NaN input torque alone, in
    /// both directions of the mapping, and not by inputs within
    /// `±MAX_TORQUE` (the limits included); a clamped input maps as the
    /// limit itself, NaN as 0.
    #[test]
    fn saturated_is_set_by_each_clamped_or_nan_input_alone() {
        let p = WristParams::thesis();
        let fm = ForceMapping::<f64>::new(&p, JacobianKind::Exact);
        assert_eq!(fm.config(), &WristConfig::new(&p));
        let m = MotorAngles {
            theta1: 0.3,
            theta3: -1.2,
        };
        let (l, big, nan) = (MAX_TORQUE, 3.0 * MAX_TORQUE, f64::NAN);
        for (t, same_as, saturated) in [
            ([1.0, -2.0], [1.0, -2.0], false),
            ([l, -l], [l, -l], false),
            ([big, 1.0], [l, 1.0], true),
            ([1.0, -big], [1.0, -l], true),
            ([nan, 1.0], [0.0, 1.0], true),
            ([1.0, nan], [1.0, 0.0], true),
        ] {
            let (a, b) = (fm.motor_torques(m, t), fm.motor_torques(m, same_as));
            assert_eq!(a.saturated, saturated, "{t:?}");
            assert_eq!(a.torque, b.torque, "{t:?}");
            let (a, b) = (fm.task_torques(m, t), fm.task_torques(m, same_as));
            assert_eq!(a.saturated, saturated, "{t:?}");
            assert_eq!(a.torque, b.torque, "{t:?}");
        }
    }

    #[test]
    fn backends_agree_on_the_force_mapping() {
        let p = WristParams::thesis();
        let f64m = ForceMapping::<f64>::new(&p, JacobianKind::Exact);
        let f32m = ForceMapping::<f32>::new(&p, JacobianKind::Exact);
        let fxm = ForceMapping::<I16F16>::new(&p, JacobianKind::Exact);
        for &(t1, t3) in &[(0.3, -1.2), (2.0, -2.5), (-1.0, 0.2)] {
            let a = f64m.motor_torques(
                MotorAngles {
                    theta1: t1,
                    theta3: t3,
                },
                [1.0, -2.0],
            );
            let b = f32m.motor_torques(
                MotorAngles {
                    theta1: t1 as f32,
                    theta3: t3 as f32,
                },
                [1.0, -2.0],
            );
            let q = |x: f64| I16F16::from_f64(x);
            let cq = fxm.motor_torques(
                MotorAngles {
                    theta1: q(t1),
                    theta3: q(t3),
                },
                [q(1.0), q(-2.0)],
            );
            for k in 0..2 {
                assert!((a.torque[k] - b.torque[k] as f64).abs() < 1e-5);
                assert!(
                    (a.torque[k] - cq.torque[k].to_f64()).abs() < 2e-3,
                    "{k} {} {}",
                    a.torque[k],
                    cq.torque[k].to_f64()
                );
            }
        }
    }
}
