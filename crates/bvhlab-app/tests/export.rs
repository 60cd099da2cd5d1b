//! The canvas exports checked from the outside: SVG parsed back with an XML parser and every
//! element's coordinates and colours compared with the shapes it came from; PNG decoded with
//! the `png` crate; crops compared pixel by pixel with the screenshot; files read back.

use std::sync::Arc;

use bvhlab_app::export::{crop, png_bytes, save_file_in, svg_document};
use egui::epaint::{CircleShape, EllipseShape, Mesh, PathShape, RectShape, TextShape, Vertex};
use egui::text::{LayoutJob, TextFormat};
use egui::{
    Color32, ColorImage, CornerRadius, FontId, Pos2, Rect, Shape, Stroke, StrokeKind, pos2, vec2,
};
use roxmltree::{Document, Node};

/// The exported area used throughout: not at the origin, so a viewBox that ignored it shows.
const AREA: Rect = Rect {
    min: pos2(5.0, 10.0),
    max: pos2(205.0, 160.0),
};

/// Coordinates are written with two decimals.
const COORD_TOLERANCE: f32 = 0.0051;

fn svg(shapes: &[Shape]) -> String {
    svg_document(shapes, AREA, Color32::from_rgb(20, 22, 30))
}

fn parse(text: &str) -> Document<'_> {
    Document::parse(text).unwrap_or_else(|e| panic!("not valid XML ({e}):\n{text}"))
}

/// The drawn elements: the root's element children after the background rect.
fn drawn<'a>(doc: &'a Document<'a>) -> Vec<Node<'a, 'a>> {
    let mut elements = doc.root_element().children().filter(Node::is_element);
    let background = elements.next().expect("a background rect");
    assert_eq!(background.tag_name().name(), "rect");
    elements.collect()
}

/// The comments in the document, trimmed.
fn comments(doc: &Document<'_>) -> Vec<String> {
    doc.descendants()
        .filter(Node::is_comment)
        .filter_map(|n| n.text().map(|t| t.trim().to_owned()))
        .collect()
}

fn number(node: Node<'_, '_>, name: &str) -> f32 {
    let text = node
        .attribute(name)
        .unwrap_or_else(|| panic!("<{}> has no {name}", node.tag_name().name()));
    text.parse()
        .unwrap_or_else(|_| panic!("{name}={text:?} is not a number"))
}

fn assert_close(got: f32, want: f32, what: &str) {
    assert!(
        (got - want).abs() <= COORD_TOLERANCE,
        "{what}: got {got}, want {want}"
    );
}

/// The straight rgb and opacity of `fill` or `stroke`, `None` for no paint.
fn paint(node: Node<'_, '_>, which: &str) -> Option<([u8; 3], f32)> {
    let value = node.attribute(which)?;
    if value == "none" {
        return None;
    }
    let hex = value.strip_prefix('#').expect("#rrggbb");
    let channel = |i: usize| u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).expect("hex");
    let opacity = node
        .attribute(format!("{which}-opacity").as_str())
        .map_or(1.0, |o| o.parse().expect("a number"));
    Some(([channel(0), channel(1), channel(2)], opacity))
}

/// Checks that `which` paints the straight colour `(r, g, b, a)`. A colour premultiplied to
/// 8 bits and divided back is only as precise as its alpha allows.
fn assert_paint(node: Node<'_, '_>, which: &str, [r, g, b, a]: [u8; 4]) {
    let (rgb, opacity) = paint(node, which).unwrap_or_else(|| panic!("no {which}"));
    let tolerance = (255.0 / (2.0 * f32::from(a))).ceil() as i16 + 1;
    for (got, want) in rgb.iter().zip([r, g, b]) {
        assert!(
            (i16::from(*got) - i16::from(want)).abs() <= tolerance,
            "{which}: {rgb:?} for {:?}",
            [r, g, b]
        );
    }
    assert!(
        (opacity - f32::from(a) / 255.0).abs() < 0.001,
        "{which}-opacity {opacity}"
    );
}

