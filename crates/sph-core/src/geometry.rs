//! Builds the initial particle set of a case: fluid blocks on a lattice, tank and
//! wall boxes as layers of fixed dummy particles, the initial density (hydrostatic
//! or from an analytic field), masses `m_i = ρ_i V0`, the sound speed and the domain.
//!
//! What only the built particles can tell is checked here: fluid inside walls or in
//! two blocks at once, an initial field that does not fit the fluid it fills, probes
//! that no fluid can reach, particles outside the domain.

use crate::case::{BoxConfig, Case, InitialField, Shape};
use crate::domain::Domain;
use crate::eos::LinearEos;
use crate::error::{Result, SphError};
use crate::particles::{Kind, Particles, Vector};
use std::collections::HashMap;
use std::f64::consts::PI;

/// Everything the case fixes before the first step.
pub struct Setup<const D: usize> {
    pub particles: Particles<D>,
    pub domain: Domain<D>,
    pub eos: LinearEos,
    pub gravity: Vector<D>,
}

fn vector<const D: usize>(v: &[f64]) -> Vector<D> {
    Vector::from_fn(|d, _| v[d])
}

/// Lattice points `lo + (k + ½)Δx` filling `[lo, hi]`, with the count per axis rounded.
fn lattice<const D: usize>(lo: &Vector<D>, hi: &Vector<D>, dx: f64) -> Vec<Vector<D>> {
    let n: Vec<usize> = (0..D)
        .map(|d| ((hi[d] - lo[d]) / dx).round().max(0.0) as usize)
        .collect();
    let total: usize = n.iter().product();
    (0..total)
        .map(|mut k| {
            let mut x = *lo;
            for d in 0..D {
                x[d] += ((k % n[d]) as f64 + 0.5) * dx;
                k /= n[d];
            }
            x
        })
        .collect()
}

/// Builds particles, domain, EOS and gravity for a validated case of dimension `D`.
pub fn build<const D: usize>(case: &Case) -> Result<Setup<D>> {
    if case.dimension != D {
        return Err(SphError::invalid(
            "dimension",
            case.dimension,
            format!("{D} (the dimension of the solver this case was given to)"),
        ));
    }
    let dx = case.dx();
    let gravity: Vector<D> = vector(&case.gravity());
    let rho0 = case.fluid.density;
    let volume = dx.powi(D as i32);

    let mut fluid: Vec<(Vector<D>, Vector<D>, usize)> = Vec::new();
    for (k, b) in case.fluid_block.iter().enumerate() {
        let points = block_points::<D>(b, dx);
        if points.is_empty() {
            return Err(SphError::invalid(
                format!("fluid_block[{k}]"),
                format!("lo = {:?}, hi = {:?}", b.lo, b.hi),
                format!("a box at least one spacing ({dx} m) wide along every axis"),
            ));
        }
        let u: Vector<D> = b
            .velocity
            .as_deref()
            .map(vector)
            .unwrap_or_else(Vector::zeros);
        fluid.extend(points.into_iter().map(|x| (x, u, k)));
    }

    let eos = LinearEos {
        rho0,
        c0: sound_speed(case, &fluid, &gravity, dx)?,
        background: case.fluid.background_pressure,
    };
    let mut particles = Particles::default();
    for &(x, mut u, k) in &fluid {
        let b = &case.fluid_block[k];
        let mut p = 0.0;
        if b.hydrostatic.unwrap_or(true) {
            // p = ρ0 (s_top - s(x)), s(x) = -g·x the height times |g|
            let top = corners(&vector(&b.lo), &vector(&b.hi))
                .iter()
                .map(|c| -gravity.dot(c))
                .fold(f64::MIN, f64::max);
            p = rho0 * (top + gravity.dot(&x));
        }
        match case.initial {
            Some(InitialField::TaylorGreen {
                amplitude,
                wavelength,
            }) => {
                let kx = 2.0 * PI / wavelength;
                let (a, b2) = (kx * x[0], kx * x[1]);
                u[0] = -amplitude * a.cos() * b2.sin();
                u[1] = amplitude * a.sin() * b2.cos();
                p = -rho0 * amplitude * amplitude / 4.0 * ((2.0 * a).cos() + (2.0 * b2).cos());
            }
            Some(InitialField::EllipticDrop {
                strain_rate,
                radius,
            }) => {
                u[0] = -strain_rate * x[0];
                u[1] = strain_rate * x[1];
                p = 0.5 * rho0 * strain_rate.powi(2) * (radius.powi(2) - x.norm_squared());
            }
            Some(InitialField::RotatingSquare {
                angular_velocity,
                side,
            }) => {
                u[0] = angular_velocity * x[1];
                u[1] = -angular_velocity * x[0];
                p = rho0 * angular_velocity.powi(2) * rotating_square_pressure(x[0], x[1], side);
            }
            None => {}
        }
        let rho = eos.density(p + eos.background);
        particles.push(Kind::Fluid, x, u, rho, rho * volume);
    }

    for (x, u) in wall_points::<D>(case) {
        particles.push(Kind::Wall, x, u, rho0, rho0 * volume);
    }
    check_overlap(&particles, dx)?;
    check_initial_field(case, &particles)?;
    let domain = domain_of(case, &particles)?;
    check_probes(case, &domain)?;
    Ok(Setup {
        particles,
        domain,
        eos,
        gravity,
    })
}

