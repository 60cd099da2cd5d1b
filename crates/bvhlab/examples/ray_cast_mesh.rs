//! Ray casting a triangle mesh: load an OBJ file, build the 4-wide BVH ([`Bvh4`]), cast one
//! ray per pixel of a small pinhole camera, and shade each hit with a normal interpolated
//! from the hit's barycentric coordinates `u`, `v`: Phong's smooth shading ("Illumination
//! for Computer Generated Pictures", CACM 1975), drawn as text.
//!
//! Run: `cargo run -p bvhlab --example ray_cast_mesh -- [MESH.obj]`. Without a file it casts
//! at a sphere of 528 triangles that it writes as OBJ text itself.
#![expect(clippy::print_stdout, reason = "an example that prints what it found")]

use std::error::Error;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::{Bvh4, Hit};

fn main() -> Result<(), Box<dyn Error>> {
    let (name, mesh) = match std::env::args().nth(1) {
        Some(path) => {
            let bytes = std::fs::read(&path).map_err(|e| format!("{path}: {e}"))?;
            let mesh = Mesh::from_obj(&bytes).map_err(|e| format!("{path}: {e}"))?;
            (path, mesh)
        }
        None => (
            "a sphere".to_owned(),
            Mesh::from_obj(uv_sphere_obj(24, 12).as_bytes())?,
        ),
    };
    let image = cast_camera_rays(&mesh, 64, 32)?;
    println!("{name}: {} triangles", mesh.len());
    println!(
        "{} of {} rays hit the mesh",
        image.hits(),
        image.pixels.len()
    );
    println!("{}", image.to_text());
    Ok(())
}

/// One pixel's answer: the hit (which triangle, `t`, barycentric `u`, `v`) and the
/// interpolated unit normal there, or `None` where the ray missed.
type Pixel = Option<(Hit, Vec3)>;

/// A `width` by `height` picture of the mesh, row by row from the top.
struct Image {
    width: usize,
    rays: Vec<Ray3>,
    pixels: Vec<Pixel>,
}

/// Looks at the mesh from the +z side and casts one ray per pixel.
///
/// # Errors
/// When the mesh has no triangles (there is nothing to frame).
fn cast_camera_rays(mesh: &Mesh, width: usize, height: usize) -> Result<Image, Box<dyn Error>> {
    if mesh.is_empty() {
        return Err("the mesh has no triangles".into());
    }
    // Build once, query many times: the build sorts the triangles into boxes (binned SAH),
    // and each ray then tests only the few triangles in the boxes it passes through.
    let tree = Bvh4::build(mesh.triangles());
    let normals = vertex_normals(mesh);

    // A pinhole camera: rays from the eye through points of a screen across the mesh's box.
    // Text characters are about twice as tall as wide, hence the `/ 2.0`.
    let bounds = mesh.bounds();
    let center = (bounds.min + bounds.max) * 0.5;
    let half_size = ((bounds.max - bounds.min).max_element() * 0.5).max(1e-3);
    let eye = center + Vec3::Z * half_size * 4.0;
    let aspect = width as f32 / height as f32 / 2.0;
    let mut rays = Vec::with_capacity(width * height);
    for row in 0..height {
        for column in 0..width {
            let x = ((column as f32 + 0.5) / width as f32 * 2.0 - 1.0) * aspect;
            let y = 1.0 - (row as f32 + 0.5) / height as f32 * 2.0;
            let on_screen = center + Vec3::new(x, y, 0.0) * half_size * 1.2;
            // `Ray3::through` refuses a zero or non-finite direction instead of returning
            // nonsense later.
            rays.push(Ray3::through(eye, on_screen)?);
        }
    }

    let pixels = rays
        .iter()
        .map(|ray| {
            let hit = tree.ray_first_hit(ray, f32::INFINITY)?;
            Some((hit, interpolated_normal(mesh, &normals, &hit)))
        })
        .collect();
    Ok(Image {
        width,
        rays,
        pixels,
    })
}

/// The normal at a hit, blended from its triangle's three vertex normals with the hit's
/// barycentric coordinates: the hit point is `(1 - u - v) a + u b + v c`, so the same
/// weights blend anything stored per vertex (normals here; texture coordinates, colours).
fn interpolated_normal(mesh: &Mesh, vertex_normals: &[Vec3], hit: &Hit) -> Vec3 {
    // `hit.prim` is the triangle's index in `mesh.triangles()`, and so in `mesh.indices()`.
    let [a, b, c] = mesh.indices()[hit.prim].map(|i| vertex_normals[i as usize]);
    (a * (1.0 - hit.u - hit.v) + b * hit.u + c * hit.v).normalize_or_zero()
}

