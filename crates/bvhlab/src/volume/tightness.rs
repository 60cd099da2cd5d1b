//! PLACEHOLDER: tightness report.
/// PLACEHOLDER.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FitKind { /// A
 Aabb }
/// PLACEHOLDER.
#[derive(Clone, Debug, PartialEq)]
pub struct FitReport;
