//! I16F16 kernel properties.
