//! The 3D view's renderer on a real (software) GPU: fixed scenes compared with reference
//! images in `tests/reference/`, and properties checked without references (the background at
//! the corners, the mesh's colour where it faces the eye, the depth test hiding a line behind
//! the mesh but not an overlay, x-ray showing what is inside, highlights winning over their
//! triangles, a mesh cut across small buffers drawing the same).
//!
//! Natively these run on whatever adapter wgpu finds; on machines without a GPU that is Mesa's
//! lavapipe. Without any adapter the tests print why and pass, unless `BVHLAB_REQUIRE_GPU=1`
//! (set in CI), which makes that a failure. `BVHLAB_BLESS=1` rewrites the references.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab_app::model::orbit_camera::OrbitCamera;
use bvhlab_app::render3d::gpu::{
    ColorTriangle, DEFAULT_SAMPLES, EguiTarget, Frame3d, Line3d, Marker, MeshData, MeshUploadError,
    OffscreenError, Renderer3d, RgbaImage, headless_device, headless_device_with_limits,
    install_in, paint_3d, read_back, render_and_read, render_offscreen,
};

/// Every scene's size: small enough to keep the references small, large enough for detail.
const SIZE: [u32; 2] = [320, 240];
const BACKGROUND: [f32; 4] = [0.1, 0.1, 0.12, 1.0];
const SPHERE_COLOR: [f32; 4] = [0.45, 0.62, 0.85, 1.0];

// ---------------------------------------------------------------------------------------
// Scenes
// ---------------------------------------------------------------------------------------

/// A revision no other mesh of this process has (a renderer takes equal revisions to be the
/// same mesh).
fn next_revision() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(1);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

fn camera() -> OrbitCamera {
    OrbitCamera {
        target: Vec3::ZERO,
        distance: 3.2,
        yaw: 0.6,
        pitch: 0.35,
        fov_y: 45f32.to_radians(),
    }
}

/// A `rows × cols` grid mapped onto a surface by `point(u, v)` (u, v in 0..1), every triangle
/// turned to face `outward(centroid)`; zero-area triangles (at a sphere's poles) are left out.
fn grid_mesh(
    rows: u32,
    cols: u32,
    point: impl Fn(f32, f32) -> Vec3,
    outward: impl Fn(Vec3) -> Vec3,
) -> MeshData {
    let mut positions = Vec::new();
    for i in 0..=rows {
        for j in 0..=cols {
            positions.push(point(i as f32 / rows as f32, j as f32 / cols as f32).to_array());
        }
    }
    let at = |i: u32, j: u32| i * (cols + 1) + j;
    let mut indices = Vec::new();
    for i in 0..rows {
        for j in 0..cols {
            for [a, b, c] in [
                [at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                [at(i, j), at(i + 1, j + 1), at(i, j + 1)],
            ] {
                let [pa, pb, pc] = [a, b, c].map(|v| Vec3::from(positions[v as usize]));
                let normal = (pb - pa).cross(pc - pa);
                if normal.length() < 1e-9 {
                    continue;
                }
                let centroid = (pa + pb + pc) / 3.0;
                let facing_out = normal.dot(outward(centroid)) > 0.0;
                indices.push(if facing_out { [a, b, c] } else { [a, c, b] });
            }
        }
    }
    MeshData {
        revision: next_revision(),
        positions,
        indices,
    }
}

fn sphere(radius: f32, stacks: u32, slices: u32) -> MeshData {
    grid_mesh(
        stacks,
        slices,
        |u, v| {
            let (theta, phi) = (u * std::f32::consts::PI, v * std::f32::consts::TAU);
            Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ) * radius
        },
        |p| p,
    )
}

fn torus(ring: f32, tube: f32, rings: u32, sides: u32) -> MeshData {
    grid_mesh(
        rings,
        sides,
        |u, v| {
            let (phi, theta) = (u * std::f32::consts::TAU, v * std::f32::consts::TAU);
            let r = ring + tube * theta.cos();
            Vec3::new(r * phi.cos(), tube * theta.sin(), r * phi.sin())
        },
        move |p| p - Vec3::new(p.x, 0.0, p.z).normalize() * ring,
    )
}

fn cube(half: f32) -> MeshData {
    let positions = (0..8)
        .map(|i| {
            let pick = |bit: u32| if i & bit == 0 { -half } else { half };
            [pick(1), pick(2), pick(4)]
        })
        .collect::<Vec<_>>();
    // Each face as a quad of corner numbers (bit 1 = +x, 2 = +y, 4 = +z), turned outwards.
    let faces = [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ];
    let mut indices = Vec::new();
    for [a, b, c, d] in faces {
        for [p, q, r] in [[a, b, c], [a, c, d]] {
            let [pp, pq, pr] = [p, q, r].map(|v: u32| Vec3::from(positions[v as usize]));
            let out = (pq - pp).cross(pr - pp).dot(pp + pq + pr) > 0.0;
            indices.push(if out { [p, q, r] } else { [p, r, q] });
        }
    }
    MeshData {
        revision: next_revision(),
        positions,
        indices,
    }
}

