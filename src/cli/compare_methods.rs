//! `slice2solid compare-methods INPUT [--reference REF] [--json] [--depth D]`: run the Delaunay
//! (Boissonnat–Memari) and the implicit (Bermano et al.) methods on the same input and print one
//! table: time, triangles, topology, section agreement, and distances to a reference mesh.
//! A method that fails or is not available gets a row saying so; the others still run.
use crate::CompareMethodsArgs;
use serde::Serialize;
use slice2solid::eval::check::{check_mesh, CheckReport};
use slice2solid::eval::compare::{compare_meshes, CompareReport, DEFAULT_SAMPLES};
use slice2solid::io::{mesh::read_trimesh, read_sections};
use slice2solid::{Error, Method, Options, Report, Result};
use std::io::IsTerminal;
use std::process::ExitCode;

#[derive(Serialize)]
struct Row {
    method: String,
    /// "ok", "unavailable: ..." or "error: ...".
    status: String,
    seconds: Option<f64>,
    triangles: Option<usize>,
    check: Option<CheckReport>,
    compare: Option<CompareReport>,
    report: Option<Report>,
}

/// A method's status when it failed: "unavailable: ..." or "error: ...".
pub(super) fn failed(e: Error) -> String {
    match e {
        Error::Unavailable(m) => format!("unavailable: {m}"),
        other => format!("error: {other}"),
    }
}

fn fmt_opt<T>(v: Option<T>, f: impl Fn(T) -> String) -> String {
    v.map(f).unwrap_or_else(|| "-".into())
}

pub fn run(args: CompareMethodsArgs) -> Result<ExitCode> {
    let sections = read_sections(&args.input)?;
    let reference = match &args.reference {
        Some(p) => Some(read_trimesh(p)?),
        None => None,
    };
    let progress = !args.json && std::io::stderr().is_terminal();
    let mut rows = Vec::new();
    for (name, method) in [
        ("delaunay", Method::Delaunay),
        ("implicit", Method::Implicit),
    ] {
        let options = Options {
            method,
            depth: args.depth,
            progress,
            ..Default::default()
        };
        let t = std::time::Instant::now();
        let row = match slice2solid::reconstruct(&sections, &options) {
            Ok(solid) => {
                let seconds = t.elapsed().as_secs_f64();
                let check = check_mesh(&solid.surface, Some(&sections));
                let compare = reference
                    .as_ref()
                    .map(|r| compare_meshes(&solid.surface, r, DEFAULT_SAMPLES, 0));
                Row {
                    method: name.into(),
                    status: "ok".into(),
                    seconds: Some(seconds),
                    triangles: Some(solid.surface.triangles.len()),
                    check: Some(check),
                    compare,
                    report: Some(solid.report),
                }
            }
            Err(e) => Row {
                method: name.into(),
                status: failed(e),
                seconds: None,
                triangles: None,
                check: None,
                compare: None,
                report: None,
            },
        };
        rows.push(row);
    }
    if args.json {
        super::print_json(&rows)?;
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{}{}",
        args.input.display(),
        args.reference
            .as_ref()
            .map(|r| format!(" vs {}", r.display()))
            .unwrap_or_default()
    );
    println!(
        "{:<9} {:>8} {:>9} {:>5} {:>5} {:>6} {:>8} {:>6} {:>10} {:>7} {:>10} {:>10}",
        "method",
        "time_s",
        "triangles",
        "genus",
        "comps",
        "closed",
        "manifold",
        "selfx",
        "sect_worst",
        "iou",
        "chamfer_l1",
        "hausdorff"
    );
    for r in &rows {
        if r.status != "ok" {
            println!("{:<9} {}", r.method, r.status);
            continue;
        }
        let c = r.check.as_ref();
        let m = r.compare.as_ref();
        println!(
            "{:<9} {:>8} {:>9} {:>5} {:>5} {:>6} {:>8} {:>6} {:>10} {:>7} {:>10} {:>10}",
            r.method,
            fmt_opt(r.seconds, |s| format!("{s:.2}")),
            fmt_opt(r.triangles, |n| n.to_string()),
            fmt_opt(c, |c| c.genus.to_string()),
            fmt_opt(c, |c| c.components.to_string()),
            fmt_opt(c, |c| if c.closed { "yes" } else { "no" }.to_string()),
            fmt_opt(c, |c| if c.manifold { "yes" } else { "no" }.to_string()),
            fmt_opt(c, |c| c.self_intersections.to_string()),
            fmt_opt(c.and_then(|c| c.worst_section.as_ref()), |w| format!(
                "{:.3e}",
                w.relative
            )),
            fmt_opt(m, |m| format!("{:.4}", m.iou)),
            fmt_opt(m, |m| format!("{:.3e}", m.chamfer_l1)),
            fmt_opt(m, |m| format!("{:.3e}", m.hausdorff)),
        );
    }
    println!("sect_worst: largest relative symmetric difference between a mesh section and its input section; distances relative to the reference's bounding-box diagonal");
    Ok(ExitCode::SUCCESS)
}
