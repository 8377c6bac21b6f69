//! `roughcontact` as a library: the command-line tool's case files, problem building,
//! output writers and plotting style, so that `xtask` (the paper's figures) builds its runs
//! exactly as the command line does. The binary (`main.rs`) only parses arguments.

pub mod bench;
pub mod case;
pub mod plot;
pub mod solve;
pub mod surface;
pub mod sweep;
pub mod theory_cmd;
