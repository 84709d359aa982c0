//! `.hair` files: [`read_hair`] turns the bytes of a file into validated [`Strands`],
//! [`write_hair`] turns strands back into bytes, and [`read_hair_file`] / [`write_hair_file`] do
//! the same with files.
//!
//! The layout is that of Cem Yuksel's HAIR file format, cyHairFile.h (cyCodeBase). Every number
//! is little-endian. A 128-byte header:
//!
//! | bytes    | field          | meaning                                                      |
//! |----------|----------------|--------------------------------------------------------------|
//! | 0..4     | `signature`    | `b"HAIR"`                                                    |
//! | 4..8     | `hair count`   | u32, the number of strands                                   |
//! | 8..12    | `point count`  | u32, the number of points over all strands                   |
//! | 12..16   | `arrays`       | u32 bitfield: 1 segments, 2 points, 4 thickness, 8 transparency, 16 colours |
//! | 16..20   | `segments`     | u32, the segment count of every strand without a segments array |
//! | 20..24   | `thickness`    | f32, the thickness of every point without a thickness array  |
//! | 24..28   | `transparency` | f32, the transparency of every point without its array       |
//! | 28..40   | `colours`      | 3 x f32, the colour of every point without a colours array   |
//! | 40..128  | `info`         | 88 bytes of text, NUL-terminated                             |
//!
//! then the arrays the bitfield declares, in this order: `segments` (u16 per strand), `points`
//! (3 x f32 per point), `thickness` (f32 per point), `transparency` (f32 per point) and
//! `colours` (3 x f32 per point). An absent array means the header's default for every strand
//! or point, which is what [`SegmentCounts::Uniform`] and [`PointAttribute::Uniform`] hold: the
//! writer stores an array exactly where the strands hold [`SegmentCounts::PerStrand`] or
//! [`PointAttribute::PerPoint`], so a file read and written back is the same [`HairFile`].
//!
//! Decisions where the format leaves a choice:
//! - The points array is required: a file without bit 2 has no geometry
//!   ([`HairFileError::MissingPoints`]).
//! - A bit above 16 is an error ([`HairFileError::UnknownArrays`]): an array this reader does
//!   not know would shift every array after it.
//! - Without a segments array the default segment count must fit a u16, as the segments array's
//!   entries do ([`HairFileError::DefaultSegments`]); with one, the default is ignored.
//! - The sum over strands of `segments + 1` must equal the point count (computed in u64, which
//!   no u32 count times a u16 can overflow; [`HairFileError::PointCount`]).
//! - Bytes after the last array are an error ([`HairFileError::TrailingBytes`]): they mean the
//!   header's counts or bitfield are wrong.
//! - `info` is the text up to the first NUL, decoded as UTF-8 lossily (an invalid byte becomes
//!   U+FFFD) and cut at a character boundary to at most 87 bytes, so whatever [`read_hair`]
//!   returns [`write_hair`] can write. The writer rejects an info longer than 87 bytes (the
//!   88th is the terminating NUL; [`HairFileError::InfoTooLong`]) or holding a NUL
//!   ([`HairFileError::InfoNul`]) rather than cutting it silently; it pads with NULs.
//! - Values are validated by [`Strands::new`] (finite points, finite thickness >= 0,
//!   transparency in `[0, 1]`, finite colours >= 0), and a bad one is reported at its byte in
//!   the file: the array's start plus the index times the entry's size, or the header field's
//!   offset for a default ([`HairFileError::BadValue`]). A header default the file overrides
//!   with an array is not read, so not validated.
//! - The header defaults the writer stores next to an array (which readers ignore) are those
//!   of cyHairFile.h: 0 segments, thickness 1, transparency 0, colour (1, 1, 1).
//!
//! Hostile headers cannot make the reader allocate: every array's byte range is computed with
//! saturating u64 arithmetic and checked against the input before anything is allocated, so a
//! vector is never longer than the bytes it is read from.
//!
//! ```
//! use glam::Vec3;
//! use hairmath::strands::hair_file::{read_hair, write_hair, HairFile};
//! use hairmath::strands::{PointAttribute, SegmentCounts, Strands};
//!
//! let strands = Strands::new(
//!     SegmentCounts::Uniform { strands: 1, segments: 1 },
//!     vec![Vec3::ZERO, Vec3::Y],
//!     PointAttribute::Uniform(0.01),
//!     PointAttribute::PerPoint(vec![0.0, 0.5]),
//!     PointAttribute::Uniform(Vec3::ONE),
//! )?;
//! let file = HairFile { strands, info: "one strand".into() };
//! let bytes = write_hair(&file)?;
//! assert_eq!(bytes.len(), 128 + 2 * 12 + 2 * 4);
//! assert_eq!(read_hair(&bytes)?, file);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::{PointAttribute, SegmentCounts, Strands, StrandsError};

