//! Ctrl-C and `kill` (SIGINT, SIGTERM) during a run: the run stops at its next check (after the
//! current integrator step of `dynamic`, before the next sweep point of `static`, between the
//! parts of a model's `flutter` analysis), writes what it computed with the status
//! `interrupted`, and exits with status 1.

use std::sync::atomic::{AtomicBool, Ordering};

/// Set by Ctrl-C or `kill` once [`catch_interrupts`] ran.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);
/// Whether a second Ctrl-C ends the process at once (exit status 130).
static SECOND_QUITS: AtomicBool = AtomicBool::new(false);

/// Catch Ctrl-C and `kill` for the rest of the process: they set the flag [`interrupted`] reads
/// instead of ending it. With `second_quits` (commands whose checks are far apart: a flutter
/// analysis part, a hard static point), a second one ends the process at once with status 130,
/// leaving `status.txt: running`; otherwise it is caught too (as while `dynamic` writes its
/// output). Only SIGKILL always ends the process at once.
pub fn catch_interrupts(second_quits: bool) {
    SECOND_QUITS.store(second_quits, Ordering::SeqCst);
    // An error means a handler is already set (a second command in the same process, in
    // tests): the first one sets the same flag.
    let _ = ctrlc::set_handler(|| {
        if INTERRUPTED.swap(true, Ordering::SeqCst) && SECOND_QUITS.load(Ordering::SeqCst) {
            std::process::exit(130);
        }
    });
}

/// Whether Ctrl-C or `kill` came (after [`catch_interrupts`]).
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}
