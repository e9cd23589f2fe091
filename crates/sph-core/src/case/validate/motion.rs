//! Checks on moving bodies: each region's `motion` agrees with its `prescribed` table,
//! the table's entries have the case's dimension, and what moving bodies cannot do
//! yet is refused in one line.

use crate::case::checks::{components, finite, non_negative, positive};
use crate::case::motion::{
    BodyMotion, FreeConfig, MotionChoice, MotionTable, PaddleChoice, PrescribedConfig,
    SpectrumConfig, SpringConfig, WavesConfig,
};
use crate::case::schema::*;
use crate::error::{Result, SphError};

impl Case {
    /// Every region's motion, then what a case with moving bodies may not combine.
    pub(super) fn validate_motions(&self) -> Result<()> {
        for body in self.body_motions() {
            self.check_motion(&body)?;
        }
        for (k, s) in self.shape.iter().enumerate() {
            let moves = s.motion.is_some() || s.prescribed.is_some() || s.free.is_some();
            if s.role != crate::case::Role::Wall && moves {
                return Err(SphError::invalid(
                    format!("shape[{k}].motion"),
                    format!("{:?}", s.motion.unwrap_or_default()),
                    "no motion on a fluid shape (fluid moves with the flow; only walls take a motion)",
                ));
            }
        }
        if !self.has_moving_bodies() {
            return Ok(());
        }
        for (k, t) in self.tank.iter().enumerate() {
            if t.lid_velocity.is_some() && t.motion.unwrap_or_default() != MotionChoice::Fixed {
                return Err(SphError::invalid(
                    format!("tank[{k}].lid_velocity"),
                    format!("{:?}", t.lid_velocity.as_deref().unwrap_or_default()),
                    "no sliding lid on a moving tank (a [[wall]] above it can carry its own motion)",
                ));
            }
        }
        Ok(())
    }

    /// One region's `motion` against its `prescribed` and `free` tables.
    fn check_motion(&self, body: &BodyMotion) -> Result<()> {
        let key = &body.key;
        let beside = |table: &str, motion: &str| {
            SphError::invalid(
                format!("{key}.{table}"),
                "a table",
                format!("motion = \"{motion}\" beside it (without it the region is fixed)"),
            )
        };
        if body.prescribed.is_some() && body.motion != MotionChoice::Prescribed {
            return Err(beside("prescribed", "prescribed"));
        }
        if body.free.is_some() && body.motion != MotionChoice::Free {
            return Err(beside("free", "free"));
        }
        let missing = |table: &str, motion: &str, what: &str| {
            SphError::invalid(
                format!("{key}.motion"),
                format!("\"{motion}\""),
                format!("a table {key}.{table} giving {what} beside it"),
            )
        };
        match body.motion {
            MotionChoice::Fixed => Ok(()),
            MotionChoice::Prescribed => match body.prescribed {
                Some(table) => self.check_prescribed(key, table),
                None => Err(missing("prescribed", "prescribed", "the motion")),
            },
            MotionChoice::Free if key.starts_with("tank") => Err(SphError::invalid(
                format!("{key}.motion"),
                "\"free\"",
                "\"fixed\" or \"prescribed\" (a tank holds the fluid and does not float; a \
                 [[wall]] or a wall [[shape]] can)",
            )),
            MotionChoice::Free => match body.free {
                Some(free) => check_free(&format!("{key}.free"), free, self.dimension),
                None => Err(missing("free", "free", "its mass")),
            },
        }
    }

