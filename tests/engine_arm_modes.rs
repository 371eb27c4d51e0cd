//! The other chapter-4 experiments with the library's joint in the loop,
//! on the arm built from bodies on the rapier3d engine
//! (`sim::engine::EngineArm`) and, for comparison, on the thesis's own
//! model (`sim::Mrr`): passive back-driving (§4.3, eq. 4.32/4.33, §4.4.2,
//! Fig. 4.11–4.12), the mode manager switching Active → Passive → Active
//! on the interaction torque, and a collision with an obstacle detected on
//! the estimated joint torque (the use of the estimate the thesis names in
//! §1 and ch. 7; the manager and detector are this crate's extension, the
//! thesis switches modes by hand).
//!
//! # Set-up (all three experiments)
//! The thesis joint ([`ModuleParams::thesis_joint`]: vertical axis, so no
//! gravity torque; its 0.64 kg, 0.45 m link only; rotor 1.14e-5 kg·m²,
//! `N = 100`, Table 4.1), with the full drive plant (SHD-17-100 backbone,
//! Maxwell slip, Table 3.2 kinematic error) and the plant's link friction
//! (`f_c = 0.6`, `f_s = 0.2 N·m`) and motor friction (`f_c = 0.010`,
//! `f_s = 0.002 N·m`), the same on both plants. The joint runs
//! `JointConfig::<S>::update` of `JointParams::table_4_1_at(0.004)` every
//! 4 ms (mode manager settings changed by name per experiment, below) on
//! counts quantized from the true angles (2^17 link counts, 2000 motor
//! counts, no noise), for `S = f32` and `I16F16`; its torque is held for
//! the tick. The hand or the obstacle is an external torque on the link
//! (`EngineArm::set_external_torque`, `Mrr::external_torque`: a
//! generalized force on `q_l`, N·m, positive in the joint's positive
//! sense), evaluated at every plant step (0.1 ms: the engine's step
//! `ARM_DT`, `Mrr`'s RK4 step). Each run is repeated on the engine at half
//! its step (0.05 ms); the engine is first order in its step, so the
//! difference between the two is about half the engine's own error.
//!
//! # Criteria, written before the first run
//! Agreement, every experiment: `Mrr` and the engine at its step agree
//! within three times the engine's step-halving difference plus a floor
//! (0.02 N·m on torques, 2 ticks on switch times, 2e-3 rad on angles: the
//! count quantization and `Mrr`'s own step).
//!
//! (a) Back-driving. A hand (impedance 200 N·m/rad, 5 N·m·s/rad following
//! `q_h = 0.5 sin(2π t/4 s)` rad, as `closed_loop::back_drive`) leads the
//! joint for 6 s; the hand torque is measured over the last 4 s (one
//! period). (A) uncompensated: motor torque 0 (the joint step runs, its
//! output is not applied). (B) the joint's passive law: the manager enters
//! Passive above 1 N·m (exit 0.5 N·m) and releases only after 1 s with
//! the motor at rest (`|q̇_m| ≤ 10 rad/s`), which a hand that keeps
//! moving never gives; so it must be Passive on every tick of the
//! measured window. The preset's passive law has `Î_m K_p = 1`: the two
//! `τ̂_t` terms of eq. (4.32) cancel and the motor supplies only the
//! friction compensation `f̂(q̇_m)` with the adapted estimates (`f̂_c =
//! 0.006 N·m` initially). Reflected through the gear that is `N f̂_c =
//! 0.6 N·m` of the reflected motor friction `N f_c = 1.0 N·m` the hand
//! otherwise overcomes (the link friction, 0.6–0.8 N·m, is on the link
//! side: no motor torque removes it). Expected: the RMS hand torque falls
//! by at least half of `N f̂_c` (read from the joint's adapted estimate at
//! the switch; the other half for the reversals, where the speed reads
//! zero below one count per tick and the compensation is off), and by no
//! more than the RMS of the motor torque reflected, `N τ_m`, plus
//! 0.1 N·m (the reduction is the motor's work, nothing else).
//!
//! (b) Mode switching (`closed_loop::interaction_scenario`'s hand at the
//! 4 ms tick): the joint holds `q_l = 0` Active; from 0.5 s the hand
//! (200 N·m/rad, 5 N·m·s/rad) leads it to 0.4 rad along a raised cosine
//! over 2 s, holds it there until 3 s and lets go; 6 s in all. Manager:
//! enter 4 N·m, exit 2 N·m, release `|q̇_m| ≤ 10 rad/s` for 1 s (the
//! settings of `ModeScenarioConfig::interaction`, the release in ticks).
//! Expected: exactly two switches, Active → Passive then Passive →
//! Active, both bumpless (`|Δτ_m| ≤ switch_jump_bound`). The first when
//! the interaction torque exceeds 4 N·m: with the link held at 0 the true
//! torque is the hand's, `200·0.2 (1 − cos(π (t − 0.5)/2))`, which reaches
//! 4 N·m at 0.787 s; the estimate reads a torque change at about half its
//! size (errata E2.9, as in `payload_drop_estimate_follows_the_step`), so
//! it may need 8 N·m, reached at 0.910 s; plus the 3-tick debounce: the
//! switch in [0.787, 0.930] s. The return: the hand stops leading at
//! 2.5 s and lets go at 3 s; the release needs 1 s at rest, so the return
//! is in [3.0, 4.0] s, after which the joint rejoins its hold: at 6 s
//! `|q_l| ≤ 0.0558 rad` (Theorem 1's bound `r_S/λ` of the 4 ms design at
//! the link, `table_4_1_at` docs).
//!
//! (c) Collision (`closed_loop::collision_scenario` at the 4 ms tick):
//! the joint tracks `0.2 (1 − cos(π t/4))` rad towards 0.4 rad; an
//! obstacle at 0.15 rad pushes back as a spring of 300 N·m/rad with
//! 2 N·m·s/rad damping (never pulling); 5 s. Manager: passive entry out of
//! reach (1000 N·m, exit 500 N·m), detector threshold 3 N·m, release
//! 1.5 N·m, debounce 3 ticks, reaction `Stop` or `Passive`. Expected:
//! contact when the link, lagging the reference by at most its measured
//! largest tracking error `e` before contact, passes 0.15 rad: between the
//! times the reference passes `0.15 − e` and `0.15 + e` (nominally
//! `t_c = (4/π) acos(0.25) = 1.6785 s`, at `q̇ = 0.152 rad/s`, so the
//! spring torque rises at 45.6 N·m/s plus 0.3 N·m of damping). Detection
//! after contact: at least the time the true torque needs to reach 3 N·m,
//! `(3 − 0.3)/45.6 = 59 ms`, and at most the time to 7.5 N·m (the
//! estimate reading at 0.4 of the change), `(7.5 − 0.3)/45.6 = 158 ms`,
//! plus the debounce and one tick (12 ms): [59, 170] ms. One switch,
//! bumpless; `Stop` goes to Hold, moves less than 0.01 rad after
//! detection and keeps pressing (contact torque below −1 N·m at the end);
//! `Passive` goes to Passive and yields: out of contact at the end.
//!
//! # Revised after the first run, and why
//! * (c) `Passive`: "out of contact at the end" ignored the friction that
//!   holds a joint at rest. The passive joint yielded from the 5.7 N·m it
//!   met at detection and stopped 2 mrad inside the obstacle (0.152 rad,
//!   −0.64 N·m on f32 `Mrr`, −0.61 N·m on I16F16): below the link's
//!   breakaway friction `f_c + f_s = 0.8 N·m`, and the compensation
//!   `f̂(q̇_m)` is off at rest, so the rotor's own breakaway friction,
//!   `N (f_c + f_s) = 1.2 N·m` reflected, holds too. Revised: at the end
//!   the obstacle pushes with at most the static friction at rest,
//!   `0.8 + 1.2 = 2.0 N·m` (the `Stop` reaction keeps its "below −1 N·m":
//!   it measured −5.6 to −6.0 N·m).
//! * (b) agreement of the return time: the release counter restarts on
//!   any single tick of motor-speed jitter or interaction above 2 N·m, so
//!   the return time is a threshold event, not a smooth function of the
//!   motion: on I16F16 `Mrr` returned at 4.000 s and the engine at
//!   3.500 s (dt/2: 3.544 s), all inside the derived window [3.0, 4.0] s.
//!   The return time is checked against that window on each plant, not
//!   compared between plants; the link traces are compared up to the
//!   let-go (3 s), and the final angles by the hold bound.
//! * link traces: a switch two ticks apart (f32: `Mrr` entered Passive at
//!   0.912 s, the engine at 0.904 s at both steps) shifts the link's
//!   catch-up with the hand by 8 ms, and the traces were 5.1e-3 rad apart
//!   against a halving difference of 3.8e-4 rad. Every trace comparison
//!   now adds the largest link speed times the difference of the first
//!   switch's time between `Mrr` and the engine. The first
//!   switch is compared as written, within 2 ticks plus three times the
//!   halving difference (an exact 2-tick difference failed on rounding:
//!   the comparison now allows 1e-9 s).
//!
//! Added after the first run, from its numbers: (a)'s uncompensated
//! runs (motor off, so the loop makes no discrete decisions; the link
//! traces were 2.7e-5 rad apart with a halving difference of 1.4e-5 rad,
//! the ratio of a first-order error) agree without the 2e-3 rad floor:
//! `Mrr` vs engine ≤ three times the halving difference plus 1e-5 rad.
//! The powered runs keep the floor: in Passive the law's friction
//! compensation switches with the sign of the count-difference speed, and
//! (B)'s traces were 1.4e-3 rad apart with a halving difference of only
//! 9.5e-5 rad (f32; 3.2e-5 rad on I16F16), so there the floor, not the
//! engine's step, accounts for the difference.
//!
//! # What the checks see (each broken by hand, not committed)
//! * the engine's external torque scaled by 0.9 (a hand or obstacle 10 %
//!   weak on the engine only): (a) fails on both backends (uncompensated
//!   hand RMS 1.985 N·m on the engine against 1.789 N·m on `Mrr`), (b)
//!   fails on I16F16 (switch to Passive 24 ms later than `Mrr`), (c)
//!   passes: its windows do not resolve a 10 % softer obstacle;
//! * the same scaled by 0.99: only the strict check of (a)'s unpowered
//!   traces fails (2.1e-4 rad against its bound of 5.0e-5 rad; the hand
//!   RMS moved by 0.018 N·m, under its 0.02 N·m floor); by 0.999 nothing
//!   fails (the 200 N·m/rad hand keeps the link on its path: a 0.002 N·m
//!   error moves it by about 1e-5 rad);
//! * the passive law's friction compensation removed: (a) fails (no
//!   reduction of the hand torque);
//! * the Stop reaction holding at 0 instead of the measured position:
//!   (c) fails; holding at the desired position instead (6 mrad further
//!   into the obstacle at the link) passes — the stiff obstacle and the
//!   4 ms law's gains keep the link within 0.1 mrad of the correct run;
//! * the manager's passive entry threshold and the detector's threshold
//!   both halved: (b) and (c) pass (switch at 0.832–0.840 s, detection
//!   latency 86–91 ms, inside the windows): the windows allow the
//!   estimate to read a torque change at 0.4–1.0 of its size (errata
//!   E2.9), a factor that also covers a threshold off by two.
//!
//! # (d) Collision on an engine contact (added later; criteria written before its first run)
//! The obstacle of (c) as the engine's contact instead of a spring torque:
//! a frictionless ball of 2 cm radius at the link's tip (centre at 0.45 m on
//! the link's axis) and a fixed box whose face the ball touches when the
//! link reaches 0.15 rad (`arm_scenarios::tip_contact`,
//! `Wall::stop_for`). The contact force is the rapier solver's, read back
//! as a torque on `q_l`; `Mrr` has no colliders, so (d) runs on the engine
//! only, at its step and at half of it; (c) stays the comparison of the
//! two plants on the same obstacle torque. Same joint, reference,
//! detector and reactions as (c); `S = f32` and `I16F16`. Expected:
//! * first contact (first step with a contact force): the link, read at
//!   the start of that step, within 1 mrad of 0.15 rad (the ball closes at
//!   most `q̇ dt ≈ 2e-5 rad` in a step), and at a time inside (c)'s window
//!   from the tracking error before contact;
//! * detection after first contact: at least two ticks (the debounce of 3
//!   ticks starts at the first tick after contact; 8 ms) and at most (c)'s
//!   170 ms (the contact is stiffer than (c)'s 300 N·m/rad spring, so its
//!   torque reaches the thresholds no later);
//! * the wall only pushes: the contact torque on `q_l` is never positive;
//! * peak contact torque, per-tick mean (the impact of one 0.1 ms step is
//!   an impulse, its tick mean the impulse over 4 ms): at most the
//!   saturated motor through the gear `N τ_max = 100 × 0.188 = 18.8 N·m`,
//!   plus the kinetic energy at contact stored in the drive's stiffest
//!   segment, `√(2 E K₃)` with `E = ½ (N² I_m + J_l) v²` (`N² I_m =
//!   0.114`, `J_l = 0.0432 kg·m²` about the joint, `K₃ = 1.3e4
//!   N·m/rad`, `v` the largest link speed before contact from the tick
//!   trace), plus the link's momentum stopped within a tick, `J_l v / T`;
//! * reactions as in (c): one switch, bumpless; `Stop` goes to Hold,
//!   moves less than 0.01 rad after detection and keeps pressing (tick-mean
//!   contact torque below −1 N·m at the end); `Passive` goes to Passive
//!   and yields down to the static friction at rest (contact torque at the
//!   end ≥ −2.0 N·m);
//! * the engine at half its step: detection within 2 ticks of the run at
//!   its step.
//!
//! # Runners
//! The runs themselves are the library's (`sim::engine::arm_scenarios`:
//! `back_driving`, `mode_switching`, `collision`, on a plant chosen by
//! `ArmPlant`); this file holds the criteria.
//!
//! # Run time
//! `cargo test --all-features --test engine_arm_modes` runs every
//! experiment on f32 and I16F16, each on `Mrr` and on the engine at its
//! step and half of it ((d) on the engine only): 35.7 s for the eight tests
//! on 2 cores (the test profile of this crate is optimized); add
//! `-- --nocapture` to print the measured values.
#![cfg(feature = "engine")]

