//! The library's integration tests, in one test binary: one link and one instantiation of the
//! generic code for all of them, instead of one per file (the test build of a fresh clone took
//! about half its compile time linking and optimizing the same generics into 40 binaries).
//! One module per validated case, as the files were; `cargo test --release -p flexwing --test suite
//! MODULE::` runs one of them.

mod aero3d_linearize;
mod aero3d_patil_deformed;
mod aero3d_planar_limit;
mod aero_chain_reference;
mod aero_convergence;
mod aero_flutter;
mod aero_gust;
mod aero_gust_family;
mod aero_linear_matrices;
mod aero_linearize;
mod aero_reduced;
mod aero_response;
mod aero_statics;
mod aero_surfaces;
mod aero_turbulence;
mod aero_typical_section;
mod architecture;
mod bad_input;
mod chain3d_bathe_bolourchi;
mod chain3d_dynamics;
mod chain3d_modes;
mod chain3d_newton_systems;
mod chain3d_planar_limit;
mod chain3d_reduced;
mod chain3d_statics;
mod common;
mod coupled_table2;
mod dynamics;
mod euler_bernoulli_modes;
mod generalized_alpha;
mod linear_consistency;
mod model_properties;
mod modes_large_n;
mod newton_systems;
mod rotary_inertia;
mod statics_arclength;
mod statics_closed_form;
mod statics_elastica;
mod statics_path;
mod tolerances;
mod torsion_modes;
