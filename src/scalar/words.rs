//! A configuration as stored words (test and verification builds only).
//!
//! A quantized configuration is written field by field as `u32` words
//! (`put`, tests) and read back by `const fn`s (`take`) that do nothing but
//! reassemble the bits: no float arithmetic, no `libm`, no slope search.
//! The Kani harnesses of the whole joint start from a configuration read
//! this way from stored words (a `const`, evaluated by the compiler), and a
//! unit test checks that the stored words are those of the library's own
//! constructor, so the verified configuration is the library's.

/// Reads stored words in order.
pub(crate) struct Words<'a> {
    w: &'a [u32],
    i: usize,
}

impl<'a> Words<'a> {
    pub(crate) const fn new(w: &'a [u32]) -> Self {
        Words { w, i: 0 }
    }

    /// Every word was read.
    pub(crate) const fn is_done(&self) -> bool {
        self.i == self.w.len()
    }

    pub(crate) const fn u32(&mut self) -> u32 {
        let v = self.w[self.i];
        self.i += 1;
        v
    }

    pub(crate) const fn i32(&mut self) -> i32 {
        self.u32() as i32
    }

    pub(crate) const fn u16(&mut self) -> u16 {
        self.u32() as u16
    }

    pub(crate) const fn u8(&mut self) -> u8 {
        self.u32() as u8
    }

    pub(crate) const fn bool(&mut self) -> bool {
        self.u32() != 0
    }

    /// Low word first.
    pub(crate) const fn u64(&mut self) -> u64 {
        let lo = self.u32() as u64;
        lo | (self.u32() as u64) << 32
    }

    pub(crate) const fn i64(&mut self) -> i64 {
        self.u64() as i64
    }

    pub(crate) const fn f64(&mut self) -> f64 {
        f64::from_bits(self.u64())
    }

    pub(crate) const fn f32(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }

    pub(crate) const fn fixed(&mut self) -> super::I16F16 {
        super::I16F16::from_bits(self.i32())
    }

    pub(crate) const fn fixed4(&mut self) -> [super::I16F16; 4] {
        [self.fixed(), self.fixed(), self.fixed(), self.fixed()]
    }

    /// A tag word (0: `None`), then the value.
    pub(crate) const fn option_fixed(&mut self) -> Option<super::I16F16> {
        if self.bool() {
            Some(self.fixed())
        } else {
            None
        }
    }

    pub(crate) const fn f32x4(&mut self) -> [f32; 4] {
        [self.f32(), self.f32(), self.f32(), self.f32()]
    }

    /// A tag word (0: `None`), then the value.
    pub(crate) const fn option_f32(&mut self) -> Option<f32> {
        if self.bool() {
            Some(self.f32())
        } else {
            None
        }
    }
}

/// `built` (the constructor's words) equals `stored`, word for word (the
/// first differing word named).
#[cfg(test)]
pub(crate) fn assert_same_words(built: &[u32], stored: &[u32]) {
    assert_eq!(built.len(), stored.len(), "word count");
    for (i, (a, b)) in built.iter().zip(stored).enumerate() {
        assert_eq!(a, b, "word {i}");
    }
}

/// Prints `words` as the body of a `const` array after the line `head`.
#[cfg(test)]
pub(crate) fn print_words(head: &str, words: &[u32]) {
    std::println!("{head}");
    for row in words.chunks(8) {
        let s: Vec<std::string::String> = row.iter().map(|x| std::format!("0x{x:08x},")).collect();
        std::println!("    {}", s.join(" "));
    }
}

/// Writes words in the order [`Words`] reads them.
#[cfg(test)]
#[derive(Default)]
pub(crate) struct Sink(pub(crate) Vec<u32>);

#[cfg(test)]
impl Sink {
    pub(crate) fn u32(&mut self, v: u32) {
        self.0.push(v);
    }

    pub(crate) fn i32(&mut self, v: i32) {
        self.u32(v as u32);
    }

    pub(crate) fn u64(&mut self, v: u64) {
        self.u32(v as u32);
        self.u32((v >> 32) as u32);
    }

    pub(crate) fn i64(&mut self, v: i64) {
        self.u64(v as u64);
    }

    pub(crate) fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }

    pub(crate) fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }

    pub(crate) fn bool(&mut self, v: bool) {
        self.u32(v as u32);
    }

    pub(crate) fn fixed(&mut self, v: super::I16F16) {
        self.i32(v.to_bits());
    }

    pub(crate) fn fixeds(&mut self, v: &[super::I16F16]) {
        v.iter().for_each(|&x| self.fixed(x));
    }

    pub(crate) fn option_fixed(&mut self, v: Option<super::I16F16>) {
        self.bool(v.is_some());
        if let Some(x) = v {
            self.fixed(x);
        }
    }

    pub(crate) fn f32s(&mut self, v: &[f32]) {
        v.iter().for_each(|&x| self.f32(x));
    }

    pub(crate) fn option_f32(&mut self, v: Option<f32>) {
        self.bool(v.is_some());
        if let Some(x) = v {
            self.f32(x);
        }
    }
}