#[test]
fn the_document_is_svg_with_the_area_as_view_box_and_the_background_first() {
    let text = svg(&[]);
    let doc = parse(&text);
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(
        root.tag_name().namespace(),
        Some("http://www.w3.org/2000/svg")
    );
    let view_box: Vec<f32> = root
        .attribute("viewBox")
        .expect("a viewBox")
        .split(' ')
        .map(|v| v.parse().expect("a number"))
        .collect();
    let want = [AREA.min.x, AREA.min.y, AREA.width(), AREA.height()];
    assert_eq!(view_box, want);
    assert_close(number(root, "width"), AREA.width(), "width");
    assert_close(number(root, "height"), AREA.height(), "height");
    let background = root.first_element_child().expect("background");
    assert_close(number(background, "x"), AREA.min.x, "x");
    assert_close(number(background, "y"), AREA.min.y, "y");
    assert_close(number(background, "width"), AREA.width(), "width");
    assert_close(number(background, "height"), AREA.height(), "height");
    assert_paint(background, "fill", [20, 22, 30, 255]);
}

#[test]
fn lines_circles_and_ellipses_keep_their_coordinates_and_colours() {
    let red = [230, 40, 10, 255];
    let sea = [0, 128, 255, 128];
    let rgba = |[r, g, b, a]: [u8; 4]| Color32::from_rgba_unmultiplied(r, g, b, a);
    let shapes = [
        Shape::line_segment(
            [pos2(10.0, 20.125), pos2(110.5, 20.0)],
            Stroke::new(2.0, rgba(red)),
        ),
        Shape::Circle(CircleShape {
            center: pos2(50.0, 60.0),
            radius: 7.5,
            fill: rgba(sea),
            stroke: Stroke::new(1.5, rgba(red)),
        }),
        Shape::Ellipse(
            EllipseShape::filled(pos2(100.0, 90.0), vec2(30.0, 12.0), rgba(sea)).with_angle(0.5),
        ),
    ];
    let text = svg(&shapes);
    let doc = parse(&text);
    let elements = drawn(&doc);
    let names: Vec<&str> = elements.iter().map(|n| n.tag_name().name()).collect();
    assert_eq!(names, ["line", "circle", "ellipse"]);

    let line = elements[0];
    assert_close(number(line, "x1"), 10.0, "x1");
    assert_close(number(line, "y1"), 20.125, "y1");
    assert_close(number(line, "x2"), 110.5, "x2");
    assert_close(number(line, "y2"), 20.0, "y2");
    assert_close(number(line, "stroke-width"), 2.0, "stroke-width");
    assert_paint(line, "stroke", red);

    let circle = elements[1];
    assert_close(number(circle, "cx"), 50.0, "cx");
    assert_close(number(circle, "cy"), 60.0, "cy");
    assert_close(number(circle, "r"), 7.5, "r");
    assert_paint(circle, "fill", sea);
    assert_paint(circle, "stroke", red);

    let ellipse = elements[2];
    assert_close(number(ellipse, "rx"), 30.0, "rx");
    assert_close(number(ellipse, "ry"), 12.0, "ry");
    assert_paint(ellipse, "fill", sea);
    assert!(paint(ellipse, "stroke").is_none());
    let degrees = 0.5_f32.to_degrees();
    let transform = ellipse.attribute("transform").expect("rotated");
    let args: Vec<f32> = transform
        .trim_start_matches("rotate(")
        .trim_end_matches(')')
        .split(' ')
        .map(|v| v.parse().expect("a number"))
        .collect();
    assert_eq!(args.len(), 3, "{transform}");
    assert_close(args[0], degrees, "angle");
    assert_close(args[1], 100.0, "pivot x");
    assert_close(args[2], 90.0, "pivot y");
}

fn point_list(node: Node<'_, '_>) -> Vec<Pos2> {
    node.attribute("points")
        .expect("points")
        .split(' ')
        .map(|pair| {
            let (x, y) = pair.split_once(',').expect("x,y");
            pos2(x.parse().expect("x"), y.parse().expect("y"))
        })
        .collect()
}

