//! Thesis ch. 2–3 experiments reproduced in simulation, and the checks
//! that the simulated robot behaves (energy, static deflection).
//!
//! Every threshold is derived in the test's comment from catalogue numbers,
//! encoder resolutions or the integrator's known error; none is tuned to
//! the measured value.
#![cfg(feature = "sim")]

use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::sim::experiments::{
    back_driven, locked_output, torque_estimation, width_at_zero, BackDrivenConfig,
    LockedOutputConfig, Models, TorqueEstimationConfig, ESTIMATORS,
};
use mrr_control::sim::experiments::{model_ranking, PlantStructure, RankingRow};
use mrr_control::sim::experiments::{ComplianceResult, TorqueEstimationResult};
use mrr_control::sim::integrator::rk4_energy_loss_per_step;
use mrr_control::sim::mrr::misaligned;
use mrr_control::sim::transmission::SHD_17_100_K3;
use mrr_control::sim::{Backbone, BackboneShape, FrictionParams, ModuleParams, Mrr, Sensors};
use std::sync::OnceLock;

const SHD: CatalogueData = CatalogueData::SHD_17_100;

fn locked() -> &'static mrr_control::sim::experiments::ComplianceResult {
    static R: OnceLock<mrr_control::sim::experiments::ComplianceResult> = OnceLock::new();
    R.get_or_init(|| locked_output(&LockedOutputConfig::default()))
}

fn estimation() -> &'static mrr_control::sim::experiments::TorqueEstimationResult {
    static R: OnceLock<mrr_control::sim::experiments::TorqueEstimationResult> = OnceLock::new();
    R.get_or_init(|| {
        torque_estimation(&TorqueEstimationConfig {
            duration: 4.0,
            ..TorqueEstimationConfig::default()
        })
    })
}

/// The energy the plant dissipates in its hysteresis (loop integral of the
/// true torque over the compliance torsion, minus the change of stored
/// energy) equals the Maxwell-slip law applied to the recorded reversals.
/// Bound: the 1 ms trapezoid sampling misplaces each reversal by at most
/// one sample, i.e. `ΣF · |δ̇|max · T_s` per half cycle and twice that for
/// the loop; `|δ̇|max ≤ 2π f δ_max` with `δ_max` the catalogue torsion at
/// the peak load `N · 0.12 N·m`, and there are `2 f D` half cycles.
#[test]
fn hysteresis_dissipation_matches_maxwell_slip_law() {
    let r = locked();
    let cfg = LockedOutputConfig::default();
    let models = Models::shd_17_100();
    let sum_f = SHD.k1 * SHD.hysteresis_loss / 2.0;
    let delta_max = models.piecewise.torsion(SHD.ratio * cfg.amplitude);
    let per_half =
        2.0 * sum_f * core::f64::consts::TAU * cfg.frequency * delta_max * cfg.control_period;
    let bound = per_half * 2.0 * cfg.frequency * cfg.duration;
    let diff = (r.loop_energy - r.maxwell_slip_energy).abs();
    assert!(r.maxwell_slip_energy > 0.0);
    assert!(
        diff <= bound,
        "loop {} J, law {} J, bound {bound}",
        r.loop_energy,
        r.maxwell_slip_energy
    );
}

/// The same energy check in the back-driven experiment (link free, driven
/// by 10 N·m at 0.25 Hz decreasing over 20 s; motor held), with the bound
/// built the same way from its amplitude and frequency.
#[test]
fn back_driven_dissipation_matches_maxwell_slip_law() {
    let cfg = BackDrivenConfig::default();
    let r = back_driven(&cfg).compliance;
    let models = Models::shd_17_100();
    let sum_f = SHD.k1 * SHD.hysteresis_loss / 2.0;
    let delta_max = models.piecewise.torsion(cfg.amplitude);
    let per_half =
        2.0 * sum_f * core::f64::consts::TAU * cfg.frequency * delta_max * cfg.control_period;
    let bound = per_half * 2.0 * cfg.frequency * cfg.duration;
    let diff = (r.loop_energy - r.maxwell_slip_energy).abs();
    assert!(r.maxwell_slip_energy > 0.0);
    assert!(
        diff <= bound,
        "loop {} J, law {} J, bound {bound}",
        r.loop_energy,
        r.maxwell_slip_energy
    );
}

