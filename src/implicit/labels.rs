//! Every label at once with the implicit method (Bermano, Vaxman & Gotsman 2011, §6): one
//! indicator per label, the exterior one more label, and each point of space takes the label
//! whose indicator is largest. The result is a partition of space into labelled domains.
//!
//! * **Indicators.** Label ℓ's indicator is the mean-value interpolant of its own sections (+1 in
//!   its regions, −1 elsewhere on every plane); the exterior's is the negated indicator of all
//!   labels as one material (the interpolant of the complement's sections, by linearity). On a
//!   plane every label's value is ±1, so a grid node on a plane takes the label of the section it
//!   lies in.
//! * **Extraction, a partition by construction.** Every finest cube is split into the six
//!   Freudenthal tetrahedra (as for one label), each node takes its label, and every tetrahedron
//!   whose nodes do not all agree is cut along its barycentric subdivision: the part of it nearest
//!   a node (the small tetrahedra `node, edge point, face point, centre`) belongs to that node's
//!   label, and the interface is made of the triangles `(edge point, face point, centre)` between
//!   the parts of two nodes of different labels. An edge point is where the two labels' indicators
//!   are equal (linear along the edge), a face point the mean of its face's edge points, a centre the
//!   mean of its tetrahedron's edge points; edge and face points are shared by key with the
//!   neighbouring tetrahedra. So every interface triangle is one triangle of both labels' surfaces
//!   with opposite orientations (no gap and no overlap between domains), and each label's surface
//!   is the frontier of a regular neighbourhood of the nodes it holds: closed and 2-manifold.
//!   Where three labels meet in a tetrahedron, the edges `(face point, centre)` are triple lines.
//! * **Islands.** A group of nodes of one label enclosed by nodes of other labels, at none of which
//!   that label's own indicator is positive, is an artefact of the argmax where several labels meet
//!   (no section of the label is near): its nodes take the best other label before extraction.
//! * **Which cubes.** The interfaces are found by flooding from the finest cubes that hold a
//!   contour vertex of any label and the cubes where the one-material indicator changes sign (its
//!   octree, as for one label), through cube faces whose corners do not all agree. An interface
//!   that touches no plane and no one-material surface cube is not found (as for one label).
use super::extract::TETS;
use super::octree::{corner, Field, Grid, IntMap, IntSet, Refinement, CUBE_FACES};
use super::{contour_points, indicator::Indicator};
use crate::arrangement::{Arrangement, CellScope};
use crate::error::{Error, Result};
use crate::mesh::TriMesh;
use crate::sections::Sections;
use crate::solid::{Options, Report};
use rayon::prelude::*;
use std::collections::HashMap;

pub use crate::solid::{Partition, EXTERIOR};

/// The labels of `sections` (increasing); an error unless there are some, all positive.
pub(crate) fn labels_of(sections: &Sections) -> Result<Vec<i32>> {
    let labels: Vec<i32> = sections.regions_per_label().into_keys().collect();
    if labels.is_empty() {
        return Err(Error::input("--all-labels", "the input has no regions"));
    }
    if let Some(l) = labels.iter().find(|&&l| l <= EXTERIOR) {
        return Err(Error::input(
            "--all-labels",
            format!("label {l}: labels must be positive (0 is the exterior)"),
        ));
    }
    Ok(labels)
}

/// The indicator of one selection of the sections (`None`: all labels as one material), over the
/// arrangement of all cells; also its arrangement's box.
pub(crate) fn indicator_of(
    sections: &Sections,
    label: Option<i32>,
    options: &Options,
    report: &mut Report,
) -> Result<(Indicator, Arrangement)> {
    let selected = sections.select_label(label)?;
    let (selected, trims) = crate::validate::reconcile_common_lines(
        selected,
        options.arrangement.snap_tolerance,
        options.arrangement.line_strip,
    )?;
    report.warnings.extend(trims.warnings);
    let mut arrangement_options = options.arrangement.clone();
    arrangement_options.scope = CellScope::All;
    let arrangement = Arrangement::build(&selected, &arrangement_options)?;
    report.warnings.extend(arrangement.warnings.iter().cloned());
    Ok((Indicator::new(&arrangement)?, arrangement))
}

