//! A prescribed rigid motion: the pivot's displacement and the rotation about it as
//! expressions of time (exmex), differentiated exactly once and twice, columns of a
//! table, or a wave maker's motion ([`crate::waves::paddle`]) with its active
//! absorption ([`crate::waves::active_absorption`]), with an optional smooth-step ramp
//! (see `PrescribedMotion::ramp_at`).

use super::rigid::{angular_rates, Pose};
use super::table::{self, Spline};
use crate::case::expression::{named_values, Compiled, Variables};
use crate::case::{MotionTable, PrescribedConfig};
use crate::error::{Result, SphError};
use crate::particles::Vector;
use crate::waves::active_absorption::ActiveAbsorption;
use crate::waves::paddle::PaddleSignal;
use nalgebra::{Rotation3, Vector3};
use std::path::Path;

/// One component of a motion as a function of t, with its first and second
/// derivatives: an expression differentiated exactly, a column of a table, or a wave
/// maker's coordinate.
enum Signal {
    /// `f`, `f'`, `f''` (boxed: a parsed expression is large).
    Expression(Box<[Compiled; 3]>),
    Table(Spline),
    Paddle(PaddleSignal),
}

impl Signal {
    fn expression(key: String, text: &str, names: &[(String, f64)]) -> Result<Self> {
        let variables = Variables {
            dimension: 0,
            time: true,
        };
        let f = Compiled::new(key, text, names, variables)?;
        let rate = f.time_derivative()?;
        let rate2 = rate.time_derivative()?;
        Ok(Self::Expression(Box::new([f, rate, rate2])))
    }

    /// `(g, g', g'')` of `g = s f` at `t`, `s` the ramp with its derivatives; a wave
    /// maker's ramped stroke takes `correction` (its active absorption's) before it
    /// becomes the paddle's coordinate.
    fn at(&self, t: f64, s: [f64; 3], correction: [f64; 3], scratch: &mut Vec<f64>) -> [f64; 3] {
        match self {
            Signal::Expression(f) => ramped(
                s,
                [
                    f[0].value(&[], t, scratch),
                    f[1].value(&[], t, scratch),
                    f[2].value(&[], t, scratch),
                ],
            ),
            Signal::Table(spline) => ramped(s, spline.at(t)),
            Signal::Paddle(paddle) => {
                let stroke = ramped(s, paddle.stroke_at(t));
                paddle.coordinate(std::array::from_fn(|k| stroke[k] + correction[k]))
            }
        }
    }
}

/// `(g, g', g'')` of `g = s f` from those of `s` and `f`.
fn ramped(s: [f64; 3], [f, f1, f2]: [f64; 3]) -> [f64; 3] {
    [
        s[0] * f,
        s[1] * f + s[0] * f1,
        s[2] * f + 2.0 * s[1] * f1 + s[0] * f2,
    ]
}

/// The motion of one body, from its `prescribed` table.
pub struct PrescribedMotion<const D: usize> {
    /// The case key of the table, `tank[0].prescribed`, for messages.
    pub key: String,
    /// The pivot at t = 0.
    pub pivot: Vector<D>,
    displacement: Vec<Signal>,
    /// 2D: the angle (about z); 3D: the rotation vector.
    rotation: Vec<Signal>,
    ramp: f64,
    /// A wave maker's `duration`: the motion ramps down over `ramp` after it.
    duration: Option<f64>,
    /// A wave maker's waves in words, for `sph-cli check`.
    pub waves: Option<String>,
    /// A wave maker's active absorption and its gauge's line (x in 2D, (x, y) in 3D).
    pub absorption: Option<Box<(ActiveAbsorption, Vec<f64>)>>,
}

