//! The separating-axis test of two OBBs in 3D (issue 32, part 2): the panel's 15 rows
//! against the boxes' corners projected here on each candidate axis, its verdict against the
//! core's `Obb3::overlaps` on seeded boxes, stepping through the axes, and a box put on a
//! brushed part's PCA box. Driven through the panel and the model's actions.

use bvhlab::Obb3;
use bvhlab::glam::Vec3;
use bvhlab::volume::AxisSource;
use bvhlab_app::LabApp;
use bvhlab_app::lab3d::sat::{SHADOW_A, SHADOW_B};
use bvhlab_app::model::Action3d;
use bvhlab_app::model::obb_pair3d::{BoxPose3, CANDIDATES, ObbPair3, axis_name};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

use crate::common::{act, click, labels, settle, shows};
use crate::view3d::{lab_3d, three};

/// A seeded stream of numbers in `[0, 1)` (splitmix64): the same boxes on every run.
struct Seeded(u64);

impl Seeded {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn vec(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) * (hi - lo) + Vec3::splat(lo)
    }

    fn pose(&mut self) -> BoxPose3 {
        BoxPose3 {
            center: self.vec(-1.5, 1.5),
            half: self.vec(0.1, 1.0),
            degrees: self.vec(-180.0, 180.0),
        }
    }
}

/// The candidate axis `source` of the two boxes, worked out here from their frames.
fn candidate(a: &Obb3, b: &Obb3, source: AxisSource) -> Option<Vec3> {
    match source {
        AxisSource::FaceA(i) => Some(a.axes[i]),
        AxisSource::FaceB(j) => Some(b.axes[j]),
        AxisSource::Edges(i, j) => a.axes[i].cross(b.axes[j]).try_normalize(),
    }
}

/// A box's shadow on `axis`: its eight corners projected, the least and the greatest.
fn shadow(obb: &Obb3, axis: Vec3) -> (f32, f32) {
    obb.corners()
        .map(|c| c.dot(axis))
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), s| {
            (lo.min(s), hi.max(s))
        })
}

fn pair(h: &Harness<'_, LabApp>) -> ObbPair3 {
    three(h).obb_pair.expect("the test is on")
}

#[test]
fn the_fifteen_axes_match_the_corners_shadows_and_the_verdict_the_cores_overlap() {
    let mut h = lab_3d();
    click(&mut h, "Show the bounding volumes");
    click(&mut h, "Separating-axis test of two OBBs (15 axes)");
    settle(&mut h);
    assert!(shows(&h, "axis 1 of 15: A face 0"));
    let mut seeded = Seeded(32);
    let (mut apart, mut overlapping) = (0, 0);
    for _ in 0..40 {
        let chosen = ObbPair3 {
            a: seeded.pose(),
            b: seeded.pose(),
            step: 0,
        };
        act(&mut h, Action3d::SetObbPair(Some(chosen)));
        settle(&mut h);
        let (a, b) = (chosen.a.obb(), chosen.b.obb());
        let tests = pair(&h).tests();
        for (source, test) in CANDIDATES.iter().zip(&tests) {
            let Some(test) = test else {
                // Left out only for (nearly) parallel edges.
                let (i, j) = match source {
                    AxisSource::Edges(i, j) => (*i, *j),
                    other => panic!("a face axis left out: {other:?}"),
                };
                assert!(a.axes[i].cross(b.axes[j]).length() < 1e-3);
                continue;
            };
            let axis = candidate(&a, &b, *source).expect("a direction");
            assert!(axis.dot(test.axis).abs() > 1.0 - 1e-5, "{source:?}");
            let sign = axis.dot(test.axis).signum();
            let slack = 1e-4 * (a.half_extents.length() + b.half_extents.length() + 3.0);
            for ((lo, hi), obb) in [(test.interval_a, &a), (test.interval_b, &b)] {
                let (mut x, mut y) = shadow(obb, axis);
                if sign < 0.0 {
                    (x, y) = (-y, -x);
                }
                assert!(
                    (lo - x).abs() <= slack && (hi - y).abs() <= slack,
                    "{source:?}: [{lo}, {hi}] against [{x}, {y}]"
                );
            }
            // The row says what the numbers say.
            let row = format!("[{:.3}, {:.3}]", test.interval_a.0, test.interval_a.1);
            assert!(shows(&h, &row), "{row}");
        }
        // The verdict is the core's, and the sentence names the first separating axis.
        if let Some(first) = pair(&h).separating() {
            assert!(!a.overlaps(&b));
            apart += 1;
            assert!(shows(&h, &format!("{} separates them", axis_name(first))));
            assert!(labels(&h).iter().any(|l| l.contains("boxes apart")));
        } else {
            assert!(a.overlaps(&b));
            overlapping += 1;
            assert!(shows(&h, "No axis separates them"));
            assert!(labels(&h).iter().any(|l| l.contains("boxes overlap")));
        }
    }
    assert!(
        apart >= 5 && overlapping >= 5,
        "both verdicts met: {apart} apart, {overlapping} overlapping"
    );
}

