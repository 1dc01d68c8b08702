//! slice2solid: reconstruct a solid from planar cross-sections of arbitrary orientation.
//!
//! Pipeline (data flows one way): `io` reads `Sections` → `arrangement` of the cutting planes with
//! the section pieces on its faces → per cell `bm` (Boissonnat–Memari Delaunay pruning, on our exact
//! `delaunay` kernel) or `implicit` (Bermano et al. mean-value interpolation) → a solid → `io::mesh`
//! (or `io::vtk_xml`, with the `cell_data` of each triangle and tetrahedron).
//! `eval` measures any mesh (check, compare); `slice` makes sections from a mesh; `render` draws one.
pub mod arrangement;
pub mod bm;
pub mod cell_data;
pub mod delaunay;
pub mod error;
pub mod eval;
pub mod fxhash;
pub mod geom;
pub mod implicit;
pub mod io;
pub mod memory;
pub mod mesh;
pub mod pipeline;
pub mod render;
pub mod sections;
pub mod slice;
pub mod solid;
pub mod validate;

pub use bm::smooth::Smoothing;
pub use error::{Error, Result};
pub use mesh::{TetMesh, TriMesh};
pub use pipeline::{reconstruct, reconstruct_partition};
pub use sections::{Contour, Plane, Region, Section, Sections};
pub use solid::{DelaunayOptions, Method, Options, Partition, Report, Solid, COLLAR_HEIGHT};
