//! Thesis ch. 2–3 experiments reproduced on the simulated SHD-17-100 joint:
//! the locked-output compliance experiment (Fig. 2.17–2.20), the
//! back-driven experiment (Fig. 2.21–2.22) and the torque-estimation
//! accuracy table (Table 3.3), and the locked-output and Table 3.3
//! comparisons repeated on plants built on different elastic backbones
//! (errata E2.9). Writes the figure data as CSV under
//! `$CARGO_TARGET_DIR/figures/` (else `target/figures/`) and prints a summary.
//!
//! ```sh
//! cargo run --release --features sim --example thesis_ch2_3
//! ```

use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::sim::experiments::{
    back_driven, locked_output, torque_estimation, width_at_zero, BackDrivenConfig,
    ComplianceResult, ErrorStats, LockedOutputConfig, Models, TorqueEstimationConfig, ESTIMATORS,
};
use mrr_control::sim::experiments::{model_ranking, PlantStructure};
use mrr_control::sim::transmission::{Backbone, SHD_17_100_K3};
use mrr_control::sim::BackboneShape;
use std::fmt::Write as _;
use std::time::Instant;

fn write_compliance_csv(path: std::path::PathBuf, r: &ComplianceResult) -> std::io::Result<()> {
    let mut s = String::from(
        "time_s,tau_w_Nm,tau_f_measured_Nm,tau_f_true_Nm,motor_angle_rad,torsion_measured_rad,torsion_true_rad,proposed_rad,flexspline_only_rad,piecewise_rad,cubic_rad,piecewise_input_rad\n",
    );
    for x in &r.samples {
        let _ = writeln!(
            s,
            "{:.4},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}",
            x.time,
            x.wave_generator_torque,
            x.flexspline_torque,
            x.true_flexspline_torque,
            x.motor_angle,
            x.measured_torsion,
            x.true_torsion,
            x.proposed,
            x.flexspline,
            x.piecewise,
            x.cubic,
            x.piecewise_input
        );
    }
    std::fs::write(path, s)
}

fn row(name: &str, e: &ErrorStats) {
    println!(
        "  {:<38} rms {:>8.2e}  max {:>9.2e}  min {:>9.2e}",
        name, e.rms, e.max, e.min
    );
}

/// `$CARGO_TARGET_DIR/figures` if the variable is set, else `target/figures`.
fn figures_dir() -> std::path::PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::path::PathBuf::from("target"))
        .join("figures")
}

