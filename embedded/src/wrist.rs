//! The wrist step of the firmware (thesis ch. 5–6): F/T gauge signals →
//! interaction torques (eq. 6.35, 6.3) → active ↔ passive mode manager
//! (admittance eq. 6.32) → inverse kinematics (eq. 5.13–5.15) → both motor
//! laws (eq. 6.12–6.15), one `WristStepConfig::update` with the Table 6.1
//! wrist, and the same step as a user would write it from the components
//! with `libm` (f32) or `cordic` (I16F16) for the trigonometry
//! ([`reference`]): the full 6×6 wrench, the half-angle inverse kinematics
//! with the round-based unwrapping of `IkState`, and the exact Jacobian
//! through the forward kinematics; the mode manager and the laws are the
//! library's in both.
//!
//! Arguments: the six gauge signals (V) and the measured `(θ1, θ3)` (rad)
//! of the counted call; `prepare_wrist` stores the rest of the tick's
//! input (target `δ, γ, δ̇, γ̇`, measured speeds, mode request), read
//! volatile by the step, and drives the state into a scenario (not
//! counted).

use core::mem::MaybeUninit;
use fixed::types::I16F16;
use mrr_control::wrist::step::{
    WristOutput, WristReadings, WristStepConfig, WristStepParams, WristStepState, WristTarget,
};
use mrr_control::wrist::{MotorAngles, PitchYaw, WristMode};
use mrr_control::Scalar;

fn ok<T, E>(r: Result<T, E>) -> T {
    match r {
        Ok(v) => v,
        Err(_) => crate::firmware_panic(),
    }
}

static mut CFG_F32: MaybeUninit<WristStepConfig<f32>> = MaybeUninit::uninit();
static mut CFG_X: MaybeUninit<WristStepConfig<I16F16>> = MaybeUninit::uninit();
static mut ST_F32: MaybeUninit<WristStepState<f32>> = MaybeUninit::uninit();
static mut ST_X: MaybeUninit<WristStepState<I16F16>> = MaybeUninit::uninit();
static mut REF_F32: MaybeUninit<reference::RefWrist<f32>> = MaybeUninit::uninit();
static mut REF_X: MaybeUninit<reference::RefWrist<I16F16>> = MaybeUninit::uninit();
static mut REF_ST_F32: MaybeUninit<reference::RefState<f32>> = MaybeUninit::uninit();
static mut REF_ST_X: MaybeUninit<reference::RefState<I16F16>> = MaybeUninit::uninit();
/// The rest of the tick's input, set by [`prepare`]: `δ, γ, δ̇, γ̇, θ̇1,
/// θ̇3` (backend words) and the mode request (0 none, 1 Active, 2
/// Passive).
static mut INPUT: [u32; 7] = [0; 7];

/// Builds the configurations (not counted).
pub unsafe fn init() {
    let p = ok(WristStepParams::table_6_1());
    CFG_F32.write(WristStepConfig::new(&p));
    CFG_X.write(WristStepConfig::new(&p));
    ST_F32.write(CFG_F32.assume_init_ref().state(MotorAngles::default()));
    ST_X.write(CFG_X.assume_init_ref().state(MotorAngles::default()));
    REF_F32.write(reference::RefWrist::new(&p));
    REF_X.write(reference::RefWrist::new(&p));
    REF_ST_F32.write(REF_F32.assume_init_ref().state(CFG_F32.assume_init_ref()));
    REF_ST_X.write(REF_X.assume_init_ref().state(CFG_X.assume_init_ref()));
}

#[inline(always)]
unsafe fn input(i: usize) -> u32 {
    (&raw const INPUT).cast::<u32>().add(i).read_volatile()
}

fn request(w: u32) -> Option<WristMode> {
    match w {
        1 => Some(WristMode::Active),
        2 => Some(WristMode::Passive),
        _ => None,
    }
}

/// The tick's readings and target from the counted call's words and
/// [`INPUT`].
#[inline(always)]
unsafe fn tick<S: Scalar + crate::io::Arg>(
    g: [S; 6],
    m: [S; 2],
) -> (WristReadings<S>, WristTarget<S>) {
    let w = |i: usize| S::from_word(input(i));
    (
        WristReadings {
            gauges: g,
            motors: MotorAngles {
                theta1: m[0],
                theta3: m[1],
            },
            motor_velocity: [w(4), w(5)],
        },
        WristTarget {
            pose: PitchYaw {
                delta: w(0),
                gamma: w(1),
            },
            rate: [w(2), w(3)],
            request: request(input(6)),
        },
    )
}

