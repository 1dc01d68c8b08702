//! Face sections: every region of an input plane split by the other planes into one piece per face.
//!
//! Decisions are exact and made in one model: the side of a contour vertex with respect to a plane
//! `P_j` is the exact sign of `n_j·p + d_j` at its 3D point `points3` (a fixed function of the vertex,
//! so every vertex is on exactly one side, or on `P_j`). A contour edge whose endpoints are strictly
//! on opposite sides crosses `P_j` at one new pool vertex tagged {i, j}; the order of several crossings
//! along one edge is exact too (sign of a degree-2 polynomial in the plane values). A contour vertex or
//! crossing that lies on two other planes is the arrangement vertex of that triple (same pool id).
//!
//! Each stretch of contour between two points is assigned to the face whose sign vector it has (an
//! edge lying on `P_j` goes to the face on its left, where the region is). Inside a face the pieces are
//! traced: contour runs, joined along the face boundary (counter-clockwise, through corners and every
//! section point on the boundary) from where a run leaves the face to where the next one enters.
//! The tracing inside a face is module `trace`.
use super::exact::{dot_plus, sign_dot_plus};
use super::signs::SignVec;
use super::{Arrangement, ArrangementOptions, PlaneTags, VertexId};
use crate::error::Result;
use crate::fxhash::FxHashMap as HashMap;
use crate::sections::{Contour, Region, Sections};
use smallvec::SmallVec;
use std::cmp::Ordering;

mod trace;
use trace::{assemble, trace_face};

struct Pt {
    id: VertexId,
    sv: SignVec,
}

#[derive(Default)]
struct FaceWork {
    runs: Vec<Vec<VertexId>>,
    closed: Vec<Vec<VertexId>>,
    bpoints: Vec<VertexId>,
}

pub(super) struct Ctx<'a> {
    pub arr: &'a mut Arrangement,
    /// Per sorted plane triple: an arrangement vertex on all three, and how many there are (two or
    /// more: the three planes share an arrangement edge, a line).
    triples: HashMap<[u32; 3], (VertexId, u32)>,
    pub warnings: Vec<String>,
    /// (section plane, pool id) of every section point that lies on another plane.
    line_points: Vec<(u32, VertexId)>,
}

fn fsign(x: f64) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

impl<'a> Ctx<'a> {
    fn add_pool(
        &mut self,
        pos: [f64; 3],
        tags: PlaneTags,
        plane: u32,
        uv_here: [f64; 2],
    ) -> VertexId {
        let uv: SmallVec<[[f64; 2]; 3]> = tags
            .iter()
            .map(|&t| {
                if t == plane {
                    uv_here
                } else {
                    self.arr.planes[t as usize].plane.to_2d(pos)
                }
            })
            .collect();
        let p = &mut self.arr.pool;
        p.positions.push(pos);
        p.tags.push(tags);
        p.uv.push(uv);
        let id = (p.positions.len() - 1) as VertexId;
        if p.tags[id as usize].len() > 1 {
            self.line_points.push((plane, id));
        }
        id
    }

    /// The arrangement vertex through plane i and two of the planes in `zeros`, if any.
    fn arrangement_vertex(&self, i: u32, zeros: &[u32]) -> Option<VertexId> {
        for a in 0..zeros.len() {
            for b in a + 1..zeros.len() {
                // Only three planes meeting in a point identify a vertex (not three through a line).
                if self.same_line(i, zeros[a], zeros[b]) {
                    continue;
                }
                let mut t = [i, zeros[a], zeros[b]];
                t.sort_unstable();
                if let Some(&(v, _)) = self.triples.get(&t) {
                    return Some(v);
                }
            }
        }
        None
    }

