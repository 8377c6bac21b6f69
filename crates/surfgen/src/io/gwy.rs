//! Gwyddion native files (`.gwy`): the magic `GWYP`, then a serialized `GwyContainer`. An
//! object is its class name (NUL-terminated), the size of its data (u32, little-endian) and its
//! components: a name, a type character and a value (`b`/`c` one byte, `i` i32, `q` i64, `d`
//! f64, `s` a NUL-terminated string, `o` an object; capitals are arrays, a u32 count then the
//! items). Each image is a `GwyDataField` under `/N/data` (`xres`, `yres`, `xreal`, `yreal` [m],
//! `si_unit_z`, `data` as f64 rows), titled by `/N/data/title`; a `/N/mask` field marks with
//! values above 0.5 the points not to be used, read here as unmeasured.

use super::{Channel, Layer, length_unit};
use crate::error::{Result, SurfError};
use ndarray::Array2;
use std::collections::HashMap;
use std::path::Path;

/// A value of a serialized object; arrays of doubles kept as their bytes.
enum Value<'a> {
    Int(i64),
    Float(f64),
    Text(String),
    Object(Object<'a>),
    Doubles(&'a [u8]),
    Other,
}

struct Object<'a> {
    items: HashMap<String, Value<'a>>,
}

impl<'a> Object<'a> {
    fn int(&self, key: &str) -> Option<usize> {
        match self.items.get(key)? {
            Value::Int(v) => usize::try_from(*v).ok(),
            _ => None,
        }
    }
    fn float(&self, key: &str) -> Option<f64> {
        match self.items.get(key)? {
            Value::Float(v) => Some(*v),
            _ => None,
        }
    }
    fn unit(&self, key: &str) -> Option<String> {
        match self.items.get(key)? {
            Value::Object(o) => match o.items.get("unitstr")? {
                Value::Text(s) => Some(s.clone()),
                _ => None,
            },
            _ => None,
        }
    }
    fn doubles(&self) -> Option<&'a [u8]> {
        match self.items.get("data")? {
            Value::Doubles(b) => Some(b),
            _ => None,
        }
    }
}

/// Reads serialized objects from a byte slice, never past its end, nested at most 32 deep.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let s = self.bytes.get(self.at..self.at.checked_add(n)?)?;
        self.at += n;
        Some(s)
    }
    fn name(&mut self) -> Option<String> {
        let rest = self.bytes.get(self.at..)?;
        let end = rest.iter().position(|&b| b == 0)?;
        let s = String::from_utf8_lossy(&rest[..end]).into_owned();
        self.at += end + 1;
        Some(s)
    }
    fn u32(&mut self) -> Option<usize> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?) as usize)
    }
    fn object(&mut self, depth: usize) -> Option<Object<'a>> {
        if depth > 32 {
            return None;
        }
        self.name()?;
        let size = self.u32()?;
        let mut inner = Reader {
            bytes: self.take(size)?,
            at: 0,
        };
        let mut items = HashMap::new();
        while inner.at < inner.bytes.len() {
            let key = inner.name()?;
            let kind = *inner.take(1)?.first()?;
            let value = inner.value(kind, depth)?;
            items.insert(key, value);
        }
        Some(Object { items })
    }
    fn value(&mut self, kind: u8, depth: usize) -> Option<Value<'a>> {
        Some(match kind {
            b'b' | b'c' => Value::Int(*self.take(1)?.first()? as i64),
            b'i' => Value::Int(i32::from_le_bytes(self.take(4)?.try_into().ok()?) as i64),
            b'q' => Value::Int(i64::from_le_bytes(self.take(8)?.try_into().ok()?)),
            b'd' => Value::Float(f64::from_le_bytes(self.take(8)?.try_into().ok()?)),
            b's' => Value::Text(self.name()?),
            b'o' => Value::Object(self.object(depth + 1)?),
            b'D' => {
                let n = self.u32()?;
                Value::Doubles(self.take(n.checked_mul(8)?)?)
            }
            b'C' | b'I' | b'Q' => {
                let n = self.u32()?;
                let width = match kind {
                    b'C' => 1,
                    b'I' => 4,
                    _ => 8,
                };
                self.take(n.checked_mul(width)?)?;
                Value::Other
            }
            b'S' => {
                for _ in 0..self.u32()? {
                    self.name()?;
                }
                Value::Other
            }
            b'O' => {
                for _ in 0..self.u32()? {
                    self.object(depth + 1)?;
                }
                Value::Other
            }
            _ => return None,
        })
    }
}

pub(super) fn layers<'a>(bytes: &'a [u8], path: &Path) -> Result<Vec<Layer<'a>>> {
    let bad = |m: String| SurfError::parse(path, None, m);
    let body = bytes
        .strip_prefix(b"GWYP")
        .ok_or_else(|| bad("not a Gwyddion file (it does not begin with GWYP)".into()))?;
    let mut reader = Reader { bytes: body, at: 0 };
    let mut container = reader
        .object(0)
        .ok_or_else(|| bad("the serialized container is truncated or malformed".into()))?;
    // The images, by their number.
    let mut numbers: Vec<usize> = container
        .items
        .keys()
        .filter_map(|k| k.strip_prefix('/')?.strip_suffix("/data")?.parse().ok())
        .collect();
    numbers.sort_unstable();
    let mut layers = Vec::new();
    for number in numbers {
        let Some(Value::Object(field)) = container.items.remove(&format!("/{number}/data")) else {
            continue;
        };
        let title = match container.items.get(&format!("/{number}/data/title")) {
            Some(Value::Text(t)) => t.clone(),
            _ => format!("image {number}"),
        };
        let mask = match container.items.remove(&format!("/{number}/mask")) {
            Some(Value::Object(m)) => m.doubles(),
            _ => None,
        };
        let (nx, ny) = (field.int("xres").unwrap_or(0), field.int("yres").unwrap_or(0));
        let data = field
            .doubles()
            .filter(|d| nx >= 1 && ny >= 1 && d.len() / 8 == nx * ny)
            .ok_or_else(|| bad(format!("image {number} ({title}): no data of {nx} x {ny} values")))?;
        let mask = mask.filter(|m| m.len() == data.len());
        let unit = field.unit("si_unit_z").unwrap_or_default();
        let metres = length_unit(&unit).filter(|_| !unit.is_empty());
        let lateral = length_unit(&field.unit("si_unit_xy").unwrap_or_default()).unwrap_or(1.0);
        let length = |key: &str| field.float(key).map(|l| l * lateral);
        let scale = metres.unwrap_or(1.0);
        for key in ["xreal", "yreal"] {
            if let Some(l) = length(key) {
                super::header(path, &format!("image {number}'s {key}"), l, super::Number::Size)?;
            }
        }
        layers.push(Layer {
            channel: Channel {
                name: title,
                nx,
                ny,
                length_x: length("xreal"),
                length_y: length("yreal"),
                unit,
                height: metres.is_some(),
            },
            values: Box::new(move || {
                let at =
                    |b: &[u8], k: usize| f64::from_le_bytes(b[8 * k..8 * k + 8].try_into().expect("8 bytes"));
                // Rows in order (SurfaceTopography's orientation); masked points unmeasured.
                Ok(Array2::from_shape_fn((ny, nx), |(j, i)| {
                    let k = j * nx + i;
                    match mask {
                        Some(m) if at(m, k) > 0.5 => f64::NAN,
                        _ => at(data, k) * scale,
                    }
                }))
            }),
        });
    }
    if layers.is_empty() {
        return Err(bad("no image (/N/data) in the file".into()));
    }
    Ok(layers)
}
