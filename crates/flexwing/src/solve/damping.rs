//! Structural damping `C` (docs/model.md, "Equations of motion"; the choices in
//! docs/model-choices.md, "Damping") and the operator `v ↦ C v` that the equations of motion apply
//! to the velocities at every right-hand side.
//!
//! * Rayleigh, `C = α M(0) + β K`; modal, `C = M₀ Φ diag(2 ζ_k ω_k) Φᵀ M₀` over the modes given a
//!   ratio (`Φᵀ M₀ Φ = I`, `M₀ = M(0)`, `ω_k = √max(λ_k, 0)` of `K φ = λ M₀ φ`).
//! * For the full model `C` is never formed: `M(0) v` is the momentum of the velocities `v` at the
//!   undeformed configuration, the O(n) recursion of `model::kinetic` (its trigonometry computed
//!   once, in the operator's own workspace), and `K` is diagonal, so Rayleigh's `C v` is O(n);
//!   modal damping is the rank-`r` product `U diag(2 ζ_k ω_k) Uᵀ v` with `U = M₀ Φ_r`, O(n r),
//!   the `r` lowest modes from [`Modes::lowest`] (Lanczos from 48 coordinates on: O(n r²) once).
//! * Other models (a reduced model: `r × r`) form `C` densely, as the formulas say.
//!
//! The dense Jacobian (small models) needs `C` itself: [`DampingOperator::matrix`] forms it from
//! the operator, column by column.

use nalgebra::DMatrix;

use super::generalized_symmetric_eigen;
use super::modes::Modes;
use crate::error::InputError;
use crate::model::StructuralModel;
use crate::text::short;

/// Structural damping `C`.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Damping {
    /// No damping.
    #[default]
    None,
    /// Rayleigh: `C = α M(0) + β K`.
    Rayleigh {
        /// Mass-proportional coefficient `α` (1/s).
        alpha: f64,
        /// Stiffness-proportional coefficient `β` (s).
        beta: f64,
    },
    /// Modal damping ratios `ζ_k` of the first modes about the undeformed state:
    /// `C = M₀ Φ diag(2 ζ_k ω_k) Φᵀ M₀` over the modes given (others undamped).
    Modal {
        /// Damping ratios of modes 1, 2, … (dimensionless).
        ratios: Vec<f64>,
    },
}

impl Damping {
    /// Check the coefficients for a model of `n_dofs` coordinates; errors name
    /// `{field}.alpha`, `{field}.ratios[k]`, ….
    ///
    /// # Errors
    /// A coefficient or ratio that is not finite and non-negative, more ratios than modes.
    pub fn validate(&self, field: &str, n_dofs: usize) -> Result<(), InputError> {
        let check = |name: &str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                crate::magnitude::check(&crate::field(field, name), "", v).map(|_| ())
            } else {
                Err(InputError::new(
                    crate::field(field, name),
                    format!("must be a finite non-negative number, got {}", short(v)),
                ))
            }
        };
        match self {
            Damping::None => Ok(()),
            Damping::Rayleigh { alpha, beta } => {
                check("alpha", *alpha)?;
                check("beta", *beta)
            }
            Damping::Modal { ratios } => {
                if ratios.len() > n_dofs {
                    return Err(InputError::new(
                        crate::field(field, "ratios"),
                        format!(
                            "{} ratios given but the model has {n_dofs} modes",
                            ratios.len()
                        ),
                    ));
                }
                for (i, z) in ratios.iter().enumerate() {
                    check(&format!("ratios[{i}]"), *z)?;
                }
                Ok(())
            }
        }
    }
}

/// `v ↦ C v` for one model's damping, allocation-free after construction (module documentation).
pub(crate) struct DampingOperator<M: StructuralModel> {
    kind: Kind<M>,
}

enum Kind<M: StructuralModel> {
    /// `C = 0`.
    None,
    /// `C` formed (models other than the full model).
    Dense(DMatrix<f64>),
    /// Full model: `α M(0) v + β K v`.
    Rayleigh {
        alpha: f64,
        beta: f64,
        /// The diagonal of `K`.
        stiffness: Vec<f64>,
        /// `x = 0`, and a workspace that stays configured there.
        x0: Vec<f64>,
        ws: M::Workspace,
    },
    /// Full model: `U diag(w) Uᵀ v`, `U = M₀ Φ_r` (`n × r`), `w_k = 2 ζ_k ω_k`.
    LowRank {
        u: DMatrix<f64>,
        weights: Vec<f64>,
        /// Scratch of length `r`: `diag(w) Uᵀ v`.
        coefficients: Vec<f64>,
    },
}

