//! A look at a case before it runs: its initial particles as a snapshot (HDF5 with
//! its XDMF index, for ParaView) and, in 2D, a PNG picture of them: walls grey, fluid
//! coloured by its initial pressure from blue (lowest) to yellow (highest).

use super::output::{with_extras, Output};
use crate::error::{Result, SphError};
use crate::particles::Kind;
use crate::simulation::Simulation;
use std::path::PathBuf;

/// The picture's longer side [px].
const LONG_SIDE: usize = 1200;
/// Blank border [px].
const BORDER: usize = 8;

/// Writes the initial snapshot, and in 2D `preview.png`, into `out`; returns the
/// paths written.
pub fn write<const D: usize>(sim: &Simulation<D>, out: &mut Output) -> Result<Vec<PathBuf>> {
    let snapshot = with_extras(sim, |extras| out.snapshot(sim.particles(), extras, 0.0, 0))?;
    let mut written = vec![snapshot];
    if D == 2 {
        let png = picture(sim).map_err(|e| SphError::output(out.dir().join("preview.png"), e))?;
        written.push(out.write_bytes("preview.png", &png)?);
    }
    Ok(written)
}

/// The particles drawn as squares of their spacing's side, as PNG bytes.
fn picture<const D: usize>(
    sim: &Simulation<D>,
) -> std::result::Result<Vec<u8>, png::EncodingError> {
    let p = sim.particles();
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for x in &p.x {
        for d in 0..2 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    let dx = sim.case().dx();
    let span = [(hi[0] - lo[0] + dx).max(dx), (hi[1] - lo[1] + dx).max(dx)];
    let scale = (LONG_SIDE - 2 * BORDER) as f64 / span[0].max(span[1]);
    let size = [0, 1].map(|d| (span[d] * scale).ceil() as usize + 2 * BORDER);
    let mut rgb = vec![255u8; size[0] * size[1] * 3];
    let fluid: Vec<f64> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| p.rho[i])
        .collect();
    let (rho_lo, rho_hi) = fluid
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &r| (a.min(r), b.max(r)));
    // each particle fills its lattice cell, rounded out to whole pixels: no gaps, no moiré
    let half = (0.5 * dx * scale + 0.5).max(1.0);
    for i in 0..p.len() {
        let colour = match p.kind[i] {
            Kind::Wall => [120, 120, 120],
            Kind::Fluid => ramp((p.rho[i] - rho_lo) / (rho_hi - rho_lo).max(f64::MIN_POSITIVE)),
        };
        let centre = [0, 1].map(|d| (p.x[i][d] - lo[d] + 0.5 * dx) * scale + BORDER as f64);
        // rows from the top: y grows upwards in the picture
        square(
            &mut rgb,
            size,
            [centre[0], size[1] as f64 - centre[1]],
            half,
            colour,
        );
    }
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, size[0] as u32, size[1] as u32);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&rgb)?;
    writer.finish()?;
    Ok(bytes)
}

/// Blue (0) through teal and green to yellow (1).
fn ramp(t: f64) -> [u8; 3] {
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

fn square(rgb: &mut [u8], size: [usize; 2], centre: [f64; 2], half: f64, colour: [u8; 3]) {
    let range = |c: f64, n: usize| {
        let a = (c - half).round().max(0.0) as usize;
        let b = ((c + half).round().max(0.0) as usize).min(n);
        a..b
    };
    for row in range(centre[1], size[1]) {
        for col in range(centre[0], size[0]) {
            let at = 3 * (row * size[0] + col);
            rgb[at..at + 3].copy_from_slice(&colour);
        }
    }
}
