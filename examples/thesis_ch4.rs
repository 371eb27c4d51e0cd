//! Thesis ch. 4 closed-loop experiments in simulation: prints the tables
//! and writes CSV to `target/figures/`.
//!
//! `cargo run --release --features sim --example thesis_ch4`

use mrr_control::sim::closed_loop::{
    active_tracking, bound_run, BoundCase, JointTorqueFeedback, TrackingConfig,
};

fn main() {
    for (ef, sq, fr) in [
        (0.9, 0.0, 0.0),
        (20.0, 1e9, 0.0),
        (40.0, 1e9, 0.0),
        (60.0, 1e9, 0.0),
        (40.0, 0.25, 0.0),
    ] {
        let case = BoundCase {
            friction: [1e-5, 0.010, 0.002],
            stribeck: 1.0,
            tilt: 0.2,
            tilt_direction: 0.3,
            payload: 1.0,
            payload_distance: 0.4,
            amplitude: 0.2 + fr,
            period: 2.0,
            error_fraction: ef,
            error_square_period: sq,
            seed: 1,
        };
        let t0 = std::time::Instant::now();
        let r = bound_run(&case, 0.5);
        println!("{ef} {sq}: delta {:.4} rbar {:.2} rS {:.2} maxr {:.3} fe {:.2} sat {} ratio {:.2} ts {:.4} {:?}", r.sampling_disturbance, r.radius, r.bound.sliding_radius, r.max_sliding, r.max_feedback_error, r.saturated_samples, r.step_ratio, r.reaching_time, t0.elapsed());
    }
    println!("Fig. 4.2-4.3: active tracking, Table 4.1 law");
    println!("| T (ms) | feedback | link max (mrad) | link RMS (mrad) | motor max (rad) | motor RMS (rad) | fb err RMS (N·m) | sat % |");
    for t in [4e-3, 2.5e-4] {
        for fb in [
            JointTorqueFeedback::None,
            JointTorqueFeedback::Sensor,
            JointTorqueFeedback::Estimated,
        ] {
            let r = active_tracking(&TrackingConfig::table_4_1(fb, t));
            println!(
                "| {} | {} | {:.3} | {:.3} | {:.4} | {:.4} | {:.3} | {:.1} |",
                t * 1e3,
                fb.label(),
                r.link_error.max_abs() * 1e3,
                r.link_error.rms * 1e3,
                r.motor_error.max_abs(),
                r.motor_error.rms,
                r.feedback_error.rms,
                100.0 * r.saturated_fraction
            );
        }
    }
}