    /// Whether three distinct planes pass through one line: exactly (rank 2), or combinatorially,
    /// when two arrangement vertices lie on all three. The second is what a pencil of planes is
    /// after rounding (a rotational fan: planes through one axis whose equations, rounded, meet in
    /// points scattered along it, merged into its two ends): treating its planes as one line makes a
    /// contour cross it at ONE vertex tagged with every plane of the pencil, not at one vertex per
    /// plane, ulps apart, each on two planes (a cell between two of them would see a cloud of
    /// near-duplicates of which one is on both its planes).
    fn same_line(&self, i: u32, j: u32, k: u32) -> bool {
        let mut t = [i, j, k];
        t.sort_unstable();
        if self.triples.get(&t).is_some_and(|&(_, n)| n >= 2) {
            return true;
        }
        let eq = |p: u32| self.arr.planes[p as usize].plane.equation();
        rank2(eq(i), eq(j), eq(k))
    }

    fn uv(&self, v: VertexId, plane: u32) -> [f64; 2] {
        self.arr.uv(v, plane).unwrap_or([f64::NAN, f64::NAN])
    }
}

pub(super) fn build_pieces(
    arr: &mut Arrangement,
    sections: &Sections,
    cell_sign: &[SignVec],
    diag: f64,
    options: &ArrangementOptions,
) -> Result<()> {
    let n_arr = arr.pool.positions.len();
    let mut triples = HashMap::default();
    for (v, tags) in arr.pool.tags.iter().enumerate() {
        let n = tags.len();
        for a in 0..n {
            for b in a + 1..n {
                for c in b + 1..n {
                    triples
                        .entry([tags[a], tags[b], tags[c]])
                        .and_modify(|e: &mut (VertexId, u32)| e.1 += 1)
                        .or_insert((v as VertexId, 1));
                }
            }
        }
    }
    let mut ctx = Ctx {
        arr,
        triples,
        warnings: Vec::new(),
        line_points: Vec::new(),
    };
    let n_planes = ctx.arr.planes.len();
    // Faces per plane, keyed by the sign vector of their positive cell with the own entry zeroed.
    let mut faces_of: Vec<Vec<u32>> = vec![Vec::new(); n_planes];
    let mut face_key: Vec<HashMap<SignVec, u32>> = vec![HashMap::default(); n_planes];
    for (f, face) in ctx.arr.faces.iter().enumerate() {
        faces_of[face.plane as usize].push(f as u32);
        if let Some(c) = face.positive_cell.or(face.negative_cell) {
            let sv = cell_sign[c as usize].clone().with(face.plane as usize, 0);
            face_key[face.plane as usize].insert(sv, f as u32);
        }
    }
    for (i, section) in sections.sections.iter().enumerate() {
        if section.regions.is_empty() {
            continue;
        }
        let eff = plane_effects(&ctx, i as u32, &face_key[i]);
        for region in &section.regions {
            process_region(&mut ctx, i as u32, region, &faces_of[i], &face_key[i], &eff);
        }
    }
    let warnings = std::mem::take(&mut ctx.warnings);
    let line_points = std::mem::take(&mut ctx.line_points);
    arr.warnings.extend(warnings);
    super::reconcile::reconcile(arr, &line_points, n_arr, diag, options);
    super::merge::merge_line_points(arr, n_arr, options.merge_tolerance * diag);
    Ok(())
}

/// How plane j splits plane i: not at all inside the box (constant side), or along a line shared by
/// a class of planes, decided through one representative (`Rep(r, f)`: side = f · side of r).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Effect {
    Own,
    Const(i8),
    Rep(u32, i8),
}

fn plane_effects(ctx: &Ctx, i: u32, face_key: &HashMap<SignVec, u32>) -> Vec<Effect> {
    let np = ctx.arr.planes.len();
    let keys: Vec<&SignVec> = face_key.keys().collect();
    let mut eff = vec![Effect::Own; np];
    let mut reps: Vec<u32> = Vec::new();
    // the planes on which the faces' sides differ, in one pass over the keys (a dense sweep has
    // a thousand planes and a thousand faces per plane, most planes far from plane i)
    let first: SignVec = keys
        .first()
        .map_or_else(|| SignVec::filled(np, -1), |k| (*k).clone());
    let mut varies = vec![0u64; SignVec::words_for(np)];
    for k in &keys[1.min(keys.len())..] {
        k.mark_differences(&first, &mut varies);
    }
    for (j, e) in eff.iter_mut().enumerate() {
        if j as u32 == i {
            continue;
        }
        if !SignVec::marked(&varies, j) {
            *e = Effect::Const(first.get(j));
            continue;
        }
        // Same line as an earlier representative: rank [P_i; P_r; P_j] = 2.
        let mut found = None;
        for &r in &reps {
            if ctx.same_line(i, r, j as u32) {
                // The two planes' sides on P_i agree or are opposite on every face.
                let k = keys
                    .iter()
                    .find(|k| k.get(j) != 0 && k.get(r as usize) != 0);
                let f = k.map_or(1, |k| k.get(j) * k.get(r as usize));
                found = Some(Effect::Rep(r, f));
                break;
            }
        }
        *e = match found {
            Some(found) => found,
            None => {
                reps.push(j as u32);
                Effect::Rep(j as u32, 1)
            }
        };
    }
    eff
}

