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
//! | `.gwy` | Gwyddion native: every `/N/data` field a channel, `/N/mask` unmeasured (read only) | each field's `xreal`, `yreal` |
//! | `.h5`, `.hdf5`, `.datx` | HDF5 (Zygo's too): every 2-D (or 1-D: a line scan) numeric dataset a channel, its `Unit` and `No Data` (read only) | [`ReadOptions`] |
//! | `.di`, `.spm`, `.001`... | Bruker / Veeco / DI Nanoscope: every image a channel (read only) | `Scan Size` |
//! | `.ibw` | Igor binary wave v5 (Asylum AFMs): every layer a channel (read only) | the wave's scaling |
//! | `.mi` | Molecular Imaging / Agilent PicoView: every buffer a channel (read only) | the header |
//! | `.nid` | Nanosurf: every channel (read only) | the channel's ranges |
//! | `.sur` | Digital Surf / MountainsMap surface (read only) | the header |
//! | `.mnt` | MountainsMap document: every measured surface a channel, its mask (read only) | the lateral axes' steps |
//! | `.opd` | Wyko / Veeco Vision (read only) | `Pixel_size`, `Aspect` |
//! | `.frt` | FRT MicroProf (read only) | its size block |
//! | `.tmd` | TrueMap / TrueSurf binary (read only) | the header |
//!
//! A file of several channels reads its first channel of heights unless
//! [`ReadOptions::channel`] names one ([`channels`] lists them). Points the instrument marks as
//! not measured read as NaN ([`read_measurement`]) and are refused or filled as
//! [`ReadOptions::unmeasured`] says; a line scan reads as a [`Profile`] ([`read_topography`]).
//!
//! Heights and lengths are in metres; [`ReadOptions::unit`] converts files written in other
//! units. Readers check everything (shape, finiteness, ragged rows, sizes against the file's
//! length) and return an error naming the file and line rather than a partial surface.

mod di;
mod fill;
mod frt;
mod gsf;
mod gwy;
mod h5;
mod ibw;
mod mi;
mod mnt;
mod netcdf;
mod nid;
mod npy;
mod opd;
mod sdf;
mod sur;
mod tmd;
mod x3p;

pub use fill::fill_harmonic;
pub use npy::write_array as write_npy;
mod options;
mod text;

pub use options::{MAX_FILLED_FRACTION, ReadOptions, Unmeasured};

use crate::error::{Result, SurfError};
use crate::generate::SurfaceSpec;
use crate::grid::Grid;
use crate::grid::MAX_LENGTH;
use crate::stats::Statistics;
use ndarray::Array2;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A reader of a format of several channels: each channel and how to read it.
type LayerReader = for<'a> fn(&'a [u8], &Path) -> Result<Vec<Layer<'a>>>;
/// How a format is read.
#[derive(Clone, Copy)]
enum Reader {
    /// One surface.
    Surface(fn(&Path, &ReadOptions) -> Result<Measurement>),
    /// A surface or a line scan (a text matrix).
    Topography(fn(&Path, &ReadOptions) -> Result<Topography>),
    /// Several channels ([`Layer`]s), each read when asked for.
    Layers(LayerReader),
}

/// The file formats, one entry each: its variant of [`Format`], its extensions (lower case),
/// how it is read, whether it is an instrument's measurement (never periodic, whatever the
/// options assume), and its writer, if it has one. Adding a format is its file and one entry.
macro_rules! formats {
    ($($variant:ident [$($extension:literal),+] $reader:expr, instrument: $instrument:literal, write: $writer:expr;)*) => {
        /// The file formats, chosen by extension.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Format {
            $($variant,)*
        }

        impl Format {
            /// Every format, in the table's order.
            const ALL: &'static [Format] = &[$(Format::$variant),*];

            /// The format's extensions, lower case.
            fn extensions(self) -> &'static [&'static str] {
                match self {
                    $(Format::$variant => &[$($extension),+],)*
                }
            }

            fn reader(self) -> Reader {
                match self {
                    $(Format::$variant => $reader,)*
                }
            }

            /// Whether a file of this format is an instrument's measurement.
            fn instrument(self) -> bool {
                match self {
                    $(Format::$variant => $instrument,)*
                }
            }

            fn writer(self) -> Option<fn(&Surface, &Path) -> Result<()>> {
                match self {
                    $(Format::$variant => $writer,)*
                }
            }
        }
    };
}

