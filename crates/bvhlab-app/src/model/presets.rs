//! Ready-made scenes: the lecture's figures and random scenes of several sizes.

use bvhlab::glam::Vec2;
use bvhlab::structure::SplitMethod;

use super::scene::{Scene, Shape, ShapeKind};
use super::structures::{BuildSettings, KdSplit, StructureKind};

/// The preset scenes, in menu order.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Preset {
    /// §2: one elongated, tilted, lopsided object, where the spheres (centroid, Ritter,
    /// Welzl), AABB, OBB and hull all differ.
    BoundingVolumes,
    /// §3, uniform grid: a long triangle that lands in several cells ("Duplicate Triangle").
    DuplicateTriangle,
    /// §3: an AABB tree on a handful of shapes, as the lecture draws a BVH: the scene the lab
    /// opens with (small enough to read every box and node).
    #[default]
    BvhHandful,
    /// §3: a k-d tree on a handful of shapes.
    KdHandful,
    /// §3: a quadtree on a handful of shapes.
    QuadtreeHandful,
    /// §3: shapes that drift and turn while playing, an AABB tree refitted beside one rebuilt
    /// every frame ([`drifting_shapes`]).
    Drifting,
    /// 200 random segments.
    RandomSegments,
    /// 300 random points.
    RandomPoints,
    /// 10,000 random segments: the lab must stay smooth.
    TenThousand,
}

impl Preset {
    /// Every preset, in menu order.
    pub const ALL: [Self; 9] = [
        Self::BoundingVolumes,
        Self::DuplicateTriangle,
        Self::BvhHandful,
        Self::KdHandful,
        Self::QuadtreeHandful,
        Self::Drifting,
        Self::RandomSegments,
        Self::RandomPoints,
        Self::TenThousand,
    ];

    /// A name for the menu.
    pub fn label(self) -> &'static str {
        match self {
            Self::BoundingVolumes => "Bounding volumes compared (§2)",
            Self::DuplicateTriangle => "Duplicate triangle in a grid (§3)",
            Self::BvhHandful => "AABB tree on a handful of shapes (§3)",
            Self::KdHandful => "k-d tree on a handful of shapes (§3)",
            Self::QuadtreeHandful => "Quadtree on a handful of shapes (§3)",
            Self::Drifting => "Shapes that drift and turn: refit against rebuild (§3)",
            Self::RandomSegments => "200 random segments",
            Self::RandomPoints => "300 random points",
            Self::TenThousand => "10,000 random segments",
        }
    }

    /// A short name for links (`?preset=...` in the page's address).
    pub fn slug(self) -> &'static str {
        match self {
            Self::BoundingVolumes => "bounding-volumes",
            Self::DuplicateTriangle => "duplicate-triangle",
            Self::BvhHandful => "aabb-tree",
            Self::KdHandful => "kd-tree",
            Self::QuadtreeHandful => "quadtree",
            Self::Drifting => "drifting-shapes",
            Self::RandomSegments => "random-segments",
            Self::RandomPoints => "random-points",
            Self::TenThousand => "10k",
        }
    }

    /// The preset with this [`slug`](Self::slug).
    pub fn from_slug(slug: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.slug() == slug)
    }

    /// The scene, and the structure settings it is best seen with.
    pub fn build(self) -> (Scene, BuildSettings) {
        let settings = BuildSettings::default();
        match self {
            Self::BoundingVolumes => (Scene::from_shapes(vec![tilted_blob()]), settings),
            Self::DuplicateTriangle => (
                duplicate_triangle(),
                BuildSettings {
                    kind: StructureKind::Grid,
                    grid_cells: 4,
                    ..settings
                },
            ),
            Self::BvhHandful => (
                handful(),
                BuildSettings {
                    kind: StructureKind::AabbTree,
                    leaf_size: 1,
                    ..settings
                },
            ),
            Self::KdHandful => (
                handful(),
                BuildSettings {
                    kind: StructureKind::KdTree,
                    kd_split: KdSplit::MedianRoundRobin,
                    leaf_size: 1,
                    ..settings
                },
            ),
            Self::QuadtreeHandful => (
                handful(),
                BuildSettings {
                    kind: StructureKind::Quadtree,
                    leaf_size: 1,
                    ..settings
                },
            ),
            Self::Drifting => (
                Scene::from_shapes(drifting_shapes(0.0)),
                BuildSettings {
                    kind: StructureKind::AabbTree,
                    bvh_split: SplitMethod::BinnedSah,
                    leaf_size: 2,
                    ..settings
                },
            ),
            Self::RandomSegments => (random_segments(200, 20.0, 1.5, 1), settings),
            Self::RandomPoints => (random_points(300, 20.0, 2), settings),
            Self::TenThousand => (random_segments(10_000, 100.0, 1.5, 3), settings),
        }
    }
}

