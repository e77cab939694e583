//! Named trainable parameters, created from a seed or taken from a checkpoint, and the few layers
//! built on them (linear maps, parameter-free layer norm).
//!
//! Candle's own initialisers draw from a thread-local generator; ours draw from the crate's seeded
//! [`Rng`], so a model built with the same seed is the same model.

use super::GenError;
use crate::data::Rng;
use candle_core::{D, DType, Device, Tensor, Var};
use std::collections::{BTreeMap, HashMap};

/// How a new parameter is initialised.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Init {
    /// Uniform in ±1/√fan_in (PyTorch's default for linear layers).
    FanIn(usize),
    /// All zeros (adaLN-Zero modulation and output layers).
    Zeros,
    /// Normal with the given standard deviation.
    Normal(f64),
}

/// The parameters of one model, by name, in a deterministic order. Fresh parameters are trainable
/// variables; loaded ones are plain tensors, so inference records no computation graph.
#[derive(Debug)]
pub struct Params {
    vars: BTreeMap<String, Var>,
    frozen: BTreeMap<String, Tensor>,
    source: Source,
}

#[derive(Debug)]
enum Source {
    Random(Rng),
    Loaded(HashMap<String, Tensor>),
}

impl Params {
    /// Fresh parameters drawn from `seed`.
    pub fn random(seed: u64) -> Params {
        Params { vars: BTreeMap::new(), frozen: BTreeMap::new(), source: Source::Random(Rng::new(seed)) }
    }

    /// Frozen parameters taken from `tensors` (a checkpoint); shapes are checked as the model asks.
    pub fn loaded(tensors: HashMap<String, Tensor>) -> Params {
        Params { vars: BTreeMap::new(), frozen: BTreeMap::new(), source: Source::Loaded(tensors) }
    }

    /// The parameter `name` of `shape`: drawn with `init`, or taken from the loaded tensors.
    pub fn get(&mut self, name: &str, shape: &[usize], init: Init) -> Result<Tensor, GenError> {
        if self.vars.contains_key(name) || self.frozen.contains_key(name) {
            return Err(mismatch(format!("parameter {name} defined twice")));
        }
        match &mut self.source {
            Source::Random(rng) => {
                let n: usize = shape.iter().product();
                let values: Vec<f32> = match init {
                    Init::FanIn(fan_in) => {
                        let bound = 1.0 / (fan_in.max(1) as f64).sqrt();
                        (0..n).map(|_| rng.uniform(-bound, bound) as f32).collect()
                    }
                    Init::Zeros => vec![0.0; n],
                    Init::Normal(std) => (0..n).map(|_| (rng.normal() * std) as f32).collect(),
                };
                let var = Var::from_vec(values, shape, &Device::Cpu)?;
                let out = var.as_tensor().clone();
                self.vars.insert(name.to_string(), var);
                Ok(out)
            }
            Source::Loaded(map) => {
                let t = map.remove(name).ok_or_else(|| missing(name))?;
                if t.dims() != shape {
                    return Err(mismatch(format!("{name} has shape {:?}, the model needs {shape:?}", t.dims())));
                }
                let t = t.to_dtype(DType::F32)?.detach();
                self.frozen.insert(name.to_string(), t.clone());
                Ok(t)
            }
        }
    }

    /// A linear layer `name.{weight,bias}` from `input` to `output` features.
    pub fn linear(&mut self, name: &str, input: usize, output: usize, zero: bool) -> Result<Linear, GenError> {
        let init = if zero { Init::Zeros } else { Init::FanIn(input) };
        let weight = self.get(&format!("{name}.weight"), &[output, input], init)?;
        let bias = self.get(&format!("{name}.bias"), &[output], if zero { Init::Zeros } else { init })?;
        Ok(Linear { weight, bias })
    }

    /// Fails when loaded tensors were left over (the checkpoint is for another model).
    pub fn finish(&self) -> Result<(), GenError> {
        if let Source::Loaded(map) = &self.source
            && let Some(name) = map.keys().min()
        {
            return Err(mismatch(format!("checkpoint has tensor {name} that the model does not use")));
        }
        Ok(())
    }

    /// The trainable parameters by name (empty for loaded ones).
    pub fn vars(&self) -> &BTreeMap<String, Var> {
        &self.vars
    }

    /// Number of scalar parameters.
    pub fn count(&self) -> usize {
        self.vars.values().map(|v| v.elem_count()).sum::<usize>()
            + self.frozen.values().map(|t| t.elem_count()).sum::<usize>()
    }

    /// The parameters by name (sharing storage with trainable ones: they follow updates).
    pub fn tensors(&self) -> BTreeMap<String, Tensor> {
        let vars = self.vars.iter().map(|(k, v)| (k.clone(), v.as_tensor().clone()));
        vars.chain(self.frozen.iter().map(|(k, t)| (k.clone(), t.clone()))).collect()
    }

    /// Copies of the current values by name (for EMA and saving).
    pub fn snapshot(&self) -> Result<BTreeMap<String, Tensor>, GenError> {
        let vars = self.vars.iter().map(|(k, v)| Ok((k.clone(), v.as_tensor().copy()?)));
        let frozen = self.frozen.iter().map(|(k, t)| Ok((k.clone(), t.copy()?)));
        vars.chain(frozen).collect()
    }
}

/// The error for a checkpoint that does not fit; the caller adds the file.
fn mismatch(message: String) -> GenError {
    GenError::checkpoint("", message)
}

fn missing(name: &str) -> GenError {
    mismatch(format!("checkpoint lacks tensor {name}"))
}

/// `y = x Wᵀ + b` over the last dimension of `x`.
#[derive(Debug, Clone)]
pub struct Linear {
    weight: Tensor,
    bias: Tensor,
}

impl Linear {
    /// The weight (output × input).
    pub fn weight(&self) -> &Tensor {
        &self.weight
    }

    /// The bias (output).
    pub fn bias(&self) -> &Tensor {
        &self.bias
    }

    /// Applies the layer to `x` of shape (…, input).
    pub fn forward(&self, x: &Tensor) -> Result<Tensor, GenError> {
        let dims = x.dims().to_vec();
        let input = *dims.last().expect("a tensor with at least one dimension");
        let rows: usize = dims[..dims.len() - 1].iter().product();
        let y = x.reshape((rows, input))?.matmul(&self.weight.t()?)?.broadcast_add(&self.bias)?;
        let mut out = dims;
        *out.last_mut().expect("non-empty") = self.weight.dim(0)?;
        Ok(y.reshape(out)?)
    }
}

/// Layer norm over the last dimension without a learned affine (adaLN provides it), built from
/// differentiable primitives (candle's fused layer norm has no backward pass).
pub fn layer_norm(x: &Tensor) -> Result<Tensor, GenError> {
    let mean = x.mean_keepdim(D::Minus1)?;
    let centred = x.broadcast_sub(&mean)?;
    let var = centred.sqr()?.mean_keepdim(D::Minus1)?;
    Ok(centred.broadcast_div(&(var + 1e-6)?.sqrt()?)?)
}