/// Loop width at zero *input* torque: after unloading, the stuck motor
/// friction (breakaway `τ_fs` = 1.2 N·cm) leaves `N τ_fs` on the
/// transmission and the slip elements another `ΣF = K1 Ψ/2`, so on the
/// backbone's first slope the torsion sits at `±(N τ_fs + ΣF)/K1`: width
/// `2(N τ_fs + ΣF)/K1 = Ψ + 2Nτ_fs/K1`. The measured torsion at a crossing
/// is quantized by half a link count plus half a motor count (output side)
/// for each of the two means.
#[test]
fn locked_output_loop_width_is_catalogue_loss_plus_motor_friction() {
    let r = locked();
    let m = ModuleParams::thesis_joint();
    let n = SHD.ratio;
    let expected = 2.0 * (n * SHD.starting_torque + SHD.k1 * SHD.hysteresis_loss / 2.0) / SHD.k1;
    let q = m.link_encoder.rad_per_count() / 2.0 + m.motor_encoder.rad_per_count() / (2.0 * n);
    let w = width_at_zero(
        &r.samples,
        |s| -s.wave_generator_torque,
        |s| s.measured_torsion,
        0.0,
        6.0,
    );
    assert!(
        (w - expected).abs() <= 2.0 * q,
        "width {w}, expected {expected} ± {}",
        2.0 * q
    );
}

/// Eq. (2.30) identified from the catalogue by eq. (2.33)–(2.37) lies
/// above the catalogue curve it was identified from: for `|τ_w| ≫ 1/c_w`
/// the wave-generator term adds its full `Ψ/2`, on top of a flexspline
/// curve that already matches the catalogue's slopes (the catalogue curve
/// is the torsion of the whole drive). Hand numbers at τ_f = 10 N·m:
/// catalogue `3.9/8400 + 6.1/9400 = 1.1132e-3` rad; eq. (2.26)
/// `atan(0.44940)/374.615 = 1.1274e-3` rad; plus `Ψ/2 (1 − e^{−8.33})
/// = 1.450e-4` rad: 1.2724e-3 rad, 14 % above the catalogue.
#[test]
fn eq_2_30_exceeds_its_catalogue_curve_by_half_the_hysteresis_loss() {
    let m = Models::shd_17_100();
    let tau = 10.0;
    let proposed = m.proposed.torsion(tau, -tau / SHD.ratio);
    let catalogue = m.piecewise.torsion(tau);
    assert!((catalogue - (3.9 / 8400.0 + 6.1 / 9400.0)).abs() < 1e-12);
    let hand =
        (0.04494f64 * 10.0).atan() / (0.04494 * 8335.98) + 1.45e-4 * (1.0 - (-8.333f64).exp());
    assert!((proposed - hand).abs() < 2e-7, "{proposed} vs {hand}");
    assert!(proposed - catalogue > SHD.hysteresis_loss / 2.0);
    // At zero torque the two compliances add: slope 1/K_f0 + 1/(N² K_w0),
    // and N² K_w0 = 2 N τ_fs/Ψ = 8276 N·m/rad is itself close to K1, so
    // the model's stiffness there (4153 N·m/rad) is half the catalogue's K1.
    let h = 1e-3;
    let fd =
        (m.proposed.torsion(h, -h / SHD.ratio) - m.proposed.torsion(-h, h / SHD.ratio)) / (2.0 * h);
    let hand = 1.0 / 8335.98 + 1.0 / (100.0 * 100.0 * 0.024 / 0.029);
    assert!((fd - hand).abs() < 1e-3 * hand, "{fd} vs {hand}");
    assert!(
        (1.0 / fd - SHD.k1 / 2.0).abs() < 0.02 * SHD.k1,
        "{}",
        1.0 / fd
    );
}

