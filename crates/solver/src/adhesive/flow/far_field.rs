//! The far field of the flow: the soft cells' rigid shift and their relaxation by conjugate
//! gradients with the other cells held.

use super::*;

/// The far field (under load control; under a prescribed mean gap for its relaxation alone):
/// the soft cells, farther than [`SOFT_CLEARANCE`] ranges from the wall with the law's
/// stiffness below a cell's own, which the flow alone moves slowest of all (their stiffness
/// is the contacts' and the free surface's long wavelengths', their mass every free cell's).
/// Cells near the wall stay out of the soft set, since a cell passing in and out of it
/// stalled the flow (`docs/decisions.md`). Two accelerations, neither of which changes the
/// states of rest (`r = 0`) nor moves a cell past one:
///
/// - the rigid shift, every step under load control: the soft cells leave their uniform mode
///   to an overdamped step of its own, a share of its Newton step `-(u^T r) / k` with `u`
///   their indicator and `k = u^T S u + sum max(K, 0)`, scaled with the flow's `dt^2` so
///   that the two never push the mode against each other; the flow moves the rest of their
///   field. One more application of the stiffness each time the soft set changes.
/// - the relaxation of the far field, every [`RELAX_EVERY`] steps ([`FarField::relax`]): all
///   of the soft cells' wavelengths at once, by conjugate gradients with the other cells
///   held and the compliance as preconditioner, where the flow's strongly damped dynamics
///   takes ~250 steps a decade at 1024^2.
pub(super) struct FarField {
    /// 1 on the held cells, 0 on the soft cells (bytes: read twice a step under load
    /// control, a field of doubles costs a step's time on grids past the cache).
    pub(super) held: Array2<u8>,
    /// `S held` \[Pa/m\] as the held set was when last transformed.
    pub(super) response: Array2<f64>,
    /// The cells whose flag changed since, by flat index, with the change (+1 held, -1 soft);
    /// `None` before the first transform.
    pub(super) changes: Option<Vec<(usize, f64)>>,
    /// The stiffness's kernel `S e_0` \[Pa/m\] at offsets `(0..=my/2, 0..=mx/2)` (it is even in
    /// each axis), made at the first transform.
    pub(super) kernel: Option<Array2<f64>>,
    /// `held^T S held` \[Pa/m, summed over cells\]: the soft cells' elastic stiffness for a
    /// uniform move, `u^T S u` with `u = 1 - held` (a periodic `S` takes no uniform field).
    pub(super) elastic: f64,
    /// The shift's Newton step \[m\].
    pub(super) step: f64,
    /// The pull's mean over the soft cells \[m per time unit squared\], which the shift moves
    /// them by instead of the flow.
    pub(super) mean: f64,
    /// The relaxation's move, residual, direction, the operator on it and the preconditioned
    /// residual (made at its first use).
    pub(super) work: Option<[Array2<f64>; 5]>,
    /// Under a prescribed mean gap, the preconditioned soft cells' indicator (made at its first
    /// use).
    pub(super) projection: Option<Array2<f64>>,
}

/// The correction of the soft cells' uniform mode in [`FarField::precondition`].
enum Correction<'a> {
    /// The uniform mode's stiffness \[Pa/m, summed over cells\] (load control).
    Uniform(f64),
    /// The preconditioned indicator `w` and `u^T w` (a prescribed mean gap).
    KeepSum(&'a Array2<f64>, f64),
}

/// The sum of a field over all cells, in a fixed order.
fn total(problem: &Problem, f: &Array2<f64>) -> f64 {
    let (mx, fs) = (problem.mx, crate::fields::flat(f));
    let [sum] = crate::sum::ordered(problem.my, |j| [fs[j * mx..(j + 1) * mx].iter().sum::<f64>()]);
    sum
}

impl FarField {
    pub(super) fn new(shape: (usize, usize)) -> FarField {
        FarField {
            held: Array2::from_elem(shape, u8::MAX),
            response: Array2::zeros(shape),
            changes: None,
            kernel: None,
            elastic: 0.0,
            step: 0.0,
            mean: 0.0,
            work: None,
            projection: None,
        }
    }

    /// Marks the soft cells at `at` in `held` (0 soft, 1 held): farther than
    /// [`SOFT_CLEARANCE`] ranges from the wall, the law's stiffness below a cell's own.
    pub(super) fn mark(&mut self, problem: &Problem, at: &Point) {
        let (clearance, cell) = (SOFT_CLEARANCE * problem.law.range(), problem.diagonal);
        Zip::from(&mut self.held)
            .and(&at.gap)
            .and(&at.curvature)
            .par_for_each(|h, &g, &c| *h = soft_or_held(g, c, clearance, cell));
    }

