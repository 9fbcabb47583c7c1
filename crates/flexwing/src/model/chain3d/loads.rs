//! Loads on the 3-D chain and their generalized forces `Q = Σ_k s_k Q_k(x)` in O(n), generic over
//! the scalar so that dual numbers give the exact load Jacobian `∂Q/∂x` (docs/chain3d-model.md,
//! "Loads").
//!
//! A force `F` at a point `X` of element `k` and a moment `N` on it do the virtual work
//! `F·δX + N·δθ_k`; a change `δφ_j` (`j ≤ k`) turns element `k` about `P_j` by `H_j δφ_j`, so
//!
//! ```text
//! Q_j = H_jᵀ N_j,    N_j = Σ_{k ≥ j} (N_k + (X − P_j) × F)   (the moment about P_j of every
//!                                                             load outboard of node j)
//! ```
//!
//! summed from the tip in one sweep. Dead loads keep their global components; follower loads
//! are given in the frame `(t, n, c)` of the element that carries the point (at a node, the
//! inboard element: the tip element at the tip) and turn with it. Distributed forces are
//! integrated exactly per element, resultant `∫ f ds` and first moment `∫ (s − s_k) f ds`
//! (rigid elements: the moment about the element's inboard node is `t_k × ∫ (s − s_k) f ds`).
//! Gravity acts at every element's mass centre.

use super::algebra::{add, cross, lift, mv, scale, zero, Real, V3};
use super::kinematics::Frames;
use super::Chain3d;
use crate::beam::profile::{integrate, Sign};
use crate::beam::Profile;
use crate::error::InputError;
use crate::model::{AppliedLoads, DistributedForce, Force, Load};

/// A force or moment vector: fixed global components, or components in the frame `(t, n, c)` of
/// the element it acts on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpatialVector {
    /// Global components `(x, y, z)` (N or N·m), fixed in space.
    Dead([f64; 3]),
    /// Components along `(t, n, c)` of the carrying element (N or N·m), turning with it.
    Follower([f64; 3]),
}

/// A force per unit length along the whole span (N/m), each component a [`Profile`].
#[derive(Debug, Clone, PartialEq)]
pub enum SpatialDistributed {
    /// Global components `(x, y, z)`.
    Dead([Profile; 3]),
    /// Components along each element's `(t, n, c)`.
    Follower([Profile; 3]),
}

/// A load on the 3-D chain. `span` is the arc length along the reference axis (m), in `[0, L]`;
/// a point at node `k` belongs to the inboard element; at `span = 0` a load goes into the clamp.
#[derive(Debug, Clone, PartialEq)]
pub enum SpatialLoad {
    /// A force at a point of the elastic axis.
    PointForce {
        /// Position along the span (m).
        span: f64,
        /// The force (N).
        force: SpatialVector,
    },
    /// A moment (N·m) on the element carrying `span`.
    PointMoment {
        /// Position along the span (m).
        span: f64,
        /// The moment (N·m).
        moment: SpatialVector,
    },
    /// A distributed force over the span.
    Distributed(SpatialDistributed),
    /// Gravity: the acceleration vector (m/s², global components, e.g. `[0, −9.81, 0]`) at every
    /// element's mass centre.
    Gravity {
        /// Acceleration of gravity (m/s²).
        acceleration: [f64; 3],
    },
}