fn line(a: Vec3, b: Vec3, color: [f32; 4], width_px: f32) -> Line3d {
    Line3d {
        a: a.to_array(),
        b: b.to_array(),
        color,
        width_px,
    }
}

/// The twelve edges of the box `min..max`.
fn box_edges(min: Vec3, max: Vec3, color: [f32; 4], width_px: f32) -> Vec<Line3d> {
    let corner = |i: u32| {
        Vec3::new(
            if i & 1 == 0 { min.x } else { max.x },
            if i & 2 == 0 { min.y } else { max.y },
            if i & 4 == 0 { min.z } else { max.z },
        )
    };
    let mut edges = Vec::new();
    for i in 0..8u32 {
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                edges.push(line(corner(i), corner(i | bit), color, width_px));
            }
        }
    }
    edges
}

/// The quad `a b c d` as two triangles.
fn quad(corners: [Vec3; 4], color: [f32; 4]) -> [ColorTriangle; 2] {
    let [a, b, c, d] = corners.map(|v| v.to_array());
    [
        ColorTriangle { a, b, c, color },
        ColorTriangle {
            a,
            b: c,
            c: d,
            color,
        },
    ]
}

fn frame_with(mesh: MeshData, mesh_color: [f32; 4]) -> Frame3d {
    Frame3d {
        camera: camera(),
        background: BACKGROUND,
        mesh: Some(Arc::new(mesh)),
        mesh_color,
        ..Frame3d::default()
    }
}

/// Scene (a): an opaque UV sphere.
fn sphere_scene() -> Frame3d {
    frame_with(sphere(1.0, 24, 48), SPHERE_COLOR)
}

/// Scene (b): a cube in x-ray holding two child boxes (thick lines) and the split plane
/// between them (translucent).
fn xray_scene() -> Frame3d {
    let mut frame = frame_with(cube(1.0), [0.75, 0.78, 0.82, 0.3]);
    frame.camera.distance = 4.8;
    frame.lines = box_edges(
        Vec3::splat(-1.0),
        Vec3::splat(1.0),
        [0.9, 0.9, 0.9, 1.0],
        2.0,
    );
    frame.lines.extend(box_edges(
        Vec3::new(-0.9, -0.8, -0.7),
        Vec3::new(0.05, 0.6, 0.8),
        [1.0, 0.55, 0.1, 1.0],
        3.0,
    ));
    frame.lines.extend(box_edges(
        Vec3::new(0.15, -0.9, -0.85),
        Vec3::new(0.9, 0.9, 0.4),
        [0.2, 0.8, 1.0, 1.0],
        3.0,
    ));
    let x = 0.1;
    frame.triangles = quad(
        [
            Vec3::new(x, -1.2, -1.2),
            Vec3::new(x, 1.2, -1.2),
            Vec3::new(x, 1.2, 1.2),
            Vec3::new(x, -1.2, 1.2),
        ],
        [1.0, 0.85, 0.2, 0.35],
    )
    .to_vec();
    frame
}

/// The first triangle of `mesh` the ray `origin + t·dir` hits, and `t`: brute force over
/// every triangle with the Möller–Trumbore test (Möller and Trumbore, "Fast, minimum storage
/// ray/triangle intersection", JGT 1997).
fn first_hit(mesh: &MeshData, origin: Vec3, dir: Vec3) -> Option<(u32, f32)> {
    let mut best: Option<(u32, f32)> = None;
    for (index, triangle) in mesh.indices.iter().enumerate() {
        let [a, b, c] = triangle.map(|v| Vec3::from(mesh.positions[v as usize]));
        let (e1, e2) = (b - a, c - a);
        let p = dir.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-12 {
            continue;
        }
        let s = origin - a;
        let u = s.dot(p) / det;
        let q = s.cross(e1);
        let v = dir.dot(q) / det;
        let t = e2.dot(q) / det;
        if u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && best.is_none_or(|(_, b)| t < b) {
            best = Some((index as u32, t));
        }
    }
    best
}

