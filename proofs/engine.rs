//! The exhaustive engine and the error measures shared by the properties.

/// Result of checking a property at one input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Verdict {
    /// The measured error at this input, in the property's unit (ulp or LSB);
    /// 0 for purely logical properties.
    pub error: f64,
    /// Whether the property holds at this input.
    pub holds: bool,
}

impl Verdict {
    /// A logical property (no error measure).
    pub fn logical(holds: bool) -> Self {
        Verdict { error: 0.0, holds }
    }

    /// An error-bound property: holds when `error <= bound` (and `error` is
    /// not NaN).
    pub fn bounded(error: f64, bound: f64) -> Self {
        Verdict {
            error,
            holds: error <= bound,
        }
    }

    /// Both properties hold; the error is the larger one.
    pub fn and(self, other: Verdict) -> Verdict {
        Verdict {
            error: if other.error > self.error {
                other.error
            } else {
                self.error
            },
            holds: self.holds && other.holds,
        }
    }
}

/// Summary of an exhaustive run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Report {
    /// Number of inputs checked.
    pub checked: u64,
    /// Number of inputs at which the property failed.
    pub failures: u64,
    /// First (lowest-index) failing input, if any.
    pub first_failure: Option<u32>,
    /// Largest error seen.
    pub max_error: f64,
    /// Input at which the largest error was seen.
    pub argmax: u32,
}

impl Report {
    fn empty() -> Self {
        Report {
            checked: 0,
            failures: 0,
            first_failure: None,
            max_error: 0.0,
            argmax: 0,
        }
    }

    fn merge(self, o: Report) -> Report {
        let (max_error, argmax) = if o.max_error > self.max_error {
            (o.max_error, o.argmax)
        } else {
            (self.max_error, self.argmax)
        };
        Report {
            checked: self.checked + o.checked,
            failures: self.failures + o.failures,
            first_failure: match (self.first_failure, o.first_failure) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            },
            max_error,
            argmax,
        }
    }
}

/// Check `property` at every `u32` code in `lo..=hi`, spread over all cores.
///
/// The code is whatever the caller decodes it as: a bit pattern of an `f32`
/// or an `I16F16`, or two packed 16-bit inputs.
#[cfg(test)]
pub fn exhaustive_u32<F>(lo: u32, hi: u32, property: F) -> Report
where
    F: Fn(u32) -> Verdict + Sync,
{
    exhaustive_u32_chained(lo, hi, |_| (), |code, _, _| property(code))
}

