//! NetCDF-3 (`.nc`) as contact.engineering and SurfaceTopography write it: dimensions `x` and
//! `y`, the variable `heights(x, y)` with a `unit` attribute, and coordinate variables `x`
//! and `y` whose attributes give the box's side (`length`), `periodic` and `unit`. Read and
//! written with the pure-Rust `netcdf3` crate (classic format).

use super::{Measurement, ReadOptions, Surface, length_unit};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use ndarray::Array2;
use netcdf3::{DataSet, FileWriter, Version};
use std::path::Path;

/// A value of a NetCDF-3 attribute: text or numbers.
#[derive(Clone, Debug)]
enum Value {
    Text(String),
    Numbers(Vec<f64>),
}

/// A variable of the header: its dimensions' ids, attributes, type and where its data begin.
struct Variable {
    name: String,
    dims: Vec<usize>,
    attributes: Vec<(String, Value)>,
    kind: u32,
    begin: u64,
}

impl Variable {
    fn text(&self, name: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|(n, _)| n == name)
            .and_then(|(_, v)| match v {
                Value::Text(t) => Some(t.as_str()),
                Value::Numbers(_) => None,
            })
    }

    fn number(&self, name: &str) -> Option<f64> {
        self.attributes
            .iter()
            .find(|(n, _)| n == name)
            .and_then(|(_, v)| match v {
                Value::Numbers(x) => x.first().copied(),
                Value::Text(_) => None,
            })
    }
}

/// Bytes of one value of a NetCDF-3 type (1 byte, 2 char, 3 short, 4 int, 5 float, 6 double).
fn type_size(kind: u32) -> Option<usize> {
    Some(match kind {
        1 | 2 => 1,
        3 => 2,
        4 | 5 => 4,
        6 => 8,
        _ => return None,
    })
}

/// A cursor over the header's big-endian fields; every count is checked against the bytes
/// left before anything is allocated for it.
struct Header<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Header<'_> {
    fn take(&mut self, n: usize) -> std::result::Result<&[u8], String> {
        let end = self
            .at
            .checked_add(n)
            .filter(|&e| e <= self.bytes.len())
            .ok_or("the header ends early")?;
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }

    fn u32(&mut self) -> std::result::Result<u32, String> {
        Ok(u32::from_be_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }

    /// A count of items of at least `min_bytes` each, which the rest of the file must hold.
    fn count(&mut self, min_bytes: usize) -> std::result::Result<usize, String> {
        let n = self.u32()? as usize;
        if n.saturating_mul(min_bytes) > self.bytes.len() - self.at {
            return Err(format!("the header claims {n} items, more than the file holds"));
        }
        Ok(n)
    }

    fn padded(&mut self, n: usize) -> std::result::Result<&[u8], String> {
        let body = self.at;
        self.take(n.div_ceil(4) * 4)?;
        Ok(&self.bytes[body..body + n])
    }

    fn name(&mut self) -> std::result::Result<String, String> {
        let n = self.count(1)?;
        Ok(String::from_utf8_lossy(self.padded(n)?).into_owned())
    }

    /// A list's tag and length: (0, 0) when absent.
    fn list(&mut self, tag: u32) -> std::result::Result<usize, String> {
        let t = self.u32()?;
        let n = self.count(4)?;
        match (t, n) {
            (0, 0) => Ok(0),
            (t, n) if t == tag => Ok(n),
            _ => Err(format!("expected a list tagged {tag}, found {t}")),
        }
    }

    fn attributes(&mut self) -> std::result::Result<Vec<(String, Value)>, String> {
        let n = self.list(0x0C)?;
        let mut out = Vec::with_capacity(n);
        for _ in 0..n {
            let name = self.name()?;
            let kind = self.u32()?;
            let size = type_size(kind).ok_or(format!("attribute {name}: unknown type {kind}"))?;
            let count = self.count(size)?;
            let raw = self.padded(count * size)?;
            let value = if kind == 2 {
                Value::Text(String::from_utf8_lossy(raw).trim_end_matches('\0').to_string())
            } else {
                Value::Numbers(raw.chunks_exact(size).map(|c| number(kind, c)).collect())
            };
            out.push((name, value));
        }
        Ok(out)
    }
}