/// Scene (c): an opaque torus, a ray (overlay) hitting it, the hit triangle and its
/// neighbours highlighted, markers at the ray's origin and hit, the torus's box (depth-tested)
/// and the ray's continuation past the hit (depth-tested, so hidden inside the torus).
fn hit_scene() -> Frame3d {
    let mesh = torus(0.8, 0.3, 48, 24);
    let origin = Vec3::new(-1.2, 0.9, 1.0);
    let dir = (Vec3::new(0.2, 0.25, 0.75) - origin).normalize();
    let (hit_triangle, t) = first_hit(&mesh, origin, dir).expect("the ray is aimed at the torus");
    let hit = origin + dir * t;
    let mut highlights = Vec::new();
    for (index, triangle) in mesh.indices.iter().enumerate() {
        let centroid = triangle
            .iter()
            .map(|&v| Vec3::from(mesh.positions[v as usize]))
            .sum::<Vec3>()
            / 3.0;
        if index as u32 != hit_triangle && centroid.distance(hit) < 0.3 {
            highlights.push((index as u32, [0.95, 0.8, 0.2, 1.0]));
        }
    }
    highlights.push((hit_triangle, [1.0, 0.3, 0.15, 1.0]));
    let mut frame = frame_with(mesh, [0.7, 0.7, 0.72, 1.0]);
    frame.camera.distance = 3.6;
    frame.highlights = highlights;
    frame.lines = box_edges(
        Vec3::new(-1.1, -0.3, -1.1),
        Vec3::new(1.1, 0.3, 1.1),
        [0.3, 0.9, 0.4, 1.0],
        2.0,
    );
    frame
        .lines
        .push(line(hit, hit + dir * 2.0, [0.6, 0.6, 0.6, 1.0], 2.0));
    frame.overlay_lines = vec![line(origin, hit, [1.0, 1.0, 1.0, 1.0], 2.5)];
    frame.markers = vec![
        Marker {
            pos: origin.to_array(),
            radius_px: 5.0,
            color: [1.0, 1.0, 1.0, 1.0],
        },
        Marker {
            pos: hit.to_array(),
            radius_px: 6.0,
            color: [1.0, 0.3, 0.15, 1.0],
        },
    ];
    frame
}

// ---------------------------------------------------------------------------------------
// Running and comparing
// ---------------------------------------------------------------------------------------

/// Renders `frame`; `None` (after saying why) when there is no adapter and none is required.
fn render(frame: &Frame3d) -> Option<RgbaImage> {
    match render_offscreen(frame, SIZE) {
        Ok(image) => Some(image),
        Err(OffscreenError::NoAdapter) => {
            no_adapter();
            None
        }
        Err(error) => panic!("rendering failed: {error}"),
    }
}

fn no_adapter() {
    assert!(
        std::env::var("BVHLAB_REQUIRE_GPU").as_deref() != Ok("1"),
        "no graphics adapter, and BVHLAB_REQUIRE_GPU=1 requires one (install Mesa's lavapipe: \
         apt-get install mesa-vulkan-drivers)"
    );
    eprintln!("SKIPPED: no graphics adapter (set BVHLAB_REQUIRE_GPU=1 to fail instead)");
}

fn reference_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference")
}

fn write_png(path: &Path, image: &RgbaImage) {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).expect("the PNG's directory");
    }
    let file = std::fs::File::create(path).expect("create the PNG");
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), image.width, image.height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().expect("PNG header");
    writer.write_image_data(&image.pixels).expect("PNG data");
}

fn read_png(path: &Path) -> Option<RgbaImage> {
    let file = std::fs::File::open(path).ok()?;
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .expect("a PNG");
    let mut pixels = vec![0; reader.output_buffer_size().expect("a sane size")];
    let info = reader.next_frame(&mut pixels).expect("PNG data");
    assert_eq!(
        (info.color_type, info.bit_depth),
        (png::ColorType::Rgba, png::BitDepth::Eight),
        "{} is not 8-bit RGBA",
        path.display()
    );
    pixels.truncate(info.buffer_size());
    Some(RgbaImage {
        width: info.width,
        height: info.height,
        pixels,
    })
}

/// Channel differences up to this count as equal. The same driver renders bit for bit the
/// same image; another rounds the lighting's `pow` and the blends a little differently. On
/// this machine the references (made with lavapipe's Vulkan) drawn by llvmpipe's OpenGL ES
/// (`WGPU_BACKEND=gl`, the path WebGL2 takes through naga's GLSL) differ by at most one level
/// in all but 1, 1 and 60 pixels of the three scenes; 4 levels leave room for other drivers.
const CHANNEL_TOLERANCE: u8 = 4;
/// The share of pixels allowed to differ by more: edge pixels, where another rasterizer may
/// cover one more or one fewer of the four samples (a quarter of the contrast). 0.5% of
/// 320 × 240 is 384 pixels, about a third of the outline length of these scenes, so a
/// systematic shift of an edge, or any change to the shading (a 0.02 change to the sphere's
/// green moves 14,751 pixels by more than 4 levels), still fails.
const PIXEL_SHARE: f64 = 0.005;

