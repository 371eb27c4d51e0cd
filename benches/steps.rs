//! Host (x86) regression benchmarks: one criterion group per kernel and per
//! run-time step, one benchmark per backend.
//!
//! These are **x86 host numbers**: they catch regressions between commits
//! on one machine and say nothing about a microcontroller. Target
//! instruction counts (Cortex-M4F / Cortex-M0+) come from
//! `embedded/count.py`. Run with
//! `cargo bench --bench steps -- --warm-up-time 1 --measurement-time 2`.
//!
//! Adding a step: one `step_group` call in `main` (below the torque
//! estimator's), with its inputs.

use core::f64::consts::FRAC_PI_2;
use core::hint::black_box;
use criterion::{BenchmarkId, Criterion, Throughput};
use mrr_control::control::{
    ControlInput, ModeConfig, ModeParams, ModeSettings, PassiveParams, RobustAdaptiveParams,
};
use mrr_control::estimation::collision::{CollisionParams, CollisionReaction, CollisionSettings};
use mrr_control::estimation::torque::{
    TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings,
};
use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::{Scalar, I16F16};

/// Arguments spread over each kernel's domain and its saturation edges
/// (the same inputs for every backend, converted by `from_f64`).
const TRIG: [f64; 12] = [
    0.0, 0.1, -0.5, 0.78, 1.0, -1.5, 2.0, 3.1, -6.0, 100.0, -1000.0, 30000.0,
];
const TAN: [f64; 10] = [
    0.0,
    0.1,
    -0.5,
    0.78,
    1.0,
    -1.2,
    1.5,
    FRAC_PI_2 - 1e-4,
    -FRAC_PI_2 - 1e-2,
    3.0,
];
const ATAN: [f64; 10] = [0.0, 0.1, -0.5, 0.6, 1.0, -1.7, 10.0, -300.0, 3e4, -3e4];
const EXP: [f64; 10] = [-20.0, -11.0, -5.0, -1.0, -0.1, 0.0, 0.3, 1.0, 5.0, 10.3];
const SQRT: [f64; 10] = [0.0, 1e-4, 0.01, 0.25, 1.0, 2.0, 10.0, 1e3, 3e4, -1.0];
const ACOS: [f64; 10] = [-1.0, -0.99, -0.5, -0.1, 0.0, 0.3, 0.7, 0.999, 1.0, 1.5];

type Group<'a> = criterion::BenchmarkGroup<'a, criterion::measurement::WallTime>;

/// One benchmark of `f(x, y)` over `x` in `args` and `y` in `args`
/// reversed (unary kernels ignore `y`).
fn kernel_bench<S: Scalar>(g: &mut Group<'_>, args: &[f64], f: impl Fn(S, S) -> S) {
    let xy: Vec<(S, S)> = args
        .iter()
        .zip(args.iter().rev())
        .map(|(&x, &y)| (S::from_f64(x), S::from_f64(y)))
        .collect();
    g.throughput(Throughput::Elements(xy.len() as u64));
    g.bench_function(BenchmarkId::from_parameter(S::NAME), |b| {
        b.iter(|| {
            for &(x, y) in &xy {
                black_box(f(black_box(x), black_box(y)));
            }
        })
    });
}

/// One group `x86-host kernel/<name>` with a benchmark per backend.
macro_rules! kernel {
    ($c:expr, $name:literal, $args:expr, |$x:ident, $y:pat_param| $e:expr) => {{
        let mut g = $c.benchmark_group(concat!("x86-host kernel/", $name));
        kernel_bench::<f32>(&mut g, &$args, |$x, $y| $e);
        kernel_bench::<f64>(&mut g, &$args, |$x, $y| $e);
        kernel_bench::<I16F16>(&mut g, &$args, |$x, $y| $e);
        g.finish();
    }};
}

/// SHD-17-100 with the Table 3.2 kinematic error, 17-bit link encoder,
/// 2000-count motor encoder, ±60 N·m (the firmware crate's configuration).
fn estimator_params() -> TorqueEstimatorParams {
    let drive = CatalogueData::SHD_17_100
        .identify()
        .expect("catalogue data");
    TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive,
        kinematic_error: Some(KinematicErrorModel::table_3_2()),
        link_counts_per_rev: 1 << 17,
        motor_counts_per_rev: 2000,
        max_torque: 60.0,
    })
    .expect("valid parameters")
}

/// Encoder readings along a loaded motion: link count, motor counter and
/// motor torque (N·m), including out-of-branch torsions and a counter wrap.
fn estimator_inputs() -> Vec<(u32, u32, f64)> {
    let mut v = Vec::new();
    let mut counter = u32::MAX - 3000;
    for i in 0..64u32 {
        counter = counter.wrapping_add(97);
        let link = (i * 2048 + (i % 7) * 13) % (1 << 17);
        let torque = (i as f64 - 32.0) * 0.006;
        v.push((link, counter, torque));
    }
    v
}

