//! Synthetic partitions of space with a known answer, for multi-label slicing and `check --partition`:
//! the slicer's input (meshes in priority order), the truth's domain of every label as one closed
//! mesh, and the interface between every two touching labels as triangles.
use super::LabelledMesh;
use crate::eval::shapes::{cuboid, cylinder, grid_box, icosphere, inverted, merged};
use crate::mesh::TriMesh;

/// A partition with a known answer.
#[derive(Clone, Debug)]
pub struct SyntheticPartition {
    pub name: String,
    /// The slicer's input, in priority order (where two overlap, the first keeps the overlap).
    pub meshes: Vec<LabelledMesh>,
    /// Per label, its domain in the truth: a closed, outward-oriented mesh (cavities reversed).
    pub domains: Vec<(i32, TriMesh)>,
    /// Per touching pair of labels (lower first), the triangles of their common boundary (as in the
    /// lower label's domain).
    pub interfaces: Vec<(i32, i32, TriMesh)>,
}

fn labelled(name: &str, mesh: &TriMesh, label: i32) -> LabelledMesh {
    LabelledMesh {
        name: name.to_string(),
        mesh: mesh.clone(),
        label,
    }
}

/// A core ball (label 1, radius 0.5, 320 triangles) inside a shell (label 2: the ball of radius 1.2, 1280 triangles,
/// minus the core), centred at (0.1, 0.2, 0.3). Sliced from the core and the big ball, the core first.
pub fn nested_spheres() -> SyntheticPartition {
    let c = [0.1, 0.2, 0.3];
    let core = icosphere(c, 0.5, 2);
    let ball = icosphere(c, 1.2, 3);
    SyntheticPartition {
        name: "nested spheres".into(),
        meshes: vec![labelled("core", &core, 1), labelled("ball", &ball, 2)],
        domains: vec![(1, core.clone()), (2, merged(&ball, &inverted(&core)))],
        interfaces: vec![(1, 2, core)],
    }
}

/// Box A = [0,2]×[0,1]×[0,1] (label 1) and box B = [0,2]×[1,1.8]×[0,1] (label 2) touching along
/// the face y = 1, which runs along the longest axis (so parallel planes cross it too).
/// `conforming`: both grids are 4×2 on that face (the boxes share its 16 triangles); otherwise B's
/// is 3×3, so their sections meet along lines cut at different points.
pub fn touching_boxes(conforming: bool) -> SyntheticPartition {
    let a = grid_box([0.0; 3], [2.0, 1.0, 1.0], [4, 2, 2]);
    let m = if conforming { [4, 2, 2] } else { [3, 3, 3] };
    let b = grid_box([0.0, 1.0, 0.0], [2.0, 1.8, 1.0], m);
    let face = faces_on(&a, |p| p[1] == 1.0);
    SyntheticPartition {
        name: format!(
            "two boxes touching on a face ({})",
            if conforming {
                "conforming"
            } else {
                "different grids"
            }
        ),
        meshes: vec![labelled("box A", &a, 1), labelled("box B", &b, 2)],
        domains: vec![(1, a), (2, b)],
        interfaces: vec![(1, 2, face)],
    }
}

/// `nx`×`ny` unit boxes side by side on the plane z = 0 (the multi-organ case: many labels, every
/// box touching its four neighbours on faces and its diagonal ones on edges): box (i, j) is
/// [i, i+1]×[j, j+1]×[0, h] with h = 1 + 0.1·((i + 2j) mod 3), label 1 + i + nx·j. Each mesh is one
/// cuboid (12 triangles), so touching sections share their outlines only after the slicer's repair.
pub fn box_grid(nx: usize, ny: usize) -> SyntheticPartition {
    let height = |i: usize, j: usize| 1.0 + 0.1 * ((i + 2 * j) % 3) as f64;
    let label = |i: usize, j: usize| (1 + i + nx * j) as i32;
    let cell = |i: usize, j: usize| {
        let lo = [i as f64, j as f64, 0.0];
        cuboid(lo, [lo[0] + 1.0, lo[1] + 1.0, height(i, j)])
    };
    let mut meshes = Vec::new();
    let mut domains = Vec::new();
    let mut interfaces = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let m = cell(i, j);
            meshes.push(labelled(&format!("box {i},{j}"), &m, label(i, j)));
            domains.push((label(i, j), m));
            // with the neighbours at +x and +y: the lower box's face on the common plane
            let mut touch = |k: usize, l: usize, axis: usize, at: f64| {
                let lower = if height(i, j) <= height(k, l) {
                    cell(i, j)
                } else {
                    cell(k, l)
                };
                let face = faces_on(&lower, |p| p[axis] == at);
                interfaces.push((label(i, j), label(k, l), face));
            };
            if i + 1 < nx {
                touch(i + 1, j, 0, (i + 1) as f64);
            }
            if j + 1 < ny {
                touch(i, j + 1, 1, (j + 1) as f64);
            }
        }
    }
    SyntheticPartition {
        name: format!("{nx}x{ny} touching boxes"),
        meshes,
        domains,
        interfaces,
    }
}

/// A cylinder of three stacked materials (labels 1, 2, 3 from the bottom): prisms over one 24-gon of
/// radius 1.5 about the z axis through (0.05, -0.1), z in [0, 0.7], [0.7, 1.5], [1.5, 2.4], sharing
/// their caps at z = 0.7 and z = 1.5 (wider than tall: parallel planes cross the caps).
pub fn stacked_cylinder() -> SyntheticPartition {
    let (c, r, n) = ([0.05, -0.1], 1.5, 24);
    let z = [0.0, 0.7, 1.5, 2.4];
    let parts: Vec<TriMesh> = (0..3).map(|i| cylinder(c, r, z[i], z[i + 1], n)).collect();
    let cap = |m: &TriMesh, at: f64| faces_on(m, |p| p[2] == at);
    SyntheticPartition {
        name: "cylinder of three stacked materials".into(),
        meshes: (0..3)
            .map(|i| labelled(&format!("layer {}", i + 1), &parts[i], i as i32 + 1))
            .collect(),
        domains: (0..3).map(|i| (i as i32 + 1, parts[i].clone())).collect(),
        interfaces: vec![(1, 2, cap(&parts[0], z[1])), (2, 3, cap(&parts[1], z[2]))],
    }
}

/// `mesh` (label 1) with a ball (icosphere, 1280 triangles) carved out as label 2; the ball must lie
/// inside the mesh's material. Sliced from the ball and the mesh, the ball first.
pub fn carved(name: &str, mesh: &TriMesh, center: [f64; 3], radius: f64) -> SyntheticPartition {
    let ball = icosphere(center, radius, 3);
    SyntheticPartition {
        name: format!("{name} with a ball carved out"),
        meshes: vec![labelled("ball", &ball, 2), labelled(name, mesh, 1)],
        domains: vec![(1, merged(mesh, &inverted(&ball))), (2, ball.clone())],
        interfaces: vec![(1, 2, inverted(&ball))],
    }
}

/// The triangles of `m` whose three vertices satisfy `on`, as a mesh (all of `m`'s vertices kept).
fn faces_on(m: &TriMesh, on: impl Fn([f64; 3]) -> bool) -> TriMesh {
    TriMesh {
        vertices: m.vertices.clone(),
        triangles: m
            .triangles
            .iter()
            .copied()
            .filter(|t| t.iter().all(|&v| on(m.vertices[v as usize])))
            .collect(),
    }
}
