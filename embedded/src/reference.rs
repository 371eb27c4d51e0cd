//! The reference a user would otherwise write: the joint-torque estimator
//! of eq. (3.8)–(3.10) with the same integer count path, the same unit
//! scales and the same prepared constants as
//! `TorqueEstimatorConfig::update`, but with `libm` (f32) or `cordic`
//! (I16F16) in place of the crate's kernels for `sin_cos`, `exp` and `tan`.
//! Only the kernels differ, so the instruction ratio is the kernels' share.

use core::f64::consts::TAU;
use fixed::types::I16F16;
use mrr_control::estimation::torque::{TorqueEstimate, TorqueEstimatorParams};
use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::scalar::Coef;
use mrr_control::Scalar;

/// The three kernels the estimator calls.
pub trait RefKernels<S> {
    fn sin_cos(x: S) -> (S, S);
    fn exp(x: S) -> S;
    fn tan(x: S) -> S;
}

/// `libm`'s `sincosf`, `expf`, `tanf`.
pub struct Libm;
impl RefKernels<f32> for Libm {
    #[inline(always)]
    fn sin_cos(x: f32) -> (f32, f32) {
        libm::sincosf(x)
    }
    #[inline(always)]
    fn exp(x: f32) -> f32 {
        libm::expf(x)
    }
    #[inline(always)]
    fn tan(x: f32) -> f32 {
        libm::tanf(x)
    }
}

/// The `cordic` crate's `sin_cos`, `exp`, `tan`.
pub struct Cordic;
impl RefKernels<I16F16> for Cordic {
    #[inline(always)]
    fn sin_cos(x: I16F16) -> (I16F16, I16F16) {
        cordic::sin_cos(x)
    }
    #[inline(always)]
    fn exp(x: I16F16) -> I16F16 {
        cordic::exp(x)
    }
    #[inline(always)]
    fn tan(x: I16F16) -> I16F16 {
        cordic::tan(x)
    }
}

/// Prepared constants (the same values the library's configuration holds).
pub struct RefEstimator<S> {
    l: u32,
    m: u32,
    n: u32,
    torsion_per_count: Coef,
    link_rad_per_count: Coef,
    motor_rad_per_count: Coef,
    c_w: Coef,
    amplitude: Coef,
    angle_per_torsion: Coef,
    torque_per_tan: Coef,
    kinematic_error: [S; 7],
    max_torque: S,
}

/// Motor position within one output revolution and the last counter.
pub struct RefState {
    turn: u32,
    in_turn: u32,
    last: u32,
}

impl<S: Scalar> RefEstimator<S> {
    pub fn new(p: &TorqueEstimatorParams) -> Self {
        let u = S::UNITS;
        let d = &p.drive();
        let n = d.ratio() as u32;
        let (l, m) = (p.link_counts_per_rev(), p.motor_counts_per_rev());
        let lmn = l as f64 * m as f64 * n as f64;
        let ck = d.flexspline().c_f() * d.flexspline().k_f0();
        let wg = &d.wave_generator();
        let ke = p.kinematic_error().map_or([0.0; 7], |k| k.coefficients());
        RefEstimator {
            l,
            m,
            n,
            torsion_per_count: Coef::new(TAU / lmn * u.torsion),
            link_rad_per_count: Coef::new(TAU / l as f64),
            motor_rad_per_count: Coef::new(TAU / m as f64),
            c_w: Coef::new(wg.c_w() / u.motor_torque),
            amplitude: Coef::new(u.torsion / (wg.c_w() * d.ratio() * wg.k_w0())),
            angle_per_torsion: Coef::new(ck / u.torsion),
            torque_per_tan: Coef::new(u.link_torque / d.flexspline().c_f()),
            kinematic_error: ke.map(|c| S::from_f64(c * u.torsion)),
            max_torque: S::from_f64(p.max_torque() * u.link_torque),
        }
    }

