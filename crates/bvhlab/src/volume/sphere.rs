//! PLACEHOLDER: spheres.
use crate::Vector;
/// PLACEHOLDER.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere<V: Vector> { /// c
 pub center: V, /// r
 pub radius: f32 }
