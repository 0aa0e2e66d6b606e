//! The seed worked examples.
