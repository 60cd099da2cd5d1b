//! The report in words, for a person who cannot see the drawing. Two uses, two amounts:
//!
//! - the drawing's description ([`crate::a11y::describe::drawing`]) holds every sentence
//!   ([`Report::text`]): the summary a student reads again at any time;
//! - the live region (`#lab-status`) says only the news: the sentences that differ from what
//!   it said last ([`news`]), so a step says its step, not the whole summary again, and a
//!   control's own change (which the control tells) adds nothing unless it changed the answer.
//!
//! Each sentence is one topic (the scene and structure, the answer, what it cost, the step,
//! the lesson, Predict), so that a change of one is told without the others.

use std::fmt::Write as _;

use super::{Report, Report3d};

impl Report {
    /// The report as sentences, one per topic, in reading order.
    pub fn sentences(&self) -> Vec<String> {
        let mut out = match &self.three {
            Some(three) => three.sentences(),
            None => self.sentences_2d(),
        };
        if let Some(step) = self.playback.first() {
            out.push(step.text().trim().to_owned());
        }
        if let Some(lesson) = &self.lesson {
            out.push(lesson.text());
        }
        if let Some(predict) = &self.predict {
            out.push(predict.text());
        }
        // The status line's message (a refused file, the lesson writer's verdict): the status
        // line is drawn, so a screen reader hears it here (the 3D half says its own above).
        if let Some(message) = &self.message
            && !out.contains(message)
        {
            out.push(message.clone());
        }
        out.retain(|s| !s.is_empty());
        out
    }

    /// The report as one text: every sentence.
    pub fn text(&self) -> String {
        self.sentences().join(" ")
    }

    fn sentences_2d(&self) -> Vec<String> {
        let mut out = vec![format!(
            "bvh-lab: {} primitives, {}.",
            self.scene.primitives, self.structure
        )];
        if let Some(q) = &self.query {
            out.push(match &q.hit {
                Some(h) => format!(
                    "Ray hits primitive {} at t = {:.3}, point ({:.2}, {:.2}).",
                    h.primitive, h.t, h.point[0], h.point[1]
                ),
                None => "Ray hits nothing.".to_owned(),
            });
            out.push(format!(
                "Nodes visited {}, bounding-volume tests {}, primitive tests {} (brute force {}).",
                q.nodes_visited, q.bound_tests, q.primitive_tests, q.brute_force_tests
            ));
        }
        if let Some(n) = &self.nearest
            && let Some((prim, _, d)) = n.nearest
        {
            out.push(format!("Nearest primitive {prim} at distance {d:.3}."));
        }
        out
    }
}

impl Report3d {
    /// The 3D view in sentences: the mesh and structure, the ray's hit or the point, what the
    /// query cost, the heat map's scale (its text equivalent: the colours only repeat it).
    pub fn sentences(&self) -> Vec<String> {
        let mut out = Vec::new();
        let mut head = format!(
            "bvh-lab, 3D: {}, {} triangles, {}",
            self.mesh.as_deref().unwrap_or("no mesh yet"),
            crate::model::dimension::thousands(self.triangles),
            self.structure
        );
        if let Some(f) = self.building {
            let _ = write!(head, ", building: {:.0}%", f * 100.0);
        }
        head.push('.');
        out.push(head);
        if self.ray.is_some() {
            out.push(match &self.hit {
                Some(h) => format!(
                    "Ray hits triangle {} at t = {:.3}, point ({:.2}, {:.2}, {:.2}).",
                    h.triangle, h.t, h.point[0], h.point[1], h.point[2]
                ),
                None => "Ray hits nothing.".to_owned(),
            });
        } else if let Some([x, y, z]) = self.point {
            out.push(format!("Query point at ({x:.2}, {y:.2}, {z:.2})."));
        }
        if let (Some([nodes, bounds, triangles]), Some(brute)) = (self.cost, self.brute_force_tests)
        {
            out.push(format!(
                "Nodes visited {nodes}, bounding-volume tests {bounds}, triangle tests \
                 {triangles} (brute force {brute})."
            ));
        }
        if let Some(heat) = &self.heat_map {
            out.push(if heat.progress < 1.0 {
                format!(
                    "Heat map of {}: {:.0}% traced.",
                    heat.metric,
                    heat.progress * 100.0
                )
            } else {
                format!(
                    "Heat map of {}: from 0, dark purple, to {}, bright yellow; the brighter a \
                     pixel, the more its ray cost.",
                    heat.metric, heat.max
                )
            });
        }
        if let Some(m) = &self.message {
            out.push(m.clone());
        }
        out
    }
}

/// What the live region says when the report goes from `told` (the sentences it said last)
/// to `now`: the sentences of `now` that `told` did not hold, in order; empty when nothing is
/// new. Steps taken faster than the region is written are coalesced by the caller, which
/// passes the last sentences told, not every frame's.
pub fn news(told: &[String], now: &[String]) -> String {
    now.iter()
        .filter(|s| !told.contains(s))
        .map(String::as_str)
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::news;

    fn said(s: &[&str]) -> Vec<String> {
        s.iter().map(|&s| s.to_owned()).collect()
    }

    #[test]
    fn the_news_is_what_changed() {
        let before = said(&[
            "20 primitives.",
            "Ray hits 3.",
            "Step 1 of 9: enter node 0.",
        ]);
        let after = said(&["20 primitives.", "Ray hits 3.", "Step 2 of 9: test node 1."]);
        assert_eq!(news(&before, &after), "Step 2 of 9: test node 1.");
        assert_eq!(news(&after, &after), "");
        assert_eq!(news(&[], &after), after.join(" "));
    }
}