impl<M: StructuralModel> DampingOperator<M> {
    /// The operator of `damping` for `model`; `field` names the damping in errors.
    ///
    /// # Errors
    /// The errors of [`Damping::validate`] (fields `{field}.*`); for modal damping, modes that
    /// cannot be computed (field `field`) or that double precision does not resolve (field
    /// `{field}.ratios`, only for the highest modes of a large model, [`Modes::lowest`]).
    pub(crate) fn new(model: &M, damping: &Damping, field: &str) -> Result<Self, InputError> {
        let n = model.n_dofs();
        damping.validate(field, n)?;
        let kind = match (damping, model.as_full_model()) {
            (Damping::None, _) => Kind::None,
            (Damping::Modal { ratios }, _) if ratios.is_empty() => Kind::None,
            (Damping::Rayleigh { alpha, beta }, Some(full)) => Kind::Rayleigh {
                alpha: *alpha,
                beta: *beta,
                stiffness: full.stiffness().to_vec(),
                x0: vec![0.0; n],
                ws: model.workspace(),
            },
            (Damping::Modal { ratios }, Some(full)) => {
                let modes = Modes::lowest(full, ratios.len())
                    .map_err(|e| InputError::new(field, e.to_string()))?;
                if modes.n_modes() < ratios.len() {
                    return Err(InputError::new(
                        crate::field(field, "ratios"),
                        format!(
                            "{} ratios given but double precision resolves only the {} lowest \
                             modes of this model",
                            ratios.len(),
                            modes.n_modes()
                        ),
                    ));
                }
                let (x0, mut ws) = (vec![0.0; n], model.workspace());
                let mut u = DMatrix::zeros(n, ratios.len());
                for (k, mut col) in u.column_iter_mut().enumerate() {
                    let phi = modes.shapes().column(k);
                    model.momentum_into(&x0, phi.as_slice(), &mut ws, col.as_mut_slice());
                }
                let weights = ratios
                    .iter()
                    .zip(modes.omega())
                    .map(|(z, w)| 2.0 * z * w)
                    .collect();
                Kind::LowRank {
                    u,
                    weights,
                    coefficients: vec![0.0; ratios.len()],
                }
            }
            (_, None) => Kind::Dense(dense_damping(model, damping, field)?),
        };
        Ok(Self { kind })
    }

    /// `out = C v` (zeros without damping). No allocation.
    pub(crate) fn apply(&mut self, model: &M, v: &[f64], out: &mut [f64]) {
        match &mut self.kind {
            Kind::None => out.fill(0.0),
            Kind::Dense(c) => {
                for (i, o) in out.iter_mut().enumerate() {
                    *o = c.row(i).iter().zip(v).map(|(a, b)| a * b).sum();
                }
            }
            Kind::Rayleigh {
                alpha,
                beta,
                stiffness,
                x0,
                ws,
            } => {
                model.momentum_into(x0, v, ws, out);
                for ((o, k), v) in out.iter_mut().zip(stiffness.iter()).zip(v) {
                    *o = *alpha * *o + *beta * k * v;
                }
            }
            Kind::LowRank {
                u,
                weights,
                coefficients,
            } => {
                for ((c, col), w) in coefficients
                    .iter_mut()
                    .zip(u.column_iter())
                    .zip(weights.iter())
                {
                    *c = w * col.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
                }
                out.fill(0.0);
                for (col, c) in u.column_iter().zip(coefficients.iter()) {
                    for (o, a) in out.iter_mut().zip(col.iter()) {
                        *o += a * c;
                    }
                }
            }
        }
    }

    /// `C` itself (`n × n`; `None` without damping), for the dense Jacobian: the dense matrix
    /// when the operator holds one, else the operator applied to the unit vectors, O(n²)
    /// (Rayleigh) or O(n² r) (modal).
    pub(crate) fn matrix(&mut self, model: &M) -> Option<DMatrix<f64>> {
        match &self.kind {
            Kind::None => None,
            Kind::Dense(c) => Some(c.clone()),
            _ => {
                let n = model.n_dofs();
                let mut c = DMatrix::zeros(n, n);
                let mut unit = vec![0.0; n];
                for j in 0..n {
                    unit[j] = 1.0;
                    self.apply(model, &unit, c.column_mut(j).as_mut_slice());
                    unit[j] = 0.0;
                }
                Some(c)
            }
        }
    }
}

/// `C` formed densely from the formulas (module documentation): the path of the models other
/// than the full model, whose `r × r` matrices are small.
pub(super) fn dense_damping<M: StructuralModel>(
    model: &M,
    damping: &Damping,
    field: &str,
) -> Result<DMatrix<f64>, InputError> {
    let n = model.n_dofs();
    let x0 = vec![0.0; n];
    let mut m0 = DMatrix::zeros(n, n);
    model.mass_matrix_into(&x0, &mut model.workspace(), &mut m0);
    match damping {
        Damping::None => Ok(DMatrix::zeros(n, n)),
        Damping::Rayleigh { alpha, beta } => Ok(&m0 * *alpha + model.stiffness_matrix() * *beta),
        Damping::Modal { ratios } => {
            let (lambda, phi) = generalized_symmetric_eigen(&model.stiffness_matrix(), &m0)
                .map_err(|e| InputError::new(field, e.to_string()))?;
            let mut c = DMatrix::zeros(n, n);
            for (k, z) in ratios.iter().enumerate() {
                let u = &m0 * phi.column(k);
                c += &u * u.transpose() * (2.0 * z * lambda[k].max(0.0).sqrt());
            }
            Ok(c)
        }
    }
}

#[cfg(test)]
mod tests;
