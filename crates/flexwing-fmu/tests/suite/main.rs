//! The FMU crate's integration tests, in one test binary (as every crate's): the instance's
//! state machine and value references through its safe API (the C shim over it is exercised by
//! FMPy in the Python suite, crates/flexwing-py/tests/test_fmu.py), and the archive.

mod instance;