/// Initial pressure of the rotating square patch over `ρ0 ω²`: the solution of
/// `∇²p = 2` on the square of side L centred at the origin with p = 0 on its edges,
/// `Σ_{m,n odd} -32 / (m n π² [(mπ/L)² + (nπ/L)²]) sin(mπx*/L) sin(nπy*/L)`,
/// `x* = x + L/2` (refdata README §5; the terms fall as 1/(m n (m² + n²))).
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

/// The lattice points of a fluid block: the whole box, or those inside the inscribed
/// ellipse (ellipsoid).
fn block_points<const D: usize>(b: &BoxConfig, dx: f64) -> Vec<Vector<D>> {
    let (lo, hi): (Vector<D>, Vector<D>) = (vector(&b.lo), vector(&b.hi));
    let mut points = lattice(&lo, &hi, dx);
    if b.shape == Some(Shape::Ellipsoid) {
        let (centre, half) = ((lo + hi) / 2.0, (hi - lo) / 2.0);
        points.retain(|x| (x - centre).component_div(&half).norm_squared() < 1.0);
    }
    points
}

fn corners<const D: usize>(lo: &Vector<D>, hi: &Vector<D>) -> Vec<Vector<D>> {
    (0..1usize << D)
        .map(|m| Vector::from_fn(|d, _| if m >> d & 1 == 1 { hi[d] } else { lo[d] }))
        .collect()
}

/// c0 given, or `factor · max(U, sqrt(Δp/ρ0))` with H the fluid height along gravity,
/// `U = max(|u0|, sqrt(2|g|H))` unless set, `Δp = ρ0|g|H`.
fn sound_speed<const D: usize>(
    case: &Case,
    fluid: &[(Vector<D>, Vector<D>, usize)],
    gravity: &Vector<D>,
    dx: f64,
) -> Result<f64> {
    if let Some(c0) = case.fluid.sound_speed {
        return Ok(c0);
    }
    let g = gravity.norm();
    let height = if g > 0.0 {
        let s: Vec<f64> = fluid.iter().map(|(x, _, _)| -gravity.dot(x) / g).collect();
        s.iter().cloned().fold(f64::MIN, f64::max) - s.iter().cloned().fold(f64::MAX, f64::min) + dx
    } else {
        0.0
    };
    let mut u0 = fluid.iter().map(|(_, u, _)| u.norm()).fold(0.0, f64::max);
    if let Some(InitialField::TaylorGreen { amplitude, .. }) = &case.initial {
        u0 = u0.max(amplitude.abs());
    }
    let u_max = case
        .fluid
        .max_velocity
        .unwrap_or(u0.max((2.0 * g * height).sqrt()));
    let rho0 = case.fluid.density;
    let c0 = LinearEos::sound_speed_rule(
        case.fluid.sound_speed_factor,
        u_max,
        rho0 * g * height,
        rho0,
    );
    if c0 > 0.0 {
        Ok(c0)
    } else {
        Err(SphError::invalid(
            "fluid.sound_speed",
            "(missing)",
            "a sound speed: with no gravity and no initial velocity it cannot be derived",
        ))
    }
}

