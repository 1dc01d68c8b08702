//! Triangle and tetrahedral mesh files. Formats are chosen by file extension (case-insensitive).
//!
//! | read | `.stl` (ASCII or binary, detected by size), `.obj`, `.ply` (ASCII, binary LE/BE) |
//! |---|---|
//! | write | `.obj`, `.off` (ASCII, shortest round-trip floats: exact), `.ply` (binary little endian, doubles: exact), `.stl` (binary, f32) |
//! | tets | `.vtk` (legacy ASCII unstructured grid, cell type 10), `.mesh` (MEDIT, reference 1); both readable back |
//!
//! STL stores no connectivity: positions that are bit-for-bit equal are welded into one vertex (so the
//! mesh is indexed and shared vertices are shared). OBJ and PLY keep the file's vertices as they are.
//! Triangles whose corners are not three distinct vertex indices (after welding, for STL) carry no
//! area and are dropped. OBJ/PLY polygons with more than three corners are fan-triangulated.
//! Every malformed file gives `Error::Input` naming the file (and the line for text formats), never a panic.
use crate::error::{Error, Result};
use crate::mesh::{TetMesh, TriMesh};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// Read a triangle mesh: STL (ASCII or binary), OBJ, PLY (ASCII or binary), OFF.
pub fn read_trimesh(path: &Path) -> Result<TriMesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let name = path.display().to_string();
    match extension(path).as_str() {
        "stl" => parse_stl(&bytes, &name),
        "obj" => parse_obj(&text(&bytes, &name)?, &name),
        "ply" => parse_ply(&bytes, &name),
        "off" => parse_off(&text(&bytes, &name)?, &name),
        other => Err(Error::input(
            name,
            format!(
                "unknown triangle mesh extension `{other}` (expected .stl, .obj, .ply or .off)"
            ),
        )),
    }
}

/// Write a triangle mesh: .obj, .ply, .stl, .off.
pub fn write_trimesh(path: &Path, mesh: &TriMesh) -> Result<()> {
    let name = path.display().to_string();
    check_trimesh(mesh, &name)?;
    if extension(path) == "stl" {
        if let Some(i) = mesh
            .vertices
            .iter()
            .position(|p| p.iter().any(|c| !(*c as f32).is_finite()))
        {
            return Err(Error::input(
                name,
                format!("vertex {i} is outside the f32 range binary STL can store"),
            ));
        }
    }
    let bytes = match extension(path).as_str() {
        "obj" => to_obj_string(mesh).into_bytes(),
        "off" => to_off_string(mesh).into_bytes(),
        "ply" => to_ply_bytes(mesh),
        "stl" => to_stl_bytes(mesh),
        other => {
            return Err(Error::input(
                name,
                format!(
                    "unknown output mesh extension `{other}` (expected .obj, .ply, .stl or .off)"
                ),
            ))
        }
    };
    write_file(path, &bytes)
}

/// Write a tetrahedral mesh: .vtk (legacy unstructured grid) or .mesh (MEDIT).
pub fn write_tetmesh(path: &Path, mesh: &TetMesh) -> Result<()> {
    let name = path.display().to_string();
    let n = mesh.vertices.len();
    if let Some((i, _)) = mesh
        .tets
        .iter()
        .enumerate()
        .find(|(_, t)| t.iter().any(|&v| v as usize >= n))
    {
        return Err(Error::input(
            name,
            format!("tetrahedron {i} has a vertex index out of range ({n} vertices)"),
        ));
    }
    let s = match extension(path).as_str() {
        "vtk" => to_vtk_string(mesh),
        "mesh" => to_medit_string(mesh),
        other => {
            return Err(Error::input(
                name,
                format!("unknown tetrahedral mesh extension `{other}` (expected .vtk or .mesh)"),
            ))
        }
    };
    write_file(path, s.as_bytes())
}

/// Read a tetrahedral mesh written by [`write_tetmesh`] (or any VTK legacy ASCII unstructured grid whose
/// cells are all tetrahedra, or MEDIT `.mesh` with `Vertices` and `Tetrahedra`). Used by tests and tools.
pub fn read_tetmesh(path: &Path) -> Result<TetMesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let name = path.display().to_string();
    let s = text(&bytes, &name)?;
    match extension(path).as_str() {
        "vtk" => parse_vtk(&s, &name),
        "mesh" => parse_medit(&s, &name),
        other => Err(Error::input(
            name,
            format!("unknown tetrahedral mesh extension `{other}` (expected .vtk or .mesh)"),
        )),
    }
}

