//! JSON cross-sections: a schema a person can write by hand (documented in README, "Input formats").
//!
//! ```json
//! {"n_labels": 1,
//!  "planes": [
//!    {"point": [0, 0, 0], "normal": [0, 0, 1],
//!     "contours": [
//!       {"points2d": [[0, 0], [4, 0], [4, 4], [0, 4]], "label": 1},
//!       {"points": [[1, 1, 0], [1, 3, 0], [3, 3, 0], [3, 1, 0]], "hole_of": 0}]}]}
//! ```
//! A plane is `point` + `normal`, or `normal` + `offset` (normal·x + offset = 0). A contour is
//! `points` (3D, snapped to the plane) or `points2d` (coordinates in the plane frame of
//! `Plane::from_point_normal`), `label` (default 1), `hole_of` (index of the outer contour in the same
//! plane's list, or null). Unknown keys are errors (typos must not be ignored).
//! The file is parsed to a `serde_json::Value` and walked by hand, so every error names its JSON path.
use crate::error::{Error, Result};
use crate::sections::{Contour, Plane, Region, Section, Sections};
use crate::validate::{
    self, check_coordinate, ContourId, Locator, ReadOptions, Role, OFF_PLANE_RELATIVE_TOLERANCE,
};
use serde_json::{json, Map, Value};
use std::path::Path;

/// Read a JSON sections file (repairing, see `ReadOptions`).
pub fn read_json(path: &Path) -> Result<Sections> {
    read_json_with(path, &ReadOptions::default())
}

/// Read a JSON sections file with `options`.
pub fn read_json_with(path: &Path, options: &ReadOptions) -> Result<Sections> {
    let text = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let text = String::from_utf8_lossy(&text);
    parse_json_with(&text, &path.display().to_string(), options)
}

/// Write a JSON sections file.
pub fn write_json(path: &Path, sections: &Sections) -> Result<()> {
    std::fs::write(path, to_json_string(sections)).map_err(|e| Error::io(path, e))
}

/// JSON text of `sections`: each plane as its frame origin and normal, contours in 2D (`points2d`,
/// exact), holes right after their outer contour with `hole_of`.
pub fn to_json_string(sections: &Sections) -> String {
    let planes: Vec<Value> = sections
        .sections
        .iter()
        .map(|s| {
            let mut contours = Vec::new();
            for r in &s.regions {
                let outer = contours.len();
                contours
                    .push(json!({"points2d": r.outer.points2, "label": r.label, "hole_of": null}));
                for h in &r.holes {
                    contours
                        .push(json!({"points2d": h.points2, "label": r.label, "hole_of": outer}));
                }
            }
            json!({"point": s.plane.origin, "normal": s.plane.normal, "contours": contours})
        })
        .collect();
    let doc = json!({"n_labels": sections.n_labels, "planes": planes});
    let mut text = serde_json::to_string_pretty(&doc).expect("a Value always serialises");
    text.push('\n');
    text
}

struct JsonLocator<'a> {
    file: &'a str,
    /// Per section: its `planes[i]` index, and per region (outer contour index, hole contour indices).
    planes: Vec<usize>,
    regions: Vec<Vec<(usize, Vec<usize>)>>,
}

