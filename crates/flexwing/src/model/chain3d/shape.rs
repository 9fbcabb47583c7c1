//! The deformed 3-D chain for output: node positions and element section frames, the data a
//! front end needs for tables, plots and VTK ribbons (node `x, y, z` and the section rotation).

use super::rotation::rotation_vector;

/// The deformed chain: node positions and section frames. Zeros carry no sign.
#[derive(Debug, Clone, PartialEq)]
pub struct Shape3d {
    /// Node stations along the reference axis `s_0 = 0 … s_n = L` (m).
    pub span: Vec<f64>,
    /// Node positions `P_0 … P_n` (m), global `(x, y, z)`.
    pub position: Vec<[f64; 3]>,
    /// Section frame of each element, `R_i` with columns `t, n, c` (global components).
    pub frames: Vec<[[f64; 3]; 3]>,
}

fn unsigned(v: f64) -> f64 {
    v + 0.0
}

impl Shape3d {
    pub(crate) fn new(span: Vec<f64>, position: Vec<[f64; 3]>, frames: Vec<[[f64; 3]; 3]>) -> Self {
        Self {
            span,
            position: position.iter().map(|p| p.map(unsigned)).collect(),
            frames: frames.iter().map(|f| f.map(|r| r.map(unsigned))).collect(),
        }
    }

    /// Tip position `P_n` (m).
    pub fn tip(&self) -> [f64; 3] {
        self.position[self.position.len() - 1]
    }

    /// Each element's section rotation as a rotation vector (rad, global components): `R_i =
    /// exp(r̂_i)`, the rotation from the global axes `(x, y, z)` to `(t, n, c)`.
    pub fn rotation_vectors(&self) -> Vec<[f64; 3]> {
        self.frames.iter().map(rotation_vector).collect()
    }
}