/// Torques and the flag word: mode (0 Active, 1 Passive) | switched << 2 |
/// saturated << 3 | invalid_input << 4 | reference_saturated << 5 |
/// torque_saturated << 6 | singular << 7.
pub type Out<S> = ((S, S), u32);

#[inline(always)]
fn out<S: Copy>(o: &WristOutput<S>) -> Out<S> {
    (
        (o.motor_torque[0], o.motor_torque[1]),
        (o.mode == WristMode::Passive) as u32
            | (o.switched as u32) << 2
            | (o.saturated as u32) << 3
            | (o.invalid_input as u32) << 4
            | (o.reference_saturated as u32) << 5
            | (o.torque_saturated as u32) << 6
            | (o.singular as u32) << 7,
    )
}

/// The library step, f32.
#[inline(always)]
pub unsafe fn step_f32(g: [f32; 6], m: [f32; 2]) -> Out<f32> {
    let (r, t) = tick(g, m);
    out(&CFG_F32
        .assume_init_ref()
        .update(ST_F32.assume_init_mut(), &r, &t))
}

/// The library step, I16F16.
#[inline(always)]
pub unsafe fn step_x(g: [I16F16; 6], m: [I16F16; 2]) -> Out<I16F16> {
    let (r, t) = tick(g, m);
    out(&CFG_X
        .assume_init_ref()
        .update(ST_X.assume_init_mut(), &r, &t))
}

/// The reference step, f32 with libm.
#[inline(always)]
pub unsafe fn step_libm_f32(g: [f32; 6], m: [f32; 2]) -> Out<f32> {
    let (r, t) = tick(g, m);
    out(&REF_F32.assume_init_ref().update::<reference::Libm>(
        CFG_F32.assume_init_ref(),
        REF_ST_F32.assume_init_mut(),
        &r,
        &t,
    ))
}

/// The reference step, I16F16 with cordic.
#[inline(always)]
pub unsafe fn step_cordic_x(g: [I16F16; 6], m: [I16F16; 2]) -> Out<I16F16> {
    let (r, t) = tick(g, m);
    out(&REF_X.assume_init_ref().update::<reference::Cordic>(
        CFG_X.assume_init_ref(),
        REF_ST_X.assume_init_mut(),
        &r,
        &t,
    ))
}

/// A small deterministic generator for the warm-up ticks.
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

/// `n` warm-up ticks: a target `(δ, γ)` rad held, gauge signals of
/// magnitude `push` V on the τ_y gauge pattern (the push column), motors
/// near the reference.
fn run<S: Scalar>(
    cfg: &WristStepConfig<S>,
    st: &mut WristStepState<S>,
    rng: &mut Rng,
    target: (f64, f64),
    push: f64,
    n: u32,
) {
    for _ in 0..n {
        let mref = st.motor_reference();
        let g = [push, -push, push, 0.5 * push, -push, 0.2 * push];
        let r = WristReadings::<S>::from_si(
            g,
            [
                mref.theta1.to_f64() + rng.sym(2e-3),
                mref.theta3.to_f64() + rng.sym(2e-3),
            ],
            [rng.sym(0.05), rng.sym(0.05)],
        );
        let t = WristTarget::from_si(target.0, target.1, 0.0, 0.0);
        cfg.update(st, &r, &t);
    }
}