formats! {
    Npy ["npy"] Reader::Surface(npy::read), instrument: false, write: None;
    Matrix ["txt", "dat", "asc", "csv"] Reader::Topography(text::read_matrix), instrument: false, write: Some(text::write_matrix);
    Xyh ["xyz", "xyh"] Reader::Surface(text::read_xyh), instrument: false, write: Some(text::write_xyh);
    Gsf ["gsf"] Reader::Surface(gsf::read), instrument: false, write: Some(gsf::write);
    X3p ["x3p"] Reader::Surface(x3p::read), instrument: false, write: Some(x3p::write);
    Sdf ["sdf"] Reader::Surface(sdf::read), instrument: false, write: Some(sdf::write);
    NetCdf ["nc"] Reader::Surface(netcdf::read), instrument: false, write: Some(netcdf::write);
    Tmd ["tmd"] Reader::Surface(tmd::read), instrument: true, write: None;
    Mi ["mi"] Reader::Layers(mi::layers), instrument: true, write: None;
    Nid ["nid"] Reader::Layers(nid::layers), instrument: true, write: None;
    Sur ["sur"] Reader::Surface(sur::read), instrument: true, write: None;
    Opd ["opd"] Reader::Surface(opd::read), instrument: true, write: None;
    Di ["di", "spm"] Reader::Layers(di::layers), instrument: true, write: None;
    Ibw ["ibw"] Reader::Layers(ibw::layers), instrument: true, write: None;
    Frt ["frt"] Reader::Surface(frt::read), instrument: true, write: None;
    Gwy ["gwy"] Reader::Layers(gwy::layers), instrument: true, write: None;
    Hdf5 ["h5", "hdf5", "hdf", "datx"] Reader::Layers(h5::layers), instrument: false, write: None;
    Mnt ["mnt"] Reader::Layers(mnt::layers), instrument: true, write: None;
}

impl Format {
    /// The format of `path`, from its extension.
    pub fn of(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        if let Some(&format) = Format::ALL
            .iter()
            .find(|f| f.extensions().contains(&ext.as_str()))
        {
            return Ok(format);
        }
        // Nanoscope's older files are numbered: .000, .001, ...
        if ext.len() == 3 && ext.bytes().all(|b| b.is_ascii_digit()) {
            return Ok(Format::Di);
        }
        let known = Format::ALL
            .iter()
            .map(|f| format!(".{}", f.extensions().join("/.")))
            .collect::<Vec<_>>()
            .join(", ");
        Err(SurfError::parse(
            path,
            None,
            if ext.is_empty() {
                format!("the file name has no extension, which names the format: give one of {known}")
            } else {
                format!("unknown surface format '.{ext}' (known: {known})")
            },
        ))
    }
}

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

/// One channel (layer, image) of a file, as [`channels`] lists it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Channel {
    /// The channel's name in the file (`Height`, `ZSensor`, `Phase`, ...).
    pub name: String,
    /// Points along x and y; `ny` is 1 for a line scan.
    pub nx: usize,
    pub ny: usize,
    /// Lateral sizes \[m\] where the file gives them.
    pub length_x: Option<f64>,
    pub length_y: Option<f64>,
    /// The unit of the values as the file names it.
    pub unit: String,
    /// Whether the values are heights (a length unit), which a contact calculation reads.
    pub height: bool,
}

/// A channel of a multi-channel file and how to read its values: heights \[m\] of shape
/// `(ny, nx)`, row 0 at y = 0, NaN where not measured.
pub(crate) struct Layer<'a> {
    pub channel: Channel,
    pub values: Box<dyn FnOnce() -> Result<Array2<f64>> + 'a>,
}

