//! CSL, the cross-section format of the public reconstruction datasets.
//!
//! ```text
//! CSLC
//! n_planes n_labels
//! index n_vertices n_components a b c d      (per plane; the plane is a x + b y + c z + d = 0)
//! x y z                                      (n_vertices lines)
//! count[hP] label i0 i1 ...                  (n_components lines)
//! ```
//! The file is read as a stream of whitespace-separated tokens, so leading spaces, blank lines and
//! wrapped lines are accepted; every token remembers its line for error messages.
//!
//! Indexing, determined from the shared data: vertex indices are 0-based (Heart-simplified.csl,
//! plane 1, has 47 vertices and its component uses exactly 0..=46). The parent `P` of a hole `hP`
//! is the 0-based position of a component in the same plane: Horsers.csl has `11h0`, and in every
//! shared file the hole lies inside component P counted from 0 (the loader's nesting check
//! verifies this for each file in `tests/io_shared_csl.rs`).
//!
//! A hole's own label is accepted and ignored: the region's label is its outer component's.
//! The writer prints shortest round-trip decimals (`{}` of f64), so CSL → CSL reproduces the 3D
//! vertices exactly; the 2D coordinates come back within a few ulps (re-projection).
use crate::error::{Error, Result};
use crate::sections::{Contour, Plane, Region, Section, Sections};
use crate::validate::planes::{repair_plane_equations, StatedPlane};
use crate::validate::{
    self, check_coordinate, ContourId, Locator, ReadOptions, Role, OFF_PLANE_RELATIVE_TOLERANCE,
};
use std::fmt::Write as _;
use std::path::Path;

/// Read a CSL file (repairing, see `ReadOptions`).
pub fn read_csl(path: &Path) -> Result<Sections> {
    read_csl_with(path, &ReadOptions::default())
}

/// Read a CSL file with `options`.
pub fn read_csl_with(path: &Path, options: &ReadOptions) -> Result<Sections> {
    let text = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let text = String::from_utf8_lossy(&text);
    parse_csl_with(&text, &path.display().to_string(), options)
}

/// Write a CSL file.
pub fn write_csl(path: &Path, sections: &Sections) -> Result<()> {
    std::fs::write(path, to_csl_string(sections)).map_err(|e| Error::io(path, e))
}

struct Tokens<'a> {
    toks: Vec<(&'a str, usize)>,
    pos: usize,
    last_line: usize,
}

impl<'a> Tokens<'a> {
    fn new(text: &'a str) -> Self {
        let mut toks = Vec::new();
        let mut last_line = 1;
        for (i, line) in text.lines().enumerate() {
            last_line = i + 1;
            toks.extend(line.split_whitespace().map(|t| (t, i + 1)));
        }
        Tokens {
            toks,
            pos: 0,
            last_line,
        }
    }
    /// Next token and its line, or the last line of the file and `None` at the end.
    fn next(&mut self) -> (Option<&'a str>, usize) {
        match self.toks.get(self.pos) {
            Some(&(t, l)) => {
                self.pos += 1;
                (Some(t), l)
            }
            None => (None, self.last_line),
        }
    }
}

/// Where we are, for messages: `FILE:LINE: plane P, component C`.
fn at(file: &str, line: usize, plane: Option<usize>, component: Option<usize>) -> String {
    let mut s = format!("{file}:{line}");
    if let Some(p) = plane {
        write!(s, ": plane {p}").unwrap();
        if let Some(c) = component {
            write!(s, ", component {c}").unwrap();
        }
    }
    s
}

/// One component as written in the file.
struct RawComponent {
    line: usize,
    hole_of: Option<usize>,
    label: i32,
    indices: Vec<usize>,
}

struct RawPlane {
    index: usize,
    line: usize,
    plane: Plane,
    vertices: Vec<[f64; 3]>,
    vertex_lines: Vec<usize>,
    components: Vec<RawComponent>,
}

/// Line numbers of what the reader built, for validation messages.
struct CslLocator<'a> {
    file: &'a str,
    planes: Vec<(usize, usize)>, // (CSL index, line)
    /// Per section, per region: (outer component, hole components); component → line.
    regions: Vec<Vec<(usize, Vec<usize>)>>,
    component_lines: Vec<Vec<usize>>,
}

