//! A wave maker's motion from the waves it is to make.
//!
//! The paddle's displacement at the still-water level is a sum of sines,
//! `X(t) = Σ X_n sin(ω_n t + φ_n)`, component `n` of wave amplitude `a_n` moving the
//! paddle by `X_n = a_n / (H/S)(k_n)` (Biesel's transfer, [`Paddle::height_over_stroke`]),
//! which makes `η_n = a_n cos(k_n x - ω_n t - φ_n)` far from the paddle. A regular
//! wave of second order adds Madsen's `X₂ sin 2ωt` to the piston's motion. A piston
//! moves by `X`; a flap whose surface crossing is `a = d - l` above its hinge turns by
//! `atan(X/a)` (clockwise about z in 2D, about y in 3D: toward +x at the top).

use super::spectrum::Component;
use super::theory::{madsen_second_order_stroke, wavenumber, Paddle};

/// The waves a wave maker is to make, in depth `depth` \[m\].
#[derive(Debug, Clone, PartialEq)]
pub struct WaveMaker {
    pub paddle: Paddle,
    pub depth: f64,
    /// The linear components (one for regular waves).
    pub components: Vec<Component>,
    /// Regular waves of second order: their height \[m\] (a piston adds Madsen's term).
    pub second_order: Option<f64>,
}

/// A wave maker's motion: the displacement at the still level as a sum of sines, and
/// for a flap the arm that turns it into an angle.
#[derive(Debug, Clone, PartialEq)]
pub struct PaddleSignal {
    /// `(X_n, ω_n, φ_n)`.
    sines: Vec<(f64, f64, f64)>,
    /// A flap's `a = d - l` and the sign of its angle (2D -1, 3D +1); `None`: a piston.
    flap: Option<(f64, f64)>,
}

impl PaddleSignal {
    /// The motion of `maker` under gravity `g` \[m/s²\] in dimension `dimension`.
    pub fn new(maker: &WaveMaker, g: f64, dimension: usize) -> Self {
        let (paddle, depth) = (maker.paddle, maker.depth);
        let stroke = |c: &Component| {
            let k = wavenumber(c.omega, depth, g);
            let x = c.amplitude / paddle.height_over_stroke(k, depth);
            (x, c.omega, c.phase)
        };
        let mut sines: Vec<(f64, f64, f64)> = maker.components.iter().map(stroke).collect();
        if let (Some(height), Paddle::Piston, [(_, omega, _)]) =
            (maker.second_order, paddle, sines.as_slice())
        {
            let k = wavenumber(*omega, depth, g);
            let x2 = madsen_second_order_stroke(height, k, depth);
            sines.push((x2, 2.0 * omega, 0.0));
        }
        let flap = match paddle {
            Paddle::Piston => None,
            Paddle::Flap { hinge } => {
                Some((depth - hinge, if dimension == 2 { -1.0 } else { 1.0 }))
            }
        };
        Self { sines, flap }
    }

    /// A signal that stays zero (the axes a flap does not turn about).
    pub fn zero() -> Self {
        Self {
            sines: Vec::new(),
            flap: None,
        }
    }

    /// Whether the paddle turns (a flap) rather than translates.
    pub fn turns(&self) -> bool {
        self.flap.is_some()
    }

    /// The displacement at the still level and its two time derivatives at `t`.
    pub fn stroke_at(&self, t: f64) -> [f64; 3] {
        self.sines
            .iter()
            .fold([0.0; 3], |[x, v, a], &(amp, w, phi)| {
                let (s, c) = (w * t + phi).sin_cos();
                [x + amp * s, v + amp * w * c, a - amp * w * w * s]
            })
    }