fn assert_points(got: &[Pos2], want: &[Pos2]) {
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(want) {
        assert_close(g.x, w.x, "x");
        assert_close(g.y, w.y, "y");
    }
}

#[test]
fn open_paths_are_polylines_and_closed_ones_filled_polygons() {
    let open = vec![pos2(20.0, 30.0), pos2(40.333, 35.0), pos2(60.0, 31.0)];
    let closed = vec![pos2(100.0, 100.0), pos2(140.0, 100.0), pos2(120.0, 130.0)];
    let stroke = Stroke::new(1.0, Color32::YELLOW);
    let shapes = [
        // An open path's fill is ignored, as egui does.
        Shape::Path(PathShape {
            points: open.clone(),
            closed: false,
            fill: Color32::RED,
            stroke: stroke.into(),
        }),
        Shape::convex_polygon(closed.clone(), Color32::from_rgb(9, 200, 9), stroke),
    ];
    let text = svg(&shapes);
    let doc = parse(&text);
    let elements = drawn(&doc);
    assert_eq!(elements[0].tag_name().name(), "polyline");
    assert_points(&point_list(elements[0]), &open);
    assert_eq!(paint(elements[0], "fill"), None);
    assert_paint(elements[0], "stroke", [255, 255, 0, 255]);
    assert_eq!(elements[1].tag_name().name(), "polygon");
    assert_points(&point_list(elements[1]), &closed);
    assert_paint(elements[1], "fill", [9, 200, 9, 255]);
}

/// The absolute end points of a path's `M`, `L` and `A` commands (the data the exporter
/// writes), and the number of `A` commands.
fn path_end_points(d: &str) -> (Vec<Pos2>, usize) {
    let mut points = Vec::new();
    let mut arcs = 0;
    let mut rest = d;
    while let Some(command) = rest.chars().next() {
        let end = rest[1..]
            .find(|c: char| c.is_ascii_alphabetic())
            .map_or(rest.len(), |i| i + 1);
        let numbers: Vec<f32> = rest[1..end]
            .split([' ', ','])
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().expect("a number"))
            .collect();
        match command {
            'M' | 'L' | 'A' => {
                let [.., x, y] = numbers[..] else {
                    panic!("{command} without coordinates in {d}")
                };
                points.push(pos2(x, y));
                arcs += usize::from(command == 'A');
            }
            'Z' => {}
            other => panic!("unexpected command {other} in {d}"),
        }
        rest = &rest[end..];
    }
    (points, arcs)
}

