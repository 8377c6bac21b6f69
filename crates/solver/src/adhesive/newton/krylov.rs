//! Restarted GMRES (Saad & Schultz, SIAM J. Sci. Stat. Comput. 7, 1986), right-preconditioned,
//! over any linear operator given as a [`LinearOperator`]: the linear solves of Newton.

use crate::error::Result;
use crate::sum::dot;
use ndarray::{Array2, Zip};

/// A linear operator `A` and a preconditioner `M^-1` on fields of one shape.
pub(super) trait LinearOperator {
    /// `out = A v`.
    fn apply(&mut self, v: &Array2<f64>, out: &mut Array2<f64>) -> Result<()>;
    /// `out = M^-1 v`.
    fn precondition(&mut self, v: &Array2<f64>, out: &mut Array2<f64>) -> Result<()>;
}

/// GMRES's storage: the Krylov basis, the Hessenberg matrix by columns, the Givens rotations
/// and the rotated right-hand side, the solution and two scratch fields.
pub(super) struct Gmres {
    restart: usize,
    max_iterations: usize,
    basis: Vec<Array2<f64>>,
    hessenberg: Vec<Vec<f64>>,
    rotations: Vec<(f64, f64)>,
    rhs: Vec<f64>,
    /// The solution of the last solve.
    pub(super) solution: Array2<f64>,
    z: Array2<f64>,
    w: Array2<f64>,
}

impl Gmres {
    /// Storage for fields of `shape`, restarting after `restart` Krylov vectors, stopping after
    /// `max_iterations` in all.
    pub(super) fn new(shape: (usize, usize), restart: usize, max_iterations: usize) -> Gmres {
        let zeros = || Array2::zeros(shape);
        Gmres {
            restart,
            max_iterations,
            basis: (0..=restart).map(|_| zeros()).collect(),
            hessenberg: vec![vec![0.0; restart + 1]; restart],
            rotations: vec![(1.0, 0.0); restart],
            rhs: vec![0.0; restart + 1],
            solution: zeros(),
            z: zeros(),
            w: zeros(),
        }
    }

