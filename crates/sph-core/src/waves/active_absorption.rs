//! Active absorption at a wave maker (after Schäffer & Klopman 2000): the paddle adds
//! to its wave-making motion `X₀(t)` a correction `X_c(t)` that makes, toward +x, the
//! opposite of what a fixed wall would reflect of the waves arriving at it, so that
//! they leave the flume through the paddle.
//!
//! A gauge a distance `x_g` in front of the paddle reads `η`. By linearity,
//! `η = η_I + η_R + G[X₀] + G[X_c]`: the incident wave coming back toward the paddle,
//! its reflection from a fixed wall, and the waves the paddle's two motions make
//! (progressive and evanescent, [`super::theory`]). Near the design frequency ω the
//! wall's reflection is the incident wave mirrored, so `η_I + η_R = 2 cos(k x_g) η_I(0, t)`
//! and the incident wave at the paddle is
//! `η_I(0, t) = (η - G[X₀] - G[X_c]) / (2 cos k x_g)`, with
//! `G[X_c](x_g, t) = F/ω U_c(t - x_g/c)`
//! (`F` = H/S the paddle's transfer, `c` = ω/k, `U_c = X_c'`, kept on a grid of
//! [`HISTORY`] samples over the delay). The correction's near field (its evanescent
//! modes) is left in the reading: it follows the paddle's acceleration, and taking it
//! off as `E(x_g) X̃_c`, exact at ω, fed a slow drift of the paddle back into itself,
//! so that in deep water (kd = π, `k x_g` = 0.93) the paddle ran away exponentially.
//! Left in, it reads as `E/F` of the incident wave (the absorbing paddle's reflection at
//! kd = 1 went from 3.3% to 3.7%, docs/validation/wave_flume.md). The paddle absorbs the incident
//! wave moving with `U_c = -(ω/F) η_I(0, t)`, the speed at which its own waves carry
//! `-η_I` away: in shallow water `ω/F → √(g/d)`, the classical `U = -√(g/d) η` of the
//! long-wave absorber. The residual's slow part (the still level's settling) is taken
//! out, and the slow part of `X_c` pulled back to the paddle's rest over
//! [`DRIFT_PERIODS`] periods, so that the paddle does not drift; slow parts are
//! followed by two first-order filters in turn, each over [`MEAN_PERIODS`] periods,
//! which pass `1/(ω T_m)²` = 0.3% of the waves at ω.
//!
//! The waves the correction makes reach the gauge after `x_g/c`, as they do in the
//! flume: the reading holds no echo of the correction that the law would feed back.
//! The law is exact for waves at ω; other frequencies are absorbed in part (a
//! broadband filter is not built). The correction is updated after every time step
//! from the gauge and extrapolated over the next with its slope, followed over
//! [`SLOPE_PERIODS`] of a period: the step-to-step slope itself, extrapolated, tripled
//! any alternation of the reading from one step to the next, and at d/Δx = 8 that loop
//! grew until the paddle shook at 5 g (docs/validation/wave_flume.md).

use super::paddle::WaveMaker;
use super::theory::{bound_second_harmonic, wavenumber};
use std::f64::consts::PI;

/// Periods over which each of the two filters that follow a slow part averages.
pub const MEAN_PERIODS: f64 = 3.0;
/// Periods over which the correction's slope follows the step-to-step one (a
/// first-order filter: at ω it lags by 17°, which moves the extrapolated velocity by
/// 0.3 ω Δt of its amplitude; of an alternation from one step to the next it passes
/// 1/(2π/(10 ω Δt) - 1), 5% at ω Δt = 0.03).
pub const SLOPE_PERIODS: f64 = 0.05;
/// Periods over which the correction is pulled back to the paddle's rest.
pub const DRIFT_PERIODS: f64 = 10.0;
/// The largest `k x_g` (rad) the gauge may sit at: `cos k x_g` ≥ 0.54.
pub const MAX_PHASE: f64 = 1.0;
/// Samples of the correction's velocity over the delay `x_g/c`.
pub const HISTORY: usize = 32;
/// The grid kept: the delay's samples and the two that bound it.
const KEPT: usize = HISTORY + 2;
/// Values in a restart file's record.
pub const RECORD: usize = 9 + KEPT;

/// The state a restart file keeps (see [`ActiveAbsorption::record`]).
pub type Record = [f64; RECORD];

/// One wave of the target elevation at the gauge: `a cos(k x_g - ωt - φ) + N sin(ωt + φ)`
/// (`N` the paddle's near field there, per the component's stroke).
#[derive(Debug, Clone, PartialEq)]
struct TargetWave {
    amplitude: f64,
    near: f64,
    k: f64,
    omega: f64,
    phase: f64,
}

