//! The per-joint control step of the firmware: the torque estimate of
//! eq. (3.8)–(3.10) feeding the mode manager of ch. 4 (robust adaptive law
//! eq. 4.19 with the adaptation of Theorem 1, passive law eq. 4.32,
//! switching and collision reaction), with the Table 4.1 joint on the
//! SHD-17-100 drive (Table 3.2 kinematic error, L = 2¹⁷, M = 2000).
//!
//! Sign conventions (errata E2.10): the ch. 4 motor angle `q_m = N q_l` runs
//! against the estimator's `θ_wi`, so the motor counter is negated for the
//! estimator; the motor torque `τ_w` of eq. (3.9) is the previous command
//! (positive driving the link forward in both conventions); the joint
//! torque of eq. (4.1) is `τ̂_t = −torque`.

use core::mem::MaybeUninit;
use fixed::types::I16F16;
#[cfg(feature = "variants")]
use mrr_control::control::{ActiveOutput, PassiveOutput};
use mrr_control::control::{
    ControlInput, ModeConfig, ModeOutput, ModeParams, ModeSettings, ModeState, PassiveConfig,
    PassiveParams, RobustAdaptiveParams, RobustAdaptiveState,
};
use mrr_control::estimation::collision::{CollisionParams, CollisionReaction, CollisionSettings};
use mrr_control::estimation::torque::{
    TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorState,
};
use mrr_control::Scalar;

use crate::reference::{Cordic, Libm, RefEstimator, RefState};

fn ok<T, E>(r: Result<T, E>) -> T {
    match r {
        Ok(v) => v,
        Err(_) => crate::firmware_panic(),
    }
}

/// Table 4.1 active and passive laws (passive gain 2000 1/(kg·m²)),
/// passive above 2 N·m interaction and back below 1 N·m, debounce 3
/// samples, dwell 5 samples, rejoin bandwidth 10 rad/s, bias time constant
/// 0.1 s; collisions above 4 N·m for 2 samples (released below 3 N·m for
/// 2 samples) stop the joint (`reaction` Stop) or make it passive
/// (`reaction` Passive).
pub fn mode_params(reaction: CollisionReaction) -> ModeParams {
    ok(ModeParams::try_new(ModeSettings {
        active: ok(RobustAdaptiveParams::table_4_1()),
        passive: ok(PassiveParams::table_4_1(2000.0)),
        enter_passive: 2.0,
        exit_passive: 1.0,
        debounce: 3,
        dwell: 5,
        rejoin_bandwidth: 10.0,
        bias_time_constant: 0.1,
        collision: Some(ok(CollisionParams::try_new(CollisionSettings {
            threshold: 4.0,
            release_threshold: 3.0,
            debounce: 2,
            release: 2,
            reaction,
        }))),
    }))
}

// The configurations a user chooses between: estimators with
// ([`KE`]) and without ([`NO_KE`]) the kinematic-error model, mode managers
// whose collision reaction is Stop ([`STOP`]) or Passive ([`PASSIVE`]).
/// Estimator with the Table 3.2 kinematic error.
pub const KE: usize = 0;
/// Estimator without a kinematic-error model.
#[cfg(feature = "variants")]
pub const NO_KE: usize = 1;
/// Collision reaction Stop (hold the position).
pub const STOP: usize = 0;
/// Collision reaction Passive (switch to the passive law).
pub const PASSIVE: usize = 1;

static mut EST_F32: MaybeUninit<[TorqueEstimatorConfig<f32>; 2]> = MaybeUninit::uninit();
static mut EST_X: MaybeUninit<[TorqueEstimatorConfig<I16F16>; 2]> = MaybeUninit::uninit();
static mut REF_F32: MaybeUninit<RefEstimator<f32>> = MaybeUninit::uninit();
static mut REF_X: MaybeUninit<RefEstimator<I16F16>> = MaybeUninit::uninit();
static mut MODE_F32: MaybeUninit<[ModeConfig<f32>; 2]> = MaybeUninit::uninit();
static mut MODE_X: MaybeUninit<[ModeConfig<I16F16>; 2]> = MaybeUninit::uninit();
static mut PASSIVE_F32: MaybeUninit<PassiveConfig<f32>> = MaybeUninit::uninit();
static mut PASSIVE_X: MaybeUninit<PassiveConfig<I16F16>> = MaybeUninit::uninit();
static mut EST_ST: MaybeUninit<TorqueEstimatorState> = MaybeUninit::uninit();
static mut REF_ST: MaybeUninit<RefState> = MaybeUninit::uninit();
static mut ST_F32: MaybeUninit<[ModeState<f32>; 2]> = MaybeUninit::uninit();
static mut ST_X: MaybeUninit<[ModeState<I16F16>; 2]> = MaybeUninit::uninit();
/// States of the stand-alone active law (copied from the warmed-up Stop
/// manager's active law by [`prepare`]).
static mut ACT_F32: MaybeUninit<RobustAdaptiveState<f32>> = MaybeUninit::uninit();
static mut ACT_X: MaybeUninit<RobustAdaptiveState<I16F16>> = MaybeUninit::uninit();
/// Desired joint torque of the passive law (a free joint: 0), read
/// volatile so the step does not specialise on it.
static mut DESIRED_TORQUE: [u32; 2] = [0; 2];

