//! A small raster chart for the bench's figures: an RGB canvas with lines, rectangles
//! and a built-in 5x7 bitmap font, a log-log line chart on it, and its PNG bytes. No
//! plotting library: the picture is the project's own, checked by the tests below.

use std::collections::HashMap;

/// An RGB colour.
pub type Rgb = [u8; 3];

/// A white RGB picture drawn into pixel by pixel.
pub struct Canvas {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major RGB bytes, 3 per pixel.
    pub pixels: Vec<u8>,
}

impl Canvas {
    /// A white canvas of `width` x `height` pixels.
    pub fn new(width: u32, height: u32) -> Canvas {
        Canvas { width, height, pixels: vec![255; width as usize * height as usize * 3] }
    }

    /// The colour at (x, y); `None` outside the canvas.
    #[cfg_attr(not(test), allow(dead_code))]
    pub fn get(&self, x: i64, y: i64) -> Option<Rgb> {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 3;
        Some([self.pixels[i], self.pixels[i + 1], self.pixels[i + 2]])
    }

    /// Sets one pixel; outside the canvas nothing happens.
    pub fn put(&mut self, x: i64, y: i64, c: Rgb) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return;
        }
        let i = (y as usize * self.width as usize + x as usize) * 3;
        self.pixels[i..i + 3].copy_from_slice(&c);
    }

    /// A filled rectangle from (x, y), `w` x `h` pixels.
    pub fn rect(&mut self, x: i64, y: i64, w: i64, h: i64, c: Rgb) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.put(xx, yy, c);
            }
        }
    }

    /// A line from (x0, y0) to (x1, y1) (Bresenham), `width` pixels wide; with
    /// `dash`, drawn `dash` steps on and `dash` steps off.
    pub fn line(&mut self, (x0, y0): (i64, i64), (x1, y1): (i64, i64), width: i64, dash: Option<u32>, c: Rgb) {
        let (dx, dy) = ((x1 - x0).abs(), -(y1 - y0).abs());
        let (sx, sy) = (if x0 < x1 { 1 } else { -1 }, if y0 < y1 { 1 } else { -1 });
        let (mut x, mut y, mut err) = (x0, y0, dx + dy);
        let off = (width - 1) / 2;
        for step in 0u32.. {
            if dash.is_none_or(|d| (step / d) % 2 == 0) {
                self.rect(x - off, y - off, width, width, c);
            }
            if x == x1 && y == y1 {
                break;
            }
            let e2 = 2 * err;
            if e2 >= dy {
                err += dy;
                x += sx;
            }
            if e2 <= dx {
                err += dx;
                y += sy;
            }
        }
    }

    /// `text` in the built-in font (upper-case letters, digits and `.,:-+/()=%` ;
    /// lower case is drawn upper case, other characters as blanks), its top-left
    /// corner at (x, y), each font pixel `scale` x `scale`. Returns the width drawn.
    pub fn text(&mut self, x: i64, y: i64, text: &str, scale: i64, c: Rgb) -> i64 {
        let mut cx = x;
        for ch in text.chars() {
            if let Some(rows) = glyph(ch.to_ascii_uppercase()) {
                for (r, row) in rows.iter().enumerate() {
                    for (k, b) in row.bytes().enumerate() {
                        if b == b'#' {
                            self.rect(cx + k as i64 * scale, y + r as i64 * scale, scale, scale, c);
                        }
                    }
                }
            }
            cx += 6 * scale;
        }
        cx - x
    }

    /// The picture as PNG bytes (8-bit RGB).
    pub fn to_png(&self) -> anyhow::Result<Vec<u8>> {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.write_header()?.write_image_data(&self.pixels)?;
        Ok(out)
    }
}

/// The width in pixels of `text` drawn at `scale`.
pub fn text_width(text: &str, scale: i64) -> i64 {
    text.chars().count() as i64 * 6 * scale
}

