//! FRT MicroProf (`.frt`): the magic `FRTM_GLIDERV` and a version (`1.00` or `1.01`), a block
//! count (u16), then blocks of an id (u16), a size (u32 in 1.00, u64 in 1.01) and their bytes,
//! little-endian. Block 0x66 gives the points along x and y and the bits a value (16: u16, 32:
//! i32); 0x67 the box's sides [m]; 0x6c the metres a count; 0x0b the heights, x varying
//! fastest, rows from the image's top. A count of 1 marks an unmeasured point.

use super::{Measurement, Number, ReadOptions, header, rows_from_top};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use std::collections::HashMap;
use std::path::Path;

const MAGIC: &[u8] = b"FRTM_GLIDERV";
const UNMEASURED: i64 = 1;

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let bytes = std::fs::read(path).map_err(|e| SurfError::io(path, e))?;
    let bad = |m: String| SurfError::parse(path, None, m);
    let rest = bytes
        .strip_prefix(MAGIC)
        .ok_or_else(|| bad("not an FRT file (it does not begin with FRTM_GLIDERV)".into()))?;
    let wide = match rest.get(..4) {
        Some(b"1.00") => false,
        Some(b"1.01") => true,
        _ => return Err(bad("FRT version other than 1.00 or 1.01".into())),
    };
    let mut at = MAGIC.len() + 4;
    let count = bytes
        .get(at..at + 2)
        .map_or(0, |b| u16::from_le_bytes([b[0], b[1]]));
    at += 2;
    let mut blocks: HashMap<u16, &[u8]> = HashMap::new();
    for _ in 0..count {
        let head = if wide { 10 } else { 6 };
        let Some(h) = bytes.get(at..at + head) else { break };
        let id = u16::from_le_bytes([h[0], h[1]]);
        let size = if wide {
            u64::from_le_bytes(h[2..10].try_into().expect("8 bytes"))
        } else {
            u32::from_le_bytes(h[2..6].try_into().expect("4 bytes")) as u64
        };
        let start = at + head;
        let end = usize::try_from(size)
            .ok()
            .and_then(|s| start.checked_add(s))
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                bad(format!(
                    "block {id:#x} of {size} bytes runs past the end of the file"
                ))
            })?;
        blocks.entry(id).or_insert(&bytes[start..end]);
        at = end;
    }
    let block = |id: u16, len: usize| {
        blocks
            .get(&id)
            .filter(|b| b.len() >= len)
            .copied()
            .ok_or_else(|| bad(format!("no block {id:#x} of at least {len} bytes")))
    };
    let u32_of = |b: &[u8], o: usize| u32::from_le_bytes(b[o..o + 4].try_into().expect("4 bytes")) as usize;
    let f64_of = |b: &[u8], o: usize| f64::from_le_bytes(b[o..o + 8].try_into().expect("8 bytes"));
    let grid = block(0x66, 12)?;
    let (nx, ny, bits) = (u32_of(grid, 0), u32_of(grid, 4), u32_of(grid, 8));
    let sizes = block(0x67, 16)?;
    let (lx, ly) = (f64_of(sizes, 0), f64_of(sizes, 8));
    let scale = header(
        path,
        "height scale (block 0x6c)",
        f64_of(block(0x6c, 12)?, 4),
        Number::Scale,
    )?;
    for (side, l) in [("x", lx), ("y", ly)] {
        header(path, &format!("size along {side} (block 0x67)"), l, Number::Size)?;
    }
    let width = match bits {
        16 => 2,
        32 => 4,
        b => return Err(bad(format!("{b} bits a value (16 or 32 are read)"))),
    };
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n >= 1)
        .ok_or_else(|| bad(format!("{nx} x {ny} points")))?;
    let data = block(0x0b, 0)?;
    if data.len() / width != n {
        return Err(bad(format!(
            "{nx} x {ny} values of {bits} bits, the data block holds {} bytes",
            data.len()
        )));
    }
    let counts = data.chunks_exact(width).map(|c| match width {
        2 => u16::from_le_bytes([c[0], c[1]]) as i64,
        _ => i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as i64,
    });
    let heights: Vec<f64> = counts
        .map(|c| {
            if c == UNMEASURED {
                f64::NAN
            } else {
                c as f64 * scale * options.unit
            }
        })
        .collect();
    let grid = Grid::new(nx, ny, lx * options.unit, ly * options.unit).map_err(|e| bad(e.to_string()))?;
    Measurement::new(rows_from_top(ny, nx, heights), grid, options.periodic)
}