/// True when the three plane equations have rank 2 (three distinct planes through one line).
fn rank2(a: [f64; 4], b: [f64; 4], c: [f64; 4]) -> bool {
    const COLS: [[usize; 3]; 4] = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];
    COLS.iter().all(|cs| {
        let r = |x: [f64; 4]| [x[cs[0]], x[cs[1]], x[cs[2]]];
        super::exact::sign_det3(r(a), r(b), r(c)) == 0
    })
}

fn process_region(
    ctx: &mut Ctx,
    i: u32,
    region: &Region,
    faces: &[u32],
    face_key: &HashMap<SignVec, u32>,
    eff: &[Effect],
) {
    let mut work: HashMap<u32, FaceWork> = HashMap::default();
    let contours: Vec<&Contour> = std::iter::once(&region.outer)
        .chain(region.holes.iter())
        .collect();
    for c in &contours {
        split_contour(ctx, i, c, face_key, eff, &mut work);
    }
    for &f in faces {
        let w = work.remove(&f).unwrap_or_default();
        let loops = trace_face(ctx, i, f, &w, region);
        let pieces = assemble(ctx, i, loops, region.label);
        ctx.arr.faces[f as usize].pieces.extend(pieces);
    }
}

/// Sign of `t_j - t_k` where `t_m = v_m(p) / (v_m(p) - v_m(q))`, for two planes strictly crossed by pq.
fn cmp_crossings(
    eq_j: [f64; 4],
    eq_k: [f64; 4],
    p: [f64; 3],
    q: [f64; 3],
    sj: i8,
    sk: i8,
) -> Ordering {
    // t_j - t_k = (vk_p vj_q - vj_p vk_q) / (D_j D_k), sign(D_m) = sign(v_m(p)).
    let nj = [eq_j[0], eq_j[1], eq_j[2]];
    let nk = [eq_k[0], eq_k[1], eq_k[2]];
    let f = |n: [f64; 3], d: f64, x: [f64; 3]| {
        let v = n[0] * x[0] + n[1] * x[1] + n[2] * x[2] + d;
        let m = (n[0] * x[0]).abs() + (n[1] * x[1]).abs() + (n[2] * x[2]).abs() + d.abs();
        (v, 8.0 * f64::EPSILON * m)
    };
    let (vjp, ejp) = f(nj, eq_j[3], p);
    let (vjq, ejq) = f(nj, eq_j[3], q);
    let (vkp, ekp) = f(nk, eq_k[3], p);
    let (vkq, ekq) = f(nk, eq_k[3], q);
    let a = vkp * vjq;
    let b = vjp * vkq;
    let diff = a - b;
    let bound = ekp * (vjq.abs() + ejq)
        + ejq * vkp.abs()
        + ejp * (vkq.abs() + ekq)
        + ekq * vjp.abs()
        + 4.0 * f64::EPSILON * (a.abs() + b.abs());
    let s = if diff.abs() > bound {
        fsign(diff)
    } else {
        let vjp = dot_plus(nj, p, eq_j[3]);
        let vjq = dot_plus(nj, q, eq_j[3]);
        let vkp = dot_plus(nk, p, eq_k[3]);
        let vkq = dot_plus(nk, q, eq_k[3]);
        vkp.mul(&vjq).sub(&vjp.mul(&vkq)).sign()
    };
    match s * sj * sk {
        1 => Ordering::Greater,
        -1 => Ordering::Less,
        _ => Ordering::Equal,
    }
}

