//! One mrr-control joint on a Cortex-M4F, in the shape of a servo
//! firmware: the configuration is built once at reset, a timer interrupt
//! (SysTick) marks each 4 ms tick, and the main loop runs one
//! [`JointConfig::update`] per tick — read the encoders, step the joint,
//! write the motor torque.
//!
//! No HAL: the encoder and motor "registers" are the atomics below. A board
//! replaces [`read_encoders`] and [`write_motor_torque`] with its timer in
//! encoder mode, its absolute-encoder interface and its current loop.
//!
//! Build: `cargo build --release --target thumbv7em-none-eabihf` in this
//! folder (its own workspace).
#![no_std]
#![no_main]

use core::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use mrr_control::joint::{JointConfig, JointParams, JointReadings, JointTarget};
use mrr_control::Scalar;

/// The servo tick, s (the Table 4.1 sample period).
const TICK: f32 = 0.004;
/// Core clock, Hz (for the SysTick reload).
const CORE_CLOCK_HZ: u32 = 168_000_000;

/// Link absolute encoder count (`[0, 2¹⁷)`), as an interface would latch it.
static LINK_COUNT: AtomicU32 = AtomicU32::new(0);
/// Free-running motor counter (quadrature-decoded), increasing as the
/// motor drives the link forward.
static MOTOR_COUNTER: AtomicU32 = AtomicU32::new(0);
/// The motor torque command in N·m, as `f32` bits, for the current loop.
static MOTOR_TORQUE: AtomicU32 = AtomicU32::new(0);
/// Set by the timer interrupt, cleared by the loop.
static TICK_DUE: AtomicBool = AtomicBool::new(false);
/// Set when the joint flags an impossible reading (a fault LED, say).
static FAULT: AtomicBool = AtomicBool::new(false);

fn read_encoders() -> (u32, u32) {
    (
        LINK_COUNT.load(Ordering::Relaxed),
        MOTOR_COUNTER.load(Ordering::Relaxed),
    )
}

fn write_motor_torque(newton_metres: f32) {
    MOTOR_TORQUE.store(newton_metres.to_bits(), Ordering::Relaxed);
}

/// Stop here on a configuration error or a panic: motor torque 0.
fn halt() -> ! {
    write_motor_torque(0.0);
    loop {
        core::hint::spin_loop();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    halt()
}

/// The firmware after reset.
fn main() -> ! {
    // Built once, in f64, validated: a bad parameter stops here, never in
    // the loop.
    let params = match JointParams::table_4_1() {
        Ok(p) => p,
        Err(_) => halt(),
    };
    let joint = JointConfig::<f32>::new(&params);
    let (link, motor) = read_encoders();
    let mut state = joint.state(link, motor);
    start_systick(CORE_CLOCK_HZ / 250);
    let mut time = 0.0f32;
    loop {
        if !TICK_DUE.swap(false, Ordering::Acquire) {
            // Sleep until the next interrupt.
            // SAFETY: `wfi` only waits for an interrupt.
            unsafe { core::arch::asm!("wfi") };
            continue;
        }
        // A slow swing of ±0.2 rad at 0.25 Hz, link side, SI.
        let w = 2.0 * core::f32::consts::PI * 0.25;
        let (s, c) = Scalar::sin_cos(w * time);
        let target = JointTarget {
            position: 0.2 * s,
            velocity: 0.2 * w * c,
            acceleration: -0.2 * w * w * s,
            ..JointTarget::default()
        };
        let (link, motor) = read_encoders();
        let out = joint.update(&mut state, &JointReadings::counts(link, motor), &target);
        write_motor_torque(out.motor_torque);
        if out.invalid_input {
            FAULT.store(true, Ordering::Relaxed);
        }
        time += TICK;
        if time > 4.0 {
            time -= 4.0;
        }
    }
}

/// SysTick: the core clock, `reload` cycles per interrupt.
fn start_systick(reload: u32) {
    const SYST_CSR: *mut u32 = 0xE000_E010 as *mut u32;
    const SYST_RVR: *mut u32 = 0xE000_E014 as *mut u32;
    const SYST_CVR: *mut u32 = 0xE000_E018 as *mut u32;
    // SAFETY: the SysTick registers of every Cortex-M core.
    unsafe {
        SYST_RVR.write_volatile(reload - 1);
        SYST_CVR.write_volatile(0);
        // Processor clock, interrupt enabled, counter enabled.
        SYST_CSR.write_volatile(0b111);
    }
}

/// The timer interrupt: mark a tick due.
extern "C" fn systick_handler() {
    TICK_DUE.store(true, Ordering::Release);
}

extern "C" fn default_handler() {
    halt()
}

extern "C" {
    static mut _sbss: u32;
    static mut _ebss: u32;
    static mut _sdata: u32;
    static mut _edata: u32;
    static _sidata: u32;
}

/// Reset: enable the FPU, initialize RAM, run `main`.
#[no_mangle]
unsafe extern "C" fn reset_handler() -> ! {
    // CPACR: full access to CP10/CP11 (the FPU) before any float code.
    let cpacr = 0xE000_ED88 as *mut u32;
    cpacr.write_volatile(cpacr.read_volatile() | (0xF << 20));
    core::arch::asm!("dsb", "isb");
    let mut p = &raw mut _sbss;
    while p < &raw mut _ebss {
        p.write_volatile(0);
        p = p.add(1);
    }
    let (mut d, mut s) = (&raw mut _sdata, &raw const _sidata);
    while d < &raw mut _edata {
        d.write_volatile(s.read());
        d = d.add(1);
        s = s.add(1);
    }
    main()
}

/// An exception vector.
#[derive(Clone, Copy)]
#[repr(C)]
union Vector {
    reset: unsafe extern "C" fn() -> !,
    handler: extern "C" fn(),
    reserved: usize,
}

/// Initial stack pointer (the top of RAM in `link.x`) and the exception
/// vectors 1–15; device interrupts would follow.
#[repr(C)]
pub struct VectorTable {
    stack_top: u32,
    vectors: [Vector; 15],
}

#[link_section = ".vector_table"]
#[no_mangle]
#[used]
pub static VECTOR_TABLE: VectorTable = VectorTable {
    stack_top: 0x2002_0000,
    vectors: {
        let mut v = [Vector {
            handler: default_handler,
        }; 15];
        v[0] = Vector {
            reset: reset_handler,
        };
        // 7–10 and 13 are reserved.
        let mut i = 6;
        while i < 10 {
            v[i] = Vector { reserved: 0 };
            i += 1;
        }
        v[12] = Vector { reserved: 0 };
        v[14] = Vector {
            handler: systick_handler,
        };
        v
    },
};
