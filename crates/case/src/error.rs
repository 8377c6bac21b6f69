//! What goes wrong in making a case: a key refused, a surface file unread, a problem the
//! libraries refuse, a run the machine cannot hold. Every message names the key, the file or
//! the limit, so that a front end prints it as it is (with its causes: `{:#}` under anyhow).

use std::fmt;

/// A case's error.
#[derive(Debug)]
pub enum Error {
    /// A key's value, or a combination of keys, refused; the message names the key.
    Key(String),
    /// The machine cannot hold the run: the estimate and what is available.
    Memory(String),
    /// A case file or a table of keys that is not valid TOML, or a case that does not serialise.
    Toml(String),
    /// A surface file unread or unwritten, or a surface the generator refuses.
    Surface(surfgen::SurfError),
    /// A problem the solver refuses.
    Solver(solver::SolverError),
    /// A law the adhesion library refuses.
    Adhesion(ljadhesion::AdhesionError),
    /// An error with what was being done when it happened.
    Context { context: String, source: Box<Error> },
}

/// A case's result.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Key(m) | Error::Memory(m) | Error::Toml(m) => f.write_str(m),
            Error::Surface(e) => e.fmt(f),
            Error::Solver(e) => e.fmt(f),
            Error::Adhesion(e) => e.fmt(f),
            Error::Context { context, .. } => f.write_str(context),
        }
    }
}

impl std::error::Error for Error {
    /// The cause: for a wrapped library error, that error's own cause (its message is this
    /// one's), so that a chain prints each message once.
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Key(_) | Error::Memory(_) | Error::Toml(_) => None,
            Error::Surface(e) => e.source(),
            Error::Solver(e) => e.source(),
            Error::Adhesion(e) => e.source(),
            Error::Context { source, .. } => Some(source.as_ref()),
        }
    }
}

impl From<surfgen::SurfError> for Error {
    fn from(e: surfgen::SurfError) -> Self {
        Error::Surface(e)
    }
}

impl From<solver::SolverError> for Error {
    fn from(e: solver::SolverError) -> Self {
        Error::Solver(e)
    }
}

impl From<ljadhesion::AdhesionError> for Error {
    fn from(e: ljadhesion::AdhesionError) -> Self {
        Error::Adhesion(e)
    }
}

impl From<toml::de::Error> for Error {
    fn from(e: toml::de::Error) -> Self {
        Error::Toml(e.to_string())
    }
}

impl From<toml::ser::Error> for Error {
    fn from(e: toml::ser::Error) -> Self {
        Error::Toml(e.to_string())
    }
}

/// What was being done, laid over an error (as anyhow's `context`), or the message a missing
/// key gives.
pub trait Context<T> {
    /// The error (or a missing value) with `context`.
    fn context(self, context: impl Into<String>) -> Result<T>;
    /// As [`Context::context`], the message made only on failure.
    fn with_context<S: Into<String>>(self, context: impl FnOnce() -> S) -> Result<T>;
}

impl<T, E: Into<Error>> Context<T> for std::result::Result<T, E> {
    fn context(self, context: impl Into<String>) -> Result<T> {
        self.map_err(|e| Error::Context {
            context: context.into(),
            source: Box::new(e.into()),
        })
    }
    fn with_context<S: Into<String>>(self, context: impl FnOnce() -> S) -> Result<T> {
        self.map_err(|e| Error::Context {
            context: context().into(),
            source: Box::new(e.into()),
        })
    }
}

/// A missing key: the message says what to give.
impl<T> Context<T> for Option<T> {
    fn context(self, context: impl Into<String>) -> Result<T> {
        self.ok_or_else(|| Error::Key(context.into()))
    }
    fn with_context<S: Into<String>>(self, context: impl FnOnce() -> S) -> Result<T> {
        self.ok_or_else(|| Error::Key(context().into()))
    }
}

/// Returns a refusal of a key ([`Error::Key`]), its message formatted.
macro_rules! bail {
    ($($message:tt)*) => {
        return Err($crate::error::Error::Key(format!($($message)*)))
    };
}
pub(crate) use bail;
