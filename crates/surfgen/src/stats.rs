//! Statistics of a surface, each with its exact definition.
//!
//! Averages `<.>` run over all grid points. Spectral quantities come from the DFT `H_k` of the
//! heights (periodic extension, no window) by Parseval's theorem,
//! `<f^2> = sum_k |F_k|^2 / N^2`, with the Nyquist wavevector taken as `pi / spacing`.
//! Finite-difference quantities use forward differences for slopes and the 3-point second
//! difference for curvatures, wrapping around on periodic surfaces and using only interior
//! points otherwise. For a resolved spectrum (shortest wavelength >= ~8 spacings) both agree;
//! for an unresolved one the finite differences are smaller, as they must be.

use crate::grid::Grid;
use fft2::Complex64;
use fft2::Fft2;
use ndarray::{ArrayView2, Axis};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Sum of per-row partial sums in a fixed order, so that results do not depend on the number
/// of threads.
fn ordered_sum<const K: usize>(rows: Vec<[f64; K]>) -> [f64; K] {
    rows.into_iter().fold([0.0; K], |mut acc, r| {
        acc.iter_mut().zip(r).for_each(|(a, v)| *a += v);
        acc
    })
}

/// Second moments of the spectrum: `<h^2>` and the mean squares of derivatives, computed
/// exactly from the DFT (zero mode excluded, so `m0` is the variance).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SpectralMoments {
    /// `<(h - <h>)^2>` [m^2].
    pub m0: f64,
    /// `<|grad h|^2>` [-].
    pub m2: f64,
    /// `<(laplacian h)^2>` [1/m^2].
    pub m4: f64,
    /// `<(d2h/dx2)^2>` [1/m^2].
    pub m4_xx: f64,
}

impl SpectralMoments {
    /// Moments of the field whose DFT is `spectrum` (transposed half spectrum, see [`fft2`]).
    pub fn from_spectrum(spectrum: ArrayView2<Complex64>, grid: &Grid) -> Self {
        let (nx, ny) = (grid.nx, grid.ny);
        let qy2: Vec<f64> = (0..ny)
            .map(|ky| Grid::wavevector(ky, ny, grid.length_y).powi(2))
            .collect();
        let rows: Vec<[f64; 4]> = spectrum
            .axis_iter(Axis(0))
            .into_par_iter()
            .enumerate()
            .map(|(kx, column)| {
                // Columns 0 < kx < nx/2 stand for themselves and their mirror image.
                let weight = if kx == 0 || (nx.is_multiple_of(2) && kx == nx / 2) {
                    1.0
                } else {
                    2.0
                };
                let qx = Grid::wavevector(kx, nx, grid.length_x);
                let mut s = [0.0; 4];
                for (ky, c) in column.iter().enumerate() {
                    if kx == 0 && ky == 0 {
                        continue;
                    }
                    let q2 = qx * qx + qy2[ky];
                    let p = weight * c.norm_sqr();
                    s[0] += p;
                    s[1] += p * q2;
                    s[2] += p * q2 * q2;
                    s[3] += p * qx.powi(4);
                }
                s
            })
            .collect();
        let n2 = (grid.len() as f64).powi(2);
        let [m0, m2, m4, m4_xx] = ordered_sum(rows).map(|v| v / n2);
        SpectralMoments { m0, m2, m4, m4_xx }
    }

    /// The moments of the same surface with all heights multiplied by `factor`.
    pub fn scaled(&self, factor: f64) -> Self {
        let f2 = factor * factor;
        SpectralMoments {
            m0: self.m0 * f2,
            m2: self.m2 * f2,
            m4: self.m4 * f2,
            m4_xx: self.m4_xx * f2,
        }
    }

    /// RMS height Rq \[m\].
    pub fn rms_height(&self) -> f64 {
        self.m0.sqrt()
    }

    /// RMS gradient `sqrt(<|grad h|^2>)` [-].
    pub fn rms_gradient(&self) -> f64 {
        self.m2.sqrt()
    }
}

