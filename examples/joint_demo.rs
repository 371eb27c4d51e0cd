//! One joint from a catalogue sheet to a running controller, on `f32`:
//!
//! 1. the SHD-17-100 catalogue sheet → the identified compliance model
//!    (eq. 2.30, [`CatalogueData::identify`]);
//! 2. the drive, the Table 3.2 kinematic error and the encoders → the
//!    torque estimator (eq. 3.8–3.10);
//! 3. the estimator and the mode manager (active eq. 4.19, passive
//!    eq. 4.32) → one [`JointConfig<f32>`], stepped from raw encoder counts;
//! 4. on the simulated thesis joint (`sim`): follow a trajectory (0–3 s),
//!    let a hand guide the link (3–5.5 s: the joint goes passive), let go
//!    and rejoin the trajectory (5.5–8 s).
//!
//! Prints what a user checks (tracking RMS, the torque the hand needed,
//! the estimate's error, every mode switch) and writes
//! `joint_demo.svg` to `DIR` (first argument), else
//! `$CARGO_TARGET_DIR/figures`, else `target/figures`.
//!
//! ```text
//! cargo run --release --features sim --example joint_demo
//! ```

use mrr_control::control::{
    JointMode, ModeParams, ModeSettings, PassiveParams, PassiveSettings, RobustAdaptiveParams,
};
use mrr_control::estimation::torque::{TorqueEstimatorParams, TorqueEstimatorSettings};
use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::joint::{JointConfig, JointParams, JointReadings, JointSettings, JointTarget};
use mrr_control::sim::closed_loop::{bound_design, fine_motor_encoder, identified_motor_friction};
use mrr_control::sim::mrr::{ModuleParams, Mrr};
use plotters::prelude::*;
use std::f64::consts::PI;
use std::path::PathBuf;

/// Control tick, s (the sampled law keeps its boundary layers here,
/// errata E4.4).
const TICK: f64 = 1e-4;
const DURATION: f64 = 8.0;
/// The hand holds the link from `HAND_ON` to `HAND_OFF`, s.
const HAND_ON: f64 = 3.0;
const HAND_OFF: f64 = 5.5;

/// The desired link trajectory `(q, q̇, q̈)`: `0.2 (1 − cos πt)` rad.
fn desired(t: f64) -> (f64, f64, f64) {
    let (s, c) = (PI * t).sin_cos();
    (0.2 * (1.0 - c), 0.2 * PI * s, 0.2 * PI * PI * c)
}

