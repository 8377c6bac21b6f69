//! Molecular Imaging / Agilent PicoView images (`.mi`): a text header of lines holding a key in
//! the first 14 characters and its value after them (`xPixels`, `yPixels`, `xLength` and
//! `yLength` [m], then a `bufferLabel` block a channel with its `bufferRange` and
//! `bufferUnit`), ended by `data BINARY` (i16) or `data BINARY_32` (i32), then each channel's
//! `xPixels * yPixels` little-endian values in turn, x varying fastest, the first row the
//! image's top. A value is `raw * bufferRange / 2^(bits - 1)` in `bufferUnit`. The height
//! channel (`Topography`, else the first in a length unit) is read.

use super::{ReadOptions, Surface, length_unit};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use ndarray::{Array2, s};
use std::path::Path;

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Surface> {
    let bytes = std::fs::read(path).map_err(|e| SurfError::io(path, e))?;
    let bad = |m: String| SurfError::parse(path, None, m);
    let mut header: Vec<(String, String)> = Vec::new();
    let mut at = 0;
    let mut bits = None;
    for line in bytes.split(|&b| b == b'\n') {
        at += line.len() + 1;
        let text = String::from_utf8_lossy(line);
        let text = text.trim_end_matches('\r');
        let split = text.char_indices().nth(14).map_or(text.len(), |(i, _)| i);
        let (key, value) = text.split_at(split);
        let (key, value) = (key.trim(), value.trim());
        if key == "data" {
            bits = Some(match value {
                "BINARY" => 16,
                "BINARY_32" => 32,
                other => {
                    return Err(bad(format!(
                        "data stored as '{other}' are not read (BINARY or BINARY_32)"
                    )));
                }
            });
            break;
        }
        header.push((key.to_string(), value.to_string()));
        if header.len() > 100_000 {
            break;
        }
    }
    if header.first().map(|(k, v)| (k.as_str(), v.as_str())) != Some(("fileType", "Image")) {
        return Err(bad(
            "not a PicoView image (the first line is not 'fileType Image')".into(),
        ));
    }
    let bits = bits.ok_or_else(|| bad("the header does not end with 'data BINARY'".into()))?;
    let get = |key: &str| header.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str());
    let number = |key: &str| -> Result<f64> {
        let v = get(key).ok_or_else(|| bad(format!("the header lacks {key}")))?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| bad(format!("cannot read {key} '{v}'")))
    };
    let (nx, ny) = (number("xPixels")? as usize, number("yPixels")? as usize);
    // The channels, in order: label, range, unit.
    let mut channels: Vec<(String, Option<f64>, Option<String>)> = Vec::new();
    for (k, v) in &header {
        match k.as_str() {
            "bufferLabel" => channels.push((v.clone(), None, None)),
            "bufferRange" => {
                if let Some(c) = channels.last_mut() {
                    c.1 = v.parse().ok();
                }
            }
            "bufferUnit" => {
                if let Some(c) = channels.last_mut() {
                    c.2 = Some(v.clone());
                }
            }
            _ => {}
        }
    }
    let is_length =
        |c: &(String, Option<f64>, Option<String>)| c.2.as_deref().and_then(length_unit).is_some();
    let index = channels
        .iter()
        .position(|c| c.0 == "Topography" && is_length(c))
        .or_else(|| channels.iter().position(is_length))
        .ok_or_else(|| {
            let names: Vec<&str> = channels.iter().map(|c| c.0.as_str()).collect();
            bad(format!(
                "no height channel in a length unit (the channels: {})",
                names.join(", ")
            ))
        })?;
    let (label, range, unit) = &channels[index];
    let range = range.ok_or_else(|| bad(format!("channel {label} has no bufferRange")))?;
    let unit = unit.as_deref().and_then(length_unit).expect("a length channel");
    let size = bits / 8;
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n >= 1)
        .ok_or_else(|| bad(format!("{nx} x {ny} pixels")))?;
    let start = n
        .checked_mul(size * index)
        .and_then(|o| o.checked_add(at))
        .unwrap_or(usize::MAX);
    let end = start.saturating_add(n * size);
    if end > bytes.len() {
        return Err(bad(format!(
            "channel {} of {} ({label}): {nx} x {ny} values need {} bytes from byte {start}, the file has {}",
            index + 1,
            channels.len(),
            n * size,
            bytes.len()
        )));
    }
    let scale = range / 2f64.powi(bits as i32 - 1) * unit * options.unit;
    let values: Vec<f64> = bytes[start..end]
        .chunks_exact(size)
        .map(|c| match size {
            2 => i16::from_le_bytes([c[0], c[1]]) as f64,
            _ => i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
        } * scale)
        .collect();
    // The first row stored is the image's top: ours is y = 0.
    let heights = Array2::from_shape_vec((ny, nx), values)
        .expect("counted")
        .slice(s![..;-1, ..])
        .to_owned();
    let grid = Grid::new(
        nx,
        ny,
        number("xLength")? * options.unit,
        number("yLength")? * options.unit,
    )
    .map_err(|e| bad(e.to_string()))?;
    Surface::new(heights, grid, options.periodic)
}
