use crate::InfoArgs;
use slice2solid::{Error, Result};
use std::process::ExitCode;

pub fn run(_args: InfoArgs) -> Result<ExitCode> {
    Err(Error::Unavailable("`info` is not implemented yet".into()))
}