/// The size of the header in bytes.
pub const HEADER_BYTES: usize = 128;
/// The longest `info` text in bytes (the header's 88 info bytes end with a NUL).
pub const MAX_INFO_BYTES: usize = 87;

const SIGNATURE: &[u8; 4] = b"HAIR";
const HAIR_COUNT_AT: usize = 4;
const POINT_COUNT_AT: usize = 8;
const ARRAYS_AT: usize = 12;
const SEGMENTS_AT: usize = 16;
const THICKNESS_AT: usize = 20;
const TRANSPARENCY_AT: usize = 24;
const COLOURS_AT: usize = 28;
const INFO_AT: usize = 40;

/// The header's fields and their offsets, in file order (to name the field a short file ends
/// in).
const HEADER_FIELDS: [(&str, usize); 9] = [
    ("signature", 0),
    ("hair count", HAIR_COUNT_AT),
    ("point count", POINT_COUNT_AT),
    ("arrays", ARRAYS_AT),
    ("segments", SEGMENTS_AT),
    ("thickness", THICKNESS_AT),
    ("transparency", TRANSPARENCY_AT),
    ("colours", COLOURS_AT),
    ("info", INFO_AT),
];

/// One of the arrays after the header: its field name, what its entries are, and its bit.
struct Array {
    field: &'static str,
    entries: &'static str,
    bit: u32,
}

const SEGMENTS: Array = Array {
    field: "segments",
    entries: "segment counts",
    bit: 1,
};
const POINTS: Array = Array {
    field: "points",
    entries: "points",
    bit: 2,
};
const THICKNESS: Array = Array {
    field: "thickness",
    entries: "thickness values",
    bit: 4,
};
const TRANSPARENCY: Array = Array {
    field: "transparency",
    entries: "transparency values",
    bit: 8,
};
const COLOURS: Array = Array {
    field: "colours",
    entries: "colours",
    bit: 16,
};
const KNOWN_ARRAYS: u32 = 31;

/// The contents of a `.hair` file (Cem Yuksel's HAIR file format, cyHairFile.h): the strands
/// and the header's info text.
#[derive(Clone, Debug, PartialEq)]
pub struct HairFile {
    /// The strands, with uniform segment counts and attributes where the file has no array.
    pub strands: Strands,
    /// The header's info text (at most [`MAX_INFO_BYTES`] bytes, no NUL, to be written).
    pub info: String,
}