    /// The lengths and ranges of one `prescribed` table.
    fn check_prescribed(&self, key: &str, m: &PrescribedConfig) -> Result<()> {
        let d = self.dimension;
        let key = format!("{key}.prescribed");
        if let Some(waves) = &m.waves {
            let other = first_given(&[
                ("table", m.table.is_some()),
                ("displacement", m.displacement.is_some()),
                ("rotation", m.rotation.is_some()),
            ]);
            if let Some(name) = other {
                return Err(SphError::invalid(
                    format!("{key}.{name}"),
                    "given",
                    "either a wave maker (waves) or a motion of its own, not both",
                ));
            }
            self.check_waves(&format!("{key}.waves"), waves, m.pivot.is_some())?;
        }
        if m.table.is_some() && (m.displacement.is_some() || m.rotation.is_some()) {
            return Err(SphError::invalid(
                format!("{key}.table"),
                m.table
                    .as_ref()
                    .map(MotionTable::describe)
                    .unwrap_or_default(),
                "either a table or displacement and rotation expressions, not both",
            ));
        }
        if let Some(texts) = &m.displacement {
            count(
                &format!("{key}.displacement"),
                texts,
                d,
                "one expression per axis",
            )?;
        }
        if let Some(texts) = &m.rotation {
            let (n, what) = match d {
                2 => (1, "one expression: the angle about z"),
                _ => (3, "three expressions: the rotation vector"),
            };
            count(&format!("{key}.rotation"), texts, n, what)?;
            if m.pivot.is_none() {
                return Err(SphError::invalid(
                    format!("{key}.pivot"),
                    "none",
                    "the point the body turns about, beside a rotation",
                ));
            }
        }
        if let Some(pivot) = &m.pivot {
            components(&format!("{key}.pivot"), pivot, d)?;
        }
        if let Some(ramp) = m.ramp {
            non_negative(&format!("{key}.ramp"), ramp)?;
        }
        Ok(())
    }
}

impl Case {
    /// A wave maker's table: a depth, and either regular waves (a height with one of
    /// period and wavelength, below the breaking limit) or a spectrum; a flap's hinge.
    fn check_waves(&self, key: &str, w: &WavesConfig, pivot: bool) -> Result<()> {
        positive(&format!("{key}.depth"), w.depth)?;
        let g = self.gravity().iter().map(|g| g * g).sum::<f64>().sqrt();
        positive("fluid.gravity (magnitude, for a wave maker)", g)?;
        if w.paddle == PaddleChoice::Flap {
            if !pivot {
                return Err(SphError::invalid(
                    format!("{key}.paddle"),
                    "\"flap\"",
                    "the flap's hinge as the table's pivot",
                ));
            }
            let hinge = w.hinge_height.unwrap_or(0.0);
            finite(&format!("{key}.hinge_height"), hinge)?;
            if hinge >= w.depth {
                return Err(SphError::invalid(
                    format!("{key}.hinge_height"),
                    hinge,
                    format!("a hinge below the still-water level (depth {})", w.depth),
                ));
            }
        }
        if let Some(duration) = w.duration {
            positive(&format!("{key}.duration"), duration)?;
        }
        match &w.spectrum {
            Some(sea) => check_spectrum(key, w, sea),
            None => check_regular(key, w, g),
        }
    }
}

/// Regular waves: height, period or wavelength, order; refused above the breaking
/// limit `H/L = 0.142 tanh kd` (Miche 1944).
fn check_regular(key: &str, w: &WavesConfig, g: f64) -> Result<()> {
    let Some(height) = w.height else {
        return Err(SphError::invalid(
            format!("{key}.height"),
            "none",
            "the wave height (or a spectrum for an irregular sea)",
        ));
    };
    positive(&format!("{key}.height"), height)?;
    match (w.period, w.wavelength) {
        (Some(t), None) => positive(&format!("{key}.period"), t)?,
        (None, Some(l)) => positive(&format!("{key}.wavelength"), l)?,
        _ => {
            return Err(SphError::invalid(
                format!("{key}.period"),
                format!("{:?} with wavelength {:?}", w.period, w.wavelength),
                "one of period and wavelength",
            ))
        }
    }
    let order = w.order();
    if !(1..=2).contains(&order) || (order == 2 && w.paddle == PaddleChoice::Flap) {
        return Err(SphError::invalid(
            format!("{key}.order"),
            order,
            "1, or 2 for a piston (a flap's second-order motion is not built)",
        ));
    }
    let omega = w.angular_frequency(g);
    let k = crate::waves::theory::wavenumber(omega, w.depth, g);
    let limit = 0.142 * (k * w.depth).tanh() * 2.0 * std::f64::consts::PI / k;
    if height >= limit {
        return Err(SphError::invalid(
            format!("{key}.height"),
            height,
            format!(
                "a height below the breaking limit 0.142 L tanh(kd) = {limit:.4e} m (L = {:.4e} m)",
                2.0 * std::f64::consts::PI / k
            ),
        ));
    }
    Ok(())
}