/// Reconstruct every label of `sections` at once (module docs).
pub fn reconstruct_partition(sections: &Sections, options: &Options) -> Result<Partition> {
    let start = std::time::Instant::now();
    let labels = labels_of(sections)?;
    let mut report = Report {
        method: "implicit".into(),
        ..Default::default()
    };
    report.warnings.extend(sections.warnings.iter().cloned());
    // the indicators: all labels as one material (the exterior's, negated), then each label
    let mut warnings = Report::default();
    let (union, union_arr) = report.time("arrangement", || {
        indicator_of(sections, None, options, &mut warnings)
    })?;
    let mut indicators = Vec::with_capacity(labels.len());
    for &l in &labels {
        let (ind, _) = report.time("arrangement", || {
            indicator_of(sections, Some(l), options, &mut warnings)
        })?;
        indicators.push(ind);
    }
    report.warnings.extend(warnings.warnings);
    let grid = Grid::new(union_arr.bbox.0, union_arr.bbox.1, options.depth);
    let mut seeds: Vec<[u32; 3]> = Vec::new();
    for ind in std::iter::once(&union).chain(&indicators) {
        seeds.extend(contour_points(ind).iter().map(|&p| grid.cube_of(p)));
    }
    let field = report.time("octree", || {
        Field::build(
            &union,
            grid.clone(),
            &contour_points(&union),
            Refinement::default(),
            &|_: &str, _: u64| {},
        )
    });
    seeds.extend(field.surface_cubes.iter().copied());
    let values = Values {
        grid: &grid,
        union: &union,
        labels: &indicators,
    };
    let (mut nodes, cubes) = report.time("flood", || flood(&values, seeds));
    let islands = report.time("islands", || relabel_islands(&grid, &mut nodes));
    report.count("implicit_islands_relabelled", islands);
    report.count("implicit_depth", grid.depth as u64);
    report.count("implicit_label_nodes", nodes.len() as u64);
    report.count("implicit_interface_cubes", cubes.len() as u64);
    let mut partition = report.time("extract", || extract(&grid, &nodes, &cubes, &labels));
    report.count(
        "interface_triangles",
        partition.interfaces.triangles.len() as u64,
    );
    report.total_seconds = start.elapsed().as_secs_f64();
    report.peak_memory = crate::memory::peak_resident();
    partition.labels = labels;
    partition.report = report;
    Ok(partition)
}

/// Every indicator at a grid node; index 0 is the exterior.
struct Values<'a> {
    grid: &'a Grid,
    union: &'a Indicator,
    labels: &'a [Indicator],
}

/// A node's indicator values (index 0 the exterior, then the labels in order) and the index of
/// the largest (the first of equal ones).
#[derive(Clone, Debug)]
struct Node {
    values: Vec<f64>,
    label: usize,
}

impl Values<'_> {
    fn node(&self, i: [u32; 3]) -> Node {
        let on_box = (0..3).any(|k| i[k] == 0 || i[k] >= self.grid.cubes[k]);
        let x = self.grid.node_position(i);
        let mut values = Vec::with_capacity(self.labels.len() + 1);
        values.push(-self.union.eval(x));
        values.extend(self.labels.iter().map(|ind| ind.eval(x)));
        // the box's boundary is exterior, so every domain is closed inside the grid
        let label = if on_box {
            0
        } else {
            let mut best = 0;
            for (k, &v) in values.iter().enumerate() {
                if v > values[best] {
                    best = k;
                }
            }
            best
        };
        Node { values, label }
    }
}

