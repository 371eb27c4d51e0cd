//! Figure data of thesis ch. 5, as plain arrays (`f64`, no allocation):
//! the workspace mapping of Fig. 5.7–5.8 (the inverse kinematics over a
//! `(δ, γ)` grid, eq. 5.14 and 5.15) and the α/β comparison of
//! Fig. 5.10–5.11 ([`alpha_beta_comparison`]).

pub use super::alpha_beta::{alpha_beta_comparison, AlphaBetaSample};
use super::kinematics::{PitchYaw, WristConfig, WristParams};

/// Which inverse-kinematics rule a workspace mapping uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MappingRule {
    /// Eq. (5.14) with `θ1, θ3` each from `atan2` in `(−π, π]` (Fig. 5.7).
    Principal,
    /// Eq. (5.15) as printed: `θ3 + 2π` when `θ1 + θ3 < −π/2` (the
    /// thesis's Fig. 5.8; in the frames that reproduce §5.2 it cuts the
    /// branch, errata E5.5).
    PrintedFix,
    /// The library's [`WristConfig::inverse`]: `θ1 + θ3` continuous.
    Library,
}

/// One point of the workspace mapping (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WorkspaceSample {
    /// Pitch `δ` (rad).
    pub delta: f64,
    /// Yaw `γ` (rad).
    pub gamma: f64,
    /// Whether the pose is in the workspace (else the motor angles are
    /// those of the saturated pose).
    pub reachable: bool,
    /// Motor angle `θ1` (rad).
    pub theta1: f64,
    /// Motor-2 side angle `θ3` (rad).
    pub theta3: f64,
}

/// Fig. 5.7–5.8: `(θ1, θ3)` over an `N × N` grid of
/// `δ, γ ∈ [−2φ, 2φ]` (rows `δ`, columns `γ`) by the chosen rule.
pub fn workspace_mapping<const N: usize>(
    p: &WristParams,
    rule: MappingRule,
) -> [[WorkspaceSample; N]; N] {
    let cfg = WristConfig::<f64>::new(p);
    let lim = p.max_bend();
    let pi = core::f64::consts::PI;
    let at = |k: usize| {
        if N > 1 {
            -lim + 2.0 * lim * k as f64 / (N - 1) as f64
        } else {
            0.0
        }
    };
    let mut out = [[WorkspaceSample::default(); N]; N];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, s) in row.iter_mut().enumerate() {
            let (delta, gamma) = (at(i), at(j));
            let r = cfg.inverse(PitchYaw { delta, gamma });
            let (t1, mut t3) = (r.motors.theta1, r.motors.theta3);
            match rule {
                MappingRule::Library => {}
                MappingRule::Principal | MappingRule::PrintedFix => {
                    // Each angle on its own principal branch.
                    t3 = libm::atan2(libm::sin(t3), libm::cos(t3));
                    if rule == MappingRule::PrintedFix && t1 + t3 < -pi / 2.0 {
                        t3 += 2.0 * pi;
                    }
                }
            }
            *s = WorkspaceSample {
                delta,
                gamma,
                reachable: p.is_reachable(delta, gamma),
                theta1: t1,
                theta3: t3,
            };
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Count grid neighbours whose `θ1 + θ3` differ by more than 1 rad:
    /// the library's rule has none; the principal branches and the
    /// printed fix have some.
    #[test]
    fn only_the_library_rule_keeps_the_sum_continuous() {
        let p = WristParams::thesis();
        let jumps = |rule| {
            let g = workspace_mapping::<41>(&p, rule);
            let mut n = 0;
            for i in 0..41 {
                for j in 0..41 {
                    let a = g[i][j];
                    for b in [g.get(i + 1).map(|r| r[j]), g[i].get(j + 1).copied()]
                        .into_iter()
                        .flatten()
                    {
                        if a.reachable
                            && b.reachable
                            && ((a.theta1 + a.theta3) - (b.theta1 + b.theta3)).abs() > 1.0
                        {
                            n += 1;
                        }
                    }
                }
            }
            n
        };
        assert_eq!(jumps(MappingRule::Library), 0);
        assert!(jumps(MappingRule::Principal) > 0);
        assert!(jumps(MappingRule::PrintedFix) > 0);
    }
}