/// One big-endian value of `kind` as f64.
fn number(kind: u32, c: &[u8]) -> f64 {
    match kind {
        1 => c[0] as i8 as f64,
        2 => c[0] as f64,
        3 => i16::from_be_bytes([c[0], c[1]]) as f64,
        4 => i32::from_be_bytes([c[0], c[1], c[2], c[3]]) as f64,
        5 => f32::from_be_bytes([c[0], c[1], c[2], c[3]]) as f64,
        _ => f64::from_be_bytes(c.try_into().expect("8 bytes")),
    }
}

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let bytes = std::fs::read(path).map_err(|e| SurfError::io(path, e))?;
    let bad = |m: String| SurfError::parse(path, None, m);
    let offset64 = match bytes.get(..4) {
        Some(b"CDF\x01") => false,
        Some(b"CDF\x02") => true,
        _ => {
            return Err(bad(
                "not a NetCDF-3 file (it does not begin with CDF 1 or CDF 2)".into()
            ));
        }
    };
    let mut h = Header { bytes: &bytes, at: 4 };
    let parsed = (|| -> std::result::Result<_, String> {
        h.u32()?; // the number of records: surfaces have no record variables
        let n = h.list(0x0A)?;
        let mut dims = Vec::with_capacity(n);
        for _ in 0..n {
            let name = h.name()?;
            dims.push((name, h.u32()? as usize));
        }
        let _global = h.attributes()?;
        let n = h.list(0x0B)?;
        let mut vars = Vec::with_capacity(n);
        for _ in 0..n {
            let name = h.name()?;
            let k = h.count(4)?;
            let ids = (0..k)
                .map(|_| h.u32().map(|d| d as usize))
                .collect::<std::result::Result<Vec<_>, _>>()?;
            let attributes = h.attributes()?;
            let kind = h.u32()?;
            h.u32()?; // vsize
            let begin = if offset64 {
                let hi = h.u32()? as u64;
                (hi << 32) | h.u32()? as u64
            } else {
                h.u32()? as u64
            };
            vars.push(Variable {
                name,
                dims: ids,
                attributes,
                kind,
                begin,
            });
        }
        Ok((dims, vars))
    })();
    let (dims, vars) = parsed.map_err(|e| bad(format!("NetCDF header: {e}")))?;
    let var = |name: &str| vars.iter().find(|v| v.name == name);
    let heights = var("heights").ok_or_else(|| {
        let names: Vec<&str> = vars.iter().map(|v| v.name.as_str()).collect();
        bad(format!(
            "no variable `heights` (the variables: {})",
            names.join(", ")
        ))
    })?;
    let [ix, iy] = heights.dims.as_slice() else {
        return Err(bad(format!(
            "`heights` has {} dimensions, a surface has 2",
            heights.dims.len()
        )));
    };
    let dim = |i: usize| {
        dims.get(i)
            .ok_or_else(|| bad(format!("`heights` names dimension {i}, which is not defined")))
    };
    let ((x_name, nx), (y_name, ny)) = (dim(*ix)?.clone(), dim(*iy)?.clone());
    let size = type_size(heights.kind)
        .filter(|_| heights.kind != 2)
        .ok_or_else(|| bad("`heights` is not numeric".into()))?;
    let start = heights.begin as usize;
    let end = nx
        .checked_mul(ny)
        .and_then(|n| n.checked_mul(size))
        .and_then(|n| n.checked_add(start))
        .filter(|&e| nx > 0 && ny > 0 && e <= bytes.len())
        .ok_or_else(|| {
            bad(format!(
                "`heights` claims {nx} x {ny} values from byte {start}, more than a file of {} bytes holds",
                bytes.len()
            ))
        })?;
    let unit = |v: Option<&Variable>| -> Result<Option<f64>> {
        match v.and_then(|v| v.text("unit")) {
            None => Ok(None),
            Some(u) => length_unit(u)
                .map(Some)
                .ok_or_else(|| bad(format!("unknown unit '{u}'"))),
        }
    };
    let z_unit = unit(Some(heights))?.unwrap_or(1.0);
    let side = |name: &str, given: Option<f64>| -> Result<Option<f64>> {
        let v = var(name);
        match (v.and_then(|v| v.number("length")), given) {
            (Some(l), _) => Ok(Some(l * unit(v)?.unwrap_or(z_unit))),
            (None, given) => Ok(given),
        }
    };
    let lx = side(&x_name, options.length_x)?.ok_or_else(|| {
        bad(format!(
            "`{x_name}` does not say the box's side (its `length`): give it (e.g. --length in metres)"
        ))
    })?;
    let ly = side(&y_name, options.length_y)?.unwrap_or(lx * ny as f64 / nx as f64);
    let periodic = var(&x_name)
        .and_then(|v| v.number("periodic"))
        .map_or(options.periodic, |p| p != 0.0);
    let scale = z_unit * options.unit;
    let values: Vec<f64> = bytes[start..end]
        .chunks_exact(size)
        .map(|c| number(heights.kind, c) * scale)
        .collect();
    // Stored (x, y), x slowest: the transpose of our (ny, nx).
    let heights = Array2::from_shape_vec((nx, ny), values)
        .expect("counted")
        .reversed_axes();
    let grid = Grid::new(nx, ny, lx * options.unit, ly * options.unit).map_err(|e| bad(e.to_string()))?;
    Measurement::new(heights.as_standard_layout().into_owned(), grid, periodic)
}