/// Curvature measures [1/m], all root-mean-square values.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Curvatures {
    /// `sqrt(<(laplacian h)^2>)`.
    pub laplacian: f64,
    /// `sqrt(<(laplacian h / 2)^2>)`: the mean curvature of the small-slope surface. For a
    /// paraboloid `r^2 / (2R)` it is `1/R`, which is why its inverse is the local radius.
    pub mean: f64,
    /// `sqrt(<(d2h/dx2)^2>)`: the curvature of x-profiles.
    pub profile_x: f64,
}

impl Curvatures {
    fn new(m4: f64, m4_xx: f64) -> Self {
        Curvatures {
            laplacian: m4.sqrt(),
            mean: 0.5 * m4.sqrt(),
            profile_x: m4_xx.sqrt(),
        }
    }
}

/// Radially averaged power spectral density on logarithmic bins, in the convention of
/// [`crate::psd`]: `C = A |H_k|^2 / ((2 pi)^2 N^2)` [m^4] averaged over the wavevectors whose
/// magnitude falls in each bin (each independent wavevector counted once). Empty bins are left out.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RadialPsd {
    /// Mean wavevector magnitude of each bin [rad/m].
    pub q: Vec<f64>,
    /// Mean PSD of each bin [m^4].
    pub psd: Vec<f64>,
    /// Standard error of that mean [m^4] (0 for bins of one wavevector).
    pub std_err: Vec<f64>,
    /// Number of independent wavevectors in each bin.
    pub count: Vec<usize>,
    /// Mean of `ln q` over the bin's wavevectors with a non-zero PSD (NaN if none).
    pub mean_ln_q: Vec<f64>,
    /// Mean of `ln C` over the same wavevectors (NaN if none). A power law `C ~ q^s` holds
    /// exactly between these log-means whatever the bin's shape, which makes them the right
    /// points for fitting `s`.
    pub mean_ln_psd: Vec<f64>,
}

impl RadialPsd {
    /// Bins the spectrum from the smallest non-zero `|q|` up, `bins_per_decade` bins per decade.
    ///
    /// # Panics
    /// If `bins_per_decade` is 0.
    pub fn from_spectrum(spectrum: ArrayView2<Complex64>, grid: &Grid, bins_per_decade: usize) -> Self {
        assert!(bins_per_decade > 0, "bins_per_decade must be positive");
        let (nx, ny) = (grid.nx, grid.ny);
        let q_min = 2.0 * PI / grid.length_x.max(grid.length_y);
        let qx_max = PI / grid.dx();
        let qy_max = PI / grid.dy();
        let q_max = (qx_max * qx_max + qy_max * qy_max).sqrt();
        let nbins = ((q_max / q_min).log10() * bins_per_decade as f64).floor() as usize + 1;
        // Squared upper edges of the bins, so that binning needs no logarithm.
        let edges2: Vec<f64> = (1..nbins)
            .map(|b| (q_min * 10f64.powf(b as f64 / bins_per_decade as f64) * (1.0 - 1e-9)).powi(2))
            .collect();
        let qy2: Vec<f64> = (0..ny)
            .map(|ky| Grid::wavevector(ky, ny, grid.length_y).powi(2))
            .collect();
        let norm = grid.area() / ((2.0 * PI).powi(2) * (grid.len() as f64).powi(2));
        let per_column: Vec<Vec<[f64; 7]>> = spectrum
            .axis_iter(Axis(0))
            .into_par_iter()
            .enumerate()
            .map(|(kx, column)| {
                let mut acc = vec![[0.0; 7]; nbins];
                let self_mirror = kx == 0 || (nx.is_multiple_of(2) && kx == nx / 2);
                let qx2 = Grid::wavevector(kx, nx, grid.length_x).powi(2);
                let mut add = |b: &mut usize, ky: usize| {
                    let q2 = qx2 + qy2[ky];
                    // |q| grows along each walk, so the bin index only moves up.
                    while *b < edges2.len() && edges2[*b] <= q2 {
                        *b += 1;
                    }
                    let p = norm * column[ky].norm_sqr();
                    let a = &mut acc[*b];
                    a[0] += 1.0;
                    a[1] += q2.sqrt();
                    a[2] += p;
                    a[3] += p * p;
                    if p > 0.0 {
                        a[4] += 1.0;
                        a[5] += 0.5 * q2.ln();
                        a[6] += p.ln();
                    }
                };
                // Walk ky = 0, 1, .., ny/2 and then ky = -1, -2, ..; the zero mode and the
                // mirror halves of self-mirrored columns are left out.
                let mut b = 0;
                for ky in usize::from(kx == 0)..=ny / 2 {
                    add(&mut b, ky);
                }
                if !self_mirror {
                    let mut b = 0;
                    for ky in (ny / 2 + 1..ny).rev() {
                        add(&mut b, ky);
                    }
                }
                acc
            })
            .collect();
        let mut total = vec![[0.0; 7]; nbins];
        for col in per_column {
            for (t, c) in total.iter_mut().zip(col) {
                t.iter_mut().zip(c).for_each(|(a, v)| *a += v);
            }
        }
        let mut out = RadialPsd::default();
        for [n, sq, sp, sp2, nl, slq, slp] in total {
            if n == 0.0 {
                continue;
            }
            let mean = sp / n;
            let var = if n > 1.0 {
                ((sp2 / n - mean * mean) * n / (n - 1.0)).max(0.0)
            } else {
                0.0
            };
            out.q.push(sq / n);
            out.psd.push(mean);
            out.std_err.push((var / n).sqrt());
            out.count.push(n as usize);
            out.mean_ln_q.push(slq / nl);
            out.mean_ln_psd.push(slp / nl);
        }
        out
    }

