//! VTK XML files for ParaView: one `.vtu` (unstructured grid) per frame and a `.pvd` collection
//! of the frames with their times ("VTK File Formats", VTK User's Guide 11th ed., Kitware 2010,
//! §19.3 "XML File Formats"; the `.pvd` collection of ParaView's readers). A frame is a chain of
//! points (the nodes) joined by line cells (the elements, VTK_LINE = 3) with point data:
//! scalars, vectors (3 components) or frames (3 × 3, 9 components, row-major). Written as ASCII
//! (`format="ascii"`): readable, diffable and read by every VTK reader and `meshio`; numbers in
//! Rust's shortest round-trip form, so a reader gets the values back to the last bit. The
//! binary (base64, appended) variant would be about 2.5× smaller; large runs have `.npz`.
//!
//! Generic over the geometry: the planar chain (`planar_frame`, `planar_mode_frame`) and the
//! 3-D chain give points and frames; the writer does not know which.

use std::fmt::Write as _;
use std::io;
use std::path::{Path, PathBuf};

/// Point data of a frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Data {
    /// One number per point.
    Scalars(Vec<f64>),
    /// Three components per point.
    Vectors(Vec<[f64; 3]>),
    /// A 3 × 3 matrix per point (a section frame: its rows the section axes), 9 components.
    Frames(Vec<[[f64; 3]; 3]>),
}

impl Data {
    fn components(&self) -> usize {
        match self {
            Data::Scalars(_) => 1,
            Data::Vectors(_) => 3,
            Data::Frames(_) => 9,
        }
    }
    fn len(&self) -> usize {
        match self {
            Data::Scalars(v) => v.len(),
            Data::Vectors(v) => v.len(),
            Data::Frames(v) => v.len(),
        }
    }
    fn values(&self) -> Box<dyn Iterator<Item = f64> + '_> {
        match self {
            Data::Scalars(v) => Box::new(v.iter().copied()),
            Data::Vectors(v) => Box::new(v.iter().flatten().copied()),
            Data::Frames(v) => Box::new(v.iter().flatten().flatten().copied()),
        }
    }
}

/// One frame: a time (or a load factor, a mode number), the points of the chain and their data.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// What the collection calls its `timestep`.
    pub time: f64,
    /// The points, in chain order (cells join consecutive points).
    pub points: Vec<[f64; 3]>,
    /// Named point data, one value per point.
    pub data: Vec<(String, Data)>,
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message)
}

/// Text safe inside an XML attribute.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// `values` as one line of ASCII numbers; a non-finite value is an error naming `what`.
fn numbers(out: &mut String, values: impl Iterator<Item = f64>, what: &str) -> io::Result<()> {
    for v in values {
        if !v.is_finite() {
            return Err(invalid(format!("{what}: non-finite value {v}")));
        }
        let _ = write!(out, "{v:?} ");
    }
    trim(out);
    Ok(())
}

/// Drop the space after a list of numbers.
fn trim(s: &mut String) {
    if s.ends_with(' ') {
        s.pop();
    }
}

