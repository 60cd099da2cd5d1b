//! Lecture §2 on a mesh ("What happens in 3D?"): which part of the mesh the volumes are
//! fitted to, and the fits of that part, kept until the mesh, the part or the brush moves.
//! The fits themselves are the 2D half's [`Fits`], over 3D vertices.

use bvhlab::glam::Vec3;
use bvhlab::structure::RangeShape;
use bvhlab::{Mesh, Primitive, Sphere3, Triangle3};

use super::volumes::{Fits, VolumeToggles};

/// Which triangles of the mesh the volumes are fitted to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Part3d {
    /// Every triangle.
    #[default]
    Mesh,
    /// The brush: the triangles within the range query's radius of the query point (move
    /// the point with its gizmo or the keys, change the radius in "Ray & point").
    Brush,
}

impl Part3d {
    /// Its word in the page's address and a lesson's setup (`volumes=brush`).
    pub fn word(self) -> &'static str {
        match self {
            Self::Mesh => "mesh",
            Self::Brush => "brush",
        }
    }

    /// Its name in the panel and the status line.
    pub fn label(self) -> &'static str {
        match self {
            Self::Mesh => "the whole mesh",
            Self::Brush => "the brush (triangles within r of q)",
        }
    }
}

/// What the §2 panel shows in 3D.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Volumes3d {
    /// Draw the bounding volumes of the part (the panel's tables show when this is on).
    pub shown: bool,
    /// Which volumes are drawn.
    pub toggles: VolumeToggles,
    /// Which triangles they are fitted to.
    pub part: Part3d,
    /// Draw the slab test of the ray against the part's AABB.
    pub slab_test: bool,
}

/// The triangles of `mesh` that `part` selects, by index, ascending: for the brush, those
/// the range query's ball of `radius` about `point` meets, by the core's own test (none
/// without a point).
pub fn selected_triangles(mesh: &Mesh, part: Part3d, point: Option<Vec3>, radius: f32) -> Vec<u32> {
    let triangles = mesh.triangles();
    match part {
        Part3d::Mesh => (0..triangles.len() as u32).collect(),
        Part3d::Brush => {
            let Some(center) = point.filter(|q| q.is_finite()) else {
                return Vec::new();
            };
            let ball = RangeShape::Ball(Sphere3 { center, radius });
            (0..triangles.len() as u32)
                .filter(|&i| ball.overlaps_primitive(&triangles[i as usize]))
                .collect()
        }
    }
}

/// The point of `triangles` closest to `point` (by each triangle's own projection, as
/// brute force answers); `None` for no finite triangle.
pub fn closest_on(triangles: &[Triangle3], point: Vec3) -> Option<Vec3> {
    triangles
        .iter()
        .filter(|t| t.has_finite_coordinates())
        .map(|t| t.project_point(point))
        .min_by(|p, q| {
            p.distance_squared(point)
                .total_cmp(&q.distance_squared(point))
        })
}

/// The vertices of the triangles `selected`, each once (a vertex shared by six triangles
/// would weigh six times in the PCA's covariance otherwise), in the mesh's order; non-finite
/// ones are left out, as the fits would skip them.
pub fn selected_vertices(mesh: &Mesh, selected: &[u32]) -> Vec<Vec3> {
    let positions = mesh.positions();
    let mut used = vec![false; positions.len()];
    for &t in selected {
        if let Some(corners) = mesh.indices().get(t as usize) {
            for &v in corners {
                if let Some(u) = used.get_mut(v as usize) {
                    *u = true;
                }
            }
        }
    }
    positions
        .iter()
        .zip(used)
        .filter(|(p, used)| *used && p.is_finite())
        .map(|(p, _)| *p)
        .collect()
}

/// What the fits were made from: the mesh's revision, the part, and (for the brush) the
/// point and radius, bit for bit.
type FitsKey = (u64, Part3d, Option<[u32; 3]>, u32);

