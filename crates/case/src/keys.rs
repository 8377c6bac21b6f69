//! A case's keys read from a TOML case file, a table of keywords and the command line's flags,
//! layered in that order, with refusals that name the key.

use crate::error::{Context, Result, bail};
use ndarray::Array2;
use serde::{Serialize, de::DeserializeOwned};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The keys a struct of options can take in a case file: its fields' names.
fn keys<T: Default + Serialize>() -> Vec<String> {
    match serde_json::to_value(T::default()) {
        Ok(Value::Object(m)) => m.keys().cloned().collect(),
        _ => Vec::new(),
    }
}

/// The first non-finite number in `table` (arrays included), with its key.
fn non_finite(table: &toml::Table) -> Option<(&str, f64)> {
    fn bad(v: &toml::Value) -> Option<f64> {
        match v {
            toml::Value::Float(x) if !x.is_finite() => Some(*x),
            toml::Value::Array(a) => a.iter().find_map(bad),
            _ => None,
        }
    }
    table.iter().find_map(|(k, v)| bad(v).map(|x| (k.as_str(), x)))
}

/// Reads a TOML case file (or text) into two option structs, each key going to the struct that
/// has it (unknown keys are an error), then lays every flag given on the command line over it.
/// Values stay typed TOML values throughout, so nothing given is lost; a NaN or infinite number
/// anywhere is refused, naming its key.
pub fn layered<A, B>(text: Option<(&str, &str)>, a: &A, b: &B) -> Result<(A, B)>
where
    A: Default + Serialize + DeserializeOwned,
    B: Default + Serialize + DeserializeOwned,
{
    let file = match text {
        Some((name, text)) => {
            let table: toml::Table = toml::from_str(text).with_context(|| format!("parsing {name}"))?;
            Some((name, table))
        }
        None => None,
    };
    let mut flags = toml::Table::try_from(a)?;
    flags.extend(toml::Table::try_from(b)?);
    if let Some((key, x)) = non_finite(&flags) {
        bail!("--{} must be a finite number, got {x}", key.replace('_', "-"));
    }
    split(file, flags)
}

/// Reads a case given as one table of keys (the Python package's keywords, a study's run) into
/// two option structs, each key going to the struct that has it; `name` says where the keys came
/// from in messages. Unknown keys, values of the wrong type and non-finite numbers are refused,
/// naming the key.
pub fn from_table<A, B>(name: &str, table: toml::Table) -> Result<(A, B)>
where
    A: Default + Serialize + DeserializeOwned,
    B: Default + Serialize + DeserializeOwned,
{
    split(Some((name, table)), toml::Table::new())
}

/// `file`'s keys sorted into the two structs, with `flags` (already sorted by name) laid over.
fn split<A, B>(file: Option<(&str, toml::Table)>, flags: toml::Table) -> Result<(A, B)>
where
    A: Default + Serialize + DeserializeOwned,
    B: Default + Serialize + DeserializeOwned,
{
    let (ka, kb) = (keys::<A>(), keys::<B>());
    let (mut ta, mut tb) = (toml::Table::new(), toml::Table::new());
    let source = file.as_ref().map_or("the flags", |(name, _)| *name).to_string();
    if let Some((name, table)) = file {
        if let Some((key, x)) = non_finite(&table) {
            bail!("{name}: `{key}` must be a finite number, got {x}");
        }
        for (k, v) in table {
            if ka.contains(&k) {
                ta.insert(k, v);
            } else if kb.contains(&k) {
                tb.insert(k, v);
            } else {
                let mut all = ka.clone();
                all.extend(kb.clone());
                all.sort();
                bail!("{name}: unknown key `{k}`; the keys are {}", all.join(", "));
            }
        }
    }
    for (k, v) in flags {
        if ka.contains(&k) {
            ta.insert(k, v);
        } else {
            tb.insert(k, v);
        }
    }
    let a = typed(&source, ta)?;
    let b = typed(&source, tb)?;
    Ok((a, b))
}

/// `table` as the option struct `T`; a value of the wrong type is refused naming its key, the
/// value given and what the key takes, in words rather than serde's.
fn typed<T: DeserializeOwned>(source: &str, table: toml::Table) -> Result<T> {
    match table.clone().try_into() {
        Ok(t) => Ok(t),
        Err(whole) => {
            // The culprit: the first key that does not deserialise on its own.
            for (key, value) in table {
                let alone: toml::Table = [(key.clone(), value.clone())].into_iter().collect();
                if let Err(e) = alone.try_into::<T>() {
                    bail!(
                        "{source}: `{key}` must be {}, got {}",
                        expected(&e.to_string()),
                        given(&value)
                    );
                }
            }
            bail!("{source}: {}", whole.to_string().trim())
        }
    }
}

/// What a key takes, from serde's "expected ..." in `message`.
fn expected(message: &str) -> String {
    let wanted = message
        .split("expected ")
        .nth(1)
        .map(|w| w.lines().next().unwrap_or(w).trim())
        .unwrap_or("");
    let wanted = wanted.split(" in `").next().unwrap_or(wanted);
    match wanted {
        "usize" | "u64" | "u32" => "a whole number >= 0".into(),
        "f64" | "f32" => "a number".into(),
        "a boolean" | "bool" => "true or false".into(),
        "path string" => "a path (a string)".into(),
        "a string" => "a string".into(),
        "a sequence" => "a list".into(),
        w if w.starts_with("one of") => w.replace('`', "\""),
        "" => "another type".into(),
        w => w.to_string(),
    }
}

/// A value as the user wrote it, with its type.
fn given(value: &toml::Value) -> String {
    let kind = match value {
        toml::Value::String(_) => "a string",
        toml::Value::Integer(_) => "an integer",
        toml::Value::Float(_) => "a number with a fraction",
        toml::Value::Boolean(_) => "a boolean",
        toml::Value::Datetime(_) => "a date",
        toml::Value::Array(_) => "a list",
        toml::Value::Table(_) => "a table",
    };
    let text = value.to_string();
    let text = if text.len() > 60 {
        format!("{}...", &text[..text.floor_char_boundary(57)])
    } else {
        text
    };
    format!("{text} ({kind})")
}

/// A path a case file gave (`from_file`: not overridden by a flag) is relative to that file's
/// directory, as in any file that names others; a flag's is relative to the working directory.
pub fn beside(config: Option<&Path>, from_file: bool, path: &mut Option<PathBuf>) {
    if let (Some(config), true, Some(p)) = (config, from_file, path.as_mut())
        && p.is_relative()
        && let Some(dir) = config.parent()
    {
        *p = dir.join(&*p);
    }
}

/// Both option structs as one TOML case (for `--print-config`).
pub fn to_toml<A: Serialize, B: Serialize>(a: &A, b: &B) -> Result<String> {
    let mut table: toml::Table = toml::Table::try_from(a)?;
    table.extend(toml::Table::try_from(b)?);
    Ok(toml::to_string(&table)?.trim_end().to_string())
}

/// FNV-1a over the heights' bits: a stable fingerprint of the input surface.
pub fn fingerprint(h: &Array2<f64>) -> String {
    let mut hash: u64 = 0xcbf29ce484222325;
    for v in h.iter() {
        for b in v.to_le_bytes() {
            hash ^= b as u64;
            hash = hash.wrapping_mul(0x100000001b3);
        }
    }
    format!("fnv1a64:{hash:016x}")
}
