#![cfg(feature = "strands")]
//! Procedural grooms: seeded and deterministic (strand k does not depend on the strand count),
//! rooted on the scalp cap and outside the head, with the counts, thickness and shape asked
//! for; invalid settings give a `ParamError` naming the setting.

use glam::Vec3;
use hairmath::strands::groom::{groom, GroomKind, GroomSettings, SCALP_CAP_DEGREES};
use hairmath::strands::{PointAttribute, SegmentCounts, Strands};
use hairmath::ParamError;
use proptest::prelude::*;

fn grow(kind: GroomKind, strands: usize, points: usize, seed: u64) -> Strands {
    groom(&GroomSettings::new(kind, strands, points, seed)).expect("valid settings")
}

fn strand(strands: &Strands, k: usize) -> &[Vec3] {
    &strands.points()[strands.strand_points(k).expect("a strand")]
}

/// The length of a strand's polyline over the distance from its root to its tip.
fn tortuosity(points: &[Vec3]) -> f32 {
    let path: f32 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    path / points[0].distance(points[points.len() - 1])
}

#[test]
fn grooms_are_seeded_and_deterministic() {
    for kind in GroomKind::ALL {
        assert_eq!(grow(kind, 50, 16, 7), grow(kind, 50, 16, 7), "{kind:?}");
        assert_ne!(
            grow(kind, 50, 16, 7).points(),
            grow(kind, 50, 16, 8).points()
        );
    }
}

#[test]
fn a_strand_does_not_depend_on_the_strand_count() {
    let few = grow(GroomKind::Curly, 10, 24, 3);
    let many = grow(GroomKind::Curly, 200, 24, 3);
    for k in 0..10 {
        assert_eq!(strand(&few, k), strand(&many, k), "strand {k}");
    }
}

#[test]
fn counts_thickness_and_transparency_are_as_asked() {
    let settings = GroomSettings {
        transparency: 0.25,
        thickness: 0.01,
        ..GroomSettings::new(GroomKind::Wavy, 37, 9, 1)
    };
    let strands = groom(&settings).unwrap();
    assert_eq!(strands.strand_count(), 37);
    assert_eq!(strands.point_count(), 37 * 9);
    assert_eq!(
        strands.segments(),
        &SegmentCounts::Uniform {
            strands: 37,
            segments: 8
        }
    );
    assert_eq!(strands.transparency(), &PointAttribute::Uniform(0.25));
    let range = strands.strand_points(5).unwrap();
    let root = strands.thickness().at(range.start);
    let tip = strands.thickness().at(range.end - 1);
    assert_eq!(root, 0.01);
    assert!((tip - 0.005).abs() < 1e-7, "tip thickness {tip}");
}

#[test]
fn roots_are_on_the_scalp_and_strands_outside_the_head() {
    let cos_cap = SCALP_CAP_DEGREES.to_radians().cos();
    for kind in GroomKind::ALL {
        let strands = grow(kind, 300, 32, 11);
        for k in 0..strands.strand_count() {
            let points = strand(&strands, k);
            let root = points[0];
            assert!((root.length() - 1.0).abs() < 1e-5, "{kind:?} root {root}");
            assert!(
                root.y >= cos_cap - 1e-5,
                "{kind:?} root {root} below the cap"
            );
            for p in &points[1..] {
                assert!(p.length() >= 1.0, "{kind:?} point {p} inside the head");
            }
            // Gravity: the tip hangs below the root.
            assert!(points[points.len() - 1].y < root.y, "{kind:?} strand {k}");
        }
    }
}

#[test]
fn curly_strands_wind_more_than_wavy_ones_and_wavy_more_than_straight() {
    let mean = |kind| {
        let strands = grow(kind, 200, 64, 5);
        (0..200)
            .map(|k| tortuosity(strand(&strands, k)))
            .sum::<f32>()
            / 200.0
    };
    let (straight, wavy, curly) = (
        mean(GroomKind::Straight),
        mean(GroomKind::Wavy),
        mean(GroomKind::Curly),
    );
    assert!(straight < wavy && wavy < curly, "{straight} {wavy} {curly}");
}

#[test]
fn kinds_have_names() {
    for kind in GroomKind::ALL {
        assert_eq!(GroomKind::from_name(kind.name()), Some(kind));
    }
    assert_eq!(GroomKind::from_name("frizzy"), None);
}

fn rejected(settings: GroomSettings) -> &'static str {
    match groom(&settings) {
        Err(ParamError::OutOfRange { name, .. }) => name,
        other => panic!("{settings:?} gave {other:?}"),
    }
}

#[test]
fn invalid_settings_name_the_setting() {
    let base = GroomSettings::new(GroomKind::Straight, 10, 8, 0);
    assert_eq!(rejected(GroomSettings { strands: 0, ..base }), "strands");
    assert_eq!(
        rejected(GroomSettings {
            strands: 2_000_000,
            ..base
        }),
        "strands"
    );
    assert_eq!(rejected(GroomSettings { points: 1, ..base }), "points");
    assert_eq!(
        rejected(GroomSettings {
            points: 65_537,
            ..base
        }),
        "points"
    );
    assert_eq!(
        rejected(GroomSettings {
            strands: 1_000_000,
            points: 65,
            ..base
        }),
        "strands x points"
    );
    assert_eq!(
        rejected(GroomSettings {
            thickness: 0.0,
            ..base
        }),
        "thickness"
    );
    assert_eq!(
        rejected(GroomSettings {
            thickness: f32::NAN,
            ..base
        }),
        "thickness"
    );
    assert_eq!(
        rejected(GroomSettings {
            length: -1.0,
            ..base
        }),
        "length"
    );
    assert_eq!(
        rejected(GroomSettings {
            length: f32::INFINITY,
            ..base
        }),
        "length"
    );
    assert_eq!(
        rejected(GroomSettings {
            transparency: 1.5,
            ..base
        }),
        "transparency"
    );
    let message = groom(&GroomSettings { points: 1, ..base })
        .unwrap_err()
        .to_string();
    assert!(message.contains("[2, 65536]"), "{message}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn every_valid_groom_is_finite_and_complete(
        kind in prop::sample::select(GroomKind::ALL.to_vec()),
        strands in 1usize..40,
        points in 2usize..40,
        seed in any::<u64>(),
        thickness in 1e-4f32..0.1,
        length in 1e-3f32..10.0,
        transparency in 0.0f32..=1.0,
    ) {
        let settings = GroomSettings { kind, strands, points, seed, thickness, length, transparency };
        let groom = groom(&settings).unwrap();
        prop_assert_eq!(groom.point_count(), strands * points);
        prop_assert!(groom.points().iter().all(|p| p.is_finite() && p.length() >= 1.0 - 1e-5));
    }
}