/// Builds the configurations (not counted).
/// `p` carries the kinematic-error model, `p_no_ke` is the same drive
/// and encoders without it.
pub unsafe fn init(p: &TorqueEstimatorParams, p_no_ke: &TorqueEstimatorParams) {
    let stop = mode_params(CollisionReaction::Stop);
    let passive = mode_params(CollisionReaction::Passive);
    EST_F32.write([
        TorqueEstimatorConfig::new(p),
        TorqueEstimatorConfig::new(p_no_ke),
    ]);
    EST_X.write([
        TorqueEstimatorConfig::new(p),
        TorqueEstimatorConfig::new(p_no_ke),
    ]);
    REF_F32.write(RefEstimator::new(p));
    REF_X.write(RefEstimator::new(p));
    MODE_F32.write([ModeConfig::new(&stop), ModeConfig::new(&passive)]);
    MODE_X.write([ModeConfig::new(&stop), ModeConfig::new(&passive)]);
    let (mf, mx) = (MODE_F32.assume_init_ref(), MODE_X.assume_init_ref());
    ST_F32.write([mf[STOP].initial_state(), mf[PASSIVE].initial_state()]);
    ST_X.write([mx[STOP].initial_state(), mx[PASSIVE].initial_state()]);
    ACT_F32.write(*mf[STOP].initial_state().active_state());
    ACT_X.write(*mx[STOP].initial_state().active_state());
    let pp = ok(PassiveParams::table_4_1(2000.0));
    PASSIVE_F32.write(PassiveConfig::new(&pp));
    PASSIVE_X.write(PassiveConfig::new(&pp));
}

/// A small deterministic generator for the warm-up samples.
struct Rng(u32);
impl Rng {
    fn next(&mut self) -> u32 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.0 = x;
        x
    }
    /// Uniform in `[-a, a]`.
    fn sym(&mut self, a: f64) -> f64 {
        a * ((self.next() >> 8) as f64 / (1u32 << 23) as f64 - 1.0)
    }
}

/// One warm-up sample (SI: motor side ±30 rad, tracking errors up to
/// `err` rad and 20·`err` rad/s, ±50 rad/s, ±2000 rad/s²) with joint
/// torque `tau` N·m and no expected torque.
fn sample<S: Scalar>(rng: &mut Rng, tau: f64, err: f64) -> ControlInput<S> {
    let u = S::UNITS;
    let qd = rng.sym(30.0);
    let vd = rng.sym(50.0);
    ControlInput {
        desired_position: S::from_f64(qd * u.angle),
        desired_velocity: S::from_f64(vd * u.speed),
        desired_acceleration: S::from_f64(rng.sym(2000.0) * u.speed),
        motor_position: S::from_f64((qd + rng.sym(err)) * u.angle),
        motor_velocity: S::from_f64((vd + rng.sym(20.0 * err)) * u.speed),
        joint_torque: S::from_f64(tau * u.link_torque),
        desired_joint_torque: S::ZERO,
        expected_joint_torque: S::ZERO,
    }
}