/// The `.vtu` text of `frame`.
///
/// # Errors
/// Data of the wrong length, or a non-finite number (a file never holds `nan` or `inf`).
pub fn vtu(frame: &Frame) -> io::Result<String> {
    let n = frame.points.len();
    let cells = n.saturating_sub(1);
    let mut s = String::with_capacity(64 * n * (1 + frame.data.len()));
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n<UnstructuredGrid>\n",
    );
    let _ = writeln!(
        s,
        "<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{cells}\">"
    );
    s.push_str("<PointData>\n");
    for (name, data) in &frame.data {
        if data.len() != n {
            return Err(invalid(format!(
                "point data {name}: {} values for {n} points",
                data.len()
            )));
        }
        // Scalars without NumberOfComponents (VTK's default, 1): readers then give a column,
        // not an n × 1 array.
        let components = match data.components() {
            1 => String::new(),
            c => format!(" NumberOfComponents=\"{c}\""),
        };
        let _ = writeln!(
            s,
            "<DataArray type=\"Float64\" Name=\"{}\"{components} format=\"ascii\">",
            escape(name)
        );
        numbers(&mut s, data.values(), name)?;
        s.push_str("\n</DataArray>\n");
    }
    s.push_str("</PointData>\n<Points>\n");
    s.push_str("<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    numbers(&mut s, frame.points.iter().flatten().copied(), "points")?;
    s.push_str("\n</DataArray>\n</Points>\n<Cells>\n");
    s.push_str("<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for i in 0..cells {
        let _ = write!(s, "{i} {} ", i + 1);
    }
    trim(&mut s);
    s.push_str("\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for i in 0..cells {
        let _ = write!(s, "{} ", 2 * (i + 1));
    }
    trim(&mut s);
    s.push_str("\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for _ in 0..cells {
        s.push_str("3 ");
    }
    trim(&mut s);
    s.push_str("\n</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    Ok(s)
}

/// The `.pvd` text of a collection: `(time, file name relative to the .pvd)` per frame.
pub fn pvd(entries: &[(f64, String)]) -> io::Result<String> {
    let mut s = String::from("<?xml version=\"1.0\"?>\n");
    s.push_str("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
    s.push_str("<Collection>\n");
    for (t, file) in entries {
        if !t.is_finite() {
            return Err(invalid(format!("{file}: non-finite time {t}")));
        }
        let _ = writeln!(
            s,
            "<DataSet timestep=\"{t:?}\" group=\"\" part=\"0\" file=\"{}\"/>",
            escape(file)
        );
    }
    s.push_str("</Collection>\n</VTKFile>\n");
    Ok(s)
}

/// Write `frames` into `dir` (created if needed) as `STEM_0000.vtu`, `STEM_0001.vtu`, … and
/// the collection `STEM.pvd`, each atomically, the `.pvd` last: a collection exists only when
/// every file it names does. Returns the `.pvd`'s path.
pub fn write_series(dir: &Path, stem: &str, frames: &[Frame]) -> io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let width = frames.len().saturating_sub(1).to_string().len().max(4);
    let mut entries = Vec::with_capacity(frames.len());
    for (k, frame) in frames.iter().enumerate() {
        let name = format!("{stem}_{k:0width$}.vtu");
        let text = vtu(frame).map_err(|e| invalid(format!("{name}: {e}")))?;
        crate::write_bytes(&dir.join(&name), text.as_bytes())?;
        entries.push((frame.time, name));
    }
    let path = dir.join(format!("{stem}.pvd"));
    crate::write_bytes(&path, pvd(&entries)?.as_bytes())?;
    Ok(path)
}

/// A frame of the planar chain: the deformed nodes `(x, y)` as points (`z = 0`), with point data
/// `displacement` (from the undeformed nodes `reference`) and `twist` (rad).
pub fn planar_frame(
    time: f64,
    x: &[f64],
    y: &[f64],
    twist: &[f64],
    reference: &[[f64; 3]],
) -> Frame {
    let points: Vec<[f64; 3]> = x.iter().zip(y).map(|(&x, &y)| [x, y, 0.0]).collect();
    let displacement = points
        .iter()
        .zip(reference)
        .map(|(p, r)| [p[0] - r[0], p[1] - r[1], p[2] - r[2]])
        .collect();
    Frame {
        time,
        points,
        data: vec![
            ("displacement".into(), Data::Vectors(displacement)),
            ("twist".into(), Data::Scalars(twist.to_vec())),
        ],
    }
}

/// A mode shape of the planar chain: the undeformed nodes `reference` as points, the shape's
/// nodal displacements `(dx, dy)` as `displacement` (ParaView: Warp By Vector) and its `twist`.
pub fn planar_mode_frame(
    number: f64,
    dx: &[f64],
    dy: &[f64],
    twist: &[f64],
    reference: &[[f64; 3]],
) -> Frame {
    Frame {
        time: number,
        points: reference.to_vec(),
        data: vec![
            (
                "displacement".into(),
                Data::Vectors(dx.iter().zip(dy).map(|(&a, &b)| [a, b, 0.0]).collect()),
            ),
            ("twist".into(), Data::Scalars(twist.to_vec())),
        ],
    }
}

/// Per node, the value of the element inboard of it (the root node: the first element's): the
/// 3-D chain's element data as point data.
fn per_node<T: Copy>(elements: &[T], nodes: usize) -> Vec<T> {
    (0..nodes).map(|k| elements[k.saturating_sub(1)]).collect()
}

/// A frame of the 3-D chain: the deformed nodes `position` as points, with point data
/// `displacement` (from the undeformed nodes `reference`), the section `rotation` vector (rad)
/// and the section axes `t` (along the reference axis), `n` (normal) and `c` (chord, toward
/// the leading edge) as unit vectors: the columns of each `frames` matrix. `rotation` and
/// `frames` are the elements' (one fewer than the nodes); node `k` carries the element inboard
/// of it, the root node the first element's.
pub fn spatial_frame(
    time: f64,
    position: &[[f64; 3]],
    rotation: &[[f64; 3]],
    frames: &[[[f64; 3]; 3]],
    reference: &[[f64; 3]],
) -> Frame {
    let nodes = position.len();
    let displacement = position
        .iter()
        .zip(reference)
        .map(|(p, r)| [p[0] - r[0], p[1] - r[1], p[2] - r[2]])
        .collect();
    let mut data = vec![
        ("displacement".to_string(), Data::Vectors(displacement)),
        (
            "rotation".to_string(),
            Data::Vectors(per_node(rotation, nodes)),
        ),
    ];
    let frames = per_node(frames, nodes);
    for (j, axis) in ["t", "n", "c"].iter().enumerate() {
        let v = frames.iter().map(|f| [f[0][j], f[1][j], f[2][j]]).collect();
        data.push(((*axis).to_string(), Data::Vectors(v)));
    }
    Frame {
        time,
        points: position.to_vec(),
        data,
    }
}

/// A mode shape of the 3-D chain: the undeformed nodes `reference` as points, the nodal
/// displacements as `displacement` (ParaView: Warp By Vector) and the elements' small section
/// rotations as `rotation` (per point as in [`spatial_frame`]).
pub fn spatial_mode_frame(
    number: f64,
    displacement: &[[f64; 3]],
    rotation: &[[f64; 3]],
    reference: &[[f64; 3]],
) -> Frame {
    Frame {
        time: number,
        points: reference.to_vec(),
        data: vec![
            ("displacement".into(), Data::Vectors(displacement.to_vec())),
            (
                "rotation".into(),
                Data::Vectors(per_node(rotation, reference.len())),
            ),
        ],
    }
}

/// The undeformed nodes of a straight planar chain at the stations `x` (m).
pub fn straight(x: &[f64]) -> Vec<[f64; 3]> {
    x.iter().map(|&x| [x, 0.0, 0.0]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_has_lines_between_consecutive_points_and_refuses_non_finite_data() {
        let f = planar_frame(
            0.5,
            &[0.0, 1.0, 2.0],
            &[0.0, 0.1, 0.3],
            &[0.0; 3],
            &straight(&[0.0, 1.0, 2.0]),
        );
        let text = vtu(&f).unwrap();
        assert!(text.contains("NumberOfPoints=\"3\" NumberOfCells=\"2\""));
        assert!(text.contains("\n0 1 1 2\n"), "{text}");
        assert!(text.contains("\n2 4\n"));
        assert!(
            text.contains("\n0.0 0.0 0.0 0.0 0.1 0.0 0.0 0.3 0.0\n"),
            "{text}"
        );
        let mut bad = f.clone();
        bad.data[1].1 = Data::Scalars(vec![0.0, f64::NAN, 0.0]);
        assert!(vtu(&bad)
            .unwrap_err()
            .to_string()
            .contains("twist: non-finite"));
        bad.data[1].1 = Data::Scalars(vec![0.0]);
        assert!(vtu(&bad)
            .unwrap_err()
            .to_string()
            .contains("1 values for 3 points"));
        let p = pvd(&[(0.0, "a_0000.vtu".into()), (0.5, "a_0001.vtu".into())]).unwrap();
        assert!(p.contains("timestep=\"0.5\" group=\"\" part=\"0\" file=\"a_0001.vtu\""));
    }
}