/// Merge vertices with bit-for-bit equal positions (`-0.0` equals `0.0`) and drop triangles that become
/// degenerate (two equal corner indices). Vertices keep the order of their first use.
pub fn weld_exact(mesh: &TriMesh) -> TriMesh {
    let mut map: HashMap<[u64; 3], u32> = HashMap::with_capacity(mesh.vertices.len());
    let mut out = TriMesh::default();
    let mut remap = vec![u32::MAX; mesh.vertices.len()];
    for t in &mesh.triangles {
        let mut nt = [0u32; 3];
        for k in 0..3 {
            let old = t[k] as usize;
            if remap[old] == u32::MAX {
                let p = mesh.vertices[old];
                let key = p.map(|c| (c + 0.0).to_bits());
                let next = out.vertices.len() as u32;
                let id = *map.entry(key).or_insert_with(|| {
                    out.vertices.push(p);
                    next
                });
                remap[old] = id;
            }
            nt[k] = remap[old];
        }
        if nt[0] != nt[1] && nt[1] != nt[2] && nt[0] != nt[2] {
            out.triangles.push(nt);
        }
    }
    out
}

/// Wavefront OBJ text: `v x y z` with shortest round-trip floats, `f a b c` 1-based.
pub fn to_obj_string(mesh: &TriMesh) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 24 * mesh.triangles.len());
    s.push_str("# slice2solid\n");
    for p in &mesh.vertices {
        let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for t in &mesh.triangles {
        let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s
}

/// OFF text with shortest round-trip floats.
pub fn to_off_string(mesh: &TriMesh) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 24 * mesh.triangles.len());
    let _ = writeln!(s, "OFF\n{} {} 0", mesh.vertices.len(), mesh.triangles.len());
    for p in &mesh.vertices {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for t in &mesh.triangles {
        let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
    }
    s
}

/// Binary little-endian PLY: vertex `double x y z`, face `list uchar int vertex_indices`.
pub fn to_ply_bytes(mesh: &TriMesh) -> Vec<u8> {
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment slice2solid\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        mesh.vertices.len(),
        mesh.triangles.len()
    );
    let mut b = header.into_bytes();
    b.reserve(24 * mesh.vertices.len() + 13 * mesh.triangles.len());
    for p in &mesh.vertices {
        for c in p {
            b.extend_from_slice(&c.to_le_bytes());
        }
    }
    for t in &mesh.triangles {
        b.push(3);
        for &i in t {
            b.extend_from_slice(&(i as i32).to_le_bytes());
        }
    }
    b
}

/// Binary STL (coordinates rounded to f32, facet normals computed from the corners).
pub fn to_stl_bytes(mesh: &TriMesh) -> Vec<u8> {
    let mut b = Vec::with_capacity(84 + 50 * mesh.triangles.len());
    let mut header = [b' '; 80];
    let tag = b"binary STL by slice2solid";
    header[..tag.len()].copy_from_slice(tag);
    b.extend_from_slice(&header);
    b.extend_from_slice(&(mesh.triangles.len() as u32).to_le_bytes());
    for t in &mesh.triangles {
        let [p, q, r] = t.map(|i| mesh.vertices[i as usize]);
        let e1 = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let e2 = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let n = if len > 0.0 {
            n.map(|c| c / len)
        } else {
            [0.0; 3]
        };
        for c in n.iter().chain(&p).chain(&q).chain(&r) {
            b.extend_from_slice(&(*c as f32).to_le_bytes());
        }
        b.extend_from_slice(&[0, 0]);
    }
    b
}

/// VTK legacy ASCII unstructured grid of tetrahedra (cell type 10), shortest round-trip floats.
pub fn to_vtk_string(mesh: &TetMesh) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 40 * mesh.tets.len());
    let _ = writeln!(
        s,
        "# vtk DataFile Version 3.0\nslice2solid tetrahedra\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double",
        mesh.vertices.len()
    );
    for p in &mesh.vertices {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    let _ = writeln!(s, "CELLS {} {}", mesh.tets.len(), 5 * mesh.tets.len());
    for t in &mesh.tets {
        let _ = writeln!(s, "4 {} {} {} {}", t[0], t[1], t[2], t[3]);
    }
    let _ = writeln!(s, "CELL_TYPES {}", mesh.tets.len());
    for _ in &mesh.tets {
        s.push_str("10\n");
    }
    s
}

