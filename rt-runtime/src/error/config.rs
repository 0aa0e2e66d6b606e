//! Configuration: a setting of a value the runtime does not know, or
//! something asked for that this build or this adapter cannot give.

/// A setting or a request the runtime cannot honour.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ConfigError {
    /// A setting (an environment variable such as `RT_BACKEND` or
    /// `RT_TRAVERSAL`) of a value the runtime does not know.
    #[error("{setting} is `{value}`; expected {expected}")]
    Setting {
        /// The setting (`RT_BACKEND`).
        setting: &'static str,
        /// The value it has.
        value: String,
        /// The values it may have.
        expected: &'static str,
    },
    /// Something asked for (a backend, a traversal) that this build or
    /// this adapter cannot give, and why.
    #[error("{asked} was asked for, but {why}")]
    Unsupported {
        /// What was asked for.
        asked: &'static str,
        /// Why it cannot be given.
        why: String,
    },
}