impl Locator for CslLocator<'_> {
    fn plane(&self, s: usize) -> String {
        let (index, line) = self.planes[s];
        at(self.file, line, Some(index), None)
    }
    fn contour(&self, id: ContourId) -> String {
        let (outer, holes) = &self.regions[id.section][id.region];
        let c = match id.role {
            Role::Outer => *outer,
            Role::Hole(h) => holes[h],
        };
        let (index, _) = self.planes[id.section];
        at(
            self.file,
            self.component_lines[id.section][c],
            Some(index),
            Some(c),
        )
    }
}

/// Parse CSL text; `file_name` is used in messages. The result is validated (see `validate`).
pub fn parse_csl(text: &str, file_name: &str) -> Result<Sections> {
    parse_csl_with(text, file_name, &ReadOptions::default())
}

/// Parse CSL text with `options` (`strict`: no repairs, see `ReadOptions`).
pub fn parse_csl_with(text: &str, file_name: &str, options: &ReadOptions) -> Result<Sections> {
    let mut t = Tokens::new(text);
    expect_header(&mut t, file_name)?;
    let n_planes = uint(&mut t, file_name, None, None, "the number of planes")?;
    let n_labels = uint(&mut t, file_name, None, None, "the number of labels")?;

    let mut raw = Vec::new();
    for _ in 0..n_planes {
        let plane = read_plane(&mut t, file_name, n_planes, raw.len())?;
        raw.push(plane);
    }
    let mut warnings = Vec::new();
    if let (Some(tok), l) = t.next() {
        warnings.push(format!(
            "{}: ignored data after the last declared plane, starting with `{}`",
            at(file_name, l, None, None),
            clip(tok)
        ));
    }
    check_holes_of_outers(&raw, file_name)?;

    let (tol, diag) = off_plane_tolerance(&raw);
    if !options.strict {
        repair_planes(&mut raw, tol, file_name, &mut warnings);
    }

    let mut sections = Vec::new();
    let mut loc = CslLocator {
        file: file_name,
        planes: Vec::new(),
        regions: Vec::new(),
        component_lines: Vec::new(),
    };
    for rp in raw {
        sections.push(to_section(rp, tol, diag, &mut loc)?);
    }
    let sections = Sections {
        sections,
        n_labels,
        warnings,
        label_names: Default::default(),
    };
    validate::validate_with_options(sections, &loc, options)
}

/// An input error at `FILE:LINE: plane P, component C`.
fn input_error(
    file: &str,
    line: usize,
    plane: Option<usize>,
    comp: Option<usize>,
    reason: String,
) -> Error {
    Error::input(at(file, line, plane, comp), reason)
}

fn expect_header(t: &mut Tokens, file: &str) -> Result<()> {
    match t.next() {
        (Some("CSLC"), _) => Ok(()),
        (Some(other), l) => Err(input_error(
            file,
            l,
            None,
            None,
            format!(
                "not a CSL file: expected header `CSLC`, found `{}`",
                clip(other)
            ),
        )),
        (None, l) => Err(input_error(
            file,
            l,
            None,
            None,
            "empty file: expected header `CSLC`".into(),
        )),
    }
}

/// One plane block: header line, vertices and components. `found` planes were read before it.
fn read_plane(t: &mut Tokens, file: &str, n_planes: usize, found: usize) -> Result<RawPlane> {
    let (first, line) = t.next();
    let index = match first {
        Some(tok) => parse_uint(tok).ok_or_else(|| {
            input_error(
                file,
                line,
                None,
                None,
                format!("expected a plane index, found `{}`", clip(tok)),
            )
        })?,
        None => {
            return Err(input_error(
                file,
                line,
                None,
                None,
                format!("unexpected end of file: {n_planes} plane(s) declared, {found} found"),
            ))
        }
    };
    let p = Some(index);
    let n_vertices = uint(t, file, p, None, "the number of vertices")?;
    let n_components = uint(t, file, p, None, "the number of components")?;
    let plane = read_plane_equation(t, file, p, line)?;
    let (vertices, vertex_lines) = read_vertices(t, file, p, n_vertices)?;
    let mut components = Vec::new();
    for c in 0..n_components {
        components.push(read_component(t, file, p, c, n_components, n_vertices)?);
    }
    Ok(RawPlane {
        index,
        line,
        plane,
        vertices,
        vertex_lines,
        components,
    })
}

