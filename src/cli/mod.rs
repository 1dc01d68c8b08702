//! One file per subcommand: turn parsed arguments into library calls and printed output.
//! Each `run` returns the process exit code; errors are printed by `main`.
pub mod check;
pub mod check_partition;
pub mod check_tets;
pub mod compare;
pub mod compare_methods;
pub mod compare_methods_labels;
pub mod delaunay;
pub mod info;
pub mod reconstruct;
pub mod reconstruct_labels;
pub mod render;
pub mod slice;
pub mod warnings;

/// Print `value` as pretty JSON on stdout (the `--json` output of the subcommands).
pub fn print_json(value: &impl serde::Serialize) -> slice2solid::Result<()> {
    let s = serde_json::to_string_pretty(value)
        .map_err(|e| slice2solid::Error::Geometry(format!("cannot serialise the report: {e}")))?;
    println!("{s}");
    Ok(())
}
