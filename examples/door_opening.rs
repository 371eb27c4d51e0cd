//! Door opening with the compact wrist (thesis §6.4.4, Fig. 6.19–6.20) on
//! the rigid-body engine ([`mrr_control::sim::engine::door`]): the mobile
//! base with wheel slip and jerks, the turret passive (eq. 4.32) on a
//! member of the joint family, the DAUJ wrist built from its parts and run
//! by the library's wrist step in admittance-passive mode at 4 ms on `f32`,
//! a hinged door.
//! Three runs per seed — passive, passive with a 3° initial heading error,
//! and wrist and turret held active (contrast) — and the verdicts of the
//! chapter-6 claims ([`mrr_control::sim::claims::ch6`]) with median and
//! spread over the seeds.
//!
//! ```text
//! cargo run --release --features sim --example door_opening                  # 3 seeds (quick)
//! cargo run --release --features sim --example door_opening -- --seeds 20    # the claims' sweep
//! cargo run --release --features sim --example door_opening -- --straight    # study: grasp at the straight pose
//! ```
//!
//! Writes `target/figures/door_opening.svg` (peak interaction torque over
//! the door angle, median and min–max band over the seeds, all three runs)
//! and `target/figures/door_opening.csv` (per-seed peaks; the first seed's
//! time series) under `$CARGO_TARGET_DIR` if set.

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use mrr_control::sim::claims::ch6::{claims, run_door, DoorRunMetrics};
use mrr_control::sim::claims::{evaluate, Runs};
use mrr_control::sim::engine::door::{door_engine_settings, DoorBody, EngineDoorRun};
use plotters::prelude::*;

type Error = Box<dyn std::error::Error>;

const RUNS: [&str; 3] = [
    "passive",
    "passive, 3° heading error",
    "held active (contrast)",
];
const COLORS: [RGBColor; 3] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(214, 39, 40),
];

