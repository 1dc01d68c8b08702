//! The implicit method of Bermano, Vaxman & Gotsman (2011): mean-value interpolation of the sections
//! per arrangement cell, zero set extracted on an octree.
pub mod mvc;

use crate::arrangement::Arrangement;
use crate::error::{Error, Result};
use crate::reconstruct::{Options, Report, Solid};
use crate::sections::Sections;

/// Reconstruct with the implicit mean-value method. Fills `report` (phases, counts, warnings).
pub fn reconstruct(
    _sections: &Sections,
    _arrangement: &Arrangement,
    _options: &Options,
    _report: &mut Report,
) -> Result<Solid> {
    Err(Error::Unavailable(
        "the implicit method is not implemented yet".into(),
    ))
}
