//! Checks of the `[[shape]]` tables that need no file: one geometry of the case's
//! dimension, positive sizes, and only the keys of its role.

use crate::case::checks::{check_box, components, finite, positive};
use crate::case::schema::Case;
use crate::case::shapes::{FileKind, Role, ShapeConfig};
use crate::error::{Result, SphError};

impl Case {
    /// The checks of one `[[shape]]` that need no file: one geometry of the case's
    /// dimension, positive sizes, and only the keys of its role.
    pub(in crate::case) fn check_shape(&self, k: usize, s: &ShapeConfig) -> Result<()> {
        let key = format!("shape[{k}]");
        let d = self.dimension;
        let geometry = s.geometry_keys();
        if geometry.len() != 1 {
            return Err(SphError::invalid(
                &key,
                format!("{geometry:?}"),
                "exactly one of polygon, file, circle, sphere, cylinder, box",
            ));
        }
        let only = |what: &str, dim: usize| -> Result<()> {
            if d == dim {
                return Ok(());
            }
            Err(SphError::invalid(
                format!("{key}.{what}"),
                "(set)",
                format!("a shape of a {d}D case ({what} is {dim}D only)"),
            ))
        };
        if let Some(vertices) = &s.polygon {
            only("polygon", 2)?;
            for (i, v) in vertices.iter().enumerate() {
                components(&format!("{key}.polygon[{i}]"), v, 2)?;
            }
        }
        if let Some(c) = &s.circle {
            only("circle", 2)?;
            components(&format!("{key}.circle.centre"), &c.centre, 2)?;
            positive(&format!("{key}.circle.radius"), c.radius)?;
        }
        if let Some(b) = &s.sphere {
            only("sphere", 3)?;
            components(&format!("{key}.sphere.centre"), &b.centre, 3)?;
            positive(&format!("{key}.sphere.radius"), b.radius)?;
        }
        if let Some(c) = &s.cylinder {
            only("cylinder", 3)?;
            components(&format!("{key}.cylinder.base"), &c.base, 3)?;
            components(&format!("{key}.cylinder.top"), &c.top, 3)?;
            positive(&format!("{key}.cylinder.radius"), c.radius)?;
            if c.base == c.top {
                return Err(SphError::invalid(
                    format!("{key}.cylinder.top"),
                    format!("{:?}", c.top),
                    "a point other than base (the axis runs from base to top)",
                ));
            }
        }
        if let Some(b) = &s.cuboid {
            check_box(&format!("{key}.box"), &b.lo, &b.hi, d)?;
        }
        if let Some(kind) = s.file_kind() {
            only("file", if kind == FileKind::Stl { 3 } else { 2 })?;
        }
        let drawing = matches!(s.file_kind(), Some(FileKind::Svg | FileKind::Dxf));
        if s.outline.is_some() && !drawing {
            return Err(SphError::invalid(
                format!("{key}.outline"),
                "(set)",
                "a file = \"*.svg\" or \"*.dxf\" beside it (outline picks an element or a \
                 layer of a drawing)",
            ));
        }
        positive(&format!("{key}.scale"), s.scale())?;
        self.check_role_keys(&key, s)
    }

    /// Walls take a name and layers, fluid a velocity and a hydrostatic start, cuts
    /// neither.
    pub(super) fn check_role_keys(&self, key: &str, s: &ShapeConfig) -> Result<()> {
        let wall_keys = [("name", s.name.is_some()), ("layers", s.layers.is_some())];
        let fluid_keys = [
            ("velocity", s.velocity.is_some()),
            ("hydrostatic", s.hydrostatic.is_some()),
            ("surface", s.surface.is_some()),
        ];
        let (wall_ok, fluid_ok) = (s.role == Role::Wall, s.role == Role::Fluid);
        let misplaced = wall_keys
            .iter()
            .filter(|_| !wall_ok)
            .chain(fluid_keys.iter().filter(|_| !fluid_ok))
            .find(|(_, set)| *set);
        if let Some((what, _)) = misplaced {
            let role = format!("{:?}", s.role).to_lowercase();
            return Err(SphError::invalid(
                format!("{key}.{what}"),
                "(set)",
                format!(
                    "no {what} for role = \"{role}\" (name and layers are for walls; velocity, \
                     hydrostatic and surface for fluid)"
                ),
            ));
        }
        if let Some(v) = &s.velocity {
            components(&format!("{key}.velocity"), v, self.dimension)?;
        }
        if let Some(h) = s.surface {
            finite(&format!("{key}.surface"), h)?;
        }
        let need = self.min_wall_layers();
        match s.layers {
            Some(n) if n < need => Err(SphError::invalid(
                format!("{key}.layers"),
                n,
                format!(
                    "at least {need} layers: layers·Δx must cover the kernel support R = {:.4} m",
                    self.support()
                ),
            )),
            _ => Ok(()),
        }
    }
}