#[test]
fn rect_strokes_sit_inside_across_or_outside_the_edge_as_in_egui() {
    let rect = Rect::from_min_max(pos2(30.0, 40.0), pos2(90.0, 70.0));
    let fill = Color32::from_rgb(0, 0, 200);
    let stroke = Stroke::new(4.0, Color32::WHITE);
    let shapes = [
        Shape::Rect(RectShape::new(rect, 5, fill, stroke, StrokeKind::Middle)),
        Shape::Rect(RectShape::new(rect, 0, fill, stroke, StrokeKind::Inside)),
        Shape::Rect(RectShape::new(
            rect,
            0,
            Color32::TRANSPARENT,
            stroke,
            StrokeKind::Outside,
        )),
        Shape::Rect(RectShape::filled(
            rect,
            CornerRadius {
                nw: 2,
                ne: 6,
                se: 0,
                sw: 10,
            },
            fill,
        )),
    ];
    let text = svg(&shapes);
    let doc = parse(&text);
    let elements = drawn(&doc);
    let names: Vec<&str> = elements.iter().map(|n| n.tag_name().name()).collect();
    // Middle: one rect; Inside: the fill, then the stroke; Outside: the stroke; then a path.
    assert_eq!(names, ["rect", "rect", "rect", "rect", "path"]);
    let check_rect = |node: Node<'_, '_>, r: Rect| {
        assert_close(number(node, "x"), r.min.x, "x");
        assert_close(number(node, "y"), r.min.y, "y");
        assert_close(number(node, "width"), r.width(), "width");
        assert_close(number(node, "height"), r.height(), "height");
    };
    check_rect(elements[0], rect);
    assert_close(number(elements[0], "rx"), 5.0, "rx");
    assert_paint(elements[0], "fill", [0, 0, 200, 255]);
    assert_paint(elements[0], "stroke", [255, 255, 255, 255]);

    check_rect(elements[1], rect);
    assert_eq!(paint(elements[1], "stroke"), None);
    // The inside stroke's centre line runs half its width in from the edge.
    check_rect(elements[2], rect.shrink(2.0));
    assert_eq!(paint(elements[2], "fill"), None);
    assert_close(number(elements[2], "stroke-width"), 4.0, "stroke-width");

    check_rect(elements[3], rect.expand(2.0));
    assert_eq!(paint(elements[3], "fill"), None);

    let (points, arcs) = path_end_points(elements[4].attribute("d").expect("d"));
    // One arc per rounded corner; the sharp south-east one is a plain corner.
    assert_eq!(arcs, 3);
    for p in &points {
        let on_edge = [
            p.x - rect.min.x,
            rect.max.x - p.x,
            p.y - rect.min.y,
            rect.max.y - p.y,
        ]
        .iter()
        .any(|d| d.abs() <= COORD_TOLERANCE);
        assert!(
            on_edge && rect.expand(COORD_TOLERANCE).contains(*p),
            "{p:?}"
        );
    }
    // The path starts where the top edge leaves the north-west rounding.
    assert_close(points[0].x, rect.min.x + 2.0, "start x");
    assert_close(points[0].y, rect.min.y, "start y");
    assert_paint(elements[4], "fill", [0, 0, 200, 255]);
}

/// Lays out `job` with egui's default fonts (they exist only inside a pass).
fn galley(job: &LayoutJob) -> Arc<egui::Galley> {
    let ctx = egui::Context::default();
    let mut galley = None;
    let mut output = ctx.run_pass(egui::RawInput::default(), |ctx| {
        galley = Some(ctx.fonts_mut(|fonts| fonts.layout_job(job.clone())));
    });
    // No renderer here takes the font atlas upload: egui insists it be dropped on purpose.
    output.textures_delta.clear();
    galley.expect("laid out")
}

#[test]
fn text_rows_become_escaped_text_at_their_baselines_in_their_colours() {
    let first = "a<b & \"c\"";
    let second = "second>";
    let mut job = LayoutJob::default();
    let red = Color32::from_rgb(250, 30, 30);
    let blue = Color32::from_rgb(30, 60, 250);
    job.append(
        &format!("{first}\n"),
        0.0,
        TextFormat::simple(FontId::proportional(14.0), red),
    );
    job.append(
        second,
        0.0,
        TextFormat::simple(FontId::monospace(11.0), blue),
    );
    let galley = galley(&job);
    assert_eq!(galley.rows.len(), 2);
    let pos = pos2(40.0, 50.0);
    let shape = Shape::Text(TextShape::new(pos, galley.clone(), Color32::GRAY));
    let text = svg(&[shape]);
    // The markup characters are escaped in the file itself.
    assert!(text.contains("a&lt;b &amp; &quot;c&quot;"), "{text}");
    assert!(text.contains("second&gt;"), "{text}");

    let doc = parse(&text);
    let elements = drawn(&doc);
    assert_eq!(elements.len(), 2);
    let wants = [
        (first, red, 14.0, "sans-serif"),
        (second, blue, 11.0, "monospace"),
    ];
    for ((node, row), (words, color, size, family)) in elements.iter().zip(&galley.rows).zip(wants)
    {
        assert_eq!(node.tag_name().name(), "text");
        assert_eq!(node.text(), Some(words));
        let [r, g, b, a] = color.to_array();
        assert_paint(*node, "fill", [r, g, b, a]);
        assert_close(number(*node, "font-size"), size, "font-size");
        assert_eq!(node.attribute("font-family"), Some(family));
        // Left-aligned text starts at the galley's left; its baseline lies inside the row,
        // below the middle (the ascent is taller than the descent).
        let row_rect = row.rect().translate(pos.to_vec2());
        let (x, y) = (number(*node, "x"), number(*node, "y"));
        assert!((x - pos.x).abs() <= 1.0, "x {x}");
        assert!(
            y > row_rect.center().y && y <= row_rect.bottom(),
            "y {y} in {row_rect:?}"
        );
    }
}

