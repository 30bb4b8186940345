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

    /// nalgebra's Frobenius norm of the matrix, bit for bit
    /// ([`Columns::norm_squared`]).
    pub(super) fn norm(&self) -> f64 {
        self.norm_squared().sqrt()
    }

    /// nalgebra's `norm_squared` of the matrix bit for bit: from `0`, plus
    /// the `dot` of every column with itself in order
    /// ([`nalgebra_dot_sized`]; the merge's small column lengths as
    /// constants).
    pub(super) fn norm_squared(&self) -> f64 {
        let mut res = 0.0;
        for column in self.data.chunks_exact(self.rows.max(1)) {
            res += match self.rows {
                2 => nalgebra_dot_sized::<2, false>(column, column),
                4 => nalgebra_dot_sized::<4, false>(column, column),
                6 => nalgebra_dot_sized::<6, false>(column, column),
                8 => nalgebra_dot_sized::<8, false>(column, column),
                12 => nalgebra_dot_sized::<12, false>(column, column),
                _ => nalgebra_dot_sized::<0, false>(column, column),
            };
        }
        res
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

/// A column-major matrix owning its entries: on the stack up to
/// [`OWNED_ON_STACK`] entries, else on the heap.
pub(super) struct OwnedColumns {
    small: [f64; OWNED_ON_STACK],
    large: Vec<f64>,
    rows: usize,
    cols: usize,
}

/// Entries of an [`OwnedColumns`] kept on the stack (the input points of
/// two pieces of degree 7 in space).
const OWNED_ON_STACK: usize = 48;

impl OwnedColumns {
    /// The `rows x cols` zero matrix.
    pub(super) fn zeros(rows: usize, cols: usize) -> Self {
        let len = rows * cols;
        Self {
            small: [0.0; OWNED_ON_STACK],
            large: if len > OWNED_ON_STACK {
                vec![0.0; len]
            } else {
                Vec::new()
            },
            rows,
            cols,
        }
    }

    /// The entries, column after column.
    pub(super) fn as_mut_slice(&mut self) -> &mut [f64] {
        let len = self.rows * self.cols;
        if len > OWNED_ON_STACK {
            &mut self.large
        } else {
            &mut self.small[..len]
        }
    }

    /// The matrix, borrowed.
    pub(super) fn columns(&self) -> Columns<'_> {
        let len = self.rows * self.cols;
        let data = if len > OWNED_ON_STACK {
            &self.large
        } else {
            &self.small[..len]
        };
        Columns::new(data, self.rows, self.cols)
    }
}

/// nalgebra's `dot` of two dynamic columns bit for bit (its `dotx`: eight
/// partial sums over blocks of eight, added pairwise into a sum from `0`,
/// then the remaining products one by one), of `|a|` and `|b|` when `ABS`;
/// the length `N` known at compile time (`0`: `a.len()`).
#[inline(always)]
pub(super) fn nalgebra_dot_sized<const N: usize, const ABS: bool>(a: &[f64], b: &[f64]) -> f64 {
    let n = if N == 0 { a.len() } else { N };
    let (a, b) = (&a[..n], &b[..n]);
    let product = |x: f64, y: f64| if ABS { x.abs() * y.abs() } else { x * y };
    let mut res = 0.0;
    let mut acc = [0.0f64; 8];
    let mut i = 0;
    while n - i >= 8 {
        for (l, s) in acc.iter_mut().enumerate() {
            *s += product(a[i + l], b[i + l]);
        }
        i += 8;
    }
    res += acc[0] + acc[4];
    res += acc[1] + acc[5];
    res += acc[2] + acc[6];
    res += acc[3] + acc[7];
    for k in i..n {
        res += product(a[k], b[k]);
    }
    res
}

/// Disjoint parts of one zeroed buffer, handed out in order (each once,
/// so every part is zeros when handed out).
pub(super) struct Parts<'a> {
    rest: &'a mut [f64],
}

impl<'a> Parts<'a> {
    /// `buffer`: all zero.
    pub(super) fn new(buffer: &'a mut [f64]) -> Self {
        debug_assert!(buffer.iter().all(|v| v.to_bits() == 0));
        Self { rest: buffer }
    }

    /// The next `len` entries (zeros).
    pub(super) fn take(&mut self, len: usize) -> &'a mut [f64] {
        let (part, rest) = std::mem::take(&mut self.rest).split_at_mut(len);
        self.rest = rest;
        part
    }

    /// The next `rows x cols` part (zeros) filled by `fill` (the
    /// column-major entries), as a matrix.
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

/// Zeros on the stack up to `N` entries, else on the heap (one
/// allocation).
pub(super) struct ZeroBuffer<const N: usize> {
    stack: [f64; N],
    heap: Vec<f64>,
}

impl<const N: usize> ZeroBuffer<N> {
    #[inline(always)]
    pub(super) fn new() -> Self {
        Self {
            stack: [0.0; N],
            heap: Vec::new(),
        }
    }

    /// `need` zeros (the buffer's first use): the first entries of the
    /// stack array when they fit, else the heap's.
    pub(super) fn zeros(&mut self, need: usize) -> &mut [f64] {
        if need <= N {
            &mut self.stack[..need]
        } else {
            self.heap.resize(need, 0.0);
            &mut self.heap
        }
    }

    /// [`ZeroBuffer::zeros`] handed out in parts.
    pub(super) fn parts(&mut self, need: usize) -> Parts<'_> {
        Parts::new(self.zeros(need))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The norms are nalgebra's bit for bit, for every column length of
    /// the constant-size dispatch and others (blocks of eight and their
    /// remainders), with signed zeros, tiny and huge entries.
    #[test]
    fn norms_are_nalgebras_to_the_bit() {
        let mut values = crate::test_values::Values(29);
        for rows in [0, 1, 2, 3, 4, 6, 7, 8, 9, 12, 16, 17, 31] {
            for cols in [0, 1, 2, 3, 5] {
                let m = DMatrix::from_fn(rows, cols, |_, _| {
                    let v = values.signed();
                    match (v * 16.0) as i64 {
                        0 => 0.0 * v.signum(),
                        1 => v * 1e-160,
                        -1 => v * 1e160,
                        _ => v,
                    }
                });
                let columns = Columns::from(&m);
                assert_eq!(
                    columns.norm_squared().to_bits(),
                    m.norm_squared().to_bits(),
                    "{rows} x {cols}"
                );
                assert_eq!(
                    columns.norm().to_bits(),
                    m.norm().to_bits(),
                    "{rows} x {cols}"
                );
            }
        }
    }
}
