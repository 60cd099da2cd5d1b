//! The canvas as an SVG document: each egui [`Shape`] (screen space, in points) becomes the SVG
//! element that paints the same thing, so that slides get sharp lines at any zoom instead of
//! a screenshot's pixels.
//!
//! Shapes entirely outside the exported rect are dropped, shapes with a non-finite coordinate
//! are skipped (a NaN in the file would make renderers reject or misdraw it), and the few
//! variants SVG cannot express here leave an XML comment saying so.

use egui::epaint::{
    CircleShape, ColorMode, CubicBezierShape, EllipseShape, PathShape, PathStroke,
    QuadraticBezierShape, RectShape,
};
use egui::{Color32, Pos2, Rect, Shape, StrokeKind};

use super::svg_syntax::{Element, Num, PathData, Points, comment, end};
use super::{svg_mesh, svg_text};

/// The SVG namespace, which every standalone SVG document must declare.
const SVG_NS: &str = "http://www.w3.org/2000/svg";

/// An SVG document of `shapes` (screen space), cropped to `rect`, with `background` filled.
///
/// The document's `viewBox` is `rect` itself, so coordinates stay the screen's points and
/// anything outside `rect` is cropped by the renderer; its `width` and `height` are the rect's
/// size in points. A `rect` that is empty or not finite gives an empty document.
pub fn svg_document(shapes: &[Shape], rect: Rect, background: Color32) -> String {
    let mut out = String::with_capacity(256 + 80 * shapes.len());
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let valid = rect.is_finite() && rect.is_positive();
    let (min, size) = if valid {
        (rect.min, rect.size())
    } else {
        (Pos2::ZERO, egui::Vec2::ZERO)
    };
    let view_box = format!(
        "{} {} {} {}",
        Num(min.x),
        Num(min.y),
        Num(size.x),
        Num(size.y)
    );
    Element::open(&mut out, "svg")
        .attr("xmlns", SVG_NS)
        .attr("width", Num(size.x))
        .attr("height", Num(size.y))
        .attr("viewBox", view_box)
        .open_children();
    if valid {
        if background.a() > 0 {
            Element::open(&mut out, "rect")
                .pos("x", "y", min)
                .attr("width", Num(size.x))
                .attr("height", Num(size.y))
                .fill(background)
                .close();
        }
        let mut writer = ShapeWriter {
            out: &mut out,
            crop: rect,
        };
        for shape in shapes {
            writer.shape(shape);
        }
    } else {
        comment(&mut out, "the export rect was empty or not finite");
    }
    end(&mut out, "svg");
    out
}

/// Why a shape was left out of the document.
pub(super) enum Skip {
    /// A coordinate, radius or width was NaN or infinite.
    NonFinite,
    /// SVG has no faithful equivalent (the reason says what is missing).
    Unsupported(&'static str),
}

/// `Ok` if every point and number is finite, else `Err(Skip::NonFinite)`.
pub(super) fn finite(points: &[Pos2], numbers: &[f32]) -> Result<(), Skip> {
    let ok = points.iter().all(|p| p.is_finite()) && numbers.iter().all(|v| v.is_finite());
    if ok { Ok(()) } else { Err(Skip::NonFinite) }
}

/// Writes shapes into the document, dropping those outside `crop`.
struct ShapeWriter<'a> {
    out: &'a mut String,
    crop: Rect,
}

