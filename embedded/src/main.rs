//! Firmware-like build of mrr-control's run-time steps, one
//! `#[no_mangle] extern "C"` entry per measured call.
//!
//! Each entry reads its arguments from the static [`IO`] buffer (volatile,
//! so nothing is constant-folded), runs one step or kernel exactly as a
//! user's firmware would call it (inlined, LTO, the target's CPU), and
//! writes the result words back to [`IO`]. `count.py` loads the ELF into a
//! CPU emulator, fills `IO.input`, calls an entry and counts the executed
//! instructions.
//!
//! Adding a step: one `entry!` line below (plus, for a stateful step, a
//! `prepare` entry that sets its state outside the counted call), and one
//! row in `count.py`'s `all_steps()`.
//!
//! On the host (`cargo run`), the same file builds a small program that
//! evaluates the batch entry for the bit-identity check of `count.py`.
#![cfg_attr(target_os = "none", no_std, no_main)]
// Entries reach the step states through `static mut` (single-threaded).
#![allow(static_mut_refs)]

mod io;
mod reference;

use fixed::types::I16F16;
use io::{arg, put, Args};
use mrr_control::estimation::torque::{
    TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings, TorqueEstimatorState,
};
use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::scalar::kernels::{f32 as kf, i16f16 as kx};
use reference::{Cordic, Libm, RefEstimator, RefState};

pub use io::IO;

/// One measured entry: `entry!(name(arg: Type, ...) => expression);`
/// reads the arguments from `IO.input`, evaluates the expression and stores
/// its words in `IO.output`.
macro_rules! entry {
    ($name:ident($($a:ident : $t:ty),*) => $e:expr) => {
        #[no_mangle]
        pub extern "C" fn $name() {
            let mut _args = Args::new();
            $(let $a: $t = arg(&mut _args);)*
            put($e);
        }
        keep!($name);
    };
}

/// Keeps an entry in the linked image (the linker would drop a function
/// that nothing in the firmware calls): its address goes to `.entries`,
/// which `link.x` keeps.
macro_rules! keep {
    ($name:ident) => {
        const _: () = {
            #[used]
            #[link_section = ".entries"]
            static KEEP: extern "C" fn() = $name;
        };
    };
}

// ---------------------------------------------------------------------------
// Call overhead: the load of one argument and the store of one result that
// every entry below pays as well.
entry!(io_overhead(x: u32) => x);

// ---------------------------------------------------------------------------
// f32 kernels (Cortex-M4F) and the libm functions they replace.
entry!(k_atan_f32(x: f32) => kf::atan(x));
entry!(k_tan_f32(x: f32) => kf::tan(x));
entry!(k_sin_f32(x: f32) => kf::sin(x));
entry!(k_cos_f32(x: f32) => kf::cos(x));
entry!(k_sin_cos_f32(x: f32) => kf::sin_cos(x));
entry!(k_atan2_f32(y: f32, x: f32) => kf::atan2(y, x));
entry!(k_exp_f32(x: f32) => kf::exp(x));
entry!(k_exp_neg_abs_f32(x: f32) => kf::exp_neg_abs(x));
entry!(k_sqrt_f32(x: f32) => kf::sqrt(x));
entry!(k_acos_f32(x: f32) => kf::acos(x));

entry!(libm_atan_f32(x: f32) => libm::atanf(x));
entry!(libm_tan_f32(x: f32) => libm::tanf(x));
entry!(libm_sin_f32(x: f32) => libm::sinf(x));
entry!(libm_cos_f32(x: f32) => libm::cosf(x));
entry!(libm_sin_cos_f32(x: f32) => libm::sincosf(x));
entry!(libm_atan2_f32(y: f32, x: f32) => libm::atan2f(y, x));
entry!(libm_exp_f32(x: f32) => libm::expf(x));
entry!(libm_exp_neg_abs_f32(x: f32) => libm::expf(-libm::fabsf(x)));
entry!(libm_sqrt_f32(x: f32) => libm::sqrtf(x));
entry!(libm_acos_f32(x: f32) => libm::acosf(x));

