//! The thesis's ch. 2–6 figures regenerated from the library and its
//! simulator, as SVG files plus an `index.html` to open in a browser.
//! Each figure carries one line: what the thesis reports, and what this run
//! gets (numbers computed here).
//!
//! ```sh
//! cargo run --release --features sim --example thesis_report            # full runs (~55 s)
//! cargo run --release --features sim --example thesis_report -- --quick # shorter runs (CI)
//! cargo run --release --features sim --example thesis_report -- --out DIR
//! cargo run --release --features sim --example thesis_report -- --chapter 6 # one chapter
//! ```
//!
//! Output: `DIR`, else `$CARGO_TARGET_DIR/figures`, else `target/figures`.
//!
//! Every curve comes from a library call (the models of
//! [`mrr_control::harmonic_drive`] and [`mrr_control::wrist`], the
//! experiments of [`mrr_control::sim`]); this file only runs them and
//! draws.
//!
//! Chapter 2's bench figures (Fig. 2.17–2.22) run on members of the
//! independent drive-bench family ([`DRIVE_RUNS`] of
//! [`mrr_control::sim::plants::drive::family`], the registry's runs through
//! [`drive_figure_run`]) with the models identified from the catalogue
//! alone. Chapter 3's figures fit eq. (3.7) to the drawn kinematic error
//! of members of the independent joint family (Fig. 3.1–3.3) and run the
//! library's joint step at 4 ms on them (Fig. 3.6–3.9), [`JOINT_RUNS`] of
//! [`mrr_control::sim::plants::joint::joint_family`] through
//! [`figure_run`]. Each figure draws the first run and states the spread
//! over all; `--quick` takes two members of the quick families. The older
//! plants of [`mrr_control::sim::experiments`] and
//! [`mrr_control::sim::closed_loop`], whose kinematic error is Table 3.2
//! (the model the estimator subtracts), give labelled comparison numbers
//! only.
//!
//! Chapter 4's engine figures (Fig. 4.3, 4.11–4.12 and the collision
//! extension) run on the arm of bodies on the engine with the drives of
//! three members of the independent joint family
//! ([`mrr_control::sim::engine::arm_scenarios::ARM_FAMILY`], one in
//! `--quick`) and show their spread; the same arm on the library's own
//! drive plant, `Mrr` and the home-made single joint are labelled
//! comparison numbers.
//!
//! Chapter 6's tracking (Fig. 6.7, 6.10–6.11), finger push (Fig.
//! 6.14–6.17) and door (Fig. 6.19–6.20) come from the rigid-body engine
//! ([`mrr_control::sim::engine`], step 0.25 ms) with the library's wrist
//! step at 4 ms on `f32`; the finger push and the door carry the verdicts
//! of their claims ([`mrr_control::sim::claims::ch6`]) over
//! [`ENGINE_SEEDS`] seeds (one in `--quick`; the claims' own sweep is 20
//! seeds: see each figure's text for the command). Fig. 6.8–6.9
//! are the library's inverse kinematics of the desired trajectory (no
//! plant). The home-made benches ([`mrr_control::sim::wrist_bench`],
//! [`mrr_control::sim::door`]) appear only as labelled comparison numbers.
//!
//! To add a figure, write a `fn(&mut Report) -> Result<Figure, Error>` and
//! list it in [`CHAPTERS`].

use mrr_control::estimation::collision::CollisionReaction;
use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::sim::claims::ch34::{
    figure_run, JointFigureRun, Table33Run, TorqueSample, TABLE_3_3_COMMANDS,
};
use mrr_control::sim::claims::ch6::{
    bench_claims, claims as door_claims, run_bench, run_door, DoorRunMetrics,
};
use mrr_control::sim::claims::{
    drive_figure_run, evaluate, ClaimResult, DriveFigureRun, Runs, RERUN,
};
use mrr_control::sim::closed_loop::{
    active_tracking, back_drive, interaction_scenario, payload_drop, BackDriveConfig,
    BackDriveMode, BackDriveResult, JointTorqueFeedback, ModeScenarioConfig, PayloadDropConfig,
    TrackingConfig, TrackingResult,
};
use mrr_control::sim::door::{door_opening, DoorConfig, DoorControl, DoorRun};
use mrr_control::sim::engine::arm_scenarios::{
    back_driving as arm_back_driving, collision as arm_collision, fig4_3_tracking, hand_path,
    CollisionObstacle, ARM_FAMILY, CONTROL_TICK as ARM_TICK, WALL_ANGLE,
};
use mrr_control::sim::engine::door::{door_engine_settings, EngineDoorRun, CONTROL_PERIOD};
use mrr_control::sim::engine::wrist_bench::{
    engine_finger_push, engine_wrist_tracking, EngineTrackingRun, EngineWristBenchRun,
    FingerCase as EngineCase, FingerPush, WristBenchSample as EngineBenchSample, CASE1_TRAVEL,
};
use mrr_control::sim::engine::{arm_settings, ArmPlant, ArmTrackingRun, EngineSettings, JointRun};
use mrr_control::sim::experiments::{
    back_driven, locked_output, loop_width, torque_estimation, width_at_zero, BackDrivenConfig,
    BackDrivenResult, ComplianceResult, ErrorStats, LockedOutputConfig, Models,
    TorqueEstimationConfig, TorqueEstimationResult, ESTIMATORS,
};
use mrr_control::sim::plants::elements::KinematicErrorPlant;
use mrr_control::sim::plants::joint::{joint_family, quick_joint_family};
use mrr_control::sim::plants::{family as drive_family, quick_family as quick_drive_family};
use mrr_control::sim::wrist_bench::{
    tracking_trajectory, wrist_finger_push, wrist_tracking, FingerCase, WristBenchRun,
    BENCH_PERIOD, FINGER_TRAVEL,
};
use mrr_control::wrist::figures::{
    alpha_beta_comparison, workspace_mapping, MappingRule, WorkspaceSample,
};
use mrr_control::wrist::{IkState, PitchYaw, WristConfig, WristParams};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Errors of a report run (I/O or drawing), as text.
pub type Error = Box<dyn std::error::Error>;

/// One rendered figure.
#[derive(Debug, Clone)]
pub struct Figure {
    /// File name of the SVG inside the output directory.
    pub file: String,
    /// Thesis figure number(s) and title.
    pub title: String,
    /// What the thesis reports.
    pub thesis: String,
    /// What this run gets.
    pub ours: String,
}

/// A figure generator.
pub type FigureFn = fn(&mut Report) -> Result<Figure, Error>;

/// The figures, by chapter.
pub const CHAPTERS: &[(&str, &[FigureFn])] = &[
    (
        "Chapter 2: harmonic-drive compliance",
        &[
            fig2_11, fig2_12, fig2_17, fig2_18, fig2_19, fig2_20, fig2_21, fig2_22,
        ],
    ),
    (
        "Chapter 3: joint torque estimation",
        &[fig3_1, fig3_2, fig3_3, fig3_6, fig3_7, fig3_8, fig3_9],
    ),
    (
        "Chapter 4: multiple-mode joint control",
        &[fig4_2, fig4_3, fig4_11, fig4_12, fig4_13_collision],
    ),
    (
        "Chapter 5: the compact wrist's kinematics",
        &[fig5_7, fig5_8, fig5_10, fig5_11],
    ),
    (
        "Chapter 6: wrist control and door opening",
        &[
            fig6_7, fig6_8, fig6_9, fig6_10, fig6_11, fig6_14, fig6_15, fig6_16, fig6_17, fig6_19,
            fig6_20,
        ],
    ),
];

/// The thesis's figures of measured data that are not drawn, each with
/// the reason. (Photographs, drawings and block diagrams — Fig. 2.1–2.10,
/// 2.13–2.16, 3.4–3.5, 4.1, 5.1–5.6, 5.9, 6.1–6.6, 6.12, 6.18 — show no
/// data and are not listed.)
pub const NOT_DRAWN: &[(&str, &str)] = &[(
    "Fig. 4.4–4.10: joint 1 tracking while joint 2 moves joint 3 as a payload (§4.4.1)",
    "not drawn: the thesis gives joint 2's motion and joint 1's desired trajectory only as \
     plots and states no number for these figures, so there is nothing to compare; the \
     coupling they show is the arm's, which `sim::mrr` integrates from the same eq. \
     (4.1)–(4.6) the joint model uses, so a rerun there would not be independent evidence",
)];

/// Run options.
#[derive(Debug, Clone)]
pub struct Options {
    /// Shorter simulations (for CI).
    pub quick: bool,
    /// Output directory.
    pub out: PathBuf,
}

/// The output directory: `$CARGO_TARGET_DIR/figures` if the variable is
/// set, else `target/figures`.
pub fn default_figures_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target"))
        .join("figures")
}

/// The simulations shared between figures, run once on first use.
pub struct Report {
    opts: Options,
    locked: Option<ComplianceResult>,
    back_driven: Option<BackDrivenResult>,
    estimation: Option<TorqueEstimationResult>,
    tracking: Option<Vec<TrackingResult>>,
    passive: Option<Vec<BackDriveResult>>,
    smooth: Option<TrackingResult>,
    wrist_tracking: Option<WristBenchRun>,
    finger: Option<Vec<WristBenchRun>>,
    door: Option<Vec<DoorRun>>,
    engine_tracking: Option<EngineTrackingRun>,
    engine_bench: Option<EngineBench>,
    engine_door: Option<EngineDoor>,
    /// Fig. 4.3 on the engine (A, B, C), then on `Mrr` (A, B, C).
    arm_tracking: Option<Vec<ArmTrackingRun>>,
    arm_back_driving: Option<Vec<JointRun>>,
    arm_collision: Option<ArmCollision>,
    /// The chapter-4 engine runs on the family members of [`ARM_FAMILY`].
    arm_family: Option<Vec<ArmFamilyRuns>>,
    /// The chapter-3 runs on members of the joint family.
    joint_figs: Option<JointFigs>,
    /// The chapter-2 runs on members of the drive-bench family.
    drive_figs: Option<DriveFigs>,
}

/// Members and seeds of the chapter-2 runs on
/// [`family`](mrr_control::sim::plants::drive::family) (216 members): each
/// backbone, both bearing shapes, both mesh break-aways, the three splits
/// of the loss, the three amplitudes and both ripples appear.
pub const DRIVE_RUNS: &[(usize, u64)] = &[(0, 0), (41, 1), (86, 2), (127, 3), (170, 4), (215, 5)];

/// The chapter-2 runs in quick mode, on
/// [`quick_family`](mrr_control::sim::plants::drive::quick_family) (4
/// members).
pub const DRIVE_RUNS_QUICK: &[(usize, u64)] = &[(0, 0), (3, 1)];

/// The chapter-2 figure runs ([`drive_figure_run`]) on members of the
/// drive-bench family, the first one drawn.
struct DriveFigs {
    /// `family` or `quick_family`.
    family: &'static str,
    /// The member's description, per run.
    labels: Vec<String>,
    /// The runs, in the order of [`DRIVE_RUNS`] (or [`DRIVE_RUNS_QUICK`]).
    runs: Vec<DriveFigureRun>,
}

impl DriveFigs {
    /// The run a figure draws, for its legend.
    fn shown(&self) -> String {
        let m = self.runs[0].metrics;
        format!("{} member {} (seed {})", self.family, m.plant, m.seed)
    }

    /// The runs, for a figure's text.
    fn runs_text(&self) -> String {
        let list = self
            .runs
            .iter()
            .map(|r| format!("{}/{}", r.metrics.plant, r.metrics.seed))
            .collect::<Vec<_>>()
            .join(", ");
        format!("{} runs (member/seed {list})", self.runs.len())
    }

    /// What produced a chapter-2 figure, for its text.
    fn source(&self) -> String {
        format!(
            "plant: {} of the independent drive-bench family (sim::plants::drive: flexspline \
             backbone and hysteresis, bearing compliance, mesh friction, a drawn kinematic \
             error with ripple, quantizing encoders, torque-sensor gain error; {}); models \
             identified from the catalogue alone (sim::claims::blind_models), runs of \
             sim::claims::drive_figure_run",
            self.shown(),
            self.labels[0]
        )
    }
}

/// [`spread`] in `e` notation, 2 decimals.
fn spread_e(v: &[f64]) -> String {
    match median_min_max(v) {
        None => "none".into(),
        Some((m, _, _)) if v.len() == 1 => format!("{m:.2e}"),
        Some((m, lo, hi)) => format!("median {m:.2e} (min {lo:.2e}, max {hi:.2e})"),
    }
}

/// Members and seeds of the chapter-3 runs on
/// [`joint_family`](mrr_control::sim::plants::joint::joint_family) (24
/// members): one of each backbone and loss split, both friction levels and
/// link inertias, each with its own seed.
pub const JOINT_RUNS: &[(usize, u64)] = &[(0, 0), (7, 1), (10, 2), (13, 3), (19, 4), (22, 5)];

/// The chapter-3 runs in quick mode, on
/// [`quick_joint_family`](mrr_control::sim::plants::joint::quick_joint_family)
/// (2 members).
pub const JOINT_RUNS_QUICK: &[(usize, u64)] = &[(0, 0), (1, 1)];

/// The chapter-3 figure runs ([`figure_run`]) on members of the joint
/// family, the first one drawn.
struct JointFigs {
    /// `joint_family` or `quick_joint_family`.
    family: &'static str,
    /// The member's description, per run.
    labels: Vec<String>,
    /// The runs, in the order of [`JOINT_RUNS`] (or [`JOINT_RUNS_QUICK`]).
    runs: Vec<JointFigureRun>,
    /// The kinematic error each run drew (the truth of the fit).
    drawn: Vec<KinematicErrorPlant>,
}

impl JointFigs {
    /// The run a figure draws, for its legend.
    fn shown(&self) -> String {
        format!(
            "{} member {} (seed {})",
            self.family, self.runs[0].plant, self.runs[0].seed
        )
    }

    /// The runs, for a figure's text.
    fn runs_text(&self) -> String {
        let list = self
            .runs
            .iter()
            .map(|r| format!("{}/{}", r.plant, r.seed))
            .collect::<Vec<_>>()
            .join(", ");
        format!("{} runs (member/seed {list})", self.runs.len())
    }

    /// What produced a chapter-3 figure, for its text.
    fn source(&self) -> String {
        format!(
            "plant: {} of the independent joint family (sim::plants::joint: flexspline \
             backbone and hysteresis, bearing compliance, mesh friction, a drawn kinematic \
             error with ripple, pre-sliding friction; {}), the library's joint step at 4 ms, \
             runs of sim::claims::ch34::figure_run",
            self.shown(),
            self.labels[0]
        )
    }
}

/// The forward calibration revolution of a run (the first half of its
/// samples).
fn forward(run: &JointFigureRun) -> &[mrr_control::sim::claims::ch34::CalibrationSample] {
    &run.calibration[..run.calibration.len() / 2]
}

/// The chapter-4 engine runs on one member of the independent joint family
/// (f32): Fig. 4.3's A, B, C, Fig. 4.11–4.12's A, B, and the collision on
/// the engine contact (Stop, Passive).
#[derive(Clone)]
struct ArmFamilyRuns {
    member: usize,
    seed: u64,
    tracking: Vec<ArmTrackingRun>,
    back_driving: Vec<JointRun>,
    stop: JointRun,
    passive: JointRun,
}

/// Every chapter-4 engine run on family member `member` with `seed`.
fn family_runs(
    member: usize,
    seed: u64,
    duration: f64,
    settle: f64,
) -> Result<ArmFamilyRuns, mrr_control::error::ParamError> {
    let plant = ArmPlant::family(member, seed);
    let mut tracking = Vec::new();
    for fb in [
        JointTorqueFeedback::None,
        JointTorqueFeedback::Sensor,
        JointTorqueFeedback::Estimated,
    ] {
        tracking.push(fig4_3_tracking::<f32>(plant, fb, duration, settle)?);
    }
    Ok(ArmFamilyRuns {
        member,
        seed,
        tracking,
        back_driving: vec![
            arm_back_driving::<f32>(plant, false)?,
            arm_back_driving::<f32>(plant, true)?,
        ],
        stop: arm_collision::<f32>(plant, CollisionObstacle::Contact, CollisionReaction::Stop)?,
        passive: arm_collision::<f32>(
            plant,
            CollisionObstacle::Contact,
            CollisionReaction::Passive,
        )?,
    })
}

