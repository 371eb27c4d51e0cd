//! The door-opening claims of thesis §6.4.4 (Fig. 6.19–6.20), judged on the
//! engine scene [`crate::sim::engine::door`] (feature `engine`) at the
//! thesis's 4 ms with the library's steps on `f32`.
//!
//! The criteria below were fixed before the sweep was run. Each seed draws
//! its own base slip and jerk sequence (the processes of
//! [`crate::sim::door`]), its own door ([`DoorBody::draw`]: mass, hinge
//! friction, closer), its own F/T calibration error and noise, and the
//! wrist's pitch at the grasp, uniform in 5°–15°: the thesis grasps the
//! knob by hand and does not state the pose, and the library's
//! kinematics describe one assembly mode of the DAUJ, which meets the other
//! at the straight pose (see [`crate::sim::engine::door`]); a grasp at the
//! straight pose is a separate study ([`START_PITCH`]).
//!
//! The metric is the peak of the *measured* interaction torques, `max(|τ_δ|,
//! |τ_γ|)` as the library's F/T chain reads them (Fig. 6.20 plots the
//! sensor's reading), from the grasp to 1.5 s after the planned opening.

use super::{rule, Claim, ClaimError, Condition, Criterion, Metric};
use crate::error::ParamError;
#[cfg(feature = "engine")]
use crate::sim::door::{DoorConfig, DoorControl};
#[cfg(feature = "engine")]
use crate::sim::engine::door::{engine_door_opening, Backend, DoorBody, EngineDoorRun};
#[cfg(feature = "engine")]
use crate::sim::engine::wrist_bench::{engine_finger_push_on, FingerCase, FingerPush};
#[cfg(feature = "engine")]
use crate::sim::engine::EngineSettings;
#[cfg(feature = "engine")]
use crate::sim::SplitMix64;

/// The range of the wrist's pitch at the grasp the seeds draw from, rad
/// (5°–15°).
pub const START_PITCH: [f64; 2] = [0.087_266_462_599_716_48, 0.261_799_387_799_149_4];

/// The thesis's heading error of the second run, rad (3°).
pub const HEADING_ERROR: f64 = 0.052_359_877_559_829_89;

/// One seed's three runs (N·m unless noted).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoorRunMetrics {
    /// The seed.
    pub seed: u64,
    /// The wrist's pitch at the grasp, rad.
    pub start_pitch: f64,
    /// Passive, no heading error: peak measured `max(|τ_δ|, |τ_γ|)`.
    pub nominal: f64,
    /// The same with the 3° heading error.
    pub heading: f64,
    /// Turret and wrist held active (contrast).
    pub hold: f64,
    /// Peak true (engine) `max(|τ_δ|, |τ_γ|)` of the three runs.
    pub true_peaks: [f64; 3],
    /// Final door angle of the three runs, rad.
    pub door_angle: [f64; 3],
}

impl DoorRunMetrics {
    /// `nominal / hold` (dimensionless).
    pub fn relief(&self) -> f64 {
        self.nominal / self.hold
    }
}

