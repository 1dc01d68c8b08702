use crate::ReconstructArgs;
use slice2solid::io::{read_sections_of_roi, write_surface, write_tets, ReadOptions};
use slice2solid::{Error, Options, Result};
use std::io::IsTerminal;
use std::process::ExitCode;

pub fn run(args: ReconstructArgs) -> Result<ExitCode> {
    if args.all_labels {
        return super::reconstruct_labels::run(args);
    }
    let sections = read_sections_of_roi(
        &args.input,
        &ReadOptions {
            strict: args.strict,
        },
        args.roi.as_deref(),
    )?;
    let options = options(&args);
    let solid = slice2solid::reconstruct(&sections, &options)?;
    write_surface(&args.output, &solid.surface, &sections, options.label)?;
    if let Some(path) = &args.tets {
        match &solid.tets {
            Some(t) => write_tets(path, t, &sections, options.label)?,
            None => {
                return Err(Error::Unavailable(format!(
                    "{}: this method produces no tetrahedra",
                    path.display()
                )))
            }
        }
    }
    for line in super::warnings::lines(
        &solid.report.warnings,
        args.all_warnings,
        args.report.as_deref(),
    ) {
        eprintln!("{line}");
    }
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(&solid.report).expect("report serialises");
        std::fs::write(path, text).map_err(|e| Error::io(path, e))?;
    }
    let memory = solid.report.peak_memory.map_or(String::new(), |m| {
        format!(
            ", peak memory {:.1} MiB",
            m.bytes as f64 / (1u64 << 20) as f64
        )
    });
    eprintln!(
        "{}: {} triangles in {:.3} s{memory}",
        args.output.display(),
        solid.surface.triangles.len(),
        solid.report.total_seconds
    );
    Ok(ExitCode::SUCCESS)
}

/// The library's options from the command line.
pub fn options(args: &ReconstructArgs) -> Options {
    Options {
        method: match args.method {
            crate::Method::Delaunay => slice2solid::Method::Delaunay,
            crate::Method::Implicit => slice2solid::Method::Implicit,
        },
        label: args.label,
        depth: args.depth,
        progress: !args.quiet && std::io::stderr().is_terminal(),
        delaunay: slice2solid::DelaunayOptions {
            branching: !args.no_branching,
            cutting: !args.no_cutting,
            thicken_flat_zones: !args.no_thicken,
            keep_topology: args.keep_topology,
            shared_samples: !args.no_shared_samples,
            collar: args.collar,
            smooth: args.smooth.then(|| slice2solid::Smoothing {
                rounds: args.smooth_rounds,
                sweeps: args.smooth_sweeps,
                order: args.smooth_order,
                ..Default::default()
            }),
        },
        ..Default::default()
    }
}
