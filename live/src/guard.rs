//! A panic in a rebuild or a render must not end `npr watch` or the
//! studio's render thread: [`catch`] runs a step and turns a panic into a
//! message (E9001: a panic is always a bug in npr), so the loop reports it
//! and goes on waiting for the next change.

use std::panic::{catch_unwind, AssertUnwindSafe};

/// Run `step`; a panic comes back as `Err(message)`.
pub fn catch<T>(step: impl FnOnce() -> T) -> Result<T, String> {
    // The state a panicking step touched is dropped by the caller (the
    // renderer is rebuilt), so observing it half-updated cannot happen.
    // Not `npr_diag::panics::catch`: this panic is a bug, so the hook still
    // prints where it happened.
    catch_unwind(AssertUnwindSafe(step)).map_err(|payload| {
        format!(
            "internal error: the render thread panicked: {}",
            npr_diag::panics::message(payload.as_ref())
        )
    })
}

/// The panic as a diagnostic, for the same printers as every other error.
pub fn panic_diagnostic(message: &str) -> npr_diag::Diagnostic {
    npr_diag::Diagnostic::error(npr_diag::codes::INTERNAL, message.to_string())
        .with_help("this is a bug in npr; the previous image is kept, and the next save tries again")
}
