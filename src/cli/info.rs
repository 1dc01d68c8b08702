//! `slice2solid info INPUT [--json] [--cells]`: what a cross-section file holds.
use crate::InfoArgs;
use serde_json::json;
use slice2solid::arrangement::Arrangement;
use slice2solid::io::{read_sections_of_roi, ReadOptions};
use slice2solid::Result;
use std::collections::BTreeMap;
use std::process::ExitCode;
use std::time::Instant;

pub fn run(args: InfoArgs) -> Result<ExitCode> {
    let t0 = Instant::now();
    let s = read_sections_of_roi(
        &args.input,
        &ReadOptions {
            strict: args.strict,
        },
        args.roi.as_deref(),
    )?;
    let read_ms = t0.elapsed().as_secs_f64() * 1e3;

    let regions: usize = s.sections.iter().map(|x| x.regions.len()).sum();
    let holes: usize = s
        .sections
        .iter()
        .flat_map(|x| &x.regions)
        .map(|r| r.holes.len())
        .sum();
    let empty = s.sections.iter().filter(|x| x.regions.is_empty()).count();
    let labels = s.regions_per_label();
    let max_off = s
        .sections
        .iter()
        .map(|x| x.max_off_plane)
        .fold(0.0, f64::max);
    let bbox = s.bounding_box();
    let diag = bbox.map_or(0.0, |(lo, hi)| {
        (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
    });

    let cells = if args.cells {
        let t = Instant::now();
        let a = Arrangement::build(&s.select_label(None)?, &Default::default())?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let with_sections = a
            .cells
            .iter()
            .filter(|c| {
                c.faces
                    .iter()
                    .any(|f| !a.faces[f.face as usize].pieces.is_empty())
            })
            .count();
        Some((
            a.cells.len(),
            a.faces.len(),
            with_sections,
            ms,
            a.max_disagreement,
            a.warnings,
        ))
    } else {
        None
    };

    if args.json {
        let mut doc = json!({
            "file": args.input.display().to_string(),
            "planes": s.sections.len(),
            "empty_planes": empty,
            "n_labels": s.n_labels,
            "label_names": s.label_names.iter().map(|(l, n)| (l.to_string(), n.clone())).collect::<BTreeMap<_, _>>(),
            "regions_per_label": labels.iter().map(|(l, n)| (l.to_string(), *n)).collect::<BTreeMap<_, _>>(),
            "vertices": s.vertex_count(),
            "contours": regions + holes,
            "regions": regions,
            "holes": holes,
            "bounding_box": bbox.map(|(lo, hi)| json!({"min": lo, "max": hi})),
            "diagonal": diag,
            "max_off_plane": max_off,
            "read_ms": read_ms,
            "warnings": s.warnings,
        });
        if let Some((c, f, w, ms, dis, warn)) = &cells {
            doc["arrangement"] = json!({"cells": c, "faces": f, "cells_with_sections": w,
                "build_ms": ms, "max_disagreement": dis, "warnings": warn});
        }
        println!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("a Value always serialises")
        );
    } else {
        println!("file:           {}", args.input.display());
        println!(
            "planes:         {} ({} without a section)",
            s.sections.len(),
            empty
        );
        let per_label: Vec<String> = labels
            .iter()
            .map(|(l, n)| format!("{l}: {n} region(s)"))
            .collect();
        println!(
            "labels:         {} declared; {}",
            s.n_labels,
            per_label.join(", ")
        );
        if !s.label_names.is_empty() {
            let names: Vec<String> = s
                .label_names
                .iter()
                .map(|(l, n)| format!("{l}: {n:?}"))
                .collect();
            println!("label names:    {}", names.join(", "));
        }
        println!("vertices:       {}", s.vertex_count());
        println!(
            "contours:       {} ({} outer, {} holes)",
            regions + holes,
            regions,
            holes
        );
        match bbox {
            Some((lo, hi)) => println!(
                "bounding box:   [{:.6}, {:.6}, {:.6}] .. [{:.6}, {:.6}, {:.6}] (diagonal {:.6})",
                lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], diag
            ),
            None => println!("bounding box:   none (no vertices)"),
        }
        let rel = if diag > 0.0 { max_off / diag } else { 0.0 };
        println!("max off-plane:  {max_off:.3e} ({rel:.2e} of the diagonal; snapped)");
        println!("read in:        {read_ms:.1} ms");
        if let Some((c, f, w, ms, dis, warn)) = &cells {
            println!("arrangement:    {c} cells, {f} faces, {w} cells with sections, built in {ms:.1} ms");
            println!("                largest disagreement of two sections along a plane crossing: {dis:.3e}");
            for w in warn {
                println!("  arrangement: {w}");
            }
        }
        if s.warnings.is_empty() {
            println!("warnings:       none");
        } else {
            println!("warnings:");
            for w in &s.warnings {
                println!("  {w}");
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
