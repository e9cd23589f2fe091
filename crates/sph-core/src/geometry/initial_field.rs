//! Analytic initial fields laid over the fluid blocks: the Taylor-Green vortex, the
//! elliptic drop, the rotating square patch and the linear standing wave, and the
//! check that a field fits the fluid it fills. Fields from expressions are in
//! `super::expressions`.

use crate::case::{Case, InitialField};
use crate::error::{Result, SphError};
use crate::particles::{Kind, Particles, Vector};
use std::f64::consts::PI;

/// Velocity and pressure of an analytic initial field at `x` (2D fields); `hydrostatic`
/// is the block's own pressure there, kept by fields that do not set one, and `g` the
/// magnitude of gravity.
pub(super) fn value<const D: usize>(
    field: &InitialField,
    x: &Vector<D>,
    rho0: f64,
    g: f64,
    hydrostatic: f64,
) -> (Vector<D>, f64) {
    let mut u = Vector::<D>::zeros();
    let p = match *field {
        InitialField::TaylorGreen {
            amplitude,
            wavelength,
        } => {
            let kx = 2.0 * PI / wavelength;
            let (a, b) = (kx * x[0], kx * x[1]);
            u[0] = -amplitude * a.cos() * b.sin();
            u[1] = amplitude * a.sin() * b.cos();
            -rho0 * amplitude * amplitude / 4.0 * ((2.0 * a).cos() + (2.0 * b).cos())
        }
        InitialField::EllipticDrop {
            strain_rate,
            radius,
        } => {
            u[0] = -strain_rate * x[0];
            u[1] = strain_rate * x[1];
            0.5 * rho0 * strain_rate.powi(2) * (radius.powi(2) - x.norm_squared())
        }
        InitialField::RotatingSquare {
            angular_velocity,
            side,
        } => {
            u[0] = angular_velocity * x[1];
            u[1] = -angular_velocity * x[0];
            rho0 * angular_velocity.powi(2) * rotating_square_pressure(x[0], x[1], side)
        }
        InitialField::StandingWave {
            amplitude,
            length,
            depth,
        } => {
            let k = PI / length;
            // u = ∇φ at t = 0: B k (-cosh ky sin kx, sinh ky cos kx)
            let bk = amplitude * standing_wave_frequency(length, depth, g) / (k * depth).sinh();
            u[0] = -bk * (k * x[1]).cosh() * (k * x[0]).sin();
            u[1] = bk * (k * x[1]).sinh() * (k * x[0]).cos();
            hydrostatic
        }
        // evaluated by [`super::expressions`], which the build asks first
        InitialField::Expressions { .. } => hydrostatic,
    };
    (u, p)
}

/// Angular frequency of the first sloshing mode by linear theory, `ω² = g k tanh kd`
/// with `k = π/L` (Lamb 1932, §257).
pub fn standing_wave_frequency(length: f64, depth: f64, g: f64) -> f64 {
    let k = PI / length;
    (g * k * (k * depth).tanh()).sqrt()
}

/// Initial pressure of the rotating square patch over `ρ0 ω²`: the solution of
/// `∇²p = 2` on the square of side L centred at the origin with p = 0 on its edges,
/// `Σ_{m,n odd} -32 / (m n π² [(mπ/L)² + (nπ/L)²]) sin(mπx*/L) sin(nπy*/L)`,
/// `x* = x + L/2` (docs/validation/data/README.md; the terms fall as 1/(m n (m² + n²))).
pub fn rotating_square_pressure(x: f64, y: f64, side: f64) -> f64 {
    const TERMS: usize = 60;
    let (xs, ys) = ((x + 0.5 * side) / side, (y + 0.5 * side) / side);
    let mut p = 0.0;
    for m in (1..2 * TERMS).step_by(2) {
        let (mf, sx) = (m as f64, (m as f64 * PI * xs).sin());
        for n in (1..2 * TERMS).step_by(2) {
            let nf = n as f64;
            let k2 = (mf * PI / side).powi(2) + (nf * PI / side).powi(2);
            p -= 32.0 / (mf * nf * PI * PI * k2) * sx * (nf * PI * ys).sin();
        }
    }
    p
}

