//! `hairmath plot`: S of one model beside the reference (Chiang's far field), against phi at
//! three inclinations ([`hairmath::diagnostics::lobe_curves`]) and against theta_i at three
//! azimuths ([`hairmath::diagnostics::theta_curves`]): six panels, the reference black, the
//! model red, S the mean over RGB, each panel scaled to its largest value. Written as SVG with
//! plotters (with titles and axes) when the path ends in `.svg`, otherwise as a PNG drawn
//! here: axes and curves, no text (no font is available to draw it). Every plotted number
//! comes from the library.

use crate::flags::{model_names, ModelFlags};
use crate::{with_stdout, CliError};
use clap::builder::PossibleValuesParser;
use clap::Args;
use hairmath::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, DEFAULT_FAR_FIELD_NODES};
use hairmath::diagnostics::{lobe_curves, theta_curves};
use hairmath::params::HairParams;
use hairmath::registry::find_model;
use hairmath::render::write_png;
use plotters::prelude::*;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The inclinations of the panels against phi, degrees.
const THETAS_DEG: [f64; 3] = [0.0, 30.0, 60.0];
/// The azimuths of the panels against theta, degrees.
const PHIS_DEG: [f64; 3] = [0.0, 90.0, 180.0];
/// Points per curve.
const SAMPLES: usize = 361;
/// The PNG's panel size in pixels.
const PANEL: (usize, usize) = (320, 220);

/// Arguments of `hairmath plot`.
#[derive(Args, Debug)]
pub struct PlotArgs {
    /// The scattering model. Inputs not given take the default hair's values (a real-time
    /// model's mapped inputs for it); the reference is the far field of the model's own hair
    /// for chiang, chiang-far and marschner, of the default hair otherwise.
    #[arg(long, default_value = "karis", value_parser = PossibleValuesParser::new(model_names()))]
    model: String,
    /// The models' inputs.
    #[command(flatten)]
    flags: ModelFlags,
    /// The file to write: SVG if it ends in `.svg`, PNG otherwise.
    #[arg(long)]
    out: PathBuf,
}

/// One panel: its title, x range and the model's and the reference's curves.
struct Panel {
    title: String,
    x: (f64, f64),
    model: Vec<(f64, f64)>,
    reference: Vec<(f64, f64)>,
}

/// Runs `hairmath plot`.
pub fn run(args: &PlotArgs) -> Result<(), CliError> {
    let entry =
        find_model(&args.model).ok_or_else(|| CliError::UnknownModel(args.model.clone()))?;
    let values = args.flags.values_at_default_hair(entry)?;
    let model = (entry.build)(&values)?;
    let hair = match entry.approximation {
        None => HairParams::from_inputs(&values).unwrap_or_default(),
        Some(_) => HairParams::default(),
    };
    let rule = FarFieldRule::gauss_legendre(DEFAULT_FAR_FIELD_NODES)?;
    let reference = ChiangFarField::with_rule(&hair, &rule);
    let panels = panels(model.as_ref(), &reference);
    let svg = args
        .out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    if svg {
        svg_plot(&args.out, entry.name, &panels)
            .map_err(|e| CliError::io(&args.out, std::io::Error::other(e)))?;
    } else {
        png_plot(&args.out, &panels)?;
    }
    with_stdout(|out| {
        writeln!(out, "{}: wrote {}", entry.name, args.out.display()).map_err(CliError::stdout)
    })
}

/// The mean over RGB.
fn mean(v: &[f64; 3]) -> f64 {
    (v[0] + v[1] + v[2]) / 3.0
}

/// The six panels: against phi (degrees) at each inclination, then against theta_i.
fn panels(model: &dyn Bcsdf<f64>, reference: &dyn Bcsdf<f64>) -> Vec<Panel> {
    let points = |xs: &[f64], v: &[[f64; 3]]| -> Vec<(f64, f64)> {
        xs.iter()
            .zip(v)
            .map(|(x, v)| (x.to_degrees(), mean(v)))
            .collect()
    };
    let by_phi = lobe_curves(model, &THETAS_DEG, SAMPLES)
        .into_iter()
        .zip(lobe_curves(reference, &THETAS_DEG, SAMPLES))
        .map(|(m, r)| Panel {
            title: format!(
                "S against phi, theta_i = {0}, theta_o = -{0} degrees",
                m.theta_deg
            ),
            x: (-180.0, 180.0),
            model: points(&m.phi, &m.value),
            reference: points(&r.phi, &r.value),
        });
    let by_theta = theta_curves(model, &PHIS_DEG, SAMPLES)
        .into_iter()
        .zip(theta_curves(reference, &PHIS_DEG, SAMPLES))
        .map(|(m, r)| Panel {
            title: format!(
                "S against theta_i, theta_o = 0, phi = {} degrees",
                m.phi_deg
            ),
            x: (-90.0, 90.0),
            model: points(&m.theta, &m.value),
            reference: points(&r.theta, &r.value),
        });
    by_phi.chain(by_theta).collect()
}

