//! An RGB picture drawn pixel by pixel: filled rectangles, text in an 8×8 bitmap font
//! (`font8x8`, public domain) scaled by whole pixels, a colour ramp, PNG bytes.

use font8x8::legacy::BASIC_LEGACY;

pub type Rgb = [u8; 3];
#[cfg(test)]
pub const WHITE: Rgb = [255, 255, 255];
pub const BLACK: Rgb = [0, 0, 0];
pub const GREY: Rgb = [120, 120, 120];

/// The side of a glyph at scale 1 [px].
pub const GLYPH: usize = 8;

/// A picture `width` × `height`, rows from the top.
pub struct Canvas {
    pub width: usize,
    pub height: usize,
    rgb: Vec<u8>,
}

impl Canvas {
    /// A white picture.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            rgb: vec![255; width * height * 3],
        }
    }

    /// Fills the pixels of columns `x0..x1` and rows `y0..y1` (clipped to the picture).
    pub fn rect(&mut self, [x0, x1]: [f64; 2], [y0, y1]: [f64; 2], colour: Rgb) {
        let span = |a: f64, b: f64, n: usize| {
            let lo = a.round().max(0.0) as usize;
            lo.min(n)..(b.round().max(0.0) as usize).min(n)
        };
        for row in span(y0, y1, self.height) {
            for col in span(x0, x1, self.width) {
                let at = 3 * (row * self.width + col);
                self.rgb[at..at + 3].copy_from_slice(&colour);
            }
        }
    }

    /// The width of `text` at `scale` [px].
    pub fn text_width(text: &str, scale: usize) -> usize {
        text.chars().count() * GLYPH * scale
    }

    /// Writes `text` with its top-left corner at (`x`, `y`), each font pixel `scale`
    /// pixels wide; characters outside ASCII are drawn as `?`.
    pub fn text(&mut self, text: &str, [x, y]: [usize; 2], scale: usize, colour: Rgb) {
        for (k, c) in text.chars().enumerate() {
            let glyph = BASIC_LEGACY[if c.is_ascii() {
                c as usize
            } else {
                b'?' as usize
            }];
            let left = x + k * GLYPH * scale;
            for (row, bits) in glyph.iter().enumerate() {
                for col in (0..GLYPH).filter(|col| bits & (1 << col) != 0) {
                    let (px, py) = (left + col * scale, y + row * scale);
                    let s = scale as f64;
                    self.rect(
                        [px as f64, px as f64 + s],
                        [py as f64, py as f64 + s],
                        colour,
                    );
                }
            }
        }
    }

    /// The picture as PNG bytes.
    pub fn png(&self) -> Result<Vec<u8>, png::EncodingError> {
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, self.width as u32, self.height as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&self.rgb)?;
        writer.finish()?;
        Ok(bytes)
    }

    /// The colour of the pixel at (`x`, `y`).
    #[cfg(test)]
    pub fn at(&self, x: usize, y: usize) -> Rgb {
        let at = 3 * (y * self.width + x);
        [self.rgb[at], self.rgb[at + 1], self.rgb[at + 2]]
    }
}

/// Blue (0) through teal and green to yellow (1).
pub fn ramp(t: f64) -> Rgb {
    const STOPS: [[f64; 3]; 4] = [
        [40., 60., 160.],
        [30., 140., 150.],
        [90., 190., 90.],
        [250., 220., 40.],
    ];
    let t = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let k = (t.floor() as usize).min(STOPS.len() - 2);
    let f = t - k as f64;
    [0, 1, 2].map(|c| (STOPS[k][c] * (1.0 - f) + STOPS[k + 1][c] * f).round() as u8)
}

/// Tick values for the interval `lo`–`hi`: multiples of 1, 2 or 5 × 10^k, about
/// `count` of them, and the decimals their labels need.
pub fn ticks(lo: f64, hi: f64, count: usize) -> (Vec<f64>, usize) {
    let raw = (hi - lo).max(f64::MIN_POSITIVE) / count.max(1) as f64;
    let power = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * power)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * power);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let values = (first..=last).map(|k| k as f64 * step).collect();
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    (values, decimals)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_numbers_inside_the_interval() {
        let (t, d) = ticks(0.0, 1.61, 5);
        assert_eq!(t, vec![0.0, 0.5, 1.0, 1.5]);
        assert_eq!(d, 1);
        let (t, d) = ticks(-0.06, 0.57, 5);
        assert_eq!((t, d), (vec![0.0, 0.2, 0.4], 1));
        let (t, d) = ticks(0.0, 3220.0, 4);
        assert_eq!((t, d), (vec![0.0, 1000.0, 2000.0, 3000.0], 0));
    }

    #[test]
    fn text_is_drawn_in_the_glyphs_pixels() {
        let mut c = Canvas::new(40, 20);
        c.text("1", [0, 0], 2, BLACK);
        // the font's "1" has its stem in columns 2-3 of rows 0-5
        assert_eq!(c.at(2 * 2 + 1, 2 * 3), BLACK);
        assert_eq!(c.at(39, 19), WHITE);
        assert_eq!(Canvas::text_width("abc", 2), 48);
    }
}
