//! PLACEHOLDER: separating-axis test.
use crate::Vector;
/// PLACEHOLDER.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisSource { /// A
 FaceA(usize) }
/// PLACEHOLDER.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisTest<V: Vector> { /// axis
 pub axis: V }
/// PLACEHOLDER.
pub type SeparatingAxis<V> = AxisTest<V>;
