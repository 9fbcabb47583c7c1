//! flexwing's output formats, shared by the CLI and the Python package: CSV without non-finite
//! cells (`csv.rs`), MATLAB's MAT-file
//! (level 5, `matfile.rs`) and NumPy's `.npz` (`npz.rs`) from one list of named values, VTK's
//! XML files for ParaView (`vtk.rs`), and the atomic write every result file goes through
//! (`atomic.rs`), so that an interrupted run never leaves a file that looks complete.

pub mod atomic;
pub mod csv;
pub mod matfile;
pub mod nodes;
pub mod npz;
pub mod vtk;

pub use atomic::{write_atomic, write_bytes};

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
    /// A column of whole numbers (indices).
    Ints(Vec<i64>),
    /// A real array of any rank, row-major (C order: the last index varies fastest), as NumPy
    /// lays arrays out by default.
    Array {
        /// The extent of each index.
        shape: Vec<usize>,
        /// Row-major entries, `shape.iter().product()` of them.
        data: Vec<f64>,
    },
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
    /// The entries of the value in column-major order (MATLAB's layout; for strings none).
    pub(crate) fn column_major(&self) -> Vec<f64> {
        match self {
            Value::Matrix { data, .. } => data.clone(),
            Value::Complex(_) | Value::Strings(_) => Vec::new(),
            Value::Ints(v) => v.iter().map(|&i| i as f64).collect(),
            Value::Array { shape, data } => {
                // Row-major strides; walk the indices with the first varying fastest.
                let mut out = Vec::with_capacity(data.len());
                let mut index = vec![0usize; shape.len()];
                let mut strides = vec![1usize; shape.len()];
                for k in (0..shape.len().saturating_sub(1)).rev() {
                    strides[k] = strides[k + 1] * shape[k + 1];
                }
                for _ in 0..data.len() {
                    out.push(
                        data[index
                            .iter()
                            .zip(&strides)
                            .map(|(i, s)| i * s)
                            .sum::<usize>()],
                    );
                    for (i, n) in index.iter_mut().zip(shape) {
                        *i += 1;
                        if *i < *n {
                            break;
                        }
                        *i = 0;
                    }
                }
                out
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn column_major_order_of_a_row_major_array() {
        // [[1, 2, 3], [4, 5, 6]] row-major is 1 4 2 5 3 6 column-major.
        let a = Value::Array {
            shape: vec![2, 3],
            data: vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        };
        assert_eq!(a.column_major(), [1.0, 4.0, 2.0, 5.0, 3.0, 6.0]);
    }
}