/// The triangles of `d` (subpaths of the form `M a L b L c Z`).
fn triangles(d: &str) -> Vec<[Pos2; 3]> {
    let (points, _) = path_end_points(d);
    assert_eq!(points.len() % 3, 0, "{d}");
    points.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect()
}

#[test]
fn mesh_triangles_become_paths_in_their_mean_colour() {
    let mut mesh = Mesh::default();
    let corners = [
        pos2(20.0, 20.0),
        pos2(60.0, 20.0),
        pos2(60.0, 60.0),
        pos2(20.0, 60.0),
    ];
    let greys = [[30, 60, 90], [60, 90, 120], [90, 120, 150], [90, 120, 150]];
    for (p, [r, g, b]) in corners.iter().zip(greys) {
        mesh.colored_vertex(*p, Color32::from_rgb(r, g, b));
    }
    // Two triangles of the same mean colour, (60, 90, 120) ...
    mesh.add_triangle(0, 1, 2);
    mesh.add_triangle(1, 0, 3);
    // One wholly outside the exported area: left out.
    for p in [pos2(300.0, 300.0), pos2(340.0, 300.0), pos2(320.0, 340.0)] {
        mesh.colored_vertex(p, Color32::GOLD);
    }
    mesh.add_triangle(4, 5, 6);
    // ... one of another: the mean of pure red, green and blue.
    for (p, c) in [
        (pos2(100.0, 100.0), Color32::RED),
        (pos2(140.0, 100.0), Color32::GREEN),
        (pos2(120.0, 140.0), Color32::BLUE),
    ] {
        mesh.colored_vertex(p, c);
    }
    mesh.add_triangle(7, 8, 9);
    // A glyph's triangle samples the font texture: left out.
    mesh.vertices.push(Vertex {
        pos: pos2(30.0, 100.0),
        uv: pos2(0.5, 0.5),
        color: Color32::WHITE,
    });
    mesh.add_triangle(10, 7, 8);
    let text = svg(&[Shape::mesh(mesh.clone())]);
    let doc = parse(&text);
    let elements = drawn(&doc);
    assert_eq!(elements.len(), 2, "{text}");
    let first = triangles(elements[0].attribute("d").expect("d"));
    assert_eq!(first.len(), 2);
    assert_points(&first[0], &[corners[0], corners[1], corners[2]]);
    assert_points(&first[1], &[corners[1], corners[0], corners[3]]);
    // Means: (30 + 60 + 90) / 3 = 60, and so on; the second triangle's corners have the
    // same three colours (vertex 3 has vertex 2's).
    assert_paint(elements[0], "fill", [60, 90, 120, 255]);
    let second = triangles(elements[1].attribute("d").expect("d"));
    assert_eq!(second.len(), 1);
    assert_points(
        &second[0],
        &[pos2(100.0, 100.0), pos2(140.0, 100.0), pos2(120.0, 140.0)],
    );
    assert_paint(elements[1], "fill", [85, 85, 85, 255]);
    assert_eq!(comments(&doc), ["1 textured triangles skipped"]);

    // An image (a mesh on another texture) is left out whole, with a note.
    let mut image = mesh;
    image.texture_id = egui::TextureId::User(7);
    let doc_text = svg(&[Shape::mesh(image)]);
    let doc = parse(&doc_text);
    assert!(drawn(&doc).is_empty());
    assert_eq!(comments(&doc).len(), 1);
}