    /// Least-squares fit of `ln C = a + s ln q` through the bins' log-means
    /// ([`RadialPsd::mean_ln_psd`]) for the bins with `q_min <= q <= q_max` and a positive PSD;
    /// the Hurst exponent is `H = -s/2 - 1` (Eq. 13). `None` with fewer than 3 bins.
    pub fn fit_hurst(&self, q_min: f64, q_max: f64) -> Option<HurstFit> {
        let pts: Vec<(f64, f64)> = (0..self.q.len())
            .filter(|&i| self.q[i] >= q_min && self.q[i] <= q_max && self.psd[i] > 0.0)
            .map(|i| (self.mean_ln_q[i], self.mean_ln_psd[i]))
            .collect();
        if pts.len() < 3 {
            return None;
        }
        let n = pts.len() as f64;
        let (mx, my) = pts
            .iter()
            .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
        let sxx: f64 = pts.iter().map(|(x, _)| (x - mx).powi(2)).sum();
        let sxy: f64 = pts.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
        let slope = sxy / sxx;
        Some(HurstFit {
            hurst: -slope / 2.0 - 1.0,
            ln_prefactor: my - slope * mx,
            q_min,
            q_max,
            bins: pts.len(),
        })
    }

    /// The default fit range: from twice the wavevector where the PSD has fallen to half its
    /// maximum (past a roll-off plateau) to half the largest wavevector with a PSD above
    /// `1e-20` of the maximum (before a cut-off or the grid's resolution limit).
    pub fn default_fit_range(&self) -> Option<(f64, f64)> {
        let peak = self.psd.iter().cloned().fold(0.0, f64::max);
        if peak <= 0.0 {
            return None;
        }
        let i_peak = self.psd.iter().position(|&c| c == peak)?;
        let half = (i_peak..self.q.len()).find(|&i| self.psd[i] < 0.5 * peak)?;
        let last = self.psd.iter().rposition(|&c| c > 1e-20 * peak)?;
        Some((2.0 * self.q[half], 0.5 * self.q[last]))
    }
}

/// Result of a Hurst-exponent fit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HurstFit {
    /// Fitted Hurst exponent H.
    pub hurst: f64,
    /// The fitted line is `ln C = ln_prefactor - 2 (1 + H) ln q` (C in m^4, q in rad/m).
    pub ln_prefactor: f64,
    /// Fit range [rad/m].
    pub q_min: f64,
    pub q_max: f64,
    /// Number of bins in the fit.
    pub bins: usize,
}

impl HurstFit {
    /// The fitted PSD at `q` [rad/m], in m^4.
    pub fn psd_at(&self, q: f64) -> f64 {
        (self.ln_prefactor - 2.0 * (1.0 + self.hurst) * q.ln()).exp()
    }
}

