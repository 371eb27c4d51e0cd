//! The wrist bench of thesis §6.4.3 (Fig. 6.13–6.17) on the rigid-body
//! engine ([`mrr_control::sim::engine::wrist_bench`]): a finger pushes the
//! output link of the DAUJ built from its parts, with the motors off
//! (Case 1) and under the library's wrist step in the admittance-passive
//! mode at 4 ms (Case 2), on `f32` (the claims' operating point) and on
//! `I16F16` fixed point (beside it, same seeds). Per seed the push (direction, travel,
//! speed) and the gear break-away are drawn ([`FingerPush::draw`]); the
//! verdicts of the bench claims ([`mrr_control::sim::claims::ch6::bench_claims`])
//! with median and spread (on `f32`; the same criteria applied to the
//! `I16F16` runs are printed as a study), the comparison with the home-made bench
//! ([`mrr_control::sim::wrist_bench`]) on its nominal push, and the engine
//! step's convergence by halving on seed 1.
//!
//! ```text
//! cargo run --release --features sim --example wrist_bench                  # 20 seeds
//! cargo run --release --features sim --example wrist_bench -- --seeds 40
//! cargo run --release --features sim --example wrist_bench -- --straight   # + study: a push through the straight pose
//! ```

use std::time::Instant;

use mrr_control::sim::claims::ch6::{bench_claims, bench_seed, run_bench, run_bench_on};
use mrr_control::sim::claims::{evaluate, Runs};
use mrr_control::sim::engine::door::{door_engine_settings, Backend};
use mrr_control::sim::engine::wrist_bench::{
    engine_finger_push_from, engine_finger_push_on, engine_wrist_tracking_on, FingerCase,
    FingerPush,
};
use mrr_control::sim::wrist_bench::{self as home, wrist_finger_push};

type Error = Box<dyn std::error::Error>;

