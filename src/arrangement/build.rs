//! Assembly of the `Arrangement`: box, duplicate check, cells, shared faces, pool, pieces.
use super::cells::CellBuilder;
use super::exact::same_plane;
use super::signs::SignVec;
use super::{
    ArrPlane, Arrangement, ArrangementOptions, Cell, CellFace, CellScope, Face, PlaneTags,
    VertexPool,
};
use crate::error::{Error, Result};
use crate::fxhash::FxHashMap as HashMap;
use crate::sections::{Plane, Sections};
use smallvec::SmallVec;

/// Margin of the culling test (`reach`), relative to the diagonal: far above the rounding of the
/// positions it compares, far below any feature.
const REACH_MARGIN: f64 = 1e-9;

pub(super) fn build(sections: &Sections, options: &ArrangementOptions) -> Result<Arrangement> {
    let n_input = sections.sections.len();
    let (lo, hi, diag) = bounding_box_and_diagonal(sections)?;
    let input_eq = checked_input_equations(sections)?;
    let (blo, bhi, walls) = box_walls(lo, hi, options.margin.max(0.0) * diag, diag, &input_eq);
    let mut planes: Vec<ArrPlane> = sections
        .sections
        .iter()
        .enumerate()
        .map(|(i, s)| ArrPlane {
            plane: s.plane,
            section: Some(i),
        })
        .collect();
    for w in &walls {
        planes.push(ArrPlane {
            plane: *w,
            section: None,
        });
    }
    let builder = cut_box(sections, &planes, diag, options)?;
    let CellsAndFaces {
        faces,
        cells,
        mut cell_sign,
    } = shared_faces(&builder)?;
    let pool = arrangement_vertex_pool(&builder, &planes);
    // its cells (faces, signs) and vertex maps are copied out: free them before the pieces
    drop(builder);

    let mut arr = Arrangement {
        planes,
        n_input,
        pool,
        faces,
        cells,
        bbox: (blo, bhi),
        scope: options.scope,
        max_disagreement: 0.0,
        warnings: Vec::new(),
    };
    // The vertices of the cells not built (`CellScope::Sections`) go.
    super::empty_cells::drop_unused_vertices(&mut arr);
    // Vertices that only rounding keeps apart (planes nearly through one point): one vertex.
    super::merge::merge_close_vertices(&mut arr, &mut cell_sign, options.merge_tolerance * diag);
    super::pieces::build_pieces(&mut arr, sections, &cell_sign, diag, options)?;
    if options.scope == CellScope::Sections {
        super::empty_cells::drop_cells_without_pieces(&mut arr);
    }
    Ok(arr)
}

/// The contour vertices' bounding box and its (finite) diagonal.
fn bounding_box_and_diagonal(sections: &Sections) -> Result<([f64; 3], [f64; 3], f64)> {
    let (lo, hi) = sections.bounding_box().ok_or_else(|| {
        Error::input(
            "sections",
            "no contour vertex: cannot bound the arrangement",
        )
    })?;
    let diag = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt();
    if !diag.is_finite() {
        return Err(Error::input("sections", "non-finite bounding box"));
    }
    Ok((lo, hi, diag))
}

/// The input planes' equations: finite, and no two the same plane.
fn checked_input_equations(sections: &Sections) -> Result<Vec<[f64; 4]>> {
    let n_input = sections.sections.len();
    let input_eq: Vec<[f64; 4]> = sections
        .sections
        .iter()
        .map(|s| s.plane.equation())
        .collect();
    for (i, e) in input_eq.iter().enumerate() {
        if e.iter().any(|x| !x.is_finite()) {
            return Err(Error::input(
                format!("plane {}", sections.sections[i].source_index),
                "non-finite plane equation",
            ));
        }
    }
    // Duplicate input planes are rejected (they would make a face with two sections).
    for i in 0..n_input {
        for j in i + 1..n_input {
            if same_plane(input_eq[i], input_eq[j]) {
                return Err(Error::input(
                    format!(
                        "planes {} and {}",
                        sections.sections[i].source_index, sections.sections[j].source_index
                    ),
                    "duplicate planes (the same plane up to scale)",
                ));
            }
        }
    }
    Ok(input_eq)
}

/// Box: padded by `margin` (at least a tiny absolute pad for a degenerate bbox); grown until no
/// input plane coincides with a wall (only possible for planes with an empty section). Returns
/// its corners and its six walls (−x, +x, −y, +y, −z, +z).
fn box_walls(
    lo: [f64; 3],
    hi: [f64; 3],
    margin: f64,
    diag: f64,
    input_eq: &[[f64; 4]],
) -> ([f64; 3], [f64; 3], Vec<Plane>) {
    let mut pad = margin.max(1e-9 * (1.0 + diag)).max(f64::MIN_POSITIVE);
    loop {
        let blo = [lo[0] - pad, lo[1] - pad, lo[2] - pad];
        let bhi = [hi[0] + pad, hi[1] + pad, hi[2] + pad];
        let mut walls = Vec::with_capacity(6);
        for k in 0..3 {
            let mut n = [0.0; 3];
            n[k] = -1.0;
            walls.push(Plane::from_equation(n, blo[k]).expect("axis plane"));
            n[k] = 1.0;
            walls.push(Plane::from_equation(n, -bhi[k]).expect("axis plane"));
        }
        let clash = walls
            .iter()
            .any(|w| input_eq.iter().any(|e| same_plane(*e, w.equation())));
        if !clash {
            return (blo, bhi, walls);
        }
        pad *= 1.5;
    }
}

