//! The simulated harmonic drive: a "true" transmission that is *not* the
//! estimator's model of eq. (2.30).
//!
//! Sign convention (thesis ch. 4, eq. 4.1–4.2): the motor angle `q_m` turns
//! `N` times the link angle `q_l` when rigid; the transmission torque `τ_t`
//! acts on the link (`+τ_t`) and on the rotor (`−τ_t/N`). The rigid torsion
//! is `δ = q_m/N − q_l` (positive when the motor leads). In the chapter-2
//! convention used by the estimator the link angle is `θ_fo = q_l`, the
//! motor angle `θ_wi = −q_m` (so that `θ_wi = −N θ_fo` when rigid,
//! eq. 2.4), the measured torsion is `Δθ = θ_fo + θ_wi/N = −δ`
//! (eq. 2.13) and the flexspline torque is `τ_f = −τ_t`.
//!
//! Elements, all derived from the SHD-17-100 numbers of thesis §2.4:
//!
//! 1. **Kinematic error** `θ_err(θ_fo, θ_wi)` of eq. (3.7) (Table 3.2): the
//!    measured torsion is the compliance torsion plus `θ_err` (eq. 3.8), so
//!    the torsion that loads the elastic parts is `δ_c = δ + θ_err`.
//! 2. **Elastic backbone**: the catalogue's piecewise-linear curve, eq. (2.11)
//!    (library [`CataloguePiecewise`], slopes `K1, K2, K3`, knees `T1, T2`),
//!    as torque from `δ_c`. `K3` is not in the thesis; the plant assumes
//!    `K3 = 1.3e4 N·m/rad` ([`SHD_17_100_K3`], our reading of the Harmonic
//!    Drive catalogue for size 17, ratio 100 — not checked against a
//!    catalogue copy here); the experiments stay below `T2 = 12 N·m`,
//!    where it plays no part.
//! 3. **Maxwell-slip hysteresis** in parallel with the backbone: `M`
//!    elasto-plastic elements `τ_i = clamp(k_i (δ_c − z_i), ±F_i)`. Their
//!    total slip torque is set by the catalogue's hysteresis loss: after
//!    loading to either side, the loop's width at zero torque is
//!    `2 ΣF / K1 = Ψ`, so `ΣF = K1 Ψ / 2` (1.218 N·m). The elements share
//!    it equally and their presliding displacements `F_i/k_i` are spread
//!    uniformly over `(0, Ψ/2]` — the thesis's bound on the wave generator's
//!    one-sided deformation (eq. 2.36).
//!
//! The generalized forces follow from the potential of the elastic parts as
//! functions of `δ_c(q_l, q_m)`, including the kinematic error's gradient,
//! so the plant is conservative when the hysteresis is switched off.

use crate::error::ParamError;
use crate::harmonic_drive::{
    kinematic_error::KinematicErrorModel, CatalogueData, CataloguePiecewise,
};

/// `K3` of the SHD-17-100 (N·m/rad) assumed by the plant (see the module
/// docs); the thesis gives only `K1`, `K2`, `T1`, `T2`.
pub const SHD_17_100_K3: f64 = 1.3e4;

/// One Maxwell-slip element: stiffness (N·m/rad) and slip torque (N·m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipElement {
    /// Presliding stiffness `k_i`, N·m/rad.
    pub stiffness: f64,
    /// Slip torque `F_i`, N·m.
    pub slip_torque: f64,
}

/// Parameters of the simulated transmission.
#[derive(Debug, Clone, PartialEq)]
pub struct DrivePlantParams {
    /// Gear ratio `N`.
    pub ratio: f64,
    /// Elastic backbone, eq. (2.11).
    pub backbone: CataloguePiecewise,
    /// Maxwell-slip elements (empty: purely elastic).
    pub slip_elements: Vec<SlipElement>,
    /// True kinematic error, eq. (3.7), or `None`.
    pub kinematic_error: Option<KinematicErrorModel>,
}

impl DrivePlantParams {
    /// The plant derived from catalogue data (see the module docs) with
    /// `elements` Maxwell-slip elements and an optional kinematic error.
    pub fn from_catalogue(
        data: &CatalogueData,
        k3: f64,
        elements: usize,
        kinematic_error: Option<KinematicErrorModel>,
    ) -> Result<Self, ParamError> {
        let backbone = CataloguePiecewise::try_new(data.k1, data.k2, k3, data.t1, data.t2)?;
        let total = data.k1 * data.hysteresis_loss / 2.0;
        let slip_elements = (1..=elements)
            .map(|i| {
                let f = total / elements as f64;
                let x = i as f64 / elements as f64 * data.hysteresis_loss / 2.0;
                SlipElement {
                    stiffness: f / x,
                    slip_torque: f,
                }
            })
            .collect();
        Ok(DrivePlantParams {
            ratio: data.ratio,
            backbone,
            slip_elements,
            kinematic_error,
        })
    }

