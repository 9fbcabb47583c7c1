//! Applied loads, their generalized forces `Q = J_Xᵀ F` and the load Jacobian `∂Q/∂q`.
//!
//! Loads are first resolved against a model ([`FullModel::apply`]) into per-element items; each
//! item remembers which user load it came from, so that every load can be scaled by its own factor
//! (a load-stepping factor in statics, a time function in dynamics): `Q(q) = Σ_k s_k Q_k(q)`.
//!
//! Everything is accumulated in absolute angles `(θ, ψ)` and transformed with `Q = Tᵀ Q_abs`,
//! `∂Q/∂q = Tᵀ (∂Q_abs/∂(θ, ψ)) T` (suffix sums), as the mass matrix.

use nalgebra::{DMatrix, DVector};

use super::{suffix_sum_blocks, FullModel, Kinematics};
use crate::beam::Profile;
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

/// A force per unit length over the whole span (N/m), each component uniform or tabulated.
/// It is lumped per element at the element midpoint (midpoint rule for the point of application,
/// exact integral of the profile over the element for the resultant).
#[derive(Debug, Clone, PartialEq)]
pub enum DistributedForce {
    /// Fixed global direction.
    Dead {
        /// Spanwise global component (N/m).
        fx: Profile,
        /// Vertical global component (N/m).
        fy: Profile,
    },
    /// In the local frame of each element (e.g. a pressure normal to the deformed beam).
    Follower {
        /// Component along the element axis (N/m).
        tangential: Profile,
        /// Component along the element normal (N/m).
        normal: Profile,
    },
}

/// A load on the beam. `span` is the position along the undeformed elastic axis (m), in `[0, L]`.
/// A point that coincides with node `k` belongs to element `k` (the inboard one); at `span = 0` a
/// load goes straight into the clamp and does nothing.
#[derive(Debug, Clone, PartialEq)]
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
    /// A distributed force over the span.
    Distributed(DistributedForce),
    /// Gravity, acceleration `g` (m/s²) along `−y`, acting at every element's mass centre.
    Gravity {
        /// Gravitational acceleration (m/s²), e.g. 9.80665.
        g: f64,
    },
}

