//! Geometry: every geometric decision goes through `predicates`. `tri_tri` (exact triangle-triangle
//! intersection) and `bvh` (bounding-volume hierarchy of boxes) serve the engine (bm::untangle) and the
//! measuring instruments (eval) alike.
pub mod bvh;
pub mod predicates;
pub mod tri_tri;
