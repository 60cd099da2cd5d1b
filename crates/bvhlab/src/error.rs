//! Why a query or a fit could not be answered.

use std::fmt;

/// Input that the geometry core refuses, with a message a student can act on.
///
/// Every constructor and checked query that can meet bad input returns this in a `Result`
/// rather than answering wrongly or panicking.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum GeometryError {
    /// A coordinate is NaN or infinite.
    NonFinite {
        /// What the value was ("ray origin", "query point", "point 17", ...).
        what: String,
        /// The offending value, formatted.
        value: String,
    },
    /// A ray direction of length zero: it points nowhere, so no `t` can be measured along it.
    ZeroDirection,
    /// A ray direction whose every component is subnormal (or zero): below
    /// [`f32::MIN_POSITIVE`] (about 1.2e-38) in magnitude. Such a direction has no usable
    /// inverse (`1 / 1e-40` overflows to infinity) and a hit at any ordinary distance would
    /// lie at a `t` beyond `f32::MAX`, so the ray would silently never hit anything.
    TinyDirection {
        /// The direction, formatted.
        value: String,
    },
    /// A fit or structure was asked for with no points at all.
    Empty {
        /// What was empty ("point set", ...).
        what: &'static str,
    },
}

impl GeometryError {
    /// A [`GeometryError::NonFinite`] for a value that prints with `Debug`.
    pub(crate) fn non_finite(what: impl Into<String>, value: impl fmt::Debug) -> Self {
        Self::NonFinite {
            what: what.into(),
            value: format!("{value:?}"),
        }
    }
}

impl fmt::Display for GeometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { what, value } => write!(
                f,
                "{what} {value} has a coordinate that is NaN or infinite; \
                 every coordinate must be a finite number"
            ),
            Self::ZeroDirection => write!(
                f,
                "the ray direction is zero; give the ray a direction with a non-zero component \
                 (it need not be unit length)"
            ),
            Self::TinyDirection { value } => write!(
                f,
                "the ray direction {value} is too small: every component is below \
                 f32::MIN_POSITIVE (about 1.2e-38, the smallest normal f32), where 1/d \
                 overflows and no hit can be measured along it; scale the direction up \
                 (it need not be unit length: t is measured in units of it)"
            ),
            Self::Empty { what } => write!(
                f,
                "the {what} is empty; a bounding volume needs at least one point"
            ),
        }
    }
}

impl std::error::Error for GeometryError {}

/// Checks that a point is finite, naming it in the error.
pub(crate) fn check_finite<V: crate::Vector>(
    what: impl FnOnce() -> String,
    p: V,
) -> Result<V, GeometryError> {
    if p.is_finite() {
        Ok(p)
    } else {
        Err(GeometryError::non_finite(what(), p))
    }
}
