//! A contact case run into a directory, as the command line and the figures run it: `solve`
//! and `sweep` with their outputs (fields, curves, summaries, plots) and progress, and `study`,
//! a grid of cases run in parallel, across MPI ranks or as a job array, resumable. The case
//! itself is the `case` crate's; the physics is the solver's.
// The doc comments of the flags are the command's help text: units stand in brackets, file names in <>.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

pub mod output;
pub mod run;
pub mod solve;
pub mod study;
pub mod sweep;
pub mod tangential;

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

/// Writes a line to standard output; a failed write (a full disk, a closed file) is an error
/// that ends the command with status 1, never a panic.
pub fn print_line(args: std::fmt::Arguments<'_>) -> anyhow::Result<()> {
    use std::io::Write;
    writeln!(std::io::stdout().lock(), "{args}")
        .map_err(|e| anyhow::anyhow!("writing to standard output: {e}"))
}

/// Writes a line to standard error, as [`print_line`] does to standard output.
pub fn eprint_line(args: std::fmt::Arguments<'_>) -> anyhow::Result<()> {
    use std::io::Write;
    writeln!(std::io::stderr().lock(), "{args}")
        .map_err(|e| anyhow::anyhow!("writing to standard error: {e}"))
}

/// A line to standard output; a failed write returns its error from the enclosing function
/// (which returns `anyhow::Result`).
#[macro_export]
macro_rules! outln {
    ($($t:tt)*) => { $crate::print_line(format_args!($($t)*))? };
}

/// A line to standard error, as [`outln!`].
#[macro_export]
macro_rules! errln {
    ($($t:tt)*) => { $crate::eprint_line(format_args!($($t)*))? };
}

/// A line to standard error where no error can be returned (a worker thread): a failed write
/// is dropped, and the command's next write reports it.
pub fn note_err(args: std::fmt::Arguments<'_>) {
    let _ = eprint_line(args);
}

/// A line to standard output unless [`quiet`]; a failed write returns its error from the
/// enclosing function (which returns `anyhow::Result`).
#[macro_export]
macro_rules! say {
    ($($t:tt)*) => { if !$crate::quiet() { $crate::print_line(format_args!($($t)*))? } };
}

/// A line to standard error unless [`quiet`], as [`say!`].
#[macro_export]
macro_rules! note {
    ($($t:tt)*) => { if !$crate::quiet() { $crate::eprint_line(format_args!($($t)*))? } };
}

/// A line to standard error unless [`quiet`], where no error can be returned (an observer of
/// the solver): a failed write is dropped, and the command's next write reports it.
#[macro_export]
macro_rules! note_unchecked {
    ($($t:tt)*) => { if !$crate::quiet() { $crate::note_err(format_args!($($t)*)) } };
}
