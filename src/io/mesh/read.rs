//! The mesh readers: STL, OBJ, PLY and OFF triangle meshes, VTK and MEDIT tetrahedral meshes,
//! parsed from the file's bytes or text (`name` locates the messages).
use super::{check_tets, drop_degenerate, weld_exact};
use crate::error::{Error, Result};
use crate::mesh::{TetMesh, TriMesh};

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

pub(super) fn parse_vtk(s: &str, name: &str) -> Result<TetMesh> {
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

pub(super) fn parse_medit(s: &str, name: &str) -> Result<TetMesh> {
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
