//! Input repairs (README, "Input formats"): each kind on a small synthetic file, the warning that
//! names where it happened, the same input refused with `strict` (library and `info --strict`),
//! and the shared files untouched (no repair, same sections as strict reading).
mod common;
use common::bin;
use slice2solid::eval::check::check_mesh;
use slice2solid::io::csl::{parse_csl, parse_csl_with, to_csl_string};
use slice2solid::io::json::{parse_json, parse_json_with};
use slice2solid::io::ReadOptions;
use slice2solid::{Options, Sections};

const STRICT: ReadOptions = ReadOptions { strict: true };

/// Plane 1: a 4x4 square on z = 0 (lines 3-8); plane 2 (line 9) with `plane2` as its equation
/// `a b c d` and the vertices `v2` (lines 10-13), one component (line 14).
fn two_planes(plane2: &str, v2: &str) -> String {
    format!("CSLC\n2 1\n1 4 1 0 0 1 0\n0 0 0\n4 0 0\n4 4 0\n0 4 0\n4 1 0 1 2 3\n2 4 1 {plane2}\n{v2}\n4 1 0 1 2 3\n")
}

/// Plane 1 as in `two_planes`; plane 2 (line 9) on z = 1 with the 2D vertices `v2` (x y, one a line,
/// from line 10) and the components `comps` (one a line, after the vertices).
fn plane2(v2: &[[f64; 2]], comps: &[&str]) -> String {
    let v: Vec<String> = v2.iter().map(|p| format!("{} {} 1", p[0], p[1])).collect();
    format!(
        "CSLC\n2 1\n1 4 1 0 0 1 0\n0 0 0\n4 0 0\n4 4 0\n0 4 0\n4 1 0 1 2 3\n2 {} {} 0 0 1 -1\n{}\n{}\n",
        v2.len(),
        comps.len(),
        v.join("\n"),
        comps.join("\n")
    )
}

/// Reconstruct `s` (all labels, or `--label l`): a closed oriented manifold without
/// self-intersections whose sections agree with the repaired input (the sections as read for all
/// labels, `select_label(Some(l))` for one).
fn assert_reconstructs(s: &Sections, label: Option<i32>) {
    let options = Options {
        label,
        ..Default::default()
    };
    let solid = slice2solid::reconstruct(s, &options).unwrap_or_else(|e| panic!("{label:?}: {e}"));
    let target = match label {
        None => s.clone(),
        Some(_) => s.select_label(label).unwrap(),
    };
    let c = check_mesh(&solid.surface, Some(&target));
    assert!(
        c.closed && c.manifold && c.oriented && c.self_intersection_free,
        "{label:?}: closed {} manifold {} oriented {} self-intersections {}",
        c.closed,
        c.manifold,
        c.oriented,
        c.self_intersections
    );
    let worst = c
        .worst_section
        .as_ref()
        .map_or(f64::INFINITY, |w| w.relative);
    assert!(worst < 1e-6, "{label:?}: section disagreement {worst}");
}

fn repairs(s: &Sections) -> Vec<&String> {
    s.warnings
        .iter()
        .filter(|w| w.contains("repaired"))
        .collect()
}

