//! Applied loads, their generalized forces `Q = J_Xᵀ F` and the load Jacobian `∂Q/∂q`.
//!
//! Loads are first resolved against a model ([`FullModel::apply`]) into per-element items; each
//! item remembers which user load it came from, so that every load can be scaled by its own factor
//! (a load-stepping factor in statics, a time function in dynamics): `Q(q) = Σ_k s_k Q_k(q)`.
//!
//! Everything is accumulated in absolute angles `(θ, ψ)` and transformed with `Q = Tᵀ Q_abs`,
//! `∂Q/∂q = Tᵀ (∂Q_abs/∂(θ, ψ)) T` (suffix sums), as the mass matrix.

use nalgebra::{DMatrix, DVector};

use super::{suffix_sum_blocks, suffix_sum_in_blocks, FullModel, Kinematics};
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
    /// Follower force, `F = f_t e(φ) + f_n n(φ)` in the frame of the beam's tangent at the point,
    /// `φ`: it turns with the beam (the paper's eq. 15 is a normal follower force at the tip).
    /// `φ` interpolates the element angles linearly between element midpoints (the mean of the
    /// two elements' angles at a node between equal elements), from 0 at the clamp, and is the
    /// tip element's angle beyond its midpoint (docs/model-choices.md, "Loads").
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

impl std::fmt::Display for Load {
    /// One line describing the load, its values and where it acts.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::text::short;
        let profile = |p: &Profile| match p {
            Profile::Uniform(v) => short(*v),
            Profile::Table { .. } => "table".into(),
        };
        match self {
            Load::PointForce { span, force } => {
                let (kind, names, a, b) = match force {
                    Force::Dead { fx, fy } => ("dead", "(fx, fy)", fx, fy),
                    Force::Follower { tangential, normal } => {
                        ("follower", "(tangential, normal)", tangential, normal)
                    }
                };
                write!(
                    f,
                    "{kind} point force {names} = ({}, {}) N at span {} m",
                    short(*a),
                    short(*b),
                    short(*span)
                )
            }
            Load::Moment { span, value } => {
                write!(f, "moment {} N·m at span {} m", short(*value), short(*span))
            }
            Load::Torque { span, value } => {
                write!(f, "torque {} N·m at span {} m", short(*value), short(*span))
            }
            Load::Distributed(d) => {
                let (kind, names, a, b) = match d {
                    DistributedForce::Dead { fx, fy } => ("dead", "(fx, fy)", fx, fy),
                    DistributedForce::Follower { tangential, normal } => {
                        ("follower", "(tangential, normal)", tangential, normal)
                    }
                };
                write!(
                    f,
                    "{kind} distributed force {names} = ({}, {}) N/m",
                    profile(a),
                    profile(b)
                )
            }
            Load::Gravity { g } => write!(f, "gravity, g = {} m/s² along -y", short(*g)),
        }
    }
}

/// Loads resolved against one model: per-element items, each tagged with its user load.
#[derive(Debug, Clone, PartialEq)]
pub struct AppliedLoads {
    items: Vec<Item>,
    n_loads: usize,
    /// Items resolved against a 3-D chain (`model::chain3d`, [`super::Chain3d::apply`]); empty
    /// for the planar models, and `items` empty for the 3-D chain.
    pub(crate) spatial: Vec<super::chain3d::SpatialItem>,
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
        turn: Turn,
    },
    Moment(f64),
    Torque(f64),
    Gravity(f64),
}

/// The direction angle of a follower force, `φ = w[0] θ_{e[0]} + w[1] θ_{e[1]}` (absolute bending
/// angles of elements next to the carrying one).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Turn {
    e: [usize; 2],
    w: [f64; 2],
}