/// Why a `.hair` file could not be read or written: the field (as the format names it:
/// `signature`, `hair count`, `point count`, `arrays`, `segments`, `points`, `thickness`,
/// `transparency`, `colours` or `info`), its byte offset, what was wrong and what is allowed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HairFileError {
    /// The file does not start with `HAIR`.
    #[error(
        "signature at byte 0: the file starts with \"{}\", but a .hair file starts with \"HAIR\"",
        .found.escape_ascii()
    )]
    Signature {
        /// The first four bytes.
        found: [u8; 4],
    },
    /// The file ends inside the 128-byte header.
    #[error(
        "{field} at byte {offset}: file ends at byte {file_len}, but the header needs bytes \
         0..128"
    )]
    TruncatedHeader {
        /// The header field the file ends in.
        field: &'static str,
        /// That field's offset.
        offset: u64,
        /// The file's length.
        file_len: u64,
    },
    /// The file ends inside an array (or before it).
    #[error(
        "{field} array: file ends at byte {file_len}, but {count} {entries} need bytes \
         {offset}..{end}"
    )]
    TruncatedArray {
        /// The array.
        field: &'static str,
        /// Where the array starts.
        offset: u64,
        /// Where it would end.
        end: u64,
        /// Its number of entries (the hair count or the point count).
        count: u32,
        /// What the entries are, in words.
        entries: &'static str,
        /// The file's length.
        file_len: u64,
    },
    /// The arrays bitfield sets bits above 16.
    #[error(
        "arrays at byte 12: the bitfield {arrays} ({arrays:#x}) sets unknown bits {:#x}; allowed \
         are 1 segments, 2 points, 4 thickness, 8 transparency and 16 colours",
        .arrays & !KNOWN_ARRAYS
    )]
    UnknownArrays {
        /// The bitfield.
        arrays: u32,
    },
    /// The arrays bitfield has no points array.
    #[error(
        "arrays at byte 12: the bitfield {arrays} ({arrays:#x}) has no points array (bit 2), but \
         a .hair file must store its points"
    )]
    MissingPoints {
        /// The bitfield.
        arrays: u32,
    },
    /// Without a segments array, the default segment count does not fit a u16.
    #[error(
        "segments at byte 16: the default segment count is {segments}, but without a segments \
         array it must be at most 65535"
    )]
    DefaultSegments {
        /// The default segment count.
        segments: u32,
    },
    /// The point count does not match the strands' segment counts.
    #[error(
        "point count at byte 8: the header says {header} points, but the segment counts imply \
         {implied} (the sum over strands of segments + 1)"
    )]
    PointCount {
        /// The header's point count.
        header: u64,
        /// The number of points the segment counts imply.
        implied: u64,
    },
    /// A value outside its domain: a non-finite point, a negative thickness, a transparency
    /// outside `[0, 1]`, a negative colour.
    #[error("{field} at byte {offset}: {} = {value} is not allowed: {allowed}", entry(.index))]
    BadValue {
        /// The array or header field.
        field: &'static str,
        /// The value's byte offset.
        offset: u64,
        /// The entry's index in its array, or `None` for a header default.
        index: Option<usize>,
        /// The value as text (a point or colour as `(x, y, z)`).
        value: String,
        /// The domain, in words.
        allowed: &'static str,
    },
    /// Bytes after the last array.
    #[error(
        "{field} array ends at byte {offset}, but the file has {} more bytes (up to byte \
         {file_len}); a .hair file ends with its last array, so its hair count, point count or \
         arrays bitfield is wrong",
        extra(.file_len, .offset)
    )]
    TrailingBytes {
        /// The last array.
        field: &'static str,
        /// Where it ends.
        offset: u64,
        /// The file's length.
        file_len: u64,
    },
    /// The writer's strands have more strands or points than a u32 counts.
    #[error(
        "{field} at byte {offset}: {count} does not fit the format's u32 (at most 4294967295)"
    )]
    TooMany {
        /// `hair count` or `point count`.
        field: &'static str,
        /// The header field's offset.
        offset: u64,
        /// The count.
        count: usize,
    },
    /// The writer's info text is longer than the header holds.
    #[error(
        "info at byte 40: {bytes} bytes of UTF-8, but the header holds at most 87 (88 with the \
         terminating NUL)"
    )]
    InfoTooLong {
        /// The info's length in bytes.
        bytes: usize,
    },
    /// The writer's info text holds a NUL, which would end it in the file.
    #[error(
        "info at byte {}: a NUL at byte {index} of the text, but the info is NUL-terminated and \
         must not contain one",
        INFO_AT + .index
    )]
    InfoNul {
        /// The NUL's index in the text.
        index: usize,
    },
    /// The file is longer than [`MAX_HAIR_FILE_BYTES`] (read no further).
    #[error(
        "{}: longer than {max} bytes, the most a .hair file may have here (67 million points \
         with every array)",
        .path.display()
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// [`MAX_HAIR_FILE_BYTES`].
        max: u64,
    },
    /// Reading or writing the file failed.
    #[error("{}: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

