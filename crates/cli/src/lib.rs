//! The `roughcontact` command line: the commands that make and read surfaces, the reference
//! models, the benchmarks, and the runs of the `runs` crate. The binary (`main.rs`) only parses
//! arguments.
// The doc comments of the flags are the command's help text: units stand in brackets, file names in <>.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

pub mod bench;
pub mod surface;
pub mod theory_cmd;

pub use plot;
pub use runs::{
    eprint_line, errln, note, note_err, note_unchecked, outln, output, print_line, quiet, run, say,
    set_quiet, solve, study, sweep,
};