/// The 5x7 glyph of `ch` as seven rows of `#` (ink) and `.`; `None` for a blank.
fn glyph(ch: char) -> Option<[&'static str; 7]> {
    let g = match ch {
        '0' => [".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."],
        '1' => ["..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."],
        '2' => [".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"],
        '3' => ["####.", "....#", "....#", ".###.", "....#", "....#", "####."],
        '4' => ["...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."],
        '5' => ["#####", "#....", "####.", "....#", "....#", "#...#", ".###."],
        '6' => ["..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."],
        '7' => ["#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."],
        '8' => [".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."],
        '9' => [".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."],
        'A' => [".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"],
        'B' => ["####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."],
        'C' => [".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."],
        'D' => ["####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."],
        'E' => ["#####", "#....", "#....", "####.", "#....", "#....", "#####"],
        'F' => ["#####", "#....", "#....", "####.", "#....", "#....", "#...."],
        'G' => [".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"],
        'H' => ["#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"],
        'I' => [".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."],
        'J' => ["..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."],
        'K' => ["#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"],
        'L' => ["#....", "#....", "#....", "#....", "#....", "#....", "#####"],
        'M' => ["#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"],
        'N' => ["#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"],
        'O' => [".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."],
        'P' => ["####.", "#...#", "#...#", "####.", "#....", "#....", "#...."],
        'Q' => [".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"],
        'R' => ["####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"],
        'S' => [".####", "#....", "#....", ".###.", "....#", "....#", "####."],
        'T' => ["#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."],
        'U' => ["#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."],
        'V' => ["#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."],
        'W' => ["#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."],
        'X' => ["#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"],
        'Y' => ["#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."],
        'Z' => ["#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"],
        '.' => [".....", ".....", ".....", ".....", ".....", ".##..", ".##.."],
        ',' => [".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."],
        ':' => [".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."],
        '-' => [".....", ".....", ".....", "#####", ".....", ".....", "....."],
        '+' => [".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."],
        '/' => [".....", "....#", "...#.", "..#..", ".#...", "#....", "....."],
        '(' => ["...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."],
        ')' => [".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."],
        '=' => [".....", ".....", "#####", ".....", "#####", ".....", "....."],
        '%' => ["##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"],
        _ => return None,
    };
    Some(g)
}

/// One line of a chart: its label, colour, whether it is dashed, and its points
/// (x, y), both positive (log-log).
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Line colour.
    pub colour: Rgb,
    /// Dashed instead of solid.
    pub dashed: bool,
    /// Line width in pixels.
    pub width: i64,
    /// Data points; points with a non-positive or non-finite coordinate are left out.
    pub points: Vec<(f64, f64)>,
}

/// Where the plot area lies on the canvas and which decades it spans.
pub struct LogAxes {
    left: i64,
    top: i64,
    width: i64,
    height: i64,
    x_decades: (i32, i32),
    y_decades: (i32, i32),
}

impl LogAxes {
    /// The pixel of the value (x, y).
    pub fn pixel(&self, x: f64, y: f64) -> (i64, i64) {
        let fx = (x.log10() - self.x_decades.0 as f64) / (self.x_decades.1 - self.x_decades.0) as f64;
        let fy = (y.log10() - self.y_decades.0 as f64) / (self.y_decades.1 - self.y_decades.0) as f64;
        (self.left + (fx * self.width as f64).round() as i64, self.top + self.height - (fy * self.height as f64).round() as i64)
    }
}

/// The decades (floor, ceil of log10) spanning `values`; at least one decade.
fn decades(values: impl Iterator<Item = f64>) -> (i32, i32) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && *v > 0.0) {
        lo = lo.min(v.log10());
        hi = hi.max(v.log10());
    }
    if !lo.is_finite() {
        return (0, 1);
    }
    let (a, b) = (lo.floor() as i32, hi.ceil() as i32);
    (a, b.max(a + 1))
}

