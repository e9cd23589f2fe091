//! Value checks beyond types: ranges, component counts, boxes, the particle budget and
//! the scheme's options. Checks that need the particles (overlaps, probes against the
//! domain, initial fields against the fluid they fill) run when the case is built
//! ([`crate::geometry`]).

mod bodies;
mod initial;
mod motion;
mod open_boundaries;
mod scheme;
mod shapes;
#[cfg(test)]
mod tests;

use super::checks::*;
use super::schema::*;
use super::shapes::Role;
use crate::error::{Result, SphError};

impl Case {
    /// Value checks beyond types; geometry checks that need particles happen when building.
    pub fn validate(&self) -> Result<()> {
        self.validate_particles_and_fluid()?;
        self.validate_regions()?;
        self.validate_tanks()?;
        self.validate_motions()?;
        self.validate_domain()?;
        self.validate_initial()?;
        self.validate_forcing()?;
        self.validate_absorbers()?;
        self.check_particle_count()?;
        self.validate_scheme()?;
        self.validate_run_controls()?;
        self.validate_diagnostics()
    }

    /// Dimension, name, spacing, h/Δx and the fluid's constants.
    fn validate_particles_and_fluid(&self) -> Result<()> {
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
        Ok(())
    }

    /// Some fluid, and each shape, open boundary, fluid block and wall box.
    fn validate_regions(&self) -> Result<()> {
        let d = self.dimension;
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
        Ok(())
    }

    /// Each tank's box, layers, open faces and lid.
    fn validate_tanks(&self) -> Result<()> {
        let d = self.dimension;
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
        Ok(())
    }

    /// The `[domain]` box and its periodic axes.
    fn validate_domain(&self) -> Result<()> {
        let d = self.dimension;
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
        Ok(())
    }

    /// End time, output intervals and the stability guard's limits.
    fn validate_run_controls(&self) -> Result<()> {
        positive("time.end", self.time.end)?;
        non_negative("time.output_interval", self.time.output_interval)?;
        positive(
            "stability.max_density_variation",
            self.stability.max_density_variation,
        )?;
        non_negative("stability.transient", self.stability.transient)?;
        positive("stability.max_mach", self.stability.max_mach)?;
        if let Some(i) = self.output.restart_interval {
            positive("output.restart_interval", i)?;
        }
        if let Some(level) = self.output.compression.filter(|&l| l > 9) {
            return Err(SphError::invalid(
                "output.compression",
                level,
                "a deflate level from 0 (none) to 9",
            ));
        }
        Ok(())
    }

    /// Series interval, probes, moment point, reference scales, sensors, body names and
    /// the surge front's axis.
    fn validate_diagnostics(&self) -> Result<()> {
        let d = self.dimension;
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
        for k in 0..self.diagnostics.gauges.len() {
            self.check_gauge(k)?;
        }
        for k in 0..self.diagnostics.sections.len() {
            self.check_flow_section(k)?;
        }
        if let Some(level) = self.diagnostics.still_level {
            finite("diagnostics.still_level", level)?;
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
}
