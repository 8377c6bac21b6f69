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
//!
//! Under a hardness `H` ([`crate::Interface`]) the wall gives way: the gap on the block may go
//! negative, by the overlap that becomes the permanent set, at the price `H |g|` a cell
//! (`E` gains `mean(H max(-g, 0))`, and the law continues below `g = 0` along its tangent, so
//! that a yielded cell feels the contact's adhesive pressure `p(0)` beside `H`). The energy is
//! then smooth but for a kink at `g = 0`, where the contact pressure fills `[0, H]`: each cell
//! keeps to its side of the kink through a step (the side of its gap, or on the wall of the
//! direction), as orthant-wise descent does for an L1 term (Andrew & Gao, ICML 2007).
//!
//! The system lives here: a point and its evaluation (the law, the stiffness's response, the
//! gradient and its projection). Its parts: the stiffness and its near/far split
//! (`stiffness`), the row-coupled preconditioner of the line and surface laws (`rows`), the
//! cold start and the finish (`setup`).

mod rows;
mod setup;
mod stiffness;

pub(super) use setup::{Setup, check_control, finish, setup, state};
pub(super) use stiffness::Stiffness;
use stiffness::{Split, near_row};

use crate::error::{Result, SolverError};
use crate::fields::{flat, flat_mut};
use elastic::Domain;
use ljadhesion::{AdhesionLaw, Cells, FieldPotential, LocalPotential};
use ndarray::{Array2, Zip, s};
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
    /// Under a hardness, the block's gaps as the law reads them ([`Problem::close_gaps`]); made
    /// when a cell first yields.
    closed: Array2<f64>,
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
    /// The hardness \[Pa\] ([`crate::Interface::cap`]): infinite for a rigid wall.
    pub(super) cap: f64,
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