    pub fn state(&self, motor_position: i64, counter: u32) -> RefState {
        let mn = self.m as i64 * self.n as i64;
        let p = motor_position.rem_euclid(mn);
        RefState {
            turn: (p / self.m as i64) as u32,
            in_turn: (p % self.m as i64) as u32,
            last: counter,
        }
    }

    #[inline(always)]
    pub fn update<K: RefKernels<S>>(
        &self,
        st: &mut RefState,
        link_count: u32,
        motor_counter: u32,
        motor_torque: S,
    ) -> TorqueEstimate<S> {
        // Motor position from the wrapping counter (as the library does).
        let delta = motor_counter.wrapping_sub(st.last) as i32 as i64;
        st.last = motor_counter;
        let m = self.m as i64;
        let mut in_turn = st.in_turn as i64 + delta;
        let mut turn = st.turn as i64;
        if (0..m).contains(&in_turn) {
        } else if in_turn >= m && in_turn < 2 * m {
            in_turn -= m;
            turn += 1;
        } else if in_turn < 0 && in_turn >= -m {
            in_turn += m;
            turn -= 1;
        } else {
            turn += in_turn.div_euclid(m);
            in_turn = in_turn.rem_euclid(m);
        }
        let n = self.n as i64;
        if !(0..n).contains(&turn) {
            turn = turn.rem_euclid(n);
        }
        st.turn = turn as u32;
        st.in_turn = in_turn as u32;
        // Torsion in counts, eq. (2.13).
        let invalid = link_count >= self.l;
        let c_l = if invalid {
            link_count % self.l
        } else {
            link_count
        };
        let mn = m * n;
        let lmn = mn * self.l as i64;
        let p = turn * m + in_turn;
        let mut d = c_l as i64 * mn + p * self.l as i64;
        if d >= lmn / 2 {
            d -= lmn;
        }
        if d >= lmn / 2 {
            d -= lmn;
        }
        let torsion = S::from_counts(d, &self.torsion_per_count);
        // Kinematic error, eq. (3.7).
        let link = K::sin_cos(S::from_counts(c_l as i64, &self.link_rad_per_count));
        let motor = K::sin_cos(S::from_counts(in_turn, &self.motor_rad_per_count));
        let kin_err = KinematicErrorModel::series(&self.kinematic_error, link, motor);
        // Eq. (3.9): flexspline torsion.
        let e = K::exp(motor_torque.abs().mul_coef(&self.c_w).neg());
        let wave = motor_torque
            .sgn()
            .mul(S::ONE.sub(e))
            .mul_coef(&self.amplitude);
        let flexspline_torsion = torsion.add(wave).sub(kin_err);
        // Eq. (3.10) with the output limit; `tan` only inside its branch.
        let angle = flexspline_torsion.mul_coef(&self.angle_per_torsion);
        let limit = if flexspline_torsion < S::ZERO {
            self.max_torque.neg()
        } else {
            self.max_torque
        };
        let (torque, saturated) = if angle.abs() >= S::FRAC_PI_2 {
            (limit, true)
        } else {
            let t = K::tan(angle).mul_coef(&self.torque_per_tan);
            if t.abs() > self.max_torque {
                (limit, true)
            } else {
                (t, false)
            }
        };
        TorqueEstimate {
            torque,
            torsion,
            flexspline_torsion,
            saturated,
            link_count_invalid: invalid,
            invalid_input: false,
        }
    }
}

/// `⌊a·b / 2³²⌋` exactly as the I16F16 kernels compute it: four 16×16
/// products and two add-with-carry steps (a form LLVM does not fold back
/// into one 64-bit multiply, so it needs no barrier).
#[inline(always)]
pub fn mulhi_split(a: u32, b: u32) -> u32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let ll = al * bl;
    let hh = ah * bh;
    let (mid, c1) = (al * bh).overflowing_add(ah * bl);
    let (_, c2) = ll.overflowing_add(mid << 16);
    hh + (mid >> 16) + ((c1 as u32) << 16) + c2 as u32
}