/// Locked-output comparison of the models (thesis Fig. 2.19–2.20 claim the
/// proposed model is better: ±1.7e-4 against ±2.3e-4 rad). On a plant whose
/// loop is centred on the catalogue curve (width Ψ, derived from the
/// catalogue) the proposed model carries the `≥ Ψ/2` offset of the test
/// above at high torque, so its RMS error exceeds the catalogue model's;
/// and both classic models, fed with the measured output torque, see the
/// friction part of the loop that eq. (2.30) attributes to the wave
/// generator. This asserts that derived ordering — the opposite of the
/// thesis's finding — so a change of plant or model that reverses it shows.
#[test]
fn locked_output_model_ranking_on_a_catalogue_centred_plant() {
    let r = locked();
    assert!(
        r.proposed.rms > r.piecewise.rms,
        "{:?} vs {:?}",
        r.proposed,
        r.piecewise
    );
    assert!(r.proposed.rms > r.cubic.rms);
    // Every model error stays within the plant's loop half width plus the
    // model's offset from the catalogue at the peak load and the encoder
    // quantization: a gross error (a sign slip) would exceed it.
    let m = Models::shd_17_100();
    let tau = SHD.ratio * LockedOutputConfig::default().amplitude;
    let offset = m.proposed.torsion(tau, -tau / SHD.ratio) - m.piecewise.torsion(tau);
    let half_width = SHD.hysteresis_loss / 2.0 + SHD.ratio * SHD.starting_torque / SHD.k1;
    let q = 4.8e-5 / 2.0 + 3.15e-5 / 2.0;
    for e in [r.proposed, r.piecewise, r.cubic] {
        assert!(
            e.max.abs().max(e.min.abs()) <= 2.0 * half_width + offset + q,
            "{e:?}"
        );
    }
}

/// Table 3.3: the kinematic-error model (Table 3.2, or fitted from two
/// calibration revolutions) lowers the RMS estimation error over all
/// torque levels, on both backends.
#[test]
fn kinematic_error_model_reduces_estimation_error() {
    let r = estimation();
    let rms = |name: &str| r.overall[ESTIMATORS.iter().position(|e| *e == name).unwrap()].rms;
    for backend in ["f64", "I16F16"] {
        let without = rms(&format!("{backend}, no KE"));
        let table = rms(&format!("{backend}, KE Table 3.2"));
        let fitted = rms(&format!("{backend}, KE fitted"));
        assert!(
            table < without && fitted < without,
            "{backend}: {without} {table} {fitted}"
        );
    }
    assert!(r.levels.iter().all(|l| !l.saturated));
}

/// The wave-generator term of eq. (3.9) adds, for `|τ_w| ≫ 1/c_w`, the
/// torsion `Ψ/2` that the catalogue curve (on which the plant's loop is
/// centred) does not have, so it biases every estimate by about
/// `K Ψ/2` ≈ 1.2–1.4 N·m against the direction of the load. Switching it
/// off (`τ_w = 0`) must then lower the RMS error; the thesis's Table 3.3
/// assumes the opposite.
#[test]
fn wave_generator_term_biases_the_estimate_on_a_catalogue_centred_plant() {
    let r = estimation();
    let idx = |name: &str| ESTIMATORS.iter().position(|e| *e == name).unwrap();
    let with = r.overall[idx("f64, KE fitted")].rms;
    let without = r.overall[idx("f64, KE fitted, tau_w = 0")].rms;
    assert!(without < with, "{without} vs {with}");
}

/// The locked-output and Table 3.3 runs (the configurations above) on a
/// plant built on each backbone shape.
fn per_backbone() -> &'static [(BackboneShape, ComplianceResult, TorqueEstimationResult)] {
    static R: OnceLock<Vec<(BackboneShape, ComplianceResult, TorqueEstimationResult)>> =
        OnceLock::new();
    R.get_or_init(|| {
        BackboneShape::ALL
            .iter()
            .map(|&shape| {
                let a = locked_output(&LockedOutputConfig {
                    backbone: shape,
                    ..LockedOutputConfig::default()
                });
                let c = torque_estimation(&TorqueEstimationConfig {
                    duration: 4.0,
                    backbone: shape,
                    ..TorqueEstimationConfig::default()
                });
                (shape, a, c)
            })
            .collect()
    })
}