impl SpatialLoad {
    /// The planar model's load as a load on the 3-D chain: forces and distributed forces in the
    /// `x–y` plane (followers along `(t, n)`), a bending moment as a dead moment about `z`, a
    /// torque (positive nose-up) as a follower moment about `−t`, gravity along `−y`. A
    /// follower force strictly between element midpoints turns with its element here, whereas
    /// the planar model interpolates the direction between the midpoints (the two agree at
    /// the tip and on distributed followers).
    pub fn from_planar(load: &Load) -> Self {
        match load {
            Load::PointForce { span, force } => SpatialLoad::PointForce {
                span: *span,
                force: match *force {
                    Force::Dead { fx, fy } => SpatialVector::Dead([fx, fy, 0.0]),
                    Force::Follower { tangential, normal } => {
                        SpatialVector::Follower([tangential, normal, 0.0])
                    }
                },
            },
            Load::Moment { span, value } => SpatialLoad::PointMoment {
                span: *span,
                moment: SpatialVector::Dead([0.0, 0.0, *value]),
            },
            Load::Torque { span, value } => SpatialLoad::PointMoment {
                span: *span,
                moment: SpatialVector::Follower([-*value, 0.0, 0.0]),
            },
            Load::Distributed(d) => SpatialLoad::Distributed(match d {
                DistributedForce::Dead { fx, fy } => {
                    SpatialDistributed::Dead([fx.clone(), fy.clone(), Profile::Uniform(0.0)])
                }
                DistributedForce::Follower { tangential, normal } => {
                    SpatialDistributed::Follower([
                        tangential.clone(),
                        normal.clone(),
                        Profile::Uniform(0.0),
                    ])
                }
            }),
            Load::Gravity { g } => SpatialLoad::Gravity {
                acceleration: [0.0, -*g, 0.0],
            },
        }
    }
}

/// One resolved load item on one element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpatialItem {
    /// The user load it came from (its scale).
    pub(crate) load: usize,
    /// The element carrying it (0-based; unused for gravity).
    pub(crate) element: usize,
    pub(crate) kind: SpatialKind,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum SpatialKind {
    /// A force at `arm` from the element's inboard node along `t`.
    Force {
        value: [f64; 3],
        arm: f64,
        follower: bool,
    },
    Moment {
        value: [f64; 3],
        follower: bool,
    },
    /// A distributed force's resultant and first moment about the inboard node (in `s`).
    Distributed {
        resultant: [f64; 3],
        first_moment: [f64; 3],
        follower: bool,
    },
    /// Gravity on every element.
    Gravity([f64; 3]),
}

impl SpatialItem {
    /// Whether the item derives from a potential: dead forces (point, distributed) and gravity
    /// do; follower forces and every moment of fixed or turning axis do not in 3-D (a moment
    /// about a fixed axis does work `N·ω`, not the differential of a function of the rotation;
    /// Argyris et al. 1979). Items of zero magnitude do.
    pub(crate) fn is_conservative(&self) -> bool {
        match self.kind {
            SpatialKind::Force {
                value, follower, ..
            } => !follower || value == [0.0; 3],
            SpatialKind::Moment { value, .. } => value == [0.0; 3],
            SpatialKind::Distributed {
                resultant,
                first_moment,
                follower,
            } => !follower || (resultant == [0.0; 3] && first_moment == [0.0; 3]),
            SpatialKind::Gravity(_) => true,
        }
    }
}