// ---------------------------------------------------------------------------
// I16F16 kernels (Cortex-M0+) and the `cordic` crate's functions.
entry!(k_atan_i16f16(x: I16F16) => kx::atan(x));
entry!(k_tan_i16f16(x: I16F16) => kx::tan(x));
entry!(k_sin_i16f16(x: I16F16) => kx::sin(x));
entry!(k_cos_i16f16(x: I16F16) => kx::cos(x));
entry!(k_sin_cos_i16f16(x: I16F16) => kx::sin_cos(x));
entry!(k_atan2_i16f16(y: I16F16, x: I16F16) => kx::atan2(y, x));
entry!(k_exp_i16f16(x: I16F16) => kx::exp(x));
entry!(k_sqrt_i16f16(x: I16F16) => kx::sqrt(x));
entry!(k_acos_i16f16(x: I16F16) => kx::acos(x));

entry!(cordic_atan_i16f16(x: I16F16) => cordic::atan(x));
entry!(cordic_tan_i16f16(x: I16F16) => cordic::tan(x));
entry!(cordic_sin_i16f16(x: I16F16) => cordic::sin(x));
entry!(cordic_cos_i16f16(x: I16F16) => cordic::cos(x));
entry!(cordic_sin_cos_i16f16(x: I16F16) => cordic::sin_cos(x));
entry!(cordic_atan2_i16f16(y: I16F16, x: I16F16) => cordic::atan2(y, x));
entry!(cordic_exp_i16f16(x: I16F16) => cordic::exp(x));
entry!(cordic_sqrt_i16f16(x: I16F16) => cordic::sqrt(x));
entry!(cordic_acos_i16f16(x: I16F16) => cordic::acos(x));

// The binary-angle cosine of the kinematic error (eq. 3.7), against the
// radian cosine of the same angle (the conversion to radians included).
entry!(k_cos_turn_f32(t: u32) => kf::cos_turn(t));
entry!(libm_cos_turn_f32(t: u32) => libm::cosf(t as i32 as f32 * 1.462_918_1e-9));
entry!(k_cos_turn_i16f16(t: u32) => kx::cos_turn(t));
entry!(cordic_cos_turn_i16f16(t: u32) => cordic::cos(I16F16::from_bits(((t as i32 as i64 * 411_775) >> 32) as i32)));

// The `⌊a·b/2³²⌋` building block of the I16F16 kernels, as written in
// `src/scalar/fixed.rs` (four 16×16 products, two add-with-carry steps),
// against the plain 64-bit product (`__aeabi_lmul` on Armv6-M).
entry!(mulhi_split_u32(a: u32, b: u32) => reference::mulhi_split(a, b));
entry!(mulhi_u64_u32(a: u32, b: u32) => ((a as u64 * b as u64) >> 32) as u32);

// ---------------------------------------------------------------------------
// Joint-torque estimation, eq. (3.8)–(3.10): the library step and the same
// formula with libm (f32) or cordic (I16F16) kernels. Arguments: link count,
// motor counter, motor torque (stored units); `prepare_*` sets the state.
entry!(est_f32(l: u32, m: u32, t: f32) => unsafe { steps::EST_F32.assume_init_ref().update(steps::EST_ST.assume_init_mut(), l, m, t) });
entry!(est_i16f16(l: u32, m: u32, t: I16F16) => unsafe { steps::EST_X.assume_init_ref().update(steps::EST_ST.assume_init_mut(), l, m, t) });
entry!(est_libm_f32(l: u32, m: u32, t: f32) => unsafe { steps::REF_F32.assume_init_ref().update::<Libm>(steps::REF_ST.assume_init_mut(), l, m, t) });
entry!(est_cordic_i16f16(l: u32, m: u32, t: I16F16) => unsafe { steps::REF_X.assume_init_ref().update::<Cordic>(steps::REF_ST.assume_init_mut(), l, m, t) });
entry!(prepare_est(pos_lo: u32, pos_hi: u32, counter: u32) => unsafe { steps::prepare_est(pos_lo, pos_hi, counter) });

