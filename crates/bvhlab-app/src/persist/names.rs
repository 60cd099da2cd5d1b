//! The words and numbers the scene format stores: a stable name for each of the lab's enums,
//! preset slugs, and coordinates that refuse to be infinite.
//!
//! Why mirror enums instead of deriving serde on the lab's own: the format must not change
//! when an app enum is renamed or reordered, and the core's [`SplitMethod`] and [`SphereFit`]
//! have no serde (the core depends on glam alone). Each name enum lists its strings literally
//! and converts to and from the lab's enum with `match`es the compiler checks are exhaustive
//! both ways, so a new variant cannot be saved without a name, nor a name read without a
//! variant. Serde rejects any other string with the list of the accepted ones.

use std::borrow::Cow;

use bvhlab::structure::SplitMethod;
use bvhlab::structure::bvh::SphereFit;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::model::presets::Preset;
use crate::model::refit::UpdateMode;
use crate::model::scene::ShapeKind;
use crate::model::structures::{KdSplit, StructureKind};
use crate::pseudocode::{Task, Variant};

use super::MAX_COORD;

/// Declares `$name`, the stored names of `$target`'s variants, with `From` both ways. A
/// variant may also be read under other names (`Variant = "name" | "other",`): it is always
/// written under the first.
macro_rules! stable_names {
    (
        $(#[$meta:meta])*
        $name:ident <=> $target:ident {
            $($variant:ident = $text:literal $(| $alias:literal)*,)+
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
        pub enum $name {
            $(
                #[doc = concat!(
                    "[`", stringify!($target), "::", stringify!($variant),
                    "`], stored as `\"", $text, "\"`."
                )]
                #[serde(rename = $text $(, alias = $alias)*)]
                $variant,
            )+
        }

        impl $name {
            /// Every stored name, in the order declared.
            pub const NAMES: &'static [&'static str] = &[$($text,)+];

            /// The variant stored as `text`, if any.
            pub fn from_name(text: &str) -> Option<Self> {
                match text {
                    $($text $(| $alias)* => Some(Self::$variant),)+
                    _ => None,
                }
            }
        }

        impl From<$target> for $name {
            fn from(value: $target) -> Self {
                match value {
                    $($target::$variant => Self::$variant,)+
                }
            }
        }

        impl From<$name> for $target {
            fn from(value: $name) -> Self {
                match value {
                    $($name::$variant => Self::$variant,)+
                }
            }
        }
    };
}

stable_names! {
    /// The structure's stored name.
    StructureName <=> StructureKind {
        BruteForce = "brute-force",
        SphereTree = "sphere-tree",
        AabbTree = "aabb-tree",
        ObbTree = "obb-tree",
        Grid = "grid",
        Bsp = "bsp",
        // In 3D the quadtree is an octree (the lab names it so there): a lesson's goal, an
        // address or an embedding page may say either.
        Quadtree = "quadtree" | "octree",
        KdTree = "kd-tree",
    }
}

stable_names! {
    /// The BVH split method's stored name.
    SplitName <=> SplitMethod {
        SpatialMedian = "spatial-median",
        ObjectMedian = "object-median",
        BinnedSah = "binned-sah",
    }
}

stable_names! {
    /// The sphere-tree node fit's stored name.
    SphereFitName <=> SphereFit {
        Ritter = "ritter",
        Welzl = "welzl",
    }
}

stable_names! {
    /// The k-d tree plane rule's stored name.
    KdSplitName <=> KdSplit {
        MedianRoundRobin = "median-round-robin",
        MedianLongest = "median-longest",
        Sah = "sah",
    }
}

stable_names! {
    /// What a lane does when the primitives move, as stored.
    UpdateName <=> UpdateMode {
        Rebuild = "rebuild",
        Refit = "refit",
    }
}

impl Default for UpdateName {
    fn default() -> Self {
        UpdateMode::default().into()
    }
}

impl UpdateName {
    /// Whether it is the default (rebuild), which files leave out.
    #[expect(
        clippy::trivially_copy_pass_by_ref,
        reason = "serde's skip_serializing_if passes a reference"
    )]
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

