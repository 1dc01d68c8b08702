//! A picture of a surface, with the input contours drawn over it: a small software rasterizer
//! (no GPU, no window) and a PNG writer.
//!
//! Orthographic camera looking at the centre of the mesh's bounding box from azimuth `az` (degrees
//! about +z, from +x) and elevation `el` (degrees above the xy plane), +z up on the image; the
//! projected mesh is framed to fill 90% of the smaller image side. Triangles are shaded by Lambert's
//! law (two-sided, so an open mesh's inside shows too) with a light from over the viewer's
//! shoulder, and hidden by a z-buffer. Contours are polylines drawn over the surface, depth-tested
//! against it with a bias of `CONTOUR_DEPTH_BIAS` × the model's size, so contours lying on the
//! surface show and those behind it do not. The image is rendered at `SUPERSAMPLE`× the size in
//! each direction and box-filtered down (antialiasing).
use crate::error::{Error, Result};
use crate::mesh::TriMesh;
use crate::sections::{cross, dot, normalize, sub, Sections};
use std::path::Path;

/// Contours within this fraction of the model's bounding-box diagonal behind the surface still show.
pub const CONTOUR_DEPTH_BIAS: f64 = 5e-3;

/// Each image pixel is the mean of SUPERSAMPLE × SUPERSAMPLE rendered samples.
pub const SUPERSAMPLE: usize = 2;

/// The largest accepted image side, in pixels.
pub const MAX_SIDE: u32 = 8192;

pub const BACKGROUND: [u8; 3] = [255, 255, 255];
const SURFACE: [f64; 3] = [0.62, 0.70, 0.82];
/// Contour colours, by label (cycled).
const CONTOUR_COLOURS: [[f64; 3]; 4] = [
    [0.85, 0.10, 0.10],
    [0.95, 0.55, 0.00],
    [0.10, 0.55, 0.15],
    [0.55, 0.10, 0.70],
];

/// Where the camera looks from, in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub azimuth: f64,
    pub elevation: f64,
}

impl Default for View {
    fn default() -> View {
        View {
            azimuth: 30.0,
            elevation: 20.0,
        }
    }
}

impl std::str::FromStr for View {
    type Err = String;
    /// `AZ,EL` in degrees, elevation in [-90, 90].
    fn from_str(s: &str) -> std::result::Result<View, String> {
        let (a, e) = s
            .split_once(',')
            .ok_or_else(|| format!("expected AZ,EL in degrees (e.g. 30,20), found {s:?}"))?;
        let num = |t: &str| {
            t.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{t:?} is not a finite number of degrees"))
        };
        let (azimuth, elevation) = (num(a)?, num(e)?);
        if !(-90.0..=90.0).contains(&elevation) {
            return Err(format!("elevation {elevation} is outside [-90, 90]"));
        }
        Ok(View { azimuth, elevation })
    }
}

/// Image size in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    pub width: u32,
    pub height: u32,
}

impl Default for Size {
    fn default() -> Size {
        Size {
            width: 800,
            height: 600,
        }
    }
}

impl std::str::FromStr for Size {
    type Err = String;
    /// `WxH`, each side 1..=`MAX_SIDE`.
    fn from_str(s: &str) -> std::result::Result<Size, String> {
        let (w, h) = s
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("expected WxH in pixels (e.g. 800x600), found {s:?}"))?;
        let side = |t: &str| {
            t.trim()
                .parse::<u32>()
                .ok()
                .filter(|&n| (1..=MAX_SIDE).contains(&n))
                .ok_or_else(|| format!("{t:?} is not an image side of 1 to {MAX_SIDE} pixels"))
        };
        Ok(Size {
            width: side(w)?,
            height: side(h)?,
        })
    }
}

/// An 8-bit RGB image, rows top to bottom.
#[derive(Clone, Debug)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

impl Image {
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y as usize * self.width as usize + x as usize);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }

    /// Write as PNG.
    pub fn write_png(&self, path: &Path) -> Result<()> {
        let io = |e: std::io::Error| Error::io(path, e);
        let png = |e: png::EncodingError| Error::io(path, std::io::Error::other(e.to_string()));
        let file = std::fs::File::create(path).map_err(io)?;
        let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(png)?;
        writer.write_image_data(&self.rgb).map_err(png)?;
        writer.finish().map_err(png)
    }
}

/// The orthographic camera: a world point to (sample x, sample y, depth; larger is farther).
struct Camera {
    right: [f64; 3],
    up: [f64; 3],
    forward: [f64; 3],
    /// Projected centre of the framing, and samples per model unit.
    centre: [f64; 2],
    scale: f64,
    half: [f64; 2],
}