// The per-joint control step, the library's `JointConfig::update`: torque
// estimate (eq. 3.8–3.10) → joint torque `τ̂_t = −torque` (errata E2.10),
// motor position and speed from the counts → mode manager (robust adaptive
// law eq. 4.19 with adaptation, passive law eq. 4.32, switching, collision
// reaction). Arguments: link count, motor counter (ch. 4 sense, `q_m =
// N q_l`), desired link position, speed and acceleration, expected joint
// torque (stored units). The motor torque `τ_w` of eq. (3.9) is the
// previous command; `prepare_joint` sets the joint state (motor position
// and counter) and drives the mode state into one of the scenarios of
// `joint::warm_up`. The reference variants are the same tick written from
// the components with the estimator's `sin_cos`, `exp`, `tan` by libm /
// cordic.
entry!(joint_f32(l: u32, m: u32, qd: f32, vd: f32, ad: f32, te: f32) => unsafe { joint::step_f32::<{ joint::KE }, { joint::STOP }>(l, m, [qd, vd, ad, te]) });
entry!(joint_i16f16(l: u32, m: u32, qd: I16F16, vd: I16F16, ad: I16F16, te: I16F16) => unsafe { joint::step_x::<{ joint::KE }, { joint::STOP }>(l, m, [qd, vd, ad, te]) });
// The entries below are built only with the `variants` feature, into a
// second image: each added caller of a library function changes LLVM's
// inlining decisions, and the image above must stay the firmware a user of
// the default joint configuration builds. In the second image functions
// shared by several of these entries are called rather than inlined, so
// its counts are, if anything, high. The stand-alone laws and
// `update_radians` (feature `laws`) are a third image, so that no joint
// configuration shares its law with a stand-alone caller.
// The other configurations a user can choose: collision reaction Passive,
// and no kinematic-error model (same readings, same prepare).
#[cfg(feature = "variants")]
entry!(joint_passive_f32(l: u32, m: u32, qd: f32, vd: f32, ad: f32, te: f32) => unsafe { joint::step_f32::<{ joint::KE }, { joint::PASSIVE }>(l, m, [qd, vd, ad, te]) });
#[cfg(feature = "variants")]
entry!(joint_noke_f32(l: u32, m: u32, qd: f32, vd: f32, ad: f32, te: f32) => unsafe { joint::step_f32::<{ joint::NO_KE }, { joint::STOP }>(l, m, [qd, vd, ad, te]) });
#[cfg(feature = "variants")]
entry!(joint_passive_noke_f32(l: u32, m: u32, qd: f32, vd: f32, ad: f32, te: f32) => unsafe { joint::step_f32::<{ joint::NO_KE }, { joint::PASSIVE }>(l, m, [qd, vd, ad, te]) });
#[cfg(feature = "variants")]
entry!(joint_passive_i16f16(l: u32, m: u32, qd: I16F16, vd: I16F16, ad: I16F16, te: I16F16) => unsafe { joint::step_x::<{ joint::KE }, { joint::PASSIVE }>(l, m, [qd, vd, ad, te]) });
#[cfg(feature = "variants")]
entry!(joint_noke_i16f16(l: u32, m: u32, qd: I16F16, vd: I16F16, ad: I16F16, te: I16F16) => unsafe { joint::step_x::<{ joint::NO_KE }, { joint::STOP }>(l, m, [qd, vd, ad, te]) });
#[cfg(feature = "variants")]
entry!(joint_passive_noke_i16f16(l: u32, m: u32, qd: I16F16, vd: I16F16, ad: I16F16, te: I16F16) => unsafe { joint::step_x::<{ joint::NO_KE }, { joint::PASSIVE }>(l, m, [qd, vd, ad, te]) });

// The stand-alone laws (arguments: desired position, speed, acceleration,
// measured position, speed, joint torque; `prepare_joint` sets the active
// law's state): the robust adaptive law with adaptation, eq. (4.19), and
// the passive law, eq. (4.32).
#[cfg(feature = "laws")]
entry!(active_f32(qd: f32, vd: f32, ad: f32, q: f32, v: f32, tau: f32) => unsafe { joint::active_f32([qd, vd, ad, q, v, tau]) });
#[cfg(feature = "laws")]
entry!(active_i16f16(qd: I16F16, vd: I16F16, ad: I16F16, q: I16F16, v: I16F16, tau: I16F16) => unsafe { joint::active_x([qd, vd, ad, q, v, tau]) });
#[cfg(feature = "laws")]
entry!(passive_f32(qd: f32, vd: f32, ad: f32, q: f32, v: f32, tau: f32) => unsafe { joint::passive_f32([qd, vd, ad, q, v, tau]) });
#[cfg(feature = "laws")]
entry!(passive_i16f16(qd: I16F16, vd: I16F16, ad: I16F16, q: I16F16, v: I16F16, tau: I16F16) => unsafe { joint::passive_x([qd, vd, ad, q, v, tau]) });

