//! The gap problem shared by the energy descent, Newton and the flow: the unknown (the gap,
//! or the padded displacement on free domains), its constraints, and the law and stiffness
//! evaluated at a point.
//!
//! With the approach `delta` given on a periodic domain the mean displacement is zero, so the
//! mean gap is fixed, `mean(g) = mean(g0) - delta`, and the total energy per area is
//! `E(g) = (1/2) <g - g0, S (g - g0)> / N + mean(V(g))` over `g >= 0` with that mean, `S` the
//! periodic stiffness ([`elastic::PeriodicStiffness`]) and `V` the law's interaction energy.
//! Its gradient `r = S (g - g0) - p(g)` \[Pa\] balances the mean-pressure multiplier where
//! `g > 0` and is the contact pressure where `g = 0`. Under load control (mean pressure
//! `p_m` given) the mean gap is free and the load's potential `p_m mean(g)` joins `E`.
//!
//! On a free domain (approach control only) the unknown is the surface displacement `U` of the
//! padded `2nx` by `2ny` grid of the DC-FFT ([`elastic::FreeStiffness`]), with
//! `E(U) = (1/2) <U, S U> / N + mean(V(g))` and `g = g0 - delta + U` on the domain's block (the
//! first `(ny, nx)` cells), where the law acts and the wall stands: the gradient `S U - p(g)` is
//! driven to the contact pressure there and to zero in the padding, where no pressure may act,
//! so the block's displacement is the free one. No mean constraint: the projection is a clip.

use super::{AdhesiveReport, AdhesiveState, Job, Outcome, Start, assemble, cells};
use crate::error::{Result, SolverError, invalid};
use crate::fields::{flat, flat_mut};
use crate::options::Control;
use crate::state::ContactState;
use elastic::{Domain, FreeStiffness, PeriodicStiffness};
use ljadhesion::{AdhesionLaw, Cells, FieldPotential, LocalPotential};
use ndarray::{Array2, ArrayView2, ArrayViewMut2, Zip, s};
use rayon::prelude::*;

/// One admissible point and what the solver needs of it. Fields have the unknown's shape.
pub(super) struct Point {
    /// The unknown: the gap \[m\] on the domain's block, the displacement \[m\] in the padding.
    pub(super) gap: Array2<f64>,
    /// `S (gap - base)` \[Pa\]: the pressure that holds the surface's displacement.
    pub(super) elastic: Array2<f64>,
    /// `p(g)` \[Pa\].
    pub(super) law: Array2<f64>,
    /// `V''(g)`, or without a potential the law's probed stiffness `-dp/dg` [Pa/m]: for a
    /// uniform change of the gaps, or of the cell's own gap alone where the problem couples
    /// rows ([`Problem::couple_rows`]).
    pub(super) curvature: Array2<f64>,
    /// Where the problem couples rows: `-dp_i/dg_j` [Pa/m] of each cell `i` of the block by its
    /// +x neighbour `j`; else empty.
    pub(super) coupling: Array2<f64>,
    /// The gradient `S (g - g0) - p(g)` \[Pa\], then projected ([`Problem::project_gradient`]).
    pub(super) gradient: Array2<f64>,
    /// Without a prescribed mean gap, `max |r|` \[Pa\] of the gradient, which
    /// [`Problem::evaluate`] then leaves projected.
    largest: f64,
    /// Elastic energy, and interaction energy plus the load's potential `p_mean mean(g)`, per
    /// area [J/m^2]; made only where the law has an energy (the descent's merit).
    pub(super) energy: (f64, f64),
    /// The gradient's sum over the cells off the wall, and their number.
    free: (f64, f64),
    /// The smallest gap \[m\] (on the domain's block).
    pub(super) min_gap: f64,
    /// Whether `law`, `curvature` and `coupling` hold the law at `gap`: not after
    /// [`Problem::evaluate_rows`] with the law by rows, until [`Problem::store_law`].
    law_stored: bool,
}

impl Point {
    pub(super) fn new(gap: Array2<f64>) -> Point {
        let shape = gap.dim();
        Point {
            gap,
            elastic: Array2::zeros(shape),
            law: Array2::zeros(shape),
            curvature: Array2::zeros(shape),
            coupling: Array2::zeros((0, 0)),
            gradient: Array2::zeros(shape),
            energy: (0.0, 0.0),
            free: (0.0, 0.0),
            largest: 0.0,
            min_gap: 0.0,
            law_stored: false,
        }
    }

    pub(super) fn total_energy(&self) -> f64 {
        self.energy.0 + self.energy.1
    }
}

/// Row `j` of a point's fields ([`Problem::row`], [`Problem::evaluate_rows`]), each the
/// row of the [`Point`] field of that name.
pub(super) struct Row<'r> {
    pub(super) j: usize,
    pub(super) gap: &'r [f64],
    pub(super) gradient: &'r [f64],
    pub(super) curvature: &'r [f64],
    /// Where the problem couples rows and the row is on the block; else empty.
    pub(super) coupling: &'r [f64],
}

/// What the solver needs of a projected gradient `rho`.
pub(super) struct GradientSums {
    /// The mean-pressure multiplier \[Pa\].
    pub(super) lambda: f64,
    /// `max |rho|` \[Pa\].
    pub(super) max: f64,
}

/// The stiffness of the unknown's grid.
pub(super) enum Stiffness {
    Periodic(PeriodicStiffness),
    Free(FreeStiffness),
}

impl Stiffness {
    pub(super) fn apply(
        &self,
        u: ArrayView2<f64>,
        p: ArrayViewMut2<f64>,
        ws: &mut elastic::Workspace,
    ) -> Result<()> {
        match self {
            Stiffness::Periodic(s) => s.apply(u, p, ws),
            Stiffness::Free(s) => s.apply(u, p, ws),
        }?;
        Ok(())
    }