/// The guiding hand: a spring (200 N·m/rad) and damper (5 N·m·s/rad) whose
/// end moves from where it grabbed the link (`start`) by +0.4 rad along a
/// raised cosine until it lets go at `HAND_OFF`.
fn hand(t: f64, start: f64, q: f64, v: f64) -> f64 {
    if !(HAND_ON..HAND_OFF).contains(&t) {
        return 0.0;
    }
    let d = HAND_OFF - HAND_ON;
    let (s, c) = (PI * (t - HAND_ON) / d).sin_cos();
    let (qh, vh) = (start + 0.2 * (1.0 - c), 0.2 * PI * s / d);
    200.0 * (qh - q) + 5.0 * (vh - v)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = std::time::Instant::now();
    let module = fine_motor_encoder(ModuleParams::thesis_joint());

    // 1. Catalogue sheet → drive model.
    let drive = CatalogueData::SHD_17_100.identify()?;
    let f = drive.flexspline();
    println!("1. SHD-17-100 catalogue sheet → eq. (2.30) model:");
    println!(
        "   K_f0 = {:.1} N·m/rad, c_f = {:.4} 1/(N·m), N = {}",
        f.k_f0(),
        f.c_f(),
        drive.ratio()
    );

    // 2. Drive + kinematic error + encoders → torque estimator.
    let estimator = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive,
        kinematic_error: Some(KinematicErrorModel::table_3_2()),
        link_counts_per_rev: module.link_encoder.counts_per_rev,
        motor_counts_per_rev: module.motor_encoder.counts_per_rev,
        max_torque: 60.0,
    })?;
    println!(
        "2. estimator: link encoder L = {}, motor encoder M = {} counts/rev",
        estimator.link_counts_per_rev(),
        estimator.motor_counts_per_rev()
    );

    // 3. Laws and switching → one joint on f32.
    let mut design = bound_design(1.0);
    design.sample_period = TICK;
    let active = RobustAdaptiveParams::try_new(design)?;
    let passive = PassiveParams::try_new(PassiveSettings {
        rotor_inertia: design.rotor_inertia, // The default of `PassiveParams::table_4_1_default`: Î_m K_p = 1.
        gain: 1.0 / design.rotor_inertia,
        ratio: design.ratio,
        eps_velocity: design.eps_velocity,
        nominal_friction: identified_motor_friction(),
        torque_limit: design.torque_limit,
    })?;
    let mode = ModeParams::try_new(ModeSettings {
        active,
        passive,
        enter_passive: 4.0,
        exit_passive: 1.0,
        debounce: 20,
        dwell: 100,
        rejoin_bandwidth: 10.0,
        bias_time_constant: 0.05,
        collision: None,
    })?;
    let params = JointParams::try_new(JointSettings {
        estimator,
        mode,
        speed_window: 4,
        max_motor_speed: mrr_control::joint::TABLE_4_1_MAX_MOTOR_SPEED,
    })?;
    let joint = JointConfig::<f32>::new(&params);
    println!(
        "3. joint on f32: T = {} ms, passive above {} N·m, active below {} N·m, speed resolution {:.3} rad/s",
        TICK * 1e3,
        4.0,
        1.0,
        params.speed_resolution()
    );

    // 4. The simulated joint.
    let mut robot = Mrr::try_new(vec![module.clone()], [0.0, 0.0, -9.81], TICK, 1, 7)?;
    let l = module.link_encoder.counts_per_rev as i64;
    let s = robot.read_sensors();
    // Homed: the firmware knows the motor position at start.
    let mut st = joint.state_at(s.motor_counts[0], s.motor_counts[0] as u32);
    let steps = (DURATION / TICK).round() as usize;
    let mut trace = Vec::with_capacity(steps / 10 + 1);
    let mut switches = Vec::new();
    let (mut sq_a, mut n_a, mut sq_c, mut n_c) = (0.0, 0usize, 0.0, 0usize);
    let (mut sq_est, mut n_est) = (0.0, 0usize);
    let (mut hand_peak, mut grab) = (0.0f64, None);
    let (mut sq_hand, mut n_hand) = (0.0, 0usize);
    let mut invalid = 0usize;
    for k in 0..steps {
        let t = k as f64 * TICK;
        let s = robot.read_sensors();
        let readings = JointReadings::counts(
            s.link_counts[0].rem_euclid(l) as u32,
            s.motor_counts[0] as u32,
        );
        let (qd, vd, ad) = desired(t);
        let target = JointTarget::<f32>::from_si(qd, vd, ad);
        let o = joint.update(&mut st, &readings, &target);
        invalid += o.invalid_input as usize;
        if o.control.switched {
            switches.push((t, o.mode, o.control.interaction_si()));
        }
        let (q, v) = (robot.link_angles()[0], robot.link_speeds()[0]);
        if t >= HAND_ON && grab.is_none() {
            grab = Some(q);
        }
        let h = hand(t, grab.unwrap_or(0.0), q, v);
        hand_peak = hand_peak.max(h.abs());
        if o.mode == JointMode::Passive && h != 0.0 {
            sq_hand += h * h;
            n_hand += 1;
        }
        let truth = robot.transmission_torques()[0];
        if (0.5..HAND_ON).contains(&t) {
            sq_a += (q - qd).powi(2);
            n_a += 1;
        }
        if t > HAND_OFF + 1.0 {
            sq_c += (q - qd).powi(2);
            n_c += 1;
        }
        sq_est += (o.joint_torque_si() - truth).powi(2);
        n_est += 1;
        if k % 10 == 0 {
            trace.push((t, q, qd, o.joint_torque_si(), truth, h, o.mode));
        }
        robot.set_motor_torque(&[o.motor_torque_si()]);
        robot.external_torque[0] = h;
        robot.step();
    }
    let rms_a = (sq_a / n_a as f64).sqrt();
    let rms_c = (sq_c / n_c as f64).sqrt();
    let rms_est = (sq_est / n_est as f64).sqrt();
    println!(
        "4. simulated thesis joint, {DURATION} s at {} kHz:",
        1e-3 / TICK
    );
    println!(
        "   tracking RMS 0.5–3 s (before the hand):   {:.2e} rad",
        rms_a
    );
    println!(
        "   tracking RMS {}–{DURATION} s (after rejoining): {:.2e} rad",
        HAND_OFF + 1.0,
        rms_c
    );
    println!("   hand torque, peak:                    {hand_peak:.2} N·m");
    println!(
        "   hand torque while passive, RMS:         {:.2} N·m over {:.2} s",
        (sq_hand / n_hand.max(1) as f64).sqrt(),
        n_hand as f64 * TICK
    );
    println!("   estimate − true joint torque, RMS:      {rms_est:.2} N·m");
    println!("   invalid readings flagged:               {invalid}");
    println!("   mode switches:");
    for (t, m, i) in &switches {
        println!("     {t:6.3} s → {m:?} (interaction {i:+.2} N·m)");
    }

    let dir = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            std::env::var_os("CARGO_TARGET_DIR")
                .map(PathBuf::from)
                .unwrap_or_else(|| PathBuf::from("target"))
                .join("figures")
        });
    std::fs::create_dir_all(&dir)?;
    let path = dir.join("joint_demo.svg");
    plot(&path, &trace, &switches)?;
    println!("figure: {}", path.display());
    println!("run time: {:.1} s", started.elapsed().as_secs_f64());
    Ok(())
}

