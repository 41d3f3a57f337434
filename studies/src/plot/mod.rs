//! The figure of a run (SVG): the crush channel's panels (crush, crush
//! rate, deceleration), one panel per role of the scenario's channels,
//! pitch, energy bookkeeping and the crush force–deflection loop, three
//! panels a row.
//!
//! This module lays the panels out and draws them; its `panels`, `crush`
//! and `channels` submodules decide what they show.

mod channels;
mod crush;
mod envelope;
mod panels;
#[cfg(test)]
mod tests;

pub use envelope::{Band, bands_svg};

use lagrangian_sim::scenario::{Channel, Signal};
use lagrangian_sim::simulate::SimulationResult;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// A figure the drawing library could not draw: its message (the
/// library's error depends on the drawing backend's).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct PlotError {
    /// What the drawing library says.
    pub message: String,
}

impl PlotError {
    /// The error of the drawing library's `e`.
    fn drawing(e: impl std::fmt::Display) -> PlotError {
        PlotError {
            message: e.to_string(),
        }
    }
}

/// What to draw beyond the raw coordinates.
#[derive(Clone, Debug, Default)]
pub struct PlotSetup {
    /// The crush channel (a combination of coordinates, compression positive).
    pub crush: Option<Signal>,
    /// The scenario's channels (`metrics.displacement`, `velocity`,
    /// `acceleration`, `force`): one panel per role that has any.
    pub channels: Vec<Channel>,
    /// Pitch coordinates (drawn relative to their initial values).
    pub pitch: Vec<usize>,
    /// Each crush element's name and the columns of its force and its
    /// deflection in [`lagrangian_sim::simulate::Sample::components`]
    /// ([`lagrangian_sim::components::BoundInputs::force_deflection_columns`]).
    pub force_deflection: Vec<(String, usize, usize)>,
    /// The unit `g` the deceleration and acceleration panels are in [m/s²]:
    /// standard gravity ([`lagrangian_sim::pulse::STANDARD_GRAVITY`]) as the summary's.
    pub g: f64,
    /// The title above the figure (`lpm simulate` writes the model and the
    /// scenario's description).
    pub title: String,
}

/// A named line: `(x, y)` points.
pub type Series = (String, Vec<(f64, f64)>);

/// How a line is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Style {
    /// A full line: the quantity itself.
    Solid,
    /// A thin, light line under its filtered version.
    Raw,
    /// A light dashed line: a quantity that is no longer what the panel
    /// shows (the crush channel after the contact ended).
    Dashed,
}

/// One line of a panel.
#[derive(Clone, Debug, PartialEq)]
struct Line {
    /// Its legend entry.
    name: String,
    /// `(x, y)` points.
    points: Vec<(f64, f64)>,
    /// Index into [`COLORS`] (wrapping).
    color: usize,
    style: Style,
}

impl Line {
    fn new(name: impl Into<String>, points: Vec<(f64, f64)>, color: usize, style: Style) -> Line {
        Line {
            name: name.into(),
            points,
            color,
            style,
        }
    }

    /// A full line in color `color`.
    fn solid(name: impl Into<String>, points: Vec<(f64, f64)>, color: usize) -> Line {
        Line::new(name, points, color, Style::Solid)
    }

    /// The stroke of the line (and of its legend entry).
    fn shape(&self) -> ShapeStyle {
        let color = COLORS[self.color % COLORS.len()];
        match self.style {
            Style::Solid => color.stroke_width(2),
            Style::Raw => color.mix(0.35).stroke_width(1),
            Style::Dashed => color.mix(0.6).stroke_width(2),
        }
    }
}

/// One panel of the figure.
#[derive(Clone, Debug, PartialEq)]
struct Panel {
    title: String,
    x_label: String,
    y_label: String,
    lines: Vec<Line>,
}

impl Panel {
    /// A panel against time in milliseconds.
    fn time(title: &str, y_label: &str, lines: Vec<Line>) -> Panel {
        Panel {
            title: title.into(),
            x_label: "t [ms]".into(),
            y_label: y_label.into(),
            lines,
        }
    }
}

