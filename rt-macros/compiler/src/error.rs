//! Compile errors: detected anywhere in the compiler, each carrying the Rust
//! span at fault; rendering them as `compile_error!` is `expand`'s job.

use proc_macro2::Span;

/// One compile error at a Rust span.
#[derive(Clone, Debug)]
pub struct Error {
    pub span: Span,
    pub message: String,
}

impl Error {
    pub fn new(span: Span, message: impl Into<String>) -> Error {
        Error { span, message: message.into() }
    }

    /// A subset violation: names the construct and says what to use.
    pub fn unsupported(span: Span, construct: &str, instead: &str) -> Error {
        Error::new(span, format!("{construct} is not supported in ray programs: {instead}"))
    }

    /// An error that follows from one already reported (a use of a local
    /// whose `let` failed, a call to a helper whose own macro reports its
    /// mistake): it stops the lowering but is not shown.
    pub fn silent(span: Span) -> Error {
        Error { span, message: String::new() }
    }

    pub fn is_silent(&self) -> bool {
        self.message.is_empty()
    }
}

impl From<syn::Error> for Error {
    fn from(e: syn::Error) -> Error {
        Error { span: e.span(), message: e.to_string() }
    }
}

/// All errors found in one item, in source order.
#[derive(Clone, Debug, Default)]
pub struct Errors(pub Vec<Error>);

impl Errors {
    pub fn push(&mut self, e: Error) {
        self.0.push(e);
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The messages alone, for tests (silent errors left out).
    pub fn messages(&self) -> Vec<String> {
        self.0.iter().filter(|e| !e.is_silent()).map(|e| e.message.clone()).collect()
    }

    /// `compile_error!`s for the errors to show (silent ones left out).
    pub fn to_compile_errors(&self) -> proc_macro2::TokenStream {
        self.0
            .iter()
            .filter(|e| !e.is_silent())
            .map(|e| syn::Error::new(e.span, &e.message).to_compile_error())
            .collect()
    }
}

impl From<Error> for Errors {
    fn from(e: Error) -> Errors {
        Errors(vec![e])
    }
}

impl std::fmt::Display for Errors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for e in self.0.iter().filter(|e| !e.is_silent()) {
            writeln!(f, "error: {}", e.message)?;
        }
        Ok(())
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
