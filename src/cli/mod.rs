//! One file per subcommand: turn parsed arguments into library calls and printed output.
//! Each `run` returns the process exit code; errors are printed by `main`.
pub mod check;
pub mod check_tets;
pub mod compare;
pub mod compare_methods;
pub mod delaunay;
pub mod info;
pub mod reconstruct;
pub mod slice;
pub mod warnings;
