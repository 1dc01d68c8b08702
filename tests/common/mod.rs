//! Helpers shared by the integration tests.
#![allow(dead_code)]
use std::path::PathBuf;
use std::process::{Command, Output};

/// The command-line binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_slice2solid"))
}

/// The JSON a successful run printed (the test fails with the run's stderr otherwise).
pub fn json_of_success(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The twelve CSL files of the shared data (stems). A test over "every shared file" runs exactly
/// these: one missing, or one more that no test names, fails.
pub const SHARED_CSL: [&str; 12] = [
    "Armadillo-23-better",
    "Elephant",
    "Heart-simplified",
    "Horsers",
    "ParallelEight",
    "ParallelEightMore",
    "SideBishop",
    "balloondog",
    "balloondog_box",
    "eight_15",
    "eight_20",
    "hand",
];

/// The shared reference meshes (stems of `data/reference/*.stl`; each CSL file of that name was
/// sliced from it).
pub const SHARED_REFERENCES: [&str; 6] = [
    "Elephant",
    "balloondog",
    "balloondog_box",
    "eight_15",
    "eight_20",
    "hand",
];

/// The shared data directory: `$SLICE2SOLID_SHARED`, else `../shared` beside the checkout. It must
/// exist: the tests read it and fail rather than skip without it.
pub fn shared_dir() -> PathBuf {
    let dir = match std::env::var_os("SLICE2SOLID_SHARED") {
        Some(d) => PathBuf::from(d),
        None => PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared")),
    };
    assert!(
        dir.join("data/csl").is_dir(),
        "shared data not found at {} (set SLICE2SOLID_SHARED or place shared/ beside the checkout)",
        dir.display()
    );
    dir
}

/// The shared CSL file `name` (panics naming the path when it is missing).
pub fn shared_csl(name: &str) -> PathBuf {
    let p = shared_dir().join(format!("data/csl/{name}.csl"));
    assert!(p.is_file(), "missing shared file {}", p.display());
    p
}

/// The shared reference mesh `name` (panics naming the path when it is missing).
pub fn shared_reference(name: &str) -> PathBuf {
    let p = shared_dir().join(format!("data/reference/{name}.stl"));
    assert!(p.is_file(), "missing shared reference {}", p.display());
    p
}

/// The shared reference mesh `mesh` cut by `planes` planes of `mode` (seed `seed`), written as CSL
/// and read back like a user's file.
pub fn sliced(
    mesh: &str,
    planes: usize,
    seed: u64,
    mode: slice2solid::slice::SliceMode,
) -> slice2solid::Sections {
    use slice2solid::slice::{make_planes, slice_mesh};
    let m = slice2solid::io::mesh::read_trimesh(&shared_reference(mesh)).unwrap();
    let s = slice_mesh(&m, &make_planes(&m, planes, seed, mode)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir
        .path()
        .join(format!("{mesh}_{mode:?}_{planes}_{seed}.csl"));
    slice2solid::io::write_sections(&path, &s).unwrap();
    slice2solid::io::read_sections(&path).unwrap()
}

/// Every `*.csl` file of the shared data, sorted; exactly the files of [`SHARED_CSL`].
pub fn shared_csl_files() -> Vec<PathBuf> {
    let dir = shared_dir().join("data/csl");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| {
            e.unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
                .path()
        })
        .filter(|p| p.extension().is_some_and(|x| x == "csl"))
        .collect();
    files.sort();
    let stems: Vec<String> = files
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    let mut expected: Vec<&str> = SHARED_CSL.to_vec();
    expected.sort();
    assert_eq!(stems, expected, "shared CSL files in {}", dir.display());
    files
}

/// The exact check of a solid's tetrahedra with its surface, and whether their boundary is that
/// surface.
pub fn check_solid_tets(solid: &slice2solid::Solid) -> (slice2solid::eval::tets::TetCheck, bool) {
    let tets = solid.tets.as_ref().expect("the complex has tetrahedra");
    let t = slice2solid::eval::tets::check_tets(tets, Some(&solid.surface));
    let equal = t
        .surface
        .as_ref()
        .is_some_and(|s| s.boundary_equals_surface);
    (t, equal)
}

/// A ball inside the figure eight: the inside candidate of a 9³ grid farthest from the mesh's
/// vertices, radius half that distance, halved until the ball's vertices are all inside and no
/// triangle of it crosses the mesh.
pub fn ball_inside(mesh: &slice2solid::TriMesh) -> ([f64; 3], f64) {
    let b = slice2solid::eval::bvh::Aabb::of_points(&mesh.vertices);
    use slice2solid::eval::partition::{check_pair, Location, MeshLocator};
    let locator = MeshLocator::new(mesh);
    let mut best = ([0.0; 3], 0.0);
    for i in 1..10 {
        for j in 1..10 {
            for k in 1..10 {
                let f = [i, j, k].map(|x| x as f64 / 10.0);
                let c: [f64; 3] = std::array::from_fn(|a| b.lo[a] + f[a] * (b.hi[a] - b.lo[a]));
                if locator.locate(c) != Location::Inside {
                    continue;
                }
                let d = mesh
                    .vertices
                    .iter()
                    .map(|&v| (0..3).map(|a| (v[a] - c[a]).powi(2)).sum::<f64>().sqrt())
                    .fold(f64::INFINITY, f64::min);
                if d > best.1 {
                    best = (c, d);
                }
            }
        }
    }
    let (c, mut r) = (best.0, 0.5 * best.1);
    loop {
        let ball = slice2solid::eval::shapes::icosphere(c, r, 3);
        let p = check_pair(mesh, &ball);
        if p.crossings == 0 && p.vertices_inside[1] == ball.vertices.len() {
            return (c, r);
        }
        r *= 0.5;
    }
}
