//! The claims registry as a table: each chapter-2 claim with its criterion,
//! verdict, median and spread over the independent plant family × seeds.
//!
//! ```text
//! cargo run --release --features sim --example claims               # full: 216 plants × 20 seeds
//! cargo run --release --features sim --example claims -- --quick    # 4 plants × 3 seeds
//! cargo run --release --features sim --example claims -- 2.19-blind # one claim
//! cargo run --release --features sim --example claims -- --seeds 5
//! ```

use std::time::Instant;

use mrr_control::sim::claims::{evaluate, registry, run, RunMetrics, Spread, RERUN};
use mrr_control::sim::plants::{family, quick_family, DrivePlant};

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

    let start = Instant::now();
    let plants: Vec<DrivePlant> = if quick { quick_family() } else { family() };
    let built = start.elapsed();
    let runs = run(&plants, seeds)?;
    let wall = start.elapsed();
    let claims: Vec<_> = registry()?
        .into_iter()
        .filter(|c| only.is_empty() || only.iter().any(|o| o.as_str() == c.id))
        .collect();
    let results = evaluate(&claims, &runs)?;

    println!(
        "{} plants × {} seeds = {} runs; family built in {:.1} s, runs done in {:.1} s (wall)",
        plants.len(),
        seeds,
        runs.len(),
        built.as_secs_f64(),
        wall.as_secs_f64()
    );
    println!();
    println!(
        "| claim | figure | criterion | verdict | median | spread (min / q1 / q3 / max) | share sup./ref. | runs |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for r in &results {
        let s = r.spread;
        println!(
            "| {} | {} | {} | **{}** | {:.3e} | {:.3e} / {:.3e} / {:.3e} / {:.3e} | {:.2} / {:.2} | {} |",
            r.claim.id,
            r.claim.figure,
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

    // Where the verdict comes from: medians by the swept choices.
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
