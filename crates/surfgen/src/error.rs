//! The one error type of `surfgen`.

use std::path::PathBuf;

/// Everything that can go wrong in `surfgen`: bad parameters, and files that cannot be read or
/// written. Readers never return a half-read surface: they return one of these instead.
#[derive(Debug, thiserror::Error)]
pub enum SurfError {
    /// A parameter is outside its physical or numerical range.
    #[error("invalid {name} = {value:?}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: String,
    },
    /// An array does not have the shape its grid requires.
    #[error("shape mismatch: expected (ny, nx) = {expected:?}, got {got:?}")]
    ShapeMismatch {
        expected: (usize, usize),
        got: (usize, usize),
    },
    /// A height is NaN or infinite, or beyond [`crate::grid::MAX_LENGTH`] in magnitude.
    #[error(
        "height {value:?} m at row {row}, column {col}: heights must be finite and at most 1e100 m in \
         magnitude (their squares overflow double precision beyond)"
    )]
    NonFinite { row: usize, col: usize, value: f64 },
    /// A file could not be opened, read or written.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A file's content is malformed; `line` is 1-based where the format has lines.
    #[error("{}{}: {message}", path.display(), line.map(|l| format!(", line {l}")).unwrap_or_default())]
    Parse {
        path: PathBuf,
        line: Option<usize>,
        message: String,
    },
}

impl SurfError {
    pub(crate) fn invalid(name: &'static str, value: f64, reason: impl Into<String>) -> Self {
        SurfError::InvalidParameter {
            name,
            value,
            reason: reason.into(),
        }
    }

    pub(crate) fn parse(path: &std::path::Path, line: Option<usize>, message: impl Into<String>) -> Self {
        SurfError::Parse {
            path: path.to_path_buf(),
            line,
            message: message.into(),
        }
    }

    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        SurfError::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

/// Shorthand for `Result<T, SurfError>`.
pub type Result<T> = std::result::Result<T, SurfError>;
