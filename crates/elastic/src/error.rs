//! The one error type of `elastic`.

/// Non-physical material data or mismatched fields.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ElasticError {
    /// A parameter is outside its physical range.
    #[error("invalid {name} = {value:?}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    /// A body the operator cannot represent, with the reason.
    #[error("{0}")]
    Unsupported(&'static str),
    /// A field does not have the operator's shape `(ny, nx)`.
    #[error("{what} has shape {got:?}, the operator expects {expected:?}")]
    ShapeMismatch {
        what: &'static str,
        expected: (usize, usize),
        got: (usize, usize),
    },
}

pub type Result<T> = std::result::Result<T, ElasticError>;
