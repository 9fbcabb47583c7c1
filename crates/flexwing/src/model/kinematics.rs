//! Absolute angles and their sines and cosines for one configuration.

/// Trigonometry of one configuration `q`, computed once and shared by the mass matrix, the
/// gyroscopic term and the generalized forces. Build with [`Kinematics::new`], refresh with
/// [`Kinematics::update`] (no allocation).
#[derive(Debug, Clone, PartialEq)]
pub struct Kinematics {
    /// Absolute bending angles `θ_i` (rad).
    pub theta: Vec<f64>,
    /// `cos θ_i`.
    pub cos_theta: Vec<f64>,
    /// `sin θ_i`.
    pub sin_theta: Vec<f64>,
    /// Absolute twists `ψ_i` (rad); zeros in a bending-only model.
    pub psi: Vec<f64>,
    /// `cos ψ_i`.
    pub cos_psi: Vec<f64>,
    /// `sin ψ_i`.
    pub sin_psi: Vec<f64>,
}

impl Kinematics {
    /// Storage for a chain of `n` elements, at the undeformed state.
    pub fn new(n: usize) -> Self {
        Self {
            theta: vec![0.0; n],
            cos_theta: vec![1.0; n],
            sin_theta: vec![0.0; n],
            psi: vec![0.0; n],
            cos_psi: vec![1.0; n],
            sin_psi: vec![0.0; n],
        }
    }

    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.theta.len()
    }

    /// Recompute from joint rotations `q` (length `n` or `2n`).
    ///
    /// # Panics
    /// If `q` has neither `n` nor `2n` entries.
    pub fn update(&mut self, q: &[f64]) {
        let n = self.n_elements();
        assert!(
            q.len() == n || q.len() == 2 * n,
            "q has {} entries for {n} elements",
            q.len()
        );
        let mut th = 0.0;
        for i in 0..n {
            th += q[i];
            self.theta[i] = th;
            (self.sin_theta[i], self.cos_theta[i]) = th.sin_cos();
        }
        if q.len() == 2 * n {
            let mut ps = 0.0;
            for i in 0..n {
                ps += q[n + i];
                self.psi[i] = ps;
                (self.sin_psi[i], self.cos_psi[i]) = ps.sin_cos();
            }
        } else {
            self.psi.fill(0.0);
            self.sin_psi.fill(0.0);
            self.cos_psi.fill(1.0);
        }
    }
}