impl HairFileError {
    /// The field the error is about, as the format names it (`None` for an I/O error or a file
    /// too large).
    pub fn field(&self) -> Option<&'static str> {
        match self {
            Self::Signature { .. } => Some("signature"),
            Self::UnknownArrays { .. } | Self::MissingPoints { .. } => Some("arrays"),
            Self::DefaultSegments { .. } => Some("segments"),
            Self::PointCount { .. } => Some("point count"),
            Self::InfoTooLong { .. } | Self::InfoNul { .. } => Some("info"),
            Self::TruncatedHeader { field, .. }
            | Self::TruncatedArray { field, .. }
            | Self::BadValue { field, .. }
            | Self::TrailingBytes { field, .. }
            | Self::TooMany { field, .. } => Some(*field),
            Self::TooLarge { .. } | Self::Io { .. } => None,
        }
    }

    /// The byte offset in the file the error is about (`None` for an I/O error): the field's
    /// offset, a bad value's own offset, where trailing bytes start, where a NUL in the info
    /// would be written, or where reading stopped in a file too large.
    pub fn offset(&self) -> Option<u64> {
        match self {
            Self::Signature { .. } => Some(0),
            Self::UnknownArrays { .. } | Self::MissingPoints { .. } => Some(ARRAYS_AT as u64),
            Self::DefaultSegments { .. } => Some(SEGMENTS_AT as u64),
            Self::PointCount { .. } => Some(POINT_COUNT_AT as u64),
            Self::InfoTooLong { .. } => Some(INFO_AT as u64),
            Self::InfoNul { index } => Some((INFO_AT + index) as u64),
            Self::TruncatedHeader { offset, .. }
            | Self::TruncatedArray { offset, .. }
            | Self::BadValue { offset, .. }
            | Self::TrailingBytes { offset, .. }
            | Self::TooMany { offset, .. } => Some(*offset),
            Self::TooLarge { max, .. } => Some(*max),
            Self::Io { .. } => None,
        }
    }
}

/// How a [`HairFileError::BadValue`] names its entry.
fn entry(index: &Option<usize>) -> String {
    index.map_or_else(|| "the header default".to_owned(), |i| format!("entry {i}"))
}

/// The number of trailing bytes of a [`HairFileError::TrailingBytes`].
fn extra(file_len: &u64, offset: &u64) -> u64 {
    file_len.saturating_sub(*offset)
}

/// Reads a `.hair` file from its bytes.
///
/// # Errors
/// A [`HairFileError`] naming the field and byte offset for a bad signature, a truncated
/// header or array, an arrays bitfield without points or with unknown bits, a default segment
/// count above 65535 without a segments array, a point count that does not match the segment
/// counts, trailing bytes, or a value [`Strands::new`] rejects.
pub fn read_hair(bytes: &[u8]) -> Result<HairFile, HairFileError> {
    let header = Header::read(bytes)?;
    let mut cursor = Cursor {
        bytes,
        at: HEADER_BYTES as u64,
        last: POINTS.field,
    };
    let segments = cursor.segments(&header)?;
    check_point_count(&segments, header.point_count)?;
    let points_at = cursor.at;
    let points = cursor.array(&POINTS, header.point_count, vec3_le)?;
    let (thickness, thickness_at) =
        cursor.attribute(&THICKNESS, &header, THICKNESS_AT, header.thickness, f32_le)?;
    let (transparency, transparency_at) = cursor.attribute(
        &TRANSPARENCY,
        &header,
        TRANSPARENCY_AT,
        header.transparency,
        f32_le,
    )?;
    let (colour, colours_at) =
        cursor.attribute(&COLOURS, &header, COLOURS_AT, header.colour, vec3_le)?;
    cursor.finish()?;
    let places = Places {
        points: Place {
            field: POINTS.field,
            start: points_at,
            stride: 12,
        },
        thickness: thickness_at,
        transparency: transparency_at,
        colours: colours_at,
    };
    let strands = Strands::new(segments, points, thickness, transparency, colour)
        .map_err(|e| places.locate(e))?;
    Ok(HairFile {
        strands,
        info: header.info,
    })
}

