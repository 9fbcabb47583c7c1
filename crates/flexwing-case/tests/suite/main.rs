//! The case crate's integration tests, in one test binary: one link and one instantiation of the
//! generic code for all of them, instead of one per file (the test build of a fresh clone took
//! about half its compile time linking and optimizing the same generics into 40 binaries).
//! One module per validated case, as the files were; `cargo test --release -p flexwing-case --test suite
//! MODULE::` runs one of them.

mod case_files;
mod documented_keys;
mod fuzz_case_files;
mod mutate;