impl<const D: usize> PrescribedMotion<D> {
    /// Parses the table `key` (its lengths were checked with the case), reading its
    /// `table` file for a run that ends at `end`; `g` is the magnitude of gravity (wave
    /// makers).
    pub fn new(key: String, config: &PrescribedConfig, end: f64, g: f64) -> Result<Self> {
        let (displacement, rotation) = match (&config.table, &config.waves) {
            (Some(table), _) => Self::columns(&key, config, table, end)?,
            (None, Some(waves)) => Self::wave_maker(PaddleSignal::new(&waves.maker(g), g, D)),
            (None, None) => Self::expressions(&key, config)?,
        };
        let wave_period = config.waves.as_ref().map(|w| w.period(g));
        let pivot = config.pivot.as_deref().unwrap_or(&[0.0; 3]);
        Ok(Self {
            pivot: Vector::from_fn(|d, _| pivot[d]),
            displacement,
            rotation,
            ramp: (config.ramp.or(wave_period.map(|t| 2.0 * t))).unwrap_or(0.0),
            duration: config.waves.as_ref().and_then(|w| w.duration),
            waves: config.waves.as_ref().map(|w| w.describe(g)),
            absorption: None,
            key,
        })
    }

    /// A piston's displacement along x, or a flap's rotation (2D about z, 3D about y).
    fn wave_maker(signal: PaddleSignal) -> (Vec<Signal>, Vec<Signal>) {
        if !signal.turns() {
            return (vec![Signal::Paddle(signal)], Vec::new());
        }
        let rotation = if D == 2 {
            vec![Signal::Paddle(signal)]
        } else {
            let zero = || Signal::Paddle(PaddleSignal::zero());
            vec![zero(), Signal::Paddle(signal), zero()]
        };
        (Vec::new(), rotation)
    }

    /// The displacement and rotation expressions of the table `key`.
    fn expressions(key: &str, config: &PrescribedConfig) -> Result<(Vec<Signal>, Vec<Signal>)> {
        let variables = Variables {
            dimension: 0,
            time: true,
        };
        let names = named_values(key, &[], config.constants.as_ref(), variables)?;
        let signals = |name: &str, texts: &Option<Vec<String>>| -> Result<Vec<Signal>> {
            (texts.iter().flatten().enumerate())
                .map(|(d, text)| Signal::expression(format!("{key}.{name}[{d}]"), text, &names))
                .collect()
        };
        Ok((
            signals("displacement", &config.displacement)?,
            signals("rotation", &config.rotation)?,
        ))
    }

    /// The columns of the `table` (a file or rows): t, then D displacements, then the
    /// rotation (none, or 2D one angle, 3D a rotation vector), each a spline.
    fn columns(
        key: &str,
        config: &PrescribedConfig,
        motion_table: &MotionTable,
        end: f64,
    ) -> Result<(Vec<Signal>, Vec<Signal>)> {
        let table_key = format!("{key}.table");
        let (t, mut columns) = match motion_table {
            MotionTable::File(file) => table::read_columns(&table_key, Path::new(file), end)?,
            MotionTable::Rows(rows) => {
                table::columns(&table_key, &motion_table.describe(), rows, end)?
            }
        };
        let turns = if D == 2 { 1 } else { 3 };
        if columns.len() != D && columns.len() != D + turns {
            return Err(SphError::invalid(
                table_key,
                format!(
                    "{} with {} value columns",
                    motion_table.describe(),
                    columns.len()
                ),
                format!(
                    "t and {D} displacement columns, then optionally {turns} rotation column{}",
                    if turns == 1 { "" } else { "s" }
                ),
            ));
        }
        if columns.len() > D && config.pivot.is_none() {
            return Err(SphError::invalid(
                format!("{key}.pivot"),
                "none",
                "the point the body turns about, beside a table with rotation columns",
            ));
        }
        let rotation = columns.split_off(D);
        let spline = |y: Vec<f64>| Signal::Table(Spline::new(t.clone(), y));
        Ok((
            columns.into_iter().map(spline).collect(),
            rotation.into_iter().map(spline).collect(),
        ))
    }