/// Compares `image` with the reference `name.png`; on a mismatch writes `name.actual.png` and
/// `name.diff.png` beside it and fails naming them. `BVHLAB_BLESS=1` rewrites the reference.
fn check_reference(name: &str, image: &RgbaImage) {
    let dir = reference_dir();
    let reference_path = dir.join(format!("{name}.png"));
    let actual_path = dir.join(format!("{name}.actual.png"));
    let diff_path = dir.join(format!("{name}.diff.png"));
    if std::env::var("BVHLAB_BLESS").as_deref() == Ok("1") {
        std::fs::create_dir_all(&dir).expect("the reference directory");
        write_png(&reference_path, image);
        eprintln!("blessed {}", reference_path.display());
        return;
    }
    let Some(reference) = read_png(&reference_path) else {
        write_png(&actual_path, image);
        panic!(
            "no reference {} (wrote {}; run with BVHLAB_BLESS=1 to accept it)",
            reference_path.display(),
            actual_path.display()
        );
    };
    let (differing, diff) = difference(&reference, image);
    let allowed = (f64::from(image.width * image.height) * PIXEL_SHARE) as usize;
    if differing > allowed {
        write_png(&actual_path, image);
        if let Some(diff) = diff {
            write_png(&diff_path, &diff);
        }
        panic!(
            "{name}: {differing} pixels differ from {} by more than {CHANNEL_TOLERANCE} levels \
             (at most {allowed} may); see {} and {}",
            reference_path.display(),
            actual_path.display(),
            diff_path.display()
        );
    }
    let _ = std::fs::remove_file(actual_path);
    let _ = std::fs::remove_file(diff_path);
}

/// How many pixels differ by more than the tolerance, and an image of where: differing
/// pixels in red, the rest a faint copy of the reference (`None` when the sizes differ).
fn difference(reference: &RgbaImage, image: &RgbaImage) -> (usize, Option<RgbaImage>) {
    if (reference.width, reference.height) != (image.width, image.height) {
        return ((image.width * image.height) as usize, None);
    }
    let mut diff = reference.clone();
    let mut differing = 0;
    for (out, (a, b)) in diff
        .pixels
        .chunks_mut(4)
        .zip(reference.pixels.chunks(4).zip(image.pixels.chunks(4)))
    {
        let worst = a
            .iter()
            .zip(b)
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap_or(0);
        if worst > CHANNEL_TOLERANCE {
            differing += 1;
            out.copy_from_slice(&[255, 0, 0, 255]);
        } else {
            let grey = (u16::from(a[0]) + u16::from(a[1]) + u16::from(a[2])) / 12;
            out.copy_from_slice(&[grey as u8, grey as u8, grey as u8, 255]);
        }
    }
    (differing, Some(diff))
}

/// An sRGB-encoded colour as the 8-bit values the image should hold.
fn to_u8(color: [f32; 4]) -> [u8; 4] {
    color.map(|c| (c * 255.0).round() as u8)
}

fn assert_near(actual: [u8; 4], expected: [u8; 4], tolerance: u8, what: &str) {
    let worst = actual
        .iter()
        .zip(expected)
        .map(|(a, e)| a.abs_diff(e))
        .max()
        .unwrap_or(0);
    assert!(
        worst <= tolerance,
        "{what}: {actual:?}, expected {expected:?} within {tolerance}"
    );
}

/// The pixel a world point lands in.
fn pixel_of(frame: &Frame3d, point: Vec3) -> (u32, u32) {
    let p = frame
        .camera
        .project(point, Vec2::new(SIZE[0] as f32, SIZE[1] as f32))
        .expect("in front of the eye");
    (p.x as u32, p.y as u32)
}

// ---------------------------------------------------------------------------------------
// Reference images
// ---------------------------------------------------------------------------------------

#[test]
fn sphere_matches_its_reference() {
    if let Some(image) = render(&sphere_scene()) {
        check_reference("sphere", &image);
    }
}

#[test]
fn xray_cube_with_boxes_and_split_plane_matches_its_reference() {
    if let Some(image) = render(&xray_scene()) {
        check_reference("xray_cube", &image);
    }
}

#[test]
fn ray_hit_with_highlights_and_markers_matches_its_reference() {
    if let Some(image) = render(&hit_scene()) {
        check_reference("ray_hit", &image);
    }
}

// ---------------------------------------------------------------------------------------
// Properties that need no reference
// ---------------------------------------------------------------------------------------

#[test]
fn the_corners_show_the_background_and_the_sphere_its_colour_head_on() {
    let Some(image) = render(&sphere_scene()) else {
        return;
    };
    let (w, h) = (image.width, image.height);
    for (x, y) in [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)] {
        assert_near(image.pixel(x, y), to_u8(BACKGROUND), 1, "corner");
    }
    // The centre pixel sees the sphere where its surface faces the eye, which the headlight
    // lights fully: the colour asked for. The facet there is tilted from the view by at most
    // half a facet (3.75°), which dims it by under 0.2% (cos 3.75° = 0.998): under one level.
    assert_near(image.pixel(w / 2, h / 2), to_u8(SPHERE_COLOR), 2, "centre");
}

