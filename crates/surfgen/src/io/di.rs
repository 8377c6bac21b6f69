//! Bruker / Veeco / Digital Instruments Nanoscope (`.di`, `.spm`, `.001`, ...), version 4.3 and
//! later: a text header of `\Key: value` lines in `\*Section` lists, ended by `\*File list end`,
//! then the images' binary data. Each `\*Ciao image list` is a channel: `Samps/line`,
//! `Number of lines`, `Scan Size: sx sy unit` (`~m` is µm), `Data offset`, `Bytes/pixel` (2 or
//! 4, little-endian, line by line from the image's top) and `@2:Z scale: V [Sens. Q] (... V/LSB)
//! hard V`. A value is `raw * hard / 2^16 * soft` (a 4-byte value first divided by 2^16),
//! where `soft` is the scanner's `@Sens. Q: V soft unit/V`; a channel is heights when that unit
//! is a length.

use super::{Channel, Layer, Number, header, length_unit, rows_from_top};
use crate::error::{Result, SurfError};
use std::collections::HashMap;
use std::path::Path;

type Section = HashMap<String, String>;

pub(super) fn layers<'a>(bytes: &'a [u8], path: &Path) -> Result<Vec<Layer<'a>>> {
    let bad = |m: String| SurfError::parse(path, None, m);
    if !bytes.starts_with(b"\\*File list") {
        return Err(bad(
            "not a Nanoscope file (it does not begin with \\*File list)".into()
        ));
    }
    let mut sections: Vec<(String, Section)> = Vec::new();
    for line in bytes.split(|&b| b == b'\n').take(100_000) {
        let line: String = line.iter().map(|&b| b as char).collect(); // Latin-1
        let line = line.trim();
        if line.eq_ignore_ascii_case("\\*File list end") {
            break;
        }
        if let Some(name) = line.strip_prefix("\\*") {
            sections.push((name.to_ascii_lowercase(), Section::new()));
        } else if let Some(entry) = line.strip_prefix('\\') {
            // Keys hold colons (`@2:Z scale`): the value follows the first ": ".
            let (key, value) = entry
                .split_once(": ")
                .unwrap_or((entry.strip_suffix(':').unwrap_or(entry), ""));
            if let Some((_, section)) = sections.last_mut() {
                section.insert(key.trim().to_ascii_lowercase(), value.trim().to_string());
            }
        } else {
            break;
        }
    }
    let mut scanner = Section::new();
    for (name, section) in &sections {
        if name == "scanner list" || name == "ciao scan list" {
            scanner.extend(section.clone());
        }
    }
    let mut layers = Vec::new();
    for (_, image) in sections.iter().filter(|(n, _)| n == "ciao image list") {
        let index = layers.len();
        let get = |key: &str| {
            image
                .get(key)
                .map(String::as_str)
                .ok_or_else(|| bad(format!("image {index} lacks \\{key}")))
        };
        let count = |key: &str| -> Result<usize> {
            let v = get(key)?;
            v.parse()
                .map_err(|_| bad(format!("image {index}: cannot read \\{key}: {v}")))
        };
        let name = image_name(get("@2:image data").unwrap_or("S [Image] \"Image\""));
        let (nx, ny, offset, size) = (
            count("samps/line")?,
            count("number of lines")?,
            count("data offset")?,
            count("bytes/pixel")?,
        );
        if !matches!(size, 2 | 4) {
            return Err(bad(format!(
                "image {index} ({name}): {size} bytes a pixel (2 or 4 are read)"
            )));
        }
        let end = nx
            .checked_mul(ny)
            .and_then(|n| n.checked_mul(size))
            .and_then(|n| n.checked_add(offset))
            .filter(|&e| nx * ny >= 1 && e <= bytes.len())
            .ok_or_else(|| {
                bad(format!(
                    "image {index} ({name}): {nx} x {ny} pixels from byte {offset} do not fit in a file of {} bytes",
                    bytes.len()
                ))
            })?;
        // The image's own byte count, where the header gives it, must be its pixels'.
        if let Some(length) = image.get("data length") {
            let length: usize = length
                .parse()
                .map_err(|_| bad(format!("image {index}: cannot read \\Data length: {length}")))?;
            if length != nx * ny * size {
                return Err(bad(format!(
                    "image {index} ({name}): \\Data length is {length} bytes, but \\Samps/line {nx} x \\Number \
                     of lines {ny} x \\Bytes/pixel {size} is {} bytes",
                    nx * ny * size
                )));
            }
        }
        let scan = get("scan size")?;
        let (sx, sy, xy_unit) =
            scan_size(scan).ok_or_else(|| bad(format!("image {index}: cannot read \\Scan Size: {scan}")))?;
        for (side, v) in [("x", sx), ("y", sy)] {
            header(
                path,
                &format!("image {index}'s \\Scan Size along {side}"),
                v,
                Number::Size,
            )?;
        }
        // A channel whose scale cannot be read is listed, not read.
        let (scale, unit) =
            z_scale(get("@2:z scale").unwrap_or(""), &scanner).unwrap_or((f64::NAN, "unknown".into()));
        let metres = length_unit(&unit).filter(|_| !unit.is_empty());
        let scale = scale * metres.unwrap_or(1.0) / if size == 4 { 65536.0 } else { 1.0 };
        let raw = &bytes[offset..end];
        let file = path.to_path_buf();
        layers.push(Layer {
            channel: Channel {
                name,
                nx,
                ny,
                length_x: Some(sx * xy_unit),
                length_y: Some(sy * xy_unit),
                unit,
                height: metres.is_some(),
            },
            values: Box::new(move || {
                // A channel whose scale cannot be read is listed; read, its scale is named.
                header(
                    &file,
                    &format!("image {index}'s \\@2:Z scale (with its \\@Sens.)"),
                    scale,
                    Number::Scale,
                )?;
                let values: Vec<f64> = raw
                    .chunks_exact(size)
                    .map(|c| {
                        let v = if size == 2 {
                            i16::from_le_bytes([c[0], c[1]]) as f64
                        } else {
                            i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64
                        };
                        v * scale
                    })
                    .collect();
                Ok(rows_from_top(ny, nx, values))
            }),
        });
    }
    if layers.is_empty() {
        return Err(bad("no \\*Ciao image list in the header".into()));
    }
    Ok(layers)
}

