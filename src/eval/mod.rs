//! Measuring instruments for any triangle mesh (ours or another tool's):
//! * [`check::check_mesh`]: closed, manifold, oriented, exact self-intersections, overlapping
//!   near-coplanar pairs (double sheets, see [`near_coplanar`]), coincident vertices, components, Euler
//!   characteristic and genus, volume and area; with input sections, per-plane agreement of the mesh's
//!   exact section with the input section.
//! * [`compare::compare_meshes`]: volumetric IoU, Chamfer L1/L2 and Hausdorff distances against a
//!   reference, normalised by the reference's bounding-box diagonal.
//! * [`tets::check_tets`]: a tetrahedral mesh is conforming (exact), with no inverted, flat or
//!   overlapping tetrahedra, and its boundary is a given surface.
pub mod check;
pub mod compare;
pub mod near_coplanar;
pub mod partition;
pub mod section;
pub mod shapes;
pub mod tets;
pub mod topology;

// moved to geom (the engine uses them too); kept reachable under their old paths
pub use crate::geom::{bvh, tri_tri};

pub use check::{check_mesh, CheckReport};
pub use compare::{compare_meshes, CompareReport};
pub use tets::{check_tets, TetCheck};