/// The chapter-6 door claims, criteria fixed here before any run.
pub fn claims() -> Result<Vec<Claim>, ParamError> {
    use Condition::{AtLeast, AtMost};
    let c =
        |s: Condition, ss: f64, r: Condition, rs: f64| Criterion::try_new(rule(s, ss), rule(r, rs));
    Ok(vec![
        Claim {
            id: "6.20-passive",
            quote: "internal torques generated in the wrist can be limited to be less than 2 Nm",
            figure: "Fig. 6.20, §6.4.4",
            metric_name: "peak measured max(|τ_δ|, |τ_γ|), passive turret and wrist",
            unit: "N·m",
            metric: Metric::Door(|m| m.nominal),
            operating_point: "4 ms (f32)",
            criterion: c(AtMost(2.0), 0.8, AtLeast(3.0), 0.5)?,
            justification: "the thesis states a bound met by its run: at or below 2 N·m in 80 % \
                of the seeds (one in five may exceed it: the thesis shows one run) supports it; \
                3 N·m or more — what the thesis reports only for its perturbed run — in half of \
                them refutes it",
        },
        Claim {
            id: "6.20-heading",
            quote: "the torque measurements at the wrist reached a maximum of 3 Nm when a \
                    3-degree initial offset was introduced",
            figure: "§6.4.4 (not plotted)",
            metric_name: "peak measured max(|τ_δ|, |τ_γ|), passive, 3° initial heading error",
            unit: "N·m",
            metric: Metric::Door(|m| m.heading),
            operating_point: "4 ms (f32)",
            criterion: c(AtMost(3.5), 0.8, AtLeast(4.5), 0.5)?,
            justification: "'a maximum of 3 Nm' read to the thesis's whole newton-metre \
                (≤ 3.5) in 80 % of the seeds supports it; 1.5 times it (≥ 4.5 N·m), no longer \
                'of comparable magnitude' to the nominal run, in half of them refutes it",
        },
        Claim {
            id: "6.20-relief",
            quote: "the developed compact wrist and the proposed multiple mode control \
                    algorithm ... have been verified to be able to relieve the potential \
                    internal forces effectively",
            figure: "§6.4.4",
            metric_name: "peak measured torque passive / held active (same seed, same door)",
            unit: "",
            metric: Metric::Door(DoorRunMetrics::relief),
            operating_point: "4 ms (f32)",
            criterion: c(AtMost(2.0 / 3.0), 0.8, AtLeast(1.0), 0.5)?,
            justification: "'effectively': the passive peak at most two thirds of the held \
                one in 80 % of the seeds supports it; no relief (a ratio of 1 or more) in half \
                of them refutes it",
        },
    ])
}

/// The three runs of one seed on the engine: the thesis's scene
/// ([`DoorConfig::thesis`]) with the seed's door and start pitch, and the
/// runs themselves (for figures). `start_pitch` overrides the drawn pitch
/// (rad; the straight-pose study passes 0).
#[cfg(feature = "engine")]
pub fn door_seed(
    seed: u64,
    start_pitch: Option<f64>,
    engine: &EngineSettings,
) -> Result<(DoorRunMetrics, [EngineDoorRun; 3]), ParamError> {
    let mut rng = SplitMix64::new(seed ^ 0x57A2_7000_0000_0006);
    let drawn = START_PITCH[0] + (START_PITCH[1] - START_PITCH[0]) * rng.uniform();
    let pitch = start_pitch.unwrap_or(drawn);
    let door = DoorBody::draw(seed);
    let run = |control, heading| {
        engine_door_opening(
            &DoorConfig::thesis(control, heading, seed),
            &door,
            pitch,
            engine,
            Backend::F32,
        )
    };
    let nominal = run(DoorControl::Passive, 0.0)?;
    let heading = run(DoorControl::Passive, HEADING_ERROR)?;
    let hold = run(DoorControl::ActiveHold, 0.0)?;
    let m = DoorRunMetrics {
        seed,
        start_pitch: pitch,
        nominal: nominal.peak(),
        heading: heading.peak(),
        hold: hold.peak(),
        true_peaks: [nominal.peak_true(), heading.peak_true(), hold.peak_true()],
        door_angle: [nominal.door_angle, heading.door_angle, hold.door_angle],
    };
    Ok((m, [nominal, heading, hold]))
}

/// [`door_seed`] for seeds `1..=seeds` on `threads` threads (at least
/// one), in seed order.
#[cfg(feature = "engine")]
pub fn run_door(
    seeds: u64,
    start_pitch: Option<f64>,
    engine: &EngineSettings,
    threads: usize,
) -> Result<Vec<(DoorRunMetrics, [EngineDoorRun; 3])>, ClaimError> {
    par_seeds(seeds, threads, |s| door_seed(s, start_pitch, engine))
}