    /// The SHD-17-100 of thesis §2.4 with 8 slip elements and the Table 3.2
    /// kinematic error.
    pub fn shd_17_100() -> Self {
        Self::from_catalogue(
            &CatalogueData::SHD_17_100,
            SHD_17_100_K3,
            8,
            Some(KinematicErrorModel::table_3_2()),
        )
        .expect("catalogue constants are valid")
    }

    /// The same without hysteresis and kinematic error (elastic backbone
    /// only).
    pub fn elastic(&self) -> Self {
        DrivePlantParams {
            slip_elements: Vec::new(),
            kinematic_error: None,
            ..self.clone()
        }
    }

    /// Total slip torque `ΣF_i`, N·m.
    pub fn total_slip_torque(&self) -> f64 {
        self.slip_elements.iter().map(|e| e.slip_torque).sum()
    }

    /// Small-amplitude stiffness at zero torque (backbone `K1` plus every
    /// element's `k_i`), N·m/rad.
    pub fn micro_stiffness(&self) -> f64 {
        self.backbone.local_stiffness(0.0)
            + self.slip_elements.iter().map(|e| e.stiffness).sum::<f64>()
    }

    /// Kinematic error `θ_err` (rad) and its partial derivatives with
    /// respect to `θ_fo` and `θ_wi`, eq. (3.7), at link angle `q_l` and
    /// motor angle `q_m` (chapter-4 angles).
    pub fn kinematic_error(&self, q_l: f64, q_m: f64) -> (f64, f64, f64) {
        match &self.kinematic_error {
            None => (0.0, 0.0, 0.0),
            Some(k) => {
                let c = &k.coefficients;
                let (sl, cl) = libm::sincos(q_l);
                let (s1, c1) = libm::sincos(-q_m);
                let (s2, c2) = (2.0 * s1 * c1, c1 * c1 - s1 * s1);
                let value = k.evaluate(q_l, -q_m);
                let d_link = -c[1] * sl + c[2] * cl;
                let d_motor = -c[3] * s1 + c[4] * c1 - 2.0 * c[5] * s2 + 2.0 * c[6] * c2;
                (value, d_link, d_motor)
            }
        }
    }

    /// Compliance torsion `δ_c = q_m/N − q_l + θ_err` (rad) and its partial
    /// derivatives `(∂δ_c/∂q_l, ∂δ_c/∂q_m)`: eq. (3.8) read backwards — the
    /// encoder torsion of eq. (2.13), `Δθ = q_l − q_m/N`, is the compliance
    /// torsion `−δ_c` plus the kinematic error of eq. (3.7).
    pub fn compliance_torsion(&self, q_l: f64, q_m: f64) -> (f64, f64, f64) {
        let (e, d_l, d_w) = self.kinematic_error(q_l, q_m);
        (
            q_m / self.ratio - q_l + e,
            -1.0 + d_l,
            1.0 / self.ratio - d_w,
        )
    }

    /// Transmission torque `τ_t` (N·m, on the link) at compliance torsion
    /// `δ_c` with slip anchors `z` (one per element): the inverse of the
    /// catalogue curve, eq. (2.11), plus the Maxwell-slip elements.
    pub fn torque(&self, delta_c: f64, anchors: &[f64]) -> f64 {
        let mut t = self.backbone.torque(delta_c);
        for (e, z) in self.slip_elements.iter().zip(anchors) {
            t += (e.stiffness * (delta_c - z)).clamp(-e.slip_torque, e.slip_torque);
        }
        t
    }

    /// Move the slip anchors after a step (plastic part of each element).
    pub fn update_anchors(&self, delta_c: f64, anchors: &mut [f64]) {
        for (e, z) in self.slip_elements.iter().zip(anchors.iter_mut()) {
            let x = e.slip_torque / e.stiffness;
            if delta_c - *z > x {
                *z = delta_c - x;
            } else if delta_c - *z < -x {
                *z = delta_c + x;
            }
        }
    }

