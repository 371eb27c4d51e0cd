//! Friction with stiction for fixed-step simulation: an elasto-plastic
//! (single Maxwell-slip) element whose sliding level is the Coulomb +
//! static + Stribeck law of eq. (4.7)/(4.8), plus viscous friction.
//!
//! A plain `sgn(q̇)` law cannot hold a joint at rest under a torque below
//! the breakaway level in a fixed-step integrator, and a smoothed one lets
//! it creep. The elasto-plastic element instead has a presliding spring
//! (stiffness `σ0`, damping `σ1`) that sticks until its torque reaches the
//! sliding level, then slips at that level:
//!
//! `f = clamp(σ0 (q − z) + σ1 q̇, ±F(q̇)) + b q̇`,
//! `F(q̇) = f_c + f_s e^{−f_τ q̇²}` (the bracket of eq. 4.7/4.8),
//!
//! and after each integration step the anchor `z` is moved so that
//! `|σ0 (q − z)| ≤ F(q̇)`. In steady sliding this is exactly eq. (4.8)
//! without its position term `f_q`; at rest it holds any torque up to the
//! breakaway level `f_c + f_s`.

/// Parameters of one friction element (rotary, SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionParams {
    /// Coulomb level `f_c`, N·m.
    pub coulomb: f64,
    /// Static excess `f_s` (breakaway = `f_c + f_s`), N·m.
    pub static_excess: f64,
    /// Stribeck coefficient `f_τ`, s²/rad².
    pub stribeck: f64,
    /// Viscous coefficient `b`, N·m·s/rad.
    pub viscous: f64,
    /// Presliding displacement at breakaway (rad): `σ0 = (f_c + f_s) / x_p`.
    pub presliding: f64,
    /// Presliding damping `σ1`, N·m·s/rad.
    pub presliding_damping: f64,
}

impl FrictionParams {
    /// No friction at all.
    pub const NONE: FrictionParams = FrictionParams {
        coulomb: 0.0,
        static_excess: 0.0,
        stribeck: 0.0,
        viscous: 0.0,
        presliding: 1.0,
        presliding_damping: 0.0,
    };

    /// Only viscous friction `b q̇`.
    pub fn viscous(b: f64) -> Self {
        FrictionParams {
            viscous: b,
            ..Self::NONE
        }
    }

    /// Breakaway torque `f_c + f_s`, N·m.
    pub fn breakaway(&self) -> f64 {
        self.coulomb + self.static_excess
    }

    /// Sliding level `F(q̇) = f_c + f_s e^{−f_τ q̇²}` (eq. 4.7/4.8).
    pub fn sliding_level(&self, speed: f64) -> f64 {
        crate::friction::FrictionParams {
            viscous: self.viscous,
            coulomb: self.coulomb,
            stribeck: self.static_excess,
            stribeck_shape: self.stribeck,
        }
        .sliding_level(speed)
    }

    /// Presliding stiffness `σ0`, N·m/rad.
    pub fn presliding_stiffness(&self) -> f64 {
        if self.breakaway() > 0.0 {
            self.breakaway() / self.presliding
        } else {
            0.0
        }
    }

    /// Friction torque (N·m, opposing motion) at position `q`, speed `v`,
    /// with anchor `z`.
    pub fn torque(&self, q: f64, v: f64, z: f64) -> f64 {
        let lim = self.sliding_level(v);
        let elastic = self.presliding_stiffness() * (q - z) + self.presliding_damping * v;
        elastic.clamp(-lim, lim) + self.viscous * v
    }

    /// Move the anchor after a step so the element is at most at its
    /// sliding level (the plastic part of the element).
    pub fn update_anchor(&self, q: f64, v: f64, z: &mut f64) {
        let s0 = self.presliding_stiffness();
        if s0 <= 0.0 {
            *z = q;
            return;
        }
        let lim = self.sliding_level(v);
        let e = s0 * (q - *z);
        if e > lim {
            *z = q - lim / s0;
        } else if e < -lim {
            *z = q + lim / s0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> FrictionParams {
        FrictionParams {
            coulomb: 0.010,
            static_excess: 0.002,
            stribeck: 1.0,
            viscous: 1e-4,
            presliding: 1e-3,
            presliding_damping: 0.0,
        }
    }

    /// Steady sliding reproduces eq. (4.8) (without f_q): after the anchor
    /// has been dragged along, the torque is F(v) sgn(v) + b v.
    #[test]
    fn steady_sliding_is_eq_4_8() {
        let f = p();
        for v in [-3.0, -0.5, 0.2, 2.0] {
            let mut z = 0.0;
            let mut q = 0.0;
            for _ in 0..1000 {
                q += v * 1e-3;
                f.update_anchor(q, v, &mut z);
            }
            let want = (0.010 + 0.002 * (-v * v).exp()) * v.signum() + 1e-4 * v;
            assert!((f.torque(q, v, z) - want).abs() < 1e-12, "v = {v}");
        }
    }

    /// At rest the element holds a displacement below x_p elastically and
    /// caps the torque at the breakaway level beyond it.
    #[test]
    fn sticks_below_breakaway() {
        let f = p();
        let mut z = 0.0;
        f.update_anchor(0.5e-3, 0.0, &mut z);
        assert_eq!(z, 0.0);
        assert!((f.torque(0.5e-3, 0.0, z) - 0.006).abs() < 1e-15);
        f.update_anchor(3e-3, 0.0, &mut z);
        assert!((f.torque(3e-3, 0.0, z) - 0.012).abs() < 1e-15);
        assert!((z - 2e-3).abs() < 1e-15);
    }
}
