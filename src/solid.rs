//! What a reconstruction is asked and what it gives back, shared by the pipeline and both engines:
//! [`Options`], [`Solid`], [`Report`]. Imports no engine, so engines and pipeline depend on it and not
//! on each other.
use crate::arrangement::ArrangementOptions;
use crate::mesh::{TetMesh, TriMesh};
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
    /// Stages of the Delaunay pruning engine that can be switched off (to study what each contributes).
    pub delaunay: DelaunayOptions,
}

/// Stages of the Delaunay pruning engine; all on by default. Switching one off changes the result:
/// they are options (never environment variables) so that a caller sees what it asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DelaunayOptions {
    /// Sample the branching (Moebius) diagram of every section (paper §3).
    pub branching: bool,
    /// Sample the cutting diagram where a site's cell on a face is disconnected.
    pub cutting: bool,
    /// Thicken flat zones (section regions neither neighbouring cell attaches to) into thin slabs;
    /// off, they are left out of the solid and warned.
    pub thicken_flat_zones: bool,
    /// Both cells of a face insert the diagram samples of both sides (`bm::shared_samples`), so
    /// that they triangulate the face alike: what makes the kept tetrahedra one conforming complex.
    /// Off, each cell inserts its own samples only and the two sides of a face may be triangulated
    /// differently (counted as `nonconforming_faces`, warned): to study what sharing contributes.
    pub shared_samples: bool,
    /// Keep the raw Boissonnat–Memari topology: voids between the planes that no section witnesses
    /// are otherwise taken into the solid (`bm::voids`), and handles that none witnesses closed by
    /// membranes of tetrahedra (`bm::tunnels`) or cut where no section is (`bm::cuts`).
    pub keep_topology: bool,
    /// Height of the collar, relative to the bounding-box diagonal (0: none): near every plane the
    /// solid is the prism over its section (`bm::collar`), so that sections just off a plane are the
    /// plane's section, not the folds of the pruned complex's vertex links there.
    pub collar: f64,
    /// Refine the surface between the planes and fair it, every section kept exactly
    /// (`bm::smooth`); `None`: the pruned complex's piecewise-linear surface as it is.
    pub smooth: Option<crate::bm::smooth::Smoothing>,
}

/// Default collar height, relative to the bounding-box diagonal: ten times the offset at which
/// outside judges take sections "just off" a plane, far below the sampling of real sections.
pub const COLLAR_HEIGHT: f64 = 1e-4;

impl Default for DelaunayOptions {
    fn default() -> Self {
        DelaunayOptions {
            branching: true,
            cutting: true,
            thicken_flat_zones: true,
            shared_samples: true,
            keep_topology: false,
            collar: COLLAR_HEIGHT,
            smooth: None,
        }
    }
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::Delaunay,
            label: None,
            depth: 9,
            progress: false,
            arrangement: ArrangementOptions::default(),
            delaunay: DelaunayOptions::default(),
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
    /// Names of the reconstructed labels, where the input names them (RTSTRUCT ROI names).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub label_names: BTreeMap<i32, String>,
    pub total_seconds: f64,
    /// Peak resident memory of the process when the reconstruction ended (`memory`: Linux
    /// `VmHWM`, else `getrusage` `ru_maxrss`; absent where the platform does not tell).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_memory: Option<crate::memory::PeakMemory>,
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
        self.note_peak_memory(name);
        out
    }

    /// The peak resident memory now, as value `peak_memory_mib.after.<phase>`: which phase raised
    /// the peak (platforms that do not tell get no entry).
    pub fn note_peak_memory(&mut self, phase: &str) {
        if let Some(peak) = crate::memory::peak_resident() {
            (self.values).insert(format!("peak_memory_mib.after.{phase}"), peak.mib());
        }
    }
    pub fn count(&mut self, key: &str, n: u64) {
        *self.counts.entry(key.to_string()).or_insert(0) += n;
    }
}

/// The label the exterior takes in the outputs of a partition (input labels are positive).
pub const EXTERIOR: i32 = 0;

/// A partition of space into labelled domains (every label at once), and the interfaces between
/// them: what `reconstruct --all-labels` gives, whichever method.
#[derive(Clone, Debug, Default)]
pub struct Partition {
    /// The input labels, increasing.
    pub labels: Vec<i32>,
    /// Per label (same order), its domain's closed oriented surface (outward normals).
    pub surfaces: Vec<TriMesh>,
    /// Every interface triangle once, oriented from the smaller label of its pair to the larger
    /// (the exterior is [`EXTERIOR`]).
    pub interfaces: TriMesh,
    /// Per triangle of `interfaces`, the labels on its two sides (smaller first).
    pub interface_labels: Vec<[i32; 2]>,
    /// The labelled tetrahedra, where the method has them (Delaunay): every tetrahedron of the
    /// domains, positive volume, shared faces matching.
    pub tets: Option<TetMesh>,
    /// Per tetrahedron of `tets`, its label.
    pub tet_labels: Vec<i32>,
    pub report: Report,
}

/// A reconstructed solid: its closed oriented boundary, and its tetrahedra when the method has them.
#[derive(Clone, Debug, Default)]
pub struct Solid {
    pub surface: TriMesh,
    pub tets: Option<TetMesh>,
    pub report: Report,
}