impl Camera {
    fn new(view: View, mesh: &TriMesh, samples: [usize; 2]) -> Camera {
        let (az, el) = (view.azimuth.to_radians(), view.elevation.to_radians());
        let eye = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
        let forward = eye.map(|x| -x);
        // Looking straight up or down, the image's up is the view's azimuth direction instead of +z.
        let world_up = if el.cos() < 1e-9 {
            [-az.cos() * el.sin(), -az.sin() * el.sin(), 0.0]
        } else {
            [0.0, 0.0, 1.0]
        };
        let right = normalize(cross(forward, world_up));
        let up = cross(right, forward);
        let mut cam = Camera {
            right,
            up,
            forward,
            centre: [0.0; 2],
            scale: 1.0,
            half: [samples[0] as f64 / 2.0, samples[1] as f64 / 2.0],
        };
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &p in &mesh.vertices {
            let q = [dot(p, right), dot(p, up)];
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        cam.centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
        let extent = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
        cam.scale = 0.9 * (samples[0] as f64 / extent[0]).min(samples[1] as f64 / extent[1]);
        cam
    }

    fn project(&self, p: [f64; 3]) -> [f64; 3] {
        [
            self.half[0] + (dot(p, self.right) - self.centre[0]) * self.scale,
            self.half[1] - (dot(p, self.up) - self.centre[1]) * self.scale,
            dot(p, self.forward),
        ]
    }
}

/// Samples being rendered: colour and depth per sample.
struct Canvas {
    width: usize,
    height: usize,
    colour: Vec<[f64; 3]>,
    depth: Vec<f64>,
}

/// Render `mesh`, with the contours of `sections` over it, as a `size` picture seen from `view`.
pub fn render(
    mesh: &TriMesh,
    sections: Option<&Sections>,
    size: Size,
    view: View,
) -> Result<Image> {
    check_mesh(mesh)?;
    let samples = [
        size.width as usize * SUPERSAMPLE,
        size.height as usize * SUPERSAMPLE,
    ];
    let camera = Camera::new(view, mesh, samples);
    let mut canvas = Canvas {
        width: samples[0],
        height: samples[1],
        colour: vec![BACKGROUND.map(|c| c as f64 / 255.0); samples[0] * samples[1]],
        depth: vec![f64::INFINITY; samples[0] * samples[1]],
    };
    draw_surface(&mut canvas, mesh, &camera);
    if let Some(sections) = sections {
        let diagonal = bounding_diagonal(mesh);
        draw_contours(
            &mut canvas,
            sections,
            &camera,
            CONTOUR_DEPTH_BIAS * diagonal,
        );
    }
    Ok(downsample(&canvas, size))
}

/// A mesh with something to draw: triangles, valid indices, finite coordinates, some extent.
fn check_mesh(mesh: &TriMesh) -> Result<()> {
    let n = mesh.vertices.len();
    if mesh.triangles.is_empty() {
        return Err(Error::input("render", "the mesh has no triangles"));
    }
    if let Some(t) = mesh
        .triangles
        .iter()
        .position(|t| t.iter().any(|&i| i as usize >= n))
    {
        return Err(Error::input(
            "render",
            format!("triangle {t} has a vertex index out of range ({n} vertices)"),
        ));
    }
    if mesh.vertices.iter().flatten().any(|x| !x.is_finite()) {
        return Err(Error::input(
            "render",
            "the mesh has a coordinate that is not finite",
        ));
    }
    if bounding_diagonal(mesh) <= 0.0 {
        return Err(Error::input(
            "render",
            "the mesh has no extent (all vertices coincide)",
        ));
    }
    Ok(())
}

fn bounding_diagonal(mesh: &TriMesh) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &mesh.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    dot(sub(hi, lo), sub(hi, lo)).sqrt()
}

/// Lambert-shaded triangles into the z-buffer.
fn draw_surface(canvas: &mut Canvas, mesh: &TriMesh, camera: &Camera) {
    // Light from over the viewer's left shoulder.
    let light = normalize(
        [0, 1, 2].map(|k| -camera.forward[k] + 0.6 * camera.up[k] - 0.4 * camera.right[k]),
    );
    let projected: Vec<[f64; 3]> = mesh.vertices.iter().map(|&p| camera.project(p)).collect();
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
        let n = cross(sub(b, a), sub(c, a));
        let len = dot(n, n).sqrt();
        if len == 0.0 {
            continue; // degenerate: covers no pixel
        }
        let lambert = (dot(n, light) / len).abs();
        let shade = 0.25 + 0.75 * lambert;
        let colour = SURFACE.map(|c| c * shade);
        fill_triangle(canvas, t.map(|i| projected[i as usize]), colour);
    }
}

/// Rasterize one projected triangle (edge functions over its bounding box, sample centres).
fn fill_triangle(canvas: &mut Canvas, [a, b, c]: [[f64; 3]; 3], colour: [f64; 3]) {
    let area = edge(a, b, c);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    let x0 = a[0].min(b[0]).min(c[0]).floor().max(0.0) as usize;
    let y0 = a[1].min(b[1]).min(c[1]).floor().max(0.0) as usize;
    let x1 = (a[0].max(b[0]).max(c[0]).ceil().max(0.0) as usize).min(canvas.width);
    let y1 = (a[1].max(b[1]).max(c[1]).ceil().max(0.0) as usize).min(canvas.height);
    for y in y0..y1 {
        for x in x0..x1 {
            let p = [x as f64 + 0.5, y as f64 + 0.5, 0.0];
            let (wa, wb, wc) = (
                edge(b, c, p) / area,
                edge(c, a, p) / area,
                edge(a, b, p) / area,
            );
            if wa < 0.0 || wb < 0.0 || wc < 0.0 {
                continue;
            }
            let depth = wa * a[2] + wb * b[2] + wc * c[2];
            let i = y * canvas.width + x;
            if depth < canvas.depth[i] {
                canvas.depth[i] = depth;
                canvas.colour[i] = colour;
            }
        }
    }
}

