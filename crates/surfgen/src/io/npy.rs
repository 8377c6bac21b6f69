//! `.npy` heights with a JSON sidecar.

use super::{Measurement, Metadata, ReadOptions, sidecar_path};
use crate::error::{Result, SurfError};
use ndarray::Array2;
use ndarray_npy::ReadNpyExt;
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

/// The data size an `.npy` header promises against the file's length, checked before reading
/// allocates it: a header claiming 100000 x 100000 values in a 32 KB file must be an error, not
/// an 80 GB allocation.
fn check_size(path: &Path, file: &mut File) -> Result<()> {
    use std::io::{Read, Seek, SeekFrom};
    let bad = |why: String| SurfError::parse(path, None, why);
    let length = file.metadata().map_err(|e| SurfError::io(path, e))?.len();
    let mut preamble = [0u8; 12];
    let got = file.read(&mut preamble).map_err(|e| SurfError::io(path, e))?;
    if got < 10 || &preamble[..6] != b"\x93NUMPY" {
        return Err(bad("not an .npy file (no NUMPY magic)".into()));
    }
    let (header_len, offset) = match preamble[6] {
        1 => (u16::from_le_bytes([preamble[8], preamble[9]]) as u64, 10),
        _ if got == 12 => (
            u32::from_le_bytes([preamble[8], preamble[9], preamble[10], preamble[11]]) as u64,
            12,
        ),
        v => return Err(bad(format!("unsupported .npy version {v}"))),
    };
    let mut header = vec![0u8; header_len.min(length.saturating_sub(offset)) as usize];
    file.seek(SeekFrom::Start(offset))
        .map_err(|e| SurfError::io(path, e))?;
    file.read_exact(&mut header).map_err(|e| SurfError::io(path, e))?;
    file.seek(SeekFrom::Start(0))
        .map_err(|e| SurfError::io(path, e))?;
    let header = String::from_utf8_lossy(&header);
    // The shape tuple, e.g. 'shape': (512, 512), ; a malformed one is left to the reader.
    let Some(shape) = header
        .split("'shape':")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .map(|t| t.trim().trim_start_matches('('))
    else {
        return Ok(());
    };
    let mut values: u64 = 1;
    for dim in shape.split(',').map(str::trim).filter(|d| !d.is_empty()) {
        let Ok(dim) = dim.parse::<u64>() else {
            return Ok(());
        };
        values = values.saturating_mul(dim);
    }
    let needed = (offset + header_len).saturating_add(values.saturating_mul(8));
    if needed > length {
        return Err(bad(format!(
            "the header claims a ({shape}) array of {values} values ({needed} bytes with the header), but the file \
             holds {length} bytes: truncated or corrupt"
        )));
    }
    Ok(())
}

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let mut file = File::open(path).map_err(|e| SurfError::io(path, e))?;
    check_size(path, &mut file)?;
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
    Measurement::new(heights, grid, periodic)
}

/// Writes an `.npy` (format 1.0) holding `heights` as little-endian f64 in C order. Written by
/// hand because the generic writer goes value by value and takes 3 times as long at 4096^2.
fn write_npy(heights: &Array2<f64>, w: &mut impl Write) -> std::io::Result<()> {
    let (ny, nx) = heights.dim();
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({ny}, {nx}), }}");
    // Magic (6) + version (2) + length (2) + header + '\n' must be a multiple of 64.
    let pad = 64 - (10 + header.len() + 1) % 64;
    header.extend(std::iter::repeat_n(' ', pad % 64));
    header.push('\n');
    w.write_all(b"\x93NUMPY\x01\x00")?;
    w.write_all(&(header.len() as u16).to_le_bytes())?;
    w.write_all(header.as_bytes())?;
    let standard = heights.as_standard_layout();
    let values = standard.as_slice().expect("standard layout");
    let mut buf = Vec::with_capacity(1 << 16);
    for chunk in values.chunks(1 << 13) {
        buf.clear();
        chunk.iter().for_each(|v| buf.extend_from_slice(&v.to_le_bytes()));
        w.write_all(&buf)?;
    }
    Ok(())
}

/// Writes any 2-D f64 field to `path` as `.npy`, without sidecar, whole or not at all.
pub fn write_array(field: &Array2<f64>, path: &Path) -> Result<()> {
    super::atomically(path, |p| {
        write_array_at(field, p).map_err(|e| SurfError::io(path, e))
    })
}

fn write_array_at(field: &Array2<f64>, path: &Path) -> std::io::Result<()> {
    let file = File::create(path)?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    write_npy(field, &mut w).and_then(|_| w.flush())
}