fn main() -> Result<(), Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut seeds: u64 = 20;
    if let Some(i) = args.iter().position(|a| a == "--seeds") {
        seeds = args
            .get(i + 1)
            .and_then(|s| s.parse().ok())
            .filter(|&n| n > 0)
            .ok_or("--seeds needs a positive integer")?;
    }
    let engine = door_engine_settings();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let start = Instant::now();
    let runs = run_bench(seeds, &engine, threads)?;
    let runs_fx = run_bench_on(seeds, &engine, threads, Backend::I16F16)?;
    println!(
        "wrist bench on the engine (dt = {} ms, wrist step at 4 ms on f32 and on I16F16): {} seeds × 2 cases × 2 backends in {:.1} s on {threads} threads",
        engine.dt() * 1e3,
        runs.len(),
        start.elapsed().as_secs_f64()
    );
    println!(
        "{:>4} {:>6} {:>7} {:>6} | {:>9} {:>8} | {:>9} {:>8} {:>8} | {:>6} || {:>9} {:>9} {:>8}",
        "seed",
        "ψ°",
        "ẋ_f",
        "B",
        "1: held",
        "travel°",
        "2: peak",
        "travel°",
        "finger°",
        "ẋ_f/K_c",
        "fx 1: held",
        "fx 2: peak",
        "travel°"
    );
    for (m, x) in runs.iter().zip(&runs_fx) {
        println!(
            "{:>4} {:>6.1} {:>7.3} {:>6.2} | {:>9.2} {:>8.2} | {:>9.2} {:>8.2} {:>8.2} | {:>6.2} || {:>10.2} {:>10.2} {:>8.2}",
            m.seed,
            m.direction.to_degrees(),
            m.finger_speed,
            m.breakaway,
            m.case1_held,
            m.case1_travel.to_degrees(),
            m.case2_peak,
            m.case2_travel.to_degrees(),
            m.finger_travel.to_degrees(),
            m.finger_speed / 0.1,
            x.case1_held,
            x.case2_peak,
            x.case2_travel.to_degrees()
        );
    }
    println!("(ψ: push direction from pitch; ẋ_f: the fingertip's peak speed at the tool, rad/s; B: gear break-away, N·m at the joint; torques N·m; the columns left of || on f32, fx: the same seeds on I16F16)");
    println!();
    for (label, bench) in [("f32", &runs), ("I16F16", &runs_fx)] {
        if label != "f32" {
            println!("the same criteria on the I16F16 runs (a study beside the claims' f32 operating point):");
        }
        for r in evaluate(
            &bench_claims()?,
            &Runs {
                bench,
                ..Runs::default()
            },
        )? {
            println!(
                "{:<15} {} ({label}); {}",
                r.claim.id,
                r.verdict_line(),
                r.claim.criterion.describe(r.claim.unit)
            );
            if label == "f32" {
                println!(
                    "{:<15} thesis: \"{}\" ({})",
                    "", r.claim.quote, r.claim.figure
                );
            }
        }
    }
    // The home-made bench against the engine on the nominal push.
    println!();
    let nominal = FingerPush::nominal(1);
    let h_off = wrist_finger_push(home::FingerCase::MotorsOff, 8.0, 1);
    let h_on = wrist_finger_push(home::FingerCase::Admittance, 8.0, 1);
    println!("nominal push (pitch, 12° over 1.5 s, B = 12 N·m): home-made bench vs engine");
    for (label, backend) in [("f32", Backend::F32), ("I16F16", Backend::I16F16)] {
        let e_off = engine_finger_push_on(FingerCase::MotorsOff, &nominal, &engine, backend)?;
        let e_on = engine_finger_push_on(FingerCase::Admittance, &nominal, &engine, backend)?;
        println!(
            "  Case 2 peak |τ| (N·m): home pitch {:.2} | engine on {label} {:.2} (true {:.2}); travel: home {:.2}° | engine {:.2}°",
            h_on.peak_interaction[0],
            e_on.peak_measured,
            e_on.peak_interaction,
            h_on.travel[0].to_degrees(),
            e_on.travel.to_degrees()
        );
        println!(
            "  Case 1: home peak pitch {:.2} N·m (12° push), travel {:.3}° | engine on {label} held {:.2} N·m (25° push), travel {:.3}°, slip {:.2e} rad",
            h_off.peak_interaction[0],
            h_off.travel[0].to_degrees(),
            e_off.held,
            e_off.travel.to_degrees(),
            e_off.slip
        );
    }
    // Convergence by halving the engine step (seed 1's draw).
    let half = engine.with_half_step();
    let a = bench_seed(1, &engine)?;
    let b = bench_seed(1, &half)?;
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(1e-9);
    println!(
        "halving dt ({} → {} ms), seed 1: Case 1 held {:.3} → {:.3} ({:.2} %), Case 2 peak {:.3} → {:.3} ({:.2} %), Case 2 travel {:.3}° → {:.3}° ({:.2} %)",
        engine.dt() * 1e3,
        half.dt() * 1e3,
        a.case1_held,
        b.case1_held,
        100.0 * rel(a.case1_held, b.case1_held),
        a.case2_peak,
        b.case2_peak,
        100.0 * rel(a.case2_peak, b.case2_peak),
        a.case2_travel.to_degrees(),
        b.case2_travel.to_degrees(),
        100.0 * rel(a.case2_travel, b.case2_travel)
    );
    // Active tracking (Fig. 6.10): engine against the home-made bench.
    let h = home::wrist_tracking(6.0, 1.0);
    let hmax = h
        .position_error
        .map(|e| e.max.abs().max(e.min.abs()).to_degrees());
    for (label, backend) in [("f32", Backend::F32), ("I16F16", Backend::I16F16)] {
        let t = engine_wrist_tracking_on(6.0, 1.0, &engine, backend)?;
        println!(
            "active tracking (6 s, after 1 s): max |δ−δ_d|, |γ−γ_d| engine on {label} {:.3}°, {:.3}° (RMS {:.3}°, {:.3}°) | home-made {:.3}°, {:.3}°",
            t.max_error[0].to_degrees(),
            t.max_error[1].to_degrees(),
            t.rms_error[0].to_degrees(),
            t.rms_error[1].to_degrees(),
            hmax[0],
            hmax[1]
        );
    }
    if args.iter().any(|a| a == "--straight") {
        // Study (not the claims' operating point): the nominal push from 3°
        // of pitch, away from the straight pose and through it.
        for (label, backend) in [("f32", Backend::F32), ("I16F16", Backend::I16F16)] {
            for psi in [0.0f64, 180.0] {
                let p = FingerPush {
                    direction: psi.to_radians(),
                    ..FingerPush::nominal(1)
                };
                let start = 3f64.to_radians();
                let r =
                    engine_finger_push_from(FingerCase::Admittance, &p, start, &engine, backend)?;
                println!(
                    "STUDY straight pose ({label}): from 3° of pitch, ψ = {psi}°: Case 2 peak {:.2} N·m (true {:.2}), travel {:.2}°, loop error {:.1e} rad",
                    r.peak_measured,
                    r.peak_interaction,
                    r.travel.to_degrees(),
                    r.loop_error
                );
            }
        }
    }
    println!("{:.1} s in all", start.elapsed().as_secs_f64());
    Ok(())
}
