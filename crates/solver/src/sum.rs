//! Deterministic parallel sums: parts computed in parallel and added in a fixed order, so
//! that results do not depend on the number of threads. Every reduction of the solvers goes
//! through here.

use ndarray::{Array2, ArrayView2};
use rayon::prelude::*;

/// `K` sums over `parts` parts, each computed by `part(k)` (in parallel) and added in the
/// order `k = 0, 1, ...`.
pub(crate) fn ordered<const K: usize>(parts: usize, part: impl Fn(usize) -> [f64; K] + Sync) -> [f64; K] {
    ordered_over((0..parts).into_par_iter(), |_, k| part(k))
}

/// [`ordered`] over the items of `parts` (rows of fields to write, say), `part(k, item)`
/// computing the sums of the `k`-th.
pub(crate) fn ordered_over<T: Send, const K: usize>(
    parts: impl IndexedParallelIterator<Item = T>,
    part: impl Fn(usize, T) -> [f64; K] + Sync,
) -> [f64; K] {
    let sums: Vec<[f64; K]> = parts.enumerate().map(|(k, t)| part(k, t)).collect();
    sums.iter().fold([0.0; K], |mut acc, p| {
        acc.iter_mut().zip(p).for_each(|(a, b)| *a += b);
        acc
    })
}

/// `sum f(a, b, c)` over all cells, each row summed in order, then the rows in order.
pub(crate) fn rows3(
    a: ArrayView2<f64>,
    b: ArrayView2<f64>,
    c: ArrayView2<f64>,
    f: impl Fn(f64, f64, f64) -> f64 + Sync,
) -> f64 {
    let [sum] = ordered(a.nrows(), |j| {
        [a.row(j)
            .iter()
            .zip(b.row(j))
            .zip(c.row(j))
            .map(|((x, y), z)| f(*x, *y, *z))
            .sum::<f64>()]
    });
    sum
}

/// `<a, b>`, each row summed in order, then the rows in order.
pub(crate) fn dot_rows(a: ArrayView2<f64>, b: ArrayView2<f64>) -> f64 {
    let [sum] = ordered(a.nrows(), |j| {
        [a.row(j).iter().zip(b.row(j)).map(|(x, y)| x * y).sum::<f64>()]
    });
    sum
}

/// `<a, b>` over two slices of equal length, in chunks of `chunk` values added in order.
pub(crate) fn dot_chunks(a: &[f64], b: &[f64], chunk: usize) -> f64 {
    let [sum] = ordered(a.len().div_ceil(chunk), |k| {
        let range = k * chunk..((k + 1) * chunk).min(a.len());
        [a[range.clone()]
            .iter()
            .zip(&b[range])
            .map(|(x, y)| x * y)
            .sum::<f64>()]
    });
    sum
}

/// Elements per chunk of [`dot`].
const CHUNK: usize = 4096;

/// `<a, b>` over two fields of one shape, in chunks of [`CHUNK`] values added in order.
pub(crate) fn dot(a: &Array2<f64>, b: &Array2<f64>) -> f64 {
    dot_chunks(crate::fields::flat(a), crate::fields::flat(b), CHUNK)
}
