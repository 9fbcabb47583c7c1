//! The command-line tool's integration tests, in one test binary: one link and one instantiation of the
//! generic code for all of them, instead of one per file (the test build of a fresh clone took
//! about half its compile time linking and optimizing the same generics into 40 binaries).
//! One module per validated case, as the files were; `cargo test --release -p flexwing-cli --test suite
//! MODULE::` runs one of them.

mod aero_cmd;
mod bad_input;
mod chain3d_cmd;
mod chain3d_dynamic_cmd;
mod common;
mod dynamic_cmd;
mod examples;
mod flutter_cmd;
mod fmu_cmd;
mod fuzz_runs;
mod gust_cmd;
mod interrupt_cmd;
mod linearize_cmd;
mod reproduce_cmd;
mod section_example;
mod static_cmd;
mod surfaces_cmd;
mod turbulence_cmd;
