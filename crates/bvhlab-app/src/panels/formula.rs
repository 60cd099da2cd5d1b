//! A lesson's formula or code, in monospace, fitted to the panel's width: never cut at its
//! right edge (a horizontal scroll hid "`t_xmax = (x_max`" behind the edge with no sign that
//! more was there).
//!
//! A line too wide is broken where a reader expects it: first at the gap between two
//! formulas set side by side (three or more spaces: each becomes its own line), then at a
//! space, its continuation indented four columns deeper so it reads as one statement.

use egui::RichText;

/// How much deeper a continuation line is indented than the line it continues.
const CONTINUATION: usize = 4;

/// The narrowest a formula is fitted to, in characters (a narrower panel clips).
const NARROWEST: usize = 12;

/// Shows `formula` in a framed block, its lines fitted to the width available.
pub fn formula_block(ui: &mut egui::Ui, formula: &str) {
    egui::Frame::group(ui.style()).show(ui, |ui| {
        let width = ui.available_width();
        let font = egui::TextStyle::Monospace.resolve(ui.style());
        let color = ui.visuals().text_color();
        let mut columns = formula
            .lines()
            .map(|l| l.chars().count())
            .max()
            .unwrap_or(0);
        let text = loop {
            let text = fit(formula, columns);
            // Measured rather than counted: a glyph from a fallback font may be wider.
            let wide = ui.fonts_mut(|f| f.layout_no_wrap(text.clone(), font.clone(), color));
            let measured = wide.size().x;
            if measured <= width || columns <= NARROWEST {
                break text;
            }
            let shrunk = (columns as f32 * width / measured).floor() as usize;
            columns = shrunk.min(columns - 1).max(NARROWEST);
        };
        ui.add(egui::Label::new(RichText::new(text).monospace()).extend());
    });
}

/// `formula` with every line at most `columns` characters wide where it can be broken (a
/// single word longer than that stays whole).
pub fn fit(formula: &str, columns: usize) -> String {
    let mut out: Vec<String> = Vec::new();
    for line in formula.lines() {
        if line.chars().count() <= columns {
            out.push(line.to_owned());
            continue;
        }
        let indent = line.len() - line.trim_start().len();
        let lead = &line[..indent];
        for part in side_by_side(line.trim_start()) {
            wrap(&format!("{lead}{part}"), indent, columns, &mut out);
        }
    }
    out.join("\n")
}

/// The formulas set side by side on one line (separated by three or more spaces).
fn side_by_side(line: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let mut rest = line;
    while let Some(gap) = rest.find("   ") {
        let (part, after) = rest.split_at(gap);
        parts.push(part.trim_end());
        rest = after.trim_start();
    }
    parts.push(rest);
    parts.retain(|p| !p.is_empty());
    parts
}

/// Pushes `line` (indented by `indent` spaces) broken at spaces into lines of at most
/// `columns` characters, continuations indented [`CONTINUATION`] deeper.
fn wrap(line: &str, indent: usize, columns: usize, out: &mut Vec<String>) {
    let deeper = " ".repeat(indent + CONTINUATION);
    let mut current = line[..indent].to_owned();
    let mut empty = true;
    for word in line[indent..].split(' ').filter(|w| !w.is_empty()) {
        let width = current.chars().count() + usize::from(!empty) + word.chars().count();
        if !empty && width > columns {
            out.push(std::mem::replace(&mut current, deeper.clone()));
            empty = true;
        }
        if !empty {
            current.push(' ');
        }
        current.push_str(word);
        empty = false;
    }
    out.push(current);
}

#[cfg(test)]
mod tests {
    use super::fit;

    #[test]
    fn a_line_that_fits_is_kept_as_it_is() {
        let f = "c = (1/n) sum v_i\nr = max_i |v_i - c|";
        assert_eq!(fit(f, 40), f);
    }

    #[test]
    fn formulas_side_by_side_become_lines_of_their_own() {
        let f = "t_xmin = (x_min - x_e) / x_d     t_xmax = (x_max - x_e) / x_d";
        assert_eq!(
            fit(f, 40),
            "t_xmin = (x_min - x_e) / x_d\nt_xmax = (x_max - x_e) / x_d"
        );
    }

    #[test]
    fn a_long_statement_continues_indented_and_keeps_every_word() {
        let f = "  if dist(point, bvNode.box) >= currentMin: return currentMin";
        let fitted = fit(f, 30);
        for line in fitted.lines() {
            assert!(line.chars().count() <= 30, "{line:?}");
        }
        let lines: Vec<&str> = fitted.lines().collect();
        assert!(lines[0].starts_with("  if dist"));
        assert!(lines[1].starts_with("      ") && !lines[1].starts_with("       "));
        let words = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
        assert_eq!(words(&fitted), words(f));
    }
}
