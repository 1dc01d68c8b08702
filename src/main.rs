//! The command line: parse arguments, call the library, print. Each subcommand's printing lives in `cli/`.
use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;

mod cli;

/// The assembly and the collar make and drop many small vectors per cell; glibc's allocator
/// fragments on dense inputs (a third of a 200-plane run in `malloc`, docs/design/scale.md).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[derive(Parser)]
#[command(
    name = "slice2solid",
    version,
    about = "Reconstruct a solid from planar cross-sections of arbitrary orientation"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Method {
    /// Boissonnat–Memari Delaunay pruning (the default)
    Delaunay,
    /// Bermano et al. mean-value implicit interpolation
    Implicit,
}

/// Plane placements of `slice` (see `slice2solid::slice::SliceMode` for the exact rules)
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SliceMode {
    /// Random orientations through the central 80% of the bounding box
    Random,
    /// Perpendicular to the longest bounding-box axis, evenly spaced
    Parallel,
    /// Cycling over x, y, z, evenly spaced on each
    Axes,
    /// Through one line (the longest axis through the box centre), evenly turned over a half-turn
    /// from a seeded start (rotational probe, radial MRI)
    Fan,
    /// Evenly spaced along the longest axis, each tilted by up to 15° in a seeded random direction
    /// (freehand ultrasound sweep)
    Sweep,
    /// Through one line outside the box (along the second-longest axis, beyond the shortest one's
    /// + face), spread across the box (probe rocked on the skin)
    Tilt,
}

#[derive(Subcommand)]
enum Command {
    /// Reconstruct a solid from cross-sections (CSL, JSON or DICOM RT Structure Set)
    Reconstruct(ReconstructArgs),
    /// Check a triangle mesh (closed, manifold, oriented, self-intersections, genus; optionally its sections)
    /// or a tetrahedral mesh (conforming, inverted/flat tets, boundary; optionally against a surface)
    Check(CheckArgs),
    /// Compare a mesh with a reference: IoU, Chamfer, Hausdorff
    Compare(CompareArgs),
    /// Run both methods on one input and print a comparison table
    CompareMethods(CompareMethodsArgs),
    /// 3D Delaunay triangulation of a point file (our kernel, or TetGen as oracle)
    Delaunay(DelaunayArgs),
    /// Cut closed triangle meshes (one per label) with planes and write the cross-sections as CSL
    Slice(SliceArgs),
    /// Draw a surface (shaded, with the input contours over it) as a PNG picture
    Render(RenderArgs),
    /// Describe a cross-section file (CSL, JSON or DICOM RT Structure Set)
    Info(InfoArgs),
}

