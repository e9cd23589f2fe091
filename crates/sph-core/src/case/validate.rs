//! Value checks beyond types: ranges, component counts, boxes, the particle budget and
//! the scheme's options. Checks that need the particles (overlaps, probes against the
//! domain, initial fields against the fluid they fill) run when the case is built
//! ([`crate::geometry`]).

use super::schema::*;
use super::shapes::Role;
use crate::error::{Result, SphError};

impl Case {
    /// Value checks beyond types; geometry checks that need particles happen when building.
    pub fn validate(&self) -> Result<()> {
        let d = self.dimension;
        if d != 2 && d != 3 {
            return Err(SphError::invalid("dimension", d, "2 or 3"));
        }
        plain_file_name("name", &self.name)?;
        positive("particles.spacing", self.particles.spacing)?;
        let ratio = self.particles.h_over_dx;
        if !(1.0..=3.0).contains(&ratio) {
            return Err(SphError::invalid(
                "particles.h_over_dx",
                ratio,
                "a value in [1, 3]",
            ));
        }
        positive("fluid.density", self.fluid.density)?;
        if let Some(g) = &self.fluid.gravity {
            components("fluid.gravity", g, d)?;
        }
        if let Some(c0) = self.fluid.sound_speed {
            positive("fluid.sound_speed", c0)?;
        }
        positive("fluid.sound_speed_factor", self.fluid.sound_speed_factor)?;
        non_negative("fluid.background_pressure", self.fluid.background_pressure)?;
        if let Some(u) = self.fluid.max_velocity {
            non_negative("fluid.max_velocity", u)?;
        }
        let fluid_shapes = self.shape.iter().filter(|s| s.role == Role::Fluid);
        if self.fluid_block.is_empty() && fluid_shapes.count() == 0 {
            return Err(SphError::invalid(
                "fluid_block",
                "[]",
                "at least one [[fluid_block]] or [[shape]] with role = \"fluid\"",
            ));
        }
        for (k, shape) in self.shape.iter().enumerate() {
            self.check_shape(k, shape)?;
        }
        for (k, b) in self.open_boundary.iter().enumerate() {
            self.check_open_boundary(k, b)?;
        }
        for (k, b) in self.fluid_block.iter().enumerate() {
            check_box(&format!("fluid_block[{k}]"), &b.lo, &b.hi, d)?;
            if let Some(v) = &b.velocity {
                components(&format!("fluid_block[{k}].velocity"), v, d)?;
            }
            if let Some(s) = b.surface {
                finite(&format!("fluid_block[{k}].surface"), s)?;
            }
        }
        for (k, b) in self.wall.iter().enumerate() {
            check_box(&format!("wall[{k}]"), &b.lo, &b.hi, d)?;
            self.check_wall_depth(k, b)?;
        }
        for (k, t) in self.tank.iter().enumerate() {
            check_box(&format!("tank[{k}]"), &t.lo, &t.hi, d)?;
            self.check_tank_layers(k, t)?;
            for face in t.open.iter().flatten() {
                if face_axis(face, d).is_none() {
                    let faces = &["-x", "+x", "-y", "+y", "-z", "+z"][..2 * d];
                    return Err(SphError::invalid(
                        format!("tank[{k}].open"),
                        format!("{face:?}"),
                        format!("faces among {faces:?}"),
                    ));
                }
            }
            if let Some(v) = &t.lid_velocity {
                let key = format!("tank[{k}].lid_velocity");
                components(&key, v, d)?;
                let top = ["+x", "+y", "+z"][d - 1];
                let top_open = t.open_faces(d).contains(&(d - 1, 1));
                if top_open || v[d - 1] != 0.0 {
                    return Err(SphError::invalid(
                        key,
                        format!("{v:?}"),
                        format!(
                            "a velocity tangential to a closed top face (set open without \"{top}\" \
                             and the last component to 0)"
                        ),
                    ));
                }
            }
        }
        if let Some(dom) = &self.domain {
            check_box("domain", &dom.lo, &dom.hi, d)?;
            if let Some(periodic) = dom.periodic.as_ref().filter(|p| p.len() != d) {
                return Err(SphError::invalid(
                    "domain.periodic",
                    format!("{periodic:?}"),
                    format!("{d} booleans (dimension = {d})"),
                ));
            }
            self.check_tanks_open_along_periodic(dom, d)?;
        }
        match &self.initial {
            Some(InitialField::TaylorGreen {
                amplitude,
                wavelength,
            }) => {
                only_2d(d, "taylor_green")?;
                finite("initial.amplitude", *amplitude)?;
                positive("initial.wavelength", *wavelength)?;
            }
            Some(InitialField::RotatingSquare {
                angular_velocity,
                side,
            }) => {
                only_2d(d, "rotating_square")?;
                finite("initial.angular_velocity", *angular_velocity)?;
                positive("initial.side", *side)?;
            }
            Some(InitialField::EllipticDrop {
                strain_rate,
                radius,
            }) => {
                only_2d(d, "elliptic_drop")?;
                finite("initial.strain_rate", *strain_rate)?;
                positive("initial.radius", *radius)?;
            }
            Some(InitialField::StandingWave {
                amplitude,
                length,
                depth,
            }) => {
                only_2d(d, "standing_wave")?;
                finite("initial.amplitude", *amplitude)?;
                positive("initial.length", *length)?;
                positive("initial.depth", *depth)?;
                let g = self.gravity();
                if g[0] != 0.0 || g[1].is_nan() || g[1] >= 0.0 {
                    return Err(SphError::invalid(
                        "fluid.gravity",
                        format!("{g:?}"),
                        "gravity along -y (initial.type = \"standing_wave\")",
                    ));
                }
            }
            Some(InitialField::Expressions {
                constants,
                u,
                p,
                rho,
                ..
            }) => {
                if let Some(u) = u {
                    if u.len() != d {
                        return Err(SphError::invalid(
                            "initial.u",
                            format!("{u:?}"),
                            format!("{d} expressions, one per velocity component"),
                        ));
                    }
                }
                if p.is_some() && rho.is_some() {
                    return Err(SphError::invalid(
                        "initial.rho",
                        "(set with initial.p)",
                        "either a pressure or a density expression, not both",
                    ));
                }
                for (name, value) in constants.iter().flatten() {
                    finite(&format!("initial.constants.{name}"), *value)?;
                }
            }
            None => {}
        }
        self.validate_forcing()?;
        self.check_particle_count()?;
        self.validate_scheme()?;
        positive("time.end", self.time.end)?;
        non_negative("time.output_interval", self.time.output_interval)?;
        positive(
            "stability.max_density_variation",
            self.stability.max_density_variation,
        )?;
        positive("stability.max_mach", self.stability.max_mach)?;
        if let Some(i) = self.output.restart_interval {
            positive("output.restart_interval", i)?;
        }
        if let Some(i) = self.diagnostics.interval {
            positive("diagnostics.interval", i)?;
        }
        for (k, p) in self.diagnostics.probes.iter().enumerate() {
            components(&format!("diagnostics.probes[{k}]"), p, d)?;
        }
        if let Some(c) = &self.diagnostics.moment_point {
            components("diagnostics.moment_point", c, d)?;
        }
        if let Some(r) = &self.diagnostics.reference {
            positive("diagnostics.reference.velocity", r.velocity)?;
            positive("diagnostics.reference.length", r.length)?;
            if let Some(rho) = r.density {
                positive("diagnostics.reference.density", rho)?;
            }
        }
        for k in 0..self.diagnostics.sensors.len() {
            self.check_sensor(k)?;
        }
        self.check_body_names()?;
        if let Some(a) = self.diagnostics.surge_front_axis {
            if a >= d {
                return Err(SphError::invalid(
                    "diagnostics.surge_front_axis",
                    a,
                    format!("an axis index below {d}"),
                ));
            }
        }
        Ok(())
    }

