//! TEMPORARY profiling marks (NPR_PROF=file): wall-clock microseconds and a label per line.
use std::io::Write;
use std::sync::{Mutex, OnceLock};

static FILE: OnceLock<Option<Mutex<std::fs::File>>> = OnceLock::new();

pub fn mark(label: &str) {
    let f = FILE.get_or_init(|| {
        std::env::var_os("NPR_PROF").map(|p| {
            Mutex::new(std::fs::OpenOptions::new().create(true).append(true).open(p).expect("prof file"))
        })
    });
    if let Some(f) = f {
        let us = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_micros();
        let _ = writeln!(f.lock().unwrap(), "{us} {label}");
    }
}