/// A state of scenario `s` (not counted), reached by running the step:
/// 0 initial (straight pose); 1 Active, pushed for four ticks (the next
/// push switches to Passive); 2 Passive, the reference driven into the
/// box corner (30°, 30°), beyond the cone (saturated), dwell passed;
/// 3 Passive at rest, released for four ticks (the next quiet tick
/// switches back to Active); 4 Active just after that switch (rejoin
/// offset decaying); 5 Active tracking near the cone's edge; other values:
/// a random walk.
fn warm_up<S: Scalar>(cfg: &WristStepConfig<S>, s: u32, seed: u32) -> WristStepState<S> {
    let mut st = cfg.state(MotorAngles::default());
    let mut rng = Rng(seed | 1);
    let rng = &mut rng;
    let near_edge = (0.3, 0.42);
    match s {
        0 => {}
        1 => {
            run(cfg, &mut st, rng, near_edge, 0.0, 60);
            run(cfg, &mut st, rng, near_edge, 1.0, 4);
        }
        2 | 3 | 4 => {
            run(cfg, &mut st, rng, near_edge, 0.0, 55);
            // A push along +δ and +γ in Passive drives the reference to
            // the corner of the box.
            run(cfg, &mut st, rng, near_edge, 1.0, 70);
            if s >= 3 {
                run(cfg, &mut st, rng, near_edge, 0.0, 4);
            }
            if s == 4 {
                run(cfg, &mut st, rng, near_edge, 0.0, 2);
            }
        }
        5 => run(cfg, &mut st, rng, (0.38, -0.35), 0.0, 30),
        _ => {
            for _ in 0..40 {
                let t = (rng.sym(0.6), rng.sym(0.6));
                let push = [0.0, 0.3, 1.0, -1.0][(rng.next() & 3) as usize];
                run(cfg, &mut st, rng, t, push, 3);
            }
        }
    }
    st
}

/// Stores the tick's input words (`w`: δ, γ, δ̇, γ̇, θ̇1, θ̇3 in the
/// backend's words) and sets the states of scenario `scenario & 0xFF`;
/// bits 8–9 select the states to warm up (f32, I16F16; none: both), bits
/// 12–13 the mode request.
pub unsafe fn prepare(scenario: u32, seed: u32, w: [u32; 6]) -> u32 {
    for (i, v) in w.iter().enumerate() {
        (&raw mut INPUT).cast::<u32>().add(i).write_volatile(*v);
    }
    (&raw mut INPUT)
        .cast::<u32>()
        .add(6)
        .write_volatile((scenario >> 12) & 3);
    let mask = match (scenario >> 8) & 3 {
        0 => 3,
        m => m,
    };
    let s = scenario & 0xFF;
    if mask & 1 != 0 {
        let c = CFG_F32.assume_init_ref();
        let st = warm_up(c, s, seed);
        ST_F32.write(st);
        REF_ST_F32.write(REF_F32.assume_init_ref().state_from(&st));
    }
    if mask & 2 != 0 {
        let c = CFG_X.assume_init_ref();
        let st = warm_up(c, s, seed);
        ST_X.write(st);
        REF_ST_X.write(REF_X.assume_init_ref().state_from(&st));
    }
    0
}

pub mod reference {
    //! The wrist step as a user would write it from the library's
    //! components and the equations, with `libm` (f32) or `cordic`
    //! (I16F16) for the trigonometry.
    use super::*;
    use mrr_control::scalar::Coef;
    use mrr_control::wrist::active::WristJointSample;
    use mrr_control::wrist::modes::{WristModeInput, WristModeState};
    use mrr_control::wrist::WristStepParams;

    /// The kernels the wrist's kinematics and sensing call.
    pub trait Kernels<S> {
        fn sin_cos(x: S) -> (S, S);
        fn sin(x: S) -> S;
        fn atan2(y: S, x: S) -> S;
        fn sqrt(x: S) -> S;
        fn acos(x: S) -> S;
    }

    /// `libm`'s `sincosf`, `sinf`, `atan2f`, `sqrtf`, `acosf`.
    pub struct Libm;
    impl Kernels<f32> for Libm {
        #[inline(always)]
        fn sin_cos(x: f32) -> (f32, f32) {
            libm::sincosf(x)
        }
        #[inline(always)]
        fn sin(x: f32) -> f32 {
            libm::sinf(x)
        }
        #[inline(always)]
        fn atan2(y: f32, x: f32) -> f32 {
            libm::atan2f(y, x)
        }
        #[inline(always)]
        fn sqrt(x: f32) -> f32 {
            libm::sqrtf(x)
        }
        #[inline(always)]
        fn acos(x: f32) -> f32 {
            libm::acosf(x)
        }
    }

    /// The `cordic` crate's functions (`sqrt` of a non-negative argument
    /// below 16 384, which the wrist's arguments are).
    pub struct Cordic;
    impl Kernels<I16F16> for Cordic {
        #[inline(always)]
        fn sin_cos(x: I16F16) -> (I16F16, I16F16) {
            cordic::sin_cos(x)
        }
        #[inline(always)]
        fn sin(x: I16F16) -> I16F16 {
            cordic::sin(x)
        }
        #[inline(always)]
        fn atan2(y: I16F16, x: I16F16) -> I16F16 {
            cordic::atan2(y, x)
        }
        #[inline(always)]
        fn sqrt(x: I16F16) -> I16F16 {
            cordic::sqrt(Ord::clamp(x, I16F16::ZERO, I16F16::from_num(16383)))
        }
        #[inline(always)]
        fn acos(x: I16F16) -> I16F16 {
            cordic::acos(x)
        }
    }

