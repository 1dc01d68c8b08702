//! Random odd but valid cross-section sets, of the kind of `../shared/data/odd` (a generator of
//! such files found most of the engine's failures on inputs no mesh was sliced for): 1–9 planes,
//! some in parallel families, some axis-aligned, some through the origin, random directions
//! otherwise; per plane none or up to three star-shaped contours of 3 to 300 vertices at scales
//! from 1e-5 to 0.5, pairwise apart, so the sections disagree along most common lines. For stress
//! tests: a seed gives one input, as JSON text (read as a file would be, validation included).
use rand::{Rng, SeedableRng};
use serde_json::{json, Value};

/// Vertex counts a contour takes.
const SIZES: [usize; 7] = [3, 4, 5, 8, 16, 64, 300];

/// The input of `seed`, as the text of a JSON sections file. Two planes of one family may
/// coincide (the reader then refuses the file: a duplicate plane), and every plane may be empty.
pub fn odd_sections_json(seed: u64) -> String {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let n_planes = rng.gen_range(1..=9);
    let mut normals: Vec<[f64; 3]> = Vec::new();
    let mut planes: Vec<Value> = Vec::new();
    for _ in 0..n_planes {
        let r: f64 = rng.gen();
        let normal = if !normals.is_empty() && r < 0.25 {
            normals[rng.gen_range(0..normals.len())]
        } else if r < 0.45 {
            let mut n = [0.0; 3];
            n[rng.gen_range(0..3)] = 1.0;
            n
        } else {
            random_direction(&mut rng)
        };
        normals.push(normal);
        let offset = if rng.gen::<f64>() < 0.2 {
            0.0
        } else {
            rng.gen_range(-0.55..0.55)
        };
        let contours: Vec<Value> = if rng.gen::<f64>() < 0.15 {
            Vec::new()
        } else {
            star_contours(&mut rng)
                .into_iter()
                .map(|points| json!({"points2d": points, "label": 1}))
                .collect()
        };
        planes.push(json!({"normal": normal, "offset": offset, "contours": contours}));
    }
    json!({ "planes": planes }).to_string()
}

fn random_direction(rng: &mut impl Rng) -> [f64; 3] {
    loop {
        let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.1 && n <= 1.0 {
            return v.map(|x| x / n);
        }
    }
}

/// One to three star-shaped contours, counter-clockwise, whose discs (centre, largest radius) are
/// apart by 1e-3 at least.
fn star_contours(rng: &mut impl Rng) -> Vec<Vec<[f64; 2]>> {
    let mut discs: Vec<([f64; 2], f64)> = Vec::new();
    let mut out = Vec::new();
    for _ in 0..rng.gen_range(1..=3) {
        let placed = (0..50).find_map(|_| {
            let m = SIZES[rng.gen_range(0..SIZES.len())];
            let scale = if rng.gen::<f64>() < 0.2 {
                10f64.powf(rng.gen_range(-5.0..0.5f64.log10()))
            } else {
                rng.gen_range(0.1..0.5)
            };
            let reach = if discs.is_empty() { 0.2 } else { 0.8 };
            let c = [rng.gen_range(-reach..reach), rng.gen_range(-reach..reach)];
            let apart = discs
                .iter()
                .all(|&(d, r)| (c[0] - d[0]).hypot(c[1] - d[1]) > scale + r + 1e-3);
            apart.then_some((m, scale, c))
        });
        let Some((m, scale, c)) = placed else {
            continue;
        };
        discs.push((c, scale));
        let mut angles: Vec<f64> = if m > 5 && rng.gen::<f64>() < 0.5 {
            (0..m)
                .map(|_| rng.gen_range(0.0..std::f64::consts::TAU))
                .collect()
        } else {
            let step = std::f64::consts::TAU / m as f64;
            (0..m)
                .map(|k| step * (k as f64 + rng.gen_range(-0.3..0.3)))
                .collect()
        };
        angles.sort_by(f64::total_cmp);
        out.push(
            angles
                .iter()
                .map(|&a| {
                    let r = scale * rng.gen_range(0.5..1.0);
                    [c[0] + r * a.cos(), c[1] + r * a.sin()]
                })
                .collect(),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_seed_gives_one_input_and_most_are_valid() {
        assert_eq!(odd_sections_json(7), odd_sections_json(7));
        assert_ne!(odd_sections_json(7), odd_sections_json(8));
        let valid = (0..40)
            .filter(|&s| crate::io::json::parse_json(&odd_sections_json(s), "odd").is_ok())
            .count();
        assert!(valid >= 30, "{valid} of 40");
    }
}
