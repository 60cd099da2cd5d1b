//! Closest points on a triangle mesh: for each query point, the nearest point of the
//! surface, which triangle it lies on and how far it is, by branch and bound in a [`Bvh4`]
//! (the lecture's BVH distance query, §3: a box farther than the best distance so far
//! cannot hold anything nearer and is skipped). Also every triangle within a distance (a
//! range query with a ball).
//!
//! Run: `cargo run -p bvhlab --example closest_points`. The mesh is a torus made in code
//! with [`Mesh::from_indexed`], the constructor for meshes that do not come from a file.
#![expect(clippy::print_stdout, reason = "an example that prints what it found")]

use std::error::Error;
use std::f32::consts::TAU;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::{Bvh4, RangeShape};

fn main() -> Result<(), Box<dyn Error>> {
    let mesh = torus(48, 24, 2.0, 0.5)?;
    // Build once, query many times.
    let tree = Bvh4::build(mesh.triangles());
    println!("a torus of {} triangles", mesh.len());

    for query in [
        Vec3::ZERO,               // the hole's centre: 1.5 from the inner rim
        Vec3::new(2.0, 0.0, 0.0), // inside the tube, on its core circle
        Vec3::new(0.0, 5.0, 3.0), // far outside
        Vec3::new(2.5, 0.0, 0.0), // on the surface
    ] {
        // `None` only for an empty mesh or a NaN query point.
        let Some(nearest) = tree.closest_point(query) else {
            continue;
        };
        println!(
            "{query}: triangle #{} at distance {:.4}, point {:.3}",
            nearest.prim, nearest.distance, nearest.point
        );
    }

    // Which triangles come within 0.3 of a point: a range query with a ball.
    let near = tree.range(&RangeShape::Ball(Sphere3::new(
        Vec3::new(2.6, 0.0, 0.0),
        0.3,
    )));
    println!("{} triangles within 0.3 of (2.6, 0, 0)", near.len());
    Ok(())
}

/// A torus around the z axis: `around` steps along the big circle of radius `major`,
/// `tube` steps around the tube of radius `minor`, two triangles per quad, given as
/// positions and index triples.
///
/// # Errors
/// Only if the numbers produce a NaN (they do not for finite radii).
fn torus(around: u32, tube: u32, major: f32, minor: f32) -> Result<Mesh, Box<dyn Error>> {
    let mut positions = Vec::new();
    for i in 0..around {
        let (sin_a, cos_a) = (TAU * i as f32 / around as f32).sin_cos();
        for j in 0..tube {
            let (sin_t, cos_t) = (TAU * j as f32 / tube as f32).sin_cos();
            let from_axis = major + minor * cos_t;
            positions.push(Vec3::new(
                from_axis * cos_a,
                from_axis * sin_a,
                minor * sin_t,
            ));
        }
    }
    let index = |i: u32, j: u32| (i % around) * tube + j % tube;
    let mut triangles = Vec::new();
    for i in 0..around {
        for j in 0..tube {
            let (a, b) = (index(i, j), index(i + 1, j));
            let (c, d) = (index(i + 1, j + 1), index(i, j + 1));
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    Ok(Mesh::from_indexed(positions, triangles)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::BruteForce;

    #[test]
    fn example_runs_and_agrees_with_brute_force() -> Result<(), Box<dyn Error>> {
        main()?;
        let (major, minor) = (2.0, 0.5);
        let mesh = torus(24, 12, major, minor)?;
        let tree = Bvh4::build(mesh.triangles());
        let binary = AabbTree3::build(mesh.triangles());
        let brute = BruteForce::build(mesh.triangles());
        for i in 0..200 {
            let s = i as f32;
            let query = Vec3::new(
                (s * 0.37) % 7.0 - 3.5,
                (s * 0.71) % 7.0 - 3.5,
                (s * 0.13) % 3.0 - 1.5,
            );
            let want = brute.closest_point(query);
            assert_eq!(tree.closest_point(query), want, "{query}");
            assert_eq!(binary.closest_point(query), want, "{query}");
            let nearest = want.ok_or("a mesh has a nearest point")?;
            assert_eq!(nearest.distance, nearest.point.distance(query));
            // The torus's own distance, |(|q_xy| - R, q_z)| - r up to sign: the mesh is
            // inscribed in it, so they differ by at most its sagitta (under 0.03 here).
            let radial = Vec3::new(query.truncate().length() - major, 0.0, query.z).length();
            let exact = (radial - minor).abs();
            assert!(
                (nearest.distance - exact).abs() < 0.05,
                "{query}: {nearest:?} vs {exact}"
            );
        }
        let ball = RangeShape::Ball(Sphere3::new(Vec3::new(2.6, 0.0, 0.0), 0.3));
        assert_eq!(tree.range(&ball), brute.range(&ball));
        Ok(())
    }
}