impl Turn {
    /// Turns with element `k` alone.
    fn element(k: usize) -> Self {
        Self {
            e: [k, k],
            w: [1.0, 0.0],
        }
    }
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
    /// Whether the loads at these scales are conservative: no follower force with a non-zero
    /// scale (dead forces, moments, torques and gravity derive from a potential; a follower force
    /// does not, and makes the tangent `K − ∂Q/∂q` non-symmetric).
    ///
    /// # Panics
    /// If `scales.len() != self.n_loads()`.
    pub fn is_conservative(&self, scales: &[f64]) -> bool {
        assert_eq!(scales.len(), self.n_loads, "one scale per load");
        self.items.iter().all(|it| match it.kind {
            ItemKind::Follower { ft, fn_, .. } => {
                scales[it.load] == 0.0 || (ft == 0.0 && fn_ == 0.0)
            }
            _ => true,
        }) && self
            .spatial
            .iter()
            .all(|it| scales[it.load] == 0.0 || it.is_conservative())
    }

    /// No loads at all.
    pub fn none() -> Self {
        Self {
            items: Vec::new(),
            n_loads: 0,
            spatial: Vec::new(),
        }
    }

    /// Loads resolved against a 3-D chain.
    pub(crate) fn from_spatial(spatial: Vec<super::chain3d::SpatialItem>, n_loads: usize) -> Self {
        Self {
            items: Vec::new(),
            n_loads,
            spatial,
        }
    }

