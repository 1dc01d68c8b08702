//! Cross-sections given as plain data: per plane its equation and its contours (3D or plane-frame
//! points, a label, the outer contour a hole belongs to), as a JSON file states them or a caller
//! builds them in memory (the Python bindings' numpy arrays). [`build_sections`] turns them into
//! [`Sections`] the way every reader does: numbers range-checked, planes normalised, 3D points
//! snapped to their plane within the tolerance, then `validate` (repairs unless strict). Errors are
//! located as `SOURCE: ROOT[plane].contours[c]...`, e.g. `in.json: $.planes[2].contours[0]`.
use crate::error::{Error, Result};
use crate::sections::{Contour, Plane, Region, Section, Sections};
use crate::validate::planes::{repair_plane_equations, StatedPlane};
use crate::validate::{
    self, check_coordinate, ContourId, Locator, ReadOptions, Role, OFF_PLANE_RELATIVE_TOLERANCE,
};

/// A plane: through `point` with `normal`, or `normal·x + offset = 0`; the normal need not be unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlaneSpec {
    PointNormal { point: [f64; 3], normal: [f64; 3] },
    Equation { normal: [f64; 3], offset: f64 },
}

/// A contour's vertices: 3D points (snapped to the plane) or coordinates in the plane's frame.
#[derive(Clone, Debug, PartialEq)]
pub enum ContourPoints {
    Xyz(Vec<[f64; 3]>),
    Uv(Vec<[f64; 2]>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct ContourSpec {
    pub points: ContourPoints,
    /// The material inside (ignored for a hole: it keeps its outer contour's label).
    pub label: i32,
    /// Index of the outer contour (in the same plane's list) this contour is a hole of.
    pub hole_of: Option<usize>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct SectionSpec {
    pub plane: PlaneSpec,
    pub contours: Vec<ContourSpec>,
}

/// How locations are written: `{source}: {root}[i]`, e.g. `in.json: $.planes[3]`.
#[derive(Clone, Copy, Debug)]
pub struct Naming<'a> {
    pub source: &'a str,
    pub root: &'a str,
}

impl Naming<'_> {
    fn plane(&self, pi: usize) -> String {
        format!("{}[{pi}]", self.root)
    }
    fn err(&self, path: &str, reason: impl Into<String>) -> Error {
        Error::input(format!("{}: {path}", self.source), reason)
    }
}

/// Validate `specs` into sections (see the module docs). `n_labels`: the declared number of labels
/// (raised to the largest label used).
pub fn build_sections(
    specs: &[SectionSpec],
    n_labels: usize,
    naming: &Naming,
    options: &ReadOptions,
) -> Result<Sections> {
    let planes = specs
        .iter()
        .enumerate()
        .map(|(pi, s)| {
            check_contours(s, &naming.plane(pi), naming)?;
            plane_of(&s.plane, &naming.plane(pi), naming)
        })
        .collect::<Result<Vec<Plane>>>()?;
    let (tol, diag) = off_plane_tolerance(specs, &planes);
    let mut warnings = Vec::new();
    let planes = if options.strict {
        planes
    } else {
        repaired_planes(specs, planes, tol, naming, &mut warnings)
    };
    let mut loc = SpecLocator {
        naming: *naming,
        planes: Vec::new(),
        regions: Vec::new(),
    };
    let mut sections = Vec::with_capacity(specs.len());
    for (pi, (spec, plane)) in specs.iter().zip(planes).enumerate() {
        let ppath = naming.plane(pi);
        let mut max_off: f64 = 0.0;
        let mut built = Vec::with_capacity(spec.contours.len());
        for (ci, c) in spec.contours.iter().enumerate() {
            built.push(match &c.points {
                // 2D input is kept exactly as given (not re-projected).
                ContourPoints::Uv(q) => q.clone(),
                ContourPoints::Xyz(p) => {
                    let mut q = Vec::with_capacity(p.len());
                    for (k, x) in p.iter().enumerate() {
                        let off = plane.signed_distance(*x).abs();
                        if off > tol {
                            return Err(naming.err(
                                &format!("{ppath}.contours[{ci}].points[{k}]"),
                                format!(
                                    "vertex is {off:.3e} off its plane; tolerance {tol:.3e} ({OFF_PLANE_RELATIVE_TOLERANCE} x model bounding-box diagonal {diag:.3e})"
                                ),
                            ));
                        }
                        max_off = max_off.max(off);
                        q.push(plane.to_2d(*x));
                    }
                    q
                }
            });
        }
        let mut regions = Vec::new();
        let mut region_contours = Vec::new();
        for (ci, c) in spec.contours.iter().enumerate() {
            if c.hole_of.is_some() {
                continue;
            }
            let holes: Vec<usize> = (0..spec.contours.len())
                .filter(|&h| spec.contours[h].hole_of == Some(ci))
                .collect();
            regions.push(Region {
                label: c.label,
                outer: Contour::from_2d(&plane, built[ci].clone()),
                holes: holes
                    .iter()
                    .map(|&h| Contour::from_2d(&plane, built[h].clone()))
                    .collect(),
            });
            region_contours.push((ci, holes));
        }
        loc.planes.push(pi);
        loc.regions.push(region_contours);
        sections.push(Section {
            plane,
            regions,
            source_index: pi,
            max_off_plane: max_off,
        });
    }
    validate::validate_with_options(
        Sections {
            sections,
            n_labels,
            warnings,
            ..Default::default()
        },
        &loc,
        options,
    )
}

/// The plane repairs every reader makes (`validate::planes`: the other sign convention of the
/// offset, a plane off its coplanar vertices), on the contours given in 3D; a plane with a contour
/// in its own frame (`Uv`) is never re-fitted, those points lie on the stated plane by definition.
fn repaired_planes(
    specs: &[SectionSpec],
    planes: Vec<Plane>,
    tol: f64,
    naming: &Naming,
    warnings: &mut Vec<String>,
) -> Vec<Plane> {
    fn xyz(spec: &SectionSpec) -> Vec<&Vec<[f64; 3]>> {
        spec.contours
            .iter()
            .filter_map(|c| match &c.points {
                ContourPoints::Xyz(p) => Some(p),
                ContourPoints::Uv(_) => None,
            })
            .collect()
    }
    let vertices: Vec<Vec<[f64; 3]>> = specs
        .iter()
        .map(|s| xyz(s).into_iter().flatten().copied().collect())
        .collect();
    let loops: Vec<Vec<Vec<usize>>> = specs
        .iter()
        .map(|s| {
            let mut next = 0;
            xyz(s)
                .into_iter()
                .map(|p| {
                    next += p.len();
                    (next - p.len()..next).collect()
                })
                .collect()
        })
        .collect();
    let mut stated: Vec<StatedPlane> = specs
        .iter()
        .zip(planes)
        .enumerate()
        .map(|(pi, (spec, plane))| StatedPlane {
            plane,
            vertices: &vertices[pi],
            loops: loops[pi].iter().map(|l| &l[..]).collect(),
            offset_form: matches!(spec.plane, PlaneSpec::Equation { .. }),
            refittable: spec
                .contours
                .iter()
                .all(|c| matches!(c.points, ContourPoints::Xyz(_))),
            location: format!("{}: {}", naming.source, naming.plane(pi)),
        })
        .collect();
    repair_plane_equations(&mut stated, tol, naming.source, warnings);
    stated.iter().map(|p| p.plane).collect()
}

/// The plane of a spec, its numbers range-checked.
fn plane_of(spec: &PlaneSpec, ppath: &str, naming: &Naming) -> Result<Plane> {
    let vec3 = |x: [f64; 3], key: &str| -> Result<[f64; 3]> {
        let mut out = x;
        for (k, c) in out.iter_mut().enumerate() {
            *c = check_coordinate(*c).map_err(|r| naming.err(&format!("{ppath}.{key}[{k}]"), r))?;
        }
        Ok(out)
    };
    let normal = match spec {
        PlaneSpec::PointNormal { normal, .. } | PlaneSpec::Equation { normal, .. } => {
            vec3(*normal, "normal")?
        }
    };
    if normal == [0.0; 3] {
        return Err(naming.err(&format!("{ppath}.normal"), "plane normal is zero"));
    }
    let plane = match *spec {
        PlaneSpec::PointNormal { point, .. } => {
            Plane::from_point_normal(vec3(point, "point")?, normal)
        }
        PlaneSpec::Equation { offset, .. } => {
            let d =
                check_coordinate(offset).map_err(|r| naming.err(&format!("{ppath}.offset"), r))?;
            Plane::from_equation(normal, d)
        }
    };
    plane.ok_or_else(|| {
        naming.err(
            ppath,
            "plane cannot be normalised (numbers too large or too small)",
        )
    })
}

/// Hole references point at another contour that is not itself a hole; coordinates are in range.
fn check_contours(spec: &SectionSpec, ppath: &str, naming: &Naming) -> Result<()> {
    let n = spec.contours.len();
    for (ci, c) in spec.contours.iter().enumerate() {
        let cpath = format!("{ppath}.contours[{ci}]");
        if let Some(h) = c.hole_of {
            if h >= n || h == ci {
                return Err(naming.err(
                    &format!("{cpath}.hole_of"),
                    format!("{h} is not another contour of this plane (0..{n})"),
                ));
            }
        }
        let (key, coords): (&str, Vec<&[f64]>) = match &c.points {
            ContourPoints::Xyz(p) => ("points", p.iter().map(|x| &x[..]).collect()),
            ContourPoints::Uv(q) => ("points2d", q.iter().map(|x| &x[..]).collect()),
        };
        for (k, x) in coords.iter().enumerate() {
            for (j, &v) in x.iter().enumerate() {
                check_coordinate(v)
                    .map_err(|r| naming.err(&format!("{cpath}.{key}[{k}][{j}]"), r))?;
            }
        }
    }
    for (ci, c) in spec.contours.iter().enumerate() {
        if let Some(h) = c.hole_of {
            if spec.contours[h].hole_of.is_some() {
                return Err(naming.err(
                    &format!("{ppath}.contours[{ci}].hole_of"),
                    format!("contour {h} is itself a hole"),
                ));
            }
        }
    }
    Ok(())
}

/// The snapping tolerance (and the diagonal it is relative to) over every point given, 2D points
/// counted at their place in their plane.
fn off_plane_tolerance(specs: &[SectionSpec], planes: &[Plane]) -> (f64, f64) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let mut extend = |p: [f64; 3]| {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    };
    for (spec, plane) in specs.iter().zip(planes) {
        for c in &spec.contours {
            match &c.points {
                ContourPoints::Xyz(p) => p.iter().for_each(|&x| extend(x)),
                ContourPoints::Uv(q) => q.iter().for_each(|&x| extend(plane.to_3d(x))),
            }
        }
    }
    let diag = if lo[0] <= hi[0] {
        ((0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>()).sqrt()
    } else {
        0.0
    };
    (OFF_PLANE_RELATIVE_TOLERANCE * diag, diag)
}

/// Locations of validation errors: the plane and contour indices of the spec.
struct SpecLocator<'a> {
    naming: Naming<'a>,
    /// Per section: its spec index, and per region (outer contour index, hole contour indices).
    planes: Vec<usize>,
    regions: Vec<Vec<(usize, Vec<usize>)>>,
}

