use crate::CompareArgs;
use slice2solid::{Error, Result};
use std::process::ExitCode;

pub fn run(_args: CompareArgs) -> Result<ExitCode> {
    Err(Error::Unavailable(
        "`compare` is not implemented yet".into(),
    ))
}
