//! The `roughcontact` command line: its case schema (flags and TOML keys) translated into
//! the library's problems, its output writers and plotting style. The binary (`main.rs`) only
//! parses arguments.
// The doc comments of the flags are the command's help text: units stand in brackets, file names in <>.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

pub mod bench;
pub mod plot;
pub mod run;
pub mod solve;
pub mod surface;
pub mod sweep;
pub mod theory_cmd;
