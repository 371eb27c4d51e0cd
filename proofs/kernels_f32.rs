//! f32 kernel properties.