/// An irregular sea: its parameters, and no regular-wave keys beside it.
fn check_spectrum(key: &str, w: &WavesConfig, sea: &SpectrumConfig) -> Result<()> {
    let regular = first_given(&[
        ("height", w.height.is_some()),
        ("period", w.period.is_some()),
        ("wavelength", w.wavelength.is_some()),
        ("order", w.order.is_some()),
    ]);
    if let Some(name) = regular {
        return Err(SphError::invalid(
            format!("{key}.{name}"),
            "given",
            "regular-wave keys or a spectrum, not both (the sea is made to first order)",
        ));
    }
    let key = format!("{key}.spectrum");
    positive(&format!("{key}.significant_height"), sea.significant_height)?;
    positive(&format!("{key}.peak_period"), sea.peak_period)?;
    if let Some(gamma) = sea.gamma {
        if !(1.0..=20.0).contains(&gamma) {
            return Err(SphError::invalid(
                format!("{key}.gamma"),
                gamma,
                "a peak enhancement in [1, 20]",
            ));
        }
    }
    if let Some(n) = sea.components {
        if !(1..=10_000).contains(&n) {
            return Err(SphError::invalid(
                format!("{key}.components"),
                n,
                "1 to 10000 components",
            ));
        }
    }
    if let Some([lo, hi]) = sea.frequencies {
        if !(lo.is_finite() && hi.is_finite() && 0.0 < lo && lo < hi) {
            return Err(SphError::invalid(
                format!("{key}.frequencies"),
                format!("[{lo}, {hi}]"),
                "[f_min, f_max] with 0 < f_min < f_max (Hz)",
            ));
        }
    }
    Ok(())
}

/// The first of the named keys that is given.
fn first_given<'a>(keys: &[(&'a str, bool)]) -> Option<&'a str> {
    keys.iter().find(|(_, given)| *given).map(|(name, _)| *name)
}

/// `texts` holds `n` expressions.
fn count(key: &str, texts: &[String], n: usize, what: &str) -> Result<()> {
    if texts.len() == n {
        return Ok(());
    }
    Err(SphError::invalid(
        key,
        format!("{} expressions", texts.len()),
        what,
    ))
}

/// The names of the degrees of freedom a free body may lock, by dimension.
pub(crate) fn degrees_of_freedom(d: usize) -> &'static [&'static str] {
    if d == 2 {
        &["x", "y", "rz"]
    } else {
        &["x", "y", "z", "rx", "ry", "rz"]
    }
}