/// The correction's state.
#[derive(Debug, Clone, PartialEq)]
struct Correction {
    /// The time of the last update \[s\].
    time: f64,
    /// `X_c` \[m\], `U_c` \[m/s\] and its followed slope \[m/s²\] then.
    x: f64,
    u: f64,
    slope: f64,
    /// The residual's slow part, after each filter (NaN before the first update), and
    /// `X_c`'s.
    mean: [f64; 2],
    x_mean: [f64; 2],
    /// How many grid samples of `U_c` have been taken (sample `n` at `n δ`).
    taken: usize,
    /// The last [`KEPT`] samples, sample `n` at `n % KEPT`.
    samples: [f64; KEPT],
}

/// A paddle's active absorption.
#[derive(Debug, Clone, PartialEq)]
pub struct ActiveAbsorption {
    /// The gauge's distance `x_g` in front of the paddle's face at rest \[m\].
    pub distance: f64,
    /// The design frequency ω \[rad/s\] (regular waves' own, a sea's peak).
    omega: f64,
    k: f64,
    /// `F` = H/S at ω.
    transfer: f64,
    target: Vec<TargetWave>,
    /// Regular waves' bound second harmonic at the gauge: `A₂ cos 2(k x_g - ωt)`.
    bound: f64,
    state: Correction,
}

impl ActiveAbsorption {
    /// The absorption of `maker`'s paddle with its gauge `distance` \[m\] in front of
    /// it, designed for angular frequency `omega` \[rad/s\] under gravity `g`.
    pub fn new(maker: &WaveMaker, omega: f64, distance: f64, g: f64) -> Self {
        let (paddle, depth) = (maker.paddle, maker.depth);
        let k = wavenumber(omega, depth, g);
        let target = (maker.components.iter())
            .map(|c| {
                let k = wavenumber(c.omega, depth, g);
                let stroke = c.amplitude / paddle.height_over_stroke(k, depth);
                TargetWave {
                    amplitude: c.amplitude,
                    near: stroke * paddle.near_field(c.omega, depth, g, distance),
                    k,
                    omega: c.omega,
                    phase: c.phase,
                }
            })
            .collect::<Vec<_>>();
        let bound = match target.as_slice() {
            [w] => bound_second_harmonic(2.0 * w.amplitude, w.k, depth),
            _ => 0.0,
        };
        Self {
            distance,
            omega,
            k,
            transfer: paddle.height_over_stroke(k, depth),
            target,
            bound,
            state: Correction {
                time: 0.0,
                x: 0.0,
                u: 0.0,
                slope: 0.0,
                mean: [f64::NAN; 2],
                x_mean: [0.0; 2],
                taken: 0,
                samples: [0.0; KEPT],
            },
        }
    }

    /// `k x_g` at the design frequency (refused above [`MAX_PHASE`]).
    pub fn phase(&self) -> f64 {
        self.k * self.distance
    }

    /// The delay `x_g/c` \[s\] of the waves the paddle makes to reach the gauge.
    fn delay(&self) -> f64 {
        self.phase() / self.omega
    }

    /// The target elevation at the gauge at `t`: the waves of the wave-making motion
    /// alone, with `s` the ramp's value (the bound harmonic takes `s²`).
    pub fn target(&self, t: f64, s: f64) -> f64 {
        let x = self.distance;
        let linear: f64 = (self.target.iter())
            .map(|w| {
                w.amplitude * (w.k * x - w.omega * t - w.phase).cos()
                    + w.near * (w.omega * t + w.phase).sin()
            })
            .sum();
        let bound = match self.target.as_slice() {
            [w] => self.bound * (2.0 * (w.k * x - w.omega * t)).cos(),
            _ => 0.0,
        };
        s * linear + s * s * bound
    }

    /// The correction `X_c` and its two derivatives at `t` (at or after the last
    /// update): the last velocity extrapolated with the followed slope.
    pub fn correction(&self, t: f64) -> [f64; 3] {
        let c = &self.state;
        let dt = t - c.time;
        [
            c.x + c.u * dt + 0.5 * c.slope * dt * dt,
            c.u + c.slope * dt,
            c.slope,
        ]
    }

    /// Samples `U_c` on the grid up to `t` (the velocity since the last update is
    /// linear) and gives `U_c(t - x_g/c)`, interpolated on the grid (0 before t = 0).
    fn delayed_velocity(&mut self, t: f64) -> f64 {
        let step = self.delay() / HISTORY as f64;
        while self.state.taken as f64 * step <= t {
            let n = self.state.taken;
            self.state.samples[n % KEPT] = self.correction(n as f64 * step)[1];
            self.state.taken += 1;
        }
        let back = (t - self.delay()) / step;
        if back < 0.0 {
            return 0.0;
        }
        let n = back.floor() as usize;
        let w = back - n as f64;
        let sample = |n: usize| self.state.samples[n % KEPT];
        (1.0 - w) * sample(n) + w * sample(n + 1)
    }

