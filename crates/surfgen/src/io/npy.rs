//! `.npy` heights with a JSON sidecar.

use super::{Metadata, ReadOptions, Surface, sidecar_path};
use crate::error::{Result, SurfError};
use ndarray::Array2;
use ndarray_npy::{ReadNpyExt, WriteNpyExt};
use std::fs::File;
use std::io::{BufReader, BufWriter, Write};
use std::path::Path;

pub(super) fn read_sidecar(path: &Path) -> Result<Option<Metadata>> {
    let side = sidecar_path(path);
    if !side.exists() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&side).map_err(|e| SurfError::io(&side, e))?;
    let meta: Metadata =
        serde_json::from_str(&text).map_err(|e| SurfError::parse(&side, Some(e.line()), e.to_string()))?;
    Ok(Some(meta))
}

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Surface> {
    let file = File::open(path).map_err(|e| SurfError::io(path, e))?;
    let heights = Array2::<f64>::read_npy(BufReader::new(file))
        .map_err(|e| SurfError::parse(path, None, format!("not a 2-D little-endian f64 .npy array: {e}")))?;
    let (ny, nx) = heights.dim();
    let (grid, periodic) = match read_sidecar(path)? {
        Some(meta) => {
            if meta.grid.shape() != (ny, nx) {
                return Err(SurfError::parse(
                    &sidecar_path(path),
                    None,
                    format!(
                        "sidecar grid (ny, nx) = {:?} does not match the array's {:?}",
                        meta.grid.shape(),
                        (ny, nx)
                    ),
                ));
            }
            (meta.grid, meta.periodic)
        }
        None => (options.grid_for(path, ny, nx)?, options.periodic),
    };
    let mut heights = heights;
    if options.unit != 1.0 {
        heights.mapv_inplace(|h| h * options.unit);
    }
    Surface::new(heights, grid, periodic)
}

pub(super) fn write(surface: &Surface, path: &Path, metadata: Option<&Metadata>) -> Result<()> {
    let file = File::create(path).map_err(|e| SurfError::io(path, e))?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    surface
        .heights
        .write_npy(&mut w)
        .map_err(|e| SurfError::io(path, std::io::Error::other(e)))?;
    w.flush().map_err(|e| SurfError::io(path, e))?;
    let own;
    let meta = match metadata {
        Some(m) => m,
        None => {
            own = Metadata::of(surface);
            &own
        }
    };
    let side = sidecar_path(path);
    let json = serde_json::to_string_pretty(meta).expect("metadata serialises");
    std::fs::write(&side, json + "\n").map_err(|e| SurfError::io(&side, e))
}