impl Locator for JsonLocator<'_> {
    fn plane(&self, s: usize) -> String {
        format!("{}: $.planes[{}]", self.file, self.planes[s])
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

/// Parse JSON text; `file_name` is used in messages. The result is validated (see `validate`).
pub fn parse_json(text: &str, file_name: &str) -> Result<Sections> {
    parse_json_with(text, file_name, &ReadOptions::default())
}

/// Parse JSON text with `options` (`strict`: no repairs, see `ReadOptions`).
pub fn parse_json_with(text: &str, file_name: &str, options: &ReadOptions) -> Result<Sections> {
    let doc: Value = serde_json::from_str(text).map_err(|e| {
        Error::input(
            format!("{file_name}:{}:{}", e.line(), e.column()),
            format!("invalid JSON: {e}"),
        )
    })?;
    let err = |path: &str, reason: String| Error::input(format!("{file_name}: {path}"), reason);
    let top = object(&doc, "$", &["planes", "n_labels"]).map_err(|r| err("$", r))?;
    let n_labels = match top.get("n_labels") {
        None | Some(Value::Null) => 0,
        Some(v) => v
            .as_u64()
            .and_then(|n| usize::try_from(n).ok())
            .ok_or_else(|| err("$.n_labels", "expected a non-negative integer".into()))?,
    };
    let planes = top
        .get("planes")
        .ok_or_else(|| err("$", "missing key \"planes\"".into()))?
        .as_array()
        .ok_or_else(|| err("$.planes", "expected an array of planes".into()))?;

    struct RawContour {
        path: String,
        label: i32,
        hole_of: Option<usize>,
        /// 3D points (given, or the plane points of the 2D input: they count in the bounding box).
        points: Vec<[f64; 3]>,
        /// The 2D input, empty for 3D input.
        points2: Vec<[f64; 2]>,
        is_3d: bool,
    }
    let mut raw = Vec::new();
    for (pi, pv) in planes.iter().enumerate() {
        let ppath = format!("$.planes[{pi}]");
        let p = object(pv, &ppath, &["point", "normal", "offset", "contours"])
            .map_err(|r| err(&ppath, r))?;
        let normal =
            vec3(p.get("normal"), &format!("{ppath}.normal")).map_err(|(path, r)| err(&path, r))?;
        if normal == [0.0; 3] {
            return Err(err(
                &format!("{ppath}.normal"),
                "plane normal is zero".into(),
            ));
        }
        let plane = match (p.get("point"), p.get("offset")) {
            (Some(pt), None) => {
                let point =
                    vec3(Some(pt), &format!("{ppath}.point")).map_err(|(path, r)| err(&path, r))?;
                Plane::from_point_normal(point, normal)
            }
            (None, Some(off)) => {
                let d = off
                    .as_f64()
                    .ok_or_else(|| err(&format!("{ppath}.offset"), "expected a number".into()))?;
                let d = check_coordinate(d).map_err(|r| err(&format!("{ppath}.offset"), r))?;
                Plane::from_equation(normal, d)
            }
            _ => {
                return Err(err(
                    &ppath,
                    "give exactly one of \"point\" and \"offset\"".into(),
                ))
            }
        }
        .ok_or_else(|| {
            err(
                &ppath,
                "plane cannot be normalised (numbers too large or too small)".into(),
            )
        })?;

        let mut contours = Vec::new();
        let list = match p.get("contours") {
            None => &[][..],
            Some(v) => v
                .as_array()
                .ok_or_else(|| err(&format!("{ppath}.contours"), "expected an array".into()))?,
        };
        for (ci, cv) in list.iter().enumerate() {
            let cpath = format!("{ppath}.contours[{ci}]");
            let c = object(cv, &cpath, &["points", "points2d", "label", "hole_of"])
                .map_err(|r| err(&cpath, r))?;
            let label = match c.get("label") {
                None => 1,
                Some(v) => v
                    .as_i64()
                    .and_then(|l| i32::try_from(l).ok())
                    .ok_or_else(|| err(&format!("{cpath}.label"), "expected an integer".into()))?,
            };
            let hole_of = match c.get("hole_of") {
                None | Some(Value::Null) => None,
                Some(v) => {
                    let h = v
                        .as_u64()
                        .and_then(|h| usize::try_from(h).ok())
                        .ok_or_else(|| {
                            err(
                                &format!("{cpath}.hole_of"),
                                "expected a contour index or null".into(),
                            )
                        })?;
                    if h >= list.len() || h == ci {
                        return Err(err(
                            &format!("{cpath}.hole_of"),
                            format!(
                                "{h} is not another contour of this plane (0..{})",
                                list.len()
                            ),
                        ));
                    }
                    Some(h)
                }
            };
            let (key, dim) = match (c.get("points"), c.get("points2d")) {
                (Some(_), None) => ("points", 3),
                (None, Some(_)) => ("points2d", 2),
                _ => {
                    return Err(err(
                        &cpath,
                        "give exactly one of \"points\" and \"points2d\"".into(),
                    ))
                }
            };
            let arr = c[key].as_array().ok_or_else(|| {
                err(
                    &format!("{cpath}.{key}"),
                    "expected an array of points".into(),
                )
            })?;
            let mut points = Vec::with_capacity(arr.len());
            let mut points2 = Vec::new();
            for (k, q) in arr.iter().enumerate() {
                let qpath = format!("{cpath}.{key}[{k}]");
                let q = q
                    .as_array()
                    .filter(|a| a.len() == dim)
                    .ok_or_else(|| err(&qpath, format!("expected a point of {dim} numbers")))?;
                let mut x = [0.0; 3];
                for (j, v) in q.iter().enumerate() {
                    let f = v
                        .as_f64()
                        .ok_or_else(|| err(&format!("{qpath}[{j}]"), "expected a number".into()))?;
                    x[j] = check_coordinate(f).map_err(|r| err(&format!("{qpath}[{j}]"), r))?;
                }
                if dim == 2 {
                    points2.push([x[0], x[1]]);
                }
                points.push(if dim == 3 {
                    x
                } else {
                    plane.to_3d([x[0], x[1]])
                });
            }
            contours.push(RawContour {
                path: cpath,
                label,
                hole_of,
                points,
                points2,
                is_3d: dim == 3,
            });
        }
        for c in &contours {
            if let Some(h) = c.hole_of {
                if contours[h].hole_of.is_some() {
                    return Err(err(
                        &format!("{}.hole_of", c.path),
                        format!("contour {h} is itself a hole"),
                    ));
                }
            }
        }
        raw.push((plane, contours));
    }

    // Snap 3D points to their plane; the tolerance is relative to the model's bounding box.
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in raw
        .iter()
        .flat_map(|(_, cs)| cs.iter().flat_map(|c| &c.points))
    {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let diag = if lo[0] <= hi[0] {
        ((0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>()).sqrt()
    } else {
        0.0
    };
    let tol = OFF_PLANE_RELATIVE_TOLERANCE * diag;
    let mut loc = JsonLocator {
        file: file_name,
        planes: Vec::new(),
        regions: Vec::new(),
    };
    let mut sections = Vec::new();
    for (pi, (plane, contours)) in raw.into_iter().enumerate() {
        let mut max_off: f64 = 0.0;
        let mut built = Vec::with_capacity(contours.len());
        for c in &contours {
            let mut points2 = Vec::with_capacity(c.points.len());
            for (k, p) in c.points.iter().enumerate() {
                if c.is_3d {
                    let off = plane.signed_distance(*p).abs();
                    if off > tol {
                        return Err(err(
                            &format!("{}.points[{k}]", c.path),
                            format!(
                                "vertex is {off:.3e} off its plane; tolerance {tol:.3e} ({OFF_PLANE_RELATIVE_TOLERANCE} x model bounding-box diagonal {diag:.3e})"
                            ),
                        ));
                    }
                    max_off = max_off.max(off);
                    points2.push(plane.to_2d(*p));
                } else {
                    // 2D input is kept exactly as given (not re-projected).
                    points2.push(c.points2[k]);
                }
            }
            built.push(points2);
        }
        let mut regions = Vec::new();
        let mut region_contours = Vec::new();
        for (ci, c) in contours.iter().enumerate() {
            if c.hole_of.is_some() {
                continue;
            }
            let holes: Vec<usize> = (0..contours.len())
                .filter(|&h| contours[h].hole_of == Some(ci))
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
            warnings: Vec::new(),
            label_names: Default::default(),
        },
        &loc,
        options,
    )
}

/// `v` as an object with only the allowed keys.
fn object<'a>(
    v: &'a Value,
    path: &str,
    allowed: &[&str],
) -> std::result::Result<&'a Map<String, Value>, String> {
    let m = v
        .as_object()
        .ok_or_else(|| format!("expected an object at {path}"))?;
    if let Some(k) = m.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(format!(
            "unknown key \"{}\" (allowed: {})",
            k.chars().take(40).collect::<String>(),
            allowed.join(", ")
        ));
    }
    Ok(m)
}

