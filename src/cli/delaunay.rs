use crate::{DelaunayArgs, Oracle};
use slice2solid::delaunay::{xyz, Delaunay};
use slice2solid::{Error, Result};
use std::fmt::Write as _;
use std::process::ExitCode;
use std::time::Instant;

pub fn run(args: DelaunayArgs) -> Result<ExitCode> {
    let points = xyz::read_xyz(&args.points)?;
    let mut deferred = None;
    let (tets, vertices, seconds, kernel_bytes) = match args.oracle {
        None => {
            let start = Instant::now();
            let threads = args.threads.unwrap_or_else(rayon::current_num_threads);
            let dt = Delaunay::try_new_with_threads(&points, threads)?;
            deferred = Some(dt.parallel_deferred());
            let seconds = start.elapsed().as_secs_f64();
            let tets: Vec<[u32; 4]> = dt.tets().map(|t| dt.tet_vertices(t)).collect();
            let vertices = dt.num_vertices() - dt.duplicates().len();
            (tets, vertices, seconds, Some(dt.memory_bytes()))
        }
        Some(Oracle::Tetgen) => {
            let (tets, seconds) = run_tetgen(&points)?;
            let mut used = vec![false; points.len()];
            tets.iter().flatten().for_each(|&v| used[v as usize] = true);
            (tets, used.iter().filter(|&&u| u).count(), seconds, None)
        }
    };
    if let Some(path) = &args.tets {
        // canonical order (each tetrahedron from its smallest vertex, orientation kept; sorted):
        // the same file for every thread count
        let mut tets: Vec<[u32; 4]> = tets.iter().map(|&t| canonical_tet(t)).collect();
        tets.sort_unstable();
        let mut s = String::with_capacity(tets.len() * 32);
        for t in &tets {
            let _ = writeln!(s, "{} {} {} {}", t[0], t[1], t[2], t[3]);
        }
        std::fs::write(path, s).map_err(|e| Error::io(path, e))?;
    }
    let peak = peak_rss_bytes();
    if args.json {
        let mut j = serde_json::json!({
            "points": points.len(),
            "vertices": vertices,
            "tets": tets.len(),
            "seconds": seconds,
            "peak_bytes": peak.or(kernel_bytes),
        });
        if let Some(k) = kernel_bytes {
            j["kernel_bytes"] = k.into();
        }
        if let Some(d) = deferred {
            j["deferred"] = d.into();
        }
        println!("{j}");
    } else {
        println!(
            "{} points, {} vertices, {} tetrahedra in {:.3} s (peak memory {} MB)",
            points.len(),
            vertices,
            tets.len(),
            seconds,
            peak.or(kernel_bytes).unwrap_or(0) / (1 << 20)
        );
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(feature = "tetgen")]
fn run_tetgen(points: &[[f64; 3]]) -> Result<(Vec<[u32; 4]>, f64)> {
    let start = Instant::now();
    let tets = slice2solid::delaunay::tetgen::tetgen_delaunay(points)?;
    Ok((tets, start.elapsed().as_secs_f64()))
}

#[cfg(not(feature = "tetgen"))]
fn run_tetgen(_points: &[[f64; 3]]) -> Result<(Vec<[u32; 4]>, f64)> {
    Err(Error::Unavailable(
        "the TetGen oracle is not built in: rebuild with `--features tetgen`".into(),
    ))
}

/// Peak resident set size of this process (VmHWM), where /proc is available.
fn peak_rss_bytes() -> Option<usize> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// `t` as its even permutation with the smallest vertex first (the orientation is kept).
fn canonical_tet(t: [u32; 4]) -> [u32; 4] {
    let k = (0..4).min_by_key(|&k| t[k]).unwrap();
    // an even permutation putting position k first
    let p: [usize; 4] = match k {
        0 => [0, 1, 2, 3],
        1 => [1, 0, 3, 2],
        2 => [2, 3, 0, 1],
        _ => [3, 2, 1, 0],
    };
    let u = p.map(|i| t[i]);
    // then rotate the last three (even) so that the smallest of them comes second
    let r = (1..4).min_by_key(|&k| u[k]).unwrap();
    match r {
        1 => u,
        2 => [u[0], u[2], u[3], u[1]],
        _ => [u[0], u[3], u[1], u[2]],
    }
}
