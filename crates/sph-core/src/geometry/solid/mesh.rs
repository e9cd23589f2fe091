//! STL surfaces (ASCII or binary, read by `stl_io`): closed, consistently wound and
//! facing outwards, as parry's oriented triangle mesh needs to tell inside from
//! outside.

use super::Solid;
use crate::error::{Result, SphError};
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::shape::{TriMesh, TriMeshFlags};

/// The solid an STL file bounds, its coordinates times `scale`.
pub(super) fn solid(key: &str, path: &str, scale: f64) -> Result<Solid> {
    let refuse = |expected: String| SphError::invalid(key, format!("{path:?}"), expected);
    let mut file =
        std::fs::File::open(path).map_err(|e| refuse(format!("a readable STL file ({e})")))?;
    let mesh = stl_io::read_stl(&mut file)
        .map_err(|e| refuse(format!("an ASCII or binary STL file ({e})")))?;
    if mesh.faces.is_empty() {
        return Err(refuse("an STL surface with triangles".into()));
    }
    mesh.validate().map_err(|e| {
        refuse(format!(
            "a closed (watertight), consistently wound STL surface: {e}"
        ))
    })?;
    let vertices: Vec<Vector> = mesh
        .vertices
        .iter()
        .map(|v| Vector::new(v[0] as f64, v[1] as f64, v[2] as f64) * scale)
        .collect();
    let triangles: Vec<[u32; 3]> = mesh
        .faces
        .iter()
        .map(|f| f.vertices.map(|i| i as u32))
        .collect();
    if signed_volume(&vertices, &triangles) <= 0.0 {
        return Err(refuse(
            "an STL surface whose normals face outwards (its triangles wind clockwise seen \
             from outside: inverted normals)"
                .into(),
        ));
    }
    let trimesh = TriMesh::with_flags(vertices, triangles, TriMeshFlags::ORIENTED)
        .map_err(|e| refuse(format!("a triangle mesh parry accepts ({e})")))?;
    Ok(Solid::space(Box::new(trimesh), Pose::IDENTITY))
}

/// Volume enclosed by a closed surface, positive when its triangles wind
/// counter-clockwise seen from outside: `V = Σ a·(b×c)/6` (divergence theorem).
fn signed_volume(v: &[Vector], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| v[i as usize]);
            a.dot(b.cross(c))
        })
        .sum::<f64>()
        / 6.0
}