/// The values `v` times `scale`, with `digits` decimals: the value for one run, else
/// `median m (min a, max b)` (the middle of the sorted runs; the mean of
/// the two middle ones for an even count).
fn spread(v: &[f64], scale: f64, digits: usize) -> String {
    let scaled: Vec<f64> = v.iter().map(|x| x * scale).collect();
    match median_min_max(&scaled) {
        None => "none".into(),
        Some((m, _, _)) if scaled.len() == 1 => format!("{m:.digits$}"),
        Some((m, lo, hi)) => format!("median {m:.digits$} (min {lo:.digits$}, max {hi:.digits$})"),
    }
}

/// Median (the mean of the two middle values for an even count), minimum
/// and maximum; `None` for no values.
fn median_min_max(v: &[f64]) -> Option<(f64, f64, f64)> {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    let median = match n {
        0 => return None,
        _ if n % 2 == 1 => s[n / 2],
        _ => 0.5 * (s[n / 2 - 1] + s[n / 2]),
    };
    Some((median, s[0], s[n - 1]))
}

/// Seeds of the chapter-6 engine sweeps in the report (the claims' own
/// sweep runs 20: [`CLAIMS_RERUN_BENCH`], [`CLAIMS_RERUN_DOOR`]).
pub const ENGINE_SEEDS: u64 = 3;

/// Seeds of the engine sweeps in quick mode (CI): one seed, so the verdicts
/// there are a smoke test, not evidence.
pub const ENGINE_SEEDS_QUICK: u64 = 1;

/// `"seed 1"` or `"seeds 1–n"`.
fn seeds_text(n: usize) -> String {
    if n == 1 {
        "seed 1".into()
    } else {
        format!("seeds 1–{n}")
    }
}

/// The command that judges the bench claims on their 20 seeds.
pub const CLAIMS_RERUN_BENCH: &str = "6.15-case1 6.16-case2 6.16-reduction";

/// The command that judges the door claims on their 20 seeds.
pub const CLAIMS_RERUN_DOOR: &str = "6.20-passive 6.20-heading 6.20-relief";

/// The wrist bench of §6.4.3 on the engine: the time series of the
/// nominal push ([`FingerPush::nominal`], seed 1: pure pitch, 12° over
/// 1.5 s, a 12 N·m break-away), and the claims' drawn pushes over
/// [`ENGINE_SEEDS`] seeds with their verdicts.
struct EngineBench {
    /// Case 1 (motors off) and Case 2 (admittance-passive), nominal push.
    off: EngineWristBenchRun,
    on: EngineWristBenchRun,
    /// The verdicts of [`bench_claims`] over the seeds.
    verdicts: Vec<ClaimResult>,
}

/// The door opening of §6.4.4 on the engine over [`ENGINE_SEEDS`] seeds:
/// per seed the metrics and the passive, 3° heading-error and held-active
/// runs, and the verdicts of the door claims.
struct EngineDoor {
    runs: Vec<(DoorRunMetrics, [EngineDoorRun; 3])>,
    verdicts: Vec<ClaimResult>,
}

/// The chapter-4 collision runs on the engine arm (f32): the engine
/// contact with the Stop and Passive reactions, and the spring obstacle
/// (Stop) on the engine and on `Mrr` for comparison.
#[derive(Clone)]
struct ArmCollision {
    stop: JointRun,
    passive: JointRun,
    spring: JointRun,
    spring_mrr: JointRun,
}

/// What produced a chapter-4 engine figure, for its text.
fn arm_source(family: &[ArmFamilyRuns]) -> String {
    let members = family
        .iter()
        .map(|f| format!("{} (seed {})", f.member, f.seed))
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "rapier3d engine, step {} ms (one substep), arm of bodies (thesis joint: link, \
         rotor); its drive members {members} of the independent joint family \
         (sim::engine::FamilyDrives on sim::plants::joint_family: flexspline backbone and \
         hysteresis, bearing compliance, mesh friction at the node, a drawn kinematic error \
         with ripple, pre-sliding motor and link friction; not the models the library \
         carries); the library's joint step at {} ms on f32; values over the members",
        arm_settings().dt() * 1e3,
        ARM_TICK * 1e3
    )
}

/// What the comparison runs on the library's own drive plant are.
const PLANT_DRIVES: &str = "the library's drive plant on the same engine arm (PlantDrives: \
     Table 3.2's eq. (3.7) kinematic error, the model the estimator subtracts, and friction \
     of eq. (4.8)'s form)";

/// The engine settings of every chapter-6 engine run (0.25 ms step).
fn engine_settings() -> EngineSettings {
    door_engine_settings()
}

/// What produced a chapter-6 engine figure, for its text.
fn engine_source() -> String {
    format!(
        "rapier3d engine, step {} ms, DAUJ built from its parts; the library's wrist step at \
         {} ms on f32",
        engine_settings().dt() * 1e3,
        CONTROL_PERIOD * 1e3
    )
}

/// One claim's verdict with median and spread, for a figure's text.
fn verdict_text(verdicts: &[ClaimResult], id: &str) -> String {
    match verdicts.iter().find(|v| v.claim.id == id) {
        Some(v) => {
            let s = v.spread;
            let unit = if v.claim.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", v.claim.unit)
            };
            format!(
                "{id} {} over {}: median {:.2}{unit} (min {:.2}, max {:.2})",
                v.verdict,
                seeds_text(v.runs),
                s.median,
                s.min,
                s.max
            )
        }
        None => format!("{id}: not judged"),
    }
}

/// The worker threads of the seed sweeps.
fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

impl Report {
    fn new(opts: Options) -> Self {
        Report {
            opts,
            locked: None,
            back_driven: None,
            estimation: None,
            tracking: None,
            passive: None,
            smooth: None,
            wrist_tracking: None,
            finger: None,
            door: None,
            engine_tracking: None,
            engine_bench: None,
            engine_door: None,
            arm_tracking: None,
            arm_back_driving: None,
            arm_collision: None,
            arm_family: None,
            joint_figs: None,
            drive_figs: None,
        }
    }

