//! The one error type of `ljadhesion`.

/// Bad parameters or fields given to an adhesive law.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AdhesionError {
    /// A law's parameter is outside its physical range.
    #[error("invalid {name} = {value:?}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    /// The gap and output fields differ in shape.
    #[error("shape mismatch: gap is {gap:?}, output is {out:?}")]
    ShapeMismatch {
        gap: (usize, usize),
        out: (usize, usize),
    },
    /// A gap is NaN or infinite.
    #[error("non-finite gap {value} at row {row}, column {col}")]
    NonFiniteGap { row: usize, col: usize, value: f64 },
}

pub type Result<T> = std::result::Result<T, AdhesionError>;

pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(AdhesionError::InvalidParameter {
            name,
            value,
            reason: "must be finite and > 0",
        })
    }
}