fn rms(v: impl Iterator<Item = f64>) -> f64 {
    let (mut n, mut s) = (0.0, 0.0);
    for x in v {
        n += 1.0;
        s += x * x;
    }
    (s / n).sqrt()
}

/// E2.9 does not depend on the plant's backbone: on the catalogue curve,
/// the cubic, a tanh curve that is none of the models, and the proposed
/// model's own flexspline curve (eq. 2.26), eq. (2.30) predicts the
/// locked-output torsion worse than eq. (2.11), eq. (2.10) and eq. (2.26)
/// alone — the wave-generator term is what makes it lose.
///
/// Margin. Write each model's error as the error the backbone curve itself
/// would make, plus the model's gap to the backbone at the recorded
/// torques; by Minkowski's inequality the RMS moves by at most the RMS of
/// that gap (`G_X`, computed here over the recorded `τ_f`, the backbone
/// inverted by bisection). For the backbone curve on a loop centred on it
/// with every element slipped, the error is `±Ψ/2` (loading / unloading)
/// minus the constant kinematic error `c = θ_err(0, 0)` the encoders see
/// (the motor turns < 0.11 rad here, where θ_err changes by < 2e-6 rad);
/// adding the wave-generator term's `Ψ/2` in the load direction makes it
/// `Ψ` or 0. Symmetric loading gives RMS `√(Ψ²/4 + c²)` and `√(Ψ²/2 + c²)`:
/// a gap `D = √(Ψ²/2 + c²) − √(Ψ²/4 + c²)` (5.4e-5 rad). So
/// `rms(2.30) − rms(X) ≥ D − G_2.26 − G_X`. Loops that do not fully
/// reverse only widen the gap: a reversal completes after a torque swing
/// of `K_b Ψ + 2ΣF` ≈ 4.9 N·m, so while the amplitude decays the unloading
/// branch stays near the backbone while the loading branch is fully
/// slipped, the classic curves' errors lean towards the load direction,
/// and the wave-generator offset, which adds torsion in that direction,
/// adds to them.
///
/// Second, that offset `o` (eq. 2.30 minus eq. 2.26, per sample) is not
/// anti-correlated with the error of eq. (2.26) alone:
/// `rms(2.30)² ≥ rms(2.26)² + rms(o)²`. On the ideal centred loop the
/// correlation is zero (loading and unloading cancel) and the partial
/// reversals above make it positive; were the plant's loop offset the way
/// eq. (2.30) assumes, `o` would cancel part of that error and the
/// inequality would fail (as it does with the sign of `τ_w` reversed, the
/// diagnostic row of the example).
#[test]
fn proposed_model_predicts_worst_on_every_backbone() {
    let psi = SHD.hysteresis_loss;
    let c = KinematicErrorModel::table_3_2().evaluate(0.0, 0.0);
    let d = (psi * psi / 2.0 + c * c).sqrt() - (psi * psi / 4.0 + c * c).sqrt();
    let m = Models::shd_17_100();
    for (shape, r, _) in per_backbone() {
        let b = Backbone::from_catalogue(*shape, &SHD, SHD_17_100_K3).unwrap();
        let gap = |f: &dyn Fn(f64) -> f64| {
            rms(r
                .samples
                .iter()
                .map(|s| f(s.flexspline_torque) - b.torsion_by_bisection(s.flexspline_torque)))
        };
        let g_flex = gap(&|t| m.proposed.flexspline().torsion(t));
        let g_pw = gap(&|t| m.piecewise.torsion(t));
        let g_cubic = gap(&|t| m.cubic.torsion(t));
        for (name, e, g) in [
            ("2.26 alone", r.flexspline, g_flex),
            ("piecewise", r.piecewise, g_pw),
            ("cubic", r.cubic, g_cubic),
        ] {
            let margin = d - g_flex - g;
            assert!(margin > 0.0, "{shape:?} {name}: margin {margin}");
            assert!(
                r.proposed.rms - e.rms >= margin,
                "{shape:?}: proposed {} vs {name} {} (margin {margin})",
                r.proposed.rms,
                e.rms
            );
        }
        let o = rms(r.samples.iter().map(|s| s.proposed - s.flexspline));
        assert!(
            r.proposed.rms.powi(2) >= r.flexspline.rms.powi(2) + o * o,
            "{shape:?}: {} {} {o}",
            r.proposed.rms,
            r.flexspline.rms
        );
    }
}