fn main() -> Result<(), Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut seeds: u64 = 3;
    if let Some(i) = args.iter().position(|a| a == "--seeds") {
        seeds = args
            .get(i + 1)
            .and_then(|s| s.parse().ok())
            .filter(|&n| n > 0)
            .ok_or("--seeds needs a positive integer")?;
    }
    let straight = args.iter().any(|a| a == "--straight");
    let mut engine = door_engine_settings();
    if args.iter().any(|a| a == "--half-step") {
        engine = engine.with_half_step();
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let start = Instant::now();
    let pitch = if straight { Some(0.0) } else { None };
    let runs = run_door(seeds, pitch, &engine, threads)?;
    let wall = start.elapsed().as_secs_f64();
    println!(
        "door opening on the engine (dt = {} ms, controllers at 4 ms on f32): {} seeds × 3 runs in {wall:.1} s on {threads} threads{}",
        engine.dt() * 1e3,
        seeds,
        if straight {
            "; STUDY: grasp at the straight pose (not the claims' operating point)"
        } else {
            ""
        }
    );
    println!(
        "peak max(|τ_δ|, |τ_γ|) in N·m, measured by the F/T chain and true (engine); door: mass kg, hinge Coulomb N·m, closer N·m/rad"
    );
    println!(
        "{:>4} {:>6} {:>6} {:>6} {:>6} | {:>8} {:>8} {:>8} | {:>6} {:>6} {:>6} | final door angle (deg)",
        "seed", "δ0°", "kg", "hinge", "closer", "passive", "heading", "hold", "true", "true", "true"
    );
    for (m, _) in &runs {
        let d = DoorBody::draw(m.seed);
        println!(
            "{:>4} {:>6.1} {:>6.1} {:>6.2} {:>6.2} | {:>8.2} {:>8.2} {:>8.2} | {:>6.2} {:>6.2} {:>6.2} | {:.1} {:.1} {:.1}",
            m.seed,
            m.start_pitch.to_degrees(),
            d.mass,
            d.hinge_coulomb,
            d.closer_stiffness,
            m.nominal,
            m.heading,
            m.hold,
            m.true_peaks[0],
            m.true_peaks[1],
            m.true_peaks[2],
            m.door_angle[0].to_degrees(),
            m.door_angle[1].to_degrees(),
            m.door_angle[2].to_degrees(),
        );
    }
    let metrics: Vec<DoorRunMetrics> = runs.iter().map(|(m, _)| *m).collect();
    if straight {
        println!("(a study at another start pose: no verdicts)");
    } else {
        println!();
        for r in evaluate(
            &claims()?,
            &Runs {
                door: &metrics,
                ..Runs::default()
            },
        )? {
            println!(
                "{:<14} {}; {}",
                r.claim.id,
                r.verdict_line(),
                r.claim.criterion.describe(r.claim.unit)
            );
            println!(
                "{:<14} thesis: \"{}\" ({})",
                "", r.claim.quote, r.claim.figure
            );
        }
    }
    let base = std::env::var("CARGO_TARGET_DIR").unwrap_or_else(|_| "target".into());
    let dir = Path::new(&base).join("figures");
    std::fs::create_dir_all(&dir)?;
    let name = if straight {
        "door_opening_straight"
    } else {
        "door_opening"
    };
    write_csv(&dir.join(format!("{name}.csv")), &runs)?;
    draw(&dir.join(format!("{name}.svg")), &runs, straight)?;
    println!(
        "wrote {0}/{name}.svg and {0}/{name}.csv ({1:.1} s in all)",
        dir.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn write_csv(path: &Path, runs: &[(DoorRunMetrics, [EngineDoorRun; 3])]) -> Result<(), Error> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(
        f,
        "# per seed: seed,start_pitch_deg,passive_Nm,heading_Nm,hold_Nm,true_passive_Nm,true_heading_Nm,true_hold_Nm"
    )?;
    for (m, _) in runs {
        writeln!(
            f,
            "seed,{},{:.3},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4}",
            m.seed,
            m.start_pitch.to_degrees(),
            m.nominal,
            m.heading,
            m.hold,
            m.true_peaks[0],
            m.true_peaks[1],
            m.true_peaks[2]
        )?;
    }
    writeln!(
        f,
        "# first seed, every 4 ms: run,time_s,door_deg,turret_deg,delta_deg,gamma_deg,delta_ref_deg,gamma_ref_deg,tau_delta_meas_Nm,tau_gamma_meas_Nm,tau_delta_true_Nm,tau_gamma_true_Nm"
    )?;
    if let Some((_, three)) = runs.first() {
        for (i, r) in three.iter().enumerate() {
            for s in &r.samples {
                writeln!(
                    f,
                    "{i},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.4},{:.4},{:.4},{:.4}",
                    s.time,
                    s.door.to_degrees(),
                    s.turret.to_degrees(),
                    s.wrist[0].to_degrees(),
                    s.wrist[1].to_degrees(),
                    s.reference[0].to_degrees(),
                    s.reference[1].to_degrees(),
                    s.measured[0],
                    s.measured[1],
                    s.interaction[0],
                    s.interaction[1]
                )?;
            }
        }
    }
    Ok(())
}

/// Per run kind: for each 1° bin of door angle, the largest measured
/// `max(|τ_δ|, |τ_γ|)` of each seed in that bin, then the median and the
/// min–max over the seeds.
fn bands(runs: &[(DoorRunMetrics, [EngineDoorRun; 3])], kind: usize) -> Vec<(f64, f64, f64, f64)> {
    let bins = 96;
    let mut per_seed = vec![vec![f64::NAN; bins]; runs.len()];
    for (j, (_, three)) in runs.iter().enumerate() {
        for s in &three[kind].samples {
            let b = s.door.to_degrees().floor();
            if !(0.0..bins as f64).contains(&b) {
                continue;
            }
            let v = s.measured[0].abs().max(s.measured[1].abs());
            let cell = &mut per_seed[j][b as usize];
            *cell = if cell.is_nan() { v } else { cell.max(v) };
        }
    }
    (0..bins)
        .filter_map(|b| {
            let mut v: Vec<f64> = per_seed
                .iter()
                .map(|s| s[b])
                .filter(|x| !x.is_nan())
                .collect();
            if v.is_empty() {
                return None;
            }
            v.sort_by(|a, b| a.total_cmp(b));
            let n = v.len();
            let median = if n % 2 == 1 {
                v[n / 2]
            } else {
                0.5 * (v[n / 2 - 1] + v[n / 2])
            };
            Some((b as f64 + 0.5, median, v[0], v[n - 1]))
        })
        .collect()
}

fn draw(
    path: &Path,
    runs: &[(DoorRunMetrics, [EngineDoorRun; 3])],
    straight: bool,
) -> Result<(), Error> {
    let all: Vec<Vec<(f64, f64, f64, f64)>> = (0..3).map(|k| bands(runs, k)).collect();
    let ymax = all
        .iter()
        .flatten()
        .map(|p| p.3)
        .fold(3.5f64, f64::max)
        .min(if straight { 150.0 } else { 20.0 });
    let root = SVGBackend::new(path, (900, 500)).into_drawing_area();
    root.fill(&WHITE)?;
    let title = format!(
        "Door opening on the engine: wrist–knob interaction torque ({} seeds, median and min–max){}",
        runs.len(),
        if straight { ", grasp at the straight pose" } else { "" }
    );
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..96.0, 0.0..ymax * 1.25)?;
    chart
        .configure_mesh()
        .x_desc("door angle (deg)")
        .y_desc("peak measured max(|τ_δ|, |τ_γ|) per 1° (N·m)")
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    for (k, band) in all.iter().enumerate() {
        let color = COLORS[k];
        let mut outline: Vec<(f64, f64)> =
            band.iter().map(|p| (p.0, p.3.min(ymax * 1.25))).collect();
        outline.extend(band.iter().rev().map(|p| (p.0, p.2.min(ymax * 1.25))));
        chart.draw_series(std::iter::once(Polygon::new(
            outline,
            color.mix(0.18).filled(),
        )))?;
        chart
            .draw_series(LineSeries::new(
                band.iter().map(|p| (p.0, p.1.min(ymax * 1.25))),
                color.stroke_width(2),
            ))?
            .label(RUNS[k])
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    for (level, text) in [
        (2.0, "thesis: < 2 N·m (passive)"),
        (3.0, "thesis: 3 N·m (3° heading error)"),
    ] {
        chart.draw_series(LineSeries::new(
            vec![(0.0, level), (96.0, level)],
            RGBColor(120, 120, 120).stroke_width(1),
        ))?;
        chart.draw_series(std::iter::once(Text::new(
            text,
            (1.0, level + 0.03 * ymax),
            ("sans-serif", 12).into_font().color(&BLACK),
        )))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