/// Height distribution: mean \[m\], RMS height Rq \[m\], extremes \[m\], skewness and kurtosis [-].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeightStats {
    /// `<h>` \[m\].
    pub mean: f64,
    /// `Rq = sqrt(<(h - <h>)^2>)` \[m\].
    pub rms_height: f64,
    pub min: f64,
    pub max: f64,
    /// `max - min` \[m\].
    pub peak_to_valley: f64,
    /// `<(h - <h>)^3> / Rq^3` [-].
    pub skewness: f64,
    /// `<(h - <h>)^4> / Rq^4` [-] (3 for a Gaussian; not the excess kurtosis).
    pub kurtosis: f64,
}

impl HeightStats {
    pub fn new(heights: ArrayView2<f64>) -> Self {
        let n = heights.len() as f64;
        let rows: Vec<[f64; 3]> = heights
            .axis_iter(Axis(0))
            .into_par_iter()
            .map(|r| {
                r.iter()
                    .fold([0.0, f64::INFINITY, f64::NEG_INFINITY], |[s, lo, hi], &h| {
                        [s + h, lo.min(h), hi.max(h)]
                    })
            })
            .collect();
        let [sum, _, _] = ordered_sum(rows.clone());
        let min = rows.iter().map(|r| r[1]).fold(f64::INFINITY, f64::min);
        let max = rows.iter().map(|r| r[2]).fold(f64::NEG_INFINITY, f64::max);
        let mean = sum / n;
        // The moments of the heights over a power of two near their spread: exact scaling, and
        // fourth powers that stay finite for any height a surface may have.
        let spread = (max - mean).abs().max((min - mean).abs());
        let scale = if spread > 0.0 && spread.is_finite() {
            2f64.powi(spread.log2().ceil() as i32)
        } else {
            1.0
        };
        let central: Vec<[f64; 3]> = heights
            .axis_iter(Axis(0))
            .into_par_iter()
            .map(|r| {
                r.iter().fold([0.0; 3], |[a, b, c], &h| {
                    let d = (h - mean) / scale;
                    let d2 = d * d;
                    [a + d2, b + d2 * d, c + d2 * d2]
                })
            })
            .collect();
        let [m2, m3, m4] = ordered_sum(central).map(|v| v / n);
        let rq = m2.sqrt() * scale;
        let rq_scaled = m2.sqrt();
        HeightStats {
            mean,
            rms_height: rq,
            min,
            max,
            peak_to_valley: max - min,
            skewness: m3 / (rq_scaled * rq_scaled * rq_scaled),
            kurtosis: m4 / (m2 * m2),
        }
    }
}

/// Finite-difference slope and curvature mean squares: `[<|grad h|^2>, <(lap h)^2>, <(h_xx)^2>]`.
fn finite_difference_moments(h: ArrayView2<f64>, grid: &Grid, periodic: bool) -> [f64; 3] {
    let (ny, nx) = h.dim();
    let (dx, dy) = (grid.dx(), grid.dy());
    let (idx2, idy2) = (1.0 / (dx * dx), 1.0 / (dy * dy));
    let rows: Vec<[f64; 6]> = (0..ny)
        .into_par_iter()
        .map(|y| {
            // Sums and counts of: slope^2, laplacian^2, h_xx^2.
            let mut s = [0.0; 6];
            let c = h.row(y);
            let (up, down) = if periodic {
                (Some(h.row((y + 1) % ny)), Some(h.row((y + ny - 1) % ny)))
            } else {
                ((y + 1 < ny).then(|| h.row(y + 1)), (y > 0).then(|| h.row(y - 1)))
            };
            let xs = if periodic { 0..nx } else { 1..nx - 1 };
            for x in xs {
                // Neighbours along x, wrapping on periodic surfaces.
                let xp = if x + 1 == nx { 0 } else { x + 1 };
                let xm = if x == 0 { nx - 1 } else { x - 1 };
                let hxx = (c[xp] - 2.0 * c[x] + c[xm]) * idx2;
                s[4] += hxx * hxx;
                s[5] += 1.0;
                if let (Some(u), Some(d)) = (up, down) {
                    let lap = hxx + (u[x] - 2.0 * c[x] + d[x]) * idy2;
                    s[2] += lap * lap;
                    s[3] += 1.0;
                }
            }
            // Forward differences: the last column (and row) has no forward neighbour unless periodic.
            if let Some(u) = up {
                let xs = if periodic { nx } else { nx - 1 };
                for x in 0..xs {
                    let xp = if x + 1 == nx { 0 } else { x + 1 };
                    let gx = (c[xp] - c[x]) / dx;
                    let gy = (u[x] - c[x]) / dy;
                    s[0] += gx * gx + gy * gy;
                    s[1] += 1.0;
                }
            }
            s
        })
        .collect();
    let s = ordered_sum(rows);
    [s[0] / s[1], s[2] / s[3], s[4] / s[5]]
}

