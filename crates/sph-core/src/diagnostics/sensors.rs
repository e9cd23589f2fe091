//! Pressure sensors as they are built: a face on a wall (a segment in 2D, a disc or a
//! rectangle in 3D) whose reading is the probe pressure averaged over its area, optionally passed
//! through a low-pass filter in time, as a transducer and its amplifier do. The raw
//! point value at the face's centre is written beside both.
//!
//! The average is the midpoint rule on sample points no further than Δx/4 apart (at
//! least 5 and at most 64 across; a face wider than 16Δx is sampled more coarsely,
//! still several points a spacing): the probe field varies over the kernel support,
//! so the rule is exact to well below the probes' own error.
//!
//! The filter is the second-order Butterworth low-pass, discretised by the bilinear
//! transform with the cut-off pre-warped to the series interval T:
//! `K = tan(π f_c T)`, `y_n = b0 (x_n + 2x_{n-1} + x_{n-2}) - a1 y_{n-1} - a2 y_{n-2}`,
//! `b0 = K²/(1 + √2K + K²)`, `a1 = 2(K² - 1)/(1 + √2K + K²)`,
//! `a2 = (1 - √2K + K²)/(1 + √2K + K²)`; it starts at rest on the first reading.

use crate::case::SensorConfig;
use crate::particles::Vector;

/// The fewest and the most sample points across a face.
const MIN_SAMPLES: usize = 5;
const MAX_SAMPLES: usize = 64;

/// One face sensor.
#[derive(Debug, Clone)]
pub struct Sensor<const D: usize> {
    pub name: String,
    pub centre: Vector<D>,
    /// The midpoints the face average is taken over.
    pub points: Vec<Vector<D>>,
    pub filter: Option<LowPass>,
}

impl<const D: usize> Sensor<D> {
    /// The sensor of `config` (validated), sampled for spacing `dx`, its filter (if
    /// any) running at the series interval `interval`.
    pub fn new(config: &SensorConfig, dx: f64, interval: f64) -> Self {
        let centre: Vector<D> = Vector::from_fn(|d, _| config.centre[d]);
        let normal: Vector<D> = Vector::<D>::from_fn(|d, _| config.normal[d]).normalize();
        let offsets = |length: f64| midpoints(length, dx);
        let points = if D == 2 {
            let tangent = Vector::<D>::from_fn(|d, _| [-normal[1], normal[0]][d]);
            offsets(config.size)
                .iter()
                .map(|&s| centre + tangent * s)
                .collect()
        } else if let (Some(width), Some(along)) = (config.width, &config.along) {
            let a = Vector::<D>::from_fn(|d, _| along[d]);
            let t1 = (a - normal * normal.dot(&a)).normalize();
            let t2 = cross(&normal, &t1);
            let across = offsets(width);
            offsets(config.size)
                .iter()
                .flat_map(|&s| across.iter().map(move |&b| centre + t1 * s + t2 * b))
                .collect()
        } else {
            let (t1, t2) = tangents(&normal);
            let radius = 0.5 * config.size;
            let grid = offsets(config.size);
            grid.iter()
                .flat_map(|&a| grid.iter().map(move |&b| (a, b)))
                .filter(|(a, b)| a * a + b * b <= radius * radius)
                .map(|(a, b)| centre + t1 * a + t2 * b)
                .collect()
        };
        Sensor {
            name: config.name.clone(),
            centre,
            points,
            filter: config.cutoff.map(|f| LowPass::new(f, interval)),
        }
    }

    /// The face average of the pressure field `probe`.
    pub fn average(&self, probe: impl Fn(&Vector<D>) -> f64) -> f64 {
        Self::mean(self.points.iter().map(probe))
    }

    /// The face average of the pressures `at_points`, one per point of [`Self::points`].
    pub fn mean(at_points: impl ExactSizeIterator<Item = f64>) -> f64 {
        let n = at_points.len();
        at_points.sum::<f64>() / n as f64
    }
}

/// The midpoints of `m` equal parts of a side `length` long, centred on 0: no further
/// than Δx/4 apart, with `MIN_SAMPLES <= m <= MAX_SAMPLES`.
fn midpoints(length: f64, dx: f64) -> Vec<f64> {
    let m = (length / (0.25 * dx))
        .ceil()
        .clamp(MIN_SAMPLES as f64, MAX_SAMPLES as f64) as usize;
    (0..m)
        .map(|k| length * ((k as f64 + 0.5) / m as f64 - 0.5))
        .collect()
}

/// Two unit vectors completing `n` (unit) to an orthonormal basis (3D).
fn tangents<const D: usize>(n: &Vector<D>) -> (Vector<D>, Vector<D>) {
    let axis = (0..D)
        .min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(0);
    let e = Vector::<D>::from_fn(|d, _| if d == axis { 1.0 } else { 0.0 });
    let t1 = (e - n * n.dot(&e)).normalize();
    (t1, cross(n, &t1))
}

/// `a × b` (3D).
fn cross<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
    Vector::<D>::from_fn(|d, _| {
        let (i, j) = ((d + 1) % 3, (d + 2) % 3);
        a[i] * b[j] - a[j] * b[i]
    })
}

/// Second-order Butterworth low-pass at a fixed sampling interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LowPass {
    b0: f64,
    a1: f64,
    a2: f64,
    /// `[x_{n-1}, x_{n-2}, y_{n-1}, y_{n-2}]`; NaN before the first reading.
    pub state: [f64; 4],
}

