//! Igor binary wave, version 5 (`.ibw`), as Asylum Research AFMs write it: a 64-byte header
//! (version, checksum, the sizes of the wave, formula, note, extended units and dimension
//! labels), a 320-byte wave header (points per dimension `nDim`, the spacing `sfA`, the data
//! type, 4-character units) and the data, the first dimension varying fastest; after it the
//! formula, the note, the extended units and the dimension labels (32 bytes each, the first
//! naming the dimension). A 3-D wave `(x, y, channel)` holds one image a channel, named by the
//! third dimension's labels; a 1-D wave is a line scan. Byte order from the version field. Channels in a length unit whose
//! name says height (`Height`, `ZSensor`) are heights: Asylum gives every channel the unit of
//! the first, so the unit alone cannot tell.

use super::{Channel, Layer, length_unit};
use crate::error::{Result, SurfError};
use ndarray::Array2;
use std::path::Path;

const BIN_HEADER: usize = 64;
const WAVE_HEADER: usize = 320;
const LABEL: usize = 32;

pub(super) fn layers<'a>(bytes: &'a [u8], path: &Path) -> Result<Vec<Layer<'a>>> {
    let bad = |m: String| SurfError::parse(path, None, m);
    if bytes.len() < BIN_HEADER + WAVE_HEADER {
        return Err(bad("not an Igor binary wave (shorter than its headers)".into()));
    }
    let little = match (bytes[0], bytes[1]) {
        (5, 0) => true,
        (0, 5) => false,
        _ => {
            return Err(bad(
                "not an Igor binary wave of version 5 (only version 5 is read)".into(),
            ));
        }
    };
    let at = Bytes { bytes, little };
    let size = |o: usize| at.u32_at(o) as usize;
    let (wave, formula, note, data_units_size) = (size(4), size(8), size(12), size(16));
    let dim_units_size: Vec<usize> = (0..4).map(|d| size(20 + 4 * d)).collect();
    let dim_labels_size: Vec<usize> = (0..4).map(|d| size(36 + 4 * d)).collect();
    let w = BIN_HEADER;
    let dims: Vec<usize> = (0..4).map(|d| size(w + 68 + 4 * d)).collect();
    let (nx, ny, layers_count) = match dims.as_slice() {
        [nx, 0, 0, 0] => (*nx, 1, 1),
        [nx, ny, 0, 0] => (*nx, *ny, 1),
        [nx, ny, nc, 0] => (*nx, *ny, *nc),
        _ => {
            return Err(bad(format!(
                "a wave of dimensions {dims:?} (1-D to 3-D are read)"
            )));
        }
    };
    let kind = at.i16_at(w + 16);
    let width = match kind {
        0x10 => 2,
        2 | 0x20 => 4,
        4 => 8,
        t => {
            return Err(bad(format!(
                "data type {t:#x} (32- or 64-bit float, 16- or 32-bit integer are read)"
            )));
        }
    };
    let data = BIN_HEADER + WAVE_HEADER;
    let image = nx.checked_mul(ny).filter(|&n| n >= 1);
    let needed = image
        .and_then(|n| n.checked_mul(layers_count))
        .and_then(|n| n.checked_mul(width))
        .filter(|&n| data + n <= bytes.len() && wave >= WAVE_HEADER + n)
        .ok_or_else(|| {
            bad(format!(
                "{nx} x {ny} x {layers_count} values of {width} bytes do not fit in a file of {} bytes",
                bytes.len()
            ))
        })?;
    let image = image.expect("checked");
    // Units: the extended units after the data replace the 4-character ones when present.
    let mut cursor = (BIN_HEADER + wave).saturating_add(formula).saturating_add(note);
    let mut section = |n: usize| {
        let s = bytes.get(cursor..cursor.saturating_add(n)).unwrap_or(&[]);
        cursor = cursor.saturating_add(n);
        s
    };
    let data_unit = match section(data_units_size) {
        [] => text(&bytes[w + 148..w + 152]),
        extended => text(extended),
    };
    let dim_unit: Vec<String> = (0..4)
        .map(|d| match section(dim_units_size[d]) {
            [] => text(&bytes[w + 152 + 4 * d..w + 156 + 4 * d]),
            extended => text(extended),
        })
        .collect();
    let labels: Vec<Vec<String>> = (0..4)
        .map(|d| section(dim_labels_size[d]).chunks(LABEL).map(text).collect())
        .collect();
    let lateral = |d: usize| {
        let unit = &dim_unit[d];
        length_unit(unit).ok_or_else(|| bad(format!("dimension {d} is in '{unit}', not a length")))
    };
    let length_x = nx as f64
        * super::header(
            path,
            "x spacing (sfA[0])",
            at.f64_at(w + 84).abs(),
            super::Number::Size,
        )?
        * lateral(0)?;
    // A line scan (one row) has no extent along y.
    let length_y = if ny > 1 {
        Some(
            ny as f64
                * super::header(
                    path,
                    "y spacing (sfA[1])",
                    at.f64_at(w + 92).abs(),
                    super::Number::Size,
                )?
                * lateral(1)?,
        )
    } else {
        None
    };
    let metres = length_unit(&data_unit).filter(|_| !data_unit.is_empty());
    let values = &bytes[data..data + needed];
    Ok((0..layers_count)
        .map(|c| {
            let name = labels[2]
                .get(c + 1)
                .filter(|l| !l.is_empty())
                .cloned()
                .unwrap_or_else(|| format!("channel {c}"));
            let lower = name.to_ascii_lowercase();
            let heights = layers_count == 1
                || ["height", "zsensor", "topograph"]
                    .iter()
                    .any(|n| lower.contains(n));
            let scale = metres.unwrap_or(1.0);
            let raw = &values[c * image * width..(c + 1) * image * width];
            Layer {
                channel: Channel {
                    name,
                    nx,
                    ny,
                    length_x: Some(length_x),
                    length_y,
                    unit: data_unit.clone(),
                    height: metres.is_some() && heights,
                },
                values: Box::new(move || {
                    let value = |k: usize| decode(kind, &raw[k * width..(k + 1) * width], little) * scale;
                    // x varies fastest; the last column of y is our y = 0, as SurfaceTopography
                    // and Gwyddion orient these images.
                    Ok(Array2::from_shape_fn((ny, nx), |(j, i)| {
                        value(i + nx * (ny - 1 - j))
                    }))
                }),
            }
        })
        .collect())
}