/// Everything `roughcontact stats` reports.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Statistics {
    #[serde(flatten)]
    pub heights: HeightStats,
    /// Spectral RMS gradient `sqrt(<|grad h|^2>)` [-].
    pub rms_gradient: f64,
    /// Finite-difference RMS gradient [-].
    pub rms_gradient_fd: f64,
    /// RMS mean curvature (spectral) [1/m]; see [`Curvatures::mean`].
    pub rms_curvature: f64,
    /// Spectral curvatures [1/m].
    pub curvature: Curvatures,
    /// Finite-difference curvatures [1/m].
    pub curvature_fd: Curvatures,
    /// Inverse RMS mean curvature `1 / rms_curvature` \[m\], the local radius of the asperities.
    pub local_radius: f64,
    /// Hurst exponent fitted to the radial PSD ([`RadialPsd::fit_hurst`]); `None` when the
    /// spectrum has too few bins in the fit range.
    pub hurst_fit: Option<f64>,
    /// The wavevector range of that fit [rad/m].
    pub hurst_fit_range: Option<[f64; 2]>,
}

/// The spectral view of a surface: what follows from its DFT, computed once.
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    pub grid: Grid,
    pub moments: SpectralMoments,
    pub radial_psd: RadialPsd,
}

impl Analysis {
    /// Transforms `heights` once and derives the spectral moments and the radial PSD.
    pub fn new(heights: ArrayView2<f64>, grid: &Grid, bins_per_decade: usize) -> Self {
        let spectrum = Fft2::new(grid.nx, grid.ny).forward(heights);
        Self::from_spectrum(spectrum.view(), grid, bins_per_decade)
    }

    /// The same from a transposed half spectrum (see [`fft2`]).
    pub fn from_spectrum(spectrum: ArrayView2<Complex64>, grid: &Grid, bins_per_decade: usize) -> Self {
        let (moments, radial_psd) = rayon::join(
            || SpectralMoments::from_spectrum(spectrum, grid),
            || RadialPsd::from_spectrum(spectrum, grid, bins_per_decade),
        );
        Analysis {
            grid: *grid,
            moments,
            radial_psd,
        }
    }

    /// The analysis of the same surface with all heights multiplied by `factor`.
    pub fn scaled(&self, factor: f64) -> Self {
        let f2 = factor * factor;
        let r = &self.radial_psd;
        Analysis {
            grid: self.grid,
            moments: self.moments.scaled(factor),
            radial_psd: RadialPsd {
                psd: r.psd.iter().map(|c| c * f2).collect(),
                std_err: r.std_err.iter().map(|c| c * f2).collect(),
                mean_ln_psd: r.mean_ln_psd.iter().map(|c| c + f2.ln()).collect(),
                ..r.clone()
            },
        }
    }
}

/// Computes all statistics of `heights` on `grid`. `fit_range` ([rad/m]) overrides the
/// default Hurst fit range ([`RadialPsd::default_fit_range`]).
pub fn statistics(
    heights: ArrayView2<f64>,
    grid: &Grid,
    periodic: bool,
    fit_range: Option<(f64, f64)>,
) -> Statistics {
    let analysis = Analysis::new(heights, grid, 10);
    statistics_with(heights, &analysis, periodic, fit_range)
}