fn main() -> std::io::Result<()> {
    let dir = figures_dir();
    std::fs::create_dir_all(&dir)?;
    let psi = CatalogueData::SHD_17_100.hysteresis_loss;

    let t0 = Instant::now();
    let a = locked_output(&LockedOutputConfig::default());
    write_compliance_csv(dir.join("fig2_17_20_locked_output.csv"), &a)?;
    println!("Locked output, sinusoidal motor torque of decreasing amplitude (Fig. 2.17-2.20)");
    println!("  torsion error against the encoder torsion, rad:");
    row("proposed eq. (2.30), tau_f + tau_w", &a.proposed);
    row("flexspline eq. (2.26) alone, tau_f", &a.flexspline);
    row("catalogue piecewise eq. (2.11), tau_f", &a.piecewise);
    row("cubic eq. (2.10), tau_f", &a.cubic);
    row("piecewise eq. (2.11), -N tau_w", &a.piecewise_input);
    // Diagnostic, not a model of the thesis: eq. (2.30) with the
    // wave-generator torque's sign reversed (errata E2.9, E2.10).
    let m = Models::shd_17_100();
    let flipped = ErrorStats::of(a.samples.iter().map(|s| {
        m.proposed
            .torsion(s.flexspline_torque, -s.wave_generator_torque)
            - s.measured_torsion
    }));
    row("diagnostic: eq. (2.30), -tau_w", &flipped);
    let w_plant = width_at_zero(
        &a.samples,
        |s| -s.wave_generator_torque,
        |s| s.measured_torsion,
        0.0,
        6.0,
    );
    let w_model = width_at_zero(
        &a.samples,
        |s| -s.wave_generator_torque,
        |s| s.proposed,
        0.0,
        6.0,
    );
    println!(
        "  loop width at zero input torque (first 6 s): plant {:.3e} rad, proposed model {:.3e} rad, catalogue Psi {:.1e} rad",
        w_plant, w_model, psi
    );
    println!(
        "  hysteresis dissipation: loop integral {:.4e} J, Maxwell-slip law from the reversals {:.4e} J",
        a.loop_energy, a.maxwell_slip_energy
    );
    let a0 = locked_output(&LockedOutputConfig {
        slip_elements: 0,
        ..LockedOutputConfig::default()
    });
    write_compliance_csv(dir.join("fig2_17_20_locked_output_friction_only.csv"), &a0)?;
    println!("  variant: drive without internal hysteresis (loop from the motor friction only):");
    row("proposed eq. (2.30), tau_f + tau_w", &a0.proposed);
    row("catalogue piecewise eq. (2.11), tau_f", &a0.piecewise);
    row("cubic eq. (2.10), tau_f", &a0.cubic);
    row("piecewise eq. (2.11), -N tau_w", &a0.piecewise_input);
    let w0 = width_at_zero(
        &a0.samples,
        |s| -s.wave_generator_torque,
        |s| s.measured_torsion,
        0.0,
        6.0,
    );
    println!(
        "  loop width at zero input torque (first 6 s): plant {:.3e} rad",
        w0
    );
    println!("  ({:.1} s)", t0.elapsed().as_secs_f64());

    let t0 = Instant::now();
    let b = back_driven(&BackDrivenConfig::default());
    write_compliance_csv(dir.join("fig2_21_22_back_driven.csv"), &b.compliance)?;
    println!(
        "\nBack-driven link, motor held (Fig. 2.21-2.22); tau_w from eq. (2.40), tau_fb = 2.0 N·m"
    );
    row(
        "proposed eq. (2.30), tau_w eq. (2.40)",
        &b.compliance.proposed,
    );
    row("proposed eq. (2.30), tau_w command", &b.proposed_command);
    row(
        "catalogue piecewise eq. (2.11), tau_f",
        &b.compliance.piecewise,
    );
    row("cubic eq. (2.10), tau_f", &b.compliance.cubic);
    println!(
        "  hysteresis dissipation: loop integral {:.4e} J, Maxwell-slip law from the reversals {:.4e} J",
        b.compliance.loop_energy, b.compliance.maxwell_slip_energy
    );
    println!("  ({:.1} s)", t0.elapsed().as_secs_f64());

    let t0 = Instant::now();
    let c = torque_estimation(&TorqueEstimationConfig::default());
    let k = c.fitted_kinematic_error.coefficients();
    println!("\nKinematic error fitted from two calibration revolutions (rad):");
    println!(
        "  a0 {:.3e} al1 {:.3e} bl1 {:.3e} aw1 {:.3e} bw1 {:.3e} aw2 {:.3e} bw2 {:.3e}",
        k[0], k[1], k[2], k[3], k[4], k[5], k[6]
    );
    let t = mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel::table_3_2()
        .coefficients();
    println!(
        "  Table 3.2:  a0 {:.3e} al1 {:.3e} bl1 {:.3e} aw1 {:.3e} bw1 {:.3e} aw2 {:.3e} bw2 {:.3e}",
        t[0], t[1], t[2], t[3], t[4], t[5], t[6]
    );
    println!("\nTorque estimation error at different motor outputs (Table 3.3), N·m (estimate - true tau_f)");
    let mut csv = String::from("motor_torque_Ncm,max_speed_rad_s,estimator,rms_Nm,max_Nm,min_Nm\n");
    print!("{:<32}", "motor torque (N·cm)");
    for l in &c.levels {
        print!("{:>8.0}", l.motor_torque * 100.0);
    }
    println!();
    print!("{:<32}", "max speed (rad/s)");
    for l in &c.levels {
        print!("{:>8.2}", l.max_speed);
    }
    println!();
    for (j, name) in ESTIMATORS.iter().enumerate() {
        for (label, f) in [("max", 0usize), ("min", 1), ("rms", 2)] {
            print!("{:<32}", format!("{name} {label}"));
            for l in &c.levels {
                let e = &l.errors[j];
                print!("{:>8.2}", [e.max, e.min, e.rms][f]);
            }
            println!();
        }
        for l in &c.levels {
            let e = &l.errors[j];
            let _ = writeln!(
                csv,
                "{},{:.3},{},{:.4},{:.4},{:.4}",
                l.motor_torque * 100.0,
                l.max_speed,
                name,
                e.rms,
                e.max,
                e.min
            );
        }
    }
    std::fs::write(dir.join("table3_3_torque_estimation.csv"), csv)?;
    println!("overall:");
    for (j, name) in ESTIMATORS.iter().enumerate() {
        row(name, &c.overall[j]);
    }
    let fx = c
        .levels
        .iter()
        .map(|l| l.fixed_vs_float)
        .fold(0.0, f64::max);
    let sat = c.levels.iter().any(|l| l.saturated);
    println!("  largest |I16F16 - f64| (fitted KE): {fx:.2e} N·m; any saturation: {sat}");
    println!("  ({:.1} s)", t0.elapsed().as_secs_f64());
    backbone_table(&dir)?;
    ranking_sweep();
    println!("\nCSV written to {}", dir.display());
    Ok(())
}