/// From `seeds`, every finest cube whose corners do not all take one label, reached through cube
/// faces whose corners do not all agree; the nodes evaluated on the way.
fn flood(values: &Values, seeds: Vec<[u32; 3]>) -> (IntMap<u64, Node>, Vec<[u32; 3]>) {
    let mut nodes: IntMap<u64, Node> = IntMap::default();
    let mut visited: IntSet<u64> = IntSet::default();
    let mut frontier: Vec<[u32; 3]> = seeds
        .into_iter()
        .filter(|&c| visited.insert(Grid::key(c)))
        .collect();
    let mut interface = Vec::new();
    while !frontier.is_empty() {
        let mut missing: Vec<u64> = frontier
            .iter()
            .flat_map(|&c| (0..8).map(move |k| Grid::key(corner(c, 1, k))))
            .filter(|k| !nodes.contains_key(k))
            .collect();
        missing.sort_unstable();
        missing.dedup();
        let evaluated: Vec<Node> = missing
            .par_iter()
            .with_min_len(64)
            .map(|&k| values.node(Grid::unkey(k)))
            .collect();
        nodes.extend(missing.into_iter().zip(evaluated));
        let mut next = Vec::new();
        for &c in &frontier {
            let label = |k: usize| nodes[&Grid::key(corner(c, 1, k))].label;
            if (1..8).all(|k| label(k) == label(0)) {
                continue;
            }
            interface.push(c);
            for &(axis, side, face) in &CUBE_FACES {
                if face.iter().all(|&k| label(k) == label(face[0])) {
                    continue;
                }
                if let Some(n) = values.grid.face_neighbour(c, axis, side) {
                    if visited.insert(Grid::key(n)) {
                        next.push(n);
                    }
                }
            }
        }
        frontier = next;
    }
    interface.sort_unstable();
    (nodes, interface)
}

/// The neighbours of a node along the edges of the Freudenthal tetrahedra (the axes, the face
/// diagonals (1,1,0), (1,0,1), (0,1,1) and the main diagonal, both ways).
const NEIGHBOURS: [[i64; 3]; 14] = [
    [1, 0, 0],
    [-1, 0, 0],
    [0, 1, 0],
    [0, -1, 0],
    [0, 0, 1],
    [0, 0, -1],
    [1, 1, 0],
    [-1, -1, 0],
    [1, 0, 1],
    [-1, 0, -1],
    [0, 1, 1],
    [0, -1, -1],
    [1, 1, 1],
    [-1, -1, -1],
];

/// Islands: connected groups of nodes of one label (through Freudenthal edges) whose every
/// neighbour has been evaluated (so the group is enclosed by other labels, not the band around a
/// larger domain) and at none of whose nodes the label's own indicator is positive: no section of
/// the label is near (argmax leaves them where several labels meet, every indicator negative). Each takes, node by node, the
/// best of the other labels. Returns how many groups were relabelled.
fn relabel_islands(grid: &Grid, nodes: &mut IntMap<u64, Node>) -> u64 {
    let step = |k: u64, d: [i64; 3]| -> Option<u64> {
        let i = Grid::unkey(k);
        let mut j = [0u32; 3];
        for a in 0..3 {
            let x = i[a] as i64 + d[a];
            if x < 0 || x > grid.cubes[a] as i64 {
                return None;
            }
            j[a] = x as u32;
        }
        Some(Grid::key(j))
    };
    let mut keys: Vec<u64> = nodes.keys().copied().collect();
    keys.sort_unstable();
    let mut seen: IntSet<u64> = IntSet::default();
    let mut islands = 0;
    for &start in &keys {
        if !seen.insert(start) {
            continue;
        }
        let label = nodes[&start].label;
        let mut group = vec![start];
        let (mut enclosed, mut witness) = (true, false);
        let mut at = 0;
        while at < group.len() {
            let k = group[at];
            at += 1;
            witness |= nodes[&k].values[label] > 0.0;
            for d in NEIGHBOURS {
                match step(k, d).and_then(|n| nodes.get(&n).map(|x| (n, x.label))) {
                    None => enclosed = false,
                    Some((n, l)) if l == label && seen.insert(n) => group.push(n),
                    _ => {}
                }
            }
        }
        if !enclosed || witness {
            continue;
        }
        islands += 1;
        for k in group {
            let node = nodes.get_mut(&k).expect("evaluated");
            let mut best = usize::from(label == 0);
            for (i, &v) in node.values.iter().enumerate() {
                if i != label && v > node.values[best] {
                    best = i;
                }
            }
            node.label = best;
        }
    }
    islands
}

