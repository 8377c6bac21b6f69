//! How a file is read: the sizes and unit it does not carry, its channel, its unmeasured points.

use crate::error::{Result, SurfError};
use crate::grid::Grid;
use std::path::Path;
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
    /// Whether a file without metadata is periodic (an instrument's file is a measurement:
    /// never).
    pub periodic: bool,
    /// Which channel of a multi-channel file to read, by its index in [`super::channels`]; `None`
    /// reads the first channel of heights.
    pub channel: Option<usize>,
    /// What to do with points the instrument marks as not measured.
    pub unmeasured: Unmeasured,
}

/// Points an instrument marks as not measured (dropouts, out of range): a contact calculation
/// needs a height at every point, so they are refused unless the user asks for them filled.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Unmeasured {
    /// An error that counts them.
    #[default]
    Refuse,
    /// Filled by harmonic interpolation from the measured points around them ([`super::fill_harmonic`]),
    /// up to this fraction of the points, in [0, 1] (more is refused).
    FillUpTo(f64),
}

/// The largest fraction of a surface's points filled unless the user allows more: beyond a
/// quarter, the filled surface is more interpolation than measurement.
pub const MAX_FILLED_FRACTION: f64 = 0.25;

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions {
            length_x: None,
            length_y: None,
            unit: 1.0,
            periodic: true,
            channel: None,
            unmeasured: Unmeasured::Refuse,
        }
    }
}

impl Unmeasured {
    /// Filled if `fill` up to `max_fraction` of the points ([`MAX_FILLED_FRACTION`] if `None`),
    /// else refused; a fraction outside [0, 1] is refused, naming `max_unmeasured`.
    pub fn filled_up_to(fill: bool, max_fraction: Option<f64>) -> Result<Self> {
        match (fill, max_fraction) {
            (_, Some(f)) if !(0.0..=1.0).contains(&f) => Err(SurfError::invalid(
                "max_unmeasured",
                f,
                "a fraction of the points in [0, 1]",
            )),
            (false, Some(f)) => Err(SurfError::invalid(
                "max_unmeasured",
                f,
                "applies with fill_unmeasured (--fill-unmeasured), which fills the points",
            )),
            (false, None) => Ok(Unmeasured::Refuse),
            (true, f) => Ok(Unmeasured::FillUpTo(f.unwrap_or(MAX_FILLED_FRACTION))),
        }
    }
}

impl ReadOptions {
    /// The grid of an `(ny, nx)` array read from `path`, from the lengths given here.
    pub(super) fn grid_for(&self, path: &Path, ny: usize, nx: usize) -> Result<Grid> {
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
