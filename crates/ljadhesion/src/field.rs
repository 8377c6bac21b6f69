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
    let last_x = next(nx - 1, nx, cells.periodic);
    const ROWS: usize = 8;
    let bad = out
        .axis_chunks_iter_mut(Axis(0), ROWS)
        .into_par_iter()
        .enumerate()
        .map(|(chunk, mut rows)| {
            let mut t = vec![0.0; nx];
            let mut bad = false;
            for (r, mut row) in rows.outer_iter_mut().enumerate() {
                let (c, u) = row_and_next(&gap, chunk * ROWS + r, cells.periodic, &node, &mut t);
                let o = row.as_slice_mut().expect("standard layout");
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

/// Runs `row(y, scratch, [a, b, c])` on every row `y` of the three outputs in parallel,
/// `scratch` a row's room, and reports the first non-finite gap if the first output has a
/// non-finite value.
pub(crate) fn rows3(
    gap: ArrayView2<f64>,
    outs: [ArrayViewMut2<f64>; 3],
    row: impl Fn(usize, &mut [f64], [&mut [f64]; 3]) + Sync,
) -> Result<()> {
    for out in &outs {
        check_shapes(&gap, out)?;
    }
    let nx = gap.ncols();
    let [mut a, mut b, mut c] = outs;
    let bad = Zip::indexed(a.rows_mut())
        .and(b.rows_mut())
        .and(c.rows_mut())
        .into_par_iter()
        .map_init(
            || vec![0.0; nx],
            |t, (y, mut a, mut b, mut c)| {
                let a = a.as_slice_mut().expect("standard layout");
                row(
                    y,
                    t,
                    [
                        &mut *a,
                        b.as_slice_mut().expect("standard layout"),
                        c.as_slice_mut().expect("standard layout"),
                    ],
                );
                a.iter().any(|v| !v.is_finite())
            },
        )
        .reduce(|| false, |a, b| a || b);
    if bad {
        locate_bad_gap(&gap)?;
    }
    Ok(())
}

/// Row `y` of a law whose `cell` gives three values a cell (a cell's pressure and its
/// stiffness by its own column and by its +x neighbour's, say), with the neighbours of
/// [`neighbours`], into `[a, b, c]`; `t` is a row's room for `node`.
pub(crate) fn neighbours3_row(
    gap: ArrayView2<f64>,
    cells: &Cells,
    y: usize,
    t: &mut [f64],
    [a, b, c]: [&mut [f64]; 3],
    node: impl Fn(f64) -> f64,
    cell: impl Fn(f64, f64, f64, f64, f64) -> [f64; 3],
) {
    let nx = gap.ncols();
    if nx == 0 {
        return;
    }
    let last_x = next(nx - 1, nx, cells.periodic);
    let (g, u) = row_and_next(&gap, y, cells.periodic, &node, t);
    // Zipped slices rather than indices, as in `neighbours`.
    let m = nx - 1;
    a[..m]
        .iter_mut()
        .zip(b[..m].iter_mut().zip(c[..m].iter_mut()))
        .zip(g[..m].iter().zip(&g[1..]))
        .zip(u[..m].iter().zip(t[..m].iter().zip(&t[1..])))
        .for_each(|(((a, (b, c)), (&g1, &g2)), (&g3, (&t1, &t2)))| {
            [*a, *b, *c] = cell(g1, g2, g3, t1, t2);
        });
    [a[m], b[m], c[m]] = cell(g[m], g[last_x], u[m], t[m], t[last_x]);
}

/// Row `y` of `gap` and its +y neighbour row (wrapped or mirrored as [`next`]), with `node` of
/// each of row `y`'s gaps written into `t`.
fn row_and_next<'a>(
    gap: &'a ArrayView2<f64>,
    y: usize,
    periodic: bool,
    node: &impl Fn(f64) -> f64,
    t: &mut [f64],
) -> (&'a [f64], &'a [f64]) {
    let ny = gap.nrows();
    let row = |y: usize| gap.row(y).to_slice().expect("standard layout");
    let (c, u) = (row(y), row(next(y, ny, periodic)));
    t.iter_mut().zip(c).for_each(|(t, &g)| *t = node(g));
    (c, u)
}

/// The neighbour of node `i` along an axis of `n` nodes: the next, wrapping around on
/// periodic domains; on free edges the last node's is mirrored (`n - 2`).
fn next(i: usize, n: usize, periodic: bool) -> usize {
    if i + 1 < n {
        i + 1
    } else if periodic || n == 1 {
        0
    } else {
        n - 2
    }
}

/// The cells whose neighbour along an axis of `n` nodes is `i` (one or two).
fn sources(i: usize, n: usize, periodic: bool) -> impl Iterator<Item = usize> {
    // The node before, and the last cell, whose neighbour wraps around or is mirrored.
    let last = (next(n - 1, n, periodic) == i).then_some(n - 1);
    i.checked_sub(1).into_iter().chain(last)
}

/// A law that derives from an energy whose cells depend on their node and its +x and +y
/// neighbours (as in [`neighbours`]): `cell(g1, g2, g3)` gives a cell's energy per area and its
/// first and second derivatives by the three gaps. Writes the cells' energies, the pressure
/// at every node (minus the derivative of the total energy by the node's gap, per cell area,
/// gathered from the cells it belongs to) and the diagonal of the second derivative.
pub(crate) fn cell_energies(
    gap: ArrayView2<f64>,
    cells: &Cells,
    mut energy: ArrayViewMut2<f64>,
    mut pressure: ArrayViewMut2<f64>,
    mut curvature: ArrayViewMut2<f64>,
    cell: impl Fn(f64, f64, f64) -> (f64, [f64; 3], [f64; 3]) + Sync,
) -> Result<()> {
    check_shapes(&gap, &energy)?;
    check_shapes(&gap, &pressure)?;
    check_shapes(&gap, &curvature)?;
    let (ny, nx) = gap.dim();
    if ny == 0 || nx == 0 {
        return Ok(());
    }
    let periodic = cells.periodic;
    let at = |y: usize, x: usize| {
        cell(
            gap[(y, x)],
            gap[(y, next(x, nx, periodic))],
            gap[(next(y, ny, periodic), x)],
        )
    };
    // A node gathers its own cell's share and those of the cells it is the +x or +y neighbour
    // of, each cell evaluated again where needed rather than stored: no field-sized buffer.
    let bad = pressure
        .axis_iter_mut(Axis(0))
        .into_par_iter()
        .zip(curvature.axis_iter_mut(Axis(0)).into_par_iter())
        .zip(energy.axis_iter_mut(Axis(0)).into_par_iter())
        .enumerate()
        .map(|(y, ((mut p, mut c), mut e))| {
            for x in 0..nx {
                let (v, own, own2) = at(y, x);
                let (mut d, mut k) = (own[0], own2[0]);
                for s in sources(x, nx, periodic) {
                    let (_, d1, c1) = at(y, s);
                    d += d1[1];
                    k += c1[1];
                }
                for s in sources(y, ny, periodic) {
                    let (_, d1, c1) = at(s, x);
                    d += d1[2];
                    k += c1[2];
                }
                e[x] = v;
                p[x] = -d;
                c[x] = k;
            }
            p.iter().chain(e.iter()).any(|v| !v.is_finite())
        })
        .reduce(|| false, |a, b| a || b);
    if bad {
        locate_bad_gap(&gap)?;
    }
    Ok(())
}
