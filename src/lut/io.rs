//! Table files: raw little-endian f32 with a hand-written JSON description, and 8-bit PNG.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::table::{ParamValue, Table};
use super::{LutError, ShapeError};

/// The generator string written to every JSON description; bump the suffix when baked values
/// change.
pub const GENERATOR: &str = concat!("hairmath ", env!("CARGO_PKG_VERSION"), " lut/1");

/// The samples as little-endian f32 bytes, in the layout of [`Table`].
pub fn raw_bytes(table: &Table) -> Vec<u8> {
    table.data().iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A JSON string literal.
pub(crate) fn json_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A JSON number: Rust's shortest round-trip form (valid JSON for finite values); non-finite
/// values become `null`.
pub(crate) fn json_number(v: f64) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else {
        "null".to_string()
    }
}

fn json_numbers(v: impl IntoIterator<Item = f64>) -> String {
    let items: Vec<String> = v.into_iter().map(json_number).collect();
    format!("[{}]", items.join(", "))
}

/// The JSON description of `table` whose samples are in the file `data_file` (a name relative
/// to the JSON file). Keys: `format`, `generator`, `kind`, `description`, `data`, `encoding`,
/// `layout`, `sampling`, `axes` (name, min, max, size), `channels`, `channel_max`,
/// `png_scale`, `parameters`. Deterministic: the same table gives the same text.
pub fn json_description(table: &Table, data_file: &str) -> String {
    let meta = table.meta();
    let mut s = String::new();
    s.push_str("{\n");
    let _ = writeln!(s, "  \"format\": \"hairmath-lut\",");
    let _ = writeln!(s, "  \"generator\": {},", json_string(GENERATOR));
    let _ = writeln!(s, "  \"kind\": {},", json_string(&meta.kind));
    let _ = writeln!(s, "  \"description\": {},", json_string(&meta.description));
    let _ = writeln!(s, "  \"data\": {},", json_string(data_file));
    let _ = writeln!(s, "  \"encoding\": \"f32le\",");
    let _ = writeln!(
        s,
        "  \"layout\": \"channel fastest, then axis 0, axis 1, axis 2: index = ((k * n1 + j) * n0 + i) * channels + c\","
    );
    let _ = writeln!(
        s,
        "  \"sampling\": \"endpoints: sample i of n at min + i * (max - min) / (n - 1); linear interpolation per axis; clamp to edge\","
    );
    s.push_str("  \"axes\": [\n");
    let n_axes = table.axes().len();
    for (i, a) in table.axes().iter().enumerate() {
        let _ = writeln!(
            s,
            "    {{\"name\": {}, \"min\": {}, \"max\": {}, \"size\": {}}}{}",
            json_string(a.name()),
            json_number(a.min()),
            json_number(a.max()),
            a.size(),
            if i + 1 < n_axes { "," } else { "" }
        );
    }
    s.push_str("  ],\n");
    let names: Vec<String> = table.channels().iter().map(|c| json_string(c)).collect();
    let _ = writeln!(s, "  \"channels\": [{}],", names.join(", "));
    let _ = writeln!(
        s,
        "  \"channel_max\": {},",
        json_numbers(table.channel_max().into_iter().map(f64::from))
    );
    let _ = writeln!(
        s,
        "  \"png_scale\": {},",
        json_numbers(table.png_scale().into_iter().map(f64::from))
    );
    s.push_str("  \"parameters\": {");
    for (i, (name, value)) in meta.parameters.iter().enumerate() {
        let v = match value {
            ParamValue::Number(x) => json_number(*x),
            ParamValue::Numbers(xs) => json_numbers(xs.iter().copied()),
            ParamValue::Text(t) => json_string(t),
            ParamValue::Flag(b) => b.to_string(),
        };
        let _ = write!(
            s,
            "{}\n    {}: {}",
            if i > 0 { "," } else { "" },
            json_string(name),
            v
        );
    }
    s.push_str(if meta.parameters.is_empty() {
        "}\n"
    } else {
        "\n  }\n"
    });
    s.push_str("}\n");
    s
}