impl Chain3d {
    /// Validate `loads` against this chain and resolve them per element; `field` prefixes the
    /// error fields (`loads` gives `loads[2].span`).
    ///
    /// # Errors
    /// A position off the reference axis, a non-finite or out-of-range value.
    pub fn apply(&self, loads: &[SpatialLoad], field: &str) -> Result<AppliedLoads, InputError> {
        let length = self.beam.length();
        let nodes = self.beam.nodes();
        let mut items = Vec::new();
        for (i, load) in loads.iter().enumerate() {
            let f = |name: &str| format!("{field}[{i}].{name}");
            let vector = |name: &str, v: &[f64; 3]| -> Result<[f64; 3], InputError> {
                for (a, x) in v.iter().enumerate() {
                    if !x.is_finite() {
                        return Err(InputError::new(
                            f(name),
                            format!("component {a} must be finite, got {x}"),
                        ));
                    }
                    crate::magnitude::check(&f(name), &format!("component {a}"), *x)?;
                }
                Ok(*v)
            };
            let at = |span: f64| -> Result<Option<(usize, f64)>, InputError> {
                if !span.is_finite() || span < 0.0 || span > length * (1.0 + 1e-12) {
                    return Err(InputError::new(
                        f("span"),
                        format!(
                            "must lie on the reference axis, in [0, {}] m, got {}",
                            crate::text::short(length),
                            crate::text::short(span)
                        ),
                    ));
                }
                let span = span.min(length);
                let k = nodes.partition_point(|&x| x < span).min(self.n);
                Ok((k > 0).then(|| (k - 1, span - nodes[k - 1])))
            };
            match load {
                SpatialLoad::PointForce { span, force } => {
                    let (value, follower) = match force {
                        SpatialVector::Dead(v) => (vector("force", v)?, false),
                        SpatialVector::Follower(v) => (vector("force", v)?, true),
                    };
                    if let Some((element, arm)) = at(*span)? {
                        items.push(SpatialItem {
                            load: i,
                            element,
                            kind: SpatialKind::Force {
                                value,
                                arm,
                                follower,
                            },
                        });
                    }
                }
                SpatialLoad::PointMoment { span, moment } => {
                    let (value, follower) = match moment {
                        SpatialVector::Dead(v) => (vector("moment", v)?, false),
                        SpatialVector::Follower(v) => (vector("moment", v)?, true),
                    };
                    if let Some((element, _)) = at(*span)? {
                        items.push(SpatialItem {
                            load: i,
                            element,
                            kind: SpatialKind::Moment { value, follower },
                        });
                    }
                }
                SpatialLoad::Distributed(d) => {
                    let (profiles, follower) = match d {
                        SpatialDistributed::Dead(p) => (p, false),
                        SpatialDistributed::Follower(p) => (p, true),
                    };
                    for (a, p) in profiles.iter().enumerate() {
                        p.validate(&f(&format!("force[{a}]")), length, Sign::Any)?;
                    }
                    for e in 0..self.n {
                        let (x0, x1) = (nodes[e], nodes[e + 1]);
                        let mut resultant = [0.0; 3];
                        let mut first_moment = [0.0; 3];
                        for (a, p) in profiles.iter().enumerate() {
                            resultant[a] = integrate(&[p], x0, x1, |x| p.at(x));
                            first_moment[a] = integrate(&[p], x0, x1, |x| (x - x0) * p.at(x));
                        }
                        if resultant != [0.0; 3] || first_moment != [0.0; 3] {
                            items.push(SpatialItem {
                                load: i,
                                element: e,
                                kind: SpatialKind::Distributed {
                                    resultant,
                                    first_moment,
                                    follower,
                                },
                            });
                        }
                    }
                }
                SpatialLoad::Gravity { acceleration } => {
                    let a = vector("acceleration", acceleration)?;
                    items.push(SpatialItem {
                        load: i,
                        element: 0,
                        kind: SpatialKind::Gravity(a),
                    });
                }
            }
        }
        Ok(AppliedLoads::from_spatial(items, loads.len()))
    }

    /// The planar model's loads on this chain ([`SpatialLoad::from_planar`]), resolved.
    ///
    /// # Errors
    /// Those of [`Chain3d::apply`].
    pub fn apply_planar(&self, loads: &[Load], field: &str) -> Result<AppliedLoads, InputError> {
        let spatial: Vec<SpatialLoad> = loads.iter().map(SpatialLoad::from_planar).collect();
        self.apply(&spatial, field)
    }