/// Loads resolved against one model: per-element items, each tagged with its user load.
#[derive(Debug, Clone, PartialEq)]
pub struct AppliedLoads {
    items: Vec<Item>,
    n_loads: usize,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum ItemKind {
    /// Dead force `(fx, fy)` or follower `(f_t, f_n)` at distance `arm` from the inboard node of
    /// `element` (0-based).
    Dead {
        fx: f64,
        fy: f64,
    },
    Follower {
        ft: f64,
        fn_: f64,
    },
    Moment(f64),
    Torque(f64),
    Gravity(f64),
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct Item {
    load: usize,
    element: usize,
    arm: f64,
    kind: ItemKind,
}

impl AppliedLoads {
    /// Number of user loads (the length of the `scales` slices).
    pub fn n_loads(&self) -> usize {
        self.n_loads
    }
    /// No loads at all.
    pub fn none() -> Self {
        Self {
            items: Vec::new(),
            n_loads: 0,
        }
    }
}

impl FullModel {
    /// Validate `loads` against this model and resolve them into per-element items.
    /// `field` prefixes error field names, e.g. `loads` gives `loads[2].span`.
    ///
    /// # Errors
    /// A position outside the beam, a non-finite value, a torque on a bending-only model.
    pub fn apply(&self, loads: &[Load], field: &str) -> Result<AppliedLoads, InputError> {
        let length = self.beam.length();
        let mut items = Vec::new();
        for (i, load) in loads.iter().enumerate() {
            let f = |name: &str| format!("{field}[{i}].{name}");
            let finite = |name: &str, v: f64| -> Result<f64, InputError> {
                if v.is_finite() {
                    Ok(v)
                } else {
                    Err(InputError::new(f(name), format!("must be finite, got {v}")))
                }
            };
            let at = |span: f64| -> Result<(usize, f64), InputError> {
                if !span.is_finite() || span < 0.0 || span > length * (1.0 + 1e-12) {
                    return Err(InputError::new(
                        f("span"),
                        format!("must lie on the beam, in [0, {length}] m, got {span}"),
                    ));
                }
                Ok(self.locate(span.min(length)))
            };
            let mut push = |(k, arm): (usize, f64), kind: ItemKind| {
                if k > 0 {
                    items.push(Item {
                        load: i,
                        element: k - 1,
                        arm,
                        kind,
                    });
                }
            };
            match load {
                Load::PointForce { span, force } => {
                    let kind = match *force {
                        Force::Dead { fx, fy } => ItemKind::Dead {
                            fx: finite("fx", fx)?,
                            fy: finite("fy", fy)?,
                        },
                        Force::Follower { tangential, normal } => ItemKind::Follower {
                            ft: finite("tangential", tangential)?,
                            fn_: finite("normal", normal)?,
                        },
                    };
                    push(at(*span)?, kind);
                }
                Load::Moment { span, value } => {
                    push(at(*span)?, ItemKind::Moment(finite("moment", *value)?));
                }
                Load::Torque { span, value } => {
                    let kind = ItemKind::Torque(finite("torque", *value)?);
                    if !self.torsion {
                        return Err(InputError::new(
                            f("torque"),
                            "the beam has no torsion data (GJ), so it cannot carry a torque",
                        ));
                    }
                    push(at(*span)?, kind);
                }
                Load::Distributed(d) => {
                    let (a, b, names, follower) = match d {
                        DistributedForce::Dead { fx, fy } => (fx, fy, ["fx", "fy"], false),
                        DistributedForce::Follower { tangential, normal } => {
                            (tangential, normal, ["tangential", "normal"], true)
                        }
                    };
                    use crate::beam::profile::{integrate, Sign};
                    a.validate(&f(names[0]), length, Sign::Any)?;
                    b.validate(&f(names[1]), length, Sign::Any)?;
                    let nodes = self.beam.nodes();
                    for e in 0..self.n {
                        let (x0, x1) = (nodes[e], nodes[e + 1]);
                        let ra = integrate(&[a], x0, x1, |x| a.at(x));
                        let rb = integrate(&[b], x0, x1, |x| b.at(x));
                        let kind = if follower {
                            ItemKind::Follower { ft: ra, fn_: rb }
                        } else {
                            ItemKind::Dead { fx: ra, fy: rb }
                        };
                        push((e + 1, 0.5 * (x1 - x0)), kind);
                    }
                }
                Load::Gravity { g } => {
                    let g = finite("g", *g)?;
                    push((1, 0.0), ItemKind::Gravity(g));
                }
            }
        }
        Ok(AppliedLoads {
            items,
            n_loads: loads.len(),
        })
    }

    /// Generalized forces `Q(q) = Σ_k scales[k] Q_k(q)` at the configuration `kin`, into `out`.
    /// Costs O(n · items) and allocates nothing.
    ///
    /// # Panics
    /// If `out.len() != n_dofs()` or `scales.len() != loads.n_loads()`.
    pub fn generalized_forces_kin_into(
        &self,
        kin: &Kinematics,
        loads: &AppliedLoads,
        scales: &[f64],
        out: &mut DVector<f64>,
    ) {
        let n = self.n;
        assert_eq!(
            out.len(),
            self.n_dofs(),
            "force buffer has the wrong length"
        );
        assert_eq!(scales.len(), loads.n_loads, "one scale per load");
        out.fill(0.0);
        let (c, s) = (&kin.cos_theta, &kin.sin_theta);
        for it in &loads.items {
            let sc = scales[it.load];
            if sc == 0.0 {
                continue;
            }
            let k = it.element;
            match it.kind {
                ItemKind::Dead { .. } | ItemKind::Follower { .. } => {
                    let (fx, fy) = it.global_force(kin, sc);
                    for j in 0..=k {
                        let len = if j == k { it.arm } else { self.ell[j] };
                        out[j] += len * (-fx * s[j] + fy * c[j]);
                    }
                }
                ItemKind::Moment(m) => out[k] += sc * m,
                ItemKind::Torque(t) => out[n + k] += sc * t,
                ItemKind::Gravity(g) => {
                    // V = g Σ_i m_i y(g_i); Q = −∂V/∂(θ, ψ); W_j = Σ_{i>j} m_i.
                    let w = sc * g;
                    let mut outboard = 0.0;
                    for j in (0..n).rev() {
                        let (mj, d) = (self.mass[j], self.d0[j]);
                        out[j] -= w
                            * (c[j] * self.ell[j] * outboard
                                + mj * (0.5 * self.ell[j] * c[j] - d * kin.sin_psi[j] * s[j]));
                        if self.torsion {
                            out[n + j] -= w * mj * d * kin.cos_psi[j] * c[j];
                        }
                        outboard += mj;
                    }
                }
            }
        }
        for block in out.as_mut_slice().chunks_mut(n) {
            for r in (0..n - 1).rev() {
                block[r] += block[r + 1];
            }
        }
    }

    /// Load Jacobian `∂Q/∂q` at `kin`, into `out` (`n_dofs × n_dofs`). Symmetric for conservative
    /// loads (dead forces, moments, torques, gravity), not for follower forces.
    /// Costs O(n²) and allocates nothing.
    ///
    /// # Panics
    /// If `out` has the wrong shape or `scales.len() != loads.n_loads()`.
    pub fn load_jacobian_kin_into(
        &self,
        kin: &Kinematics,
        loads: &AppliedLoads,
        scales: &[f64],
        out: &mut DMatrix<f64>,
    ) {
        let n = self.n;
        let nd = self.n_dofs();
        assert_eq!(out.shape(), (nd, nd), "Jacobian buffer has the wrong shape");
        assert_eq!(scales.len(), loads.n_loads, "one scale per load");
        out.fill(0.0);
        let (c, s) = (&kin.cos_theta, &kin.sin_theta);
        for it in &loads.items {
            let sc = scales[it.load];
            if sc == 0.0 {
                continue;
            }
            let k = it.element;
            match it.kind {
                ItemKind::Dead { .. } | ItemKind::Follower { .. } => {
                    // Q_j = len_j F·n_j:  ∂/∂θ_j = −len_j F·e_j;  ∂/∂θ_k = len_j (∂F/∂θ_k)·n_j.
                    let (fx, fy) = it.global_force(kin, sc);
                    let dfdk = match it.kind {
                        ItemKind::Follower { ft, fn_ } => {
                            // ∂F/∂θ_k = f_t n_k − f_n e_k.
                            let (ft, fn_) = (sc * ft, sc * fn_);
                            Some((-ft * s[k] - fn_ * c[k], ft * c[k] - fn_ * s[k]))
                        }
                        _ => None,
                    };
                    for j in 0..=k {
                        let len = if j == k { it.arm } else { self.ell[j] };
                        out[(j, j)] -= len * (fx * c[j] + fy * s[j]);
                        if let Some((dx, dy)) = dfdk {
                            out[(j, k)] += len * (-dx * s[j] + dy * c[j]);
                        }
                    }
                }
                ItemKind::Moment(_) | ItemKind::Torque(_) => {}
                ItemKind::Gravity(g) => {
                    let w = sc * g;
                    let mut outboard = 0.0;
                    for j in (0..n).rev() {
                        let (mj, d) = (self.mass[j], self.d0[j]);
                        let (cp, sp) = (kin.cos_psi[j], kin.sin_psi[j]);
                        out[(j, j)] += w
                            * (s[j] * self.ell[j] * outboard
                                + mj * (0.5 * self.ell[j] * s[j] + d * sp * c[j]));
                        if self.torsion {
                            let tp = w * mj * d * cp * s[j];
                            out[(j, n + j)] += tp;
                            out[(n + j, j)] += tp;
                            out[(n + j, n + j)] += w * mj * d * sp * c[j];
                        }
                        outboard += mj;
                    }
                }
            }
        }
        suffix_sum_blocks(out, n);
    }
}

impl Item {
    /// Global components of a force item at `kin`, scaled by `sc`.
    fn global_force(&self, kin: &Kinematics, sc: f64) -> (f64, f64) {
        let k = self.element;
        match self.kind {
            ItemKind::Dead { fx, fy } => (sc * fx, sc * fy),
            ItemKind::Follower { ft, fn_ } => {
                let (c, s) = (kin.cos_theta[k], kin.sin_theta[k]);
                (sc * (ft * c - fn_ * s), sc * (ft * s + fn_ * c))
            }
            _ => (0.0, 0.0),
        }
    }
}
