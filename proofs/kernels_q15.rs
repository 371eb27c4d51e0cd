//! Q15 kernel properties.