    /// [`Stiffness::apply`] to `u` given row by row (`u(y, row)` writes row `y`).
    pub(super) fn apply_rows(
        &self,
        u: impl Fn(usize, &mut [f64]) + Sync,
        p: ArrayViewMut2<f64>,
        ws: &mut elastic::Workspace,
    ) -> Result<()> {
        match self {
            Stiffness::Periodic(s) => s.apply_rows(u, p, ws),
            Stiffness::Free(s) => s.apply_rows(u, p, ws),
        }?;
        Ok(())
    }

    /// The inverse: the displacement under the pressure `p` (zero mean, periodic).
    pub(super) fn invert(
        &self,
        p: ArrayView2<f64>,
        u: ArrayViewMut2<f64>,
        ws: &mut elastic::Workspace,
    ) -> Result<()> {
        match self {
            Stiffness::Periodic(s) => s.invert(p, u, ws),
            Stiffness::Free(s) => s.invert(p, u, ws),
        }?;
        Ok(())
    }
}

/// The energy of the law, if it has one.
#[derive(Clone, Copy)]
pub(super) enum Energy<'a> {
    /// None: only the law's pressure field and a probed stiffness are evaluated (Newton).
    None,
    /// Of each cell's own gap.
    Local(&'a dyn LocalPotential),
    /// Of the whole field.
    Field(&'a dyn FieldPotential),
}

impl<'a> Energy<'a> {
    /// The energy `law` derives from: of each cell's own gap, of the whole field, or none.
    pub(super) fn of(law: &'a dyn AdhesionLaw) -> Energy<'a> {
        match (law.local_potential(), law.field_potential()) {
            (Some(local), _) => Energy::Local(local),
            (None, Some(field)) => Energy::Field(field),
            (None, None) => Energy::None,
        }
    }
}

pub(super) struct Problem<'a> {
    pub(super) stiffness: Stiffness,
    pub(super) ws: elastic::Workspace,
    /// The law's energy (descent), or none (Newton).
    energy: Energy<'a>,
    pub(super) law: &'a dyn AdhesionLaw,
    pub(super) cells: Cells,
    domain: Domain,
    /// The block's gap shifted by a probe, and the law's pressure there (without an energy and
    /// without the law's stiffness in closed form; made at the first probe); the cells'
    /// energies (a field energy); empty otherwise.
    probe: (Array2<f64>, Array2<f64>),
    /// The unknown less the surface displacement \[m\] (up to its mean, periodic): `g0` periodic;
    /// `g0 - delta` on the domain's block and zero in the padding, free.
    base: Array2<f64>,
    /// Columns and rows of the unknown: `(nx, ny)` periodic, `(2nx, 2ny)` free.
    pub(super) mx: usize,
    pub(super) my: usize,
    /// Columns and rows of the domain's block, where the unknown is the gap.
    pub(super) nx: usize,
    pub(super) ny: usize,
    /// The prescribed mean gap \[m\] (periodic approach control; free domains have none).
    pub(super) mean_gap: Option<f64>,
    /// The prescribed mean pressure \[Pa\] (periodic load control: the mean gap is free).
    load: Option<f64>,
    pub(super) calls: usize,
    /// The stiffness's diagonal `S_ii` [Pa/m] (the same for every cell).
    pub(super) diagonal: f64,
    /// Whether the law's stiffness is taken by a cell's own gap and by its +x neighbour's
    /// apart ([`Problem::couple_rows`]).
    couple: bool,
    /// The elastic force split into a near part made every evaluation and a far part kept
    /// from the last transform ([`Problem::split_elastic`]); none unless asked for.
    split: Option<Split>,
}

/// The stiffness's response `S u` split as `S_near u + F`: `S_near` the stiffness's own
/// coefficients between cells at most two apart along each axis (its 5 x 5 stencil), with the
/// sum of all 25 taken off evenly from the 16 of its outer ring so that a uniform move costs no
/// force; `F = S u' - S_near u'` the far part at the last point `u'` transformed. Where only
/// `near` is asked for, an evaluation takes `S_near u + F` and no transform: exact at `u'`, and
/// off elsewhere by the far part's change, which is small for the moves of a few steps: a
/// cell's own stiffness and its nearest neighbours' stay exact (`docs/decisions.md`).
struct Split {
    /// `S_near`'s quadrant: the coefficient \[Pa/m\] between cells `q` rows and `e` columns
    /// apart at `[q][e]` (the stencil is even in both axes).
    stencil: [[f64; 3]; 3],
    /// `F` \[Pa\].
    far: Array2<f64>,
    /// Whether `far` has been made.
    made: bool,
    /// Whether the next evaluations take the near part and `far` rather than transforming.
    near: bool,
}

/// Row `j` of `S_near (g - b)` ([`Split`], its quadrant `c`) on a periodic `(ny, nx)` grid
/// into `out`, with `rows` a scratch of three padded rows.
fn near_row(
    c: &[[f64; 3]; 3],
    gs: &[f64],
    bs: &[f64],
    (ny, nx): (usize, usize),
    j: usize,
    rows: &mut Vec<f64>,
    out: &mut [f64],
) {
    let w = nx + 4;
    rows.resize(3 * w, 0.0);
    // Row q of the scratch: the rows `q` above and below summed (row `j` itself for q = 0),
    // wrapped by two cells at each end.
    for (q, row) in rows.chunks_mut(w).enumerate() {
        let at = |y: usize| (&gs[y * nx..][..nx], &bs[y * nx..][..nx]);
        let (ga, ba) = at((j + q) % ny);
        let inner = &mut row[2..2 + nx];
        if q == 0 {
            inner
                .iter_mut()
                .zip(ga.iter().zip(ba))
                .for_each(|(r, (g, b))| *r = g - b);
        } else {
            let (gb, bb) = at((j + ny - q) % ny);
            inner
                .iter_mut()
                .zip(ga.iter().zip(ba))
                .zip(gb.iter().zip(bb))
                .for_each(|((r, (g, b)), (h, c))| *r = (g - b) + (h - c));
        }
        for k in 0..2 {
            row[k] = row[nx + k];
            row[2 + nx + k] = row[2 + k];
        }
    }
    let at = |q: usize, e: usize| &rows[q * w + e..][..nx];
    let [a, b, d] = [0, 1, 2].map(|q| [0, 1, 2, 3, 4].map(|e| at(q, e)));
    for (i, o) in out[..nx].iter_mut().enumerate() {
        *o = c[0][0] * a[2][i]
            + c[0][1] * (a[1][i] + a[3][i])
            + c[0][2] * (a[0][i] + a[4][i])
            + c[1][0] * b[2][i]
            + c[1][1] * (b[1][i] + b[3][i])
            + c[1][2] * (b[0][i] + b[4][i])
            + c[2][0] * d[2][i]
            + c[2][1] * (d[1][i] + d[3][i])
            + c[2][2] * (d[0][i] + d[4][i]);
    }
}

impl Problem<'_> {
    /// Whether the next evaluations take the split's near part alone ([`Split`]): asks for it
    /// (`true`) or for a transform; returns whether it is taken (a split whose far part has
    /// been made).
    pub(super) fn near_only(&mut self, near: bool) -> bool {
        self.split.as_mut().is_some_and(|s| {
            s.near = near && s.made;
            s.near
        })
    }

    /// Splits the elastic force of a periodic grid of at least 5 x 5 cells into its near and
    /// far parts ([`Split`]), from the stiffness's response to one cell's move (one
    /// application); the next evaluation transforms.
    pub(super) fn split_elastic(&mut self) -> Result<()> {
        let (mx, my) = (self.mx, self.my);
        debug_assert!((mx, my) == (self.nx, self.ny) && mx >= 5 && my >= 5);
        let mut kernel = Array2::zeros((my, mx));
        kernel[(0, 0)] = 1.0;
        let impulse = kernel.clone();
        self.stiffness
            .apply(impulse.view(), kernel.view_mut(), &mut self.ws)?;
        self.calls += 1;
        let mut stencil: [[f64; 3]; 3] = std::array::from_fn(|q| std::array::from_fn(|e| kernel[(q, e)]));
        // Each coefficient stands for 1, 2 or 4 cells of the 5 x 5.
        let count = |q: usize, e: usize| (if q == 0 { 1.0 } else { 2.0 }) * (if e == 0 { 1.0 } else { 2.0 });
        let total: f64 = (0..3)
            .flat_map(|q| (0..3).map(move |e| (q, e)))
            .map(|(q, e)| count(q, e) * stencil[q][e])
            .sum();
        for (q, row) in stencil.iter_mut().enumerate() {
            for (e, c) in row.iter_mut().enumerate() {
                if q == 2 || e == 2 {
                    *c -= total / 16.0;
                }
            }
        }
        self.split = Some(Split {
            stencil,
            far: Array2::zeros((my, mx)),
            made: false,
            near: false,
        });
        Ok(())
    }

    /// Writes `max(from + step d + c, 0)` into `gap` (on the domain's block; no bound in the
    /// padding), with the shift `c` that restores a prescribed mean gap (else 0), except on
    /// cells of `from` on the wall that `d` leaves there, which stay: the projection of the
    /// step onto the constraints within the current face. `c` comes from Newton on the
    /// convex, piecewise-linear mean (exact after finitely many steps). With `hold` (periodic),
    /// cells of `from` with a gap at most `hold` \[m\] stay where they are and only the others
    /// shift (a warm start's first guess).
    pub(super) fn step_and_project(
        &self,
        from: &Array2<f64>,
        d: &Array2<f64>,
        step: f64,
        gap: &mut Array2<f64>,
        hold: Option<f64>,
    ) {
        let (mx, nx, ny, n) = (self.mx, self.nx, self.ny, (self.nx * self.ny) as f64);
        let (fs, ds) = (flat(from), flat(d));
        let mean_gap = self.mean_gap.unwrap_or(0.0);
        // Holding every cell would leave nothing to restore the mean gap with.
        let hold = hold.filter(|&h| self.mean_gap.is_some() && fs.iter().any(|&f| f > h));
        // Cells on the wall that the direction does not lift stay on it: the shift restores
        // the mean with the others. (Shifting them too, the exact Euclidean projection, lifts
        // the whole contact set by a round-off gap whenever the shift is positive; their
        // contact pressures then enter the next direction, which presses them back into the
        // wall, and the step is cut again and again.)
        let held = |f: f64, d: f64| hold.is_some_and(|h| f <= h) || (f <= 0.0 && d == 0.0);
        let mut c = 0.0;
        // A prescribed mean gap is periodic: the unknown is the gap everywhere.
        for _ in 0..if self.mean_gap.is_some() { 100 } else { 0 } {
            let [sum, free] = crate::sum::ordered(self.ny, |j| {
                let (f, d) = (&fs[j * nx..][..nx], &ds[j * nx..][..nx]);
                f.iter().zip(d).fold([0.0, 0.0], |[s, k], (&f, &d)| {
                    let v = f + step * d + c;
                    if held(f, d) {
                        [s + f, k]
                    } else if v > 0.0 {
                        [s + v, k + 1.0]
                    } else {
                        [s, k]
                    }
                })
            });
            if free == 0.0 {
                // Everything below the wall: lift the highest cell to the mean gap.
                let top = fs
                    .iter()
                    .zip(ds)
                    .fold(f64::NEG_INFINITY, |m, (&f, &d)| m.max(f + step * d));
                c = mean_gap - top;
                continue;
            }
            let excess = sum / n - mean_gap;
            if excess.abs() <= 1e-15 * mean_gap {
                break;
            }
            c -= excess * n / free;
        }
        flat_mut(gap).par_chunks_mut(mx).enumerate().for_each(|(j, gr)| {
            for (i, g) in gr.iter_mut().enumerate() {
                let k = j * mx + i;
                let (f, inside) = (fs[k], j < ny && i < nx);
                *g = if !inside {
                    f + step * ds[k]
                } else if held(f, ds[k]) {
                    f
                } else {
                    (f + step * ds[k] + c).max(0.0)
                };
            }
        });
    }

    /// Updates each cell's velocity \[m per time unit\] to `new(v, k, inside)` (`k` its flat
    /// index, `inside` whether it is on the domain's block) and moves the cells by `step` times
    /// it, as [`Problem::step_and_project`] would; a cell that ends on the wall keeps no
    /// velocity into it. With `shift = (held, by)` the cells where `held` is 0 then move by
    /// `by` \[m\] more, projected onto the wall (a periodic domain's unknown, the gap
    /// everywhere; no prescribed mean gap). Without a prescribed mean gap this is one pass over
    /// the fields.
    pub(super) fn move_cells(
        &self,
        from: &Array2<f64>,
        velocity: &mut Array2<f64>,
        step: f64,
        gap: &mut Array2<f64>,
        shift: Option<(&Array2<u8>, f64)>,
        new: impl Fn(f64, usize, bool) -> f64 + Sync,
    ) {
        let (mx, nx, ny) = (self.mx, self.nx, self.ny);
        if self.mean_gap.is_some() {
            debug_assert!(shift.is_none(), "a shift would move the prescribed mean gap");
            // The shift that keeps the mean needs every cell's step first.
            flat_mut(velocity)
                .par_chunks_mut(mx)
                .enumerate()
                .for_each(|(j, vr)| {
                    for (i, v) in vr.iter_mut().enumerate() {
                        *v = new(*v, j * mx + i, j < ny && i < nx);
                    }
                });
            self.step_and_project(from, velocity, step, gap, None);
            Zip::from(velocity.slice_mut(s![..ny, ..nx]))
                .and(gap.slice(s![..ny, ..nx]))
                .par_for_each(|v, &g| {
                    if g <= 0.0 && *v < 0.0 {
                        *v = 0.0
                    }
                });
            return;
        }
        let fs = flat(from);
        let (held, by) = shift.map_or((None, 0.0), |(h, by)| (Some(flat(h)), by));
        flat_mut(gap)
            .par_chunks_mut(mx)
            .zip(flat_mut(velocity).par_chunks_mut(mx))
            .enumerate()
            .for_each(|(j, (gr, vr))| {
                for i in 0..mx {
                    let (k, inside) = (j * mx + i, j < ny && i < nx);
                    let (f, v) = (fs[k], new(vr[i], k, inside));
                    gr[i] = if !inside {
                        f + step * v
                    } else if f <= 0.0 && v == 0.0 {
                        f
                    } else {
                        (f + step * v).max(0.0)
                    };
                    vr[i] = if inside && gr[i] <= 0.0 && v < 0.0 { 0.0 } else { v };
                    if held.is_some_and(|h| h[k] == 0) {
                        gr[i] = (gr[i] + by).max(0.0);
                    }
                }
            });
    }

    /// Fills `at`'s fields, energy and raw gradient from its admissible gap (made by
    /// [`Problem::step_and_project`] or [`Problem::move_cells`]); without a prescribed mean gap
    /// the gradient is projected in the same pass ([`Problem::project_gradient`] then has
    /// nothing left to do). The stiffness takes `gap - base` row by row as it goes, which no
    /// field keeps.
    pub(super) fn evaluate(&mut self, at: &mut Point) -> Result<()> {
        self.evaluate_rows(at, false, vec![(); self.my], |_, _, _| ())
            .map(|_| ())
    }

    /// As [`Problem::evaluate`], handing each row of the point, once made, with the row's
    /// item of `extra` (one a row of the unknown) to `then`, whose results come back in order
    /// of the rows: a pass that uses the fields of a row at once rather than reading them
    /// again. With `by_rows`, where the problem couples rows and the law gives its stiffness
    /// by rows, the law's three fields are made a row at a time and not stored (a step's six
    /// field-sized passes fewer on grids past the cache), until [`Problem::store_law`].
    pub(super) fn evaluate_rows<T: Send, S: Send>(
        &mut self,
        at: &mut Point,
        by_rows: bool,
        extra: Vec<T>,
        then: impl Fn(&Problem, Row<'_>, T) -> S + Sync,
    ) -> Result<Vec<S>> {
        let (mx, nx, ny) = (self.mx, self.nx, self.ny);
        let (gs, bs) = (flat(&at.gap), flat(&self.base));
        let near = self.split.as_ref().is_some_and(|s| s.near && s.made);
        if !near {
            self.stiffness.apply_rows(
                |y, row| {
                    let at = y * mx..(y + 1) * mx;
                    row.iter_mut()
                        .zip(&gs[at.clone()])
                        .zip(&bs[at])
                        .for_each(|((u, g), b)| *u = g - b);
                },
                at.elastic.view_mut(),
                &mut self.ws,
            )?;
            self.calls += 1;
        }
        let energy = self.energy;
        let with_energy = !matches!(energy, Energy::None);
        // By rows on a periodic grid only: the unknown is the block, with no padding.
        let law_rows = by_rows
            .then(|| self.law.stiffness_rows())
            .flatten()
            .filter(|_| self.couple && (mx, self.my) == (nx, ny));
        match energy {
            Energy::None if law_rows.is_some() => {}
            Energy::None => self.law_on_block(at)?,
            Energy::Field(field) => {
                let block = s![..self.ny, ..self.nx];
                field.evaluate_field(
                    at.gap.slice(block),
                    &self.cells,
                    self.probe.0.view_mut(),
                    at.law.slice_mut(block),
                    at.curvature.slice_mut(block),
                )?;
            }
            Energy::Local(_) => {}
        }
        let load = self.load.unwrap_or(0.0);
        let project = self.mean_gap.is_none();
        let cell_energies = flat(&self.probe.0);
        let (gs, bs) = (flat(&at.gap), flat(&self.base));
        // The split's far part is taken out for the pass over the rows, which writes it (after
        // a transform) or reads it (near), and put back after it.
        let mut split = self.split.take();
        let stencil = split.as_ref().map(|s| s.stencil);
        let far_rows: Vec<Option<&mut [f64]>> = match &mut split {
            Some(s) => flat_mut(&mut s.far).chunks_mut(mx).map(Some).collect(),
            None => (0..self.my).map(|_| None).collect(),
        };
        let elastic_rows: Vec<&mut [f64]> = flat_mut(&mut at.elastic).chunks_mut(mx).collect();
        let (block_gap, coupling) = (at.gap.slice(s![..ny, ..nx]), &at.coupling);
        let shared = &*self;
        let rows: Vec<([f64; 7], S)> = flat_mut(&mut at.law)
            .par_chunks_mut(mx)
            .zip(flat_mut(&mut at.curvature).par_chunks_mut(mx))
            .zip(flat_mut(&mut at.gradient).par_chunks_mut(mx))
            .zip(extra)
            .zip(elastic_rows)
            .zip(far_rows)
            .enumerate()
            .map_init(
                || {
                    let law = law_rows.map(|_| std::array::from_fn::<_, 4, _>(|_| vec![0.0; nx]));
                    (law, Vec::new(), vec![0.0; mx])
                },
                |(scratch, rows, near_row), (j, (((((lr, cr), rr), extra), es), far))| {
                    // The split's near part: with the far part the elastic pressure (near), or
                    // the far part from the transform's.
                    if let (Some(c), Some(far)) = (&stencil, far) {
                        self::near_row(c, gs, bs, (ny, nx), j, rows, near_row);
                        if near {
                            es.iter_mut()
                                .zip(&*far)
                                .zip(&*near_row)
                                .for_each(|((e, f), n)| *e = f + n);
                        } else {
                            far.iter_mut()
                                .zip(&*es)
                                .zip(&*near_row)
                                .for_each(|((f, e), n)| *f = e - n);
                        }
                    }
                    // The law's pressure, stiffness and coupling of this row: made here, or stored.
                    let (lr, cr, coupling): (&mut [f64], &mut [f64], &[f64]) = match (scratch, law_rows) {
                        (Some([t, p, c, d]), Some(rows)) => {
                            if j < ny {
                                rows.stiffness_row(block_gap, &shared.cells, j, t, [p, c, d]);
                            }
                            (p, c, d)
                        }
                        _ => (lr, cr, shared.coupling_row(coupling, j)),
                    };
                    // Elastic energy, interaction energy and the load's potential, free gradient
                    // and count, non-finite gaps, smallest gap, largest projected gradient.
                    let mut sums = [0.0, 0.0, 0.0, 0.0, 0.0, f64::INFINITY, 0.0];
                    for i in 0..mx {
                        let k = j * mx + i;
                        let g = gs[k];
                        if with_energy {
                            sums[0] += (g - bs[k]) * es[i];
                        }
                        if !g.is_finite() {
                            sums[4] += 1.0;
                        }
                        if j >= ny || i >= nx {
                            // The padding: elasticity alone (the law's fields written only if not
                            // zero already: the padding is 3/4 of a free grid).
                            if lr[i] != 0.0 || cr[i] != 0.0 {
                                (lr[i], cr[i]) = (0.0, 0.0);
                            }
                            rr[i] = es[i];
                            sums[6] = sums[6].max(es[i].abs());
                            continue;
                        }
                        // Only a local potential writes here: rewriting the law's fields unchanged
                        // would cost two field-sized writes a step on grids past the cache.
                        let (v, p) = match energy {
                            Energy::Local(potential) => {
                                let (v, p, c) = potential.evaluate(g);
                                (lr[i], cr[i]) = (p, c);
                                (v, p)
                            }
                            Energy::Field(_) => (cell_energies[j * nx + i], lr[i]),
                            Energy::None => (0.0, lr[i]),
                        };
                        rr[i] = es[i] - p + load;
                        sums[1] += v + load * g;
                        sums[5] = sums[5].min(g);
                        if g > 0.0 {
                            sums[2] += rr[i];
                            sums[3] += 1.0;
                        } else if project && rr[i] >= 0.0 {
                            rr[i] = 0.0;
                        }
                        sums[6] = sums[6].max(rr[i].abs());
                    }
                    let row = Row {
                        j,
                        gap: &gs[j * mx..][..mx],
                        gradient: rr,
                        curvature: cr,
                        coupling,
                    };
                    (sums, then(shared, row, extra))
                },
            )
            .collect();
        if let Some(s) = &mut split {
            s.made = true;
        }
        self.split = split;
        let (sums, results): (Vec<[f64; 7]>, Vec<S>) = rows.into_iter().unzip();
        let t = sums
            .iter()
            .fold([0.0, 0.0, 0.0, 0.0, 0.0, f64::INFINITY, 0.0], |mut a, b| {
                a.iter_mut().take(5).zip(b).for_each(|(a, b)| *a += b);
                a[5] = a[5].min(b[5]);
                a[6] = a[6].max(b[6]);
                a
            });
        if t[4] > 0.0 {
            let k = gs.iter().position(|g| !g.is_finite()).unwrap_or(0);
            return Err(SolverError::NonFinite {
                what: "gap",
                row: k / mx,
                col: k % mx,
                value: gs[k],
            });
        }
        let n = (self.nx * self.ny) as f64;
        at.energy = (0.5 * t[0] / n, t[1] / n);
        at.free = (t[2], t[3]);
        at.min_gap = t[5];
        at.largest = t[6];
        at.law_stored = law_rows.is_none();
        Ok(results)
    }

    /// Stores the law's fields at `at` where [`Problem::evaluate_rows`] left them unstored,
    /// for what reads them whole (the far field's relaxation, the state at the end): the same
    /// values, bit for bit.
    pub(super) fn store_law(&mut self, at: &mut Point) -> Result<()> {
        if !at.law_stored {
            self.law_on_block(at)?;
            at.law_stored = true;
        }
        Ok(())
    }

    /// Row `j` of `at`'s stored fields.
    pub(super) fn row<'r>(&self, at: &'r Point, j: usize) -> Row<'r> {
        debug_assert!(at.law_stored, "the law's fields are not stored");
        let mx = self.mx;
        Row {
            j,
            gap: &flat(&at.gap)[j * mx..][..mx],
            gradient: &flat(&at.gradient)[j * mx..][..mx],
            curvature: &flat(&at.curvature)[j * mx..][..mx],
            coupling: self.coupling_row(&at.coupling, j),
        }
    }

    /// Row `j` of a stored coupling field where the problem couples rows and `j` is on the
    /// block; else empty.
    fn coupling_row<'r>(&self, coupling: &'r Array2<f64>, j: usize) -> &'r [f64] {
        if self.couple && j < self.ny {
            &flat(coupling)[j * self.nx..][..self.nx]
        } else {
            &[]
        }
    }

    /// Writes the law's pressure at `at`'s gaps on the domain's block into `at.law`, and its
    /// stiffness `-dp/dg` [Pa/m] there into `at.curvature` (coupled: by the cell's own gap,
    /// and by its +x neighbour's into `at.coupling`), in closed form where the law has it,
    /// else from a probe at gaps larger by a thousandth of the range: a law without a local
    /// potential may depend on the neighbours' gaps (the surface law), so the field is
    /// evaluated as a whole.
    fn law_on_block(&mut self, at: &mut Point) -> Result<()> {
        let block = s![..self.ny, ..self.nx];
        let gap = at.gap.slice(block);
        if self.couple {
            if at.coupling.dim() != (self.ny, self.nx) {
                at.coupling = Array2::zeros((self.ny, self.nx));
            }
            if self.law.pressure_and_stiffness_field(
                gap,
                &self.cells,
                at.law.slice_mut(block),
                at.curvature.slice_mut(block),
                at.coupling.view_mut(),
            )? {
                return Ok(());
            }
        }
        self.law
            .pressure_field(gap, &self.cells, at.law.slice_mut(block))?;
        if self.probe.1.dim() != gap.dim() {
            self.probe = (Array2::zeros(gap.dim()), Array2::zeros(gap.dim()));
        }
        let probe = 1e-3 * self.law.range();
        if self.couple {
            // Every other column probed at a time: a cell's pressure depends on its own gap and
            // its +x neighbour's (and on its +y neighbour's only through the area factor, whose
            // column is probed with its own).
            for parity in 0..2 {
                let (shifted, shifted_law) = &mut self.probe;
                Zip::indexed(&mut *shifted)
                    .and(&gap)
                    .par_for_each(|(_, i), s, &g| *s = if i % 2 == parity { g + probe } else { g });
                self.law
                    .pressure_field(shifted.view(), &self.cells, shifted_law.view_mut())?;
                Zip::indexed(at.curvature.slice_mut(block))
                    .and(&mut at.coupling)
                    .and(&at.law.slice(block))
                    .and(&self.probe.1)
                    .par_for_each(|(_, i), own, next, &lo, &hi| {
                        if i % 2 == parity {
                            *own = (lo - hi) / probe;
                        } else {
                            *next = (lo - hi) / probe;
                        }
                    });
            }
            return Ok(());
        }
        let (shifted, shifted_law) = &mut self.probe;
        Zip::from(&mut *shifted)
            .and(&gap)
            .par_for_each(|s, &g| *s = g + probe);
        self.law
            .pressure_field(shifted.view(), &self.cells, shifted_law.view_mut())?;
        Zip::from(at.curvature.slice_mut(block))
            .and(&at.law.slice(block))
            .and(&*shifted_law)
            .par_for_each(|c, &lo, &hi| *c = (lo - hi) / probe);
        Ok(())
    }

    /// Projects `at`'s raw gradient in place: less the mean-pressure multiplier (its mean over
    /// the cells off the wall), zero where a cell on the wall is pushed into it (that is its
    /// contact pressure), and with zero mean over the cells that move, so that the mean gap
    /// stays (the multiplier and the mean only where the mean gap is prescribed).
    pub(super) fn project_gradient(&self, at: &mut Point) -> GradientSums {
        let (mx, nx, ny) = (self.mx, self.nx, self.ny);
        let lambda = if self.mean_gap.is_some() && at.free.1 > 0.0 {
            at.free.0 / at.free.1
        } else {
            0.0
        };
        if self.mean_gap.is_none() {
            // No multiplier and no mean to keep: projected by `evaluate`.
            return GradientSums {
                lambda,
                max: at.largest,
            };
        }
        let gs = flat(&at.gap);
        let [sum, moving] = {
            let rs = flat_mut(&mut at.gradient);
            let parts: Vec<[f64; 2]> = rs
                .par_chunks_mut(mx)
                .enumerate()
                .map(|(j, row)| {
                    let mut sums = [0.0; 2];
                    for (i, (r, &g)) in row.iter_mut().zip(&gs[j * mx..][..mx]).enumerate() {
                        let v = *r - lambda;
                        *r = if on_wall(j, i, g, nx, ny) && v >= 0.0 {
                            0.0
                        } else {
                            v
                        };
                        if *r != 0.0 {
                            sums[0] += *r;
                            sums[1] += 1.0;
                        }
                    }
                    sums
                })
                .collect();
            parts.iter().fold([0.0; 2], |a, b| [a[0] + b[0], a[1] + b[1]])
        };
        let shift = if self.mean_gap.is_some() && moving > 0.0 {
            sum / moving
        } else {
            0.0
        };
        let max = flat_mut(&mut at.gradient)
            .par_iter_mut()
            .map(|r| {
                if *r != 0.0 {
                    *r -= shift;
                }
                r.abs()
            })
            .reduce(|| 0.0, f64::max);
        GradientSums { lambda, max }
    }

    /// Writes the preconditioned gradient `z = (r - mu) / m` into `out`, with `m = S_ii +
    /// max(V'', 0)` the curvature's diagonal (the Lennard-Jones tail just above the wall is
    /// many times stiffer than a cell), `r` `at`'s projected gradient and `mu` the weighted mean
    /// that keeps the moving cells' sum at zero when the mean gap is prescribed. Returns
    /// `<z, r>` and `<z, old>`.
    pub(super) fn precondition(&self, at: &Point, old: &Array2<f64>, out: &mut Array2<f64>) -> [f64; 2] {
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
    pub(super) fn couple_rows(&mut self, at: &mut Point) -> Result<()> {
        if matches!(self.energy, Energy::None) && self.law.local_potential().is_none() {
            self.couple = true;
            self.evaluate(at)?;
        }
        Ok(())
    }

    /// Whether the grid is periodic with at least `n` cells along each axis.
    pub(super) fn periodic_at_least(&self, n: usize) -> bool {
        (self.mx, self.my) == (self.nx, self.ny) && self.nx >= n && self.ny >= n
    }

    /// Whether [`Problem::couple_rows`] took effect.
    pub(super) fn coupled(&self) -> bool {
        self.couple
    }

    /// As [`Problem::precondition`], with the mass `m` coupled to the +x neighbour as the law
    /// couples the cells (the line and surface laws), for the flow. Returns `<z, r>`.
    pub(super) fn precondition_rows(&self, at: &Point, out: &mut Array2<f64>) -> f64 {
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
    pub(super) fn pull_row(&self, row: &Row, zr: &mut [f64]) -> f64 {
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
    pub(super) fn solve_rows(
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
    pub(super) fn mass(&self, curvature: &[f64], j: usize, i: usize, k: usize) -> f64 {
        self.cell_mass(j, i, || curvature[k])
    }

    /// [`Problem::mass`] of cell `i` of `row`.
    pub(super) fn row_mass(&self, row: &Row, i: usize) -> f64 {
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

/// Whether cell `(j, i)` of the unknown, at `g`, is on the wall: the unknown is the gap (the
/// domain's `(ny, nx)` block) and it is closed.
pub(super) fn on_wall(j: usize, i: usize, g: f64, nx: usize, ny: usize) -> bool {
    g <= 0.0 && j < ny && i < nx
}

/// Refuses, for the solver `name`, the controls the gap problem does not take: loads and
/// central gaps on free domains, central gaps anywhere.
pub(super) fn check_control(job: &Job, name: &str) -> Result<()> {
    if !job.op.domain().periodic && !matches!(job.control, Control::Approach(_)) {
        return Err(SolverError::Unsupported(format!(
            "{name} on a free domain takes the approach only (use `accelerated` for loads and \
             central gaps)"
        )));
    }
    if let Control::CentralGap(g) = job.control {
        return Err(invalid(
            "central_gap",
            g,
            format!("{name} takes the approach (or mean gap), the load or the mean pressure"),
        ));
    }
    Ok(())
}

/// A problem over the gap, set up from a solve's arguments, at its first admissible point.
pub(super) struct Setup<'a> {
    pub(super) problem: Problem<'a>,
    /// The first admissible point, evaluated (its gradient not yet projected).
    pub(super) x: Point,
    /// The approach \[m\] (approach control; else 0).
    pub(super) delta: f64,
    /// The mean pressure \[Pa\] (load control; else `None`).
    pub(super) load: Option<f64>,
}

/// Sets up the problem over the gap (or the padded displacement, free) under approach control
/// (`Control::Approach`) or, periodic only, load control (`Control::Force`,
/// `Control::MeanPressure`), with the law's `energy` if it has one; see the module docs.
pub(super) fn setup<'a>(job: &Job<'a>, energy: Energy<'a>) -> Result<Setup<'a>> {
    let (op, law, g0, settings) = (job.op, job.law, job.g0, job.settings);
    let (control, start) = (job.control, job.start);
    let domain = *op.domain();
    let shape = domain.shape();
    let (ny, nx) = shape;
    if let Some(((row, col), &value)) = g0.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(SolverError::NonFinite {
            what: "initial gap",
            row,
            col,
            value,
        });
    }
    let n = (nx * ny) as f64;
    // The cells' energies of a field energy; a probe's buffers are made when first needed.
    let probe = || {
        let energies = if matches!(energy, Energy::Field(_)) {
            shape
        } else {
            (0, 0)
        };
        (Array2::zeros(energies), Array2::zeros((0, 0)))
    };
    let cells = cells(&domain);
    let (delta, load) = match control {
        Control::Approach(d) => (d, None),
        Control::MeanPressure(p) => (0.0, Some(p)),
        Control::Force(w) => (0.0, Some(w / (n * domain.cell_area()))),
        Control::CentralGap(_) => unreachable!("refused by the caller"),
    };
    let mean_gap = g0.mean().unwrap_or(0.0) - delta;
    if domain.periodic && load.is_none() && mean_gap <= 0.0 {
        return Err(invalid(
            "approach",
            delta,
            "reaches the mean initial gap: a periodic surface is in full contact before that",
        ));
    }
    let (mut problem, first, hold) = if domain.periodic {
        let stiffness = PeriodicStiffness::new(domain, op.e_star())?;
        let first = match start {
            // A first step from the rigid overlap (or, under load control, where the rigid
            // shift has no elastic stiffness, from a point contact) would snap far more of
            // the surface in than a quasi-static approach does: start from the non-adhesive
            // contact at the same compressive load or approach instead.
            Start::Loading => {
                let non_adhesive = |control| {
                    crate::cg::solve(op, g0, control, &settings.contact, None, &mut ()).map(|(s, _)| s.gap)
                };
                match load {
                    Some(p) if p > 0.0 => non_adhesive(Control::MeanPressure(p))?,
                    None if delta > 0.0 => non_adhesive(Control::Approach(delta))?,
                    _ => g0.mapv(|g| g - delta),
                }
            }
            Start::Unloading => Array2::zeros(shape),
            Start::Warm(s) => s.contact.gap.clone(),
        };
        let problem = Problem {
            ws: stiffness.make_workspace(),
            stiffness: Stiffness::Periodic(stiffness),
            energy,
            law,
            cells,
            domain,
            probe: probe(),
            couple: false,
            base: g0.to_owned(),
            mx: nx,
            my: ny,
            nx,
            ny,
            mean_gap: load.is_none().then_some(mean_gap),
            load,
            calls: 0,
            diagonal: 0.0,
            split: None,
        };
        // A warm start keeps its attached cells (gap within the law's range) in place and
        // moves only the rest: a uniform shift would tear the attached rim off at once (or
        // press cells into attraction on loading), and the descent would settle in that
        // state's basin rather than follow the branch; from the held guess the descent itself
        // decides what peels off.
        let hold = matches!(start, Start::Warm(_)).then(|| law.range());
        (problem, first, hold)
    } else {
        let stiffness = FreeStiffness::new(domain, op.e_star())?;
        let padded = stiffness.padded_shape();
        let mut ws = stiffness.make_workspace();
        let mut base = Array2::zeros(padded);
        base.slice_mut(s![..ny, ..nx]).assign(&g0.mapv(|g| g - delta));
        // The first guess: the base (no displacement) from scratch; a warm start keeps the old
        // displacement, with its attached cells held at their old gaps (as on periodic grids).
        let mut first = Array2::zeros(padded);
        match start {
            Start::Loading => first.assign(&base),
            Start::Unloading => {}
            Start::Warm(s) => {
                let total = &s.contact.pressure + &s.adhesive_pressure;
                stiffness.displacement(total.view(), first.view_mut(), &mut ws)?;
                first += &base;
                let range = law.range();
                Zip::from(first.slice_mut(s![..ny, ..nx]))
                    .and(&s.contact.gap)
                    .for_each(|f, &old| {
                        if old <= range {
                            *f = old;
                        }
                    });
            }
        }
        let problem = Problem {
            ws,
            stiffness: Stiffness::Free(stiffness),
            energy,
            law,
            cells,
            domain,
            probe: probe(),
            couple: false,
            base,
            mx: padded.1,
            my: padded.0,
            nx,
            ny,
            mean_gap: None,
            load: None,
            calls: 0,
            diagonal: 0.0,
            split: None,
        };
        (problem, first, None)
    };
    let unknown = first.dim();
    {
        // The stiffness is a convolution: its diagonal is the response to a unit impulse.
        let mut impulse = Array2::zeros(unknown);
        impulse[(0, 0)] = 1.0;
        let mut response = Array2::zeros(unknown);
        problem
            .stiffness
            .apply(impulse.view(), response.view_mut(), &mut problem.ws)?;
        problem.diagonal = response[(0, 0)];
        problem.calls += 1;
    }
    let mut x = Point::new(Array2::zeros(unknown));
    problem.step_and_project(&first, &first, 0.0, &mut x.gap, hold);
    drop(first);
    problem.evaluate(&mut x)?;
    Ok(Setup {
        problem,
        x,
        delta,
        load,
    })
}

/// The state and report at the solution `x`, whose gradient `sums` describe (see [`setup`]
/// for `delta` and `load`); `outcome`'s operator calls are replaced by the problem's count.
pub(super) fn finish(
    job: &Job,
    problem: &Problem,
    x: Point,
    sums: &GradientSums,
    (delta, load): (f64, Option<f64>),
    mut outcome: Outcome,
) -> (AdhesiveState, AdhesiveReport) {
    let g0 = job.g0;
    let domain = problem.domain;
    let shape = domain.shape();
    let (ny, nx) = shape;
    // The mean pressure: prescribed, or minus the multiplier of the mean gap (free: none).
    let mean_pressure = load.unwrap_or(-sums.lambda);
    let block = s![..ny, ..nx];
    let (gap, elastic, law_pressure) = if domain.periodic {
        (x.gap, x.elastic, x.law)
    } else {
        let take = |a: &Array2<f64>| a.slice(block).to_owned();
        (take(&x.gap), take(&x.elastic), take(&x.law))
    };
    // Contact pressure where the gap is closed: the gradient's elastic and adhesive part plus
    // the mean pressure.
    let mut pressure = Array2::zeros(shape);
    Zip::from(&mut pressure)
        .and(&gap)
        .and(&elastic)
        .and(&law_pressure)
        .par_for_each(|p, &g, &e, &l| {
            *p = if g <= 0.0 {
                (e - l + mean_pressure).max(0.0)
            } else {
                0.0
            }
        });
    // Periodic: the mean displacement is zero. Free: the base is `g0 - delta`.
    let mut displacement = &gap - &problem.base.slice(block);
    if domain.periodic {
        let mean = displacement.mean().unwrap_or(0.0);
        displacement.mapv_inplace(|u| u - mean);
    }
    let approach = match load {
        None => delta,
        Some(_) => g0.mean().unwrap_or(0.0) - gap.mean().unwrap_or(0.0),
    };
    let contact = ContactState {
        pressure,
        gap,
        displacement,
        approach,
    };
    outcome.operator_calls = problem.calls;
    assemble(job, contact, law_pressure, outcome)
}
