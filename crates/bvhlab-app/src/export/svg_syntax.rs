//! The SVG syntax the exporter writes: elements with attributes, numbers rounded to a few
//! decimals, egui colours as SVG paint, path data, and XML escaping. Kept apart from the
//! shapes so that the shape code reads as geometry.

use std::fmt::{self, Write as _};

use egui::{Color32, Pos2};

/// Appends formatted text. Writing into a `String` cannot fail, so the `fmt::Result` (which
/// exists for writers that can) carries nothing here.
fn append(out: &mut String, args: fmt::Arguments<'_>) {
    let _ = out.write_fmt(args);
}

/// A coordinate or length written with at most two decimals and no trailing zeros (`3`,
/// `2.5`, `-0.12`): a hundredth of a point is far below what a slide shows, and the files
/// stay small.
#[derive(Clone, Copy, Debug)]
pub(super) struct Num(pub f32);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_trimmed(f, f64::from(self.0), 2)
    }
}

/// An opacity in 0..=1, written with three decimals so that 8-bit alpha survives a round
/// trip (1/255 is about 0.004).
#[derive(Clone, Copy, Debug)]
struct Opacity(f32);

impl fmt::Display for Opacity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_trimmed(f, f64::from(self.0), 3)
    }
}

/// Writes `value` rounded to `decimals` decimals, without trailing zeros and never as `-0`.
fn write_trimmed(f: &mut fmt::Formatter<'_>, value: f64, decimals: u32) -> fmt::Result {
    let scale = 10_u64.pow(decimals);
    let scaled = (value * scale as f64).round();
    // Far beyond any screen, the integer path below would overflow: no decimals matter there.
    if scaled.abs() >= 9.0e15 {
        return write!(f, "{value:.0}");
    }
    let scaled = scaled as i64;
    if scaled == 0 {
        return f.write_str("0");
    }
    let sign = if scaled < 0 { "-" } else { "" };
    let magnitude = scaled.unsigned_abs();
    let (whole, mut fraction) = (magnitude / scale, magnitude % scale);
    if fraction == 0 {
        return write!(f, "{sign}{whole}");
    }
    let mut width = decimals as usize;
    while fraction % 10 == 0 {
        fraction /= 10;
        width -= 1;
    }
    write!(f, "{sign}{whole}.{fraction:0width$}")
}

/// An egui colour as SVG paint. egui's [`Color32`] holds premultiplied alpha while SVG colours
/// are straight, so the colour channels are divided by alpha and alpha becomes an opacity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Paint {
    /// Straight (not premultiplied) sRGB.
    rgb: [u8; 3],
    /// Alpha, 1 is opaque.
    opacity: f32,
}

impl Paint {
    /// The paint of `color`, or `None` when it paints nothing: zero alpha is transparent, or
    /// one of egui's additive colours, which SVG cannot blend, so they are left out.
    pub(super) fn of(color: Color32) -> Option<Self> {
        let [r, g, b, a] = color.to_srgba_unmultiplied();
        (a > 0).then(|| Self {
            rgb: [r, g, b],
            opacity: f32::from(a) / 255.0,
        })
    }
}

impl fmt::Display for Paint {
    /// The colour part, as `#rrggbb`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [r, g, b] = self.rgb;
        write!(f, "#{r:02x}{g:02x}{b:02x}")
    }
}

/// XML text with `& < > " '` escaped and the control characters XML 1.0 forbids dropped, fit
/// for both element content and attribute values.
pub(super) struct Escaped<'a>(pub &'a str);

impl fmt::Display for Escaped<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for c in self.0.chars() {
            match c {
                '&' => f.write_str("&amp;")?,
                '<' => f.write_str("&lt;")?,
                '>' => f.write_str("&gt;")?,
                '"' => f.write_str("&quot;")?,
                '\'' => f.write_str("&apos;")?,
                '\t' | '\n' | '\r' => f.write_char(c)?,
                c if c.is_control() => {}
                c => f.write_char(c)?,
            }
        }
        Ok(())
    }
}

