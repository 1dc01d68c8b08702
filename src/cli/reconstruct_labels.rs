//! `slice2solid reconstruct IN -o OUT.EXT --all-labels [--method implicit] [--interfaces NET.ply]
//! [--tets T.vtk]`: every label at once as a partition of space
//! (`slice2solid::reconstruct_partition`); one surface per label written as `OUT.labelL.EXT`, and a
//! line per label on stderr; the Delaunay method also writes its labelled tetrahedra.
use crate::ReconstructArgs;
use slice2solid::eval::topology::analyze;
use slice2solid::io::mesh::{write_labelled_network, write_trimesh};
use slice2solid::io::{read_sections_of_roi, write_labelled_tets, ReadOptions};
use slice2solid::reconstruct_partition;
use slice2solid::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `out.obj` → `out.label3.obj`.
pub fn labelled_path(path: &Path, label: i32) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let name = match path.extension() {
        Some(e) => format!("{stem}.label{label}.{}", e.to_string_lossy()),
        None => format!("{stem}.label{label}"),
    };
    path.with_file_name(name)
}

pub fn run(args: ReconstructArgs) -> Result<ExitCode> {
    let sections = read_sections_of_roi(
        &args.input,
        &ReadOptions {
            strict: args.strict,
        },
        None,
    )?;
    let options = super::reconstruct::options(&args);
    let partition = reconstruct_partition(&sections, &options)?;
    let mut report = partition.report.clone();
    for (label, surface) in partition.labels.iter().zip(&partition.surfaces) {
        let path = labelled_path(&args.output, *label);
        write_trimesh(&path, surface)?;
        let topo = analyze(surface);
        let genus: i64 = topo.components.iter().filter_map(|c| c.genus).sum();
        report.count(
            &format!("label{label}.triangles"),
            surface.triangles.len() as u64,
        );
        report.count(
            &format!("label{label}.components"),
            topo.components.len() as u64,
        );
        eprintln!(
            "{}: label {label}, {} triangles, {} component(s), genus {genus}{}",
            path.display(),
            surface.triangles.len(),
            topo.components.len(),
            if topo.closed && topo.manifold {
                ""
            } else {
                " (NOT a closed manifold)"
            }
        );
    }
    if let Some(path) = &args.tets {
        match &partition.tets {
            Some(t) => write_labelled_tets(path, t, &partition.tet_labels)?,
            None => {
                return Err(Error::Unavailable(format!(
                    "{}: this method produces no tetrahedra",
                    path.display()
                )))
            }
        }
    }
    if let Some(path) = &args.interfaces {
        write_labelled_network(path, &partition.interfaces, &partition.interface_labels)?;
        eprintln!(
            "{}: {} interface triangles",
            path.display(),
            partition.interfaces.triangles.len()
        );
    }
    for line in super::warnings::lines(&report.warnings, args.all_warnings, args.report.as_deref())
    {
        eprintln!("{line}");
    }
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(&report).expect("report serialises");
        std::fs::write(path, text).map_err(|e| Error::io(path, e))?;
    }
    eprintln!(
        "{} labels in {:.3} s",
        partition.labels.len(),
        report.total_seconds
    );
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_label_goes_before_the_extension() {
        assert_eq!(
            labelled_path(Path::new("d/out.obj"), 3),
            PathBuf::from("d/out.label3.obj")
        );
        assert_eq!(
            labelled_path(Path::new("out"), 12),
            PathBuf::from("out.label12")
        );
    }
}
