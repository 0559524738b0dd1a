//! The exit codes of every command: a leaf that the commands, the printer
//! and `main` share without importing the command line's definitions.

/// The command did what was asked.
pub const EXIT_OK: i32 = 0;
/// The user's input was refused (a diagnostic with a code says why).
pub const EXIT_USER: i32 = 1;
/// npr itself failed (a device, a write, an internal error).
pub const EXIT_INTERNAL: i32 = 2;