/// MEDIT `.mesh` (double precision, 1-based indices, every vertex and tetrahedron with reference 1).
pub fn to_medit_string(mesh: &TetMesh) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 40 * mesh.tets.len());
    let _ = writeln!(
        s,
        "MeshVersionFormatted 2\nDimension 3\nVertices\n{}",
        mesh.vertices.len()
    );
    for p in &mesh.vertices {
        let _ = writeln!(s, "{:?} {:?} {:?} 1", p[0], p[1], p[2]);
    }
    let _ = writeln!(s, "Tetrahedra\n{}", mesh.tets.len());
    for t in &mesh.tets {
        let _ = writeln!(s, "{} {} {} {} 1", t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    }
    s.push_str("End\n");
    s
}

// ---------------------------------------------------------------------------------------------
// Readers

/// Parse STL bytes. Binary when the size matches `84 + 50 n` (n from the header), else ASCII when the
/// text starts with `solid`; a binary file that is too short is reported as truncated.
pub fn parse_stl(bytes: &[u8], name: &str) -> Result<TriMesh> {
    let binary_count = (bytes.len() >= 84)
        .then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64);
    let size_matches = binary_count.is_some_and(|n| 84 + 50 * n == bytes.len() as u64);
    let trimmed = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .map_or(&bytes[..0], |i| &bytes[i..]);
    // Many binary exporters start the header with `solid` too: text that parses as ASCII STL wins,
    // otherwise a size that matches the triangle count means binary.
    if trimmed.starts_with(b"solid") {
        if let Ok(s) = std::str::from_utf8(bytes) {
            match parse_stl_ascii(s, name) {
                Ok(m) => return Ok(m),
                Err(e) if !size_matches => return Err(e),
                Err(_) => {}
            }
        }
    }
    if size_matches {
        return parse_stl_binary(bytes, binary_count.unwrap_or(0) as usize, name);
    }
    match binary_count {
        Some(n) if 84 + 50 * n > bytes.len() as u64 => Err(Error::input(
            name,
            format!(
                "truncated binary STL: the header announces {n} triangles ({} bytes) but the file has {} bytes",
                84 + 50 * n,
                bytes.len()
            ),
        )),
        // Trailing bytes after the announced triangles: some exporters pad; read the announced ones.
        Some(n) => parse_stl_binary(bytes, n as usize, name),
        None => Err(Error::input(
            name,
            format!(
                "not an STL file: {} bytes, too short for binary STL and not ASCII (`solid ...`)",
                bytes.len()
            ),
        )),
    }
}

fn parse_stl_binary(bytes: &[u8], n: usize, name: &str) -> Result<TriMesh> {
    let mut soup = TriMesh {
        vertices: Vec::with_capacity(3 * n),
        triangles: Vec::with_capacity(n),
    };
    for i in 0..n {
        let rec = &bytes[84 + 50 * i..84 + 50 * i + 50];
        for k in 0..3 {
            let mut p = [0.0f64; 3];
            for (c, pc) in p.iter_mut().enumerate() {
                let o = 12 + 12 * k + 4 * c;
                *pc = f32::from_le_bytes([rec[o], rec[o + 1], rec[o + 2], rec[o + 3]]) as f64;
            }
            if !p.iter().all(|c| c.is_finite()) {
                return Err(Error::input(
                    name,
                    format!("triangle {i}, corner {k}: coordinate is not finite ({p:?})"),
                ));
            }
            soup.vertices.push(p);
        }
        let b = 3 * i as u32;
        soup.triangles.push([b, b + 1, b + 2]);
    }
    Ok(weld_exact(&soup))
}