fn strict_error(text: &str) -> String {
    match parse_csl_with(text, "t.csl", &STRICT) {
        Ok(_) => panic!("strict accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// `slice2solid info` on `text` written to a file: (success, stdout, stderr).
fn info(text: &str, strict: bool) -> (bool, String, String) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("t.csl");
    std::fs::write(&p, text).unwrap();
    let mut cmd = bin();
    cmd.arg("info").arg(&p);
    if strict {
        cmd.arg("--strict");
    }
    let out = cmd.output().unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn assert_cli_repairs_and_strict_refuses(text: &str, warning: &str, error: &str) {
    let (ok, out, err) = info(text, false);
    assert!(ok && out.contains(warning), "{out}{err}");
    let (ok, out, err) = info(text, true);
    assert!(!ok && err.contains(error), "{out}{err}");
}

#[test]
fn flipped_offset_file_is_read_with_that_convention() {
    // z = 1 written as 0 0 1 1 (z + 1 = 0): every plane fits z - d = 0 instead.
    let text = two_planes("0 0 1 1", "0 0 1\n4 0 1\n4 4 1\n0 4 1");
    let s = parse_csl(&text, "t.csl").unwrap();
    let r = repairs(&s);
    assert_eq!(r.len(), 1, "{:?}", s.warnings);
    assert!(
        r[0].starts_with("t.csl: repaired plane equations")
            && r[0].contains("1 of 2 plane(s)")
            && r[0].contains("- d = 0"),
        "{}",
        r[0]
    );
    assert_eq!(s.sections.len(), 2);
    assert!(s.sections[1].plane.signed_distance([3.0, 3.0, 1.0]).abs() < 1e-12);
    assert!(s.sections[0].plane.signed_distance([3.0, 3.0, 0.0]).abs() < 1e-12);
    for sec in &s.sections {
        assert_eq!(sec.regions.len(), 1);
        assert!((sec.area() - 16.0).abs() < 1e-9, "{}", sec.area());
        assert!(sec.max_off_plane < 1e-12);
    }
    let e = strict_error(&text);
    assert!(
        e.starts_with("t.csl:10: plane 2") && e.contains("vertex 0 is 2.000e0 off its plane"),
        "{e}"
    );
    assert_cli_repairs_and_strict_refuses(&text, "repaired plane equations", "plane 2");
    assert_reconstructs(&s, None);
}

#[test]
fn plane_equation_off_its_coplanar_vertices_takes_their_plane() {
    // Stated z = 1; the vertices lie on z = 1 + 0.01 x (0.04 off at x = 4; tolerance 5.8e-3).
    let text = two_planes("0 0 1 -1", "0 0 1\n4 0 1.04\n4 4 1.04\n0 4 1");
    let s = parse_csl(&text, "t.csl").unwrap();
    let r = repairs(&s);
    assert_eq!(r.len(), 1, "{:?}", s.warnings);
    assert!(
        r[0].starts_with("t.csl:9: plane 2: repaired plane equation")
            && r[0].contains("up to 4.000e-2 off")
            && r[0].contains("normal turned by 0.573 degrees"),
        "{}",
        r[0]
    );
    let sec = &s.sections[1];
    for v in [
        [0.0, 0.0, 1.0],
        [4.0, 0.0, 1.04],
        [4.0, 4.0, 1.04],
        [0.0, 4.0, 1.0],
    ] {
        assert!(sec.plane.signed_distance(v).abs() < 1e-12);
    }
    let area = 16.0 * (1.0f64 + 1e-4).sqrt();
    assert!((sec.area() - area).abs() < 1e-9, "{}", sec.area());
    let e = strict_error(&text);
    assert!(
        e.starts_with("t.csl:11: plane 2") && e.contains("vertex 1 is 4.000e-2 off its plane"),
        "{e}"
    );
    assert_cli_repairs_and_strict_refuses(&text, "repaired plane equation", "plane 2");
    assert_reconstructs(&s, None);
}

#[test]
fn one_vertex_off_an_agreeing_plane_is_still_rejected() {
    // Three of four vertices agree with z = 1; the fourth is misplaced, not the plane.
    let text = two_planes("0 0 1 -1", "0 0 1\n4 0 1\n4 4 1.5\n0 4 1");
    let e = parse_csl(&text, "t.csl").unwrap_err().to_string();
    assert!(
        e.starts_with("t.csl:12: plane 2") && e.contains("off its plane"),
        "{e}"
    );
    // Non-coplanar vertices with no majority on the stated plane: rejected too.
    let text = two_planes("0 0 1 -1", "0 0 1.2\n4 0 1\n4 4 1.2\n0 4 1");
    let e = parse_csl(&text, "t.csl").unwrap_err().to_string();
    assert!(e.contains("plane 2") && e.contains("off its plane"), "{e}");
}

/// Nothing valid is repaired: every shared file reads without a repair warning, and to the same
/// sections (CSL text byte for byte, and every number of the model) as strict reading, which
/// performs no repair at all.
#[test]
fn shared_files_are_not_repaired() {
    for path in common::shared_csl_files() {
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path.display().to_string();
        let repaired = parse_csl(&text, &name).unwrap();
        let strict = parse_csl_with(&text, &name, &STRICT).unwrap();
        assert!(
            repairs(&repaired).is_empty(),
            "{name}: {:?}",
            repaired.warnings
        );
        assert_eq!(repaired.warnings, strict.warnings, "{name}");
        assert!(
            to_csl_string(&repaired) == to_csl_string(&strict),
            "{name}: sections differ"
        );
        assert!(repaired == strict, "{name}: sections differ");
        // No plane has touching labels: all labels as one material are the sections as read.
        assert!(
            repaired.select_label(None).unwrap() == repaired,
            "{name}: the one-material view differs"
        );
    }
}

#[test]
fn bow_tie_splits_into_two_regions() {
    let text = plane2(
        &[[0.0, 0.0], [4.0, 4.0], [4.0, 0.0], [0.0, 4.0]],
        &["4 1 0 1 2 3"],
    );
    let s = parse_csl(&text, "t.csl").unwrap();
    let r = repairs(&s);
    assert_eq!(r.len(), 1, "{:?}", s.warnings);
    assert!(
        r[0].starts_with("t.csl:14: plane 2, component 0: repaired self-intersecting")
            && r[0].contains("split into 2 regions with 0 hole(s)"),
        "{}",
        r[0]
    );
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    let sec = &s.sections[1];
    assert_eq!(sec.regions.len(), 2);
    for region in &sec.regions {
        assert_eq!(region.label, 1);
        assert!(region.holes.is_empty());
        assert_eq!(region.outer.points2.len(), 3);
        // Each lobe's copy of the crossing (2, 2) moved 1e-5 x diagonal into its lobe.
        let nudge = slice2solid::validate::NUDGE_RELATIVE * 33f64.sqrt();
        let area = 0.5 * 4.0 * (2.0 - nudge);
        assert!((region.area() - area).abs() < 1e-12, "{}", region.area());
        assert!(region.outer.signed_area() > 0.0);
    }
    let e = strict_error(&text);
    assert!(
        e.starts_with("t.csl:14: plane 2, component 0") && e.contains("self-intersecting contour"),
        "{e}"
    );
    assert_cli_repairs_and_strict_refuses(&text, "split into 2 regions", "self-intersecting");
    assert_reconstructs(&s, None);
}

#[test]
fn keyhole_becomes_an_outer_contour_and_a_hole() {
    // The outline runs up a zero-width channel at x = 2 into the hole [1,3]x[1,3], round it
    // clockwise, and back down.
    let v = [
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [1.0, 3.0],
        [3.0, 3.0],
        [3.0, 1.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [0.0, 4.0],
    ];
    let text = plane2(&v, &["12 1 0 1 2 3 4 5 6 2 1 7 8 9"]);
    let s = parse_csl(&text, "t.csl").unwrap();
    let r = repairs(&s);
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    assert!(
        r[0].starts_with("t.csl:20: plane 2, component 0: repaired self-intersecting")
            && r[0].contains("keyhole: 1 outer + 1 hole(s)"),
        "{}",
        r[0]
    );
    let sec = &s.sections[1];
    assert_eq!(sec.regions.len(), 1);
    let region = &sec.regions[0];
    assert_eq!(region.holes.len(), 1);
    assert!((region.outer.signed_area() - 16.0).abs() < 1e-9);
    assert!((region.holes[0].signed_area() + 4.0).abs() < 1e-9);
    assert!((region.area() - 12.0).abs() < 1e-9);
    let e = strict_error(&text);
    assert!(
        e.starts_with("t.csl:20: plane 2, component 0") && e.contains("self-intersecting contour"),
        "{e}"
    );
    assert_cli_repairs_and_strict_refuses(&text, "keyhole", "self-intersecting");
    assert_reconstructs(&s, None);
}

#[test]
fn touching_components_of_one_label_are_merged() {
    // Two 2x2 squares of label 1 sharing the edge x = 2 (components 0 and 1, lines 18 and 19).
    let v = [
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 2.0],
        [0.0, 2.0],
        [2.0, 0.0],
        [4.0, 0.0],
        [4.0, 2.0],
        [2.0, 2.0],
    ];
    let text = plane2(&v, &["4 1 0 1 2 3", "4 1 4 5 6 7"]);
    let s = parse_csl(&text, "t.csl").unwrap();
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    let w = &s.warnings[0];
    assert!(
        w.starts_with("t.csl:18: plane 2, component 0: repaired 2 touching or overlapping components of label 1 (with t.csl:19: plane 2, component 1)")
            && w.contains("merged into 1 region(s) with 0 hole(s)"),
        "{w}"
    );
    let sec = &s.sections[1];
    assert_eq!(sec.regions.len(), 1);
    assert_eq!(sec.regions[0].label, 1);
    assert!(sec.regions[0].holes.is_empty());
    assert!((sec.area() - 8.0).abs() < 1e-9, "{}", sec.area());
    let e = strict_error(&text);
    assert!(
        e.starts_with("t.csl:18: plane 2, component 0")
            && e.contains("contours of one plane cross"),
        "{e}"
    );
    assert_cli_repairs_and_strict_refuses(&text, "touching or overlapping components", "cross");
    assert_reconstructs(&s, None);

    // Overlapping in area: [0,3]x[0,2] and [2,4]x[0,2] become [0,4]x[0,2].
    let v = [
        [0.0, 0.0],
        [3.0, 0.0],
        [3.0, 2.0],
        [0.0, 2.0],
        [2.0, 0.5],
        [4.0, 0.5],
        [4.0, 1.5],
        [2.0, 1.5],
    ];
    let s = parse_csl(&plane2(&v, &["4 1 0 1 2 3", "4 1 4 5 6 7"]), "t.csl").unwrap();
    assert_eq!(s.sections[1].regions.len(), 1, "{:?}", s.warnings);
    assert!((s.sections[1].area() - 7.0).abs() < 1e-9);
    assert_reconstructs(&s, None);
    // One inside the other's material: the outer one is what is left.
    let v = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [0.0, 4.0],
        [1.0, 1.0],
        [2.0, 1.0],
        [2.0, 2.0],
        [1.0, 2.0],
    ];
    let text = plane2(&v, &["4 1 0 1 2 3", "4 1 4 5 6 7"]);
    let s = parse_csl(&text, "t.csl").unwrap();
    assert_eq!(s.sections[1].regions.len(), 1, "{:?}", s.warnings);
    assert!((s.sections[1].area() - 16.0).abs() < 1e-9);
    assert!(strict_error(&text).contains("regions overlap"));
    assert_reconstructs(&s, None);
}

#[test]
fn hole_touching_its_outer_contour_is_subtracted() {
    // Hole [1,3]x[0,2] on the bottom edge of [0,4]^2 (component 1, line 19): a U of area 12.
    let v = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [0.0, 4.0],
        [1.0, 0.0],
        [3.0, 0.0],
        [3.0, 2.0],
        [1.0, 2.0],
    ];
    let text = plane2(&v, &["4 1 0 1 2 3", "4h0 1 4 5 6 7"]);
    let s = parse_csl(&text, "t.csl").unwrap();
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    let w = &s.warnings[0];
    assert!(
        w.starts_with("t.csl:18: plane 2, component 0: repaired a hole touching or crossing its outer contour:")
            && w.contains("merged into 1 region(s) with 0 hole(s)"),
        "{w}"
    );
    let sec = &s.sections[1];
    assert_eq!(sec.regions.len(), 1);
    assert!(sec.regions[0].holes.is_empty());
    assert_eq!(sec.regions[0].outer.points2.len(), 8);
    assert!((sec.area() - 12.0).abs() < 1e-9, "{}", sec.area());
    let e = strict_error(&text);
    assert!(
        e.contains("plane 2, component") && e.contains("cross"),
        "{e}"
    );
    assert_cli_repairs_and_strict_refuses(&text, "a hole touching", "cross");
    assert_reconstructs(&s, None);
}

/// Two planes (z = 0, lines 3-13, and z = 1, lines 14-24), each with the same two rectangles:
/// component 0 of label `l0` on `a` and component 1 of label `l1` on `b` (x0 y0 x1 y1).
fn two_labels(l0: i32, a: [f64; 4], l1: i32, b: [f64; 4]) -> String {
    let rect = |r: [f64; 4], z: f64| {
        format!(
            "{} {} {z}\n{} {} {z}\n{} {} {z}\n{} {} {z}",
            r[0], r[1], r[2], r[1], r[2], r[3], r[0], r[3]
        )
    };
    let plane = |i: usize, z: f64| {
        format!(
            "{i} 8 2 0 0 1 {}\n{}\n{}\n4 {l0} 0 1 2 3\n4 {l1} 4 5 6 7\n",
            -z,
            rect(a, z),
            rect(b, z)
        )
    };
    format!("CSLC\n2 2\n{}{}", plane(1, 0.0), plane(2, 1.0))
}

fn region_areas(s: &Sections, section: usize) -> Vec<(i32, f64)> {
    s.sections[section]
        .regions
        .iter()
        .map(|r| (r.label, r.area()))
        .collect()
}

#[test]
fn touching_different_labels_keep_their_shared_boundary() {
    // Label 1 on [0,2]x[0,2] and label 2 on [2,4]x[0,2]: they share the edge x = 2.
    let text = two_labels(1, [0.0, 0.0, 2.0, 2.0], 2, [2.0, 0.0, 4.0, 2.0]);
    let s = parse_csl(&text, "t.csl").unwrap();
    assert_eq!(s.warnings.len(), 2, "{:?}", s.warnings);
    for (w, (c0, c1)) in s.warnings.iter().zip([(12, 13), (23, 24)]) {
        let plane = if c0 == 12 { 1 } else { 2 };
        let head = format!(
            "t.csl:{c0}: plane {plane}, component 0 (label 1) and t.csl:{c1}: plane {plane}, component 1 (label 2): repaired touching components of different labels"
        );
        assert!(
            w.starts_with(&head) && w.contains("overlap area 0.000e0"),
            "{w}"
        );
    }
    for k in 0..2 {
        assert_eq!(region_areas(&s, k), vec![(1, 4.0), (2, 4.0)]);
        // Nothing moved: the outlines are the input's, shared edge included.
        let r = &s.sections[k].regions;
        assert!(r[0].outer.points2.contains(&r[1].outer.points2[0]));
    }
    // All labels as one material: one 4x2 region per plane; one label: that label's rectangle.
    let all = s.select_label(None).unwrap();
    for k in 0..2 {
        assert_eq!(all.sections[k].regions.len(), 1);
        assert!((all.sections[k].area() - 8.0).abs() < 1e-12);
        assert!(all.sections[k].regions[0].holes.is_empty());
    }
    let two = s.select_label(Some(2)).unwrap();
    assert_eq!(region_areas(&two, 1), vec![(2, 4.0)]);
    let e = strict_error(&text);
    assert!(
        e.starts_with("t.csl:12: plane 1, component 0")
            && e.contains("contours of one plane cross")
            && e.contains("t.csl:13: plane 1, component 1"),
        "{e}"
    );
    assert_cli_repairs_and_strict_refuses(&text, "repaired touching components", "cross");
    assert_reconstructs(&s, None);
    assert_reconstructs(&s, Some(1));
    assert_reconstructs(&s, Some(2));
}

#[test]
fn overlapping_different_labels_the_lower_label_keeps_the_overlap() {
    // Label 1 on [0,3]x[0,2], label 2 on [2,4]x[0,2]: they overlap on [2,3]x[0,2] (area 2).
    let text = two_labels(1, [0.0, 0.0, 3.0, 2.0], 2, [2.0, 0.0, 4.0, 2.0]);
    let s = parse_csl(&text, "t.csl").unwrap();
    let r = repairs(&s);
    assert_eq!(r.len(), 4, "{:?}", s.warnings);
    assert!(
        r[0].starts_with("t.csl:12: plane 1, component 0 (label 1) and t.csl:13: plane 1, component 1 (label 2): repaired overlapping components of different labels: overlap area 2.000000e0; the lower label 1 keeps it"),
        "{}",
        r[0]
    );
    assert!(
        r[1].starts_with("t.csl:13: plane 1, component 1: repaired label 2 component overlapped by lower labels: became 1 region(s) with 0 hole(s)"),
        "{}",
        r[1]
    );
    for k in 0..2 {
        assert_eq!(region_areas(&s, k), vec![(1, 6.0), (2, 2.0)]);
        let r2 = &s.sections[k].regions[1];
        assert!(r2.outer.points3.iter().all(|p| p[0] >= 3.0), "{r2:?}");
    }
    assert!((s.select_label(None).unwrap().sections[0].area() - 8.0).abs() < 1e-12);
    // The rule is by label number, not by order in the file: swapped, label 1 keeps [2,4].
    let swapped = two_labels(2, [0.0, 0.0, 3.0, 2.0], 1, [2.0, 0.0, 4.0, 2.0]);
    let t = parse_csl(&swapped, "t.csl").unwrap();
    assert_eq!(region_areas(&t, 0), vec![(2, 4.0), (1, 4.0)]);
    assert!(repairs(&t)[0].contains("the lower label 1 keeps it"));
    let e = strict_error(&text);
    assert!(
        e.starts_with("t.csl:12: plane 1, component 0")
            && e.contains("contours of one plane cross"),
        "{e}"
    );
    assert_cli_repairs_and_strict_refuses(&text, "overlap area 2.000000e0", "cross");
    assert_reconstructs(&s, None);
    assert_reconstructs(&s, Some(1));
    assert_reconstructs(&s, Some(2));
}

#[test]
fn a_lower_label_inside_a_higher_one_becomes_its_hole() {
    // Label 2 on [0,4]^2 and label 1 on [1,2]^2 inside its material (no contours touch): label 2
    // gets a hole where label 1 is; as one material the plane is the full square again.
    let text = two_labels(2, [0.0, 0.0, 4.0, 4.0], 1, [1.0, 1.0, 2.0, 2.0]);
    let s = parse_csl(&text, "t.csl").unwrap();
    assert!(
        repairs(&s)[0].contains("overlap area 1.000000e0")
            && repairs(&s)[1].contains("became 1 region(s) with 1 hole(s)"),
        "{:?}",
        s.warnings
    );
    for k in 0..2 {
        assert_eq!(region_areas(&s, k), vec![(2, 15.0), (1, 1.0)]);
    }
    let all = s.select_label(None).unwrap();
    assert_eq!(all.sections[0].regions.len(), 1);
    assert!(all.sections[0].regions[0].holes.is_empty());
    assert!((all.sections[0].area() - 16.0).abs() < 1e-12);
    assert!(strict_error(&text).contains("regions overlap"));
    assert_reconstructs(&s, None);
    assert_reconstructs(&s, Some(2));
    // The other way round, label 2 is removed where it lies inside label 1.
    let text = two_labels(1, [0.0, 0.0, 4.0, 4.0], 2, [1.0, 1.0, 2.0, 2.0]);
    let s = parse_csl(&text, "t.csl").unwrap();
    assert!(repairs(&s)[1].contains("removed"), "{:?}", s.warnings);
    assert_eq!(region_areas(&s, 0), vec![(1, 16.0)]);
}

#[test]
fn reconstruct_and_check_from_the_command_line() {
    // Touching labels: `reconstruct` (all labels, and --label 2) and `check --sections` on the file.
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("t.csl");
    std::fs::write(
        &input,
        two_labels(1, [0.0, 0.0, 2.0, 2.0], 2, [2.0, 0.0, 4.0, 2.0]),
    )
    .unwrap();
    for label in [None, Some("2")] {
        let out = dir.path().join("out.obj");
        let mut cmd = bin();
        cmd.arg("reconstruct").arg(&input).arg("-o").arg(&out);
        if let Some(l) = label {
            cmd.args(["--label", l]);
        }
        let run = cmd.output().unwrap();
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(String::from_utf8_lossy(&run.stderr).contains("repaired touching"));
        let check = bin()
            .arg("check")
            .arg(&out)
            .arg("--sections")
            .arg(&input)
            .arg("--json")
            .output()
            .unwrap();
        let report = common::json_of_success(&check);
        let worst = report["worst_section"]["relative"].as_f64().unwrap();
        match label {
            None => assert!(worst < 1e-6, "{report}"),
            // Against the whole file, one label's solid misses the other label.
            Some(_) => assert!((worst - 0.5).abs() < 1e-6, "{report}"),
        }
    }
    let run = bin()
        .arg("reconstruct")
        .arg(&input)
        .arg("-o")
        .arg(dir.path().join("x.obj"))
        .arg("--strict")
        .output()
        .unwrap();
    assert!(!run.status.success());
    assert!(String::from_utf8_lossy(&run.stderr).contains("plane 1, component 0"));
}

/// A 4x4 square at height `z` (x + 0.01 `tilt` x), as a JSON contour given in 3D.
fn json_square(z: f64, tilt: f64) -> String {
    format!(
        r#"{{"points": [[0,0,{z}],[4,0,{}],[4,4,{}],[0,4,{z}]]}}"#,
        z + 0.04 * tilt,
        z + 0.04 * tilt
    )
}

fn json_error(text: &str, options: &ReadOptions) -> String {
    match parse_json_with(text, "t.json", options) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn json_planes_get_the_csl_plane_repairs() {
    // Plane 1 is z = 1 stated as normal (0,0,1), offset 1 (z + 1 = 0); plane 0 is given by a
    // point (no sign convention) and fits.
    let text = format!(
        r#"{{"planes": [{{"point": [0,0,0], "normal": [0,0,1], "contours": [{}]}},
            {{"normal": [0,0,1], "offset": 1, "contours": [{}]}}]}}"#,
        json_square(0.0, 0.0),
        json_square(1.0, 0.0)
    );
    let s = parse_json(&text, "t.json").unwrap();
    let r = repairs(&s);
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    assert!(
        r[0].starts_with("t.json: repaired plane equations")
            && r[0].contains("1 of 2 plane(s)")
            && r[0].contains("(the planes stated with an offset)"),
        "{}",
        r[0]
    );
    assert!(s.sections[1].plane.signed_distance([3.0, 3.0, 1.0]).abs() < 1e-12);
    assert!((s.sections[1].area() - 16.0).abs() < 1e-9);
    let e = json_error(&text, &STRICT);
    assert!(
        e.starts_with("t.json: $.planes[1].contours[0].points[0]") && e.contains("off its plane"),
        "{e}"
    );
    assert_reconstructs(&s, None);

    // Plane 1 stated as z = 1 through a point, its vertices on z = 1 + 0.01 x: their plane.
    let text = format!(
        r#"{{"planes": [{{"point": [0,0,0], "normal": [0,0,1], "contours": [{}]}},
            {{"point": [0,0,1], "normal": [0,0,1], "contours": [{}]}}]}}"#,
        json_square(0.0, 0.0),
        json_square(1.0, 1.0)
    );
    let s = parse_json(&text, "t.json").unwrap();
    let r = repairs(&s);
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    assert!(
        r[0].starts_with("t.json: $.planes[1]: repaired plane equation")
            && r[0].contains("normal turned by 0.573 degrees"),
        "{}",
        r[0]
    );
    assert!(s.sections[1].plane.signed_distance([4.0, 4.0, 1.04]).abs() < 1e-12);
    let area = 16.0 * (1.0f64 + 1e-4).sqrt();
    assert!((s.sections[1].area() - area).abs() < 1e-9);
    let e = json_error(&text, &STRICT);
    assert!(
        e.starts_with("t.json: $.planes[1].contours[0].points[1]") && e.contains("off its plane"),
        "{e}"
    );
    assert_reconstructs(&s, None);

    // A contour in the plane's own frame (points2d) pins the stated plane: no re-fit.
    let pinned = text.replacen(
        r#"{"point": [0,0,1], "normal": [0,0,1], "contours": ["#,
        r#"{"point": [0,0,1], "normal": [0,0,1], "contours": [{"points2d": [[-7,5],[-6,5],[-6,6]], "label": 2}, "#,
        1,
    );
    let e = json_error(&pinned, &ReadOptions::default());
    assert!(
        e.starts_with("t.json: $.planes[1].contours[1].points[1]") && e.contains("off its plane"),
        "{e}"
    );
}
