//! Typed errors for parameter validation and estimation.
//!
//! Every variant names the offending quantity and carries the value that was
//! rejected, so a caller can report *which* number was wrong without parsing a
//! string. All error types are `Copy` and allocation-free so they can be
//! returned from `no_std` firmware.

use core::fmt;

/// A physical parameter was rejected by a `try_new` constructor.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum ParamError {
    /// The value is NaN or infinite.
    NotFinite {
        /// Name of the parameter, as written in the docs (e.g. `"k1"`).
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// The value must be strictly positive.
    NotPositive {
        /// Name of the parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// The value must be zero or positive.
    Negative {
        /// Name of the parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// The value lies outside the closed interval `[min, max]`.
    OutOfRange {
        /// Name of the parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// Smallest accepted value.
        min: f64,
        /// Largest accepted value.
        max: f64,
    },
    /// Two parameters violate an ordering the model needs (`lower < upper`).
    NotIncreasing {
        /// Name of the parameter that must be the smaller one.
        lower: &'static str,
        /// Its value.
        lower_value: f64,
        /// Name of the parameter that must be the larger one.
        upper: &'static str,
        /// Its value.
        upper_value: f64,
    },
    /// The value cannot be represented by the chosen scalar backend (it would
    /// saturate or quantize to zero).
    NotRepresentable {
        /// Name of the parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// The value must be an integer in `[min, max]` (a gear ratio used as a
    /// count modulus, for example).
    NotInteger {
        /// Name of the parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// Smallest accepted integer.
        min: f64,
        /// Largest accepted integer (`+∞` for no upper limit).
        max: f64,
    },
    /// A product (or another combination) of several parameters lies
    /// outside `[min, max]`; `name` spells the combination with the names
    /// of every parameter in it, e.g. `"c_f·k_f0"`.
    CombinationOutOfRange {
        /// The combination, written with the parameters' names.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Smallest accepted value.
        min: f64,
        /// Largest accepted value.
        max: f64,
    },
    /// Two parameters violate a non-strict ordering (`lower ≤ upper`, e.g.
    /// the two corners of a box, where a fixed component has
    /// `min = max`).
    Exceeds {
        /// Name of the parameter that must not be the larger one.
        lower: &'static str,
        /// Its value.
        lower_value: f64,
        /// Name of the parameter it must not exceed.
        upper: &'static str,
        /// Its value.
        upper_value: f64,
    },
    /// An element of a slice argument (of any length, so its index cannot
    /// be part of a `&'static str` name) is not finite or lies outside
    /// `[min, max]`: `name` is the argument (e.g. `"cw"`), `index` the
    /// element's position in it.
    ElementOutOfRange {
        /// Name of the slice argument (or of a combination of elements
        /// written with `[i]`, e.g. `"cw[i] - ccw[i]"`).
        name: &'static str,
        /// Position of the rejected element.
        index: usize,
        /// The rejected value.
        value: f64,
        /// Smallest accepted value.
        min: f64,
        /// Largest accepted value.
        max: f64,
    },
    /// A field whose value another field determines was set to something
    /// else: it would be overwritten, so a different value is rejected
    /// rather than silently ignored. `0` (not set) is also accepted.
    Overridden {
        /// Name of the field, as the user wrote it.
        name: &'static str,
        /// The value the user gave.
        value: f64,
        /// The value the other fields determine (the only one accepted
        /// besides `0`).
        expected: f64,
    },
    /// A computed result of valid inputs is not a finite number (e.g. an
    /// angle sum that overflows); `name` spells the result in the inputs'
    /// names.
    ResultNotFinite {
        /// The result, written with the arguments' names.
        name: &'static str,
        /// Its value (an infinity or NaN).
        value: f64,
    },
}

/// A value printed for a reader: shortest round-trip digits (`{}`) for
/// ordinary magnitudes, scientific notation (`{:e}`, still the shortest
/// digits that round-trip) below `1e-4` or from `1e6` on, so no message
/// carries hundreds of zeros.
#[derive(Clone, Copy)]
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let a = v.abs();
        if v == 0.0 || !v.is_finite() || (1e-4..1e6).contains(&a) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

impl ParamError {
    /// The name of the offending parameter (for two-parameter variants,
    /// the first named: `lower`).
    pub fn name(&self) -> &'static str {
        match *self {
            ParamError::NotFinite { name, .. }
            | ParamError::NotPositive { name, .. }
            | ParamError::Negative { name, .. }
            | ParamError::OutOfRange { name, .. }
            | ParamError::NotRepresentable { name, .. }
            | ParamError::NotInteger { name, .. }
            | ParamError::CombinationOutOfRange { name, .. }
            | ParamError::ElementOutOfRange { name, .. }
            | ParamError::Overridden { name, .. }
            | ParamError::ResultNotFinite { name, .. } => name,
            ParamError::NotIncreasing { lower, .. } | ParamError::Exceeds { lower, .. } => lower,
        }
    }

    /// The same error with every parameter name passed through `f` (a
    /// composite constructor maps the names a part's validation uses to
    /// the field paths its user wrote, e.g. `"viscous"` →
    /// `"initial_friction.viscous"`).
    pub(crate) fn map_names(self, f: impl Fn(&'static str) -> &'static str) -> Self {
        let mut e = self;
        match &mut e {
            ParamError::NotFinite { name, .. }
            | ParamError::NotPositive { name, .. }
            | ParamError::Negative { name, .. }
            | ParamError::OutOfRange { name, .. }
            | ParamError::NotRepresentable { name, .. }
            | ParamError::NotInteger { name, .. }
            | ParamError::CombinationOutOfRange { name, .. }
            | ParamError::ElementOutOfRange { name, .. }
            | ParamError::Overridden { name, .. }
            | ParamError::ResultNotFinite { name, .. } => *name = f(name),
            ParamError::NotIncreasing { lower, upper, .. }
            | ParamError::Exceeds { lower, upper, .. } => {
                *lower = f(lower);
                *upper = f(upper);
            }
        }
        e
    }

    /// The same error with its (every) name replaced by `name`.
    pub(crate) fn renamed(self, name: &'static str) -> Self {
        self.map_names(|_| name)
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ParamError::NotFinite { name, value } => {
                write!(f, "parameter `{name}` must be finite, got {}", Num(value))
            }
            ParamError::NotPositive { name, value } => {
                write!(f, "parameter `{name}` must be > 0, got {}", Num(value))
            }
            ParamError::Negative { name, value } => {
                write!(f, "parameter `{name}` must be >= 0, got {}", Num(value))
            }
            ParamError::OutOfRange {
                name,
                value,
                min,
                max,
            } => write!(
                f,
                "parameter `{name}` must lie in [{}, {}], got {}",
                Num(min),
                Num(max),
                Num(value)
            ),
            ParamError::NotIncreasing {
                lower,
                lower_value,
                upper,
                upper_value,
            } => write!(
                f,
                "parameter `{lower}` ({}) must be smaller than `{upper}` ({})",
                Num(lower_value),
                Num(upper_value)
            ),
            ParamError::NotRepresentable { name, value } => write!(
                f,
                "parameter `{name}` = {} is not representable by the chosen scalar backend",
                Num(value)
            ),
            ParamError::NotInteger {
                name,
                value,
                min,
                max,
            } => {
                if max == f64::INFINITY {
                    write!(
                        f,
                        "parameter `{name}` must be an integer >= {}, got {}",
                        Num(min),
                        Num(value)
                    )
                } else {
                    write!(
                        f,
                        "parameter `{name}` must be an integer in [{}, {}], got {}",
                        Num(min),
                        Num(max),
                        Num(value)
                    )
                }
            }
            ParamError::CombinationOutOfRange {
                name,
                value,
                min,
                max,
            } => write!(
                f,
                "`{name}` must lie in [{}, {}], got {}",
                Num(min),
                Num(max),
                Num(value)
            ),
            ParamError::Exceeds {
                lower,
                lower_value,
                upper,
                upper_value,
            } => write!(
                f,
                "parameter `{lower}` ({}) must be <= `{upper}` ({})",
                Num(lower_value),
                Num(upper_value)
            ),
            ParamError::ElementOutOfRange {
                name,
                index,
                value,
                min,
                max,
            } => {
                if value.is_finite() {
                    write!(
                        f,
                        "parameter `{name}` (i = {index}) must lie in [{}, {}], got {}",
                        Num(min),
                        Num(max),
                        Num(value)
                    )
                } else {
                    write!(
                        f,
                        "parameter `{name}` (i = {index}) must be finite, got {}",
                        Num(value)
                    )
                }
            }
            ParamError::Overridden {
                name,
                value,
                expected,
            } => write!(
                f,
                "parameter `{name}` is set from other fields: leave it 0 or give {}, got {}",
                Num(expected),
                Num(value)
            ),
            ParamError::ResultNotFinite { name, value } => write!(
                f,
                "result `{name}` of finite arguments is not finite ({}): the arguments are too large",
                Num(value)
            ),
        }
    }
}

/// Available without `std` (`core::error::Error`, stable since Rust 1.81),
/// so `?` into `Box<dyn Error>` works whatever the features.
impl core::error::Error for ParamError {}

#[allow(dead_code)] // used by the model parameter constructors
/// Check that `value` is finite; return it or a [`ParamError::NotFinite`].
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, ParamError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ParamError::NotFinite { name, value })
    }
}