    /// Takes the gauge's reading `measured` \[m\] at `t` (the ramp at `s`) and sets the
    /// correction's velocity from it (see the module's law).
    pub fn update(&mut self, t: f64, measured: f64, s: f64) {
        let [x, _, _] = self.correction(t);
        let delayed = self.delayed_velocity(t);
        let c = &self.state;
        let dt = t - c.time;
        let period = 2.0 * PI / self.omega;
        let weight = (dt / (MEAN_PERIODS * period)).min(1.0);
        let follow = |[m1, m2]: [f64; 2], value: f64| {
            let m1 = m1 + (value - m1) * weight;
            [m1, m2 + (m1 - m2) * weight]
        };
        let x_mean = follow(c.x_mean, x);
        let made = self.transfer / self.omega * delayed;
        let residual = measured - self.target(t, s) - made;
        let mean = match c.mean[0].is_nan() {
            true => [residual; 2],
            false => follow(c.mean, residual),
        };
        let incident = (residual - mean[1]) / (2.0 * self.phase().cos());
        let pull = x_mean[1] / (DRIFT_PERIODS * period);
        let velocity = -self.omega / self.transfer * incident - pull;
        let slope = match dt > 0.0 {
            true => {
                let follow = (dt / (SLOPE_PERIODS * period)).min(1.0);
                c.slope + ((velocity - c.u) / dt - c.slope) * follow
            }
            false => c.slope,
        };
        self.state = Correction {
            time: t,
            x,
            u: velocity,
            slope,
            mean,
            x_mean,
            ..self.state
        };
    }

    /// The state for a restart file: the time of the last update, `X_c`, `U_c`, its
    /// slope, the two running means, the samples taken and the kept samples.
    pub fn record(&self) -> Record {
        let c = &self.state;
        let mut r = [0.0; RECORD];
        let [m1, m2] = c.mean;
        let [x1, x2] = c.x_mean;
        r[..9].copy_from_slice(&[c.time, c.x, c.u, c.slope, m1, m2, x1, x2, c.taken as f64]);
        r[9..].copy_from_slice(&c.samples);
        r
    }

