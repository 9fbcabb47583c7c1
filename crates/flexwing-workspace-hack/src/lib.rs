//! No code: this crate only fixes the features of shared dependencies so that every command
//! builds them once (see its Cargo.toml).