type Sample = (f64, f64, f64, f64, f64, f64, JointMode);

fn plot(
    path: &std::path::Path,
    trace: &[Sample],
    switches: &[(f64, JointMode, f64)],
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (900, 640)).into_drawing_area();
    root.fill(&WHITE)?;
    let (top, bottom) = root.split_vertically(320);
    let span = |f: &dyn Fn(&Sample) -> [f64; 3]| {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for s in trace {
            for v in f(s) {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        let pad = 0.08 * (hi - lo).max(1e-9);
        (lo - pad)..(hi + 3.0 * pad)
    };
    let mut a = ChartBuilder::on(&top)
        .caption(
            "Joint on f32: tracking, guided by hand (passive), rejoining",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(0.0..DURATION, span(&|s| [s.1, s.2, s.1]))?;
    a.configure_mesh()
        .x_desc("time (s)")
        .y_desc("link angle (rad)")
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    // Passive stretches shaded.
    let y = span(&|s| [s.1, s.2, s.1]);
    a.draw_series(
        trace
            .windows(2)
            .filter(|w| w[0].6 == JointMode::Passive)
            .map(|w| {
                Rectangle::new(
                    [(w[0].0, y.start), (w[1].0, y.end)],
                    RGBColor(255, 235, 200).filled(),
                )
            }),
    )?;
    a.draw_series(LineSeries::new(
        trace.iter().map(|s| (s.0, s.2)),
        BLUE.stroke_width(1),
    ))?
    .label("desired q_d")
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    a.draw_series(LineSeries::new(
        trace.iter().map(|s| (s.0, s.1)),
        RED.stroke_width(1),
    ))?
    .label("link q_l (shaded: passive)")
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    a.configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    let mut b = ChartBuilder::on(&bottom)
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(0.0..DURATION, span(&|s| [s.3, s.4, s.5]))?;
    b.configure_mesh()
        .x_desc("time (s)")
        .y_desc("torque (N·m)")
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    let yb = span(&|s| [s.3, s.4, s.5]);
    for (t, _, _) in switches {
        b.draw_series(LineSeries::new(
            vec![(*t, yb.start), (*t, yb.end)],
            BLACK.mix(0.3),
        ))?;
    }
    b.draw_series(LineSeries::new(
        trace.iter().map(|s| (s.0, s.4)),
        BLACK.stroke_width(1),
    ))?
    .label("true τ_t")
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    b.draw_series(LineSeries::new(
        trace.iter().map(|s| (s.0, s.3)),
        RED.stroke_width(1),
    ))?
    .label("estimate τ̂_t (f32)")
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    b.draw_series(LineSeries::new(
        trace.iter().map(|s| (s.0, s.5)),
        GREEN.stroke_width(1),
    ))?
    .label("hand torque (grey lines: switches)")
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], GREEN.stroke_width(2)));
    b.configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
