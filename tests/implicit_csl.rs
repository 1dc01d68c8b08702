//! Every shared CSL file reconstructs with the implicit method to a closed, manifold surface
//! (depth 6 to keep the test short; the release CLI runs use depth 8/9).
mod common;

use slice2solid::eval::check::check_mesh;
use slice2solid::io::read_sections;
use slice2solid::{reconstruct, Method, Options};

#[test]
fn every_shared_csl_reconstructs_to_a_closed_manifold() {
    for path in common::shared_csl_files() {
        let sections = read_sections(&path).unwrap();
        let options = Options {
            method: Method::Implicit,
            depth: 6,
            ..Default::default()
        };
        let solid =
            reconstruct(&sections, &options).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let r = check_mesh(&solid.surface, None);
        assert!(
            r.closed && r.manifold,
            "{}: closed {} manifold {} ({} boundary, {} non-manifold edges)",
            path.display(),
            r.closed,
            r.manifold,
            r.boundary_edges,
            r.nonmanifold_edges
        );
        assert_eq!(r.self_intersections, 0, "{}", path.display());
        assert!(r.volume > 0.0, "{}", path.display());
        assert!(solid.report.counts["implicit_evaluations"] > 0);
    }
}
