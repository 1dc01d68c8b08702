//! Timing of the implicit method's zero set on a sliced sphere (12 planes, 200 vertices each) at
//! depths `IMPLICIT_DEPTHS` (default "7,8"): `cargo run --release --example implicit_timing`.
//! Prints evaluations and phase times per depth.
use slice2solid::implicit::fixtures::{circle, horizontal_slabs, Level};
use slice2solid::implicit::surface;
use slice2solid::Report;

fn main() {
    let levels: Vec<Level> = (0..12)
        .map(|i| {
            let z = -0.77 + 1.4 * i as f64 / 11.0;
            Level {
                z,
                pieces: vec![(circle([0.0, 0.0], (0.81 - z * z).sqrt(), 200), vec![])],
            }
        })
        .collect();
    let arr = horizontal_slabs([-1.0; 3], [1.0; 3], &levels);
    let depths = std::env::var("IMPLICIT_DEPTHS").unwrap_or_else(|_| "7,8".into());
    for depth in depths.split(',').map(|d| d.trim().parse::<u32>().unwrap()) {
        let mut report = Report::default();
        let t = std::time::Instant::now();
        let mesh = surface(&arr, depth, false, &mut report).unwrap();
        let chi = slice2solid::eval::topology::analyze(&mesh).euler;
        println!(
            "depth {depth}: {:.2} s, {} triangles, χ = {chi}, phases {:?}, counts {:?}",
            t.elapsed().as_secs_f64(),
            mesh.triangles.len(),
            report
                .phases
                .iter()
                .map(|p| format!("{} {:.2}", p.name, p.seconds))
                .collect::<Vec<_>>(),
            report.counts
        );
    }
}