#[allow(dead_code)] // used by the model parameter constructors
/// Check that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, ParamError> {
    let value = finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(ParamError::NotPositive { name, value })
    }
}

/// Check `lower < upper` for two named parameters.
pub(crate) fn increasing(
    lower: (&'static str, f64),
    upper: (&'static str, f64),
) -> Result<(), ParamError> {
    if lower.1 < upper.1 {
        Ok(())
    } else {
        Err(ParamError::NotIncreasing {
            lower: lower.0,
            lower_value: lower.1,
            upper: upper.0,
            upper_value: upper.1,
        })
    }
}

/// `value` if it is finite and not negative; otherwise the error naming it.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64, ParamError> {
    let value = finite(name, value)?;
    if value < 0.0 {
        Err(ParamError::Negative { name, value })
    } else {
        Ok(value)
    }
}

/// Check a gear ratio: finite and at least 1.
pub(crate) fn gear_ratio(value: f64) -> Result<f64, ParamError> {
    let value = finite("ratio", value)?;
    if value >= 1.0 {
        Ok(value)
    } else {
        Err(ParamError::OutOfRange {
            name: "ratio",
            value,
            min: 1.0,
            max: f64::INFINITY,
        })
    }
}

/// `value` if it is finite and inside `[min, max]`; otherwise the error
/// naming it ([`ParamError::NotFinite`] or [`ParamError::OutOfRange`]).
pub(crate) fn in_range(
    name: &'static str,
    value: f64,
    min: f64,
    max: f64,
) -> Result<f64, ParamError> {
    let value = finite(name, value)?;
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(ParamError::OutOfRange {
            name,
            value,
            min,
            max,
        })
    }
}

