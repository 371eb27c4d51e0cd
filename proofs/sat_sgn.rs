//! sat/sgn properties.