#[test]
fn nested_vecs_are_written_in_painting_order() {
    let stroke = Stroke::new(1.0, Color32::WHITE);
    let dot = |x: f32| Shape::circle_filled(pos2(x, 80.0), 3.0, Color32::WHITE);
    let shapes = [
        dot(10.0),
        Shape::Vec(vec![
            dot(20.0),
            Shape::Noop,
            Shape::Vec(vec![
                dot(30.0),
                Shape::line_segment([pos2(0.0, 0.0), pos2(50.0, 50.0)], stroke),
            ]),
            dot(40.0),
        ]),
        dot(50.0),
    ];
    let text = svg(&shapes);
    let doc = parse(&text);
    let elements = drawn(&doc);
    let summary: Vec<(String, Option<f32>)> = elements
        .iter()
        .map(|n| {
            (
                n.tag_name().name().to_owned(),
                n.attribute("cx").map(|_| number(*n, "cx")),
            )
        })
        .collect();
    let want = [
        ("circle", Some(10.0)),
        ("circle", Some(20.0)),
        ("circle", Some(30.0)),
        ("line", None),
        ("circle", Some(40.0)),
        ("circle", Some(50.0)),
    ]
    .map(|(name, cx)| (name.to_owned(), cx));
    assert_eq!(summary, want);
}

#[test]
fn non_finite_shapes_are_skipped_and_the_others_kept() {
    let stroke = Stroke::new(1.0, Color32::WHITE);
    let shapes = [
        Shape::line_segment([pos2(f32::NAN, 20.0), pos2(50.0, 50.0)], stroke),
        Shape::circle_filled(pos2(60.0, 60.0), f32::INFINITY, Color32::WHITE),
        Shape::closed_line(
            vec![pos2(20.0, 20.0), pos2(f32::NAN, 30.0), pos2(40.0, 50.0)],
            stroke,
        ),
        Shape::rect_filled(
            Rect::from_min_max(pos2(20.0, 20.0), pos2(f32::NAN, 30.0)),
            0,
            Color32::WHITE,
        ),
        Shape::circle_filled(pos2(70.0, 70.0), 4.0, Color32::WHITE),
    ];
    let text = svg(&shapes);
    assert!(!text.contains("NaN") && !text.contains("inf"), "{text}");
    let doc = parse(&text);
    let elements = drawn(&doc);
    assert_eq!(elements.len(), 1);
    assert_close(number(elements[0], "cx"), 70.0, "cx");
    let notes = comments(&doc);
    assert_eq!(notes.len(), 4, "{notes:?}");
    assert!(
        notes.iter().all(|n| n.ends_with("skipped: not finite")),
        "{notes:?}"
    );
}

#[test]
fn shapes_outside_the_area_are_left_out() {
    let stroke = Stroke::new(2.0, Color32::WHITE);
    let shapes = [
        // Wholly left of the area, then one crossing its left edge.
        Shape::line_segment([pos2(-50.0, 50.0), pos2(2.0, 50.0)], stroke),
        Shape::line_segment([pos2(-50.0, 60.0), pos2(20.0, 60.0)], stroke),
        Shape::circle_filled(pos2(300.0, 300.0), 10.0, Color32::WHITE),
    ];
    let text = svg(&shapes);
    let doc = parse(&text);
    let elements = drawn(&doc);
    assert_eq!(elements.len(), 1);
    assert_close(number(elements[0], "y1"), 60.0, "y1");
}

#[test]
fn many_random_segments_round_trip() {
    // A small linear congruential generator (Knuth's MMIX constants): reproducible, no
    // dependency.
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let segments: Vec<([Pos2; 2], Color32)> = (0..500)
        .map(|_| {
            let mut p = || {
                pos2(
                    AREA.min.x + next() * AREA.width(),
                    AREA.min.y + next() * AREA.height(),
                )
            };
            let ends = [p(), p()];
            let color = Color32::from_rgb((next() * 255.0) as u8, (next() * 255.0) as u8, 7);
            (ends, color)
        })
        .collect();
    let shapes: Vec<Shape> = segments
        .iter()
        .map(|(ends, color)| Shape::line_segment(*ends, Stroke::new(1.0, *color)))
        .collect();
    let text = svg(&shapes);
    let doc = parse(&text);
    let elements = drawn(&doc);
    assert_eq!(elements.len(), segments.len());
    for (node, ([a, b], color)) in elements.iter().zip(&segments) {
        assert_close(number(*node, "x1"), a.x, "x1");
        assert_close(number(*node, "y1"), a.y, "y1");
        assert_close(number(*node, "x2"), b.x, "x2");
        assert_close(number(*node, "y2"), b.y, "y2");
        assert_eq!(
            paint(*node, "stroke"),
            Some(([color.r(), color.g(), 7], 1.0))
        );
    }
}