/// As [`statistics`], reusing an [`Analysis`] of the same heights.
pub fn statistics_with(
    heights: ArrayView2<f64>,
    analysis: &Analysis,
    periodic: bool,
    fit_range: Option<(f64, f64)>,
) -> Statistics {
    let m = analysis.moments;
    let [g2, lap2, xx2] = finite_difference_moments(heights, &analysis.grid, periodic);
    let curvature = Curvatures::new(m.m4, m.m4_xx);
    let range = fit_range.or_else(|| analysis.radial_psd.default_fit_range());
    let fit = range.and_then(|(lo, hi)| analysis.radial_psd.fit_hurst(lo, hi));
    Statistics {
        heights: HeightStats::new(heights),
        rms_gradient: m.rms_gradient(),
        rms_gradient_fd: g2.sqrt(),
        rms_curvature: curvature.mean,
        curvature,
        curvature_fd: Curvatures::new(lap2, xx2),
        local_radius: 1.0 / curvature.mean,
        hurst_fit: fit.map(|f| f.hurst),
        hurst_fit_range: fit.map(|f| [f.q_min, f.q_max]),
    }
}

/// The bearing-area (Abbott-Firestone, material ratio) curve: for `levels` heights equally
/// spaced from the maximum down to the minimum, the fraction of points with `h >= level`.
/// Returns `(level \[m\], ratio [-])` pairs, ratio rising from `1/N` (or more, for ties) to 1.
///
/// # Panics
/// If `levels < 2`.
pub fn bearing_area_curve(heights: ArrayView2<f64>, levels: usize) -> Vec<(f64, f64)> {
    assert!(levels >= 2, "need at least two levels");
    let hs = HeightStats::new(heights);
    let n = heights.len() as f64;
    let step = hs.peak_to_valley / (levels - 1) as f64;
    let level = |i: usize| {
        if i == levels - 1 {
            hs.min
        } else {
            hs.max - step * i as f64
        }
    };
    // counts[i] = points in (level(i+1), level(i)]; level 0 is the maximum.
    let mut counts = vec![0usize; levels];
    for &h in heights.iter() {
        let mut i = if step > 0.0 {
            ((hs.max - h) / step).floor() as usize
        } else {
            0
        };
        i = i.min(levels - 1);
        // Correct the rounding of the division so that h >= level(i) holds exactly.
        while i > 0 && h >= level(i - 1) {
            i -= 1;
        }
        while h < level(i) {
            i += 1;
        }
        counts[i] += 1;
    }
    let mut above = 0usize;
    (0..levels)
        .map(|i| {
            above += counts[i];
            (level(i), above as f64 / n)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::{Array2, array};

    #[test]
    fn height_moments_of_a_known_sample() {
        // Values -1, -1, -1, 3: mean 0, variance 3, third moment 6, fourth moment 21.
        let h = array![[-1.0, -1.0], [-1.0, 3.0]];
        let s = HeightStats::new(h.view());
        assert_eq!(s.mean, 0.0);
        assert!((s.rms_height - 3f64.sqrt()).abs() < 1e-15);
        assert!((s.skewness - 6.0 / 3f64.powf(1.5)).abs() < 1e-14);
        assert!((s.kurtosis - 21.0 / 9.0).abs() < 1e-14);
        assert_eq!((s.min, s.max, s.peak_to_valley), (-1.0, 3.0, 4.0));
    }

    #[test]
    fn bearing_area_counts_points_at_or_above_each_level() {
        // Heights 0..99: at level z, the points with h >= z number 100 - ceil(z).
        let h = Array2::from_shape_fn((10, 10), |(y, x)| (10 * y + x) as f64);
        let curve = bearing_area_curve(h.view(), 34);
        assert_eq!(curve[0], (99.0, 0.01));
        assert_eq!(*curve.last().unwrap(), (0.0, 1.0));
        for (z, r) in curve {
            let above = h.iter().filter(|&&v| v >= z).count() as f64 / 100.0;
            assert_eq!(r, above, "level {z}");
        }
    }

    #[test]
    fn non_periodic_finite_differences_skip_the_edges() {
        // A plane h = 2x + 3y has slope^2 = 13 and no curvature, but only without wrap-around.
        let g = Grid::new(16, 8, 16.0, 8.0).unwrap();
        let h = Array2::from_shape_fn((8, 16), |(y, x)| 2.0 * x as f64 + 3.0 * y as f64);
        let [g2, lap2, xx2] = finite_difference_moments(h.view(), &g, false);
        assert!((g2 - 13.0).abs() < 1e-12);
        assert!(lap2.abs() < 1e-20 && xx2.abs() < 1e-20);
        let [g2, ..] = finite_difference_moments(h.view(), &g, true);
        assert!(g2 > 13.0, "wrapping a plane adds a cliff");
    }
}
