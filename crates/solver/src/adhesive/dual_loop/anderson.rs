//! Anderson mixing (Anderson 1965; Walker & Ni, SIAM J. Numer. Anal. 49, 2011) for a fixed
//! point `x = G(x)`: from the last `depth` iterates and residuals `f = G(x) - x` it takes the
//! combination whose linearised residual is smallest, then a relaxed step from it.

use ndarray::{Array2, ArrayView2, Zip};
use std::collections::VecDeque;

use crate::sum::dot_rows as dot;

/// The mixing history: differences of iterates and of residuals, and their Gram matrix.
pub(crate) struct Anderson {
    depth: usize,
    last: Option<(Array2<f64>, Array2<f64>)>,
    dx: VecDeque<Array2<f64>>,
    df: VecDeque<Array2<f64>>,
    /// `gram[i][j] = <df_i, df_j>`, kept in step with `df`.
    gram: VecDeque<Vec<f64>>,
}

impl Anderson {
    pub(crate) fn new(depth: usize) -> Self {
        Anderson {
            depth,
            last: None,
            dx: VecDeque::new(),
            df: VecDeque::new(),
            gram: VecDeque::new(),
        }
    }

    /// Forgets the history (after a step that made things worse).
    pub(crate) fn reset(&mut self) {
        self.last = None;
        self.dx.clear();
        self.df.clear();
        self.gram.clear();
    }

    /// Replaces `x` by the next iterate, given its residual `f = G(x) - x` and the mixing
    /// factors `beta` (one per component: a diagonal preconditioner; `beta = 1` with no
    /// history is plain substitution).
    pub(crate) fn step(&mut self, x: &mut Array2<f64>, f: ArrayView2<f64>, beta: ArrayView2<f64>) {
        if self.depth == 0 {
            Zip::from(&mut *x)
                .and(f)
                .and(beta)
                .par_for_each(|x, f, b| *x += b * f);
            return;
        }
        if let Some((x_old, f_old)) = self.last.take() {
            let mut dx = x_old;
            Zip::from(&mut dx).and(&*x).par_for_each(|d, x| *d = x - *d);
            let mut df = f_old;
            Zip::from(&mut df).and(f).par_for_each(|d, f| *d = f - *d);
            if self.df.len() == self.depth {
                self.dx.pop_front();
                self.df.pop_front();
                self.gram.pop_front();
                for row in &mut self.gram {
                    row.remove(0);
                }
            }
            let row: Vec<f64> = self.df.iter().map(|d| dot(d.view(), df.view())).collect();
            let diag = dot(df.view(), df.view());
            for (g, v) in self.gram.iter_mut().zip(&row) {
                g.push(*v);
            }
            let mut row = row;
            row.push(diag);
            self.gram.push_back(row);
            self.dx.push_back(dx);
            self.df.push_back(df);
        }
        self.last = Some((x.clone(), f.to_owned()));
        let m = self.df.len();
        let gamma = if m == 0 {
            Vec::new()
        } else {
            let rhs: Vec<f64> = self.df.iter().map(|d| dot(d.view(), f)).collect();
            let trace: f64 = (0..m).map(|i| self.gram[i][i]).sum();
            let mut a: Vec<Vec<f64>> = self.gram.iter().cloned().collect();
            for (i, row) in a.iter_mut().enumerate() {
                // Tikhonov regularisation: the differences are often nearly collinear.
                row[i] += 1e-12 * trace.max(f64::MIN_POSITIVE);
            }
            solve_dense(a, rhs)
        };
        Zip::from(&mut *x)
            .and(f)
            .and(beta)
            .par_for_each(|x, f, b| *x += b * f);
        for ((dx, df), g) in self.dx.iter().zip(&self.df).zip(&gamma) {
            Zip::from(&mut *x)
                .and(dx)
                .and(df)
                .and(beta)
                .par_for_each(|x, dx, df, b| *x -= g * (dx + b * df));
        }
    }
}

/// Solves the small dense system `a y = b` by Gaussian elimination with partial pivoting;
/// a singular pivot gives a zero component (that history entry is ignored).
fn solve_dense(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let pivot = (k..n)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap_or(k);
        a.swap(k, pivot);
        b.swap(k, pivot);
        if a[k][k] == 0.0 {
            continue;
        }
        let (top, rest) = a.split_at_mut(k + 1);
        let pivot_row = &top[k];
        for (offset, row) in rest.iter_mut().enumerate() {
            let factor = row[k] / pivot_row[k];
            for (x, p) in row[k..].iter_mut().zip(&pivot_row[k..]) {
                *x -= factor * p;
            }
            b[k + 1 + offset] -= factor * b[k];
        }
    }
    let mut y = vec![0.0; n];
    for k in (0..n).rev() {
        if a[k][k] == 0.0 {
            continue;
        }
        let s: f64 = (k + 1..n).map(|j| a[k][j] * y[j]).sum();
        y[k] = (b[k] - s) / a[k][k];
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a linear contraction Anderson mixing converges in about as many steps as the
    /// dimension; plain relaxation needs hundreds.
    #[test]
    fn solves_a_linear_fixed_point_fast() {
        let n = 6;
        // G(x) = A x + c with spectral radius 0.95.
        let a = |x: &Array2<f64>| -> Array2<f64> {
            Array2::from_shape_fn((1, n), |(_, i)| {
                0.95 * x[(0, i)] * if i % 2 == 0 { 1.0 } else { -1.0 } + 0.01 * x[(0, (i + 1) % n)] + i as f64
            })
        };
        let mut x = Array2::<f64>::zeros((1, n));
        let mut mixer = Anderson::new(8);
        let beta = Array2::ones((1, n));
        let mut steps = 0;
        loop {
            let f = a(&x) - &x;
            let norm = dot(f.view(), f.view()).sqrt();
            if norm < 1e-10 {
                break;
            }
            mixer.step(&mut x, f.view(), beta.view());
            steps += 1;
            assert!(steps < 30, "Anderson did not converge: |f| = {norm}");
        }
        let f = a(&x) - &x;
        assert!(dot(f.view(), f.view()).sqrt() < 1e-10);
    }
}
