//! The fluid's inertia (apparent mass) in the kinetic energy of the chain
//! (docs/aeroelastic-model.md §3).
//!
//! Theodorsen's non-circulatory acceleration loads are exactly those of the fluid kinetic energy
//! per unit span `T_f = ½ πρb² (Ẋ(ζ_m)·ν)² + ½ (πρb⁴/8) ψ̇²` (Bisplinghoff, Ashley & Halfman §5-6).
//! Per element `i` this is a *directional* mass `m_a = πρb²ℓ` acting only along the section
//! normal `ν_i = cos ψ_i n_i − sin ψ_i ẑ` at mid-chord (station `ζ_m = a b`), plus a polar inertia
//! `J_a = πρb⁴ℓ/8`. With the node velocity `V_{i−1} = Σ_{j<i} ℓ_j θ̇_j n_j`, its normal velocity is
//!
//! ```text
//! u_i = ν_i·Ẋ_i(ζ_m) = cos ψ_i (n_i·V_{i−1}) + (ℓ_i/2) cos ψ_i θ̇_i + ζ_m,i ψ̇_i
//! ```
//!
//! (`ν·e = 0`, `ν·n = cos ψ`, `ẑ·V = 0`), and `T_f = ½ Σ m_a,i u_i² + ½ Σ J_a,i ψ̇_i²`. Its terms in
//! the chain recursions, in absolute angles, with the outboard sum `S^f_j = Σ_{i>j} m_a,i u_i cos ψ_i n_i`:
//!
//! ```text
//! ∂T_f/∂θ̇_j = ℓ_j n_j·S^f_j + m_a,j u_j (ℓ_j/2) cos ψ_j
//! ∂T_f/∂ψ̇_j = m_a,j u_j ζ_m,j + J_a,j ψ̇_j
//! ∂T_f/∂θ_j = −ℓ_j θ̇_j e_j·S^f_j − m_a,j u_j cos ψ_j e_j·V_{j−1}
//! ∂T_f/∂ψ_j = −m_a,j u_j sin ψ_j (n_j·V_{j−1} + (ℓ_j/2) θ̇_j)
//! ```
//!
//! (`model::kinetic`); the mass matrix gains `Σ_i m_a,i r_i r_iᵀ + J_a,i` with `r_i = ∂u_i/∂(θ̇, ψ̇)`,
//! assembled in O(n²) with suffix sums of `m_a cos²ψ (cos²θ, cos θ sin θ, sin²θ)` (`model::mass`);
//! and each step of the Riccati sweep of `model::chain_solve` gains the rank-one terms of
//! `½ m_a (rᵀV + βᵀu)²`, `r = cos ψ n`, `β = ((ℓ/2) cos ψ, ζ_m)`: `H += m_a ββᵀ + diag(0, J_a)`,
//! `G += m_a β rᵀ`, `P += m_a r rᵀ`.

/// Per-element fluid inertia of the chain (all vectors of length `n`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FluidInertia {
    /// Directional apparent mass `m_a,i = πρ b_i² ℓ_i` along the section normal (kg).
    pub(crate) mass: Vec<f64>,
    /// Mid-chord station `ζ_m,i = a_i b_i`, toward the leading edge from the elastic axis (m).
    pub(crate) station: Vec<f64>,
    /// Polar apparent inertia `J_a,i = πρ b_i⁴ ℓ_i / 8` (kg·m²).
    pub(crate) inertia: Vec<f64>,
}

