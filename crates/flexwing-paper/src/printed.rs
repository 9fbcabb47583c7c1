//! The numbers the paper prints, for the "paper" columns of the tables (clearly labelled as
//! such): Veronese, Ribeiro & Moreira, *Reduced order modeling of highly flexible structures*
//! (COBEM 2021), section 5.

/// Table 2 as printed: per mode, (lumped n = 16, semi-analytical, error %) and the same at n = 32.
pub const TABLE2: [[f64; 6]; 9] = [
    [2.21, 2.21, 0.02, 2.21, 2.21, 0.01],
    [9.55, 9.55, 0.01, 9.55, 9.55, 0.00],
    [13.78, 13.80, 0.10, 13.79, 13.80, 0.03],
    [27.39, 27.40, 0.02, 27.40, 27.40, 0.01],
    [36.38, 36.66, 0.76, 36.59, 36.66, 0.19],
    [46.69, 46.95, 0.56, 46.88, 46.95, 0.16],
    [63.14, 64.02, 1.38, 63.79, 64.02, 0.37],
    [65.05, 66.52, 2.21, 65.96, 66.52, 0.84],
    [80.53, 86.71, 7.14, 83.08, 86.71, 4.19],
];

/// Table 3 (tip force, n = 20): CPU time of the reduced models relative to the full one.
pub const TABLE3_RATIOS: [(usize, f64); 2] = [(2, 0.32), (3, 0.36)];
/// Table 5 (two forces, n = 10): CPU time of the reduced models relative to the full one.
pub const TABLE5_RATIOS: [(usize, f64); 2] = [(2, 0.34), (3, 0.32)];
/// Table 6: mean absolute and relative error of the finite-difference gradient, its CPU ratio.
pub const TABLE6: (f64, f64, f64) = (8.99e-10, 1.26e-8, 0.084);
/// Table 7: CPU time of the simplified model relative to the full one (n = 10).
pub const TABLE7_RATIO: f64 = 0.197;
/// Table 8: CPU time of the reduced model (r = 2) relative to the full one (n = 20).
pub const TABLE8_RATIO: f64 = 0.146;
/// Figure 5: the largest relative error of the simplified model the paper reports.
pub const FIGURE5_MAX_ERROR: f64 = 0.04;
