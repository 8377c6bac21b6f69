//! MountainsMap documents (`.mnt`), as SurfaceTopography 1.27 documents their layout (Digital
//! Surf publishes none): an OLE compound file whose `ScopedContents` stream holds, after its
//! size (u64), a tree of entries (a tag u16, a size u64, then the value or nested entries; text
//! is the byte 4 and UTF-16). The main entry's `0x02BD` lists the document's objects (each
//! preceded by a size u64): a class number and a body. A measured surface (class 9012) holds a
//! surface data object (9062) whose measurement gives the lateral axes (a step with its unit,
//! the number of points), the height axis (a step a count, its unit, an origin in the display
//! unit), the heights (9049: the count of values, then their bytes in zlib blocks, each of its
//! offset and length in values and compressed size), and optionally a mask image with a border
//! of one pixel in which 9 marks a measured point. Heights are `count * step + origin`, stored
//! row by row, x fastest; every measured surface of the document is a channel.

use super::{Channel, Layer, Number, header, length_unit};
use crate::error::{Result, SurfError};
use ndarray::Array2;
use std::io::Read;
use std::path::Path;

const CLASS_SURFACE: u32 = 9012;
const CLASS_SURFACE_DATA: u32 = 9062;
const CLASS_MASK: u32 = 9056;
const CLASS_HEIGHTS: u32 = 9049;
const MEASURED: u8 = 9;

/// The entries `(tag, value)` of a value, each after a prefix of `prefix` bytes; `None` if the
/// bytes are not exactly a list of entries.
fn entries(b: &[u8], prefix: usize) -> Option<Vec<(u16, &[u8])>> {
    let mut out = Vec::new();
    let mut at = 0;
    while at < b.len() {
        let head = b.get(at + prefix..at + prefix + 10)?;
        let tag = u16::from_le_bytes([head[0], head[1]]);
        let size = usize::try_from(u64::from_le_bytes(head[2..10].try_into().ok()?)).ok()?;
        let start = at + prefix + 10;
        out.push((tag, b.get(start..start.checked_add(size)?)?));
        at = start + size;
    }
    Some(out)
}

/// The first value tagged `tag` among the entries of `b`.
fn child(b: &[u8], tag: u16) -> Option<&[u8]> {
    entries(b, 0)?
        .into_iter()
        .find(|(t, _)| *t == tag)
        .map(|(_, v)| v)
}

/// The value at a path of tags.
fn at<'a>(b: &'a [u8], path: &[u16]) -> Option<&'a [u8]> {
    path.iter().try_fold(b, |v, &tag| child(v, tag))
}

fn u32_of(b: &[u8]) -> Option<u32> {
    Some(u32::from_le_bytes(b.try_into().ok()?))
}

fn f64_of(b: &[u8]) -> Option<f64> {
    Some(f64::from_le_bytes(b.try_into().ok()?)).filter(|v| v.is_finite())
}

fn text(b: &[u8]) -> Option<String> {
    let rest = b.strip_prefix(&[4])?;
    let units: Vec<u16> = rest
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    Some(
        String::from_utf16_lossy(&units)
            .trim_end_matches('\0')
            .to_string(),
    )
}

/// An object's class number and body.
fn object(b: &[u8]) -> Option<(u32, &[u8])> {
    Some((u32_of(at(b, &[1, 1])?)?, child(b, 2)?))
}

/// An axis scale: its step in metres (a length) or in its unit, the unit, and the origin in
/// metres (or units).
struct Scale {
    step: f64,
    unit: String,
    origin: f64,
}

fn scale(b: &[u8]) -> Option<Scale> {
    let unit = text(child(b, 2)?)?;
    let display = child(b, 3).and_then(text).unwrap_or_else(|| unit.clone());
    let metres = |u: &str| length_unit(u).unwrap_or(1.0);
    Some(Scale {
        step: f64_of(child(b, 1)?)? * metres(&unit),
        origin: child(b, 5).and_then(f64_of).unwrap_or(0.0) * metres(&display),
        unit: display,
    })
}

/// The values of an array of zlib blocks: `count` elements of `width` bytes.
fn blocks(data: &[u8], count: usize, width: usize, path: &Path) -> Result<Vec<u8>> {
    let bad = |m: &str| SurfError::parse(path, None, format!("MNT array: {m}"));
    let total = data
        .get(..8)
        .and_then(|b| usize::try_from(u64::from_le_bytes(b.try_into().ok()?)).ok())
        .ok_or_else(|| bad("truncated"))?;
    if Some(total) != count.checked_mul(width) {
        return Err(bad(&format!("{total} bytes for {count} values of {width} bytes")));
    }
    // Compressed data inflate; bound the array as a zip bomb is bounded.
    if total / 1100 > data.len() {
        return Err(bad("declares far more than it can hold"));
    }
    let mut out = vec![0u8; total];
    let (mut filled, mut pos) = (0, 8);
    while pos < data.len() {
        let head = data.get(pos..pos + 16).ok_or_else(|| bad("truncated block"))?;
        let offset =
            usize::try_from(u64::from_le_bytes(head[..8].try_into().expect("8 bytes"))).unwrap_or(usize::MAX);
        let length = u32::from_le_bytes(head[8..12].try_into().expect("4 bytes")) as usize;
        let compressed = u32::from_le_bytes(head[12..16].try_into().expect("4 bytes")) as usize;
        pos += 16;
        let stream = data
            .get(pos..pos + compressed)
            .ok_or_else(|| bad("truncated block"))?;
        pos += compressed;
        let start = offset.saturating_mul(width);
        let end = length
            .checked_mul(width)
            .and_then(|n| start.checked_add(n))
            .filter(|&e| e <= total)
            .ok_or_else(|| bad("a block outside the array"))?;
        let mut inflated = Vec::with_capacity(end - start);
        flate2::read::ZlibDecoder::new(stream)
            .take((end - start + 1) as u64)
            .read_to_end(&mut inflated)
            .map_err(|e| bad(&format!("a block does not inflate: {e}")))?;
        if inflated.len() != end - start {
            return Err(bad("a block of another length than it says"));
        }
        out[start..end].copy_from_slice(&inflated);
        filled += end - start;
    }
    if filled != total {
        return Err(bad(&format!("{filled} of {total} bytes in its blocks")));
    }
    Ok(out)
}