/// A free body's table: mass or density, the lengths of its vectors, an inertia that
/// is positive definite, known and distinct locked degrees of freedom, no initial
/// velocity along a locked one, and its springs.
fn check_free(key: &str, f: &FreeConfig, d: usize) -> Result<()> {
    match (f.mass, f.density) {
        (Some(m), None) => positive(&format!("{key}.mass"), m)?,
        (None, Some(rho)) => positive(&format!("{key}.density"), rho)?,
        (None, None) => {
            return Err(SphError::invalid(
                format!("{key}.mass"),
                "none",
                "the body's mass, or its density",
            ))
        }
        (Some(_), Some(_)) => {
            return Err(SphError::invalid(
                format!("{key}.density"),
                "a density beside a mass",
                "either the mass or the density of the body, not both",
            ))
        }
    }
    for (name, v) in [("centre_of_mass", &f.centre_of_mass), ("hinge", &f.hinge)] {
        if let Some(v) = v {
            components(&format!("{key}.{name}"), v, d)?;
        }
    }
    if let Some(inertia) = &f.inertia {
        check_inertia(&format!("{key}.inertia"), inertia, d)?;
    }
    let dofs = degrees_of_freedom(d);
    let locked = f.locked.clone().unwrap_or_default();
    for (k, name) in locked.iter().enumerate() {
        if !dofs.contains(&name.as_str()) || locked[..k].contains(name) {
            return Err(SphError::invalid(
                format!("{key}.locked"),
                format!("{name:?}"),
                format!("distinct names among {dofs:?}"),
            ));
        }
    }
    let turns = if d == 2 { 1 } else { 3 };
    let rotations = &dofs[d..];
    if let Some(v) = &f.velocity {
        components(&format!("{key}.velocity"), v, d)?;
        for (axis, &speed) in dofs[..d].iter().zip(v) {
            let held = f.hinge.is_some() || locked.iter().any(|l| l == axis);
            if held && speed != 0.0 {
                return Err(SphError::invalid(
                    format!("{key}.velocity"),
                    format!("{v:?}"),
                    format!("no velocity along {axis}, which is held (locked or hinged)"),
                ));
            }
        }
    }
    if let Some(w) = &f.angular_velocity {
        let what = format!("{turns} component(s), finite");
        if w.len() != turns || w.iter().any(|v| !v.is_finite()) {
            return Err(SphError::invalid(
                format!("{key}.angular_velocity"),
                format!("{w:?}"),
                what,
            ));
        }
        for (axis, &rate) in rotations.iter().zip(w) {
            if rate != 0.0 && locked.iter().any(|l| l == axis) {
                return Err(SphError::invalid(
                    format!("{key}.angular_velocity"),
                    format!("{w:?}"),
                    format!("no rotation about {axis}, which is locked"),
                ));
            }
        }
    }
    for (k, spring) in f.springs.iter().flatten().enumerate() {
        check_spring(&format!("{key}.springs[{k}]"), spring, d)?;
    }
    Ok(())
}

/// An inertia of the dimension's shape, symmetric positive definite.
fn check_inertia(key: &str, v: &[f64], d: usize) -> Result<()> {
    let expected = if d == 2 {
        "one positive value (about z)"
    } else {
        "three positive values (about x, y, z) or six (Ixx, Iyy, Izz, Ixy, Ixz, Iyz) of a \
         positive-definite tensor"
    };
    let refuse = || SphError::invalid(key, format!("{v:?}"), expected);
    let fits = if d == 2 {
        v.len() == 1
    } else {
        v.len() == 3 || v.len() == 6
    };
    if !fits || v.iter().any(|x| !x.is_finite()) {
        return Err(refuse());
    }
    let tensor = crate::motion::free::inertia_tensor(v);
    if tensor.symmetric_eigenvalues().iter().any(|&e| e <= 0.0) {
        return Err(refuse());
    }
    Ok(())
}

/// A spring's ends, stiffness, damping and rest length.
fn check_spring(key: &str, s: &SpringConfig, d: usize) -> Result<()> {
    components(&format!("{key}.point"), &s.point, d)?;
    components(&format!("{key}.anchor"), &s.anchor, d)?;
    non_negative(&format!("{key}.stiffness"), s.stiffness)?;
    finite(&format!("{key}.stiffness"), s.stiffness)?;
    if let Some(l) = s.rest_length {
        non_negative(&format!("{key}.rest_length"), l)?;
    }
    if let Some(c) = s.damping {
        non_negative(&format!("{key}.damping"), c)?;
    }
    let length = (s.point.iter().zip(&s.anchor))
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>();
    if length == 0.0 {
        return Err(SphError::invalid(
            format!("{key}.anchor"),
            format!("{:?}", s.anchor),
            "an anchor apart from the point (the line's direction is undefined)",
        ));
    }
    Ok(())
}
