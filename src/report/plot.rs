//! Plots of error against time: plotters draws SVG, resvg turns it into PNG with a font
//! embedded in the binary (so no system fonts are needed).

use plotters::prelude::*;

/// One series of points.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// Join the points with lines (in the order given).
    pub joined: bool,
}

/// A scatter (or line) plot on logarithmic axes.
pub struct Plot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

/// The range of positive values, widened to whole powers of ten around them.
fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return 0.1..10.0;
    }
    10f64.powf(lo.log10().floor())
        ..10f64.powf((hi.log10() + 1e-9).ceil().max(lo.log10().floor() + 1.0))
}

impl Plot {
    /// The plot as SVG text, 800×500.
    pub fn svg(&self) -> Result<String, String> {
        let mut svg = String::new();
        {
            let area = SVGBackend::with_string(&mut svg, (800, 500)).into_drawing_area();
            area.fill(&WHITE).map_err(|e| e.to_string())?;
            let points = || self.series.iter().flat_map(|s| s.points.iter());
            let x_range = log_range(points().map(|p| p.0));
            let y_range = log_range(points().map(|p| p.1));
            let mut chart = ChartBuilder::on(&area)
                .caption(&self.title, ("sans-serif", 22))
                .margin(12)
                .x_label_area_size(48)
                .y_label_area_size(70)
                .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc(&self.x_label)
                .y_desc(&self.y_label)
                .label_style(("sans-serif", 14))
                .draw()
                .map_err(|e| e.to_string())?;
            for (index, series) in self.series.iter().enumerate() {
                let color = PALETTE[index % PALETTE.len()];
                let visible: Vec<(f64, f64)> = series
                    .points
                    .iter()
                    .copied()
                    .filter(|p| p.0 > 0.0 && p.1 > 0.0)
                    .collect();
                if series.joined {
                    chart
                        .draw_series(LineSeries::new(visible.clone(), color.stroke_width(2)))
                        .map_err(|e| e.to_string())?;
                }
                chart
                    .draw_series(visible.iter().map(|&p| Circle::new(p, 4, color.filled())))
                    .map_err(|e| e.to_string())?
                    .label(&series.name)
                    .legend(move |(x, y)| Circle::new((x + 8, y), 4, color.filled()));
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 14))
                .draw()
                .map_err(|e| e.to_string())?;
            area.present().map_err(|e| e.to_string())?;
        }
        Ok(svg)
    }

    /// The plot as PNG bytes.
    pub fn png(&self) -> Result<Vec<u8>, String> {
        let svg = self.svg()?;
        let mut options = resvg::usvg::Options::default();
        let fonts = options.fontdb_mut();
        fonts.load_font_data(epaint_default_fonts::UBUNTU_LIGHT.to_vec());
        let family = fonts
            .faces()
            .next()
            .and_then(|face| face.families.first())
            .map(|(name, _)| name.clone())
            .unwrap_or_default();
        fonts.set_sans_serif_family(family);
        let tree = resvg::usvg::Tree::from_str(&svg, &options).map_err(|e| e.to_string())?;
        let size = tree.size().to_int_size();
        let mut pixmap =
            resvg::tiny_skia::Pixmap::new(size.width(), size.height()).ok_or("empty plot")?;
        resvg::render(&tree, Default::default(), &mut pixmap.as_mut());
        pixmap.encode_png().map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plot_renders_to_a_png_with_its_labels() {
        let plot = Plot {
            title: "error against time".into(),
            x_label: "ms".into(),
            y_label: "error".into(),
            series: vec![Series {
                name: "heat".into(),
                points: vec![(1.0, 0.01), (10.0, 0.001)],
                joined: true,
            }],
        };
        assert!(plot.svg().unwrap().contains("error against time"));
        let png = plot.png().unwrap();
        let image = image::load_from_memory(&png).unwrap();
        assert_eq!((image.width(), image.height()), (800, 500));
    }
}