#[derive(clap::Args)]
pub struct ReconstructArgs {
    pub input: PathBuf,
    /// Output surface (.obj, .ply, .stl, .off, or .vtp: VTK XML with each triangle's input plane and label)
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the tetrahedral mesh (.vtk, .mesh, or .vtu: VTK XML with each tetrahedron's label)
    #[arg(long)]
    pub tets: Option<PathBuf>,
    /// Write a JSON report (timings, counts, topology, warnings)
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Reconstruct only this label (default: every region that is not a hole)
    #[arg(long, conflicts_with = "roi")]
    pub label: Option<i32>,
    /// Reconstruct every label at once as a partition of space (either method): one surface per
    /// label, `OUT.labelL.EXT`, with shared interfaces; with --tets (Delaunay) the tetrahedra
    /// with a label each
    #[arg(long, conflicts_with_all = ["label", "roi"])]
    pub all_labels: bool,
    /// With --all-labels: write the interface network (.ply, the two labels of each triangle as
    /// face properties `label0 label1`; the exterior is label 0)
    #[arg(long, requires = "all_labels")]
    pub interfaces: Option<PathBuf>,
    /// DICOM RT Structure Set input: reconstruct only the ROI of this name (ROIs may overlap, so
    /// the others are not even validated)
    #[arg(long)]
    pub roi: Option<String>,
    #[arg(long, value_enum, default_value = "delaunay")]
    pub method: Method,
    /// Octree depth for the implicit method
    #[arg(long, default_value_t = 9)]
    pub depth: u32,
    /// No progress bar
    #[arg(short, long)]
    pub quiet: bool,
    /// Print every warning (by default each kind is shown three times, then counted; the report
    /// always has them all)
    #[arg(long)]
    pub all_warnings: bool,
    /// Delaunay method: do not sample the branching diagram (to study what it contributes)
    #[arg(long)]
    pub no_branching: bool,
    /// Delaunay method: do not sample the cutting diagram
    #[arg(long)]
    pub no_cutting: bool,
    /// Delaunay method: leave flat zones out of the solid instead of thickening them (warned)
    #[arg(long)]
    pub no_thicken: bool,
    /// Delaunay method: height of the collar, relative to the bounding-box diagonal: near every
    /// plane the solid is the prism over its section, so sections just off a plane are that
    /// plane's section (0: no collar, the pruned complex as it is)
    #[arg(long, default_value_t = slice2solid::COLLAR_HEIGHT, value_name = "H")]
    pub collar: f64,
    /// Delaunay method: keep the raw Boissonnat–Memari topology (by default, voids between the
    /// planes and handles that no section witnesses are filled and closed)
    #[arg(long)]
    pub keep_topology: bool,
    /// Delaunay method: refine the surface between the planes and fair it (thin-plate,
    /// bi-Laplacian), every contour and section kept exactly where the input puts it; the
    /// tetrahedra (`--tets`) follow
    #[arg(long)]
    pub smooth: bool,
    /// With --smooth: rounds of refinement between the planes (each splits every surface edge
    /// from one plane to another; 2: three points on such an edge)
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub smooth_rounds: u32,
    /// With --smooth: Gauss-Seidel sweeps of the fairing
    #[arg(long, default_value_t = 10, value_name = "N")]
    pub smooth_sweeps: u32,
    /// With --smooth: 2 fairs a thin plate (bi-Laplacian), 1 a membrane (Laplacian)
    #[arg(long, default_value_t = 2, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=2))]
    pub smooth_order: u32,
    /// Delaunay method: each cell inserts its own diagram samples only, not those of the other
    /// side of its faces (the two sides of a face may then be triangulated differently and the
    /// tetrahedra do not conform there; to study what sharing contributes)
    #[arg(long)]
    pub no_shared_samples: bool,
    /// Refuse input that would be repaired (plane equations off their vertices, self-intersecting
    /// contours, touching or overlapping components): each repair becomes a located error
    #[arg(long)]
    pub strict: bool,
}

#[derive(clap::Args)]
pub struct CheckArgs {
    /// A triangle surface (.obj, .ply, .stl, .off) or a tetrahedral mesh (.vtk, .mesh)
    #[arg(required_unless_present = "partition", conflicts_with = "partition")]
    pub mesh: Option<PathBuf>,
    /// Check labelled domains as one partition: each `SURFACE` or `SURFACE:LABEL` (without `:LABEL`,
    /// the N of a name `*.labelN.*`, else the position 1, 2, ...): every domain a closed oriented
    /// manifold, every two disjoint except shared interface triangles; with --sections, each
    /// label's sections against its domain
    #[arg(long, num_args = 1.., conflicts_with = "surface")]
    pub partition: Vec<String>,
    /// Compare the surface's sections with these input sections (CSL or JSON; surfaces only)
    #[arg(long)]
    pub sections: Option<PathBuf>,
    /// Tetrahedral mesh only: compare its boundary with this surface (exact vertex positions)
    #[arg(long)]
    pub surface: Option<PathBuf>,
    #[arg(long)]
    pub json: bool,
}

#[derive(clap::Args)]
pub struct CompareArgs {
    pub mesh: PathBuf,
    pub reference: PathBuf,
    #[arg(long)]
    pub json: bool,
    /// Surface samples each way
    #[arg(long, default_value_t = 25_000)]
    pub samples: usize,
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

#[derive(clap::Args)]
pub struct CompareMethodsArgs {
    pub input: PathBuf,
    #[arg(long, conflicts_with = "all_labels")]
    pub reference: Option<PathBuf>,
    /// Compare the methods' partitions of every label at once (`reconstruct --all-labels`): per
    /// label its domain's check and section agreement, per method disjointness and gaps, and per
    /// label the Delaunay domain against the implicit one
    #[arg(long)]
    pub all_labels: bool,
    #[arg(long)]
    pub json: bool,
    #[arg(long, default_value_t = 9)]
    pub depth: u32,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Oracle {
    Tetgen,
}

#[derive(clap::Args)]
pub struct DelaunayArgs {
    /// One `x y z` per line
    pub points: PathBuf,
    /// Write one tetrahedron per line as four 0-based point indices
    #[arg(long)]
    pub tets: Option<PathBuf>,
    #[arg(long)]
    pub json: bool,
    #[arg(long, value_enum)]
    pub oracle: Option<Oracle>,
    /// Threads of our kernel (default: the number of cores; 1 is the sequential kernel). The
    /// tetrahedra are the same for every count
    #[arg(long)]
    pub threads: Option<usize>,
}

#[derive(clap::Args)]
pub struct SliceArgs {
    /// Closed meshes, each `MESH` or `MESH:LABEL`. One mesh without a label is label 1; several make
    /// labelled sections partitioning every plane (a mesh without `:LABEL` takes its position, 1, 2, …):
    /// where meshes overlap, the one listed first keeps the overlap
    #[arg(required = true, num_args = 1..)]
    pub meshes: Vec<String>,
    #[arg(short, long)]
    pub output: PathBuf,
    #[arg(long, default_value_t = 10)]
    pub planes: usize,
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    #[arg(long, value_enum, default_value = "random")]
    pub mode: SliceMode,
}

#[derive(clap::Args)]
pub struct RenderArgs {
    /// A triangle surface (.obj, .ply, .stl, .off)
    pub mesh: PathBuf,
    /// Draw the contours of these cross-sections over the surface (CSL, JSON or RT Structure Set)
    #[arg(long)]
    pub sections: Option<PathBuf>,
    /// The picture (.png)
    #[arg(short, long)]
    pub output: PathBuf,
    /// Image size in pixels, WxH
    #[arg(long, default_value = "800x600")]
    pub size: slice2solid::render::Size,
    /// Camera direction in degrees: azimuth about +z from +x, elevation above the xy plane
    #[arg(long, default_value = "30,20", allow_hyphen_values = true)]
    pub view: slice2solid::render::View,
}

#[derive(clap::Args)]
pub struct InfoArgs {
    pub input: PathBuf,
    #[arg(long)]
    pub json: bool,
    /// DICOM RT Structure Set input: describe only the ROI of this name
    #[arg(long)]
    pub roi: Option<String>,
    /// Also build the plane arrangement and print its size
    #[arg(long)]
    pub cells: bool,
    /// Refuse input that would be repaired (plane equations off their vertices, self-intersecting
    /// contours, touching or overlapping components): each repair becomes a located error
    #[arg(long)]
    pub strict: bool,
}

fn main() -> ExitCode {
    // Rust ignores SIGPIPE, which turns a closed pipe (`| head`) into a panic inside println!:
    // take the default action instead, like every other command-line tool
    #[cfg(unix)]
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Reconstruct(a) => cli::reconstruct::run(a),
        Command::Check(a) => cli::check::run(a),
        Command::Compare(a) => cli::compare::run(a),
        Command::CompareMethods(a) if a.all_labels => cli::compare_methods_labels::run(a),
        Command::CompareMethods(a) => cli::compare_methods::run(a),
        Command::Delaunay(a) => cli::delaunay::run(a),
        Command::Slice(a) => cli::slice::run(a),
        Command::Render(a) => cli::render::run(a),
        Command::Info(a) => cli::info::run(a),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