/// Table 3.3 on every backbone: the wave-generator term of eq. (3.9)
/// raises the RMS estimation error. Its shift of the estimate is at
/// least `K_f0 (Ψ/2)(1 − e^{−|τ_m|/τ_fs})` on every level with a motor
/// torque (the inverse eq. 3.10 has slope `≥ K_f0`), so over the seven
/// equally long levels (six with `|τ_m| ≥ 3` N·cm) its RMS is at least
/// `K_f0 (Ψ/2)(1 − e^{−0.03/0.012}) √(6/7)` ≈ 1.03 N·m. As in the
/// locked-output test, the shift is not anti-correlated with the error of
/// the estimate without it: `rms(with)² ≥ rms(without)² + rms(shift)²`.
#[test]
fn wave_generator_term_raises_estimation_error_on_every_backbone() {
    let m = Models::shd_17_100();
    let idx = |name: &str| ESTIMATORS.iter().position(|e| *e == name).unwrap();
    let low = m.proposed.flexspline().k_f0()
        * SHD.hysteresis_loss
        * 0.5
        * (1.0 - (-0.03 / SHD.starting_torque).exp())
        * (6.0f64 / 7.0).sqrt();
    for (shape, _, r) in per_backbone() {
        let with = r.overall[idx("f64, KE fitted")].rms;
        let without = r.overall[idx("f64, KE fitted, tau_w = 0")].rms;
        let shift = r.wave_generator_shift.rms;
        assert!(shift >= low, "{shape:?}: shift {shift} < {low}");
        assert!(
            with * with >= without * without + shift * shift,
            "{shape:?}: with {with}, without {without}, shift {shift}"
        );
    }
}

/// The kinematic error fitted from the two calibration revolutions
/// recovers every coefficient of the plant's (Table 3.2; the largest,
/// `b_l1`, is 7.5e-5 rad) to a tenth of the output-side motor count
/// `q = 2π/(MN)` = 3.1e-5 rad. The fit averages ~6 000 samples whose
/// quantization errors spread over a count, a standard error of about
/// `q/√12/√3000` ≈ 1.6e-7 rad; the rest of the margin covers the run's
/// dynamics (the motor harmonics at 8 and 16 Hz excite the link-drive
/// mode, `√(K1 (1/I_l + 1/(N² I_m)))` ≈ 82 Hz, by ≤ (16/82)² ≈ 4 %) and
/// friction.
#[test]
fn calibration_recovers_the_kinematic_error() {
    let r = estimation();
    let t = mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel::table_3_2();
    let q = core::f64::consts::TAU / (2000.0 * 100.0);
    let fitted = r.fitted_kinematic_error.coefficients();
    for (f, t) in fitted.iter().zip(t.coefficients()) {
        assert!((f - t).abs() < q / 10.0, "{fitted:?} vs {t}");
    }
}

/// I16F16 agrees with f64 on the same counts. Budget in stored units
/// (mrad, LSB 2⁻¹⁶): the torsion from counts rounds once (½ LSB); the
/// seven kinematic-error products round (7 × ½ LSB) and their coefficients
/// were rounded (7 × ½ LSB); the wave-generator term (exp ≤ 2 LSB scaled
/// by its 0.145 mrad amplitude, two roundings) ≤ 2 LSB: 9.5 LSB of torsion.
/// The tan argument is that times `c_f K_f0` = 0.3746 rad/mrad plus ½ LSB;
/// tan's slope `1 + (c_f τ)²` ≤ 1.46 at 15 N·m, its own error 1 LSB; the
/// result is scaled by `1/c_f` = 22.3 N·m and rounded (½ LSB).
#[test]
fn fixed_point_estimate_agrees_with_f64() {
    let r = estimation();
    let lsb = 1.0 / 65536.0;
    let m = Models::shd_17_100();
    let ck = m.proposed.flexspline().c_f() * m.proposed.flexspline().k_f0() * 1e-3;
    let slope = 1.0 + (m.proposed.flexspline().c_f() * 15.0f64).powi(2);
    let bound = ((9.5 * ck + 0.5) * slope + 1.0) * lsb / m.proposed.flexspline().c_f() + 0.5 * lsb;
    for l in &r.levels {
        assert!(l.fixed_vs_float <= bound, "{} > {bound}", l.fixed_vs_float);
    }
}

