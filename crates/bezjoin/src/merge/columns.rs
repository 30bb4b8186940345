//! Column-major matrices on borrowed slices, and the one buffer that the
//! orthogonal stage 1 takes its intermediate matrices from (on the stack
//! for small degrees): no allocation per matrix.

use nalgebra::{DMatrix, DMatrixView};

/// A column-major `rows x cols` matrix on a borrowed slice. nalgebra's
/// operations on it go through [`Columns::view`]: the same generic code
/// on the same strides as for the `DMatrix` of these values, so the same
/// values bit for bit.
#[derive(Clone, Copy, Debug)]
pub(super) struct Columns<'a> {
    data: &'a [f64],
    rows: usize,
    cols: usize,
}

impl<'a> Columns<'a> {
    pub(super) fn new(data: &'a [f64], rows: usize, cols: usize) -> Self {
        assert_eq!(data.len(), rows * cols, "a {rows} x {cols} matrix");
        Self { data, rows, cols }
    }

    pub(super) fn nrows(&self) -> usize {
        self.rows
    }

    pub(super) fn ncols(&self) -> usize {
        self.cols
    }

    pub(super) fn shape(&self) -> (usize, usize) {
        (self.rows, self.cols)
    }

    /// The entries, column after column.
    pub(super) fn as_slice(&self) -> &'a [f64] {
        self.data
    }

    /// The matrix as a nalgebra view (no copy).
    pub(super) fn view(&self) -> DMatrixView<'a, f64> {
        DMatrixView::from_slice(self.data, self.rows, self.cols)
    }

    /// nalgebra's Frobenius norm of the matrix.
    pub(super) fn norm(&self) -> f64 {
        self.view().norm()
    }

    /// A new matrix of these values.
    pub(super) fn to_matrix(self) -> DMatrix<f64> {
        DMatrix::from_column_slice(self.rows, self.cols, self.data)
    }
}

impl<'a> From<&'a DMatrix<f64>> for Columns<'a> {
    fn from(m: &'a DMatrix<f64>) -> Self {
        Self::new(m.as_slice(), m.nrows(), m.ncols())
    }
}

/// Disjoint parts of one buffer, handed out in order.
pub(super) struct Parts<'a> {
    rest: &'a mut [f64],
}

impl<'a> Parts<'a> {
    pub(super) fn new(buffer: &'a mut [f64]) -> Self {
        Self { rest: buffer }
    }

    /// The next `len` entries, as the buffer holds them (zeros in a
    /// zeroed buffer: every part is handed out once).
    pub(super) fn take(&mut self, len: usize) -> &'a mut [f64] {
        let (part, rest) = std::mem::take(&mut self.rest).split_at_mut(len);
        self.rest = rest;
        part
    }

    /// A zeroed `rows x cols` part filled by `fill` (the column-major
    /// entries), as a matrix.
    pub(super) fn matrix(
        &mut self,
        rows: usize,
        cols: usize,
        fill: impl FnOnce(&mut [f64]),
    ) -> Columns<'a> {
        let part = self.take(rows * cols);
        fill(part);
        Columns::new(part, rows, cols)
    }
}

/// `need` zeros: the first entries of `stack` when they fit, else `heap`
/// grown to `need` zeros (one allocation).
pub(super) fn stack_or_heap<'a>(
    stack: &'a mut [f64],
    heap: &'a mut Vec<f64>,
    need: usize,
) -> &'a mut [f64] {
    if need <= stack.len() {
        &mut stack[..need]
    } else {
        heap.resize(need, 0.0);
        heap
    }
}