fn parse_stl_ascii(s: &str, name: &str) -> Result<TriMesh> {
    let mut soup = TriMesh::default();
    let mut loop_corners: Vec<[f64; 3]> = Vec::new();
    let mut in_loop = false;
    let mut in_solid = false;
    let mut loop_line = 0;
    for (ln, line) in s.lines().enumerate() {
        let ln = ln + 1;
        let at = || format!("{name}:{ln}");
        let mut tok = line.split_whitespace();
        let Some(key) = tok.next() else { continue };
        match key {
            "solid" if !in_solid => in_solid = true,
            "endsolid" if in_solid && !in_loop => in_solid = false,
            "facet" | "endfacet" if in_solid && !in_loop => {}
            "outer" if in_solid && !in_loop => {
                in_loop = true;
                loop_line = ln;
                loop_corners.clear();
            }
            "vertex" if in_loop => {
                let p = parse_xyz(&mut tok, &at)?;
                loop_corners.push(p);
            }
            "endloop" if in_loop => {
                in_loop = false;
                if loop_corners.len() < 3 {
                    return Err(Error::input(
                        format!("{name}:{loop_line}"),
                        format!("facet loop has {} vertices, needs 3", loop_corners.len()),
                    ));
                }
                let b = soup.vertices.len() as u32;
                soup.vertices.extend_from_slice(&loop_corners);
                for k in 1..loop_corners.len() as u32 - 1 {
                    soup.triangles.push([b, b + k, b + k + 1]);
                }
            }
            _ => {
                return Err(Error::input(
                    at(),
                    format!("unexpected `{key}` in ASCII STL"),
                ))
            }
        }
    }
    if in_loop {
        return Err(Error::input(
            format!("{name}:{loop_line}"),
            "file ends inside a facet loop (truncated ASCII STL)",
        ));
    }
    Ok(weld_exact(&soup))
}

fn parse_xyz<'a>(
    tok: &mut impl Iterator<Item = &'a str>,
    at: &dyn Fn() -> String,
) -> Result<[f64; 3]> {
    let mut p = [0.0; 3];
    for c in &mut p {
        let t = tok
            .next()
            .ok_or_else(|| Error::input(at(), "expected three coordinates"))?;
        *c = t
            .parse::<f64>()
            .map_err(|_| Error::input(at(), format!("`{t}` is not a number")))?;
        if !c.is_finite() {
            return Err(Error::input(
                at(),
                format!("coordinate `{t}` is not finite"),
            ));
        }
    }
    Ok(p)
}

/// Parse OBJ text: `v` lines (extra components such as w or colours ignored) and `f` lines (corner
/// forms `i`, `i/t`, `i//n`, `i/t/n`, negative indices relative to the vertices read so far); other
/// statements are ignored.
pub fn parse_obj(s: &str, name: &str) -> Result<TriMesh> {
    let mut mesh = TriMesh::default();
    let mut face_lines: Vec<(usize, usize)> = Vec::new(); // (first triangle, line)
    for (ln, line) in s.lines().enumerate() {
        let ln = ln + 1;
        let at = || format!("{name}:{ln}");
        let line = line.split('#').next().unwrap_or("");
        let mut tok = line.split_whitespace();
        match tok.next() {
            Some("v") => mesh.vertices.push(parse_xyz(&mut tok, &at)?),
            Some("f") => {
                let mut corners: Vec<i64> = Vec::with_capacity(4);
                for t in tok {
                    let first = t.split('/').next().unwrap_or("");
                    let i: i64 = first.parse().map_err(|_| {
                        Error::input(at(), format!("`{t}` is not a face corner index"))
                    })?;
                    let idx = match i {
                        0 => return Err(Error::input(at(), "face index 0 (OBJ is 1-based)")),
                        i if i > 0 => i - 1,
                        i => mesh.vertices.len() as i64 + i,
                    };
                    if idx < 0 || idx > u32::MAX as i64 {
                        return Err(Error::input(
                            at(),
                            format!("face index {i} is out of range"),
                        ));
                    }
                    corners.push(idx);
                }
                if corners.len() < 3 {
                    return Err(Error::input(
                        at(),
                        format!("face has {} corners, needs at least 3", corners.len()),
                    ));
                }
                face_lines.push((mesh.triangles.len(), ln));
                for k in 1..corners.len() - 1 {
                    mesh.triangles
                        .push([corners[0], corners[k], corners[k + 1]].map(|c| c as u32));
                }
            }
            _ => {}
        }
    }
    // Forward references are legal in OBJ, so ranges are checked once every vertex is known.
    let n = mesh.vertices.len();
    for (fi, &(first, ln)) in face_lines.iter().enumerate() {
        let end = face_lines.get(fi + 1).map_or(mesh.triangles.len(), |f| f.0);
        if let Some(&bad) = mesh.triangles[first..end]
            .iter()
            .flatten()
            .find(|&&i| i as usize >= n)
        {
            return Err(Error::input(
                format!("{name}:{ln}"),
                format!(
                    "face refers to vertex {} but the file has {n}",
                    bad as u64 + 1
                ),
            ));
        }
    }
    drop_degenerate(&mut mesh);
    Ok(mesh)
}

