//! Reading and writing surfaces with their grid spacing.
//!
//! | extension | format | spacing from |
//! |---|---|---|
//! | `.npy` | NumPy f64 array `(ny, nx)` + JSON sidecar `<stem>.json` ([`Metadata`]) | the sidecar, else [`ReadOptions`] |
//! | `.txt`, `.dat`, `.asc`, `.csv` | plain-text matrix, one row of heights per line | a `# length_x=.. length_y=..` comment written by us, or Gwyddion's export header (`# Width: 10.00 µm`, `# Height:`, `# Value units:`), else [`ReadOptions`] |
//! | `.xyz`, `.xyh` | `x y h` triples, one per line, rows separated by blank lines (the contact-mechanics challenge's format) | the coordinates |
//! | `.gsf` | Gwyddion Simple Field (heights as f32) | the header |
//! | `.x3p` | ISO 25178-72 XML 3D surface profile (zip: `main.xml` + binary heights) | the x and y increments |
//! | `.sdf` | ISO 25178-71 Surface Data File (text, or binary i16/i32/f64) | `Xscale`, `Yscale` |
//! | `.nc` | NetCDF-3 as contact.engineering writes it (`heights(x, y)`) | the `length` of `x` and `y` |
//! | `.tmd` | TrueMap / TrueSurf binary (read only) | the header |
//! | `.mi` | Molecular Imaging / Agilent PicoView image, its height channel (read only) | the header |
//! | `.nid` | Nanosurf, its first height channel (read only) | the channel's ranges |
//! | `.sur` | Digital Surf / MountainsMap surface, every point measured (read only) | the header |
//! | `.opd` | Wyko / Veeco Vision, every point measured (read only) | `Pixel_size`, `Aspect` |
//!
//! Heights and lengths are in metres; [`ReadOptions::unit`] converts files written in other
//! units. Readers check everything (shape, finiteness, ragged rows) and return an error naming
//! the file and line rather than a partial surface.

mod gsf;
mod mi;
mod netcdf;
mod nid;
mod npy;
mod opd;
mod sdf;
mod sur;
mod tmd;
mod x3p;

pub use npy::write_array as write_npy;
mod text;

use crate::error::{Result, SurfError};
use crate::generate::SurfaceSpec;
use crate::grid::{Grid, check_finite};
use crate::stats::Statistics;
use ndarray::Array2;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A height map on its grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// Heights \[m\], shape `(ny, nx)`.
    pub heights: Array2<f64>,
    pub grid: Grid,
    /// Whether the surface repeats itself across the box edges (generated surfaces do).
    pub periodic: bool,
}

impl Surface {
    /// A surface, checked: shape matching the grid, finite heights.
    pub fn new(heights: Array2<f64>, grid: Grid, periodic: bool) -> Result<Self> {
        grid.check(heights.view())?;
        Ok(Surface {
            heights,
            grid,
            periodic,
        })
    }
}

/// Options for files that do not carry their spacing, or carry it in other units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReadOptions {
    /// Lateral size along x \[m\] for formats without spacing (bare `.npy`, plain matrix).
    pub length_x: Option<f64>,
    /// Lateral size along y \[m\]; defaults to `length_x * ny / nx` (square cells).
    pub length_y: Option<f64>,
    /// Metres per file unit, applied to heights and to coordinates read from the file
    /// (e.g. `1e-4` for the contact-mechanics challenge's files, in units of 0.1 mm).
    pub unit: f64,
    /// Whether a file without metadata is periodic.
    pub periodic: bool,
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions {
            length_x: None,
            length_y: None,
            unit: 1.0,
            periodic: true,
        }
    }
}

impl ReadOptions {
    /// The grid of an `(ny, nx)` array read from `path`, from the lengths given here.
    fn grid_for(&self, path: &Path, ny: usize, nx: usize) -> Result<Grid> {
        let lx = self.length_x.ok_or_else(|| {
            SurfError::parse(
                path,
                None,
                "the file does not say its lateral size: give it (e.g. --length in metres)",
            )
        })?;
        let ly = self.length_y.unwrap_or(lx * ny as f64 / nx as f64);
        Grid::new(nx, ny, lx, ly)
    }
}

/// The JSON sidecar of a `.npy` surface: its grid, how it was made and its statistics.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Metadata {
    /// Always `"roughcontact-surface"`.
    pub format: String,
    /// Version of the crate that wrote it.
    pub version: String,
    /// Units of every length in this file and in the array: always `"m"`.
    pub units: String,
    pub grid: Grid,
    pub periodic: bool,
    /// The generator's parameters, for generated surfaces.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spec: Option<SurfaceSpec>,
    /// The realised PSD plateau C0 [m^4], for generated surfaces.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prefactor: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub statistics: Option<Statistics>,
}