/// One element being written: opened with its name, given attributes, then closed empty or
/// with text content.
pub(super) struct Element<'a> {
    out: &'a mut String,
    name: &'static str,
}

impl<'a> Element<'a> {
    /// Starts `<name`.
    pub(super) fn open(out: &'a mut String, name: &'static str) -> Self {
        out.push('<');
        out.push_str(name);
        Self { out, name }
    }

    /// Adds `name="value"`; `value` must not need escaping (numbers, paint, fixed words).
    pub(super) fn attr(self, name: &str, value: impl fmt::Display) -> Self {
        append(self.out, format_args!(" {name}=\"{value}\""));
        self
    }

    /// Adds `name="value"` with `value` escaped (text that comes from the user).
    pub(super) fn attr_text(self, name: &str, value: &str) -> Self {
        self.attr(name, Escaped(value))
    }

    /// `x` and `y` attributes (with a prefix: `cx`/`cy`, `x1`/`y1`).
    pub(super) fn pos(self, x: &str, y: &str, p: Pos2) -> Self {
        self.attr(x, Num(p.x)).attr(y, Num(p.y))
    }

    /// The fill, or `fill="none"` (SVG fills black by default).
    pub(super) fn fill(self, color: Color32) -> Self {
        match Paint::of(color) {
            None => self.attr("fill", "none"),
            Some(paint) if paint.opacity < 1.0 => self
                .attr("fill", paint)
                .attr("fill-opacity", Opacity(paint.opacity)),
            Some(paint) => self.attr("fill", paint),
        }
    }

    /// The stroke, if it paints anything (SVG draws no stroke by default).
    pub(super) fn stroke(self, width: f32, color: Color32) -> Self {
        match Paint::of(color) {
            Some(paint) if width > 0.0 => {
                let this = self.attr("stroke", paint).attr("stroke-width", Num(width));
                if paint.opacity < 1.0 {
                    this.attr("stroke-opacity", Opacity(paint.opacity))
                } else {
                    this
                }
            }
            _ => self,
        }
    }

    /// A clockwise rotation by `angle` radians about `pivot` (egui's angles turn clockwise on
    /// screen, as SVG's do, since both have y pointing down); nothing for no rotation.
    pub(super) fn rotate(self, angle: f32, pivot: Pos2) -> Self {
        if angle == 0.0 {
            return self;
        }
        let degrees = Num(angle.to_degrees());
        let (x, y) = (Num(pivot.x), Num(pivot.y));
        self.attr("transform", format_args!("rotate({degrees} {x} {y})"))
    }

    /// Ends the element without content: `/>`.
    pub(super) fn close(self) {
        self.out.push_str("/>\n");
    }

    /// Ends the start tag and writes `text` as the (escaped) content, then the end tag.
    pub(super) fn close_with_text(self, text: &str) {
        append(
            self.out,
            format_args!(">{}</{}>\n", Escaped(text), self.name),
        );
    }

    /// Ends the start tag only: children follow, then [`end`].
    pub(super) fn open_children(self) {
        self.out.push_str(">\n");
    }
}

/// Writes the end tag of an element opened with [`Element::open_children`].
pub(super) fn end(out: &mut String, name: &str) {
    append(out, format_args!("</{name}>\n"));
}

/// Writes an XML comment (for what the export leaves out). `text` must not contain `--`.
pub(super) fn comment(out: &mut String, text: impl fmt::Display) {
    append(out, format_args!("<!-- {text} -->\n"));
}

/// A `points` attribute value: `x,y x,y ...`.
pub(super) struct Points<'a>(pub &'a [Pos2]);

impl fmt::Display for Points<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, p) in self.0.iter().enumerate() {
            let sep = if i == 0 { "" } else { " " };
            write!(f, "{sep}{},{}", Num(p.x), Num(p.y))?;
        }
        Ok(())
    }
}

/// Path data (the `d` attribute), built command by command.
#[derive(Default)]
pub(super) struct PathData(String);

impl PathData {
    /// `M x,y`: starts a subpath.
    pub(super) fn move_to(&mut self, p: Pos2) {
        append(&mut self.0, format_args!("M{},{}", Num(p.x), Num(p.y)));
    }

