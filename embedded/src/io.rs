//! The argument/result buffer every entry uses, and the conversions
//! between words and the step's types.

use fixed::types::I16F16;
use mrr_control::estimation::torque::TorqueEstimate;

/// Words in and out of one entry call. `count.py` finds it by symbol name.
#[repr(C)]
pub struct Io {
    /// Argument words, read in order by [`arg`].
    pub input: [u32; 8],
    /// Result words, written in order by [`put`].
    pub output: [u32; 8],
}

/// The buffer of the entries.
#[no_mangle]
pub static mut IO: Io = Io {
    input: [0; 8],
    output: [0; 8],
};

/// Position of the next argument word.
pub struct Args(usize);

impl Args {
    pub fn new() -> Self {
        Args(0)
    }
}

/// A type read from argument words.
pub trait Arg {
    fn from_word(w: u32) -> Self;
}
impl Arg for u32 {
    #[inline(always)]
    fn from_word(w: u32) -> Self {
        w
    }
}
impl Arg for f32 {
    #[inline(always)]
    fn from_word(w: u32) -> Self {
        f32::from_bits(w)
    }
}
impl Arg for I16F16 {
    #[inline(always)]
    fn from_word(w: u32) -> Self {
        I16F16::from_bits(w as i32)
    }
}

/// The next argument (volatile read: the value is unknown to the compiler).
#[inline(always)]
pub fn arg<T: Arg>(a: &mut Args) -> T {
    // SAFETY: single-threaded; index below 8 for every entry here.
    let w = unsafe { (&raw const IO.input).cast::<u32>().add(a.0).read_volatile() };
    a.0 += 1;
    T::from_word(w)
}

/// A result written as words.
pub trait Put {
    fn put(self, out: &mut Out);
}

/// Position of the next result word.
pub struct Out(usize);

impl Out {
    #[inline(always)]
    fn word(&mut self, w: u32) {
        // SAFETY: single-threaded; at most 8 result words per entry.
        unsafe {
            (&raw mut IO.output)
                .cast::<u32>()
                .add(self.0)
                .write_volatile(w)
        };
        self.0 += 1;
    }
}

impl Put for u32 {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        out.word(self)
    }
}
impl Put for bool {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        out.word(self as u32)
    }
}
impl Put for f32 {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        out.word(self.to_bits())
    }
}
impl Put for I16F16 {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        out.word(self.to_bits() as u32)
    }
}
impl<A: Put, B: Put> Put for (A, B) {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        self.0.put(out);
        self.1.put(out);
    }
}
impl<S: Put> Put for TorqueEstimate<S> {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        self.torque.put(out);
        self.flexspline_torsion.put(out);
        (self.saturated as u32 | (self.link_count_invalid as u32) << 1).put(out);
    }
}

/// Write a result to `IO.output`.
#[inline(always)]
pub fn put<T: Put>(v: T) {
    v.put(&mut Out(0))
}
impl<S: Put + Copy> Put for mrr_control::control::ModeOutput<S> {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        self.torque.put(out);
        self.interaction.put(out);
        (self.mode as u32
            | (self.switched as u32) << 2
            | (self.saturated as u32) << 3
            | (self.invalid_input as u32) << 4
            | (self.collision as u32) << 5)
            .put(out);
    }
}
impl<S: Put + Copy> Put for mrr_control::joint::JointOutput<S> {
    /// As the mode manager's output, with the joint's `invalid_input`
    /// (estimator or manager).
    #[inline(always)]
    fn put(self, out: &mut Out) {
        self.motor_torque.put(out);
        self.control.interaction.put(out);
        (self.mode as u32
            | (self.control.switched as u32) << 2
            | (self.control.saturated as u32) << 3
            | (self.invalid_input as u32) << 4
            | (self.control.collision as u32) << 5)
            .put(out);
    }
}
impl<S: Put + Copy> Put for mrr_control::control::ActiveOutput<S> {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        self.torque.put(out);
        self.law_torque.put(out);
        (self.saturated as u32 | (self.invalid_input as u32) << 1).put(out);
    }
}
impl<S: Put + Copy> Put for mrr_control::control::PassiveOutput<S> {
    #[inline(always)]
    fn put(self, out: &mut Out) {
        self.torque.put(out);
        self.law_torque.put(out);
        (self.saturated as u32 | (self.invalid_input as u32) << 1).put(out);
    }
}
