//! The cross-section model: validated planes with an orthonormal frame, and per plane its regions
//! (outer contour, holes, label) in both plane (u,v) coordinates and 3D.
//!
//! Conventions (every module relies on them):
//! * A plane is `{x : normal·x + offset = 0}` with `normal` of unit length; its frame is
//!   `origin` (the point of the plane closest to the world origin), `u`, `v` with `u × v = normal`,
//!   so a point (s,t) of the plane is `origin + s u + t v`.
//! * Outer contours are counter-clockwise in (u,v), i.e. seen from the tip of the normal; holes are
//!   clockwise. Contours are open polylines (the closing edge last→first is implicit), with no two
//!   consecutive equal vertices.
//! * In a plane, the contours of one label are disjoint (no two touch) and properly nested.
//!   Regions of different labels have disjoint interiors but may touch (organs in contact share
//!   part of their outline); `Sections::select_label` gives the view the engines take, with
//!   disjoint contours.
//! * `points2` are the authoritative coordinates (exact decisions inside a plane use them);
//!   `points3` are `origin + s u + t v` evaluated in floating point (not exactly coplanar).
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Plane {
    pub normal: [f64; 3],
    pub offset: f64,
    pub origin: [f64; 3],
    pub u: [f64; 3],
    pub v: [f64; 3],
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Contour {
    pub points2: Vec<[f64; 2]>,
    pub points3: Vec<[f64; 3]>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Region {
    /// Integer label of the material inside (CSL: 1 is inside; other labels mark other materials).
    pub label: i32,
    pub outer: Contour,
    pub holes: Vec<Contour>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Section {
    pub plane: Plane,
    pub regions: Vec<Region>,
    /// Index of this plane in the input file (CSL plane index, JSON array position).
    pub source_index: usize,
    /// Largest distance of an input vertex of this plane from the plane before snapping.
    pub max_off_plane: f64,
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Sections {
    pub sections: Vec<Section>,
    /// Number of labels the input declares (CSL header); at least the largest label used.
    pub n_labels: usize,
    /// Repairs made while reading (orientation fixed, duplicate vertices removed, ...), with locations.
    pub warnings: Vec<String>,
    /// Names of labels, where the input names them (an RT Structure Set's ROI names, by ROI number).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub label_names: BTreeMap<i32, String>,
}

impl Plane {
    /// Plane through `normal·x + offset = 0`; `normal` need not be unit. None if it is zero or not finite.
    pub fn from_equation(normal: [f64; 3], offset: f64) -> Option<Plane> {
        let len = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
        if !(len.is_finite() && len > 0.0 && offset.is_finite()) {
            return None;
        }
        let n = [normal[0] / len, normal[1] / len, normal[2] / len];
        let d = offset / len;
        // u: the world axis least aligned with n, orthogonalised; v = n × u, so u × v = n.
        let a = if n[0].abs() <= n[1].abs() && n[0].abs() <= n[2].abs() {
            [1.0, 0.0, 0.0]
        } else if n[1].abs() <= n[2].abs() {
            [0.0, 1.0, 0.0]
        } else {
            [0.0, 0.0, 1.0]
        };
        let u = normalize(cross(a, n));
        let v = cross(n, u);
        let origin = [-d * n[0], -d * n[1], -d * n[2]];
        Some(Plane {
            normal: n,
            offset: d,
            origin,
            u,
            v,
        })
    }

    /// Plane through `point` with `normal`.
    pub fn from_point_normal(point: [f64; 3], normal: [f64; 3]) -> Option<Plane> {
        let d = -(normal[0] * point[0] + normal[1] * point[1] + normal[2] * point[2]);
        Plane::from_equation(normal, d)
    }

    /// The plane's equation `[n, d]` (n · x + d = 0).
    pub fn equation(&self) -> [f64; 4] {
        [self.normal[0], self.normal[1], self.normal[2], self.offset]
    }

    pub fn signed_distance(&self, p: [f64; 3]) -> f64 {
        dot(self.normal, p) + self.offset
    }

    /// (u,v) coordinates of the orthogonal projection of `p`.
    pub fn to_2d(&self, p: [f64; 3]) -> [f64; 2] {
        let d = sub(p, self.origin);
        [dot(d, self.u), dot(d, self.v)]
    }

    pub fn to_3d(&self, q: [f64; 2]) -> [f64; 3] {
        [
            self.origin[0] + q[0] * self.u[0] + q[1] * self.v[0],
            self.origin[1] + q[0] * self.u[1] + q[1] * self.v[1],
            self.origin[2] + q[0] * self.u[2] + q[1] * self.v[2],
        ]
    }
}

impl Contour {
    pub fn from_2d(plane: &Plane, points2: Vec<[f64; 2]>) -> Contour {
        let points3 = points2.iter().map(|&q| plane.to_3d(q)).collect();
        Contour { points2, points3 }
    }
    /// Signed area in (u,v): positive for counter-clockwise.
    pub fn signed_area(&self) -> f64 {
        polygon_signed_area(&self.points2)
    }
}

/// Signed area of a closed polygon (shoelace formula): positive for counter-clockwise.
pub fn polygon_signed_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    let mut a = 0.0;
    for i in 0..n {
        let (x0, y0) = (p[i][0], p[i][1]);
        let (x1, y1) = (p[(i + 1) % n][0], p[(i + 1) % n][1]);
        a += x0 * y1 - x1 * y0;
    }
    0.5 * a
}

impl Region {
    pub fn area(&self) -> f64 {
        self.outer.signed_area().abs()
            - self
                .holes
                .iter()
                .map(|h| h.signed_area().abs())
                .sum::<f64>()
    }
}

impl Section {
    pub fn area(&self) -> f64 {
        self.regions.iter().map(Region::area).sum()
    }
}

impl Sections {
    pub fn vertex_count(&self) -> usize {
        self.sections
            .iter()
            .flat_map(|s| &s.regions)
            .map(|r| r.outer.points2.len() + r.holes.iter().map(|h| h.points2.len()).sum::<usize>())
            .sum()
    }

    /// Axis-aligned bounding box of all contour vertices, `None` when there are none.
    pub fn bounding_box(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut it = self.sections.iter().flat_map(|s| &s.regions).flat_map(|r| {
            r.outer
                .points3
                .iter()
                .chain(r.holes.iter().flat_map(|h| &h.points3))
        });
        let first = *it.next()?;
        let (mut lo, mut hi) = (first, first);
        for p in it {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        Some((lo, hi))
    }

    /// Number of regions per label, by label.
    pub fn regions_per_label(&self) -> BTreeMap<i32, usize> {
        let mut labels = BTreeMap::new();
        for r in self.sections.iter().flat_map(|x| &x.regions) {
            *labels.entry(r.label).or_default() += 1;
        }
        labels
    }

    /// What `--label` selects: the regions of one label (`Some(l)`), or all labels as one material
    /// (`None`): every region, and where regions of different labels touch (which validated input
    /// allows, see `validate`), the union of the plane's material instead
    /// ([`crate::validate::one_material`]). The result has disjoint contours in every plane.
    pub fn select_label(&self, label: Option<i32>) -> crate::error::Result<Sections> {
        let Some(l) = label else {
            return crate::validate::one_material(self);
        };
        let mut out = self.clone();
        for s in &mut out.sections {
            s.regions.retain(|r| r.label == l);
        }
        Ok(out)
    }
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_right_handed_and_orthonormal() {
        for n in [[0.0, 0.0, 1.0], [1.0, 2.0, -3.0], [-0.245, 0.826, -0.507]] {
            let p = Plane::from_equation(n, 2.5).unwrap();
            assert!((dot(p.u, p.u) - 1.0).abs() < 1e-15);
            assert!(dot(p.u, p.v).abs() < 1e-15);
            let c = cross(p.u, p.v);
            for (ck, nk) in c.iter().zip(p.normal) {
                assert!((ck - nk).abs() < 1e-15);
            }
            assert!(p.signed_distance(p.origin).abs() < 1e-14);
            let q = p.to_3d([0.3, -0.7]);
            let back = p.to_2d(q);
            assert!((back[0] - 0.3).abs() < 1e-14 && (back[1] + 0.7).abs() < 1e-14);
        }
        assert!(Plane::from_equation([0.0, 0.0, 0.0], 1.0).is_none());
        assert!(Plane::from_equation([f64::NAN, 0.0, 1.0], 1.0).is_none());
    }
}