    /// Writes into `trial`'s gap (to be evaluated) the point `x` with its soft cells moved
    /// towards their balance with the other cells held: conjugate gradients on
    /// `(S + max(K, 0)) d = -r` restricted to the soft cells (positive definite: the held cells
    /// give even the uniform mode a stiffness), for at most [`RELAX_ITERATIONS`]. The law's
    /// curvature enters by its stable part only and is weak this far from the wall, so the
    /// move falls short of the balance rather than past it. Preconditioned by the compliance
    /// restricted to the soft cells, `P S^-1 P` ([`FarField::precondition`]): the soft cells
    /// are most of the grid, so it is nearly the operator's inverse, and a solve takes about
    /// ten iterations at any size where the diagonal took hundreds (`docs/decisions.md`).
    /// Under a prescribed mean gap the move keeps the soft cells' sum (projected conjugate
    /// gradients).
    pub(super) fn relax(&mut self, problem: &mut Problem, x: &Point, trial: &mut Point) -> Result<()> {
        use crate::fields::{flat, flat_mut};
        use crate::sum::ordered_over;
        use rayon::prelude::*;
        let mx = problem.mx;
        let [delta, residual, direction, applied, z] = self
            .work
            .get_or_insert_with(|| std::array::from_fn(|_| Array2::zeros(x.gap.dim())));
        let (held, hs) = (&self.held, flat(&self.held));
        let law = |c: f64| c.max(0.0);
        let correction = match problem.mean_gap {
            Some(_) => {
                // `w = P S^-1 P u` and `u^T w`, `u` the soft cells' indicator.
                let w = self.projection.get_or_insert_with(|| Array2::zeros(x.gap.dim()));
                Zip::from(&mut *z)
                    .and(held)
                    .par_for_each(|u, &h| *u = f64::from(u8::from(h == 0)));
                FarField::compliance(problem, held, z, w)?;
                let uw = total(problem, w);
                Correction::KeepSum(w, uw)
            }
            None => {
                let [law_sum] = crate::sum::ordered(problem.my, |j| {
                    let row = j * mx..(j + 1) * mx;
                    let (cs, hs) = (&flat(&x.curvature)[row.clone()], &hs[row]);
                    [cs.iter()
                        .zip(hs)
                        .filter(|(_, h)| **h == 0)
                        .map(|(&c, _)| law(c))
                        .sum::<f64>()]
                });
                Correction::Uniform(self.elastic + law_sum)
            }
        };
        delta.fill(0.0);
        // Each pass below also makes the sums the next step needs, row by row in order (as
        // `crate::sum`), so that a field is read once where it is written.
        let (rs, cs) = (flat(&x.gradient), flat(&x.curvature));
        let [mut q_sum] = ordered_over(flat_mut(residual).par_chunks_mut(mx), |j, qr| {
            let row = j * mx..(j + 1) * mx;
            let mut sum = 0.0;
            for ((q, &h), &r) in qr.iter_mut().zip(&hs[row.clone()]).zip(&rs[row]) {
                *q = if h == 0 { -r } else { 0.0 };
                sum += *q;
            }
            [sum]
        });
        let mut qz = FarField::precondition(problem, held, &correction, residual, q_sum, z)?;
        direction.assign(z);
        let first = qz;
        for _ in 0..RELAX_ITERATIONS {
            if qz <= RELAX_TOLERANCE * RELAX_TOLERANCE * first {
                break;
            }
            problem
                .stiffness
                .apply(direction.view(), applied.view_mut(), &mut problem.ws)?;
            problem.calls += 1;
            let ds = flat(direction);
            let [curvature] = ordered_over(flat_mut(applied).par_chunks_mut(mx), |j, ar| {
                let row = j * mx..(j + 1) * mx;
                let mut sum = 0.0;
                for (((a, &h), &d), &c) in ar
                    .iter_mut()
                    .zip(&hs[row.clone()])
                    .zip(&ds[row.clone()])
                    .zip(&cs[row])
                {
                    *a = if h == 0 { *a + law(c) * d } else { 0.0 };
                    sum += d * *a;
                }
                [sum]
            });
            if curvature <= 0.0 {
                break;
            }
            let alpha = qz / curvature;
            let applieds = flat(applied);
            [q_sum] = ordered_over(
                flat_mut(delta)
                    .par_chunks_mut(mx)
                    .zip(flat_mut(residual).par_chunks_mut(mx)),
                |j, (dr, qr)| {
                    let row = j * mx..(j + 1) * mx;
                    let mut sum = 0.0;
                    for (((e, q), &d), &a) in dr.iter_mut().zip(qr).zip(&ds[row.clone()]).zip(&applieds[row])
                    {
                        *e += alpha * d;
                        *q += -alpha * a;
                        sum += *q;
                    }
                    [sum]
                },
            );
            let qz_new = FarField::precondition(problem, held, &correction, residual, q_sum, z)?;
            let beta = qz_new / qz;
            Zip::from(flat_mut(direction))
                .and(flat(z))
                .par_for_each(|d, &z| *d = z + beta * *d);
            qz = qz_new;
        }
        problem.step_and_project(&x.gap, delta, 1.0, &mut trial.gap, None);
        Ok(())
    }

