//! Applied loads and their generalized forces `Q = J_Xᵀ F`.

use nalgebra::DVector;

use super::{FullModel, Kinematics};
use crate::error::InputError;

/// A force applied at a point of the elastic axis. The model is planar in bending, so a force has
/// components in the `x–y` plane only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Force {
    /// Dead force: fixed global components `(fx, fy)` (N).
    Dead {
        /// Spanwise global component (N).
        fx: f64,
        /// Vertical global component (N).
        fy: f64,
    },
    /// Follower force, `F = f_t e(θ_k) + f_n n(θ_k)` in the frame of the element `k` carrying the
    /// point: it turns with the beam (the paper's eq. 15 is a normal follower force at the tip).
    Follower {
        /// Component along the element axis `e(θ_k)` (N).
        tangential: f64,
        /// Component along the element normal `n(θ_k)` (N).
        normal: f64,
    },
}

/// A load on the beam. `span` is the position along the undeformed elastic axis (m), in `[0, L]`.
/// A point that coincides with node `k` belongs to element `k` (the inboard one); at `span = 0` a
/// load goes straight into the clamp and does nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Load {
    /// A point force.
    PointForce {
        /// Position along the span (m).
        span: f64,
        /// The force.
        force: Force,
    },
    /// A bending moment about `ẑ` (N·m), applied to the element carrying `span`.
    Moment {
        /// Position along the span (m).
        span: f64,
        /// Moment (N·m), positive nose-up in the `x–y` plane.
        value: f64,
    },
    /// A torque about the beam axis (N·m), applied to the element carrying `span`.
    Torque {
        /// Position along the span (m).
        span: f64,
        /// Torque (N·m).
        value: f64,
    },
}

impl Load {
    /// Span position of the load (m).
    pub fn span(&self) -> f64 {
        match *self {
            Load::PointForce { span, .. }
            | Load::Moment { span, .. }
            | Load::Torque { span, .. } => span,
        }
    }
}

impl FullModel {
    /// Check `loads` against this model: positions inside the beam, finite values, no torque on a
    /// bending-only model. `field` prefixes the error's field name, e.g. `loads`.
    pub fn check_loads(&self, loads: &[Load], field: &str) -> Result<(), InputError> {
        let length = self.beam.length();
        for (i, load) in loads.iter().enumerate() {
            let f = |name: &str| format!("{field}[{i}].{name}");
            let span = load.span();
            if !span.is_finite() || span < 0.0 || span > length * (1.0 + 1e-12) {
                return Err(InputError::new(
                    f("span"),
                    format!("must lie on the beam, in [0, {length}] m, got {span}"),
                ));
            }
            let values: &[(&str, f64)] = match *load {
                Load::PointForce {
                    force: Force::Dead { fx, fy },
                    ..
                } => &[("fx", fx), ("fy", fy)],
                Load::PointForce {
                    force: Force::Follower { tangential, normal },
                    ..
                } => &[("tangential", tangential), ("normal", normal)],
                Load::Moment { value, .. } => &[("moment", value)],
                Load::Torque { value, .. } => &[("torque", value)],
            };
            for &(name, v) in values {
                if !v.is_finite() {
                    return Err(InputError::new(f(name), format!("must be finite, got {v}")));
                }
            }
            if matches!(load, Load::Torque { .. }) && !self.torsion {
                return Err(InputError::new(
                    f("torque"),
                    "the beam has no torsion data (GJ), so it cannot carry a torque",
                ));
            }
        }
        Ok(())
    }

    /// Generalized forces `Q(q)` of `loads` at the configuration `kin`, into `out`.
    /// Costs O(n + number of loads × n) and allocates nothing.
    ///
    /// # Panics
    /// If `out.len() != n_dofs()`.
    pub fn generalized_forces_kin_into(
        &self,
        kin: &Kinematics,
        loads: &[Load],
        out: &mut DVector<f64>,
    ) {
        let n = self.n;
        assert_eq!(
            out.len(),
            self.n_dofs(),
            "force buffer has the wrong length"
        );
        out.fill(0.0);
        // Accumulate the forces conjugate to the absolute angles, then Q = Tᵀ Q_abs.
        for load in loads {
            let (k, a) = self.locate(load.span());
            if k == 0 {
                continue;
            }
            match *load {
                Load::PointForce { force, .. } => {
                    let (c, s) = (kin.cos_theta[k - 1], kin.sin_theta[k - 1]);
                    let (fx, fy) = match force {
                        Force::Dead { fx, fy } => (fx, fy),
                        Force::Follower { tangential, normal } => {
                            (tangential * c - normal * s, tangential * s + normal * c)
                        }
                    };
                    // ∂X/∂θ_j = len_j n(θ_j).
                    for j in 0..k {
                        let len = if j + 1 == k { a } else { self.ell[j] };
                        out[j] += len * (-fx * kin.sin_theta[j] + fy * kin.cos_theta[j]);
                    }
                }
                Load::Moment { value, .. } => out[k - 1] += value,
                Load::Torque { value, .. } => out[n + k - 1] += value,
            }
        }
        let q = out.as_mut_slice();
        for block in q.chunks_mut(n) {
            for r in (0..n - 1).rev() {
                block[r] += block[r + 1];
            }
        }
    }
}