/// Exact sides of contour points with respect to the planes of the arrangement, as seen from plane
/// `i`: decided for the representative planes, the others follow from them (`Effect`).
/// Only the planes that vary on plane i are looked at per point: a dense sweep has a thousand
/// planes, a few hundred of them crossing plane i inside the box.
struct SideModel {
    i: u32,
    eq: Vec<[f64; 4]>,
    /// The representative planes, ascending.
    reps: Vec<u32>,
    /// The sign vector with every representative's sign 0 (the constant planes' sides).
    base: SignVec,
    /// (plane m, its representative, the factor) for every plane decided through one, ascending.
    dependents: Vec<(u32, u32, i8)>,
    /// The planes a point's sign vector can be 0 on, ascending.
    maybe_zero: Vec<u32>,
}

impl SideModel {
    fn new(ctx: &Ctx, i: u32, eff: &[Effect]) -> Self {
        let eq: Vec<[f64; 4]> = ctx
            .arr
            .planes
            .iter()
            .map(|p| {
                [
                    p.plane.normal[0],
                    p.plane.normal[1],
                    p.plane.normal[2],
                    p.plane.offset,
                ]
            })
            .collect();
        let mut reps = Vec::new();
        let mut dependents = Vec::new();
        let mut maybe_zero = Vec::new();
        for (j, e) in eff.iter().enumerate() {
            let j = j as u32;
            match *e {
                Effect::Rep(r, f) => {
                    if r == j && f == 1 {
                        reps.push(j);
                    }
                    dependents.push((j, r, f));
                    maybe_zero.push(j);
                }
                Effect::Const(0) | Effect::Own => maybe_zero.push(j),
                Effect::Const(_) => {}
            }
        }
        let base = SignVec::from_fn(eq.len(), |j| match eff[j] {
            Effect::Const(s) => s,
            _ => 0,
        });
        SideModel {
            i,
            eq,
            reps,
            base,
            dependents,
            maybe_zero,
        }
    }

    fn n_planes(&self) -> usize {
        self.eq.len()
    }

    /// The full sign vector from the signs `r` with respect to the representatives (own plane 0,
    /// constant planes their side, the others `f` times their representative's sign).
    fn expand(&self, r: &[i8]) -> SignVec {
        let mut sv = self.base.clone();
        for &(m, rep, f) in &self.dependents {
            let s = f * r[rep as usize];
            if s != 0 {
                sv.set(m as usize, s);
            }
        }
        sv
    }

    /// Exact signs of `p` with respect to the representative planes (0 for the others).
    fn rep_signs(&self, p: [f64; 3]) -> Vec<i8> {
        let mut out = vec![0; self.n_planes()];
        for &j in &self.reps {
            let e = self.eq[j as usize];
            out[j as usize] = sign_dot_plus([e[0], e[1], e[2]], p, e[3]);
        }
        out
    }

    /// The other planes a point with sign vector `s` lies on.
    fn zeros_of(&self, s: &SignVec) -> Vec<u32> {
        (self.maybe_zero.iter().copied())
            .filter(|&j| j != self.i && s.get(j as usize) == 0)
            .collect()
    }
}

/// The arrangement vertex of a point of plane `i` on the planes `zeros`, if it is one; otherwise
/// a new pool vertex tagged with them (built by `make`: position and uv).
fn section_point_id(
    ctx: &mut Ctx,
    i: u32,
    zeros: &[u32],
    make: impl FnOnce(&Ctx) -> ([f64; 3], [f64; 2]),
) -> VertexId {
    let id = if zeros.len() >= 2 {
        ctx.arrangement_vertex(i, zeros)
    } else {
        None
    };
    id.unwrap_or_else(|| {
        let (pos, uv) = make(ctx);
        let mut tags: PlaneTags = zeros.iter().copied().collect();
        tags.push(i);
        tags.sort_unstable();
        ctx.add_pool(pos, tags, i, uv)
    })
}

