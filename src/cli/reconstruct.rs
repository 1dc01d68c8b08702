use crate::ReconstructArgs;
use slice2solid::{Error, Result};
use std::process::ExitCode;

pub fn run(_args: ReconstructArgs) -> Result<ExitCode> {
    Err(Error::Unavailable(
        "`reconstruct` is not implemented yet".into(),
    ))
}