pub(super) fn layers<'a>(bytes: &'a [u8], path: &Path) -> Result<Vec<Layer<'a>>> {
    let bad = |m: &str| SurfError::parse(path, None, m.to_string());
    let mut file = cfb::CompoundFile::open(std::io::Cursor::new(bytes)).map_err(|e| {
        bad(&format!(
            "not a MountainsMap document (an OLE compound file): {e}"
        ))
    })?;
    let mut contents = Vec::new();
    file.open_stream("/ScopedContents")
        .map_err(|_| bad("no ScopedContents stream: not a MountainsMap document"))?
        .take(bytes.len() as u64 + 1)
        .read_to_end(&mut contents)
        .map_err(|e| bad(&format!("ScopedContents: {e}")))?;
    let document = contents
        .get(8..)
        .and_then(|b| at(b, &[1, 0x02BD, 2, 1]))
        .ok_or_else(|| bad("no document in ScopedContents"))?;
    let objects = entries(document, 8).ok_or_else(|| bad("the document's objects are malformed"))?;
    let mut layers = Vec::new();
    for (_, raw) in objects {
        let Some((CLASS_SURFACE, body)) = object(raw) else {
            continue;
        };
        let title = at(body, &[0xFFFF, 4]).and_then(text);
        let Some((CLASS_SURFACE_DATA, data)) = child(body, 1).and_then(object) else {
            continue;
        };
        let Some(measurement) = child(data, 0xFFFF) else {
            continue;
        };
        let grid = child(measurement, 0xFFFF).ok_or_else(|| bad("a surface without its grid"))?;
        let axis = |tag: u16| -> Option<(usize, Scale)> {
            let a = at(grid, &[tag, 0xFFFF])?;
            Some((u32_of(child(a, 1)?)? as usize, scale(child(a, 0xFFFF)?)?))
        };
        let ((nx, sx), (ny, sy)) = axis(1)
            .zip(axis(2))
            .ok_or_else(|| bad("a surface without its lateral axes"))?;
        let sz = at(measurement, &[2, 0xFFFF])
            .and_then(scale)
            .ok_or_else(|| bad("a surface without its height axis"))?;
        for (field, v, number) in [
            ("x axis step", sx.step, Number::Size),
            ("y axis step", sy.step, Number::Size),
            ("height axis step", sz.step, Number::Scale),
        ] {
            header(path, field, v, number)?;
        }
        super::offset(path, "height axis origin", sz.origin, "height axis step", sz.step)?;
        let n = nx
            .checked_mul(ny)
            .filter(|&n| n >= 1)
            .ok_or_else(|| bad("an empty grid"))?;
        let heights = match child(measurement, 1).and_then(object) {
            Some((CLASS_HEIGHTS, array)) => array,
            _ => return Err(bad("a surface without its heights")),
        };
        let count = at(heights, &[1]).and_then(u32_of).map(|c| c as usize);
        // The closure owns its compressed bytes: the stream read here does not outlive this call.
        let stored = at(heights, &[2])
            .ok_or_else(|| bad("heights without data"))?
            .to_vec();
        if count != Some(n) {
            return Err(bad(&format!("{count:?} heights on a grid of {nx} x {ny}")));
        }
        let mask = match at(grid, &[3]).and_then(object) {
            Some((CLASS_MASK, m)) => Some(
                at(m, &[5])
                    .and_then(object)
                    .and_then(|(_, a)| Some((at(a, &[1]).and_then(u32_of)? as usize, at(a, &[2])?.to_vec())))
                    .ok_or_else(|| bad("a malformed mask"))?,
            ),
            _ => None,
        };
        let name = at(grid, &[0xFFFF, 0xFFFF, 1])
            .and_then(text)
            .or(title)
            .unwrap_or_else(|| "surface".into());
        let metres = length_unit(&sz.unit);
        let at_path = path.to_path_buf();
        layers.push(Layer {
            channel: Channel {
                name,
                nx,
                ny,
                length_x: Some(nx as f64 * sx.step),
                length_y: Some(ny as f64 * sy.step),
                unit: sz.unit.clone(),
                height: metres.is_some(),
            },
            values: Box::new(move || {
                let raw = blocks(&stored, n, 4, &at_path)?;
                let mut heights: Vec<f64> = raw
                    .chunks_exact(4)
                    .map(|c| i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64 * sz.step + sz.origin)
                    .collect();
                if let Some((count, data)) = mask {
                    if count != (nx + 2) * (ny + 2) {
                        return Err(SurfError::parse(
                            &at_path,
                            None,
                            "the mask does not match the grid",
                        ));
                    }
                    let image = blocks(&data, count, 1, &at_path)?;
                    for (k, h) in heights.iter_mut().enumerate() {
                        let (j, i) = (k / nx, k % nx);
                        if image[(j + 1) * (nx + 2) + i + 1] != MEASURED {
                            *h = f64::NAN;
                        }
                    }
                }
                Ok(Array2::from_shape_vec((ny, nx), heights).expect("counted"))
            }),
        });
    }
    if layers.is_empty() {
        return Err(bad("no measured surface in the document"));
    }
    Ok(layers)
}
