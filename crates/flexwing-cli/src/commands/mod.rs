//! One module per subcommand. Each returns a [`Failure`] that says whether the input or the run
//! was at fault, which decides the exit status.

pub mod modes;

use std::fmt::Display;

/// Why a command failed.
#[derive(Debug)]
pub enum Failure {
    /// The input is wrong (command line or case file): exit status 2.
    Input(anyhow::Error),
    /// The run failed (a solver, or writing the results): exit status 1.
    Run(anyhow::Error),
}

impl Failure {
    /// A bad-input failure with the given message.
    pub fn input(message: impl Display) -> Self {
        Self::Input(anyhow::anyhow!("{message}"))
    }
    /// A run failure with the given message.
    pub fn run(message: impl Display) -> Self {
        Self::Run(anyhow::anyhow!("{message}"))
    }
    /// Exit status of the process.
    pub fn exit_status(&self) -> u8 {
        match self {
            Self::Input(_) => 2,
            Self::Run(_) => 1,
        }
    }
    /// The error, for printing.
    pub fn error(&self) -> &anyhow::Error {
        match self {
            Self::Input(e) | Self::Run(e) => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_statuses() {
        assert_eq!(Failure::input("bad key").exit_status(), 2);
        assert_eq!(Failure::run("solver failed").exit_status(), 1);
    }
}