/// `f` on seeds `1..=seeds`, spread over `threads` threads (at least one),
/// in seed order. Errors: no seeds, the first error of `f`.
#[cfg(feature = "engine")]
fn par_seeds<T: Send>(
    seeds: u64,
    threads: usize,
    f: impl Fn(u64) -> Result<T, ParamError> + Sync,
) -> Result<Vec<T>, ClaimError> {
    if seeds == 0 {
        return Err(ClaimError::NoRuns { name: "seeds" });
    }
    let threads = threads.clamp(1, usize::try_from(seeds).unwrap_or(usize::MAX));
    let f = &f;
    let results: Vec<Result<Vec<(u64, T)>, ParamError>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                scope.spawn(move || {
                    (1..=seeds)
                        .filter(|s| (s - 1) % threads as u64 == t as u64)
                        .map(|s| f(s).map(|v| (s, v)))
                        .collect::<Result<Vec<_>, _>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| {
                h.join().unwrap_or(Err(ParamError::NotFinite {
                    name: "seed run thread",
                    value: f64::NAN,
                }))
            })
            .collect()
    });
    let mut all = Vec::new();
    for r in results {
        all.extend(r?);
    }
    all.sort_by_key(|(s, _)| *s);
    Ok(all.into_iter().map(|(_, v)| v).collect())
}

/// One seed of the wrist bench of §6.4.3 (N·m unless noted): the push
/// drawn by [`FingerPush::draw`] (feature `engine`), run in both cases.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristBenchMetrics {
    /// The seed.
    pub seed: u64,
    /// Direction of the push, rad (0: pitch).
    pub direction: f64,
    /// The fingertip's peak speed at the tool, rad/s.
    pub finger_speed: f64,
    /// The gear break-away drawn, N·m at the joint.
    pub breakaway: f64,
    /// Case 1: the largest measured `|(τ_δ, τ_γ)|` with both gears still
    /// holding (no rotor slipped).
    pub case1_held: f64,
    /// Case 1: the pose's largest distance from its start, rad.
    pub case1_travel: f64,
    /// Case 2: the peak measured `|(τ_δ, τ_γ)|`.
    pub case2_peak: f64,
    /// Case 2: the pose's largest distance from its start, rad.
    pub case2_travel: f64,
    /// Case 2: the fingertip's travel at the tool, rad.
    pub finger_travel: f64,
}

impl WristBenchMetrics {
    /// Case 2's peak over Case 1's held torque (dimensionless).
    pub fn reduction(&self) -> f64 {
        self.case2_peak / self.case1_held
    }
}

