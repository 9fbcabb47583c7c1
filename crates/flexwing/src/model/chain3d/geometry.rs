//! The reference (stress-free) geometry of the 3-D chain: where the nodes are and how each
//! element's section frame `(t, n, c)` is oriented before any load (docs/chain3d-model.md,
//! "Reference geometry").
//!
//! * [`Geometry3d::Span`]: a reference axis of arc length `L` from the root, turned along the
//!   span by sweep `Λ(s)`, dihedral `Γ(s)` and pretwist `β(s)` (tables over the span, rad). The
//!   section frame at `s` is `R(s) = R_y(Λ) R_z(Γ) R_x(−β)`: sweep back (tip toward `−z`, aft)
//!   positive, dihedral tip up positive, pretwist nose-up positive (a rotation about `−t`, the
//!   planar model's sign). Element `i` takes the frame at its midpoint and is the straight chord
//!   `P_{i+1} = P_i + ℓ_i t_i` (the midpoint rule: second order in the element length).
//! * [`Geometry3d::Curve`]: the nodes themselves (a polyline from the root at the origin, e.g.
//!   points of a curved beam) and a section normal `n` at each node; element `i` is the chord
//!   between nodes `i` and `i + 1`, its `n` the mean of its nodes' normals made orthogonal to the
//!   chord, `c = t × n`.
//!
//! The clamp frame is the global frame; joint `i` joins element `i − 1` (the clamp for `i = 0`)
//! to element `i`, with the stress-free relative rotation `R⁰_i = R_{i−1}ᵀ R_i` of the reference
//! frames.

use super::algebra::{cross, dot, mm, mtm, M3, V3};
use crate::beam::profile::Sign;
use crate::beam::{Discretization, Profile};
use crate::error::InputError;

/// The reference geometry of a 3-D chain.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry3d {
    /// A reference axis of arc length `length` (m), cut at the stations of `discretization`,
    /// oriented along the span by sweep, dihedral and pretwist (rad; zero for a straight
    /// untwisted beam along `x`, with `n = y` and `c = z`).
    Span {
        /// Arc length of the reference axis (m).
        length: f64,
        /// Where the nodes are along the span.
        discretization: Discretization,
        /// Sweep angle `Λ(s)` (rad), positive back.
        sweep: Profile,
        /// Dihedral angle `Γ(s)` (rad), positive tip up.
        dihedral: Profile,
        /// Pretwist `β(s)` (rad), positive nose-up.
        pretwist: Profile,
    },
    /// The chain's nodes on a curve, from the root.
    Curve {
        /// Node positions `P_0 … P_n` (m); `P_0` must be the root, the origin.
        points: Vec<[f64; 3]>,
        /// Section normal `n` at each node (any length, not along the curve).
        normals: Vec<[f64; 3]>,
    },
}

impl Geometry3d {
    /// A straight, untwisted reference axis along `x` of `length`, cut into `n` equal elements.
    pub fn straight(length: f64, n: usize) -> Self {
        Geometry3d::Span {
            length,
            discretization: Discretization::Uniform(n),
            sweep: Profile::Uniform(0.0),
            dihedral: Profile::Uniform(0.0),
            pretwist: Profile::Uniform(0.0),
        }
    }
}

/// The resolved reference geometry: stations, lengths, frames.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Reference {
    /// Node stations along the reference axis (arc length, m), `s_0 = 0 … s_n = L`.
    pub(crate) nodes: Vec<f64>,
    /// Element lengths `ℓ_i`.
    pub(crate) lengths: Vec<f64>,
    /// Reference frame of each element (columns `t, n, c` in global components).
    pub(crate) frames: Vec<M3<f64>>,
    /// Stress-free relative rotation of each joint, `R⁰_i = R_{i−1}ᵀ R_i` (`R_{−1} = I`).
    pub(crate) relative: Vec<M3<f64>>,
    /// Reference node positions `P_0 … P_n` (m).
    pub(crate) positions: Vec<V3<f64>>,
    /// Whether the axis is straight along `x` and untwisted (every frame the identity).
    pub(crate) straight: bool,
}

fn rot_x(a: f64) -> M3<f64> {
    let (s, c) = a.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}
fn rot_y(a: f64) -> M3<f64> {
    let (s, c) = a.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}