#[test]
fn an_empty_area_gives_an_empty_document() {
    let shapes = [Shape::circle_filled(pos2(1.0, 1.0), 1.0, Color32::WHITE)];
    let empty = Rect::from_min_max(pos2(10.0, 10.0), pos2(10.0, 40.0));
    for rect in [empty, Rect::NAN] {
        let text = svg_document(&shapes, rect, Color32::BLACK);
        let doc = parse(&text);
        assert_eq!(
            doc.root_element()
                .children()
                .filter(Node::is_element)
                .count(),
            0
        );
        assert_eq!(doc.root_element().attribute("viewBox"), Some("0 0 0 0"));
    }
}

/// A screenshot whose pixel at (x, y) says where it is: red = x, green = y.
fn coordinates_image(width: usize, height: usize) -> ColorImage {
    let pixels = (0..height)
        .flat_map(|y| (0..width).map(move |x| Color32::from_rgb(x as u8, y as u8, 99)))
        .collect();
    ColorImage::new([width, height], pixels)
}

#[test]
fn png_round_trips_through_the_png_decoder() {
    let (width, height) = (7, 5);
    // Straight colours with varied alpha; opaque ones must come back exactly.
    let straight = |x: usize, y: usize| -> [u8; 4] {
        let alpha = [255, 255, 128, 200, 17][y];
        [(x * 36) as u8, (y * 60) as u8, 200, alpha]
    };
    let pixels = (0..height)
        .flat_map(|y| {
            (0..width).map(move |x| {
                let [r, g, b, a] = straight(x, y);
                Color32::from_rgba_unmultiplied(r, g, b, a)
            })
        })
        .collect();
    let image = ColorImage::new([width, height], pixels);
    let bytes = png_bytes(&image).expect("encodes");

    let decoder = png::Decoder::new(std::io::Cursor::new(&bytes[..]));
    let mut reader = decoder.read_info().expect("a PNG header");
    let mut buffer = vec![0; reader.output_buffer_size().expect("a size")];
    let info = reader.next_frame(&mut buffer).expect("a frame");
    assert_eq!((info.width, info.height), (width as u32, height as u32));
    assert_eq!(info.color_type, png::ColorType::Rgba);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    for y in 0..height {
        for x in 0..width {
            let i = 4 * (y * width + x);
            let got = &buffer[i..i + 4];
            let want = straight(x, y);
            let tolerance = if want[3] == 255 {
                0
            } else {
                (255 / (2 * u16::from(want[3]))) as i16 + 1
            };
            for (g, w) in got.iter().zip(want) {
                assert!(
                    (i16::from(*g) - i16::from(w)).abs() <= tolerance,
                    "({x}, {y}): {got:?} vs {want:?}"
                );
            }
            assert_eq!(got[3], want[3]);
        }
    }
}

#[test]
fn png_refuses_empty_and_inconsistent_images() {
    assert!(png_bytes(&ColorImage::new([0, 0], Vec::new())).is_err());
    let mut image = coordinates_image(3, 3);
    image.pixels.pop();
    assert!(png_bytes(&image).is_err());
}

