//! The fast door scene of `sim::door` (two task-space wrist axes, its own
//! integrator) over seeds 1–20: the median, quartiles and range of the
//! peak measured wrist–knob torque `max(|τ_δ|, |τ_γ|)` (N·m) in the three
//! runs, to set beside the engine scene's (`door_opening -- --seeds 20`),
//! which validates it (`sim::door`'s module docs).
//!
//! `cargo run --release --features sim --example door_approximation`

use mrr_control::sim::door::{door_opening, DoorConfig, DoorControl};

fn main() {
    for (name, control, heading) in [
        ("passive", DoorControl::Passive, 0.0),
        ("heading", DoorControl::Passive, 3f64.to_radians()),
        ("hold", DoorControl::ActiveHold, 0.0),
    ] {
        let mut v: Vec<f64> = (1..=20)
            .map(|s| door_opening(&DoorConfig::thesis(control, heading, s)).peak())
            .collect();
        v.sort_by(|a, b| a.total_cmp(b));
        // Order statistics of 20 values: the median between the 10th and
        // 11th, the quartiles at the 6th and 15th.
        println!(
            "{name}: median {:.2} min {:.2} max {:.2} q1 {:.2} q3 {:.2}",
            0.5 * (v[9] + v[10]),
            v[0],
            v[19],
            v[5],
            v[14]
        );
    }
}
