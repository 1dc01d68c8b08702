mod bm_common;
use bm_common::*;
use slice2solid::{Options, Report};
use std::collections::HashMap;
#[test]
#[ignore]
fn debug_one_four() {
    let four: Vec<Poly> = [(-0.6, -0.6), (0.6, -0.6), (0.6, 0.6), (-0.6, 0.6)]
        .iter()
        .map(|&(x, y)| (circle(x, y, 0.4, 24), vec![]))
        .collect();
    let (sections, arr) = parallel_case(&[
        (0.0, vec![(circle(0.0, 0.0, 1.2, 48), vec![])]),
        (1.0, four),
    ]);
    let mut report = Report::default();
    let solid =
        slice2solid::bm::reconstruct(&sections, &arr, &Options::default(), &mut report).unwrap();
    let m = &solid.surface;
    let mut edges: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (i, t) in m.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.entry((a.min(b), a.max(b))).or_default().push(i);
        }
    }
    for (e, ts) in &edges {
        if ts.len() != 2 {
            let p = |v: u32| m.vertices[v as usize];
            eprintln!("edge {:?} {:?}-{:?}: {} tris", e, p(e.0), p(e.1), ts.len());
            for &t in ts {
                let tr = m.triangles[t];
                eprintln!("   {:?}", tr.map(p));
            }
        }
    }
}