    /// Whether these loads were resolved against a planar model (or are empty).
    pub(crate) fn has_planar_items(&self) -> bool {
        !self.items.is_empty()
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
                    crate::magnitude::check(&f(name), "", v)
                } else {
                    Err(InputError::new(f(name), format!("must be finite, got {v}")))
                }
            };
            let at = |span: f64| -> Result<(usize, f64), InputError> {
                if !span.is_finite() || span < 0.0 || span > length * (1.0 + 1e-12) {
                    return Err(InputError::new(
                        f("span"),
                        format!(
                            "must lie on the beam, in [0, {}] m, got {}",
                            crate::text::short(length),
                            crate::text::short(span)
                        ),
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
                    let place = at(*span)?;
                    let kind = match *force {
                        Force::Dead { fx, fy } => ItemKind::Dead {
                            fx: finite("fx", fx)?,
                            fy: finite("fy", fy)?,
                        },
                        Force::Follower { tangential, normal } => ItemKind::Follower {
                            ft: finite("tangential", tangential)?,
                            fn_: finite("normal", normal)?,
                            turn: self.tangent_turn(span.min(length)),
                        },
                    };
                    push(place, kind);
                }
                Load::Moment { span, value } => {
                    push(at(*span)?, ItemKind::Moment(finite("value", *value)?));
                }
                Load::Torque { span, value } => {
                    if !self.torsion {
                        return Err(InputError::new(
                            format!("{field}[{i}]"),
                            "a torque needs torsion, but the beam is bending-only (it has no \
                             torsional stiffness GJ)",
                        ));
                    }
                    let kind = ItemKind::Torque(finite("value", *value)?);
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
                        // Lumped at the element midpoint, where the tangent is the element's.
                        let kind = if follower {
                            ItemKind::Follower {
                                ft: ra,
                                fn_: rb,
                                turn: Turn::element(e),
                            }
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
            spatial: Vec::new(),
        })
    }

    /// The beam's tangent angle at `span` (`0 < span ≤ L`) as a combination of element angles:
    /// linear interpolation between the element midpoints `c_j`, where the element angles are
    /// second-order approximations of the continuous beam's tangent; from the clamp (angle 0 at
    /// `span = 0`) to `c_0`; the tip element's angle from `c_{n−1}` to the tip (the paper's
    /// eq. 15 at the tip). At a node between equal elements this is the mean of their angles.
    fn tangent_turn(&self, span: f64) -> Turn {
        let nodes = self.beam.nodes();
        let mid = |j: usize| 0.5 * (nodes[j] + nodes[j + 1]);
        let n = self.n;
        if span >= mid(n - 1) {
            return Turn::element(n - 1);
        }
        if span <= mid(0) {
            return Turn {
                e: [0, 0],
                w: [span / mid(0), 0.0],
            };
        }
        // The interval [c_j, c_{j+1}) holding span.
        let j = (0..n - 1)
            .rev()
            .find(|&j| mid(j) <= span)
            .expect("span lies past the first midpoint");
        let t = (span - mid(j)) / (mid(j + 1) - mid(j));
        Turn {
            e: [j, j + 1],
            w: [1.0 - t, t],
        }
    }

    /// Generalized forces `Q(q) = Σ_k scales[k] Q_k(q)` at the configuration `kin`, into `out`.
    /// Costs O(n + items).
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
        let mut r = Resultants::zeros(self.n);
        r.update(self, kin, loads, scales);
        self.forces_from(kin, &r, out);
    }

    pub(super) fn forces_from(&self, kin: &Kinematics, r: &Resultants, out: &mut DVector<f64>) {
        self.forces_abs_from(kin, r, out.as_mut_slice());
        suffix_sum_in_blocks(out.as_mut_slice(), self.n);
    }

    /// Generalized forces conjugate to the absolute angles, `Q_abs` (`Q = Tᵀ Q_abs`).
    pub(super) fn forces_abs_from(&self, kin: &Kinematics, r: &Resultants, out: &mut [f64]) {
        assert_eq!(
            out.len(),
            self.n_dofs(),
            "force buffer has the wrong length"
        );
        let n = self.n;
        let (c, s) = (&kin.cos_theta, &kin.sin_theta);
        // Q_θ,j = n_j · (ℓ_j R_j + A_j) + M_j, R_j the resultant of the forces outboard of
        // element j, A_j the arm-weighted forces on element j itself.
        let mut outboard = [0.0; 2];
        for j in (0..n).rev() {
            let lever = [
                self.ell[j] * outboard[0] + r.arm_force[j][0],
                self.ell[j] * outboard[1] + r.arm_force[j][1],
            ];
            out[j] = -s[j] * lever[0] + c[j] * lever[1] + r.moment[j];
            outboard[0] += r.force[j][0];
            outboard[1] += r.force[j][1];
            if self.torsion {
                out[n + j] = r.torque[j];
            }
        }
        if r.gravity != 0.0 {
            // V = g Σ_i m_i y(g_i), Q = −∂V/∂(θ, ψ), W_j = Σ_{i>j} m_i.
            let w = r.gravity;
            let mut mass_out = 0.0;
            for j in (0..n).rev() {
                let (mj, d) = (self.mass[j], self.d0[j]);
                out[j] -= w
                    * (c[j] * self.ell[j] * mass_out
                        + mj * (0.5 * self.ell[j] * c[j] - d * kin.sin_psi[j] * s[j]));
                if self.torsion {
                    out[n + j] -= w * mj * d * kin.cos_psi[j] * c[j];
                }
                mass_out += mj;
            }
        }
    }

    /// Load Jacobian `∂Q/∂q` at `kin`, into `out` (`n_dofs × n_dofs`). Symmetric for conservative
    /// loads (dead forces, moments, torques, gravity), not for follower forces. Costs O(n²).
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
        let mut r = Resultants::zeros(self.n);
        r.update(self, kin, loads, scales);
        let mut dir = vec![0.0; self.n_dofs()];
        self.jacobian_from(kin, &r, &mut dir, out);
    }

    /// Dense `∂Q/∂q` from the resultants; `dir` is scratch of length `n_dofs`, left zero.
    pub(super) fn jacobian_from(
        &self,
        kin: &Kinematics,
        r: &Resultants,
        dir: &mut [f64],
        out: &mut DMatrix<f64>,
    ) {
        let nd = self.n_dofs();
        assert_eq!(out.shape(), (nd, nd), "Jacobian buffer has the wrong shape");
        if !r.has_rates {
            // Conservative loads: each element's Q_abs depends on its own angles only, so
            // ∂Q_abs/∂(θ, ψ) is block-diagonal; O(n) entries, then the O(n²) map Tᵀ (·) T.
            self.block_diagonal_abs(kin, r, out);
            suffix_sum_blocks(out, self.n);
            return;
        }
        // Column c of ∂Q_abs/∂(θ, ψ) is the derivative along the unit direction c.
        for col in 0..nd {
            dir[col] = 1.0;
            let mut column = out.column_mut(col);
            self.directional_abs(kin, r, dir, column.as_mut_slice());
            dir[col] = 0.0;
        }
        suffix_sum_blocks(out, self.n);
    }

    /// `∂Q_abs/∂(θ, ψ)` of loads without follower forces (block-diagonal: dead forces and
    /// moments give `∂Q_θ,j/∂θ_j = −e_j · lever_j`, gravity the 2 × 2 blocks of element `j`),
    /// into `out`; the same entries as [`Self::directional_abs`] along unit directions.
    fn block_diagonal_abs(&self, kin: &Kinematics, r: &Resultants, out: &mut DMatrix<f64>) {
        let n = self.n;
        let (c, s) = (&kin.cos_theta, &kin.sin_theta);
        out.fill(0.0);
        let mut outboard = [0.0; 2];
        for j in (0..n).rev() {
            let lever = [
                self.ell[j] * outboard[0] + r.arm_force[j][0],
                self.ell[j] * outboard[1] + r.arm_force[j][1],
            ];
            out[(j, j)] = -(c[j] * lever[0] + s[j] * lever[1]);
            outboard[0] += r.force[j][0];
            outboard[1] += r.force[j][1];
        }
        if r.gravity != 0.0 {
            let mut mass_out = 0.0;
            for j in (0..n).rev() {
                let [bb, bt, tt] = self.gravity_block(kin, r.gravity, j, mass_out);
                out[(j, j)] += bb;
                if self.torsion {
                    out[(j, n + j)] += bt;
                    out[(n + j, j)] += bt;
                    out[(n + j, n + j)] += tt;
                }
                mass_out += self.mass[j];
            }
        }
    }

    /// Gravity `w = g`'s block of `∂Q_abs/∂(θ_j, ψ_j)`: `[θθ, θψ = ψθ, ψψ]`, with `mass_out` the
    /// mass outboard of element `j`.
    fn gravity_block(&self, kin: &Kinematics, w: f64, j: usize, mass_out: f64) -> [f64; 3] {
        let (mj, d, l) = (self.mass[j], self.d0[j], self.ell[j]);
        let (c, s) = (kin.cos_theta[j], kin.sin_theta[j]);
        let (cp, sp) = (kin.cos_psi[j], kin.sin_psi[j]);
        [
            w * (s * l * mass_out + mj * (0.5 * l * s + d * sp * c)),
            w * mj * d * cp * s,
            w * mj * d * sp * c,
        ]
    }

    /// `(∂Q/∂q) V` for a block of directions `V` (`n_dofs × r`, joint coordinates), into `out`
    /// (`n_dofs × r`), without forming `∂Q/∂q`: O((n + items) r). This is what makes the
    /// tangent of a reduced model cheap.
    ///
    /// # Panics
    /// If the shapes do not match or `scales.len() != loads.n_loads()`.
    pub fn load_jacobian_times_kin_into(
        &self,
        kin: &Kinematics,
        loads: &AppliedLoads,
        scales: &[f64],
        v: &DMatrix<f64>,
        out: &mut DMatrix<f64>,
    ) {
        let mut r = Resultants::zeros(self.n);
        r.update(self, kin, loads, scales);
        let mut dir = vec![0.0; self.n_dofs()];
        self.jacobian_times_from(kin, &r, v, &mut dir, out);
    }

    /// `(∂Q/∂q) V` from the resultants; `dir` is scratch of length `n_dofs`.
    pub(super) fn jacobian_times_from(
        &self,
        kin: &Kinematics,
        r: &Resultants,
        v: &DMatrix<f64>,
        dir: &mut [f64],
        out: &mut DMatrix<f64>,
    ) {
        let n = self.n;
        let nd = self.n_dofs();
        assert_eq!(v.nrows(), nd, "directions have the wrong length");
        assert_eq!(out.shape(), v.shape(), "output block has the wrong shape");
        for col in 0..v.ncols() {
            // Absolute-angle direction T v: prefix sums within each block.
            for (dst, src) in dir.chunks_mut(n).zip(v.column(col).as_slice().chunks(n)) {
                let mut acc = 0.0;
                for (d, x) in dst.iter_mut().zip(src) {
                    acc += x;
                    *d = acc;
                }
            }
            let mut column = out.column_mut(col);
            let o = column.as_mut_slice();
            self.directional_abs(kin, r, dir, o);
            suffix_sum_in_blocks(o, n);
        }
    }

    /// Derivative of `Q_abs` along the absolute-angle direction `dir = (dθ, dψ)`, into `out`.
    fn directional_abs(&self, kin: &Kinematics, r: &Resultants, dir: &[f64], out: &mut [f64]) {
        let n = self.n;
        let (c, s) = (&kin.cos_theta, &kin.sin_theta);
        let mut outboard = [0.0; 2];
        let mut d_outboard = [0.0; 2];
        for j in (0..n).rev() {
            let dth = dir[j];
            // Rates of the follower forces on element j along dir: they turn with the angles of
            // elements j − 1, j and j + 1 (slots 0, 1, 2).
            let mut d_force = [0.0; 2];
            let mut d_arm = [0.0; 2];
            for slot in 0..if r.has_rates { 3 } else { 0 } {
                let Some(e) = (j + slot).checked_sub(1).filter(|&e| e < n) else {
                    continue;
                };
                for a in 0..2 {
                    d_force[a] += r.force_rate[j][slot][a] * dir[e];
                    d_arm[a] += r.arm_rate[j][slot][a] * dir[e];
                }
            }
            let lever = [
                self.ell[j] * outboard[0] + r.arm_force[j][0],
                self.ell[j] * outboard[1] + r.arm_force[j][1],
            ];
            let d_lever = [
                self.ell[j] * d_outboard[0] + d_arm[0],
                self.ell[j] * d_outboard[1] + d_arm[1],
            ];
            // d(n_j · lever) = −e_j · lever dθ_j + n_j · d lever.
            out[j] =
                -(c[j] * lever[0] + s[j] * lever[1]) * dth - s[j] * d_lever[0] + c[j] * d_lever[1];
            outboard[0] += r.force[j][0];
            outboard[1] += r.force[j][1];
            d_outboard[0] += d_force[0];
            d_outboard[1] += d_force[1];
            if self.torsion {
                out[n + j] = 0.0;
            }
        }
        if r.gravity != 0.0 {
            let w = r.gravity;
            let mut mass_out = 0.0;
            for j in (0..n).rev() {
                let [bb, bt, tt] = self.gravity_block(kin, w, j, mass_out);
                out[j] += bb * dir[j];
                if self.torsion {
                    out[j] += bt * dir[n + j];
                    out[n + j] += bt * dir[j] + tt * dir[n + j];
                }
                mass_out += self.mass[j];
            }
        }
    }
}

