//! The wrist bench of thesis §6.4.3 on the engine
//! ([`mrr_control::sim::engine::wrist_bench`]): checks that can fail.

use mrr_control::sim::engine::door::door_engine_settings;
use mrr_control::sim::engine::wrist_bench::{engine_finger_push, FingerCase, FingerPush};

#[test]
fn probe() {
    let e = door_engine_settings();
    let t = std::time::Instant::now();
    for case in [FingerCase::MotorsOff, FingerCase::Admittance] {
        let r = engine_finger_push(case, &FingerPush::nominal(1), &e).unwrap();
        println!(
            "{case:?}: peak_meas {:.3} peak_true {:.3} held {:.3} travel {:.4} slip {:.5} loop {:.2e} off {} ({:.1?})",
            r.peak_measured, r.peak_interaction, r.held, r.travel, r.slip, r.loop_error, r.off_mode_ticks, t.elapsed()
        );
        for s in r.samples.iter().step_by(100) {
            println!("  t {:.2} pose {:.4?} meas {:.3?} true {:.3?} m {:.4?} slip {:.2e}", s.time, s.pose, s.measured, s.interaction, s.motor_torque, s.slip);
        }
    }
}
