//! Text the student can read: the smallest text size, the pseudocode's colours in the dark
//! and the light theme, and the weak text's colour, all chosen to meet WCAG 2's AA contrast
//! (4.5:1 for body text), with the contrast ratio the tests check them with.

use egui::{Color32, Theme};

/// The smallest text the lab uses, in points (egui's "small" style is 9 by default, which a
/// student reads as about 7 pixels tall).
pub const SMALLEST_TEXT: f32 = 12.0;

/// WCAG 2's AA contrast for body text.
pub const AA_CONTRAST: f32 = 4.5;

/// The colours of the pseudocode listing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CodePalette {
    /// Behind the listing.
    pub background: Color32,
    /// Every line but the current one.
    pub text: Color32,
    /// Behind the current line.
    pub current_background: Color32,
    /// The current line.
    pub current_text: Color32,
}

/// The listing's colours in `theme`.
pub fn code_palette(theme: Theme) -> CodePalette {
    match theme {
        Theme::Dark => CodePalette {
            background: Color32::from_rgb(20, 22, 28),
            text: Color32::from_gray(200),
            current_background: Color32::from_rgb(90, 74, 16),
            current_text: Color32::WHITE,
        },
        Theme::Light => CodePalette {
            background: Color32::from_rgb(240, 242, 246),
            text: Color32::from_gray(40),
            current_background: Color32::from_rgb(255, 222, 120),
            current_text: Color32::BLACK,
        },
    }
}

/// Weak text (hints, notes) in `theme`: dimmer than the body text, still AA on the panels.
pub fn weak_text(theme: Theme) -> Color32 {
    match theme {
        Theme::Dark => Color32::from_gray(150),
        Theme::Light => Color32::from_gray(96),
    }
}

/// The status line's messages (a refused file, a check's verdict) in `theme`: amber, to stand
/// out from the hints beside them, and AA on the panels (the drawing's selection yellow is
/// 1.4:1 on the light panel).
pub fn message_text(theme: Theme) -> Color32 {
    match theme {
        Theme::Dark => Color32::from_rgb(255, 210, 80),
        Theme::Light => Color32::from_rgb(140, 90, 0),
    }
}

/// The lab's text sizes and weak text colour, in both themes' styles (the page follows the
/// system's theme). Idempotent.
pub fn install(ctx: &egui::Context) {
    for theme in [Theme::Dark, Theme::Light] {
        ctx.style_mut_of(theme, |style| {
            for font in style.text_styles.values_mut() {
                font.size = font.size.max(SMALLEST_TEXT);
            }
            style.visuals.weak_text_color = Some(weak_text(theme));
            // Thin scroll bars that stay drawn while there is more to see: egui's floating
            // ones show only under the pointer, and a table or listing wider than its panel
            // looked cut at the panel's edge ("naive: t in" read "naive: t i").
            style.spacing.scroll = egui::style::ScrollStyle::thin();
            if theme == Theme::Dark {
                // egui's dark body text (gray 140) is 5:1 on its panels; a little brighter
                // so that weak text can be dimmer and still pass.
                style.visuals.widgets.noninteractive.fg_stroke.color = Color32::from_gray(175);
            }
        });
    }
}

/// A colour's relative luminance (WCAG 2: linearised sRGB, weighted). Alpha is ignored.
pub fn luminance(c: Color32) -> f32 {
    let [r, g, b, _] = c.to_srgba_unmultiplied();
    let lin = |v: u8| {
        let v = f32::from(v) / 255.0;
        if v <= 0.040_45 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b)
}

/// The contrast ratio of two opaque colours (1 to 21), as WCAG 2 defines it.
pub fn contrast(a: Color32, b: Color32) -> f32 {
    let (la, lb) = (luminance(a), luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contrast_matches_wcags_examples() {
        assert!((contrast(Color32::BLACK, Color32::WHITE) - 21.0).abs() < 1e-3);
        assert!((contrast(Color32::RED, Color32::RED) - 1.0).abs() < 1e-6);
        // #777 on white is WCAG's well-known 4.48:1, just short of AA.
        assert!((contrast(Color32::from_gray(0x77), Color32::WHITE) - 4.48).abs() < 0.01);
    }

    #[test]
    fn the_status_lines_message_is_aa_on_the_panels_of_both_themes() {
        for theme in [Theme::Dark, Theme::Light] {
            let panel = match theme {
                Theme::Dark => egui::Visuals::dark(),
                Theme::Light => egui::Visuals::light(),
            }
            .panel_fill;
            let ratio = contrast(message_text(theme), panel);
            assert!(ratio >= AA_CONTRAST, "{theme:?}: {ratio:.2}:1");
        }
    }
}
