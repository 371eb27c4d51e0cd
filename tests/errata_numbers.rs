//! The numbers printed in docs/ERRATA.md, recomputed independently of the
//! library's own tests, and checked against the text (so a slip in the
//! docs fails here). Test names start with the erratum id
//! (`e2_3_…` for E2.3), which `.ci/errata.py` uses as a filter.

use mrr_control::control::adaptive::RobustAdaptiveDesign;
use mrr_control::friction::FrictionParams;
use mrr_control::harmonic_drive::kinematic_error::{KinematicErrorModel, TABLE_3_1};
use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::{Scalar, I16F16};

const ERRATA: &str = include_str!("../docs/ERRATA.md");
const README: &str = include_str!("../README.md");
const REPRODUCTION: &str = include_str!("../docs/reproduction.md");
const VERIFICATION: &str = include_str!("../docs/verification.md");
const PERFORMANCE: &str = include_str!("../docs/performance.md");
const KINEMATIC_ERROR_RS: &str = include_str!("../src/harmonic_drive/kinematic_error.rs");
const THESIS_CH2_3_RS: &str = include_str!("thesis_ch2_3.rs");

/// The entry `id` of ERRATA.md (from its heading to the next one).
fn entry(id: &str) -> &'static str {
    let start = ERRATA
        .find(&format!("### {id} — "))
        .unwrap_or_else(|| panic!("no entry {id}"));
    let rest = &ERRATA[start + 4..];
    let end = rest
        .find("\n### ")
        .or(rest.find("\n## "))
        .unwrap_or(rest.len());
    &rest[..end]
}

fn assert_printed(id: &str, text: &str) {
    assert!(entry(id).contains(text), "{id} should print `{text}`");
}

/// K_f0 by hand from the §2.4 inputs (eq. 2.33), and every `K_f0`-like
/// number `83xx.x` printed in the errata, the README and the pages moved
/// out of it (reproduction, verification, performance) is that value.
#[test]
fn e2_3_k_f0_is_8335_98_everywhere() {
    let (k1, k2, t1, t2) = (8.4e3f64, 9.4e3f64, 3.9f64, 12.0f64);
    let s = t1 + t2;
    let hand = (k1 * s * s - k2 * t1 * t1) / (s * s - t1 * t1);
    let lib = CatalogueData::SHD_17_100
        .identify()
        .unwrap()
        .flexspline()
        .k_f0();
    assert!((hand - lib).abs() < 1e-9 * hand);
    assert_eq!(format!("{hand:.2}"), "8335.98");
    assert_printed("E2.3", "8 335.98 N·m/rad");
    assert!(REPRODUCTION.contains(&format!("`K_f0 = {hand:.2} N·m/rad`")));
    for doc in [
        ERRATA,
        README,
        REPRODUCTION,
        VERIFICATION,
        PERFORMANCE,
        THESIS_CH2_3_RS,
    ] {
        for wrong in ["8 336.1", "8336.1", "8336.07", "8.336e3"] {
            assert!(!doc.contains(wrong), "`{wrong}` printed");
        }
    }
}

/// E2.9's hand numbers at τ_f = 10 N·m.
#[test]
fn e2_9_hand_numbers_at_10_nm() {
    let (k1, k2, t1, t2) = (8.4e3f64, 9.4e3f64, 3.9f64, 12.0f64);
    let s = t1 + t2;
    let k_f0 = (k1 * s * s - k2 * t1 * t1) / (s * s - t1 * t1);
    let c_f = 2.0 * ((k2 - k1) / (k1 * s * s - k2 * t1 * t1)).sqrt();
    let flex = (c_f * 10.0).atan() / (c_f * k_f0);
    let wg = 2.9e-4 / 2.0 * (1.0 - (-0.1f64 / 0.012).exp());
    let cat = 3.9 / 8400.0 + 6.1 / 9400.0;
    assert_eq!(format!("{flex:.4e}"), "1.1274e-3");
    assert_eq!(format!("{:.4e}", flex + wg), "1.2724e-3");
    assert_eq!(format!("{cat:.4e}"), "1.1132e-3");
    assert_eq!(format!("{:.3}", c_f * k_f0), "374.615");
    for n in ["1.1274e-3", "1.2724e-3", "1.1132e-3", "374.615", "1.450e-4"] {
        assert_printed("E2.9", n);
    }
    for doc in [entry("E2.9"), THESIS_CH2_3_RS] {
        assert!(!doc.contains("1.1271e-3") && !doc.contains("1.2721e-3"));
    }
    assert!(THESIS_CH2_3_RS.contains("1.1274e-3") && THESIS_CH2_3_RS.contains("1.2724e-3"));
}