use mrr_control::estimation::collision::CollisionReaction;
use mrr_control::prelude::JointMode;
use mrr_control::sim::engine::arm_scenarios::{
    back_driving as back_driving_run, collision as collision_run, mode_switching as switching_run,
    reference_passes, spring_wall, CollisionObstacle, WALL_ANGLE,
};
use mrr_control::sim::engine::{arm_settings, ArmPlant, JointRun};
use mrr_control::{Scalar, I16F16};

const TICK: f64 = 4e-3;

/// The three plants of every experiment: `Mrr`, the engine at its step,
/// the engine at half of it.
const PLANTS: [&str; 3] = ["Mrr", "engine", "engine dt/2"];

/// The plant `PLANTS[i]` (the runners build it fresh at rest).
fn plant(i: usize) -> ArmPlant {
    let s = arm_settings();
    match i {
        0 => ArmPlant::Mrr,
        1 => ArmPlant::Engine(s),
        _ => ArmPlant::Engine(s.with_half_step()),
    }
}

/// `x` (from `Mrr`) and `y` (engine) agree within three times the
/// engine's halving difference `|y − y2|` plus `floor`.
fn within(what: &str, x: f64, y: f64, y2: f64, floor: f64) {
    let tol = 3.0 * (y - y2).abs() + floor + 1e-9;
    println!(
        "  {what}: Mrr {x:.4}, engine {y:.4}, engine dt/2 {y2:.4}; |Mrr − engine| {:.2e} ≤ {tol:.2e}",
        (x - y).abs()
    );
    assert!(
        (x - y).abs() <= tol,
        "{what}: Mrr {x} vs engine {y} (dt/2 {y2})"
    );
}