    /// `L x,y`: a straight line.
    pub(super) fn line_to(&mut self, p: Pos2) {
        append(&mut self.0, format_args!("L{},{}", Num(p.x), Num(p.y)));
    }

    /// `Q c,c p,p`: a quadratic Bézier curve.
    pub(super) fn quad_to(&mut self, c: Pos2, p: Pos2) {
        let (cx, cy, x, y) = (Num(c.x), Num(c.y), Num(p.x), Num(p.y));
        append(&mut self.0, format_args!("Q{cx},{cy} {x},{y}"));
    }

    /// `C c,c d,d p,p`: a cubic Bézier curve.
    pub(super) fn cubic_to(&mut self, c: Pos2, d: Pos2, p: Pos2) {
        let (cx, cy, dx, dy) = (Num(c.x), Num(c.y), Num(d.x), Num(d.y));
        let (x, y) = (Num(p.x), Num(p.y));
        append(&mut self.0, format_args!("C{cx},{cy} {dx},{dy} {x},{y}"));
    }

    /// `A r r 0 0 1 p,p`: a clockwise quarter-circle arc of radius `r` (rounded corners); a
    /// straight line for a sharp corner (`r` = 0).
    pub(super) fn arc_to(&mut self, r: f32, p: Pos2) {
        if r <= 0.0 {
            self.line_to(p);
            return;
        }
        let (r, x, y) = (Num(r), Num(p.x), Num(p.y));
        append(&mut self.0, format_args!("A{r},{r} 0 0 1 {x},{y}"));
    }

    /// `Z`: closes the subpath.
    pub(super) fn close(&mut self) {
        self.0.push('Z');
    }

    /// Whether no command was written.
    pub(super) fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The `d` attribute's value.
    pub(super) fn as_str(&self) -> &str {
        &self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_to_two_decimals_and_drop_trailing_zeros() {
        let cases = [
            (3.0, "3"),
            (2.5, "2.5"),
            (-0.125, "-0.13"),
            (0.001, "0"),
            (-0.001, "0"),
            (10.10, "10.1"),
            (1234.567, "1234.57"),
            (-7.0, "-7"),
            (0.05, "0.05"),
        ];
        for (value, text) in cases {
            assert_eq!(Num(value).to_string(), text, "{value}");
            // Whatever is written parses back to within half a hundredth.
            let back: f32 = text.parse().expect("a number");
            assert!((back - value).abs() <= 0.005 + 1e-6, "{value} -> {text}");
        }
        // Far off screen: no decimals, but still the same number.
        let huge = Num(3.0e20).to_string();
        assert_eq!(huge.parse::<f32>().expect("a number"), 3.0e20, "{huge}");
    }

    #[test]
    fn paint_unpremultiplies_and_leaves_out_zero_alpha() {
        for (r, g, b, a) in [(200, 100, 50, 255), (200, 100, 50, 128), (10, 250, 90, 17)] {
            let paint = Paint::of(Color32::from_rgba_unmultiplied(r, g, b, a)).expect("visible");
            // Premultiplying to 8 bits and back loses up to 255 / (2 a) per channel.
            let tolerance = (255.0 / (2.0 * f32::from(a))).ceil() as i32 + 1;
            for (got, want) in paint.rgb.iter().zip([r, g, b]) {
                assert!((i32::from(*got) - i32::from(want)).abs() <= tolerance);
            }
            assert!((paint.opacity - f32::from(a) / 255.0).abs() < 1e-6);
        }
        assert_eq!(Paint::of(Color32::TRANSPARENT), None);
        assert_eq!(Paint::of(Color32::from_additive_luminance(200)), None);
        let hex = Paint::of(Color32::from_rgb(255, 16, 1)).expect("opaque");
        assert_eq!(hex.to_string(), "#ff1001");
    }

    #[test]
    fn escaping_covers_markup_and_drops_control_characters() {
        let text = Escaped("a<b & \"c\" 'd'>\u{7}e").to_string();
        assert_eq!(text, "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;e");
    }
}
