//! How many threads the batch queries and the parallel builds use (the `parallel` feature).
//!
//! They run on rayon's pool: by default its global pool, with one thread per core. A program
//! that shares the machine (a server answering queries beside other work, a benchmark of one
//! core) runs them inside a pool of its own size instead: [`with_threads`] for one job, or a
//! [`rayon::ThreadPool`] built once and its [`install`](rayon::ThreadPool::install) for many
//! (building a pool starts its threads, which costs far more than a small batch). Inside
//! either, every batch call ([`ray_first_hits`](crate::RayCast::ray_first_hits),
//! [`ray_any_hits`](crate::RayCast::ray_any_hits),
//! [`closest_points`](crate::PointQuery::closest_points)) and every `build_parallel` splits
//! its work over that pool's threads only. The answers do not depend on the thread count.
//!
//! ```
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//!
//! let tris = [Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y)];
//! let tree = Bvh4::build(&tris);
//! let rays: Vec<Ray3> = (0..1000)
//!     .map(|i| Ray3::new(Vec3::new(0.1, 0.1, 1.0 + i as f32), -Vec3::Z))
//!     .collect::<Result<_, _>>()?;
//! // Two threads for this batch, whatever the machine has.
//! let hits = bvhlab::queries::with_threads(2, || tree.ray_first_hits(&rays, f32::INFINITY))?;
//! assert!(hits.iter().all(Option::is_some));
//!
//! // Many batches on one pool of two threads: build it once (rayon is re-exported).
//! let pool = bvhlab::rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
//! let again = pool.install(|| tree.ray_first_hits(&rays, f32::INFINITY));
//! assert_eq!(again, hits);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

/// Runs `job` on a pool of `threads` threads made for it, so that the batch queries and
/// parallel builds inside it use that many (0: rayon's default, one per core, or the
/// `RAYON_NUM_THREADS` environment variable). The pool is made and dropped for this call:
/// for many calls build a [`rayon::ThreadPool`] once and use its
/// [`install`](rayon::ThreadPool::install).
///
/// # Errors
/// rayon's error when the operating system refuses to start the threads.
pub fn with_threads<R: Send>(
    threads: usize,
    job: impl FnOnce() -> R + Send,
) -> Result<R, rayon::ThreadPoolBuildError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    Ok(pool.install(job))
}
