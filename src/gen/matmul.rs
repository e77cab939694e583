//! Matrix products on `f32` slices through `gemm`, behind one bounds-checked safe function, and the
//! linear layer `y = x Wᵀ + b` with its backward pass on weights stored as candle stores them
//! (`output × input`, row-major).
//!
//! A [`Mat`] is a view: a slice with a shape and strides, so a transpose is a view too (no copy).
//! Products run on the calling thread (`Parallelism::None`): callers parallelise over batch items.

/// A strided matrix view of a slice.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mat<'a> {
    data: &'a [f32],
    rows: usize,
    cols: usize,
    row_stride: usize,
    col_stride: usize,
}

impl<'a> Mat<'a> {
    /// `data` read as `rows × cols`, row-major.
    pub(crate) fn rows(data: &'a [f32], rows: usize, cols: usize) -> Mat<'a> {
        Mat { data, rows, cols, row_stride: cols, col_stride: 1 }
    }

    /// The transpose, as a view.
    pub(crate) fn t(self) -> Mat<'a> {
        Mat { rows: self.cols, cols: self.rows, row_stride: self.col_stride, col_stride: self.row_stride, ..self }
    }

    /// Whether every element the view names lies inside its slice.
    fn fits(&self) -> bool {
        self.rows == 0
            || self.cols == 0
            || (self.rows - 1) * self.row_stride + (self.cols - 1) * self.col_stride < self.data.len()
    }
}

/// `c` (a.rows × b.cols, row-major) = `a · b`, or `c += a · b` when `accumulate`.
///
/// # Panics
/// When the shapes do not agree or a view reaches past its slice.
pub(crate) fn matmul(c: &mut [f32], accumulate: bool, a: Mat, b: Mat) {
    let (m, k, n) = (a.rows, a.cols, b.cols);
    assert_eq!(b.rows, k, "inner dimensions");
    assert_eq!(c.len(), m * n, "output size");
    assert!(a.fits() && b.fits(), "a view reaches past its slice");
    if m == 0 || n == 0 {
        return;
    }
    if k == 0 {
        if !accumulate {
            c.fill(0.0);
        }
        return;
    }
    // SAFETY: every index gemm reads is (row · row_stride + col · col_stride) < len for the views
    // (checked by `fits`) and row · n + col < m · n for `c`; `c` is a unique borrow, so it aliases
    // neither input.
    unsafe {
        gemm::gemm(
            m,
            n,
            k,
            c.as_mut_ptr(),
            1,
            n as isize,
            accumulate,
            a.data.as_ptr(),
            a.col_stride as isize,
            a.row_stride as isize,
            b.data.as_ptr(),
            b.col_stride as isize,
            b.row_stride as isize,
            1.0,
            1.0,
            false,
            false,
            false,
            gemm::Parallelism::None,
        );
    }
}

/// Where a linear layer's weight and bias (`output`) lie in a flat vector; the weight is stored
/// transposed, `input × output` row-major (see [`super::flat`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LinearAt {
    pub(crate) weight: usize,
    pub(crate) bias: usize,
    pub(crate) input: usize,
    pub(crate) output: usize,
}