#[test]
fn a_line_behind_the_mesh_is_hidden_and_an_overlay_line_is_not() {
    let plain = sphere_scene();
    let Some(without) = render(&plain) else {
        return;
    };
    let forward = plain.camera.basis().forward;
    let right = plain.camera.basis().right;
    // A short segment beyond the sphere, on the line of sight through its centre.
    let behind = forward * 1.6;
    let segment =
        |centre: Vec3, color| line(centre - right * 0.2, centre + right * 0.2, color, 4.0);
    let green = [0.0, 1.0, 0.0, 1.0];
    let magenta = [1.0, 0.0, 1.0, 1.0];

    let mut hidden = plain.clone();
    hidden.lines = vec![segment(behind, green)];
    let with_hidden = render(&hidden).expect("rendered above");
    assert_eq!(
        with_hidden.pixels, without.pixels,
        "the line behind the sphere changed the image"
    );

    let mut overlay = plain.clone();
    overlay.overlay_lines = vec![segment(behind, magenta)];
    let with_overlay = render(&overlay).expect("rendered above");
    let (x, y) = pixel_of(&plain, behind);
    assert_near(with_overlay.pixel(x, y), to_u8(magenta), 1, "overlay line");

    // The same depth-tested line in front of the sphere is drawn.
    let mut in_front = plain.clone();
    let front = -forward * 1.5;
    in_front.lines = vec![segment(front, green)];
    let with_front = render(&in_front).expect("rendered above");
    let (x, y) = pixel_of(&plain, front);
    assert_near(with_front.pixel(x, y), to_u8(green), 1, "line in front");
}

#[test]
fn xray_shows_lines_inside_the_mesh_and_opaque_hides_them() {
    let red = [1.0, 0.0, 0.0, 1.0];
    let inside = line(
        Vec3::new(-0.5, 0.0, 0.0),
        Vec3::new(0.5, 0.0, 0.0),
        red,
        5.0,
    );
    for (mesh_color, shows) in [
        ([0.75, 0.78, 0.82, 0.3], true),
        ([0.75, 0.78, 0.82, 1.0], false),
    ] {
        let plain = frame_with(cube(1.0), mesh_color);
        let mut with_line = plain.clone();
        with_line.lines = vec![inside];
        let Some(before) = render(&plain) else {
            return;
        };
        let after = render(&with_line).expect("rendered above");
        let (x, y) = pixel_of(&plain, Vec3::ZERO);
        let (b, a) = (before.pixel(x, y), after.pixel(x, y));
        if shows {
            // Seen through two translucent faces (alpha 0.3 each): about half the red.
            assert!(
                a[0] > b[0] + 40 && a[1] + 40 < b[1],
                "x-ray: {b:?} -> {a:?}"
            );
        } else {
            assert_eq!(
                after.pixels, before.pixels,
                "opaque: the inside line showed"
            );
        }
    }
}

