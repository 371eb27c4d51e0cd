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
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ParamError::NotFinite { name, value } => {
                write!(f, "parameter `{name}` must be finite, got {value}")
            }
            ParamError::NotPositive { name, value } => {
                write!(f, "parameter `{name}` must be > 0, got {value}")
            }
            ParamError::Negative { name, value } => {
                write!(f, "parameter `{name}` must be >= 0, got {value}")
            }
            ParamError::OutOfRange {
                name,
                value,
                min,
                max,
            } => write!(
                f,
                "parameter `{name}` must lie in [{min}, {max}], got {value}"
            ),
            ParamError::NotIncreasing {
                lower,
                lower_value,
                upper,
                upper_value,
            } => write!(
                f,
                "parameter `{lower}` ({lower_value}) must be smaller than `{upper}` ({upper_value})"
            ),
            ParamError::NotRepresentable { name, value } => write!(
                f,
                "parameter `{name}` = {value} is not representable by the chosen scalar backend"
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
                        "parameter `{name}` must be an integer >= {min}, got {value}"
                    )
                } else {
                    write!(
                        f,
                        "parameter `{name}` must be an integer in [{min}, {max}], got {value}"
                    )
                }
            }
            ParamError::CombinationOutOfRange {
                name,
                value,
                min,
                max,
            } => write!(f, "`{name}` must lie in [{min}, {max}], got {value}"),
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
                "`c_f·k_f0` must lie in [1, 2], got 1000000000",
            ),
            (
                in_range("c_w", 0.0, 1e-6, 1e6).unwrap_err(),
                "parameter `c_w` must lie in [0.000001, 1000000], got 0",
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
