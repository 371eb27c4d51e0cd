//! The claims registry as a table: each claim of chapters 2–4 and 6 with
//! its criterion, verdict, median and spread over the independent plant
//! families × seeds (chapter 2 on the drive bench, chapters 3–4 on the
//! dynamic joint at the thesis's 4 ms, chapter 6 on the engine: the door
//! opening of §6.4.4 and the wrist bench of §6.4.3, the library's steps at
//! 4 ms on `f32`).
//!
//! ```text
//! cargo run --release --features sim --example claims               # full: 216 drive + 24 joint plants, door, bench × 20 seeds
//! cargo run --release --features sim --example claims -- --quick    # 4 drive + 2 joint plants, door, bench × 3 seeds
//! cargo run --release --features sim --example claims -- 2.19-blind # one claim
//! cargo run --release --features sim --example claims -- --seeds 5
//! ```

use std::time::Instant;

use mrr_control::sim::claims::ch6::{run_bench, run_door};
use mrr_control::sim::claims::{
    evaluate, registry, run, run_joint, JointRunMetrics, Metric, RunMetrics, Runs, Spread, RERUN,
};
use mrr_control::sim::engine::door::door_engine_settings;
use mrr_control::sim::plants::{
    family, joint_family, quick_family, quick_joint_family, DrivePlant, JointPlant,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let mut seeds: u64 = if quick { 3 } else { 20 };
    if let Some(i) = args.iter().position(|a| a == "--seeds") {
        seeds = args
            .get(i + 1)
            .and_then(|s| s.parse().ok())
            .ok_or("--seeds needs a positive integer")?;
    }
    let only: Vec<&String> = args
        .iter()
        .enumerate()
        .filter(|(i, a)| !a.starts_with("--") && (*i == 0 || args[i - 1] != "--seeds"))
        .map(|(_, a)| a)
        .collect();

    let claims: Vec<_> = registry()?
        .into_iter()
        .filter(|c| only.is_empty() || only.iter().any(|o| o.as_str() == c.id))
        .collect();
    let need_drive = claims.iter().any(|c| matches!(c.metric, Metric::Drive(_)));
    let need_joint = claims.iter().any(|c| matches!(c.metric, Metric::Joint(_)));
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());

    let start = Instant::now();
    let plants: Vec<DrivePlant> = match (need_drive, quick) {
        (false, _) => Vec::new(),
        (true, true) => quick_family(),
        (true, false) => family(),
    };
    let runs = if need_drive {
        run(&plants, seeds)?
    } else {
        Vec::new()
    };
    let drive_time = start.elapsed();
    let joints: Vec<JointPlant> = match (need_joint, quick) {
        (false, _) => Vec::new(),
        (true, true) => quick_joint_family(),
        (true, false) => joint_family(),
    };
    let joint_runs = if need_joint {
        run_joint(&joints, seeds, threads)?
    } else {
        Vec::new()
    };
    let joint_time = start.elapsed();
    // Chapter 6 on the engine: the same seeds whatever the mode (the
    // scenes draw their own door, push and sensor error per seed).
    let need_door = claims.iter().any(|c| matches!(c.metric, Metric::Door(_)));
    let need_bench = claims
        .iter()
        .any(|c| matches!(c.metric, Metric::WristBench(_)));
    let engine = door_engine_settings();
    let door: Vec<_> = if need_door {
        run_door(seeds, None, &engine, threads)?
            .into_iter()
            .map(|(m, _)| m)
            .collect()
    } else {
        Vec::new()
    };
    let bench = if need_bench {
        run_bench(seeds, &engine, threads)?
    } else {
        Vec::new()
    };
    let wall = start.elapsed();
    let results = evaluate(
        &claims,
        &Runs {
            drive: &runs,
            joint: &joint_runs,
            door: &door,
            bench: &bench,
        },
    )?;

    println!(
        "drive: {} plants × {} seeds = {} runs in {:.1} s; joint (4 ms): {} plants × {} seeds = {} runs in {:.1} s; engine (dt = {} ms): door {} seeds × 3 runs, wrist bench {} seeds × 2 cases in {:.1} s; on {threads} threads; total {:.1} s (wall)",
        plants.len(),
        seeds,
        runs.len(),
        drive_time.as_secs_f64(),
        joints.len(),
        seeds,
        joint_runs.len(),
        (joint_time - drive_time).as_secs_f64(),
        engine.dt() * 1e3,
        door.len(),
        bench.len(),
        (wall - joint_time).as_secs_f64(),
        wall.as_secs_f64()
    );
    println!();
    println!(
        "| claim | figure | at | criterion | verdict | median | spread (min / q1 / q3 / max) | share sup./ref. | runs |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for r in &results {
        let s = r.spread;
        println!(
            "| {} | {} | {} | {} | **{}** | {:.3e} | {:.3e} / {:.3e} / {:.3e} / {:.3e} | {:.2} / {:.2} | {} |",
            r.claim.id,
            r.claim.figure,
            r.claim.operating_point,
            r.claim.criterion.describe(r.claim.unit),
            r.verdict,
            s.median,
            s.min,
            s.q1,
            s.q3,
            s.max,
            r.shares.0,
            r.shares.1,
            r.runs
        );
    }
    println!();
    for r in &results {
        println!("{}: \"{}\"", r.claim.id, r.claim.quote);
        let unit = if r.claim.unit.is_empty() {
            "dimensionless"
        } else {
            r.claim.unit
        };
        println!("  metric: {} [{unit}]", r.claim.metric_name);
        println!("  thresholds: {}", r.claim.justification);
        let mode = if quick { " --quick" } else { "" };
        println!("  rerun: {RERUN}{mode} {}", r.claim.id);
    }

    // Where the verdicts come from: medians by the swept choices.
    if !joint_runs.is_empty() {
        println!();
        println!("Joint medians by plant (est. peak fit / none N·m; RMS fit / none / Table 3.2 N·m; 3.7 residual; T1 ratio preset / Table 4.1; active share; link RMS A/B/C rad; step share; hand RMS A/B/C N·m):");
        for (i, p) in joints.iter().enumerate() {
            let sel: Vec<&JointRunMetrics> = joint_runs.iter().filter(|m| m.plant == i).collect();
            let med = |f: &dyn Fn(&JointRunMetrics) -> f64| {
                Spread::of(&sel.iter().map(|m| f(m)).collect::<Vec<_>>())
                    .map_or(f64::NAN, |s| s.median)
            };
            println!(
                "  {:>2} {}: {:.2}/{:.2}; {:.2}/{:.2}/{:.2}; {:.2}; {:.2}/{:.2}; {:.3}; {:.2e}/{:.2e}/{:.2e}; {:.2}; {:.2}/{:.2}/{:.2}",
                i,
                p.label(),
                med(&|m| m.est_peak_fit),
                med(&|m| m.est_peak_none),
                med(&|m| m.est_rms_fit),
                med(&|m| m.est_rms_none),
                med(&|m| m.est_rms_table),
                med(&|m| m.ke_fit_residual),
                med(&|m| m.preset_bound_ratio),
                med(&|m| m.thesis_bound_ratio),
                med(&|m| m.preset_active_share),
                med(&|m| m.link_rms_none),
                med(&|m| m.link_rms_sensor),
                med(&|m| m.link_rms_estimate),
                med(&|m| m.step_share),
                med(&|m| m.hand_rms_none),
                med(&|m| m.hand_rms_estimate),
                med(&|m| m.hand_rms_sensor),
            );
        }
    }
    if runs.is_empty() {
        return Ok(());
    }
    println!();
    println!("Medians by open choice (reduction blind / oracle; peak |e| rad of 2.11 and 2.30 blind; held 2.30 blind):");
    let group = |name: &str, key: &dyn Fn(&DrivePlant) -> String| {
        let mut keys: Vec<String> = plants.iter().map(key).collect();
        keys.sort();
        keys.dedup();
        for k in keys {
            let sel: Vec<&RunMetrics> =
                runs.iter().filter(|m| key(&plants[m.plant]) == k).collect();
            let med = |f: &dyn Fn(&RunMetrics) -> f64| {
                Spread::of(&sel.iter().map(|m| f(m)).collect::<Vec<_>>())
                    .map_or(f64::NAN, |s| s.median)
            };
            println!(
                "  {name} {k:>14}: {:+.3} / {:+.3}; {:.2e} {:.2e}; held {:.2e}  ({} runs)",
                med(&|m| m.reduction_blind()),
                med(&|m| m.reduction_oracle()),
                med(&|m| m.locked_classic_blind),
                med(&|m| m.locked_proposed_blind),
                med(&|m| m.held_proposed_blind),
                sel.len()
            );
        }
    };
    group("node share", &|p| format!("{:.1}", p.node_share));
    group("amplitude", &|p| format!("{:.0} N·m", p.amplitude));
    group("backbone", &|p| p.backbone.name().to_string());
    group("bearing", &|p| p.wave_generator.name().to_string());
    group("mesh F", &|p| {
        format!("{:.1} N·m", p.mesh_friction.breakaway())
    });
    group("ripple", &|p| format!("{:.0e}", p.ripple));
    Ok(())
}