/// Twice the signed area of (a, b, p) in the image plane.
fn edge(a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// Every contour as a closed polyline, where it is not behind the surface by more than `bias`.
fn draw_contours(canvas: &mut Canvas, sections: &Sections, camera: &Camera, bias: f64) {
    // Lines about 1.5 image pixels wide.
    let radius = (SUPERSAMPLE as f64 * 0.75).max(1.0);
    for region in sections.sections.iter().flat_map(|s| &s.regions) {
        let colour = CONTOUR_COLOURS[region.label.unsigned_abs() as usize % CONTOUR_COLOURS.len()];
        for contour in std::iter::once(&region.outer).chain(&region.holes) {
            let n = contour.points3.len();
            for i in 0..n {
                let a = camera.project(contour.points3[i]);
                let b = camera.project(contour.points3[(i + 1) % n]);
                draw_segment(canvas, a, b, radius, bias, colour);
            }
        }
    }
}

/// A thick depth-tested segment: discs of `radius` samples stepped along it.
fn draw_segment(
    canvas: &mut Canvas,
    a: [f64; 3],
    b: [f64; 3],
    radius: f64,
    bias: f64,
    colour: [f64; 3],
) {
    let length = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
    if !length.is_finite() {
        return;
    }
    let steps = (length * 2.0).ceil().max(1.0) as usize;
    let r = radius.ceil() as isize;
    for s in 0..=steps {
        let t = s as f64 / steps as f64;
        let p = [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
        for dy in -r..=r {
            for dx in -r..=r {
                if ((dx * dx + dy * dy) as f64) > radius * radius {
                    continue;
                }
                let (x, y) = (p[0].floor() as isize + dx, p[1].floor() as isize + dy);
                if x < 0 || y < 0 || x as usize >= canvas.width || y as usize >= canvas.height {
                    continue;
                }
                let i = y as usize * canvas.width + x as usize;
                // Not written to the z-buffer: a contour hides nothing.
                if p[2] <= canvas.depth[i] + bias {
                    canvas.colour[i] = colour;
                }
            }
        }
    }
}

/// Box filter SUPERSAMPLE × SUPERSAMPLE samples into each pixel.
fn downsample(canvas: &Canvas, size: Size) -> Image {
    let (w, h) = (size.width as usize, size.height as usize);
    let mut rgb = Vec::with_capacity(3 * w * h);
    let n = (SUPERSAMPLE * SUPERSAMPLE) as f64;
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0.0; 3];
            for sy in 0..SUPERSAMPLE {
                for sx in 0..SUPERSAMPLE {
                    let c =
                        canvas.colour[(y * SUPERSAMPLE + sy) * canvas.width + x * SUPERSAMPLE + sx];
                    for k in 0..3 {
                        sum[k] += c[k];
                    }
                }
            }
            rgb.extend(sum.map(|s| (s / n * 255.0).round().clamp(0.0, 255.0) as u8));
        }
    }
    Image {
        width: size.width,
        height: size.height,
        rgb,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn view_and_size_parse_or_say_why_not() {
        assert_eq!(
            "30,20".parse::<View>(),
            Ok(View {
                azimuth: 30.0,
                elevation: 20.0
            })
        );
        assert!("30".parse::<View>().unwrap_err().contains("AZ,EL"));
        assert!("30,91"
            .parse::<View>()
            .unwrap_err()
            .contains("outside [-90, 90]"));
        assert!("a,1"
            .parse::<View>()
            .unwrap_err()
            .contains("not a finite number"));
        assert_eq!(
            "640x480".parse::<Size>(),
            Ok(Size {
                width: 640,
                height: 480
            })
        );
        assert!("640".parse::<Size>().unwrap_err().contains("WxH"));
        assert!("0x10".parse::<Size>().unwrap_err().contains("1 to 8192"));
        assert!("10x99999"
            .parse::<Size>()
            .unwrap_err()
            .contains("1 to 8192"));
    }

    #[test]
    fn looking_straight_down_still_has_a_frame() {
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            triangles: vec![[0, 1, 2]],
        };
        for elevation in [90.0, -90.0] {
            let view = View {
                azimuth: 0.0,
                elevation,
            };
            let image = render(
                &mesh,
                None,
                Size {
                    width: 40,
                    height: 30,
                },
                view,
            )
            .unwrap();
            let covered = image.rgb.chunks(3).filter(|p| p != &BACKGROUND).count();
            // The triangle is half of its bounding square, framed to 90% of the height.
            assert!(covered > 200 && covered < 600, "{covered}");
        }
        let empty = TriMesh::default();
        assert!(render(&empty, None, Size::default(), View::default()).is_err());
    }
}
