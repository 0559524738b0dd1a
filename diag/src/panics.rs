//! Panics that npr expects and turns into diagnostics: a third-party crate
//! that panics on input it should reject (naga 30's constant evaluator,
//! a mesh reader). [`catch`] runs such a call and returns its panic as a
//! message; while it runs, the hook [`install_quiet_hook`] installs prints
//! nothing, so the user sees the diagnostic alone (an E9001 or E0402), not
//! Rust's "thread 'main' panicked at …" line above it. Any other panic
//! still reaches the previous hook: it is a bug in npr, and its location is
//! what a bug report needs.
//!
//! The hook is process-wide, so only a binary installs it (`npr`'s main);
//! the flag is per thread, so a panic on another thread is never hidden.

use std::any::Any;
use std::cell::Cell;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    /// Whether this thread is inside [`catch`].
    static EXPECTED: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f`; a panic comes back as `Err` with its message. The caller owns
/// whatever `f` touched and drops it, so no half-updated state is seen.
pub fn catch<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    let outer = EXPECTED.with(|e| e.replace(true));
    let result = catch_unwind(AssertUnwindSafe(f));
    EXPECTED.with(|e| e.set(outer));
    result.map_err(|payload| message(payload.as_ref()))
}

/// A panic's message: its `&str` or `String` payload.
pub fn message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "no message".into())
}

/// Whether the current thread is inside [`catch`].
pub fn expected() -> bool {
    EXPECTED.with(Cell::get)
}

/// Installs (once) a panic hook that is silent for panics inside [`catch`]
/// and hands every other panic to the hook that was there before.
pub fn install_quiet_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !expected() {
                previous(info);
            }
        }));
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_caught_panic_is_its_message_and_the_flag_is_restored() {
        assert!(!expected());
        let r: Result<(), String> = catch(|| panic!("bad input {}", 7));
        assert_eq!(r, Err("bad input 7".to_string()));
        assert!(!expected());
        let nested = catch(|| {
            let inner: Result<(), String> = catch(|| panic!("inner"));
            (inner, expected())
        });
        assert_eq!(
            nested,
            Ok((Err("inner".to_string()), true)),
            "still inside the outer catch"
        );
        assert!(!expected());
        assert_eq!(catch(|| 3), Ok(3));
    }
}
