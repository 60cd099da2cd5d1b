//! Frame timing: how long frames take while the student interacts, so the lab can show (and
//! the note can quote) its frame rate. Uses `web_time::Instant`, which is the browser's
//! `performance.now()` on the web.

use std::collections::VecDeque;
use web_time::Instant;

/// The recent frame intervals.
#[derive(Clone, Debug, Default)]
pub struct FrameClock {
    last: Option<Instant>,
    intervals_ms: VecDeque<f64>,
    cpu_ms: VecDeque<f64>,
}

/// How many intervals the clock keeps.
const WINDOW: usize = 120;

impl FrameClock {
    /// Records a frame starting at `now`.
    pub fn tick(&mut self, now: Instant) {
        if let Some(last) = self.last {
            let ms = now.duration_since(last).as_secs_f64() * 1e3;
            // Gaps of a second or more are idle time (egui only repaints on input), not frames.
            if ms < 1000.0 {
                if self.intervals_ms.len() == WINDOW {
                    self.intervals_ms.pop_front();
                }
                self.intervals_ms.push_back(ms);
            }
        }
        self.last = Some(now);
    }

    /// Records the CPU time the previous frame took (the lab's UI, tessellation and issuing
    /// the draw calls, as eframe measures it), in milliseconds. Unlike the interval between
    /// frames it leaves out the rasterisation, which a software renderer does on the CPU.
    pub fn record_cpu(&mut self, ms: f64) {
        if self.cpu_ms.len() == WINDOW {
            self.cpu_ms.pop_front();
        }
        self.cpu_ms.push_back(ms);
    }

    /// The median frame interval in milliseconds, over the last frames.
    pub fn median_ms(&self) -> Option<f64> {
        median(&self.intervals_ms)
    }

    /// The median CPU time per frame in milliseconds, over the last frames.
    pub fn median_cpu_ms(&self) -> Option<f64> {
        median(&self.cpu_ms)
    }

    /// Frames per second from the median interval.
    pub fn fps(&self) -> Option<f64> {
        self.median_ms().filter(|&ms| ms > 0.0).map(|ms| 1e3 / ms)
    }
}

fn median(values: &VecDeque<f64>) -> Option<f64> {
    let mut v: Vec<f64> = values.iter().copied().collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    Some(v[v.len() / 2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn median_of_steady_frames() {
        let mut clock = FrameClock::default();
        let start = Instant::now();
        for i in 0..10 {
            clock.tick(start + Duration::from_millis(16 * i));
        }
        assert_eq!(clock.median_ms(), Some(16.0));
        // An idle gap is not a frame.
        clock.tick(start + Duration::from_mins(1));
        assert_eq!(clock.median_ms(), Some(16.0));
    }
}