/// An analytic initial field must fit the fluid it is laid over: the elliptic drop and
/// the rotating square take their pressure from the radius and side they are given
/// (zero on the free surface), the standing wave its mode from the tank it fills, and
/// the Taylor-Green field must be periodic with the domain. A mismatch gives negative
/// pressure outside a smaller disc, a jump, or flow through the walls.
pub(super) fn check<const D: usize>(case: &Case, particles: &Particles<D>) -> Result<()> {
    let dx = case.dx();
    let fluid = || {
        (0..particles.len())
            .filter(|&i| particles.kind[i] == Kind::Fluid)
            .map(|i| particles.x[i])
    };
    let fits = |extent: f64, size: f64| extent <= size + 1e-9 * size && extent >= size - dx;
    match case.initial {
        Some(InitialField::EllipticDrop { radius, .. }) => {
            let extent = fluid().map(|x| x.norm()).fold(0.0, f64::max);
            if !fits(extent, radius) {
                return Err(field_mismatch("initial.radius", radius, "radius", extent));
            }
        }
        Some(InitialField::RotatingSquare { side, .. }) => {
            let extent = 2.0 * (fluid().map(|x| x.amax()).fold(0.0, f64::max) + 0.5 * dx);
            if !fits(extent, side) {
                return Err(field_mismatch("initial.side", side, "side", extent));
            }
        }
        Some(InitialField::StandingWave { length, depth, .. }) => {
            let span = |d: usize| {
                let (lo, hi) = fluid().fold((f64::MAX, f64::MIN), |(lo, hi), x| {
                    (lo.min(x[d] - 0.5 * dx), hi.max(x[d] + 0.5 * dx))
                });
                (lo.abs() < 1e-9 * length).then_some(hi)
            };
            let close =
                |got: Option<f64>, want: f64| got.is_some_and(|h| (h - want).abs() <= 1e-6 * want);
            if !close(span(0), length) {
                return Err(field_mismatch_box("initial.length", length, "x", span(0)));
            }
            if !close(span(1), depth) {
                return Err(field_mismatch_box("initial.depth", depth, "y", span(1)));
            }
        }
        Some(InitialField::TaylorGreen { wavelength, .. }) => {
            let periods: Vec<f64> = match &case.domain {
                Some(dom) if (0..D).all(|d| dom.is_periodic(d)) => {
                    (0..D).map(|d| dom.hi[d] - dom.lo[d]).collect()
                }
                _ => Vec::new(),
            };
            let whole = |p: &f64| {
                let k = p / wavelength;
                k.round() >= 1.0 && (k - k.round()).abs() < 1e-6
            };
            if periods.is_empty() || !periods.iter().all(whole) {
                return Err(SphError::invalid(
                    "initial.wavelength",
                    wavelength,
                    format!(
                        "a wavelength that divides the periodic box (domain.lo, domain.hi \
                         periodic along every axis; periods {periods:?})"
                    ),
                ));
            }
        }
        // checked value by value as they are evaluated
        Some(InitialField::Expressions { .. }) | None => {}
    }
    Ok(())
}

fn field_mismatch(key: &str, value: f64, what: &str, extent: f64) -> SphError {
    SphError::invalid(
        key,
        value,
        format!(
            "the {what} of the fluid the field fills, centred at the origin (the fluid_block \
             particles span a {what} of {extent:.6} m)"
        ),
    )
}

fn field_mismatch_box(key: &str, value: f64, axis: &str, hi: Option<f64>) -> SphError {
    let span = hi.map_or("does not start at 0".to_string(), |h| {
        format!("spans 0 to {h:.6} m")
    });
    SphError::invalid(
        key,
        value,
        format!("the extent along {axis} of the fluid the field fills, from 0 (the fluid {span})"),
    )
}