/// Per-element resultants of the applied loads at one configuration: what the O(n) recursions
/// for `Q` and its directional derivatives need.
#[derive(Debug, Clone)]
pub(super) struct Resultants {
    /// Σ of the global forces on element k.
    force: Vec<[f64; 2]>,
    /// Σ arm · force on element k.
    arm_force: Vec<[f64; 2]>,
    /// Σ ∂F/∂θ_{k−1+slot} of the follower forces on element k, slots 0, 1, 2 for the elements
    /// k − 1, k, k + 1 (a follower force turns with the tangent at its point).
    force_rate: Vec<[[f64; 2]; 3]>,
    /// Σ arm · ∂F/∂θ_{k−1+slot}.
    arm_rate: Vec<[[f64; 2]; 3]>,
    moment: Vec<f64>,
    torque: Vec<f64>,
    /// Σ scale · g of the gravity loads.
    gravity: f64,
    /// Whether any follower force acts (non-zero rates): without, `∂Q_abs/∂(θ, ψ)` is
    /// block-diagonal (each element's generalized force depends on its own angles only).
    has_rates: bool,
}

impl Resultants {
    /// Whether the chain form of the load stiffness (`FullModel::chain_load_stiffness`) is
    /// exact for elements of lengths `ell`. It carries a follower force's rate with the
    /// neighbouring angles through the levers of whole elements, which is exact when the force
    /// turning with `θ_{k−1}` has no arm on its element `k` (it sits at the element's inboard
    /// node) and the one turning with `θ_{k+1}` has the arm `ℓ_k` (the outboard node); forces
    /// turning with their own element's angle only (midpoints) are exact anyway. The terms left
    /// out otherwise are next to the diagonal.
    pub(super) fn chain_exact(&self, ell: &[f64]) -> bool {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (a.abs() + b.abs());
        self.arm_rate
            .iter()
            .zip(&self.force_rate)
            .zip(ell)
            .all(|((arm, rate), &l)| {
                arm[0] == [0.0, 0.0]
                    && close(arm[2][0], l * rate[2][0])
                    && close(arm[2][1], l * rate[2][1])
            })
    }

