//! The mesh reader's integration tests in one test binary: each file beside this one is a
//! module (one link instead of one per file; issue 28). One file's tests:
//! `cargo test -p bvhlab-meshio --test all broken::`.

mod support;

mod broken;
mod builtin;
mod fuzz_corpus;
mod real_meshes;
mod roundtrip;
mod timings;
