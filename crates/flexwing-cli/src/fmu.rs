//! `flexwing fmu`: a co-simulation FMU (FMI 2.0) of the case's aeroelastic response, written by
//! the `flexwing-fmu` crate's writer, carrying the compiled library of that crate (found with
//! `--library`, `FLEXWING_FMU_LIBRARY`, or beside the `flexwing` executable). docs/control.md.

use std::path::PathBuf;

use flexwing::analysis::aero::stepper::Hold;
use flexwing_case::Case;
use flexwing_fmu::description::{find_library, fmu_bytes};
use flexwing_fmu::{write_fmu, FmuError, FmuOptions};

use crate::driver::Failure;

/// Options of `flexwing fmu`.
#[derive(Debug, clap::Args)]
pub struct FmuArgs {
    /// Case file (TOML) with [aero] and [dynamic]; see docs/case-file.md.
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,

    /// The FMU file to write [default: <case file stem>.fmu].
    #[arg(long, short, value_name = "FILE.fmu")]
    pub out: Option<PathBuf>,

    /// Inputs, comma-separated (`root_angle,gust,force[16]`) [default: root_angle,speed,gust].
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub inputs: Option<Vec<String>>,

    /// Outputs, comma-separated (`tip_y,lift`) [default: tip_x, tip_y, (tip_twist),
    /// root_bending_moment, (root_torque), lift].
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub outputs: Option<Vec<String>>,

    /// Index of the model among the case's dynamic models (0: the full model if [dynamic] runs
    /// it, then the reduced ones).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub model: usize,

    /// Start value of the FMU's `hold` parameter: `zero` or `linear`.
    #[arg(long, value_name = "HOLD", default_value = "zero")]
    pub hold: String,

    /// The compiled FMU library (libflexwing_fmu.so) [default: FLEXWING_FMU_LIBRARY, else
    /// beside the flexwing executable].
    #[arg(long, value_name = "PATH")]
    pub library: Option<PathBuf>,
}

/// Run `flexwing fmu`.
pub fn run(args: &FmuArgs) -> Result<(), Failure> {
    let hold = Hold::from_name(&args.hold).ok_or_else(|| {
        Failure::input(format!(
            "--hold: unknown value {:?}; expected \"zero\" or \"linear\"",
            args.hold
        ))
    })?;
    let case = Case::load(&args.case).map_err(Failure::input)?;
    let beside = std::env::current_exe()
        .ok()
        .and_then(|p| p.parent().map(std::path::Path::to_path_buf));
    let options = FmuOptions {
        inputs: args.inputs.clone(),
        outputs: args.outputs.clone(),
        model: args.model,
        hold,
    };
    let library = match find_library(args.library.as_deref(), beside.as_deref()) {
        Ok(library) => library,
        Err(missing) => {
            // A case the FMU cannot carry is the user's first error (exit 2), whether or not the
            // library is built: check it with an empty binary before reporting the library.
            if let Err(FmuError::Input(m)) = fmu_bytes(&case, &options, &[]) {
                return Err(Failure::input(m));
            }
            return Err(Failure::run(missing));
        }
    };
    let out = args.out.clone().unwrap_or_else(|| {
        let stem = args.case.file_stem().unwrap_or_default().to_string_lossy();
        PathBuf::from(format!("{stem}.fmu"))
    });
    let summary = write_fmu(&case, &options, &library, &out).map_err(|e| match e {
        FmuError::Input(m) => Failure::input(m),
        FmuError::Io(m) => Failure::run(m),
    })?;
    println!(
        "wrote {} ({:.1} MB): FMI 2.0 co-simulation, the {} model, binary for {}",
        out.display(),
        summary.bytes as f64 / 1e6,
        summary.model,
        summary.platform
    );
    println!("  inputs:  {}", summary.inputs.join(", "));
    println!("  outputs: {}", summary.outputs.join(", "));
    println!("  parameter: hold = {}", hold.name());
    Ok(())
}
