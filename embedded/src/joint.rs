//! The per-joint control step of the firmware: the library's
//! [`JointConfig::update`] — the torque estimate of eq. (3.8)–(3.10), the
//! motor position and speed from the counts, and the mode manager of ch. 4
//! (robust adaptive law eq. 4.19 with the adaptation of Theorem 1, passive
//! law eq. 4.32, switching and collision reaction) — with the Table 4.1
//! joint on the SHD-17-100 drive (Table 3.2 kinematic error, L = 2¹⁷,
//! M = 2000, speed over one tick).
//!
//! Sign conventions (errata E2.10) are the joint type's: the readings and
//! the target are in the ch. 4 sense (`q_m = N q_l`), the step negates the
//! motor counter for the estimator, takes the previous command as the
//! motor torque `τ_w` of eq. (3.9), and feeds the manager `τ̂_t = −torque`.
//! The libm / cordic references are the same tick written from the
//! components ([`ref_step`]).

use core::mem::MaybeUninit;
use fixed::types::I16F16;
#[cfg(feature = "laws")]
use mrr_control::control::{ActiveOutput, PassiveOutput};
use mrr_control::control::{
    ControlInput, ModeConfig, ModeOutput, ModeParams, ModeSettings, ModeState, PassiveConfig,
    PassiveParams, RobustAdaptiveParams, RobustAdaptiveState,
};
use mrr_control::estimation::collision::{CollisionParams, CollisionReaction, CollisionSettings};
use mrr_control::estimation::torque::TorqueEstimatorParams;
use mrr_control::joint::{
    JointConfig, JointOutput, JointParams, JointReadings, JointSettings, JointState, JointTarget,
};
use mrr_control::scalar::Coef;
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

/// The joint configurations, `[estimator][reaction]`.
static mut JOINT_F32: MaybeUninit<[[JointConfig<f32>; 2]; 2]> = MaybeUninit::uninit();
static mut JOINT_X: MaybeUninit<[[JointConfig<I16F16>; 2]; 2]> = MaybeUninit::uninit();
/// The joint states, per reaction (the estimator configurations share the
/// drive and encoders, so one state serves both).
static mut JST_F32: MaybeUninit<[JointState<f32>; 2]> = MaybeUninit::uninit();
static mut JST_X: MaybeUninit<[JointState<I16F16>; 2]> = MaybeUninit::uninit();
static mut REF_F32: MaybeUninit<RefEstimator<f32>> = MaybeUninit::uninit();
static mut REF_X: MaybeUninit<RefEstimator<I16F16>> = MaybeUninit::uninit();
/// The mode managers alone (warm-up, the stand-alone laws), the same
/// parameters as the joints'.
static mut MODE_F32: MaybeUninit<[ModeConfig<f32>; 2]> = MaybeUninit::uninit();
static mut MODE_X: MaybeUninit<[ModeConfig<I16F16>; 2]> = MaybeUninit::uninit();
static mut PASSIVE_F32: MaybeUninit<PassiveConfig<f32>> = MaybeUninit::uninit();
static mut PASSIVE_X: MaybeUninit<PassiveConfig<I16F16>> = MaybeUninit::uninit();
static mut REF_ST: MaybeUninit<RefState> = MaybeUninit::uninit();
/// The reference's motor count and last counter (ch. 4 sense), and its
/// `N`, angle per count and speed per count.
static mut REF_MOTOR: (i64, u32) = (0, 0);
static mut REF_COEF: MaybeUninit<[Coef; 3]> = MaybeUninit::uninit();
/// The warmed-up mode states per reaction; the references run the Stop
/// one.
static mut ST_F32: MaybeUninit<[ModeState<f32>; 2]> = MaybeUninit::uninit();
static mut ST_X: MaybeUninit<[ModeState<I16F16>; 2]> = MaybeUninit::uninit();
/// States of the stand-alone active law (copied from the warmed-up Stop
/// manager's active law by [`prepare`]).
static mut ACT_F32: MaybeUninit<RobustAdaptiveState<f32>> = MaybeUninit::uninit();
static mut ACT_X: MaybeUninit<RobustAdaptiveState<I16F16>> = MaybeUninit::uninit();
/// Desired joint torque of the passive law (a free joint: 0), read
/// volatile so the step does not specialise on it.
static mut DESIRED_TORQUE: [u32; 2] = [0; 2];
/// Whole output turns of the target, read volatile so the step does not
/// specialise on them (the frame's origin moves at run time).
static mut TARGET_TURNS: i32 = 0;

/// The joint of estimator parameters `p` and collision reaction `r`.
fn joint_params(p: &TorqueEstimatorParams, r: CollisionReaction) -> JointParams {
    ok(JointParams::try_new(JointSettings {
        estimator: *p,
        mode: mode_params(r),
        speed_window: 1,
        max_motor_speed: mrr_control::joint::TABLE_4_1_MAX_MOTOR_SPEED,
    }))
}