fn io_error(path: &Path, source: std::io::Error) -> LutError {
    LutError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Writes the samples to `path` (raw little-endian f32) and the JSON description to `path`
/// with `.json` appended (for example `gerard.f32` and `gerard.f32.json`). Returns the JSON
/// file's path.
///
/// # Errors
/// [`LutError::Io`] if a file cannot be written.
pub fn write_raw(table: &Table, path: &Path) -> Result<PathBuf, LutError> {
    std::fs::write(path, raw_bytes(table)).map_err(|e| io_error(path, e))?;
    let mut json_path = path.as_os_str().to_owned();
    json_path.push(".json");
    let json_path = PathBuf::from(json_path);
    let data_file = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    std::fs::write(&json_path, json_description(table, &data_file))
        .map_err(|e| io_error(&json_path, e))?;
    Ok(json_path)
}

/// Reads a raw little-endian f32 file.
///
/// # Errors
/// [`LutError::Io`] if it cannot be read, [`LutError::Shape`] if its length is not a multiple
/// of 4.
pub fn read_raw(path: &Path) -> Result<Vec<f32>, LutError> {
    let bytes = std::fs::read(path).map_err(|e| io_error(path, e))?;
    if bytes.len() % 4 != 0 {
        return Err(LutError::Shape(ShapeError::RawLength {
            path: path.display().to_string(),
            bytes: bytes.len(),
        }));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect())
}

/// The RGBA8 pixels of a 2D table (width = axis 0, rows = axis 1, first row = first sample of
/// axis 1): up to four `channels` go to R, G, B, A in order, each stored as
/// `round(255 clamp(value / scale, 0, 1))` with `scale` from [`Table::png_scale`]; missing
/// colour channels are 0 and a missing alpha is 255. Returns (width, height, pixels).
///
/// # Errors
/// [`LutError::Shape`] unless the table is 2D and `channels` names 1 to 4 existing channels.
pub fn quantize_rgba8(table: &Table, channels: &[usize]) -> Result<(u32, u32, Vec<u8>), LutError> {
    let axes = table.axes();
    let nc = table.channels().len();
    if axes.len() != 2 {
        return Err(LutError::Shape(ShapeError::ImageAxes { axes: axes.len() }));
    }
    if channels.is_empty() || channels.len() > 4 || channels.iter().any(|&c| c >= nc) {
        return Err(LutError::Shape(ShapeError::ImageChannels {
            channels: nc,
            requested: channels.to_vec(),
        }));
    }
    let (w, h) = (axes[0].size(), axes[1].size());
    let scale = table.png_scale();
    let mut pixels = Vec::with_capacity(w * h * 4);
    for texel in table.data().chunks_exact(nc) {
        for slot in 0..4 {
            let byte = match channels.get(slot) {
                Some(&c) => {
                    let v = f64::from(texel[c]) / f64::from(scale[c]);
                    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
                    (255.0 * v).round() as u8
                }
                None if slot == 3 => 255,
                None => 0,
            };
            pixels.push(byte);
        }
    }
    let dim = |n: usize| {
        u32::try_from(n).map_err(|_| LutError::Shape(ShapeError::ImageSize { pixels: n }))
    };
    Ok((dim(w)?, dim(h)?, pixels))
}

/// Writes up to four `channels` of a 2D table as an 8-bit RGBA PNG (see [`quantize_rgba8`]);
/// the matching JSON description gives each channel's `png_scale`. Only with the `cli`
/// feature.
///
/// # Errors
/// As [`quantize_rgba8`], and [`LutError::Io`] if the file cannot be written.
#[cfg(feature = "png")]
pub fn write_png(table: &Table, channels: &[usize], path: &Path) -> Result<(), LutError> {
    let (w, h, pixels) = quantize_rgba8(table, channels)?;
    let file = std::fs::File::create(path).map_err(|e| io_error(path, e))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), w, h);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let to_io = |e: png::EncodingError| match e {
        png::EncodingError::IoError(e) => io_error(path, e),
        other => io_error(path, std::io::Error::other(other.to_string())),
    };
    let mut writer = encoder.write_header().map_err(to_io)?;
    writer.write_image_data(&pixels).map_err(to_io)?;
    writer.finish().map_err(to_io)
}