    /// `z = P S^-1 P q` on the soft cells (0 on the held ones), with the correction
    /// `correction` says: the periodic compliance takes no uniform field, so under load control
    /// the soft cells' uniform mode gets its own stiffness back as a rank-one term, and under
    /// a prescribed mean gap `z` is projected onto moves that keep their sum (`P S^-1 P` is
    /// positive definite on those while any cell is held). `q_sum` is the sum of `q`; returns
    /// `<q, z>`.
    fn precondition(
        problem: &mut Problem,
        held: &Array2<u8>,
        correction: &Correction,
        q: &Array2<f64>,
        q_sum: f64,
        z: &mut Array2<f64>,
    ) -> Result<f64> {
        use crate::fields::{flat, flat_mut};
        use crate::sum::ordered_over;
        use rayon::prelude::*;
        problem
            .stiffness
            .invert(q.view(), z.view_mut(), &mut problem.ws)?;
        problem.calls += 1;
        let (mx, hs, qs) = (problem.mx, flat(held), flat(q));
        // `z` on the soft cells plus `by`, 0 on the held ones, and `<q, z>`.
        let finish = |z: &mut Array2<f64>, by: f64| {
            let [qz] = ordered_over(flat_mut(z).par_chunks_mut(mx), |j, zr| {
                let row = j * mx..(j + 1) * mx;
                let mut sum = 0.0;
                for ((z, &h), &q) in zr.iter_mut().zip(&hs[row.clone()]).zip(&qs[row]) {
                    *z = if h == 0 { *z + by } else { 0.0 };
                    sum += q * *z;
                }
                [sum]
            });
            qz
        };
        Ok(match *correction {
            Correction::KeepSum(w, uw) if uw > 0.0 => {
                finish(z, 0.0);
                let c = total(problem, z) / uw;
                z.scaled_add(-c, w);
                crate::sum::dot_chunks(qs, flat(z), mx)
            }
            Correction::Uniform(stiffness) if stiffness > 0.0 => finish(z, q_sum / stiffness),
            _ => finish(z, 0.0),
        })
    }

    /// `out = P S^-1 P q` for `q` zero on the held cells.
    pub(super) fn compliance(
        problem: &mut Problem,
        held: &Array2<u8>,
        q: &Array2<f64>,
        out: &mut Array2<f64>,
    ) -> Result<()> {
        problem
            .stiffness
            .invert(q.view(), out.view_mut(), &mut problem.ws)?;
        problem.calls += 1;
        Zip::from(out).and(held).par_for_each(|o, &h| {
            if h != 0 {
                *o = 0.0
            }
        });
        Ok(())
    }

    /// Writes the pull `M^-1 r` at `at` into `pull` and finds the soft cells there, the
    /// shift's step and the pull's mean over them; returns the force weight `<r, M^-1 r>` and
    /// the step's [`Moments`] with that mean taken out of the soft cells' pull, all in one pass
    /// over the cells (on grids past the cache each pass is a step's cost).
    pub(super) fn update(
        &mut self,
        problem: &mut Problem,
        at: &Point,
        velocity: &Array2<f64>,
        pull: &mut Array2<f64>,
    ) -> Result<(f64, Moments)> {
        use crate::fields::{flat, flat_mut};
        use rayon::prelude::*;
        let (mx, shared) = (problem.mx, &*problem);
        let rows: Vec<([f64; 13], Vec<usize>)> = flat_mut(&mut self.held)
            .par_chunks_mut(mx)
            .zip(flat_mut(pull).par_chunks_mut(mx))
            .enumerate()
            .map(|(j, (hr, pr))| FarField::update_row(shared, shared.row(at, j), flat(velocity), hr, pr))
            .collect();
        self.settle(problem, &rows)
    }