fn estimator_bench<S: Scalar>(g: &mut Group<'_>) {
    let p = estimator_params();
    let cfg = TorqueEstimatorConfig::<S>::new(&p);
    let scale = S::UNITS.motor_torque;
    let inputs: Vec<(u32, u32, S)> = estimator_inputs()
        .into_iter()
        .map(|(l, m, t)| (l, m, S::from_f64(t * scale)))
        .collect();
    g.throughput(Throughput::Elements(inputs.len() as u64));
    g.bench_function(BenchmarkId::from_parameter(S::NAME), |b| {
        let mut st = cfg.state(0, inputs[0].1);
        b.iter(|| {
            for &(l, m, t) in &inputs {
                black_box(cfg.update(&mut st, black_box(l), black_box(m), black_box(t)));
            }
        })
    });
}

/// The firmware crate's mode manager: Table 4.1 laws, passive above 2 N·m
/// interaction and back below 1 N·m (debounce 3, dwell 5), collision stop
/// above 4 N·m.
fn mode_params() -> ModeParams {
    ModeParams::try_new(ModeSettings {
        active: RobustAdaptiveParams::table_4_1().expect("Table 4.1"),
        passive: PassiveParams::table_4_1(2000.0).expect("Table 4.1"),
        enter_passive: 2.0,
        exit_passive: 1.0,
        debounce: 3,
        dwell: 5,
        rejoin_bandwidth: 10.0,
        bias_time_constant: 0.1,
        collision: Some(
            CollisionParams::try_new(CollisionSettings {
                threshold: 4.0,
                release_threshold: 3.0,
                debounce: 2,
                release: 2,
                reaction: CollisionReaction::Stop,
            })
            .expect("valid detector"),
        ),
    })
    .expect("valid mode parameters")
}

/// The per-joint step: estimate (counter negated, E2.10) → `τ̂_t = −torque` →
/// mode manager, along the estimator's readings with a tracking error
/// sweeping through the boundary layers and expected torques that switch
/// modes, so every branch runs inside one iteration.
fn joint_bench<S: Scalar>(g: &mut Group<'_>) {
    let est = TorqueEstimatorConfig::<S>::new(&estimator_params());
    let mode = ModeConfig::<S>::new(&mode_params());
    let u = S::UNITS;
    let inputs: Vec<(u32, u32, ControlInput<S>)> = estimator_inputs()
        .into_iter()
        .enumerate()
        .map(|(i, (l, m, _))| {
            let k = i as f64;
            let qd = 0.3 * k - 9.0;
            let vd = 4.0 - 0.1 * k;
            let x = ControlInput {
                desired_position: S::from_f64(qd * u.angle),
                desired_velocity: S::from_f64(vd * u.speed),
                desired_acceleration: S::from_f64((k - 32.0) * 30.0 * u.speed),
                motor_position: S::from_f64((qd + (k - 32.0) * 1e-4) * u.angle),
                motor_velocity: S::from_f64((vd + (k - 32.0) * 2e-3) * u.speed),
                joint_torque: S::ZERO,
                desired_joint_torque: S::ZERO,
                expected_joint_torque: S::from_f64((i % 16) as f64 * 0.4 * u.link_torque),
            };
            (l, m, x)
        })
        .collect();
    g.throughput(Throughput::Elements(inputs.len() as u64));
    g.bench_function(BenchmarkId::from_parameter(S::NAME), |b| {
        let mut est_st = est.state(0, inputs[0].1.wrapping_neg());
        let mut st = mode.initial_state();
        b.iter(|| {
            for (l, m, x) in &inputs {
                let e = est.update(
                    &mut est_st,
                    black_box(*l),
                    black_box(m.wrapping_neg()),
                    st.last_torque(),
                );
                let mut x = *black_box(x);
                x.joint_torque = e.torque.neg();
                black_box(mode.update(&mut st, &x));
            }
        })
    });
}

/// One group `x86-host step/<name>` with a benchmark per backend.
fn step_group(c: &mut Criterion, name: &str, benches: &[fn(&mut Group<'_>)]) {
    let mut g = c.benchmark_group(format!("x86-host step/{name}"));
    for b in benches {
        b(&mut g);
    }
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    let c = &mut c;
    kernel!(c, "atan", ATAN, |x, _| x.atan());
    kernel!(c, "tan", TAN, |x, _| x.tan());
    kernel!(c, "sin", TRIG, |x, _| x.sin());
    kernel!(c, "cos", TRIG, |x, _| x.cos());
    kernel!(c, "sin_cos", TRIG, |x, _| {
        let (s, co) = x.sin_cos();
        s.add(co)
    });
    kernel!(c, "atan2", TRIG, |y, x| y.atan2(x));
    kernel!(c, "exp", EXP, |x, _| x.exp());
    kernel!(c, "sqrt", SQRT, |x, _| x.sqrt());
    kernel!(c, "acos", ACOS, |x, _| x.acos());
    step_group(
        c,
        "torque estimation",
        &[
            estimator_bench::<f32>,
            estimator_bench::<f64>,
            estimator_bench::<I16F16>,
        ],
    );
    step_group(
        c,
        "joint step",
        &[
            joint_bench::<f32>,
            joint_bench::<f64>,
            joint_bench::<I16F16>,
        ],
    );
    c.final_summary();
}
