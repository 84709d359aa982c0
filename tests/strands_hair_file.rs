#![cfg(feature = "strands")]
//! Cem Yuksel's `.hair` files (`hairmath::strands::hair_file`): strands with every combination
//! of the optional arrays round-trip through the writer, a file written byte by byte from the
//! documented layout reads to its values, and every truncated, inconsistent or hostile file
//! gives a `HairFileError` naming the field and byte offset, whose message holds the numbers.
//! Random bytes and mutated files never panic, whatever reads is written back unchanged, and a
//! counting allocator shows the reader never allocates more than a small multiple of its
//! input, whatever the header's counts say.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::time::{Duration, Instant};

use glam::Vec3;
use hairmath::strands::hair_file::{
    read_hair, read_hair_file, write_hair, write_hair_file, HairFile, HairFileError,
};
use hairmath::strands::{PointAttribute, SegmentCounts, Strands};
use proptest::prelude::*;

/// The system allocator, recording the largest allocation of each thread.
struct Largest;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards every call to `System` unchanged; the bookkeeping only reads the layout and
// touches a const-initialised thread-local `Cell` (which does not allocate).
unsafe impl GlobalAlloc for Largest {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = LARGEST.try_with(|largest| largest.set(largest.get().max(layout.size())));
        // SAFETY: the caller's contract is `System.alloc`'s.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` was allocated by `System` with `layout`.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Largest = Largest;

/// `read_hair(bytes)` and the largest allocation it made (on this thread).
fn read_measured(bytes: &[u8]) -> (Result<HairFile, HairFileError>, usize) {
    LARGEST.with(|largest| largest.set(0));
    let read = read_hair(bytes);
    (read, LARGEST.with(Cell::get))
}

/// The layout's header with the given counts, bitfield and default segment count; the other
/// defaults are thickness 0.5, transparency 0.25, colour (0.1, 0.2, 0.3), info "hand written".
fn header(hair_count: u32, point_count: u32, arrays: u32, segments: u32) -> Vec<u8> {
    let mut bytes = b"HAIR".to_vec();
    for field in [hair_count, point_count, arrays, segments] {
        bytes.extend_from_slice(&field.to_le_bytes());
    }
    push_f32s(&mut bytes, &[0.5, 0.25, 0.1, 0.2, 0.3]);
    let mut info = [0u8; 88];
    info[..12].copy_from_slice(b"hand written");
    bytes.extend_from_slice(&info);
    assert_eq!(bytes.len(), 128);
    bytes
}

fn push_f32s(bytes: &mut Vec<u8>, values: &[f32]) {
    for v in values {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
}

const HAND_POINTS: [[f32; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.5, 2.0, 0.0],
    [1.0, 0.0, 1.0],
    [1.0, -1.0, 1.5],
];
const HAND_THICKNESS: [f32; 5] = [0.1, 0.09, 0.08, 0.2, 0.1];
const HAND_COLOURS: [[f32; 3]; 5] = [
    [0.9, 0.8, 0.7],
    [0.6, 0.5, 0.4],
    [0.3, 0.2, 0.1],
    [1.0, 0.0, 0.5],
    [0.0, 1.0, 2.0],
];

/// Two strands of 2 and 1 segments (5 points) with the segments, points, thickness and
/// colours arrays and no transparency array: segments at 128..132, points 132..192, thickness
/// 192..212, colours 212..272.
fn hand_written() -> Vec<u8> {
    let mut bytes = header(2, 5, 1 | 2 | 4 | 16, 7);
    for segments in [2u16, 1] {
        bytes.extend_from_slice(&segments.to_le_bytes());
    }
    push_f32s(&mut bytes, HAND_POINTS.as_flattened());
    push_f32s(&mut bytes, &HAND_THICKNESS);
    push_f32s(&mut bytes, HAND_COLOURS.as_flattened());
    assert_eq!(bytes.len(), 272);
    bytes
}

/// Writes `value` at `offset`.
fn patch(bytes: &mut [u8], offset: usize, value: [u8; 4]) {
    bytes[offset..offset + 4].copy_from_slice(&value);
}

/// The strands of the round trip: segments per strand (2, 0, 3, 1: 10 points) or uniform (4
/// strands of 2: 12 points), and thickness, transparency and colours per point or uniform, as
/// the bits 1, 2, 4 and 8 of `optional` say.
fn strands_with(optional: u32) -> Strands {
    let segments = if optional & 1 != 0 {
        SegmentCounts::PerStrand(vec![2, 0, 3, 1])
    } else {
        SegmentCounts::Uniform {
            strands: 4,
            segments: 2,
        }
    };
    let n = if optional & 1 != 0 { 10 } else { 12 };
    let per_point = |bit: u32| optional & bit != 0;
    let points = (0..n)
        .map(|i| Vec3::new(i as f32, 0.5 * i as f32, -(i as f32) * 0.25))
        .collect();
    let thickness = attribute(per_point(2), 0.02, n, |i| 0.01 * (i + 1) as f32);
    let transparency = attribute(per_point(4), 0.25, n, |i| i as f32 / n as f32);
    let colour = attribute(per_point(8), Vec3::new(0.4, 0.3, 0.2), n, |i| {
        Vec3::new(0.1 * i as f32, 0.2, 0.3)
    });
    Strands::new(segments, points, thickness, transparency, colour).expect("valid strands")
}

fn attribute<T>(
    per_point: bool,
    uniform: T,
    n: usize,
    value: impl Fn(usize) -> T,
) -> PointAttribute<T> {
    if per_point {
        PointAttribute::PerPoint((0..n).map(value).collect())
    } else {
        PointAttribute::Uniform(uniform)
    }
}

/// Writes `file`, reads it back and checks it is unchanged.
fn rewrites(file: &HairFile) -> Result<(), TestCaseError> {
    let bytes = write_hair(file).map_err(|e| TestCaseError::fail(e.to_string()))?;
    let again = read_hair(&bytes).map_err(|e| TestCaseError::fail(e.to_string()))?;
    prop_assert_eq!(&again, file);
    Ok(())
}

#[test]
fn every_combination_of_arrays_round_trips() {
    for optional in 0..16u32 {
        let strands = strands_with(optional);
        let (h, p) = (strands.strand_count(), strands.point_count());
        let file = HairFile {
            strands,
            info: format!("optional arrays {optional:04b}: ✓"),
        };
        let bytes = write_hair(&file).expect("writes");
        let present = |bit: u32, size: usize| usize::from(optional & bit != 0) * size;
        let length = 128
            + present(1, 2 * h)
            + 12 * p
            + present(2, 4 * p)
            + present(4, 4 * p)
            + present(8, 12 * p);
        assert_eq!(bytes.len(), length, "optional arrays {optional:04b}");
        let bits = u32::from_le_bytes(bytes[12..16].try_into().unwrap());
        let expected = (optional & 1) | 2 | ((optional & 14) << 1);
        assert_eq!(bits, expected, "optional arrays {optional:04b}");
        assert_eq!(read_hair(&bytes).expect("reads"), file);
    }
}

#[test]
fn uniform_values_are_the_header_defaults() {
    let bytes = write_hair(&HairFile {
        strands: strands_with(0),
        info: String::new(),
    })
    .expect("writes");
    assert_eq!(u32::from_le_bytes(bytes[4..8].try_into().unwrap()), 4);
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 12);
    assert_eq!(u32::from_le_bytes(bytes[16..20].try_into().unwrap()), 2);
    let f32_at = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    assert_eq!(
        [f32_at(20), f32_at(24), f32_at(28), f32_at(32), f32_at(36)],
        [0.02, 0.25, 0.4, 0.3, 0.2]
    );
    assert_eq!(bytes[40..128], [0; 88]);
}

#[test]
fn a_file_written_from_the_layout_reads_to_its_values() {
    let file = read_hair(&hand_written()).expect("reads");
    assert_eq!(file.info, "hand written");
    let strands = &file.strands;
    assert_eq!(strands.segments(), &SegmentCounts::PerStrand(vec![2, 1]));
    assert_eq!(strands.strand_count(), 2);
    assert_eq!(strands.strand_points(0), Some(0..3));
    assert_eq!(strands.strand_points(1), Some(3..5));
    let points: Vec<Vec3> = HAND_POINTS.iter().map(|&p| Vec3::from_array(p)).collect();
    assert_eq!(strands.points(), points.as_slice());
    assert_eq!(
        strands.thickness(),
        &PointAttribute::PerPoint(HAND_THICKNESS.to_vec())
    );
    // No transparency array: the header's default for every point.
    assert_eq!(strands.transparency(), &PointAttribute::Uniform(0.25));
    let colours = HAND_COLOURS.iter().map(|&c| Vec3::from_array(c)).collect();
    assert_eq!(strands.colour(), &PointAttribute::PerPoint(colours));
}

#[test]
fn a_file_with_only_points_takes_every_default() {
    // Three strands of one segment each: 6 points, every other value from the header.
    let mut bytes = header(3, 6, 2, 1);
    push_f32s(&mut bytes, &[1.0; 18]);
    let strands = read_hair(&bytes).expect("reads").strands;
    assert_eq!(
        strands.segments(),
        &SegmentCounts::Uniform {
            strands: 3,
            segments: 1
        }
    );
    assert_eq!(strands.points(), &[Vec3::ONE; 6]);
    assert_eq!(strands.thickness(), &PointAttribute::Uniform(0.5));
    assert_eq!(strands.transparency(), &PointAttribute::Uniform(0.25));
    assert_eq!(
        strands.colour(),
        &PointAttribute::Uniform(Vec3::new(0.1, 0.2, 0.3))
    );
    assert_eq!(strands.strand_points(2), Some(4..6));
}

/// Reads `bytes`, expecting an error at `field` and `offset` whose message contains every one
/// of `numbers`.
#[track_caller]
fn expect_error(bytes: &[u8], field: &str, offset: u64, numbers: &[&str]) -> HairFileError {
    let error = read_hair(bytes).expect_err("a bad file");
    check_error(&error, field, offset, numbers);
    error
}

#[track_caller]
fn check_error(error: &HairFileError, field: &str, offset: u64, numbers: &[&str]) {
    let message = error.to_string();
    assert_eq!(error.field(), Some(field), "{message}");
    assert_eq!(error.offset(), Some(offset), "{message}");
    for number in numbers {
        assert!(message.contains(number), "{message:?} lacks {number:?}");
    }
}

#[test]
fn a_bad_signature_is_an_error() {
    let mut bytes = hand_written();
    bytes[..4].copy_from_slice(b"HAIX");
    let error = expect_error(&bytes, "signature", 0, &["\"HAIX\"", "\"HAIR\""]);
    assert!(matches!(error, HairFileError::Signature { found } if &found == b"HAIX"));
    bytes[..4].copy_from_slice(&[0, 255, b'\n', b'"']);
    expect_error(&bytes, "signature", 0, &["\\x00\\xff\\n\\\""]);
}

#[test]
fn a_file_without_points_is_an_error() {
    let mut bytes = hand_written();
    patch(&mut bytes, 12, (1u32 | 4 | 16).to_le_bytes());
    let error = expect_error(&bytes, "arrays", 12, &["21", "0x15", "bit 2"]);
    assert!(matches!(error, HairFileError::MissingPoints { arrays: 21 }));
}

#[test]
fn unknown_array_bits_are_an_error() {
    let mut bytes = hand_written();
    patch(&mut bytes, 12, (2u32 | 32).to_le_bytes());
    expect_error(&bytes, "arrays", 12, &["34", "0x22", "0x20", "16 colours"]);
    patch(&mut bytes, 12, u32::MAX.to_le_bytes());
    expect_error(&bytes, "arrays", 12, &["4294967295", "0xffffffe0"]);
}

#[test]
fn a_truncated_header_names_the_field_it_ends_in() {
    let bytes = hand_written();
    for (len, field, offset) in [
        (0, "signature", 0),
        (3, "signature", 0),
        (4, "hair count", 4),
        (10, "point count", 8),
        (12, "arrays", 12),
        (19, "segments", 16),
        (20, "thickness", 20),
        (27, "transparency", 24),
        (39, "colours", 28),
        (40, "info", 40),
        (127, "info", 40),
    ] {
        let error = expect_error(&bytes[..len], field, offset, &[&len.to_string(), "0..128"]);
        assert!(matches!(error, HairFileError::TruncatedHeader { .. }));
    }
}

#[test]
fn a_truncated_array_names_the_array_and_its_bytes() {
    // 4 strands, 10 points, every array: segments 128..136, points 136..256, thickness
    // 256..296, transparency 296..336, colours 336..456.
    let bytes = write_hair(&HairFile {
        strands: strands_with(15),
        info: String::new(),
    })
    .expect("writes");
    assert_eq!(bytes.len(), 456);
    for (field, start, end, count) in [
        ("segments", 128, 136, "4 segment counts"),
        ("points", 136, 256, "10 points"),
        ("thickness", 256, 296, "10 thickness values"),
        ("transparency", 296, 336, "10 transparency values"),
        ("colours", 336, 456, "10 colours"),
    ] {
        for len in [start, start + 1, end - 1] {
            let range = format!("{start}..{end}");
            let ends = format!("ends at byte {len}");
            expect_error(&bytes[..len], field, start as u64, &[&range, &ends, count]);
        }
    }
}

#[test]
fn a_point_count_that_does_not_match_the_segments_is_an_error() {
    let mut bytes = hand_written();
    patch(&mut bytes, 8, 6u32.to_le_bytes());
    let error = expect_error(&bytes, "point count", 8, &["6 points", "imply 5"]);
    assert!(matches!(
        error,
        HairFileError::PointCount {
            header: 6,
            implied: 5
        }
    ));
    // Without a segments array: 3 strands of 4 segments imply 15 points.
    let bytes = header(3, 14, 2, 4);
    expect_error(&bytes, "point count", 8, &["14 points", "imply 15"]);
}

#[test]
fn huge_counts_are_errors_without_huge_allocations() {
    let max = u64::from(u32::MAX);
    let hostile = [
        // u32::MAX strands with a segments array: 2 bytes each.
        (
            header(u32::MAX, 5, 1 | 2, 0),
            "segments",
            128,
            128 + 2 * max,
        ),
        // u32::MAX strands of one point, u32::MAX points: 12 bytes each.
        (
            header(u32::MAX, u32::MAX, 2, 0),
            "points",
            128,
            128 + 12 * max,
        ),
        (
            header(u32::MAX, u32::MAX, 31, 0),
            "segments",
            128,
            128 + 2 * max,
        ),
        // u32::MAX points but one strand: the counts disagree.
        (header(1, u32::MAX, 2, 0), "point count", 8, max),
        // u32::MAX strands of 65535 segments: about 2^48 points, more than a u32 counts.
        (header(u32::MAX, 7, 2, 65535), "point count", 8, max * 65536),
    ];
    for (mut bytes, field, offset, number) in hostile {
        bytes.extend_from_slice(&[0; 64]);
        let start = Instant::now();
        let (read, largest) = read_measured(&bytes);
        let error = read.expect_err("a hostile file");
        check_error(&error, field, offset, &[&number.to_string()]);
        assert!(largest < 4096, "{largest} bytes allocated for {error}");
        assert!(start.elapsed() < Duration::from_secs(1), "{error}");
    }
}

#[test]
fn a_nan_point_is_an_error_at_its_byte() {
    // Point 3 of the hand-written file starts at 128 + 2 * 2 + 12 * 3 = 168.
    for component in 0..3 {
        let mut bytes = hand_written();
        patch(&mut bytes, 168 + 4 * component, f32::NAN.to_le_bytes());
        let error = expect_error(&bytes, "points", 168, &["168", "NaN", "entry 3", "finite"]);
        assert!(matches!(
            error,
            HairFileError::BadValue { index: Some(3), .. }
        ));
    }
    let mut bytes = hand_written();
    patch(&mut bytes, 132 + 4, f32::INFINITY.to_le_bytes());
    expect_error(&bytes, "points", 132, &["inf", "entry 0"]);
}

#[test]
fn a_negative_thickness_is_an_error_at_its_byte() {
    // Thickness 2 of the hand-written file is at 192 + 4 * 2.
    let mut bytes = hand_written();
    patch(&mut bytes, 200, (-1.0f32).to_le_bytes());
    expect_error(&bytes, "thickness", 200, &["200", "-1", "entry 2", ">= 0"]);
    // Without a thickness array the header default is checked, at its header field.
    let mut bytes = header(1, 2, 2, 1);
    patch(&mut bytes, 20, (-0.5f32).to_le_bytes());
    push_f32s(&mut bytes, &[0.0; 6]);
    let error = expect_error(&bytes, "thickness", 20, &["-0.5", "header default"]);
    assert!(matches!(error, HairFileError::BadValue { index: None, .. }));
}

#[test]
fn a_transparency_outside_zero_one_is_an_error_at_its_byte() {
    // The hand-written file has no transparency array: its default (byte 24) is used.
    let mut bytes = hand_written();
    patch(&mut bytes, 24, 2.0f32.to_le_bytes());
    expect_error(&bytes, "transparency", 24, &["= 2 ", "[0, 1]"]);
    // With the array (296..336 in the written strands), transparency 4 is at 312.
    let mut bytes = write_hair(&HairFile {
        strands: strands_with(15),
        info: String::new(),
    })
    .expect("writes");
    patch(&mut bytes, 312, 2.0f32.to_le_bytes());
    expect_error(&bytes, "transparency", 312, &["312", "entry 4", "= 2 "]);
}

#[test]
fn a_negative_colour_is_an_error_at_its_byte() {
    // Colour 1 of the hand-written file starts at 212 + 12.
    let mut bytes = hand_written();
    patch(&mut bytes, 228, (-0.5f32).to_le_bytes());
    expect_error(&bytes, "colours", 224, &["224", "entry 1", "-0.5"]);
    let mut bytes = header(1, 1, 2, 0);
    patch(&mut bytes, 32, f32::INFINITY.to_le_bytes());
    push_f32s(&mut bytes, &[0.0; 3]);
    expect_error(
        &bytes,
        "colours",
        28,
        &["(0.1, inf, 0.3)", "header default"],
    );
}

#[test]
fn a_default_segment_count_above_u16_is_an_error_without_a_segments_array() {
    let bytes = header(1, 70001, 2, 70000);
    let error = expect_error(&bytes, "segments", 16, &["70000", "65535"]);
    assert!(matches!(
        error,
        HairFileError::DefaultSegments { segments: 70000 }
    ));
    // With the segments array the default is ignored.
    let mut bytes = hand_written();
    patch(&mut bytes, 16, u32::MAX.to_le_bytes());
    read_hair(&bytes).expect("the default is ignored");
}

#[test]
fn trailing_bytes_are_an_error() {
    let mut bytes = hand_written();
    bytes.extend_from_slice(&[0, 0, 0]);
    expect_error(&bytes, "colours", 272, &["272", "3 more bytes", "275"]);
    let mut bytes = header(1, 1, 2, 0);
    push_f32s(&mut bytes, &[0.0; 4]);
    expect_error(&bytes, "points", 140, &["140", "4 more bytes", "144"]);
}

#[test]
fn the_writer_rejects_an_info_the_header_cannot_hold() {
    let file = |info: String| HairFile {
        strands: strands_with(5),
        info,
    };
    let fits = file("a".repeat(87));
    let bytes = write_hair(&fits).expect("87 bytes fit");
    assert_eq!(bytes[127], 0);
    assert_eq!(read_hair(&bytes).expect("reads"), fits);
    for (long, bytes) in [
        ("a".repeat(88), "88 bytes"),
        ("é".repeat(44), "88 bytes"),
        ("✓".repeat(30), "90 bytes"),
    ] {
        let error = write_hair(&file(long)).expect_err("too long");
        check_error(&error, "info", 40, &[bytes, "at most 87"]);
        assert!(matches!(error, HairFileError::InfoTooLong { .. }));
    }
    let error = write_hair(&file("ab\0c".into())).expect_err("a NUL");
    check_error(&error, "info", 42, &["42", "NUL"]);
}

#[test]
fn the_reader_keeps_an_info_the_writer_can_write() {
    // 88 bytes without a NUL: the last is dropped.
    let mut bytes = hand_written();
    bytes[40..128].copy_from_slice(&[b'x'; 88]);
    let file = read_hair(&bytes).expect("reads");
    assert_eq!(file.info, "x".repeat(87));
    // Invalid UTF-8 becomes U+FFFD (3 bytes each), cut to 29 of them (87 bytes).
    bytes[40..128].copy_from_slice(&[0xff; 88]);
    let file = read_hair(&bytes).expect("reads");
    assert_eq!(file.info, "\u{fffd}".repeat(29));
    let bytes = write_hair(&file).expect("writes what it read");
    assert_eq!(read_hair(&bytes).expect("reads"), file);
}

#[test]
fn files_round_trip_and_io_errors_name_the_path() {
    let path = std::env::temp_dir().join(format!("hairmath-hair-file-{}.hair", std::process::id()));
    let file = HairFile {
        strands: strands_with(9),
        info: "on disk".into(),
    };
    write_hair_file(&path, &file).expect("writes the file");
    let read = read_hair_file(&path);
    std::fs::remove_file(&path).expect("removes the file");
    assert_eq!(read.expect("reads the file"), file);
    let error = read_hair_file(&path).expect_err("no such file");
    assert!(matches!(error, HairFileError::Io { .. }));
    assert_eq!((error.field(), error.offset()), (None, None));
    assert!(error.to_string().contains(&path.display().to_string()));
    let missing = path.join("in-a-file.hair");
    let error = write_hair_file(&missing, &file).expect_err("not a directory");
    assert!(error.to_string().contains(&missing.display().to_string()));
}

/// Every finite f32, mostly in a modest range.
fn finite() -> impl Strategy<Value = f32> + Clone {
    prop_oneof![
        3 => -100.0f32..100.0,
        1 => prop::num::f32::NORMAL | prop::num::f32::SUBNORMAL | prop::num::f32::ZERO,
    ]
}

fn vec3(component: impl Strategy<Value = f32> + Clone) -> impl Strategy<Value = Vec3> + Clone {
    [component.clone(), component.clone(), component].prop_map(Vec3::from_array)
}

/// An attribute uniform or per point (`n` points).
fn point_attribute<T: Clone + core::fmt::Debug>(
    value: impl Strategy<Value = T> + Clone,
    n: usize,
) -> impl Strategy<Value = PointAttribute<T>> {
    prop_oneof![
        value.clone().prop_map(PointAttribute::Uniform),
        proptest::collection::vec(value, n).prop_map(PointAttribute::PerPoint),
    ]
}

/// Valid strands: 0 to 5 strands of 0 to 4 segments, per strand or uniform, finite points and
/// every attribute uniform or per point.
fn any_strands() -> impl Strategy<Value = Strands> {
    let segments = prop_oneof![
        (0usize..6, 0u16..5)
            .prop_map(|(strands, segments)| SegmentCounts::Uniform { strands, segments }),
        proptest::collection::vec(0u16..5, 0..6).prop_map(SegmentCounts::PerStrand),
    ];
    segments
        .prop_flat_map(|segments| {
            let n = match &segments {
                SegmentCounts::Uniform { strands, segments } => strands * (*segments as usize + 1),
                SegmentCounts::PerStrand(counts) => counts.iter().map(|&s| s as usize + 1).sum(),
            };
            (
                Just(segments),
                proptest::collection::vec(vec3(finite()), n),
                point_attribute(0.0f32..10.0, n),
                point_attribute(0.0f32..=1.0, n),
                point_attribute(vec3(0.0f32..4.0), n),
            )
        })
        .prop_map(|(segments, points, thickness, transparency, colour)| {
            Strands::new(segments, points, thickness, transparency, colour).expect("valid")
        })
}

fn any_file() -> impl Strategy<Value = HairFile> {
    (any_strands(), "[a-zA-Z0-9 éß✓]{0,25}").prop_map(|(strands, info)| HairFile { strands, info })
}

/// A change to a valid file.
#[derive(Clone, Debug)]
enum Mutation {
    Flip(usize, u8),
    Overwrite(usize, u8),
    Insert(usize, u8),
    Remove(usize),
    Truncate(usize),
    /// Sets the hair count, point count, arrays or default segments (0 to 3).
    Header(usize, u32),
}

fn any_mutation() -> impl Strategy<Value = Mutation> {
    let position = any::<usize>();
    let count = prop_oneof![
        Just(u32::MAX),
        Just(u32::MAX / 2),
        Just(1 << 31),
        0u32..40,
        any::<u32>()
    ];
    prop_oneof![
        (position, 0u8..8).prop_map(|(at, bit)| Mutation::Flip(at, bit)),
        (position, any::<u8>()).prop_map(|(at, byte)| Mutation::Overwrite(at, byte)),
        (position, any::<u8>()).prop_map(|(at, byte)| Mutation::Insert(at, byte)),
        position.prop_map(Mutation::Remove),
        position.prop_map(Mutation::Truncate),
        (0usize..4, count).prop_map(|(field, value)| Mutation::Header(field, value)),
    ]
}

impl Mutation {
    fn apply(&self, bytes: &mut Vec<u8>) {
        let len = bytes.len();
        match *self {
            Mutation::Insert(at, byte) => bytes.insert(at % (len + 1), byte),
            Mutation::Header(field, value) => {
                if let Some(slot) = bytes.get_mut(4 + 4 * field..8 + 4 * field) {
                    slot.copy_from_slice(&value.to_le_bytes());
                }
            }
            _ if len == 0 => {}
            Mutation::Flip(at, bit) => bytes[at % len] ^= 1 << bit,
            Mutation::Overwrite(at, byte) => bytes[at % len] = byte,
            Mutation::Remove(at) => drop(bytes.remove(at % len)),
            Mutation::Truncate(at) => bytes.truncate(at % len),
        }
    }
}

/// Reads `bytes`: an error must name a field and offset; a file must write back unchanged; and
/// no allocation may exceed a small multiple of the input.
fn reads_or_locates(bytes: &[u8]) -> Result<(), TestCaseError> {
    let (read, largest) = read_measured(bytes);
    prop_assert!(
        largest <= 4 * bytes.len() + 1024,
        "{largest} bytes allocated for {} bytes of input",
        bytes.len()
    );
    match read {
        Ok(file) => rewrites(&file),
        Err(error) => {
            prop_assert!(
                error.field().is_some() && error.offset().is_some(),
                "{error}"
            );
            prop_assert!(!error.to_string().is_empty());
            Ok(())
        }
    }
}

/// A header that mostly passes the signature and bitfield checks, with counts small or huge.
fn any_header() -> impl Strategy<Value = Vec<u8>> {
    let count = prop_oneof![4 => 0u32..6, 1 => Just(u32::MAX), 1 => any::<u32>()];
    let arrays = prop_oneof![
        4 => (0u32..32).prop_map(|arrays| arrays | 2),
        1 => 0u32..32,
        1 => any::<u32>(),
    ];
    let segments = prop_oneof![4 => 0u32..4, 1 => 65530u32..65540, 1 => any::<u32>()];
    let values = proptest::collection::vec(any::<u8>(), 108);
    (count.clone(), count, arrays, segments, values).prop_map(
        |(hairs, points, arrays, segments, values)| {
            let mut bytes = b"HAIR".to_vec();
            for field in [hairs, points, arrays, segments] {
                bytes.extend_from_slice(&field.to_le_bytes());
            }
            bytes.extend_from_slice(&values);
            bytes
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        reads_or_locates(&bytes)?;
    }

    #[test]
    fn random_headers_never_panic(
        header in any_header(),
        body in proptest::collection::vec(any::<u8>(), 0..512),
    ) {
        let mut bytes = header;
        bytes.extend_from_slice(&body);
        reads_or_locates(&bytes)?;
    }

    #[test]
    fn mutated_files_never_panic(
        file in any_file(),
        mutations in proptest::collection::vec(any_mutation(), 1..5),
    ) {
        let mut bytes = write_hair(&file).expect("writes");
        for mutation in &mutations {
            mutation.apply(&mut bytes);
        }
        reads_or_locates(&bytes)?;
    }

    #[test]
    fn valid_strands_round_trip(file in any_file()) {
        rewrites(&file)?;
    }
}