fn split_contour(
    ctx: &mut Ctx,
    i: u32,
    c: &Contour,
    face_key: &HashMap<SignVec, u32>,
    eff: &[Effect],
    work: &mut HashMap<u32, FaceWork>,
) {
    let n = c.points2.len();
    if n < 3 {
        return;
    }
    let model = SideModel::new(ctx, i, eff);
    let rsv: Vec<Vec<i8>> = c.points3.iter().map(|&p| model.rep_signs(p)).collect();
    let sv: Vec<SignVec> = rsv.iter().map(|r| model.expand(r)).collect();
    // Pool ids of the contour vertices.
    let mut vid = Vec::with_capacity(n);
    for (k, svk) in sv.iter().enumerate() {
        let z = model.zeros_of(svk);
        vid.push(section_point_id(ctx, i, &z, |_| {
            (c.points3[k], c.points2[k])
        }));
    }
    let mut pts: Vec<Pt> = Vec::with_capacity(n * 2);
    for k in 0..n {
        let (a, b) = (k, (k + 1) % n);
        pts.push(Pt {
            id: vid[a],
            sv: sv[a].clone(),
        });
        push_edge_crossings(ctx, c, &model, (a, b), (&rsv[a], &rsv[b]), &mut pts);
    }
    let fe = stretch_faces(ctx, i, &pts, face_key);
    hand_out_stretches(ctx, &pts, &fe, work);
}

/// The points where contour edge `ab` (representative signs `ra`, `rb`) strictly crosses planes,
/// in order along it; planes crossed at the same point make one point.
fn push_edge_crossings(
    ctx: &mut Ctx,
    c: &Contour,
    model: &SideModel,
    (a, b): (usize, usize),
    (ra, rb): (&[i8], &[i8]),
    pts: &mut Vec<Pt>,
) {
    let i = model.i;
    let np = model.n_planes();
    let eq = &model.eq;
    let (p3, q3) = (c.points3[a], c.points3[b]);
    // only representatives have signs in `ra`, `rb` (ascending, as a scan of all planes)
    let mut cross: Vec<u32> = (model.reps.iter().copied())
        .filter(|&j| ra[j as usize] * rb[j as usize] < 0)
        .collect();
    if cross.is_empty() {
        return;
    }
    let cmp = |x: u32, y: u32| {
        cmp_crossings(
            eq[x as usize],
            eq[y as usize],
            p3,
            q3,
            ra[x as usize],
            ra[y as usize],
        )
    };
    cross.sort_by(|&x, &y| cmp(x, y));
    let mut g = 0;
    while g < cross.len() {
        let mut e = g + 1;
        while e < cross.len() && cmp(cross[g], cross[e]) == Ordering::Equal {
            e += 1;
        }
        let group = &cross[g..e];
        let j0 = group[0];
        let mut rs = vec![0i8; np];
        for &m in &model.reps {
            if group.contains(&m) {
                continue;
            }
            let (sp, sq) = (ra[m as usize], rb[m as usize]);
            rs[m as usize] = if sp * sq < 0 {
                match cmp(m, j0) {
                    Ordering::Less => sq,
                    Ordering::Greater => sp,
                    Ordering::Equal => 0,
                }
            } else if sp != 0 {
                sp
            } else {
                sq
            };
        }
        let s = model.expand(&rs);
        let z = model.zeros_of(&s);
        let id = section_point_id(ctx, i, &z, |ctx| {
            let e0 = eq[j0 as usize];
            let vp = e0[0] * p3[0] + e0[1] * p3[1] + e0[2] * p3[2] + e0[3];
            let vq = e0[0] * q3[0] + e0[1] * q3[1] + e0[2] * q3[2] + e0[3];
            let t = (vp / (vp - vq)).clamp(0.0, 1.0);
            let (p2, q2) = (c.points2[a], c.points2[b]);
            let uv = [p2[0] + t * (q2[0] - p2[0]), p2[1] + t * (q2[1] - p2[1])];
            let own = &ctx.arr.planes[i as usize].plane;
            // exactly on the axis-aligned planes it crosses (and, on an axis-aligned plane of its
            // own, its uv read back from that point, which is then exact too)
            let crossed: Vec<[f64; 4]> = z.iter().map(|&j| eq[j as usize]).collect();
            let pos = crate::geom::on_axis_planes(own.to_3d(uv), &crossed);
            let axis_aligned = crate::geom::axis_of(&own.equation()).is_some();
            (pos, if axis_aligned { own.to_2d(pos) } else { uv })
        });
        pts.push(Pt { id, sv: s });
        g = e;
    }
}