fn chain(n: usize) -> Vec<ModuleParams> {
    (0..n)
        .map(|i| {
            let mut m = ModuleParams::thesis_joint();
            m.axis = match i {
                0 => [0.0, 0.0, 1.0],
                1 => misaligned([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], 0.05),
                _ => [0.0, 1.0, 0.0],
            };
            m.origin = if i == 0 { [0.0; 3] } else { [0.45, 0.0, 0.0] };
            m.link_mass = if i + 1 < n { 1.2 + 0.64 } else { 0.64 };
            m
        })
        .collect()
}

/// Without friction, control or hysteresis the plant is conservative; RK4
/// loses at most `1 − |R(iωh)|²` of the energy of a mode of frequency `ω`
/// per step, so the drift after `S` steps is bounded by the oscillation
/// energy times `S · loss(ω_max h)`, with `ω_max` the stiffest mode
/// (generalized eigenvalue of the drive stiffness and the inertia matrix,
/// by power iteration). The slow gravity/Coriolis motion adds errors of
/// order `(ω_slow h)⁴` per unit time, negligible at ω_slow < 30 rad/s.
#[test]
fn energy_is_conserved_within_the_rk4_bound() {
    let mut mods = chain(3);
    for m in mods.iter_mut() {
        m.drive = m.drive.elastic();
        m.drive.kinematic_error =
            Some(mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel::table_3_2());
        m.motor_friction = FrictionParams::NONE;
        m.link_friction = FrictionParams::NONE;
    }
    let (period, steps) = (1e-3, 10);
    let mut r = Mrr::try_new(mods, [0.0, 0.0, -9.81], period, steps, 7).expect("valid plant");
    // Small torsions (first catalogue slope) and link speeds.
    let q_l = [0.1, -0.4, 0.6];
    let q_m: Vec<f64> = q_l
        .iter()
        .zip([2e-4, -1e-4, 1.5e-4])
        .map(|(q, d)| 100.0 * (q + d))
        .collect();
    r.set_state(&q_l, &q_m, &[0.3, -0.2, 0.5], &[0.0, 10.0, -5.0]);
    let e0 = r.energy();
    // Oscillation energy: kinetic + elastic (gravity potential excluded).
    let m = r.inertia_matrix();
    let v: Vec<f64> = r
        .link_speeds()
        .iter()
        .chain(r.motor_speeds())
        .copied()
        .collect();
    let mut kin = 0.0;
    for i in 0..6 {
        for j in 0..6 {
            kin += 0.5 * v[i] * m[i * 6 + j] * v[j];
        }
    }
    let e_osc = kin + (0..3).map(|i| r.drive_energy(i)).sum::<f64>();
    // Stiffness matrix of the drives (first slope K1) in (q_l, q_m).
    let k1 = SHD.k1;
    let mut k = vec![0.0; 36];
    for i in 0..3 {
        let (l, mm) = (i, 3 + i);
        k[l * 6 + l] = k1;
        k[mm * 6 + mm] = k1 / 1e4;
        k[l * 6 + mm] = -k1 / 100.0;
        k[mm * 6 + l] = -k1 / 100.0;
    }
    let omega_max = largest_generalized_frequency(&k, &m, 6);
    let h = period / steps as f64;
    let duration = 0.3;
    let n_steps = (duration / h).round();
    let mut ctl = |_: &Sensors, out: &mut [f64]| out.iter_mut().for_each(|t| *t = 0.0);
    while r.time() < duration - 1e-9 {
        r.sample(&mut ctl, &mut |_, _| {});
    }
    let drift = (r.energy() - e0).abs();
    let bound =
        e_osc * n_steps * rk4_energy_loss_per_step(omega_max * h) + 1e-12 * e0.abs().max(e_osc);
    assert!(
        drift <= bound,
        "drift {drift} J > bound {bound} J (ω_max {omega_max})"
    );
    assert!(drift > 0.0);
}

