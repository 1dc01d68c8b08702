use crate::CompareMethodsArgs;
use slice2solid::{Error, Result};
use std::process::ExitCode;

pub fn run(_args: CompareMethodsArgs) -> Result<ExitCode> {
    Err(Error::Unavailable(
        "`compare-methods` is not implemented yet".into(),
    ))
}