/// Face of every stretch between consecutive points of the split contour.
fn stretch_faces(ctx: &mut Ctx, i: u32, pts: &[Pt], face_key: &HashMap<SignVec, u32>) -> Vec<u32> {
    let m = pts.len();
    let mut fe = Vec::with_capacity(m);
    for k in 0..m {
        let s = stretch_signs(ctx, i, &pts[k], &pts[(k + 1) % m]);
        let f = match face_key.get(&s) {
            Some(&f) => f,
            None => {
                // Only possible within rounding of a multiple point: take the closest sign vector.
                let mut best = (usize::MAX, 0u32);
                for (key, &f) in face_key {
                    let d = key.iter().zip(s.iter()).filter(|(x, y)| x != y).count();
                    if d < best.0 {
                        best = (d, f);
                    }
                }
                ctx.warnings.push(format!(
                    "plane {i}: a contour stretch has no exact face (rounding at a multiple point); assigned to the nearest face {}",
                    best.1
                ));
                best.1
            }
        };
        fe.push(f);
    }
    fe
}

/// Sign vector of the stretch from `a` to `b` (0 for plane `i` itself).
fn stretch_signs(ctx: &Ctx, i: u32, a: &Pt, b: &Pt) -> SignVec {
    let np = ctx.arr.planes.len();
    let plane_i = ctx.arr.planes[i as usize].plane;
    SignVec::from_fn(np, |j| {
        if j as u32 == i {
            0
        } else if a.sv.get(j) != 0 {
            a.sv.get(j)
        } else if b.sv.get(j) != 0 {
            b.sv.get(j)
        } else {
            // The stretch lies on P_j: it belongs to the face on its left (the region's side).
            let pj = &ctx.arr.planes[j].plane;
            let g = [
                crate::sections::dot(pj.normal, plane_i.u),
                crate::sections::dot(pj.normal, plane_i.v),
            ];
            let (ua, ub) = (ctx.uv(a.id, i), ctx.uv(b.id, i));
            let d = [ub[0] - ua[0], ub[1] - ua[1]];
            let x = -d[1] * g[0] + d[0] * g[1];
            if x < 0.0 {
                -1
            } else {
                1
            }
        }
    })
}

/// Give each face its boundary points and its runs of the contour (or the whole contour, closed,
/// when it stays in one face).
fn hand_out_stretches(ctx: &Ctx, pts: &[Pt], fe: &[u32], work: &mut HashMap<u32, FaceWork>) {
    let m = pts.len();
    let on_boundary = |ctx: &Ctx, id: VertexId| ctx.arr.pool.tags[id as usize].len() > 1;
    for k in 0..m {
        let w = work.entry(fe[k]).or_default();
        for id in [pts[k].id, pts[(k + 1) % m].id] {
            if on_boundary(ctx, id) {
                w.bpoints.push(id);
            }
        }
    }
    if fe.iter().all(|&f| f == fe[0]) {
        work.entry(fe[0])
            .or_default()
            .closed
            .push(pts.iter().map(|p| p.id).collect());
        return;
    }
    let k0 = (0..m).find(|&k| fe[(k + m - 1) % m] != fe[k]).unwrap_or(0);
    let mut k = k0;
    loop {
        let f = fe[k];
        let mut run = vec![pts[k].id];
        let mut kk = k;
        loop {
            run.push(pts[(kk + 1) % m].id);
            kk = (kk + 1) % m;
            if fe[kk] != f || kk == k0 {
                break;
            }
        }
        work.entry(f).or_default().runs.push(run);
        k = kk;
        if k == k0 {
            break;
        }
    }
}