pub(super) fn write(surface: &Surface, path: &Path) -> Result<()> {
    let g = surface.grid;
    let fail = |e: String| SurfError::parse(path, None, format!("writing NetCDF: {e}"));
    let mut data = DataSet::new();
    data.add_fixed_dim("x", g.nx)
        .map_err(|e| fail(format!("{e:?}")))?;
    data.add_fixed_dim("y", g.ny)
        .map_err(|e| fail(format!("{e:?}")))?;
    data.add_var_f64("heights", &["x", "y"])
        .map_err(|e| fail(format!("{e:?}")))?;
    data.add_var_attr_string("heights", "unit", "m")
        .map_err(|e| fail(format!("{e:?}")))?;
    for (name, length) in [("x", g.length_x), ("y", g.length_y)] {
        data.add_var_f64(name, &[name])
            .map_err(|e| fail(format!("{e:?}")))?;
        data.add_var_attr_f64(name, "length", vec![length])
            .map_err(|e| fail(format!("{e:?}")))?;
        data.add_var_attr_i32(name, "periodic", vec![i32::from(surface.periodic)])
            .map_err(|e| fail(format!("{e:?}")))?;
        data.add_var_attr_string(name, "unit", "m")
            .map_err(|e| fail(format!("{e:?}")))?;
    }
    if path.exists() {
        std::fs::remove_file(path).map_err(|e| SurfError::io(path, e))?;
    }
    let mut writer = FileWriter::create_new(path).map_err(|e| fail(format!("{e:?}")))?;
    writer
        .set_def(&data, Version::Classic, 0)
        .map_err(|e| fail(format!("{e:?}")))?;
    // (x, y) order, x slowest: our (ny, nx) transposed.
    let heights: Vec<f64> = surface.heights.t().iter().copied().collect();
    writer
        .write_var_f64("heights", &heights)
        .map_err(|e| fail(format!("{e:?}")))?;
    let x: Vec<f64> = (0..g.nx).map(|i| i as f64 * g.dx()).collect();
    let y: Vec<f64> = (0..g.ny).map(|j| j as f64 * g.dy()).collect();
    writer
        .write_var_f64("x", &x)
        .map_err(|e| fail(format!("{e:?}")))?;
    writer
        .write_var_f64("y", &y)
        .map_err(|e| fail(format!("{e:?}")))?;
    writer.close().map_err(|e| fail(format!("{e:?}")))
}
