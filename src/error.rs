//! One error type for the library. Input errors always say where (file, line or JSON path,
//! plane/component) and why, so the CLI can print them as they are.
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Malformed or invalid input. `location` is already formatted, e.g.
    /// `data/x.csl:12: plane 3, component 1` or `in.json: $.planes[2].contours[0]`.
    #[error("{location}: {reason}")]
    Input { location: String, reason: String },

    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    /// A geometric computation could not produce a valid result (never for valid input: a bug).
    #[error("geometry: {0}")]
    Geometry(String),

    /// A capability that is not built into this binary (e.g. the TetGen oracle without the feature).
    #[error("not available: {0}")]
    Unavailable(String),
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    pub fn input(location: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::Input {
            location: location.into(),
            reason: reason.into(),
        }
    }
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}