    /// Solves `A d = b` from `d = 0` to the relative residual `eta` into
    /// [`Gmres::solution`]. Returns the Krylov iterations and whether they reached `eta` (not
    /// stopped by the iteration limit).
    pub(super) fn solve(
        &mut self,
        op: &mut dyn LinearOperator,
        b: &Array2<f64>,
        eta: f64,
    ) -> Result<(usize, bool)> {
        self.solution.fill(0.0);
        let b_norm = dot(b, b).sqrt();
        if b_norm == 0.0 {
            return Ok((0, true));
        }
        let target = eta * b_norm;
        // The residual `b - A d` of the current solution, into the first basis vector.
        self.basis[0].assign(b);
        let mut beta = b_norm;
        let mut iterations = 0;
        loop {
            self.basis[0].mapv_inplace(|b| b / beta);
            self.rhs.fill(0.0);
            self.rhs[0] = beta;
            let mut used = 0;
            let mut reached = beta;
            for j in 0..self.restart {
                let mut z = std::mem::take(&mut self.z);
                let mut w = std::mem::take(&mut self.w);
                let v = std::mem::take(&mut self.basis[j]);
                op.precondition(&v, &mut z)?;
                self.basis[j] = v;
                op.apply(&z, &mut w)?;
                for i in 0..=j {
                    let h = dot(&w, &self.basis[i]);
                    self.hessenberg[j][i] = h;
                    w.zip_mut_with(&self.basis[i], |w, &v| *w -= h * v);
                }
                let h_next = dot(&w, &w).sqrt();
                self.hessenberg[j][j + 1] = h_next;
                if h_next > 0.0 {
                    self.basis[j + 1].zip_mut_with(&w, |v, &w| *v = w / h_next);
                }
                (self.z, self.w) = (z, w);
                // Rotate the new column by the earlier rotations, then zero its subdiagonal.
                let column = &mut self.hessenberg[j];
                for (i, &(c, s)) in self.rotations[..j].iter().enumerate() {
                    let (a, b) = (column[i], column[i + 1]);
                    (column[i], column[i + 1]) = (c * a + s * b, -s * a + c * b);
                }
                let (a, b) = (column[j], column[j + 1]);
                let norm = a.hypot(b);
                let (c, s) = if norm > 0.0 {
                    (a / norm, b / norm)
                } else {
                    (1.0, 0.0)
                };
                self.rotations[j] = (c, s);
                (column[j], column[j + 1]) = (norm, 0.0);
                self.rhs[j + 1] = -s * self.rhs[j];
                self.rhs[j] *= c;
                iterations += 1;
                used = j + 1;
                reached = self.rhs[j + 1].abs();
                if reached <= target || iterations >= self.max_iterations || h_next == 0.0 {
                    break;
                }
            }
            // The least-squares coefficients, by back substitution; the correction is
            // `M^-1` of their combination of the basis.
            let mut y = vec![0.0; used];
            for i in (0..used).rev() {
                let tail: f64 = (i + 1..used).map(|k| self.hessenberg[k][i] * y[k]).sum();
                y[i] = (self.rhs[i] - tail) / self.hessenberg[i][i];
            }
            let mut combination = std::mem::take(&mut self.w);
            combination.fill(0.0);
            for (v, &y) in self.basis.iter().zip(&y) {
                combination.zip_mut_with(v, |c, &v| *c += y * v);
            }
            let mut z = std::mem::take(&mut self.z);
            op.precondition(&combination, &mut z)?;
            self.solution += &z;
            (self.z, self.w) = (z, combination);
            if reached <= target || iterations >= self.max_iterations {
                return Ok((iterations, reached <= target));
            }
            // Restart from the true residual.
            let mut w = std::mem::take(&mut self.w);
            let solution = std::mem::take(&mut self.solution);
            op.apply(&solution, &mut w)?;
            self.solution = solution;
            Zip::from(&mut self.basis[0])
                .and(b)
                .and(&w)
                .par_for_each(|v, &b, &a| *v = b - a);
            self.w = w;
            beta = dot(&self.basis[0], &self.basis[0]).sqrt();
            if beta <= target {
                return Ok((iterations, true));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A nonsymmetric convection-diffusion stencil on a row of cells, `(A v)_i = 2.2 v_i -
    /// 1.3 v_(i-1) - 0.7 v_(i+1)`, unpreconditioned.
    struct Stencil;

    impl LinearOperator for Stencil {
        fn apply(&mut self, v: &Array2<f64>, out: &mut Array2<f64>) -> Result<()> {
            let n = v.ncols();
            for i in 0..n {
                let left = if i > 0 { v[[0, i - 1]] } else { 0.0 };
                let right = if i + 1 < n { v[[0, i + 1]] } else { 0.0 };
                out[[0, i]] = 2.2 * v[[0, i]] - 1.3 * left - 0.7 * right;
            }
            Ok(())
        }

        fn precondition(&mut self, v: &Array2<f64>, out: &mut Array2<f64>) -> Result<()> {
            out.assign(v);
            Ok(())
        }
    }

    /// Restarted after as few vectors as the basis cap allows on the largest grids, GMRES still
    /// finds the solution (through its restarts from the true residual).
    #[test]
    fn restarted_gmres_solves_a_nonsymmetric_system() {
        let n = 200;
        let exact = Array2::from_shape_fn((1, n), |(_, i)| (0.37 * i as f64).sin() + 0.01 * i as f64);
        let mut b = Array2::zeros((1, n));
        Stencil.apply(&exact, &mut b).unwrap();
        for restart in [5, 30] {
            let mut gmres = Gmres::new((1, n), restart, 5000);
            let (iterations, reached) = gmres.solve(&mut Stencil, &b, 1e-12).unwrap();
            assert!(reached, "restart {restart}: {iterations} iterations");
            assert!(iterations > restart, "restart {restart} never restarted");
            let error = (&gmres.solution - &exact)
                .mapv(f64::abs)
                .fold(0.0f64, |m, &e| m.max(e));
            assert!(error < 1e-9, "restart {restart}: error {error:e}");
        }
    }
}
