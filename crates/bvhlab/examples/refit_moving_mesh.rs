//! Refitting a moving mesh: each frame the triangles move, and instead of building the tree
//! again, [`Bvh4::refit`] fits every box to the new positions and keeps the tree's shape, in
//! time linear in its nodes (Wald, Boulos and Shirley, "Ray Tracing Deformable Scenes Using
//! Dynamic Bounding Volume Hierarchies", ACM TOG 2007). The shape was chosen for where the
//! triangles were, so as they drift apart the boxes grow and queries slow down; the
//! [`RefitReport`] gives the SAH cost (the expected cost of a ray, `MacDonald` and Booth
//! 1990) now and at build time, and `needs_rebuild(1.5)` says when it has grown by half and
//! a rebuild pays for itself.
//!
//! Run: `cargo run -p bvhlab --example refit_moving_mesh`. The mesh is a square sheet that
//! slides (a rigid motion: the cost stays), then bursts apart (the cost grows, and the tree
//! is rebuilt each time it has grown by half).
#![expect(clippy::print_stdout, reason = "an example that prints what it found")]

use std::error::Error;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::bvh::RefitReport;
use bvhlab::{Bvh4, Hit};

/// Rebuild when the SAH cost has grown past this factor of its build-time value.
const MAX_GROWTH: f32 = 1.5;

fn main() -> Result<(), Box<dyn Error>> {
    for frame in animate(40, 16)? {
        let refitted = &frame.refitted;
        let rebuilt = frame
            .rebuilt
            .map_or(String::new(), |cost| format!(", rebuilt: {cost:.2}"));
        println!(
            "frame {:2}: refitted SAH cost {:6.2} ({:.2} x build{rebuilt}); the probe ray {}",
            frame.number,
            refitted.sah_cost.unwrap_or(f32::NAN),
            refitted.cost_ratio().unwrap_or(f32::NAN),
            frame
                .hit
                .map_or("misses".into(), |h| format!("hits #{}", h.prim)),
        );
    }
    Ok(())
}

/// What happened in one frame.
struct Frame {
    number: usize,
    /// The SAH cost after the refit, and at the last build.
    refitted: RefitReport,
    /// The SAH cost of the tree built again, when the refitted one's had grown past
    /// [`MAX_GROWTH`] times its build-time cost.
    rebuilt: Option<f32>,
    /// The first hit of [`probe_ray`].
    hit: Option<Hit>,
}

/// Moves an `n` by `n` sheet of triangles for `frames` frames, keeping a [`Bvh4`] up to
/// date: a refit every frame, a rebuild when the refit report says it pays.
fn animate(n: usize, frames: usize) -> Result<Vec<Frame>, Box<dyn Error>> {
    let rest = sheet(n);
    let mut tree = Bvh4::build(&rest);
    let mut log = Vec::new();
    for number in 0..frames {
        let triangles: Vec<Triangle3> = rest
            .iter()
            .enumerate()
            .map(|(i, t)| moved(t, i, number))
            .collect();
        // Same triangles, same order, new positions: refit. (A different count is a
        // `RefitError`: build a new tree then.)
        let refitted = tree.refit(&triangles)?;
        // A rebuild costs far more than a refit (O(n log n) against O(n)); it pays when the
        // queries until the next one save more than that. The SAH cost predicts the
        // queries' cost, so rebuild when it has grown by a chosen factor (Wald et al.).
        let rebuilt = refitted.needs_rebuild(MAX_GROWTH).then(|| {
            tree = Bvh4::build(&triangles);
            tree.sah_cost().unwrap_or(f32::NAN)
        });
        let hit = tree.ray_first_hit(&probe_ray(n)?, f32::INFINITY);
        log.push(Frame {
            number,
            refitted,
            rebuilt,
            hit,
        });
    }
    Ok(log)
}

/// A ray straight down through the middle of an `n` by `n` sheet.
fn probe_ray(n: usize) -> Result<Ray3, GeometryError> {
    let middle = n as f32 * 0.5 + 0.3;
    Ray3::new(Vec3::new(middle, 50.0, middle), -Vec3::Y)
}

/// A flat `n` by `n` sheet in the xz plane, two triangles per unit square.
fn sheet(n: usize) -> Vec<Triangle3> {
    let mut triangles = Vec::with_capacity(2 * n * n);
    for x in 0..n {
        for z in 0..n {
            let corner = |dx: usize, dz: usize| Vec3::new((x + dx) as f32, 0.0, (z + dz) as f32);
            triangles.push(Triangle3::new(corner(0, 0), corner(0, 1), corner(1, 1)));
            triangles.push(Triangle3::new(corner(0, 0), corner(1, 1), corner(1, 0)));
        }
    }
    triangles
}

/// Where triangle `index` is in frame `frame`: for the first seven frames the whole sheet
/// slides along x (a rigid motion); then each triangle also flies off in a direction of its
/// own, so neighbours that the tree grouped together drift apart.
fn moved(triangle: &Triangle3, index: usize, frame: usize) -> Triangle3 {
    let slide = Vec3::X * frame as f32 * 0.5;
    let burst = frame.saturating_sub(6) as f32 * 0.4;
    let offset = slide + scattered_direction(index) * burst;
    Triangle3::new(
        triangle.a + offset,
        triangle.b + offset,
        triangle.c + offset,
    )
}

/// A direction that looks random but is fixed for each index (a hash of it, `SplitMix64`'s
/// finaliser), with coordinates in [-1, 1].
fn scattered_direction(index: usize) -> Vec3 {
    let coordinate = |axis: u64| {
        let mut z = (index as u64 * 3 + axis).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 23) as f32 - 1.0
    };
    Vec3::new(coordinate(0), coordinate(1), coordinate(2))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::BruteForce;

    #[test]
    fn example_runs_and_agrees_with_brute_force() -> Result<(), Box<dyn Error>> {
        let n = 12;
        let frames = animate(n, 12)?;
        let rest = sheet(n);
        for frame in &frames {
            let triangles: Vec<Triangle3> = rest
                .iter()
                .enumerate()
                .map(|(i, t)| moved(t, i, frame.number))
                .collect();
            let brute = BruteForce::build(&triangles);
            assert_eq!(
                frame.hit,
                brute.ray_first_hit(&probe_ray(n)?, f32::INFINITY)
            );
            let ratio = frame
                .refitted
                .cost_ratio()
                .ok_or("a sheet has an SAH cost")?;
            // A rebuild exactly when the refitted cost grew by more than half.
            assert_eq!(
                frame.rebuilt.is_some(),
                ratio > MAX_GROWTH,
                "frame {}",
                frame.number
            );
        }
        // Sliding keeps every box's shape: the cost does not change, nothing is rebuilt.
        for frame in &frames[..7] {
            let ratio = frame.refitted.cost_ratio().ok_or("a cost")?;
            assert!(
                (ratio - 1.0).abs() < 1e-3,
                "frame {}: {ratio}",
                frame.number
            );
            assert!(
                frame.hit.is_some(),
                "frame {}: the ray must hit",
                frame.number
            );
        }
        // Bursting apart grows the boxes until a rebuild pays.
        assert!(frames.iter().any(|f| f.rebuilt.is_some()), "no rebuild");
        Ok(())
    }
}
