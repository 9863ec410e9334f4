//! Movement primitives learned from demonstration: DMP, ProMP and KMP.
