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
use super::plain::{build_sections, ContourPoints, ContourSpec, Naming, PlaneSpec, SectionSpec};
use crate::error::{Error, Result};
use crate::sections::Sections;
use crate::validate::ReadOptions;
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

/// Parse JSON text; `file_name` is used in messages. The result is validated (see `validate`).
pub fn parse_json(text: &str, file_name: &str) -> Result<Sections> {
    parse_json_with(text, file_name, &ReadOptions::default())
}

/// Parse JSON text with `options` (`strict`: no repairs, see `ReadOptions`). The file's structure is
/// checked here (keys, types, arities); its numbers and geometry by `plain::build_sections`.
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
    let specs = planes
        .iter()
        .enumerate()
        .map(|(pi, pv)| section_spec(pv, &format!("$.planes[{pi}]")).map_err(|(p, r)| err(&p, r)))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    let naming = Naming {
        source: file_name,
        root: "$.planes",
    };
    build_sections(&specs, n_labels, &naming, options)
}

/// An error at a JSON path: (path, reason).
type PathError = (String, String);

/// One plane object: `point` + `normal` or `normal` + `offset`, and its contours.
fn section_spec(pv: &Value, ppath: &str) -> std::result::Result<SectionSpec, PathError> {
    let at = |path: &str, r: &str| (path.to_string(), r.to_string());
    let p = object(pv, ppath, &["point", "normal", "offset", "contours"])
        .map_err(|r| (ppath.to_string(), r))?;
    let normal = vec3(p.get("normal"), &format!("{ppath}.normal"))?;
    let plane = match (p.get("point"), p.get("offset")) {
        (Some(pt), None) => PlaneSpec::PointNormal {
            point: vec3(Some(pt), &format!("{ppath}.point"))?,
            normal,
        },
        (None, Some(off)) => PlaneSpec::Equation {
            normal,
            offset: off
                .as_f64()
                .ok_or_else(|| at(&format!("{ppath}.offset"), "expected a number"))?,
        },
        _ => return Err(at(ppath, "give exactly one of \"point\" and \"offset\"")),
    };
    let list = match p.get("contours") {
        None => &[][..],
        Some(v) => v
            .as_array()
            .ok_or_else(|| at(&format!("{ppath}.contours"), "expected an array"))?,
    };
    let contours = list
        .iter()
        .enumerate()
        .map(|(ci, cv)| contour_spec(cv, &format!("{ppath}.contours[{ci}]")))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok(SectionSpec { plane, contours })
}

/// One contour object: `points` or `points2d`, optional `label` and `hole_of`.
fn contour_spec(cv: &Value, cpath: &str) -> std::result::Result<ContourSpec, PathError> {
    let at = |path: String, r: &str| (path, r.to_string());
    let c = object(cv, cpath, &["points", "points2d", "label", "hole_of"])
        .map_err(|r| (cpath.to_string(), r))?;
    let label = match c.get("label") {
        None => 1,
        Some(v) => v
            .as_i64()
            .and_then(|l| i32::try_from(l).ok())
            .ok_or_else(|| at(format!("{cpath}.label"), "expected an integer"))?,
    };
    let hole_of = match c.get("hole_of") {
        None | Some(Value::Null) => None,
        Some(v) => Some(
            v.as_u64()
                .and_then(|h| usize::try_from(h).ok())
                .ok_or_else(|| {
                    at(
                        format!("{cpath}.hole_of"),
                        "expected a contour index or null",
                    )
                })?,
        ),
    };
    let (key, dim) = match (c.get("points"), c.get("points2d")) {
        (Some(_), None) => ("points", 3),
        (None, Some(_)) => ("points2d", 2),
        _ => {
            return Err(at(
                cpath.to_string(),
                "give exactly one of \"points\" and \"points2d\"",
            ))
        }
    };
    let arr = c[key]
        .as_array()
        .ok_or_else(|| at(format!("{cpath}.{key}"), "expected an array of points"))?;
    let mut coords = Vec::with_capacity(arr.len());
    for (k, q) in arr.iter().enumerate() {
        let qpath = format!("{cpath}.{key}[{k}]");
        let q = q
            .as_array()
            .filter(|a| a.len() == dim)
            .ok_or_else(|| (qpath.clone(), format!("expected a point of {dim} numbers")))?;
        let mut x = [0.0; 3];
        for (j, v) in q.iter().enumerate() {
            x[j] = v
                .as_f64()
                .ok_or_else(|| at(format!("{qpath}[{j}]"), "expected a number"))?;
        }
        coords.push(x);
    }
    let points = if dim == 3 {
        ContourPoints::Xyz(coords)
    } else {
        ContourPoints::Uv(coords.iter().map(|x| [x[0], x[1]]).collect())
    };
    Ok(ContourSpec {
        points,
        label,
        hole_of,
    })
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

fn vec3(v: Option<&Value>, path: &str) -> std::result::Result<[f64; 3], PathError> {
    let a = v
        .and_then(Value::as_array)
        .filter(|a| a.len() == 3)
        .ok_or_else(|| (path.to_string(), "expected 3 numbers".to_string()))?;
    let mut x = [0.0; 3];
    for (k, e) in a.iter().enumerate() {
        x[k] = e
            .as_f64()
            .ok_or_else(|| (format!("{path}[{k}]"), "expected a number".to_string()))?;
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
