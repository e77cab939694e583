//! A model's parameters as one flat `f32` vector: the [`ParamLayout`] says where each named tensor
//! lies (in name order), so parameters, gradients, optimiser moments and EMA weights are plain
//! vectors of the same length, and checkpoints keep their named tensors.
//!
//! Matrices (the linear layers' weights, `output × input` in checkpoints and candle) are stored
//! transposed, `input × output` row-major, as the forward pass reads them: a product with a
//! row-major right-hand side computes every output row alike whatever the number of rows (through
//! a transposed view it does not, for one or two rows), so an item's numbers never depend on the
//! rows stacked with it. Conversions happen only here, when tensors come in or go out.
//!
//! It does not know what the tensors mean; [`super::grad::GradNet`] finds its layers by name.

use super::GenError;
use candle_core::{DType, Device, Tensor};
use std::collections::BTreeMap;
use std::ops::Range;

/// One named tensor's place.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Entry {
    name: String,
    shape: Vec<usize>,
    offset: usize,
}

/// Names, shapes and offsets of a model's parameters.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParamLayout {
    entries: Vec<Entry>,
    len: usize,
}

impl ParamLayout {
    /// The layout of `tensors` (name order) and their values laid out by it.
    pub fn of(tensors: &BTreeMap<String, Tensor>) -> Result<(ParamLayout, Vec<f32>), GenError> {
        let mut entries = Vec::with_capacity(tensors.len());
        let mut values = Vec::new();
        for (name, t) in tensors {
            entries.push(Entry { name: name.clone(), shape: t.dims().to_vec(), offset: values.len() });
            values.extend(stored(t.dims(), &t.to_dtype(DType::F32)?.flatten_all()?.to_vec1::<f32>()?));
        }
        Ok((ParamLayout { entries, len: values.len() }, values))
    }

    /// Scalars in all.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are no parameters.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Where `name` lies and its shape (as in checkpoints: a matrix lies transposed).
    pub fn find(&self, name: &str) -> Option<(Range<usize>, &[usize])> {
        let e = self.entries.iter().find(|e| e.name == name)?;
        let n: usize = e.shape.iter().product();
        Some((e.offset..e.offset + n, &e.shape))
    }

    /// The parameter names with their ranges, in order.
    pub fn ranges(&self) -> impl Iterator<Item = (&str, Range<usize>)> {
        self.entries.iter().map(|e| (e.name.as_str(), e.offset..e.offset + e.shape.iter().product::<usize>()))
    }

    /// `values` (laid out by this layout) as named tensors.
    pub fn tensors(&self, values: &[f32]) -> Result<BTreeMap<String, Tensor>, GenError> {
        assert_eq!(values.len(), self.len, "values of this layout");
        self.entries
            .iter()
            .map(|e| {
                let n: usize = e.shape.iter().product();
                let plain = unstored(&e.shape, &values[e.offset..e.offset + n]);
                Ok((e.name.clone(), Tensor::from_vec(plain, e.shape.as_slice(), &Device::Cpu)?))
            })
            .collect()
    }

    /// Named tensors laid out by this layout; `take(name, shape)` gives each one's values
    /// (row-major, as in checkpoints) or the error (a missing tensor, a wrong shape) to report.
    pub fn gather(
        &self,
        mut take: impl FnMut(&str, &[usize]) -> Result<Vec<f32>, GenError>,
    ) -> Result<Vec<f32>, GenError> {
        let mut values = Vec::with_capacity(self.len);
        for e in &self.entries {
            let plain = take(&e.name, &e.shape)?;
            assert_eq!(plain.len(), e.shape.iter().product::<usize>(), "values of {}", e.name);
            values.extend(stored(&e.shape, &plain));
        }
        Ok(values)
    }
}

/// A tensor's row-major values as stored: a matrix transposed, anything else as it is.
fn stored(shape: &[usize], values: &[f32]) -> Vec<f32> {
    match *shape {
        [rows, cols] => transpose(values, rows, cols),
        _ => values.to_vec(),
    }
}

/// The inverse of [`stored`].
fn unstored(shape: &[usize], values: &[f32]) -> Vec<f32> {
    match *shape {
        [rows, cols] => transpose(values, cols, rows),
        _ => values.to_vec(),
    }
}

/// `values` (rows × cols, row-major) transposed.
fn transpose(values: &[f32], rows: usize, cols: usize) -> Vec<f32> {
    let mut out = vec![0f32; values.len()];
    for r in 0..rows {
        for c in 0..cols {
            out[c * rows + r] = values[r * cols + c];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tensors_go_flat_in_name_order_and_come_back() {
        let mut map = BTreeMap::new();
        map.insert("b".to_string(), Tensor::new(&[[1f32, 2.0], [3.0, 4.0]], &Device::Cpu).unwrap());
        map.insert("a".to_string(), Tensor::new(&[5f32, 6.0, 7.0], &Device::Cpu).unwrap());
        let (layout, values) = ParamLayout::of(&map).unwrap();
        // The matrix lies transposed.
        assert_eq!(values, [5.0, 6.0, 7.0, 1.0, 3.0, 2.0, 4.0]);
        assert_eq!(layout.find("b").unwrap(), (3..7, &[2usize, 2][..]));
        let back = layout.tensors(&values).unwrap();
        assert_eq!(back["b"].to_vec2::<f32>().unwrap(), [[1.0, 2.0], [3.0, 4.0]]);
        let again = layout.gather(|name, _| Ok(back[name].flatten_all().unwrap().to_vec1().unwrap())).unwrap();
        assert_eq!(again, values);
    }
}