/// The box (the planes after the inputs) cut by every input plane, keeping the cells `scope` asks
/// for, with complete sign vectors.
fn cut_box(
    sections: &Sections,
    planes: &[ArrPlane],
    diag: f64,
    options: &ArrangementOptions,
) -> Result<CellBuilder> {
    let n_input = sections.sections.len();
    let eq: Vec<[f64; 4]> = planes.iter().map(|p| p.plane.equation()).collect();
    let wall_ids: [u32; 6] = std::array::from_fn(|k| (n_input + k) as u32);
    let mut builder = CellBuilder::new_box(eq, wall_ids);
    let reach = super::reach::SectionReach::new(sections, REACH_MARGIN * diag);
    let keep_all = |_: &CellBuilder, _: &super::cells::BCell| true;
    let keep_reached = |b: &CellBuilder, c: &super::cells::BCell| reach.may_touch(b, c);
    let keep: super::cells::Keep = match options.scope {
        CellScope::All => &keep_all,
        CellScope::Sections => &keep_reached,
    };
    for h in 0..n_input as u32 {
        builder
            .cut(h, keep)
            .map_err(|e| Error::Geometry(format!("arrangement: {e}")))?;
    }
    builder.complete_signs();
    Ok(builder)
}

/// The cells with their faces, each face shared by the cells on its two sides (identical plane and
/// vertex set), and each cell's sign vector.
fn shared_faces(builder: &CellBuilder) -> Result<CellsAndFaces> {
    let mut faces: Vec<Face> = Vec::new();
    let mut face_index: HashMap<(u32, Vec<u32>), u32> = HashMap::default();
    let mut cells: Vec<Cell> = Vec::with_capacity(builder.cells.len());
    let mut cell_sign: Vec<SignVec> = Vec::with_capacity(builder.cells.len());
    for (c, bc) in builder.cells.iter().enumerate() {
        let c = c as u32;
        let mut cfaces = Vec::with_capacity(bc.faces.len());
        let volume = cell_volume(builder, bc);
        for bf in &bc.faces {
            let mut key_v = bf.poly.clone();
            key_v.sort_unstable();
            let key = (bf.plane, key_v);
            // The cell is on the negative side of the plane: its outward normal is the plane normal.
            let outward_is_plane_normal = bc.sign.get(bf.plane as usize) < 0;
            let fid = match face_index.get(&key) {
                Some(&f) => f,
                None => {
                    let polygon = if outward_is_plane_normal {
                        bf.poly.clone()
                    } else {
                        bf.poly.iter().rev().copied().collect()
                    };
                    faces.push(Face {
                        plane: bf.plane,
                        positive_cell: None,
                        negative_cell: None,
                        polygon,
                        pieces: Vec::new(),
                    });
                    face_index.insert(key, (faces.len() - 1) as u32);
                    (faces.len() - 1) as u32
                }
            };
            let f = &mut faces[fid as usize];
            let slot = if outward_is_plane_normal {
                &mut f.negative_cell
            } else {
                &mut f.positive_cell
            };
            if slot.is_some() {
                return Err(Error::Geometry(format!(
                    "arrangement: face {fid} has two cells on the same side"
                )));
            }
            *slot = Some(c);
            cfaces.push(CellFace {
                face: fid,
                outward_is_plane_normal,
            });
        }
        cells.push(Cell {
            faces: cfaces,
            volume,
        });
        cell_sign.push(bc.sign.clone());
    }
    Ok(CellsAndFaces {
        faces,
        cells,
        cell_sign,
    })
}

struct CellsAndFaces {
    faces: Vec<Face>,
    cells: Vec<Cell>,
    cell_sign: Vec<SignVec>,
}

/// Volume of a cell: its faces fanned from the first face's first vertex (positions taken
/// relative to it).
fn cell_volume(builder: &CellBuilder, bc: &super::cells::BCell) -> f64 {
    let mut volume = 0.0;
    let origin = builder.pos[bc.faces[0].poly[0] as usize];
    for bf in &bc.faces {
        let p: Vec<[f64; 3]> = bf
            .poly
            .iter()
            .map(|&v| {
                let x = builder.pos[v as usize];
                [x[0] - origin[0], x[1] - origin[1], x[2] - origin[2]]
            })
            .collect();
        for i in 1..p.len() - 1 {
            volume += det3(p[0], p[i], p[i + 1]) / 6.0;
        }
    }
    volume
}

/// Pool: the arrangement vertices first (ids = builder vertex ids).
fn arrangement_vertex_pool(builder: &CellBuilder, planes: &[ArrPlane]) -> VertexPool {
    let mut pool = VertexPool::default();
    for v in 0..builder.pos.len() {
        let pos = builder.pos[v];
        let tags: PlaneTags = builder.tags[v].clone();
        let uv: SmallVec<[[f64; 2]; 3]> = tags
            .iter()
            .map(|&t| planes[t as usize].plane.to_2d(pos))
            .collect();
        pool.positions.push(pos);
        pool.tags.push(tags);
        pool.uv.push(uv);
    }
    pool
}

fn det3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}