/// A small deterministic generator (`SplitMix64`, Steele, Lea and Flood, OOPSLA 2014): presets
/// must look the same on every machine and every visit.
struct SplitMix(u64);

impl SplitMix {
    fn next_unit(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next_unit()
    }
}

fn shape(kind: ShapeKind, points: &[[f32; 2]]) -> Shape {
    Shape {
        kind,
        points: points.iter().map(|&[x, y]| Vec2::new(x, y)).collect(),
    }
}

/// A lopsided, tilted wedge: a round head with many vertices, and a wide, flat tail ending
/// in two corners. Its AABB is loose and its OBB tight. The three spheres of the lecture
/// differ (issue 29: on a teardrop, Ritter's sphere was Welzl's): the centroid sphere is
/// centred among the head's vertices, so its radius reaches out to the tail's corners and it
/// is the loosest; Ritter's starts from the two tail corners' circle and grows to take in the
/// head; Welzl's, the smallest, rests on the head and both corners.
fn tilted_blob() -> Shape {
    let (sin, cos) = 0.5f32.sin_cos();
    let tail = [Vec2::new(7.0, -4.0), Vec2::new(7.0, 4.0)];
    // The head: an arc of radius 2.5 around (-4, 0), from 70° round the back to 290°.
    let head = (0..=8).map(|i| {
        let angle = (70.0 + 220.0 * i as f32 / 8.0).to_radians();
        Vec2::new(-4.0, 0.0) + Vec2::from_angle(angle) * 2.5
    });
    let points = tail
        .into_iter()
        .chain(head)
        .map(|p| Vec2::new(p.x * cos - p.y * sin, p.x * sin + p.y * cos))
        .collect();
    Shape {
        kind: ShapeKind::Polygon,
        points,
    }
}

fn duplicate_triangle() -> Scene {
    Scene::from_shapes(vec![
        // The long triangle crossing several cells.
        shape(ShapeKind::Polygon, &[[0.5, 0.5], [7.5, 4.0], [2.0, 3.0]]),
        shape(ShapeKind::Polygon, &[[5.5, 0.5], [7.5, 0.6], [6.4, 1.6]]),
        shape(ShapeKind::Polygon, &[[0.4, 6.0], [1.6, 5.8], [1.0, 7.5]]),
        shape(ShapeKind::Polygon, &[[5.6, 6.2], [7.6, 7.6], [5.2, 7.4]]),
    ])
}

fn handful() -> Scene {
    Scene::from_shapes(vec![
        shape(ShapeKind::Polygon, &[[1.0, 1.0], [3.0, 1.2], [2.0, 2.6]]),
        shape(
            ShapeKind::Polygon,
            &[[6.0, 0.8], [7.4, 1.0], [7.0, 2.2], [6.2, 2.0]],
        ),
        shape(ShapeKind::Segment, &[[4.0, 4.0], [5.5, 5.2]]),
        shape(ShapeKind::Polyline, &[[0.8, 6.0], [2.0, 7.2], [3.2, 6.4]]),
        shape(ShapeKind::Polygon, &[[8.0, 6.0], [9.4, 6.6], [8.6, 7.8]]),
        shape(ShapeKind::Segment, &[[1.2, 3.8], [2.2, 4.6]]),
        shape(ShapeKind::Points, &[[5.0, 8.4], [6.2, 8.0], [9.0, 3.5]]),
        shape(ShapeKind::Polygon, &[[7.6, 4.0], [8.6, 4.2], [8.2, 5.0]]),
    ])
}

