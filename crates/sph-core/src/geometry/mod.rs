//! Builds the initial particle set of a case: fluid blocks on a lattice, tank and
//! wall boxes as layers of fixed dummy particles, the initial density (hydrostatic
//! or from an analytic field), masses `m_i = ρ_i V0`, the sound speed and the domain.
//!
//! What only the built particles can tell is checked here: fluid inside walls or in
//! two blocks at once, an initial field that does not fit the fluid it fills, probes
//! that no fluid can reach, particles outside the domain (`checks`,
//! [`initial_field`]); the lattice of blocks and walls is `lattice`.

mod checks;
mod expressions;
pub mod initial_field;
mod lattice;
mod regions;
mod report;
pub mod solid;

pub use checks::probe_refusal;
pub use report::Region;

use crate::boundary::bodies::Body;
use crate::case::{Case, InitialField};
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::particles::{Kind, Particles, Vector};
use crate::physics::eos::LinearEos;
use expressions::ExpressionField;
use regions::Shapes;

/// Everything the case fixes before the first step.
pub struct Setup<const D: usize> {
    pub particles: Particles<D>,
    pub domain: Domain<D>,
    pub eos: LinearEos,
    pub gravity: Vector<D>,
    /// The tanks and walls, by the ids of their particles.
    pub bodies: Vec<Body>,
    /// Every fluid region and wall, by the ids of its particles, in build order.
    pub regions: Vec<Region>,
    /// The solids of the `[[shape]]` walls with their index in `case.shape`.
    pub wall_solids: Vec<(usize, solid::Solid)>,
}

pub(super) fn vector<const D: usize>(v: &[f64]) -> Vector<D> {
    Vector::from_fn(|d, _| v[d])
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

    let shapes = Shapes::build(case)?;
    let (regions, fluid) = fluid_points::<D>(case, &shapes, &gravity)?;

    let expressions = ExpressionField::of(case, gravity.norm())?;
    let mut field_speed = 0.0_f64;
    if let Some(field) = &expressions {
        for (x, _) in &fluid {
            if let Some(u) = field.velocity(x)? {
                field_speed = field_speed.max(u.norm());
            }
        }
    }
    let eos = LinearEos {
        rho0,
        c0: sound_speed(case, &regions, &fluid, field_speed, &gravity, dx)?,
        background: case.fluid.background_pressure,
    };
    let mut particles = Particles::default();
    // the fluid points come region by region: each region's ids are one range
    let mut counts = vec![0u32; regions.len()];
    for (_, k) in &fluid {
        counts[*k] += 1;
    }
    let mut built = Vec::new();
    let mut first = particles.next_id;
    for (region, count) in regions.iter().zip(counts) {
        built.push(Region {
            key: region.key.clone(),
            name: None,
            kind: Kind::Fluid,
            ids: first..first + count,
        });
        first += count;
    }
    for &(x, k) in &fluid {
        let region = &regions[k];
        let mut u = region.velocity;
        let mut p = 0.0;
        if let Some(top) = region.top {
            // p = ρ0 (s_top - s(x)), s(x) = -g·x the height times |g|
            p = rho0 * (top + gravity.dot(&x));
        }
        let mut rho = None;
        match (&expressions, &case.initial) {
            (Some(field), _) => {
                u = field.velocity(&x)?.unwrap_or(u);
                let (pressure, density) = field.state(&x)?;
                p = pressure.unwrap_or(p);
                rho = density;
            }
            (None, Some(field)) => {
                (u, p) = initial_field::value(field, &x, rho0, gravity.norm(), p);
            }
            (None, None) => {}
        }
        let rho = rho.unwrap_or_else(|| eos.density(p + eos.background));
        particles.push(Kind::Fluid, x, u, rho, rho * volume);
    }

    let mut bodies = Vec::new();
    let mut walls = lattice::wall_points::<D>(case);
    for (k, solid) in &shapes.walls {
        let points = regions::wall_points::<D>(case, *k, solid)?;
        walls.push(points.into_iter().map(|x| (x, Vector::zeros())).collect());
    }
    for ((key, name), points) in case.body_names().into_iter().zip(walls) {
        let first = particles.next_id;
        for (x, u) in points {
            particles.push(Kind::Wall, x, u, rho0, rho0 * volume);
        }
        built.push(Region {
            key: key.trim_end_matches(".name").to_string(),
            name: Some(name.clone()),
            kind: Kind::Wall,
            ids: first..particles.next_id,
        });
        bodies.push(Body {
            name,
            ids: first..particles.next_id,
        });
    }
    checks::check_overlap(&particles, dx)?;
    initial_field::check(case, &particles)?;
    let domain = domain_of(case, &particles)?;
    checks::check_probes(case, &domain, &shapes.walls)?;
    Ok(Setup {
        particles,
        domain,
        eos,
        gravity,
        bodies,
        regions: built,
        wall_solids: shapes.walls,
    })
}

