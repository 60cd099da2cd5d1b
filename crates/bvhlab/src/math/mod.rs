//! Small dense linear algebra in `f64`, sized at compile time, used by the fits.

pub mod eigen;
pub(crate) mod exact;
pub mod linear_solve;
