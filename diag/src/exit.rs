//! The exit codes of npr's programs and of the libraries that run as one
//! (the language server, the live view and studio, the style tests): one
//! definition, so `npr`'s commands and a program built on the libraries
//! mean the same by 1 and 2.

/// The command did what was asked.
pub const EXIT_OK: i32 = 0;
/// The user's input was refused (a diagnostic with a code says why).
pub const EXIT_USER: i32 = 1;
/// npr itself failed (a device, a write, an internal error).
pub const EXIT_INTERNAL: i32 = 2;