/// A fluid block or fluid shape: its initial velocity, and the height times |g| of
/// the free surface its hydrostatic start hangs from (none: no hydrostatic start).
struct FluidRegion<const D: usize> {
    /// `fluid_block[k]` or `shape[k]`.
    key: String,
    velocity: Vector<D>,
    top: Option<f64>,
}

impl<const D: usize> FluidRegion<D> {
    /// `surface` when set, else the highest corner of the box `[lo, hi]` along -g.
    fn new(
        key: String,
        velocity: Option<&[f64]>,
        hydrostatic: Option<bool>,
        surface: Option<f64>,
        (lo, hi): (&Vector<D>, &Vector<D>),
        gravity: &Vector<D>,
    ) -> Self {
        let top = hydrostatic.unwrap_or(true).then(|| match surface {
            Some(height) => height * gravity.norm(),
            None => lattice::corners(lo, hi)
                .iter()
                .map(|c| -gravity.dot(c))
                .fold(f64::MIN, f64::max),
        });
        FluidRegion {
            key,
            velocity: velocity.map(vector).unwrap_or_else(Vector::zeros),
            top,
        }
    }
}

/// Every fluid lattice point with the index of its region: the fluid blocks, then the
/// fluid shapes, less what the cuts and wall shapes remove.
#[allow(clippy::type_complexity)]
fn fluid_points<const D: usize>(
    case: &Case,
    shapes: &Shapes,
    gravity: &Vector<D>,
) -> Result<(Vec<FluidRegion<D>>, Vec<(Vector<D>, usize)>)> {
    let dx = case.dx();
    let mut regions = Vec::new();
    let mut fluid = Vec::new();
    for (k, b) in case.fluid_block.iter().enumerate() {
        let points = lattice::block_points::<D>(b, dx);
        if points.is_empty() {
            return Err(SphError::invalid(
                format!("fluid_block[{k}]"),
                format!("lo = {:?}, hi = {:?}", b.lo, b.hi),
                format!("a box at least one spacing ({dx} m) wide along every axis"),
            ));
        }
        let bounds = (&vector(&b.lo), &vector(&b.hi));
        let region = FluidRegion::new(
            format!("fluid_block[{k}]"),
            b.velocity.as_deref(),
            b.hydrostatic,
            b.surface,
            bounds,
            gravity,
        );
        fluid.extend(points.into_iter().map(|x| (x, regions.len())));
        regions.push(region);
    }
    for (k, solid) in &shapes.fluid {
        let s = &case.shape[*k];
        let points = regions::fluid_points::<D>(case, *k, solid)?;
        let bounds = (&vector(&solid.lo), &vector(&solid.hi));
        let region = FluidRegion::new(
            format!("shape[{k}]"),
            s.velocity.as_deref(),
            s.hydrostatic,
            s.surface,
            bounds,
            gravity,
        );
        fluid.extend(points.into_iter().map(|x| (x, regions.len())));
        regions.push(region);
    }
    fluid.retain(|(x, _)| shapes.keeps_fluid(x, dx));
    if fluid.is_empty() {
        return Err(SphError::invalid(
            "shape",
            format!(
                "{} cut and {} wall shapes",
                shapes.cuts.len(),
                shapes.walls.len()
            ),
            "shapes that leave some fluid (they remove every fluid particle)",
        ));
    }
    Ok((regions, fluid))
}

/// c0 given, or `factor · max(U, sqrt(Δp/ρ0))` with H the fluid height along gravity,
/// `U = max(|u0|, |u_in|, sqrt(2|g|H))` unless set (`u_in` the inlets' speeds),
/// `Δp = ρ0|g|H`; `field_speed` is the largest speed of an expression field.
fn sound_speed<const D: usize>(
    case: &Case,
    regions: &[FluidRegion<D>],
    fluid: &[(Vector<D>, usize)],
    field_speed: f64,
    gravity: &Vector<D>,
    dx: f64,
) -> Result<f64> {
    if let Some(c0) = case.fluid.sound_speed {
        return Ok(c0);
    }
    let g = gravity.norm();
    let height = if g > 0.0 {
        let s: Vec<f64> = fluid.iter().map(|(x, _)| -gravity.dot(x) / g).collect();
        s.iter().cloned().fold(f64::MIN, f64::max) - s.iter().cloned().fold(f64::MAX, f64::min) + dx
    } else {
        0.0
    };
    let mut u0 = regions
        .iter()
        .map(|r| r.velocity.norm())
        .fold(0.0, f64::max);
    if let Some(InitialField::TaylorGreen { amplitude, .. }) = &case.initial {
        u0 = u0.max(amplitude.abs());
    }
    u0 = u0.max(field_speed).max(inflow_speed(case));
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
            "a sound speed, or fluid.max_velocity (the flow's largest speed, which the rule \
             c0 = sound_speed_factor × U takes): with no gravity, no initial velocity and no \
             inflow it cannot be derived",
        ))
    }
}

