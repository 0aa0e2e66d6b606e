//! Post-processing: a stage whose variable is missing or does not fit, and
//! a command list used out of order.

/// A post-processing stage or a command list that cannot run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PostProcessError {
    /// A post-processing stage whose variable (a buffer, a setting) is
    /// missing or does not fit: `stage` names the stage (its index and
    /// kind), `variable` the variable at fault.
    #[error("post-processing stage {stage}: variable `{variable}` {problem}")]
    BadStage {
        /// The stage: its index and kind.
        stage: String,
        /// The variable at fault.
        variable: String,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A command list used out of order (appended to after finalizing,
    /// executed before), or one of its commands that does not fit.
    #[error("command list: {problem}")]
    BadCommandList {
        /// What is wrong, in a sentence.
        problem: String,
    },
}