/// The channel `options` asks for (by default the first channel of heights), read.
pub(crate) fn pick(path: &Path, layers: Vec<Layer<'_>>, options: &ReadOptions) -> Result<Topography> {
    let bad = |m: String| SurfError::parse(path, None, m);
    let names = || {
        layers
            .iter()
            .enumerate()
            .map(|(i, l)| format!("{i} '{}' [{}]", l.channel.name, l.channel.unit))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let index = match options.channel {
        Some(i) if i >= layers.len() => {
            return Err(bad(format!("no channel {i}: the file holds {}", names())));
        }
        Some(i) if !layers[i].channel.height => {
            return Err(bad(format!(
                "channel {i} '{}' holds {}, not heights (the file holds {})",
                layers[i].channel.name,
                layers[i].channel.unit,
                names()
            )));
        }
        Some(i) => i,
        None => {
            // A surface before a line scan; among them, a channel named as the topography
            // before the other channels in a length unit.
            let rank = |l: &Layer| {
                let name = l.channel.name.to_ascii_lowercase();
                let named = ["height", "topography", "zsensor"]
                    .iter()
                    .any(|n| name.contains(n));
                (l.channel.ny == 1, !named)
            };
            layers
                .iter()
                .enumerate()
                .filter(|(_, l)| l.channel.height)
                .min_by_key(|(i, l)| (rank(l), *i))
                .map(|(i, _)| i)
                .ok_or_else(|| bad(format!("no channel of heights among {}", names())))?
        }
    };
    let layer = layers.into_iter().nth(index).expect("in range");
    let Channel {
        nx,
        ny,
        length_x,
        length_y,
        ..
    } = layer.channel;
    let heights = (layer.values)()?.mapv(|h| h * options.unit);
    if ny == 1 {
        return Ok(Topography::Profile(Profile {
            heights: heights.into_iter().collect(),
            // The file's length is in its units; a length given in the options is in metres.
            length: length_x.map(|l| l * options.unit).or(options.length_x),
            channel: index,
        }));
    }
    let grid = match (length_x, length_y) {
        (Some(lx), Some(ly)) => {
            Grid::new(nx, ny, lx * options.unit, ly * options.unit).map_err(|e| bad(e.to_string()))?
        }
        _ => options.grid_for(path, ny, nx)?,
    };
    Ok(Topography::Surface(Measurement {
        channel: index,
        ..Measurement::new(heights, grid, options.periodic)?
    }))
}

/// What a file holds: a surface, or a line scan.
#[derive(Clone, Debug, PartialEq)]
pub enum Topography {
    Surface(Measurement),
    Profile(Profile),
}

/// A line scan: heights \[m\] along x, NaN where not measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    pub heights: Vec<f64>,
    /// Its length \[m\], where the file or [`ReadOptions::length_x`] gives it.
    pub length: Option<f64>,
    /// The index of the channel read.
    pub channel: usize,
}

/// A surface as a file holds it: heights \[m\] of shape `(ny, nx)`, NaN where the instrument
/// did not measure.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    pub heights: Array2<f64>,
    pub grid: Grid,
    pub periodic: bool,
    /// The index of the channel read (0 for formats of one surface).
    pub channel: usize,
}

impl Measurement {
    /// A measurement, checked for its shape.
    pub(crate) fn new(heights: Array2<f64>, grid: Grid, periodic: bool) -> Result<Self> {
        if heights.dim() != grid.shape() {
            return Err(SurfError::ShapeMismatch {
                expected: grid.shape(),
                got: heights.dim(),
            });
        }
        Ok(Measurement {
            heights,
            grid,
            periodic,
            channel: 0,
        })
    }

    /// How many points are not measured.
    pub fn unmeasured(&self) -> usize {
        self.heights.iter().filter(|h| h.is_nan()).count()
    }

