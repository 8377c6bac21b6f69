//! Runs cached by their inputs: a run's result is stored as JSON under a key hashed from its
//! kind and its inputs (serialised), so that rebuilding one figure, or a figure sharing runs
//! with another (Figs. 11-14), does not recompute what is already known. Bump [`VERSION`]
//! when the physics or a result's layout changes; `--fresh` ignores what is stored.

use anyhow::{Context, Result};
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;
use std::path::PathBuf;

/// Part of every key: results of older code are not reused.
pub const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "/figures-2");

pub struct Cache {
    dir: PathBuf,
    fresh: bool,
}

/// FNV-1a, 64 bits: stable across platforms and releases (unlike `DefaultHasher`).
fn fnv1a(text: &str) -> u64 {
    let mut hash = 0xcbf29ce484222325u64;
    for b in text.bytes() {
        hash ^= b as u64;
        hash = hash.wrapping_mul(0x100000001b3);
    }
    hash
}

impl Cache {
    pub fn new(dir: PathBuf, fresh: bool) -> Result<Self> {
        std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        Ok(Cache { dir, fresh })
    }

    /// The stored result of `job`, or `compute()`'s, stored for next time.
    pub fn get_or<J: Serialize, R: Serialize + DeserializeOwned>(
        &self,
        kind: &str,
        job: &J,
        compute: impl FnOnce() -> Result<R>,
    ) -> Result<R> {
        let inputs = serde_json::to_value(job)?;
        let key = format!("{VERSION}|{kind}|{inputs}");
        let path = self.dir.join(format!("{kind}-{:016x}.json", fnv1a(&key)));
        if !self.fresh
            && let Ok(text) = std::fs::read_to_string(&path)
            && let Ok(stored) = serde_json::from_str::<Value>(&text)
            && stored.get("key").and_then(Value::as_str) == Some(key.as_str())
            && let Some(result) = stored.get("result")
            && let Ok(result) = serde_json::from_value(result.clone())
        {
            return Ok(result);
        }
        let result = compute()?;
        let stored = serde_json::json!({ "key": key, "inputs": inputs, "result": result });
        // Written whole then renamed, so that an interrupted run leaves no half file.
        let tmp = path.with_extension("tmp");
        std::fs::write(&tmp, serde_json::to_string(&stored)?)?;
        std::fs::rename(&tmp, &path)?;
        Ok(result)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stored_result_is_reused_and_fresh_recomputes() {
        let dir = std::env::temp_dir().join(format!("xtask-cache-{}", std::process::id()));
        let cache = Cache::new(dir.clone(), false).unwrap();
        let a: f64 = cache.get_or("t", &(1, "x"), || Ok(2.5)).unwrap();
        let b: f64 = cache.get_or("t", &(1, "x"), || panic!("not reused")).unwrap();
        assert_eq!((a, b), (2.5, 2.5));
        let c: f64 = cache.get_or("t", &(2, "x"), || Ok(4.0)).unwrap();
        assert_eq!(c, 4.0);
        let fresh = Cache::new(dir.clone(), true).unwrap();
        let d: f64 = fresh.get_or("t", &(1, "x"), || Ok(7.0)).unwrap();
        assert_eq!(d, 7.0);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn stored_floats_come_back_bit_for_bit() {
        // A figure redrawn from the cache must be byte-identical to the one computed.
        let dir = std::env::temp_dir().join(format!("xtask-cache-bits-{}", std::process::id()));
        let cache = Cache::new(dir.clone(), false).unwrap();
        let values: Vec<f64> = (1..200)
            .map(|k| (k as f64 * 0.37).sin() * 10f64.powi(k % 40 - 20))
            .collect();
        let _: Vec<f64> = cache.get_or("t", &1, || Ok(values.clone())).unwrap();
        let back: Vec<f64> = cache.get_or("t", &1, || panic!("not reused")).unwrap();
        for (a, b) in values.iter().zip(&back) {
            assert_eq!(a.to_bits(), b.to_bits(), "{a:e} came back as {b:e}");
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn the_hash_is_fnv1a() {
        // Reference values of 64-bit FNV-1a.
        assert_eq!(fnv1a(""), 0xcbf29ce484222325);
        assert_eq!(fnv1a("a"), 0xaf63dc4c8601ec8c);
    }
}