/// `S [Height] "Height"` -> `Height`.
fn image_name(value: &str) -> String {
    value
        .split_once('[')
        .and_then(|(_, rest)| rest.split_once(']'))
        .map_or(value, |(name, _)| name)
        .to_string()
}

/// `500 500 nm` -> (500, 500, 1e-9); `10 10 ~m` is µm.
fn scan_size(value: &str) -> Option<(f64, f64, f64)> {
    let mut words = value.split_whitespace();
    let sx: f64 = words.next()?.parse().ok()?;
    let sy: f64 = words.next()?.parse().ok()?;
    let unit = words.next()?.replace('~', "µ");
    Some((sx, sy, length_unit(&unit)?)).filter(|(x, y, _)| x.is_finite() && y.is_finite())
}

/// `V [Sens. Zsens] (0.0050354 V/LSB) 2.910461 V` with the scanner's `@Sens. Zsens: V 20.8 nm/V`
/// -> (metres-or-units per raw count in `nm`, "nm").
fn z_scale(value: &str, scanner: &Section) -> Option<(f64, String)> {
    let rest = value.strip_prefix('V')?.trim_start();
    let (quantity, rest) = match rest.strip_prefix('[') {
        Some(r) => {
            let (q, r) = r.split_once(']')?;
            (Some(q), r)
        }
        None => (None, rest),
    };
    let rest = rest.split_once(')').map_or(rest, |(_, r)| r);
    let mut words = rest.split_whitespace();
    let hard: f64 = words.next()?.parse().ok()?;
    let hard_unit = words.next().unwrap_or("V");
    let Some(quantity) = quantity else {
        return Some((hard / 65536.0, hard_unit.to_string()));
    };
    let sens = scanner.get(&format!("@{}", quantity.to_ascii_lowercase()))?;
    let mut words = sens.strip_prefix('V')?.split_whitespace();
    let soft: f64 = words.next()?.parse().ok()?;
    // A sensitivity without a unit (`V 1.000`) leaves the hard value's unit.
    let Some((unit, per)) = words.next().and_then(|u| u.split_once('/')) else {
        return Some((hard / 65536.0 * soft, hard_unit.to_string()));
    };
    let ratio = if hard_unit == per {
        1.0
    } else {
        volts(hard_unit)? / volts(per)?
    };
    Some((hard * ratio / 65536.0 * soft, unit.replace('~', "µ")))
}

fn volts(unit: &str) -> Option<f64> {
    Some(match unit {
        "V" => 1.0,
        "mV" => 1e-3,
        "uV" | "µV" | "~V" => 1e-6,
        _ => return None,
    })
}
