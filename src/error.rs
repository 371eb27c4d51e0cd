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
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ParamError {}

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
}
