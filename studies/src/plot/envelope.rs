//! The envelope plot of a sweep: per channel, the band between the minimum
//! and the maximum over the runs, shaded, with the weighted mean history
//! as a line over it.

use super::panels::ms;
use super::{COLORS, Line, PlotError, Style, TITLE_HEIGHT, WIDE_PANEL_SIZE, bounds};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One channel's envelope: at each time, the least and greatest value
/// over the runs and their weighted mean.
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    /// The channel's name (the panel's title).
    pub name: String,
    /// Times \[s\].
    pub t: Vec<f64>,
    /// The minimum over the runs at each time.
    pub min: Vec<f64>,
    /// The maximum over the runs at each time.
    pub max: Vec<f64>,
    /// The weighted mean at each time.
    pub mean: Vec<f64>,
}

impl Band {
    /// `(t [ms], y)` of `values` where both are finite.
    fn points(&self, values: &[f64]) -> Vec<(f64, f64)> {
        (self.t.iter().zip(values))
            .filter(|(t, y)| t.is_finite() && y.is_finite())
            .map(|(&t, &y)| (ms(t), y))
            .collect()
    }
}

/// The envelope plot as SVG text: one panel per band, side by side.
pub fn bands_svg(title: &str, bands: &[Band]) -> Result<String, PlotError> {
    let columns = bands.len().max(1) as u32;
    let size = (
        WIDE_PANEL_SIZE.0 * columns,
        WIDE_PANEL_SIZE.1 + TITLE_HEIGHT,
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let root = (root.titled(title, ("sans-serif", 22))).map_err(PlotError::drawing)?;
        let areas = root.split_evenly((1, columns as usize));
        for (k, (area, band)) in areas.iter().zip(bands).enumerate() {
            draw_band(area, band, COLORS[k % COLORS.len()]).map_err(PlotError::drawing)?;
        }
        root.present().map_err(PlotError::drawing)?;
    }
    Ok(svg)
}

/// One panel: the shaded band, its edges and the mean.
fn draw_band<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    band: &Band,
    color: RGBColor,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (max, min) = (band.points(&band.max), band.points(&band.min));
    let edges = [
        Line::new("max", max.clone(), 0, Style::Raw),
        Line::new("min", min.clone(), 0, Style::Raw),
    ];
    let ((x0, x1), (y0, y1)) = bounds(&edges);
    let mut chart = ChartBuilder::on(area)
        .caption(&band.name, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    (chart.configure_mesh())
        .x_desc("t [ms]")
        .y_desc(&band.name)
        .label_style(("sans-serif", 13))
        .draw()?;
    let outline: Vec<(f64, f64)> = max.iter().chain(min.iter().rev()).copied().collect();
    chart
        .draw_series(std::iter::once(Polygon::new(
            outline,
            color.mix(0.25).filled(),
        )))?
        .label("min – max over the runs")
        .legend(move |(x, y)| {
            Rectangle::new([(x, y - 5), (x + 18, y + 5)], color.mix(0.25).filled())
        });
    for edge in [max, min] {
        chart.draw_series(LineSeries::new(edge, color.mix(0.5).stroke_width(1)))?;
    }
    chart
        .draw_series(LineSeries::new(
            band.points(&band.mean),
            color.stroke_width(2),
        ))?
        .label("weighted mean")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
    (chart.configure_series_labels())
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plot_shades_the_band_and_draws_the_mean() {
        let band = Band {
            name: "x".into(),
            t: vec![0.0, 0.001, 0.002],
            min: vec![0.0, 1.0, 2.0],
            max: vec![1.0, 3.0, 4.0],
            mean: vec![0.5, 2.0, 3.0],
        };
        let svg = bands_svg("Envelopes", &[band]).unwrap();
        assert!(svg.contains("<polygon"), "no band");
        assert!(
            svg.contains("weighted mean"),
            "no legend entry for the mean"
        );
        assert!(svg.contains("min – max over the runs"));
    }
}
