//! Meshes as VTK XML PolyData (`.vtp`, one file per time) and the ParaView collection
//! (`.pvd`) that lists them in time order: the formats ParaView, VisIt and pyvista
//! open without a plugin. ASCII, so that a file can be read by eye and diffed; written
//! atomically ([`super::atomic`]).

use super::atomic;
use super::snapshot::CREATOR;
use crate::error::Result;
use std::fmt::Write as _;
use std::path::Path;

/// What a mesh's cells are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cells {
    /// Polylines (VTK `Lines`).
    Lines,
    /// Polygons (VTK `Polys`): triangles here.
    Polygons,
}

/// A mesh to write: points (z = 0 in 2D), cells as lists of point indices, scalar
/// point data by name, and the time it shows.
pub struct PolyData<'a> {
    pub points: &'a [[f64; 3]],
    pub cells: &'a [Vec<u32>],
    pub kind: Cells,
    pub point_data: &'a [(&'a str, &'a [f64])],
    pub time: f64,
}

/// The first lines of every `.vtp` file this module writes (how a tool recognises its
/// own files before replacing them).
pub fn header(what: &str) -> String {
    format!("<?xml version=\"1.0\"?>\n<!-- {CREATOR}: {what} -->\n")
}

impl PolyData<'_> {
    /// The VTK XML text, after `header(what)`.
    pub fn to_xml(&self, what: &str) -> String {
        let (n, m) = (self.points.len(), self.cells.len());
        let (lines, polys) = match self.kind {
            Cells::Lines => (m, 0),
            Cells::Polygons => (0, m),
        };
        let mut s = header(what);
        s +=
            "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n<PolyData>\n";
        s += "<FieldData>\n";
        s += &array("Float64", "TimeValue", 1, &format!("{:e}", self.time));
        s += "</FieldData>\n";
        let _ = writeln!(
            s,
            "<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"0\" NumberOfLines=\"{lines}\" \
             NumberOfStrips=\"0\" NumberOfPolys=\"{polys}\">"
        );
        s += "<PointData>\n";
        for (name, values) in self.point_data {
            s += &array(
                "Float64",
                name,
                1,
                &join(values.iter().map(|v| format!("{v:e}"))),
            );
        }
        s += "</PointData>\n<Points>\n";
        let coordinates = self.points.iter().flatten().map(|v| format!("{v:e}"));
        s += &array("Float64", "Points", 3, &join(coordinates));
        s += "</Points>\n";
        let tag = match self.kind {
            Cells::Lines => "Lines",
            Cells::Polygons => "Polys",
        };
        let connectivity = self.cells.iter().flatten().map(u32::to_string);
        let offsets = self.cells.iter().scan(0, |end, c| {
            *end += c.len();
            Some(end.to_string())
        });
        let _ = writeln!(s, "<{tag}>");
        s += &array("Int64", "connectivity", 1, &join(connectivity));
        s += &array("Int64", "offsets", 1, &join(offsets));
        let _ = writeln!(s, "</{tag}>");
        s + "</Piece>\n</PolyData>\n</VTKFile>\n"
    }

    /// Writes the mesh to `path` (atomically).
    pub fn write(&self, path: &Path, what: &str) -> Result<()> {
        let text = self.to_xml(what);
        atomic::write(path, |tmp| std::fs::write(tmp, &text))
    }
}

/// A ParaView collection listing `(time, file)` pairs, the files relative to it.
pub fn write_collection(path: &Path, entries: &[(f64, String)]) -> Result<()> {
    let mut s = format!(
        "<?xml version=\"1.0\"?>\n<!-- {CREATOR} -->\n<VTKFile type=\"Collection\" \
         version=\"0.1\">\n<Collection>\n"
    );
    for (time, file) in entries {
        let _ = writeln!(s, "<DataSet timestep=\"{time:e}\" file=\"{file}\"/>");
    }
    s += "</Collection>\n</VTKFile>\n";
    atomic::write(path, |tmp| std::fs::write(tmp, &s))
}

fn array(ty: &str, name: &str, components: usize, values: &str) -> String {
    format!(
        "<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{components}\" \
         format=\"ascii\">\n{values}\n</DataArray>\n"
    )
}

fn join(values: impl Iterator<Item = String>) -> String {
    values.collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_and_a_polyline_are_written_as_vtk_reads_them() {
        let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let cells = [vec![0, 1, 2], vec![2, 0]];
        let mesh = PolyData {
            points: &points,
            cells: &cells,
            kind: Cells::Lines,
            point_data: &[("wall_fraction", &[0.0, 0.5, 0.25])],
            time: 0.5,
        };
        let xml = mesh.to_xml("test");
        assert!(xml.starts_with(&header("test")));
        assert!(xml.contains("NumberOfPoints=\"3\""));
        assert!(xml.contains("NumberOfLines=\"2\""));
        assert!(xml.contains("<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\""));
        assert!(xml.contains(">\n0 1 2 2 0\n</DataArray>"));
        assert!(xml.contains(">\n3 5\n</DataArray>"));
        assert!(xml.contains(">\n0e0 5e-1 2.5e-1\n</DataArray>"));
    }
}
