//! SVG and PNG figures (plotters; text rendered with the system's DejaVu Sans through
//! ab_glyph, so no fontconfig is needed).

use crate::study::{sim_normalised, ts_normalised, Cell, Model, Sweep};
use anyhow::{anyhow, Context, Result};
use brdf_core::models::GeometricTerm;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Where the font is looked for (Debian/Ubuntu package `fonts-dejavu-core`).
pub const FONT_PATHS: [&str; 3] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
];

/// Registers DejaVu Sans as plotters' "sans-serif" (once per process).
pub fn register_font() -> Result<()> {
    static DONE: std::sync::OnceLock<std::result::Result<(), String>> = std::sync::OnceLock::new();
    DONE.get_or_init(|| {
        let bytes = FONT_PATHS
            .iter()
            .find_map(|p| std::fs::read(p).ok())
            .ok_or_else(|| {
                format!("no DejaVuSans.ttf in {FONT_PATHS:?}: install the Debian package fonts-dejavu-core")
            })?;
        let leaked: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        plotters::style::register_font("sans-serif", FontStyle::Normal, leaked)
            .map_err(|_| "invalid font file".to_string())
    })
    .clone()
    .map_err(|e| anyhow!(e))
}

pub fn pe<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("plotting: {e:?}")
}

/// Line colour of each model.
pub fn model_color(m: Model) -> RGBColor {
    match m {
        Model::Blinn => RGBColor(214, 39, 40),
        Model::Modified => RGBColor(31, 119, 180),
        Model::ModifiedPrinted => RGBColor(148, 103, 189),
        Model::SmithSeparable => RGBColor(44, 160, 44),
        Model::SmithCorrelated => RGBColor(255, 127, 14),
    }
}

/// A drawing routine generic over the backend (SVG or bitmap).
pub trait Figure {
    /// Draws on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>;
}

/// Writes a [`Figure`] as SVG and PNG.
pub fn write<F: Figure>(dir: &Path, name: &str, size: (u32, u32), f: &F) -> Result<()> {
    register_font()?;
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let svg = dir.join(format!("{name}.svg"));
    {
        let root = SVGBackend::new(&svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(pe)?;
        f.draw(&root)?;
        root.present().map_err(pe)?;
    }
    let png = dir.join(format!("{name}.png"));
    {
        let root = BitMapBackend::new(&png, size).into_drawing_area();
        root.fill(&WHITE).map_err(pe)?;
        f.draw(&root)?;
        root.present().map_err(pe)?;
    }
    Ok(())
}

/// Fig. 6 analogue: G against θr at fixed θi and σ.
pub struct Fig6<'a> {
    /// The fine θr sweep.
    pub sweep: &'a Sweep,
    /// θi, degrees.
    pub ti: f64,
}

impl Figure for Fig6<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let sigma = self.sweep.sigma;
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("G(θi = {:.0}°, θr), σ = {sigma}", self.ti),
                ("sans-serif", 22),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(-90f64..90f64, 0f64..1.05f64)
            .map_err(pe)?;
        chart
            .configure_mesh()
            .x_desc("θr (degrees)")
            .y_desc("G")
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(pe)?;
        let ti = self.ti.to_radians();
        for m in Model::ALL {
            let c = model_color(m);
            let pts: Vec<(f64, f64)> = (-1780..=1780)
                .map(|k| {
                    let tr = k as f64 * 0.05;
                    (tr, m.g(sigma, ti, tr.to_radians()))
                })
                .collect();
            curve(&mut chart, pts, c, m.name())?;
        }
        let sn = &self.sweep.cells;
        chart
            .draw_series(sn.iter().map(|c| {
                Cross::new(
                    (c.tr, c.sn.g.mean),
                    3,
                    RGBColor(120, 120, 120).stroke_width(1),
                )
            }))
            .map_err(pe)?
            .label("single-neighbour model, simulated")
            .legend(|(x, y)| Cross::new((x + 9, y), 3, RGBColor(120, 120, 120)));
        let sim: Vec<_> = sn
            .iter()
            .map(|c| {
                let (g, e) = (c.sim.g.mean, 2.0 * c.sim.g.se());
                (c.tr, g - e, g, g + e)
            })
            .collect();
        simulated_and_legend(&mut chart, &sim)
    }
}

/// One model's curve, labelled `name` in the legend.
fn curve<'a, DB: DrawingBackend + 'a, Y: Ranged<ValueType = f64>>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>,
    pts: impl IntoIterator<Item = (f64, f64)>,
    c: RGBColor,
    name: &str,
) -> Result<()> {
    chart
        .draw_series(LineSeries::new(pts, c.stroke_width(2)))
        .map_err(pe)?
        .label(name)
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], c.stroke_width(2)));
    Ok(())
}

