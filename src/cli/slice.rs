use crate::SliceArgs;
use slice2solid::{Error, Result};
use std::process::ExitCode;

pub fn run(_args: SliceArgs) -> Result<ExitCode> {
    Err(Error::Unavailable("`slice` is not implemented yet".into()))
}