    /// The paddle's coordinate (a piston's displacement, a flap's angle) and its two
    /// time derivatives from the displacement at the still level and its derivatives
    /// `[x, v, a]`: for a flap, `θ = ±atan u`, `u = X/a`, `θ' = ±u'/(1 + u²)`,
    /// `θ'' = ±(u''/(1 + u²) - 2u u'²/(1 + u²)²)`.
    pub fn coordinate(&self, [x, v, a]: [f64; 3]) -> [f64; 3] {
        let Some((arm, sign)) = self.flap else {
            return [x, v, a];
        };
        let (u, u1, u2) = (x / arm, v / arm, a / arm);
        let q = 1.0 / (1.0 + u * u);
        [
            sign * u.atan(),
            sign * u1 * q,
            sign * (u2 * q - 2.0 * u * u1 * u1 * q * q),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::super::spectrum::Jonswap;

    impl PaddleSignal {
        fn coordinate_at(&self, t: f64) -> [f64; 3] {
            self.coordinate(self.stroke_at(t))
        }
    }
    use super::super::theory::frequency;
    use super::*;
    use std::f64::consts::PI;

    const G: f64 = 9.81;

    fn regular(paddle: Paddle, height: f64, omega: f64, second_order: bool) -> WaveMaker {
        WaveMaker {
            paddle,
            depth: 0.5,
            components: vec![Component {
                amplitude: 0.5 * height,
                omega,
                phase: 0.0,
            }],
            second_order: second_order.then_some(height),
        }
    }

    /// A first-order piston's stroke is `H/(H/S)`, its motion `S/2 sin ωt`; a flap's
    /// angle moves its surface crossing by the same law, and the derivatives of both
    /// match central differences of the values.
    #[test]
    fn regular_paddle_motions_follow_biesel() {
        let omega = 2.0 * PI / 1.6;
        let signal = PaddleSignal::new(&regular(Paddle::Piston, 0.02, omega, false), G, 2);
        let k = wavenumber(omega, 0.5, G);
        let s = 0.02 / Paddle::Piston.height_over_stroke(k, 0.5);
        let t = 0.3;
        assert!((signal.coordinate_at(t)[0] - 0.5 * s * (omega * t).sin()).abs() < 1e-15);
        let (flap, k) = (Paddle::Flap { hinge: 0.1 }, 2.0 * PI / 3.0);
        let omega = frequency(k, 0.5, G);
        let f = PaddleSignal::new(&regular(flap, 0.02, omega, false), G, 2);
        let stroke = 0.02 / flap.height_over_stroke(k, 0.5);
        let theta = f.coordinate_at(0.7)[0];
        assert!(((-theta).tan() * 0.4 - 0.5 * stroke * (omega * 0.7).sin()).abs() < 1e-15);
        let f3 = PaddleSignal::new(&regular(flap, 0.02, omega, false), G, 3);
        assert!((f3.coordinate_at(0.7)[0] + theta).abs() < 1e-15);
        for sig in [&signal, &f, &f3] {
            let e = 1e-5;
            let (lo, mid, hi) = (
                sig.coordinate_at(t - e),
                sig.coordinate_at(t),
                sig.coordinate_at(t + e),
            );
            assert!(((hi[0] - lo[0]) / (2.0 * e) - mid[1]).abs() < 1e-8);
            assert!(((hi[1] - lo[1]) / (2.0 * e) - mid[2]).abs() < 1e-7);
        }
    }

    /// A second-order piston adds Madsen's term at 2ω (a flap does not); an irregular
    /// sea's paddle moves each component by its own transfer.
    #[test]
    fn second_order_and_irregular_signals_add_their_components() {
        let omega = 2.0 * PI / 1.6;
        let two = PaddleSignal::new(&regular(Paddle::Piston, 0.02, omega, true), G, 2);
        let one = PaddleSignal::new(&regular(Paddle::Piston, 0.02, omega, false), G, 2);
        let k = wavenumber(omega, 0.5, G);
        let x2 = madsen_second_order_stroke(0.02, k, 0.5);
        let t = 0.37;
        assert!(
            (two.coordinate_at(t)[0] - one.coordinate_at(t)[0] - x2 * (2.0 * omega * t).sin())
                .abs()
                < 1e-15
        );
        let sea = Jonswap {
            significant_height: 0.05,
            peak_period: 1.5,
            gamma: 3.3,
        };
        let components = sea.components(50, 0.3, 1.7, 1);
        let maker = WaveMaker {
            paddle: Paddle::Piston,
            depth: 0.5,
            components: components.clone(),
            second_order: None,
        };
        let s = PaddleSignal::new(&maker, G, 2);
        let expected: f64 = (components.iter())
            .map(|c| {
                let k = wavenumber(c.omega, 0.5, G);
                let x = c.amplitude / Paddle::Piston.height_over_stroke(k, 0.5);
                x * (c.omega * t + c.phase).sin()
            })
            .sum();
        assert!((s.coordinate_at(t)[0] - expected).abs() < 1e-14);
    }
}
