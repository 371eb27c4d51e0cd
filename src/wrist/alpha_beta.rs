//! The polar (α, β) description of the wrist, thesis eq. (5.16)–(5.21).
//!
//! `β ∈ [0, 2φ]` is the bend of the output axis from the base `z` axis
//! (rad) and `α` its direction (rad), defined as in eq. (5.16)–(5.19) by
//! the third row of the orientation: `t31 = −cos α sin β`,
//! `t32 = sin α sin β`, `t33 = cos β`. Eq. (5.16) is the product
//! `R = R_z(−α′) R_y(β) R_z(α)` (the order that yields the printed
//! matrix), with `α′` read from the third column.
//!
//! * Exact, eq. (5.17)–(5.19): `β = acos(C4 Sφ² + Cφ²)` (printed with `C2`,
//!   errata E5.6), evaluated as `2 asin(Sφ |sin(θ4/2)|)`, and
//!   `α = atan2(t32, −t31)`, eq. (5.19) (correct as printed). Eq. (5.18)
//!   repeats the forward-kinematics root, eq. (5.12).
//! * Ryew–Choi, eq. (5.20)–(5.21): the printed eq. (5.21) has the wrong
//!   offsets for the thesis's own zero (errata E5.7). In the frames of
//!   [`super::kinematics`], eq. (5.20) with `θ1 ← −θ1 − π/2`,
//!   `θ3 ← θ3 + π/2` reads
//!
//!   ```text
//!   α ≈ (θ3 − θ1)/2 + π,
//!   β ≈ −2 atan(tan φ · sin((θ1 + θ3)/2)),
//!   ```
//!
//!   a signed bend (a negative `β` is the bend `|β|` in direction
//!   `α + π`); [`WristConfig::alpha_beta_approx`] returns it normalized.
//!   Over the reachable poses with `|δ|, |γ| ≤ 30°` its bend differs from
//!   the exact one by at most 0.0088 rad = 1.6 % of `2φ`, its direction by
//!   0.040 rad (1.3 % of π; for `β > 0.05`), and the bend vector
//!   `β(cos α, sin α)` by 0.023 rad = 4.0 % of `2φ`
//!   (`tests::ryew_choi_error_over_the_workspace`): the thesis's "less
//!   than 2 %" holds for `β` and `α` of this corrected form, not for the
//!   pose they describe together.

use super::kinematics::{denan, hypot, wrap, MotorAngles, PitchYaw, WristConfig, WristParams};
use crate::scalar::Scalar;

/// A polar description of the pose: direction `alpha ∈ (−π, π]` and bend
/// `beta ∈ [0, π]` of the output axis (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AlphaBeta<S> {
    /// Direction `α` (rad), eq. (5.19).
    pub alpha: S,
    /// Bend `β ≥ 0` (rad), eq. (5.17).
    pub beta: S,
}

impl<S: Scalar> WristConfig<S> {
    /// Exact `(α, β)` of the motor angles (rad), eq. (5.17)–(5.19).
    pub fn alpha_beta(&self, m: MotorAngles<S>) -> AlphaBeta<S> {
        let f = self.forward(m);
        let (s3, c3) = denan(m.theta3).sin_cos();
        let (s4, c4) = f.theta4.sin_cos();
        let cp = self.cos_phi;
        // Eq. (5.19).
        let y = s4.mul(s3).neg().sub(c3.mul(cp)).add(c4.mul(c3).mul(cp));
        let x = c4.mul(s3).mul(cp).neg().add(s3.mul(cp)).sub(s4.mul(c3));
        // Eq. (5.17): cos β = C4 Sφ² + Cφ², i.e. sin(β/2) = Sφ |sin(θ4/2)|.
        let two = S::ONE.add(S::ONE);
        let sb = self.sin_phi.mul(f.theta4.div(two).sin().abs());
        AlphaBeta {
            alpha: y.atan2(x),
            beta: two.mul(sb.atan2(S::ONE.sub(sb.mul(sb)).sqrt())),
        }
    }