/// How many triangles drift in [`drifting_shapes`].
pub const DRIFTING: usize = 48;
/// The side of the square they drift in.
const DRIFT_BOX: f32 = 20.0;

/// The drifting preset's shapes `t` seconds into the animation: [`DRIFTING`] small
/// triangles, each with its own (seeded) start, velocity and spin, bouncing inside a square
/// of side 20. The same `t` gives the same shapes on every machine.
pub fn drifting_shapes(t: f32) -> Vec<Shape> {
    let mut rng = SplitMix(7);
    // Where `x` is after bouncing between 0 and the box's side.
    let bounce = |x: f32| {
        let m = x.rem_euclid(2.0 * DRIFT_BOX);
        if m <= DRIFT_BOX {
            m
        } else {
            2.0 * DRIFT_BOX - m
        }
    };
    (0..DRIFTING)
        .map(|_| {
            let start = Vec2::new(
                rng.range(1.0, DRIFT_BOX - 1.0),
                rng.range(1.0, DRIFT_BOX - 1.0),
            );
            let velocity =
                Vec2::from_angle(rng.range(0.0, std::f32::consts::TAU)) * rng.range(0.8, 3.0);
            let spin = rng.range(-2.0, 2.0);
            let size = rng.range(0.5, 1.1);
            let turn = rng.range(0.0, std::f32::consts::TAU) + spin * t;
            let p = start + velocity * t;
            let centre = Vec2::new(bounce(p.x), bounce(p.y));
            let points = [0.0f32, 2.3, 4.1]
                .into_iter()
                .map(|a| centre + Vec2::from_angle(turn + a) * size)
                .collect();
            Shape {
                kind: ShapeKind::Polygon,
                points,
            }
        })
        .collect()
}

/// `n` segments of length up to `length` in a square of side `extent`.
pub fn random_segments(n: usize, extent: f32, length: f32, seed: u64) -> Scene {
    let mut rng = SplitMix(seed);
    let shapes = (0..n)
        .map(|_| {
            let a = Vec2::new(rng.range(0.0, extent), rng.range(0.0, extent));
            let angle = rng.range(0.0, std::f32::consts::TAU);
            let len = rng.range(0.2, 1.0) * length;
            let b = a + Vec2::from_angle(angle) * len;
            Shape {
                kind: ShapeKind::Segment,
                points: vec![a, b],
            }
        })
        .collect();
    Scene::from_shapes(shapes)
}

/// One cloud of `n` points in a square of side `extent`.
pub fn random_points(n: usize, extent: f32, seed: u64) -> Scene {
    let mut rng = SplitMix(seed);
    let points = (0..n)
        .map(|_| Vec2::new(rng.range(0.0, extent), rng.range(0.0, extent)))
        .collect();
    Scene::from_shapes(vec![Shape {
        kind: ShapeKind::Points,
        points,
    }])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid_and_deterministic() {
        for preset in Preset::ALL {
            let (a, _) = preset.build();
            let (b, _) = preset.build();
            assert!(!a.shapes().is_empty(), "{preset:?}");
            assert_eq!(a.shapes(), b.shapes(), "{preset:?}");
            for s in a.shapes() {
                Shape::new(s.kind, s.points.clone()).expect("preset shapes are valid");
            }
        }
        assert_eq!(
            Preset::TenThousand.build().0.primitives().segments.len(),
            10_000
        );
    }

    #[test]
    fn the_bounding_volumes_presets_three_spheres_visibly_differ() {
        let (scene, _) = Preset::BoundingVolumes.build();
        let fits = super::super::volumes::Fits::of(&scene.vertices(&[])).expect("a shape");
        let (centroid, ritter, welzl) =
            (fits.centroid.radius, fits.ritter.radius, fits.welzl.radius);
        assert!(
            centroid >= 1.15 * welzl,
            "the centroid sphere ({centroid}) is at least 15 % larger than Welzl's ({welzl})"
        );
        assert!(
            centroid >= 1.15 * ritter,
            "{centroid} against Ritter's {ritter}"
        );
        assert!(
            ritter >= 1.05 * welzl,
            "Ritter's sphere ({ritter}) is at least 5 % larger than Welzl's ({welzl})"
        );
    }
}