fn vec3(v: Option<&Value>, path: &str) -> std::result::Result<[f64; 3], (String, String)> {
    let a = v
        .and_then(Value::as_array)
        .filter(|a| a.len() == 3)
        .ok_or_else(|| (path.to_string(), "expected 3 numbers".to_string()))?;
    let mut x = [0.0; 3];
    for (k, e) in a.iter().enumerate() {
        let f = e
            .as_f64()
            .ok_or_else(|| (format!("{path}[{k}]"), "expected a number".to_string()))?;
        x[k] = check_coordinate(f).map_err(|r| (format!("{path}[{k}]"), r))?;
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_written_example_round_trips() {
        let text = r#"{"planes": [{"point": [0, 0, 1], "normal": [0, 0, 2], "contours": [
            {"points": [[0, 0, 1], [4, 0, 1], [4, 4, 1], [0, 4, 1]], "label": 1},
            {"points2d": [[-1, 1], [-3, 1], [-3, 3], [-1, 3]], "hole_of": 0}]}]}"#;
        // The frame of normal +z is u = (0,-1,0), v = (1,0,0): (s,t) = (-y, x).
        let s = parse_json(text, "t.json").unwrap();
        assert_eq!(s.sections[0].regions[0].holes.len(), 1);
        assert!((s.sections[0].area() - 12.0).abs() < 1e-12);
        let hole = &s.sections[0].regions[0].holes[0];
        assert_eq!(hole.points3[0], [1.0, 1.0, 1.0]);
        let again = parse_json(&to_json_string(&s), "u.json").unwrap();
        assert_eq!(
            again.sections[0].regions[0].outer.points2,
            s.sections[0].regions[0].outer.points2
        );
    }

    #[test]
    fn errors_name_the_path() {
        let e = parse_json(
            r#"{"planes": [{"point": [0,0,0], "normal": [0,0,0]}]}"#,
            "t.json",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("t.json: $.planes[0].normal") && e.contains("zero"),
            "{e}"
        );
        let e = parse_json(r#"{"planes": [{"point": [0,0,0], "normal": [0,0,1], "contours": [{"points2d": [[0,0],[1,0]]}]}]}"#, "t.json")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("t.json: $.planes[0].contours[0]") && e.contains("at least 3"),
            "{e}"
        );
        let e = parse_json("{\"planes\": [", "t.json")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("t.json:1:") && e.contains("invalid JSON"),
            "{e}"
        );
    }
}