/// Parse PLY (ASCII, binary little or big endian) with ply-rs: vertex `x y z` (any numeric type),
/// face list `vertex_indices` or `vertex_index` (any integer type).
pub fn parse_ply(bytes: &[u8], name: &str) -> Result<TriMesh> {
    use ply_rs::parser::Parser;
    use ply_rs::ply::{DefaultElement, Property};
    let parser = Parser::<DefaultElement>::new();
    let mut reader = std::io::BufReader::new(bytes);
    let ply = parser
        .read_ply(&mut reader)
        .map_err(|e| Error::input(name, format!("malformed PLY: {e}")))?;
    let empty = Vec::new();
    let verts = ply.payload.get("vertex").unwrap_or(&empty);
    let faces = ply.payload.get("face").unwrap_or(&empty);
    let mut mesh = TriMesh {
        vertices: Vec::with_capacity(verts.len()),
        triangles: Vec::with_capacity(faces.len()),
    };
    let scalar = |p: Option<&Property>| -> Option<f64> {
        Some(match p? {
            Property::Float(x) => *x as f64,
            Property::Double(x) => *x,
            Property::Char(x) => *x as f64,
            Property::UChar(x) => *x as f64,
            Property::Short(x) => *x as f64,
            Property::UShort(x) => *x as f64,
            Property::Int(x) => *x as f64,
            Property::UInt(x) => *x as f64,
            _ => return None,
        })
    };
    for (i, v) in verts.iter().enumerate() {
        let mut p = [0.0; 3];
        for (c, key) in ["x", "y", "z"].iter().enumerate() {
            p[c] = scalar(v.get(*key)).ok_or_else(|| {
                Error::input(
                    format!("{name}: vertex {i}"),
                    format!("missing or non-scalar property `{key}`"),
                )
            })?;
            if !p[c].is_finite() {
                return Err(Error::input(
                    format!("{name}: vertex {i}"),
                    format!("coordinate {key} is not finite"),
                ));
            }
        }
        mesh.vertices.push(p);
    }
    let n = mesh.vertices.len() as i64;
    for (i, f) in faces.iter().enumerate() {
        let at = || format!("{name}: face {i}");
        let list: Vec<i64> = match f.get("vertex_indices").or_else(|| f.get("vertex_index")) {
            Some(Property::ListChar(l)) => l.iter().map(|&x| x as i64).collect(),
            Some(Property::ListUChar(l)) => l.iter().map(|&x| x as i64).collect(),
            Some(Property::ListShort(l)) => l.iter().map(|&x| x as i64).collect(),
            Some(Property::ListUShort(l)) => l.iter().map(|&x| x as i64).collect(),
            Some(Property::ListInt(l)) => l.iter().map(|&x| x as i64).collect(),
            Some(Property::ListUInt(l)) => l.iter().map(|&x| x as i64).collect(),
            _ => {
                return Err(Error::input(
                    at(),
                    "missing integer list property `vertex_indices` (or `vertex_index`)",
                ))
            }
        };
        if list.len() < 3 {
            return Err(Error::input(
                at(),
                format!("face has {} corners, needs at least 3", list.len()),
            ));
        }
        if let Some(&bad) = list.iter().find(|&&x| x < 0 || x >= n) {
            return Err(Error::input(
                at(),
                format!("vertex index {bad} is out of range ({n} vertices)"),
            ));
        }
        for k in 1..list.len() - 1 {
            mesh.triangles
                .push([list[0], list[k], list[k + 1]].map(|c| c as u32));
        }
    }
    drop_degenerate(&mut mesh);
    Ok(mesh)
}

/// Parse OFF text: `OFF`, `nv nf ne`, vertices, faces `k i0 .. ik-1` (trailing colour values ignored).
pub fn parse_off(s: &str, name: &str) -> Result<TriMesh> {
    let mut t = Tokens::new(s, name);
    if t.next()? != "OFF" {
        return Err(t.err("expected `OFF` header"));
    }
    let (nv, nf) = (t.usize()?, t.usize()?);
    t.usize()?;
    let mut mesh = TriMesh::default();
    for _ in 0..nv {
        mesh.vertices.push(t.xyz()?);
    }
    for _ in 0..nf {
        let k = t.usize()?;
        let line = t.line;
        if k < 3 {
            return Err(t.err(format!("face has {k} corners, needs at least 3")));
        }
        let corners = (0..k).map(|_| t.index(0)).collect::<Result<Vec<u32>>>()?;
        if let Some(bad) = corners.iter().find(|&&i| i as usize >= nv) {
            return Err(Error::input(
                format!("{name}:{line}"),
                format!("vertex index {bad} is out of range ({nv} vertices)"),
            ));
        }
        // Skip anything else on the face's line (colours).
        while t.peek_line() == Some(line) {
            t.next()?;
        }
        for j in 1..k - 1 {
            mesh.triangles
                .push([corners[0], corners[j], corners[j + 1]]);
        }
    }
    drop_degenerate(&mut mesh);
    Ok(mesh)
}