impl Locator for SpecLocator<'_> {
    fn plane(&self, s: usize) -> String {
        format!(
            "{}: {}",
            self.naming.source,
            self.naming.plane(self.planes[s])
        )
    }
    fn contour(&self, id: ContourId) -> String {
        let (outer, holes) = &self.regions[id.section][id.region];
        let c = match id.role {
            Role::Outer => *outer,
            Role::Hole(h) => holes[h],
        };
        format!("{}.contours[{c}]", self.plane(id.section))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(z: f64) -> ContourSpec {
        ContourSpec {
            points: ContourPoints::Xyz(vec![[0., 0., z], [1., 0., z], [1., 1., z], [0., 1., z]]),
            label: 1,
            hole_of: None,
        }
    }

    #[test]
    fn names_follow_the_root_and_holes_must_be_of_outer_contours() {
        let naming = Naming {
            source: "arrays",
            root: "planes",
        };
        let mut spec = SectionSpec {
            plane: PlaneSpec::PointNormal {
                point: [0., 0., 0.],
                normal: [0., 0., 3.],
            },
            contours: vec![square(0.0)],
        };
        let s = build_sections(&[spec.clone()], 0, &naming, &ReadOptions::default()).unwrap();
        assert_eq!(s.n_labels, 1);
        assert!((s.sections[0].area() - 1.0).abs() < 1e-12);
        spec.contours[0].points =
            ContourPoints::Xyz(vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.5]]);
        let e = build_sections(&[spec.clone()], 0, &naming, &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("arrays: planes[0].contours[0].points[2]: vertex is 5.000e-1 off"),
            "{e}"
        );
        spec.contours = vec![square(0.0), square(0.0), square(0.0)];
        spec.contours[1].hole_of = Some(0);
        spec.contours[2].hole_of = Some(1);
        let e = build_sections(&[spec], 0, &naming, &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "arrays: planes[0].contours[2].hole_of: contour 1 is itself a hole"
        );
    }
}