/// Builds the configurations (not counted).
/// `p` carries the kinematic-error model, `p_no_ke` is the same drive
/// and encoders without it.
pub unsafe fn init(p: &TorqueEstimatorParams, p_no_ke: &TorqueEstimatorParams) {
    let stop = mode_params(CollisionReaction::Stop);
    let passive = mode_params(CollisionReaction::Passive);
    let jp = [p, p_no_ke]
        .map(|e| [CollisionReaction::Stop, CollisionReaction::Passive].map(|r| joint_params(e, r)));
    JOINT_F32.write(jp.map(|row| row.map(|j| JointConfig::new(&j))));
    JOINT_X.write(jp.map(|row| row.map(|j| JointConfig::new(&j))));
    let (jf, jx) = (JOINT_F32.assume_init_ref(), JOINT_X.assume_init_ref());
    JST_F32.write([jf[KE][STOP].state_at(0, 0), jf[KE][PASSIVE].state_at(0, 0)]);
    JST_X.write([jx[KE][STOP].state_at(0, 0), jx[KE][PASSIVE].state_at(0, 0)]);
    REF_F32.write(RefEstimator::new(p));
    REF_X.write(RefEstimator::new(p));
    let j = &jp[KE][STOP];
    REF_COEF.write([
        Coef::new(j.ratio()),
        Coef::new(j.motor_rad_per_count()),
        Coef::new(j.speed_resolution()),
    ]);
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

/// Joint states at motor position `lo, hi` (i64, motor counts, ch. 4
/// sense) while the counter reads `counter`, with the mode states of
/// `scenario` (see [`warm_up`]).
pub unsafe fn prepare(lo: u32, hi: u32, counter: u32, scenario: u32, seed: u32) -> u32 {
    let pos = ((hi as u64) << 32 | lo as u64) as i64;
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
    let (jf, jx) = (JOINT_F32.assume_init_ref(), JOINT_X.assume_init_ref());
    let (tf, tx) = (JST_F32.assume_init_mut(), JST_X.assume_init_mut());
    for r in [STOP, PASSIVE] {
        if mask & (1 << r) != 0 {
            sf[r] = warm_up(&mf[r], scenario, seed);
        }
        if mask & (4 << r) != 0 {
            sx[r] = warm_up(&mx[r], scenario, seed);
        }
        tf[r] = jf[KE][r].state_at(pos, counter).with_mode_state(sf[r]);
        tx[r] = jx[KE][r].state_at(pos, counter).with_mode_state(sx[r]);
    }
    // The reference: the estimator in its own sign, the motor count.
    REF_ST.write(
        REF_F32
            .assume_init_ref()
            .state(pos.wrapping_neg(), counter.wrapping_neg()),
    );
    REF_MOTOR = (pos, counter);
    ACT_F32.write(*sf[STOP].active_state());
    ACT_X.write(*sx[STOP].active_state());
    0
}

#[inline(always)]
unsafe fn desired(i: usize) -> u32 {
    (&raw const DESIRED_TORQUE)
        .cast::<u32>()
        .add(i)
        .read_volatile()
}

/// The tick's target: `a` = desired link position, speed, acceleration,
/// expected joint torque; `td` the desired joint torque.
#[inline(always)]
fn target<S: Scalar>(a: [S; 4], td: S) -> JointTarget<S> {
    JointTarget {
        // Read at run time, so that the bound covers a target whose turns
        // change (a turret, a wheel).
        turns: unsafe { (&raw const TARGET_TURNS).read_volatile() },
        position: a[0],
        velocity: a[1],
        acceleration: a[2],
        joint_torque: td,
        expected_joint_torque: a[3],
    }
}

/// The per-joint step of configuration (`E` estimator, `R` reaction):
/// link count, motor counter, then `a` as in [`target`].
#[inline(always)]
pub unsafe fn step_f32<const E: usize, const R: usize>(
    l: u32,
    m: u32,
    a: [f32; 4],
) -> JointOutput<f32> {
    // The configuration read through an opaque reference (no code, the
    // same address), as from a pointer: every field is then addressed at
    // its offset from the configuration. Read from its static's address,
    // a field kilobytes past a base shared with other statics costs one
    // to three more instructions per read (26 on the M4F f32 step).
    core::hint::black_box(JOINT_F32.assume_init_ref())[E][R].update(
        &mut JST_F32.assume_init_mut()[R],
        &JointReadings::counts(l, m),
        &target(a, f32::from_bits(desired(0))),
    )
}

/// As [`step_f32`], I16F16.
#[inline(always)]
pub unsafe fn step_x<const E: usize, const R: usize>(
    l: u32,
    m: u32,
    a: [I16F16; 4],
) -> JointOutput<I16F16> {
    // The configuration read through an opaque reference (no code, the
    // same address), as from a pointer: every field is then addressed at
    // its offset from the configuration. Read from its static's address,
    // a field kilobytes past a base shared with other statics costs one
    // to three more instructions per read (26 on the M4F f32 step).
    core::hint::black_box(JOINT_X.assume_init_ref())[E][R].update(
        &mut JST_X.assume_init_mut()[R],
        &JointReadings::counts(l, m),
        &target(a, I16F16::from_bits(desired(1) as i32)),
    )
}

/// The stand-alone sample of the active and passive laws: `a` = desired
/// position, speed, acceleration, measured position, speed, joint torque.
#[cfg(feature = "laws")]
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
#[cfg(feature = "laws")]
#[inline(always)]
pub unsafe fn active_f32(a: [f32; 6]) -> ActiveOutput<f32> {
    let x = sample_of(a, f32::from_bits(desired(0)));
    MODE_F32.assume_init_ref()[STOP]
        .active()
        .update(ACT_F32.assume_init_mut(), &x)
}

/// As [`active_f32`], I16F16.
#[cfg(feature = "laws")]
#[inline(always)]
pub unsafe fn active_x(a: [I16F16; 6]) -> ActiveOutput<I16F16> {
    let x = sample_of(a, I16F16::from_bits(desired(1) as i32));
    MODE_X.assume_init_ref()[STOP]
        .active()
        .update(ACT_X.assume_init_mut(), &x)
}

/// The passive law of eq. (4.32) alone (Table 4.1, gain 2000).
#[cfg(feature = "laws")]
#[inline(always)]
pub unsafe fn passive_f32(a: [f32; 6]) -> PassiveOutput<f32> {
    let x = sample_of(a, f32::from_bits(desired(0)));
    PASSIVE_F32.assume_init_ref().update(&x)
}

/// As [`passive_f32`], I16F16.
#[cfg(feature = "laws")]
#[inline(always)]
pub unsafe fn passive_x(a: [I16F16; 6]) -> PassiveOutput<I16F16> {
    let x = sample_of(a, I16F16::from_bits(desired(1) as i32));
    PASSIVE_X.assume_init_ref().update(&x)
}

/// The reference tick, written from the components as a user without the
/// joint type would: the estimate with kernels `K` (motor counter
/// negated), the motor position and speed from the counts (speed over one
/// tick), the target times `N`, `τ̂_t = −torque`, the mode manager.
#[inline(always)]
unsafe fn ref_step<S: Scalar, K>(
    est: &RefEstimator<S>,
    mode: &ModeConfig<S>,
    st: &mut ModeState<S>,
    l: u32,
    m: u32,
    a: [S; 4],
    td: S,
) -> ModeOutput<S>
where
    K: crate::reference::RefKernels<S>,
{
    let e = est.update::<K>(
        REF_ST.assume_init_mut(),
        l,
        m.wrapping_neg(),
        st.last_torque(),
    );
    let delta = m.wrapping_sub(REF_MOTOR.1) as i32;
    REF_MOTOR = (REF_MOTOR.0.wrapping_add(delta as i64), m);
    let [n, angle, speed] = REF_COEF.assume_init_ref();
    let x = ControlInput {
        desired_position: a[0].mul_coef(n),
        desired_velocity: a[1].mul_coef(n),
        desired_acceleration: a[2].mul_coef(n),
        motor_position: S::from_counts(REF_MOTOR.0, angle),
        motor_velocity: S::from_counts(delta as i64, speed),
        joint_torque: e.torque.neg(),
        desired_joint_torque: td,
        expected_joint_torque: a[3],
    };
    mode.update(st, &x)
}

#[inline(always)]
pub unsafe fn step_libm_f32(l: u32, m: u32, a: [f32; 4]) -> ModeOutput<f32> {
    ref_step::<f32, Libm>(
        REF_F32.assume_init_ref(),
        &MODE_F32.assume_init_ref()[STOP],
        &mut ST_F32.assume_init_mut()[STOP],
        l,
        m,
        a,
        f32::from_bits(desired(0)),
    )
}

#[inline(always)]
pub unsafe fn step_cordic_x(l: u32, m: u32, a: [I16F16; 4]) -> ModeOutput<I16F16> {
    ref_step::<I16F16, Cordic>(
        REF_X.assume_init_ref(),
        &MODE_X.assume_init_ref()[STOP],
        &mut ST_X.assume_init_mut()[STOP],
        l,
        m,
        a,
        I16F16::from_bits(desired(1) as i32),
    )
}
