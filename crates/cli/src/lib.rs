//! The `roughcontact` command line: its case schema (flags and TOML keys) translated into
//! the library's problems, its output writers and plotting style. The binary (`main.rs`) only
//! parses arguments.
// The doc comments of the flags are the command's help text: units stand in brackets, file names in <>.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

pub mod bench;
pub mod plot;
pub mod run;
pub mod solve;
pub mod study;
pub mod surface;
pub mod sweep;
pub mod theory_cmd;

use std::sync::atomic::{AtomicBool, Ordering};

static QUIET: AtomicBool = AtomicBool::new(false);

/// Silences the reports, warnings and progress of `solve` and `sweep` (a study's runs, whose
/// summaries say all of it).
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// Whether the reports are silenced.
pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// `println!` unless [`quiet`].
#[macro_export]
macro_rules! say {
    ($($t:tt)*) => { if !$crate::quiet() { println!($($t)*) } };
}

/// `eprintln!` unless [`quiet`].
#[macro_export]
macro_rules! note {
    ($($t:tt)*) => { if !$crate::quiet() { eprintln!($($t)*) } };
}
