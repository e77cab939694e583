//! Errors of the generator: tensors, checkpoints, datasets and inputs.

use std::path::PathBuf;

/// Why a model operation failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GenError {
    /// A tensor operation failed (a bug or an exhausted machine, not bad input).
    #[error("tensor operation failed: {0}")]
    Tensor(#[from] candle_core::Error),
    /// A checkpoint is missing, corrupt or does not fit the model.
    #[error("{}: {message}", path.display())]
    Checkpoint {
        /// The checkpoint file or folder.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A file or folder could not be read or written.
    #[error("{}: {error}", path.display())]
    Io {
        /// The path.
        path: PathBuf,
        /// The operating-system error.
        error: std::io::Error,
    },
    /// The training data is missing or unusable.
    #[error(transparent)]
    Data(#[from] crate::data::DataError),
    /// An input scene cannot be generated for.
    #[error("{}: {message}", path.display())]
    Input {
        /// The input file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
}

impl GenError {
    /// A checkpoint error at `path`.
    pub fn checkpoint(path: impl Into<PathBuf>, message: impl Into<String>) -> GenError {
        GenError::Checkpoint { path: path.into(), message: message.into() }
    }

    /// An I/O error at `path`.
    pub fn io(path: impl Into<PathBuf>, error: std::io::Error) -> GenError {
        GenError::Io { path: path.into(), error }
    }
}