/// The colour the lighting model gives a face of `color` whose normal makes an angle of
/// `acos(facing)` with the direction to the eye: linear `base · (0.25 + 0.75·facing)`,
/// encoded again (ambient 0.25, the headlight the rest).
fn lit(color: [f32; 4], facing: f32) -> [u8; 4] {
    let linear = |c: f32| {
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    let gamma = |c: f32| {
        if c <= 0.003_130_8 {
            c * 12.92
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        }
    };
    let shade = 0.25 + 0.75 * facing;
    let [r, g, b, a] = color;
    to_u8([
        gamma(linear(r) * shade),
        gamma(linear(g) * shade),
        gamma(linear(b) * shade),
        a,
    ])
}

#[test]
fn a_highlight_wins_over_its_triangle_and_is_lit_like_the_mesh() {
    let mut frame = sphere_scene();
    let mesh = frame.mesh.clone().expect("a mesh");
    let size = Vec2::new(SIZE[0] as f32, SIZE[1] as f32);
    let ray = frame.camera.ray_through(size * 0.5, size).expect("a ray");
    let (triangle, _) = first_hit(&mesh, ray.origin(), ray.dir()).expect("the sphere is hit");
    let orange = [1.0, 0.5, 0.1, 1.0];
    // A highlight naming a triangle that does not exist is left out.
    frame.highlights = vec![(triangle, orange), (u32::MAX, orange)];
    let Some(image) = render(&frame) else {
        return;
    };
    let [a, b, c] = mesh.triangle(triangle).expect("exists").map(Vec3::from);
    let centroid = (a + b + c) / 3.0;
    let facing = (b - a)
        .cross(c - a)
        .normalize()
        .dot((frame.camera.eye() - centroid).normalize());
    let (x, y) = pixel_of(&frame, centroid);
    assert_near(image.pixel(x, y), lit(orange, facing.abs()), 2, "highlight");
}

#[test]
fn a_mesh_cut_across_small_buffers_draws_the_same() {
    let frame = sphere_scene();
    let Some(whole) = render(&frame) else {
        return;
    };
    let mesh = frame.mesh.as_deref().expect("a mesh");
    let vertex_bytes = mesh.positions.len() as u64 * 12;
    let index_bytes = mesh.indices.len() as u64 * 12;
    // Shared vertices with the indices in three buffers, then every piece with its own.
    for limit in [vertex_bytes.max(index_bytes / 3 + 12), vertex_bytes / 4] {
        let (device, queue, _) = headless_device_with_limits(|limits| wgpu_limits(limits, limit))
            .expect("an adapter, as for the first image");
        assert_eq!(device.limits().max_buffer_size, limit);
        let mut renderer = Renderer3d::new(&device);
        let cut = render_and_read(&device, &queue, &mut renderer, &frame, SIZE).expect("drawn");
        assert!(renderer.mesh_gpu_bytes() >= vertex_bytes + index_bytes);
        let (differing, _) = difference(&whole, &cut);
        assert_eq!(differing, 0, "limit {limit}: {differing} pixels differ");
    }
}

fn wgpu_limits(mut limits: eframe::wgpu::Limits, max_buffer_size: u64) -> eframe::wgpu::Limits {
    limits.max_buffer_size = max_buffer_size;
    limits
}

#[test]
fn a_bad_index_is_reported_and_the_rest_is_still_drawn() {
    let mut frame = sphere_scene();
    let mut mesh = sphere(1.0, 8, 8);
    mesh.indices[5][2] = 10_000;
    mesh.revision = next_revision();
    let vertex_count = mesh.positions.len();
    frame.mesh = Some(Arc::new(mesh));
    let white = [1.0, 1.0, 1.0, 1.0];
    frame.overlay_lines = vec![line(Vec3::ZERO, Vec3::X, white, 4.0)];
    let Some((device, queue, _)) = headless_device() else {
        no_adapter();
        return;
    };
    let mut renderer = Renderer3d::new(&device);
    let error = render_and_read(&device, &queue, &mut renderer, &frame, SIZE)
        .expect_err("index 10000 is past the vertices");
    assert_eq!(
        error,
        OffscreenError::Mesh(MeshUploadError::VertexOutOfRange {
            triangle: 5,
            vertex: 10_000,
            vertex_count
        })
    );
    let texture = renderer.color_texture().expect("the frame was still drawn");
    let image = read_back(&device, &queue, texture).expect("read back");
    let (x, y) = pixel_of(&frame, Vec3::new(0.5, 0.0, 0.0));
    assert_near(
        image.pixel(x, y),
        to_u8(white),
        1,
        "overlay line without the mesh",
    );
    let (cx, cy) = pixel_of(&frame, Vec3::new(0.0, 0.5, 0.0));
    assert_near(image.pixel(cx, cy), to_u8(BACKGROUND), 1, "no mesh drawn");
}

#[test]
fn a_new_size_gives_an_image_of_that_size() {
    let Some((device, queue, _)) = headless_device() else {
        no_adapter();
        return;
    };
    let mut renderer = Renderer3d::new(&device);
    let frame = sphere_scene();
    for size in [[320, 240], [101, 57], [320, 240]] {
        let image = render_and_read(&device, &queue, &mut renderer, &frame, size).expect("drawn");
        assert_eq!([image.width, image.height], size);
        assert_eq!(image.pixels.len(), (size[0] * size[1] * 4) as usize);
        // The sphere, framed the same way, covers the centre at every size.
        assert_near(
            image.pixel(size[0] / 2, size[1] / 2),
            to_u8(SPHERE_COLOR),
            3,
            "centre",
        );
    }
}

#[test]
fn one_sample_per_pixel_draws_the_same_scene_with_rougher_edges() {
    let Some((device, queue, _)) = headless_device() else {
        no_adapter();
        return;
    };
    let frame = hit_scene();
    let draw = |samples| {
        let mut renderer = Renderer3d::with_samples(&device, samples);
        render_and_read(&device, &queue, &mut renderer, &frame, SIZE).expect("drawn")
    };
    let (single, multi) = (draw(1), draw(4));
    let (differing, _) = difference(&multi, &single);
    let total = (SIZE[0] * SIZE[1]) as usize;
    // Only edges differ: some (multisampling smooths them), but few.
    assert!(
        differing > 100,
        "4x and 1x agree everywhere: {differing} pixels differ"
    );
    assert!(
        differing < total / 20,
        "{differing} of {total} pixels differ"
    );
}

// ---------------------------------------------------------------------------------------
// Through egui: the paint callback and the blit
// ---------------------------------------------------------------------------------------

/// What egui's pass is cleared to around the view.
const EGUI_CLEAR: eframe::wgpu::Color = eframe::wgpu::Color {
    r: 0.0,
    g: 0.2,
    b: 0.0,
    a: 1.0,
};

/// One egui frame at `pixels_per_point` on a `window_px` screen that paints `frame` as a 3D
/// view into `rect` (points), rendered by `egui_wgpu` into a `format` texture with
/// `msaa` samples, as eframe would, and read back.
fn paint_through_egui(
    device: &eframe::wgpu::Device,
    queue: &eframe::wgpu::Queue,
    target: EguiTarget,
    window_px: [u32; 2],
    pixels_per_point: f32,
    rect: egui::Rect,
    frame: &Frame3d,
) -> RgbaImage {
    use eframe::egui_wgpu::{Renderer, RendererOptions, ScreenDescriptor};
    use eframe::wgpu;
    let ctx = egui::Context::default();
    let mut input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(window_px[0] as f32, window_px[1] as f32) / pixels_per_point,
        )),
        ..egui::RawInput::default()
    };
    input
        .viewports
        .entry(egui::ViewportId::ROOT)
        .or_default()
        .native_pixels_per_point = Some(pixels_per_point);
    let mut output = ctx.run_ui(input, |ui| {
        paint_3d(
            ui,
            rect,
            egui::Id::unique("view3d under test"),
            frame.clone(),
        );
    });
    let mut renderer = Renderer::new(
        device,
        target.format,
        RendererOptions {
            msaa_samples: target.msaa_samples,
            dithering: false,
            ..RendererOptions::default()
        },
    );
    install_in(&mut renderer, device, target, DEFAULT_SAMPLES);
    for (id, deltas) in &output.textures_delta.set {
        for delta in deltas {
            renderer.update_texture(device, queue, *id, delta);
        }
    }
    output.textures_delta.set.clear();
    let primitives = ctx.tessellate(std::mem::take(&mut output.shapes), pixels_per_point);
    let screen = ScreenDescriptor {
        size_in_pixels: window_px,
        pixels_per_point,
    };
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let prepared = renderer.update_buffers(device, queue, &mut encoder, &primitives, &screen);
    let texture = |sample_count, usage| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("egui target"),
            size: wgpu::Extent3d {
                width: window_px[0],
                height: window_px[1],
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count,
            dimension: wgpu::TextureDimension::D2,
            format: target.format,
            usage,
            view_formats: &[],
        })
    };
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
    let resolved = texture(1, usage | wgpu::TextureUsages::COPY_SRC);
    let resolved_view = resolved.create_view(&wgpu::TextureViewDescriptor::default());
    let multisampled = (target.msaa_samples > 1).then(|| {
        texture(target.msaa_samples, usage).create_view(&wgpu::TextureViewDescriptor::default())
    });
    {
        let (view, resolve_target) = match &multisampled {
            Some(view) => (view, Some(&resolved_view)),
            None => (&resolved_view, None),
        };
        let mut pass = encoder
            .begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(EGUI_CLEAR),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..wgpu::RenderPassDescriptor::default()
            })
            .forget_lifetime();
        renderer.render(&mut pass, &primitives, &screen);
    }
    queue.submit(prepared.into_iter().chain([encoder.finish()]));
    read_back(device, queue, &resolved).expect("read back")
}

