//! Time-optimal path parameterization (TOPP-RA) and time rescaling.