/// The ray-traced points (x, mean − 2 SE, mean, mean + 2 SE) as error bars and dots, then
/// the legend box.
fn simulated_and_legend<'a, DB: DrawingBackend + 'a, Y: Ranged<ValueType = f64>>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>,
    sim: &[(f64, f64, f64, f64)],
) -> Result<()> {
    chart
        .draw_series(
            sim.iter()
                .map(|&(x, lo, y, hi)| ErrorBar::new_vertical(x, lo, y, hi, BLACK.filled(), 4)),
        )
        .map_err(pe)?;
    chart
        .draw_series(
            sim.iter()
                .map(|&(x, _, y, _)| Circle::new((x, y), 2, BLACK.filled())),
        )
        .map_err(pe)?
        .label("random surface, ray traced (±2 SE)")
        .legend(|(x, y)| Circle::new((x + 9, y), 3, BLACK.filled()));
    legend(chart, SeriesLabelPosition::LowerMiddle, 13)
}

/// The legend box at `position`, labels in `font` px.
fn legend<'a, DB: DrawingBackend + 'a, Y: Ranged<ValueType = f64>>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>,
    position: SeriesLabelPosition,
    font: u32,
) -> Result<()> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", font))
        .draw()
        .map_err(pe)?;
    Ok(())
}

/// Fig. 7 analogue: normalised Torrance–Sparrow BRDF at θi = 10°.
pub struct Fig7<'a> {
    /// The fine θr sweep at θi = 10°.
    pub sweep: &'a Sweep,
}

impl Figure for Fig7<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let sigma = self.sweep.sigma;
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("Torrance–Sparrow f(θr)/f(10°), θi = 10°, σ = {sigma}"),
                ("sans-serif", 22),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(-90f64..90f64, (1e-3f64..1e1f64).log_scale())
            .map_err(pe)?;
        chart
            .configure_mesh()
            .x_desc("θr (degrees)")
            .y_desc("f / f(θr = 10°)")
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(pe)?;
        let clip = |v: f64| v.clamp(1e-3, 1e1);
        let mut terms: Vec<(GeometricTerm, &str, RGBColor)> =
            vec![(GeometricTerm::None, "no G", RGBColor(100, 100, 100))];
        terms.extend(
            Model::ALL
                .iter()
                .map(|&m| (m.term(), m.name(), model_color(m))),
        );
        for (t, name, c) in terms {
            let pts: Vec<(f64, f64)> = (-1780..=1780)
                .map(|k| {
                    let tr = k as f64 * 0.05;
                    (tr, clip(ts_normalised(sigma, t, 10.0, tr)))
                })
                .collect();
            curve(&mut chart, pts, c, name)?;
        }
        let row: Vec<&Cell> = self.sweep.cells.iter().collect();
        let sim: Vec<_> = sim_normalised(sigma, &row)
            .into_iter()
            .filter(|p| p.1 > 1e-3)
            .map(|(tr, f, se)| (tr, clip(f - 2.0 * se), f, clip(f + 2.0 * se)))
            .collect();
        simulated_and_legend(&mut chart, &sim)
    }
}

/// Diverging colour for an error in [−lim, lim]: blue (model too low) – white – red.
pub fn diverging(e: f64, lim: f64) -> RGBColor {
    let t = (e / lim).clamp(-1.0, 1.0);
    let (r, g, b) = if t >= 0.0 {
        (1.0, 1.0 - 0.85 * t, 1.0 - 0.85 * t)
    } else {
        (1.0 + 0.85 * t, 1.0 + 0.85 * t, 1.0)
    };
    RGBColor((r * 255.0) as u8, (g * 255.0) as u8, (b * 255.0) as u8)
}

/// One difference map: cells (x, y, value) of half-size `half` on the unit square, coloured
/// by [`diverging`] within ±`lim` (saturating beyond).
pub struct DiffPanel {
    /// The panel's caption.
    pub caption: String,
    /// (x, y, value) per cell.
    pub cells: Vec<(f64, f64, f64)>,
    /// Half the cell's width and height.
    pub half: (f64, f64),
    /// Colour limit.
    pub lim: f64,
}

/// Difference maps over (μ = N·V, r), `cols` panels a row.
pub struct DiffMaps {
    /// The panels, row by row.
    pub panels: Vec<DiffPanel>,
    /// Panels per row.
    pub cols: usize,
}