#[cfg(test)]
mod tests {
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties,
        TorsionProperties,
    };
    use crate::model::{FullModel, ReducedModel, StructuralModel};
    use crate::solve::Modes;
    use nalgebra::{DMatrix, DVector};

    use super::FluidInertia;

    fn wet(torsion: bool) -> FullModel {
        wet_n(torsion, 6)
    }

    fn wet_n(torsion: bool, n: usize) -> FullModel {
        let section = SectionProperties {
            ei: Profile::Uniform(10.0),
            mass_per_length: Profile::Table {
                x: vec![0.0, 2.0],
                value: vec![0.6, 0.2],
            },
            torsion: torsion.then_some(TorsionProperties {
                gj: Profile::Uniform(3.0),
                polar_inertia: Profile::Uniform(0.01),
                inertia_axis: InertiaAxis::MassCentre,
                offset: Profile::Uniform(0.1),
            }),
        };
        let beam = Beam::new(
            2.0,
            &section,
            &Discretization::Uniform(n),
            Calibration::TipLoad,
        )
        .unwrap();
        let fluid = FluidInertia {
            mass: (0..n).map(|i| 0.05 + 0.01 * i as f64).collect(),
            station: (0..n).map(|i| -0.04 + 0.015 * i as f64).collect(),
            inertia: (0..n).map(|i| 1e-4 * (1.0 + i as f64)).collect(),
        };
        FullModel::new(beam).with_fluid(fluid)
    }

    /// The fluid kinetic energy summed directly from its definition, element by element.
    fn fluid_energy(model: &FullModel, q: &[f64], qd: &[f64]) -> f64 {
        let n = model.n_elements();
        let f = model.fluid.as_ref().unwrap();
        let kin = model.kinematics(q);
        let torsion = model.has_torsion();
        let (mut th_d, mut ps_d) = (0.0, 0.0);
        let mut v = [0.0; 2];
        let mut t = 0.0;
        for i in 0..n {
            th_d += qd[i];
            if torsion {
                ps_d += qd[n + i];
            }
            let (c, s) = (kin.cos_theta[i], kin.sin_theta[i]);
            let (cp, sp) = (kin.cos_psi[i], kin.sin_psi[i]);
            let nv = [-s, c, 0.0];
            let e = [c, s, 0.0];
            let nu = [cp * nv[0], cp * nv[1], -sp];
            let h = 0.5 * model.ell[i];
            // Ẋ(ζ) = ċ + ζ (ψ̇ ν − θ̇ sin ψ e), ċ = V + (ℓ/2) θ̇ n.
            let z = f.station[i];
            let xdot: Vec<f64> = (0..3)
                .map(|k| {
                    let vk = if k < 2 { v[k] } else { 0.0 };
                    vk + h * th_d * nv[k] + z * (ps_d * nu[k] - th_d * sp * e[k])
                })
                .collect();
            let u: f64 = (0..3).map(|k| xdot[k] * nu[k]).sum();
            t += 0.5 * f.mass[i] * u * u + 0.5 * f.inertia[i] * ps_d * ps_d;
            v[0] -= model.ell[i] * s * th_d;
            v[1] += model.ell[i] * c * th_d;
        }
        t
    }

    /// The wet model's kinetic terms against the definition `T = T_structure + T_f`: the mass
    /// matrix (`½ q̇ᵀ M q̇` against the energies summed directly), the O(n) momentum (`M q̇`), the
    /// O(n) velocity solve (`M⁻¹ p` gives `q̇` back) and the gyroscopic term (central differences
    /// of `T` at fixed `q̇`, step 1e-6: truncation ~1e-12, tolerance 1e-7).
    #[test]
    fn fluid_inertia_enters_every_kinetic_term_consistently() {
        for torsion in [false, true] {
            let model = wet(torsion);
            let dry = FullModel::new(model.beam().clone());
            let nd = model.n_dofs();
            let q: Vec<f64> = (0..nd).map(|i| 0.3 * (1.0 + i as f64).sin()).collect();
            let qd: Vec<f64> = (0..nd).map(|i| 0.8 * (2.0 * i as f64).cos()).collect();
            let energy = |q: &[f64]| dry.kinetic_energy(q, &qd) + fluid_energy(&model, q, &qd);
            let mut ws = model.workspace();
            let mut m = DMatrix::zeros(nd, nd);
            model.mass_matrix_into(&q, &mut ws, &mut m);
            let qv = DVector::from_column_slice(&qd);
            let t_matrix = 0.5 * qv.dot(&(&m * &qv));
            assert!(
                (t_matrix - energy(&q)).abs() < 1e-12 * energy(&q),
                "{torsion}"
            );
            let mut p = vec![0.0; nd];
            StructuralModel::momentum_into(&model, &q, &qd, &mut ws, &mut p);
            let mq = &m * &qv;
            for i in 0..nd {
                assert!((p[i] - mq[i]).abs() < 1e-12 * mq.amax());
            }
            let mut back = vec![0.0; nd];
            assert!(model.velocities_into(&q, &p, &mut ws, &mut back));
            for i in 0..nd {
                assert!((back[i] - qd[i]).abs() < 1e-11, "{torsion} {i}");
            }
            let mut gamma = vec![0.0; nd];
            StructuralModel::gyroscopic_into(&model, &q, &qd, &mut ws, &mut gamma);
            let h = 1e-6;
            for i in 0..nd {
                let (mut qp, mut qm) = (q.clone(), q.clone());
                qp[i] += h;
                qm[i] -= h;
                let fd = (energy(&qp) - energy(&qm)) / (2.0 * h);
                assert!(
                    (fd - gamma[i]).abs() < 1e-7,
                    "{torsion} {i}: {fd} vs {}",
                    gamma[i]
                );
            }
        }
    }

    /// The chain's Newton sweeps do not carry the fluid's inertia: a wet model refuses them, and
    /// `Auto` keeps it on the dense path at any size and for any method (48 coordinates here,
    /// above every crossover of `chain_newton_min_dofs` but the fixed step's).
    #[test]
    fn a_wet_model_keeps_dense_newton_systems() {
        use crate::solve::integrate::{integrate, IntegratorSettings, Method};
        use crate::solve::{Damping, EquationsOfMotion, Gyroscopic, NewtonSystems};
        let model = wet_n(true, 24);
        let loads = model.apply(&[], "loads").unwrap();
        let mut eom =
            EquationsOfMotion::new(&model, &loads, vec![], Gyroscopic::Exact, &Damping::None)
                .unwrap();
        let e = eom.set_newton_systems(NewtonSystems::Chain).unwrap_err();
        assert_eq!(e.field, "newton_systems");
        let dry = FullModel::new(model.beam().clone());
        let dry_loads = dry.apply(&[], "loads").unwrap();
        let mut dry_eom =
            EquationsOfMotion::new(&dry, &dry_loads, vec![], Gyroscopic::Exact, &Damping::None)
                .unwrap();
        let y0 = vec![0.0; 2 * model.n_dofs()];
        let settings = IntegratorSettings::default();
        for e in [&mut eom, &mut dry_eom] {
            integrate(
                Method::Radau,
                &settings,
                e,
                0.0,
                &y0,
                &[0.0, 1e-3],
                &mut |_| {},
            )
            .unwrap();
        }
        assert!(!eom.uses_chain_newton() && dry_eom.uses_chain_newton());
    }

    /// The reduced model of a wet full model: `M_r = Φᵀ M Φ` and `γ_r = Φᵀ γ(Φη, Φη̇)` with the
    /// fluid terms (the cached modal fields must carry them).
    #[test]
    fn reduced_wet_model_projects_the_fluid_terms() {
        let full = wet(true);
        let rom =
            ReducedModel::first(&full, Modes::undeformed(&full).unwrap().shapes(), 4).unwrap();
        let nd = full.n_dofs();
        let eta = [0.3, -0.2, 0.1, 0.05];
        let etad = [1.0, 0.4, -2.0, 0.3];
        let q = rom.full_coordinates(&eta);
        let qd = rom.full_coordinates(&etad);
        let phi = rom.basis();
        let mut fws = full.workspace();
        let mut m = DMatrix::zeros(nd, nd);
        full.mass_matrix_into(&q, &mut fws, &mut m);
        let m_r = phi.transpose() * &m * phi;
        let mut ws = rom.workspace();
        let mut got = DMatrix::zeros(4, 4);
        rom.mass_matrix_into(&eta, &mut ws, &mut got);
        assert!((&got - &m_r).amax() < 1e-12 * m_r.amax());
        let mut g = vec![0.0; nd];
        StructuralModel::gyroscopic_into(&full, &q, &qd, &mut fws, &mut g);
        let g_r = phi.transpose() * DVector::from_column_slice(&g);
        let mut gr = vec![0.0; 4];
        rom.gyroscopic_into(&eta, &etad, &mut ws, &mut gr);
        for a in 0..4 {
            assert!((gr[a] - g_r[a]).abs() < 1e-12 * (1.0 + g_r.amax()));
        }
    }
}