    /// Evaluates `at` ([`Problem::evaluate`]) and makes the far field's [`FarField::update`]
    /// there in the same pass over the rows, with the law's fields made a row at a time and
    /// not stored ([`Problem::evaluate_rows`]): the same numbers, bit for bit, in fewer passes
    /// over the fields.
    pub(super) fn evaluate_and_update(
        &mut self,
        problem: &mut Problem,
        at: &mut Point,
        velocity: &Array2<f64>,
        pull: &mut Array2<f64>,
    ) -> Result<(f64, Moments)> {
        use crate::fields::{flat, flat_mut};
        let mx = problem.mx;
        let rows: Vec<(&mut [u8], &mut [f64])> = flat_mut(&mut self.held)
            .chunks_mut(mx)
            .zip(flat_mut(pull).chunks_mut(mx))
            .collect();
        let vs = flat(velocity);
        let rows = problem.evaluate_rows(at, true, rows, |problem, row, (hr, pr)| {
            FarField::update_row(problem, row, vs, hr, pr)
        })?;
        self.settle(problem, &rows)
    }

    /// Row `row.j` of [`FarField::update`]: writes the row's pull into `pr` and its held cells
    /// into `hr`; returns the number of held cells that changed, the law's stable stiffness,
    /// force, pull, number, and `sum m v`, `sum m a`, `sum m` over the soft cells; the moments
    /// over all cells; the force weight; and the changed cells, the first [`ROW_RECORD`].
    pub(super) fn update_row(
        problem: &Problem,
        row: Row,
        vs: &[f64],
        hr: &mut [u8],
        pr: &mut [f64],
    ) -> ([f64; 13], Vec<usize>) {
        let (cell, clearance) = (problem.diagonal, SOFT_CLEARANCE * problem.law.range());
        let vs = &vs[row.j * problem.mx..][..problem.mx];
        let (gs, cs, rs) = (row.gap, row.curvature, row.gradient);
        let (mut sums, mut changed) = ([0.0; 13], Vec::new());
        sums[12] = problem.pull_row(&row, pr);
        for (i, (h, &a)) in hr.iter_mut().zip(&*pr).enumerate() {
            let held = soft_or_held(gs[i], cs[i], clearance, cell);
            if *h != held {
                *h = held;
                sums[0] += 1.0;
                if changed.len() < ROW_RECORD {
                    changed.push(row.j * problem.mx + i);
                }
            }
            let (m, v) = (problem.row_mass(&row, i), vs[i]);
            if held == 0 {
                sums[1] += cs[i].max(0.0);
                sums[2] += rs[i];
                sums[3] += a;
                sums[4] += 1.0;
                sums[5] += m * v;
                sums[6] += m * a;
                sums[7] += m;
            }
            Moments::add(&mut sums[8..], rs[i], m, v, a);
        }
        (sums, changed)
    }

    /// The rest of [`FarField::update`] from its rows' sums.
    pub(super) fn settle(
        &mut self,
        problem: &mut Problem,
        rows: &[([f64; 13], Vec<usize>)],
    ) -> Result<(f64, Moments)> {
        let sums = rows.iter().map(|r| &r.0).fold([0.0; 13], |mut a, r| {
            a.iter_mut().zip(r).for_each(|(a, r)| *a += r);
            a
        });
        let [
            changed,
            law,
            force,
            pulled,
            soft,
            mv,
            ma,
            mass,
            power,
            vv,
            va,
            aa,
            weight,
        ] = sums;
        if changed > 0.0 {
            self.follow_held(problem, changed as usize, rows.iter().flat_map(|r| &r.1))?;
        }
        let stiffness = self.elastic + law;
        (self.step, self.mean) = if soft == 0.0 || stiffness <= 0.0 {
            (0.0, 0.0)
        } else {
            (-force / stiffness, pulled / soft)
        };
        // `a - mean` on the soft cells.
        let mean = self.mean;
        let moments = Moments {
            power,
            vv,
            va: va - mean * mv,
            aa: (aa - 2.0 * mean * ma + mean * mean * mass).max(0.0),
        };
        Ok((weight, moments))
    }