    /// The ramp `s = 10τ³ - 15τ⁴ + 6τ⁵`, τ = t/T, for t < T (1 after) and its two
    /// derivatives: s' and s'' vanish at both ends, so that the motion's velocity and
    /// acceleration start from zero and join the unramped motion without a jump (a
    /// cosine ramp leaves an acceleration jump at t = T that rings through the water).
    /// After a wave maker's `duration` the motion is multiplied again, by `1 - s` of
    /// `t - duration`, and stops.
    pub fn ramp_at(&self, t: f64) -> [f64; 3] {
        let up = smooth_step(t, self.ramp);
        let Some(end) = self.duration else {
            return up;
        };
        let [d, d1, d2] = smooth_step(t - end, self.ramp);
        ramped(up, [1.0 - d, -d1, -d2])
    }

    /// The pose at time `t` (with an active absorption's correction, at or after its
    /// last update).
    pub fn pose(&self, t: f64) -> Pose<D> {
        let s = self.ramp_at(t);
        let correction = (self.absorption.as_deref()).map_or([0.0; 3], |(a, _)| a.correction(t));
        let scratch = &mut Vec::new();
        let mut linear = [Vector::<D>::zeros(); 3];
        for (d, e) in self.displacement.iter().enumerate() {
            for (k, v) in e.at(t, s, correction, scratch).into_iter().enumerate() {
                linear[k][d] = v;
            }
        }
        let mut angular = [Vector3::zeros(); 3];
        let axes: &[usize] = if D == 2 { &[2] } else { &[0, 1, 2] };
        for (e, &axis) in self.rotation.iter().zip(axes) {
            for (k, v) in e.at(t, s, correction, scratch).into_iter().enumerate() {
                angular[k][axis] = v;
            }
        }
        let (omega, alpha) = angular_rates(&angular[0], &angular[1], &angular[2]);
        Pose {
            pivot: self.pivot + linear[0],
            phi: angular[0],
            rotation: Rotation3::from_scaled_axis(angular[0]),
            velocity: linear[1],
            acceleration: linear[2],
            omega,
            alpha,
        }
    }

    /// Refuses a motion that is not finite at the sample times `times`, or that does
    /// not start at rest where it is built (displacement and rotation zero at t = 0).
    pub fn check(&self, times: &[f64]) -> Result<()> {
        let start = self.pose(0.0);
        let moved = (start.pivot - self.pivot).norm() + start.rotation.angle();
        if moved > 1e-9 {
            return Err(SphError::invalid(
                &self.key,
                format!(
                    "a displacement {:?} and rotation {:.3e} rad at t = 0",
                    (start.pivot - self.pivot).as_slice(),
                    start.rotation.angle()
                ),
                "a motion that starts where the case builds the body: displacement and \
                 rotation zero at t = 0 (or a ramp)",
            ));
        }
        for &t in times {
            let p = self.pose(t);
            let values = (p.pivot.iter().chain(&p.velocity).chain(&p.acceleration))
                .chain(p.omega.iter().chain(&p.alpha));
            if values.clone().any(|v| !v.is_finite()) {
                return Err(SphError::invalid(
                    &self.key,
                    format!("t = {t}"),
                    "a motion finite, with finite first and second derivatives, over the run",
                ));
            }
        }
        Ok(())
    }
}