/// The largest inflow speed of the case's inlets (0 without).
fn inflow_speed(case: &Case) -> f64 {
    (case.open_boundary.iter())
        .filter_map(|b| b.velocity.as_ref())
        .map(|v| v.iter().map(|c| c * c).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
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

#[cfg(test)]
mod tests {
    use super::initial_field::rotating_square_pressure;
    use super::*;

    /// A tank at h/Δx = 1.33 (three wall layers), which the figures below count in.
    const TANK: &str = r#"
        dimension = 2
        [particles]
        spacing = 0.05
        h_over_dx = 1.33
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
    fn the_sound_speed_rule_takes_the_inflow_speed_or_names_the_key_that_sets_it() {
        // a channel of fluid at rest, no gravity, fed at 2 m/s: c0 = 10 × 2
        let channel = |inlet: &str| {
            format!(
                "dimension = 2\n[particles]\nspacing = 0.05\n[fluid]\ndensity = 1000.0\n\
                 [[fluid_block]]\nlo = [0.0, 0.0]\nhi = [1.0, 0.8]\nhydrostatic = false\n\
                 [domain]\nlo = [0.0, 0.0]\nhi = [1.0, 0.8]\nperiodic = [false, true]\n{inlet}\
                 [[open_boundary]]\ntype = \"outlet\"\naxis = 0\nside = \"hi\"\n\
                 [time]\nend = 0.1\n"
            )
        };
        let inlet = "[[open_boundary]]\ntype = \"inlet\"\naxis = 0\nside = \"lo\"\n\
                     velocity = [2.0, 0.0]\n";
        let setup = build::<2>(&Case::from_toml_str(&channel(inlet)).unwrap()).unwrap();
        assert_eq!(setup.eos.c0, 20.0);
        let e = build_error(&channel(""));
        assert!(
            e.starts_with(
                "fluid.sound_speed = (missing): expected a sound speed, or fluid.max_velocity"
            ),
            "{e}"
        );
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
    fn the_standing_wave_must_fill_its_tank_from_the_origin() {
        let wave = |length: f64, depth: f64| {
            TANK.replace("hi = [1.2, 0.6]", "hi = [1.0, 0.5]")
                + &format!(
                    "[initial]\ntype = \"standing_wave\"\namplitude = 0.01\n\
                     length = {length:?}\ndepth = {depth:?}\n"
                )
        };
        assert!(build::<2>(&Case::from_toml_str(&wave(1.0, 0.5)).unwrap()).is_ok());
        let e = build_error(&wave(3.2196, 0.5));
        assert!(
            e.starts_with("initial.length = 3.2196: expected the extent along x of the fluid"),
            "{e}"
        );
        let e = build_error(&wave(1.0, 0.6));
        assert!(
            e.starts_with("initial.depth = 0.6: expected the extent along y"),
            "{e}"
        );
        let sideways = Case::from_toml_str(
            &wave(1.0, 0.5).replace("gravity = [0.0, -9.81]", "gravity = [-9.81, 0.0]"),
        );
        let e = sideways.unwrap_err().to_string();
        assert!(
            e.starts_with("fluid.gravity = [-9.81, 0.0]: expected gravity along -y"),
            "{e}"
        );
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

    /// The centre value quoted in `docs/validation/data/README.md`, -0.147343 ρ0 ω² L²,
    /// and p = 0 on the edges.
    #[test]
    fn rotating_square_pressure_series() {
        assert!((rotating_square_pressure(0.0, 0.0, 1.0) + 0.147343).abs() < 2e-6);
        assert!((rotating_square_pressure(0.0, 0.0, 2.0) + 4.0 * 0.147343).abs() < 1e-5);
        assert!(rotating_square_pressure(0.5, 0.1, 1.0).abs() < 1e-12);
    }
}
