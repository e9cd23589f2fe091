//! The `[[shape]]` table: a solid of any shape (a polygon, an STL surface, a circle,
//! sphere, cylinder or box) and the role it plays in the case: fluid filled on the
//! lattice, a wall of dummy particles, or a hole cut out of the fluid. Its geometry is
//! built and checked in [`crate::geometry::solid`].

use super::schema::Case;
use super::validate::{check_box, components, finite, positive};
use crate::error::{Result, SphError};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What a shape is in the case.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Fluid on the lattice points inside the solid, hydrostatic by default.
    Fluid,
    /// Dummy wall particles on the lattice points inside the solid, down to `layers`
    /// spacings below its surface. The fluid it overlaps is removed, to half a spacing
    /// from its surface.
    Wall,
    /// Removes the fluid of every fluid block and fluid shape inside it.
    Cut,
}

/// What a shape's file holds, told by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// `.stl`: a triangulated surface (3D).
    Stl,
    /// `.svg`: a drawing with an outline element (2D).
    Svg,
    /// `.dxf`: a drawing with a 2D polyline (2D).
    Dxf,
    /// Anything else: a vertex list (2D).
    Vertices,
}

/// A disc (2D) or ball (3D).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BallConfig {
    /// Centre [m].
    pub centre: Vec<f64>,
    /// Radius [m].
    pub radius: f64,
}

/// A circular cylinder (3D) between the centres of its two end faces.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CylinderConfig {
    /// Centre of one end face [m].
    pub base: Vec<f64>,
    /// Centre of the other end face [m].
    pub top: Vec<f64>,
    /// Radius [m].
    pub radius: f64,
}

/// An axis-aligned box.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CuboidConfig {
    /// Lower corner [m].
    pub lo: Vec<f64>,
    /// Upper corner [m].
    pub hi: Vec<f64>,
}

/// One `[[shape]]`: exactly one of the geometry keys (`polygon`, `file`, `circle`,
/// `sphere`, `cylinder`, `box`) and the keys of its role.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShapeConfig {
    /// What the shape is. Shapes use the lattice (k+½)Δx from the origin, so fluid and
    /// wall particles share one lattice (fluid blocks share it when their `lo` is a
    /// multiple of Δx).
    pub role: Role,
    /// 2D: the vertices of a closed polygon, `[[x, y], ...]`, in either winding; the
    /// last vertex joins the first. Fewer than 3 distinct vertices, no area or crossing
    /// edges are refused. A shape takes exactly one geometry key: `polygon`, `file`,
    /// `circle`, `sphere`, `cylinder` or `box`.
    #[serde(default)]
    pub polygon: Option<Vec<Vec<f64>>>,
    /// A file: `.stl` (3D, ASCII or binary, closed and outward-facing); in 2D an
    /// `.svg` drawing (one `path`, `polygon`, `polyline` or `rect` element; SVG's
    /// downward y axis is turned up, so the shape looks as drawn), a `.dxf` drawing
    /// (one closed `LWPOLYLINE` or 2D `POLYLINE`, bulges as arcs), or any other name a
    /// vertex list, one `x y` or `x, y` pair a line, `#` comments. Curves become chords
    /// within Δx/100. A relative path is taken from the case file's folder.
    #[serde(default)]
    pub file: Option<String>,
    /// Which outline of an `.svg` or `.dxf` file: the SVG element's `id`, or the DXF
    /// layer. Default: the drawing's only outline.
    #[serde(default)]
    pub outline: Option<String>,
    /// 2D disc.
    #[serde(default)]
    pub circle: Option<BallConfig>,
    /// 3D ball.
    #[serde(default)]
    pub sphere: Option<BallConfig>,
    /// 3D cylinder.
    #[serde(default)]
    pub cylinder: Option<CylinderConfig>,
    /// Axis-aligned box (2D or 3D).
    #[serde(default, rename = "box")]
    pub cuboid: Option<CuboidConfig>,
    /// Factor from the file's or polygon's units to metres (0.001 for millimetres); a
    /// shape 100× larger than the rest of the case is refused as a suspected unit
    /// mismatch. Default: 1.
    #[serde(default)]
    pub scale: Option<f64>,
    /// Name of the body in the loads' columns (walls only). Default: `shape<k>`.
    #[serde(default)]
    pub name: Option<String>,
    /// Wall layers (walls only), at least enough to cover R; the solid must be at least
    /// that thick. Default: the fewest that cover the kernel support.
    #[serde(default)]
    pub layers: Option<usize>,
    /// Initial velocity [m/s] (fluid only). Default: at rest.
    #[serde(default)]
    pub velocity: Option<Vec<f64>>,
    /// Hydrostatic start from the shape's top, or from `surface` (fluid only). Default:
    /// true.
    #[serde(default)]
    pub hydrostatic: Option<bool>,
    /// Height (along -g) of the free surface of the hydrostatic start (fluid only).
    /// Default: the shape's top.
    #[serde(default)]
    pub surface: Option<f64>,
}

impl ShapeConfig {
    /// The geometry keys that are set.
    pub fn geometry_keys(&self) -> Vec<&'static str> {
        [
            ("polygon", self.polygon.is_some()),
            ("file", self.file.is_some()),
            ("circle", self.circle.is_some()),
            ("sphere", self.sphere.is_some()),
            ("cylinder", self.cylinder.is_some()),
            ("box", self.cuboid.is_some()),
        ]
        .into_iter()
        .filter_map(|(key, set)| set.then_some(key))
        .collect()
    }

    /// What the shape's file holds, if it has one.
    pub fn file_kind(&self) -> Option<FileKind> {
        let path = std::path::Path::new(self.file.as_deref()?);
        let extension = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        Some(match extension.as_deref() {
            Some("stl") => FileKind::Stl,
            Some("svg") => FileKind::Svg,
            Some("dxf") => FileKind::Dxf,
            _ => FileKind::Vertices,
        })
    }

    /// The scale factor in force (1 unless set).
    pub fn scale(&self) -> f64 {
        self.scale.unwrap_or(1.0)
    }
}

impl Case {
    /// The checks of one `[[shape]]` that need no file: one geometry of the case's
    /// dimension, positive sizes, and only the keys of its role.
    pub(super) fn check_shape(&self, k: usize, s: &ShapeConfig) -> Result<()> {
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
    fn check_role_keys(&self, key: &str, s: &ShapeConfig) -> Result<()> {
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

impl ShapeConfig {
    /// Wall layers of this shape: as given, or [`Case::min_wall_layers`].
    pub fn layer_count(&self, case: &Case) -> usize {
        self.layers.unwrap_or_else(|| case.min_wall_layers())
    }
}