/// The sign of the permutation `p` of 0..4.
fn parity(p: [usize; 4]) -> i32 {
    let mut s = 1;
    for i in 0..4 {
        for j in i + 1..4 {
            if p[i] > p[j] {
                s = -s;
            }
        }
    }
    s
}

/// The orientation of a Freudenthal tetrahedron (its corners' offsets in the unit cube).
fn tet_orientation(t: [usize; 4]) -> i32 {
    let off = |c: usize| [(c & 1) as i32, (c >> 1 & 1) as i32, (c >> 2 & 1) as i32];
    let (o, a, b, c) = (off(t[0]), off(t[1]), off(t[2]), off(t[3]));
    let d = |p: [i32; 3]| [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
    let (a, b, c) = (d(a), d(b), d(c));
    let det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0]);
    det.signum()
}

/// The interface's vertices: edge and face points shared by key.
struct Points<'a> {
    grid: &'a Grid,
    nodes: &'a IntMap<u64, Node>,
    positions: Vec<[f64; 3]>,
    edge: HashMap<(u64, u64), u32>,
    face: HashMap<[u64; 3], u32>,
    /// Per vertex, whether it is an edge point (not a face point or a centre).
    on_edge: Vec<bool>,
}

impl Points<'_> {
    /// Where the indicators of the labels of nodes `a` and `b` are equal, linear along the edge.
    fn edge_position(&self, a: u64, b: u64) -> [f64; 3] {
        let (na, nb) = (&self.nodes[&a], &self.nodes[&b]);
        let (la, lb) = (na.label, nb.label);
        let da = na.values[la] - na.values[lb];
        let db = nb.values[la] - nb.values[lb];
        let t = (da / (da - db)).clamp(1e-3, 1.0 - 1e-3);
        let t = if t.is_finite() { t } else { 0.5 };
        let pa = self.grid.node_position(Grid::unkey(a));
        let pb = self.grid.node_position(Grid::unkey(b));
        [0, 1, 2].map(|k| pa[k] + t * (pb[k] - pa[k]))
    }

    fn edge_point(&mut self, a: u64, b: u64) -> u32 {
        let key = (a.min(b), a.max(b));
        if let Some(&v) = self.edge.get(&key) {
            return v;
        }
        let p = self.edge_position(key.0, key.1);
        let v = self.positions.len() as u32;
        self.positions.push(p);
        self.on_edge.resize(self.positions.len(), false);
        self.on_edge[v as usize] = true;
        self.edge.insert(key, v);
        v
    }

    /// The mean of the edge points of the face `f` (its edges between different labels).
    fn face_point(&mut self, mut f: [u64; 3]) -> u32 {
        f.sort_unstable();
        if let Some(&v) = self.face.get(&f) {
            return v;
        }
        let ids: Vec<u32> = [(0, 1), (0, 2), (1, 2)]
            .iter()
            .filter(|&&(i, j)| self.nodes[&f[i]].label != self.nodes[&f[j]].label)
            .map(|&(i, j)| self.edge_point(f[i], f[j]))
            .collect();
        let p = self.mean(&ids);
        let v = self.positions.len() as u32;
        self.positions.push(p);
        self.face.insert(f, v);
        v
    }

    fn is_edge_point(&self, v: u32) -> bool {
        self.on_edge.get(v as usize).copied().unwrap_or(false)
    }

    fn mean(&self, ids: &[u32]) -> [f64; 3] {
        let mut p = [0.0; 3];
        for &i in ids {
            for (s, x) in p.iter_mut().zip(self.positions[i as usize]) {
                *s += x;
            }
        }
        p.map(|x| x / ids.len() as f64)
    }
}