/// A wave's bytes in the file's byte order.
struct Bytes<'a> {
    bytes: &'a [u8],
    little: bool,
}

impl Bytes<'_> {
    fn u32_at(&self, o: usize) -> u32 {
        let b: [u8; 4] = self.bytes[o..o + 4].try_into().expect("4 bytes");
        if self.little {
            u32::from_le_bytes(b)
        } else {
            u32::from_be_bytes(b)
        }
    }

    fn i16_at(&self, o: usize) -> i16 {
        let b = [self.bytes[o], self.bytes[o + 1]];
        if self.little {
            i16::from_le_bytes(b)
        } else {
            i16::from_be_bytes(b)
        }
    }

    fn f64_at(&self, o: usize) -> f64 {
        let b: [u8; 8] = self.bytes[o..o + 8].try_into().expect("8 bytes");
        if self.little {
            f64::from_le_bytes(b)
        } else {
            f64::from_be_bytes(b)
        }
    }
}

/// A NUL-terminated Latin-1 string, trimmed.
fn text(b: &[u8]) -> String {
    b.iter()
        .take_while(|&&c| c != 0)
        .map(|&c| c as char)
        .collect::<String>()
        .trim()
        .to_string()
}

/// One value of Igor type `kind` (checked: f32, f64, i16, i32) from its bytes.
fn decode(kind: i16, b: &[u8], little: bool) -> f64 {
    let mut a = [0u8; 8];
    a[..b.len()].copy_from_slice(b);
    if !little {
        a[..b.len()].reverse();
    }
    match kind {
        2 => f32::from_le_bytes([a[0], a[1], a[2], a[3]]) as f64,
        4 => f64::from_le_bytes(a),
        0x10 => i16::from_le_bytes([a[0], a[1]]) as f64,
        _ => i32::from_le_bytes([a[0], a[1], a[2], a[3]]) as f64,
    }
}
