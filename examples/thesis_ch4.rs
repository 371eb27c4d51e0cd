//! Thesis ch. 4 closed-loop experiments in simulation: prints the tables
//! and writes CSV to `target/figures/`.
//!
//! `cargo run --release --features sim --example thesis_ch4`

use mrr_control::sim::closed_loop::{active_tracking, JointTorqueFeedback, TrackingConfig};

fn main() {
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