    /// Body names head the loads' columns: a letter, then letters, digits or `_`, each
    /// name once.
    fn check_body_names(&self) -> Result<()> {
        let names = self.body_names();
        for (k, (key, name)) in names.iter().enumerate() {
            if !column_name(name) {
                return Err(SphError::invalid(
                    key,
                    format!("{name:?}"),
                    "a letter, then letters, digits or _ (it heads the loads' columns)",
                ));
            }
            if let Some((other, _)) = names[..k].iter().find(|(_, n)| n == name) {
                return Err(SphError::invalid(
                    key,
                    format!("{name:?}"),
                    format!("a name no other body has ({other} has it)"),
                ));
            }
        }
        Ok(())
    }

    /// A sensor needs a plain name of its own, a face of positive size with a normal,
    /// and a cut-off below the Nyquist frequency of the series it is filtered at.
    fn check_sensor(&self, k: usize) -> Result<()> {
        let sensors = &self.diagnostics.sensors;
        let s = &sensors[k];
        let key = |what: &str| format!("diagnostics.sensors[{k}].{what}");
        if !column_name(&s.name) || sensors[..k].iter().any(|o| o.name == s.name) {
            return Err(SphError::invalid(
                key("name"),
                format!("{:?}", s.name),
                "a name no other sensor has: a letter, then letters, digits or _",
            ));
        }
        components(&key("centre"), &s.centre, self.dimension)?;
        components(&key("normal"), &s.normal, self.dimension)?;
        if s.normal.iter().all(|&c| c == 0.0) {
            return Err(SphError::invalid(
                key("normal"),
                format!("{:?}", s.normal),
                "a non-zero normal of the face",
            ));
        }
        positive(&key("size"), s.size)?;
        self.check_rectangle(k, s)?;
        if let Some(f) = s.cutoff {
            let nyquist = 0.5 / self.series_interval();
            if !(f > 0.0 && f < nyquist) {
                return Err(SphError::invalid(
                    key("cutoff"),
                    f,
                    format!(
                        "a frequency in (0, {nyquist}) Hz: below the Nyquist frequency of the \
                         series it filters (diagnostics.interval = {} s)",
                        self.series_interval()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// A rectangular face (3D only) needs a positive width and a direction `along` for
    /// its `size` side that is not the normal's.
    fn check_rectangle(&self, k: usize, s: &SensorConfig) -> Result<()> {
        let key = |what: &str| format!("diagnostics.sensors[{k}].{what}");
        let (width, along) = match (s.width, &s.along) {
            (None, None) => return Ok(()),
            (Some(_), _) if self.dimension == 2 => {
                return Err(SphError::invalid(
                    key("width"),
                    s.width.unwrap_or_default(),
                    "no width in 2D (a 2D face is a segment `size` long)",
                ))
            }
            (Some(w), Some(a)) => (w, a),
            (Some(w), None) => {
                return Err(SphError::invalid(
                    key("width"),
                    w,
                    "`along` with it: the direction of the rectangle's `size` side",
                ))
            }
            (None, Some(a)) => {
                return Err(SphError::invalid(
                    key("along"),
                    format!("{a:?}"),
                    "`width` with it: `along` orients a rectangular face",
                ))
            }
        };
        positive(&key("width"), width)?;
        components(&key("along"), along, self.dimension)?;
        let dot: f64 = along.iter().zip(&s.normal).map(|(a, n)| a * n).sum();
        let (a2, n2): (f64, f64) = (
            along.iter().map(|a| a * a).sum(),
            s.normal.iter().map(|n| n * n).sum(),
        );
        if a2 * n2 - dot * dot <= 1e-12 * a2 * n2 {
            return Err(SphError::invalid(
                key("along"),
                format!("{along:?}"),
                format!(
                    "a direction in the face's plane, not along its normal {:?}",
                    s.normal
                ),
            ));
        }
        Ok(())
    }

    /// Along a periodic axis the fluid wraps around, so a tank may have no wall there:
    /// both its faces on that axis must be open.
    fn check_tanks_open_along_periodic(&self, dom: &DomainConfig, d: usize) -> Result<()> {
        const FACES: [[&str; 2]; 3] = [["-x", "+x"], ["-y", "+y"], ["-z", "+z"]];
        for (k, t) in self.tank.iter().enumerate() {
            let open = t.open_faces(d);
            for axis in (0..d).filter(|&a| dom.is_periodic(a)) {
                let missing: Vec<&str> = [-1i8, 1]
                    .iter()
                    .zip(FACES[axis])
                    .filter(|(side, _)| !open.contains(&(axis, **side)))
                    .map(|(_, name)| name)
                    .collect();
                if missing.is_empty() {
                    continue;
                }
                let current = (t.open.clone()).unwrap_or_else(|| vec![FACES[d - 1][1].into()]);
                let value = match t.open {
                    Some(_) => format!("{current:?}"),
                    None => format!("{current:?} (the default)"),
                };
                let mut faces = current;
                faces.extend(missing.iter().map(|f| f.to_string()));
                return Err(SphError::invalid(
                    format!("tank[{k}].open"),
                    value,
                    format!(
                        "the faces along periodic axis {} open (domain.periodic): add {}, \
                         e.g. open = {faces:?}",
                        ["x", "y", "z"][axis],
                        missing
                            .iter()
                            .map(|f| format!("\"{f}\""))
                            .collect::<Vec<_>>()
                            .join(" and ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// A tank's layers must reach at least the kernel support deep: fluid by the wall
    /// would otherwise miss part of its neighbourhood and leak through.
    fn check_tank_layers(&self, k: usize, t: &TankConfig) -> Result<()> {
        let (need, layers) = (self.min_wall_layers(), t.layer_count(self));
        if layers < need {
            return Err(SphError::invalid(
                format!("tank[{k}].layers"),
                layers,
                format!(
                    "at least {need} layers: layers·Δx must cover the kernel support R = {:.4} m \
                     (particles.kernel, particles.h_over_dx = {}); leave layers unset for the minimum",
                    self.support(),
                    self.particles.h_over_dx
                ),
            ));
        }
        Ok(())
    }

    /// A wall box must be at least the kernel support thick along every axis, or fluid
    /// on either side sees through it.
    fn check_wall_depth(&self, k: usize, b: &WallConfig) -> Result<()> {
        let support = self.support();
        let thinnest =
            b.lo.iter()
                .zip(&b.hi)
                .map(|(l, h)| h - l)
                .fold(f64::INFINITY, f64::min);
        if thinnest < support * (1.0 - 1e-9) {
            return Err(SphError::invalid(
                format!("wall[{k}]"),
                format!("lo = {:?}, hi = {:?}", b.lo, b.hi),
                format!(
                    "a box at least the kernel support R = {support:.4} m thick along every axis \
                     (particles.kernel, particles.h_over_dx)"
                ),
            ));
        }
        Ok(())
    }

    /// One expression per component and finite constants; the expressions themselves
    /// are parsed when the run is built.
    fn validate_forcing(&self) -> Result<()> {
        let Some(forcing) = &self.forcing else {
            return Ok(());
        };
        let d = self.dimension;
        if forcing.acceleration.len() != d {
            return Err(SphError::invalid(
                "forcing.acceleration",
                format!("{:?}", forcing.acceleration),
                format!("{d} expressions, one per component"),
            ));
        }
        for (name, value) in forcing.constants.iter().flatten() {
            finite(&format!("forcing.constants.{name}"), *value)?;
        }
        Ok(())
    }

    fn validate_scheme(&self) -> Result<()> {
        let s = &self.scheme;
        if !(0.0..=1.0).contains(&s.delta) {
            return Err(SphError::invalid(
                "scheme.delta",
                s.delta,
                "a value in [0, 1]",
            ));
        }
        match s.viscosity {
            ViscosityChoice::Artificial => non_negative("scheme.alpha", s.alpha())?,
            ViscosityChoice::Physical => match s.dynamic_viscosity {
                Some(mu) => positive("scheme.dynamic_viscosity", mu)?,
                None => {
                    return Err(SphError::invalid(
                        "scheme.dynamic_viscosity",
                        "(missing)",
                        "a positive viscosity μ in Pa·s when scheme.viscosity = \"physical\"",
                    ))
                }
            },
            ViscosityChoice::None => {}
        }
        let cfl = s.cfl();
        if !(cfl > 0.0 && cfl <= 3.0) {
            return Err(SphError::invalid(
                "scheme.cfl",
                cfl,
                "a Courant number in (0, 3]",
            ));
        }
        if let Some(c) = s.viscous_cfl {
            positive("scheme.viscous_cfl", c)?;
        }
        if let Some(c) = s.diffusion_cfl {
            positive("scheme.diffusion_cfl", c)?;
        }
        positive("scheme.force_cfl", s.force_cfl)?;
        if s.turbulence == TurbulenceChoice::DeltaLes {
            self.check_les()?;
        }
        Ok(())
    }

    /// δ-LES-SPH: its constants, and the flows it is offered for: periodic along every
    /// axis, without walls or open boundaries, with its own shifting and a physical (or
    /// no) molecular viscosity.
    fn check_les(&self) -> Result<()> {
        let s = &self.scheme;
        let constants = [
            ("scheme.smagorinsky_constant", s.smagorinsky_constant),
            ("scheme.diffusion_constant", s.diffusion_constant),
            ("scheme.les_shifting", s.les_shifting),
        ];
        for (key, value) in constants {
            if let Some(v) = value {
                non_negative(key, v)?;
            }
        }
        for (key, value) in [
            ("scheme.les_length", s.les_length),
            ("scheme.les_velocity", s.les_velocity),
        ] {
            if let Some(v) = value {
                positive(key, v)?;
            }
        }
        let expected = |what: &str| {
            format!("{what} with scheme.turbulence = \"delta_les\" (offered for periodic flows without walls)")
        };
        if s.viscosity == ViscosityChoice::Artificial {
            return Err(SphError::invalid(
                "scheme.viscosity",
                "\"artificial\"",
                expected("\"physical\" or \"none\""),
            ));
        }
        if s.shifting != ShiftingChoice::None {
            return Err(SphError::invalid(
                "scheme.shifting",
                "\"delta_plus\"",
                expected("\"none\" (δ-LES-SPH shifts with its own δu)"),
            ));
        }
        let walls = !self.tank.is_empty()
            || !self.wall.is_empty()
            || self.shape.iter().any(|sh| sh.role == Role::Wall);
        if walls {
            return Err(SphError::invalid(
                "tank/wall/shape",
                "walls",
                expected("no walls"),
            ));
        }
        if !self.open_boundary.is_empty() {
            return Err(SphError::invalid(
                "open_boundary",
                self.open_boundary.len(),
                expected("none"),
            ));
        }
        let periodic = (self.domain.as_ref())
            .is_some_and(|dom| (0..self.dimension).all(|d| dom.is_periodic(d)));
        if !periodic {
            return Err(SphError::invalid(
                "domain.periodic",
                format!(
                    "{:?}",
                    self.domain.as_ref().and_then(|dom| dom.periodic.clone())
                ),
                expected("every axis periodic"),
            ));
        }
        Ok(())
    }
}

/// A name that can head time-series columns: a letter, then letters, digits or `_`.
fn column_name(name: &str) -> bool {
    name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A name that is one plain path component: not empty, no separator, not `.` or
/// `..`, no control character, so that `<name>_out` stays inside the working folder.
fn plain_file_name(key: &str, name: &str) -> Result<()> {
    let bad = name.is_empty()
        || name == "."
        || name == ".."
        || name.len() > 200
        || name
            .chars()
            .any(|c| c == '/' || c == '\\' || c.is_control());
    if bad {
        return Err(SphError::invalid(
            key,
            format!("{name:?}"),
            "a plain file name (no path separators, not empty, not \".\" or \"..\", \
             at most 200 bytes): the default output folder is <name>_out",
        ));
    }
    Ok(())
}

pub(super) fn positive(key: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a positive number"))
    }
}

pub(super) fn non_negative(key: &str, v: f64) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a number >= 0"))
    }
}

pub(super) fn finite(key: &str, v: f64) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a finite number"))
    }
}

pub(super) fn components(key: &str, v: &[f64], d: usize) -> Result<()> {
    if v.len() != d {
        return Err(SphError::invalid(
            key,
            format!("{v:?}"),
            format!("{d} components (dimension = {d})"),
        ));
    }
    if v.iter().any(|c| !c.is_finite()) {
        return Err(SphError::invalid(
            key,
            format!("{v:?}"),
            "finite components",
        ));
    }
    Ok(())
}

pub(super) fn check_box(key: &str, lo: &[f64], hi: &[f64], d: usize) -> Result<()> {
    components(&format!("{key}.lo"), lo, d)?;
    components(&format!("{key}.hi"), hi, d)?;
    if lo.iter().zip(hi).any(|(a, b)| b <= a) {
        return Err(SphError::invalid(
            format!("{key}.hi"),
            format!("{hi:?}"),
            format!("every component above lo = {lo:?}"),
        ));
    }
    Ok(())
}

fn only_2d(d: usize, field: &str) -> Result<()> {
    if d == 2 {
        Ok(())
    } else {
        Err(SphError::invalid(
            "initial.type",
            format!("\"{field}\""),
            "dimension = 2",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{error_of, MINIMAL};
    use super::super::Case;

    /// A 3D rectangle sensor on the tank's +x face, with `extra` keys.
    fn sensor_3d(extra: &str) -> String {
        MINIMAL
            .replace("dimension = 2", "dimension = 3")
            .replace("[0.0, -9.81]", "[0.0, 0.0, -9.81]")
            .replace("lo = [0.0, 0.0]", "lo = [0.0, 0.0, 0.0]")
            .replace("hi = [0.2, 0.1]", "hi = [0.2, 0.1, 0.1]")
            .replace("hi = [0.5, 0.3]", "hi = [0.5, 0.3, 0.3]")
            + "[[diagnostics.sensors]]\nname = \"s\"\ncentre = [0.5, 0.1, 0.05]\n\
               normal = [-1.0, 0.0, 0.0]\nsize = 0.02\n"
            + extra
    }

    #[test]
    fn rectangle_sensors_need_a_width_and_a_direction_in_their_plane() {
        assert!(Case::from_toml_str(&sensor_3d("width = 0.01\nalong = [0.0, 0.0, 1.0]\n")).is_ok());
        let e = error_of(&sensor_3d("width = 0.01\n"));
        assert!(
            e.starts_with("diagnostics.sensors[0].width = 0.01: expected `along` with it"),
            "{e}"
        );
        let e = error_of(&sensor_3d("along = [0.0, 1.0, 0.0]\n"));
        assert!(
            e.starts_with("diagnostics.sensors[0].along = [0.0, 1.0, 0.0]: expected `width`"),
            "{e}"
        );
        let e = error_of(&sensor_3d("width = 0.01\nalong = [2.0, 0.0, 0.0]\n"));
        assert!(
            e.starts_with("diagnostics.sensors[0].along = [2.0, 0.0, 0.0]: expected a direction in the face's plane"),
            "{e}"
        );
        let e = error_of(&sensor_3d("width = -0.01\nalong = [0.0, 0.0, 1.0]\n"));
        assert!(e.starts_with("diagnostics.sensors[0].width = -0.01"), "{e}");
        let flat = MINIMAL.to_string()
            + "[[diagnostics.sensors]]\nname = \"s\"\ncentre = [0.5, 0.1]\n\
               normal = [-1.0, 0.0]\nsize = 0.02\nwidth = 0.01\n";
        let e = error_of(&flat);
        assert!(
            e.starts_with("diagnostics.sensors[0].width = 0.01: expected no width in 2D"),
            "{e}"
        );
    }

    #[test]
    fn absurd_spacing_is_refused_before_building() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 1e-9"));
        assert!(
            e.starts_with("particles.spacing = 0.000000001: expected a spacing giving at most"),
            "{e}"
        );
    }

    #[test]
    fn a_periodic_axis_names_the_tank_faces_to_open() {
        let periodic = MINIMAL.to_string()
            + "[domain]\nlo = [-0.1, -0.1]\nhi = [0.6, 0.5]\nperiodic = [true, false]\n";
        let e = error_of(&periodic);
        assert_eq!(
            e,
            "tank[0].open = [\"+y\"] (the default): expected the faces along periodic axis x open \
             (domain.periodic): add \"-x\" and \"+x\", e.g. open = [\"+y\", \"-x\", \"+x\"]"
        );
        let half = periodic.replace(
            "hi = [0.5, 0.3]",
            "hi = [0.5, 0.3]\nopen = [\"+y\", \"-x\"]",
        );
        let e = error_of(&half);
        assert!(
            e.contains("add \"+x\", e.g. open = [\"+y\", \"-x\", \"+x\"]"),
            "{e}"
        );
        let open = half.replace("\"-x\"]", "\"-x\", \"+x\"]");
        assert!(Case::from_toml_str(&open).is_ok());
    }

    #[test]
    fn negative_spacing_is_refused() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = -0.01"));
        assert_eq!(e, "particles.spacing = -0.01: expected a positive number");
    }

    #[test]
    fn body_names_are_plain_and_unique() {
        let walls = |a: &str, b: &str| {
            MINIMAL.to_string()
                + &format!(
                    "[[wall]]\nname = \"{a}\"\nlo = [0.3, 0.0]\nhi = [0.4, 0.1]\n\
                     [[wall]]\nname = \"{b}\"\nlo = [0.4, 0.0]\nhi = [0.5, 0.1]\n"
                )
        };
        assert!(Case::from_toml_str(&walls("step", "baffle_2")).is_ok());
        let e = error_of(&walls("step", "step"));
        assert!(
            e.starts_with(
                "wall[1].name = \"step\": expected a name no other body has (wall[0].name has it)"
            ),
            "{e}"
        );
        let e = error_of(&walls("tank0", "b"));
        assert!(
            e.starts_with("wall[0].name = \"tank0\": expected a name no other"),
            "{e}"
        );
        let e = error_of(&walls("a b", "c"));
        assert!(
            e.starts_with("wall[0].name = \"a b\": expected a letter"),
            "{e}"
        );
        let named = MINIMAL.replace("hi = [0.2, 0.1]", "hi = [0.2, 0.1]\nname = \"water\"");
        let e = error_of(&named);
        assert!(
            e.starts_with("fluid_block[0].name") && e.contains("unknown field"),
            "fluid blocks carry no load, so no name: {e}"
        );
    }

    #[test]
    fn h_over_dx_out_of_range() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nh_over_dx = 7"));
        assert!(e.starts_with("particles.h_over_dx = 7"), "{e}");
    }

    #[test]
    fn wrong_component_count() {
        let e = error_of(&MINIMAL.replace("gravity = [0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]"));
        assert!(
            e.starts_with("fluid.gravity = [0.0, 0.0, -9.81]: expected 2 components"),
            "{e}"
        );
    }

    #[test]
    fn inverted_box() {
        let e = error_of(&MINIMAL.replace("hi = [0.2, 0.1]", "hi = [0.2, -0.1]"));
        assert!(e.starts_with("fluid_block[0].hi"), "{e}");
    }

    /// δ-LES-SPH is offered for periodic flows without walls: each other setting is
    /// refused in one line naming its key.
    #[test]
    fn les_is_refused_where_it_is_not_offered() {
        let les = "[scheme]\nturbulence = \"delta_les\"\nviscosity = \"physical\"\n\
                   dynamic_viscosity = 0.001";
        let e = error_of(&format!("{MINIMAL}\n{les}"));
        assert!(e.starts_with("tank/wall/shape = walls"), "{e}");
        let periodic = "[domain]\nlo = [0.0, 0.0]\nhi = [0.2, 0.1]\nperiodic = [true, true]";
        let open = MINIMAL.replace(
            "[[tank]]\n        lo = [0.0, 0.0]\n        hi = [0.5, 0.3]",
            "",
        );
        let e = error_of(&format!("{open}\n{les}"));
        assert!(e.starts_with("domain.periodic = None"), "{e}");
        let e = error_of(&format!(
            "{open}\n{les}\nshifting = \"delta_plus\"\n{periodic}"
        ));
        assert!(e.starts_with("scheme.shifting = \"delta_plus\""), "{e}");
        let e = error_of(&format!(
            "{open}\n{les}\nsmagorinsky_constant = -0.1\n{periodic}"
        ));
        assert!(e.starts_with("scheme.smagorinsky_constant = -0.1"), "{e}");
        let artificial = "[scheme]\nturbulence = \"delta_les\"";
        let e = error_of(&format!("{open}\n{artificial}\n{periodic}"));
        assert!(e.starts_with("scheme.viscosity = \"artificial\""), "{e}");
    }

    #[test]
    fn physical_viscosity_needs_mu() {
        let e = error_of(&format!("{MINIMAL}\n[scheme]\nviscosity = \"physical\""));
        assert!(e.starts_with("scheme.dynamic_viscosity = (missing)"), "{e}");
    }

    #[test]
    fn bad_open_face() {
        let e = error_of(&MINIMAL.replace("hi = [0.5, 0.3]", "hi = [0.5, 0.3]\nopen = [\"+z\"]"));
        assert!(e.starts_with("tank[0].open = \"+z\""), "{e}");
    }

    #[test]
    fn name_must_be_a_plain_file_name() {
        for bad in ["../x", "/tmp/x", "a/b", "..", "", "a\\\\b"] {
            let e = error_of(&format!("name = {bad:?}\n{MINIMAL}"));
            assert!(
                e.starts_with(&format!("name = {bad:?}: expected a plain file name")),
                "{e}"
            );
        }
        assert!(Case::from_toml_str(&format!("name = \"dam-break_2\"\n{MINIMAL}")).is_ok());
    }

    #[test]
    fn wall_layers_must_cover_the_support() {
        // h/Δx = 2: R = 4Δx, three layers are too few; unset, the default is four
        let text = MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nh_over_dx = 2.0");
        let e = error_of(&text.replace("hi = [0.5, 0.3]", "hi = [0.5, 0.3]\nlayers = 3"));
        assert!(
            e.starts_with("tank[0].layers = 3: expected at least 4 layers"),
            "{e}"
        );
        let case = Case::from_toml_str(&text).unwrap();
        assert_eq!(case.tank[0].layer_count(&case), 4);
    }

    #[test]
    fn thin_wall_boxes_are_refused() {
        let wall = "\n[[wall]]\nlo = [0.3, 0.0]\nhi = [0.32, 0.2]\n";
        let e = error_of(&format!("{MINIMAL}{wall}"));
        assert!(
            e.starts_with("wall[0] = lo = [0.3, 0.0], hi = [0.32, 0.2]: expected a box at least"),
            "{e}"
        );
    }
}