/// The interface triangles of every tetrahedron of `cubes` (module docs), as a partition.
fn extract(
    grid: &Grid,
    nodes: &IntMap<u64, Node>,
    cubes: &[[u32; 3]],
    labels: &[i32],
) -> Partition {
    let mut points = Points {
        grid,
        nodes,
        positions: Vec::new(),
        edge: HashMap::new(),
        face: HashMap::new(),
        on_edge: Vec::new(),
    };
    // per triangle: vertices oriented outward from the part of the first label, and the two labels
    let mut tris: Vec<([u32; 3], usize, usize)> = Vec::new();
    for &c in cubes {
        for tet in TETS {
            let keys = tet.map(|k| Grid::key(corner(c, 1, k)));
            let lab = keys.map(|k| nodes[&k].label);
            if (1..4).all(|i| lab[i] == lab[0]) {
                continue;
            }
            let segments = face_segments(&mut points, keys, lab, tet_orientation(tet));
            tet_triangles(&mut points, segments, &mut tris);
        }
    }
    assemble(points.positions, tris, labels)
}

/// A piece of the interface on a face of a tetrahedron: from `p` to `q`, oriented so that the
/// triangle `(p, q, centre)` faces away from the part of label `out` into that of label `into`.
#[derive(Clone, Copy, Debug)]
struct Segment {
    p: u32,
    q: u32,
    out: usize,
    into: usize,
}

/// The interface on the four faces of a tetrahedron with nodes `keys`, labels `lab` and
/// orientation `orientation`. On a face of two labels, the segment between the lone node's two
/// edge points; on a face of three, the three segments from the edge points to the face point.
/// Orientation from the barycentric subdivision: the small tetrahedron (node x, edge xy, face
/// xyz, centre) has the sign of the permutation (x, y, z, w) times the tetrahedron's, and its
/// face opposite x faces away from x's part.
fn face_segments(
    points: &mut Points,
    keys: [u64; 4],
    lab: [usize; 4],
    orientation: i32,
) -> Vec<Segment> {
    let mut out = Vec::with_capacity(6);
    for w in 0..4 {
        let f: Vec<usize> = (0..4).filter(|&i| i != w).collect();
        let (a, b, c) = (f[0], f[1], f[2]);
        let (la, lb, lc) = (lab[a], lab[b], lab[c]);
        if la == lb && lb == lc {
            continue;
        }
        // outward from x, the path edge(x, y) → g (face point, or the other edge point)
        let mut push = |x: usize, y: usize, z: usize, e: u32, g: u32| {
            let (p, q) = if parity([x, y, z, w]) * orientation > 0 {
                (e, g)
            } else {
                (g, e)
            };
            out.push(Segment {
                p,
                q,
                out: lab[x],
                into: lab[y],
            });
        };
        if la != lb && lb != lc && la != lc {
            let g = points.face_point([keys[a], keys[b], keys[c]]);
            for (x, y, z) in [(a, b, c), (a, c, b), (b, c, a)] {
                let e = points.edge_point(keys[x], keys[y]);
                push(x, y, z, e, g);
            }
        } else {
            // the lone node and the other two
            let (x, y, z) = if lb == lc {
                (a, b, c)
            } else if la == lc {
                (b, a, c)
            } else {
                (c, a, b)
            };
            let e = points.edge_point(keys[x], keys[y]);
            let g = points.edge_point(keys[x], keys[z]);
            push(x, y, z, e, g);
        }
    }
    out
}