    /// Exact `(α, β)` of a pose (rad): `α = atan2(cos δ sin γ, sin δ)`,
    /// `sin(β/2) = |(sin(δ/2), √cos δ sin(γ/2))|`.
    pub fn alpha_beta_of_pose(&self, p: PitchYaw<S>) -> AlphaBeta<S> {
        let half_pi = S::FRAC_PI_2;
        let d = denan(p.delta).clamp(half_pi.neg(), half_pi);
        let g = denan(p.gamma).clamp(half_pi.neg(), half_pi);
        let (sd, cd) = d.sin_cos();
        let sg = g.sin();
        let two = S::ONE.add(S::ONE);
        let half = S::ONE.div(two);
        let sb = hypot(d.mul(half).sin(), cd.sqrt().mul(g.mul(half).sin())).min(S::ONE);
        AlphaBeta {
            alpha: cd.mul(sg).atan2(sd),
            beta: two.mul(sb.atan2(S::ONE.sub(sb.mul(sb)).sqrt())),
        }
    }

    /// The pose of a polar description (rad): `sin δ = cos α sin β`,
    /// `tan γ = sin α tan β` (the third row of eq. 5.6 against eq. 5.16).
    pub fn pose_of_alpha_beta(&self, ab: AlphaBeta<S>) -> PitchYaw<S> {
        let (sa, ca) = denan(ab.alpha).sin_cos();
        let (sb, cb) = denan(ab.beta).sin_cos();
        let sd = ca.mul(sb);
        PitchYaw {
            delta: sd.atan2(hypot(sa.mul(sb), cb)),
            gamma: sa.mul(sb).atan2(cb),
        }
    }

    /// Ryew–Choi's approximation, eq. (5.20)–(5.21) corrected (errata
    /// E5.7), normalized to `β ≥ 0`, `α ∈ (−π, π]` (rad).
    pub fn alpha_beta_approx(&self, m: MotorAngles<S>) -> AlphaBeta<S> {
        let two = S::ONE.add(S::ONE);
        let t1 = wrap_turns(denan(m.theta1));
        let t3 = wrap_turns(denan(m.theta3));
        // Eq. (5.21) corrected: signed β.
        let signed = two
            .mul(self.tan_phi.mul(t1.add(t3).div(two).sin()).atan())
            .neg();
        let alpha = wrap(t3.sub(t1).div(two).add(S::PI));
        if signed < S::ZERO {
            AlphaBeta {
                alpha: wrap(alpha.add(S::PI)),
                beta: signed.neg(),
            }
        } else {
            AlphaBeta {
                alpha,
                beta: signed,
            }
        }
    }
}

/// `x` reduced to `[−π, π]` for any `x`, through `(sin x, cos x)`.
fn wrap_turns<S: Scalar>(x: S) -> S {
    let (s, c) = x.sin_cos();
    s.atan2(c)
}

/// One sample of the α/β comparison of Fig. 5.10–5.11 (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AlphaBetaSample {
    /// Motor 1 angle `θ1` (rad).
    pub theta1: f64,
    /// Motor 2 side angle `θ3` (rad).
    pub theta3: f64,
    /// Exact direction, eq. (5.19).
    pub alpha_exact: f64,
    /// Exact bend, eq. (5.17).
    pub beta_exact: f64,
    /// Direction by eq. (5.21) corrected.
    pub alpha_approx: f64,
    /// Bend by eq. (5.21) corrected.
    pub beta_approx: f64,
}