/// 10^e as a short label: 1, 10, 100, 1K, 10K, 100K, 1M, 10M ...
fn decade_label(e: i32) -> String {
    match e {
        i32::MIN..=-1 => format!("1E{e}"),
        0..=2 => format!("{}", 10u64.pow(e as u32)),
        3..=5 => format!("{}K", 10u64.pow(e as u32 - 3)),
        6..=8 => format!("{}M", 10u64.pow(e as u32 - 6)),
        _ => format!("1E{e}"),
    }
}

const BLACK: Rgb = [0, 0, 0];
const GRID: Rgb = [222, 222, 222];

/// A log-log line chart of `series` on a `width` x `height` canvas: decade grid lines
/// with labels and minor ticks on both axes, axis titles, a title, and a legend right
/// of the plot (one entry per series, in order). Returns the canvas and its axes.
pub fn log_log(width: u32, height: u32, title: &str, x_title: &str, y_title: &str, series: &[Series]) -> (Canvas, LogAxes) {
    let mut canvas = Canvas::new(width, height);
    let points = || series.iter().flat_map(|s| s.points.iter()).filter(|(x, y)| *x > 0.0 && *y > 0.0);
    let legend_width = series.iter().map(|s| text_width(&s.label, 1)).max().unwrap_or(0) + 40;
    let axes = LogAxes {
        left: 70,
        top: 40,
        width: width as i64 - 70 - 20 - legend_width,
        height: height as i64 - 40 - 60,
        x_decades: decades(points().map(|p| p.0)),
        y_decades: decades(points().map(|p| p.1)),
    };
    canvas.text(axes.left, 10, title, 2, BLACK);
    let (bottom, right) = (axes.top + axes.height, axes.left + axes.width);
    for e in axes.x_decades.0..=axes.x_decades.1 {
        let (x, _) = axes.pixel(10f64.powi(e), 1.0);
        canvas.line((x, axes.top), (x, bottom), 1, None, GRID);
        canvas.line((x, bottom), (x, bottom + 6), 1, None, BLACK);
        let label = decade_label(e);
        canvas.text(x - text_width(&label, 1) / 2, bottom + 10, &label, 1, BLACK);
        for m in (2..10).filter(|_| e < axes.x_decades.1) {
            let (xm, _) = axes.pixel(m as f64 * 10f64.powi(e), 1.0);
            canvas.line((xm, bottom), (xm, bottom + 3), 1, None, BLACK);
        }
    }
    for e in axes.y_decades.0..=axes.y_decades.1 {
        let (_, y) = axes.pixel(1.0, 10f64.powi(e));
        canvas.line((axes.left, y), (right, y), 1, None, GRID);
        canvas.line((axes.left - 6, y), (axes.left, y), 1, None, BLACK);
        let label = decade_label(e);
        canvas.text(axes.left - 10 - text_width(&label, 1), y - 3, &label, 1, BLACK);
        for m in (2..10).filter(|_| e < axes.y_decades.1) {
            let (_, ym) = axes.pixel(1.0, m as f64 * 10f64.powi(e));
            canvas.line((axes.left - 3, ym), (axes.left, ym), 1, None, BLACK);
        }
    }
    canvas.line((axes.left, axes.top), (axes.left, bottom), 1, None, BLACK);
    canvas.line((axes.left, bottom), (right, bottom), 1, None, BLACK);
    canvas.text(axes.left + axes.width / 2 - text_width(x_title, 1), bottom + 28, x_title, 2, BLACK);
    canvas.text(4, axes.top - 14, y_title, 1, BLACK);
    let legend_x = right + 20;
    for (k, s) in series.iter().enumerate() {
        let dash = s.dashed.then_some(4);
        let pts: Vec<(i64, i64)> = s
            .points
            .iter()
            .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
            .map(|&(x, y)| axes.pixel(x, y))
            .collect();
        for w in pts.windows(2) {
            canvas.line(w[0], w[1], s.width, dash, s.colour);
        }
        for &(x, y) in &pts {
            canvas.rect(x - 2, y - 2, 5, 5, s.colour);
        }
        let y = axes.top + 4 + 14 * k as i64;
        canvas.line((legend_x, y + 3), (legend_x + 24, y + 3), s.width, dash, s.colour);
        canvas.text(legend_x + 30, y, &s.label, 1, BLACK);
    }
    (canvas, axes)
}

