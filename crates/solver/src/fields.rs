//! Flat row-major access to the solvers' own fields, so that loops can run over rows in
//! parallel. Every field a solver allocates is row-major, and inputs of any layout are copied
//! to row-major where a solve begins ([`crate::ContactProblem::solve`], [`crate::cg::solve`]),
//! so these views cannot fail on the fields they are used on.

use ndarray::{ArrayBase, Data, DataMut, Ix2};

/// The values of a row-major field, row after row.
pub(crate) fn flat<T, S: Data<Elem = T>>(a: &ArrayBase<S, Ix2>) -> &[T] {
    a.as_slice().expect("solver fields are row-major")
}

/// The values of a row-major field, row after row, to write.
pub(crate) fn flat_mut<T, S: DataMut<Elem = T>>(a: &mut ArrayBase<S, Ix2>) -> &mut [T] {
    a.as_slice_mut().expect("solver fields are row-major")
}