    /// Elastic energy (J) of the backbone at torsion `δ_c` plus that stored
    /// in the slip elements: `∫₀^δ K(x) x dx` piecewise, and `τ_i²/(2k_i)`.
    pub fn elastic_energy(&self, delta_c: f64, anchors: &[f64]) -> f64 {
        let b = &self.backbone;
        let d = delta_c.abs();
        let (d1, d2) = (b.torsion_at_t1(), b.torsion_at_t2());
        let (t1, t2) = (b.torque(d1), b.torque(d2));
        let k1 = b.local_stiffness(0.0);
        let k2 = b.local_stiffness(0.5 * (t1 + t2));
        let k3 = b.local_stiffness(2.0 * t2);
        let mut v = 0.5 * k1 * d.min(d1).powi(2);
        if d > d1 {
            let x = d.min(d2) - d1;
            v += t1 * x + 0.5 * k2 * x * x;
        }
        if d > d2 {
            let x = d - d2;
            v += t2 * x + 0.5 * k3 * x * x;
        }
        for (e, z) in self.slip_elements.iter().zip(anchors) {
            let t = (e.stiffness * (delta_c - z)).clamp(-e.slip_torque, e.slip_torque);
            v += t * t / (2.0 * e.stiffness);
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The loop of the plant's compliance, driven quasi-statically by the
    /// torsion, has width Ψ at zero torque (independent: the backbone slope
    /// K1 and ΣF = K1 Ψ/2 give 2ΣF/K1 = Ψ).
    #[test]
    fn loop_width_at_zero_torque_is_psi() {
        let p = DrivePlantParams::shd_17_100();
        let psi = CatalogueData::SHD_17_100.hysteresis_loss;
        let mut z = vec![0.0; p.slip_elements.len()];
        // Load to +8 N·m worth of torsion, then sweep down and find where
        // the torque crosses zero.
        let amp = 1.0e-3;
        let steps = 20_000;
        let mut crossing_down = f64::NAN;
        let mut crossing_up = f64::NAN;
        let mut prev = (0.0, p.torque(0.0, &z));
        for k in 0..=4 * steps {
            let phase = k as f64 / steps as f64; // 0..4 quarter cycles
            let d = amp * (phase * core::f64::consts::FRAC_PI_2).sin();
            p.update_anchors(d, &mut z);
            let t = p.torque(d, &z);
            if k > steps && prev.1 > 0.0 && t <= 0.0 {
                crossing_down = prev.0 + (d - prev.0) * prev.1 / (prev.1 - t);
            }
            prev = (d, t);
        }
        for k in 0..=2 * steps {
            let phase = k as f64 / steps as f64;
            let d = -amp * (phase * core::f64::consts::FRAC_PI_2).cos();
            p.update_anchors(d, &mut z);
            let t = p.torque(d, &z);
            if prev.1 < 0.0 && t >= 0.0 {
                crossing_up = prev.0 + (d - prev.0) * (-prev.1) / (t - prev.1);
            }
            prev = (d, t);
        }
        let width = crossing_down - crossing_up;
        assert!((width - psi).abs() < 1e-3 * psi, "width {width}");
    }

    /// While every slip element sticks, the torque is the derivative of
    /// the stored energy (finite differences), so the generalized forces
    /// derived from it are conservative.
    #[test]
    fn torque_is_energy_gradient() {
        let p = DrivePlantParams::shd_17_100();
        for d in [-2e-3, -1e-4, 3e-5, 4e-4, 1.2e-3, 2.5e-3] {
            // Each element half-way to its slip torque.
            let z: Vec<f64> = p
                .slip_elements
                .iter()
                .map(|e| d - 0.5 * e.slip_torque / e.stiffness)
                .collect();
            let h = 1e-9;
            let fd = (p.elastic_energy(d + h, &z) - p.elastic_energy(d - h, &z)) / (2.0 * h);
            let t = p.torque(d, &z);
            assert!((fd - t).abs() < 1e-5 * (1.0 + t.abs()), "{d}: {fd} vs {t}");
        }
    }

    /// The analytic gradient of θ_err matches finite differences.
    #[test]
    fn kinematic_error_gradient() {
        let p = DrivePlantParams::shd_17_100();
        for (l, m) in [(0.3, 17.0), (-2.0, -150.0), (5.0, 2.0)] {
            let h = 1e-6;
            let (_, dl, dw) = p.kinematic_error(l, m);
            let fl = (p.kinematic_error(l + h, m).0 - p.kinematic_error(l - h, m).0) / (2.0 * h);
            // θ_wi = −q_m
            let fw = (p.kinematic_error(l, m - h).0 - p.kinematic_error(l, m + h).0) / (2.0 * h);
            assert!((dl - fl).abs() < 1e-9 && (dw - fw).abs() < 1e-9);
        }
    }
}