impl ShapeWriter<'_> {
    /// Writes one shape (recursing into [`Shape::Vec`]), or a comment if it is skipped.
    fn shape(&mut self, shape: &Shape) {
        match shape {
            Shape::Noop => return,
            Shape::Vec(shapes) => {
                for shape in shapes {
                    self.shape(shape);
                }
                return;
            }
            _ => {}
        }
        // Off the picture: leave it out. (Bounds that are not finite go on, so that the
        // shape's own check reports them.)
        let bounds = shape.visual_bounding_rect();
        if bounds.is_finite() && !bounds.intersects(self.crop) {
            return;
        }
        let written = match shape {
            Shape::Noop | Shape::Vec(_) => Ok(()),
            Shape::LineSegment { points, stroke } => {
                self.line_segment(*points, stroke.width, stroke.color)
            }
            Shape::Path(path) => self.path(path),
            Shape::Circle(circle) => self.circle(circle),
            Shape::Ellipse(ellipse) => self.ellipse(ellipse),
            Shape::Rect(rect) => self.rect(rect),
            Shape::Text(text) => svg_text::text(self.out, text),
            Shape::Mesh(mesh) => svg_mesh::mesh(self.out, mesh, self.crop),
            Shape::QuadraticBezier(curve) => self.quadratic(curve),
            Shape::CubicBezier(curve) => self.cubic(curve),
            Shape::Band(_) => Err(Skip::Unsupported("bands are not exported")),
            Shape::Callback(_) => Err(Skip::Unsupported("backend paint callbacks draw on the GPU")),
        };
        if let Err(skip) = written {
            let why = match skip {
                Skip::NonFinite => "not finite",
                Skip::Unsupported(why) => why,
            };
            comment(self.out, format_args!("{} skipped: {why}", variant(shape)));
        }
    }

    fn line_segment(&mut self, [a, b]: [Pos2; 2], width: f32, color: Color32) -> Result<(), Skip> {
        finite(&[a, b], &[width])?;
        if width <= 0.0 || color.a() == 0 {
            return Ok(());
        }
        Element::open(self.out, "line")
            .pos("x1", "y1", a)
            .pos("x2", "y2", b)
            .stroke(width, color)
            .close();
        Ok(())
    }

    /// An open path is a `<polyline>`, a closed one a `<polygon>` (egui fills only closed
    /// paths). Strokes are centred on the path: egui's inside and outside strokes of closed
    /// paths have no SVG equivalent short of offsetting the outline.
    fn path(&mut self, path: &PathShape) -> Result<(), Skip> {
        finite(&path.points, &[path.stroke.width])?;
        if path.points.len() < 2 {
            return Ok(());
        }
        let stroke = stroke_color(&path.stroke, &path.points);
        let fill = if path.closed {
            path.fill
        } else {
            Color32::TRANSPARENT
        };
        let name = if path.closed { "polygon" } else { "polyline" };
        Element::open(self.out, name)
            .attr("points", Points(&path.points))
            .fill(fill)
            .stroke(path.stroke.width, stroke)
            .close();
        Ok(())
    }

    fn circle(&mut self, c: &CircleShape) -> Result<(), Skip> {
        finite(&[c.center], &[c.radius, c.stroke.width])?;
        if c.radius < 0.0 {
            return Ok(());
        }
        Element::open(self.out, "circle")
            .pos("cx", "cy", c.center)
            .attr("r", Num(c.radius))
            .fill(c.fill)
            .stroke(c.stroke.width, c.stroke.color)
            .close();
        Ok(())
    }

    fn ellipse(&mut self, e: &EllipseShape) -> Result<(), Skip> {
        finite(
            &[e.center],
            &[e.radius.x, e.radius.y, e.stroke.width, e.angle],
        )?;
        if e.radius.x < 0.0 || e.radius.y < 0.0 {
            return Ok(());
        }
        Element::open(self.out, "ellipse")
            .pos("cx", "cy", e.center)
            .attr("rx", Num(e.radius.x))
            .attr("ry", Num(e.radius.y))
            .fill(e.fill)
            .stroke(e.stroke.width, e.stroke.color)
            .rotate(e.angle, e.center)
            .close();
        Ok(())
    }

    /// A rectangle: the fill covers `rect`, while egui's stroke lies inside, across or
    /// outside its edge ([`StrokeKind`]), so an SVG stroke (always centred) runs along `rect`
    /// shrunk or grown by half the width; with rounded corners, those radii shrink or grow
    /// alike. Textures (brushes) and blur are left out: the fill colour stands for them.
    fn rect(&mut self, r: &RectShape) -> Result<(), Skip> {
        finite(&[r.rect.min, r.rect.max], &[r.stroke.width, r.angle])?;
        let offset = match r.stroke_kind {
            StrokeKind::Inside => -0.5 * r.stroke.width,
            StrokeKind::Middle => 0.0,
            StrokeKind::Outside => 0.5 * r.stroke.width,
        };
        let radii = [
            r.corner_radius.nw,
            r.corner_radius.ne,
            r.corner_radius.se,
            r.corner_radius.sw,
        ]
        .map(f32::from);
        let has_stroke = r.stroke.width > 0.0 && r.stroke.color.a() > 0;
        if r.fill.a() == 0 && !has_stroke {
            return Ok(());
        }
        if offset == 0.0 || !has_stroke {
            self.rounded_rect(r.rect, radii, r.angle)
                .fill(r.fill)
                .stroke(r.stroke.width, r.stroke.color)
                .close();
            return Ok(());
        }
        if r.fill.a() > 0 {
            self.rounded_rect(r.rect, radii, r.angle)
                .fill(r.fill)
                .close();
        }
        let stroke_rect = r.rect.expand(offset);
        if stroke_rect.is_positive() {
            self.rounded_rect(stroke_rect, radii.map(|c| (c + offset).max(0.0)), r.angle)
                .fill(Color32::TRANSPARENT)
                .stroke(r.stroke.width, r.stroke.color)
                .close();
        }
        Ok(())
    }

    /// Opens a `<rect>` (equal corner radii, `[nw, ne, se, sw]`) or a `<path>` (different
    /// ones), rotated by `angle` about its centre; the caller adds paint and closes it.
    fn rounded_rect(&mut self, rect: Rect, radii: [f32; 4], angle: f32) -> Element<'_> {
        // No corner can round more than half the shorter side.
        let radii = radii.map(|c| c.min(0.5 * rect.width().min(rect.height())).max(0.0));
        let [nw, ne, se, sw] = radii;
        let element = if radii.iter().all(|&c| c == nw) {
            let element = Element::open(self.out, "rect")
                .pos("x", "y", rect.min)
                .attr("width", Num(rect.width()))
                .attr("height", Num(rect.height()));
            if nw > 0.0 {
                element.attr("rx", Num(nw))
            } else {
                element
            }
        } else {
            let (min, max) = (rect.min, rect.max);
            let mut d = PathData::default();
            d.move_to(Pos2::new(min.x + nw, min.y));
            d.line_to(Pos2::new(max.x - ne, min.y));
            d.arc_to(ne, Pos2::new(max.x, min.y + ne));
            d.line_to(Pos2::new(max.x, max.y - se));
            d.arc_to(se, Pos2::new(max.x - se, max.y));
            d.line_to(Pos2::new(min.x + sw, max.y));
            d.arc_to(sw, Pos2::new(min.x, max.y - sw));
            d.line_to(Pos2::new(min.x, min.y + nw));
            d.arc_to(nw, Pos2::new(min.x + nw, min.y));
            d.close();
            Element::open(self.out, "path").attr("d", d.as_str())
        };
        element.rotate(angle, rect.center())
    }

    fn quadratic(&mut self, q: &QuadraticBezierShape) -> Result<(), Skip> {
        finite(&q.points, &[q.stroke.width])?;
        let [a, c, b] = q.points;
        let mut d = PathData::default();
        d.move_to(a);
        d.quad_to(c, b);
        self.curve(d, q.closed, q.fill, &q.stroke, &q.points);
        Ok(())
    }

    fn cubic(&mut self, q: &CubicBezierShape) -> Result<(), Skip> {
        finite(&q.points, &[q.stroke.width])?;
        let [a, c, e, b] = q.points;
        let mut d = PathData::default();
        d.move_to(a);
        d.cubic_to(c, e, b);
        self.curve(d, q.closed, q.fill, &q.stroke, &q.points);
        Ok(())
    }

    /// A Bézier curve's `<path>`, filled only when closed (as egui does).
    fn curve(
        &mut self,
        mut d: PathData,
        closed: bool,
        fill: Color32,
        stroke: &PathStroke,
        points: &[Pos2],
    ) {
        if closed {
            d.close();
        }
        Element::open(self.out, "path")
            .attr("d", d.as_str())
            .fill(if closed { fill } else { Color32::TRANSPARENT })
            .stroke(stroke.width, stroke_color(stroke, points))
            .close();
    }
}

/// A path stroke's colour. A colour that varies along the path (a UV callback) is sampled
/// once, at the centre of the path's bounds: SVG gradients could follow it only roughly.
fn stroke_color(stroke: &PathStroke, points: &[Pos2]) -> Color32 {
    match &stroke.color {
        ColorMode::Solid(color) => *color,
        ColorMode::UV(color_at) => {
            let bounds = Rect::from_points(points);
            color_at(bounds, bounds.center())
        }
    }
}

/// The variant's name, for comments.
fn variant(shape: &Shape) -> &'static str {
    match shape {
        Shape::Noop => "Noop",
        Shape::Vec(_) => "Vec",
        Shape::Circle(_) => "Circle",
        Shape::Ellipse(_) => "Ellipse",
        Shape::LineSegment { .. } => "LineSegment",
        Shape::Path(_) => "Path",
        Shape::Band(_) => "Band",
        Shape::Rect(_) => "Rect",
        Shape::Text(_) => "Text",
        Shape::Mesh(_) => "Mesh",
        Shape::QuadraticBezier(_) => "QuadraticBezier",
        Shape::CubicBezier(_) => "CubicBezier",
        Shape::Callback(_) => "Callback",
    }
}
