//! The figure of a run (SVG): crush, velocity, deceleration, pitch, energy
//! bookkeeping and the crush force–deflection loop.

use crate::scenario::Signal;
use crate::simulate::{Sample, SimulationResult};
use plotters::prelude::*;

/// What to draw beyond the raw coordinates.
#[derive(Clone, Debug, Default)]
pub struct PlotSetup {
    /// The crush channel (a combination of coordinates, compression positive).
    pub crush: Option<Signal>,
    /// Pitch coordinates (drawn relative to their initial values).
    pub pitch: Vec<usize>,
    /// Each crush element's name and the columns of its force and its
    /// deflection in [`crate::simulate::Sample::components`]
    /// ([`crate::crash::BoundInputs::force_deflection_columns`]).
    pub force_deflection: Vec<(String, usize, usize)>,
    /// The gravitational acceleration the deceleration panel is in [m/s²]
    /// ([`SimulationResult::g`]).
    pub g: f64,
    /// The title above the figure (`lpm simulate` writes the model and the scenario).
    pub title: String,
}

/// A named line: `(x, y)` points.
pub type Series = (String, Vec<(f64, f64)>);

const COLORS: [RGBColor; 5] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
];

/// The figure as SVG text.
pub fn figure_svg(result: &SimulationResult, setup: &PlotSetup) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1500, 900)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let root = root
            .titled(&setup.title, ("sans-serif", 22))
            .map_err(|e| e.to_string())?;
        let panels = root.split_evenly((2, 3));
        for (area, (title, x_label, y_label, series)) in panels.iter().zip(panels_of(result, setup))
        {
            draw_panel(area, &title, &x_label, &y_label, &series).map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// One panel of the figure: `(title, x label, y label, lines)`.
type Panel = (String, String, String, Vec<Series>);

/// A panel against time in milliseconds.
fn time_panel(title: &str, y_label: &str, series: Vec<Series>) -> Panel {
    (title.into(), "t [ms]".into(), y_label.into(), series)
}

/// Seconds to milliseconds, the time axis of the panels.
fn ms(t: f64) -> f64 {
    t * 1e3
}

/// The panels of a run, in reading order: the crush pulse (or the raw
/// coordinates without a crush coordinate), pitch, energies, and the crush
/// force–deflection loop.
fn panels_of(result: &SimulationResult, setup: &PlotSetup) -> Vec<Panel> {
    let mut panels = match &setup.crush {
        Some(crush) => crush_panels(result, crush, setup.g),
        None => coordinate_panels(result),
    };
    if !setup.pitch.is_empty() {
        panels.push(pitch_panel(result, &setup.pitch));
    }
    panels.push(energy_panel(result));
    if !setup.force_deflection.is_empty() {
        panels.push(force_deflection_panel(
            &result.samples,
            &setup.force_deflection,
        ));
    }
    panels
}

/// Each crush element's force against its own deflection, from the
/// samples' component columns.
fn force_deflection_panel(samples: &[Sample], elements: &[(String, usize, usize)]) -> Panel {
    let lines = elements
        .iter()
        .map(|(name, force, deflection)| {
            let points = samples
                .iter()
                .map(|x| (x.components[*deflection], 1e-3 * x.components[*force]));
            (name.clone(), points.collect())
        })
        .collect();
    (
        "Crush force against crush".into(),
        "deflection [m]".into(),
        "force [kN]".into(),
        lines,
    )
}

/// Crush, velocity towards the barrier and deceleration \[g\] of the crush
/// channel (compression positive).
fn crush_panels(result: &SimulationResult, crush: &Signal, g: f64) -> Vec<Panel> {
    let s = &result.samples;
    let of = |values: &[f64]| crush.of_coordinates(values);
    let velocity = s.iter().map(|x| (ms(x.t), of(&x.v))).collect();
    let deceleration = s.iter().map(|x| (ms(x.t), -of(&x.a) / g)).collect();
    let crush = s.iter().map(|x| (ms(x.t), of(&x.q))).collect();
    vec![
        time_panel("Crush", "crush [m]", vec![("crush".into(), crush)]),
        time_panel(
            "Velocity towards the barrier",
            "velocity [m/s]",
            vec![("velocity".into(), velocity)],
        ),
        time_panel(
            "Deceleration (unfiltered)",
            "deceleration [g]",
            vec![("deceleration".into(), deceleration)],
        ),
    ]
}

/// Every coordinate and every velocity, for a run without a crush
/// coordinate.
fn coordinate_panels(result: &SimulationResult) -> Vec<Panel> {
    let s = &result.samples;
    let coordinates = result
        .coordinates
        .iter()
        .enumerate()
        .map(|(k, name)| (name.clone(), s.iter().map(|x| (ms(x.t), x.q[k])).collect()))
        .collect();
    let velocities = result
        .coordinates
        .iter()
        .enumerate()
        .map(|(k, name)| {
            (
                format!("d{name}/dt"),
                s.iter().map(|x| (ms(x.t), x.v[k])).collect(),
            )
        })
        .collect();
    vec![
        time_panel("Coordinates", "q", coordinates),
        time_panel("Velocities", "dq/dt", velocities),
    ]
}

/// The pitch coordinates in degrees, relative to their initial values.
fn pitch_panel(result: &SimulationResult, pitch: &[usize]) -> Panel {
    let lines = pitch
        .iter()
        .map(|&k| {
            let q0 = result.initial_q[k];
            (
                result.coordinates[k].clone(),
                result
                    .samples
                    .iter()
                    .map(|x| (ms(x.t), (x.q[k] - q0).to_degrees()))
                    .collect(),
            )
        })
        .collect();
    time_panel("Pitch from static equilibrium", "angle [°]", lines)
}

/// The energy bookkeeping [kJ]: kinetic, potential from its start,
/// dissipated, and absorbed by the inputs.
fn energy_panel(result: &SimulationResult) -> Panel {
    let s = &result.samples;
    let first = s.first().map_or(0.0, |x| x.potential);
    let kj = 1e-3;
    let line = |name: &str, value: &dyn Fn(&Sample) -> f64| -> Series {
        (
            name.into(),
            s.iter().map(|x| (ms(x.t), kj * value(x))).collect(),
        )
    };
    time_panel(
        "Energy",
        "energy [kJ]",
        vec![
            line("kinetic", &|x| x.kinetic),
            line("potential − V(0)", &|x| x.potential - first),
            line("dissipated by D", &|x| x.dissipated),
            line("absorbed by inputs", &|x| -x.external_work),
        ],
    )
}

/// Panels of lines side by side, one row: `(title, x label, y label, lines)`.
pub fn panels_svg(
    title: &str,
    panels: &[(String, String, String, Vec<Series>)],
) -> Result<String, String> {
    let mut svg = String::new();
    {
        let width = 700 * panels.len().max(1) as u32;
        let root = SVGBackend::with_string(&mut svg, (width, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let root = root
            .titled(title, ("sans-serif", 22))
            .map_err(|e| e.to_string())?;
        let areas = root.split_evenly((1, panels.len().max(1)));
        for (area, (name, x_label, y_label, series)) in areas.iter().zip(panels) {
            draw_panel(area, name, x_label, y_label, series).map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

fn bounds(series: &[Series]) -> ((f64, f64), (f64, f64)) {
    let points = series
        .iter()
        .flat_map(|(_, p)| p.iter())
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

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let ((x0, x1), (y0, y1)) = bounds(series);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_labels(8)
        .y_labels(8)
        .label_style(("sans-serif", 13))
        .draw()?;
    for (i, (name, points)) in series.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        chart
            .draw_series(LineSeries::new(
                points.iter().copied(),
                color.stroke_width(2),
            ))?
            .label(name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(components: Vec<f64>) -> Sample {
        Sample {
            t: 0.0,
            q: Vec::new(),
            v: Vec::new(),
            a: Vec::new(),
            kinetic: 0.0,
            potential: 0.0,
            dissipated: 0.0,
            external_work: 0.0,
            inputs: Vec::new(),
            outputs: Vec::new(),
            components,
        }
    }

    #[test]
    fn each_crush_element_is_drawn_against_its_own_deflection() {
        // Columns: a.force, a.deflection, b.deflection, b.force.
        let samples = [
            sample(vec![1e3, 0.1, 0.5, 4e3]),
            sample(vec![2e3, 0.2, 0.6, 5e3]),
        ];
        let elements = [("a".to_string(), 0, 1), ("b".to_string(), 3, 2)];
        let (title, _, _, lines) = force_deflection_panel(&samples, &elements);
        assert_eq!(title, "Crush force against crush");
        assert_eq!(
            lines,
            [
                ("a".to_string(), vec![(0.1, 1.0), (0.2, 2.0)]),
                ("b".to_string(), vec![(0.5, 4.0), (0.6, 5.0)]),
            ]
        );
    }
}
