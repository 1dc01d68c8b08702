//! `slice2solid compare-methods INPUT --all-labels [--json] [--depth D]`: both methods' partitions
//! (`reconstruct --all-labels`) of one multi-label input side by side. Per method and label: time,
//! triangles, topology, defects and section agreement, as `check --partition` judges the domains;
//! per method: are the domains disjoint, where do sections say two labels touch but the domains
//! leave a gap; per label: how far the two methods' domains agree (IoU, Chamfer, Hausdorff).
use crate::CompareMethodsArgs;
use serde::Serialize;
use slice2solid::eval::compare::{compare_meshes, CompareReport, DEFAULT_SAMPLES};
use slice2solid::eval::partition::{check_partition, PartitionReport};
use slice2solid::io::read_sections;
use slice2solid::{reconstruct_partition, Method, Options, Partition, Result, Sections};
use std::process::ExitCode;

/// One method's run.
#[derive(Serialize)]
struct MethodRun {
    method: String,
    /// "ok", "unavailable: ..." or "error: ...".
    status: String,
    seconds: Option<f64>,
    check: Option<PartitionReport>,
    #[serde(skip)]
    partition: Option<Partition>,
}

/// Per label, the Delaunay domain against the implicit one.
#[derive(Serialize)]
struct Agreement {
    label: i32,
    compare: CompareReport,
}

#[derive(Serialize)]
struct Comparison {
    methods: Vec<MethodRun>,
    agreement: Vec<Agreement>,
}

fn run_method(sections: &Sections, method: Method, args: &CompareMethodsArgs) -> MethodRun {
    let options = Options {
        method,
        depth: args.depth,
        ..Default::default()
    };
    let name = format!("{method:?}").to_lowercase();
    let t = std::time::Instant::now();
    let outcome = reconstruct_partition(sections, &options).and_then(|p| {
        let seconds = t.elapsed().as_secs_f64();
        let domains: Vec<_> = (p.labels.iter().zip(&p.surfaces))
            .map(|(l, s)| (*l, format!("label {l}"), s.clone()))
            .collect();
        Ok((p, seconds, check_partition(&domains, Some(sections))?))
    });
    match outcome {
        Ok((p, seconds, check)) => MethodRun {
            method: name,
            status: "ok".into(),
            seconds: Some(seconds),
            check: Some(check),
            partition: Some(p),
        },
        Err(e) => MethodRun {
            method: name,
            status: super::compare_methods::failed(e),
            seconds: None,
            check: None,
            partition: None,
        },
    }
}

/// Per label both methods have, the Delaunay domain compared with the implicit one.
fn agreement(runs: &[MethodRun]) -> Vec<Agreement> {
    let [Some(a), Some(b)] = [&runs[0].partition, &runs[1].partition] else {
        return Vec::new();
    };
    (a.labels.iter().zip(&a.surfaces))
        .filter_map(|(l, s)| {
            let i = b.labels.iter().position(|m| m == l)?;
            Some(Agreement {
                label: *l,
                compare: compare_meshes(s, &b.surfaces[i], DEFAULT_SAMPLES, 0),
            })
        })
        .collect()
}

pub fn run(args: CompareMethodsArgs) -> Result<ExitCode> {
    let sections = read_sections(&args.input)?;
    let methods: Vec<MethodRun> = [Method::Delaunay, Method::Implicit]
        .into_iter()
        .map(|m| run_method(&sections, m, &args))
        .collect();
    let comparison = Comparison {
        agreement: agreement(&methods),
        methods,
    };
    if args.json {
        super::print_json(&comparison)?;
    } else {
        print_tables(&args, &comparison);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_tables(args: &CompareMethodsArgs, c: &Comparison) {
    println!("{} (every label at once)", args.input.display());
    println!(
        "{:<9} {:>6} {:>8} {:>9} {:>5} {:>5} {:>6} {:>8} {:>6} {:>10}",
        "method",
        "label",
        "time_s",
        "triangles",
        "genus",
        "comps",
        "closed",
        "manifold",
        "selfx",
        "sect_worst"
    );
    for run in &c.methods {
        let Some(check) = &run.check else {
            println!("{:<9} {}", run.method, run.status);
            continue;
        };
        for d in &check.domains {
            let k = &d.check;
            println!(
                "{:<9} {:>6} {:>8.2} {:>9} {:>5} {:>5} {:>6} {:>8} {:>6} {:>10}",
                run.method,
                d.label,
                run.seconds.unwrap_or(0.0),
                k.triangles,
                k.genus,
                k.components,
                if k.closed { "yes" } else { "no" },
                if k.manifold { "yes" } else { "no" },
                k.self_intersections,
                (k.worst_section.as_ref()).map_or("-".into(), |w| format!("{:.3e}", w.relative)),
            );
        }
        let crossings: usize = check.pairs.iter().map(|p| p.crossings).sum();
        println!(
            "{:<9} partition: {} ({} crossing pairs between domains, {} gaps where sections touch)",
            run.method,
            if check.valid { "valid" } else { "NOT valid" },
            crossings,
            check.gaps
        );
    }
    if !c.agreement.is_empty() {
        println!(
            "{:<6} {:>7} {:>10} {:>10}",
            "label", "iou", "chamfer_l1", "hausdorff"
        );
        for a in &c.agreement {
            println!(
                "{:<6} {:>7.4} {:>10.3e} {:>10.3e}",
                a.label, a.compare.iou, a.compare.chamfer_l1, a.compare.hausdorff
            );
        }
        println!("iou etc.: the Delaunay domain against the implicit one, distances relative to the implicit domain's bounding-box diagonal");
    }
    println!("sect_worst: largest relative symmetric difference between a domain's section and its label's input section");
}