impl Problem<'_> {
    /// Writes `max(from + step d + c, 0)` into `gap` (on the domain's block; no bound in the
    /// padding), with the shift `c` that restores a prescribed mean gap (else 0), except on
    /// cells of `from` on the wall that `d` leaves there, which stay: the projection of the
    /// step onto the constraints within the current face. Under a hardness a cell below the
    /// wall, or on it and sent below by `d`, is bounded from above instead, `min(.., 0)` (it
    /// stays on its side of the kink, module docs). `c` comes from Newton on the monotone,
    /// piecewise-linear mean (exact after finitely many steps). With `hold` (periodic),
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
        let held = |f: f64, d: f64| hold.is_some_and(|h| f <= h) || (f == 0.0 && d == 0.0);
        let yields = self.cap.is_finite();
        // The cell's side of the kink: below the wall (bounded above by it) or above.
        let below = |f: f64, d: f64| yields && (f < 0.0 || (f == 0.0 && d < 0.0));
        let project = |f: f64, d: f64, v: f64| if below(f, d) { v.min(0.0) } else { v.max(0.0) };
        let mut c = 0.0;
        // A prescribed mean gap is periodic: the unknown is the gap everywhere.
        for _ in 0..if self.mean_gap.is_some() { 100 } else { 0 } {
            let [sum, free] = crate::sum::ordered(self.ny, |j| {
                let (f, d) = (&fs[j * nx..][..nx], &ds[j * nx..][..nx]);
                f.iter().zip(d).fold([0.0, 0.0], |[s, k], (&f, &d)| {
                    let v = f + step * d + c;
                    if held(f, d) {
                        [s + f, k]
                    } else if (v > 0.0) != below(f, d) && v != 0.0 {
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
                    project(f, ds[k], f + step * ds[k] + c)
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
        // Under a hardness a cell stays on its side of the kink, as in `step_and_project`, and
        // one stopped at the kink from either side keeps no velocity across it.
        let yields = self.cap.is_finite();
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
                    if g == 0.0 && (*v < 0.0 || (yields && *v > 0.0)) {
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
                    let below = yields && (f < 0.0 || (f == 0.0 && v < 0.0));
                    gr[i] = if !inside {
                        f + step * v
                    } else if f == 0.0 && v == 0.0 {
                        f
                    } else if below {
                        (f + step * v).min(0.0)
                    } else {
                        (f + step * v).max(0.0)
                    };
                    let stopped = gr[i] == 0.0 && if below { v > 0.0 } else { v < 0.0 };
                    vr[i] = if inside && stopped { 0.0 } else { v };
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
        // By rows on a periodic grid only: the unknown is the block, with no padding.
        let law_rows = by_rows
            .then(|| self.law.stiffness_rows())
            .flatten()
            .filter(|_| self.couple && (mx, self.my) == (nx, ny));
        // The gaps the law reads here (`law_on_block` closes its own).
        let closed = (law_rows.is_some() || matches!(energy, Energy::Field(_))) && self.close_gaps(at);
        match energy {
            Energy::None if law_rows.is_some() => {}
            Energy::None => self.law_on_block(at)?,
            Energy::Field(field) => {
                let block = s![..self.ny, ..self.nx];
                let gap = if closed {
                    self.closed.view()
                } else {
                    at.gap.slice(block)
                };
                field.evaluate_field(
                    gap,
                    &self.cells,
                    self.probe.0.view_mut(),
                    at.law.slice_mut(block),
                    at.curvature.slice_mut(block),
                )?;
            }
            Energy::Local(_) => {}
        }
        let (gs, bs) = (flat(&at.gap), flat(&self.base));
        let pass = Pass {
            shape: (mx, nx, ny),
            gap: gs,
            base: bs,
            cell_energies: flat(&self.probe.0),
            energy,
            load: self.load.unwrap_or(0.0),
            project: self.mean_gap.is_none(),
            cap: self.cap,
        };
        // The split's far part is taken out for the pass over the rows, which writes it (after
        // a transform) or reads it (near), and put back after it.
        let mut split = self.split.take();
        let stencil = split.as_ref().map(|s| s.stencil);
        let far_rows: Vec<Option<&mut [f64]>> = match &mut split {
            Some(s) => flat_mut(&mut s.far).chunks_mut(mx).map(Some).collect(),
            None => (0..self.my).map(|_| None).collect(),
        };
        let elastic_rows: Vec<&mut [f64]> = flat_mut(&mut at.elastic).chunks_mut(mx).collect();
        let block_gap = if closed {
            self.closed.view()
        } else {
            at.gap.slice(s![..ny, ..nx])
        };
        let coupling = &at.coupling;
        let shared = &*self;
        let rows: Vec<(RowSums, S)> = flat_mut(&mut at.law)
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
                    let sums = pass.balance_row(j, es, lr, cr, rr);
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
        let (sums, results): (Vec<RowSums>, Vec<S>) = rows.into_iter().unzip();
        let t = sums.iter().fold(RowSums::EMPTY, RowSums::and);
        if t.non_finite > 0.0 {
            let k = gs.iter().position(|g| !g.is_finite()).unwrap_or(0);
            return Err(SolverError::NonFinite {
                what: "gap",
                row: k / mx,
                col: k % mx,
                value: gs[k],
            });
        }
        let n = (self.nx * self.ny) as f64;
        at.energy = (0.5 * t.elastic_energy / n, t.interaction_energy / n);
        at.free = (t.free_gradient, t.free_cells);
        at.min_gap = t.min_gap;
        at.largest = t.max_gradient;
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

    /// Under a hardness, with a cell yielded below the wall, writes the block's gaps as the law
    /// sees them into `closed` and returns true: closed there (the yielded surface lies on the
    /// counterface; a law of the neighbours' gaps would otherwise read the overlap as a tilt).
    /// Else false: the law reads the gaps themselves.
    fn close_gaps(&mut self, at: &Point) -> bool {
        let block = at.gap.slice(s![..self.ny, ..self.nx]);
        if !self.cap.is_finite() || !block.iter().any(|&g| g < 0.0) {
            return false;
        }
        if self.closed.dim() != block.dim() {
            self.closed = Array2::zeros(block.dim());
        }
        Zip::from(&mut self.closed)
            .and(&block)
            .par_for_each(|c, &g| *c = g.max(0.0));
        true
    }

    /// Writes the law's pressure at `at`'s gaps on the domain's block into `at.law`, and its
    /// stiffness `-dp/dg` [Pa/m] there into `at.curvature` (coupled: by the cell's own gap,
    /// and by its +x neighbour's into `at.coupling`), in closed form where the law has it,
    /// else from a probe at gaps larger by a thousandth of the range: a law without a local
    /// potential may depend on the neighbours' gaps (the surface law), so the field is
    /// evaluated as a whole.
    fn law_on_block(&mut self, at: &mut Point) -> Result<()> {
        let block = s![..self.ny, ..self.nx];
        let gap = if self.close_gaps(at) {
            self.closed.view()
        } else {
            at.gap.slice(block)
        };
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
    /// the cells off the wall), less what the wall takes up where a cell on it is pushed into
    /// it (that is its contact pressure, at most the hardness), and with zero mean over the
    /// cells that move, so that the mean gap stays (the multiplier and the mean only where the
    /// mean gap is prescribed).
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
                        *r = if on_wall(j, i, g, nx, ny) {
                            v - v.clamp(0.0, self.cap)
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
}

/// What one evaluation's pass over the rows shares ([`Problem::evaluate_rows`]).
struct Pass<'a> {
    /// Columns of the unknown, columns and rows of the domain's block.
    shape: (usize, usize, usize),
    /// The unknown and the base, flat.
    gap: &'a [f64],
    base: &'a [f64],
    /// The cells' energies of a field energy (else empty).
    cell_energies: &'a [f64],
    energy: Energy<'a>,
    /// The prescribed mean pressure \[Pa\] (else 0).
    load: f64,
    /// Whether the gradient is projected here (no prescribed mean gap).
    project: bool,
    /// The hardness \[Pa\] (infinite: a rigid wall).
    cap: f64,
}

/// A row's share of an evaluation's sums, added over the rows in order
/// ([`crate::sum`]'s rule: the same bits on any number of threads).
#[derive(Clone, Copy)]
struct RowSums {
    /// `sum (g - b) S (g - b)` \[Pa m\] (with an energy only).
    elastic_energy: f64,
    /// Interaction energy plus the load's potential, summed \[J/m^2\].
    interaction_energy: f64,
    /// The gradient's sum over the cells off the wall \[Pa\], and their number.
    free_gradient: f64,
    free_cells: f64,
    /// Cells with a non-finite gap.
    non_finite: f64,
    /// The smallest gap \[m\] on the block.
    min_gap: f64,
    /// The largest projected gradient `|r|` \[Pa\].
    max_gradient: f64,
}

impl RowSums {
    const EMPTY: RowSums = RowSums {
        elastic_energy: 0.0,
        interaction_energy: 0.0,
        free_gradient: 0.0,
        free_cells: 0.0,
        non_finite: 0.0,
        min_gap: f64::INFINITY,
        max_gradient: 0.0,
    };

    fn and(mut self, b: &RowSums) -> RowSums {
        self.elastic_energy += b.elastic_energy;
        self.interaction_energy += b.interaction_energy;
        self.free_gradient += b.free_gradient;
        self.free_cells += b.free_cells;
        self.non_finite += b.non_finite;
        self.min_gap = self.min_gap.min(b.min_gap);
        self.max_gradient = self.max_gradient.max(b.max_gradient);
        self
    }
}

impl Pass<'_> {
    /// Row `j`'s gradient `rr` from its elastic pressure `es` and the law (its pressure `lr` and
    /// curvature `cr`, written here by a local potential), projected without a prescribed mean
    /// gap, and the row's sums.
    fn balance_row(&self, j: usize, es: &[f64], lr: &mut [f64], cr: &mut [f64], rr: &mut [f64]) -> RowSums {
        let Pass {
            shape: (mx, nx, ny),
            gap: gs,
            base: bs,
            cell_energies,
            energy,
            load,
            project,
            cap,
        } = *self;
        let with_energy = !matches!(energy, Energy::None);
        let mut sums = RowSums::EMPTY;
        for i in 0..mx {
            let k = j * mx + i;
            let g = gs[k];
            if with_energy {
                sums.elastic_energy += (g - bs[k]) * es[i];
            }
            if !g.is_finite() {
                sums.non_finite += 1.0;
            }
            if j >= ny || i >= nx {
                // The padding: elasticity alone (the law's fields written only if not
                // zero already: the padding is 3/4 of a free grid).
                if lr[i] != 0.0 || cr[i] != 0.0 {
                    (lr[i], cr[i]) = (0.0, 0.0);
                }
                rr[i] = es[i];
                sums.max_gradient = sums.max_gradient.max(es[i].abs());
                continue;
            }
            // Only a local potential writes here: rewriting the law's fields unchanged
            // would cost two field-sized writes a step on grids past the cache.
            let (mut v, p) = match energy {
                Energy::Local(potential) => {
                    let (v, p, c) = potential.evaluate(g);
                    (lr[i], cr[i]) = (p, c);
                    (v, p)
                }
                Energy::Field(_) => (cell_energies[j * nx + i], lr[i]),
                Energy::None => (0.0, lr[i]),
            };
            rr[i] = es[i] - p + load;
            if g < 0.0 {
                // Yielded (only under a hardness): the law goes on along its tangent at contact
                // (the pressure the laws give a negative gap, no curvature), and the cell pays
                // `H` for every metre below the wall.
                v -= (p + cap) * g;
                cr[i] = 0.0;
                rr[i] -= cap;
            }
            sums.interaction_energy += v + load * g;
            sums.min_gap = sums.min_gap.min(g);
            if g != 0.0 {
                sums.free_gradient += rr[i];
                sums.free_cells += 1.0;
            } else if project {
                // On the wall: the contact pressure takes up what it can, up to the hardness.
                rr[i] -= rr[i].clamp(0.0, cap);
            }
            sums.max_gradient = sums.max_gradient.max(rr[i].abs());
        }
        sums
    }
}

/// Roughly the peak memory \[bytes\] of a gap method's solve on a grid of `cells` cells
/// without a Krylov basis (the energy descent, the flow): the bytes a cell measured at
/// 256^2-1024^2 (`docs/performance.md`); a free domain's unknown is the padded 2nx x 2ny grid.
pub(super) fn peak_bytes(cells: f64, periodic: bool) -> f64 {
    if periodic { 256.0 * cells } else { 768.0 * cells }
}

/// Whether cell `(j, i)` of the unknown, at `g`, is on the wall: the unknown is the gap (the
/// domain's `(ny, nx)` block) and it is closed (not yielded below it).
pub(super) fn on_wall(j: usize, i: usize, g: f64, nx: usize, ny: usize) -> bool {
    g == 0.0 && j < ny && i < nx
}
