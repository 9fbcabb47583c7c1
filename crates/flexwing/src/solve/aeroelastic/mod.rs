//! Aeroelastic analyses (docs/aeroelastic-model.md §5): the equations of motion with strip
//! aerodynamics, static aeroelastic equilibrium and divergence, stability and flutter, the
//! frequency-domain (p-k) check, time responses to gusts and manoeuvres, and the flutter study
//! against a load level (`study.rs`), on the planar chain and the 3-D chain.

mod audit;
mod balance;
mod clu;
mod equations;
mod evaluator;
pub(crate) mod flight;
mod linear;
mod schur;

pub use equations::{AeroelasticEquations, LinearSystem};
pub use flight::{
    kussner_fit, FlightHistory, Gust, GustPenetration, GustShape, KUSSNER_A, KUSSNER_BETA,
};
pub use schur::AeroNewtonSystems;
mod statics;

pub use statics::{
    static_sweep, static_sweep_polled, AeroEquilibrium, AeroStaticOptions, AeroStaticSolution,
    Divergence, DivergenceBasis, SteadyAeroModel, SteadyAeroWorkspace,
};
mod flutter;
mod linearize;
mod signals;
mod tracking;
pub mod turbulence;

pub use flutter::{
    flutter, flutter_polled, stability_eigenvalues, Branch, Crossing, CrossingKind, FlutterMethod,
    FlutterOptions, FlutterSolution, FlutterStats, FlutterStop, MAC_MIN, MAX_MERGED_STEPS,
    MAX_SUBSTEPS,
};
mod response;

pub use linearize::{linearize, poles, LinearizeOptions, StateSpace};
pub use signals::{Input, Output, Signal, StateBasis, INPUT_NAMES, OUTPUT_NAMES};

pub use response::{response, ResponseOptions, ResponseSample, ResponseSolution};
mod study;

pub use study::{
    deflection_study, DeflectionPoint, DeflectionStudyOptions, DeflectionStudySolution,
    StudyParameter,
};
