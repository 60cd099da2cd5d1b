//! The scenes of the side-by-side comparison with peer libraries: the three real meshes of
//! `../shared/data/meshes` (Stanford bunny, dragon, ogre), a torus of about 420k triangles and a
//! displaced sphere of about 2M triangles, all deterministic.

use bvhlab::glam::Vec3;
use bvhlab::{Mesh, Triangle3};

use crate::rng::SplitMix64;
use crate::workload::unit_vector;
use crate::{shared_mesh, torus_with};

/// A scene of the comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneId {
    /// `stanford-bunny.obj`, 69,451 triangles, about 0.15 units wide.
    Bunny,
    /// `dragon.obj`, 100,000 triangles.
    Dragon,
    /// `ogre.obj`, 124,008 triangles (the table).
    Ogre,
    /// A torus of about 420k triangles ([`torus_with`]).
    Torus,
    /// A displaced sphere of about 2M triangles ([`displaced_sphere`]).
    DisplacedSphere,
}

impl SceneId {
    /// Every scene, smallest real mesh first.
    pub const ALL: [Self; 5] = [
        Self::Bunny,
        Self::Dragon,
        Self::Ogre,
        Self::Torus,
        Self::DisplacedSphere,
    ];

    /// The scene's short name (for tables and command lines).
    pub fn name(self) -> &'static str {
        match self {
            Self::Bunny => "bunny",
            Self::Dragon => "dragon",
            Self::Ogre => "ogre",
            Self::Torus => "torus-420k",
            Self::DisplacedSphere => "sphere-2m",
        }
    }

    /// The OBJ file of a real mesh in `../shared/data/meshes`, `None` for generated scenes.
    pub fn obj_file(self) -> Option<&'static str> {
        match self {
            Self::Bunny => Some("stanford-bunny.obj"),
            Self::Dragon => Some("dragon.obj"),
            Self::Ogre => Some("ogre.obj"),
            Self::Torus | Self::DisplacedSphere => None,
        }
    }

    /// The scene's triangles: generated, or read from the shared meshes.
    ///
    /// # Errors
    /// A message when a real mesh is missing or does not parse.
    pub fn triangles(self) -> Result<Vec<Triangle3>, String> {
        match self {
            Self::Torus => Ok(torus_with(420_000)),
            Self::DisplacedSphere => Ok(displaced_sphere(2_000_000, 0x5EED_2026)),
            real => {
                let file = real.obj_file().unwrap_or_default();
                let path = shared_mesh(file)
                    .ok_or_else(|| format!("{file} is not in ../shared/data/meshes"))?;
                let bytes = std::fs::read(&path).map_err(|e| format!("{file}: {e}"))?;
                triangles_from_obj(&bytes).map_err(|e| format!("{file}: {e}"))
            }
        }
    }
}

/// The triangles of an OBJ file, read with the core's reader.
///
/// # Errors
/// The reader's message when the file does not parse.
pub fn triangles_from_obj(bytes: &[u8]) -> Result<Vec<Triangle3>, String> {
    Mesh::from_obj(bytes)
        .map(|mesh| mesh.triangles().to_vec())
        .map_err(|e| e.to_string())
}

/// A sphere of radius 1 with about `n` triangles (a latitude-longitude grid), its radius
/// displaced by the sum of eight random waves `0.03 · sin(k · p + φ)` (directions, frequencies
/// 3-15 and phases drawn from `seed`): a lumpy surface with no two triangles alike.
pub fn displaced_sphere(n: usize, seed: u64) -> Vec<Triangle3> {
    let mut rng = SplitMix64::new(seed);
    let waves: Vec<(Vec3, f32)> = (0..8)
        .map(|_| {
            let k = unit_vector(&mut rng) * (3.0 + 12.0 * rng.next_f32());
            (k, std::f32::consts::TAU * rng.next_f32())
        })
        .collect();
    let radius = |p: Vec3| {
        1.0 + waves
            .iter()
            .map(|(k, phase)| 0.03 * (k.dot(p) + phase).sin())
            .sum::<f32>()
    };
    // 2 · rings · sectors triangles, with sectors = 2 · rings (square-ish cells).
    let rings = ((n as f32 / 4.0).sqrt() as usize).max(2);
    let sectors = 2 * rings;
    let vertex = |i: usize, j: usize| {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        let phi = std::f32::consts::TAU * (j % sectors) as f32 / sectors as f32;
        let p = Vec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        );
        p * radius(p)
    };
    let grid: Vec<Vec3> = (0..=rings)
        .flat_map(|i| (0..sectors).map(move |j| (i, j)))
        .map(|(i, j)| vertex(i, j))
        .collect();
    let at = |i: usize, j: usize| grid[i * sectors + j % sectors];
    let mut tris = Vec::with_capacity(2 * rings * sectors);
    for i in 0..rings {
        for j in 0..sectors {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            // The cells at the poles have two corners at the pole: keep their one real triangle.
            if i + 1 < rings {
                tris.push(Triangle3::new(a, b, c));
            }
            if i > 0 {
                tris.push(Triangle3::new(a, c, d));
            }
        }
    }
    tris
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::workload::bounds;

    #[test]
    fn displaced_sphere_has_about_the_asked_size_and_no_degenerate_triangle() {
        let tris = displaced_sphere(20_000, 1);
        assert!((19_000..=20_500).contains(&tris.len()), "{}", tris.len());
        assert!(tris.iter().all(|t| !t.is_degenerate()));
        // Lumps of at most 8 · 0.03 on the unit sphere.
        let (lo, hi) = bounds(&tris);
        assert!(lo.min_element() > -1.25 && hi.max_element() < 1.25);
    }
}
