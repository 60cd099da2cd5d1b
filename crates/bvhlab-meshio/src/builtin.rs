//! The meshes the lab offers without a file: simple shapes with known answers, a scanned
//! model, one large enough to time a structure's build at a million triangles, and one that
//! moves ([`deforms`], [`make_at`]), for refitting a tree every frame.
//!
//! Each is listed once in [`list`] (what a menu shows) and made by [`make`]. The random ones
//! take a fixed seed, so every student, test and benchmark sees the same triangles; the
//! generators are public to make others (other sizes, other seeds).

mod bunny;
mod cube;
mod lumpy_sphere;
mod random;
mod tetrahedra;
mod torus;
mod twisting_torus;
mod uv_sphere;

use bvhlab::Mesh;

pub use self::cube::cube;
pub use self::lumpy_sphere::lumpy_sphere;
pub use self::tetrahedra::tetrahedra;
pub use self::torus::torus;
pub use self::twisting_torus::twisting_torus;
pub use self::uv_sphere::uv_sphere;

/// A built-in mesh, as a menu shows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Builtin {
    /// The name [`make`] takes (and a share link can carry): lowercase, no spaces.
    pub slug: &'static str,
    /// The name shown to the student.
    pub name: &'static str,
    /// One sentence on what it has and why it is in the lab.
    pub about: &'static str,
}

/// The seed of the built-in tetrahedra cloud.
pub const TETRAHEDRA_SEED: u64 = 418;
/// The seed of the built-in lumpy sphere.
pub const LUMPY_SPHERE_SEED: u64 = 2504;

const BUILTINS: [Builtin; 7] = [
    Builtin {
        slug: "cube",
        name: "Cube",
        about: "12 triangles with axis-aligned faces and edges: rays along an axis graze them, \
                the slab test's hard cases",
    },
    Builtin {
        slug: "sphere",
        name: "UV sphere",
        about: "960 triangles on 16 bands of 32 segments: even in the middle, long and thin \
                at the poles",
    },
    Builtin {
        slug: "torus",
        name: "Torus",
        about: "2,304 triangles around a hole: rays through the middle hit nothing, though \
                they pass through the bounding box",
    },
    Builtin {
        slug: "tetrahedra",
        name: "Tetrahedra cloud",
        about: "500 small tetrahedra (2,000 triangles) scattered at random: many separate \
                objects whose boxes overlap",
    },
    Builtin {
        slug: "bunny",
        name: "Stanford bunny",
        about: "3,674 triangles of a scanned clay bunny (Stanford 3D Scanning Repository): \
                a real model with uneven detail",
    },
    Builtin {
        slug: "lumpy-sphere",
        name: "Lumpy sphere (1M triangles)",
        about: "1,000,000 triangles: a sphere pushed in and out by random waves, to time \
                builds and queries at scale",
    },
    Builtin {
        slug: TWISTING_TORUS,
        name: "Twisting torus (moves)",
        about: "4,096 triangles of a flattened torus that twists and ripples as time passes: \
                the tree is refitted (or rebuilt) every frame",
    },
];

/// The slug of the built-in mesh that moves.
pub const TWISTING_TORUS: &str = "twisting-torus";

/// The twisting torus's steps around its axis and around its tube.
const TWISTING_TORUS_GRID: (u32, u32) = (64, 32);

/// Every built-in mesh, in menu order.
pub fn list() -> &'static [Builtin] {
    &BUILTINS
}

/// The built-in mesh named `slug`, or `None` for a slug [`list`] does not have.
///
/// The meshes are made on each call (the largest in well under a second natively); keep the
/// result rather than calling again.
pub fn make(slug: &str) -> Option<Mesh> {
    match slug {
        "cube" => Some(cube()),
        "sphere" => Some(uv_sphere(32, 16)),
        "torus" => Some(torus(48, 24, 0.35)),
        "tetrahedra" => Some(tetrahedra(500, TETRAHEDRA_SEED)),
        "bunny" => Some(bunny::bunny()),
        "lumpy-sphere" => Some(lumpy_sphere(1000, 501, LUMPY_SPHERE_SEED)),
        _ => make_at(slug, 0.0),
    }
}

/// Whether the built-in mesh `slug` moves: [`make_at`] gives it at any time.
pub fn deforms(slug: &str) -> bool {
    slug == TWISTING_TORUS
}

/// The built-in mesh `slug` that moves, `seconds` into its motion (`None` for a slug that
/// does not move). A pure function of the time: the same triangles for the same time, with
/// the same indices at every time (only the vertices move), so a tree built on one time can be
/// refitted to another.
pub fn make_at(slug: &str, seconds: f64) -> Option<Mesh> {
    let (rings, sides) = TWISTING_TORUS_GRID;
    deforms(slug).then(|| twisting_torus(rings, sides, seconds))
}

/// The mesh of generated vertices and triangles. Generators make only finite vertices and
/// indices in range; should one ever fail that, an empty mesh shows it in every test.
fn indexed(positions: Vec<bvhlab::glam::Vec3>, indices: Vec<[u32; 3]>) -> Mesh {
    Mesh::from_indexed(positions, indices).unwrap_or_default()
}