/// E3.2: the model's motor terms are harmonics of the measured input angle
/// θ_wi (the argument the library is given), written out term by term.
#[test]
fn e3_2_motor_terms_are_harmonics_of_the_input_angle() {
    let m = KinematicErrorModel::table_3_2();
    let c = m.coefficients();
    for k in 0..50 {
        let l = -3.0 + 0.123 * k as f64;
        let w = 40.0 - 1.7 * k as f64;
        let hand = c[0]
            + c[1] * l.cos()
            + c[2] * l.sin()
            + c[3] * w.cos()
            + c[4] * w.sin()
            + c[5] * (2.0 * w).cos()
            + c[6] * (2.0 * w).sin();
        assert!((m.evaluate(l, w) - hand).abs() < 1e-15, "{l} {w}");
    }
}

/// E3.3: the peak-to-peak error of Table 3.2 read in degrees, by a grid
/// search over independent link and motor angles, and the drift of the
/// printed `w_w` over 100 motor turns.
#[test]
fn e3_3_peak_to_peak_and_drift() {
    let m = KinematicErrorModel::table_3_2();
    let n = 1500;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..n {
        let l = std::f64::consts::TAU * i as f64 / n as f64;
        for j in 0..n {
            let w = std::f64::consts::TAU * j as f64 / n as f64;
            let e = m.evaluate(l, w);
            lo = lo.min(e);
            hi = hi.max(e);
        }
    }
    let p2p = hi - lo;
    println!("E3.3: peak-to-peak {p2p:.4e} rad");
    assert_eq!(format!("{p2p:.2e}"), "3.33e-4");
    assert!(p2p < 4.4e-4);
    let drift = 100.0 * 360.0 * (1.0 - 0.01734 / (std::f64::consts::PI / 180.0));
    println!("E3.3: drift over 100 motor turns {drift:.2}°");
    assert_eq!(format!("{drift:.1}"), "233.7");
    assert_printed("E3.3", "3.33e-4 rad");
    assert_printed("E3.3", "233.7°");
    assert!(KINEMATIC_ERROR_RS.contains("error, 3.33e-4 rad, lies within it"));
}

/// E3.4: the SHD-17-100's rated torque (Table 3.1) lies above its `T2`
/// (§2.4), where the catalogue slope is `K3`, not `K2`.
#[test]
fn e3_4_shd17_rated_torque_lies_beyond_t2() {
    let row = TABLE_3_1[3];
    assert_eq!((row.size, row.ratio), (17, 100));
    let t2 = CatalogueData::SHD_17_100.t2;
    assert!(row.rated_torque > t2, "{} vs {t2}", row.rated_torque);
    let with_k3 = 1.3e4 * row.max_kinematic_error;
    assert_eq!(format!("{with_k3:.1}"), "5.7");
    assert_printed("E3.4", "5.7 N·m instead of 4.1 N·m");
}

/// E3.5: the principal branch of eq. (3.10) ends at π/(2 c_f K_f0).
#[test]
fn e3_5_tan_branch_ends_at_pi_over_two() {
    let p = CatalogueData::SHD_17_100.identify().unwrap().flexspline();
    let limit = std::f64::consts::FRAC_PI_2 / (p.c_f() * p.k_f0());
    assert!((p.max_torsion() - limit).abs() < 1e-15);
    assert_eq!(format!("{limit:.3e}"), "4.193e-3");
    assert_printed("E3.5", "4.193e-3 rad");
    // Just inside the branch the torque is huge and positive; just past it
    // tan changes sign: the value the library must not return.
    let inside = (p.c_f() * p.k_f0() * (limit - 1e-9)).tan() / p.c_f();
    let outside = (p.c_f() * p.k_f0() * (limit + 1e-9)).tan() / p.c_f();
    assert!(inside > 1e6 && outside < -1e6);
    let t = p.torque(limit + 1e-9);
    assert!(t.saturated && t.torque > 0.0, "{t:?}");
}