fn rot_z(a: f64) -> M3<f64> {
    let (s, c) = a.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn is_zero(p: &Profile) -> bool {
    match p {
        Profile::Uniform(v) => *v == 0.0,
        Profile::Table { value, .. } => value.iter().all(|v| *v == 0.0),
    }
}

fn norm(v: &V3<f64>) -> f64 {
    dot(v, v).sqrt()
}

impl Reference {
    /// Validate and resolve `geometry`; errors name `{prefix}.length`, `{prefix}.sweep`,
    /// `{prefix}.points`, ….
    pub(crate) fn new(prefix: &str, geometry: &Geometry3d) -> Result<Self, InputError> {
        let field = |key: &str| crate::field(prefix, key);
        match geometry {
            Geometry3d::Span {
                length,
                discretization,
                sweep,
                dihedral,
                pretwist,
            } => {
                let length = *length;
                if !(length.is_finite() && length > 0.0) {
                    return Err(InputError::new(
                        field("length"),
                        format!(
                            "must be a finite positive number, got {}",
                            crate::text::short(length)
                        ),
                    ));
                }
                crate::magnitude::check(&field("length"), "", length)?;
                let nodes = crate::beam::stations(prefix, length, discretization)?;
                sweep.validate(&field("sweep"), length, Sign::Any)?;
                dihedral.validate(&field("dihedral"), length, Sign::Any)?;
                pretwist.validate(&field("pretwist"), length, Sign::Any)?;
                let straight = is_zero(sweep) && is_zero(dihedral) && is_zero(pretwist);
                let n = nodes.len() - 1;
                let lengths: Vec<f64> = nodes.windows(2).map(|w| w[1] - w[0]).collect();
                let frames: Vec<M3<f64>> = (0..n)
                    .map(|i| {
                        let s = 0.5 * (nodes[i] + nodes[i + 1]);
                        mm(
                            &mm(&rot_y(sweep.at(s)), &rot_z(dihedral.at(s))),
                            &rot_x(-pretwist.at(s)),
                        )
                    })
                    .collect();
                let mut positions = vec![[0.0; 3]];
                for i in 0..n {
                    let p = positions[i];
                    let t = [frames[i][0][0], frames[i][1][0], frames[i][2][0]];
                    positions.push([
                        p[0] + lengths[i] * t[0],
                        p[1] + lengths[i] * t[1],
                        p[2] + lengths[i] * t[2],
                    ]);
                }
                Ok(Self::finish(nodes, lengths, frames, positions, straight))
            }
            Geometry3d::Curve { points, normals } => {
                let fp = field("points");
                let fnrm = field("normals");
                if points.len() < 2 {
                    return Err(InputError::new(
                        fp,
                        format!(
                            "needs at least two points (one element), got {}",
                            points.len()
                        ),
                    ));
                }
                if points.len() - 1 > crate::beam::MAX_ELEMENTS {
                    return Err(InputError::new(
                        fp,
                        format!(
                            "at most {} elements are supported, got {}",
                            crate::beam::MAX_ELEMENTS,
                            points.len() - 1
                        ),
                    ));
                }
                if normals.len() != points.len() {
                    return Err(InputError::new(
                        fnrm,
                        format!(
                            "needs one normal per point ({}), got {}",
                            points.len(),
                            normals.len()
                        ),
                    ));
                }
                for (k, p) in points.iter().chain(normals.iter()).enumerate() {
                    let (f, k) = if k < points.len() {
                        (&fp, k)
                    } else {
                        (&fnrm, k - points.len())
                    };
                    for (a, v) in p.iter().enumerate() {
                        if !v.is_finite() {
                            return Err(InputError::new(
                                f.clone(),
                                format!("[{k}][{a}] must be finite, got {v}"),
                            ));
                        }
                        crate::magnitude::check(f, &format!("[{k}][{a}]"), *v)?;
                    }
                }
                let n = points.len() - 1;
                let mut lengths = Vec::with_capacity(n);
                let mut tangents = Vec::with_capacity(n);
                for i in 0..n {
                    let d = [
                        points[i + 1][0] - points[i][0],
                        points[i + 1][1] - points[i][1],
                        points[i + 1][2] - points[i][2],
                    ];
                    let l = norm(&d);
                    lengths.push(l);
                    tangents.push([d[0] / l, d[1] / l, d[2] / l]);
                }
                let total: f64 = lengths.iter().sum();
                if !(total > 0.0) {
                    return Err(InputError::new(fp, "the points do not span any length"));
                }
                let tol = 1e-12 * total;
                if norm(&points[0]) > tol {
                    return Err(InputError::new(
                        fp,
                        format!(
                            "must start at the root, the origin (0, 0, 0), got ({}, {}, {})",
                            crate::text::short(points[0][0]),
                            crate::text::short(points[0][1]),
                            crate::text::short(points[0][2])
                        ),
                    ));
                }
                for (i, &l) in lengths.iter().enumerate() {
                    if !(l > 1e-9 * total) {
                        return Err(InputError::new(
                            fp,
                            format!(
                                "element {} (points [{i}] and [{}]) has zero length: \
                                 consecutive points must differ",
                                i + 1,
                                i + 1
                            ),
                        ));
                    }
                }
                let mut frames = Vec::with_capacity(n);
                for i in 0..n {
                    let t = tangents[i];
                    let (a, b) = (normals[i], normals[i + 1]);
                    let (na, nb) = (norm(&a), norm(&b));
                    if !(na > 0.0 && nb > 0.0) {
                        let k = if na > 0.0 { i + 1 } else { i };
                        return Err(InputError::new(
                            fnrm,
                            format!("[{k}] is zero: a normal needs a direction"),
                        ));
                    }
                    let m = [
                        0.5 * (a[0] / na + b[0] / nb),
                        0.5 * (a[1] / na + b[1] / nb),
                        0.5 * (a[2] / na + b[2] / nb),
                    ];
                    let along = dot(&m, &t);
                    let perp = [
                        m[0] - along * t[0],
                        m[1] - along * t[1],
                        m[2] - along * t[2],
                    ];
                    let pn = norm(&perp);
                    if !(pn > 1e-6) {
                        return Err(InputError::new(
                            fnrm,
                            format!(
                                "[{i}] and [{}] lie along element {} (or cancel): the section \
                                 normal must have a component across the element",
                                i + 1,
                                i + 1
                            ),
                        ));
                    }
                    let nn = [perp[0] / pn, perp[1] / pn, perp[2] / pn];
                    let c = cross(&t, &nn);
                    frames.push([
                        [t[0], nn[0], c[0]],
                        [t[1], nn[1], c[1]],
                        [t[2], nn[2], c[2]],
                    ]);
                }
                let mut nodes = vec![0.0];
                for l in &lengths {
                    nodes.push(nodes[nodes.len() - 1] + l);
                }
                let mut positions: Vec<V3<f64>> = points.clone();
                positions[0] = [0.0; 3];
                let straight = frames.iter().all(|f| {
                    (0..3).all(|r| (0..3).all(|c| f[r][c] == if r == c { 1.0 } else { 0.0 }))
                });
                Ok(Self::finish(nodes, lengths, frames, positions, straight))
            }
        }
    }

    fn finish(
        nodes: Vec<f64>,
        lengths: Vec<f64>,
        frames: Vec<M3<f64>>,
        positions: Vec<V3<f64>>,
        straight: bool,
    ) -> Self {
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let relative = (0..frames.len())
            .map(|i| {
                if i == 0 {
                    frames[0]
                } else {
                    mtm(&frames[i - 1], &frames[i])
                }
            })
            .collect::<Vec<_>>();
        let relative = if straight {
            vec![identity; frames.len()]
        } else {
            relative
        };
        Self {
            nodes,
            lengths,
            frames,
            relative,
            positions,
            straight,
        }
    }

    /// Length of the reference axis (m).
    pub(crate) fn length(&self) -> f64 {
        self.nodes[self.nodes.len() - 1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_and_dihedral_turn_the_axis_as_named() {
        let g = Geometry3d::Span {
            length: 2.0,
            discretization: Discretization::Uniform(2),
            sweep: Profile::Uniform(0.3),
            dihedral: Profile::Uniform(0.1),
            pretwist: Profile::Uniform(0.2),
        };
        let r = Reference::new("beam", &g).unwrap();
        let tip = r.positions[2];
        // Tip: 2 (cos Λ cos Γ, sin Γ, −sin Λ cos Γ): aft (−z) and up (+y).
        let want = [
            2.0 * 0.3f64.cos() * 0.1f64.cos(),
            2.0 * 0.1f64.sin(),
            -2.0 * 0.3f64.sin() * 0.1f64.cos(),
        ];
        for k in 0..3 {
            assert!((tip[k] - want[k]).abs() < 1e-15, "{tip:?} vs {want:?}");
        }
        // Nose-up pretwist lifts the leading edge c toward +n.
        let f = r.frames[0];
        let c = [f[0][2], f[1][2], f[2][2]];
        let n = [f[0][1], f[1][1], f[2][1]];
        let up = [0.0, 1.0, 0.0];
        assert!(dot(&c, &up) > 0.0 && dot(&n, &up) > 0.0);
        // Uniform angles: the joints between elements carry no relative rotation.
        let rel = r.relative[1];
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((rel[i][j] - e).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn a_curve_must_start_at_the_root_and_have_no_zero_length_element() {
        let normals = vec![[0.0, 0.0, 1.0]; 3];
        let e = Reference::new(
            "beam",
            &Geometry3d::Curve {
                points: vec![[1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]],
                normals: normals.clone(),
            },
        )
        .unwrap_err();
        assert_eq!(e.field, "beam.points");
        assert!(e.reason.contains("root"), "{e}");
        let e = Reference::new(
            "beam",
            &Geometry3d::Curve {
                points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
                normals: normals.clone(),
            },
        )
        .unwrap_err();
        assert!(e.reason.contains("zero length"), "{e}");
        let e = Reference::new(
            "beam",
            &Geometry3d::Curve {
                points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
                normals: vec![[1.0, 0.0, 0.0]; 3],
            },
        )
        .unwrap_err();
        assert_eq!(e.field, "beam.normals");
    }
}
