//! `npr_diag::panics::install_quiet_hook` (its own test binary: the hook is
//! process-wide): a panic inside `panics::catch` reaches no hook, and any
//! other panic reaches the hook that was there before, on every thread.

use std::sync::Mutex;

static SEEN: Mutex<Vec<String>> = Mutex::new(Vec::new());

#[test]
fn only_unexpected_panics_reach_the_previous_hook() {
    std::panic::set_hook(Box::new(|info| {
        let message = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        SEEN.lock().expect("lock").push(message);
    }));
    npr_diag::panics::install_quiet_hook();
    npr_diag::panics::install_quiet_hook(); // once: not wrapped twice

    let caught: Result<(), String> = npr_diag::panics::catch(|| panic!("naga-like"));
    assert_eq!(caught, Err("naga-like".to_string()));
    assert!(SEEN.lock().expect("lock").is_empty(), "an expected panic printed");

    let other = std::thread::spawn(|| panic!("a bug")).join();
    assert!(other.is_err());
    assert_eq!(
        *SEEN.lock().expect("lock"),
        ["a bug"],
        "an unexpected panic reaches the hook once"
    );
}