impl LowPass {
    /// The filter of cut-off `cutoff` \[Hz\] for readings every `interval` \[s\] (below
    /// the Nyquist frequency 1/2T, validated).
    pub fn new(cutoff: f64, interval: f64) -> Self {
        let k = (std::f64::consts::PI * cutoff * interval).tan();
        let norm = 1.0 + std::f64::consts::SQRT_2 * k + k * k;
        LowPass {
            b0: k * k / norm,
            a1: 2.0 * (k * k - 1.0) / norm,
            a2: (1.0 - std::f64::consts::SQRT_2 * k + k * k) / norm,
            state: [f64::NAN; 4],
        }
    }

    /// Takes the next reading; returns the filtered value.
    pub fn push(&mut self, x: f64) -> f64 {
        if self.state[0].is_nan() {
            self.state = [x; 4];
        }
        let [x1, x2, y1, y2] = self.state;
        let y = self.b0 * (x + 2.0 * x1 + x2) - self.a1 * y1 - self.a2 * y2;
        self.state = [x, x1, y, y1];
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gain of the discrete filter at frequency f: |H(e^{iωT})| with ω = 2πf.
    fn gain(filter: &LowPass, f: f64, interval: f64) -> f64 {
        let mut lp = *filter;
        let n = 20_000;
        let mut peak: f64 = 0.0;
        for k in 0..n {
            let y = lp.push((2.0 * std::f64::consts::PI * f * k as f64 * interval).sin());
            if k > n / 2 {
                peak = peak.max(y.abs());
            }
        }
        peak
    }

    /// A Butterworth filter passes DC, halves the power (gain 1/√2) at the cut-off, and
    /// falls at 12 dB per octave above it: gain 1/√(1 + 4⁴) at four times the cut-off
    /// (to 1% at fc·T = 0.01).
    #[test]
    fn the_low_pass_has_the_butterworth_response() {
        let (fc, interval) = (100.0, 1e-4);
        let filter = LowPass::new(fc, interval);
        let mut dc = filter;
        let mut y = 0.0;
        for _ in 0..2000 {
            y = dc.push(3.0);
        }
        assert!((y - 3.0).abs() < 1e-12, "{y}");
        let at_cutoff = gain(&filter, fc, interval);
        assert!((at_cutoff - 0.5f64.sqrt()).abs() < 2e-3, "{at_cutoff}");
        let two_octaves = gain(&filter, 4.0 * fc, interval);
        assert!(
            (two_octaves * 257.0f64.sqrt() - 1.0).abs() < 0.03,
            "{two_octaves}"
        );
    }

    #[test]
    fn faces_are_sampled_across_their_size() {
        let config = |centre: Vec<f64>, normal: Vec<f64>| SensorConfig {
            name: "s".into(),
            centre,
            normal,
            size: 0.01,
            width: None,
            along: None,
            cutoff: None,
        };
        let segment = Sensor::<2>::new(&config(vec![1.0, 0.2], vec![-1.0, 0.0]), 0.004, 1e-3);
        assert_eq!(segment.points.len(), 10);
        let ys: Vec<f64> = segment.points.iter().map(|p| p[1]).collect();
        assert!(segment.points.iter().all(|p| p[0] == 1.0));
        assert!((ys.iter().sum::<f64>() / 10.0 - 0.2).abs() < 1e-12);
        assert!((ys.iter().cloned().fold(f64::MIN, f64::max) - 0.2045).abs() < 1e-12);
        let disc = Sensor::<3>::new(
            &config(vec![0.0, 0.0, 0.0], vec![0.0, 0.0, 1.0]),
            0.004,
            1e-3,
        );
        // the grid points of a 10 × 10 square within the inscribed circle
        assert!(disc
            .points
            .iter()
            .all(|p| p[2].abs() < 1e-15 && p.norm() <= 0.005));
        let area = disc.points.len() as f64 * 1e-6;
        assert!(
            (area / (std::f64::consts::PI * 0.005 * 0.005) - 1.0).abs() < 0.1,
            "{area}"
        );
    }

    /// A rectangle `size` long along `along` and `width` across it, on a wall whose
    /// normal is x: its midpoints fill the rectangle, no further than Δx/4 apart, so
    /// the average of a linear field is its value at the centre, and the average of
    /// (z - z_c)², w²/12 (1 - 1/m²) by the midpoint rule with m points across, is that
    /// of the face.
    #[test]
    fn rectangles_are_sampled_along_and_across() {
        let config = SensorConfig {
            name: "r".into(),
            centre: vec![1.0, 0.3, 0.2],
            normal: vec![-1.0, 0.0, 0.0],
            size: 0.012,
            width: Some(0.006),
            along: Some(vec![0.5, 1.0, 0.0]),
            cutoff: None,
        };
        let face = Sensor::<3>::new(&config, 0.004, 1e-3);
        assert_eq!(face.points.len(), 12 * 6);
        assert!(face.points.iter().all(|p| (p[0] - 1.0).abs() < 1e-15));
        let extent = |d: usize| {
            let dev = face.points.iter().map(|p| (p[d] - config.centre[d]).abs());
            dev.fold(0.0f64, f64::max)
        };
        // the sides run along y (projected from `along`) and z, each to half a spacing
        // of its samples from its ends
        assert!(
            (extent(1) - (0.006 - 0.0005)).abs() < 1e-12,
            "{}",
            extent(1)
        );
        assert!(
            (extent(2) - (0.003 - 0.0005)).abs() < 1e-12,
            "{}",
            extent(2)
        );
        let linear = face.average(|p| 2.0 + 3.0 * p[1] - 5.0 * p[2]);
        assert!((linear - (2.0 + 0.9 - 1.0)).abs() < 1e-12, "{linear}");
        let square = face.average(|p| (p[2] - 0.2).powi(2));
        let exact = 0.006f64.powi(2) / 12.0;
        assert!(
            (square / exact - (1.0 - 1.0 / 36.0)).abs() < 1e-9,
            "{square} against {exact}"
        );
    }
}