    /// Restores what [`Self::record`] gave.
    pub fn restore(&mut self, r: &Record) {
        let mut samples = [0.0; KEPT];
        samples.copy_from_slice(&r[9..]);
        self.state = Correction {
            time: r[0],
            x: r[1],
            u: r[2],
            slope: r[3],
            mean: [r[4], r[5]],
            x_mean: [r[6], r[7]],
            taken: r[8] as usize,
            samples,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::super::spectrum::Component;
    use super::super::theory::Paddle;
    use super::*;

    const G: f64 = 9.81;

    fn maker(paddle: Paddle) -> WaveMaker {
        WaveMaker {
            paddle,
            depth: 0.5,
            components: vec![Component {
                amplitude: 0.02,
                omega: 2.0 * PI / 1.625,
                phase: 0.0,
            }],
            second_order: None,
        }
    }

    /// The law on linear theory's own waves: a gauge that reads the target plus an
    /// incident wave `η_I` and its fixed-wall reflection (the paddle at rest) makes the
    /// paddle move at `-(ω/F) η_I(0, t)`; one that reads the target alone leaves it at
    /// rest.
    #[test]
    fn the_paddle_moves_to_cancel_what_a_wall_would_reflect() {
        for paddle in [Paddle::Piston, Paddle::Flap { hinge: 0.1 }] {
            let m = maker(paddle);
            let omega = m.components[0].omega;
            let mut a = ActiveAbsorption::new(&m, omega, 0.15, G);
            let (k, xg, amp) = (a.k, a.distance, 0.005);
            // the first reading fixes the still level's offset
            let t = 3.3;
            a.update(t - 1e-9, a.target(t - 1e-9, 1.0) + 0.001, 1.0);
            let incident = |t: f64| amp * (k * xg + omega * t).cos();
            let reflected = |t: f64| amp * (-k * xg + omega * t).cos();
            let reading = 0.001 + a.target(t, 1.0) + incident(t) + reflected(t);
            a.update(t, reading, 1.0);
            let expected = -omega / a.transfer * amp * (omega * t).cos();
            let [_, u, _] = a.correction(t);
            assert!(
                (u - expected).abs() < 1e-3 * expected.abs(),
                "{u} {expected}"
            );
            let mut still = ActiveAbsorption::new(&m, omega, 0.15, G);
            for t in [0.0, 0.5, 1.0] {
                still.update(t, still.target(t, 0.7), 0.7);
            }
            assert!(still.correction(1.0)[1].abs() < 1e-15);
        }
    }

    /// In a flume that answers as linear theory does (the paddle's waves reach the
    /// gauge after `x_g/c`; a fixed wall mirrors the incident wave; at kd = 1 its near
    /// field at once, `E X_c` for the paddle's oscillation at ω and nothing for a slow
    /// drift), a wave train arriving at a paddle making waves of its own is absorbed:
    /// what leaves the paddle besides its own waves, `η_I(0, t) + (F/ω) U_c(t)`, falls
    /// below 5% of the incident wave (the near field left in the reading: measured 1.0%
    /// for the piston, 4.0% for the flap, whose `E/F` is 7%; 0.3% without it), at kd = 1
    /// with `k x_g` = 0.4 and at kd = π with `k x_g` = 0.93; a restart record continues
    /// the run bit for bit. (The deep-water paddle's near field, `E/F` = 22%, is left
    /// to the SPH flume: with it this model's loop grows, which the SPH flume's does not,
    /// `tests/physics/waves.rs`.)
    #[test]
    fn in_a_linear_flume_the_paddle_takes_the_incident_waves() {
        for (period, distance, near_field) in [(1.625, 0.2, true), (0.8, 0.1478, false)] {
            for paddle in [Paddle::Piston, Paddle::Flap { hinge: 0.1 }] {
                let k_r = linear_flume_reflection(paddle, period, distance, near_field);
                println!("{paddle:?}, T = {period} s: K_r = {k_r:.4}");
                assert!(k_r < 0.05, "{paddle:?}, T = {period} s: {k_r}");
            }
        }
    }

    /// The model flume's steps per period, and a quarter period of them.
    const STEPS_PER_PERIOD: usize = 300;
    const QUARTER: usize = STEPS_PER_PERIOD / 4;

    /// The reflection of [`in_a_linear_flume_the_paddle_takes_the_incident_waves`] for
    /// one paddle, period \[s\] and gauge distance \[m\] (depth 0.5 m), with or without the
    /// paddle's near field in the reading.
    fn linear_flume_reflection(
        paddle: Paddle,
        period: f64,
        distance: f64,
        near_field: bool,
    ) -> f64 {
        let mut m = maker(paddle);
        let omega = 2.0 * PI / period;
        m.components[0].omega = omega;
        let mut a = ActiveAbsorption::new(&m, omega, distance, G);
        let near = match near_field {
            true => paddle.near_field(omega, m.depth, G, distance),
            false => 0.0,
        };
        let (k, xg, f, amp) = (a.k, a.distance, a.transfer, 0.005);
        let c = omega / k;
        let envelope = |t: f64| {
            let tau = (t / (2.0 * period)).clamp(0.0, 1.0);
            tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau)
        };
        let incident = |x: f64, t: f64| amp * envelope(t + x / c) * (k * x + omega * t).cos();
        let dt = period / STEPS_PER_PERIOD as f64;
        let mut velocities: Vec<f64> = Vec::new();
        let (mut out, mut inc) = (0.0, 0.0);
        let mut copy: Option<ActiveAbsorption> = None;
        for n in 0..(20.0 * period / dt) as usize {
            let t = n as f64 * dt;
            let [_, u, _] = a.correction(t);
            velocities.push(u);
            // the near field E X at ω, read as E U(t - T/4)/ω: exact at ω, and nearly
            // nothing for a slow drift of the paddle, which makes no evanescent waves
            let oscillation = match n.checked_sub(QUARTER) {
                Some(j) => velocities[j] / omega,
                None => 0.0,
            };
            let back = (t - a.delay()) / dt;
            let delayed = match back < 0.0 {
                true => 0.0,
                false => {
                    let (j, w) = (back.floor() as usize, back.fract());
                    (1.0 - w) * velocities[j] + w * velocities[(j + 1).min(n)]
                }
            };
            let reading = a.target(t, 1.0)
                + incident(xg, t)
                + incident(-xg, t)
                + f / omega * delayed
                + near * oscillation;
            a.update(t, reading, 1.0);
            if let Some(b) = copy.as_mut() {
                b.update(t, reading, 1.0);
            }
            if t > 16.0 * period {
                let leaving = incident(0.0, t) + f / omega * a.correction(t)[1];
                out += leaving * leaving;
                inc += incident(0.0, t).powi(2);
            }
            if n == 1000 {
                let mut b = ActiveAbsorption::new(&m, omega, distance, G);
                b.restore(&a.record());
                copy = Some(b);
            }
        }
        assert_eq!(copy.map(|b| b.record()), Some(a.record()));
        (out / inc).sqrt()
    }
}
