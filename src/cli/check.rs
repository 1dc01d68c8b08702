use crate::CheckArgs;
use slice2solid::{Error, Result};
use std::process::ExitCode;

pub fn run(_args: CheckArgs) -> Result<ExitCode> {
    Err(Error::Unavailable("`check` is not implemented yet".into()))
}
