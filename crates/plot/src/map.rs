//! A height map drawn as a colour image with markers (summits) and a colour bar.

use std::path::Path;

use plotters::prelude::*;

use crate::PlotError;

/// A grid of values drawn as an image, with optional markers.
#[derive(Clone, Debug, Default)]
pub struct ImageMap {
    /// Title above the image.
    pub title: String,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// Label of the colour bar.
    pub value_label: String,
    /// Columns.
    pub nx: usize,
    /// Rows (row 0 at the bottom, y = 0).
    pub ny: usize,
    /// Values row-major (`iy * nx + ix`); NaN is drawn grey.
    pub values: Vec<f64>,
    /// The image covers `[0, x_max] x [0, y_max]` in axis units.
    pub x_max: f64,
    /// See `x_max`.
    pub y_max: f64,
    /// Marker positions in axis units.
    pub markers: Vec<(f64, f64)>,
    /// Image size in pixels (default 1200 wide, the height from the map's aspect ratio).
    pub size_px: Option<(u32, u32)>,
    /// Tick label font size in pixels (default 15; the title and labels scale with it).
    pub font_px: Option<f64>,
}

/// A perceptually ordered colour map (viridis, 5 anchors, linear between them), `t` in [0, 1].
fn viridis(t: f64) -> RGBColor {
    const A: [(f64, f64, f64); 5] =
        [(68., 1., 84.), (59., 82., 139.), (33., 145., 140.), (94., 201., 98.), (253., 231., 37.)];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let i = (t.floor() as usize).min(3);
    let f = t - i as f64;
    let c = |a: f64, b: f64| (a + (b - a) * f).round() as u8;
    RGBColor(c(A[i].0, A[i + 1].0), c(A[i].1, A[i + 1].1), c(A[i].2, A[i + 1].2))
}

/// Block means of a row-major `nx x ny` grid (`values[iy * nx + ix]`) for drawing: the smallest
/// whole block side `b` that brings the longer side to at most `max_cells` cells, and the mean of
/// each `b x b` block (the last row and column of blocks may be partial). NaN values are left out
/// of a mean; a block without any is NaN (drawn grey). Returns `(b, cells_x, cells_y, means)`.
pub fn block_means(values: &[f64], nx: usize, ny: usize, max_cells: usize) -> (usize, usize, usize, Vec<f64>) {
    let block = nx.max(ny).div_ceil(max_cells.max(1)).max(1);
    let (cx, cy) = (nx.div_ceil(block), ny.div_ceil(block));
    let mut cells = vec![f64::NAN; cx * cy];
    for by in 0..cy {
        for bx in 0..cx {
            let (mut sum, mut n) = (0.0, 0usize);
            for iy in by * block..((by + 1) * block).min(ny) {
                for ix in bx * block..((bx + 1) * block).min(nx) {
                    let v = values[iy * nx + ix];
                    if !v.is_nan() {
                        sum += v;
                        n += 1;
                    }
                }
            }
            if n > 0 {
                cells[by * cx + bx] = sum / n as f64;
            }
        }
    }
    (block, cx, cy, cells)
}