/// `value` if it is an integer in `[min, max]`; otherwise
/// [`ParamError::NotInteger`] naming it (a NaN or an infinity is not an
/// integer either).
pub(crate) fn integer(
    name: &'static str,
    value: f64,
    min: f64,
    max: f64,
) -> Result<f64, ParamError> {
    if value.is_finite() && value == libm::floor(value) && (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(ParamError::NotInteger {
            name,
            value,
            min,
            max,
        })
    }
}

/// `value` of the combination `name` if it is a number inside `[min, max]`;
/// otherwise [`ParamError::CombinationOutOfRange`].
pub(crate) fn combination(
    name: &'static str,
    value: f64,
    min: f64,
    max: f64,
) -> Result<f64, ParamError> {
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(ParamError::CombinationOutOfRange {
            name,
            value,
            min,
            max,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positive_rejects_zero_negative_and_nan_naming_the_value() {
        assert_eq!(
            positive("k1", 0.0),
            Err(ParamError::NotPositive {
                name: "k1",
                value: 0.0
            })
        );
        assert_eq!(
            positive("k1", -2.5),
            Err(ParamError::NotPositive {
                name: "k1",
                value: -2.5
            })
        );
        assert!(matches!(
            positive("k1", f64::NAN),
            Err(ParamError::NotFinite { name: "k1", .. })
        ));
        assert_eq!(positive("k1", 3.0), Ok(3.0));
    }

    #[test]
    fn display_names_parameter_and_value() {
        extern crate std;
        use std::string::ToString;
        let s = ParamError::NotPositive {
            name: "k2",
            value: -1.0,
        }
        .to_string();
        assert!(s.contains("k2") && s.contains("-1"), "{s}");
    }

    /// Every variant's message, word for word: the parameter, the value and
    /// the rule.
    #[test]
    fn display_states_parameter_value_and_rule() {
        extern crate std;
        use std::string::ToString;
        let cases = [
            (
                integer("ratio", 100.5, 1.0, f64::INFINITY).unwrap_err(),
                "parameter `ratio` must be an integer >= 1, got 100.5",
            ),
            (
                integer("ratio", 0.0, 1.0, 65535.0).unwrap_err(),
                "parameter `ratio` must be an integer in [1, 65535], got 0",
            ),
            (
                integer("ratio", f64::NAN, 1.0, 65535.0).unwrap_err(),
                "parameter `ratio` must be an integer in [1, 65535], got NaN",
            ),
            (
                combination("c_f·k_f0", 1e9, 1.0, 2.0).unwrap_err(),
                "`c_f·k_f0` must lie in [1, 2], got 1e9",
            ),
            (
                in_range("c_w", 0.0, 1e-6, 1e6).unwrap_err(),
                "parameter `c_w` must lie in [1e-6, 1e6], got 0",
            ),
            (
                in_range("c_w", f64::INFINITY, 1e-6, 1e6).unwrap_err(),
                "parameter `c_w` must be finite, got inf",
            ),
            (
                non_negative("a3", -1.5).unwrap_err(),
                "parameter `a3` must be >= 0, got -1.5",
            ),
            (
                positive("k_f0", 0.0).unwrap_err(),
                "parameter `k_f0` must be > 0, got 0",
            ),
        ];
        for (e, want) in cases {
            assert_eq!(e.to_string(), want);
        }
    }

    /// Numbers print with their shortest round-trip digits, in scientific
    /// notation outside `[1e-4, 1e6)`: never hundreds of digits.
    #[test]
    fn display_prints_readable_numbers() {
        extern crate std;
        use std::string::ToString;
        let e = |v: f64| {
            ParamError::NotPositive {
                name: "x",
                value: v,
            }
            .to_string()
        };
        for (v, want) in [
            (1e300, "1e300"),
            (-1e304, "-1e304"),
            (5e-324, "5e-324"),
            (1.5e-5, "1.5e-5"),
            (1e-4, "0.0001"),
            (999_999.5, "999999.5"),
            (1e6, "1e6"),
            (0.1 + 0.2, "0.30000000000000004"),
            (2_631_578.947_368_421, "2.631578947368421e6"),
            (0.0, "0"),
            (-0.0, "-0"),
            (f64::NEG_INFINITY, "-inf"),
        ] {
            assert_eq!(e(v), std::format!("parameter `x` must be > 0, got {want}"));
        }
    }

    /// The variants added for field paths, word for word.
    #[test]
    fn display_of_pair_element_override_and_result_variants() {
        extern crate std;
        use std::string::ToString;
        let cases = [
            (
                ParamError::Exceeds {
                    lower: "min.viscous",
                    lower_value: 2e-4,
                    upper: "max.viscous",
                    upper_value: 1e-4,
                },
                "parameter `min.viscous` (0.0002) must be <= `max.viscous` (0.0001)",
            ),
            (
                ParamError::ElementOutOfRange {
                    name: "cw",
                    index: 3,
                    value: f64::NAN,
                    min: f64::MIN,
                    max: f64::MAX,
                },
                "parameter `cw` (i = 3) must be finite, got NaN",
            ),
            (
                ParamError::ElementOutOfRange {
                    name: "cw[i] - ccw[i] (wrapped)",
                    index: 0,
                    value: 0.5,
                    min: -0.25,
                    max: 0.25,
                },
                "parameter `cw[i] - ccw[i] (wrapped)` (i = 0) must lie in [-0.25, 0.25], got 0.5",
            ),
            (
                ParamError::Overridden {
                    name: "law.rotor_inertia",
                    value: 1.0,
                    expected: 0.5,
                },
                "parameter `law.rotor_inertia` is set from other fields: leave it 0 or give 0.5, got 1",
            ),
            (
                ParamError::ResultNotFinite {
                    name: "a + b",
                    value: f64::INFINITY,
                },
                "result `a + b` of finite arguments is not finite (inf): the arguments are too large",
            ),
        ];
        for (e, want) in cases {
            assert_eq!(e.to_string(), want);
        }
    }

    /// `map_names` reaches every name of a pair; `renamed` every name.
    #[test]
    fn names_map_to_field_paths() {
        let e = increasing(("t1", 2.0), ("t2", 1.0)).unwrap_err();
        let m = e.map_names(|n| if n == "t1" { "curve.t1" } else { "curve.t2" });
        assert!(matches!(
            m,
            ParamError::NotIncreasing {
                lower: "curve.t1",
                upper: "curve.t2",
                ..
            }
        ));
        assert_eq!(m.name(), "curve.t1");
        assert_eq!(
            positive("k", -1.0).unwrap_err().renamed("law.k").name(),
            "law.k"
        );
    }

    /// `ParamError` is a `core::error::Error` without any feature, so `?`
    /// converts it into `Box<dyn Error>`.
    #[test]
    fn param_error_boxes_as_core_error() {
        extern crate std;
        fn run() -> Result<(), std::boxed::Box<dyn core::error::Error>> {
            positive("k_f0", -1.0)?;
            Ok(())
        }
        let e = run().unwrap_err();
        assert_eq!(std::format!("{e}"), "parameter `k_f0` must be > 0, got -1");
    }
}
