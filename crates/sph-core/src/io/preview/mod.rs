//! A look at a case before it runs: its initial particles as a snapshot (HDF5 with
//! its XDMF index, for ParaView) and `preview.png`: walls grey, fluid coloured by its
//! initial pressure from blue (lowest) to yellow (highest), with the case's name and
//! particle counts as a title, axes with ticks in metres and a colour bar in Pascals.
//! A 2D case is drawn as it is; a 3D case as two projections side by side, a side view
//! (x, z) and a top view (x, y), each particle drawn over those behind it.

mod canvas;

use super::output::{with_extras, Output};
use crate::error::{Result, SphError};
use crate::particles::{Kind, Particles};
use crate::simulation::Simulation;
use canvas::{ramp, ticks, Canvas, Rgb, BLACK, GLYPH, GREY};
use std::path::PathBuf;

/// The drawing's width, all panels together [px].
const WIDTH: usize = 1200;
/// The tallest a panel is drawn [px].
const MAX_PANEL_HEIGHT: usize = 700;
/// Text scale: each font pixel is this many pixels.
const SCALE: usize = 2;
/// Room for the title above, tick labels left and below, the colour bar right [px].
const TOP: usize = 64;
const LEFT: usize = 88;
const BOTTOM: usize = 56;
const RIGHT: usize = 150;
/// Between two panels [px].
const GAP: usize = 96;

/// Writes the initial snapshot and `preview.png` into `out`; returns the paths written.
pub fn write<const D: usize>(sim: &Simulation<D>, out: &mut Output) -> Result<Vec<PathBuf>> {
    let snapshot = with_extras(sim, |extras| out.snapshot(sim.particles(), extras, 0.0, 0))?;
    let png = picture(sim).map_err(|e| SphError::output(out.dir().join("preview.png"), e))?;
    Ok(vec![snapshot, out.write_bytes("preview.png", &png)?])
}

/// One view of the particles: the axes drawn across and up, the bounds shown along
/// them, and where they are drawn.
struct Panel {
    across: usize,
    up: usize,
    bounds: [[f64; 2]; 2],
    /// The pixel of the bounds' lower-left corner.
    origin: [f64; 2],
    /// Pixels per metre.
    scale: f64,
}

impl Panel {
    /// The view along `across` and `up` of the particles' bounds grown by half a
    /// spacing; placed later.
    fn new<const D: usize>(across: usize, up: usize, p: &Particles<D>, dx: f64) -> Self {
        let range = |axis: usize| {
            let (lo, hi) = (p.x.iter()).fold((f64::MAX, f64::MIN), |(lo, hi), x| {
                (lo.min(x[axis]), hi.max(x[axis]))
            });
            [lo - 0.5 * dx, hi + 0.5 * dx]
        };
        Self {
            across,
            up,
            bounds: [range(across), range(up)],
            origin: [0.0; 2],
            scale: 1.0,
        }
    }

    /// The bounds' extent along the view's two axes [m].
    fn extent(&self) -> [f64; 2] {
        self.bounds.map(|[lo, hi]| hi - lo)
    }

    /// The pixel of the point at `a` across and `u` up.
    fn pixel(&self, a: f64, u: f64) -> [f64; 2] {
        [
            self.origin[0] + (a - self.bounds[0][0]) * self.scale,
            self.origin[1] - (u - self.bounds[1][0]) * self.scale,
        ]
    }
}

/// The picture of the initial particles, as PNG bytes.
fn picture<const D: usize>(
    sim: &Simulation<D>,
) -> std::result::Result<Vec<u8>, png::EncodingError> {
    let (p, dx) = (sim.particles(), sim.case().dx());
    let views: &[(usize, usize)] = if D == 2 { &[(0, 1)] } else { &[(0, 2), (0, 1)] };
    let mut panels: Vec<Panel> = views
        .iter()
        .map(|&(a, u)| Panel::new(a, u, p, dx))
        .collect();
    // one scale for every panel, the widest fitting across and none taller than allowed
    let room = (WIDTH - LEFT - RIGHT - GAP * (panels.len() - 1)) as f64;
    let across: f64 = panels.iter().map(|v| v.extent()[0]).sum();
    let up = panels.iter().map(|v| v.extent()[1]).fold(0.0, f64::max);
    let scale = (room / across).min(MAX_PANEL_HEIGHT as f64 / up);
    let height = TOP + (up * scale).ceil() as usize + BOTTOM;
    let mut canvas = Canvas::new(WIDTH, height);
    let pressure = Range::of(p);
    let mut left = LEFT as f64;
    for view in &mut panels {
        (view.origin, view.scale) = ([left, (TOP as f64) + up * scale], scale);
        draw_particles(&mut canvas, p, view, dx, &pressure);
        draw_axes(&mut canvas, view);
        left += view.extent()[0] * scale + GAP as f64;
    }
    draw_colour_bar(&mut canvas, &pressure, (TOP, height - BOTTOM));
    let fluid = p.kind.iter().filter(|k| **k == Kind::Fluid).count();
    let title = format!(
        "{}: initial pressure; {fluid} fluid, {} wall particles, dx = {dx} m",
        sim.case().name,
        p.len() - fluid
    );
    // the title at the text's scale if it fits, else at half of it
    let fits = Canvas::text_width(&title, SCALE) <= WIDTH - 16;
    canvas.text(&title, [8, 8], if fits { SCALE } else { 1 }, BLACK);
    canvas.png()
}

/// The fluid's pressure range and the colour of a particle.
struct Range {
    lo: f64,
    hi: f64,
}

