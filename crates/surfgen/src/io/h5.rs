//! HDF5 (`.h5`, `.hdf5`, and Zygo's `.datx`), read with the pure-Rust `hdf5-pure`: every
//! numeric dataset of two dimensions (or one: a line scan), in any group, is a channel named by
//! its path (the contact-mechanics challenge's files hold one, `surface`; Zygo's,
//! `Measurement/Surface`). A dataset's `Unit` attribute (a length unit) gives its heights' unit
//! and its `No Data` attribute the value of unmeasured points, as Zygo writes them; HDF5 has no
//! convention for the lateral size (Zygo's sits in a compound attribute `hdf5-pure` does not
//! decode), so it comes from [`ReadOptions`] like a plain matrix's. The first index is y, as
//! NumPy and h5py store a `(ny, nx)` array.

use super::length_unit;
use super::{Channel, Layer};
use crate::error::{Result, SurfError};
use hdf5_pure::{AttrValue, DType, File, Group};
use ndarray::Array2;
use std::path::Path;

/// Groups deeper than this are not searched; more datasets than this are not listed.
const DEPTH: usize = 8;
const MOST: usize = 1000;

pub(super) fn layers<'a>(bytes: &'a [u8], path: &Path) -> Result<Vec<Layer<'a>>> {
    let bad = |m: String| SurfError::parse(path, None, m);
    if !bytes.starts_with(b"\x89HDF\r\n\x1a\n") {
        return Err(bad("not an HDF5 file (no HDF5 signature at its start)".into()));
    }
    let file = std::rc::Rc::new(File::from_bytes(bytes.to_vec()).map_err(|e| bad(format!("HDF5: {e}")))?);
    let mut found = Vec::new();
    walk(&file.root(), "", 0, &mut found).map_err(|e| bad(format!("HDF5: {e}")))?;
    found.sort();
    let mut layers = Vec::new();
    for name in found {
        let dataset = file
            .dataset(&name)
            .map_err(|e| bad(format!("HDF5 {name}: {e}")))?;
        let shape = dataset.shape().map_err(|e| bad(format!("HDF5 {name}: {e}")))?;
        let numeric = matches!(
            dataset.dtype(),
            Ok(DType::F32
                | DType::F64
                | DType::I8
                | DType::I16
                | DType::I32
                | DType::I64
                | DType::U8
                | DType::U16
                | DType::U32
                | DType::U64)
        );
        // A 1-D dataset is a line scan: one row.
        let (ny, nx) = match shape[..] {
            [n] => (1, n),
            [ny, nx] => (ny, nx),
            _ => continue,
        };
        let (nx, ny) = (usize::try_from(nx).unwrap_or(0), usize::try_from(ny).unwrap_or(0));
        // A compressed dataset may inflate; bound it as a zip bomb is bounded.
        if !numeric || nx == 0 || ny == 0 || nx.saturating_mul(ny) / 1100 > bytes.len() {
            continue;
        }
        let attrs = dataset.attrs().unwrap_or_default();
        let unit = attrs.get("Unit").and_then(AttrValue::as_str).map(str::to_string);
        // No unit: heights in the user's unit; an empty or other unit: not heights.
        let scale = match unit.as_deref() {
            Some("") => None,
            Some(u) => length_unit(u),
            None => Some(1.0),
        };
        let no_data = attrs
            .get("No Data")
            .and_then(|v| v.as_f64().or_else(|| v.to_f64s()?.first().copied()));
        let (what, file, at) = (name.clone(), file.clone(), path.to_path_buf());
        layers.push(Layer {
            channel: Channel {
                name,
                nx,
                ny,
                length_x: None,
                length_y: None,
                unit: unit.clone().unwrap_or_else(|| "unstated".into()),
                height: scale.is_some(),
            },
            values: Box::new(move || {
                let values = file
                    .dataset(&what)
                    .and_then(|d| d.read_f64())
                    .map_err(|e| SurfError::parse(&at, None, format!("HDF5 {what}: {e}")))?;
                let scale = scale.unwrap_or(1.0);
                let values = values
                    .into_iter()
                    .map(|v| {
                        if Some(v) == no_data || v.is_nan() {
                            f64::NAN
                        } else {
                            v * scale
                        }
                    })
                    .collect();
                Array2::from_shape_vec((ny, nx), values)
                    .map_err(|_| SurfError::parse(&at, None, format!("HDF5 {what}: not {ny} x {nx} values")))
            }),
        });
    }
    if layers.is_empty() {
        return Err(bad(
            "no numeric dataset of one or two dimensions in the file".into()
        ));
    }
    Ok(layers)
}

/// The paths of the datasets under `group`, depth first.
fn walk(
    group: &Group,
    prefix: &str,
    depth: usize,
    found: &mut Vec<String>,
) -> std::result::Result<(), hdf5_pure::Error> {
    for name in group.datasets()? {
        if found.len() < MOST {
            found.push(format!("{prefix}{name}"));
        }
    }
    if depth < DEPTH {
        for name in group.groups()? {
            let child = group.group(&name)?;
            walk(&child, &format!("{prefix}{name}/"), depth + 1, found)?;
        }
    }
    Ok(())
}