/// The plane's `a b c d`, normalised.
fn read_plane_equation(t: &mut Tokens, file: &str, p: Option<usize>, line: usize) -> Result<Plane> {
    let mut eq = [0.0; 4];
    for (k, x) in eq.iter_mut().enumerate() {
        *x = float(t, file, p, ["a", "b", "c", "d"][k])?;
    }
    if eq[..3] == [0.0; 3] {
        return Err(input_error(
            file,
            line,
            p,
            None,
            "plane normal (a, b, c) is zero".into(),
        ));
    }
    Plane::from_equation([eq[0], eq[1], eq[2]], eq[3]).ok_or_else(|| {
        input_error(
            file,
            line,
            p,
            None,
            "plane equation cannot be normalised (too large or too small)".into(),
        )
    })
}

/// `n_vertices` points and the line each ends on.
fn read_vertices(
    t: &mut Tokens,
    file: &str,
    p: Option<usize>,
    n_vertices: usize,
) -> Result<(Vec<[f64; 3]>, Vec<usize>)> {
    let mut vertices = Vec::new();
    let mut vertex_lines = Vec::new();
    for _ in 0..n_vertices {
        let mut v = [0.0; 3];
        let mut vline = 0;
        for (k, x) in v.iter_mut().enumerate() {
            let (tok, l) = t.next();
            vline = l;
            *x = number(tok, l, file, p, ["x", "y", "z"][k])?;
        }
        vertices.push(v);
        vertex_lines.push(vline);
    }
    Ok((vertices, vertex_lines))
}

/// Component `c` of plane `p`: `count[hP] label i0 i1 ...`.
fn read_component(
    t: &mut Tokens,
    file: &str,
    p: Option<usize>,
    c: usize,
    n_components: usize,
    n_vertices: usize,
) -> Result<RawComponent> {
    let err = |line, reason: String| input_error(file, line, p, Some(c), reason);
    let (tok, cline) = t.next();
    let tok =
        tok.ok_or_else(|| err(cline, "unexpected end of file: expected a component".into()))?;
    let (count, hole_of) = match tok.split_once(['h', 'H']) {
        Some((n, parent)) => (parse_uint(n), parse_uint(parent).map(Some)),
        None => (parse_uint(tok), Some(None)),
    };
    let (Some(count), Some(hole_of)) = (count, hole_of) else {
        return Err(err(
            cline,
            format!(
                "expected a vertex count like `12` or `12h0`, found `{}`",
                clip(tok)
            ),
        ));
    };
    if let Some(parent) = hole_of {
        if parent >= n_components || parent == c {
            return Err(err(
                cline,
                format!(
                    "hole parent {parent} is not another component of this plane (components 0..{})",
                    n_components
                ),
            ));
        }
    }
    let (ltok, lline) = t.next();
    let label = match ltok {
        Some(s) => s.parse::<i32>().map_err(|_| {
            err(
                lline,
                format!("expected an integer label, found `{}`", clip(s)),
            )
        })?,
        None => {
            return Err(err(
                lline,
                "unexpected end of file: expected a label".into(),
            ))
        }
    };
    let indices = read_indices(t, count, n_vertices, &err)?;
    Ok(RawComponent {
        line: cline,
        hole_of,
        label,
        indices,
    })
}

/// A component's `count` vertex indices, each below `n_vertices`; `err` places the messages.
fn read_indices(
    t: &mut Tokens,
    count: usize,
    n_vertices: usize,
    err: &dyn Fn(usize, String) -> Error,
) -> Result<Vec<usize>> {
    let mut indices = Vec::new();
    for k in 0..count {
        let (itok, iline) = t.next();
        let Some(itok) = itok else {
            return Err(err(
                iline,
                format!("unexpected end of file: component declares {count} vertices, {k} found"),
            ));
        };
        let i = parse_uint(itok).ok_or_else(|| {
            err(
                iline,
                format!("expected a vertex index, found `{}`", clip(itok)),
            )
        })?;
        if i >= n_vertices {
            return Err(err(
                iline,
                format!(
                    "vertex index {i} out of range (the plane has {n_vertices} vertices, 0-based)"
                ),
            ));
        }
        indices.push(i);
    }
    Ok(indices)
}