    /// The surface, its unmeasured points refused or filled as `policy` says; `path` names
    /// the file in the error.
    pub fn into_surface(mut self, path: &Path, policy: Unmeasured) -> Result<Surface> {
        let unmeasured = self.unmeasured();
        let n = self.heights.len();
        if unmeasured == n {
            return Err(SurfError::parse(path, None, "no point is measured"));
        }
        if unmeasured > 0 {
            let fraction = unmeasured as f64 / n as f64;
            if let Unmeasured::FillUpTo(limit) = policy
                && fraction > limit
            {
                return Err(SurfError::parse(
                    path,
                    None,
                    format!(
                        "{unmeasured} of {n} points ({:.1} %) are not measured: filling more than {:.0} % \
                         of a surface invents it rather than measures it; give max_unmeasured \
                         (--max-unmeasured) up to 1 to fill them anyway",
                        100.0 * fraction,
                        100.0 * limit
                    ),
                ));
            }
            match policy {
                Unmeasured::Refuse => {
                    return Err(SurfError::parse(
                        path,
                        None,
                        format!(
                            "{unmeasured} of {n} points are not measured (the file marks them): a contact \
                             calculation needs every point; fill them by harmonic interpolation \
                             (--fill-unmeasured) or in the instrument's software"
                        ),
                    ));
                }
                Unmeasured::FillUpTo(_) => fill_harmonic(&mut self.heights, self.periodic),
            }
        }
        Surface::new(self.heights, self.grid, self.periodic)
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

/// `ny` rows of `nx` values stored from an image's top, as heights with row 0 at y = 0.
pub(crate) fn rows_from_top(ny: usize, nx: usize, values: Vec<f64>) -> Array2<f64> {
    let mut a = Array2::from_shape_vec((ny, nx), values).expect("counted by the reader");
    a.invert_axis(ndarray::Axis(0));
    a.as_standard_layout().into_owned()
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

/// The sidecar path of a `.npy` file: same stem, `.json`.
pub fn sidecar_path(path: &Path) -> PathBuf {
    path.with_extension("json")
}

/// Reads a surface in any known format (see the module docs); unmeasured points are refused or
/// filled as [`ReadOptions::unmeasured`] says.
pub fn read(path: &Path, options: &ReadOptions) -> Result<Surface> {
    Ok(read_noting(path, options)?.0)
}

/// [`read`], with a note of the points filled, if any, for the user to see.
pub fn read_noting(path: &Path, options: &ReadOptions) -> Result<(Surface, Option<String>)> {
    let measured = read_measurement(path, options)?;
    let (unmeasured, n) = (measured.unmeasured(), measured.heights.len());
    let surface = measured.into_surface(path, options.unmeasured)?;
    let note = (unmeasured > 0).then(|| {
        format!(
            "{}: {unmeasured} of {n} points ({:.2} %) were not measured and are filled by harmonic \
             interpolation; results depend on the fill there",
            path.display(),
            100.0 * unmeasured as f64 / n as f64
        )
    });
    Ok((surface, note))
}

/// Reads a surface as the file holds it, NaN where the instrument did not measure; a line
/// scan is refused, saying what it is.
pub fn read_measurement(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    match read_topography(path, options)? {
        Topography::Surface(m) => Ok(m),
        Topography::Profile(p) => Err(SurfError::parse(
            path,
            None,
            format!(
                "a line scan (a profile of {} points{}), not a surface: a contact calculation needs \
                 a two-dimensional topography",
                p.heights.len(),
                p.length.map(|l| format!(" over {l:e} m")).unwrap_or_default()
            ),
        )),
    }
}

/// Reads what a file holds, surface or line scan, NaN where the instrument did not measure.
pub fn read_topography(path: &Path, options: &ReadOptions) -> Result<Topography> {
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
    let format = Format::of(path)?;
    let instrument = format.instrument();
    let options = &ReadOptions {
        periodic: options.periodic && !instrument,
        ..*options
    };
    let read = if let Some(reader) = layer_reader(format) {
        pick(path, reader(&read_bytes(path)?, path)?, options)?
    } else {
        read_single(path, format, options)?
    };
    given_options_used(path, &read, options)?;
    Ok(read)
}

/// Refuses a box size or a non-periodic reading asked for in the options that the reading did
/// not use: a file that carries its own size (or says it repeats) is read as it says, and an
/// option given beside it would otherwise be dropped without a word (and recorded as if it had
/// been used).
fn given_options_used(path: &Path, read: &Topography, options: &ReadOptions) -> Result<()> {
    if let Topography::Surface(m) = read
        && m.periodic
        && !options.periodic
    {
        return Err(SurfError::parse(
            path,
            None,
            "the file says the surface repeats across its edges (periodic), so a non-periodic \
             reading (--not-periodic, periodic=False) does not apply: leave it out",
        ));
    }
    let (lx, ly) = match read {
        Topography::Surface(m) => (Some(m.grid.length_x), Some(m.grid.length_y)),
        Topography::Profile(p) => (p.length, None),
    };
    let differs = |given: Option<f64>, used: Option<f64>| match (given, used) {
        (Some(g), Some(u)) => (g - u).abs() > 1e-12 * u.abs(),
        (Some(_), None) => true,
        _ => false,
    };
    for (name, given, used) in [
        ("length", options.length_x, lx),
        ("length_y", options.length_y, ly),
    ] {
        if differs(given, used) {
            return Err(SurfError::parse(
                path,
                None,
                format!(
                    "the file gives its own box ({}), so `{name}` = {:e} m does not apply: leave it out",
                    match (lx, ly) {
                        (Some(x), Some(y)) => format!("{x:e} x {y:e} m"),
                        (Some(x), None) => format!("a line of {x:e} m"),
                        _ => "no size".to_string(),
                    },
                    given.unwrap_or(f64::NAN)
                ),
            ));
        }
    }
    Ok(())
}

/// Reads a format of one surface.
fn read_single(path: &Path, format: Format, options: &ReadOptions) -> Result<Topography> {
    if let Some(c) = options.channel.filter(|&c| c > 0) {
        return Err(SurfError::parse(
            path,
            None,
            format!("no channel {c}: the file holds one surface (channel 0)"),
        ));
    }
    match format.reader() {
        Reader::Surface(read) => Ok(Topography::Surface(read(path, options)?)),
        Reader::Topography(read) => read(path, options),
        Reader::Layers(_) => unreachable!("formats of several channels are read by their layers"),
    }
}

/// What a number of a file's header is, and so what it must be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Number {
    /// An offset: finite and at most [`MAX_LENGTH`] in magnitude.
    Offset,
    /// A height per stored count: not zero (its sign may flip the heights), and small enough
    /// that any count times it stays within [`MAX_LENGTH`].
    Scale,
    /// A size or a spacing: > 0 and at most [`MAX_LENGTH`].
    Size,
}

/// The largest height scale a header may give [m a count]: [`MAX_LENGTH`] over the largest
/// 32-bit count.
const MAX_SCALE: f64 = MAX_LENGTH / 4294967296.0;

/// A number `value` of the header field `field` of `path`, checked where it is read, so that a
/// bad header is named instead of turning into NaN heights, a flat surface or a broken grid.
pub(crate) fn header(path: &Path, field: &str, value: f64, number: Number) -> Result<f64> {
    let (ok, what) = match number {
        Number::Offset => (
            value.abs() <= MAX_LENGTH,
            "a finite number of at most 1e100 in magnitude",
        ),
        Number::Scale => (
            value != 0.0 && value.abs() <= MAX_SCALE,
            "a number other than 0, of at most 2.3e90 in magnitude",
        ),
        Number::Size => (
            value > 0.0 && value <= MAX_LENGTH,
            "a number > 0 and at most 1e100",
        ),
    };
    if ok {
        Ok(value)
    } else {
        Err(SurfError::parse(
            path,
            None,
            format!("the header's {field} is {value:?}; it must be {what}"),
        ))
    }
}

/// A height offset `value` of the header field `field`, checked against the height step
/// `step` (from the field `step_field`) it is added to: an offset so much larger than the step
/// that the heights' differences fall below its rounding would read as a flat surface, so the
/// pair is refused, both named.
pub(crate) fn offset(path: &Path, field: &str, value: f64, step_field: &str, step: f64) -> Result<f64> {
    header(path, field, value, Number::Offset)?;
    // Beyond 2^50 steps the offset's rounding (2^-52 of it) reaches a quarter of a step.
    if value.abs() > step.abs() * 2f64.powi(50) {
        return Err(SurfError::parse(
            path,
            None,
            format!(
                "the header's {field} is {value:?}, more than 2^50 height steps ({:?}, from its \
                 {step_field}): the heights would lose their differences to its rounding",
                step.abs()
            ),
        ));
    }
    Ok(value)
}

impl ReadOptions {
    /// These options reading the channel `key` names in the file at `path` (an index or a
    /// name, [`channel_index`]); `None` keeps the default channel.
    pub fn with_channel(self, path: &Path, key: Option<&str>) -> Result<Self> {
        Ok(match key {
            Some(key) => ReadOptions {
                channel: Some(channel_index(path, &self, key)?),
                ..self
            },
            None => self,
        })
    }
}

/// The index of the channel `key` names in the file: an index, or a channel's name (exactly,
/// else ignoring case).
pub fn channel_index(path: &Path, options: &ReadOptions, key: &str) -> Result<usize> {
    if let Ok(index) = key.trim().parse() {
        return Ok(index);
    }
    let channels = channels(path, options)?;
    channels
        .iter()
        .position(|c| c.name == key)
        .or_else(|| channels.iter().position(|c| c.name.eq_ignore_ascii_case(key)))
        .ok_or_else(|| {
            let names: Vec<String> = channels.iter().map(|c| format!("'{}'", c.name)).collect();
            SurfError::parse(
                path,
                None,
                format!("no channel named '{key}' (the file holds {})", names.join(", ")),
            )
        })
}

/// The reader of `format` if it holds several channels; `None` for a format of one surface.
fn layer_reader(format: Format) -> Option<LayerReader> {
    match format.reader() {
        Reader::Layers(reader) => Some(reader),
        Reader::Surface(_) | Reader::Topography(_) => None,
    }
}

fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| SurfError::io(path, e))
}

