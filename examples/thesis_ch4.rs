//! Thesis ch. 4 closed-loop experiments in simulation: active tracking
//! with and without joint-torque feedback (Fig. 4.2–4.3), the ultimate
//! bound of Theorem 1 on random cases, the passive mode (Fig. 4.11–4.12),
//! the payload drop (Fig. 3.8) and the mode manager. Prints the tables and
//! writes CSV to `$CARGO_TARGET_DIR/figures/` (else `target/figures/`).
//!
//! `cargo run --release --features sim --example thesis_ch4`

use mrr_control::estimation::collision::CollisionReaction;
use mrr_control::sim::closed_loop::{
    active_tracking, back_drive, bound_run, collision_scenario, interaction_scenario, payload_drop,
    BackDriveConfig, BackDriveMode, BoundCase, JointTorqueFeedback, ModeScenarioConfig,
    PayloadDropConfig, TrackingConfig,
};
use mrr_control::sim::SplitMix64;
use std::f64::consts::TAU;
use std::io::Write;

const FEEDBACKS: [JointTorqueFeedback; 3] = [
    JointTorqueFeedback::None,
    JointTorqueFeedback::Sensor,
    JointTorqueFeedback::Estimated,
];

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
    let start = std::time::Instant::now();

    println!(
        "Fig. 4.2-4.3: active tracking, q_l^d = 0.25(1 - cos(2 pi t/4 s)) rad, 12 s (2 s ignored),"
    );
    println!(
        "thesis joint carrying joints 2, 3 and the link (2.4 kg at 0.45 m), axis tilted 20 deg"
    );
    println!("| law | T (ms) | feedback | link max (mrad) | link RMS (mrad) | motor max (rad) | motor RMS (rad) | feedback err RMS (N m) | saturated % |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut csv = std::fs::File::create(dir.join("fig4_3_tracking.csv"))?;
    writeln!(csv, "law,T_s,feedback,link_max_rad,link_rms_rad,motor_max_rad,motor_rms_rad,feedback_err_rms_Nm,saturated_fraction")?;
    let mut rows = Vec::new();
    for t in [4e-3, 2.5e-4] {
        for fb in FEEDBACKS {
            rows.push(("Table 4.1", TrackingConfig::table_4_1(fb, t)));
        }
    }
    for fb in FEEDBACKS {
        rows.push(("smooth layers", TrackingConfig::smooth(fb)));
    }
    for (name, cfg) in rows {
        let r = active_tracking(&cfg);
        println!(
            "| {name} | {} | {} | {:.3} | {:.3} | {:.4} | {:.4} | {:.3} | {:.1} |",
            r.sample_period * 1e3,
            r.feedback.label(),
            r.link_error.max_abs() * 1e3,
            r.link_error.rms * 1e3,
            r.motor_error.max_abs(),
            r.motor_error.rms,
            r.feedback_error.rms,
            100.0 * r.saturated_fraction
        );
        writeln!(
            csv,
            "{name},{},{},{},{},{},{},{},{}",
            r.sample_period,
            r.feedback.label(),
            r.link_error.max_abs(),
            r.link_error.rms,
            r.motor_error.max_abs(),
            r.motor_error.rms,
            r.feedback_error.rms,
            r.saturated_fraction
        )?;
    }

    println!(
        "\nTheorem 1 (eq. 4.28-4.31) on 128 random cases, 0.3 s each, T = 50 us (bound_design):"
    );
    let mut rng = SplitMix64::new(2024);
    let mut u = |a: f64, b: f64| a + (b - a) * rng.uniform();
    let (mut worst_ratio, mut worst_r, mut worst_delta) = (0.0f64, 0.0f64, 0.0f64);
    let (mut rs, mut rbar_max) = (0.0, 0.0f64);
    let mut csv = std::fs::File::create(dir.join("theorem1_random_cases.csv"))?;
    writeln!(csv, "case,max_sliding,radius,sliding_radius,sampling_disturbance,reaching_time,max_feedback_error")?;
    for k in 0..128 {
        let case = BoundCase {
            friction: [u(0.0, 1e-4), u(0.0, 0.012), u(0.0, 0.012)],
            stribeck: u(0.1, 10.0),
            tilt: u(0.0, 0.3),
            tilt_direction: u(0.0, TAU),
            payload: u(0.0, 1.2),
            payload_distance: u(0.1, 0.45),
            amplitude: u(0.0, 0.2),
            period: u(1.5, 4.0),
            error_fraction: u(0.0, 0.9),
            error_square_period: if k % 2 == 0 { 0.0 } else { u(0.02, 0.5) },
            seed: k,
            estimated_feedback: false,
        };
        let r = bound_run(&case, 0.3);
        worst_ratio = worst_ratio.max(r.max_sliding / r.radius);
        worst_r = worst_r.max(r.max_sliding);
        worst_delta = worst_delta.max(r.sampling_disturbance);
        rs = r.bound.sliding_radius;
        rbar_max = rbar_max.max(r.radius);
        writeln!(
            csv,
            "{k},{},{},{},{},{},{}",
            r.max_sliding,
            r.radius,
            r.bound.sliding_radius,
            r.sampling_disturbance,
            r.reaching_time,
            r.max_feedback_error
        )?;
    }
    println!("| r_S (rad/s) | worst |r| after t_s (rad/s) | largest delta (N m) | largest r_bar (rad/s) | worst |r|/r_bar |");
    println!("|---|---|---|---|---|");
    println!("| {rs:.3} | {worst_r:.3} | {worst_delta:.4} | {rbar_max:.2} | {worst_ratio:.4} |");
    println!("Violations (same case, torque feedback biased by E = k rho_tau, eq. 4.14 violated for k > 1):");
    println!("| k | max |r| (rad/s) | r_bar (rad/s) | exceeded |");
    println!("|---|---|---|---|");
    for k in [0.9, 20.0, 40.0, 60.0] {
        let case = BoundCase::feedback_bias(k);
        let r = bound_run(&case, 0.3);
        println!(
            "| {k} | {:.3} | {:.2} | {} |",
            r.max_sliding,
            r.radius,
            r.max_sliding > r.radius
        );
    }

    println!("\nAssumption 5 (eq. 4.14): the estimator's error in the ch. 3-4 loops");
    let survey = mrr_control::sim::closed_loop::estimator_error_survey();
    for c in &survey {
        println!(
            "  {:<58} max |error| {:>6.3} N m",
            c.scenario,
            c.error.max_abs()
        );
    }
    let d = mrr_control::control::RobustAdaptiveDesign::table_4_1();
    println!("| rho_tau (N m) | r_S (rad/s) | link |e| bound (rad) | K_r (N m) | law applied (K_r < 0.188) |");
    println!("|---|---|---|---|---|");
    for rho in [1.0, 4.0, 25.354] {
        let (b, kr, ok) = mrr_control::control::UltimateBound::for_torque_error(&d, rho);
        println!(
            "| {rho} | {:.3} | {:.3e} | {kr:.3} | {ok} |",
            b.sliding_radius, b.link_tracking_error
        );
    }

    println!("\nPassive joint (eq. 4.32-4.33) under the back-driving hand (200 N m/rad, 5 N m s/rad), link 0.0432 kg m^2");
    println!("| T (ms) | I_m K_p | J (kg m^2) | w_n (rad/s) | zeta | decay (1/s) | max |z| | sampled decay (1/s) |");
    println!("|---|---|---|---|---|---|---|---|");
    let hand = mrr_control::control::HandContact {
        stiffness: 200.0,
        damping: 5.0,
        link_inertia: 0.64 * 0.45 * 0.45 / 3.0,
    };
    for (t, imkp) in [(4e-3, 0.2), (2.5e-4, 1.0), (2.5e-4, 3.0)] {
        let c = mrr_control::control::PassiveParams::table_4_1(imkp / 1.14e-5)
            .and_then(|p| p.characteristics(&hand, t))
            .map_err(|e| std::io::Error::other(format!("{e:?}")))?;
        println!(
            "| {} | {imkp} | {:.4} | {:.2} | {:.3} | {:.2} | {:.5} | {:.2} |",
            t * 1e3,
            c.apparent_inertia,
            c.natural_frequency,
            c.damping_ratio,
            c.decay_rate,
            c.spectral_radius,
            c.discrete_decay_rate
        );
    }

    println!(
        "\nFig. 4.11-4.12: hand back-driving the joint (+-0.5 rad, 4 s period, 200 N m/rad), 12 s"
    );
    println!("| T (ms) | I_m K_p | mode | hand torque RMS (N m) | hand torque max (N m) | lag RMS (mrad) | tau_t RMS (N m) |");
    println!("|---|---|---|---|---|---|---|");
    let mut csv = std::fs::File::create(dir.join("fig4_11_passive.csv"))?;
    writeln!(
        csv,
        "T_s,Im_Kp,mode,hand_rms_Nm,hand_max_Nm,lag_rms_rad,joint_torque_rms_Nm"
    )?;
    for (t, imkp) in [(4e-3, 0.2), (2.5e-4, 1.0), (2.5e-4, 3.0)] {
        for m in [
            BackDriveMode::Uncompensated,
            BackDriveMode::Estimated,
            BackDriveMode::Sensor,
        ] {
            let mut c = BackDriveConfig::new(m);
            c.sample_period = t;
            c.gain = imkp / 1.14e-5;
            let r = back_drive(&c);
            println!(
                "| {} | {imkp} | {} | {:.3} | {:.3} | {:.2} | {:.3} |",
                t * 1e3,
                m.label(),
                r.hand_torque.rms,
                r.hand_torque.max_abs(),
                r.lag.rms * 1e3,
                r.joint_torque.rms
            );
            writeln!(
                csv,
                "{t},{imkp},{},{},{},{},{}",
                m.label(),
                r.hand_torque.rms,
                r.hand_torque.max_abs(),
                r.lag.rms,
                r.joint_torque.rms
            )?;
        }
    }

    println!("\nFig. 3.8: 1 kg cut at 0.4 m from the horizontal joint (held, 0.1 ms tick)");
    let r = payload_drop(&PayloadDropConfig::default());
    println!("| signal | before (N m) | after (N m) | step (N m) | half-way time (ms) | settling, 25 % of true step (ms) | overshoot (% of step) |");
    println!("|---|---|---|---|---|---|---|");
    for (name, s) in [("true tau_t", r.truth), ("estimate", r.estimate)] {
        println!(
            "| {name} | {:.3} | {:.3} | {:.3} | {:.2} | {:.1} | {:.0} |",
            s.before,
            s.after,
            s.after - s.before,
            s.half_time * 1e3,
            s.settling_time * 1e3,
            100.0 * s.overshoot
        );
    }
    println!(
        "estimate error before: RMS {:.3} N m (min {:.3}, max {:.3}); after: RMS {:.3} N m",
        r.error_before.rms, r.error_before.min, r.error_before.max, r.error_after.rms
    );
    let mut csv = std::fs::File::create(dir.join("fig3_8_payload_drop.csv"))?;
    writeln!(csv, "t_s,true_torque_Nm,estimate_Nm")?;
    for (t, a, b) in &r.trace {
        writeln!(csv, "{t},{a},{b}")?;
    }

    println!("\nMode manager (estimated torque, 0.1 ms): hand leads the held joint 0.4 rad, lets go at 3 s");
    let r = interaction_scenario(&ModeScenarioConfig::interaction());
    let times: Vec<String> = r
        .switches
        .iter()
        .map(|e| format!("{:.3} s -> {:?}", e.time, e.to))
        .collect();
    println!("switches: {}", times.join(", "));
    let mut old = ModeScenarioConfig::interaction();
    old.release = Some(mrr_control::control::ReleaseRule::torque_only(20));
    println!(
        "the same with the torque-only release rule: {} switches",
        interaction_scenario(&old).switches.len()
    );
    let jump = r.switches.iter().map(|e| e.torque_jump).fold(0.0, f64::max);
    let off = r
        .switches
        .iter()
        .map(|e| e.reference_offset)
        .fold(0.0, f64::max);
    println!(
        "largest torque jump {jump:.3e} N m (bound {:.3e}); largest reference-vs-measured offset at a switch {off:.3e} rad",
        r.jump_bound
    );
    println!(
        "released at {:.4} rad; rejoin peak speed {:.3} rad/s (critically damped o0 w/e = {:.3}); tracking error while rejoining {:.2e} rad (motor); final {:.2e} rad from the hold",
        r.release_link_angle,
        r.rejoin_peak_speed,
        r.release_link_angle.abs() * 10.0 / std::f64::consts::E,
        r.rejoin_tracking_error,
        r.final_link_angle - r.final_desired
    );
    let mut csv = std::fs::File::create(dir.join("mode_interaction.csv"))?;
    writeln!(
        csv,
        "t_s,link_angle_rad,mode,estimate_Nm,true_torque_Nm,motor_torque_Nm"
    )?;
    for x in &r.trace {
        writeln!(
            csv,
            "{},{},{:?},{},{},{}",
            x.time, x.link_angle, x.mode, x.estimate, x.joint_torque, x.motor_torque
        )?;
    }
    println!(
        "Collision with a 300 N m/rad obstacle at 0.15 rad (threshold 3 N m on the estimate):"
    );
    println!("| reaction | contact (s) | detected (s) | latency (ms) | max penetration (mrad) | final link angle (rad) | final contact torque (N m) |");
    println!("|---|---|---|---|---|---|---|");
    for reaction in [CollisionReaction::Stop, CollisionReaction::Passive] {
        let mut c = ModeScenarioConfig::interaction();
        c.enter_passive = 1000.0;
        c.exit_passive = 500.0;
        c.collision = Some((3.0, 1.5, reaction));
        let r = collision_scenario(&c);
        println!(
            "| {reaction:?} | {:.4} | {:.4} | {:.1} | {:.2} | {:.4} | {:.3} |",
            r.contact_time,
            r.detection_time,
            (r.detection_time - r.contact_time) * 1e3,
            r.max_penetration * 1e3,
            r.final_link_angle,
            r.final_contact_torque
        );
    }
    println!("\n(total {:.1} s)", start.elapsed().as_secs_f64());
    Ok(())
}
