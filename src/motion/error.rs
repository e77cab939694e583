//! The error of reading and importing a motion file: one line that names the file and, where
//! there is one, the line or frame at fault.

use std::path::PathBuf;

/// Why a motion file could not be imported.
#[derive(Debug, thiserror::Error)]
pub enum MotionError {
    /// The file could not be read.
    #[error("{}: {error}", file.display())]
    Io {
        /// The file.
        file: PathBuf,
        /// The operating-system error.
        error: std::io::Error,
    },
    /// The file is not a motion this reader understands, or breaks a rule of its format.
    #[error("{}: {message}", file.display())]
    Invalid {
        /// The file.
        file: PathBuf,
        /// What is wrong, with the line or frame where there is one.
        message: String,
    },
}

impl MotionError {
    /// An [`MotionError::Invalid`] for `file`.
    pub fn invalid(file: impl Into<PathBuf>, message: impl Into<String>) -> MotionError {
        MotionError::Invalid { file: file.into(), message: message.into() }
    }
}