// The estimate from angles (`update_radians`, eq. 2.13 from radians; with
// the kinematic-error model): link angle, motor angle (stored angle units),
// motor torque.
#[cfg(feature = "laws")]
entry!(est_radians_f32(l: f32, m: f32, t: f32) => unsafe { steps::EST_F32.assume_init_ref().update_radians(l, m, t) });
#[cfg(feature = "laws")]
entry!(est_radians_i16f16(l: I16F16, m: I16F16, t: I16F16) => unsafe { steps::EST_X.assume_init_ref().update_radians(l, m, t) });

// Hook for the wrist step (ch. 5-6): one `entry!` line per backend here,
// its configuration built in `init`, and a `Step` row in count.py's
// `wrist_steps()`.
// The wrist step (`WristStepConfig::update`, Table 6.1 wrist): arguments
// the six gauge signals (V) and the measured θ1, θ3 (rad); `prepare_wrist`
// (scenario word, seed, then δ, γ, δ̇, γ̇ of the target and θ̇1, θ̇3 in the
// backend's words) stores the rest of the tick's input and sets the state.
// The libm / cordic entries are the same tick written from the components
// (src/wrist.rs, `reference`). Built with the `wrist` feature into a third
// image, so that the default image's joint counts do not move.
#[cfg(feature = "wrist")]
entry!(wrist_f32(g0: f32, g1: f32, g2: f32, g3: f32, g4: f32, g5: f32, t1: f32, t3: f32) => unsafe { wrist::step_f32([g0, g1, g2, g3, g4, g5], [t1, t3]) });
#[cfg(feature = "wrist")]
entry!(wrist_i16f16(g0: I16F16, g1: I16F16, g2: I16F16, g3: I16F16, g4: I16F16, g5: I16F16, t1: I16F16, t3: I16F16) => unsafe { wrist::step_x([g0, g1, g2, g3, g4, g5], [t1, t3]) });
#[cfg(feature = "wrist")]
entry!(wrist_libm_f32(g0: f32, g1: f32, g2: f32, g3: f32, g4: f32, g5: f32, t1: f32, t3: f32) => unsafe { wrist::step_libm_f32([g0, g1, g2, g3, g4, g5], [t1, t3]) });
#[cfg(feature = "wrist")]
entry!(wrist_cordic_i16f16(g0: I16F16, g1: I16F16, g2: I16F16, g3: I16F16, g4: I16F16, g5: I16F16, t1: I16F16, t3: I16F16) => unsafe { wrist::step_cordic_x([g0, g1, g2, g3, g4, g5], [t1, t3]) });
#[cfg(feature = "wrist")]
entry!(prepare_wrist(scenario: u32, seed: u32, w0: u32, w1: u32, w2: u32, w3: u32, w4: u32, w5: u32) => unsafe { wrist::prepare(scenario, seed, [w0, w1, w2, w3, w4, w5]) });
entry!(joint_libm_f32(l: u32, m: u32, qd: f32, vd: f32, ad: f32, te: f32) => unsafe { joint::step_libm_f32(l, m, [qd, vd, ad, te]) });
entry!(joint_cordic_i16f16(l: u32, m: u32, qd: I16F16, vd: I16F16, ad: I16F16, te: I16F16) => unsafe { joint::step_cordic_x(l, m, [qd, vd, ad, te]) });
entry!(prepare_joint(pos_lo: u32, pos_hi: u32, counter: u32, scenario: u32, seed: u32) => unsafe { joint::prepare(pos_lo, pos_hi, counter, scenario, seed) });

mod joint;
#[cfg(feature = "wrist")]
mod wrist;

/// Configurations and states of the stateful steps. They are built once by
/// [`init`] (not counted), as a firmware builds them at start-up.
mod steps {
    use super::*;
    use core::mem::MaybeUninit;