    pub(super) fn zeros(n: usize) -> Self {
        Self {
            force: vec![[0.0; 2]; n],
            arm_force: vec![[0.0; 2]; n],
            force_rate: vec![[[0.0; 2]; 3]; n],
            arm_rate: vec![[[0.0; 2]; 3]; n],
            moment: vec![0.0; n],
            torque: vec![0.0; n],
            gravity: 0.0,
            has_rates: false,
        }
    }

    /// Recompute for the configuration `kin` and load scales `scales` (no allocation).
    pub(super) fn update(
        &mut self,
        model: &FullModel,
        kin: &Kinematics,
        loads: &AppliedLoads,
        scales: &[f64],
    ) {
        assert_eq!(scales.len(), loads.n_loads, "one scale per load");
        debug_assert_eq!(self.force.len(), model.n);
        self.force.fill([0.0; 2]);
        self.arm_force.fill([0.0; 2]);
        self.force_rate.fill([[0.0; 2]; 3]);
        self.arm_rate.fill([[0.0; 2]; 3]);
        self.moment.fill(0.0);
        self.torque.fill(0.0);
        self.gravity = 0.0;
        self.has_rates = false;
        let r = self;
        for it in &loads.items {
            let sc = scales[it.load];
            let k = it.element;
            let (f, rate, turn) = match it.kind {
                ItemKind::Dead { fx, fy } => ([sc * fx, sc * fy], [0.0, 0.0], None),
                ItemKind::Follower { ft, fn_, turn } => {
                    let (ft, fn_) = (sc * ft, sc * fn_);
                    let (s, c) = if turn.w == [1.0, 0.0] {
                        (kin.sin_theta[turn.e[0]], kin.cos_theta[turn.e[0]])
                    } else {
                        (turn.w[0] * kin.theta[turn.e[0]] + turn.w[1] * kin.theta[turn.e[1]])
                            .sin_cos()
                    };
                    // F = f_t e(φ) + f_n n(φ), ∂F/∂φ = f_t n(φ) − f_n e(φ).
                    (
                        [ft * c - fn_ * s, ft * s + fn_ * c],
                        [-ft * s - fn_ * c, ft * c - fn_ * s],
                        Some(turn),
                    )
                }
                ItemKind::Moment(m) => {
                    r.moment[k] += sc * m;
                    continue;
                }
                ItemKind::Torque(t) => {
                    r.torque[k] += sc * t;
                    continue;
                }
                ItemKind::Gravity(g) => {
                    r.gravity += sc * g;
                    continue;
                }
            };
            for a in 0..2 {
                r.force[k][a] += f[a];
                r.arm_force[k][a] += it.arm * f[a];
            }
            if let Some(turn) = turn {
                r.has_rates |= rate != [0.0, 0.0];
                for (e, w) in turn.e.into_iter().zip(turn.w) {
                    // e ∈ {k − 1, k, k + 1}: slot e + 1 − k.
                    let slot = e + 1 - k;
                    for a in 0..2 {
                        r.force_rate[k][slot][a] += w * rate[a];
                        r.arm_rate[k][slot][a] += w * it.arm * rate[a];
                    }
                }
            }
        }
    }
}

