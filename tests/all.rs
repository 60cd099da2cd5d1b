//! The cross-crate tests in one test binary: each file beside this one is a module (one link
//! instead of one per file; issue 28). One file's tests:
//! `cargo test -p bvhlab-tests --test all structures::`.

mod aabb;
mod contract;
mod cross_volume;
mod event_order;
mod extreme_values;
mod fits_contain;
mod meshes;
mod outline;
mod primitives;
mod ray;
mod sphere;
mod structures;