/// The mode state of a scenario, reached by running the manager (not
/// counted): 0 initial; 1 Active, two samples into a switch to Passive;
/// 2 Passive, two samples into a switch back to Active; 3 Active with the
/// collision detector one sample from detection; 4 Hold, latched; 5 Hold,
/// acknowledged, two samples into the return to Active; 6 Active just
/// after a switch (rejoin offset and bias non-zero); other values: a
/// random walk through every mode.
fn warm_up<S: Scalar>(cfg: &ModeConfig<S>, scenario: u32, seed: u32) -> ModeState<S> {
    let mut st = cfg.initial_state();
    let mut rng = Rng(seed | 1);
    let run = |st: &mut ModeState<S>, rng: &mut Rng, tau: f64, n: u32| {
        for i in 0..n {
            let err = if i % 2 == 0 { 0.05 } else { 5e-4 };
            cfg.update(st, &sample(rng, tau, err));
        }
    };
    match scenario {
        0 => {}
        1 => {
            run(&mut st, &mut rng, 0.0, 20);
            run(&mut st, &mut rng, 2.5, 2);
        }
        2 | 6 => {
            run(&mut st, &mut rng, 0.0, 20);
            run(&mut st, &mut rng, 2.5, 9);
            run(&mut st, &mut rng, 0.5, 2);
            if scenario == 6 {
                run(&mut st, &mut rng, 0.5, 3);
            }
        }
        3 => {
            run(&mut st, &mut rng, 0.0, 20);
            run(&mut st, &mut rng, 5.0, 1);
        }
        4 | 5 => {
            run(&mut st, &mut rng, 0.0, 20);
            run(&mut st, &mut rng, 5.0, 2);
            run(&mut st, &mut rng, 0.0, 8);
            if scenario == 5 {
                cfg.acknowledge_collision(&mut st);
                run(&mut st, &mut rng, 0.0, 2);
            }
        }
        _ => {
            for _ in 0..40 {
                let tau = [0.0, 0.5, 2.5, 5.0][(rng.next() & 3) as usize];
                run(&mut st, &mut rng, tau, 1);
                if rng.next() & 7 == 0 {
                    cfg.acknowledge_collision(&mut st);
                }
            }
        }
    }
    st
}

/// Estimator states at motor position `lo, hi` (i64, motor counts) and
/// counter `counter` (both in the ch. 4 sense of the step's counter), and the mode states of `scenario` (see [`warm_up`]).
pub unsafe fn prepare(lo: u32, hi: u32, counter: u32, scenario: u32, seed: u32) -> u32 {
    // Position and counter in the ch. 4 sense, negated for the estimator
    // as in the step.
    let pos = ((hi as u64) << 32 | lo as u64) as i64;
    let (pos, counter) = (pos.wrapping_neg(), counter.wrapping_neg());
    EST_ST.write(EST_F32.assume_init_ref()[KE].state(pos, counter));
    REF_ST.write(REF_F32.assume_init_ref().state(pos, counter));
    // Bits 8-11 of `scenario` select the states to warm up (f32 Stop, f32
    // Passive, I16F16 Stop, I16F16 Passive; none set: all), so that a row
    // does not pay for the others (soft-float warm-ups on the M0+).
    let mask = match (scenario >> 8) & 0xF {
        0 => 0xF,
        m => m,
    };
    let scenario = scenario & 0xFF;
    let (mf, mx) = (MODE_F32.assume_init_ref(), MODE_X.assume_init_ref());
    let (sf, sx) = (ST_F32.assume_init_mut(), ST_X.assume_init_mut());
    for r in [STOP, PASSIVE] {
        if mask & (1 << r) != 0 {
            sf[r] = warm_up(&mf[r], scenario, seed);
        }
        if mask & (4 << r) != 0 {
            sx[r] = warm_up(&mx[r], scenario, seed);
        }
    }
    ACT_F32.write(*sf[STOP].active_state());
    ACT_X.write(*sx[STOP].active_state());
    0
}

/// The control part: `a` = desired position, speed, acceleration,
/// measured position, speed, expected joint torque.
#[inline(always)]
fn control<S: Scalar>(
    cfg: &ModeConfig<S>,
    st: &mut ModeState<S>,
    torque: S,
    td: S,
    a: [S; 6],
) -> ModeOutput<S> {
    let x = ControlInput {
        desired_position: a[0],
        desired_velocity: a[1],
        desired_acceleration: a[2],
        motor_position: a[3],
        motor_velocity: a[4],
        joint_torque: torque.neg(),
        desired_joint_torque: td,
        expected_joint_torque: a[5],
    };
    cfg.update(st, &x)
}

#[inline(always)]
unsafe fn desired(i: usize) -> u32 {
    (&raw const DESIRED_TORQUE)
        .cast::<u32>()
        .add(i)
        .read_volatile()
}

