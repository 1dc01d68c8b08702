//! Readers and writers: cross-sections (CSL, JSON) and meshes.
pub mod csl;
pub mod json;
pub mod mesh;
