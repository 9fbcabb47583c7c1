//! Binary formats of the linear models: MATLAB's MAT-file (level 5, `matfile.rs`) and NumPy's
//! `.npz` (`npz.rs`), from one list of named values.

pub mod matfile;
pub mod npz;

/// A named value of a MAT or NPZ file.
pub enum Value {
    /// A real matrix, column-major, `rows × cols`.
    Matrix {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
        /// Column-major entries.
        data: Vec<f64>,
    },
    /// A complex column vector.
    Complex(Vec<(f64, f64)>),
    /// A list of strings (MATLAB: a cell column; NumPy: a unicode array).
    Strings(Vec<String>),
}

impl Value {
    /// A matrix from nalgebra.
    pub fn matrix(m: &nalgebra::DMatrix<f64>) -> Self {
        Value::Matrix {
            rows: m.nrows(),
            cols: m.ncols(),
            data: m.as_slice().to_vec(),
        }
    }
    /// A column vector.
    pub fn column(v: &[f64]) -> Self {
        Value::Matrix {
            rows: v.len(),
            cols: 1,
            data: v.to_vec(),
        }
    }
    /// A scalar.
    pub fn scalar(v: f64) -> Self {
        Value::column(&[v])
    }
}