#[cfg(any(test, armv6m))]
use super::WideCoef;
use super::{Coef, CoefRow, CountCoef, CountToTurn, Gain, IntFactor, SignedCoef, I16F16};

impl SignedCoef {
    /// The stored fields; the halves of `m` and the low-word rounding
    /// constant are derived as [`SignedCoef::new`] derives them.
    const fn take(r: &mut Words) -> Self {
        let m = r.i32();
        let high_only = r.bool();
        let round = r.u32();
        SignedCoef {
            m,
            #[cfg(any(test, armv6m))]
            m_hi: ((m as i64 + (1 << 15)) >> 16) as i32,
            #[cfg(any(test, armv6m))]
            m_lo: m as i16 as i32,
            #[cfg(any(test, armv6m))]
            round_lo: if high_only { 0 } else { round },
            high_only,
            round,
            rs: r.u32(),
        }
    }

    #[cfg(test)]
    fn put(&self, s: &mut Sink) {
        s.i32(self.m);
        s.bool(self.high_only);
        s.u32(self.round);
        s.u32(self.rs);
    }
}

impl Coef {
    /// The stored fields; the product form of `scale_wide` is derived
    /// from the mantissa and exponent as [`WideCoef::new`] derives it.
    pub(crate) const fn take(r: &mut Words) -> Self {
        let value = r.f64();
        let value_f32 = r.f32();
        let mult = r.i64();
        let shift = r.i32();
        Coef {
            value,
            value_f32,
            mult,
            shift,
            mag: r.u32(),
            negative: r.bool(),
            signed: if r.bool() {
                Some(SignedCoef::take(r))
            } else {
                None
            },
            units: [r.i32(), r.i32()],
            #[cfg(any(test, armv6m))]
            wide: WideCoef::new(mult, shift),
        }
    }

    pub(crate) const fn take4(r: &mut Words) -> [Self; 4] {
        [Coef::take(r), Coef::take(r), Coef::take(r), Coef::take(r)]
    }

    #[cfg(test)]
    pub(crate) fn put(&self, s: &mut Sink) {
        s.f64(self.value);
        s.f32(self.value_f32);
        s.i64(self.mult);
        s.i32(self.shift);
        s.u32(self.mag);
        s.bool(self.negative);
        s.bool(self.signed.is_some());
        if let Some(c) = &self.signed {
            c.put(s);
        }
        s.i32(self.units[0]);
        s.i32(self.units[1]);
    }

    #[cfg(test)]
    pub(crate) fn put_all(c: &[Self], s: &mut Sink) {
        c.iter().for_each(|c| c.put(s));
    }
}

impl CoefRow<2> {
    /// The stored fields; the split mantissas are derived as
    /// [`CoefRow::new`] derives them.
    pub(crate) const fn take(r: &mut Words) -> Self {
        let coefs = [Coef::take(r), Coef::take(r)];
        let mant = [r.i32(), r.i32()];
        CoefRow {
            coefs,
            mant,
            split: [
                (mant[0] >> 16, mant[0] & 0xFFFF),
                (mant[1] >> 16, mant[1] & 0xFFFF),
            ],
            shift: r.i32(),
        }
    }

    #[cfg(test)]
    pub(crate) fn put(&self, s: &mut Sink) {
        Coef::put_all(&self.coefs, s);
        s.i32(self.mant[0]);
        s.i32(self.mant[1]);
        s.i32(self.shift);
    }
}

impl CountCoef {
    pub(crate) const fn take(r: &mut Words) -> Self {
        CountCoef {
            coef: Coef::take(r),
            bits: Coef::take(r),
            top: r.i32(),
        }
    }

    #[cfg(test)]
    pub(crate) fn put(&self, s: &mut Sink) {
        self.coef.put(s);
        self.bits.put(s);
        s.i32(self.top);
    }
}

impl IntFactor {
    pub(crate) const fn take(r: &mut Words) -> Self {
        IntFactor {
            coef: Coef::take(r),
            n: r.i32(),
            high: r.i32(),
            low: r.i32(),
        }
    }

    #[cfg(test)]
    pub(crate) fn put(&self, s: &mut Sink) {
        self.coef.put(s);
        s.i32(self.n);
        s.i32(self.high);
        s.i32(self.low);
    }
}

/// `take`/`put` of a backend's gain, with that backend's optional-value
/// reader and writer.
macro_rules! stored_gain {
    ($t:ty, $opt:ident) => {
        impl Gain<$t> {
            pub(crate) const fn take(r: &mut Words) -> Self {
                Gain {
                    coef: Coef::take(r),
                    exact: r.$opt(),
                }
            }

            #[cfg(test)]
            pub(crate) fn put(&self, s: &mut Sink) {
                self.coef.put(s);
                s.$opt(self.exact);
            }
        }
    };
}
stored_gain!(I16F16, option_fixed);
stored_gain!(f32, option_f32);

impl CountToTurn {
    pub(crate) const fn take(r: &mut Words) -> Self {
        CountToTurn {
            hi: r.u32(),
            lo: r.u32(),
        }
    }

    #[cfg(test)]
    pub(crate) fn put(&self, s: &mut Sink) {
        s.u32(self.hi);
        s.u32(self.lo);
    }
}