/// The wrist-bench claims of §6.4.3, criteria fixed here before any seed
/// sweep was run (see [`crate::sim::engine::wrist_bench`] for the bench and
/// the assumptions: the gear friction is taken from Case 1 itself).
pub fn bench_claims() -> Result<Vec<Claim>, ParamError> {
    use Condition::{AtLeast, AtMost};
    let c =
        |s: Condition, ss: f64, r: Condition, rs: f64| Criterion::try_new(rule(s, ss), rule(r, rs));
    Ok(vec![
        Claim {
            id: "6.15-case1",
            quote: "the wrist does not move even when more than 10Nm pitch torque is generated \
                    at the force/torque sensor mounting point",
            figure: "Fig. 6.13, 6.15, §6.4.3",
            metric_name: "Case 1 (motors off): largest measured |(τ_δ, τ_γ)| with no gear slipped",
            unit: "N·m",
            metric: Metric::WristBench(|m| m.case1_held),
            operating_point: "4 ms (f32 F/T chain), motors off",
            criterion: c(AtLeast(10.0), 0.8, AtMost(8.0), 0.5)?,
            justification: "the thesis's bound held in 80 % of the seeds supports it; a hold \
                below 8 N·m (a fifth under it) in half of them refutes it. The gear \
                break-away is an assumption drawn near 12 N·m per joint (no other source): \
                the verdict is on the mechanism's mapping of the finger's push onto the two \
                gears, given that friction",
        },
        Claim {
            id: "6.16-case2",
            quote: "The residual internal torques are less than 2Nm",
            figure: "Fig. 6.16, §6.4.3",
            metric_name: "Case 2 (admittance-passive, K_c = 0.1): peak measured |(τ_δ, τ_γ)|",
            unit: "N·m",
            metric: Metric::WristBench(|m| m.case2_peak),
            operating_point: "4 ms (f32)",
            criterion: c(AtMost(2.0), 0.8, AtLeast(3.0), 0.5)?,
            justification: "as the door claim 6.20-passive: at or below 2 N·m in 80 % of the \
                seeds supports it, 3 N·m or more in half of them refutes it. The finger's speed \
                is drawn (0.10–0.29 rad/s at the tool); the admittance law follows a finger \
                at ẋ_f with τ ≈ ẋ_f / K_c",
        },
        Claim {
            id: "6.16-reduction",
            quote: "which have been reduced dramatically compared to the case without control",
            figure: "Fig. 6.15–6.16, §6.4.3",
            metric_name: "Case 2 peak / Case 1 held torque (same seed)",
            unit: "",
            metric: Metric::WristBench(WristBenchMetrics::reduction),
            operating_point: "4 ms (f32)",
            criterion: c(AtMost(0.25), 0.8, AtLeast(0.5), 0.5)?,
            justification: "'dramatically': at most a quarter in 80 % of the seeds supports it; \
                half or more in half of them refutes it",
        },
    ])
}

/// Both cases of one seed on the engine ([`FingerPush::draw`]`(seed)`),
/// the wrist step on `f32` (the claims' operating point).
#[cfg(feature = "engine")]
pub fn bench_seed(seed: u64, engine: &EngineSettings) -> Result<WristBenchMetrics, ParamError> {
    bench_seed_on(seed, engine, Backend::F32)
}

/// [`bench_seed`] with the wrist step on `backend`.
#[cfg(feature = "engine")]
pub fn bench_seed_on(
    seed: u64,
    engine: &EngineSettings,
    backend: Backend,
) -> Result<WristBenchMetrics, ParamError> {
    let push = FingerPush::draw(seed);
    let off = engine_finger_push_on(FingerCase::MotorsOff, &push, engine, backend)?;
    let on = engine_finger_push_on(FingerCase::Admittance, &push, engine, backend)?;
    Ok(WristBenchMetrics {
        seed,
        direction: push.direction,
        finger_speed: push.peak_speed(),
        breakaway: push.breakaway,
        case1_held: off.held,
        case1_travel: off.travel,
        case2_peak: on.peak_measured,
        case2_travel: on.travel,
        finger_travel: push.travel,
    })
}

/// [`bench_seed`] for seeds `1..=seeds` on `threads` threads (at least
/// one), in seed order: the runs the bench claims are judged on (`f32`).
#[cfg(feature = "engine")]
pub fn run_bench(
    seeds: u64,
    engine: &EngineSettings,
    threads: usize,
) -> Result<Vec<WristBenchMetrics>, ClaimError> {
    run_bench_on(seeds, engine, threads, Backend::F32)
}

/// [`run_bench`] with the wrist step on `backend` (another backend than
/// `f32` is a study beside the claims' operating point).
#[cfg(feature = "engine")]
pub fn run_bench_on(
    seeds: u64,
    engine: &EngineSettings,
    threads: usize,
    backend: Backend,
) -> Result<Vec<WristBenchMetrics>, ClaimError> {
    par_seeds(seeds, threads, |s| bench_seed_on(s, engine, backend))
}

#[cfg(test)]
mod tests {
    use super::super::{evaluate, Runs};
    use super::*;