/// The view's image in egui's target matches the image rendered offscreen at the view's
/// pixel size, shifted to where the view is: pixel for pixel for a gamma target, within a
/// level for an sRGB one (decoded by the blit, encoded again by the hardware). Around it is
/// egui's background.
fn check_blit(target: EguiTarget, rect: egui::Rect, shift: (i32, i32)) {
    const PPP: f32 = 1.5;
    const WINDOW: [u32; 2] = [300, 225];
    let Some((device, queue, _)) = headless_device() else {
        no_adapter();
        return;
    };
    let frame = sphere_scene();
    let mut window = paint_through_egui(&device, &queue, target, WINDOW, PPP, rect, &frame);
    if matches!(
        target.format,
        eframe::wgpu::TextureFormat::Bgra8Unorm | eframe::wgpu::TextureFormat::Bgra8UnormSrgb
    ) {
        window.pixels.chunks_mut(4).for_each(|p| p.swap(0, 2));
    }
    let view_px = [
        ((rect.max.x * PPP).round() - (rect.min.x * PPP).round()) as u32,
        ((rect.max.y * PPP).round() - (rect.min.y * PPP).round()) as u32,
    ];
    let mut renderer = Renderer3d::new(&device);
    let view = render_and_read(&device, &queue, &mut renderer, &frame, view_px).expect("drawn");
    let tolerance = u8::from(target.format.is_srgb());
    let outside = window.pixel(WINDOW[0] - 1, 0);
    assert_ne!(
        outside,
        view.pixel(0, 0),
        "egui's background looks like the view's"
    );
    let mut inside = 0;
    for y in 0..WINDOW[1] {
        for x in 0..WINDOW[0] {
            let (vx, vy) = (x as i32 - shift.0, y as i32 - shift.1);
            let in_view =
                (0..view_px[0] as i32).contains(&vx) && (0..view_px[1] as i32).contains(&vy);
            let expected = if in_view {
                inside += 1;
                view.pixel(vx as u32, vy as u32)
            } else {
                outside
            };
            assert_near(
                window.pixel(x, y),
                expected,
                tolerance,
                &format!("({x}, {y})"),
            );
        }
    }
    assert!(inside > 10_000, "the view covered only {inside} pixels");
}

