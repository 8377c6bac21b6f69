//! The stiffness of the gap problem's grid, and its split into a near stencil and a far part
//! kept between transforms.

use super::Problem;
use crate::error::Result;
use elastic::{FreeStiffness, PeriodicStiffness};
use ndarray::{Array2, ArrayView2, ArrayViewMut2};

/// The stiffness of the unknown's grid.
pub(in crate::adhesive) enum Stiffness {
    Periodic(PeriodicStiffness),
    Free(FreeStiffness),
}

impl Stiffness {
    pub(in crate::adhesive) fn apply(
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
    pub(in crate::adhesive) fn apply_rows(
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
    pub(in crate::adhesive) fn invert(
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

/// The stiffness's response `S u` split as `S_near u + F`: `S_near` the stiffness's own
/// coefficients between cells at most two apart along each axis (its 5 x 5 stencil), with the
/// sum of all 25 taken off evenly from the 16 of its outer ring so that a uniform move costs no
/// force; `F = S u' - S_near u'` the far part at the last point `u'` transformed. Where only
/// `near` is asked for, an evaluation takes `S_near u + F` and no transform: exact at `u'`, and
/// off elsewhere by the far part's change, which is small for the moves of a few steps: a
/// cell's own stiffness and its nearest neighbours' stay exact (`docs/decisions.md`).
pub(super) struct Split {
    /// `S_near`'s quadrant: the coefficient \[Pa/m\] between cells `q` rows and `e` columns
    /// apart at `[q][e]` (the stencil is even in both axes).
    pub(super) stencil: [[f64; 3]; 3],
    /// `F` \[Pa\].
    pub(super) far: Array2<f64>,
    /// Whether `far` has been made.
    pub(super) made: bool,
    /// Whether the next evaluations take the near part and `far` rather than transforming.
    pub(super) near: bool,
}

/// Row `j` of `S_near (g - b)` ([`Split`], its quadrant `c`) on a periodic `(ny, nx)` grid
/// into `out`, with `rows` a scratch of three padded rows.
pub(super) fn near_row(
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
    pub(in crate::adhesive) fn near_only(&mut self, near: bool) -> bool {
        self.split.as_mut().is_some_and(|s| {
            s.near = near && s.made;
            s.near
        })
    }

    /// Splits the elastic force of a periodic grid of at least 5 x 5 cells into its near and
    /// far parts ([`Split`]), from the stiffness's response to one cell's move (one
    /// application); the next evaluation transforms.
    pub(in crate::adhesive) fn split_elastic(&mut self) -> Result<()> {
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
}
