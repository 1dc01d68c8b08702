//! The library's front door: `reconstruct(&Sections, &Options) -> Solid`, whichever method: select the
//! label, build the arrangement, dispatch to an engine, measure the surface's topology.
use crate::arrangement::{Arrangement, CellScope};
use crate::error::{Error, Result};
use crate::sections::Sections;
use crate::solid::{Method, Options, Partition, Report, Solid, SurfaceTopology};
use std::time::Instant;

pub fn reconstruct(sections: &Sections, options: &Options) -> Result<Solid> {
    let start = Instant::now();
    let mut report = Report {
        method: match options.method {
            Method::Delaunay => "delaunay".into(),
            Method::Implicit => "implicit".into(),
        },
        ..Default::default()
    };
    report.warnings.extend(sections.warnings.iter().cloned());
    if options.method == Method::Implicit && options.delaunay.smooth.is_some() {
        return Err(Error::input(
            "--smooth",
            "smoothing is a stage of the Delaunay method (the implicit surface is smooth already)",
        ));
    }
    if let Some(l) = options.label {
        let present = sections.regions_per_label();
        if !present.contains_key(&l) {
            let list: Vec<String> = present.keys().map(i32::to_string).collect();
            return Err(Error::input(
                format!("--label {l}"),
                format!(
                    "no region of the input has this label (labels present: {})",
                    if list.is_empty() {
                        "none".to_string()
                    } else {
                        list.join(", ")
                    }
                ),
            ));
        }
    }
    let (selected, arrangement) = arranged(sections, options, false, &mut report)?;
    let mut solid = match options.method {
        Method::Delaunay => delaunay(&selected, arrangement, options, &mut report)?,
        Method::Implicit => {
            crate::implicit::reconstruct(&selected, &arrangement, options, &mut report)?
        }
    };
    report.total_seconds = start.elapsed().as_secs_f64();
    report.peak_memory = crate::memory::peak_resident();
    let topo = crate::eval::topology::analyze(&solid.surface);
    report.surface = Some(SurfaceTopology {
        triangles: solid.surface.triangles.len(),
        closed: topo.closed,
        manifold: topo.manifold,
        oriented: topo.oriented,
        components: topo.components.len(),
        euler: topo.euler,
        genus: topo.components.iter().filter_map(|c| c.genus).sum(),
    });
    solid.report = report;
    Ok(solid)
}

/// The Delaunay method on `selected`. Where a cell had to be triangulated untagged (its points
/// exactly cospherical across two planes, which the tagged kernel cannot decide) and a face is
/// then triangulated differently by its two cells, the contour vertices are moved to generic
/// position in their planes (`validate::move_to_generic_position`, 1e-10 of the diagonal) and the
/// method runs again; the run with fewer such faces (then fewer untagged cells) is kept, the first
/// on a tie, with a warning when the moved one is. An untagged cell whose faces all match its
/// neighbours' costs no second run (Elephant under 40 fan planes has one).
fn delaunay(
    selected: &Sections,
    arrangement: Arrangement,
    options: &Options,
    report: &mut Report,
) -> Result<Solid> {
    let before = report.clone();
    let solid = crate::bm::reconstruct(selected, &arrangement, options, report)?;
    let harm = |r: &Report| {
        let n = |k: &str| r.counts.get(k).copied().unwrap_or(0);
        (n("nonconforming_faces"), n("cells_untagged"))
    };
    let first = harm(report);
    if first.0 == 0 || first.1 == 0 {
        return Ok(solid);
    }
    let (moved, moves) = crate::validate::move_to_generic_position(selected);
    let mut again = before;
    let arrangement = arrangement_of(&moved, &options.arrangement, &mut again)?;
    let retried = crate::bm::reconstruct(&moved, &arrangement, options, &mut again)?;
    let second = harm(&again);
    if second >= first {
        report.count("generic_position_retries_not_kept", 1);
        return Ok(solid);
    }
    again.count("generic_position_vertices_moved", moves.moved);
    again.warnings.push(format!(
        "{} cells had points exactly cospherical across two planes (sections symmetric about a \
         common line) that the tagged kernel cannot decide, {} faces triangulated differently: {} \
         contour vertices moved in their planes by at most {:.3e} (1e-10 of the diagonal) to \
         generic position, {} on common lines kept; {} such cells and {} such faces left",
        first.1, first.0, moves.moved, moves.max_move, moves.kept_on_lines, second.1, second.0
    ));
    *report = again;
    Ok(retried)
}