fn parse_vtk(s: &str, name: &str) -> Result<TetMesh> {
    let mut t = Tokens::new(s, name);
    let mut mesh = TetMesh::default();
    let mut got_cells = false;
    while let Some(key) = t.next_opt() {
        match key.to_ascii_uppercase().as_str() {
            "POINTS" => {
                let n = t.usize()?;
                t.next()?; // data type
                mesh.vertices = (0..n).map(|_| t.xyz()).collect::<Result<_>>()?;
            }
            "CELLS" => {
                let n = t.usize()?;
                t.usize()?;
                for _ in 0..n {
                    if t.usize()? != 4 {
                        return Err(t.err("cell is not a tetrahedron (expected 4 vertices)"));
                    }
                    let tet = [t.index(0)?, t.index(0)?, t.index(0)?, t.index(0)?];
                    mesh.tets.push(tet);
                }
                got_cells = true;
            }
            "CELL_TYPES" => {
                let n = t.usize()?;
                for _ in 0..n {
                    if t.usize()? != 10 {
                        return Err(t.err("cell type is not 10 (tetrahedron)"));
                    }
                }
            }
            _ => {}
        }
    }
    if !got_cells {
        return Err(Error::input(name, "no CELLS section"));
    }
    check_tets(&mesh, name)?;
    Ok(mesh)
}

fn parse_medit(s: &str, name: &str) -> Result<TetMesh> {
    let mut t = Tokens::new(s, name);
    let mut mesh = TetMesh::default();
    while let Some(key) = t.next_opt() {
        match key {
            "Vertices" => {
                let n = t.usize()?;
                for _ in 0..n {
                    let p = t.xyz()?;
                    t.next()?; // reference
                    mesh.vertices.push(p);
                }
            }
            "Tetrahedra" => {
                let n = t.usize()?;
                for _ in 0..n {
                    let tet = [t.index(1)?, t.index(1)?, t.index(1)?, t.index(1)?];
                    t.next()?; // reference
                    mesh.tets.push(tet);
                }
            }
            "End" => break,
            _ => {}
        }
    }
    check_tets(&mesh, name)?;
    Ok(mesh)
}

/// Whitespace tokens of a text file with line numbers (for the tet formats; `#` starts a comment).
struct Tokens<'a> {
    it: std::iter::Peekable<Box<dyn Iterator<Item = (usize, &'a str)> + 'a>>,
    name: &'a str,
    line: usize,
}

impl<'a> Tokens<'a> {
    fn new(s: &'a str, name: &'a str) -> Self {
        let it = s.lines().enumerate().flat_map(|(i, l)| {
            let l = l.split('#').next().unwrap_or("");
            l.split_whitespace().map(move |w| (i + 1, w))
        });
        let it: Box<dyn Iterator<Item = (usize, &'a str)> + 'a> = Box::new(it);
        Tokens {
            it: it.peekable(),
            name,
            line: 0,
        }
    }
    fn peek_line(&mut self) -> Option<usize> {
        self.it.peek().map(|&(l, _)| l)
    }
    fn next_opt(&mut self) -> Option<&'a str> {
        let (l, w) = self.it.next()?;
        self.line = l;
        Some(w)
    }
    fn err(&self, reason: impl Into<String>) -> Error {
        Error::input(format!("{}:{}", self.name, self.line), reason)
    }
    fn next(&mut self) -> Result<&'a str> {
        self.next_opt()
            .ok_or_else(|| self.err("unexpected end of file (truncated)"))
    }
    fn usize(&mut self) -> Result<usize> {
        let w = self.next()?;
        w.parse()
            .map_err(|_| self.err(format!("`{w}` is not a non-negative integer")))
    }
    fn index(&mut self, base: usize) -> Result<u32> {
        let i = self.usize()?;
        if i < base || i - base > u32::MAX as usize {
            return Err(self.err(format!("index {i} is out of range")));
        }
        Ok((i - base) as u32)
    }
    fn xyz(&mut self) -> Result<[f64; 3]> {
        let mut p = [0.0f64; 3];
        for c in &mut p {
            let w = self.next()?;
            *c = w
                .parse()
                .map_err(|_| self.err(format!("`{w}` is not a number")))?;
            if !c.is_finite() {
                return Err(self.err(format!("coordinate `{w}` is not finite")));
            }
        }
        Ok(p)
    }
}