/// The per-joint step of configuration (`E` estimator, `R` reaction).
#[inline(always)]
pub unsafe fn step_f32<const E: usize, const R: usize>(
    l: u32,
    m: u32,
    a: [f32; 6],
) -> ModeOutput<f32> {
    let st = &mut ST_F32.assume_init_mut()[R];
    let e = EST_F32.assume_init_ref()[E].update(
        EST_ST.assume_init_mut(),
        l,
        m.wrapping_neg(),
        st.last_torque(),
    );
    control(
        &MODE_F32.assume_init_ref()[R],
        st,
        e.torque,
        f32::from_bits(desired(0)),
        a,
    )
}

/// The per-joint step of configuration (`E` estimator, `R` reaction).
#[inline(always)]
pub unsafe fn step_x<const E: usize, const R: usize>(
    l: u32,
    m: u32,
    a: [I16F16; 6],
) -> ModeOutput<I16F16> {
    let st = &mut ST_X.assume_init_mut()[R];
    let e = EST_X.assume_init_ref()[E].update(
        EST_ST.assume_init_mut(),
        l,
        m.wrapping_neg(),
        st.last_torque(),
    );
    control(
        &MODE_X.assume_init_ref()[R],
        st,
        e.torque,
        I16F16::from_bits(desired(1) as i32),
        a,
    )
}

/// The stand-alone sample of the active and passive laws: `a` = desired
/// position, speed, acceleration, measured position, speed, joint torque.
#[cfg(feature = "variants")]
#[inline(always)]
fn sample_of<S: Scalar>(a: [S; 6], td: S) -> ControlInput<S> {
    ControlInput {
        desired_position: a[0],
        desired_velocity: a[1],
        desired_acceleration: a[2],
        motor_position: a[3],
        motor_velocity: a[4],
        joint_torque: a[5],
        desired_joint_torque: td,
        expected_joint_torque: S::ZERO,
    }
}

/// The robust adaptive law of eq. (4.19) with its adaptation, alone (the
/// Stop manager's active law and state).
#[cfg(feature = "variants")]
#[inline(always)]
pub unsafe fn active_f32(a: [f32; 6]) -> ActiveOutput<f32> {
    let x = sample_of(a, f32::from_bits(desired(0)));
    MODE_F32.assume_init_ref()[STOP]
        .active()
        .update(ACT_F32.assume_init_mut(), &x)
}

/// As [`active_f32`], I16F16.
#[cfg(feature = "variants")]
#[inline(always)]
pub unsafe fn active_x(a: [I16F16; 6]) -> ActiveOutput<I16F16> {
    let x = sample_of(a, I16F16::from_bits(desired(1) as i32));
    MODE_X.assume_init_ref()[STOP]
        .active()
        .update(ACT_X.assume_init_mut(), &x)
}

/// The passive law of eq. (4.32) alone (Table 4.1, gain 2000).
#[cfg(feature = "variants")]
#[inline(always)]
pub unsafe fn passive_f32(a: [f32; 6]) -> PassiveOutput<f32> {
    let x = sample_of(a, f32::from_bits(desired(0)));
    PASSIVE_F32.assume_init_ref().update(&x)
}

/// As [`passive_f32`], I16F16.
#[cfg(feature = "variants")]
#[inline(always)]
pub unsafe fn passive_x(a: [I16F16; 6]) -> PassiveOutput<I16F16> {
    let x = sample_of(a, I16F16::from_bits(desired(1) as i32));
    PASSIVE_X.assume_init_ref().update(&x)
}

#[inline(always)]
pub unsafe fn step_libm_f32(l: u32, m: u32, a: [f32; 6]) -> ModeOutput<f32> {
    let st = &mut ST_F32.assume_init_mut()[STOP];
    let e = REF_F32.assume_init_ref().update::<Libm>(
        REF_ST.assume_init_mut(),
        l,
        m.wrapping_neg(),
        st.last_torque(),
    );
    control(
        &MODE_F32.assume_init_ref()[STOP],
        st,
        e.torque,
        f32::from_bits(desired(0)),
        a,
    )
}

#[inline(always)]
pub unsafe fn step_cordic_x(l: u32, m: u32, a: [I16F16; 6]) -> ModeOutput<I16F16> {
    let st = &mut ST_X.assume_init_mut()[STOP];
    let e = REF_X.assume_init_ref().update::<Cordic>(
        REF_ST.assume_init_mut(),
        l,
        m.wrapping_neg(),
        st.last_torque(),
    );
    control(
        &MODE_X.assume_init_ref()[STOP],
        st,
        e.torque,
        I16F16::from_bits(desired(1) as i32),
        a,
    )
}