    /// SHD-17-100 with the Table 3.2 kinematic error, a 17-bit link encoder
    /// and a 2000-count motor encoder, ±60 N·m output limit.
    /// `with_kinematic_error: false`: the same drive and encoders without
    /// the model.
    pub fn params(with_kinematic_error: bool) -> TorqueEstimatorParams {
        let drive = match CatalogueData::SHD_17_100.identify() {
            Ok(d) => d,
            Err(_) => crate::firmware_panic(),
        };
        match TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: if with_kinematic_error {
                Some(KinematicErrorModel::table_3_2())
            } else {
                None
            },
            link_counts_per_rev: 1 << 17,
            motor_counts_per_rev: 2000,
            max_torque: 60.0,
        }) {
            Ok(p) => p,
            Err(_) => crate::firmware_panic(),
        }
    }

    pub static mut EST_F32: MaybeUninit<TorqueEstimatorConfig<f32>> = MaybeUninit::uninit();
    pub static mut EST_X: MaybeUninit<TorqueEstimatorConfig<I16F16>> = MaybeUninit::uninit();
    /// One state for both backends (the f32 and I16F16 configurations
    /// share the encoders, so `state` gives the same value).
    pub static mut EST_ST: MaybeUninit<TorqueEstimatorState> = MaybeUninit::uninit();
    pub static mut REF_F32: MaybeUninit<RefEstimator<f32>> = MaybeUninit::uninit();
    pub static mut REF_X: MaybeUninit<RefEstimator<I16F16>> = MaybeUninit::uninit();
    pub static mut REF_ST: MaybeUninit<RefState> = MaybeUninit::uninit();

    pub unsafe fn init() {
        let p = params(true);
        EST_F32.write(TorqueEstimatorConfig::new(&p));
        EST_X.write(TorqueEstimatorConfig::new(&p));
        REF_F32.write(RefEstimator::new(&p));
        REF_X.write(RefEstimator::new(&p));
        crate::joint::init(&p, &params(false));
        #[cfg(feature = "wrist")]
        crate::wrist::init();
    }

    /// Motor position (i64 from two words) and counter for every estimator
    /// state.
    pub unsafe fn prepare_est(lo: u32, hi: u32, counter: u32) -> u32 {
        let pos = ((hi as u64) << 32 | lo as u64) as i64;
        EST_ST.write(EST_F32.assume_init_ref().state(pos, counter));
        REF_ST.write(REF_F32.assume_init_ref().state(pos, counter));
        0
    }
}

/// Builds every configuration once (not counted).
#[no_mangle]
pub extern "C" fn init() {
    // SAFETY: single-threaded firmware; nothing else runs.
    unsafe { steps::init() }
}

// ---------------------------------------------------------------------------
// Batch evaluation for the bit-identity check: `n` cases of two input words
// in `BATCH`, each replaced by two result words.

/// Case buffer of [`batch_i16f16`]: two words in, two words out per case.
#[no_mangle]
pub static mut BATCH: [u32; 2 * BATCH_CASES] = [0; 2 * BATCH_CASES];
/// Largest number of cases per batch call.
pub const BATCH_CASES: usize = 4096;

/// Kernel `id` (the order of `count.py`'s `BATCH_KERNELS`) over the first
/// `n` cases of [`BATCH`]; arguments in `IO.input[0..2]`.
#[no_mangle]
pub extern "C" fn batch_i16f16() {
    let mut a = Args::new();
    let id: u32 = arg(&mut a);
    let n: u32 = arg(&mut a);
    let n = (n as usize).min(BATCH_CASES);
    let x = |w: u32| I16F16::from_bits(w as i32);
    let b = |v: I16F16| v.to_bits() as u32;
    for i in 0..n {
        // SAFETY: single-threaded; index below the buffer length.
        let (w0, w1) = unsafe {
            let p = (&raw mut BATCH).cast::<u32>().add(2 * i);
            (p.read_volatile(), p.add(1).read_volatile())
        };
        let (r0, r1) = match id {
            0 => (b(kx::atan(x(w0))), 0),
            1 => (b(kx::tan(x(w0))), 0),
            2 => (b(kx::sin(x(w0))), 0),
            3 => (b(kx::cos(x(w0))), 0),
            4 => {
                let (s, c) = kx::sin_cos(x(w0));
                (b(s), b(c))
            }
            5 => (b(kx::atan2(x(w0), x(w1))), 0),
            6 => (b(kx::exp(x(w0))), 0),
            7 => (b(kx::sqrt(x(w0))), 0),
            8 => (b(kx::acos(x(w0))), 0),
            _ => (0, 0),
        };
        // SAFETY: as above.
        unsafe {
            let p = (&raw mut BATCH).cast::<u32>().add(2 * i);
            p.write_volatile(r0);
            p.add(1).write_volatile(r1);
        }
    }
    put(0u32);
}
keep!(batch_i16f16);
keep!(init);