/// Largest difference of two link traces, rad.
fn apart(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Link traces: `Mrr` vs engine within three times engine dt vs dt/2 plus
/// 2e-3 rad, plus what a switch `shift` s earlier or later moves a trace
/// by: the largest link speed (tick differences of the engine's trace)
/// times `shift` (revised after the first run, module docs).
fn traces_agree(name: &str, runs: &[JointRun], shift: f64) {
    let d = apart(&runs[0].link, &runs[1].link);
    let h = apart(&runs[1].link, &runs[2].link);
    let v = runs[1]
        .link
        .windows(2)
        .map(|w| (w[1] - w[0]).abs() / TICK)
        .fold(0.0, f64::max);
    let tol = 3.0 * h + 2e-3 + v * shift;
    println!(
        "  {name}: link traces Mrr vs engine {d:.3e} rad, engine dt vs dt/2 {h:.3e} rad, \
         switch shift {shift:.3} s × largest speed {v:.3} rad/s; bound {tol:.3e} rad"
    );
    assert!(d <= tol, "{name}: {d:.3e} vs bound {tol:.3e}");
}

/// The difference of the first switch's time between `Mrr` and the
/// engine at its step, s (0 when either has none).
fn switch_shift(runs: &[JointRun]) -> f64 {
    match (runs[0].switches.first(), runs[1].switches.first()) {
        (Some(a), Some(b)) => (a.time - b.time).abs(),
        _ => 0.0,
    }
}

// ---------------------------------------------------------------------------
// (a) Back-driving.

fn back_driving<S: Scalar>(name: &str) {
    let mut a_runs = Vec::new();
    let mut b_runs = Vec::new();
    for (i, pname) in PLANTS.iter().enumerate() {
        let a = back_driving_run::<S>(plant(i), false).unwrap();
        let b = back_driving_run::<S>(plant(i), true).unwrap();
        let fc = b.coulomb_at_switch.unwrap_or(f64::NAN);
        let passive_ticks = b.modes[500..]
            .iter()
            .filter(|m| **m == JointMode::Passive)
            .count();
        println!(
            "{name} {pname:<12} hand RMS (A) {:.4} N·m, (B) {:.4} N·m, reduction {:.4}; \
             N f̂_c {:.3}, RMS N τ_m {:.4}; switches {:?}; Passive {passive_ticks}/{} ticks after 2 s",
            a.env_rms,
            b.env_rms,
            a.env_rms - b.env_rms,
            100.0 * fc,
            b.reflected_motor_rms,
            b.switches,
            b.modes.len() - 500
        );
        assert_eq!(passive_ticks, b.modes.len() - 500, "{name} {pname}");
        let reduction = a.env_rms - b.env_rms;
        assert!(reduction >= 0.5 * 100.0 * fc, "{name} {pname}: {reduction}");
        assert!(
            reduction <= b.reflected_motor_rms + 0.1,
            "{name} {pname}: {reduction} vs {}",
            b.reflected_motor_rms
        );
        a_runs.push(a);
        b_runs.push(b);
    }
    within(
        "(A) hand RMS",
        a_runs[0].env_rms,
        a_runs[1].env_rms,
        a_runs[2].env_rms,
        0.02,
    );
    within(
        "(B) hand RMS",
        b_runs[0].env_rms,
        b_runs[1].env_rms,
        b_runs[2].env_rms,
        0.02,
    );
    traces_agree("(A)", &a_runs, 0.0);
    // Added after the first run (module docs): unpowered, the loop makes
    // no discrete decisions, and the difference is the engine's own
    // first-order error, without the 2e-3 rad floor.
    let d = apart(&a_runs[0].link, &a_runs[1].link);
    let h = apart(&a_runs[1].link, &a_runs[2].link);
    assert!(d <= 3.0 * h + 1e-5, "(A): {d:.3e} vs halving {h:.3e}");
    traces_agree("(B)", &b_runs, switch_shift(&b_runs));
}

#[test]
fn passive_law_reduces_the_back_driving_torque_f32() {
    back_driving::<f32>("f32");
}

#[test]
fn passive_law_reduces_the_back_driving_torque_i16f16() {
    back_driving::<I16F16>("I16F16");
}

// ---------------------------------------------------------------------------
// (b) Mode switching.

fn mode_switching<S: Scalar>(name: &str) {
    let mut runs = Vec::new();
    for (i, pname) in PLANTS.iter().enumerate() {
        let r = switching_run::<S>(plant(i)).unwrap();
        let end = *r.link.last().unwrap();
        println!(
            "{name} {pname:<12} switches {:?}; link at 6 s {end:.4} rad; jump bound {:.2e}",
            r.switches
                .iter()
                .map(|s| (s.time, s.from, s.to, s.jump))
                .collect::<Vec<_>>(),
            r.jump_bound
        );
        assert_eq!(r.switches.len(), 2, "{name} {pname}: {:?}", r.switches);
        let (on, off) = (r.switches[0], r.switches[1]);
        assert_eq!((on.from, on.to), (JointMode::Active, JointMode::Passive));
        assert_eq!((off.from, off.to), (JointMode::Passive, JointMode::Active));
        assert!((0.787..=0.930).contains(&on.time), "{name} {pname}: {on:?}");
        assert!((3.0..=4.0).contains(&off.time), "{name} {pname}: {off:?}");
        for s in &r.switches {
            assert!(s.jump <= r.jump_bound, "{name} {pname}: {s:?}");
        }
        assert!(end.abs() <= 0.0558, "{name} {pname}: {end}");
        runs.push(r);
    }
    let t: Vec<f64> = runs.iter().map(|r| r.switches[0].time).collect();
    within("switch to Passive (s)", t[0], t[1], t[2], 2.0 * TICK);
    // Up to the let-go (revised: the return is a threshold event).
    let let_go = (3.0 / TICK).round() as usize;
    let shift = switch_shift(&runs);
    for r in &mut runs {
        r.link.truncate(let_go);
    }
    traces_agree("mode switching, to 3 s", &runs, shift);
}

#[test]
fn manager_switches_to_passive_and_back_f32() {
    mode_switching::<f32>("f32");
}

#[test]
fn manager_switches_to_passive_and_back_i16f16() {
    mode_switching::<I16F16>("I16F16");
}

// ---------------------------------------------------------------------------
// (c) Collision.

fn collision<S: Scalar>(name: &str, reaction: CollisionReaction) {
    let mut runs = Vec::new();
    for (i, pname) in PLANTS.iter().enumerate() {
        let r = collision_run::<S>(plant(i), CollisionObstacle::Spring, reaction).unwrap();
        let contact = r.contact.unwrap_or(f64::NAN);
        let detection = r.detection.unwrap_or(f64::NAN);
        let e = r.error_before_contact;
        let (early, late) = (
            reference_passes(WALL_ANGLE - e),
            reference_passes(WALL_ANGLE + e),
        );
        let end = *r.link.last().unwrap();
        let at_detection = r.link[(detection / TICK).round() as usize];
        let end_torque = spring_wall(5.0, end, 0.0);
        println!(
            "{name} {reaction:?} {pname:<12} contact {contact:.4} s (window [{early:.4}, {late:.4}], \
             tracking error before {e:.2e} rad), detection {detection:.3} s (latency {:.1} ms), \
             switches {:?}, link at detection {at_detection:.4}, at end {end:.4} rad, contact \
             torque at end {end_torque:.3} N·m",
            1e3 * (detection - contact),
            r.switches
                .iter()
                .map(|s| (s.time, s.to, s.jump))
                .collect::<Vec<_>>()
        );
        assert!(
            (early..=late).contains(&contact),
            "{name} {pname}: contact {contact}"
        );
        let latency = detection - contact;
        assert!(
            (0.059..=0.170).contains(&latency),
            "{name} {pname}: latency {latency}"
        );
        reacted(
            &r,
            reaction,
            at_detection,
            end,
            end_torque,
            &format!("{name} {pname}"),
        );
        runs.push(r);
    }
    let t = |f: &dyn Fn(&JointRun) -> f64| -> Vec<f64> { runs.iter().map(f).collect() };
    let c = t(&|r| r.contact.unwrap_or(f64::NAN));
    within("contact time (s)", c[0], c[1], c[2], 2.0 * TICK);
    let d = t(&|r| r.detection.unwrap_or(f64::NAN));
    within("detection time (s)", d[0], d[1], d[2], 2.0 * TICK);
    traces_agree("collision", &runs, switch_shift(&runs));
}

#[test]
fn collision_is_detected_and_stops_or_yields_f32() {
    collision::<f32>("f32", CollisionReaction::Stop);
    collision::<f32>("f32", CollisionReaction::Passive);
}

#[test]
fn collision_is_detected_and_stops_or_yields_i16f16() {
    collision::<I16F16>("I16F16", CollisionReaction::Stop);
    collision::<I16F16>("I16F16", CollisionReaction::Passive);
}

// ---------------------------------------------------------------------------
// (d) Collision on an engine contact.

/// `N τ_max` of the thesis joint (N·m), its rotor reflected `N² I_m` and
/// its link about the joint `J_l` (kg·m²), the drive's stiffest segment
/// `K₃` (N·m/rad): from `ModuleParams::thesis_joint` and Table 2.2's
/// SHD-17-100 (module docs (d)).
const STALL: f64 = 18.8;
const ROTOR_REFLECTED: f64 = 0.114;
const LINK_INERTIA: f64 = 0.0432;
const K3: f64 = 1.3e4;

fn contact_collision<S: Scalar>(name: &str, reaction: CollisionReaction) {
    let mut detections = Vec::new();
    for i in [1, 2] {
        let pname = PLANTS[i];
        let r = collision_run::<S>(plant(i), CollisionObstacle::Contact, reaction).unwrap();
        let contact = r.contact.unwrap_or(f64::NAN);
        let detection = r.detection.unwrap_or(f64::NAN);
        let e = r.error_before_contact;
        let (early, late) = (
            reference_passes(WALL_ANGLE - e),
            reference_passes(WALL_ANGLE + e),
        );
        let k_contact = ((contact / TICK).floor() as usize).min(r.link.len() - 1);
        let speed = r.link[..=k_contact]
            .windows(2)
            .map(|w| (w[1] - w[0]).abs() / TICK)
            .fold(0.0, f64::max);
        let energy = 0.5 * (ROTOR_REFLECTED + LINK_INERTIA) * speed * speed;
        let bound = STALL + (2.0 * energy * K3).sqrt() + LINK_INERTIA * speed / TICK;
        let peak = r
            .environment_torque
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let most_positive = r.environment_torque.iter().fold(f64::MIN, |m, x| m.max(*x));
        let end = *r.link.last().unwrap();
        let at_detection = r.link[((detection / TICK).round() as usize).min(r.link.len() - 1)];
        let end_torque = *r.environment_torque.last().unwrap();
        println!(
            "{name} {reaction:?} {pname:<12} contact {contact:.4} s (window [{early:.4}, \
             {late:.4}]), link at contact {:.5} rad, detection {detection:.3} s (latency \
             {:.1} ms), peak tick-mean contact torque {peak:.3} N·m (bound {bound:.2}, speed \
             {speed:.4} rad/s), peak step torque {:.2} N·m, switches {:?}, link at detection \
             {at_detection:.4}, at end {end:.4} rad, contact torque at end {end_torque:.3} N·m",
            r.link_at_contact.unwrap_or(f64::NAN),
            1e3 * (detection - contact),
            r.env_peak,
            r.switches
                .iter()
                .map(|s| (s.time, s.to, s.jump))
                .collect::<Vec<_>>()
        );
        let at_contact = r.link_at_contact.unwrap_or(f64::NAN);
        assert!(
            (at_contact - WALL_ANGLE).abs() <= 1e-3,
            "{name} {pname}: link at contact {at_contact}"
        );
        assert!(
            (early..=late).contains(&contact),
            "{name} {pname}: contact {contact}"
        );
        let latency = detection - contact;
        assert!(
            (2.0 * TICK..=0.170).contains(&latency),
            "{name} {pname}: latency {latency}"
        );
        assert!(most_positive <= 0.0, "{name} {pname}: {most_positive}");
        assert!(peak <= bound, "{name} {pname}: peak {peak} > {bound}");
        reacted(
            &r,
            reaction,
            at_detection,
            end,
            end_torque,
            &format!("{name} {pname}"),
        );
        detections.push(detection);
    }
    assert!(
        (detections[0] - detections[1]).abs() <= 2.0 * TICK + 1e-9,
        "{name}: detection at dt and dt/2 {detections:?}"
    );
}

#[test]
fn engine_contact_collision_is_detected_and_stops_or_yields_f32() {
    contact_collision::<f32>("f32 contact", CollisionReaction::Stop);
    contact_collision::<f32>("f32 contact", CollisionReaction::Passive);
}

#[test]
fn engine_contact_collision_is_detected_and_stops_or_yields_i16f16() {
    contact_collision::<I16F16>("I16F16 contact", CollisionReaction::Stop);
    contact_collision::<I16F16>("I16F16 contact", CollisionReaction::Passive);
}

/// The reaction after a detected collision, the same for the spring
/// obstacle and the engine contact: one switch, bumpless; Stop holds where
/// it detected (within 0.01 rad) and keeps pressing (below −1 N·m at the
/// end); Passive yields down to the static friction at rest (revised:
/// the contact torque at the end is at least −2 N·m).
fn reacted(
    r: &JointRun,
    reaction: CollisionReaction,
    at_detection: f64,
    end: f64,
    end_torque: f64,
    what: &str,
) {
    assert_eq!(r.switches.len(), 1, "{what}: {:?}", r.switches);
    assert!(r.switches[0].jump <= r.jump_bound, "{what}");
    match reaction {
        CollisionReaction::Stop => {
            assert_eq!(r.switches[0].to, JointMode::Hold, "{what}");
            assert!((end - at_detection).abs() < 0.01, "{what}");
            assert!(end_torque < -1.0, "{what}: {end_torque}");
        }
        CollisionReaction::Passive => {
            assert_eq!(r.switches[0].to, JointMode::Passive, "{what}");
            assert!(end_torque >= -2.0, "{what}: {end_torque}");
        }
    }
}