    /// Prepared constants.
    pub struct RefWrist<S> {
        matrix: [[Coef; 6]; 6],
        offset: Coef,
        sp: S,
        cp: S,
        sp2: S,
        cp2: S,
        s2p: S,
        c2p: S,
        inv_t: Coef,
        inv_t_rate: Coef,
    }

    /// Mode and law states, the continuous motor references, the last
    /// reference yaw and rates.
    pub struct RefState<S: Scalar> {
        modes: WristModeState<S>,
        laws: mrr_control::wrist::active::WristActiveState<S>,
        motors: [S; 2],
        gamma: S,
        rate: [S; 2],
    }

    fn wrap<S: Scalar>(x: S) -> S {
        let tp = S::PI.add(S::PI);
        if x > S::PI {
            x.sub(tp)
        } else if x <= S::PI.neg() {
            x.add(tp)
        } else {
            x
        }
    }

    fn hypot<S: Scalar, K: Kernels<S>>(a: S, b: S) -> S {
        let (a, b) = (a.abs(), b.abs());
        let (m, n) = if a >= b { (a, b) } else { (b, a) };
        if m <= S::ZERO {
            return S::ZERO;
        }
        let r = n.div(m);
        m.mul(K::sqrt(S::ONE.add(r.mul(r))))
    }

    impl<S: Scalar> RefWrist<S> {
        pub fn new(p: &WristStepParams) -> Self {
            let s = p.settings();
            let u = S::UNITS;
            let m = s.sensor.decoupling().matrix();
            let mut matrix = [[Coef::new(0.0); 6]; 6];
            for i in 0..6 {
                for j in 0..6 {
                    matrix[i][j] = Coef::new(m[i][j] * u.link_torque);
                }
            }
            let phi = s.kinematics.phi();
            let t = p.sample_period();
            RefWrist {
                matrix,
                offset: Coef::new(s.sensor.offset()),
                sp: S::from_f64(libm::sin(phi)),
                cp: S::from_f64(libm::cos(phi)),
                sp2: S::from_f64(libm::sin(phi) * libm::sin(phi)),
                cp2: S::from_f64(libm::cos(phi) * libm::cos(phi)),
                s2p: S::from_f64(libm::sin(2.0 * phi)),
                c2p: S::from_f64(libm::cos(2.0 * phi)),
                inv_t: Coef::new(u.speed / (t * u.angle)),
                inv_t_rate: Coef::new(1.0 / t),
            }
        }

        /// At rest at the straight pose, as the library step's initial state.
        pub fn state(&self, cfg: &WristStepConfig<S>) -> RefState<S> {
            self.state_from(&cfg.state(MotorAngles::default()))
        }

        /// The state matching a state of the library step.
        pub fn state_from(&self, st: &WristStepState<S>) -> RefState<S> {
            let m = st.motor_reference();
            RefState {
                modes: *st.mode_state(),
                laws: *st.law_state(),
                motors: [m.theta1, m.theta3],
                gamma: st.pose_reference().gamma,
                rate: [S::ZERO; 2],
            }
        }