/// Distinct line colours, taken in order (then again from the start).
pub const PALETTE: [Rgb; 10] = [
    [31, 119, 180],
    [214, 39, 40],
    [44, 160, 44],
    [255, 127, 14],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
    [188, 189, 34],
    [127, 127, 127],
];

/// A stable colour per name: the first name seen gets the palette's first colour.
#[derive(Default)]
pub struct Colours(HashMap<String, Rgb>);

impl Colours {
    /// The colour of `name`.
    pub fn of(&mut self, name: &str) -> Rgb {
        let next = PALETTE[self.0.len() % PALETTE.len()];
        *self.0.entry(name.to_string()).or_insert(next)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_lights_its_pixels_and_no_others() {
        let mut c = Canvas::new(20, 10);
        c.line((2, 5), (17, 5), 1, None, [255, 0, 0]);
        for x in 0..20 {
            let want = if (2..=17).contains(&x) { [255, 0, 0] } else { [255; 3] };
            assert_eq!(c.get(x, 5), Some(want), "x = {x}");
            assert_eq!(c.get(x, 4), Some([255; 3]));
        }
        // A diagonal visits one pixel per step; a dashed one skips every other run of 3.
        let mut d = Canvas::new(10, 10);
        d.line((0, 0), (9, 9), 1, Some(3), [0, 0, 255]);
        let lit: Vec<i64> = (0..10).filter(|&i| d.get(i, i) == Some([0, 0, 255])).collect();
        assert_eq!(lit, [0, 1, 2, 6, 7, 8]);
    }

    #[test]
    fn text_draws_the_glyphs_and_skips_unknown_characters() {
        let mut c = Canvas::new(40, 10);
        assert_eq!(c.text(0, 0, "1?", 1, BLACK), 12);
        // '1': its stem is column 2, rows 0-6; the base is columns 1-3 of row 6.
        assert!((0..7).all(|r| c.get(2, r) == Some(BLACK)));
        assert_eq!(c.get(1, 6), Some(BLACK));
        assert_eq!(c.get(0, 0), Some([255; 3]));
        assert!((6..12).all(|x| (0..10).all(|y| c.get(x, y) == Some([255; 3]))), "'?' draws nothing");
        for ch in "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.,:-+/()=%".chars() {
            let g = glyph(ch).expect("every listed character has a glyph");
            assert!(g.iter().all(|row| row.len() == 5), "{ch}");
        }
    }

    #[test]
    fn log_log_puts_points_on_decades_and_the_png_decodes() {
        let series = [Series { label: "GREEDY".into(), colour: [255, 0, 0], dashed: false, width: 2, points: vec![(1e3, 10.0), (1e5, 1000.0)] }];
        let (canvas, axes) = log_log(400, 300, "T", "X", "Y", &series);
        assert_eq!((axes.x_decades, axes.y_decades), ((3, 5), (1, 3)));
        // The corners of the plot area are the points; the middle of the line is the
        // point (1e4, 100), two decades from each end on both axes.
        assert_eq!(axes.pixel(1e3, 10.0), (axes.left, axes.top + axes.height));
        assert_eq!(axes.pixel(1e5, 1000.0), (axes.left + axes.width, axes.top));
        let (mx, my) = axes.pixel(1e4, 100.0);
        assert_eq!(canvas.get(mx, my), Some([255, 0, 0]));
        let bytes = canvas.to_png().unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height, info.color_type), (400, 300, png::ColorType::Rgb));
        let i = (my as usize * 400 + mx as usize) * 3;
        assert_eq!(&buf[i..i + 3], &[255, 0, 0]);
        assert_eq!(decade_label(6), "1M");
        assert_eq!(decade_label(4), "10K");
    }
}
