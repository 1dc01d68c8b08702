//! Write the generated odd inputs of seeds FROM..TO as DIR/oddSEED.json (`slice::odd`), for
//! stress runs from the command line: `cargo run --release --example odd_sections -- 0 200 /tmp/odd`.
fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 4 {
        eprintln!("usage: odd_sections FROM TO DIR");
        std::process::exit(2);
    }
    let (from, to): (u64, u64) = match (args[1].parse(), args[2].parse()) {
        (Ok(a), Ok(b)) => (a, b),
        _ => {
            eprintln!("odd_sections: FROM and TO are seeds (integers)");
            std::process::exit(2);
        }
    };
    let dir = std::path::Path::new(&args[3]);
    if let Err(e) = std::fs::create_dir_all(dir) {
        eprintln!("odd_sections: {}: {e}", dir.display());
        std::process::exit(1);
    }
    for seed in from..to {
        let path = dir.join(format!("odd{seed:03}.json"));
        if let Err(e) = std::fs::write(&path, slice2solid::slice::odd::odd_sections_json(seed)) {
            eprintln!("odd_sections: {}: {e}", path.display());
            std::process::exit(1);
        }
    }
}
