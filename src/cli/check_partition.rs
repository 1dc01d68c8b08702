//! `slice2solid check --partition A.obj B.obj ... [--sections IN] [--json]`: labelled domains as one
//! partition (`slice2solid::eval::partition`). Exit status 1 unless every domain is a closed
//! oriented self-intersection-free manifold and every two are disjoint (gaps are reported only).
use crate::CheckArgs;
use slice2solid::eval::partition::{check_partition, PartitionReport};
use slice2solid::io::mesh::read_trimesh;
use slice2solid::io::read_sections;
use slice2solid::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The label of a `--partition` argument: `PATH:LABEL`, else the N of a file named `*.labelN.*`,
/// else `position` (1-based).
pub fn labelled_path(arg: &str, position: usize) -> (PathBuf, i32) {
    let (path, label) = super::slice::parse_mesh_arg(arg);
    let from_name = || {
        let name = path.file_name()?.to_str()?;
        name.split('.')
            .find_map(|part| part.strip_prefix("label")?.parse::<i32>().ok())
    };
    let label = label.or_else(from_name).unwrap_or(position as i32);
    (path, label)
}

pub fn run(args: &CheckArgs) -> Result<ExitCode> {
    if args.partition.len() < 2 {
        return Err(Error::input(
            "--partition",
            "a partition needs at least two domains (one surface per label)",
        ));
    }
    let mut domains = Vec::with_capacity(args.partition.len());
    for (i, arg) in args.partition.iter().enumerate() {
        let (path, label) = labelled_path(arg, i + 1);
        if let Some((_, other, _)) = domains.iter().find(|(l, _, _)| *l == label) {
            return Err(Error::input(
                path.display().to_string(),
                format!("label {label} is also the label of {other}"),
            ));
        }
        domains.push((label, path.display().to_string(), read_trimesh(&path)?));
    }
    let sections = match &args.sections {
        Some(p) => Some(read_sections(p)?),
        None => None,
    };
    let report = check_partition(&domains, sections.as_ref())?;
    if args.json {
        super::print_json(&report)?;
    } else {
        print_report(&report, args.sections.as_deref());
    }
    Ok(if report.valid {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn yes(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "NO"
    }
}

fn print_report(r: &PartitionReport, sections: Option<&Path>) {
    println!("label  closed  manifold  oriented  self-int  components  volume        worst section  file");
    for d in &r.domains {
        let c = &d.check;
        let worst = c
            .worst_section
            .as_ref()
            .map_or("-".to_string(), |w| format!("{:.3e}", w.relative));
        println!(
            "{:>5}  {:>6}  {:>8}  {:>8}  {:>8}  {:>10}  {:<12.6e}  {:>13}  {}",
            d.label,
            yes(c.closed),
            yes(c.manifold),
            yes(c.oriented),
            c.self_intersections + c.overlapping_coplanar_pairs,
            c.components,
            c.volume,
            worst,
            d.name
        );
    }
    for p in &r.pairs {
        let [a, b] = p.labels;
        print!(
            "labels {a}-{b}: interface {} triangles, area {:.6e}",
            p.interface_triangles, p.interface_area
        );
        if let Some(n) = p.section_contact_planes {
            print!("; touching in {n} planes of the sections");
        }
        println!();
        if p.coincident_same_orientation > 0 {
            println!(
                "  OVERLAP: {} triangles of both labels coincide with the same orientation",
                p.coincident_same_orientation
            );
        }
        if let (Some([i, j]), Some(x)) = (p.crossing_example, p.crossing_at) {
            println!(
                "  OVERLAP: {} crossing triangle pairs, e.g. triangle {i} of label {a} and {j} of label {b}, near ({:.6}, {:.6}, {:.6})",
                p.crossings, x[0], x[1], x[2]
            );
        }
        if p.vertices_inside.iter().any(|&n| n > 0) {
            let x = p.inside_example.unwrap_or_default();
            println!(
                "  OVERLAP: {} vertices of label {a} strictly inside label {b}, {} of label {b} inside label {a}, e.g. ({:.6}, {:.6}, {:.6})",
                p.vertices_inside[0], p.vertices_inside[1], x[0], x[1], x[2]
            );
        }
        if p.gap {
            println!(
                "  GAP: the sections say labels {a} and {b} touch, the domains share no interface"
            );
        }
    }
    if let Some(s) = sections {
        println!("(sections: {}, per label)", s.display());
    }
    println!(
        "  => {}{}",
        if r.valid {
            "a valid partition"
        } else {
            "NOT a partition"
        },
        if r.gaps > 0 {
            format!(" ({} gaps)", r.gaps)
        } else {
            String::new()
        }
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_of_partition_arguments() {
        assert_eq!(labelled_path("a.obj:7", 1), ("a.obj".into(), 7));
        assert_eq!(
            labelled_path("out/x.label3.obj", 1),
            ("out/x.label3.obj".into(), 3)
        );
        assert_eq!(labelled_path("b.obj", 2), ("b.obj".into(), 2));
    }
}
