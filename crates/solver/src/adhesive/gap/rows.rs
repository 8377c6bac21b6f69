//! The row-coupled preconditioner: for the line and surface laws, whose cell pressure is a mean
//! over the gaps from a node to its +x neighbour, each cell's stiffness by its own gap and by its
//! neighbour's, solved along each row; and the diagonal preconditioner of the other laws.

use super::{Energy, Point, Problem, Row};
use crate::error::Result;
use crate::fields::{flat, flat_mut};
use ndarray::Array2;
use rayon::prelude::*;

impl Problem<'_> {
    /// Writes the preconditioned gradient `z = (r - mu) / m` into `out`, with `m = S_ii +
    /// max(V'', 0)` the curvature's diagonal (the Lennard-Jones tail just above the wall is
    /// many times stiffer than a cell), `r` `at`'s projected gradient and `mu` the weighted mean
    /// that keeps the moving cells' sum at zero when the mean gap is prescribed. Returns
    /// `<z, r>` and `<z, old>`.
    pub(in crate::adhesive) fn precondition(
        &self,
        at: &Point,
        old: &Array2<f64>,
        out: &mut Array2<f64>,
    ) -> [f64; 2] {
        let mx = self.mx;
        let rs = flat(&at.gradient);
        let cs = flat(&at.curvature);
        let weight = |j: usize, i: usize, k: usize| 1.0 / self.mass(cs, j, i, k);
        let mu = if self.mean_gap.is_some() {
            let [a, b] = crate::sum::ordered(self.my, |j| {
                let mut sums = [0.0; 2];
                for i in 0..mx {
                    let k = j * mx + i;
                    if rs[k] != 0.0 {
                        let w = weight(j, i, k);
                        sums[0] += w * rs[k];
                        sums[1] += w;
                    }
                }
                sums
            });
            if b > 0.0 { a / b } else { 0.0 }
        } else {
            0.0
        };
        let os = flat(old);
        let parts: Vec<[f64; 2]> = flat_mut(out)
            .par_chunks_mut(mx)
            .enumerate()
            .map(|(j, zr)| {
                let mut sums = [0.0; 2];
                for (i, z) in zr.iter_mut().enumerate() {
                    let k = j * mx + i;
                    *z = if rs[k] != 0.0 {
                        (rs[k] - mu) * weight(j, i, k)
                    } else {
                        0.0
                    };
                    sums[0] += *z * rs[k];
                    sums[1] += *z * os[k];
                }
                sums
            })
            .collect();
        parts.iter().fold([0.0; 2], |a, b| [a[0] + b[0], a[1] + b[1]])
    }

    /// Takes, for a law whose cell pressure depends on its neighbours' gaps (no local
    /// potential) and that is evaluated without an energy, each cell's stiffness by its own
    /// gap and by its +x neighbour's apart (in closed form where the law gives it, else
    /// probed: one more evaluation of the law a step), for [`Problem::solve_rows`], and
    /// evaluates `at` (the point [`setup`] made) again so.
    pub(in crate::adhesive) fn couple_rows(&mut self, at: &mut Point) -> Result<()> {
        if matches!(self.energy, Energy::None) && self.law.local_potential().is_none() {
            self.couple = true;
            self.evaluate(at)?;
        }
        Ok(())
    }

    /// Whether the grid is periodic with at least `n` cells along each axis.
    pub(in crate::adhesive) fn periodic_at_least(&self, n: usize) -> bool {
        (self.mx, self.my) == (self.nx, self.ny) && self.nx >= n && self.ny >= n
    }

    /// Whether [`Problem::couple_rows`] took effect.
    pub(in crate::adhesive) fn coupled(&self) -> bool {
        self.couple
    }

    /// As [`Problem::precondition`], with the mass `m` coupled to the +x neighbour as the law
    /// couples the cells (the line and surface laws), for the flow. Returns `<z, r>`.
    pub(in crate::adhesive) fn precondition_rows(&self, at: &Point, out: &mut Array2<f64>) -> f64 {
        let (rs, cs) = (flat(&at.gradient), flat(&at.curvature));
        let weight = |j: usize, i: usize, k: usize| {
            if rs[k] == 0.0 {
                0.0
            } else {
                1.0 / self.mass(cs, j, i, k)
            }
        };
        self.solve_rows(at, &weight, &at.gradient, out)
    }

    /// Row `row.j` of the pull `z = P^-1 r` of [`Problem::precondition_rows`] (coupled) or
    /// [`Problem::precondition`] (not) into `zr`, where no mean gap is prescribed, for a pass
    /// over the cells that uses it at once; returns the row's `<z, r>`.
    pub(in crate::adhesive) fn pull_row(&self, row: &Row, zr: &mut [f64]) -> f64 {
        debug_assert!(
            self.mean_gap.is_none(),
            "the mean gap's multiplier needs every row"
        );
        let rr = row.gradient;
        // The flow's weight `1 / m`, 0 where the projected gradient holds the cell.
        let weight = |i: usize| {
            if rr[i] == 0.0 {
                0.0
            } else {
                1.0 / self.row_mass(row, i)
            }
        };
        if self.couple {
            self.solve_row(row.j, row.coupling, weight, |i| rr[i], |i, z| zr[i] = z);
            return zr.iter().zip(rr).map(|(z, v)| z * v).sum::<f64>();
        }
        let mut dot = 0.0;
        for (i, (z, &r)) in zr.iter_mut().zip(rr).enumerate() {
            *z = if r != 0.0 { r * weight(i) } else { 0.0 };
            dot += *z * r;
        }
        dot
    }

    /// `z = P^-1 (v - mu)` into `out`, with `P` the diagonal `1 / weight(j, i, k)` (held cells
    /// have weight 0 and get 0) plus the law's stiffness at `at` by the +x neighbour,
    /// `-dp_i/dg_j` ([`Problem::couple_rows`]; at most `ROW_COUPLING` times the cell's own
    /// diagonal, so that the back substitution along a row stays bounded, and times the
    /// geometric mean of its diagonal and its neighbour's, so that `P`'s symmetric part stays
    /// positive definite and `<v, P^-1 v> > 0`; none across the block's edge or a periodic
    /// wrap), and `mu` the multiple of `P^-1 1` that keeps the moving cells' sum at
    /// zero where the mean gap is prescribed. Returns `<z, v>`.
    pub(in crate::adhesive) fn solve_rows(
        &self,
        at: &Point,
        weight: &(impl Fn(usize, usize, usize) -> f64 + Sync),
        v: &Array2<f64>,
        out: &mut Array2<f64>,
    ) -> f64 {
        let mx = self.mx;
        let vs = flat(v);
        let dot_row = |j: usize, zr: &[f64]| {
            zr.iter()
                .zip(&vs[j * mx..][..mx])
                .map(|(z, v)| z * v)
                .sum::<f64>()
        };
        let prescribed = self.mean_gap.is_some();
        let coupling = |j: usize| self.coupling_row(&at.coupling, j);
        // `P^-1 v` into `out`, with each row's sum, that of `P^-1 1` (its values not kept) and
        // `<z, v>`.
        let rows: Vec<[f64; 3]> = flat_mut(out)
            .par_chunks_mut(mx)
            .enumerate()
            .map(|(j, zr)| {
                let (cs, w, v) = (coupling(j), |i| weight(j, i, j * mx + i), &vs[j * mx..][..mx]);
                let a = self.solve_row(j, cs, w, |i| v[i], |i, z| zr[i] = z);
                let b = if prescribed {
                    self.solve_row(j, cs, w, |_| 1.0, |_, _| {})
                } else {
                    0.0
                };
                // Where `mu` follows, `<z, v>` is taken after it.
                [a, b, if prescribed { 0.0 } else { dot_row(j, zr) }]
            })
            .collect();
        let [a, b, dot] = rows.iter().fold([0.0; 3], |mut acc, r| {
            acc.iter_mut().zip(r).for_each(|(a, r)| *a += r);
            acc
        });
        if !prescribed {
            return dot;
        }
        // Less `mu P^-1 1`, solved again row by row rather than kept.
        let mu = if b > 0.0 { a / b } else { 0.0 };
        flat_mut(out)
            .par_chunks_mut(mx)
            .enumerate()
            .map(|(j, zr)| {
                if mu != 0.0 {
                    let w = |i| weight(j, i, j * mx + i);
                    self.solve_row(j, coupling(j), w, |_| 1.0, |i, z| zr[i] -= mu * z);
                }
                dot_row(j, zr)
            })
            .collect::<Vec<f64>>()
            .iter()
            .sum()
    }

    /// `P^-1 rhs` on row `j` of [`Problem::solve_rows`] by back substitution, with the row's
    /// `coupling` (empty off the block) and `weight` by column, each `z_i` handed to
    /// `sink(i, z_i)`; returns the sum of the `z`.
    fn solve_row(
        &self,
        j: usize,
        coupling: &[f64],
        weight: impl Fn(usize) -> f64,
        rhs: impl Fn(usize) -> f64,
        mut sink: impl FnMut(usize, f64),
    ) -> f64 {
        const ROW_COUPLING: f64 = 0.9;
        let (mx, nx, ny) = (self.mx, self.nx, self.ny);
        // The weights and the couplings' bounds first, in passes that vectorise (their
        // divisions and roots were most of a row's time), then the back substitution, a block
        // of the row at a time from its end (no allocation). A stiff cell beside a soft one
        // made `<v, P^-1 v>` negative, the flow's force weight, which then stopped every step
        // (docs/decisions.md): the bound is the smaller of the cell's diagonal and the
        // geometric mean of its and its neighbour's (none beside a held one), `1 / max(w,
        // sqrt(w w'))` in one division (the same bits: division rounds monotonically).
        const BLOCK: usize = 256;
        let (mut weights, mut bounds) = ([0.0; BLOCK + 1], [0.0; BLOCK]);
        let mut sum = 0.0;
        // `z` of the +x neighbour, solved just before, and the weight of the cell after the
        // block (none after the row's last).
        let (mut next, mut after) = (0.0, 0.0);
        let mut end = mx;
        while end > 0 {
            let start = end.saturating_sub(BLOCK);
            let n = end - start;
            weights[..n]
                .iter_mut()
                .enumerate()
                .for_each(|(k, w)| *w = weight(start + k));
            weights[n] = after;
            bounds[..n]
                .iter_mut()
                .zip(weights[..n].iter().zip(&weights[1..=n]))
                .for_each(|(b, (&w, &next))| *b = w.max((w * next).sqrt()).recip());
            for k in (0..n).rev() {
                let (i, w) = (start + k, weights[k]);
                let z = if w == 0.0 {
                    0.0
                } else {
                    let c = if j < ny && i + 1 < nx {
                        coupling[i].clamp(-ROW_COUPLING * bounds[k], ROW_COUPLING * bounds[k])
                    } else {
                        0.0
                    };
                    (rhs(i) - c * next) * w
                };
                sink(i, z);
                next = z;
                sum += z;
            }
            (after, end) = (weights[0], start);
        }
        sum
    }

    /// Cell `(j, i)`'s mass \[Pa/m\], `k` its flat index and `curvature` the law's stiffness
    /// field: `S_ii + max(V'', 0)` on the domain's block, `S_ii` in the padding.
    pub(in crate::adhesive) fn mass(&self, curvature: &[f64], j: usize, i: usize, k: usize) -> f64 {
        self.cell_mass(j, i, || curvature[k])
    }

    /// [`Problem::mass`] of cell `i` of `row`.
    pub(in crate::adhesive) fn row_mass(&self, row: &Row, i: usize) -> f64 {
        self.cell_mass(row.j, i, || row.curvature[i])
    }

    /// [`Problem::mass`] of cell `(j, i)`, its law's stiffness read only on the block.
    fn cell_mass(&self, j: usize, i: usize, curvature: impl FnOnce() -> f64) -> f64 {
        if j < self.ny && i < self.nx {
            self.diagonal + curvature().max(0.0)
        } else {
            self.diagonal
        }
    }
}