impl Metadata {
    /// Metadata of `surface` with nothing else known.
    pub fn of(surface: &Surface) -> Self {
        Metadata {
            format: "roughcontact-surface".into(),
            version: env!("CARGO_PKG_VERSION").into(),
            units: "m".into(),
            grid: surface.grid,
            periodic: surface.periodic,
            spec: None,
            prefactor: None,
            statistics: None,
        }
    }
}

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
}

/// Metres per unit of a length unit's name as instruments write it (`m`, `mm`, `µm` or `um`,
/// `nm`, `pm`, `Å`, ...).
pub(crate) fn length_unit(name: &str) -> Option<f64> {
    Some(match name.trim() {
        "" | "m" => 1.0,
        "dm" => 1e-1,
        "cm" => 1e-2,
        "mm" => 1e-3,
        "um" | "µm" | "μm" | "micrometer" | "micrometre" => 1e-6,
        "nm" => 1e-9,
        "Å" | "A" | "angstrom" => 1e-10,
        "pm" => 1e-12,
        _ => return None,
    })
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
            "" => Err(SurfError::parse(
                path,
                None,
                "the file name has no extension, which names the format: give one of .npy, \
                 .txt/.dat/.asc/.csv, .xyz/.xyh, .gsf, .x3p, .sdf, .nc, .tmd, .mi, .nid, .sur, .opd",
            )),
            _ => Err(SurfError::parse(
                path,
                None,
                format!(
                    "unknown surface format '.{ext}' (known: .npy, .txt/.dat/.asc/.csv, .xyz/.xyh, .gsf, .x3p, .sdf, .nc, .tmd, .mi, .nid, .sur, .opd)"
                ),
            )),
        }
    }
}

/// The sidecar path of a `.npy` file: same stem, `.json`.
pub fn sidecar_path(path: &Path) -> PathBuf {
    path.with_extension("json")
}

/// Reads a surface in any known format (see the module docs).
pub fn read(path: &Path, options: &ReadOptions) -> Result<Surface> {
    if !(options.unit.is_finite() && options.unit > 0.0) {
        return Err(SurfError::invalid(
            "unit",
            options.unit,
            "metres per file unit must be > 0",
        ));
    }
    if path.is_dir() {
        return Err(SurfError::parse(path, None, "is a directory, not a surface file"));
    }
    let surface = match Format::of(path)? {
        Format::Npy => npy::read(path, options)?,
        Format::Matrix => text::read_matrix(path, options)?,
        Format::Xyh => text::read_xyh(path, options)?,
        Format::Gsf => gsf::read(path, options)?,
        Format::X3p => x3p::read(path, options)?,
        Format::Sdf => sdf::read(path, options)?,
        Format::NetCdf => netcdf::read(path, options)?,
        Format::Tmd => tmd::read(path, options)?,
        Format::Mi => mi::read(path, options)?,
        Format::Nid => nid::read(path, options)?,
        Format::Sur => sur::read(path, options)?,
        Format::Opd => opd::read(path, options)?,
    };
    check_finite(surface.heights.view())?;
    Ok(surface)
}

/// Writes `surface` in the format its extension names. For `.npy`, `metadata` (or, when `None`,
/// [`Metadata::of`] the surface) goes to the JSON sidecar; other formats keep grid and
/// periodicity only. `.gsf` stores heights as f32.
pub fn write(surface: &Surface, path: &Path, metadata: Option<&Metadata>) -> Result<()> {
    match Format::of(path)? {
        Format::Npy => npy::write(surface, path, metadata),
        Format::Matrix => text::write_matrix(surface, path),
        Format::Xyh => text::write_xyh(surface, path),
        Format::Gsf => gsf::write(surface, path),
        Format::X3p => x3p::write(surface, path),
        Format::Sdf => sdf::write(surface, path),
        Format::NetCdf => netcdf::write(surface, path),
        Format::Tmd | Format::Mi | Format::Nid | Format::Sur | Format::Opd => Err(SurfError::parse(
            path,
            None,
            "instruments' own formats are read, not written: write .x3p, .sdf or .nc for other tools",
        )),
    }
}

/// Reads the JSON sidecar of a `.npy` file, if there is one.
pub fn read_metadata(npy_path: &Path) -> Result<Option<Metadata>> {
    npy::read_sidecar(npy_path)
}

/// Writes `metadata` as the JSON sidecar of the surface file `path` (`<stem>.json`), whatever
/// the surface's format.
pub fn write_metadata(path: &Path, metadata: &Metadata) -> Result<()> {
    let side = sidecar_path(path);
    let json = serde_json::to_string_pretty(metadata).expect("metadata serialises");
    std::fs::write(&side, json + "\n").map_err(|e| SurfError::io(&side, e))
}
