//! `hairmath report --plots DIR`: SVG plots of the report's speed-against-error catalogues
//! ([`hairmath::plan::catalogue`]), drawn with plotters. Every plotted number comes from the
//! library; this file only draws.
//!
//! - `front-<scene>.svg`: the Pareto front (weighted cost against error E, log-log) with the
//!   published models and the plan marked.
//! - `lobes-<scene>.svg`: S (the mean over RGB) against phi at each inclination of
//!   [`hairmath::plan::CURVE_THETAS_DEG`], every model against the reference.
//!
//! SVG needs no font files: the text is written as SVG text and drawn by the viewer.

use crate::{create_dir, CliError};
use hairmath::plan::{Catalogue, ModelCurves};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The colours of the plotted models after the reference (black), in order.
const PALETTE: [RGBColor; 10] = [
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
];

/// A plotters error, in words (the caller names the file).
fn plot_error(e: impl std::fmt::Display) -> String {
    format!("cannot draw a plot: {e}")
}

/// Writes both plots of every `(scene name, catalogue)` into `dir` (created if missing) and
/// returns the files written.
pub fn write(dir: &Path, catalogues: &[(&str, Catalogue)]) -> Result<Vec<PathBuf>, CliError> {
    create_dir(dir)?;
    let failed = |path: &Path| {
        let path = path.to_path_buf();
        move |e: String| CliError::io(&path, std::io::Error::other(e))
    };
    let mut files = Vec::new();
    for (name, catalogue) in catalogues {
        let front = dir.join(format!("front-{name}.svg"));
        front_plot(&front, name, catalogue).map_err(failed(&front))?;
        let lobes = dir.join(format!("lobes-{name}.svg"));
        lobe_plot(&lobes, name, &catalogue.curves).map_err(failed(&lobes))?;
        files.extend([front, lobes]);
    }
    Ok(files)
}

/// The range `[min / 1.5, max * 1.5]` of the positive `values` (a log axis).
fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return 1e-3..1.0;
    }
    lo / 1.5..hi * 1.5
}

/// The front plot of one scene.
fn front_plot(path: &Path, name: &str, c: &Catalogue) -> Result<(), String> {
    let root = SVGBackend::new(path, (900, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_error)?;
    let costs = c
        .front
        .iter()
        .map(|p| p.cost)
        .chain(c.published.iter().map(|p| p.cost))
        .chain([c.plan.cost]);
    let errors = c
        .front
        .iter()
        .map(|p| p.error)
        .chain(c.published.iter().map(|p| p.error))
        .chain([c.plan.error]);
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "{name} hair: cost against error ({} compositions)",
                c.combinations
            ),
            ("sans-serif", 20),
        )
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d(log_range(costs).log_scale(), log_range(errors).log_scale())
        .map_err(plot_error)?;
    chart
        .configure_mesh()
        .x_desc("weighted operation count (cost)")
        .y_desc("error E against the Chiang far field")
        .x_label_formatter(&|cost| format!("{cost:.0}"))
        .y_label_formatter(&|error| format!("{error:.0e}"))
        .draw()
        .map_err(plot_error)?;
    let front: Vec<(f64, f64)> = c.front.iter().map(|p| (p.cost, p.error)).collect();
    let blue = PALETTE[1];
    chart
        .draw_series(LineSeries::new(front.iter().copied(), blue.stroke_width(2)))
        .map_err(plot_error)?
        .label("Pareto front of the compositions")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], blue.stroke_width(2)));
    chart
        .draw_series(front.iter().map(|&p| Circle::new(p, 3, blue.filled())))
        .map_err(plot_error)?;
    let red = PALETTE[0];
    chart
        .draw_series(
            c.published
                .iter()
                .map(|p| TriangleMarker::new((p.cost, p.error), 7, red.filled())),
        )
        .map_err(plot_error)?
        .label("published models")
        .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 6, red.filled()));
    chart
        .draw_series(c.published.iter().map(|p| {
            Text::new(
                p.model.to_string(),
                (p.cost * 1.04, p.error),
                ("sans-serif", 13),
            )
        }))
        .map_err(plot_error)?;
    let green = PALETTE[2];
    let plan = (c.plan.cost, c.plan.error);
    chart
        .draw_series([Cross::new(plan, 9, green.stroke_width(3))])
        .map_err(plot_error)?
        .label(format!(
            "the plan (budget {}, E = {:.3})",
            c.budget, c.plan.error
        ))
        .legend(move |(x, y)| Cross::new((x + 10, y), 6, green.stroke_width(3)));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(plot_error)?;
    root.present().map_err(plot_error)
}

/// The lobe plot of one scene: a panel per inclination.
fn lobe_plot(path: &Path, name: &str, models: &[ModelCurves]) -> Result<(), String> {
    let panels = models.first().map_or(0, |m| m.curves.len());
    let root = SVGBackend::new(path, (900, 360 * panels.max(1) as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_error)?;
    for (k, area) in root.split_evenly((panels.max(1), 1)).iter().enumerate() {
        if k < panels {
            lobe_panel(area, name, models, k)?;
        }
    }
    root.present().map_err(plot_error)
}

/// The mean over RGB of a value.
fn mean(v: &[f64; 3]) -> f64 {
    (v[0] + v[1] + v[2]) / 3.0
}

/// One panel of the lobe plot: every model's curve `k`.
fn lobe_panel(
    area: &DrawingArea<SVGBackend, Shift>,
    name: &str,
    models: &[ModelCurves],
    k: usize,
) -> Result<(), String> {
    let top = models
        .iter()
        .flat_map(|m| m.curves[k].value.iter().map(mean))
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let theta = models[0].curves[k].theta_deg;
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "{name} hair: S against phi at theta_i = {theta}, theta_o = {} degrees",
                0.0 - theta
            ),
            ("sans-serif", 16),
        )
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(-180.0..180.0, 0.0..top * 1.05)
        .map_err(plot_error)?;
    chart
        .configure_mesh()
        .x_desc("phi (degrees)")
        .y_desc("S, mean over RGB")
        .x_label_formatter(&|phi| format!("{phi:.0}"))
        .draw()
        .map_err(plot_error)?;
    for (i, model) in models.iter().enumerate() {
        let colour = match i {
            0 => BLACK,
            _ => PALETTE[(i - 1) % PALETTE.len()],
        };
        // The reference thick, the plan (second) medium, the published models thin.
        let width = match i {
            0 => 3,
            1 => 2,
            _ => 1,
        };
        let curve = &model.curves[k];
        let points = curve
            .phi
            .iter()
            .zip(&curve.value)
            .map(|(p, v)| (p.to_degrees(), mean(v)));
        chart
            .draw_series(LineSeries::new(points, colour.stroke_width(width)))
            .map_err(plot_error)?
            .label(model.model.clone())
            .legend(move |(x, y)| {
                PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(width))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(plot_error)
}