/// The locked-output and Table 3.3 comparisons on every backbone (the
/// configurations of `tests/thesis_ch2_3.rs`).
fn backbone_table(dir: &std::path::Path) -> std::io::Result<()> {
    let t0 = Instant::now();
    let shd = CatalogueData::SHD_17_100;
    let m = Models::shd_17_100();
    println!("\nModel comparison per plant backbone (errata E2.9)");
    println!(
        "  curve gap: largest |model curve - backbone| over |tau_f| <= T2 (rad), no hysteresis"
    );
    println!("  locked output: RMS torsion error (rad); Table 3.3 (4 s/level): RMS estimate error (N·m), f64, KE fitted");
    println!(
        "  {:<24}{:>10}{:>10}{:>10} |{:>10}{:>10}{:>10}{:>10} |{:>9}{:>9}",
        "backbone",
        "gap 2.26",
        "gap 2.11",
        "gap 2.10",
        "proposed",
        "2.26 only",
        "piecewise",
        "cubic",
        "with tw",
        "tw = 0"
    );
    let mut csv = String::from("backbone,gap_flexspline_rad,gap_piecewise_rad,gap_cubic_rad,rms_proposed_rad,rms_flexspline_only_rad,rms_piecewise_rad,rms_cubic_rad,est_rms_with_tau_w_Nm,est_rms_tau_w_0_Nm\n");
    for shape in BackboneShape::ALL {
        let b = Backbone::from_catalogue(shape, &shd, SHD_17_100_K3).expect("valid catalogue");
        let mut gap = [0.0f64; 3];
        for i in 0..=1200 {
            let tau = i as f64 * shd.t2 / 1200.0;
            let truth = b.torsion_by_bisection(tau);
            let models = [
                m.proposed.flexspline().torsion(tau),
                m.piecewise.torsion(tau),
                m.cubic.torsion(tau),
            ];
            for (g, x) in gap.iter_mut().zip(models) {
                *g = g.max((x - truth).abs());
            }
        }
        let a = locked_output(&LockedOutputConfig {
            backbone: shape,
            ..LockedOutputConfig::default()
        });
        let c = torque_estimation(&TorqueEstimationConfig {
            duration: 4.0,
            backbone: shape,
            ..TorqueEstimationConfig::default()
        });
        let idx = |name: &str| ESTIMATORS.iter().position(|e| *e == name).unwrap();
        let with = c.overall[idx("f64, KE fitted")].rms;
        let without = c.overall[idx("f64, KE fitted, tau_w = 0")].rms;
        println!(
            "  {:<24}{:>10.2e}{:>10.2e}{:>10.2e} |{:>10.3e}{:>10.3e}{:>10.3e}{:>10.3e} |{:>9.3}{:>9.3}",
            shape.name(),
            gap[0],
            gap[1],
            gap[2],
            a.proposed.rms,
            a.flexspline.rms,
            a.piecewise.rms,
            a.cubic.rms,
            with,
            without
        );
        let _ = writeln!(
            csv,
            "{},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4},{:.4}",
            shape.name(),
            gap[0],
            gap[1],
            gap[2],
            a.proposed.rms,
            a.flexspline.rms,
            a.piecewise.rms,
            a.cubic.rms,
            with,
            without
        );
    }
    std::fs::write(dir.join("e12_backbones.csv"), csv)?;
    println!("  ({:.1} s)", t0.elapsed().as_secs_f64());
    Ok(())
}

/// Errata E2.9: the locked-output ranking over the drive-torque amplitude
/// and the plant structure (the table `tests/thesis_ch2_3.rs` checks).
fn ranking_sweep() {
    let t0 = Instant::now();
    println!("\nLocked-output RMS torsion error (rad) per plant structure and drive-torque amplitude (errata E2.9)");
    println!(
        "  {:<24} {:>6}  {:>9} {:>9} {:>9} {:>9}  (2.30) best?",
        "plant", "N·A", "(2.30)", "(2.26)", "(2.11)", "(2.10)"
    );
    let structures = [
        PlantStructure::MeshFriction,
        PlantStructure::Centred(BackboneShape::CataloguePiecewise),
        PlantStructure::Centred(BackboneShape::IdentifiedFlexspline),
    ];
    for s in structures {
        for a in [3.0, 5.0, 8.0, 10.0, 15.0] {
            let r = model_ranking(s, a);
            println!(
                "  {:<24} {:>6.1}  {:>9.3e} {:>9.3e} {:>9.3e} {:>9.3e}  {}",
                s.name(),
                a,
                r.proposed,
                r.flexspline,
                r.piecewise,
                r.cubic,
                if r.proposed_beats_classic() {
                    "yes"
                } else {
                    "no"
                }
            );
        }
    }
    println!("  ({:.1} s)", t0.elapsed().as_secs_f64());
}