/// The smooth step `s = 10τ³ - 15τ⁴ + 6τ⁵`, τ = t/T, 0 before t = 0 and 1 after T,
/// with its two derivatives.
fn smooth_step(t: f64, ramp: f64) -> [f64; 3] {
    if t >= ramp {
        return [1.0, 0.0, 0.0];
    }
    if t <= 0.0 {
        return [0.0; 3];
    }
    let (tau, inv) = (t / ramp, 1.0 / ramp);
    let rest = 1.0 - tau;
    [
        tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau),
        30.0 * tau * tau * rest * rest * inv,
        60.0 * tau * rest * (1.0 - 2.0 * tau) * inv * inv,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion<const D: usize>(toml: &str) -> PrescribedMotion<D> {
        let config: PrescribedConfig = toml::from_str(toml).unwrap();
        PrescribedMotion::new("wall[0].prescribed".into(), &config, 1.0, 9.81).unwrap()
    }

    #[test]
    fn derivatives_are_exact_and_the_ramp_is_smooth() {
        let m = motion::<2>(
            "pivot = [1.0, 0.5]\ndisplacement = [\"A*sin(w*t)\", \"t^2\"]\n\
             rotation = [\"0.1*t^3\"]\nconstants = { A = 0.2, w = 3.0 }",
        );
        let t = 0.7;
        let p = m.pose(t);
        let (a, w) = (0.2, 3.0);
        let close = |x: f64, y: f64| (x - y).abs() < 1e-13 * (1.0 + y.abs());
        assert!(close(p.pivot[0], 1.0 + a * (w * t).sin()) && close(p.pivot[1], 0.5 + t * t));
        assert!(close(p.velocity[0], a * w * (w * t).cos()) && close(p.velocity[1], 2.0 * t));
        assert!(close(p.acceleration[0], -a * w * w * (w * t).sin()));
        assert!(close(p.acceleration[1], 2.0));
        assert!(close(p.omega[2], 0.3 * t * t) && close(p.alpha[2], 0.6 * t));
        assert!(close(p.rotation.angle(), 0.1 * t.powi(3)));
        // with a ramp of 1 s the motion and its first two derivatives start at zero and
        // join the unramped motion continuously
        let m = motion::<2>("displacement = [\"1 + t\", \"0\"]\nramp = 1.0");
        let p = m.pose(0.0);
        assert!(p.pivot.norm() == 0.0 && p.velocity.norm() == 0.0 && p.acceleration.norm() == 0.0);
        assert!(close(m.pose(0.5).pivot[0], 0.5 * 1.5));
        let (before, after) = (m.pose(1.0 - 1e-9), m.pose(1.0 + 1e-9));
        assert!((before.velocity - after.velocity).norm() < 1e-7);
        assert!((before.acceleration - after.acceleration).norm() < 1e-6);
        assert!(m.check(&[0.0, 0.5, 2.0]).is_ok());
    }

    /// A wave maker with a `duration` ramps down after it, without a jump in velocity
    /// or acceleration, and stands still at its rest once the ramp is over.
    #[test]
    fn a_wave_train_ramps_down_and_stops() {
        let m = motion::<2>(
            "ramp = 1.0
[waves]
paddle = \"piston\"
depth = 0.5
height = 0.02
             period = 1.3
duration = 3.0
",
        );
        let close = |a: &Pose<2>, b: &Pose<2>| {
            (a.velocity - b.velocity).norm() < 1e-7
                && (a.acceleration - b.acceleration).norm() < 1e-6
        };
        for t in [1.0, 3.0, 4.0] {
            assert!(close(&m.pose(t - 1e-9), &m.pose(t + 1e-9)), "t = {t}");
        }
        assert!(m.pose(2.0).velocity.norm() > 1e-3);
        let rest = m.pose(4.5);
        assert!(rest.pivot.norm() == 0.0 && rest.velocity.norm() == 0.0);
    }

    #[test]
    fn motions_that_jump_or_blow_up_are_refused() {
        let jump = motion::<2>("displacement = [\"1 + t\", \"0\"]");
        let e = jump.check(&[1.0]).unwrap_err().to_string();
        assert!(
            e.starts_with("wall[0].prescribed = a displacement [1.0, 0.0]"),
            "{e}"
        );
        let blow = motion::<3>("rotation = [\"0\", \"0\", \"t/(t - 1)\"]\npivot = [0, 0, 0]");
        let e = blow.check(&[0.5, 1.0]).unwrap_err().to_string();
        assert!(e.contains("t = 1") && e.contains("finite"), "{e}");
    }
}
