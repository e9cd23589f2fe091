//! Checks of the walls and what is measured on them: tank layers and faces, wall
//! boxes, body names, pressure sensors.

use crate::case::checks::{column_name, components, own_column_name, positive};
use crate::case::schema::*;
use crate::case::MAX_GAUGE_SAMPLES;
use crate::error::{Result, SphError};

impl Case {
    /// name once.
    pub(super) fn check_body_names(&self) -> Result<()> {
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
    pub(super) fn check_sensor(&self, k: usize) -> Result<()> {
        let sensors = &self.diagnostics.sensors;
        let s = &sensors[k];
        let key = |what: &str| format!("diagnostics.sensors[{k}].{what}");
        let earlier = sensors[..k].iter().map(|o| o.name.as_str());
        own_column_name(&key("name"), &s.name, earlier, "sensor")?;
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

    /// A gauge needs a plain name of its own, a horizontal position and a vertical
    /// line from bottom to top (its own or the domain's or tanks'), at most
    /// [`MAX_GAUGE_SAMPLES`] samples of Δx/4 long.
    pub(super) fn check_gauge(&self, k: usize) -> Result<()> {
        let gauges = &self.diagnostics.gauges;
        let g = &gauges[k];
        let key = |what: &str| format!("diagnostics.gauges[{k}].{what}");
        let earlier = gauges[..k].iter().map(|o| o.name.as_str());
        own_column_name(&key("name"), &g.name, earlier, "gauge")?;
        components(&key("position"), &g.position, self.dimension - 1)?;
        let Some([bottom, top]) = self.gauge_line(g) else {
            return Err(SphError::invalid(
                key("bottom"),
                "none",
                "the bottom and top of the gauge's line (no [domain] or [[tank]] gives them)",
            ));
        };
        let samples = (top - bottom) / (0.25 * self.dx());
        if !(bottom.is_finite() && top.is_finite() && samples >= 1.0) {
            return Err(SphError::invalid(
                key("top"),
                top,
                format!("a top above the bottom {bottom} by Δx/4 at least"),
            ));
        }
        if samples > MAX_GAUGE_SAMPLES as f64 {
            return Err(SphError::invalid(
                key("top"),
                top,
                format!(
                    "a line from the bottom {bottom} of at most {} samples of Δx/4",
                    MAX_GAUGE_SAMPLES
                ),
            ));
        }
        Ok(())
    }

    /// A section needs a plain name of its own and corners that span it
    /// ([`SectionConfig::check`]).
    pub(super) fn check_flow_section(&self, k: usize) -> Result<()> {
        let sections = &self.diagnostics.sections;
        let key = |what: &str| format!("diagnostics.sections[{k}].{what}");
        let earlier = sections[..k].iter().map(|o| o.name.as_str());
        own_column_name(&key("name"), &sections[k].name, earlier, "section")?;
        sections[k].check(&key("corners"), self.dimension, self.dx())
    }

    /// A rectangular face (3D only) needs a positive width and a direction `along` for
    /// its `size` side that is not the normal's.
    pub(super) fn check_rectangle(&self, k: usize, s: &SensorConfig) -> Result<()> {
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
    pub(super) fn check_tanks_open_along_periodic(
        &self,
        dom: &DomainConfig,
        d: usize,
    ) -> Result<()> {
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
    pub(super) fn check_tank_layers(&self, k: usize, t: &TankConfig) -> Result<()> {
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
    pub(super) fn check_wall_depth(&self, k: usize, b: &WallConfig) -> Result<()> {
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
}