#[test]
fn the_callback_blits_the_view_into_a_gamma_target_pixel_for_pixel() {
    let rect = egui::Rect::from_min_max(egui::pos2(20.0, 10.0), egui::pos2(180.0, 130.0));
    check_blit(
        EguiTarget::new(eframe::wgpu::TextureFormat::Rgba8Unorm),
        rect,
        (30, 15),
    );
}

#[test]
fn the_callback_blits_into_a_multisampled_srgb_target() {
    let rect = egui::Rect::from_min_max(egui::pos2(20.0, 10.0), egui::pos2(180.0, 130.0));
    let target = EguiTarget {
        msaa_samples: 4,
        ..EguiTarget::new(eframe::wgpu::TextureFormat::Bgra8UnormSrgb)
    };
    check_blit(target, rect, (30, 15));
}

#[test]
fn a_view_partly_off_the_window_is_cut_not_squeezed() {
    // 225 × 150 pixels, its left 45 off the window.
    let rect = egui::Rect::from_min_max(egui::pos2(-30.0, 20.0), egui::pos2(120.0, 120.0));
    check_blit(
        EguiTarget::new(eframe::wgpu::TextureFormat::Rgba8Unorm),
        rect,
        (-45, 30),
    );
}

// ---------------------------------------------------------------------------------------
// Measurement (run with `--ignored --nocapture`)
// ---------------------------------------------------------------------------------------

/// Milliseconds of the median of five frames (after one that uploads), each recorded,
/// submitted and waited for; with `read` also copied back to the CPU.
fn time_frames(
    device: &eframe::wgpu::Device,
    queue: &eframe::wgpu::Queue,
    renderer: &mut Renderer3d,
    frame: &Frame3d,
    size: [u32; 2],
    read: bool,
) -> f64 {
    let mut one = || {
        let started = Instant::now();
        if read {
            render_and_read(device, queue, renderer, frame, size).expect("drawn");
        } else {
            let mut encoder =
                device.create_command_encoder(&eframe::wgpu::CommandEncoderDescriptor::default());
            renderer
                .render(device, queue, &mut encoder, size, frame)
                .expect("drawn");
            queue.submit([encoder.finish()]);
            device
                .poll(eframe::wgpu::PollType::wait_indefinitely())
                .expect("finished");
        }
        started.elapsed().as_secs_f64() * 1e3
    };
    one();
    let mut times = (0..5).map(|_| one()).collect::<Vec<_>>();
    times.sort_by(f64::total_cmp);
    times[2]
}

#[test]
#[ignore = "a measurement, not a check: run with --ignored --nocapture"]
fn measure_a_million_triangles_at_800_by_600() {
    let Some((device, queue, info)) = headless_device() else {
        no_adapter();
        return;
    };
    eprintln!("adapter: {} ({:?})", info.name, info.backend);
    // UV spheres less their poles' empty halves: 998,000 triangles over 501,501 vertices,
    // then 1,998,000 over 1,002,001.
    for (stacks, sample_counts) in [(500, &[1, 4][..]), (1000, &[1][..])] {
        let mesh = Arc::new(sphere(1.0, stacks, 1000));
        let triangles = mesh.indices.len();
        let mut big = frame_with(MeshData::default(), SPHERE_COLOR);
        big.mesh = Some(Arc::clone(&mesh));
        for &samples in sample_counts {
            let mut renderer = Renderer3d::with_samples(&device, samples);
            let started = Instant::now();
            render_and_read(&device, &queue, &mut renderer, &big, [800, 600]).expect("drawn");
            let first = started.elapsed().as_secs_f64() * 1e3;
            let drawn = time_frames(&device, &queue, &mut renderer, &big, [800, 600], false);
            let read = time_frames(&device, &queue, &mut renderer, &big, [800, 600], true);
            let bytes = renderer.mesh_gpu_bytes();
            eprintln!(
                "{triangles} triangles, {samples}x: first frame (upload, read-back) {first:.0} \
                 ms; then {drawn:.0} ms per frame, {read:.0} ms with read-back; mesh buffers \
                 {bytes} B = {:.1} B/triangle",
                bytes as f64 / triangles as f64
            );
            if stacks == 500 {
                for (name, scene) in [("x-ray cube", xray_scene()), ("ray hit", hit_scene())] {
                    let ms = time_frames(&device, &queue, &mut renderer, &scene, [800, 600], false);
                    eprintln!("{name}, {samples}x: {ms:.1} ms per frame");
                }
            }
        }
    }
}