stable_names! {
    /// The shape kind's stored name.
    ShapeName <=> ShapeKind {
        Segment = "segment",
        Polyline = "polyline",
        Polygon = "polygon",
        Points = "points",
    }
}

stable_names! {
    /// The stepped-through task's stored name.
    TaskName <=> Task {
        FirstHit = "first-hit",
        AnyHit = "any-hit",
        AllHits = "all-hits",
        Nearest = "nearest",
        Range = "range",
        Build = "build",
    }
}

stable_names! {
    /// The algorithm variant's stored name.
    VariantName <=> Variant {
        Full = "full",
        Lecture = "lecture",
        LecturePruned = "lecture-pruned",
    }
}

/// A preset, stored as its [`Preset::slug`] (the same word `?preset=` takes in the address).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct PresetSlug(pub Preset);

impl Serialize for PresetSlug {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.0.slug())
    }
}

impl<'de> Deserialize<'de> for PresetSlug {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let slug = Cow::<str>::deserialize(deserializer)?;
        Preset::from_slug(&slug).map(Self).ok_or_else(|| {
            let known: Vec<&str> = Preset::ALL.iter().map(|p| p.slug()).collect();
            D::Error::custom(format!(
                "unknown preset \"{}\", expected one of {}",
                shorten(&slug, 40),
                known.join(", ")
            ))
        })
    }
}

/// A coordinate or length as the format stores it: an `f32`, written as the shortest decimal
/// that reads back to the same bits, and read through `f64` so that a number too large for
/// the lab is refused by name instead of silently becoming infinity. JSON has no NaN or
/// infinity, and a string where a number belongs is a type error.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
#[serde(transparent)]
pub struct Coord(pub f32);

impl<'de> Deserialize<'de> for Coord {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = f64::deserialize(deserializer)?;
        // Compared as f32: the limit itself (1e15 is 999,999,986,991,104 in f32) is written
        // as "1e15" and must read back. Too large a number becomes infinity here.
        let near = value as f32;
        if near.abs() <= MAX_COORD {
            Ok(Self(near))
        } else {
            Err(D::Error::custom(format!(
                "the number {value:e} is too large: coordinates and lengths must lie within ±{MAX_COORD:e}"
            )))
        }
    }
}

/// A point as the format stores it: `[x, y]`.
pub type StoredPoint = [Coord; 2];

/// `text` cut to at most `max` characters (with an ellipsis), so that a hostile file cannot
/// put a megabyte of text into the status line.
pub(crate) fn shorten(text: &str, max: usize) -> Cow<'_, str> {
    match text.char_indices().nth(max) {
        Some((cut, _)) => Cow::Owned(format!("{}…", &text[..cut])),
        None => Cow::Borrowed(text),
    }
}

/// What the lab says about a name it does not know: `no structure named "kdtree"; try
/// kd-tree, aabb-tree, ...`, every name it knows listed, the nearest spelling first (so a
/// dropped hyphen or a typo is answered with the name meant).
pub fn no_such_name(kind: &str, value: &str, names: &[&str]) -> String {
    let typed = comparable(value);
    let mut sorted: Vec<(usize, &str)> = names
        .iter()
        .map(|n| (edit_distance(&typed, &comparable(n)), *n))
        .collect();
    // Stable: equally near names keep their listed order.
    sorted.sort_by_key(|&(d, _)| d);
    let list: Vec<&str> = sorted.into_iter().map(|(_, n)| n).collect();
    format!(
        "no {kind} named \"{}\"; try {}",
        shorten(value, 40),
        list.join(", ")
    )
}

/// A name as compared for nearness: lower case, without hyphens, underscores and spaces.
fn comparable(text: &str) -> Vec<char> {
    text.chars()
        .take(64)
        .filter(|c| !matches!(c, '-' | '_' | ' '))
        .flat_map(char::to_lowercase)
        .collect()
}

/// Levenshtein's distance: the fewest insertions, deletions and substitutions from `a` to `b`.
fn edit_distance(a: &[char], b: &[char]) -> usize {
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substituted = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substituted.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}
