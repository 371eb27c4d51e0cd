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

/// A table of up to `N` argument/value pairs of one function; a call
/// beyond `N` new arguments fails the harness (raise `N`).
pub struct Memo<const N: usize> {
    n: usize,
    keys: [u64; N],
    vals: [u64; N],
}

impl<const N: usize> Memo<N> {
    pub const fn new() -> Self {
        Memo {
            n: 0,
            keys: [0; N],
            vals: [0; N],
        }
    }

    /// The value at `key`: the recorded one, or a fresh `kani::any()`
    /// recorded for later calls.
    pub fn call(&mut self, key: u64) -> u64 {
        let mut i = 0;
        while i < self.n {
            if self.keys[i] == key {
                return self.vals[i];
            }
            i += 1;
        }
        assert!(
            self.n < N,
            "uninterpreted function: more arguments than its table"
        );
        let v: u64 = kani::any();
        self.keys[self.n] = key;
        self.vals[self.n] = v;
        self.n += 1;
        v
    }
}
