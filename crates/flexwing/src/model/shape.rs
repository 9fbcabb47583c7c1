//! The deformed shape of the full model: node positions on the elastic axis and the twist at
//! each node (docs/model.md, "Frames and coordinates"), from the joint rotations `q`. Every
//! result that shows a deformed beam (static equilibria, dynamic snapshots, tip histories) is
//! built here.

use super::FullModel;

/// The deformed elastic axis: node positions and nodal twists. Zeros carry no sign (`-0.0` is
/// stored as `0.0`), so that outputs never print a negative zero.
#[derive(Debug, Clone, PartialEq)]
pub struct Shape {
    /// Node positions `x_0 … x_n` (m).
    pub x: Vec<f64>,
    /// Node positions `y_0 … y_n` (m).
    pub y: Vec<f64>,
    /// Twist at each node (rad): that of the element inboard of it, 0 at the clamp; all zeros
    /// in a bending-only model.
    pub twist: Vec<f64>,
}

impl Shape {
    /// Tip position and twist `(x, y, twist)`.
    pub fn tip(&self) -> (f64, f64, f64) {
        let n = self.x.len() - 1;
        (self.x[n], self.y[n], self.twist[n])
    }
}

/// `v` without the sign of a zero.
fn unsigned_zero(v: f64) -> f64 {
    v + 0.0
}

impl FullModel {
    /// The deformed shape at joint rotations `q`.
    ///
    /// # Panics
    /// If `q.len() != self.n_dofs()`.
    ///
    /// ```
    /// let model = flexwing::paper::table4_beam(4)?;
    /// let shape = model.shape(&[0.0; 4]);
    /// assert_eq!(shape.tip(), (1.0, 0.0, 0.0));
    /// # Ok::<(), flexwing::InputError>(())
    /// ```
    pub fn shape(&self, q: &[f64]) -> Shape {
        let kin = self.kinematics(q);
        let nodes = self.node_positions(&kin);
        let twist = (0..nodes.len())
            .map(|k| {
                if k == 0 || !self.has_torsion() {
                    0.0
                } else {
                    unsigned_zero(kin.psi[k - 1])
                }
            })
            .collect();
        Shape {
            x: nodes.iter().map(|p| unsigned_zero(p[0])).collect(),
            y: nodes.iter().map(|p| unsigned_zero(p[1])).collect(),
            twist,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::paper::table1_beam;

    #[test]
    fn shape_of_a_rotated_root_and_a_twist() {
        let model = table1_beam(2).unwrap();
        // Root bending joint at 90°, tip torsion joint at 0.1 rad.
        let q = [std::f64::consts::FRAC_PI_2, 0.0, 0.0, 0.1];
        let s = model.shape(&q);
        // Each element is 8 m long; both point along +y (cos(π/2) ≈ 6e-17).
        assert!(s.x.iter().all(|x| x.abs() < 1e-15), "{:?}", s.x);
        assert_eq!(s.y, [0.0, 8.0, 16.0]);
        assert_eq!(s.twist, [0.0, 0.0, 0.1]);
        assert_eq!(s.tip().2, 0.1);
        assert!(s
            .x
            .iter()
            .chain(&s.y)
            .all(|v| v.is_sign_positive() || *v != 0.0));
    }
}