/// One normal per vertex: the sum of its triangles' normals, each as long as twice the
/// triangle's area (so big triangles count more; Gouraud's averaging, weighted by area).
fn vertex_normals(mesh: &Mesh) -> Vec<Vec3> {
    let mut normals = vec![Vec3::ZERO; mesh.positions().len()];
    for (&[a, b, c], tri) in mesh.indices().iter().zip(mesh.triangles()) {
        let area_normal = (tri.b - tri.a).cross(tri.c - tri.a);
        for corner in [a, b, c] {
            normals[corner as usize] += area_normal;
        }
    }
    normals.iter().map(|n| n.normalize_or_zero()).collect()
}

impl Image {
    /// How many rays hit the mesh.
    fn hits(&self) -> usize {
        self.pixels.iter().flatten().count()
    }

    /// The picture as text: brighter characters where the surface faces the light
    /// (Lambert's cosine law), a space where the ray missed.
    fn to_text(&self) -> String {
        const RAMP: &[u8] = b".:-=+*#%@";
        let light = Vec3::new(-1.0, 1.0, 1.0).normalize();
        let mut text = String::new();
        for (i, (ray, pixel)) in self.rays.iter().zip(&self.pixels).enumerate() {
            let shade = pixel.map_or(' ', |(_, normal)| {
                // Seen from behind, a surface shows its other side: face the normal to the eye.
                let normal = if normal.dot(ray.dir()) > 0.0 {
                    -normal
                } else {
                    normal
                };
                let lambert = normal.dot(light).max(0.0);
                RAMP[(lambert * (RAMP.len() - 1) as f32).round() as usize] as char
            });
            text.push(shade);
            if (i + 1) % self.width == 0 {
                text.push('\n');
            }
        }
        text
    }
}

/// A unit sphere at the origin as OBJ text: `rings` bands of `segments` quads from pole to
/// pole, the two bands at the poles made of triangles that share the pole's vertex.
/// `Mesh::from_obj` splits each quad into two triangles.
fn uv_sphere_obj(segments: usize, rings: usize) -> String {
    use std::f32::consts::PI;
    use std::fmt::Write;
    let mut obj = String::from("# a UV sphere\nv 0 1 0\n");
    for ring in 1..rings {
        let polar = PI * ring as f32 / rings as f32;
        for segment in 0..segments {
            let azimuth = 2.0 * PI * segment as f32 / segments as f32;
            let (x, z) = (polar.sin() * azimuth.cos(), polar.sin() * azimuth.sin());
            let _ = writeln!(obj, "v {x} {} {z}", polar.cos());
        }
    }
    obj.push_str("v 0 -1 0\n");
    // OBJ counts vertices from 1: the north pole, the rings in between, the south pole.
    let vertex = |ring: usize, segment: usize| match ring {
        0 => 1,
        r if r == rings => 2 + (rings - 1) * segments,
        r => 2 + (r - 1) * segments + segment % segments,
    };
    // Each face counter-clockwise seen from outside, so its normal points out.
    for ring in 0..rings {
        for segment in 0..segments {
            let (a, b) = (vertex(ring, segment), vertex(ring, segment + 1));
            let (c, d) = (vertex(ring + 1, segment + 1), vertex(ring + 1, segment));
            if ring == 0 {
                let _ = writeln!(obj, "f {a} {c} {d}");
            } else if ring == rings - 1 {
                let _ = writeln!(obj, "f {a} {b} {d}");
            } else {
                let _ = writeln!(obj, "f {a} {b} {c} {d}");
            }
        }
    }
    obj
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::BruteForce;

    #[test]
    fn example_runs_and_agrees_with_brute_force() -> Result<(), Box<dyn Error>> {
        let mesh = Mesh::from_obj(uv_sphere_obj(16, 8).as_bytes())?;
        let image = cast_camera_rays(&mesh, 24, 12)?;
        // Brute force tests every triangle: the tree must give exactly its answers.
        let brute = BruteForce::build(mesh.triangles());
        for (ray, pixel) in image.rays.iter().zip(&image.pixels) {
            assert_eq!(
                pixel.map(|(hit, _)| hit),
                brute.ray_first_hit(ray, f32::INFINITY)
            );
        }
        // The sphere fills the middle of the picture, not its corners.
        let hits = image.hits();
        assert!(hits > 24 * 12 / 4 && hits < 24 * 12, "{hits} hits");
        for (ray, (hit, normal)) in image
            .rays
            .iter()
            .zip(&image.pixels)
            .filter_map(|(r, p)| Some((r, (*p)?)))
        {
            // On a unit sphere the true normal is the hit point itself; the interpolated
            // one comes close (the mesh is coarse), and faces the eye.
            let point = ray.at(hit.t);
            assert!(
                normal.angle_between(point.normalize()) < 0.1,
                "{normal} at {point}"
            );
            assert!(normal.dot(ray.dir()) < 0.0, "{normal} faces away");
        }
        assert_eq!(image.to_text().lines().count(), 12);
        Ok(())
    }
}