/// The selected sections (`options.label`), reconciled along their planes' common lines, and
/// their arrangement (every cell of the box for the implicit method). `junctions`: all labels as
/// one material keeping the labels' vertices on its outline (`one_material_with_junctions`).
fn arranged(
    sections: &Sections,
    options: &Options,
    junctions: bool,
    report: &mut Report,
) -> Result<(Sections, Arrangement)> {
    let selected = match (options.label, junctions) {
        (None, true) => crate::validate::one_material_with_junctions(sections)?,
        _ => sections.select_label(options.label)?,
    };
    let (selected, trims) = crate::validate::reconcile_common_lines(
        selected,
        options.arrangement.snap_tolerance,
        options.arrangement.line_strip,
    )?;
    report.count("common_lines_trimmed", trims.trimmed as u64);
    report.warnings.extend(trims.warnings);
    let reconstructed = selected.regions_per_label();
    report.label_names = (selected.label_names.iter())
        .filter(|(l, _)| reconstructed.contains_key(l))
        .map(|(l, n)| (*l, n.clone()))
        .collect();
    // The implicit method interpolates in every cell of the box; the Delaunay method needs only
    // the cells with a section on a face.
    let mut arrangement_options = options.arrangement.clone();
    if options.method == Method::Implicit {
        arrangement_options.scope = CellScope::All;
    }
    let arrangement = arrangement_of(&selected, &arrangement_options, report)?;
    Ok((selected, arrangement))
}

/// The arrangement of `selected`, timed, with its counts and warnings in `report`.
fn arrangement_of(
    selected: &Sections,
    options: &crate::arrangement::ArrangementOptions,
    report: &mut Report,
) -> Result<Arrangement> {
    let arrangement = report.time("arrangement", || Arrangement::build(selected, options))?;
    report.count("cells", arrangement.cells.len() as u64);
    report.count("faces", arrangement.faces.len() as u64);
    report.warnings.extend(arrangement.warnings.iter().cloned());
    Ok(arrangement)
}

/// Every label at once (`reconstruct --all-labels`): a partition of space into labelled domains,
/// by the implicit method (`implicit::labels`) or the Delaunay method (`bm::partition`: all labels
/// as one material, with the outlines labels share as points of the cells' triangulations, then
/// its complex split between the labels).
pub fn reconstruct_partition(sections: &Sections, options: &Options) -> Result<Partition> {
    if options.delaunay.smooth.is_some() {
        // the partition reads labels off the planes through the complex's points; the faired
        // points between them are not placed for that yet
        return Err(Error::input(
            "--smooth",
            "not supported with --all-labels yet (smooth one label at a time with --label)",
        ));
    }
    if options.method == Method::Implicit {
        return crate::implicit::labels::reconstruct_partition(sections, options);
    }
    let start = Instant::now();
    let labels = crate::implicit::labels::labels_of(sections)?;
    let mut report = Report {
        method: "delaunay".into(),
        ..Default::default()
    };
    report.warnings.extend(sections.warnings.iter().cloned());
    let one = Options {
        label: None,
        ..options.clone()
    };
    let (selected, arrangement) = arranged(sections, &one, true, &mut report)?;
    let shared = crate::bm::partition::shared_segments(sections);
    let seeds = crate::bm::partition::seeds(&shared, &arrangement);
    let complex =
        crate::bm::reconstruct_complex(&selected, &arrangement, &one, &mut report, &seeds)?;
    // the tetrahedra the planes leave open take the label of the largest mean-value indicator
    // (the implicit method's, one per label) at their centroids
    // (one label: every tetrahedron is that label's, nothing to decide)
    let decide = if labels.len() > 1 { &labels[..] } else { &[] };
    // (their warnings are not the partition's: the Delaunay path reported the sections already)
    let indicators = report.time("partition indicators", || {
        use rayon::prelude::*;
        (decide.par_iter())
            .map(|&l| {
                let mut ignored = Report::default();
                let ind =
                    crate::implicit::labels::indicator_of(sections, Some(l), &one, &mut ignored);
                ind.map(|(ind, _)| ind)
            })
            .collect::<Result<Vec<_>>>()
    })?;
    let prefer = |l: u32, x: [f64; 3]| indicators[l as usize].eval(x);
    let mut partition = report.time("partition", || {
        let prefer =
            (!indicators.is_empty()).then_some(&prefer as &crate::bm::partition::labels::Prefer);
        crate::bm::partition::split(sections, &arrangement, complex, &labels, &shared, prefer)
    });
    report.warnings.append(&mut partition.report.warnings);
    for (k, v) in std::mem::take(&mut partition.report.counts) {
        report.count(&k, v);
    }
    report.total_seconds = start.elapsed().as_secs_f64();
    report.peak_memory = crate::memory::peak_resident();
    partition.report = report;
    Ok(partition)
}
