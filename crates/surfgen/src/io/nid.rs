//! Nanosurf (`.nid`): an INI-style text header (`[Section]` and `Key=Value` lines) ended by
//! `#!`, then the channels' binary data in the order the `[DataSet]` section lists them
//! (`Gr0-Ch0=DataSet-0:0`, ..., group by group). A channel's section gives `Points` and
//! `Lines`, the lateral ranges `Dim0Range`, `Dim1Range` [`Dim0Unit`], its quantity's `Dim2Min`,
//! `Dim2Range` and `Dim2Unit`, and the storage (`SaveBits`, `SaveSign`, little-endian); a
//! value is `Dim2Min + (raw - smallest raw) * Dim2Range / 2^bits`, rows stored from the
//! image's top. Channels in a length unit are heights.

use super::{Channel, Layer, Number, header, length_unit, rows_from_top};
use crate::error::{Result, SurfError};
use std::collections::HashMap;
use std::path::Path;

pub(super) fn layers<'a>(bytes: &'a [u8], path: &Path) -> Result<Vec<Layer<'a>>> {
    let bad = |m: String| SurfError::parse(path, None, m);
    if !bytes.starts_with(b"[DataSet]") {
        return Err(bad(
            "not a Nanosurf file (it does not begin with [DataSet])".into()
        ));
    }
    let end = bytes
        .windows(2)
        .position(|w| w == b"#!")
        .ok_or_else(|| bad("the header is not ended by #!".into()))?;
    let text = String::from_utf8_lossy(&bytes[..end]);
    let mut sections: HashMap<String, HashMap<String, String>> = HashMap::new();
    let mut current = String::new();
    for line in text.lines() {
        let line = line.trim();
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            current = name.to_string();
        } else if let Some((k, v)) = line.split_once('=') {
            sections
                .entry(current.clone())
                .or_default()
                .insert(k.trim().to_string(), v.trim().to_string());
        }
    }
    let set = sections
        .get("DataSet")
        .ok_or_else(|| bad("no [DataSet] section".into()))?;
    let int = |map: &HashMap<String, String>, key: &str| -> Option<usize> { map.get(key)?.parse().ok() };
    // The channels in stored order: group by group, channel numbers ascending.
    let mut channels = Vec::new();
    for g in 0..int(set, "GroupCount").unwrap_or(0).min(1000) {
        for c in 0..int(set, &format!("Gr{g}-Count")).unwrap_or(0).min(1000) {
            if let Some(name) = set.get(&format!("Gr{g}-Ch{c}")) {
                channels.push(name.clone());
            }
        }
    }
    let data = &bytes[end + 2..];
    let mut offset = 0usize;
    let mut layers = Vec::new();
    for name in channels {
        let ch = sections
            .get(&name)
            .ok_or_else(|| bad(format!("the channel [{name}] is not described")))?;
        let (nx, ny) = (int(ch, "Points").unwrap_or(0), int(ch, "Lines").unwrap_or(0));
        let bits = int(ch, "SaveBits").unwrap_or(32);
        if !matches!(bits, 16 | 32) {
            return Err(bad(format!("[{name}]: SaveBits {bits} (16 or 32 are read)")));
        }
        let size = nx
            .checked_mul(ny)
            .and_then(|n| n.checked_mul(bits / 8))
            .filter(|&s| s >= 1 && offset + s <= data.len())
            .ok_or_else(|| bad(format!("[{name}]: {nx} x {ny} points cannot fit in the file")))?;
        let raw = &data[offset..offset + size];
        offset += size;
        let unit = ch.get("Dim2Unit").cloned().unwrap_or_default();
        let metres = length_unit(&unit).filter(|_| !unit.is_empty());
        let number = |key: &str| -> Result<f64> {
            ch.get(key)
                .and_then(|v| v.split_whitespace().next()?.parse::<f64>().ok())
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(format!("[{name}] lacks a number {key}")))
        };
        let lateral = |key: &str| -> Result<f64> {
            let unit = ch.get(key).map(String::as_str).unwrap_or("m");
            length_unit(unit).ok_or_else(|| bad(format!("[{name}]: unknown unit {key} '{unit}'")))
        };
        // Checked when the channel is read: a listed channel may lack them, but one it gives
        // must be a size.
        let length = |range: &str, unit: &str| Some(number(range).ok()? * lateral(unit).ok()?);
        let (length_x, length_y) = (length("Dim0Range", "Dim0Unit"), length("Dim1Range", "Dim1Unit"));
        let bad_length = ["Dim0Range", "Dim1Range"].into_iter().find_map(|key| {
            ch.get(key)?;
            match number(key) {
                Err(e) => Some(e),
                Ok(v) => header(path, &format!("[{name}] {key}"), v, Number::Size).err(),
            }
        });
        let signed = ch.get("SaveSign").is_none_or(|s| s == "Signed");
        let smallest = if signed {
            -(2f64.powi(bits as i32 - 1))
        } else {
            0.0
        };
        let (min, range) = (number("Dim2Min"), number("Dim2Range"));
        let z = metres.unwrap_or(1.0);
        let file = path.to_path_buf();
        layers.push(Layer {
            channel: Channel {
                name: match (ch.get("Dim2Name"), ch.get("Frame")) {
                    (Some(q), Some(frame)) => format!("{q} ({frame})"),
                    (Some(q), None) => q.clone(),
                    _ => name.clone(),
                },
                nx,
                ny,
                length_x,
                length_y,
                unit,
                height: metres.is_some(),
            },
            values: Box::new(move || {
                let (min, range) = (min?, range?);
                header(&file, &format!("[{name}] Dim2Range"), range, Number::Scale)?;
                super::offset(
                    &file,
                    &format!("[{name}] Dim2Min"),
                    min,
                    "Dim2Range",
                    range / 2f64.powi(bits as i32),
                )?;
                if let Some(e) = bad_length {
                    return Err(e);
                }
                let scale = range / 2f64.powi(bits as i32);
                let values: Vec<f64> = raw
                    .chunks_exact(bits / 8)
                    .map(|c| {
                        let v = match (bits, signed) {
                            (16, true) => i16::from_le_bytes([c[0], c[1]]) as f64,
                            (16, false) => u16::from_le_bytes([c[0], c[1]]) as f64,
                            (_, true) => i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
                            (_, false) => u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
                        };
                        (min + (v - smallest) * scale) * z
                    })
                    .collect();
                Ok(rows_from_top(ny, nx, values))
            }),
        });
    }
    Ok(layers)
}