    /// Brings `elastic`, `held^T S held`, up to `changed` cells of `held` changing (those
    /// `recorded`): from the transform's `S held` and the kernel between the changed cells,
    /// `e + 2 d^T S h + d^T S d` for a change `d` of `h`, while that takes fewer lookups than
    /// [`LOOKUP_SHARE`] allows; else by transforming `held` again. The same number to rounding:
    /// a step's changes are a few cells while the contact set snaps.
    pub(super) fn follow_held<'a>(
        &mut self,
        problem: &mut Problem,
        changed: usize,
        recorded: impl Iterator<Item = &'a usize>,
    ) -> Result<()> {
        use crate::fields::flat;
        use rayon::prelude::*;
        let (mx, my) = (problem.mx, problem.my);
        let hs = flat(&self.held);
        let new: Vec<(usize, f64)> = recorded
            .map(|&k| (k, if hs[k] == 1 { 1.0 } else { -1.0 }))
            .collect();
        if let (Some(changes), Some(kernel)) = (&mut self.changes, &self.kernel)
            && new.len() == changed
            && changed * (changes.len() + changed) <= mx * my / LOOKUP_SHARE
        {
            let fold = |a: usize, b: usize, n: usize| {
                let d = a.abs_diff(b);
                d.min(n - d)
            };
            let k = |a: usize, b: usize| kernel[(fold(a / mx, b / mx, my), fold(a % mx, b % mx, mx))];
            let response = flat(&self.response);
            // Each changed cell's term in parallel (the lookups miss the cache), added in order.
            let terms: Vec<f64> = new
                .par_iter()
                .map(|&(i, d)| {
                    let s_h = response[i] + changes.iter().map(|&(j, e)| e * k(i, j)).sum::<f64>();
                    d * (2.0 * s_h + new.iter().map(|&(j, e)| e * k(i, j)).sum::<f64>())
                })
                .collect();
            self.elastic += terms.iter().fold(0.0, |step, t| step + t);
            changes.extend(new);
            return Ok(());
        }
        if self.kernel.is_none() {
            problem.stiffness.apply_rows(
                |y, row| {
                    row.fill(0.0);
                    if y == 0 {
                        row[0] = 1.0;
                    }
                },
                self.response.view_mut(),
                &mut problem.ws,
            )?;
            problem.calls += 1;
            self.kernel = Some(self.response.slice(ndarray::s![..=my / 2, ..=mx / 2]).to_owned());
        }
        problem.stiffness.apply_rows(
            |y, row| {
                let at = &hs[y * mx..(y + 1) * mx];
                row.iter_mut().zip(at).for_each(|(u, &h)| *u = f64::from(h));
            },
            self.response.view_mut(),
            &mut problem.ws,
        )?;
        problem.calls += 1;
        let response = flat(&self.response);
        let [elastic] = crate::sum::ordered(my, |j| {
            let row = j * mx..(j + 1) * mx;
            [hs[row.clone()]
                .iter()
                .zip(&response[row])
                .map(|(&h, r)| f64::from(h) * r)
                .sum::<f64>()]
        });
        self.elastic = elastic;
        self.changes = Some(Vec::new());
        Ok(())
    }
}

/// 0 for a soft cell (its gap `g` beyond `clearance`, the law's stiffness `c` below a cell's
/// own, `cell`), 1 for a held one.
pub(super) fn soft_or_held(g: f64, c: f64, clearance: f64, cell: f64) -> u8 {
    u8::from(g < clearance || c > cell)
}

/// The sums over the cells a step needs of the velocity `v` and the pull `a = M^-1 r`.
pub(super) struct Moments {
    /// The force's power on the velocity, `-<r, v>`.
    pub(super) power: f64,
    /// `sum m v^2`, `sum m v a` and `sum m a^2`.
    pub(super) vv: f64,
    pub(super) va: f64,
    pub(super) aa: f64,
}

impl Moments {
    pub(super) fn of(problem: &Problem, x: &Point, velocity: &Array2<f64>, pull: &Array2<f64>) -> Moments {
        use crate::fields::flat;
        let mx = problem.mx;
        let (rs, cs, vs, ps) = (flat(&x.gradient), flat(&x.curvature), flat(velocity), flat(pull));
        let [power, vv, va, aa] = crate::sum::ordered(problem.my, |j| {
            let mut sums = [0.0; 4];
            for i in 0..mx {
                let k = j * mx + i;
                Moments::add(&mut sums, rs[k], problem.mass(cs, j, i, k), vs[k], ps[k]);
            }
            sums
        });
        Moments { power, vv, va, aa }
    }

    /// Adds a cell's terms to `[power, vv, va, aa]`: its force `r`, mass `m`, velocity `v`
    /// and pull `a`.
    pub(super) fn add(sums: &mut [f64], r: f64, m: f64, v: f64, a: f64) {
        sums[0] -= r * v;
        sums[1] += m * v * v;
        sums[2] += m * v * a;
        sums[3] += m * a * a;
    }

    /// `sum m (v - dt a)^2`, with `v = 0` if `stopped`.
    pub(super) fn kinetic_after(&self, dt: f64, stopped: bool) -> f64 {
        let (vv, va) = if stopped { (0.0, 0.0) } else { (self.vv, self.va) };
        (vv - 2.0 * dt * va + dt * dt * self.aa).max(0.0)
    }
}