    /// `Q(x) = Σ_k scales[k] Q_k(x)` at the configuration `fr` into `out`; `own_f`, `own_n`
    /// (one entry per element) are scratch. O(n + items).
    ///
    /// # Panics
    /// If `loads` were resolved against a planar model, or `scales.len() != loads.n_loads()`.
    pub(crate) fn forces_frames<D: Real>(
        &self,
        fr: &Frames<D>,
        loads: &AppliedLoads,
        scales: &[f64],
        own_f: &mut [V3<D>],
        own_n: &mut [V3<D>],
        out: &mut [D],
    ) {
        assert!(
            !loads.has_planar_items(),
            "loads resolved against a planar model given to the 3-D chain"
        );
        assert_eq!(scales.len(), loads.n_loads(), "one scale per load");
        let n = self.n;
        own_f.fill(zero());
        own_n.fill(zero());
        for it in &loads.spatial {
            let s = scales[it.load];
            if s == 0.0 {
                continue;
            }
            let k = it.element;
            let global = |v: &[f64; 3], follower: bool| -> V3<D> {
                let v = lift::<D>(&[s * v[0], s * v[1], s * v[2]]);
                if follower {
                    mv(&fr.r[k], &v)
                } else {
                    v
                }
            };
            match it.kind {
                SpatialKind::Force {
                    value,
                    arm,
                    follower,
                } => {
                    let f = global(&value, follower);
                    let lever = scale(D::from(arm / self.beam.reference.lengths[k]), &fr.d[k]);
                    own_f[k] = add(&own_f[k], &f);
                    own_n[k] = add(&own_n[k], &cross(&lever, &f));
                }
                SpatialKind::Moment { value, follower } => {
                    own_n[k] = add(&own_n[k], &global(&value, follower));
                }
                SpatialKind::Distributed {
                    resultant,
                    first_moment,
                    follower,
                } => {
                    let f = global(&resultant, follower);
                    let g = global(&first_moment, follower);
                    let t = scale(D::from(1.0 / self.beam.reference.lengths[k]), &fr.d[k]);
                    own_f[k] = add(&own_f[k], &f);
                    own_n[k] = add(&own_n[k], &cross(&t, &g));
                }
                SpatialKind::Gravity(a) => {
                    for e in 0..n {
                        let m = s * self.beam.masses[e];
                        let f = lift::<D>(&[m * a[0], m * a[1], m * a[2]]);
                        own_f[e] = add(&own_f[e], &f);
                        own_n[e] = add(&own_n[e], &cross(&fr.arm[e], &f));
                    }
                }
            }
        }
        let (mut force, mut moment): (V3<D>, V3<D>) = (zero(), zero());
        for j in (0..n).rev() {
            // About P_j: the outboard resultant moved from P_{j+1}, then element j's own loads.
            moment = add(&add(&moment, &cross(&fr.d[j], &force)), &own_n[j]);
            force = add(&force, &own_f[j]);
            let q = super::algebra::mtv(&fr.h[j], &moment);
            out[3 * j..3 * j + 3].copy_from_slice(&q);
        }
    }

    /// The potential energy of the conservative loads at `fr` (J), `V = −Σ s F·X` over dead
    /// point and distributed forces and gravity (relative to the reference state): for checks of
    /// `Q = −∂V/∂x`. Non-conservative items are left out.
    pub(crate) fn load_potential(
        &self,
        fr: &Frames<f64>,
        loads: &AppliedLoads,
        scales: &[f64],
    ) -> f64 {
        let mut v = 0.0;
        for it in &loads.spatial {
            let s = scales[it.load];
            let k = it.element;
            match it.kind {
                SpatialKind::Force {
                    value,
                    arm,
                    follower: false,
                } => {
                    let x = add(
                        &fr.p[k],
                        &scale(arm / self.beam.reference.lengths[k], &fr.d[k]),
                    );
                    v -= s * super::algebra::dot(&value, &x);
                }
                SpatialKind::Distributed {
                    resultant,
                    first_moment,
                    follower: false,
                } => {
                    let t = scale(1.0 / self.beam.reference.lengths[k], &fr.d[k]);
                    v -= s
                        * (super::algebra::dot(&resultant, &fr.p[k])
                            + super::algebra::dot(&first_moment, &t));
                }
                SpatialKind::Gravity(a) => {
                    for e in 0..self.n {
                        let g = add(&fr.p[e], &fr.arm[e]);
                        v -= s * self.beam.masses[e] * super::algebra::dot(&a, &g);
                    }
                }
                _ => {}
            }
        }
        v
    }
}