// ---------------------------------------------------------------------------
// Target support: vector table, reset, panic.

/// Where a panic ends; the counter stops here and reports the input.
#[no_mangle]
#[inline(never)]
pub extern "C" fn firmware_panic() -> ! {
    loop {
        core::hint::spin_loop();
    }
}

#[cfg(target_os = "none")]
mod target {
    use super::*;

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        firmware_panic()
    }

    /// Initial stack pointer (top of the 256 KiB RAM) and exception vectors.
    #[repr(C)]
    pub struct VectorTable {
        sp: u32,
        handlers: [unsafe extern "C" fn() -> !; 15],
    }

    #[link_section = ".vector_table"]
    #[no_mangle]
    #[used]
    pub static VECTOR_TABLE: VectorTable = VectorTable {
        sp: 0x2004_0000,
        handlers: [
            reset_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
            fault_handler,
        ],
    };

    /// Any exception: exit the emulator with status 1.
    #[no_mangle]
    pub unsafe extern "C" fn fault_handler() -> ! {
        semihosting_exit(1)
    }

    /// Reset (QEMU only; the unicorn counter calls the entries directly):
    /// enable the FPU, build the configurations, run the cross-check
    /// sequence and exit through semihosting.
    #[no_mangle]
    pub unsafe extern "C" fn reset_handler() -> ! {
        #[cfg(target_abi = "eabihf")]
        {
            // CPACR: full access to CP10/CP11.
            let cpacr = 0xE000_ED88 as *mut u32;
            cpacr.write_volatile(cpacr.read_volatile() | (0xF << 20));
            core::arch::asm!("dsb", "isb");
        }
        init();
        crosscheck();
        semihosting_exit(0)
    }

    /// The instruction sequence both emulators run from `crosscheck_start`
    /// to `crosscheck_end` (see `count.py --qemu`): every argument vector of
    /// `CROSSCHECK` through its entry.
    #[no_mangle]
    #[inline(never)]
    pub extern "C" fn crosscheck() {
        crosscheck_start();
        for case in CROSSCHECK.iter() {
            // SAFETY: single-threaded.
            unsafe {
                let p = (&raw mut IO.input).cast::<u32>();
                for (i, w) in case.1.iter().enumerate() {
                    p.add(i).write_volatile(*w);
                }
            }
            (case.0)();
        }
        crosscheck_end();
    }

    /// Markers of the measured span (distinct bodies, so the linker
    /// cannot fold them into one function).
    #[no_mangle]
    #[inline(never)]
    pub extern "C" fn crosscheck_start() {
        // SAFETY: single-threaded.
        unsafe {
            (&raw mut IO.output)
                .cast::<u32>()
                .write_volatile(0x5354_4152)
        };
    }
    #[no_mangle]
    #[inline(never)]
    pub extern "C" fn crosscheck_end() {
        // SAFETY: single-threaded.
        unsafe {
            (&raw mut IO.output)
                .cast::<u32>()
                .write_volatile(0x454e_4421)
        };
    }

    type Case = (extern "C" fn(), [u32; 8]);
    /// Pads an argument list to the eight words of a case.
    const fn w<const N: usize>(a: [u32; N]) -> [u32; 8] {
        let mut out = [0; 8];
        let mut i = 0;
        while i < N {
            out[i] = a[i];
            i += 1;
        }
        out
    }
    /// IT-heavy f32 kernels (M4F) and the I16F16 kernels (M0+) at inputs
    /// that take different branches, then the joint step on both cores
    /// (its state set by `prepare_joint`, scenario 1 with only the
    /// backend's Stop state warmed up; an in-range reading and a link count
    /// out of range with a counter jump).
    #[cfg(target_abi = "eabihf")]
    static CROSSCHECK: [Case; 16] = [
        (k_atan_f32, w([0x3f00_0000, 0, 0])),
        (k_atan_f32, w([0xc2c8_0000, 0, 0])),
        (k_tan_f32, w([0x3fc9_0fda, 0, 0])),
        (k_tan_f32, w([0xbf40_0000, 0, 0])),
        (k_sin_cos_f32, w([0x4479_8000, 0, 0])),
        (k_atan2_f32, w([0xbf80_0000, 0xc000_0000, 0])),
        (k_exp_f32, w([0xc2c0_0000, 0, 0])),
        (k_sqrt_f32, w([0x0000_0003, 0, 0])),
        (k_acos_f32, w([0xbf7f_0000, 0, 0])),
        (libm_tan_f32, w([0x4479_8000, 0, 0])),
        (est_f32, w([1000, 5, 0x3e4c_cccd])),
        (est_f32, w([0xffff_ffff, 0x7fff_ffff, 0xbf80_0000])),
        (prepare_joint, w([0xffff_fc18, 0xffff_ffff, 5, 0x101, 7])),
        (
            joint_f32,
            [
                1000,
                5,
                0x3f80_0000,
                0x4000_0000,
                0x42c8_0000,
                0x3f80_20c5,
                0x4020_0000,
                0x3f00_0000,
            ],
        ),
        (prepare_joint, w([0x3b9a_c9ff, 0, 0x1234_5678, 0x103, 99])),
        (
            joint_f32,
            [
                0xffff_ffff,
                0x7fff_ffff,
                0xc1f0_0000,
                0x4248_0000,
                0x46ea_6000,
                0xc1ef_ffff,
                0x4120_0000,
                0xc0a0_0000,
            ],
        ),
    ];
    #[cfg(not(target_abi = "eabihf"))]
    static CROSSCHECK: [Case; 12] = [
        (k_atan_i16f16, w([0x0001_8000, 0, 0])),
        (k_tan_i16f16, w([0x0001_9000, 0, 0])),
        (k_sin_cos_i16f16, w([0x0100_0000, 0, 0])),
        (k_atan2_i16f16, w([0xffff_0000, 0xfffe_0000, 0])),
        (k_exp_i16f16, w([0xfffc_0000, 0, 0])),
        (k_sqrt_i16f16, w([0x0000_0003, 0, 0])),
        (est_i16f16, w([1000, 5, 0x0000_c000])),
        (est_i16f16, w([0xffff_ffff, 0x7fff_ffff, 0xfc18_0000])),
        (prepare_joint, w([0xffff_fc18, 0xffff_ffff, 5, 0x401, 7])),
        (
            joint_i16f16,
            [
                1000,
                5,
                0x0001_0000,
                0x0002_0000,
                0x0064_0000,
                0x0001_0042,
                0x0002_8000,
                0x0000_8000,
            ],
        ),
        (prepare_joint, w([0x3b9a_c9ff, 0, 0x1234_5678, 0x403, 99])),
        (
            joint_i16f16,
            [
                0xffff_ffff,
                0x7fff_ffff,
                0xffe2_0000,
                0x0032_0000,
                0x7530_0000,
                0xffe2_0001,
                0x000a_0000,
                0xfffb_0000,
            ],
        ),
    ];

    /// Semihosting `SYS_EXIT` (`ADP_Stopped_ApplicationExit` for status 0).
    unsafe fn semihosting_exit(status: u32) -> ! {
        let reason: u32 = if status == 0 { 0x20026 } else { 0x20024 };
        core::arch::asm!("bkpt #0xab", in("r0") 0x18u32, in("r1") reason);
        firmware_panic()
    }
}

/// Host program: reads `id n` and `n` lines of two hexadecimal words from
/// standard input, runs [`batch_i16f16`] and prints the result words.
#[cfg(not(target_os = "none"))]
fn main() {
    use std::io::BufRead;
    let stdin = std::io::stdin();
    let mut lines = stdin.lock().lines();
    let head = lines.next().unwrap().unwrap();
    let mut it = head.split_whitespace().map(|s| s.parse::<u32>().unwrap());
    let (id, n) = (it.next().unwrap(), it.next().unwrap());
    for i in 0..n as usize {
        let l = lines.next().unwrap().unwrap();
        let mut w = l
            .split_whitespace()
            .map(|s| u32::from_str_radix(s, 16).unwrap());
        // SAFETY: single-threaded program.
        unsafe {
            BATCH[2 * i] = w.next().unwrap();
            BATCH[2 * i + 1] = w.next().unwrap();
        }
    }
    // SAFETY: as above.
    unsafe {
        IO.input[0] = id;
        IO.input[1] = n;
    }
    batch_i16f16();
    for i in 0..n as usize {
        // SAFETY: as above.
        unsafe { println!("{:08x} {:08x}", BATCH[2 * i], BATCH[2 * i + 1]) };
    }
}