/// E4.4: the robust terms outside their boundary layers, from the
/// library's Table 4.1 design, with the assumed `ρ_f` and with 0.
#[test]
fn e4_4_robust_terms_outside_their_layers() {
    let d = RobustAdaptiveDesign::table_4_1();
    let rho_f = d.uncertainty.boundary_layer;
    let k_r = d.robust_gain();
    let rho = d.friction_bounds.variable();
    // By hand from Table 4.1: ρ_fq + I_m ρ_base + ρ_τ/N.
    let without = 0.002 + 1.14e-5 * 1e4 + 1.0 / 100.0;
    assert!((k_r - rho_f - without).abs() < 1e-12);
    let total0 = without + rho[1] + rho[2];
    let total = total0 + rho_f;
    let share = total0 / d.torque_limit;
    println!(
        "E4.4: rho_f {rho_f:.3}, K_r {k_r:.3}, outside layers {total:.3} (rho_f = 0: {total0:.3}, {:.0} % of {})",
        100.0 * share,
        d.torque_limit
    );
    assert_eq!(format!("{rho_f:.3}"), "0.044");
    assert_eq!(format!("{total0:.3}"), "0.146");
    assert_eq!(format!("{total:.3}"), "0.190");
    assert_eq!(format!("{:.0}", 100.0 * share), "78");
    assert_eq!(format!("{:.3}", without), "0.126");
    for n in [
        "0.146 N·m with `ρ_f = 0` (78 % of 0.188 N·m)",
        "0.190 N·m",
        "0.126 N·m",
    ] {
        assert_printed("E4.4", n);
    }
}

/// E4.7: `sat(x, y)` with `y ≤ 0` is `sgn(x)`, on every backend.
#[test]
fn e4_7_sat_with_a_non_positive_layer_is_the_sign() {
    fn check<S: Scalar>() {
        for x in [-2.0, -0.25, 0.0, 0.25, 2.0] {
            for y in [0.0, -0.5] {
                let got = S::from_f64(x).sat(S::from_f64(y)).to_f64();
                let want = if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                };
                assert_eq!(got, want, "sat({x}, {y})");
            }
            // Positive layer: x/y inside, the sign outside.
            let got = S::from_f64(x).sat(S::from_f64(0.5)).to_f64();
            let want = (x / 0.5f64).clamp(-1.0, 1.0);
            assert!((got - want).abs() < 1e-4, "sat({x}, 0.5) = {got}");
        }
    }
    check::<f64>();
    check::<f32>();
    check::<I16F16>();
}

/// E4.9: `f(F) − f̂ − Y(F̂)(F − F̂)` against the closed-form second-order
/// remainder, nonzero outside the layer where `f̌ = 0`.
#[test]
fn e4_9_linearisation_leaves_a_second_order_remainder() {
    let eps = 0.01;
    let truth = FrictionParams {
        viscous: 5e-5,
        coulomb: 0.006,
        stribeck: 0.012,
        stribeck_shape: 1.0,
    }
    .validated()
    .unwrap();
    let est = FrictionParams {
        viscous: 5e-5,
        coulomb: 0.006,
        stribeck: 0.012,
        stribeck_shape: 10.0,
    }
    .validated()
    .unwrap();
    let (t, e) = (truth.to_array(), est.to_array());
    let mut worst: f64 = 0.0;
    for k in 1..400 {
        let qd = 0.01 * k as f64; // all outside the layer: f̌ = 0
        let y = est.regressor(qd, eps);
        let lin: f64 = (0..4).map(|j| y[j] * (t[j] - e[j])).sum();
        let r = truth.nominal(qd, eps) - est.nominal(qd, eps) - lin;
        assert_eq!(truth.boundary_layer_residual(qd, eps), 0.0);
        let s = qd.clamp(-eps, eps) / eps;
        let (et, ee) = ((-t[3] * qd * qd).exp(), (-e[3] * qd * qd).exp());
        let hand =
            s * (t[2] * et - e[2] * ee - (t[2] - e[2]) * ee + e[2] * qd * qd * ee * (t[3] - e[3]));
        assert!((r - hand).abs() < 1e-15, "{qd}: {r} vs {hand}");
        worst = worst.max(r.abs());
    }
    println!("E4.9: largest remainder {worst:.2e} N·m");
    assert!(worst > 1e-3);
    assert_printed("E4.9", &format!("{worst:.1e} N·m"));
}