/// Wall particles with their (fixed or sliding-lid) velocities.
fn wall_points<const D: usize>(case: &Case) -> Vec<(Vector<D>, Vector<D>)> {
    let dx = case.dx();
    let mut points = Vec::new();
    for t in &case.tank {
        let (lo, hi): (Vector<D>, Vector<D>) = (vector(&t.lo), vector(&t.hi));
        let pad = Vector::<D>::repeat(t.layer_count(case) as f64 * dx);
        let open = t.open_faces(D);
        let lid: Vector<D> = t
            .lid_velocity
            .as_deref()
            .map(vector)
            .unwrap_or_else(Vector::zeros);
        points.extend(
            lattice(&(lo - pad), &(hi + pad), dx)
                .into_iter()
                .filter(|x| {
                    let outside = (0..D).any(|d| x[d] < lo[d] || x[d] > hi[d]);
                    let beyond_open =
                        open.iter()
                            .any(|&(d, s)| if s > 0 { x[d] > hi[d] } else { x[d] < lo[d] });
                    outside && !beyond_open
                })
                .map(|x| {
                    let above = x[D - 1] > hi[D - 1];
                    (x, if above { lid } else { Vector::zeros() })
                }),
        );
    }
    for b in &case.wall {
        let box_points = lattice(&vector(&b.lo), &vector(&b.hi), dx);
        points.extend(box_points.into_iter().map(|x| (x, Vector::zeros())));
    }
    points
}

/// No fluid particle may sit closer than Δx/2 to another particle: a fluid particle
/// in a wall, or fluid blocks that overlap (doubled particles), is an input error.
fn check_overlap<const D: usize>(particles: &Particles<D>, dx: f64) -> Result<()> {
    let cell = |x: &Vector<D>| -> [i64; D] { std::array::from_fn(|d| (x[d] / dx).floor() as i64) };
    let mut cells: HashMap<[i64; D], Vec<usize>> = HashMap::new();
    for i in 0..particles.len() {
        cells.entry(cell(&particles.x[i])).or_default().push(i);
    }
    let min = 0.5 * dx * (1.0 - 1e-6);
    for i in (0..particles.len()).filter(|&i| particles.kind[i] == Kind::Fluid) {
        let c = cell(&particles.x[i]);
        for m in 0..3usize.pow(D as u32) {
            let mut key = c;
            let mut rem = m;
            for k in key.iter_mut() {
                *k += (rem % 3) as i64 - 1;
                rem /= 3;
            }
            for &j in cells.get(&key).into_iter().flatten() {
                let r = (particles.x[i] - particles.x[j]).norm();
                if j != i && r < min {
                    return Err(overlap_error(particles, i, j, r));
                }
            }
        }
    }
    Ok(())
}

fn overlap_error<const D: usize>(p: &Particles<D>, i: usize, j: usize, r: f64) -> SphError {
    let (other, what) = match p.kind[j] {
        Kind::Wall => ("wall particle", "fluid clear of walls"),
        Kind::Fluid => ("fluid particle", "fluid blocks that do not overlap"),
    };
    SphError::invalid(
        "fluid_block",
        format!("a fluid particle at {:?}", p.x[i].as_slice()),
        format!(
            "{what} (it lies {r:.3e} m from the {other} at {:?}; keep at least Δx/2)",
            p.x[j].as_slice()
        ),
    )
}

/// The domain of the case: its `[domain]` box, or the particles' bounding box widened
/// on every side by half its extent along that axis (at least 10Δx), so that fluid
/// leaving the initial geometry (off an open tank, or splashing high) is removed well
/// away from it. Every particle must start inside the box.
fn domain_of<const D: usize>(case: &Case, particles: &Particles<D>) -> Result<Domain<D>> {
    let Some(dom) = &case.domain else {
        let (mut lo, mut hi) = (Vector::<D>::repeat(f64::MAX), Vector::<D>::repeat(f64::MIN));
        for x in &particles.x {
            lo = lo.inf(x);
            hi = hi.sup(x);
        }
        let pad = ((hi - lo) * 0.5).map(|p| p.max(10.0 * case.dx()));
        return Ok(Domain::new(lo - pad, hi + pad, [false; D]));
    };
    let periodic: [bool; D] = std::array::from_fn(|d| dom.is_periodic(d));
    let (lo, hi): (Vector<D>, Vector<D>) = (vector(&dom.lo), vector(&dom.hi));
    let support = case.support();
    for d in (0..D).filter(|&d| periodic[d]) {
        let period = hi[d] - lo[d];
        if period < 3.3 * support {
            return Err(SphError::invalid(
                "domain.hi",
                format!("{:?}", dom.hi),
                format!(
                    "a periodic length of at least 3.3 kernel supports ({:.4} m)",
                    3.3 * support
                ),
            ));
        }
    }
    let outside = |x: &Vector<D>| (0..D).any(|d| x[d] < lo[d] || x[d] > hi[d]);
    if let Some(k) = particles.x.iter().position(outside) {
        return Err(SphError::invalid(
            "domain",
            format!("lo = {:?}, hi = {:?}", dom.lo, dom.hi),
            format!(
                "a box holding every particle (a {:?} particle lies at {:?})",
                particles.kind[k],
                particles.x[k].as_slice()
            ),
        ));
    }
    Ok(Domain::new(lo, hi, periodic))
}