        /// Inverse kinematics as in the library (half-angle form, eq.
        /// 5.13–5.15, projection onto the cone), reduced angles, on the
        /// root of eq. (5.13) whose `θ1` is nearer `prev1` (the previous
        /// `θ1` reference): `θ1 = arg A + π − ψ` (`θ4 ≥ 0`) or its mirror
        /// `arg A + ψ` (`θ4 ≤ 0`, `θ1 + θ3 = ε + 2ψ`), the latter when
        /// `cos(arg A − prev1) > 0`; `θ4 ≥ 0` on a tie, as the library.
        fn inverse<K: Kernels<S>>(&self, d0: S, g0: S, prev1: S) -> (S, S, PitchYaw<S>, bool, bool) {
            let two = S::ONE.add(S::ONE);
            let half = S::ONE.div(two);
            let hp = S::FRAC_PI_2;
            let mut d = d0.clamp(hp.neg(), hp);
            let mut g = g0.clamp(hp.neg(), hp);
            let mut sat = d != d0 || g != g0;
            let (mut sd, mut cd) = K::sin_cos(d);
            let (mut sg, mut cg) = K::sin_cos(g);
            let mut hb = hypot::<S, K>(K::sin(d.mul(half)), K::sqrt(cd).mul(K::sin(g.mul(half))));
            if hb > self.sp {
                sat = true;
                let (zx, zy) = (sd.mul(cg), sg.neg());
                let n = hypot::<S, K>(zx, zy);
                let (ux, uy) = if n > S::ZERO {
                    (zx.div(n), zy.div(n))
                } else {
                    (S::ONE, S::ZERO)
                };
                let (bx, by, bz) = (ux.mul(self.s2p), uy.mul(self.s2p), self.c2p);
                d = K::atan2(bx, bz);
                g = K::atan2(by.neg(), hypot::<S, K>(bx, bz));
                (sd, cd) = K::sin_cos(d);
                (sg, cg) = K::sin_cos(g);
                hb = self.sp;
            }
            let pose = PitchYaw { delta: d, gamma: g };
            let sh = hb.div(self.sp).min(S::ONE);
            if sh == S::ZERO {
                return (S::ZERO, S::ZERO, pose, sat, true);
            }
            let ch = K::sqrt(S::ONE.sub(sh.mul(sh)));
            let psi = K::atan2(self.cp.mul(sh), ch);
            let az = K::atan2(sg.neg(), cg.mul(sd));
            let t1 = wrap(S::PI.add(az).sub(psi));
            let eps = K::atan2(
                two.mul(sd).mul(sg).mul(hb.mul(hb)).neg(),
                cg.mul(sd.mul(sd)).add(cd.mul(sg.mul(sg))),
            );
            if K::sin_cos(az.sub(prev1)).1 > S::ZERO {
                let t1 = wrap(az.add(psi));
                let u = eps.add(two.mul(psi));
                return (t1, u.sub(t1), pose, sat, false);
            }
            let u = eps.sub(two.mul(psi));
            (t1, u.sub(t1), pose, sat, false)
        }

        /// Forward kinematics then the exact Jacobian (as the library's
        /// `WristConfig::jacobian`).
        fn jacobian<K: Kernels<S>>(&self, t1: S, t3: S) -> [[S; 2]; 2] {
            let (s1, c1) = K::sin_cos(t1);
            let (s3, c3) = K::sin_cos(t3);
            let (cp, sp, cp2, sp2) = (self.cp, self.sp, self.cp2, self.sp2);
            let a_coef = s1.mul(c3).add(c1.mul(s3).mul(cp2));
            let b_coef = cp.mul(c1.mul(c3).sub(s1.mul(s3)));
            let c_coef = c1.mul(s3).mul(sp2).neg();
            let b = hypot::<S, K>(a_coef, b_coef);
            let a = K::atan2(b_coef, a_coef);
            let t4 = wrap(a.sub(K::acos(c_coef.div(b).clamp(S::ONE.neg(), S::ONE))));
            let (s4, c4) = K::sin_cos(t4);
            let v = S::ONE.sub(c4);
            let t11 = c1
                .mul(c4)
                .mul(c3)
                .sub(s1.mul(s4).mul(c3).mul(cp))
                .sub(c1.mul(s4).mul(s3).mul(cp))
                .sub(s1.mul(c4).mul(s3).mul(cp2))
                .sub(s1.mul(s3).mul(sp2));
            let t31 = sp.mul(s4.mul(c3).sub(v.mul(cp).mul(s3)));
            let t22 = c1
                .mul(c4)
                .mul(c3)
                .mul(cp2)
                .add(c1.mul(c3).mul(sp2))
                .sub(s1.mul(c4).mul(s3))
                .sub(c1.mul(s4).mul(s3).mul(cp))
                .sub(s1.mul(s4).mul(c3).mul(cp));
            let t23 = sp.mul(c1.mul(v).mul(cp).add(s1.mul(s4))).neg();
            let (sd, cd) = K::sin_cos(K::atan2(t31.neg(), t11));
            let (sg, cg) = K::sin_cos(K::atan2(t23.neg(), t22));
            let d = sd.mul(sp).mul(s1).add(cd.mul(cp));
            [
                [
                    cd.mul(sp).mul(c1).div(d),
                    sp.mul(c1).mul(cg).sub(sg.mul(d)).div(d),
                ],
                [
                    sp.mul(s1).neg().div(d),
                    cg.mul(sd.mul(cp).sub(cd.mul(sp).mul(s1))).div(d),
                ],
            ]
        }