/// Figure data for Fig. 5.10–5.11: exact and approximate `(α, β)` on an
/// `N × N` grid of the motor strip that reaches every pose,
/// `θ1 + θ3 ∈ [−π, 0]` (rows) by `θ1 − θ3 ∈ [−π, π]` (columns).
pub fn alpha_beta_comparison<const N: usize>(p: &WristParams) -> [[AlphaBetaSample; N]; N] {
    let cfg = WristConfig::<f64>::new(p);
    let pi = core::f64::consts::PI;
    let step = |k: usize| {
        if N > 1 {
            k as f64 / (N - 1) as f64
        } else {
            0.5
        }
    };
    let mut out = [[AlphaBetaSample::default(); N]; N];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, s) in row.iter_mut().enumerate() {
            let u = -pi * step(i);
            let w = -pi + 2.0 * pi * step(j);
            let m = MotorAngles {
                theta1: 0.5 * (u + w),
                theta3: 0.5 * (u - w),
            };
            let e = cfg.alpha_beta(m);
            let a = cfg.alpha_beta_approx(m);
            *s = AlphaBetaSample {
                theta1: m.theta1,
                theta3: m.theta3,
                alpha_exact: e.alpha,
                beta_exact: e.beta,
                alpha_approx: a.alpha,
                beta_approx: a.beta,
            };
        }
    }
    out
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::kinematics::tests::{chain, dist, mul, ry, rz};
    use super::*;
    use core::f64::consts::PI;
    use proptest::prelude::*;

    fn cfg() -> WristConfig<f64> {
        WristConfig::new(&WristParams::thesis())
    }

    /// Eq. (5.16) as a product of rotations reproduces the chain of
    /// eq. (5.4) with α, β from eq. (5.17)/(5.19) and α′ from the third
    /// column; β agrees with the printed acos form (C4 for C2).
    fn rotation_identity_holds(t1: f64, t3: f64) -> Result<(), TestCaseError> {
        let c = cfg();
        let m = MotorAngles {
            theta1: t1,
            theta3: t3,
        };
        let f = c.forward(m);
        let ab = c.alpha_beta(m);
        let r = chain(c.phi(), t1, f.theta4, t3);
        prop_assume!(ab.beta > 1e-6);
        let alpha_p = (-r[1][2]).atan2(r[0][2]);
        let r516 = mul(&mul(&rz(-alpha_p), &ry(ab.beta)), &rz(ab.alpha));
        // α and α′ are directions of vectors of length O(β) (eq. 5.19
        // and the third column) whose components carry O(ε) rounding,
        // so each is off by O(ε/β): near the straight pose the product
        // is good to that, not to 1e-12 (β = 2.6e-5 gives 1.75e-12).
        let tol = 1e-12 + 16.0 * f64::EPSILON / ab.beta;
        prop_assert!(
            dist(&r, &r516) < tol,
            "{} > {} at beta {}",
            dist(&r, &r516),
            tol,
            ab.beta
        );
        let (sp, cp) = c.phi().sin_cos();
        let beta_517 = (f.theta4.cos() * sp * sp + cp * cp).clamp(-1.0, 1.0).acos();
        prop_assert!((beta_517 - ab.beta).abs() < 1e-7);
        // Pose ↔ (α, β) agree both ways.
        let ab2 = c.alpha_beta_of_pose(f.pose);
        prop_assert!((ab2.beta - ab.beta).abs() < 1e-12);
        prop_assert!((wrap(ab2.alpha - ab.alpha)).abs() < 1e-9 / ab.beta);
        let p = c.pose_of_alpha_beta(ab);
        prop_assert!(
            (p.delta - f.pose.delta).abs() < 1e-12 && (p.gamma - f.pose.gamma).abs() < 1e-12
        );
        Ok(())
    }

    proptest! {
        #[test]
        fn exact_alpha_beta_satisfy_the_rotation_identity(t1 in -4.0f64..4.0, t3 in -4.0f64..4.0) {
            rotation_identity_holds(t1, t3)?;
        }
    }

    /// Inputs near the straight pose (β ≈ 1e-5) where a 1e-12 tolerance
    /// without the ε/β term failed (1.75e-12 and 3.5e-12).
    #[test]
    fn rotation_identity_near_the_straight_pose() {
        for (t1, t3) in [
            (2.8201941531737216, 3.4629016675734183),
            (-3.376756588525684, 3.3768210031516803),
        ] {
            rotation_identity_holds(t1, t3).unwrap();
        }
    }

    /// The "less than 2 %" claim: the corrected eq. (5.21) against the
    /// exact (α, β) over every reachable pose with |δ|, |γ| ≤ 30° (via the
    /// inverse kinematics), and over the whole motor strip.
    #[test]
    fn ryew_choi_error_over_the_workspace() {
        let p = WristParams::thesis();
        let c = cfg();
        let lim = 30f64.to_radians();
        let (mut eb, mut ea, mut ev) = (0.0f64, 0.0f64, 0.0f64);
        let (mut reach, mut total) = (0usize, 0usize);
        let n = 121;
        for i in 0..n {
            for j in 0..n {
                let d = -lim + 2.0 * lim * i as f64 / (n - 1) as f64;
                let g = -lim + 2.0 * lim * j as f64 / (n - 1) as f64;
                total += 1;
                if !p.is_reachable(d, g) {
                    continue;
                }
                reach += 1;
                let m = c.inverse(PitchYaw { delta: d, gamma: g }).motors;
                let e = c.alpha_beta(m);
                let a = c.alpha_beta_approx(m);
                eb = eb.max((e.beta - a.beta).abs());
                if e.beta > 0.05 {
                    ea = ea.max(wrap(e.alpha - a.alpha).abs());
                }
                // Bend vectors (β cos α, β sin α): no 0/0 at the straight pose.
                let dv = (e.beta * e.alpha.cos() - a.beta * a.alpha.cos())
                    .hypot(e.beta * e.alpha.sin() - a.beta * a.alpha.sin());
                ev = ev.max(dv);
            }
        }
        let cover = reach as f64 / total as f64;
        std::println!(
            "Ryew-Choi vs exact over |delta|,|gamma| <= 30 deg: max |dbeta| = {eb:.5} rad = {:.2} % of 2phi, max |dalpha| (beta > 0.05) = {ea:.4} rad, max bend-vector error = {ev:.5} rad; reachable share of the +-30 deg square = {:.1} %",
            100.0 * eb / p.max_bend(),
            100.0 * cover
        );
        assert!(eb / p.max_bend() < 0.02, "{eb}");
        assert!(eb / p.max_bend() > 0.01, "{eb}");
        assert!(ea < 0.05 && ea > 0.02, "{ea}");
        assert!(ev < 0.03 && ev > 0.01, "{ev}");
        // The square is not inside the workspace: its corners bend 41.4°.
        assert!(cover < 0.9 && cover > 0.6, "{cover}");
    }

    #[test]
    fn printed_eq_5_21_is_off_by_the_zero_offsets() {
        // As printed, β = 2 atan(tan φ cos((θ1+θ3)/2)) gives the largest
        // bend 2φ at the straight pose θ1 = θ3 = 0, and α = (θ1 − θ3)/2.
        let c = cfg();
        let m = MotorAngles {
            theta1: 0.0,
            theta3: 0.0,
        };
        let printed_beta = 2.0 * (c.phi().tan() * 0.0f64.cos()).atan();
        assert!((printed_beta - 2.0 * c.phi()).abs() < 1e-15);
        assert!(c.alpha_beta(m).beta.abs() < 1e-15);
        assert!(c.alpha_beta_approx(m).beta.abs() < 1e-15);
        // Away from the straight pose the printed α is mirrored: exact
        // α ≈ π − (θ1 − θ3)/2.
        let m = MotorAngles {
            theta1: 0.2,
            theta3: -1.5,
        };
        let e = c.alpha_beta(m);
        let printed_alpha = (m.theta1 - m.theta3) / 2.0;
        assert!(wrap(e.alpha - printed_alpha).abs() > 1.0);
        assert!(wrap(e.alpha - (PI - printed_alpha)).abs() < 0.05);
    }

    #[test]
    fn figure_data_is_finite_and_matches_the_maps() {
        let data = alpha_beta_comparison::<9>(&WristParams::thesis());
        let c = cfg();
        for row in &data {
            for s in row {
                let m = MotorAngles {
                    theta1: s.theta1,
                    theta3: s.theta3,
                };
                assert_eq!(c.alpha_beta(m).beta, s.beta_exact);
                assert!(
                    s.beta_exact <= 2.0 * c.phi() + 1e-12 && s.beta_approx <= 2.0 * c.phi() + 1e-12
                );
            }
        }
        assert!((data[8][0].beta_exact - 2.0 * c.phi()).abs() < 1e-9);
        assert!(data[0][3].beta_exact.abs() < 1e-12);
    }
}
