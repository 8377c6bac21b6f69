//! Refusing a run this machine cannot hold, before anything is allocated.

use crate::error::{Error, Result, bail};

const GIB: f64 = 1024.0 * 1024.0 * 1024.0;

/// The memory available to a new process and the machine's total [bytes], from
/// `/proc/meminfo` (None where there is none).
fn machine() -> Option<(f64, f64)> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let field = |key: &str| -> Option<f64> {
        let line = text.lines().find(|l| l.starts_with(key))?;
        let kib: f64 = line[key.len()..]
            .trim()
            .trim_end_matches("kB")
            .trim()
            .parse()
            .ok()?;
        Some(kib * 1024.0)
    };
    Some((field("MemAvailable:")?, field("MemTotal:")?))
}

/// Refuses `what` when its estimated peak memory `bytes` exceeds what this machine has
/// available, with both numbers.
pub fn check(what: &str, bytes: f64) -> Result<()> {
    if let Some((available, total)) = machine()
        && bytes > available
    {
        return Err(Error::Memory(format!(
            "{what} needs about {:.1} GiB of memory; this machine has {:.1} GiB available (of {:.1} GiB)",
            bytes / GIB,
            available / GIB,
            total / GIB
        )));
    }
    Ok(())
}

/// The most worker threads a process starts per core: beyond, threads only cost memory and
/// start-up time (and enough of them make the system refuse to start more).
pub const THREADS_PER_CORE: usize = 64;

/// Refuses a count of threads `name` below 1 or beyond [`THREADS_PER_CORE`] per core of this
/// machine.
pub fn check_threads(name: &str, threads: usize) -> Result<()> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if threads == 0 || threads > THREADS_PER_CORE * cores {
        bail!(
            "{name} must be between 1 and {} ({THREADS_PER_CORE} per core; this machine has {cores}), got {threads}",
            THREADS_PER_CORE * cores
        );
    }
    Ok(())
}
