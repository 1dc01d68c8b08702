//! Boissonnat–Memari reconstruction: per arrangement cell, Delaunay of contour vertices and branching samples,
//! pruned in three steps; the cells glued into one solid.
use crate::arrangement::Arrangement;
use crate::error::{Error, Result};
use crate::reconstruct::{Options, Report, Solid};
use crate::sections::Sections;

/// Reconstruct with the Delaunay pruning method. Fills `report` (phases, counts, warnings).
pub fn reconstruct(
    _sections: &Sections,
    _arrangement: &Arrangement,
    _options: &Options,
    _report: &mut Report,
) -> Result<Solid> {
    Err(Error::Unavailable(
        "the Delaunay pruning engine is not implemented yet".into(),
    ))
}
