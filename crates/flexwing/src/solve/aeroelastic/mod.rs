//! Aeroelastic analyses (docs/aeroelastic-model.md §5): the equations of motion with strip
//! aerodynamics, static aeroelastic equilibrium and divergence, stability and flutter, the
//! frequency-domain (p-k) check, and time responses to gusts and manoeuvres.

mod audit;
mod balance;
mod clu;
mod equations;
mod evaluator;
mod flight;
mod linear;
mod schur;

pub use equations::{AeroelasticEquations, LinearSystem};
pub use flight::{FlightHistory, Gust, GustShape};
pub use schur::AeroNewtonSystems;
mod statics;

pub use statics::{
    static_sweep, static_sweep_polled, AeroEquilibrium, Divergence, DivergenceBasis,
    StaticAeroOutcome, StaticAeroPlan, SteadyAeroModel, SteadyAeroWorkspace,
};
mod flutter;

pub use flutter::{
    flutter, flutter_polled, stability_eigenvalues, Branch, Crossing, CrossingKind, FlutterMethod,
    FlutterOutcome, FlutterPlan, FlutterStats, FlutterStop, MAC_MIN, MAX_MERGED_STEPS,
    MAX_SUBSTEPS,
};
mod response;

pub use response::{response, ResponseOutcome, ResponsePlan, ResponseSample};