impl Figure for DiffMaps {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let cols = self.cols.max(1);
        let areas = root.split_evenly((self.panels.len().div_ceil(cols), cols));
        for (p, area) in self.panels.iter().zip(&areas) {
            let mut ch = ChartBuilder::on(area)
                .caption(&p.caption, ("sans-serif", 13))
                .margin(6)
                .x_label_area_size(26)
                .y_label_area_size(34)
                .build_cartesian_2d(0f64..1f64, 0f64..1f64)
                .map_err(pe)?;
            ch.configure_mesh()
                .disable_mesh()
                .x_desc("μ = N·V")
                .y_desc("r")
                .label_style(("sans-serif", 11))
                .draw()
                .map_err(pe)?;
            let (hx, hy) = p.half;
            ch.draw_series(p.cells.iter().map(|&(x, y, e)| {
                Rectangle::new(
                    [(x - hx, y - hy), (x + hx, y + hy)],
                    diverging(e, p.lim).filled(),
                )
            }))
            .map_err(pe)?;
        }
        Ok(())
    }
}

/// Heat maps of G_model − G_sim over (θr, θi), one row per σ, one column per model.
pub struct Heat<'a> {
    /// The grid sweeps to show.
    pub sweeps: Vec<&'a Sweep>,
    /// Grid step, degrees.
    pub step: f64,
    /// Colour-scale limit.
    pub lim: f64,
}

impl Figure for Heat<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let (body, bar) = root.split_vertically(root.dim_in_pixel().1 - 70);
        let panels = body.split_evenly((self.sweeps.len(), Model::ALL.len()));
        let h = self.step / 2.0;
        for (r, sw) in self.sweeps.iter().enumerate() {
            for (k, m) in Model::ALL.iter().enumerate() {
                let area = &panels[r * Model::ALL.len() + k];
                let mut chart = ChartBuilder::on(area)
                    .caption(
                        format!("{}, σ = {}", m.name(), sw.sigma),
                        ("sans-serif", 14),
                    )
                    .margin(6)
                    .x_label_area_size(28)
                    .y_label_area_size(32)
                    .build_cartesian_2d(-90f64..90f64, 0f64 - h..85.0 + h)
                    .map_err(pe)?;
                chart
                    .configure_mesh()
                    .disable_mesh()
                    .x_desc("θr")
                    .y_desc("θi")
                    .x_labels(7)
                    .y_labels(4)
                    .label_style(("sans-serif", 11))
                    .draw()
                    .map_err(pe)?;
                chart
                    .draw_series(sw.cells.iter().map(|c| {
                        let e = c.models[k] - c.sim.g.mean;
                        Rectangle::new(
                            [(c.tr - h, c.ti - h), (c.tr + h, c.ti + h)],
                            diverging(e, self.lim).filled(),
                        )
                    }))
                    .map_err(pe)?;
            }
        }
        // Colour bar.
        let mut cb = ChartBuilder::on(&bar)
            .margin_left(300)
            .margin_right(300)
            .margin_bottom(8)
            .x_label_area_size(30)
            .build_cartesian_2d(-self.lim..self.lim, 0f64..1f64)
            .map_err(pe)?;
        cb.configure_mesh()
            .disable_mesh()
            .disable_y_axis()
            .x_desc("G_model − G_simulated (red: model too high, blue: too low)")
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(pe)?;
        let n = 200;
        cb.draw_series((0..n).map(|i| {
            let a = -self.lim + 2.0 * self.lim * i as f64 / n as f64;
            let b = a + 2.0 * self.lim / n as f64;
            Rectangle::new(
                [(a, 0.0), (b, 1.0)],
                diverging(0.5 * (a + b), self.lim).filled(),
            )
        }))
        .map_err(pe)?;
        Ok(())
    }
}

/// A named, coloured polyline.
pub type Series = (String, RGBColor, Vec<(f64, f64)>);

/// A generic line plot: named series of (x, y) points.
pub struct Lines {
    /// Title.
    pub title: String,
    /// Axis labels.
    pub x_desc: String,
    /// Axis labels.
    pub y_desc: String,
    /// Ranges.
    pub x: (f64, f64),
    /// Ranges.
    pub y: (f64, f64),
    /// (name, colour, points).
    pub series: Vec<Series>,
}

impl Figure for Lines {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(self.x.0..self.x.1, self.y.0..self.y.1)
            .map_err(pe)?;
        chart
            .configure_mesh()
            .x_desc(self.x_desc.as_str())
            .y_desc(self.y_desc.as_str())
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(pe)?;
        for (name, c, pts) in &self.series {
            curve(&mut chart, pts.iter().copied(), *c, name)?;
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight, 12)
    }
}
