//! Errors of making, reading and writing datasets.

use std::path::PathBuf;

/// Why a dataset operation failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DataError {
    /// A file or folder could not be read or written.
    #[error("{}: {error}", path.display())]
    Io {
        /// The path.
        path: PathBuf,
        /// The operating-system error.
        error: std::io::Error,
    },
    /// A scene in the dataset is bad.
    #[error(transparent)]
    Scene(#[from] crate::scene::SceneError),
    /// `stats.json` is missing or malformed.
    #[error("{}: {message}", path.display())]
    Stats {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A folder that should hold a dataset does not.
    #[error("{}: {message}", path.display())]
    NotADataset {
        /// The folder.
        path: PathBuf,
        /// What is missing.
        message: String,
    },
}

impl DataError {
    /// An I/O error at `path`.
    pub fn io(path: impl Into<PathBuf>, error: std::io::Error) -> DataError {
        DataError::Io { path: path.into(), error }
    }
}