/// The crop computed the slow way: every pixel whose centre lies in the rect scaled to
/// pixels.
fn brute_crop(image: &ColorImage, rect: Rect, ppp: f32) -> (Vec<Color32>, [usize; 2]) {
    let px = Rect::from_min_max(rect.min * ppp, rect.max * ppp);
    let mut pixels = Vec::new();
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for y in 0..image.size[1] {
        for x in 0..image.size[0] {
            let centre = pos2(x as f32 + 0.5, y as f32 + 0.5);
            if px.contains(centre) {
                pixels.push(image.pixels[y * image.size[0] + x]);
                xs.push(x);
                ys.push(y);
            }
        }
    }
    xs.sort_unstable();
    xs.dedup();
    ys.sort_unstable();
    ys.dedup();
    (pixels, [xs.len(), ys.len()])
}

#[test]
fn crops_take_the_pixels_under_the_rect_at_any_scale() {
    let screenshot = coordinates_image(40, 30);
    let cases = [
        (Rect::from_min_max(pos2(2.0, 3.0), pos2(6.0, 8.0)), 1.0),
        (Rect::from_min_max(pos2(1.0, 1.5), pos2(3.0, 4.0)), 2.0),
        (Rect::from_min_max(pos2(3.5, 2.0), pos2(12.0, 9.5)), 2.0),
        // Reaching past the window: the part inside it.
        (Rect::from_min_max(pos2(-5.0, 20.0), pos2(10.0, 50.0)), 1.0),
        (Rect::from_min_max(pos2(15.0, 10.0), pos2(30.0, 40.0)), 2.0),
    ];
    for (rect, ppp) in cases {
        let cut = crop(&screenshot, rect, ppp);
        let (pixels, size) = brute_crop(&screenshot, rect, ppp);
        assert_eq!(cut.size, size, "{rect:?} at {ppp}");
        assert_eq!(cut.pixels, pixels, "{rect:?} at {ppp}");
    }
    // At 2 pixels per point, the point (1, 1.5) is the pixel (2, 3).
    let cut = crop(
        &screenshot,
        Rect::from_min_max(pos2(1.0, 1.5), pos2(3.0, 4.0)),
        2.0,
    );
    assert_eq!(cut.size, [4, 5]);
    assert_eq!(cut.pixels[0], Color32::from_rgb(2, 3, 99));
    // Everything is the whole image; nothing, outside or NaN give empty images.
    assert_eq!(
        crop(&screenshot, Rect::EVERYTHING, 1.0).pixels,
        screenshot.pixels
    );
    for rect in [
        Rect::NOTHING,
        Rect::NAN,
        Rect::from_min_max(pos2(50.0, 0.0), pos2(60.0, 5.0)),
    ] {
        let cut = crop(&screenshot, rect, 1.0);
        assert_eq!(cut.size, [0, 0], "{rect:?}");
        assert!(cut.pixels.is_empty());
    }
}

/// A fresh directory under the system's temporary one, removed when dropped.
struct TempDir(std::path::PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let dir = std::env::temp_dir().join(format!(
            "bvhlab-export-{tag}-{}-{nanos}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        Self(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn saved_files_read_back_and_never_overwrite() {
    let dir = TempDir::new("save");
    let first: Vec<u8> = (0..=255).collect();
    let second = b"<svg/>".to_vec();
    let a = save_file_in(&dir.0, "canvas.svg", &first).expect("saved");
    let b = save_file_in(&dir.0, "canvas.svg", &second).expect("saved again");
    assert_eq!(a, dir.0.join("canvas.svg"));
    assert_eq!(b, dir.0.join("canvas (1).svg"));
    assert_eq!(std::fs::read(&a).expect("readable"), first);
    assert_eq!(std::fs::read(&b).expect("readable"), second);

    // Directories in the name are dropped: the file lands in `dir`.
    let c = save_file_in(&dir.0, "../../escape.png", &second).expect("saved");
    assert_eq!(c, dir.0.join("escape.png"));
    for bad in ["", "..", "some/dir/"] {
        assert!(save_file_in(&dir.0, bad, &second).is_err(), "{bad:?}");
    }
    let entries = std::fs::read_dir(&dir.0).expect("listable").count();
    assert_eq!(entries, 3);
}