/// The largest finite value of a panel's curves (at least the smallest positive number).
fn top(panel: &Panel) -> f64 {
    panel
        .model
        .iter()
        .chain(&panel.reference)
        .map(|p| p.1)
        .filter(|v| v.is_finite())
        .fold(f64::MIN_POSITIVE, f64::max)
}

/// The panels as a PNG, three per row: a grey frame, the reference black, the model red.
fn png_plot(path: &Path, panels: &[Panel]) -> Result<(), CliError> {
    let (w, h) = PANEL;
    let (width, height) = (3 * w, panels.len().div_ceil(3) * h);
    let mut canvas = Canvas {
        width,
        rgb: vec![255; 3 * width * height],
    };
    for (k, panel) in panels.iter().enumerate() {
        let (left, upper) = ((k % 3) * w, (k / 3) * h);
        let (x0, y0, x1, y1) = (left + 16, upper + 12, left + w - 12, upper + h - 16);
        let frame = [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)];
        let grey = [150, 150, 150];
        for pair in frame.windows(2) {
            canvas.line(pair[0], pair[1], grey);
        }
        let scale = 1.05 * top(panel);
        let pixel = |(x, v): (f64, f64)| {
            let fx = (x - panel.x.0) / (panel.x.1 - panel.x.0);
            let fy = (v / scale).clamp(0.0, 1.0);
            let px = x0 as f64 + fx * (x1 - x0) as f64;
            let py = y1 as f64 - fy * (y1 - y0) as f64;
            (px.round() as usize, py.round() as usize)
        };
        for (curve, colour) in [(&panel.reference, [0, 0, 0]), (&panel.model, [214, 39, 40])] {
            let finite = curve.iter().filter(|p| p.1.is_finite()).map(|&p| pixel(p));
            let points: Vec<(usize, usize)> = finite.collect();
            for pair in points.windows(2) {
                canvas.line(pair[0], pair[1], colour);
            }
        }
    }
    write_png(path, width, height, &canvas.rgb).map_err(|e| CliError::io(path, e))
}

/// An RGB buffer to draw lines into.
struct Canvas {
    width: usize,
    rgb: Vec<u8>,
}

impl Canvas {
    /// A line from `a` to `b` (Bresenham), clipped to the buffer.
    fn line(&mut self, a: (usize, usize), b: (usize, usize), colour: [u8; 3]) {
        let (mut x, mut y) = (a.0 as i64, a.1 as i64);
        let (bx, by) = (b.0 as i64, b.1 as i64);
        let (dx, dy) = ((bx - x).abs(), -(by - y).abs());
        let (sx, sy) = (if x < bx { 1 } else { -1 }, if y < by { 1 } else { -1 });
        let mut error = dx + dy;
        loop {
            self.set(x, y, colour);
            if x == bx && y == by {
                break;
            }
            let e2 = 2 * error;
            if e2 >= dy {
                error += dy;
                x += sx;
            }
            if e2 <= dx {
                error += dx;
                y += sy;
            }
        }
    }

    fn set(&mut self, x: i64, y: i64, colour: [u8; 3]) {
        let height = (self.rgb.len() / 3 / self.width) as i64;
        if (0..self.width as i64).contains(&x) && (0..height).contains(&y) {
            let k = 3 * (y as usize * self.width + x as usize);
            self.rgb[k..k + 3].copy_from_slice(&colour);
        }
    }
}

/// The panels as SVG with plotters: titles, axes, a legend.
fn svg_plot(path: &Path, name: &str, panels: &[Panel]) -> Result<(), String> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot draw the plot: {e}");
    let root = SVGBackend::new(path, (1200, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    for (area, panel) in root.split_evenly((2, 3)).iter().zip(panels) {
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.title, ("sans-serif", 13))
            .margin(8)
            .x_label_area_size(28)
            .y_label_area_size(48)
            .build_cartesian_2d(panel.x.0..panel.x.1, 0.0..1.05 * top(panel))
            .map_err(|e| fail(&e))?;
        chart.configure_mesh().draw().map_err(|e| fail(&e))?;
        let curves = [
            (
                &panel.reference,
                BLACK,
                "chiang-far (reference)".to_string(),
            ),
            (&panel.model, RGBColor(214, 39, 40), name.to_string()),
        ];
        for (curve, colour, label) in curves {
            let points = curve.iter().copied().filter(|p| p.1.is_finite());
            chart
                .draw_series(LineSeries::new(points, colour.stroke_width(2)))
                .map_err(|e| fail(&e))?
                .label(label)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}