/// The triangles of one tetrahedron from its face segments: with two labels, the one loop they
/// make, fanned from its first point; with more, every segment fanned to the centre (the mean of
/// the edge points), the triple lines running from face points to the centre.
fn tet_triangles(
    points: &mut Points,
    mut segments: Vec<Segment>,
    tris: &mut Vec<([u32; 3], usize, usize)>,
) {
    let (a, b) = (segments[0].out, segments[0].into);
    let two = segments
        .iter()
        .all(|s| (s.out == a && s.into == b) || (s.out == b && s.into == a));
    if two {
        for s in &mut segments {
            if s.out != a {
                std::mem::swap(&mut s.p, &mut s.q);
            }
        }
        let mut loop_ = vec![segments[0].p];
        let mut at = segments[0].q;
        while at != segments[0].p && loop_.len() <= segments.len() {
            loop_.push(at);
            at = match segments.iter().find(|s| s.p == at) {
                Some(s) => s.q,
                None => break,
            };
        }
        for i in 1..loop_.len() - 1 {
            tris.push(([loop_[0], loop_[i], loop_[i + 1]], a, b));
        }
        return;
    }
    let mut edge_points: Vec<u32> = segments
        .iter()
        .flat_map(|s| [s.p, s.q])
        .filter(|&v| points.is_edge_point(v))
        .collect();
    edge_points.sort_unstable();
    edge_points.dedup();
    let centre = points.positions.len() as u32;
    let p = points.mean(&edge_points);
    points.positions.push(p);
    for s in segments {
        tris.push(([s.p, s.q, centre], s.out, s.into));
    }
}