/// Holes may only refer to outer components.
fn check_holes_of_outers(raw: &[RawPlane], file: &str) -> Result<()> {
    for rp in raw {
        for (c, comp) in rp.components.iter().enumerate() {
            if let Some(parent) = comp.hole_of {
                if rp.components[parent].hole_of.is_some() {
                    return Err(input_error(
                        file,
                        comp.line,
                        Some(rp.index),
                        Some(c),
                        format!("hole parent {parent} is itself a hole"),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// The snapping tolerance and the diagonal it is relative to: the bounding box of every vertex.
fn off_plane_tolerance(raw: &[RawPlane]) -> (f64, f64) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for v in raw.iter().flat_map(|r| &r.vertices) {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    let diag = if lo[0] <= hi[0] {
        ((0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>()).sqrt()
    } else {
        0.0
    };
    (OFF_PLANE_RELATIVE_TOLERANCE * diag, diag)
}

/// Refit plane equations their vertices do not lie on (see `repair_plane_equations`).
fn repair_planes(raw: &mut [RawPlane], tol: f64, file: &str, warnings: &mut Vec<String>) {
    let mut stated: Vec<StatedPlane> = raw
        .iter()
        .map(|r| StatedPlane {
            plane: r.plane,
            vertices: &r.vertices,
            loops: r.components.iter().map(|c| &c.indices[..]).collect(),
            offset_form: true,
            refittable: true,
            location: at(file, r.line, Some(r.index), None),
        })
        .collect();
    repair_plane_equations(&mut stated, tol, file, warnings);
    let repaired: Vec<Plane> = stated.iter().map(|p| p.plane).collect();
    for (r, plane) in raw.iter_mut().zip(repaired) {
        r.plane = plane;
    }
}

/// Project a plane's vertices to 2D (each within `tol` of the plane) and group its components
/// into regions; `loc` learns where each came from.
fn to_section(rp: RawPlane, tol: f64, diag: f64, loc: &mut CslLocator) -> Result<Section> {
    let mut max_off: f64 = 0.0;
    let mut points2 = Vec::with_capacity(rp.vertices.len());
    for (i, v) in rp.vertices.iter().enumerate() {
        let off = rp.plane.signed_distance(*v).abs();
        if off > tol {
            return Err(input_error(
                loc.file,
                rp.vertex_lines[i],
                Some(rp.index),
                None,
                format!(
                    "vertex {i} is {off:.3e} off its plane; tolerance {tol:.3e} ({OFF_PLANE_RELATIVE_TOLERANCE} x model bounding-box diagonal {diag:.3e})"
                ),
            ));
        }
        max_off = max_off.max(off);
        let q = rp.plane.to_2d(*v);
        points2.push([
            check_coordinate(q[0]).unwrap_or(q[0]),
            check_coordinate(q[1]).unwrap_or(q[1]),
        ]);
    }
    let contour = |comp: &RawComponent| {
        Contour::from_2d(
            &rp.plane,
            comp.indices.iter().map(|&i| points2[i]).collect(),
        )
    };
    let mut regions = Vec::new();
    let mut region_components = Vec::new();
    for (c, comp) in rp.components.iter().enumerate() {
        if comp.hole_of.is_some() {
            continue;
        }
        let holes: Vec<usize> = (0..rp.components.len())
            .filter(|&h| rp.components[h].hole_of == Some(c))
            .collect();
        regions.push(Region {
            label: comp.label,
            outer: contour(comp),
            holes: holes.iter().map(|&h| contour(&rp.components[h])).collect(),
        });
        region_components.push((c, holes));
    }
    loc.planes.push((rp.index, rp.line));
    loc.regions.push(region_components);
    loc.component_lines
        .push(rp.components.iter().map(|c| c.line).collect());
    Ok(Section {
        plane: rp.plane,
        regions,
        source_index: rp.index,
        max_off_plane: max_off,
    })
}

fn clip(s: &str) -> String {
    s.chars().take(40).collect()
}

fn parse_uint(s: &str) -> Option<usize> {
    if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    s.parse().ok()
}

fn uint(
    t: &mut Tokens,
    file: &str,
    plane: Option<usize>,
    comp: Option<usize>,
    what: &str,
) -> Result<usize> {
    let (tok, line) = t.next();
    match tok {
        Some(s) => parse_uint(s).ok_or_else(|| {
            Error::input(
                at(file, line, plane, comp),
                format!(
                    "expected {what} (a non-negative integer), found `{}`",
                    clip(s)
                ),
            )
        }),
        None => Err(Error::input(
            at(file, line, plane, comp),
            format!("unexpected end of file: expected {what}"),
        )),
    }
}

fn float(t: &mut Tokens, file: &str, plane: Option<usize>, what: &str) -> Result<f64> {
    let (tok, line) = t.next();
    number(tok, line, file, plane, what)
}

fn number(
    tok: Option<&str>,
    line: usize,
    file: &str,
    plane: Option<usize>,
    what: &str,
) -> Result<f64> {
    let loc = || at(file, line, plane, None);
    let Some(s) = tok else {
        return Err(Error::input(
            loc(),
            format!("unexpected end of file: expected {what}"),
        ));
    };
    let x: f64 = s.parse().map_err(|_| {
        Error::input(
            loc(),
            format!("expected a number for {what}, found `{}`", clip(s)),
        )
    })?;
    check_coordinate(x).map_err(|e| Error::input(loc(), format!("{what}: {e}")))
}

/// CSL text of `sections`: planes numbered from 1, vertices as `origin + s u + t v` (the snapped
/// 3D points), one component line per contour, holes as `count h P` after their outer component P.
pub fn to_csl_string(sections: &Sections) -> String {
    let max_label = sections
        .sections
        .iter()
        .flat_map(|s| &s.regions)
        .map(|r| r.label.max(0) as usize)
        .max()
        .unwrap_or(0);
    let mut out = String::new();
    writeln!(out, "CSLC").unwrap();
    writeln!(
        out,
        "{} {}",
        sections.sections.len(),
        sections.n_labels.max(max_label)
    )
    .unwrap();
    for (i, s) in sections.sections.iter().enumerate() {
        let contours: usize = s.regions.iter().map(|r| 1 + r.holes.len()).sum();
        let verts: usize = s
            .regions
            .iter()
            .map(|r| r.outer.points2.len() + r.holes.iter().map(|h| h.points2.len()).sum::<usize>())
            .sum();
        let n = s.plane.normal;
        writeln!(
            out,
            "\n{} {} {} {} {} {} {}\n",
            i + 1,
            verts,
            contours,
            n[0],
            n[1],
            n[2],
            s.plane.offset
        )
        .unwrap();
        let all = s
            .regions
            .iter()
            .flat_map(|r| std::iter::once(&r.outer).chain(&r.holes));
        for c in all {
            for q in &c.points2 {
                let p = s.plane.to_3d(*q);
                writeln!(out, "{} {} {}", p[0], p[1], p[2]).unwrap();
            }
        }
        let mut next_vertex = 0;
        let mut component = 0;
        let mut line = |out: &mut String, c: &Contour, head: String, label: i32| {
            write!(out, "{head} {label}").unwrap();
            for k in 0..c.points2.len() {
                write!(out, " {}", next_vertex + k).unwrap();
            }
            out.push('\n');
            next_vertex += c.points2.len();
        };
        for r in &s.regions {
            let outer = component;
            line(
                &mut out,
                &r.outer,
                r.outer.points2.len().to_string(),
                r.label,
            );
            component += 1;
            for h in &r.holes {
                line(
                    &mut out,
                    h,
                    format!("{}h{}", h.points2.len(), outer),
                    r.label,
                );
                component += 1;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE_WITH_HOLE: &str = "CSLC\n1 1\n\n 1 8 2 0 0 1 -2\n\n0 0 2\n4 0 2\n4 4 2\n0 4 2\n1 1 2\n1 3 2\n3 3 2\n3 1 2\n4 1 0 1 2 3\n4h0 2 4 7 6 5\n";

    #[test]
    fn parses_square_with_hole() {
        let s = parse_csl(SQUARE_WITH_HOLE, "t.csl").unwrap();
        assert_eq!(s.sections.len(), 1);
        let r = &s.sections[0].regions;
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].holes.len(), 1);
        assert_eq!(r[0].label, 1);
        assert!((s.sections[0].area() - 12.0).abs() < 1e-12);
        // The hole is given counter-clockwise: fixed with a warning naming its line.
        assert!(
            s.warnings
                .iter()
                .any(|w| w.contains("t.csl:15: plane 1, component 1")),
            "{:?}",
            s.warnings
        );
        let again = parse_csl(&to_csl_string(&s), "u.csl").unwrap();
        assert_eq!(again.sections[0].regions, s.sections[0].regions);
        assert!(again.warnings.is_empty());
    }

    #[test]
    fn errors_name_line_and_reason() {
        let bad = SQUARE_WITH_HOLE.replace("4 1 0 1 2 3", "4 1 0 1 2 9");
        let e = parse_csl(&bad, "t.csl").unwrap_err().to_string();
        assert!(
            e.starts_with("t.csl:14: plane 1, component 0") && e.contains("out of range"),
            "{e}"
        );
        let e = parse_csl("CSLC\n1 1\n1 3 1 0 0 1", "t.csl")
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.csl:3") && e.contains("end of file"), "{e}");
    }
}