impl ImageMap {
    /// The drawn cells as CSV: one row per cell with its centre and value, columns named from the
    /// axis and colour-bar labels with their units (`x_um,y_um,height_nm`); an empty value where
    /// the cell has none (drawn grey). The numbers are exactly the ones the image shows.
    pub fn data_csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        let keys =
            [crate::column_key(&self.x_label), crate::column_key(&self.y_label), crate::column_key(&self.value_label)];
        // Writing to a Vec cannot fail.
        w.write_record(&keys).ok();
        if self.nx > 0 && self.ny > 0 && self.values.len() == self.nx * self.ny {
            let (cx, cy) = (self.x_max / self.nx as f64, self.y_max / self.ny as f64);
            for iy in 0..self.ny {
                for ix in 0..self.nx {
                    let v = self.values[iy * self.nx + ix];
                    w.write_record([
                        format!("{}", (ix as f64 + 0.5) * cx),
                        format!("{}", (iy as f64 + 0.5) * cy),
                        if v.is_finite() { format!("{v}") } else { String::new() },
                    ])
                    .ok();
                }
            }
        }
        String::from_utf8(w.into_inner().unwrap_or_default()).unwrap_or_default()
    }

    /// Writes the image as PNG (1200 x 900 px, or narrower for tall maps).
    pub fn write_png(&self, path: &Path) -> Result<(), PlotError> {
        let backend_err =
            |e: &dyn std::fmt::Display| PlotError::Backend { path: path.display().to_string(), message: e.to_string() };
        let finite: Vec<f64> = self.values.iter().copied().filter(|v| v.is_finite()).collect();
        if finite.is_empty() || self.nx == 0 || self.ny == 0 || self.values.len() != self.nx * self.ny {
            return Err(PlotError::Empty { title: self.title.clone() });
        }
        let lo = finite.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let span = if hi > lo { hi - lo } else { 1.0 };
        let aspect = (self.y_max / self.x_max).clamp(0.05, 20.0);
        let (w, h) = self.size_px.unwrap_or((1200u32, ((1000.0 * aspect) as u32 + 160).clamp(300, 1400)));
        let f = self.font_px.unwrap_or(15.0);
        let root = BitMapBackend::new(path, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| backend_err(&e))?;
        let (main, bar) = root.split_horizontally(w.saturating_sub((170.0 * f / 15.0) as u32).max(w / 2));
        // Square pixels: the plot area keeps the map's aspect ratio whatever the image size; the
        // spare width or height goes to the right or bottom margin. The caption's height is
        // estimated from its font size (plotters draws it at about 1.2 font heights).
        let (mw, mh) = main.dim_in_pixel();
        let caption_px = (f * 22.0 / 15.0 * 1.2).round() as u32;
        let (avail_w, avail_h) =
            (mw.saturating_sub(14 * 2 + 70).max(50) as f64, mh.saturating_sub(14 * 2 + 52 + caption_px).max(50) as f64);
        let px_per_unit = (avail_w / self.x_max).min(avail_h / self.y_max);
        let spare_w = (avail_w - px_per_unit * self.x_max).max(0.0).floor() as u32;
        let spare_h = (avail_h - px_per_unit * self.y_max).max(0.0).floor() as u32;
        let mut chart = ChartBuilder::on(&main)
            .caption(&self.title, ("sans-serif", f * 22.0 / 15.0))
            .margin_top(14 + spare_h / 2)
            .margin_left(14)
            .margin_right(14 + spare_w)
            .margin_bottom(14 + spare_h - spare_h / 2)
            .x_label_area_size(52)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..self.x_max, 0.0..self.y_max)
            .map_err(|e| backend_err(&e))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style(("sans-serif", f))
            .axis_desc_style(("sans-serif", f * 17.0 / 15.0))
            .draw()
            .map_err(|e| backend_err(&e))?;
        let (cx, cy) = (self.x_max / self.nx as f64, self.y_max / self.ny as f64);
        chart
            .draw_series((0..self.ny).flat_map(|iy| {
                (0..self.nx).map(move |ix| {
                    let v = self.values[iy * self.nx + ix];
                    let color = if v.is_finite() { viridis((v - lo) / span) } else { RGBColor(160, 160, 160) };
                    let (x0, y0) = (ix as f64 * cx, iy as f64 * cy);
                    Rectangle::new([(x0, y0), (x0 + cx, y0 + cy)], color.filled())
                })
            }))
            .map_err(|e| backend_err(&e))?;
        if !self.markers.is_empty() {
            chart
                .draw_series(
                    self.markers.iter().map(|&p| Circle::new(p, 3, RGBColor(0xd6, 0x27, 0x28).stroke_width(1))),
                )
                .map_err(|e| backend_err(&e))?
                .label("summits")
                .legend(|(x, y)| Circle::new((x + 10, y), 4, RGBColor(0xd6, 0x27, 0x28).stroke_width(2)));
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .label_font(("sans-serif", f))
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| backend_err(&e))?;
        }
        // Colour bar, labelled with as many decimals as a fifth of its span needs.
        let decimals = (-(span / 5.0).log10()).ceil().clamp(0.0, 6.0) as usize;
        // The bar spans the plot area's height (its caption, the value label, just above it).
        let bar_caption_px = (f * 1.2).round() as u32;
        let mut cb = ChartBuilder::on(&bar)
            .margin_top((14 + spare_h / 2 + caption_px).saturating_sub(bar_caption_px))
            .margin_bottom(14 + 52 + spare_h - spare_h / 2)
            .margin_right(10)
            .y_label_area_size(80)
            .caption(&self.value_label, ("sans-serif", f))
            .build_cartesian_2d(0.0..1.0, lo..lo + span)
            .map_err(|e| backend_err(&e))?;
        cb.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_label_formatter(&|v| format!("{v:.decimals$}"))
            .label_style(("sans-serif", f * 14.0 / 15.0))
            .draw()
            .map_err(|e| backend_err(&e))?;
        let steps = 200;
        cb.draw_series((0..steps).map(|k| {
            let (a, b) = (lo + span * k as f64 / steps as f64, lo + span * (k + 1) as f64 / steps as f64);
            Rectangle::new([(0.0, a), (1.0, b)], viridis(k as f64 / (steps - 1) as f64).filled())
        }))
        .map_err(|e| backend_err(&e))?;
        root.present().map_err(|e| backend_err(&e))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Block means: a 5 x 3 grid in blocks of 2 (max 3 cells a side), partial blocks and a NaN
    /// left out of its block's mean; values chosen so every mean is exact in binary.
    #[test]
    fn block_means_average_whole_and_partial_blocks() {
        let v = [1.0, 3.0, 5.0, 7.0, 9.0, 2.0, f64::NAN, 6.0, 8.0, 10.0, 0.5, 0.5, 0.5, 0.5, 0.5];
        let (b, cx, cy, m) = block_means(&v, 5, 3, 3);
        assert_eq!((b, cx, cy), (2, 3, 2));
        assert_eq!(m, vec![2.0, 6.5, 9.5, 0.5, 0.5, 0.5]);
    }

    /// The CSV holds the cell centres and the values drawn, keyed by the labels' units.
    #[test]
    fn data_csv_holds_the_cells() {
        let m = ImageMap {
            x_label: "x (µm)".into(),
            y_label: "y (µm)".into(),
            value_label: "height (nm)".into(),
            nx: 2,
            ny: 1,
            values: vec![1.5, f64::NAN],
            x_max: 4.0,
            y_max: 1.0,
            ..ImageMap::default()
        };
        assert_eq!(m.data_csv(), "x_um,y_um,height_nm\n1,0.5,1.5\n3,0.5,\n");
    }
}
