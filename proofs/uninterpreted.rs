//! Uninterpreted functions for Kani stubs (`cfg(kani)` only).
//!
//! A harness whose property holds for *every* deterministic function in
//! some place (oddness from `f(|x|)` with the sign applied afterwards;
//! `sin_cos` = `(sin, cos)` from the same cores selected the same way) can
//! replace that function by [`Memo::call`]: any value for a new argument,
//! the same value again for an argument seen before. Every pure function
//! is one of the behaviours this allows, so a harness that verifies with
//! the stub holds for the real function; what the stub removes is the
//! solver's work of proving two copies of the same arithmetic circuit
//! equal (two multipliers with the same inputs), which CBMC does not do
//! in 600 s. The value itself is unconstrained, so nothing about the
//! function's accuracy or range is assumed.

use core::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, AtomicUsize, Ordering::Relaxed};

/// A table of up to `N` argument/value pairs of one function, for a
/// `static` (atomics: the crate has no `unsafe`; Kani runs each harness as
/// one single-threaded program). A call beyond `N` new arguments fails the
/// harness (raise `N`).
pub struct Memo<const N: usize> {
    n: AtomicUsize,
    keys: [AtomicU64; N],
    vals: [AtomicU64; N],
}

impl<const N: usize> Memo<N> {
    pub const fn new() -> Self {
        Memo {
            n: AtomicUsize::new(0),
            keys: [const { AtomicU64::new(0) }; N],
            vals: [const { AtomicU64::new(0) }; N],
        }
    }

    /// The value at `key`: the recorded one, or a fresh `kani::any()`
    /// recorded for later calls.
    pub fn call(&self, key: u64) -> u64 {
        let n = self.n.load(Relaxed);
        let mut i = 0;
        while i < n {
            if self.keys[i].load(Relaxed) == key {
                return self.vals[i].load(Relaxed);
            }
            i += 1;
        }
        assert!(
            n < N,
            "uninterpreted function: more arguments than its table"
        );
        let v: u64 = kani::any();
        self.keys[n].store(key, Relaxed);
        self.vals[n].store(v, Relaxed);
        self.n.store(n + 1, Relaxed);
        v
    }
}

/// The operands and result of the first call of a stubbed two-operand
/// function (as bits), for a stub that relates a second call to the first
/// by a lemma (same divisor, dividends in order, ...).
pub struct FirstCall {
    seen: AtomicBool,
    a: AtomicU32,
    b: AtomicU32,
    q: AtomicU32,
}

impl FirstCall {
    pub const fn new() -> Self {
        FirstCall {
            seen: AtomicBool::new(false),
            a: AtomicU32::new(0),
            b: AtomicU32::new(0),
            q: AtomicU32::new(0),
        }
    }

    /// `None` on the first call (which is recorded), then the first
    /// call's `(a, b, q)`.
    pub fn first_or_record(&self, a: u32, b: u32, q: u32) -> Option<(u32, u32, u32)> {
        if self.seen.load(Relaxed) {
            return Some((
                self.a.load(Relaxed),
                self.b.load(Relaxed),
                self.q.load(Relaxed),
            ));
        }
        self.seen.store(true, Relaxed);
        self.a.store(a, Relaxed);
        self.b.store(b, Relaxed);
        self.q.store(q, Relaxed);
        None
    }

    /// The order lemma of a stubbed one-argument function on `u32`: the
    /// first call's `(arg, value)` is recorded; at the second, the value is
    /// assumed in the order of the arguments (`increasing`) or in the
    /// reverse order, and equal for an equal argument.
    pub fn assume_in_order_u32(&self, arg: u32, value: u32, increasing: bool) {
        if let Some((arg1, _, value1)) = self.first_or_record(arg, 0, value) {
            // postcondition of the stubbed function: the order lemma
            kani::assume(if arg == arg1 {
                value == value1
            } else if (arg > arg1) == increasing {
                value >= value1
            } else {
                value <= value1
            });
        }
    }

    /// [`assume_in_order_u32`](Self::assume_in_order_u32) for a function on
    /// `f32`, in the order of the values; the same value (bits) for the
    /// same argument (bits), and nothing assumed between `−0.0` and `+0.0`.
    pub fn assume_in_order_f32(&self, arg: f32, value: f32, increasing: bool) {
        if let Some((arg1, _, value1)) = self.first_or_record(arg.to_bits(), 0, value.to_bits()) {
            let (a1, v1) = (f32::from_bits(arg1), f32::from_bits(value1));
            // postcondition of the stubbed function: the order lemma
            kani::assume(if arg > a1 || arg < a1 {
                if (arg > a1) == increasing {
                    value >= v1
                } else {
                    value <= v1
                }
            } else {
                arg.to_bits() != arg1 || value.to_bits() == value1
            });
        }
    }
}
