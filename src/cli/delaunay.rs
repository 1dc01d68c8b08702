use crate::DelaunayArgs;
use slice2solid::{Error, Result};
use std::process::ExitCode;

pub fn run(_args: DelaunayArgs) -> Result<ExitCode> {
    Err(Error::Unavailable(
        "`delaunay` is not implemented yet".into(),
    ))
}
