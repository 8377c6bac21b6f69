//! The one error type of `solver`.

/// Bad input to a contact problem, or a breakdown of the numerics.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolverError {
    /// A parameter is outside its range.
    #[error("invalid {name} = {value:?}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: String,
    },
    /// A field does not match the operator's grid.
    #[error("{what} has shape {got:?}, the grid is {expected:?}")]
    ShapeMismatch {
        what: &'static str,
        expected: (usize, usize),
        got: (usize, usize),
    },
    /// A height or gap is NaN or infinite.
    #[error("non-finite {what} {value} at row {row}, column {col}")]
    NonFinite {
        what: &'static str,
        row: usize,
        col: usize,
        value: f64,
    },
    /// A solve's result holds a NaN or an infinity: the problem's numbers overflow double
    /// precision. A result that is not finite is never reported as a solution.
    #[error(
        "the solve's {what} is {value}, not a finite number: the problem's numbers overflow double \
         precision (check the units of the heights, lengths, modulus and loads)"
    )]
    NonFiniteResult { what: String, value: f64 },
    /// The problem lacks a part.
    #[error("the problem needs {0}")]
    Incomplete(&'static str),
    /// The chosen method cannot solve this problem (the message says what can).
    #[error("{0}")]
    Unsupported(String),
    /// The elastic operator refused its input.
    #[error(transparent)]
    Elastic(#[from] elastic::ElasticError),
    /// The adhesive law refused its input.
    #[error(transparent)]
    Adhesion(#[from] ljadhesion::AdhesionError),
}

pub type Result<T> = std::result::Result<T, SolverError>;

pub(crate) fn invalid(name: &'static str, value: f64, reason: impl Into<String>) -> SolverError {
    SolverError::InvalidParameter {
        name,
        value,
        reason: reason.into(),
    }
}

/// Refuses an input field holding a NaN or an infinity, naming where.
pub(crate) fn finite(what: &'static str, field: ndarray::ArrayView2<f64>) -> Result<()> {
    match field.indexed_iter().find(|(_, v)| !v.is_finite()) {
        Some(((row, col), &value)) => Err(SolverError::NonFinite {
            what,
            row,
            col,
            value,
        }),
        None => Ok(()),
    }
}

/// Refuses a result with a non-finite field or number, naming the first one found.
pub(crate) fn finite_result(fields: &[(&str, &ndarray::Array2<f64>)], numbers: &[(&str, f64)]) -> Result<()> {
    if let Some((name, value)) = numbers.iter().find(|(_, v)| !v.is_finite()) {
        return Err(SolverError::NonFiniteResult {
            what: name.to_string(),
            value: *value,
        });
    }
    for (name, field) in fields {
        if let Some(((row, col), &value)) = field.indexed_iter().find(|(_, v)| !v.is_finite()) {
            return Err(SolverError::NonFiniteResult {
                what: format!("{name} at row {row}, column {col}"),
                value,
            });
        }
    }
    Ok(())
}
