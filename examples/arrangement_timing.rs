//! Arrangement build time for 24, 50 and 100 random planes, each with a 400-vertex circle:
//! `cargo run --release --example arrangement_timing`.
use slice2solid::arrangement::{Arrangement, ArrangementOptions};
use std::time::Instant;

fn main() {
    use rand::{Rng, SeedableRng};
    use slice2solid::sections::{Contour, Plane, Region, Section, Sections};
    for k in [24usize, 50, 100] {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(k as u64);
        let mut s = Sections {
            sections: Vec::new(),
            n_labels: 1,
            warnings: Vec::new(),
            label_names: Default::default(),
        };
        for idx in 0..k {
            let n = [
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            ];
            let plane = Plane::from_equation(n, rng.gen_range(-0.5..0.5)).unwrap();
            let rr = (1.0 - plane.offset * plane.offset).sqrt();
            let pts: Vec<[f64; 2]> = (0..400)
                .map(|a| {
                    let t = a as f64 / 400.0 * std::f64::consts::TAU;
                    [rr * t.cos(), rr * t.sin()]
                })
                .collect();
            let outer = Contour::from_2d(&plane, pts);
            s.sections.push(Section {
                plane,
                regions: vec![Region {
                    label: 1,
                    outer,
                    holes: vec![],
                }],
                source_index: idx,
                max_off_plane: 0.0,
            });
        }
        let t = Instant::now();
        let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
        eprintln!(
            "{k} planes: {} cells, {} faces, {} pool vertices, {:.1} ms",
            arr.cells.len(),
            arr.faces.len(),
            arr.pool.positions.len(),
            t.elapsed().as_secs_f64() * 1e3
        );
    }
}