/// `sqrt(λ_max)` of `K v = λ M v` by power iteration on `M⁻¹ K`.
fn largest_generalized_frequency(k: &[f64], m: &[f64], dim: usize) -> f64 {
    let mut v = vec![1.0; dim];
    let mut lambda = 0.0;
    for _ in 0..500 {
        let kv: Vec<f64> = (0..dim)
            .map(|i| (0..dim).map(|j| k[i * dim + j] * v[j]).sum())
            .collect();
        let w = solve(m, &kv, dim);
        let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt();
        lambda = norm / v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v = w.iter().map(|x| x / norm).collect();
    }
    lambda.sqrt()
}

fn solve(a: &[f64], b: &[f64], n: usize) -> Vec<f64> {
    let mut a = a.to_vec();
    let mut b = b.to_vec();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| a[i * n + c].abs().total_cmp(&a[j * n + c].abs()))
            .unwrap();
        for j in 0..n {
            a.swap(c * n + j, p * n + j);
        }
        b.swap(c, p);
        for i in c + 1..n {
            let f = a[i * n + c] / a[c * n + c];
            for j in c..n {
                a[i * n + j] -= f * a[c * n + j];
            }
            b[i] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|j| a[i * n + j] * x[j]).sum();
        x[i] = (b[i] - s) / a[i * n + i];
    }
    x
}

/// A two-module arm held horizontal by motor-side PD control on the
/// quantized encoder counts (4 ms zero-order hold) settles with every
/// drive twisted by the catalogue torsion of its gravity load. The load is
/// computed by hand (not by the plant): joint 1 carries both links,
/// `g (m1 l/2 + m2 (l + l/2))`, joint 2 `g m2 l/2`. The PD's derivative
/// acts on count differences, so its torque chatters by up to
/// `K_d · (2π/M)/T` at the motor, `N` times that at the link; the torsion
/// (true, averaged over the last second) may differ from the static value
/// by that torque over `K1`. The sag changes the lever arms by
/// `1 − cos(sag)` < 1e-3 relatively (sag ≈ 0.02 rad), added to the bound.
#[test]
fn static_deflection_under_gravity_matches_the_catalogue_compliance() {
    let mut mods = chain(2);
    for m in mods.iter_mut() {
        m.axis = [0.0, 1.0, 0.0];
        m.drive = m.drive.elastic();
        m.motor_friction = FrictionParams::viscous(1e-4);
        m.link_friction = FrictionParams::viscous(0.5);
        m.max_motor_torque = 1.0;
    }
    mods[0].link_mass = 1.84;
    let (m1, m2, l, g) = (1.84, 0.64, 0.45, 9.81);
    let mut r = Mrr::try_new(mods, [0.0, 0.0, -9.81], 4e-3, 40, 11).expect("valid plant");
    let q_m = 2.0 * core::f64::consts::PI / 2000.0;
    let mut prev: Option<[i64; 2]> = None;
    let mut ctl = |s: &Sensors, out: &mut [f64]| {
        for i in 0..2 {
            let c = s.motor_counts[i];
            let v = prev.map_or(0.0, |p| (c - p[i]) as f64 * q_m / 4e-3);
            out[i] = -0.05 * c as f64 * q_m - 1e-3 * v;
        }
        prev = Some([s.motor_counts[0], s.motor_counts[1]]);
    };
    let mut mean = [0.0; 2];
    let mut count = 0.0;
    while r.time() < 5.0 {
        r.sample(&mut ctl, &mut |_, _| {});
        if r.time() > 4.0 {
            for (i, m) in mean.iter_mut().enumerate() {
                *m += r.motor_angles()[i] / 100.0 - r.link_angles()[i];
            }
            count += 1.0;
        }
    }
    // With the axes along +y, gravity along −z and the links along +x,
    // gravity's moment `(x, 0, 0) × (0, 0, −mg) = (0, mgx, 0)` is positive
    // about the axes: the drives hold with τ_t = −load, i.e. a negative
    // torsion δ = q_m/N − q_l.
    let load = [g * (m1 * l / 2.0 + m2 * 1.5 * l), g * m2 * l / 2.0];
    let models = Models::shd_17_100();
    let chatter = 1e-3 * q_m / 4e-3 * 100.0 / SHD.k1;
    for i in 0..2 {
        let torsion = mean[i] / count;
        let expected = -models.piecewise.torsion(load[i]);
        let bound = chatter + 1e-3 * expected.abs();
        assert!(
            (torsion - expected).abs() <= bound,
            "joint {i}: {torsion} vs {expected} ± {bound}"
        );
    }
}

