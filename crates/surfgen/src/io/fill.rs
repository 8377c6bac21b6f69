//! Filling unmeasured points: the harmonic interpolant (Laplace's equation on the unmeasured
//! points, the measured ones as boundary values), as Gwyddion's "Laplace" and
//! SurfaceTopography's `interpolate_undefined_data('harmonic')` fill them.

use ndarray::Array2;

/// Replaces every NaN of `heights` by the discrete harmonic interpolant of the finite heights
/// around it (5-point Laplacian; across the edges only if `periodic`, else the edges are
/// reflecting). Needs at least one finite height.
pub fn fill_harmonic(heights: &mut Array2<f64>, periodic: bool) {
    let (ny, nx) = heights.dim();
    let unknown: Vec<(usize, usize)> = heights
        .indexed_iter()
        .filter(|(_, h)| h.is_nan())
        .map(|(p, _)| p)
        .collect();
    if unknown.is_empty() {
        return;
    }
    assert!(unknown.len() < ny * nx, "no finite height to fill from");
    let mut slot = Array2::from_elem((ny, nx), usize::MAX);
    for (k, &p) in unknown.iter().enumerate() {
        slot[p] = k;
    }
    let neighbours = |(j, i): (usize, usize)| {
        let mut out = [None; 4];
        let steps = [(0isize, -1isize), (0, 1), (-1, 0), (1, 0)];
        for (o, (dj, di)) in out.iter_mut().zip(steps) {
            let (jj, ii) = (j as isize + dj, i as isize + di);
            *o = if periodic {
                Some((
                    jj.rem_euclid(ny as isize) as usize,
                    ii.rem_euclid(nx as isize) as usize,
                ))
            } else if (0..ny as isize).contains(&jj) && (0..nx as isize).contains(&ii) {
                Some((jj as usize, ii as usize))
            } else {
                None
            };
        }
        out
    };
    // A u = b: a row per unknown, its degree on the diagonal, -1 per unknown neighbour, the
    // known neighbours' heights on the right. Symmetric positive definite because every
    // connected set of unknowns touches a known point; conjugate gradients.
    let apply = |u: &[f64], out: &mut [f64]| {
        for (k, &p) in unknown.iter().enumerate() {
            let mut sum = 0.0;
            for q in neighbours(p).into_iter().flatten() {
                sum += u[k];
                if slot[q] != usize::MAX {
                    sum -= u[slot[q]];
                }
            }
            out[k] = sum;
        }
    };
    let b: Vec<f64> = unknown
        .iter()
        .map(|&p| {
            neighbours(p)
                .into_iter()
                .flatten()
                .filter(|&q| slot[q] == usize::MAX)
                .map(|q| heights[q])
                .sum()
        })
        .collect();
    let n = unknown.len();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut u = vec![0.0; n];
    let mut r = b.clone();
    let mut p = r.clone();
    let mut ap = vec![0.0; n];
    let mut rr = dot(&r, &r);
    let tolerance = 1e-28 * dot(&b, &b).max(f64::MIN_POSITIVE);
    for _ in 0..10 * n + 100 {
        if rr <= tolerance {
            break;
        }
        apply(&p, &mut ap);
        let alpha = rr / dot(&p, &ap);
        for k in 0..n {
            u[k] += alpha * p[k];
            r[k] -= alpha * ap[k];
        }
        let next = dot(&r, &r);
        let beta = next / rr;
        rr = next;
        for k in 0..n {
            p[k] = r[k] + beta * p[k];
        }
    }
    for (k, &p) in unknown.iter().enumerate() {
        heights[p] = u[k];
    }
}