// ---------------------------------------------------------------------------------------------
// Helpers

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

fn text(bytes: &[u8], name: &str) -> Result<String> {
    String::from_utf8(bytes.to_vec()).map_err(|e| {
        Error::input(
            name,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

pub(crate) fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut f = std::fs::File::create(path).map_err(|e| Error::io(path, e))?;
    f.write_all(bytes).map_err(|e| Error::io(path, e))
}

fn drop_degenerate(mesh: &mut TriMesh) {
    mesh.triangles
        .retain(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
}

fn check_trimesh(mesh: &TriMesh, name: &str) -> Result<()> {
    check_indices(&mesh.triangles, mesh.vertices.len(), name, "triangle")
}

fn check_tets(mesh: &TetMesh, name: &str) -> Result<()> {
    check_indices(&mesh.tets, mesh.vertices.len(), name, "tetrahedron")
}

/// Writers refuse a cell that refers past the vertex array instead of writing a file that cannot be read back.
fn check_indices<const K: usize>(
    cells: &[[u32; K]],
    n: usize,
    name: &str,
    what: &str,
) -> Result<()> {
    match cells
        .iter()
        .position(|c| c.iter().any(|&v| v as usize >= n))
    {
        Some(i) => Err(Error::input(
            name,
            format!("{what} {i} has a vertex index out of range ({n} vertices)"),
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra() -> TriMesh {
        TriMesh {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.1, 0.2, 1.0 / 3.0],
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
        }
    }

    #[test]
    fn obj_and_off_text_round_trip_exactly() {
        let m = tetra();
        assert_eq!(parse_obj(&to_obj_string(&m), "t.obj").unwrap(), m);
        assert_eq!(parse_ply(&to_ply_bytes(&m), "t.ply").unwrap(), m);
        assert_eq!(parse_off(&to_off_string(&m), "t.off").unwrap(), m);
    }

    #[test]
    fn stl_binary_welds_shared_corners() {
        let m = tetra();
        let back = parse_stl(&to_stl_bytes(&m), "t.stl").unwrap();
        assert_eq!(back.vertices.len(), 4);
        assert_eq!(back.triangles.len(), 4);
    }

    #[test]
    fn big_endian_ply_with_float_coordinates() {
        let m = tetra();
        let mut b = String::from(
            "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
             property float z\nelement face 4\nproperty list uchar uint vertex_index\nend_header\n"
        )
        .into_bytes();
        for p in &m.vertices {
            for c in p {
                b.extend_from_slice(&(*c as f32).to_be_bytes());
            }
        }
        for t in &m.triangles {
            b.push(3);
            for i in t {
                b.extend_from_slice(&i.to_be_bytes());
            }
        }
        let back = parse_ply(&b, "be.ply").unwrap();
        assert_eq!(back.triangles, m.triangles);
        assert_eq!(back.vertices[3][2], (1.0f64 / 3.0) as f32 as f64);
    }

    #[test]
    fn binary_stl_whose_header_says_solid_is_binary() {
        let mut b = to_stl_bytes(&tetra());
        b[..12].copy_from_slice(b"solid tetra ");
        let m = parse_stl(&b, "s.stl").unwrap();
        assert_eq!(m.triangles.len(), 4);
        assert_eq!(m.vertices.len(), 4);
    }

    #[test]
    fn obj_polygons_are_fan_triangulated_and_negative_indices_work() {
        let s = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2//2 3 -1\n";
        let m = parse_obj(s, "q.obj").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn bad_obj_names_the_line() {
        let e = parse_obj("v 0 0 0\nv 1 0 nan\n", "b.obj").unwrap_err();
        assert!(e.to_string().starts_with("b.obj:2:"), "{e}");
        let e = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", "b.obj").unwrap_err();
        assert!(e.to_string().starts_with("b.obj:5:"), "{e}");
    }
}