/// The channels of a file: each with its grid, size and unit, and whether it holds heights. A
/// format of one surface gives one channel, `heights`, read with `options`.
pub fn channels(path: &Path, options: &ReadOptions) -> Result<Vec<Channel>> {
    let format = Format::of(path)?;
    if let Some(reader) = layer_reader(format) {
        let bytes = read_bytes(path)?;
        return Ok(reader(&bytes, path)?.into_iter().map(|l| l.channel).collect());
    }
    Ok(vec![match read_topography(path, options)? {
        Topography::Surface(m) => Channel {
            name: "heights".into(),
            nx: m.grid.nx,
            ny: m.grid.ny,
            length_x: Some(m.grid.length_x),
            length_y: Some(m.grid.length_y),
            unit: "m".into(),
            height: true,
        },
        Topography::Profile(p) => Channel {
            name: "profile".into(),
            nx: p.heights.len(),
            ny: 1,
            length_x: p.length,
            length_y: None,
            unit: "m".into(),
            height: true,
        },
    }])
}

/// Writes `surface` in the format its extension names. For `.npy`, `metadata` (or, when `None`,
/// [`Metadata::of`] the surface) goes to the JSON sidecar; other formats keep grid and
/// periodicity only. `.gsf` stores heights as f32.
pub fn write(surface: &Surface, path: &Path, metadata: Option<&Metadata>) -> Result<()> {
    let format = Format::of(path)?;
    if format == Format::Npy {
        npy::write_array(&surface.heights, path)?;
        return write_metadata(path, metadata.unwrap_or(&Metadata::of(surface)));
    }
    let Some(writer) = format.writer() else {
        return Err(SurfError::parse(
            path,
            None,
            "instruments' own formats are read, not written: write .x3p, .sdf or .nc for other tools",
        ));
    };
    atomically(path, |p| writer(surface, p))
}

/// Writes `path` whole or not at all: `write` writes a hidden sibling of the same extension
/// (writers choose the format by it), which is then renamed onto `path`; on failure the
/// sibling is removed and `path` is left as it was. A run killed at any moment leaves the old
/// file or the new one, never half of one.
pub fn atomically<E: From<SurfError>>(
    path: &Path,
    write: impl FnOnce(&Path) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let ext = path
        .extension()
        .map_or(String::new(), |e| format!(".{}", e.to_string_lossy()));
    let partial = path.with_file_name(format!(".{stem}.partial-{}{ext}", std::process::id()));
    let written = write(&partial)
        .and_then(|()| std::fs::rename(&partial, path).map_err(|e| SurfError::io(path, e).into()));
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written
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
    atomically(&side, |p| {
        std::fs::write(p, json + "\n").map_err(|e| SurfError::io(&side, e))
    })
}