        #[inline(always)]
        pub fn update<K: Kernels<S>>(
            &self,
            cfg: &WristStepConfig<S>,
            st: &mut RefState<S>,
            r: &WristReadings<S>,
            t: &WristTarget<S>,
        ) -> WristOutput<S> {
            // Eq. (6.35): the whole wrench; eq. (6.3).
            let mut w = [S::ZERO; 6];
            for i in 0..6 {
                let mut acc = S::ZERO;
                for j in 0..6 {
                    acc = acc.add(r.gauges[j].mul_coef(&self.matrix[i][j]));
                }
                w[i] = acc;
            }
            let (s, c) = K::sin_cos(st.gamma);
            let mx = w[3].sub(w[1].mul_coef(&self.offset));
            let my = w[4].add(w[0].mul_coef(&self.offset));
            let mut tau = [c.mul(mx).sub(s.mul(w[5])), my.neg()];
            let dd = |v: S| v.sub(v);
            let mut probe = dd(tau[0]).add(dd(tau[1]));
            for g in r.gauges.iter() {
                probe = probe.add(dd(*g));
            }
            let bad = probe != S::ZERO;
            if bad {
                tau = [S::ZERO; 2];
            }
            let m = cfg.modes().update(
                &mut st.modes,
                &WristModeInput {
                    desired: [t.pose.delta, t.pose.gamma],
                    desired_rate: t.rate,
                    interaction: tau,
                    request: t.request,
                },
            );
            let p = st.motors;
            let (n1, n3, pose, sat, straight) =
                self.inverse::<K>(m.reference[0], m.reference[1], p[0]);
            st.gamma = pose.gamma;
            let (n1, n3) = if straight {
                (p[0], p[0].neg())
            } else {
                (n1, n3)
            };
            // IkState: nearest multiple of 2π to the previous value.
            let near = |p: S, n: S| {
                let tp = S::PI.add(S::PI);
                let mut diff = n.sub(p);
                let turns = S::from_f64(libm::round(diff.div(tp).to_f64()));
                diff = diff.sub(turns.mul(tp));
                let (s, c) = K::sin_cos(diff);
                p.add(K::atan2(s, c))
            };
            let now = [near(p[0], n1), near(p[1], n3)];
            let mut rate = [S::ZERO; 2];
            let mut acc = [S::ZERO; 2];
            for i in 0..2 {
                rate[i] = now[i].sub(p[i]).mul_coef(&self.inv_t);
                acc[i] = rate[i].sub(st.rate[i]).mul_coef(&self.inv_t_rate);
            }
            st.motors = now;
            st.rate = rate;
            let j = self.jacobian::<K>(now[0], now[1]);
            let jt = [
                j[0][0].mul(tau[0]).add(j[1][0].mul(tau[1])).neg(),
                j[0][1].mul(tau[0]).add(j[1][1].mul(tau[1])).neg(),
            ];
            let pos = [r.motors.theta1, r.motors.theta3];
            let sample = |i: usize| WristJointSample {
                desired_position: now[i],
                desired_velocity: rate[i],
                desired_acceleration: acc[i],
                position: pos[i],
                velocity: r.motor_velocity[i],
                interaction_torque: jt[i],
            };
            let laws = cfg.active().update(&mut st.laws, &[sample(0), sample(1)]);
            let torque_saturated = (laws[0].saturated && !laws[0].invalid_input)
                || (laws[1].saturated && !laws[1].invalid_input);
            WristOutput {
                motor_torque: [laws[0].torque, laws[1].torque],
                mode: m.mode,
                switched: m.switched,
                interaction: tau,
                joint_torque: jt,
                reference: pose,
                motor_reference: MotorAngles {
                    theta1: now[0],
                    theta3: now[1],
                },
                motor_reference_rate: rate,
                saturated: m.saturated || sat || torque_saturated,
                reference_saturated: m.saturated || sat,
                torque_saturated,
                singular: false,
                invalid_input: bad
                    || m.invalid_input
                    || laws[0].invalid_input
                    || laws[1].invalid_input,
                laws,
            }
        }
    }
}