impl Range {
    fn of<const D: usize>(p: &Particles<D>) -> Self {
        let fluid = (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid);
        let (lo, hi) = fluid.fold((f64::MAX, f64::MIN), |(a, b), i| {
            (a.min(p.p[i]), b.max(p.p[i]))
        });
        if lo > hi {
            return Self { lo: 0.0, hi: 0.0 };
        }
        Self { lo, hi }
    }

    fn colour(&self, value: f64) -> Rgb {
        ramp((value - self.lo) / (self.hi - self.lo).max(f64::MIN_POSITIVE))
    }
}

/// The particles of one view as squares of their spacing's side. In 3D from the back (the hidden axis' far side) to
/// the front, leaving out the walls beyond the fluid along the hidden axis (a tank's
/// near and far faces, which would hide everything inside it).
fn draw_particles<const D: usize>(
    canvas: &mut Canvas,
    p: &Particles<D>,
    view: &Panel,
    dx: f64,
    pressure: &Range,
) {
    let mut order: Vec<usize> = (0..p.len()).collect();
    if D == 3 {
        // the hidden axis: y for a side view (seen from -y), z for a top view (from +z)
        let depth = 3 - view.across - view.up;
        let fluid = (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid);
        let (lo, hi) = fluid.fold((f64::MAX, f64::MIN), |(a, b), i| {
            (a.min(p.x[i][depth]), b.max(p.x[i][depth]))
        });
        order.retain(|&i| p.kind[i] == Kind::Fluid || (lo..=hi).contains(&p.x[i][depth]));
        let sign = if view.up == 2 { -1.0 } else { 1.0 };
        order.sort_by(|&i, &j| (sign * p.x[i][depth]).total_cmp(&(sign * p.x[j][depth])));
    }
    // each particle fills its lattice cell, rounded out to whole pixels: no gaps, no moiré
    let half = (0.5 * dx * view.scale + 0.5).max(1.0);
    for i in order {
        let colour = match p.kind[i] {
            Kind::Wall => GREY,
            Kind::Fluid => pressure.colour(p.p[i]),
        };
        let [x, y] = view.pixel(p.x[i][view.across], p.x[i][view.up]);
        canvas.rect([x - half, x + half], [y - half, y + half], colour);
    }
}

/// The view's axes: a frame, ticks with their values, and the axes' names.
fn draw_axes(canvas: &mut Canvas, view: &Panel) {
    let name = |axis: usize| ["x [m]", "y [m]", "z [m]"][axis];
    let [w, h] = view.extent().map(|e| e * view.scale);
    let (b, [x0, y0]) = (&view.bounds, view.origin);
    for (xs, ys) in [
        ([x0 - 1.0, x0 + w + 1.0], [y0, y0 + 1.0]),
        ([x0 - 1.0, x0 + w + 1.0], [y0 - h - 1.0, y0 - h]),
        ([x0 - 1.0, x0], [y0 - h - 1.0, y0 + 1.0]),
        ([x0 + w, x0 + w + 1.0], [y0 - h - 1.0, y0 + 1.0]),
    ] {
        canvas.rect(xs, ys, BLACK);
    }
    let glyph = (GLYPH * SCALE) as f64;
    let (values, decimals) = ticks(b[0][0], b[0][1], 5);
    for v in values {
        let x = view.pixel(v, b[1][0])[0];
        canvas.rect([x, x + 1.0], [y0, y0 + 6.0], BLACK);
        let label = format!("{v:.decimals$}");
        let half = Canvas::text_width(&label, SCALE) as f64 / 2.0;
        canvas.text(
            &label,
            [(x - half).max(0.0) as usize, (y0 + 9.0) as usize],
            SCALE,
            BLACK,
        );
    }
    let (values, decimals) = ticks(b[1][0], b[1][1], 4);
    for v in values {
        let y = view.pixel(b[0][0], v)[1];
        canvas.rect([x0 - 6.0, x0], [y, y + 1.0], BLACK);
        let label = format!("{v:.decimals$}");
        let width = Canvas::text_width(&label, SCALE) as f64;
        let at = [
            (x0 - 9.0 - width).max(0.0) as usize,
            (y - glyph / 2.0).max(0.0) as usize,
        ];
        canvas.text(&label, at, SCALE, BLACK);
    }
    let across = name(view.across);
    let x = x0 + w / 2.0 - Canvas::text_width(across, SCALE) as f64 / 2.0;
    canvas.text(
        across,
        [x.max(0.0) as usize, (y0 + 9.0 + glyph + 6.0) as usize],
        SCALE,
        BLACK,
    );
    let up = name(view.up);
    canvas.text(
        up,
        [x0 as usize, (y0 - h - glyph - 4.0).max(0.0) as usize],
        SCALE,
        BLACK,
    );
}

/// The colour bar right of the panels, rows `top`–`bottom`, labelled in Pascals.
fn draw_colour_bar(canvas: &mut Canvas, pressure: &Range, (top, bottom): (usize, usize)) {
    let left = (WIDTH - RIGHT + 40) as f64;
    let (top, bottom) = (top as f64 + 24.0, bottom as f64);
    for row in top as usize..bottom as usize {
        let t = (bottom - row as f64) / (bottom - top);
        let colour = ramp(t);
        canvas.rect([left, left + 20.0], [row as f64, row as f64 + 1.0], colour);
    }
    canvas.text(
        "p [Pa]",
        [left as usize - 16, top as usize - 22],
        SCALE,
        BLACK,
    );
    let glyph = (GLYPH * SCALE) as f64;
    for (value, y) in [(pressure.hi, top), (pressure.lo, bottom - glyph)] {
        let label = format!("{value:.3e}");
        let x = (WIDTH - Canvas::text_width(&label, 1) - 4) as f64;
        canvas.text(&label, [x as usize, y as usize], 1, BLACK);
    }
}
