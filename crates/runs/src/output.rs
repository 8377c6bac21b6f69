//! The one way the command line writes a run's files: whole or not at all
//! ([`surfgen::io::atomically`]: written beside their place, then renamed into it, so that a
//! killed run leaves the old file or the new one, never half of one), and never a field that is
//! not finite (refused, naming it). Plots are written the same way by `plot`, which also
//! refuses to map a field that is not finite.

use anyhow::{Context, Result, bail};
use ndarray::Array2;
use std::path::Path;

/// Writes `text` to `path`, whole or not at all.
pub fn text(path: &Path, text: &str) -> Result<()> {
    surfgen::io::atomically(path, |p| {
        std::fs::write(p, text).with_context(|| format!("writing {}", path.display()))
    })
}

/// Refuses a field that holds a NaN or an infinity, naming it and the first such cell.
pub fn finite(name: &str, field: &Array2<f64>) -> Result<()> {
    if let Some(((row, col), v)) = field.indexed_iter().find(|(_, v)| !v.is_finite()) {
        bail!("{name} holds {v} at row {row}, column {col}: a field that is not finite is not written");
    }
    Ok(())
}

/// Writes the field `name` as `dir/name.npy`, whole or not at all, if it is finite.
pub fn field(dir: &Path, name: &str, field: &Array2<f64>) -> Result<()> {
    finite(name, field)?;
    let path = dir.join(format!("{name}.npy"));
    surfgen::io::write_npy(field, &path).with_context(|| format!("writing {}", path.display()))
}