/// An analytic initial field must fit the fluid it is laid over: the elliptic drop and
/// the rotating square take their pressure from the radius and side they are given
/// (zero on the free surface), and the Taylor-Green field must be periodic with the
/// domain. A mismatch gives negative pressure outside a smaller disc, or a jump.
fn check_initial_field<const D: usize>(case: &Case, particles: &Particles<D>) -> Result<()> {
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
        None => {}
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

/// A probe must lie where fluid can be: inside the domain along its open directions and
/// not deeper than the kernel support inside a wall, or it can never read a pressure.
fn check_probes<const D: usize>(case: &Case, domain: &Domain<D>) -> Result<()> {
    let support = case.support();
    for (k, probe) in case.diagnostics.probes.iter().enumerate() {
        let x: Vector<D> = vector(probe);
        let reason = if domain.escaped(&x) {
            Some(format!(
                "a point inside the domain lo = {:?}, hi = {:?} (domain.lo, domain.hi; without \
                 [domain], the particles' bounding box widened by half its size)",
                domain.lo.as_slice(),
                domain.hi.as_slice()
            ))
        } else {
            buried_in_wall(case, &x, support).map(|wall| {
                format!("a point fluid can reach, not deeper than the kernel support inside {wall}")
            })
        };
        if let Some(expected) = reason {
            return Err(SphError::invalid(
                format!("diagnostics.probes[{k}]"),
                format!("{probe:?}"),
                expected,
            ));
        }
    }
    Ok(())
}

/// The wall (`tank[k]` or `wall[k]`) inside which `x` lies deeper than `depth`.
fn buried_in_wall<const D: usize>(case: &Case, x: &Vector<D>, depth: f64) -> Option<String> {
    let inside = |lo: &Vector<D>, hi: &Vector<D>| (0..D).all(|d| x[d] > lo[d] && x[d] < hi[d]);
    for (k, t) in case.tank.iter().enumerate() {
        let (lo, hi): (Vector<D>, Vector<D>) = (vector(&t.lo), vector(&t.hi));
        let pad = Vector::<D>::repeat(t.layer_count(case) as f64 * case.dx());
        let open = t.open_faces(D);
        let beyond_closed_face = (0..D).any(|d| {
            (x[d] < lo[d] - depth && !open.contains(&(d, -1)))
                || (x[d] > hi[d] + depth && !open.contains(&(d, 1)))
        });
        if inside(&(lo - pad), &(hi + pad)) && beyond_closed_face {
            return Some(format!("tank[{k}]"));
        }
    }
    for (k, b) in case.wall.iter().enumerate() {
        let (lo, hi): (Vector<D>, Vector<D>) = (vector(&b.lo), vector(&b.hi));
        let margin = Vector::<D>::repeat(depth);
        if inside(&(lo + margin), &(hi - margin)) {
            return Some(format!("wall[{k}]"));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    const TANK: &str = r#"
        dimension = 2
        [particles]
        spacing = 0.05
        [fluid]
        density = 1000.0
        gravity = [0.0, -9.81]
        [[fluid_block]]
        lo = [0.0, 0.0]
        hi = [1.2, 0.6]
        [[tank]]
        lo = [0.0, 0.0]
        hi = [3.2196, 1.8]
        [time]
        end = 0.1
    "#;

    fn build_error(text: &str) -> String {
        let case = Case::from_toml_str(text).unwrap();
        match build::<2>(&case) {
            Ok(_) => panic!("built: {text}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn probes_no_fluid_can_reach_are_refused() {
        let with_probe =
            |p: &str| format!("{TANK}\n[diagnostics]\nprobes = [[3.2196, 0.16], {p}]\n");
        let e = build_error(&with_probe("[5.0, 5.0]"));
        assert!(
            e.starts_with("diagnostics.probes[1] = [5.0, 5.0]: expected a point inside the domain"),
            "{e}"
        );
        // in the bottom wall, deeper than the kernel support R = 0.133 m: 3 layers of 0.05 m
        let e = build_error(&with_probe("[1.0, -0.14]"));
        assert!(
            e.contains("not deeper than the kernel support inside tank[0]"),
            "{e}"
        );
        // on the wall's face (the P1 probe), in the fluid, and over the open top: fine
        let case = Case::from_toml_str(&with_probe("[1.0, 2.0]")).unwrap();
        assert!(build::<2>(&case).is_ok());
    }

    #[test]
    fn initial_fields_must_fit_the_fluid_they_fill() {
        let drop = |radius: f64| {
            format!(
                "dimension = 2\n[particles]\nspacing = 0.04\n[fluid]\ndensity = 1000.0\n\
                 sound_speed = 1400.0\n[[fluid_block]]\nlo = [-1.0, -1.0]\nhi = [1.0, 1.0]\n\
                 shape = \"ellipsoid\"\n[initial]\ntype = \"elliptic_drop\"\nstrain_rate = 100.0\n\
                 radius = {radius:?}\n[time]\nend = 0.01\n"
            )
        };
        assert!(build::<2>(&Case::from_toml_str(&drop(1.0)).unwrap()).is_ok());
        let e = build_error(&drop(0.5));
        assert!(
            e.starts_with("initial.radius = 0.5: expected the radius of the fluid the field fills"),
            "{e}"
        );
        let square =
            TANK.replace(
                "lo = [0.0, 0.0]\n        hi = [1.2, 0.6]",
                "lo = [-0.5, -0.5]\n        hi = [0.5, 0.5]",
            )
            .replace("gravity = [0.0, -9.81]", "sound_speed = 10.0")
            .replace(
                "[[tank]]\n        lo = [0.0, 0.0]\n        hi = [3.2196, 1.8]",
                "",
            ) + "[initial]\ntype = \"rotating_square\"\nangular_velocity = 1.0\nside = 2.0\n";
        let e = build_error(&square);
        assert!(
            e.starts_with("initial.side = 2: expected the side of the fluid"),
            "{e}"
        );
        assert!(build::<2>(
            &Case::from_toml_str(&square.replace("side = 2.0", "side = 1.0")).unwrap()
        )
        .is_ok());
    }

    #[test]
    fn the_taylor_green_field_must_be_periodic_with_the_domain() {
        let tg = |wavelength: f64| {
            format!(
                "dimension = 2\n[particles]\nspacing = 0.05\n[fluid]\ndensity = 1.0\nsound_speed = 10.0\n\
                 [[fluid_block]]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\nhydrostatic = false\n\
                 [domain]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\nperiodic = [true, true]\n\
                 [initial]\ntype = \"taylor_green\"\namplitude = 1.0\nwavelength = {wavelength:?}\n\
                 [time]\nend = 0.1\n"
            )
        };
        assert!(build::<2>(&Case::from_toml_str(&tg(0.5)).unwrap()).is_ok());
        let e = build_error(&tg(0.3));
        assert!(
            e.starts_with("initial.wavelength = 0.3: expected a wavelength that divides"),
            "{e}"
        );
    }

    #[test]
    fn the_default_domain_widens_the_initial_box_by_half() {
        let case = Case::from_toml_str(TANK).unwrap();
        let setup = build::<2>(&case).unwrap();
        let (lo, hi) = (setup.domain.lo, setup.domain.hi);
        // wall particles span x from -0.125 to 3.325 (70 lattice points from -0.15) and
        // y from -0.125 to 1.775 (the top is open): half of 3.45 and of 1.9 on each side
        for (got, want) in [
            (lo[0], -1.85),
            (lo[1], -1.075),
            (hi[0], 5.05),
            (hi[1], 2.725),
        ] {
            assert!((got - want).abs() < 1e-9, "{lo:?} {hi:?}");
        }
    }

    /// The centre value quoted in `../shared/refdata/README.md` §5, -0.147343 ρ0 ω² L²,
    /// and p = 0 on the edges.
    #[test]
    fn rotating_square_pressure_series() {
        assert!((rotating_square_pressure(0.0, 0.0, 1.0) + 0.147343).abs() < 2e-6);
        assert!((rotating_square_pressure(0.0, 0.0, 2.0) + 4.0 * 0.147343).abs() < 1e-5);
        assert!(rotating_square_pressure(0.5, 0.1, 1.0).abs() < 1e-12);
    }
}