/// Like [`exhaustive_u32`], for properties that relate each input to its
/// predecessor (monotonicity, continuity): `eval` runs once per code and
/// `property(code, value, previous)` gets the value at `code − 1` (`None`
/// at `lo`), so nothing is evaluated twice.
#[cfg(test)]
pub fn exhaustive_u32_chained<T, E, P>(lo: u32, hi: u32, eval: E, property: P) -> Report
where
    T: Send,
    E: Fn(u32) -> T + Sync,
    P: Fn(u32, &T, Option<&T>) -> Verdict + Sync,
{
    extern crate std;
    assert!(lo <= hi);
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .max(1) as u64;
    const BLOCK: u64 = 1 << 16;
    let total = hi as u64 - lo as u64 + 1;
    let blocks = total.div_ceil(BLOCK);
    let (eval, property) = (&eval, &property);
    std::thread::scope(|s| {
        let handles: std::vec::Vec<_> = (0..threads)
            .map(|t| {
                s.spawn(move || {
                    let mut rep = Report::empty();
                    let mut b = t;
                    while b < blocks {
                        let start = lo as u64 + b * BLOCK;
                        let end = (start + BLOCK).min(hi as u64 + 1);
                        let mut prev = (start > lo as u64).then(|| eval((start - 1) as u32));
                        for code in start..end {
                            let code = code as u32;
                            let cur = eval(code);
                            let v = property(code, &cur, prev.as_ref());
                            rep.checked += 1;
                            if !v.holds {
                                rep.failures += 1;
                                if rep.first_failure.is_none_or(|f| code < f) {
                                    rep.first_failure = Some(code);
                                }
                            }
                            if v.error > rep.max_error {
                                rep.max_error = v.error;
                                rep.argmax = code;
                            }
                            prev = Some(cur);
                        }
                        b += threads;
                    }
                    rep
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("exhaustive worker panicked"))
            .fold(Report::empty(), Report::merge)
    })
}

/// Error of an `f32` result in units in the last place of the reference.
///
/// The ulp is that of the `f32` binade containing `|reference|`
/// (`2^(e-23)`, at least `2^-149` for subnormals), so an error of 0.5 ulp is
/// the best a correctly rounded result can do.
pub fn ulp_error_f32(got: f32, reference: f64) -> f64 {
    if got.is_nan() || reference.is_nan() {
        return f64::INFINITY;
    }
    let diff = (got as f64 - reference).abs();
    if diff == 0.0 {
        return 0.0;
    }
    let mag = reference.abs();
    // Exponent of |reference| as an f32 binade (floor(log2)), clamped to the
    // normal range; subnormal ulp is 2^-149.
    let e = if mag == 0.0 {
        -126
    } else {
        let bits = mag.to_bits();
        let e = ((bits >> 52) & 0x7ff) as i32 - 1023;
        e.clamp(-126, 127)
    };
    diff / libm::exp2((e - 23) as f64)
}

/// A xorshift64 generator from a nonzero `seed`: reproducible random bit
/// patterns for the tests that compare two forms of a check.
pub fn xorshift64(seed: u64) -> impl FnMut() -> u64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    }
}

/// Error of a fixed-point result in LSBs (`lsb` is the value of one LSB).
pub fn lsb_error(got: f64, reference: f64, lsb: f64) -> f64 {
    if reference.is_nan() || got.is_nan() {
        return f64::INFINITY;
    }
    (got - reference).abs() / lsb
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ulp_error_measures_in_reference_binade() {
        assert_eq!(ulp_error_f32(1.0, 1.0), 0.0);
        let one_up = f32::from_bits(1.0f32.to_bits() + 1);
        assert_eq!(ulp_error_f32(one_up, 1.0), 1.0);
        // Reference halfway between the last f32 below 2 and 2 itself: the
        // binade is [1, 2), whose ulp is 2^-23, and the distance is 2^-24.
        assert_eq!(ulp_error_f32(2.0, 2.0 - 2f64.powi(-24)), 0.5);
        // Subnormal reference: ulp is 2^-149.
        assert_eq!(ulp_error_f32(0.0, 3.0 * 2f64.powi(-149)), 3.0);
        assert_eq!(ulp_error_f32(f32::NAN, 1.0), f64::INFINITY);
    }

    #[test]
    fn chained_engine_sees_every_predecessor() {
        // Property: value(code) = value(code - 1) + 1 for value = code, and a
        // deliberate break at 200_000 is found.
        let r = exhaustive_u32_chained(
            5,
            400_000,
            |c| if c == 200_000 { c + 7 } else { c },
            |c, v, p| {
                Verdict::logical(
                    p.is_none_or(|p| *v == p + 1) || c == 200_001 && *v + 6 == *p.unwrap(),
                )
            },
        );
        assert_eq!(r.checked, 400_000 - 5 + 1);
        assert_eq!(r.failures, 1);
        assert_eq!(r.first_failure, Some(200_000));
    }

    #[test]
    fn engine_counts_every_code_and_finds_failures() {
        let r = exhaustive_u32(10, 300_000, |c| Verdict::bounded((c % 7) as f64, 5.0));
        assert_eq!(r.checked, 300_000 - 10 + 1);
        // codes with c % 7 == 6 fail; the first >= 10 is 13.
        assert_eq!(r.first_failure, Some(13));
        assert_eq!(r.max_error, 6.0);
        let expected_failures = (10..=300_000u32).filter(|c| c % 7 == 6).count() as u64;
        assert_eq!(r.failures, expected_failures);
    }
}