/// Errata E2.9: the locked-output ranking depends on the plant's structure
/// and on the torque amplitude, so it is stated only where it holds. The
/// table (printed with `--nocapture`) covers drive-torque amplitudes of
/// 3–15 N·m on the Fig. 2.7 plant (wave-generator compliance carrying the
/// motor torque, mesh friction `τ_fb = 2 N·m` between it and the
/// flexspline, its catalogue-style test matching the catalogue; see
/// `MeshFrictionPlant`) and on the plant centred on the catalogue curve.
///
/// Why the crossover: on the Fig. 2.7 plant the classic models, fed with
/// the flexspline torque, miss the wave generator's torsion `g_w(N τ_m)`,
/// which eq. (2.30) carries; but eq. (2.30)'s flexspline curve already has
/// the catalogue's whole compliance, so once `g_w` saturates (`|N τ_m| ≫
/// N τ_fs = 1.2 N·m`) its extra `Ψ/2` becomes an offset that grows in
/// weight with the share of samples at high torque. On the centred plant
/// the loop carries no such wave-generator torsion and eq. (2.30) is worst
/// at every amplitude.
#[test]
fn model_ranking_over_amplitudes_and_plant_structures() {
    let amplitudes = [3.0, 5.0, 8.0, 10.0, 15.0];
    let mut rows: Vec<RankingRow> = Vec::new();
    for s in [
        PlantStructure::MeshFriction,
        PlantStructure::Centred(BackboneShape::CataloguePiecewise),
    ] {
        for a in amplitudes {
            rows.push(model_ranking(s, a));
        }
    }
    println!("plant                     N·A     (2.30)    (2.26)    (2.11)    (2.10)");
    for r in &rows {
        println!(
            "{:<24} {:>5.1}  {:.3e} {:.3e} {:.3e} {:.3e}",
            r.structure.name(),
            r.drive_amplitude,
            r.proposed,
            r.flexspline,
            r.piecewise,
            r.cubic
        );
    }
    for r in &rows {
        let mesh = r.structure == PlantStructure::MeshFriction;
        // On the Fig. 2.7 plant at small amplitudes the wave generator's
        // torsion is most of the classic models' error: eq. (2.30) wins.
        if mesh && r.drive_amplitude <= 8.0 {
            assert!(r.proposed_beats_classic(), "{r:?}");
            assert!(r.proposed < r.flexspline, "{r:?}");
        }
        if mesh && r.drive_amplitude <= 5.0 {
            assert!(r.proposed < 0.5 * r.piecewise, "{r:?}");
        }
        // At 10 N·m and above eq. (2.30) loses on both structures.
        if r.drive_amplitude >= 10.0 {
            assert!(!r.proposed_beats_classic(), "{r:?}");
            assert!(r.proposed > r.piecewise && r.proposed > r.cubic, "{r:?}");
        }
        // On the centred plant eq. (2.30) is worst at every amplitude.
        if !mesh {
            assert!(
                r.proposed > r.piecewise.max(r.cubic).max(r.flexspline),
                "{r:?}"
            );
        }
    }
}
