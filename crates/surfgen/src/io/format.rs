//! The file formats, chosen by extension.

use crate::error::{Result, SurfError};
use std::path::Path;
/// The extensions read, for messages.
const KNOWN: &str = ".npy, .txt/.dat/.asc/.csv, .xyz/.xyh, .gsf, .x3p, .sdf, .nc, .tmd, .mi, .nid, .sur, .opd, \
                     .di/.spm, .ibw, .frt, .gwy, .h5/.hdf5/.datx, .mnt";

/// The file formats, chosen by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Npy,
    Matrix,
    Xyh,
    Gsf,
    X3p,
    Sdf,
    NetCdf,
    Tmd,
    Mi,
    Nid,
    Sur,
    Opd,
    Di,
    Ibw,
    Frt,
    Gwy,
    Hdf5,
    Mnt,
}

impl Format {
    /// The format of `path`, from its extension.
    pub fn of(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        match ext.as_str() {
            "npy" => Ok(Format::Npy),
            "txt" | "dat" | "asc" | "csv" => Ok(Format::Matrix),
            "xyz" | "xyh" => Ok(Format::Xyh),
            "gsf" => Ok(Format::Gsf),
            "x3p" => Ok(Format::X3p),
            "sdf" => Ok(Format::Sdf),
            "nc" => Ok(Format::NetCdf),
            "tmd" => Ok(Format::Tmd),
            "mi" => Ok(Format::Mi),
            "nid" => Ok(Format::Nid),
            "sur" => Ok(Format::Sur),
            "opd" => Ok(Format::Opd),
            "di" | "spm" => Ok(Format::Di),
            "ibw" => Ok(Format::Ibw),
            "frt" => Ok(Format::Frt),
            "gwy" => Ok(Format::Gwy),
            "h5" | "hdf5" | "hdf" | "datx" => Ok(Format::Hdf5),
            // Nanoscope's older files are numbered: .000, .001, ...
            e if e.len() == 3 && e.bytes().all(|b| b.is_ascii_digit()) => Ok(Format::Di),
            "mnt" => Ok(Format::Mnt),
            "" => Err(SurfError::parse(
                path,
                None,
                format!("the file name has no extension, which names the format: give one of {KNOWN}"),
            )),
            _ => Err(SurfError::parse(
                path,
                None,
                format!("unknown surface format '.{ext}' (known: {KNOWN})"),
            )),
        }
    }
}