const COLORS: [RGBColor; 5] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
];

/// Panels a row of the figure.
const COLUMNS: usize = 3;
/// Size of one panel of the figure in pixels.
const PANEL_SIZE: (u32, u32) = (500, 420);
/// Size of one panel of [`panels_svg`] in pixels.
const WIDE_PANEL_SIZE: (u32, u32) = (700, 460);
/// Height of the figure's title in pixels.
const TITLE_HEIGHT: u32 = 40;

/// The figure as SVG text.
pub fn figure_svg(result: &SimulationResult, setup: &PlotSetup) -> Result<String, PlotError> {
    let panels = panels::panels_of(result, setup);
    draw_grid(&setup.title, &panels, COLUMNS, PANEL_SIZE)
}

/// Panels of lines side by side, one row: `(title, x label, y label, lines)`.
pub fn panels_svg(
    title: &str,
    panels: &[(String, String, String, Vec<Series>)],
) -> Result<String, PlotError> {
    let panels: Vec<Panel> = (panels.iter())
        .map(|(name, x_label, y_label, series)| Panel {
            title: name.clone(),
            x_label: x_label.clone(),
            y_label: y_label.clone(),
            lines: (series.iter().enumerate())
                .map(|(i, (name, points))| Line::solid(name.clone(), points.clone(), i))
                .collect(),
        })
        .collect();
    draw_grid(title, &panels, panels.len().max(1), WIDE_PANEL_SIZE)
}

/// `panels` of `panel_size` pixels under `title`, `columns` a row, as many
/// rows as they need.
fn draw_grid(
    title: &str,
    panels: &[Panel],
    columns: usize,
    panel_size: (u32, u32),
) -> Result<String, PlotError> {
    let rows = panels.len().div_ceil(columns).max(1);
    let size = (
        panel_size.0 * columns as u32,
        panel_size.1 * rows as u32 + TITLE_HEIGHT,
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let root = root
            .titled(title, ("sans-serif", 22))
            .map_err(PlotError::drawing)?;
        for (area, panel) in root.split_evenly((rows, columns)).iter().zip(panels) {
            draw_panel(area, panel).map_err(PlotError::drawing)?;
        }
        root.present().map_err(PlotError::drawing)?;
    }
    Ok(svg)
}

