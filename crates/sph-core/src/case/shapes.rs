//! The `[[shape]]` table: a solid of any shape (a polygon, an STL surface, a circle,
//! sphere, cylinder or box) and the role it plays in the case: fluid filled on the
//! lattice, a wall of dummy particles, or a hole cut out of the fluid. Its geometry is
//! built and checked in [`crate::geometry::solid`].

use super::motion::{FreeConfig, MotionChoice, PrescribedConfig};
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
    /// Centre \[m\].
    pub centre: Vec<f64>,
    /// Radius \[m\].
    pub radius: f64,
}

/// A circular cylinder (3D) between the centres of its two end faces.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CylinderConfig {
    /// Centre of one end face \[m\].
    pub base: Vec<f64>,
    /// Centre of the other end face \[m\].
    pub top: Vec<f64>,
    /// Radius \[m\].
    pub radius: f64,
}

/// An axis-aligned box.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CuboidConfig {
    /// Lower corner \[m\].
    pub lo: Vec<f64>,
    /// Upper corner \[m\].
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
    /// How the wall moves (walls only): "fixed", "prescribed" (then its `prescribed` table
    /// gives the motion) or "free" (a floating body: its `free` table). Default: "fixed".
    #[serde(default)]
    pub motion: Option<MotionChoice>,
    /// The motion when `motion = "prescribed"`.
    #[serde(default)]
    pub prescribed: Option<PrescribedConfig>,
    /// The body when `motion = "free"`.
    #[serde(default)]
    pub free: Option<FreeConfig>,
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
