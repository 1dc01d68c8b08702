//! Geometry: every geometric decision goes through `predicates`.
pub mod predicates;