/// The part's triangles and their fits, made again only when what they depend on changes.
#[derive(Clone, Debug, Default)]
pub struct PartFits {
    key: Option<FitsKey>,
    /// Counts the times the part was selected again: what is derived from the part (the
    /// collision query) is made again when it changes.
    pub generation: u64,
    /// The triangles selected, by index.
    pub triangles: Vec<u32>,
    /// How many distinct vertices they have.
    pub vertices: usize,
    /// The fits of those vertices (`None` when there are none).
    pub fits: Option<Fits<Vec3>>,
}

impl PartFits {
    /// Brings the fits up to date with the mesh (of `revision`), `part`, `point` and
    /// `radius`.
    pub fn refresh(
        &mut self,
        mesh: &Mesh,
        revision: u64,
        part: Part3d,
        point: Option<Vec3>,
        radius: f32,
    ) {
        let key = match part {
            Part3d::Mesh => (revision, part, None, 0),
            Part3d::Brush => (
                revision,
                part,
                point.map(|p| p.to_array().map(f32::to_bits)),
                radius.to_bits(),
            ),
        };
        if self.key == Some(key) {
            return;
        }
        self.key = Some(key);
        self.generation += 1;
        self.triangles = selected_triangles(mesh, part, point, radius);
        let vertices = selected_vertices(mesh, &self.triangles);
        self.vertices = vertices.len();
        self.fits = Fits::of(&vertices);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_triangles() -> Mesh {
        Mesh::from_indexed(
            vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::new(10.0, 0.0, 0.0),
                Vec3::new(11.0, 0.0, 0.0),
                Vec3::new(10.0, 1.0, 0.0),
                Vec3::new(99.0, 99.0, 99.0),
            ],
            vec![[0, 1, 2], [3, 4, 5]],
        )
        .expect("mesh")
    }

    #[test]
    fn the_brush_takes_the_triangles_within_its_radius_and_their_vertices_once() {
        let mesh = two_triangles();
        assert_eq!(
            selected_triangles(&mesh, Part3d::Mesh, None, 0.0),
            vec![0, 1]
        );
        assert!(selected_triangles(&mesh, Part3d::Brush, None, 5.0).is_empty());
        let near_first = Some(Vec3::new(0.2, 0.2, 1.0));
        assert_eq!(
            selected_triangles(&mesh, Part3d::Brush, near_first, 1.0),
            vec![0]
        );
        assert!(selected_triangles(&mesh, Part3d::Brush, near_first, 0.9).is_empty());
        // The unused vertex (99, 99, 99) is in no fit.
        assert_eq!(selected_vertices(&mesh, &[0, 1]).len(), 6);
        assert_eq!(
            selected_vertices(&mesh, &[1]),
            vec![
                Vec3::new(10.0, 0.0, 0.0),
                Vec3::new(11.0, 0.0, 0.0),
                Vec3::new(10.0, 1.0, 0.0)
            ]
        );
    }

    #[test]
    fn fits_are_made_again_only_when_what_they_depend_on_changes() {
        let mesh = two_triangles();
        let mut fits = PartFits::default();
        fits.refresh(&mesh, 1, Part3d::Mesh, None, 1.0);
        assert_eq!(fits.triangles, vec![0, 1]);
        let aabb = fits.fits.as_ref().expect("fits").aabb;
        assert_eq!(aabb.max, Vec3::new(11.0, 1.0, 0.0));
        // The point does not matter to the whole mesh.
        fits.refresh(&mesh, 1, Part3d::Mesh, Some(Vec3::ONE), 1.0);
        assert_eq!(fits.triangles, vec![0, 1]);
        fits.refresh(
            &mesh,
            1,
            Part3d::Brush,
            Some(Vec3::new(10.5, 0.2, 0.0)),
            0.5,
        );
        assert_eq!(fits.triangles, vec![1]);
        fits.refresh(
            &mesh,
            1,
            Part3d::Brush,
            Some(Vec3::new(50.0, 0.0, 0.0)),
            0.5,
        );
        assert!(fits.triangles.is_empty());
        assert!(fits.fits.is_none(), "no triangles, no fits");
    }
}