#[test]
fn the_axes_are_stepped_one_by_one_and_the_view_draws_the_shadows_of_the_one_looked_at() {
    let mut h = lab_3d();
    click(&mut h, "Show the bounding volumes");
    click(&mut h, "Separating-axis test of two OBBs (15 axes)");
    settle(&mut h);
    for clicks in 0..16 {
        let step = pair(&h).step;
        assert_eq!(step, clicks % 15, "after {clicks} clicks on Next");
        if let Some(test) = pair(&h).tests()[step] {
            let drawn = &h.state().ui.view3d.drawn[0].overlay;
            for (color, (lo, hi)) in [(SHADOW_A, test.interval_a), (SHADOW_B, test.interval_b)] {
                let shade = bvhlab_app::lab3d::draw::rgba(color, 1.0);
                let seg = drawn
                    .iter()
                    .find(|s| s.color == shade && s.width == 5.0)
                    .expect("the shadow is drawn");
                // Its length on the axis is the shadow's.
                let length = (seg.b - seg.a).dot(test.axis);
                assert!(
                    (length - (hi - lo)).abs() < 1e-3 * (1.0 + hi - lo),
                    "{length} against {}",
                    hi - lo
                );
            }
        }
        click(&mut h, "Next axis");
        settle(&mut h);
    }
    click(&mut h, "Previous axis");
    settle(&mut h);
    assert_eq!(pair(&h).step, 0);
}

#[test]
fn a_box_is_put_on_the_brushed_parts_pca_box() {
    let mut h = lab_3d();
    click(&mut h, "Show the bounding volumes");
    click(&mut h, "Separating-axis test of two OBBs (15 axes)");
    settle(&mut h);
    // Each number is named for screen readers by its box, row and axis.
    for name in [
        "A centre: x",
        "B half extents: y",
        "B turn about x, y, z: z",
    ] {
        assert!(h.query_by_label(name).is_some(), "a field named {name}");
    }
    click(&mut h, "A = the part's OBB");
    settle(&mut h);
    let fitted = three(&h)
        .part_fits()
        .and_then(|p| p.fits.as_ref())
        .expect("fits")
        .obb;
    let a = pair(&h).a.obb();
    let size = fitted.half_extents.max_element();
    assert!(a.center.distance(fitted.center) < 1e-5 * size);
    assert_eq!(a.half_extents, fitted.half_extents);
    for (ours, core) in a.axes.iter().zip(fitted.axes) {
        assert!(ours.dot(core) > 1.0 - 1e-5, "{ours} against {core}");
    }
    // A bad number is refused and changes nothing.
    let before = pair(&h);
    let mut bad = before;
    bad.b.half.x = -1.0;
    let refused = h.state_mut().apply(Action3d::SetObbPair(Some(bad)));
    assert!(refused.expect_err("refused").contains("half extents"));
    assert_eq!(pair(&h), before);
}

#[test]
fn the_two_boxes_put_the_trees_away_and_bring_them_back() {
    let mut h = lab_3d();
    assert!(three(&h).display.structure);
    // Without the volumes: the test is on its own in the panel.
    click(&mut h, "Separating-axis test of two OBBs (15 axes)");
    assert!(three(&h).obb_pair.is_some() && !three(&h).volumes.shown);
    assert!(!three(&h).display.structure && !three(&h).display.marks);
    // The volumes shown and hidden again while the boxes stay: the trees stay away.
    click(&mut h, "Show the bounding volumes");
    click(&mut h, "Show the bounding volumes");
    assert!(!three(&h).display.structure);
    act(&mut h, Action3d::SetObbPair(None));
    assert!(three(&h).display.structure && three(&h).display.marks);
}
