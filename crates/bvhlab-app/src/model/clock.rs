//! The model's one clock: a build's share of a frame and the timing of builds and refits
//! (`build_job.rs`) read it, nothing else in the model does.
//!
//! In the fuzz targets (`cfg(fuzzing)`, set by `tests/fuzz.sh` as by cargo-fuzz) it is a
//! counter that moves one millisecond each time it is read: the same input then does the same
//! work on every run (the wall clock is the one input a fuzzer cannot replay), which keeps
//! `tests/fuzz.sh check` deterministic. A build still stops after its budget's worth of reads,
//! and a timing makes one run.

#[cfg(fuzzing)]
use std::cell::Cell;

/// Milliseconds since it started.
pub struct Stopwatch {
    #[cfg(not(fuzzing))]
    start: web_time::Instant,
    #[cfg(fuzzing)]
    reads: Cell<u32>,
}

impl Stopwatch {
    /// Starts now.
    pub fn start() -> Self {
        Self {
            #[cfg(not(fuzzing))]
            start: web_time::Instant::now(),
            #[cfg(fuzzing)]
            reads: Cell::new(0),
        }
    }

    /// Milliseconds since [`start`](Self::start).
    pub fn elapsed_ms(&self) -> f64 {
        #[cfg(not(fuzzing))]
        {
            self.start.elapsed().as_secs_f64() * 1e3
        }
        #[cfg(fuzzing)]
        {
            self.reads.set(self.reads.get() + 1);
            f64::from(self.reads.get())
        }
    }
}
