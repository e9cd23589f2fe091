//! Solids of any shape for `[[shape]]`: closed polygons (inline, or from a vertex
//! list, an SVG or a DXF drawing), STL surfaces, and the primitives circle, sphere, cylinder and box. Each
//! answers one query, the signed distance of a point to its surface (negative
//! inside), computed by parry (`parry2d-f64`, `parry3d-f64`): point projection on an
//! oriented polyline or triangle mesh, whose pseudo-normals tell inside from outside.
//!
//! What makes a surface unusable is refused with a one-line error naming the key:
//! an open, degenerate or self-intersecting polygon (`polygon`, `outline`), an STL
//! that is not closed or faces inwards (`mesh`).

mod dxf;
mod mesh;
mod outline;
mod polygon;
mod svg;

use crate::case::{Case, FileKind, ShapeConfig};
use crate::error::Result;
use parry2d_f64::shape as plane;
use parry3d_f64::shape as space;

/// A closed solid of the case's dimension.
pub struct Solid {
    surface: Surface,
    /// Bounding box.
    pub lo: Vec<f64>,
    pub hi: Vec<f64>,
}

enum Surface {
    Plane(Box<dyn plane::Shape>, parry2d_f64::math::Pose),
    Space(Box<dyn space::Shape>, parry3d_f64::math::Pose),
}

impl Solid {
    fn plane(shape: Box<dyn plane::Shape>, pose: parry2d_f64::math::Pose) -> Self {
        let aabb = shape.compute_aabb(&pose);
        Solid {
            lo: aabb.mins.to_array().to_vec(),
            hi: aabb.maxs.to_array().to_vec(),
            surface: Surface::Plane(shape, pose),
        }
    }

    fn space(shape: Box<dyn space::Shape>, pose: parry3d_f64::math::Pose) -> Self {
        let aabb = shape.compute_aabb(&pose);
        Solid {
            lo: aabb.mins.to_array().to_vec(),
            hi: aabb.maxs.to_array().to_vec(),
            surface: Surface::Space(shape, pose),
        }
    }

    /// Distance from `x` to the surface, negative inside the solid.
    pub fn signed_distance(&self, x: &[f64]) -> f64 {
        match &self.surface {
            Surface::Plane(shape, pose) => {
                let p = pose.inverse_transform_point(glam_2(x));
                shape.distance_to_local_point(p, false)
            }
            Surface::Space(shape, pose) => {
                let p = pose.inverse_transform_point(glam_3(x));
                shape.distance_to_local_point(p, false)
            }
        }
    }

    /// Length of the bounding box's diagonal.
    pub fn size(&self) -> f64 {
        self.lo
            .iter()
            .zip(&self.hi)
            .map(|(l, h)| (h - l).powi(2))
            .sum::<f64>()
            .sqrt()
    }
}

fn glam_2(x: &[f64]) -> parry2d_f64::math::Vector {
    parry2d_f64::math::Vector::new(x[0], x[1])
}

fn glam_3(x: &[f64]) -> parry3d_f64::math::Vector {
    parry3d_f64::math::Vector::new(x[0], x[1], x[2])
}

/// Builds the solid of `case.shape[k]` (validated: exactly one geometry key of the
/// case's dimension), reading its file if it has one.
pub fn build(case: &Case, k: usize) -> Result<Solid> {
    let s: &ShapeConfig = &case.shape[k];
    let key = format!("shape[{k}]");
    if let Some(vertices) = &s.polygon {
        let scaled: Vec<[f64; 2]> = vertices
            .iter()
            .map(|v| [v[0] * s.scale(), v[1] * s.scale()])
            .collect();
        return polygon::solid(&format!("{key}.polygon"), scaled);
    }
    if let Some(path) = &s.file {
        let key = format!("{key}.file");
        if case.dimension == 3 {
            return mesh::solid(&key, path, s.scale());
        }
        // curves become chords within Δx/100 of them, in the file's units
        let tolerance = 0.01 * case.dx() / s.scale();
        let outline = s.outline.as_deref();
        let vertices = match s.file_kind() {
            Some(FileKind::Svg) => svg::read(&key, path, outline, tolerance)?,
            Some(FileKind::Dxf) => dxf::read(&key, path, outline, tolerance)?,
            _ => polygon::read(&key, path)?,
        };
        let scaled = vertices
            .into_iter()
            .map(|[x, y]| [x * s.scale(), y * s.scale()])
            .collect();
        return polygon::solid(&key, scaled);
    }
    Ok(primitive(s))
}

/// The circle, sphere, cylinder or box of a shape (validated sizes).
fn primitive(s: &ShapeConfig) -> Solid {
    use parry2d_f64::math::Pose as Pose2;
    use parry3d_f64::math::{Pose as Pose3, Rot3 as Rot, Vector as V3};
    let k = s.scale();
    if let Some(c) = &s.circle {
        let centre = glam_2(&c.centre) * k;
        return Solid::plane(
            Box::new(plane::Ball::new(c.radius * k)),
            Pose2::from_translation(centre),
        );
    }
    if let Some(b) = &s.sphere {
        return Solid::space(
            Box::new(space::Ball::new(b.radius * k)),
            Pose3::from_translation(glam_3(&b.centre) * k),
        );
    }
    if let Some(c) = &s.cylinder {
        let (base, top) = (glam_3(&c.base) * k, glam_3(&c.top) * k);
        let axis = top - base;
        // parry's cylinder stands along its local y axis, centred on the origin
        let rotation = Rot::from_rotation_arc(V3::Y, axis.normalize());
        return Solid::space(
            Box::new(space::Cylinder::new(0.5 * axis.length(), c.radius * k)),
            Pose3::from_parts((base + top) * 0.5, rotation),
        );
    }
    let b = s.cuboid.as_ref().expect("validated: one geometry key");
    let (lo, hi): (Vec<f64>, Vec<f64>) = (
        b.lo.iter().map(|v| v * k).collect(),
        b.hi.iter().map(|v| v * k).collect(),
    );
    let half: Vec<f64> = lo.iter().zip(&hi).map(|(l, h)| 0.5 * (h - l)).collect();
    let centre: Vec<f64> = lo.iter().zip(&hi).map(|(l, h)| 0.5 * (h + l)).collect();
    if lo.len() == 2 {
        Solid::plane(
            Box::new(plane::Cuboid::new(glam_2(&half))),
            Pose2::from_translation(glam_2(&centre)),
        )
    } else {
        Solid::space(
            Box::new(space::Cuboid::new(glam_3(&half))),
            Pose3::from_translation(glam_3(&centre)),
        )
    }
}
