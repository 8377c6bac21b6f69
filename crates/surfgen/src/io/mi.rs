//! Molecular Imaging / Agilent PicoView images (`.mi`): a text header of lines holding a key in
//! the first 14 characters and its value after them (`xPixels`, `yPixels`, `xLength` and
//! `yLength` [m], then a `bufferLabel` block a channel with its `bufferRange` and
//! `bufferUnit`), ended by `data BINARY` (i16) or `data BINARY_32` (i32), then each channel's
//! `xPixels * yPixels` little-endian values in turn, x varying fastest, the first row the
//! image's top. A value is `raw * bufferRange / 2^(bits - 1)` in `bufferUnit`. Channels in a
//! length unit are heights.

use super::{Channel, Layer, Number, length_unit, rows_from_top};
use crate::error::{Result, SurfError};
use std::path::Path;

pub(super) fn layers<'a>(bytes: &'a [u8], path: &Path) -> Result<Vec<Layer<'a>>> {
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
    let size = bits / 8;
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n >= 1)
        .ok_or_else(|| bad(format!("{nx} x {ny} pixels")))?;
    let (lx, ly) = (
        super::header(path, "xLength", number("xLength")?, Number::Size)?,
        super::header(path, "yLength", number("yLength")?, Number::Size)?,
    );
    let count = channels.len();
    let mut layers = Vec::new();
    for (index, (label, range, unit)) in channels.into_iter().enumerate() {
        let start = n
            .checked_mul(size * index)
            .and_then(|o| o.checked_add(at))
            .unwrap_or(usize::MAX);
        let end = start.saturating_add(n * size);
        if end > bytes.len() {
            return Err(bad(format!(
                "channel {} of {count} ({label}): {nx} x {ny} values need {} bytes from byte {start}, the file has {}",
                index + 1,
                n * size,
                bytes.len()
            )));
        }
        let metres = unit.as_deref().filter(|u| !u.is_empty()).and_then(length_unit);
        let range = range.ok_or_else(|| bad(format!("channel {label} has no bufferRange")))?;
        let range = super::header(
            path,
            &format!("channel {label}'s bufferRange"),
            range,
            Number::Scale,
        )?;
        let scale = range / 2f64.powi(bits as i32 - 1) * metres.unwrap_or(1.0);
        let raw = &bytes[start..end];
        layers.push(Layer {
            channel: Channel {
                name: label,
                nx,
                ny,
                length_x: Some(lx),
                length_y: Some(ly),
                unit: unit.unwrap_or_default(),
                height: metres.is_some(),
            },
            values: Box::new(move || {
                let values: Vec<f64> = raw
                        .chunks_exact(size)
                        .map(|c| match size {
                            2 => i16::from_le_bytes([c[0], c[1]]) as f64,
                            _ => i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
                        } * scale)
                        .collect();
                Ok(rows_from_top(ny, nx, values))
            }),
        });
    }
    Ok(layers)
}
