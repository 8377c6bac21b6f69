//! The loops that apply a law over a gap field, in parallel over rows.

use crate::Cells;
use crate::error::{AdhesionError, Result};
use ndarray::{ArrayView2, ArrayViewMut2, Axis, Zip};
use rayon::prelude::*;

fn check_shapes(gap: &ArrayView2<f64>, out: &ArrayViewMut2<f64>) -> Result<()> {
    if gap.dim() != out.dim() {
        return Err(AdhesionError::ShapeMismatch {
            gap: gap.dim(),
            out: out.dim(),
        });
    }
    Ok(())
}

/// Finds the first non-finite gap, once a non-finite output has shown there is one.
fn locate_bad_gap(gap: &ArrayView2<f64>) -> Result<()> {
    match gap.indexed_iter().find(|(_, v)| !v.is_finite()) {
        Some(((row, col), &value)) => Err(AdhesionError::NonFiniteGap { row, col, value }),
        None => Ok(()),
    }
}

/// `out\[i\] = f(gap\[i\])`.
pub(crate) fn nodal(
    gap: ArrayView2<f64>,
    mut out: ArrayViewMut2<f64>,
    f: impl Fn(f64) -> f64 + Sync,
) -> Result<()> {
    check_shapes(&gap, &out)?;
    Zip::from(&mut out).and(&gap).par_for_each(|o, &g| *o = f(g));
    if out.iter().any(|v| !v.is_finite()) {
        locate_bad_gap(&gap)?;
    }
    Ok(())
}

/// `out\[i\] = cell(g1, g2, g3, t1, t2)` with node 1 = the cell's own node `(y, x)`, node 2 its
/// +x neighbour and node 3 its +y neighbour, and `t = node(g)` worked out once per node (a
/// division, say) rather than once per cell that uses it. Periodic cells wrap around; on free
/// edges the missing neighbour is the mirror image of the one on the other side (`x - 1`,
/// `y - 1`), so that differences there are one-sided backward differences.
pub(crate) fn neighbours(
    gap: ArrayView2<f64>,
    cells: &Cells,
    mut out: ArrayViewMut2<f64>,
    node: impl Fn(f64) -> f64 + Sync,
    cell: impl Fn(f64, f64, f64, f64, f64) -> f64 + Sync,
) -> Result<()> {
    check_shapes(&gap, &out)?;
    let (ny, nx) = gap.dim();
    if ny == 0 || nx == 0 {
        return Ok(());
    }
    let next = |i: usize, n: usize| {
        if i + 1 < n {
            i + 1
        } else if cells.periodic || n == 1 {
            0
        } else {
            n - 2
        }
    };
    let last_x = next(nx - 1, nx);
    const ROWS: usize = 8;
    let bad = out
        .axis_chunks_iter_mut(Axis(0), ROWS)
        .into_par_iter()
        .enumerate()
        .map(|(chunk, mut rows)| {
            let mut t = vec![0.0; nx];
            let mut bad = false;
            for (r, mut row) in rows.outer_iter_mut().enumerate() {
                let y = chunk * ROWS + r;
                let c = gap.row(y);
                let u = gap.row(next(y, ny));
                let (c, u, o) = (
                    c.as_slice().expect("standard layout"),
                    u.as_slice().expect("standard layout"),
                    row.as_slice_mut().expect("standard layout"),
                );
                t.iter_mut().zip(c).for_each(|(t, &g)| *t = node(g));
                // Zipped slices rather than indices: no bounds checks, so the loop vectorises.
                let m = nx - 1;
                o[..m]
                    .iter_mut()
                    .zip(c[..m].iter().zip(&c[1..]))
                    .zip(u[..m].iter().zip(t[..m].iter().zip(&t[1..])))
                    .for_each(|((o, (&g1, &g2)), (&g3, (&t1, &t2)))| *o = cell(g1, g2, g3, t1, t2));
                o[nx - 1] = cell(c[nx - 1], c[last_x], u[nx - 1], t[nx - 1], t[last_x]);
                bad |= o.iter().any(|v| !v.is_finite());
            }
            bad
        })
        .reduce(|| false, |a, b| a || b);
    if bad {
        locate_bad_gap(&gap)?;
    }
    Ok(())
}