impl LinearAt {
    /// Wᵀ (input × output).
    fn weight_t<'a>(&self, params: &'a [f32]) -> Mat<'a> {
        Mat::rows(&params[self.weight..self.weight + self.input * self.output], self.input, self.output)
    }

    /// `y` (rows × output) = `x` (rows × input) Wᵀ + b.
    pub(crate) fn forward(&self, params: &[f32], x: &[f32], y: &mut [f32]) {
        let rows = x.len() / self.input;
        assert_eq!(x.len(), rows * self.input, "input width");
        // The product first, then the bias: gemm adds into an existing output differently for one
        // row than for several, and an item's numbers must not depend on the rows beside it.
        matmul(y, false, Mat::rows(x, rows, self.input), self.weight_t(params));
        let bias = &params[self.bias..self.bias + self.output];
        for row in y.chunks_exact_mut(self.output) {
            row.iter_mut().zip(bias).for_each(|(v, b)| *v += b);
        }
    }

    /// [`forward`](Self::forward) into a new vector.
    pub(crate) fn map(&self, params: &[f32], x: &[f32]) -> Vec<f32> {
        let mut y = vec![0f32; x.len() / self.input * self.output];
        self.forward(params, x, &mut y);
        y
    }

    /// Adds the weight and bias gradients of `dy` (rows × output) for input `x` into `grads` (laid
    /// out like the parameters) and, when asked, the input's gradient `dy · W` into `dx`.
    pub(crate) fn backward(&self, params: &[f32], grads: &mut [f32], x: &[f32], dy: &[f32], dx: Option<&mut [f32]>) {
        let rows = dy.len() / self.output;
        assert_eq!(x.len(), rows * self.input, "input of the forward pass");
        let dy_mat = Mat::rows(dy, rows, self.output);
        let dw = &mut grads[self.weight..self.weight + self.input * self.output];
        matmul(dw, true, Mat::rows(x, rows, self.input).t(), dy_mat);
        let db = &mut grads[self.bias..self.bias + self.output];
        for row in dy.chunks_exact(self.output) {
            db.iter_mut().zip(row).for_each(|(g, v)| *g += v);
        }
        if let Some(dx) = dx {
            matmul(dx, true, dy_mat, self.weight_t(params).t());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_and_transposed_views_match_hand_computed_ones() {
        // a = [[1, 2, 3], [4, 5, 6]], b = [[1, 0], [0, 1], [1, 1]].
        let a = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let b = [1.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let mut c = [0.0; 4];
        matmul(&mut c, false, Mat::rows(&a, 2, 3), Mat::rows(&b, 3, 2));
        assert_eq!(c, [4.0, 5.0, 10.0, 11.0]);
        matmul(&mut c, true, Mat::rows(&a, 2, 3), Mat::rows(&b, 3, 2));
        assert_eq!(c, [8.0, 10.0, 20.0, 22.0]);
        // aᵀ a (3 × 3): first row [17, 22, 27].
        let mut g = [0.0; 9];
        matmul(&mut g, false, Mat::rows(&a, 2, 3).t(), Mat::rows(&a, 2, 3));
        assert_eq!(g[..3], [17.0, 22.0, 27.0]);
    }

    #[test]
    #[should_panic(expected = "past its slice")]
    fn a_view_past_its_slice_is_refused() {
        let mut c = [0.0; 4];
        matmul(&mut c, false, Mat::rows(&[1.0; 5], 2, 3), Mat::rows(&[1.0; 6], 3, 2));
    }

    #[test]
    fn the_linear_backward_matches_finite_differences() {
        // Two inputs → three outputs; loss = Σ y · r for a fixed r.
        let layer = LinearAt { weight: 0, bias: 6, input: 2, output: 3 };
        let params = vec![0.5, -1.0, 2.0, 0.25, -0.5, 1.5, 0.1, 0.2, 0.3];
        let x = [1.0, 2.0, -1.0, 0.5];
        let r = [1.0, -2.0, 0.5, 3.0, 1.0, -1.0];
        let loss = |p: &[f32], x: &[f32]| layer.map(p, x).iter().zip(&r).map(|(y, r)| (y * r) as f64).sum::<f64>();
        let mut grads = vec![0.0; 9];
        let mut dx = vec![0.0; 4];
        layer.backward(&params, &mut grads, &x, &r, Some(&mut dx));
        for i in 0..9 {
            let mut p = params.clone();
            p[i] += 1e-2;
            let numeric = (loss(&p, &x) - loss(&params, &x)) / 1e-2;
            assert!((numeric - grads[i] as f64).abs() < 1e-3, "parameter {i}: {numeric} vs {}", grads[i]);
        }
        for i in 0..4 {
            let mut xi = x;
            xi[i] += 1e-2;
            let numeric = (loss(&params, &xi) - loss(&params, &x)) / 1e-2;
            assert!((numeric - dx[i] as f64).abs() < 1e-3, "input {i}: {numeric} vs {}", dx[i]);
        }
    }
}