/// Reads the `.hair` file at `path`.
///
/// # Errors
/// [`HairFileError::Io`] naming the path if the file cannot be read,
/// [`HairFileError::TooLarge`] if it is longer than [`MAX_HAIR_FILE_BYTES`]; otherwise as
/// [`read_hair`].
pub fn read_hair_file(path: &Path) -> Result<HairFile, HairFileError> {
    use std::io::Read;
    let io = |source| HairFileError::Io {
        path: path.to_owned(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(MAX_HAIR_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_HAIR_FILE_BYTES {
        return Err(HairFileError::TooLarge {
            path: path.to_owned(),
            max: MAX_HAIR_FILE_BYTES,
        });
    }
    read_hair(&bytes)
}

/// The longest `.hair` file [`read_hair_file`] reads: 2 GiB (67 million points with every
/// array), so that a stream without end (`/dev/zero`) is refused after a bounded read.
pub const MAX_HAIR_FILE_BYTES: u64 = 1 << 31;

/// Writes strands as the bytes of a `.hair` file: an array exactly where the strands hold
/// [`SegmentCounts::PerStrand`] or [`PointAttribute::PerPoint`], the header default where they
/// hold a uniform value.
///
/// # Errors
/// [`HairFileError::TooMany`] if the strand or point count does not fit a u32;
/// [`HairFileError::InfoTooLong`] or [`HairFileError::InfoNul`] if the info is longer than
/// [`MAX_INFO_BYTES`] or holds a NUL.
pub fn write_hair(file: &HairFile) -> Result<Vec<u8>, HairFileError> {
    let strands = &file.strands;
    let hair_count = count_u32("hair count", HAIR_COUNT_AT, strands.strand_count())?;
    let point_count = count_u32("point count", POINT_COUNT_AT, strands.point_count())?;
    check_info(&file.info)?;
    let (segments, segment_array) = match strands.segments() {
        SegmentCounts::Uniform { segments, .. } => (u32::from(*segments), None),
        SegmentCounts::PerStrand(counts) => (0, Some(counts.as_slice())),
    };
    let (thickness, thickness_array) = split(strands.thickness(), 1.0);
    let (transparency, transparency_array) = split(strands.transparency(), 0.0);
    let (colour, colour_array) = split(strands.colour(), Vec3::ONE);
    let arrays = [
        (SEGMENTS.bit, segment_array.is_some()),
        (POINTS.bit, true),
        (THICKNESS.bit, thickness_array.is_some()),
        (TRANSPARENCY.bit, transparency_array.is_some()),
        (COLOURS.bit, colour_array.is_some()),
    ]
    .iter()
    .filter(|(_, present)| *present)
    .fold(0, |bits, (bit, _)| bits | bit);

    let mut out = Vec::new();
    out.extend_from_slice(SIGNATURE);
    for value in [hair_count, point_count, arrays, segments] {
        value.put(&mut out);
    }
    thickness.put(&mut out);
    transparency.put(&mut out);
    colour.put(&mut out);
    out.extend_from_slice(file.info.as_bytes());
    out.resize(HEADER_BYTES, 0);
    put_all(&mut out, segment_array);
    put_all(&mut out, Some(strands.points()));
    put_all(&mut out, thickness_array);
    put_all(&mut out, transparency_array);
    put_all(&mut out, colour_array);
    Ok(out)
}

/// Writes strands to the `.hair` file at `path`.
///
/// # Errors
/// As [`write_hair`], and [`HairFileError::Io`] naming the path if the file cannot be written.
pub fn write_hair_file(path: &Path, file: &HairFile) -> Result<(), HairFileError> {
    let bytes = write_hair(file)?;
    std::fs::write(path, bytes).map_err(|source| HairFileError::Io {
        path: path.to_owned(),
        source,
    })
}

/// The header's fields.
struct Header {
    hair_count: u32,
    point_count: u32,
    arrays: u32,
    segments: u32,
    thickness: f32,
    transparency: f32,
    colour: Vec3,
    info: String,
}

impl Header {
    /// The header of `bytes`, with the signature and the arrays bitfield checked.
    fn read(bytes: &[u8]) -> Result<Self, HairFileError> {
        if let Some(found) = bytes.first_chunk::<4>() {
            if found != SIGNATURE {
                return Err(HairFileError::Signature { found: *found });
            }
        }
        let Some(header) = bytes.first_chunk::<HEADER_BYTES>() else {
            return Err(truncated_header(bytes.len()));
        };
        let arrays = u32_at(header, ARRAYS_AT);
        if arrays & !KNOWN_ARRAYS != 0 {
            return Err(HairFileError::UnknownArrays { arrays });
        }
        if arrays & POINTS.bit == 0 {
            return Err(HairFileError::MissingPoints { arrays });
        }
        Ok(Self {
            hair_count: u32_at(header, HAIR_COUNT_AT),
            point_count: u32_at(header, POINT_COUNT_AT),
            arrays,
            segments: u32_at(header, SEGMENTS_AT),
            thickness: f32_at(header, THICKNESS_AT),
            transparency: f32_at(header, TRANSPARENCY_AT),
            colour: vec3_at(header, COLOURS_AT),
            info: read_info(header),
        })
    }

    /// Whether the file has `array`.
    fn has(&self, array: &Array) -> bool {
        self.arrays & array.bit != 0
    }
}

/// The error for a file of `len < 128` bytes: the header field it ends in.
fn truncated_header(len: usize) -> HairFileError {
    let (field, offset) = HEADER_FIELDS
        .iter()
        .rev()
        .find(|(_, offset)| *offset <= len)
        .copied()
        .unwrap_or(("signature", 0));
    HairFileError::TruncatedHeader {
        field,
        offset: offset as u64,
        file_len: len as u64,
    }
}

/// The info text: the bytes up to the first NUL, decoded lossily, cut at a character boundary
/// to at most [`MAX_INFO_BYTES`] bytes.
fn read_info(header: &[u8; HEADER_BYTES]) -> String {
    let field = header.get(INFO_AT..).unwrap_or_default();
    let text = field.split(|&b| b == 0).next().unwrap_or_default();
    let text = String::from_utf8_lossy(text);
    let end = text
        .char_indices()
        .map(|(i, c)| i + c.len_utf8())
        .take_while(|&end| end <= MAX_INFO_BYTES)
        .last()
        .unwrap_or(0);
    text.get(..end).unwrap_or_default().to_owned()
}

/// Reads the arrays after the header in order, each checked against the input's length before
/// it is allocated.
struct Cursor<'a> {
    bytes: &'a [u8],
    /// Where the next array starts.
    at: u64,
    /// The field of the last array read.
    last: &'static str,
}

impl Cursor<'_> {
    /// `count` entries of `N` bytes each, decoded by `decode`, from the cursor on.
    fn array<T, const N: usize>(
        &mut self,
        array: &Array,
        count: u32,
        decode: impl Fn(&[u8; N]) -> T,
    ) -> Result<Vec<T>, HairFileError> {
        let start = self.at;
        let end = start.saturating_add(u64::from(count).saturating_mul(N as u64));
        let slice = usize::try_from(start)
            .ok()
            .zip(usize::try_from(end).ok())
            .and_then(|(start, end)| self.bytes.get(start..end))
            .ok_or(HairFileError::TruncatedArray {
                field: array.field,
                offset: start,
                end,
                count,
                entries: array.entries,
                file_len: self.bytes.len() as u64,
            })?;
        self.at = end;
        self.last = array.field;
        Ok(slice.as_chunks::<N>().0.iter().map(decode).collect())
    }

    /// The segment counts: the segments array, or the header default for every strand.
    fn segments(&mut self, header: &Header) -> Result<SegmentCounts, HairFileError> {
        if header.has(&SEGMENTS) {
            let counts = self.array(&SEGMENTS, header.hair_count, |b: &[u8; 2]| {
                u16::from_le_bytes(*b)
            })?;
            return Ok(SegmentCounts::PerStrand(counts));
        }
        let segments =
            u16::try_from(header.segments).map_err(|_| HairFileError::DefaultSegments {
                segments: header.segments,
            })?;
        Ok(SegmentCounts::Uniform {
            strands: header.hair_count as usize,
            segments,
        })
    }

    /// A per-point attribute: its array if the file has one, else the header default at
    /// `default_at`; with where its values are in the file.
    fn attribute<T, const N: usize>(
        &mut self,
        array: &Array,
        header: &Header,
        default_at: usize,
        default: T,
        decode: impl Fn(&[u8; N]) -> T,
    ) -> Result<(PointAttribute<T>, Place), HairFileError> {
        if !header.has(array) {
            let place = Place {
                field: array.field,
                start: default_at as u64,
                stride: 0,
            };
            return Ok((PointAttribute::Uniform(default), place));
        }
        let place = Place {
            field: array.field,
            start: self.at,
            stride: N as u64,
        };
        let values = self.array(array, header.point_count, decode)?;
        Ok((PointAttribute::PerPoint(values), place))
    }

    /// Checks that the last array ends the file.
    fn finish(&self) -> Result<(), HairFileError> {
        let file_len = self.bytes.len() as u64;
        if file_len == self.at {
            Ok(())
        } else {
            Err(HairFileError::TrailingBytes {
                field: self.last,
                offset: self.at,
                file_len,
            })
        }
    }
}

/// Checks the header's point count against the segment counts.
fn check_point_count(segments: &SegmentCounts, point_count: u32) -> Result<(), HairFileError> {
    let implied = match segments {
        SegmentCounts::Uniform { strands, segments } => {
            (*strands as u64).saturating_mul(u64::from(*segments) + 1)
        }
        SegmentCounts::PerStrand(counts) => counts
            .iter()
            .fold(0u64, |sum, &s| sum.saturating_add(u64::from(s) + 1)),
    };
    if implied == u64::from(point_count) {
        Ok(())
    } else {
        Err(HairFileError::PointCount {
            header: point_count.into(),
            implied,
        })
    }
}

/// Where an attribute's values are in the file: `start + index * stride` (stride 0 for a
/// header default).
#[derive(Clone, Copy)]
struct Place {
    field: &'static str,
    start: u64,
    stride: u64,
}

/// Where each validated field's values are in the file.
struct Places {
    points: Place,
    thickness: Place,
    transparency: Place,
    colours: Place,
}

impl Places {
    /// The file error for an error of [`Strands::new`]: the field and byte offset of the bad
    /// value. (The reader checks the point count first and reads every per-point array with
    /// the point count's entries, so a wrong length cannot happen; it is reported as a point
    /// count mismatch.)
    fn locate(&self, error: StrandsError) -> HairFileError {
        match error {
            StrandsError::BadValue {
                field,
                index,
                value,
                allowed,
            } => {
                let place = match field {
                    "points" => self.points,
                    "thickness" => self.thickness,
                    "transparency" => self.transparency,
                    _ => self.colours,
                };
                let uniform = place.stride == 0;
                HairFileError::BadValue {
                    field: place.field,
                    offset: place
                        .start
                        .saturating_add((index as u64).saturating_mul(place.stride)),
                    index: (!uniform).then_some(index),
                    value,
                    allowed,
                }
            }
            StrandsError::WrongLength {
                expected, found, ..
            } => HairFileError::PointCount {
                header: found as u64,
                implied: expected as u64,
            },
        }
    }
}

/// `count` as a header count, or [`HairFileError::TooMany`].
fn count_u32(field: &'static str, offset: usize, count: usize) -> Result<u32, HairFileError> {
    u32::try_from(count).map_err(|_| HairFileError::TooMany {
        field,
        offset: offset as u64,
        count,
    })
}

/// Checks that `info` fits the header's info field.
fn check_info(info: &str) -> Result<(), HairFileError> {
    if info.len() > MAX_INFO_BYTES {
        return Err(HairFileError::InfoTooLong { bytes: info.len() });
    }
    match info.bytes().position(|b| b == 0) {
        Some(index) => Err(HairFileError::InfoNul { index }),
        None => Ok(()),
    }
}

/// An attribute as the header default and the array to write: the uniform value and no
/// array, or `absent` (the default a file with the array stores) and the values.
fn split<T: Copy>(attribute: &PointAttribute<T>, absent: T) -> (T, Option<&[T]>) {
    match attribute {
        PointAttribute::Uniform(value) => (*value, None),
        PointAttribute::PerPoint(values) => (absent, Some(values)),
    }
}

/// A value the file stores, written little-endian.
trait Put {
    fn put(&self, out: &mut Vec<u8>);
}

impl Put for u16 {
    fn put(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl Put for u32 {
    fn put(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl Put for f32 {
    fn put(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl Put for Vec3 {
    fn put(&self, out: &mut Vec<u8>) {
        for c in self.to_array() {
            c.put(out);
        }
    }
}

/// Writes an array if there is one.
fn put_all<T: Put>(out: &mut Vec<u8>, values: Option<&[T]>) {
    for value in values.unwrap_or_default() {
        value.put(out);
    }
}

/// The little-endian u32 at `bytes[at..at + 4]` of a fixed-size block (the offsets are
/// constants within the block, so no input can make it panic).
fn u32_at<const N: usize>(bytes: &[u8; N], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

/// The little-endian f32 at `bytes[at..at + 4]` of a fixed-size block.
fn f32_at<const N: usize>(bytes: &[u8; N], at: usize) -> f32 {
    f32::from_bits(u32_at(bytes, at))
}

/// The three little-endian f32 at `bytes[at..at + 12]` of a fixed-size block.
fn vec3_at<const N: usize>(bytes: &[u8; N], at: usize) -> Vec3 {
    Vec3::new(
        f32_at(bytes, at),
        f32_at(bytes, at + 4),
        f32_at(bytes, at + 8),
    )
}

/// An f32 array entry.
fn f32_le(bytes: &[u8; 4]) -> f32 {
    f32::from_le_bytes(*bytes)
}

/// A 3 x f32 array entry.
fn vec3_le(bytes: &[u8; 12]) -> Vec3 {
    vec3_at(bytes, 0)
}