    fn door(runs: &[DoorRunMetrics]) -> Runs<'_> {
        Runs {
            door: runs,
            ..Runs::default()
        }
    }

    fn benches(runs: &[WristBenchMetrics]) -> Runs<'_> {
        Runs {
            bench: runs,
            ..Runs::default()
        }
    }

    fn metrics(nominal: f64, heading: f64, hold: f64) -> DoorRunMetrics {
        DoorRunMetrics {
            seed: 1,
            start_pitch: 0.1,
            nominal,
            heading,
            hold,
            true_peaks: [nominal, heading, hold],
            door_angle: [1.57; 3],
        }
    }

    /// The verdicts follow the criteria written above: 1.5 N·m in every
    /// seed supports the 2 N·m bound, 3.5 refutes it, one seed in two at
    /// 2.5 leaves it undecided; the relief is the ratio passive/held.
    #[test]
    fn verdicts_follow_the_criteria() {
        use super::super::Verdict::{Refuted, Supported, Undecided};
        let c = claims().unwrap();
        let judge = |runs: &[DoorRunMetrics]| -> Vec<_> {
            evaluate(&c, &door(runs))
                .unwrap()
                .iter()
                .map(|r| r.verdict)
                .collect()
        };
        assert_eq!(judge(&[metrics(1.5, 2.9, 6.0); 5]), [Supported; 3]);
        assert_eq!(
            judge(&[metrics(3.5, 5.0, 3.5); 5]),
            [Refuted, Refuted, Refuted]
        );
        let mixed = [metrics(1.5, 3.0, 2.0), metrics(2.5, 4.0, 3.0)];
        // 1.5/2.0 = 0.75 and 2.5/3.0 = 0.83: neither a relief nor none.
        assert_eq!(judge(&mixed), [Undecided; 3]);
        let r = evaluate(&c, &door(&mixed)).unwrap();
        assert!((r[0].spread.median - 2.0).abs() < 1e-12);
        assert!((r[2].spread.max - 2.5 / 3.0).abs() < 1e-12);
    }

    fn bench(held: f64, peak: f64) -> WristBenchMetrics {
        WristBenchMetrics {
            seed: 1,
            direction: 0.0,
            finger_speed: 0.2,
            breakaway: 12.0,
            case1_held: held,
            case1_travel: 0.01,
            case2_peak: peak,
            case2_travel: 0.2,
            finger_travel: 0.2,
        }
    }

    /// The bench verdicts follow the criteria: a 12 N·m hold and a 1.5 N·m
    /// passive peak support all three; 7 and 3.5 N·m (a ratio of 0.5)
    /// refute them; a door metric is not a bench metric.
    #[test]
    fn bench_verdicts_follow_the_criteria() {
        use super::super::Verdict::{Refuted, Supported, Undecided};
        let c = bench_claims().unwrap();
        let judge = |runs: &[WristBenchMetrics]| -> Vec<_> {
            evaluate(&c, &benches(runs))
                .unwrap()
                .iter()
                .map(|r| r.verdict)
                .collect()
        };
        assert_eq!(judge(&[bench(12.0, 1.5); 5]), [Supported; 3]);
        assert_eq!(judge(&[bench(7.0, 3.5); 5]), [Refuted; 3]);
        assert_eq!(judge(&[bench(9.0, 2.5); 5]), [Undecided; 3]);
        let door_claims = claims().unwrap();
        assert!(matches!(
            evaluate(&door_claims, &benches(&[bench(12.0, 1.5)])),
            Err(ClaimError::NoMetrics)
        ));
    }

    #[test]
    fn evaluate_rejects_what_it_cannot_judge() {
        let c = claims().unwrap();
        assert!(matches!(
            evaluate(&c, &door(&[])),
            Err(ClaimError::NoMetrics)
        ));
        assert!(matches!(
            evaluate(&c, &door(&[metrics(f64::NAN, 1.0, 1.0)])),
            Err(ClaimError::NotFinite { run: 0, .. })
        ));
        let other = super::super::ch34::claims().unwrap();
        assert!(matches!(
            evaluate(&other[..1], &door(&[metrics(1.0, 1.0, 1.0)])),
            Err(ClaimError::NoMetrics)
        ));
    }
}
