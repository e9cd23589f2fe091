//! Errors a user can cause, each with a one-line first message naming the key,
//! the value and what was expected.

use thiserror::Error;

#[derive(Debug, Clone, Error)]
pub enum SphError {
    /// The case file cannot be read or parsed.
    #[error("{path}: {message}")]
    CaseFile { path: String, message: String },
    /// A key holds a value the solver cannot accept.
    #[error("{key} = {value}: expected {expected}")]
    InvalidValue {
        key: String,
        value: String,
        expected: String,
    },
    /// A key is unknown or has the wrong type.
    #[error("{key} = {value}: {message}")]
    Schema {
        key: String,
        value: String,
        message: String,
    },
    /// The run blew up; the output written so far is kept.
    #[error("unstable at t = {time:.6} s (step {step}): {reason} at particle {particle}, x = {position}")]
    Unstable {
        time: f64,
        step: u64,
        particle: u32,
        position: String,
        reason: String,
    },
    /// Writing the output failed.
    #[error("output {path}: {message}")]
    Output { path: String, message: String },
}

impl SphError {
    pub fn invalid(
        key: impl Into<String>,
        value: impl ToString,
        expected: impl Into<String>,
    ) -> Self {
        SphError::InvalidValue {
            key: key.into(),
            value: value.to_string(),
            expected: expected.into(),
        }
    }

    /// An output error; the message (an HDF5 or OS error) is folded onto one line.
    pub fn output(path: impl AsRef<std::path::Path>, e: impl ToString) -> Self {
        let message = e.to_string();
        SphError::Output {
            path: path.as_ref().display().to_string(),
            message: message.split_whitespace().collect::<Vec<_>>().join(" "),
        }
    }
}

pub type Result<T> = std::result::Result<T, SphError>;