/// The ranges of the finite points of `lines`, padded by 5 %.
fn bounds(lines: &[Line]) -> ((f64, f64), (f64, f64)) {
    let points = lines
        .iter()
        .flat_map(|line| line.points.iter())
        .filter(|(x, y)| x.is_finite() && y.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in points {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let pad = |a: f64, b: f64| {
        let span = (b - a).abs().max(1e-9 * a.abs().max(1.0));
        (a - 0.05 * span, b + 0.05 * span)
    };
    (pad(x0, x1), pad(y0, y1))
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let ((x0, x1), y_range) = bounds(&panel.lines);
    let (corner, (y0, y1)) = legend_place(&panel.lines, (x0, x1), y_range);
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .x_labels(8)
        .y_labels(8)
        .x_label_formatter(&tick_label)
        .y_label_formatter(&tick_label)
        .label_style(("sans-serif", 13))
        .draw()?;
    for line in &panel.lines {
        draw_line(&mut chart, line)?;
    }
    chart
        .configure_series_labels()
        .position(corner)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()?;
    Ok(())
}

/// A tick's label as plotters writes it, without the sign of a zero
/// (`-0.0` where a tick lands a rounding error below 0).
fn tick_label(value: &f64) -> String {
    use plotters::coord::ranged1d::ValueFormatter;
    let label = RangedCoordf64::format(value);
    match label.strip_prefix('-') {
        Some(zero) if zero.chars().all(|c| c == '0' || c == '.') => zero.to_string(),
        _ => label,
    }
}

/// The legend's corner ([`legend_corner`]) and the y range that keeps it
/// off the data: where every corner has points, the range grows on the
/// corner's side until its box ([`legend_height`]) holds none.
fn legend_place(
    lines: &[Line],
    xs: (f64, f64),
    (y0, y1): (f64, f64),
) -> (SeriesLabelPosition, (f64, f64)) {
    let corner = legend_corner(lines, (xs, (y0, y1)));
    let (corner, crowded) = corner_count(lines, corner, (xs, (y0, y1)));
    if crowded == 0 {
        return (corner, (y0, y1));
    }
    let h = legend_height(lines);
    let grown = match corner {
        SeriesLabelPosition::UpperRight | SeriesLabelPosition::UpperLeft => {
            (y0, (y1 - h * y0) / (1.0 - h) + 0.02 * (y1 - y0))
        }
        _ => ((y0 - h * y1) / (1.0 - h) - 0.02 * (y1 - y0), y1),
    };
    (corner, grown)
}

/// The share of a panel's height its legend takes: about 5.5 % an entry
/// and a margin, at most 40 %.
fn legend_height(lines: &[Line]) -> f64 {
    (0.06 + 0.055 * lines.len() as f64).min(0.4)
}

/// The share of a panel's width its legend takes: its sample line and
/// margins, and about 1.6 % a character of its longest entry (measured on
/// the rendered figure), 25 % to 95 %.
fn legend_width(lines: &[Line]) -> f64 {
    let longest = lines
        .iter()
        .map(|l| l.name.chars().count())
        .max()
        .unwrap_or(0);
    (0.12 + 0.016 * longest as f64).clamp(0.25, 0.95)
}

/// The corner's box ([`legend_width`] of the width, [`legend_height`] of
/// the height) and the number of points in it.
fn corner_count(
    lines: &[Line],
    corner: SeriesLabelPosition,
    ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
) -> (SeriesLabelPosition, usize) {
    let (w, h) = (legend_width(lines), legend_height(lines));
    let (right, upper) = (x1 - w * (x1 - x0), y1 - h * (y1 - y0));
    let (left, lower) = (x0 + w * (x1 - x0), y0 + h * (y1 - y0));
    let (xs, ys) = match corner {
        SeriesLabelPosition::UpperRight => ((right, x1), (upper, y1)),
        SeriesLabelPosition::LowerRight => ((right, x1), (y0, lower)),
        SeriesLabelPosition::UpperLeft => ((x0, left), (upper, y1)),
        _ => ((x0, left), (y0, lower)),
    };
    let inside = |(a, b): (f64, f64), v: f64| a <= v && v <= b;
    let n = (lines.iter().flat_map(|l| &l.points))
        .filter(|&&(x, y)| inside(xs, x) && inside(ys, y))
        .count();
    (corner, n)
}

/// The corner of the plot area the fewest points fall in (a box of
/// [`legend_width`] and [`legend_height`]), for the legend: the first of
/// equals in the order upper right, lower right, upper left, lower left.
fn legend_corner(lines: &[Line], bounds: ((f64, f64), (f64, f64))) -> SeriesLabelPosition {
    let corners = [
        SeriesLabelPosition::UpperRight,
        SeriesLabelPosition::LowerRight,
        SeriesLabelPosition::UpperLeft,
        SeriesLabelPosition::LowerLeft,
    ];
    let counted = corners.map(|corner| corner_count(lines, corner, bounds));
    let [first, rest @ ..] = counted;
    let best = rest
        .into_iter()
        .fold(first, |best, (corner, n)| match n < best.1 {
            true => (corner, n),
            false => best,
        });
    best.0
}

/// One line with its legend entry.
fn draw_line<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    line: &Line,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let shape = line.shape();
    let points = line.points.iter().copied();
    let drawn = match line.style {
        Style::Solid | Style::Raw => chart.draw_series(LineSeries::new(points, shape))?,
        Style::Dashed => chart.draw_series(DashedLineSeries::new(points, 8, 5, shape))?,
    };
    drawn
        .label(line.name.as_str())
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], shape));
    Ok(())
}