impl FullModel {
    /// The load stiffness `G = −∂Q/∂q` in the chain form of the O(n) Newton sweeps
    /// (`model::chain_newton`, docs/model-choices.md, "O(n) Newton systems"). In absolute angles
    /// `G` is, for element `j`, a local 2 × 2 block `local[j] = [g_θθ, g_θψ, g_ψψ]` (levers of
    /// the forces, gravity, and the follower rates that act on joint `j` itself), plus the total
    /// rate `rate[j] = Σ_k ∂F_k/∂θ_j` of the follower forces turned by `θ_j` (a follower force
    /// on element `k` turns with the tangent at its point, so with `θ_{k−1}`, `θ_k`, `θ_{k+1}`),
    /// which acts on every inboard joint `i < j` through its lever: `G_abs[θ_i, θ_j] = −ℓ_i n_i
    /// · rate[j]`. This is exact for follower forces at nodes and element midpoints; a follower
    /// force strictly between a node and a midpoint adds terms next to the diagonal that the
    /// chain form leaves out (its Newton iterations are then simplified ones: they still
    /// converge to the exact residual's root, more slowly). Returns true when `G` is symmetric
    /// (no follower force acts).
    pub(super) fn chain_load_stiffness(
        &self,
        kin: &Kinematics,
        r: &Resultants,
        local: &mut [[f64; 3]],
        rate: &mut [[f64; 2]],
    ) -> bool {
        let n = self.n;
        let (c, s) = (&kin.cos_theta, &kin.sin_theta);
        let mut outboard = [0.0; 2];
        let mut symmetric = true;
        let w = r.gravity;
        let mut mass_out = 0.0;
        for j in (0..n).rev() {
            let lever = [
                self.ell[j] * outboard[0] + r.arm_force[j][0],
                self.ell[j] * outboard[1] + r.arm_force[j][1],
            ];
            // Element j's own force turned by θ_j, through its arm.
            let arm = r.arm_rate[j][1];
            // The force of the outboard element j + 1 turned by θ_j, through the lever ℓ_j.
            let next = if j + 1 < n {
                [
                    self.ell[j] * r.force_rate[j + 1][0][0],
                    self.ell[j] * r.force_rate[j + 1][0][1],
                ]
            } else {
                [0.0; 2]
            };
            // −∂/∂θ_j of n_j · lever_j.
            let mut tt = c[j] * lever[0] + s[j] * lever[1]
                - (-s[j] * (arm[0] + next[0]) + c[j] * (arm[1] + next[1]));
            let (mut tp, mut pp) = (0.0, 0.0);
            if w != 0.0 {
                let (mj, d) = (self.mass[j], self.d0[j]);
                let (cp, sp) = (kin.cos_psi[j], kin.sin_psi[j]);
                tt -= w
                    * (s[j] * self.ell[j] * mass_out
                        + mj * (0.5 * self.ell[j] * s[j] + d * sp * c[j]));
                if self.torsion {
                    tp = -w * mj * d * cp * s[j];
                    pp = -w * mj * d * sp * c[j];
                }
                mass_out += mj;
            }
            local[j] = [tt, tp, pp];
            let mut total = r.force_rate[j][1];
            if j > 0 {
                let inboard = r.force_rate[j - 1][2];
                total = [total[0] + inboard[0], total[1] + inboard[1]];
            }
            if j + 1 < n {
                let outboard = r.force_rate[j + 1][0];
                total = [total[0] + outboard[0], total[1] + outboard[1]];
            }
            rate[j] = total;
            symmetric &= !r.has_rates;
            outboard[0] += r.force[j][0];
            outboard[1] += r.force[j][1];
        }
        symmetric
    }
}
