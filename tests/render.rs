//! `slice2solid render`: a PNG of the requested size with the object and, given sections, its
//! contours; contours behind the surface hidden; bad sizes and views refused.
mod common;
use common::bin;
use slice2solid::io::json::parse_json;
use slice2solid::render::{render, Size, View, BACKGROUND};
use slice2solid::TriMesh;

const EIGHT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/eight_15.csl");

/// Pixels that are the contour colour of label 1 (orange), not the blue-grey surface.
fn contour_pixels(rgb: &[u8]) -> usize {
    rgb.chunks(3)
        .filter(|p| p[0] > 180 && p[0] as i32 - p[2] as i32 > 100)
        .count()
}

fn object_pixels(rgb: &[u8]) -> usize {
    rgb.chunks(3).filter(|p| *p != BACKGROUND).count()
}

/// (width, height, RGB) of a PNG file.
fn decode(path: &std::path::Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

#[test]
fn cli_draws_the_shipped_example_with_its_contours() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("eight.obj");
    let o = bin()
        .args(["reconstruct", EIGHT, "-q", "-o"])
        .arg(&obj)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (with, without) = (dir.path().join("with.png"), dir.path().join("without.png"));
    for (png, sections) in [(&with, Some(EIGHT)), (&without, None)] {
        let mut cmd = bin();
        cmd.arg("render").arg(&obj).arg("-o").arg(png);
        cmd.args(["--size", "320x240", "--view", "30,20"]);
        if let Some(s) = sections {
            cmd.args(["--sections", s]);
        }
        let o = cmd.output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let (w, h, rgb) = decode(&with);
    assert_eq!((w, h), (320, 240));
    // The figure eight is tall and thin: framed to 90% of the height, it covers about a fifth.
    let covered = object_pixels(&rgb) as f64 / (w * h) as f64;
    assert!(covered > 0.1 && covered < 0.4, "{covered}");
    // 15 contours, about half of each in front: a few thousand pixels.
    let lines = contour_pixels(&rgb);
    assert!(lines > 1000, "{lines}");
    let (_, _, plain) = decode(&without);
    assert_eq!(contour_pixels(&plain), 0);
    // Lines on the silhouette reach a pixel beyond it.
    let (bare, drawn) = (object_pixels(&plain), object_pixels(&rgb));
    assert!(bare < drawn && drawn < bare + bare / 20, "{bare} {drawn}");
}

/// The cube [-1,1]^3, outward triangles.
fn cube() -> TriMesh {
    let v: Vec<[f64; 3]> = (0..8)
        .map(|k| [0, 1, 2].map(|a| if k >> a & 1 == 1 { 1.0 } else { -1.0 }))
        .collect();
    let quads = [
        [0, 2, 3, 1], // z = -1
        [4, 5, 7, 6], // z = +1
        [0, 1, 5, 4], // y = -1
        [2, 6, 7, 3], // y = +1
        [0, 4, 6, 2], // x = -1
        [1, 3, 7, 5], // x = +1
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    TriMesh {
        vertices: v,
        triangles,
    }
}

#[test]
fn contours_behind_the_surface_are_hidden() {
    // A square on the face x = -1.
    let sections = parse_json(
        r#"{"planes": [{"point": [-1, 0, 0], "normal": [1, 0, 0], "contours": [
            {"points": [[-1, -0.5, -0.5], [-1, 0.5, -0.5], [-1, 0.5, 0.5], [-1, -0.5, 0.5]]}]}]}"#,
        "face.json",
    )
    .unwrap();
    let size = Size {
        width: 120,
        height: 100,
    };
    let seen_from = |azimuth: f64| {
        let view = View {
            azimuth,
            elevation: 10.0,
        };
        render(&cube(), Some(&sections), size, view).unwrap()
    };
    let front = seen_from(180.0); // from -x: the face with the square faces the camera
    let back = seen_from(0.0); // from +x: the cube hides it
    assert_eq!((front.width, front.height), (120, 100));
    assert!(
        contour_pixels(&front.rgb) > 100,
        "{}",
        contour_pixels(&front.rgb)
    );
    assert_eq!(contour_pixels(&back.rgb), 0);
}

#[test]
fn bad_size_view_or_mesh_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let mesh = dir.path().join("cube.obj");
    slice2solid::io::mesh::write_trimesh(&mesh, &cube()).unwrap();
    for (args, expect) in [
        (vec!["--size", "800"], "expected WxH"),
        (
            vec!["--size", "0x600"],
            "not an image side of 1 to 8192 pixels",
        ),
        (vec!["--size", "20000x10"], "not an image side"),
        (vec!["--view", "30"], "expected AZ,EL"),
        (vec!["--view", "30,95"], "outside [-90, 90]"),
        (vec!["--view", "x,10"], "not a finite number"),
    ] {
        let o = bin()
            .arg("render")
            .arg(&mesh)
            .arg("-o")
            .arg(&out)
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains(expect),
            "{args:?}: {err}"
        );
        assert!(!out.exists());
    }
    // A negative azimuth or elevation is a value, not an option.
    let o = bin()
        .arg("render")
        .arg(&mesh)
        .arg("-o")
        .arg(&out)
        .args(["--view", "-45,-30"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = bin()
        .args(["render", "missing.obj", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("missing.obj"));
}
