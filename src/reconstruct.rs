//! The library's front door: `reconstruct(&Sections, &Options) -> Solid`, whichever method.
use crate::arrangement::{Arrangement, ArrangementOptions};
use crate::error::{Error, Result};
use crate::mesh::{TetMesh, TriMesh};
use crate::sections::Sections;
use serde::Serialize;
use std::collections::BTreeMap;
use std::time::Instant;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    Delaunay,
    Implicit,
}

#[derive(Clone, Debug)]
pub struct Options {
    pub method: Method,
    /// Reconstruct only this label; `None`: every region that is not a hole is inside.
    pub label: Option<i32>,
    /// Octree depth of the implicit method.
    pub depth: u32,
    /// Show a progress bar (the CLI sets it when stderr is a terminal).
    pub progress: bool,
    pub arrangement: ArrangementOptions,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::Delaunay,
            label: None,
            depth: 9,
            progress: false,
            arrangement: ArrangementOptions::default(),
        }
    }
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct Phase {
    pub name: String,
    pub seconds: f64,
}

/// What a run did: per-phase times, counts, warnings. Serialised as the `--report` JSON.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Report {
    pub method: String,
    pub phases: Vec<Phase>,
    pub counts: BTreeMap<String, u64>,
    pub values: BTreeMap<String, f64>,
    pub warnings: Vec<String>,
    pub total_seconds: f64,
    /// Topology of the output surface (combinatorial; self-intersections are left to `check`).
    pub surface: Option<SurfaceTopology>,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct SurfaceTopology {
    pub triangles: usize,
    pub closed: bool,
    pub manifold: bool,
    pub oriented: bool,
    pub components: usize,
    pub euler: i64,
    /// Sum of the genera of the closed, oriented manifold components.
    pub genus: i64,
}

impl Report {
    /// Run `f`, recording its wall time as phase `name`.
    pub fn time<T>(&mut self, name: &str, f: impl FnOnce() -> T) -> T {
        let t = Instant::now();
        let out = f();
        self.phases.push(Phase {
            name: name.to_string(),
            seconds: t.elapsed().as_secs_f64(),
        });
        out
    }
    pub fn count(&mut self, key: &str, n: u64) {
        *self.counts.entry(key.to_string()).or_insert(0) += n;
    }
}

/// A reconstructed solid: its closed oriented boundary, and its tetrahedra when the method has them.
#[derive(Clone, Debug, Default)]
pub struct Solid {
    pub surface: TriMesh,
    pub tets: Option<TetMesh>,
    pub report: Report,
}

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
    let selected = sections.select_label(options.label);
    let arrangement = report.time("arrangement", || {
        Arrangement::build(&selected, &options.arrangement)
    })?;
    report.count("cells", arrangement.cells.len() as u64);
    report.count("faces", arrangement.faces.len() as u64);
    report.warnings.extend(arrangement.warnings.iter().cloned());
    let mut solid = match options.method {
        Method::Delaunay => crate::bm::reconstruct(&selected, &arrangement, options, &mut report)?,
        Method::Implicit => {
            crate::implicit::reconstruct(&selected, &arrangement, options, &mut report)?
        }
    };
    report.total_seconds = start.elapsed().as_secs_f64();
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