/// Per label its surface, and the interface network, from the oriented triangles.
fn assemble(
    positions: Vec<[f64; 3]>,
    tris: Vec<([u32; 3], usize, usize)>,
    labels: &[i32],
) -> Partition {
    let label_of = |i: usize| if i == 0 { EXTERIOR } else { labels[i - 1] };
    let mut per_label: Vec<Vec<[u32; 3]>> = vec![Vec::new(); labels.len() + 1];
    let mut network = Vec::with_capacity(tris.len());
    let mut pairs = Vec::with_capacity(tris.len());
    for &(t, a, b) in &tris {
        let flipped = [t[0], t[2], t[1]];
        per_label[a].push(t);
        per_label[b].push(flipped);
        if label_of(a) < label_of(b) {
            network.push(t);
            pairs.push([label_of(a), label_of(b)]);
        } else {
            network.push(flipped);
            pairs.push([label_of(b), label_of(a)]);
        }
    }
    let surfaces = per_label[1..]
        .iter()
        .map(|tris| TriMesh::with_used_vertices(&positions, tris))
        .collect();
    Partition {
        labels: Vec::new(),
        surfaces,
        interfaces: TriMesh::with_used_vertices(&positions, &network),
        interface_labels: pairs,
        ..Default::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every node of a 4³-cube grid label 1, the centre label 2 with `centre` values.
    fn grid_with_centre(centre: Vec<f64>) -> (Grid, IntMap<u64, Node>) {
        let grid = Grid::new([0.0; 3], [1.0; 3], 2);
        let mut nodes = IntMap::default();
        for x in 0..5 {
            for y in 0..5 {
                for z in 0..5 {
                    let node = if [x, y, z] == [2, 2, 2] {
                        Node {
                            values: centre.clone(),
                            label: 2,
                        }
                    } else {
                        Node {
                            values: vec![-1.0, 0.5, -0.5],
                            label: 1,
                        }
                    };
                    nodes.insert(Grid::key([x, y, z]), node);
                }
            }
        }
        (grid, nodes)
    }

    #[test]
    fn an_enclosed_group_whose_own_indicator_is_negative_is_an_island() {
        let (grid, mut nodes) = grid_with_centre(vec![-1.0, -0.3, -0.2]);
        assert_eq!(relabel_islands(&grid, &mut nodes), 1);
        assert_eq!(nodes[&Grid::key([2, 2, 2])].label, 1);
        // its own indicator positive somewhere: witnessed, kept
        let (grid, mut nodes) = grid_with_centre(vec![-1.0, -0.3, 0.1]);
        assert_eq!(relabel_islands(&grid, &mut nodes), 0);
        assert_eq!(nodes[&Grid::key([2, 2, 2])].label, 2);
        // a neighbour not evaluated: the band around something larger, kept
        let (grid, mut nodes) = grid_with_centre(vec![-1.0, -0.3, -0.2]);
        nodes.remove(&Grid::key([3, 3, 3]));
        assert_eq!(relabel_islands(&grid, &mut nodes), 0);
    }

    /// Signed volume of a closed triangle mesh.
    fn volume(m: &TriMesh) -> f64 {
        m.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| m.vertices[v as usize]);
                (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0
            })
            .sum()
    }

    #[test]
    fn three_labels_meeting_make_closed_oriented_surfaces_sharing_their_interfaces() {
        // 5³ nodes; the box's boundary exterior; inside, label by x (1, 2) and for x = 3 by y
        // (3 where y = 1, else 1 again), so three labels and the exterior meet along lines
        let grid = Grid::new([0.0; 3], [1.0; 3], 2);
        let mut nodes = IntMap::default();
        let mut cubes = Vec::new();
        for x in 0..5u32 {
            for y in 0..5u32 {
                for z in 0..5u32 {
                    let inner = [x, y, z].iter().all(|&c| (1..4).contains(&c));
                    let label: usize = match (inner, x, y) {
                        (false, ..) => 0,
                        (true, 1, _) => 1,
                        (true, 2, _) => 2,
                        (true, _, 1) => 3,
                        _ => 1,
                    };
                    // own value 0.6, the others graded by position so the roots vary
                    let values = (0..4)
                        .map(|l| {
                            if l == label {
                                0.6
                            } else {
                                -0.2 - 0.1 * ((x as usize + y as usize + z as usize + l) % 3) as f64
                            }
                        })
                        .collect();
                    nodes.insert(Grid::key([x, y, z]), Node { values, label });
                    if x < 4 && y < 4 && z < 4 {
                        cubes.push([x, y, z]);
                    }
                }
            }
        }
        let p = extract(&grid, &nodes, &cubes, &[1, 2, 3]);
        for (i, s) in p.surfaces.iter().enumerate() {
            let mut directed: std::collections::HashMap<(u32, u32), i32> = Default::default();
            for t in &s.triangles {
                for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                    *directed.entry((a, b)).or_default() += 1;
                }
            }
            for (&(a, b), &n) in &directed {
                assert_eq!(
                    n,
                    1,
                    "label {}: edge ({a}, {b}) used {n} times one way",
                    i + 1
                );
                assert_eq!(
                    directed.get(&(b, a)),
                    Some(&1),
                    "label {}: open edge",
                    i + 1
                );
            }
            assert!(volume(s) > 0.0, "label {}: volume {}", i + 1, volume(s));
        }
        // the interfaces are shared: every network triangle is in both labels' surfaces
        let pairs: std::collections::HashSet<[i32; 2]> =
            p.interface_labels.iter().copied().collect();
        for want in [[0, 1], [0, 2], [0, 3], [1, 2], [2, 3], [1, 3]] {
            assert!(pairs.contains(&want), "no interface {want:?}: {pairs:?}");
        }
        let total: usize = p.surfaces.iter().map(|s| s.triangles.len()).sum();
        let exterior = p
            .interface_labels
            .iter()
            .filter(|l| l[0] == EXTERIOR)
            .count();
        assert_eq!(total, 2 * p.interface_labels.len() - exterior);
    }

    #[test]
    fn every_freudenthal_tetrahedron_has_an_orientation() {
        for t in TETS {
            assert_ne!(tet_orientation(t), 0, "{t:?}");
        }
        assert_eq!(parity([0, 1, 2, 3]), 1);
        assert_eq!(parity([1, 0, 2, 3]), -1);
        assert_eq!(parity([1, 2, 0, 3]), 1);
    }
}