    /// The chapter-2 runs on the drive-bench family ([`DRIVE_RUNS`], or
    /// [`DRIVE_RUNS_QUICK`] on the quick family), one thread per run.
    fn drive_figs(&mut self) -> Result<&DriveFigs, Error> {
        if self.drive_figs.is_none() {
            let (family, name, list) = if self.opts.quick {
                (quick_drive_family(), "quick_family", DRIVE_RUNS_QUICK)
            } else {
                (drive_family(), "family", DRIVE_RUNS)
            };
            let family = &family;
            let results: Vec<Result<DriveFigureRun, String>> = std::thread::scope(|scope| {
                let handles: Vec<_> = list
                    .iter()
                    .map(|&(m, s)| {
                        scope.spawn(move || {
                            drive_figure_run(family, m, s).map_err(|e| e.to_string())
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .map(|h| {
                        h.join()
                            .unwrap_or_else(|_| Err("a drive run panicked".into()))
                    })
                    .collect()
            });
            let mut runs = Vec::new();
            for r in results {
                runs.push(r?);
            }
            let labels = runs
                .iter()
                .map(|r| family[r.metrics.plant].label())
                .collect();
            self.drive_figs = Some(DriveFigs {
                family: name,
                labels,
                runs,
            });
        }
        self.drive_figs
            .as_ref()
            .ok_or_else(|| "drive family runs missing".into())
    }

    /// The chapter-3 runs on the joint family ([`JOINT_RUNS`], or
    /// [`JOINT_RUNS_QUICK`] on the quick family), one thread per run.
    fn joint_figs(&mut self) -> Result<&JointFigs, Error> {
        if self.joint_figs.is_none() {
            let (family, name, list) = if self.opts.quick {
                (quick_joint_family(), "quick_joint_family", JOINT_RUNS_QUICK)
            } else {
                (joint_family(), "joint_family", JOINT_RUNS)
            };
            let family = &family;
            let results: Vec<Result<JointFigureRun, String>> = std::thread::scope(|scope| {
                let handles: Vec<_> = list
                    .iter()
                    .map(|&(m, s)| {
                        scope.spawn(move || figure_run(family, m, s).map_err(|e| e.to_string()))
                    })
                    .collect();
                handles
                    .into_iter()
                    .map(|h| {
                        h.join()
                            .unwrap_or_else(|_| Err("a joint run panicked".into()))
                    })
                    .collect()
            });
            let mut runs = Vec::new();
            for r in results {
                runs.push(r?);
            }
            let labels = runs.iter().map(|r| family[r.plant].label()).collect();
            let drawn = runs
                .iter()
                .map(|r| family[r.plant].rest(0.0, r.seed).kinematic_error)
                .collect();
            self.joint_figs = Some(JointFigs {
                family: name,
                labels,
                runs,
                drawn,
            });
        }
        self.joint_figs
            .as_ref()
            .ok_or_else(|| "joint family runs missing".into())
    }

    /// Seeds of the engine sweeps: [`ENGINE_SEEDS`], or
    /// [`ENGINE_SEEDS_QUICK`] in quick mode.
    fn engine_seeds(&self) -> u64 {
        if self.opts.quick {
            ENGINE_SEEDS_QUICK
        } else {
            ENGINE_SEEDS
        }
    }

    /// §6.4.2 on the engine: the library's wrist step, held Active,
    /// tracking the task trajectory (errors counted after 1 s).
    fn engine_tracking(&mut self) -> Result<&EngineTrackingRun, Error> {
        if self.engine_tracking.is_none() {
            let duration = if self.opts.quick { 6.0 } else { 12.0 };
            self.engine_tracking = Some(engine_wrist_tracking(duration, 1.0, &engine_settings())?);
        }
        self.engine_tracking
            .as_ref()
            .ok_or_else(|| "engine tracking run missing".into())
    }

    /// §6.4.3 on the engine: the nominal push in both cases, and the
    /// bench claims over [`ENGINE_SEEDS`] drawn pushes.
    fn engine_bench(&mut self) -> Result<&EngineBench, Error> {
        if self.engine_bench.is_none() {
            let n = self.engine_seeds();
            let engine = engine_settings();
            let push = FingerPush::nominal(1);
            let off = engine_finger_push(EngineCase::MotorsOff, &push, &engine)?;
            let on = engine_finger_push(EngineCase::Admittance, &push, &engine)?;
            let seeds = run_bench(n, &engine, threads())?;
            let verdicts = evaluate(
                &bench_claims()?,
                &Runs {
                    bench: &seeds,
                    ..Runs::default()
                },
            )?;
            self.engine_bench = Some(EngineBench { off, on, verdicts });
        }
        self.engine_bench
            .as_ref()
            .ok_or_else(|| "engine bench runs missing".into())
    }

    /// §6.4.4 on the engine: [`ENGINE_SEEDS`] seeds of the three door runs
    /// and the door claims' verdicts over them.
    fn engine_door(&mut self) -> Result<&EngineDoor, Error> {
        if self.engine_door.is_none() {
            let n = self.engine_seeds();
            let runs = run_door(n, None, &engine_settings(), threads())?;
            let metrics: Vec<DoorRunMetrics> = runs.iter().map(|(m, _)| *m).collect();
            let verdicts = evaluate(
                &door_claims()?,
                &Runs {
                    door: &metrics,
                    ..Runs::default()
                },
            )?;
            self.engine_door = Some(EngineDoor { runs, verdicts });
        }
        self.engine_door
            .as_ref()
            .ok_or_else(|| "engine door runs missing".into())
    }

    /// §6.4.2: the wrist tracking a task trajectory in active mode.
    fn wrist_tracking(&mut self) -> &WristBenchRun {
        let quick = self.opts.quick;
        self.wrist_tracking
            .get_or_insert_with(|| wrist_tracking(if quick { 6.0 } else { 12.0 }, 1.0))
    }

    /// §6.4.3: the finger push, Case 1 (motors off) and Case 2
    /// (admittance).
    fn finger(&mut self) -> &[WristBenchRun] {
        self.finger.get_or_insert_with(|| {
            [FingerCase::MotorsOff, FingerCase::Admittance]
                .into_iter()
                .map(|c| wrist_finger_push(c, 8.0, 1))
                .collect()
        })
    }

    /// §6.4.4: passive, passive with a 3° heading error, active hold
    /// (seed 7, as `examples/door_opening.rs`).
    fn door(&mut self) -> &[DoorRun] {
        self.door.get_or_insert_with(|| {
            [
                (DoorControl::Passive, 0.0),
                (DoorControl::Passive, 3f64.to_radians()),
                (DoorControl::ActiveHold, 0.0),
            ]
            .into_iter()
            .map(|(c, h)| door_opening(&DoorConfig::thesis(c, h, 7)))
            .collect()
        })
    }

    fn locked(&mut self) -> &ComplianceResult {
        let quick = self.opts.quick;
        self.locked.get_or_insert_with(|| {
            locked_output(&LockedOutputConfig {
                duration: if quick { 6.0 } else { 20.0 },
                ..LockedOutputConfig::default()
            })
        })
    }

    fn back_driven(&mut self) -> &BackDrivenResult {
        let quick = self.opts.quick;
        self.back_driven.get_or_insert_with(|| {
            back_driven(&BackDrivenConfig {
                duration: if quick { 8.0 } else { 20.0 },
                ..BackDrivenConfig::default()
            })
        })
    }

    fn estimation(&mut self) -> &TorqueEstimationResult {
        let quick = self.opts.quick;
        self.estimation.get_or_insert_with(|| {
            let mut c = TorqueEstimationConfig::default();
            if quick {
                c.duration = 1.5;
                c.calibration_speed = 2.0;
            }
            torque_estimation(&c)
        })
    }

    /// Table 4.1's law at 4 ms with feedback A (none), B (F/T sensor),
    /// C (estimate).
    fn tracking(&mut self) -> &[TrackingResult] {
        let quick = self.opts.quick;
        self.tracking.get_or_insert_with(|| {
            [
                JointTorqueFeedback::None,
                JointTorqueFeedback::Sensor,
                JointTorqueFeedback::Estimated,
            ]
            .into_iter()
            .map(|fb| {
                let mut c = TrackingConfig::table_4_1(fb, 4e-3);
                if quick {
                    c.duration = 4.0;
                    c.settle = 1.0;
                }
                active_tracking(&c)
            })
            .collect()
        })
    }

    /// The smooth regime (layers the sampled law holds, 0.1 ms) with the
    /// estimated torque fed back.
    fn smooth(&mut self) -> &TrackingResult {
        let quick = self.opts.quick;
        self.smooth.get_or_insert_with(|| {
            let mut c = TrackingConfig::smooth(JointTorqueFeedback::Estimated);
            if quick {
                c.duration = 4.0;
                c.settle = 1.0;
            }
            active_tracking(&c)
        })
    }

    /// Duration and settling time of the chapter-4 engine tracking runs, s
    /// (shorter in quick mode).
    fn arm_run_length(&self) -> (f64, f64) {
        if self.opts.quick {
            (4.0, 1.0)
        } else {
            (12.0, 2.0)
        }
    }

    /// Fig. 4.3 on the engine arm (f32): the §4.4.1 joint tracking the
    /// raised cosine with feedback A (none), B (transmission torque), C
    /// (the joint step on the estimate); as long as the home-made runs.
    /// Then the same three on `Mrr` (the plant-independence check).
    fn arm_tracking(&mut self) -> Result<&[ArmTrackingRun], Error> {
        if self.arm_tracking.is_none() {
            let (duration, settle) = self.arm_run_length();
            let mut runs = Vec::new();
            for plant in [ArmPlant::engine(), ArmPlant::Mrr] {
                for fb in [
                    JointTorqueFeedback::None,
                    JointTorqueFeedback::Sensor,
                    JointTorqueFeedback::Estimated,
                ] {
                    runs.push(fig4_3_tracking::<f32>(plant, fb, duration, settle)?);
                }
            }
            self.arm_tracking = Some(runs);
        }
        self.arm_tracking
            .as_deref()
            .ok_or_else(|| "engine arm tracking runs missing".into())
    }

    /// Every chapter-4 engine run on the family members of [`ARM_FAMILY`]
    /// (one member in quick mode), one thread per member.
    fn arm_family(&mut self) -> Result<&[ArmFamilyRuns], Error> {
        if self.arm_family.is_none() {
            let (duration, settle) = self.arm_run_length();
            let n = self.engine_seeds() as usize;
            let results: Vec<Result<ArmFamilyRuns, String>> = std::thread::scope(|scope| {
                let handles: Vec<_> = ARM_FAMILY
                    .iter()
                    .take(n)
                    .map(|&(member, seed)| {
                        scope.spawn(move || {
                            family_runs(member, seed, duration, settle).map_err(|e| e.to_string())
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .map(|h| {
                        h.join()
                            .unwrap_or_else(|_| Err("a family run panicked".into()))
                    })
                    .collect()
            });
            let mut runs = Vec::new();
            for r in results {
                runs.push(r?);
            }
            self.arm_family = Some(runs);
        }
        self.arm_family
            .as_deref()
            .ok_or_else(|| "family arm runs missing".into())
    }

    /// Fig. 4.11–4.12 on the engine arm (f32): the hand back-drives the
    /// thesis joint unpowered (A) and under eq. (4.32) on the estimate (B).
    fn arm_back_driving(&mut self) -> Result<&[JointRun], Error> {
        if self.arm_back_driving.is_none() {
            let runs = vec![
                arm_back_driving::<f32>(ArmPlant::engine(), false)?,
                arm_back_driving::<f32>(ArmPlant::engine(), true)?,
            ];
            self.arm_back_driving = Some(runs);
        }
        self.arm_back_driving
            .as_deref()
            .ok_or_else(|| "engine back-driving runs missing".into())
    }

    /// The collision on the engine contact (Stop, Passive) and on the
    /// spring obstacle (Stop, engine and `Mrr`), f32.
    fn arm_collision(&mut self) -> Result<&ArmCollision, Error> {
        if self.arm_collision.is_none() {
            let engine = ArmPlant::engine();
            let c = ArmCollision {
                stop: arm_collision::<f32>(
                    engine,
                    CollisionObstacle::Contact,
                    CollisionReaction::Stop,
                )?,
                passive: arm_collision::<f32>(
                    engine,
                    CollisionObstacle::Contact,
                    CollisionReaction::Passive,
                )?,
                spring: arm_collision::<f32>(
                    engine,
                    CollisionObstacle::Spring,
                    CollisionReaction::Stop,
                )?,
                spring_mrr: arm_collision::<f32>(
                    ArmPlant::Mrr,
                    CollisionObstacle::Spring,
                    CollisionReaction::Stop,
                )?,
            };
            self.arm_collision = Some(c);
        }
        self.arm_collision
            .as_ref()
            .ok_or_else(|| "engine collision runs missing".into())
    }

    /// Eq. (4.32) at 4 ms: A uncompensated, B estimate, C F/T sensor.
    fn passive(&mut self) -> &[BackDriveResult] {
        let quick = self.opts.quick;
        self.passive.get_or_insert_with(|| {
            [
                BackDriveMode::Uncompensated,
                BackDriveMode::Estimated,
                BackDriveMode::Sensor,
            ]
            .into_iter()
            .map(|m| {
                let mut c = BackDriveConfig::new(m);
                if quick {
                    c.duration = 4.0;
                    c.settle = 1.0;
                }
                back_drive(&c)
            })
            .collect()
        })
    }
}

// ---------------------------------------------------------------- drawing

/// One curve (or point cloud) of a chart.
struct Series {
    label: String,
    color: RGBColor,
    points: Vec<(f64, f64)>,
    dots: bool,
}

fn line(label: &str, color: RGBColor, points: Vec<(f64, f64)>) -> Series {
    Series {
        label: label.to_string(),
        color,
        points: thin(points, 2500),
        dots: false,
    }
}

fn dots(label: &str, color: RGBColor, points: Vec<(f64, f64)>) -> Series {
    Series {
        label: label.to_string(),
        color,
        points: thin(points, 1500),
        dots: true,
    }
}

/// Keep at most about `max` points (every k-th), so the SVGs stay small.
fn thin(points: Vec<(f64, f64)>, max: usize) -> Vec<(f64, f64)> {
    let step = points.len().div_ceil(max).max(1);
    points
        .into_iter()
        .enumerate()
        .filter(|(i, _)| i % step == 0)
        .map(|(_, p)| p)
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect()
}

const BLUE_: RGBColor = RGBColor(31, 119, 180);
const ORANGE: RGBColor = RGBColor(255, 127, 14);
const GREEN_: RGBColor = RGBColor(44, 160, 44);
const RED_: RGBColor = RGBColor(214, 39, 40);
const GREY: RGBColor = RGBColor(120, 120, 120);
const BLACK_: RGBColor = RGBColor(0, 0, 0);

/// A chart: title, axis labels, series, and vertical markers `(x, text)`
/// (area labels A/B/C).
struct Chart<'a> {
    title: &'a str,
    x: &'a str,
    y: &'a str,
    series: Vec<Series>,
    markers: Vec<(f64, String)>,
}

fn draw(path: &Path, c: &Chart) -> Result<(), Error> {
    let all = c.series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 > x1 {
        return Err(format!("{}: no data", c.title).into());
    }
    let pad = |a: f64, b: f64| {
        let d = (b - a).abs().max(1e-12 * a.abs().max(1.0));
        (a - 0.05 * d, b + 0.05 * d)
    };
    let (x0, x1) = pad(x0, x1);
    // Room above the data for the legend.
    let (y0, y1) = pad(y0, y1 + 0.25 * (y1 - y0).abs().max(1e-12));
    let root = SVGBackend::new(path, (820, 460)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(c.title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(c.x)
        .y_desc(c.y)
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    for &(x, ref text) in &c.markers {
        chart.draw_series(LineSeries::new(
            vec![(x, y0), (x, y1)],
            GREY.stroke_width(1),
        ))?;
        chart.draw_series(std::iter::once(Text::new(
            text.clone(),
            (x, y1 - 0.04 * (y1 - y0)),
            ("sans-serif", 14).into_font().color(&BLACK),
        )))?;
    }
    for s in &c.series {
        let color = s.color;
        if s.dots {
            chart
                .draw_series(
                    s.points
                        .iter()
                        .map(move |&p| Circle::new(p, 3, color.filled())),
                )?
                .label(s.label.clone())
                .legend(move |(x, y)| Circle::new((x + 10, y), 3, color.filled()));
        } else {
            chart
                .draw_series(LineSeries::new(s.points.clone(), color.stroke_width(1)))?
                .label(s.label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
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

fn figure(
    dir: &Path,
    file: &str,
    title: &str,
    chart: Chart,
    thesis: String,
    ours: String,
) -> Result<Figure, Error> {
    draw(&dir.join(file), &chart)?;
    Ok(Figure {
        file: file.to_string(),
        title: title.to_string(),
        thesis,
        ours,
    })
}

fn max_abs(e: &ErrorStats) -> f64 {
    e.max.abs().max(e.min.abs())
}

/// Torques from 0 to `T2` and `−T2`, N·m.
fn torque_grid(t2: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|i| -1.2 * t2 + 2.4 * t2 * i as f64 / n as f64)
        .collect()
}

// ---------------------------------------------------------------- chapter 2

fn fig2_11(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let d = CatalogueData::SHD_17_100;
    let m = Models::shd_17_100();
    let taus = torque_grid(d.t2, 480);
    let proposed: Vec<_> = taus
        .iter()
        .map(|&t| (t, m.proposed.flexspline().local_stiffness(t) * 1e-3))
        .collect();
    let piecewise: Vec<_> = taus
        .iter()
        .map(|&t| (t, m.piecewise.local_stiffness(t) * 1e-3))
        .collect();
    let cubic: Vec<_> = taus
        .iter()
        .map(|&t| (t, m.cubic.local_stiffness(m.cubic.torsion(t)) * 1e-3))
        .collect();
    let k = |t: f64| m.proposed.flexspline().local_stiffness(t) * 1e-3;
    figure(
        &dir,
        "fig2_11_local_stiffness.svg",
        "Fig. 2.11: local elastic coefficient",
        Chart {
            title: "Fig. 2.11  local stiffness dτ/dΔθ of the three models (SHD-17-100)",
            x: "flexspline torque τ_f (N·m)",
            y: "local stiffness (kN·m/rad)",
            series: vec![
                line("proposed, eq. (2.26)", BLUE_, proposed),
                line("catalogue piecewise, eq. (2.11)", ORANGE, piecewise),
                line("cubic, eq. (2.10)", GREEN_, cubic),
            ],
            markers: vec![],
        },
        "the proposed model's stiffness matches the piecewise and cubic models \
         (catalogue K1 = 8.4, K2 = 9.4 kN·m/rad)"
            .into(),
        format!(
            "proposed K(0) = {:.2}, K(T1) = {:.2}, K(T2) = {:.2} kN·m/rad against K1 = {:.1}, K2 = {:.1}",
            k(0.0),
            k(d.t1),
            k(d.t2),
            d.k1 * 1e-3,
            d.k2 * 1e-3
        ),
    )
}

fn fig2_12(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let d = CatalogueData::SHD_17_100;
    let m = Models::shd_17_100();
    let taus = torque_grid(d.t2, 480);
    let curve = |f: &dyn Fn(f64) -> f64| -> Vec<(f64, f64)> {
        taus.iter().map(|&t| (f(t) * 1e3, t)).collect()
    };
    let mut gap = 0.0f64;
    for &t in taus.iter().filter(|t| t.abs() <= d.t2) {
        gap = gap.max((m.proposed.flexspline().torsion(t) - m.piecewise.torsion(t)).abs());
    }
    figure(
        &dir,
        "fig2_12_stiffness_curves.svg",
        "Fig. 2.12: stiffness curves",
        Chart {
            title: "Fig. 2.12  torque–torsion curves (SHD-17-100)",
            x: "torsion Δθ (mrad)",
            y: "torque (N·m)",
            series: vec![
                line(
                    "proposed, eq. (2.26)",
                    BLUE_,
                    curve(&|t| m.proposed.flexspline().torsion(t)),
                ),
                line(
                    "catalogue piecewise, eq. (2.11)",
                    ORANGE,
                    curve(&|t| m.piecewise.torsion(t)),
                ),
                line("cubic, eq. (2.10)", GREEN_, curve(&|t| m.cubic.torsion(t))),
            ],
            markers: vec![],
        },
        "the three stiffness curves agree over the rated range".into(),
        format!(
            "largest |proposed − piecewise| torsion over |τ| ≤ T2 = {} N·m: {:.1} µrad \
             (torsion at T2: {:.3} mrad)",
            d.t2,
            gap * 1e6,
            m.piecewise.torsion(d.t2) * 1e3
        ),
    )
}

/// Samples per cycle of the drive bench's profile
/// ([`DrivePlant::profile`](mrr_control::sim::plants::DrivePlant::profile)).
const PROFILE_CYCLE: f64 = 100.0;

fn fig2_17(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let old = r.locked();
    let old_peak = old
        .samples
        .iter()
        .map(|s| s.wave_generator_torque.abs() * 100.0)
        .fold(0.0, f64::max);
    let d = r.drive_figs()?;
    let run = &d.runs[0];
    let pts: Vec<_> = run
        .locked
        .iter()
        .enumerate()
        .map(|(k, s)| (k as f64 / PROFILE_CYCLE, s.wave_generator_torque * 100.0))
        .collect();
    let peak = pts.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let peaks: Vec<f64> = d
        .runs
        .iter()
        .map(|x| {
            x.locked
                .iter()
                .map(|s| s.wave_generator_torque.abs() * 100.0)
                .fold(0.0, f64::max)
        })
        .collect();
    figure(
        &dir,
        "fig2_17_input_torque.svg",
        "Fig. 2.17: motor-side input torque",
        Chart {
            title: "Fig. 2.17  motor torque command, output locked",
            x: "profile cycles (100 samples each; the plant is rate-independent)",
            y: "motor torque τ_w (N·cm)",
            series: vec![line(&format!("τ_w, {}", d.shown()), BLUE_, pts)],
            markers: vec![],
        },
        "a sinusoidal motor torque of decreasing amplitude drives the locked drive".into(),
        format!(
            "{}: ten cycles decreasing linearly to 0, peak {peak:.1} N·cm; peaks over {}: {} \
             N·cm. Comparison only, the old plant of sim::experiments: peak {old_peak:.1} N·cm",
            d.source(),
            d.runs_text(),
            spread(&peaks, 1.0, 1)
        ),
    )
}

fn fig2_18(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let psi = CatalogueData::SHD_17_100.hysteresis_loss;
    let a = r.locked();
    let to = a.samples.last().map_or(0.0, |s| s.time).min(6.0);
    let old_plant = width_at_zero(
        &a.samples,
        |s| -s.wave_generator_torque,
        |s| s.measured_torsion,
        0.0,
        to,
    );
    let old_model = width_at_zero(
        &a.samples,
        |s| -s.wave_generator_torque,
        |s| s.proposed,
        0.0,
        to,
    );
    let d = r.drive_figs()?;
    let run = &d.runs[0];
    let meas: Vec<_> = run
        .locked
        .iter()
        .map(|s| (-s.wave_generator_torque * 100.0, s.torsion * 1e3))
        .collect();
    let model: Vec<_> = run
        .locked
        .iter()
        .zip(&run.locked_proposed)
        .map(|(s, p)| (-s.wave_generator_torque * 100.0, p * 1e3))
        .collect();
    let widths = |x: &DriveFigureRun| {
        let plant = loop_width(&x.locked, |s| -s.wave_generator_torque, |s| s.torsion);
        let idx: Vec<usize> = (0..x.locked.len()).collect();
        let model = loop_width(
            &idx,
            |&i| -x.locked[i].wave_generator_torque,
            |&i| x.locked_proposed[i],
        );
        (plant, model)
    };
    let (w_plant, w_model) = widths(run);
    let ratio: Vec<f64> = d
        .runs
        .iter()
        .map(|x| {
            let (p, m) = widths(x);
            m / p
        })
        .collect();
    figure(
        &dir,
        "fig2_18_hysteresis.svg",
        "Fig. 2.18: input torque versus output torsion",
        Chart {
            title: "Fig. 2.18  torsion versus motor torque (hysteresis loop)",
            x: "input torque −τ_w (N·cm)",
            y: "torsion Δθ (mrad)",
            series: vec![
                dots(&format!("encoders, {}", d.shown()), GREY, meas),
                line("proposed model, eq. (2.30), catalogue", RED_, model),
            ],
            markers: vec![],
        },
        format!(
            "the measured loop and the model's agree; catalogue hysteresis loss Ψ = {:.1e} rad",
            psi
        ),
        format!(
            "{}: loop width at zero torque (whole run) plant {:.2e} rad, eq. (2.30) identified \
             from the catalogue {:.2e} rad; model/plant width over {}: {}. Comparison only, the \
             old plant of sim::experiments (first {to:.0} s): plant {:.2e} rad, model {:.2e} rad",
            d.source(),
            w_plant,
            w_model,
            d.runs_text(),
            spread(&ratio, 1.0, 2),
            old_plant,
            old_model
        ),
    )
}

fn fig2_19(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let old = r.locked().clone();
    let d = r.drive_figs()?;
    let run = &d.runs[0];
    let err = |pred: &[f64]| -> Vec<(f64, f64)> {
        run.locked
            .iter()
            .zip(pred)
            .enumerate()
            .map(|(k, (s, p))| (k as f64 / PROFILE_CYCLE, (p - s.torsion) * 1e3))
            .collect()
    };
    let m = run.metrics;
    let reduction: Vec<f64> = d.runs.iter().map(|x| x.metrics.reduction_blind()).collect();
    let proposed: Vec<f64> = d
        .runs
        .iter()
        .map(|x| x.metrics.locked_proposed_blind)
        .collect();
    figure(
        &dir,
        "fig2_19_error_time.svg",
        "Fig. 2.19: estimation error versus time",
        Chart {
            title: "Fig. 2.19  torsion error (model − encoders), output locked",
            x: "profile cycles (100 samples each)",
            y: "torsion error (mrad)",
            series: vec![
                line(
                    "piecewise, eq. (2.11), catalogue",
                    ORANGE,
                    err(&run.locked_classic),
                ),
                line(
                    &format!("proposed, eq. (2.30), catalogue; {}", d.shown()),
                    BLUE_,
                    err(&run.locked_proposed),
                ),
            ],
            markers: vec![],
        },
        "error reduced from ±2.3e-4 rad (eq. 2.11) to ±1.7e-4 rad (eq. 2.30)".into(),
        format!(
            "{}: peak |error| piecewise {:.2e} rad, proposed {:.2e} rad; over {}: proposed peak \
             {} rad (claim 2.19-level), 1 − proposed/piecewise {} (claim 2.19-blind). \
             Comparison only, the old plant of sim::experiments: proposed {:+.2e} … {:+.2e} \
             rad, piecewise {:+.2e} … {:+.2e} rad",
            d.source(),
            m.locked_classic_blind,
            m.locked_proposed_blind,
            d.runs_text(),
            spread_e(&proposed),
            spread(&reduction, 1.0, 2),
            old.proposed.min,
            old.proposed.max,
            old.piecewise.min,
            old.piecewise.max
        ),
    )
}

fn fig2_20(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let d = r.drive_figs()?;
    let run = &d.runs[0];
    let tau = std::f64::consts::TAU;
    let err = |pred: &[f64]| -> Vec<(f64, f64)> {
        run.locked
            .iter()
            .zip(pred)
            .map(|(s, p)| (s.motor_angle.rem_euclid(tau), (p - s.torsion) * 1e3))
            .collect()
    };
    let (lo, hi) = run.locked.iter().fold((f64::MAX, f64::MIN), |(l, h), s| {
        (l.min(s.motor_angle), h.max(s.motor_angle))
    });
    let idx: Vec<usize> = (0..run.locked.len()).collect();
    let gap = |pred: &[f64]| {
        loop_width(
            &idx,
            |&i| -run.locked[i].wave_generator_torque,
            |&i| pred[i] - run.locked[i].torsion,
        )
    };
    figure(
        &dir,
        "fig2_20_error_motor.svg",
        "Fig. 2.20: estimation error versus motor position",
        Chart {
            title: "Fig. 2.20  torsion error versus motor position",
            x: "motor angle θ_wi mod 2π (rad)",
            y: "torsion error (mrad)",
            series: vec![
                dots("piecewise, eq. (2.11)", ORANGE, err(&run.locked_classic)),
                dots(
                    &format!("proposed, eq. (2.30); {}", d.shown()),
                    BLUE_,
                    err(&run.locked_proposed),
                ),
            ],
            markers: vec![],
        },
        "two similar curves (kinematic error); the proposed model narrows the gap between \
         them (hysteresis)"
            .into(),
        format!(
            "{}: the motor swings over {:.2} rad; signed gap between the error's unloading and \
             loading branches at zero torque (a model without hysteresis leaves the plant's \
             loop, one whose hysteresis is too wide flips its sign): piecewise {:+.2e} rad, \
             proposed {:+.2e} rad",
            d.source(),
            hi - lo,
            gap(&run.locked_classic),
            gap(&run.locked_proposed)
        ),
    )
}

fn fig2_21(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let old_peak = r
        .back_driven()
        .compliance
        .samples
        .iter()
        .map(|s| s.flexspline_torque.abs())
        .fold(0.0, f64::max);
    let d = r.drive_figs()?;
    let run = &d.runs[0];
    let pts: Vec<_> = run
        .held
        .iter()
        .enumerate()
        .map(|(k, s)| (k as f64 / PROFILE_CYCLE, s.flexspline_torque))
        .collect();
    let peak = pts.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let peaks: Vec<f64> = d
        .runs
        .iter()
        .map(|x| {
            x.held
                .iter()
                .map(|s| s.flexspline_torque.abs())
                .fold(0.0, f64::max)
        })
        .collect();
    figure(
        &dir,
        "fig2_21_external_torque.svg",
        "Fig. 2.21: external torque on the output side",
        Chart {
            title: "Fig. 2.21  output-side torque, motor held",
            x: "profile cycles (100 samples each)",
            y: "flexspline torque τ_f (N·m)",
            series: vec![line(
                &format!("τ_f (torque sensor), {}", d.shown()),
                BLUE_,
                pts,
            )],
            markers: vec![],
        },
        "a bidirectional external torque of decreasing amplitude back-drives the link".into(),
        format!(
            "{}: measured flexspline torque peaks at {peak:.1} N·m; over {}: {} N·m. \
             Comparison only, the old plant of sim::experiments: {old_peak:.1} N·m",
            d.source(),
            d.runs_text(),
            spread(&peaks, 1.0, 1)
        ),
    )
}

fn fig2_22(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let old = r.back_driven().compliance.clone();
    let d = r.drive_figs()?;
    let run = &d.runs[0];
    let meas: Vec<_> = run
        .held
        .iter()
        .map(|s| (s.torsion * 1e3, s.flexspline_torque))
        .collect();
    let model: Vec<_> = run
        .held
        .iter()
        .zip(&run.held_proposed)
        .map(|(s, p)| (p * 1e3, s.flexspline_torque))
        .collect();
    let held: Vec<f64> = d
        .runs
        .iter()
        .map(|x| x.metrics.held_proposed_blind)
        .collect();
    let m = run.metrics;
    figure(
        &dir,
        "fig2_22_back_driven.svg",
        "Fig. 2.22: output torque versus output torsion (back-driven)",
        Chart {
            title: "Fig. 2.22  output torque versus torsion, back-driven",
            x: "torsion Δθ (mrad)",
            y: "flexspline torque τ_f (N·m)",
            series: vec![
                dots(&format!("encoders, {}", d.shown()), GREY, meas),
                line("eq. (2.30), τ_w from eq. (2.40), catalogue", RED_, model),
            ],
            markers: vec![],
        },
        "the torsion predicted by eq. (2.30) with τ_w from eq. (2.40) agrees with the measured one"
            .into(),
        format!(
            "{}: peak |torsion error| eq. (2.30) {:.2e} rad, piecewise eq. (2.11) {:.2e} rad; \
             eq. (2.30) over {}: {} rad (claim 2.22-blind). Comparison only, the old plant of \
             sim::experiments: RMS eq. (2.30) {:.2e} rad, piecewise {:.2e} rad, cubic {:.2e} rad",
            d.source(),
            m.held_proposed_blind,
            m.held_classic_blind,
            d.runs_text(),
            spread_e(&held),
            old.proposed.rms,
            old.piecewise.rms,
            old.cubic.rms
        ),
    )
}

// ---------------------------------------------------------------- chapter 3

/// The link-side part of a kinematic-error model (`a0`, `a_l1`, `b_l1`).
fn link_part(m: &KinematicErrorModel) -> KinematicErrorModel {
    let c = m.coefficients();
    KinematicErrorModel::try_new([c[0], c[1], c[2], 0.0, 0.0, 0.0, 0.0])
        .expect("a part of a valid model is valid")
}

/// The motor-side part (`a_w1`, `b_w1`, `a_w2`, `b_w2`).
fn motor_part(m: &KinematicErrorModel) -> KinematicErrorModel {
    let c = m.coefficients();
    KinematicErrorModel::try_new([0.0, 0.0, 0.0, c[3], c[4], c[5], c[6]])
        .expect("a part of a valid model is valid")
}

/// Link angles over one output revolution, rad.
fn revolution(n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |i| std::f64::consts::TAU * i as f64 / n as f64)
}

fn fig3_1(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let j = r.joint_figs()?;
    let run = &j.runs[0];
    let deg = 180.0 / std::f64::consts::PI;
    let total: Vec<_> = forward(run)
        .iter()
        .map(|c| (c.link * deg, c.error * 1e6))
        .collect();
    let fit: Vec<_> = revolution(720)
        .map(|q| (q * deg, link_part(&run.fitted).evaluate(q, 0.0) * 1e6))
        .collect();
    let amp = |m: &KinematicErrorModel| m.phase_form().amplitudes[0];
    // Fitted link amplitude over the drawn output term, every run.
    let share: Vec<f64> = j
        .runs
        .iter()
        .zip(&j.drawn)
        .map(|(x, k)| amp(&x.fitted) / k.output.0)
        .collect();
    figure(
        &dir,
        "fig3_1_ke_link.svg",
        "Fig. 3.1: kinematic error versus link position",
        Chart {
            title: "Fig. 3.1  kinematic error over one output revolution",
            x: "link angle θ_fo (deg)",
            y: "kinematic error (µrad)",
            series: vec![
                line(
                    &format!("drawn truth, {}", j.shown()),
                    GREY,
                    thin(total, 6100),
                ),
                line("fitted link harmonic, eq. (3.3)", RED_, fit),
            ],
            markers: vec![],
        },
        format!(
            "the measured error has a once-per-output-revolution harmonic (Table 3.2: \
             amplitude {:.1} µrad)",
            amp(&KinematicErrorModel::table_3_2()) * 1e6
        ),
        format!(
            "{}; truth: its drawn kinematic error (wave-generator harmonics 1–4, tooth-pass \
             ripple, output term {:.1} µrad), not eq. (3.7); eq. (3.7) fitted by \
             KinematicErrorFit from the plant's encoders over one revolution each way at zero \
             load (§3.1): link amplitude {:.1} µrad; fitted/drawn link amplitude over {}: {}",
            j.source(),
            j.drawn[0].output.0 * 1e6,
            amp(&run.fitted) * 1e6,
            j.runs_text(),
            spread(&share, 1.0, 3)
        ),
    )
}

fn fig3_2(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let j = r.joint_figs()?;
    let run = &j.runs[0];
    let deg = 180.0 / std::f64::consts::PI;
    let tau = std::f64::consts::TAU;
    let residual: Vec<_> = forward(run)
        .iter()
        .map(|c| {
            (
                c.motor.rem_euclid(tau) * deg,
                (c.error - link_part(&run.fitted).evaluate(c.link, 0.0)) * 1e6,
            )
        })
        .collect();
    // The estimator's θ_wi is −θ_m.
    let fit: Vec<_> = revolution(720)
        .map(|qm| (qm * deg, motor_part(&run.fitted).evaluate(0.0, -qm) * 1e6))
        .collect();
    let amps = |x: &JointFigureRun| {
        let a = x.fitted.phase_form().amplitudes;
        [a[1], a[2]]
    };
    let (mut h1, mut h2) = (Vec::new(), Vec::new());
    for (x, k) in j.runs.iter().zip(&j.drawn) {
        let a = amps(x);
        h1.push(a[0] / k.wave_generator[0].0);
        h2.push(a[1] / k.wave_generator[1].0);
    }
    let k = &j.drawn[0];
    let a = amps(run);
    figure(
        &dir,
        "fig3_2_ke_motor.svg",
        "Fig. 3.2: kinematic error versus motor position",
        Chart {
            title: "Fig. 3.2  residual kinematic error over one motor revolution",
            x: "motor angle θ_m mod 360° (deg)",
            y: "residual error (µrad)",
            series: vec![
                dots(
                    &format!("drawn truth minus fitted link harmonic, {}", j.shown()),
                    GREY,
                    thin(residual, 4000),
                ),
                line("fitted motor harmonics, eq. (3.5)", RED_, fit),
            ],
            markers: vec![],
        },
        "the residual repeats once per motor revolution with two harmonics (eq. 3.5)".into(),
        format!(
            "{}: drawn wave-generator harmonics 1, 2 of {:.1}, {:.1} µrad, fitted {:.1}, {:.1} \
             µrad; the content eq. (3.5) lacks (harmonics 3, 4 and the ripple: {:.1}, {:.1}, \
             {:.1} µrad) stays in the residual; fitted/drawn over {}: harmonic 1 {}, \
             harmonic 2 {}",
            j.shown(),
            k.wave_generator[0].0 * 1e6,
            k.wave_generator[1].0 * 1e6,
            a[0] * 1e6,
            a[1] * 1e6,
            k.wave_generator[2].0 * 1e6,
            k.wave_generator[3].0 * 1e6,
            k.ripple.0 * 1e6,
            j.runs_text(),
            spread(&h1, 1.0, 3),
            spread(&h2, 1.0, 3)
        ),
    )
}

fn fig3_3(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let j = r.joint_figs()?;
    let run = &j.runs[0];
    let deg = 180.0 / std::f64::consts::PI;
    let cal = forward(run);
    let t: Vec<_> = cal.iter().map(|c| (c.link * deg, c.error * 1e6)).collect();
    let f: Vec<_> = cal
        .iter()
        .map(|c| (c.link * deg, run.fitted.evaluate(c.link, -c.motor) * 1e6))
        .collect();
    let worst = t
        .iter()
        .zip(&f)
        .map(|(a, b)| (a.1 - b.1).abs())
        .fold(0.0, f64::max);
    let peak = cal.iter().map(|c| c.error.abs()).fold(0.0, f64::max);
    let residuals: Vec<f64> = j.runs.iter().map(|x| x.ke_fit_residual).collect();
    let d = CatalogueData::SHD_17_100;
    figure(
        &dir,
        "fig3_3_ke_model.svg",
        "Fig. 3.3: modelled kinematic error",
        Chart {
            title: "Fig. 3.3  kinematic error model, eq. (3.7), against the drawn truth",
            x: "link angle θ_fo (deg)",
            y: "kinematic error (µrad)",
            series: vec![
                line(&format!("drawn truth, {}", j.shown()), GREY, thin(t, 6100)),
                line("fitted, eq. (3.7)", RED_, thin(f, 6100)),
            ],
            markers: vec![],
        },
        "eq. (3.7) models the kinematic error; without it the torque error would reach \
         K2·θ_err (eq. 3.1, Table 3.1: 4.1 N·m for this size)"
            .into(),
        format!(
            "{}: largest |truth| {:.1} µrad (K2·that = {:.2} N·m), largest |fitted − truth| \
             {:.1} µrad, residual RMS/error RMS {:.3}; over {}: {} (claim 3.1-fit: at most 0.5 \
             in 80 % of the runs)",
            j.shown(),
            peak * 1e6,
            peak * d.k2,
            worst,
            run.ke_fit_residual,
            j.runs_text(),
            spread(&residuals, 1.0, 3)
        ),
    )
}

/// `τ̂_t − τ_t` of a trace.
fn errors(trace: &[TorqueSample]) -> ErrorStats {
    ErrorStats::of(trace.iter().map(|s| s.estimate - s.truth))
}

/// Points of one curve, `(x, y)`.
type Points = Vec<(f64, f64)>;

/// The true torque and the estimate of a trace, against time.
fn torque_series(trace: &[TorqueSample]) -> (Points, Points) {
    (
        trace.iter().map(|s| (s.time, s.truth)).collect(),
        trace.iter().map(|s| (s.time, s.estimate)).collect(),
    )
}

fn fig3_6(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let chattering = r.tracking()[2].feedback_error;
    let smooth = r.smooth().feedback_error;
    let j = r.joint_figs()?;
    let run = &j.runs[0];
    let (truth, est) = torque_series(&run.tracking);
    let e = errors(&run.tracking);
    let peaks: Vec<f64> = j
        .runs
        .iter()
        .map(|x| max_abs(&errors(&x.tracking)))
        .collect();
    let rmss: Vec<f64> = j.runs.iter().map(|x| errors(&x.tracking).rms).collect();
    figure(
        &dir,
        "fig3_6_estimation_slow.svg",
        "Fig. 3.6: estimated versus measured torque, slow changes",
        Chart {
            title: "Fig. 3.6  joint torque while tracking a slow raised cosine (4 ms preset)",
            x: "time (s)",
            y: "joint torque τ_t (N·m)",
            series: vec![
                line(
                    &format!("true τ_t (F/T sensor), {}", j.shown()),
                    GREY,
                    truth,
                ),
                line("estimate, eq. (3.8)–(3.10)", RED_, est),
            ],
            markers: vec![],
        },
        "estimation error around 1 N·m, comparable with the F/T sensor".into(),
        format!(
            "{}; the joint step of table_4_1_at(0.004) with the fitted eq. (3.7) tracks 0.8 rad \
             in 3 s under a payload G sin θ_l: estimate − true τ_t from 0.2 s, shown run RMS \
             {:.2} N·m, max |·| {:.2} N·m; over {}: max |·| {}, RMS {} N·m (claim 3.6-level). \
             Comparison only, the old plant of sim::closed_loop (Table 3.2's kinematic error, \
             the model the estimator subtracts): 0.1 ms layers RMS {:.2}, max |·| {:.2} N·m; \
             Table 4.1 at 4 ms RMS {:.2}, max |·| {:.2} N·m",
            j.source(),
            e.rms,
            max_abs(&e),
            j.runs_text(),
            spread(&peaks, 1.0, 2),
            spread(&rmss, 1.0, 2),
            smooth.rms,
            max_abs(&smooth),
            chattering.rms,
            max_abs(&chattering)
        ),
    )
}

/// The Table 3.3 run drawn in Fig. 3.7: +5 N·cm at the motor.
const FIG3_7_COMMAND: usize = 3;

fn fig3_7(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let old = interaction_scenario(&ModeScenarioConfig::interaction());
    let old_e = ErrorStats::of(old.trace.iter().map(|x| x.estimate - x.joint_torque));
    let j = r.joint_figs()?;
    let pick = |x: &JointFigureRun| -> Result<Vec<TorqueSample>, Error> {
        Ok(x.table_3_3
            .get(FIG3_7_COMMAND)
            .ok_or("Table 3.3 run missing")?
            .trace
            .clone())
    };
    let shown = pick(&j.runs[0])?;
    let (truth, est) = torque_series(&shown);
    let e = errors(&shown);
    let peak = shown.iter().map(|x| x.truth.abs()).fold(0.0, f64::max);
    let mut peaks = Vec::new();
    for x in &j.runs {
        peaks.push(max_abs(&errors(&pick(x)?)));
    }
    figure(
        &dir,
        "fig3_7_estimation_fast.svg",
        "Fig. 3.7: estimated versus measured torque, fast changes",
        Chart {
            title: "Fig. 3.7  joint torque while a hand moves the link out and back",
            x: "time (s)",
            y: "joint torque τ_t (N·m)",
            series: vec![
                line(&format!("true τ_t, {}", j.shown()), GREY, truth),
                line("estimate", RED_, est),
            ],
            markers: vec![],
        },
        "the estimate follows torque applied by hand; error around 1 N·m".into(),
        format!(
            "{}; motor open loop at {:+.0} N·cm while a hand guides the link 0.48 rad out \
             and back in 1 s (Table 3.3's run): true torque up to {peak:.1} N·m; estimate − \
             true RMS {:.2} N·m, max |·| {:.2} N·m; max |·| over {}: {} N·m. Comparison \
             only, the old plant of sim::closed_loop (Table 3.2's kinematic error): RMS {:.2}, \
             max |·| {:.2} N·m",
            j.source(),
            TABLE_3_3_COMMANDS[FIG3_7_COMMAND] * 100.0,
            e.rms,
            max_abs(&e),
            j.runs_text(),
            spread(&peaks, 1.0, 2),
            old_e.rms,
            max_abs(&old_e)
        ),
    )
}

fn fig3_8(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let p = payload_drop(&PayloadDropConfig::default());
    let j = r.joint_figs()?;
    let run = &j.runs[0];
    let (truth, est) = torque_series(&run.payload_cut);
    let shares: Vec<f64> = j.runs.iter().map(|x| x.step_share).collect();
    figure(
        &dir,
        "fig3_8_payload_drop.svg",
        "Fig. 3.8: torque estimation when the payload is cut",
        Chart {
            title: "Fig. 3.8  a 1.5 N·m payload cut at t = 1 s, joint holding position",
            x: "time (s)",
            y: "joint torque τ_t (N·m)",
            series: vec![
                line(&format!("true τ_t, {}", j.shown()), GREY, truth),
                line("estimate", RED_, est),
            ],
            markers: vec![],
        },
        "the estimate has a relatively good dynamic response to the sudden change".into(),
        format!(
            "{}; share of the true step the estimate shows 40–100 ms after the cut: shown \
             run {:.2}; over {}: {} (claim 3.8-step). Comparison only, the old plant of \
             sim::closed_loop (1 kg at 0.4 m, Table 3.2's kinematic error): step {:.2} N·m \
             (true {:.2}), half-way after {:.1} ms (true {:.1} ms)",
            j.source(),
            run.step_share,
            j.runs_text(),
            spread(&shares, 1.0, 2),
            p.estimate.after - p.estimate.before,
            p.truth.after - p.truth.before,
            p.estimate.half_time * 1e3,
            p.truth.half_time * 1e3,
        ),
    )
}

fn fig3_9(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    // Table 3.3 as printed: motor torque (N·cm), max and min error (N·m).
    const TABLE_3_3: [(f64, f64, f64); 7] = [
        (0.0, 0.3, -0.5),
        (3.0, 0.2, -1.2),
        (-3.0, 0.6, -1.1),
        (5.0, 0.8, -1.2),
        (-5.0, 0.7, -1.3),
        (10.0, 1.0, -0.9),
        (-10.0, 0.6, -2.3),
    ];
    let c = r.estimation();
    let k = ESTIMATORS
        .iter()
        .position(|e| *e == "f64, KE fitted")
        .ok_or("estimator missing")?;
    let old = c.overall[k];
    let j = r.joint_figs()?;
    // Per motor torque, the envelope over the runs.
    let mut env: Vec<(f64, f64, f64)> = TABLE_3_3_COMMANDS
        .iter()
        .enumerate()
        .map(|(i, &cmd)| {
            let lo = j
                .runs
                .iter()
                .filter_map(|x| x.table_3_3.get(i).map(|t| t.min))
                .fold(f64::INFINITY, f64::min);
            let hi = j
                .runs
                .iter()
                .filter_map(|x| x.table_3_3.get(i).map(|t| t.max))
                .fold(f64::NEG_INFINITY, f64::max);
            (cmd * 100.0, lo, hi)
        })
        .collect();
    env.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (lo, hi) = env
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), e| {
            (l.min(e.1), h.max(e.2))
        });
    let peaks: Vec<f64> = j
        .runs
        .iter()
        .map(|x| x.table_3_3.iter().map(Table33Run::peak).fold(0.0, f64::max))
        .collect();
    let worst_thesis = TABLE_3_3
        .iter()
        .map(|t| t.1.abs().max(t.2.abs()))
        .fold(0.0, f64::max);
    figure(
        &dir,
        "fig3_9_table3_3.svg",
        "Fig. 3.9 / Table 3.3: estimation error at different motor torques",
        Chart {
            title: "Table 3.3  largest and smallest estimation error per motor torque",
            x: "motor torque (N·cm)",
            y: "estimate − true (N·m)",
            series: vec![
                dots(
                    "thesis max",
                    ORANGE,
                    TABLE_3_3.iter().map(|t| (t.0, t.1)).collect(),
                ),
                dots(
                    "thesis min",
                    RED_,
                    TABLE_3_3.iter().map(|t| (t.0, t.2)).collect(),
                ),
                line(
                    &format!("family max over {}", j.runs_text()),
                    BLUE_,
                    env.iter().map(|e| (e.0, e.2)).collect(),
                ),
                line(
                    "family min",
                    GREEN_,
                    env.iter().map(|e| (e.0, e.1)).collect(),
                ),
            ],
            markers: vec![],
        },
        format!("errors within −2.3 … +1.0 N·m (largest |·| {worst_thesis:.1} N·m)"),
        format!(
            "{}; each motor torque open loop while a hand moves the link at up to 1.5 rad/s: \
             errors within {lo:+.2} … {hi:+.2} N·m over {}; largest |·| per run {} N·m \
             (claim 3.3-table). Comparison only, the old plant of sim::experiments (Table \
             3.2's kinematic error): {:+.2} … {:+.2} N·m",
            j.source(),
            j.runs_text(),
            spread(&peaks, 1.0, 2),
            old.min,
            old.max
        ),
    )
}

// ---------------------------------------------------------------- chapter 4

fn fig4_2(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let c = r.tracking()[0].clone();
    let pts: Vec<_> = c.trace.iter().map(|s| (s.time, s.desired)).collect();
    let peak = pts.iter().map(|p| p.1).fold(0.0, f64::max);
    figure(
        &dir,
        "fig4_2_desired.svg",
        "Fig. 4.2: desired trajectory, active mode",
        Chart {
            title: "Fig. 4.2  desired link trajectory",
            x: "time (s)",
            y: "q_l^d (rad)",
            series: vec![line("q_l^d = 0.25 (1 − cos 2πt/4 s)", BLUE_, pts)],
            markers: vec![],
        },
        "a smooth periodic link trajectory".into(),
        format!("raised cosine, 4 s period, peak {peak:.2} rad"),
    )
}

/// Three runs laid end to end, labelled A, B, C.
fn abc<T>(
    runs: &[T],
    duration: impl Fn(&T) -> f64,
    labels: &[&str],
) -> (Vec<f64>, Vec<(f64, String)>) {
    let mut offsets = Vec::new();
    let mut markers = Vec::new();
    let mut t0 = 0.0;
    for (run, label) in runs.iter().zip(labels.iter().copied()) {
        offsets.push(t0);
        markers.push((t0, label.to_string()));
        t0 += duration(run);
    }
    (offsets, markers)
}

fn fig4_3(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.tracking().to_vec();
    let all = r.arm_tracking()?.to_vec();
    let family = r.arm_family()?.to_vec();
    let (runs, on_mrr) = all.split_at(3.min(all.len()));
    let first = family.first().ok_or("no family run")?;
    let (off, markers) = abc(
        &first.tracking,
        |x| x.time.last().map_or(0.0, |t| t + ARM_TICK),
        &["A: no JTF", "B: JTF, sensor", "C: JTF, estimate"],
    );
    let member_pts = |f: &ArmFamilyRuns| -> Vec<(f64, f64)> {
        f.tracking
            .iter()
            .zip(&off)
            .flat_map(|(x, o)| {
                x.time
                    .iter()
                    .zip(&x.link_error)
                    .map(move |(t, e)| (o + t, e * 1e3))
            })
            .collect()
    };
    let mut series: Vec<_> = family
        .iter()
        .zip([BLUE_, ORANGE, GREEN_])
        .map(|(f, c)| {
            line(
                &format!("engine arm, member {} seed {}", f.member, f.seed),
                c,
                member_pts(f),
            )
        })
        .collect();
    let home_pts: Vec<_> = home
        .iter()
        .zip(&off)
        .flat_map(|(x, o)| {
            x.trace
                .iter()
                .map(move |s| (o + s.time, s.link_error * 1e3))
        })
        .collect();
    let rms = |v: Vec<f64>| {
        v.iter()
            .zip(["A", "B", "C"])
            .map(|(x, l)| format!("{l} {:.2}", x * 1e3))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let over = |k: usize, f: &dyn Fn(&ArmTrackingRun) -> f64| -> String {
        let v: Vec<f64> = family
            .iter()
            .filter_map(|m| m.tracking.get(k))
            .map(f)
            .collect();
        spread(&v, 1e3, 2)
    };
    let abc_over = |f: &dyn Fn(&ArmTrackingRun) -> f64| {
        ["A", "B", "C"]
            .iter()
            .enumerate()
            .map(|(k, l)| format!("{l} {}", over(k, f)))
            .collect::<Vec<_>>()
            .join("; ")
    };
    let ours = abc_over(&|x| x.rms_error[0]);
    let max = abc_over(&|x| x.max_error[0]);
    let plant_rms = rms(runs.iter().map(|x| x.rms_error[0]).collect());
    let mrr_rms = rms(on_mrr.iter().map(|x| x.rms_error[0]).collect());
    let home_rms = rms(home.iter().map(|x| x.link_error.rms).collect());
    let settle = if r.opts.quick { 1.0 } else { 2.0 };
    figure(
        &dir,
        "fig4_3_tracking.svg",
        "Fig. 4.3: active mode, link position error A/B/C",
        Chart {
            title: "Fig. 4.3  link error on the engine arm, eq. (4.19), Table 4.1, T = 4 ms (f32)",
            x: "time (s), three runs end to end",
            y: "q_l − q_l^d (mrad)",
            series: {
                series.push(line("home-made single joint (comparison)", GREY, home_pts));
                series
            },
            markers,
        },
        "area A (no joint-torque feedback) has the largest error; with feedback from the \
         F/T sensor (B) or the estimate (C) it is smaller"
            .into(),
        format!(
            "{}; §4.4.1 joint 20° from the vertical with 2.4 kg at the link's end, the \
             crate's 4 ms preset (JointParams::table_4_1_at, gains redesigned for the tick); \
             A and B its active law fed 0 or the drive's true transmission torque (a \
             noiseless sensor), C the joint step on its estimate. Link error after {settle} s \
             (mrad): RMS {ours}; max {max}. Comparison, {PLANT_DRIVES}: RMS {plant_rms}; the \
             same loop on Mrr (eq. 4.1–4.6): RMS {mrr_rms}. Comparison, home-made single \
             joint (sim::closed_loop: Table 4.1's gains at 4 ms, f64 law, noisy F/T sensor): \
             RMS {home_rms}",
            arm_source(&family)
        ),
    )
}

/// The hand torque of an engine back-driving run, per tick.
fn hand_torque_series(run: &JointRun, offset: f64) -> Vec<(f64, f64)> {
    run.time
        .iter()
        .zip(&run.environment_torque)
        .map(|(t, h)| (offset + t, *h))
        .collect()
}

fn fig4_11(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.passive().to_vec();
    let runs = r.arm_back_driving()?.to_vec();
    let family = r.arm_family()?.to_vec();
    let first = family.first().ok_or("no family run")?;
    let (off, markers) = abc(
        &first.back_driving,
        |x| x.time.last().map_or(0.0, |t| t + ARM_TICK),
        &["A: no compensation", "B: eq. 4.32, estimate"],
    );
    let series: Vec<_> = family
        .iter()
        .zip([BLUE_, ORANGE, GREEN_])
        .map(|(f, c)| {
            let pts: Vec<_> = f
                .back_driving
                .iter()
                .zip(&off)
                .flat_map(|(x, o)| hand_torque_series(x, *o))
                .collect();
            line(
                &format!("hand torque, member {} seed {}", f.member, f.seed),
                c,
                pts,
            )
        })
        .collect();
    let over = |f: &dyn Fn(&[JointRun]) -> f64, scale: f64, digits: usize| {
        let v: Vec<f64> = family.iter().map(|m| f(&m.back_driving)).collect();
        spread(&v, scale, digits)
    };
    let home_rms = home
        .iter()
        .zip(["A", "B", "C"])
        .map(|(x, l)| format!("{l} {:.2}", x.hand_torque.rms))
        .collect::<Vec<_>>()
        .join(", ");
    figure(
        &dir,
        "fig4_11_passive.svg",
        "Fig. 4.11: passive mode, torque needed to back-drive",
        Chart {
            title: "Fig. 4.11  hand torque back-driving the engine arm's joint, eq. (4.32), T = 4 ms (f32)",
            x: "time (s), two runs end to end",
            y: "hand torque (N·m)",
            series,
            markers,
        },
        "back-driving without torque feedback (A) takes more torque than with eq. (4.32) on \
         the estimate (B) or the F/T sensor (C)"
            .into(),
        format!(
            "{}; hand 200 N·m/rad, 5 N·m·s/rad on q_h = 0.5 sin(2πt/4 s), RMS over 2–6 s \
             (N·m): A {}, B {} (reduction A − B {}; RMS N τ_m in B {}); B in Passive from {} s \
             (mode manager, entry 1 N·m). Comparison, {PLANT_DRIVES}: RMS A {:.3}, B {:.3} N·m. \
             Area C (F/T sensor) only in the comparison, home-made single joint \
             (sim::closed_loop, 6 s): RMS {home_rms}",
            arm_source(&family),
            over(&|x| x[0].env_rms, 1.0, 3),
            over(&|x| x[1].env_rms, 1.0, 3),
            over(&|x| x[0].env_rms - x[1].env_rms, 1.0, 3),
            over(&|x| x[1].reflected_motor_rms, 1.0, 3),
            over(
                &|x| x[1].switches.first().map_or(f64::NAN, |s| s.time),
                1.0,
                2
            ),
            runs[0].env_rms,
            runs[1].env_rms,
        ),
    )
}

fn fig4_12(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.passive().to_vec();
    let runs = r.arm_back_driving()?.to_vec();
    let family = r.arm_family()?.to_vec();
    let first = family.first().ok_or("no family run")?;
    let (off, markers) = abc(
        &first.back_driving,
        |x| x.time.last().map_or(0.0, |t| t + ARM_TICK),
        &["A", "B"],
    );
    let links: Vec<_> = family
        .iter()
        .zip([BLUE_, ORANGE, GREEN_])
        .map(|(f, c)| {
            let pts: Vec<_> = f
                .back_driving
                .iter()
                .zip(&off)
                .flat_map(|(x, o)| x.time.iter().zip(&x.link).map(move |(t, q)| (o + t, *q)))
                .collect();
            line(
                &format!("link q_l, member {} seed {}", f.member, f.seed),
                c,
                pts,
            )
        })
        .collect();
    let hand: Vec<_> = first
        .back_driving
        .iter()
        .zip(&off)
        .flat_map(|(x, o)| x.time.iter().map(move |t| (o + t, hand_path(*t).0)))
        .collect();
    let lag = |x: &JointRun| {
        let v: Vec<f64> = x
            .time
            .iter()
            .zip(&x.link)
            .filter(|(t, _)| **t >= 2.0)
            .map(|(t, q)| hand_path(*t).0 - q)
            .collect();
        (v.iter().map(|e| e * e).sum::<f64>() / v.len().max(1) as f64).sqrt()
    };
    let home_lag = home
        .iter()
        .zip(["A", "B", "C"])
        .map(|(x, l)| format!("{l} {:.1}", x.lag.rms * 1e3))
        .collect::<Vec<_>>()
        .join(", ");
    figure(
        &dir,
        "fig4_12_passive_position.svg",
        "Fig. 4.12: joint position in passive mode",
        Chart {
            title: "Fig. 4.12  engine arm's link angle while back-driven, T = 4 ms (f32)",
            x: "time (s), two runs end to end",
            y: "angle (rad)",
            series: {
                let mut v = vec![line("hand q_h", GREY, hand)];
                v.extend(links);
                v
            },
            markers,
        },
        "the joint follows the hand".into(),
        format!(
            "{}; link lag behind the hand over 2–6 s, RMS (mrad): A {}, B {}. Comparison, \
             {PLANT_DRIVES}: A {:.1}, B {:.1}; home-made single joint (sim::closed_loop): \
             {home_lag}",
            arm_source(&family),
            spread(
                &family
                    .iter()
                    .map(|f| lag(&f.back_driving[0]))
                    .collect::<Vec<_>>(),
                1e3,
                1
            ),
            spread(
                &family
                    .iter()
                    .map(|f| lag(&f.back_driving[1]))
                    .collect::<Vec<_>>(),
                1e3,
                1
            ),
            lag(&runs[0]) * 1e3,
            lag(&runs[1]) * 1e3
        ),
    )
}

/// Extension (not a thesis figure): a collision on the engine's contact,
/// detected on the estimated joint torque.
fn fig4_13_collision(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let c = r.arm_collision()?.clone();
    let family = r.arm_family()?.to_vec();
    let first = family.first().ok_or("no family run")?;
    let window = |x: &JointRun, f: &dyn Fn(&JointRun, usize) -> f64| -> Vec<(f64, f64)> {
        x.time
            .iter()
            .enumerate()
            .filter(|(_, t)| (1.5..=2.5).contains(*t))
            .map(|(i, t)| (*t, f(x, i)))
            .collect()
    };
    let contact = |x: &JointRun, i: usize| x.environment_torque[i];
    let estimate = |x: &JointRun, i: usize| -x.estimate[i];
    let mut markers = Vec::new();
    if let Some(t) = first.stop.contact {
        markers.push((t, "contact".to_string()));
    }
    if let Some(t) = first.stop.detection {
        markers.push((t, "detected".to_string()));
    }
    let latency = |x: &JointRun| match (x.contact, x.detection) {
        (Some(a), Some(b)) => format!("{:.1} ms", (b - a) * 1e3),
        _ => "none".into(),
    };
    let peak = |x: &JointRun| {
        x.environment_torque
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
    };
    let end = |x: &JointRun| x.environment_torque.last().copied().unwrap_or(f64::NAN);
    let delay = |x: &JointRun| match (x.contact, x.detection) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    };
    let over = |f: &dyn Fn(&ArmFamilyRuns) -> f64, scale: f64, digits: usize| {
        spread(&family.iter().map(f).collect::<Vec<_>>(), scale, digits)
    };
    let detected = |f: &dyn Fn(&ArmFamilyRuns) -> &JointRun| {
        family
            .iter()
            .filter(|m| f(m).detection.is_some() && f(m).contact.is_some())
            .count()
    };
    figure(
        &dir,
        "fig4_13_collision_contact.svg",
        "Extension: collision on an engine contact, detected on the estimated joint torque",
        Chart {
            title: "Collision on the engine's contact (crate extension), T = 4 ms (f32)",
            x: "time (s)",
            y: "torque on the link (N·m)",
            series: vec![
                line(
                    &format!(
                        "contact torque, Stop, member {} seed {}",
                        first.member, first.seed
                    ),
                    BLUE_,
                    window(&first.stop, &contact),
                ),
                line(
                    "contact torque, Passive",
                    ORANGE,
                    window(&first.passive, &contact),
                ),
                line(
                    "−τ̂_t (estimate), Stop",
                    GREEN_,
                    window(&first.stop, &estimate),
                ),
            ],
            markers,
        },
        "the thesis names collision detection on the estimated torque as a use (§1, ch. 7) \
         and switches modes by hand; this figure is the crate's extension (mode manager and \
         detector), not a thesis figure"
            .into(),
        format!(
            "{}; a 2 cm ball at the link's tip meets a fixed box at {WALL_ANGLE} rad (rapier \
             colliders, frictionless; the force is the engine's contact). Detector 3 N·m, \
             debounce 3 ticks. Stop: detected on {} of {} members, contact at {} s, detected \
             after {} ms, peak tick-mean contact torque {} N·m, {} N·m at 5 s. \
             Passive: detected on {} of {}, after {} ms, {} N·m at 5 s. \
             Comparison, {PLANT_DRIVES}: Stop detected after {}, Passive after {}; the spring \
             obstacle (300 N·m/rad, a torque the crate writes), Stop, on that plant: detected \
             after {} on the engine, {} on Mrr",
            arm_source(&family),
            detected(&|m| &m.stop),
            family.len(),
            over(&|m| m.stop.contact.unwrap_or(f64::NAN), 1.0, 4),
            over(&|m| delay(&m.stop), 1e3, 1),
            over(&|m| peak(&m.stop), 1.0, 2),
            over(&|m| end(&m.stop), 1.0, 2),
            detected(&|m| &m.passive),
            family.len(),
            over(&|m| delay(&m.passive), 1e3, 1),
            over(&|m| end(&m.passive), 1.0, 2),
            latency(&c.stop),
            latency(&c.passive),
            latency(&c.spring),
            latency(&c.spring_mrr)
        ),
    )
}

// ---------------------------------------------------------------- chapter 5

/// Grid of the workspace figures.
const GRID: usize = 41;

/// Reachable grid neighbours whose `θ1 + θ3` differ by more than 1 rad.
fn mapping_jumps(g: &[[WorkspaceSample; GRID]; GRID]) -> usize {
    let mut n = 0;
    for i in 0..GRID {
        for j in 0..GRID {
            let a = g[i][j];
            let next = [g.get(i + 1).map(|r| r[j]), g[i].get(j + 1).copied()];
            for b in next.into_iter().flatten() {
                if a.reachable
                    && b.reachable
                    && ((a.theta1 + a.theta3) - (b.theta1 + b.theta3)).abs() > 1.0
                {
                    n += 1;
                }
            }
        }
    }
    n
}

/// `(θ1, θ3)` of the reachable grid points, degrees.
fn mapping_points(g: &[[WorkspaceSample; GRID]; GRID]) -> Vec<(f64, f64)> {
    g.iter()
        .flatten()
        .filter(|s| s.reachable)
        .map(|s| (s.theta1.to_degrees(), s.theta3.to_degrees()))
        .collect()
}

fn fig5_7(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let p = WristParams::thesis();
    let g = workspace_mapping::<GRID>(&p, MappingRule::Principal);
    let jumps = mapping_jumps(&g);
    figure(
        &dir,
        "fig5_7_workspace.svg",
        "Fig. 5.7: workspace mapping, eq. (5.14) on principal branches",
        Chart {
            title: "Fig. 5.7  (θ1, θ3) of the reachable (δ, γ) grid, eq. (5.14)",
            x: "θ1 (deg)",
            y: "θ3 (deg)",
            series: vec![dots(
                &format!("{GRID}×{GRID} grid of δ, γ ∈ ±2φ, reachable points"),
                BLUE_,
                mapping_points(&g),
            )],
            markers: vec![],
        },
        "for continuous δ and γ the motor angles θ1, θ3 of eq. (5.14) can be discontinuous".into(),
        format!(
            "φ = {:.2}°: {jumps} pairs of reachable grid neighbours whose θ1 + θ3 jumps by \
             more than 1 rad",
            p.phi().to_degrees()
        ),
    )
}

fn fig5_8(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let p = WristParams::thesis();
    let printed = workspace_mapping::<GRID>(&p, MappingRule::PrintedFix);
    let lib = workspace_mapping::<GRID>(&p, MappingRule::Library);
    let (jp, jl) = (mapping_jumps(&printed), mapping_jumps(&lib));
    figure(
        &dir,
        "fig5_8_workspace_adjusted.svg",
        "Fig. 5.8: adjusted workspace mapping, eq. (5.15)",
        Chart {
            title: "Fig. 5.8  (θ1, θ3): printed fix (5.15) and the library's rule",
            x: "θ1 (deg)",
            y: "θ3 (deg)",
            series: vec![
                dots("eq. (5.15) as printed", ORANGE, mapping_points(&printed)),
                dots("library: θ1 + θ3 continuous", BLUE_, mapping_points(&lib)),
            ],
            markers: vec![],
        },
        "with θ3 shifted by 2π where θ1 + θ3 < −π/2, eq. (5.15), the mapping becomes continuous"
            .into(),
        format!(
            "jumps of θ1 + θ3 > 1 rad between reachable neighbours: {jp} with eq. (5.15) as \
             printed (errata E5.5), {jl} with the library's inverse kinematics"
        ),
    )
}

/// `(θ1 − θ3 in degrees, exact − approximate)` over the motor strip, for
/// `α` (wrapped, where `β > 0.05` rad) or `β`.
fn alpha_beta_errors(alpha: bool) -> (Vec<(f64, f64)>, f64) {
    let p = WristParams::thesis();
    let g = alpha_beta_comparison::<GRID>(&p);
    let mut pts = Vec::new();
    let mut worst = 0.0f64;
    for s in g.iter().flatten() {
        let e = if alpha {
            if s.beta_exact <= 0.05 {
                continue;
            }
            let d = s.alpha_exact - s.alpha_approx;
            d.sin().atan2(d.cos())
        } else {
            s.beta_exact - s.beta_approx
        };
        worst = worst.max(e.abs());
        pts.push(((s.theta1 - s.theta3).to_degrees(), e.to_degrees()));
    }
    (pts, worst)
}

fn fig5_10(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let (pts, worst) = alpha_beta_errors(true);
    figure(
        &dir,
        "fig5_10_alpha.svg",
        "Fig. 5.10: α exact (5.19) minus Ryew–Choi (5.21)",
        Chart {
            title: "Fig. 5.10  α exact − α approximate, motor strip θ1 + θ3 ∈ [−π, 0]",
            x: "θ1 − θ3 (deg)",
            y: "Δα (deg)",
            series: vec![dots("Δα where β > 0.05 rad", BLUE_, pts)],
            markers: vec![],
        },
        "the difference between eq. (5.19) and eq. (5.21) is less than 2 %".into(),
        format!(
            "max |Δα| = {:.3} rad = {:.1} % of π over the whole motor strip (bend up to 2φ), \
             with eq. (5.21) corrected (errata E5.7)",
            worst,
            100.0 * worst / std::f64::consts::PI
        ),
    )
}

fn fig5_11(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let (pts, worst) = alpha_beta_errors(false);
    let two_phi = 2.0 * WristParams::thesis().phi();
    figure(
        &dir,
        "fig5_11_beta.svg",
        "Fig. 5.11: β exact (5.17) minus Ryew–Choi (5.21)",
        Chart {
            title: "Fig. 5.11  β exact − β approximate, motor strip θ1 + θ3 ∈ [−π, 0]",
            x: "θ1 − θ3 (deg)",
            y: "Δβ (deg)",
            series: vec![dots("Δβ", BLUE_, pts)],
            markers: vec![],
        },
        "the difference between eq. (5.17) and eq. (5.21) is less than 2 %".into(),
        format!(
            "max |Δβ| = {:.4} rad = {:.1} % of the largest bend 2φ over the whole motor strip",
            worst,
            100.0 * worst / two_phi
        ),
    )
}

// ---------------------------------------------------------------- chapter 6

/// The task trajectory of §6.4.2 and its joint-space image through the
/// continuous inverse kinematics (eq. 5.14–5.15), sampled every 4 ms:
/// `(t, [δ_d, γ_d], [θ1, θ3], [θ̇1, θ̇3], |FK(θ) − x_d|)`, rates by central
/// differences over one period, angles in rad.
#[allow(clippy::type_complexity)]
fn wrist_joint_trajectory(quick: bool) -> Vec<(f64, [f64; 2], [f64; 2], [f64; 2], f64)> {
    let kin = WristConfig::<f64>::new(&WristParams::thesis());
    let at = |x: [f64; 2]| PitchYaw {
        delta: x[0],
        gamma: x[1],
    };
    let duration = if quick { 6.0 } else { 12.0 };
    let n = (duration / BENCH_PERIOD).round() as usize;
    let mut ik = IkState::new(kin.inverse(at(tracking_trajectory(0.0))).motors);
    let motors: Vec<[f64; 2]> = (0..=n + 1)
        .map(|k| {
            let m = kin
                .update(&mut ik, at(tracking_trajectory(k as f64 * BENCH_PERIOD)))
                .motors;
            [m.theta1, m.theta3]
        })
        .collect();
    (1..=n)
        .map(|k| {
            let t = k as f64 * BENCH_PERIOD;
            let x = tracking_trajectory(t);
            let q = motors[k];
            let rate = [0, 1].map(|i| (motors[k + 1][i] - motors[k - 1][i]) / (2.0 * BENCH_PERIOD));
            let back = kin
                .forward(mrr_control::wrist::MotorAngles {
                    theta1: q[0],
                    theta3: q[1],
                })
                .pose;
            let miss = (back.delta - x[0]).hypot(back.gamma - x[1]);
            (t, x, q, rate, miss)
        })
        .collect()
}

/// `(t, f(sample))` over the engine's tracking run.
fn tracking_series(
    run: &EngineTrackingRun,
    f: impl Fn(&(f64, [f64; 2], [f64; 2])) -> f64,
) -> Vec<(f64, f64)> {
    run.samples.iter().map(|s| (s.0, f(s))).collect()
}

fn fig6_7(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let run = r.engine_tracking()?;
    let peak = |i: usize| {
        run.samples
            .iter()
            .map(|s| s.1[i].abs())
            .fold(0.0, f64::max)
            .to_degrees()
    };
    figure(
        &dir,
        "fig6_7_wrist_task_trajectory.svg",
        "Fig. 6.7: desired task-space trajectory, active mode",
        Chart {
            title: "Fig. 6.7  desired δ_d, γ_d and reached δ, γ (engine, step 0.25 ms)",
            x: "time (s)",
            y: "angle (deg)",
            series: vec![
                line("δ_d", BLUE_, tracking_series(run, |s| s.1[0].to_degrees())),
                line("γ_d", ORANGE, tracking_series(run, |s| s.1[1].to_degrees())),
                line(
                    "δ (engine)",
                    GREEN_,
                    tracking_series(run, |s| s.2[0].to_degrees()),
                ),
                line(
                    "γ (engine)",
                    RED_,
                    tracking_series(run, |s| s.2[1].to_degrees()),
                ),
            ],
            markers: vec![],
        },
        "a pitch-and-yaw trajectory for the active mode (shown as a plot only, no number \
         given)"
            .into(),
        format!(
            "{}; the thesis's trajectory is not given in numbers; this one \
             (sim::wrist_bench::tracking_trajectory) bends the output 12–24° and swings it from \
             pitch through yaw: peak |δ_d| {:.1}°, |γ_d| {:.1}°; the mechanism's universal joint \
             follows it within {:.3}° (δ), {:.3}° (γ) after 1 s",
            engine_source(),
            peak(0),
            peak(1),
            run.max_error[0].to_degrees(),
            run.max_error[1].to_degrees()
        ),
    )
}

fn fig6_8(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let tr = wrist_joint_trajectory(r.opts.quick);
    let range = |i: usize| {
        let (lo, hi) = tr.iter().fold((f64::MAX, f64::MIN), |(l, h), p| {
            (l.min(p.2[i]), h.max(p.2[i]))
        });
        (lo.to_degrees(), hi.to_degrees())
    };
    let miss = tr.iter().map(|p| p.4).fold(0.0, f64::max);
    let jump = tr
        .windows(2)
        .map(|w| {
            (w[1].2[0] - w[0].2[0])
                .abs()
                .max((w[1].2[1] - w[0].2[1]).abs())
        })
        .fold(0.0, f64::max);
    let (a, b) = (range(0), range(1));
    figure(
        &dir,
        "fig6_8_wrist_joint_trajectory.svg",
        "Fig. 6.8: joint-space trajectory from the inverse kinematics",
        Chart {
            title: "Fig. 6.8  motor angles θ1, θ3 of Fig. 6.7, eq. (5.14)–(5.15)",
            x: "time (s)",
            y: "angle (deg)",
            series: vec![
                line(
                    "θ1",
                    BLUE_,
                    tr.iter().map(|p| (p.0, p.2[0].to_degrees())).collect(),
                ),
                line(
                    "θ3",
                    ORANGE,
                    tr.iter().map(|p| (p.0, p.2[1].to_degrees())).collect(),
                ),
            ],
            markers: vec![],
        },
        "the joint trajectory the inverse kinematics derives from Fig. 6.7 (no number given)"
            .into(),
        format!(
            "no plant: the library's inverse kinematics (f64) of the desired trajectory of \
             Fig. 6.7 (the engine run does not return its motor references); θ1 over {:.1}…{:.1}°, θ3 over {:.1}…{:.1}°; largest change between 4 ms \
             samples {:.2}° (no branch jump); the forward kinematics of each sample returns \
             the task point within {:.1e} rad",
            a.0,
            a.1,
            b.0,
            b.1,
            jump.to_degrees(),
            miss
        ),
    )
}

fn fig6_9(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let tr = wrist_joint_trajectory(r.opts.quick);
    let peak = |i: usize| {
        tr.iter()
            .map(|p| p.3[i].abs())
            .fold(0.0, f64::max)
            .to_degrees()
    };
    figure(
        &dir,
        "fig6_9_wrist_joint_velocity.svg",
        "Fig. 6.9: joint-space velocities",
        Chart {
            title: "Fig. 6.9  motor rates θ̇1, θ̇3 (central differences over 4 ms)",
            x: "time (s)",
            y: "rate (deg/s)",
            series: vec![
                line(
                    "θ̇1",
                    BLUE_,
                    tr.iter().map(|p| (p.0, p.3[0].to_degrees())).collect(),
                ),
                line(
                    "θ̇3",
                    ORANGE,
                    tr.iter().map(|p| (p.0, p.3[1].to_degrees())).collect(),
                ),
            ],
            markers: vec![],
        },
        "the joint velocities from the differential kinematics (no number given)".into(),
        format!(
            "no plant: central differences of the library's inverse kinematics (f64) of the \
             desired trajectory of Fig. 6.7; peak |θ̇1| {:.1}°/s, |θ̇3| {:.1}°/s",
            peak(0),
            peak(1)
        ),
    )
}

fn fig6_10(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.wrist_tracking().clone();
    let home_max = |i: usize| max_abs(&home.position_error[i]).to_degrees();
    let run = r.engine_tracking()?;
    figure(
        &dir,
        "fig6_10_wrist_position_error.svg",
        "Fig. 6.10: wrist position tracking errors, active mode",
        Chart {
            title: "Fig. 6.10  task-space position error on the engine, T = 4 ms (f32)",
            x: "time (s)",
            y: "error (deg)",
            series: vec![
                line(
                    "δ − δ_d",
                    BLUE_,
                    tracking_series(run, |s| (s.2[0] - s.1[0]).to_degrees()),
                ),
                line(
                    "γ − γ_d",
                    ORANGE,
                    tracking_series(run, |s| (s.2[1] - s.1[1]).to_degrees()),
                ),
            ],
            markers: vec![],
        },
        "the active-mode law makes the wrist follow the desired pitch and yaw (errors shown, \
         no number given)"
            .into(),
        format!(
            "{}; after 1 s max |error| δ {:.3}°, γ {:.3}° (RMS {:.3}°, {:.3}°), loop-closure \
             error ≤ {:.1e} rad, {} ticks out of Active. Comparison, home-made bench \
             (sim::wrist_bench, library kinematics): max |error| δ {:.3}°, γ {:.3}°",
            engine_source(),
            run.max_error[0].to_degrees(),
            run.max_error[1].to_degrees(),
            run.rms_error[0].to_degrees(),
            run.rms_error[1].to_degrees(),
            run.loop_error,
            run.off_mode_ticks,
            home_max(0),
            home_max(1)
        ),
    )
}

/// Rates of the engine's tracking run by central differences of its 4 ms
/// samples: `(t, [δ̇ − δ̇_d, γ̇ − γ̇_d], [δ̇_d, γ̇_d])`, rad/s.
fn tracking_rate_errors(run: &EngineTrackingRun) -> Vec<(f64, [f64; 2], [f64; 2])> {
    run.samples
        .windows(3)
        .map(|w| {
            let h = w[2].0 - w[0].0;
            let rate = |i: usize| (w[2].2[i] - w[0].2[i]) / h;
            let desired = |i: usize| (w[2].1[i] - w[0].1[i]) / h;
            (
                w[1].0,
                [rate(0) - desired(0), rate(1) - desired(1)],
                [desired(0), desired(1)],
            )
        })
        .collect()
}

fn fig6_11(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.wrist_tracking().clone();
    let home_rms = |i: usize| home.velocity_error[i].rms.to_degrees();
    let run = r.engine_tracking()?;
    let rates = tracking_rate_errors(run);
    let after: Vec<&(f64, [f64; 2], [f64; 2])> = rates.iter().filter(|p| p.0 >= 1.0).collect();
    let rms = |i: usize| {
        let n = after.len().max(1) as f64;
        (after.iter().map(|p| p.1[i] * p.1[i]).sum::<f64>() / n)
            .sqrt()
            .to_degrees()
    };
    let peak = |i: usize| {
        rates
            .iter()
            .map(|p| p.2[i].abs())
            .fold(0.0, f64::max)
            .to_degrees()
    };
    figure(
        &dir,
        "fig6_11_wrist_velocity_error.svg",
        "Fig. 6.11: wrist velocity tracking errors, active mode",
        Chart {
            title: "Fig. 6.11  task-space velocity error on the engine (central differences, 4 ms)",
            x: "time (s)",
            y: "error (deg/s)",
            series: vec![
                line(
                    "δ̇ − δ̇_d",
                    BLUE_,
                    rates.iter().map(|p| (p.0, p.1[0].to_degrees())).collect(),
                ),
                line(
                    "γ̇ − γ̇_d",
                    ORANGE,
                    rates.iter().map(|p| (p.0, p.1[1].to_degrees())).collect(),
                ),
            ],
            markers: vec![],
        },
        "velocity tracking errors of the active mode (no number given)".into(),
        format!(
            "{}; rates by central differences of the engine's 4 ms poses (the run returns \
             poses only): RMS after 1 s δ̇ {:.3}°/s, γ̇ {:.3}°/s (peak desired rates {:.1} and \
             {:.1}°/s). Comparison, home-made bench (sim::wrist_bench, library kinematics, \
             true rates): RMS {:.3}°/s, {:.3}°/s",
            engine_source(),
            rms(0),
            rms(1),
            peak(0),
            peak(1),
            home_rms(0),
            home_rms(1)
        ),
    )
}

/// `(t, f(sample))` over an engine bench run.
fn bench_series(
    run: &EngineWristBenchRun,
    f: impl Fn(&EngineBenchSample) -> f64,
) -> Vec<(f64, f64)> {
    run.samples.iter().map(|s| (s.time, f(s))).collect()
}

/// The push the bench figures show, for their text.
fn nominal_push_text() -> String {
    let p = FingerPush::nominal(1);
    format!(
        "nominal push, seed 1 (pure pitch, {:.0}° at the tool over {:.1} s in Case 2, {:.0}° in \
         Case 1; gear break-away {:.0} N·m)",
        p.travel.to_degrees(),
        p.rise,
        CASE1_TRAVEL.to_degrees(),
        p.breakaway
    )
}

fn fig6_14(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.finger().to_vec();
    let b = r.engine_bench()?;
    let (off, on) = (&b.off, &b.on);
    figure(
        &dir,
        "fig6_14_passive_motion.svg",
        "Fig. 6.13–6.14: interactive motions, motors off (Case 1) and admittance (Case 2)",
        Chart {
            title: "Fig. 6.13–6.14  wrist pose while a finger pushes pitch (engine, 0.25 ms)",
            x: "time from the touch (s)",
            y: "angle (deg)",
            series: vec![
                line(
                    "δ, Case 2",
                    BLUE_,
                    bench_series(on, |s| s.pose[0].to_degrees()),
                ),
                line(
                    "γ, Case 2",
                    ORANGE,
                    bench_series(on, |s| s.pose[1].to_degrees()),
                ),
                line(
                    "δ, Case 1",
                    GREEN_,
                    bench_series(off, |s| s.pose[0].to_degrees()),
                ),
                line(
                    "γ, Case 1",
                    RED_,
                    bench_series(off, |s| s.pose[1].to_degrees()),
                ),
            ],
            markers: vec![],
        },
        "Case 1: the wrist does not move; Case 2: it moves freely with a small finger force".into(),
        format!(
            "{}; {}: wrist travel Case 1 {:.3}° (rotor slip {:.1e} rad), Case 2 {:.2}°. \
             Comparison, home-made bench (sim::wrist_bench, library kinematics, pitch then \
             yaw, {:.0}° per push): travel of δ, γ Case 1 {:.2}°, {:.2}°; Case 2 {:.1}°, {:.1}°",
            engine_source(),
            nominal_push_text(),
            off.travel.to_degrees(),
            off.slip,
            on.travel.to_degrees(),
            FINGER_TRAVEL.to_degrees(),
            home[0].travel[0].to_degrees(),
            home[0].travel[1].to_degrees(),
            home[1].travel[0].to_degrees(),
            home[1].travel[1].to_degrees()
        ),
    )
}

/// The measured (F/T chain) and true (engine) torques of a bench run.
fn engine_finger_torques(run: &EngineWristBenchRun, title: &'static str) -> Chart<'static> {
    Chart {
        title,
        x: "time from the touch (s)",
        y: "torque (N·m)",
        series: vec![
            line("τ_δ measured", BLUE_, bench_series(run, |s| s.measured[0])),
            line("τ_γ measured", ORANGE, bench_series(run, |s| s.measured[1])),
            line(
                "τ_δ true (engine)",
                GREEN_,
                bench_series(run, |s| s.interaction[0]),
            ),
            line(
                "τ_γ true (engine)",
                RED_,
                bench_series(run, |s| s.interaction[1]),
            ),
        ],
        markers: vec![],
    }
}

fn fig6_15(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.finger()[0].clone();
    let b = r.engine_bench()?;
    let run = &b.off;
    figure(
        &dir,
        "fig6_15_internal_case1.svg",
        "Fig. 6.15: internal torques, motors off (Case 1)",
        engine_finger_torques(
            run,
            "Fig. 6.15  interaction torques, motors off (Case 1), engine",
        ),
        "more than 10 N·m of pitch torque without the wrist moving".into(),
        format!(
            "{}; {}: held {:.2} N·m measured with no gear slipped (peak measured {:.2}, true \
             {:.2} N·m), wrist travel {:.3}°. {} (drawn pushes; 20 seeds: `{RERUN} \
             {CLAIMS_RERUN_BENCH}`). Comparison, home-made bench (sim::wrist_bench, library \
             kinematics, {:.0}° pitch push): peak |τ_δ| {:.2} N·m",
            engine_source(),
            nominal_push_text(),
            run.held,
            run.peak_measured,
            run.peak_interaction,
            run.travel.to_degrees(),
            verdict_text(&b.verdicts, "6.15-case1"),
            FINGER_TRAVEL.to_degrees(),
            home.peak_interaction[0]
        ),
    )
}

fn fig6_16(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.finger()[1].clone();
    let b = r.engine_bench()?;
    let run = &b.on;
    figure(
        &dir,
        "fig6_16_internal_case2.svg",
        "Fig. 6.16: internal torques, admittance-passive mode (Case 2)",
        engine_finger_torques(
            run,
            "Fig. 6.16  interaction torques, admittance K_c = 0.1 (Case 2), engine",
        ),
        "residual internal torques less than 2 N·m".into(),
        format!(
            "{}; {}: peak measured |(τ_δ, τ_γ)| {:.2} N·m (true {:.2}), wrist travel {:.2}°, \
             {} ticks out of Passive; the admittance moves the wrist at K_c τ, so a finger at \
             speed v meets v/K_c. {}; {} (drawn pushes; 20 seeds: `{RERUN} \
             {CLAIMS_RERUN_BENCH}`). Comparison, home-made bench (sim::wrist_bench, library \
             kinematics, {:.0}° pitch push): peak |τ_δ| {:.2} N·m",
            engine_source(),
            nominal_push_text(),
            run.peak_measured,
            run.peak_interaction,
            run.travel.to_degrees(),
            run.off_mode_ticks,
            verdict_text(&b.verdicts, "6.16-case2"),
            verdict_text(&b.verdicts, "6.16-reduction"),
            FINGER_TRAVEL.to_degrees(),
            home.peak_interaction[0]
        ),
    )
}

fn fig6_17(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.finger()[1].clone();
    let b = r.engine_bench()?;
    let run = &b.on;
    let peak = |i: usize| {
        run.samples
            .iter()
            .map(|s| s.motor_torque[i].abs())
            .fold(0.0, f64::max)
    };
    figure(
        &dir,
        "fig6_17_compensation.svg",
        "Fig. 6.17: compensation torques of the motors (Case 2)",
        Chart {
            title: "Fig. 6.17  motor torques in admittance-passive mode (engine)",
            x: "time from the touch (s)",
            y: "motor torque (N·m)",
            series: vec![
                line("τ_m1 (θ1)", BLUE_, bench_series(run, |s| s.motor_torque[0])),
                line(
                    "τ_m3 (θ3)",
                    ORANGE,
                    bench_series(run, |s| s.motor_torque[1]),
                ),
            ],
            markers: vec![],
        },
        "the motors generate the torques that compensate the friction (no number given)".into(),
        format!(
            "{}; {}: peak commanded |τ_m| {:.3} and {:.3} N·m (motor side). Comparison, \
             home-made bench (sim::wrist_bench, library kinematics): {:.3} and {:.3} N·m",
            engine_source(),
            nominal_push_text(),
            peak(0),
            peak(1),
            home.peak_motor_torque[0],
            home.peak_motor_torque[1]
        ),
    )
}

/// The measured `(door angle in deg, τ_i)` of a door run.
fn door_torque(run: &EngineDoorRun, i: usize) -> Vec<(f64, f64)> {
    run.samples
        .iter()
        .map(|s| (s.door.to_degrees(), s.measured[i]))
        .collect()
}

/// Over the seeds, per 1° bin of door angle: the largest measured
/// `max(|τ_δ|, |τ_γ|)` of each seed's run `kind` (0 passive, 1 heading
/// error, 2 held) in the bin, then `(bin centre in deg, median, min, max)`
/// over the seeds that reach the bin.
fn door_peak_band(
    runs: &[(DoorRunMetrics, [EngineDoorRun; 3])],
    kind: usize,
) -> Vec<(f64, f64, f64, f64)> {
    let mut bins: std::collections::BTreeMap<i64, Vec<f64>> = Default::default();
    for (_, three) in runs {
        let mut own: std::collections::BTreeMap<i64, f64> = Default::default();
        for s in &three[kind].samples {
            let v = s.measured[0].abs().max(s.measured[1].abs());
            if !(v.is_finite() && s.door.is_finite()) {
                continue;
            }
            let cell = own.entry(s.door.to_degrees().floor() as i64).or_insert(v);
            *cell = cell.max(v);
        }
        for (b, v) in own {
            bins.entry(b).or_default().push(v);
        }
    }
    bins.into_iter()
        .filter_map(|(b, v)| {
            let (median, lo, hi) = median_min_max(&v)?;
            Some((b as f64 + 0.5, median, lo, hi))
        })
        .collect()
}

fn fig6_19(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.door()[0].clone();
    let d = r.engine_door()?;
    let (m, three) = d.runs.first().ok_or("no door seed")?;
    let pts = |run: &EngineDoorRun, i: usize| -> Vec<(f64, f64)> {
        run.samples
            .iter()
            .map(|s| (s.door.to_degrees(), s.wrist[i].to_degrees()))
            .collect()
    };
    let angles: Vec<String> = d
        .runs
        .iter()
        .map(|(m, three)| {
            format!(
                "{:.1}° (grasp δ {:.1}°, door {:.1} kg)",
                m.door_angle[0].to_degrees(),
                m.start_pitch.to_degrees(),
                three[0].door.mass
            )
        })
        .collect();
    figure(
        &dir,
        "fig6_19_door_motion.svg",
        "Fig. 6.19: wrist motion during door opening",
        Chart {
            title: "Fig. 6.19  wrist pitch δ and yaw γ over the door angle (engine, seed 1)",
            x: "door angle (deg)",
            y: "wrist angle (deg)",
            series: vec![
                line("δ, passive", BLUE_, pts(&three[0], 0)),
                line("γ, passive", ORANGE, pts(&three[0], 1)),
                line("δ, 3° heading error", GREEN_, pts(&three[1], 0)),
                line("γ, 3° heading error", RED_, pts(&three[1], 1)),
            ],
            markers: vec![],
        },
        "the passive wrist moves with the door while the base jerks and slides (no number \
         given)"
            .into(),
        format!(
            "{}, base and turret on the engine too; seed {} shown: the passive run opened the \
             door to {:.1}°, wrist range |δ| {:.2}°, |γ| {:.2}°; final door angle of the passive \
             run over {}: {}. Comparison, home-made \
             integrator (sim::door, seed 7): door to {:.1}°, |δ| {:.2}°, |γ| {:.2}°",
            engine_source(),
            m.seed,
            three[0].door_angle.to_degrees(),
            three[0].wrist_range[0].to_degrees(),
            three[0].wrist_range[1].to_degrees(),
            seeds_text(d.runs.len()),
            angles.join(", "),
            home.door_angle.to_degrees(),
            home.wrist_range[0].to_degrees(),
            home.wrist_range[1].to_degrees()
        ),
    )
}

fn fig6_20(r: &mut Report) -> Result<Figure, Error> {
    let dir = r.opts.out.clone();
    let home = r.door().to_vec();
    let d = r.engine_door()?;
    let (m, three) = d.runs.first().ok_or("no door seed")?;
    let band = door_peak_band(&d.runs, 0);
    let n = d.runs.len();
    let peaks = |k: usize| -> String {
        d.runs
            .iter()
            .map(|(m, _)| {
                format!(
                    "{:.2}",
                    match k {
                        0 => m.nominal,
                        1 => m.heading,
                        _ => m.hold,
                    }
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let home_peak = |k: usize| home[k].peak_measured[0].max(home[k].peak_measured[1]);
    figure(
        &dir,
        "fig6_20_door_torques.svg",
        "Fig. 6.20: wrist–knob interaction torques during door opening",
        Chart {
            title:
                "Fig. 6.20  measured τ_δ, τ_γ over the door angle (engine, seed 1; band of seeds)",
            x: "door angle (deg)",
            y: "torque (N·m)",
            series: vec![
                line("τ_δ, passive, seed 1", BLUE_, door_torque(&three[0], 0)),
                line("τ_γ, passive, seed 1", ORANGE, door_torque(&three[0], 1)),
                line(
                    "τ_γ, 3° heading error, seed 1",
                    GREEN_,
                    door_torque(&three[1], 1),
                ),
                line(
                    &format!("passive max|τ| per 1°: median, {}", seeds_text(n)),
                    BLACK_,
                    band.iter().map(|p| (p.0, p.1)).collect(),
                ),
                line(
                    &format!("passive max|τ| per 1°: max, {}", seeds_text(n)),
                    GREY,
                    band.iter().map(|p| (p.0, p.3)).collect(),
                ),
            ],
            markers: vec![],
        },
        "internal torques below 2 N·m; a maximum of 3 N·m with a 3° initial heading error".into(),
        format!(
            "{}; peak measured max(|τ_δ|, |τ_γ|) over {} (N·m): passive {}; 3° \
             heading error {}; held active (contrast) {}. {}; {}; {} (20 seeds: `{RERUN} \
             {CLAIMS_RERUN_DOOR}`). Seed {} drawn: grasp at δ = {:.1}°. Comparison, home-made \
             integrator (sim::door, seed 7): passive {:.2}, heading {:.2}, held {:.2} N·m",
            engine_source(),
            seeds_text(n),
            peaks(0),
            peaks(1),
            peaks(2),
            verdict_text(&d.verdicts, "6.20-passive"),
            verdict_text(&d.verdicts, "6.20-heading"),
            verdict_text(&d.verdicts, "6.20-relief"),
            m.seed,
            m.start_pitch.to_degrees(),
            home_peak(0),
            home_peak(1),
            home_peak(2)
        ),
    )
}

// ---------------------------------------------------------------- index

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn index_html(chapters: &[(&str, Vec<Figure>)], quick: bool) -> String {
    let mut h = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n\
         <title>mrr-control: thesis figures</title>\n<style>\n\
         body{font-family:sans-serif;max-width:900px;margin:auto;padding:1em;color:#222}\n\
         figure{margin:2em 0;border-top:1px solid #ccc;padding-top:1em}\n\
         img{max-width:100%}\nfigcaption{font-size:0.95em}\n\
         .thesis{color:#555}\n</style>\n</head>\n<body>\n\
         <h1>H. Zhang (2013), ch. 2–6, regenerated by mrr-control</h1>\n",
    );
    let _ = writeln!(
        h,
        "<p>Every curve is computed by the library and its simulator \
         (<code>examples/thesis_report.rs</code>){}. \
         The thesis's figures are photographs of lab measurements; the line under each \
         figure compares what the thesis reports with what this run gets.</p>",
        if quick {
            ", in the shortened <code>--quick</code> mode"
        } else {
            ""
        }
    );
    h.push_str("<ul>\n");
    for (chapter, figs) in chapters {
        for f in figs {
            let _ = writeln!(
                h,
                "<li><a href=\"#{}\">{}</a> <small>({})</small></li>",
                escape(&f.file),
                escape(&f.title),
                escape(chapter)
            );
        }
    }
    h.push_str("</ul>\n");
    for (chapter, figs) in chapters {
        let _ = writeln!(h, "<h2>{}</h2>", escape(chapter));
        for f in figs {
            let _ = writeln!(
                h,
                "<figure id=\"{id}\">\n<a href=\"{id}\"><img src=\"{id}\" alt=\"{t}\"/></a>\n\
                 <figcaption><b>{t}.</b> <span class=\"thesis\">Thesis: {th}.</span> \
                 Here: {o}.</figcaption>\n</figure>",
                id = escape(&f.file),
                t = escape(&f.title),
                th = escape(&f.thesis),
                o = escape(&f.ours)
            );
        }
    }
    h.push_str("<h2>Not drawn</h2>\n<ul>\n");
    for (title, why) in NOT_DRAWN {
        let _ = writeln!(h, "<li><b>{}</b>: {}</li>", escape(title), escape(why));
    }
    h.push_str("</ul>\n</body>\n</html>\n");
    h
}

/// Text for a Markdown table cell (`|` escaped).
pub fn md_cell(s: &str) -> String {
    s.replace('|', "\\|")
}

/// The per-figure comparison as a Markdown table (for docs/reproduction.md).
fn summary_md(chapters: &[(&str, Vec<Figure>)], quick: bool) -> String {
    let mut m = format!(
        "| figure | thesis reports | this run ({}) |\n|---|---|---|\n",
        if quick { "--quick" } else { "full" }
    );
    for (_, figs) in chapters {
        for f in figs {
            let _ = writeln!(
                m,
                "| {} | {} | {} |",
                md_cell(&f.title),
                md_cell(&f.thesis),
                md_cell(&f.ours)
            );
        }
    }
    for (title, why) in NOT_DRAWN {
        let _ = writeln!(m, "| {} | — | {} |", md_cell(title), md_cell(why));
    }
    m
}

/// Render every figure of [`CHAPTERS`] and the index into `opts.out`;
/// returns the figures in order.
pub fn run(opts: &Options) -> Result<Vec<Figure>, Error> {
    run_chapters(opts, None)
}

/// [`run`] for the chapter numbered `only` (2–6) if given, else for all.
/// Errors: a chapter number outside 2–6, I/O or drawing.
pub fn run_chapters(opts: &Options, only: Option<usize>) -> Result<Vec<Figure>, Error> {
    if let Some(c) = only {
        if !(2..2 + CHAPTERS.len()).contains(&c) {
            return Err(format!(
                "--chapter {c}: the report has chapters 2 to {}",
                1 + CHAPTERS.len()
            )
            .into());
        }
    }
    std::fs::create_dir_all(&opts.out)?;
    let mut report = Report::new(opts.clone());
    let mut chapters = Vec::new();
    for (k, (name, figs)) in CHAPTERS.iter().enumerate() {
        if only.is_some_and(|c| c != k + 2) {
            continue;
        }
        let mut done = Vec::new();
        for f in figs.iter() {
            done.push(f(&mut report)?);
        }
        chapters.push((*name, done));
    }
    std::fs::write(
        opts.out.join("index.html"),
        index_html(&chapters, opts.quick),
    )?;
    std::fs::write(
        opts.out.join("summary.md"),
        summary_md(&chapters, opts.quick),
    )?;
    Ok(chapters.into_iter().flat_map(|(_, f)| f).collect())
}

#[allow(dead_code)]
fn main() -> Result<(), Error> {
    let mut args = std::env::args().skip(1);
    let mut opts = Options {
        quick: false,
        out: default_figures_dir(),
    };
    let mut only = None;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--quick" => opts.quick = true,
            "--out" => opts.out = PathBuf::from(args.next().ok_or("--out needs a directory")?),
            "--chapter" => {
                only = Some(
                    args.next()
                        .and_then(|c| c.parse::<usize>().ok())
                        .ok_or("--chapter needs a chapter number (2 to 6)")?,
                )
            }
            other => {
                return Err(
                    format!("unknown argument {other:?} (--quick, --out DIR, --chapter N)").into(),
                )
            }
        }
    }
    let start = std::time::Instant::now();
    let figures = run_chapters(&opts, only)?;
    for f in &figures {
        println!("{}\n  thesis: {}\n  here:   {}", f.title, f.thesis, f.ours);
    }
    println!(
        "\n{} figures in {:.1} s; open {}",
        figures.len(),
        start.elapsed().as_secs_f64(),
        opts.out.join("index.html").display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use mrr_control::sim::engine::door::{DoorBody, EngineDoorSample};

    fn door_sample(door_deg: f64, measured: [f64; 2]) -> EngineDoorSample {
        EngineDoorSample {
            time: 0.0,
            door: door_deg.to_radians(),
            turret: 0.0,
            wrist: [0.0; 2],
            reference: [0.0; 2],
            measured,
            interaction: measured,
            base: [0.0; 3],
            motors: [0.0; 2],
            motor_reference: [0.0; 2],
        }
    }

    fn door_run(samples: Vec<EngineDoorSample>) -> EngineDoorRun {
        EngineDoorRun {
            samples,
            peak_measured: [0.0; 2],
            peak_interaction: [0.0; 2],
            peak_force: 0.0,
            door_angle: 0.0,
            wrist_range: [0.0; 2],
            loop_error: 0.0,
            off_mode_ticks: 0,
            saturated_ticks: 0,
            door: DoorBody::nominal(),
        }
    }

    fn seed(seed: u64, passive: Vec<EngineDoorSample>) -> (DoorRunMetrics, [EngineDoorRun; 3]) {
        let m = DoorRunMetrics {
            seed,
            start_pitch: 0.1,
            nominal: 0.0,
            heading: 0.0,
            hold: 0.0,
            true_peaks: [0.0; 3],
            door_angle: [0.0; 3],
        };
        (
            m,
            [
                door_run(passive),
                door_run(vec![door_sample(0.5, [9.0, 9.0])]),
                door_run(vec![]),
            ],
        )
    }

    /// Per 1° bin, each seed contributes the largest `max(|τ_δ|, |τ_γ|)`
    /// of its own samples there; the band is the median, min and max of
    /// those (worked by hand below). Only the requested run counts.
    #[test]
    fn door_band_takes_each_seeds_bin_peak_then_median_and_range() {
        let runs = vec![
            // Seed 1: bin 0 peaks at |−3| = 3 (two samples), bin 1 at 1.
            seed(
                1,
                vec![
                    door_sample(0.2, [1.0, -3.0]),
                    door_sample(0.7, [2.0, 0.5]),
                    door_sample(1.5, [1.0, 0.0]),
                ],
            ),
            // Seed 2: bin 0 peaks at 5, no sample in bin 1.
            seed(2, vec![door_sample(0.9, [-5.0, 4.0])]),
            // Seed 3: bin 0 peaks at 1, bin 1 at 2.
            seed(
                3,
                vec![door_sample(0.1, [0.0, 1.0]), door_sample(1.2, [2.0, -1.0])],
            ),
        ];
        let band = door_peak_band(&runs, 0);
        assert_eq!(band.len(), 2);
        // Bin 0: seed peaks {3, 5, 1} -> median 3, min 1, max 5.
        assert_eq!(band[0], (0.5, 3.0, 1.0, 5.0));
        // Bin 1: seed peaks {1, 2} -> median 1.5, min 1, max 2.
        assert_eq!(band[1], (1.5, 1.5, 1.0, 2.0));
        // The heading-error run (kind 1) has its own samples only.
        assert_eq!(door_peak_band(&runs, 1), vec![(0.5, 9.0, 9.0, 9.0)]);
    }

    /// The rate errors by central differences are exact for quadratics:
    /// desired `(t², 3t)`, reached `(t² + 0.01 t, 3t − 0.02 t²)` give an
    /// error `(0.01, −0.04 t)` and desired rates `(2t, 3)`.
    #[test]
    fn tracking_rate_errors_are_central_differences() {
        let samples: Vec<(f64, [f64; 2], [f64; 2])> = (0..6)
            .map(|k| {
                let t = 0.004 * k as f64;
                (
                    t,
                    [t * t, 3.0 * t],
                    [t * t + 0.01 * t, 3.0 * t - 0.02 * t * t],
                )
            })
            .collect();
        let run = EngineTrackingRun {
            samples,
            max_error: [0.0; 2],
            rms_error: [0.0; 2],
            loop_error: 0.0,
            off_mode_ticks: 0,
        };
        let rates = tracking_rate_errors(&run);
        assert_eq!(rates.len(), 4);
        for (k, (t, err, desired)) in rates.iter().enumerate() {
            let expected_t = 0.004 * (k + 1) as f64;
            assert!((t - expected_t).abs() < 1e-15);
            assert!((err[0] - 0.01).abs() < 1e-9, "{err:?}");
            assert!((err[1] + 0.04 * expected_t).abs() < 1e-9, "{err:?}");
            assert!((desired[0] - 2.0 * expected_t).abs() < 1e-9, "{desired:?}");
            assert!((desired[1] - 3.0).abs() < 1e-9, "{desired:?}");
        }
    }

    /// A verdict's text names the claim, the verdict, the seeds and the
    /// median and range of the values it was judged on; an id not judged
    /// says so.
    #[test]
    fn verdict_text_reports_the_claims_spread() {
        let claims = door_claims().expect("door claims");
        let metrics: Vec<DoorRunMetrics> = [1.0, 1.5, 4.0]
            .iter()
            .enumerate()
            .map(|(i, &nominal)| DoorRunMetrics {
                seed: i as u64 + 1,
                start_pitch: 0.1,
                nominal,
                heading: 2.0,
                hold: 6.0,
                true_peaks: [0.0; 3],
                door_angle: [1.57; 3],
            })
            .collect();
        let verdicts = evaluate(
            &claims,
            &Runs {
                door: &metrics,
                ..Runs::default()
            },
        )
        .expect("verdicts");
        // 2 of 3 seeds at or below 2 N·m (67 % < 80 %), 1 of 3 at or above
        // 3 N·m (33 % < 50 %): undecided; median 1.5, range 1.0–4.0.
        assert_eq!(
            verdict_text(&verdicts, "6.20-passive"),
            "6.20-passive undecided over seeds 1–3: median 1.50 N·m (min 1.00, max 4.00)"
        );
        assert_eq!(
            verdict_text(&verdicts, "6.16-case2"),
            "6.16-case2: not judged"
        );
        assert_eq!(seeds_text(1), "seed 1");
    }
}
