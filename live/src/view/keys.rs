//! `npr view`'s key and mouse bindings: one table, which both dispatches a
//! key press and writes the help printed at start and in `--help`.

use winit::keyboard::KeyCode;

/// What a key does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    TogglePause,
    /// Orbit ↔ fly.
    SwitchCamera,
    /// Back to the scene's own camera (animated, if it is).
    SceneCamera,
    ChooseParam(i32),
    StepParam(i32),
    /// One frame (1/fps) back or forward in time.
    StepTime(i32),
    Quit,
    /// A fly movement key: held, not pressed once.
    Move(Motion),
}

/// The fly camera's movement keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    Forward,
    Back,
    Left,
    Right,
    Up,
    Down,
    Fast,
}

/// Every key binding: the keys, what they do, and its line of help.
pub const KEYS: &[(&[KeyCode], Action, &str, &str)] = &[
    (&[KeyCode::Space], Action::TogglePause, "space", "pause / run time"),
    (
        &[KeyCode::Comma],
        Action::StepTime(-1),
        ", .",
        "one frame back / forward in time (1/fps)",
    ),
    (&[KeyCode::Period], Action::StepTime(1), "", ""),
    (
        &[KeyCode::Tab],
        Action::SwitchCamera,
        "tab",
        "switch orbit / fly camera",
    ),
    (&[KeyCode::KeyC], Action::SceneCamera, "c", "back to the scene's camera"),
    (
        &[KeyCode::KeyW, KeyCode::ArrowUp],
        Action::Move(Motion::Forward),
        "w a s d",
        "fly forward, left, back, right (arrows too)",
    ),
    (&[KeyCode::KeyA, KeyCode::ArrowLeft], Action::Move(Motion::Left), "", ""),
    (&[KeyCode::KeyS, KeyCode::ArrowDown], Action::Move(Motion::Back), "", ""),
    (
        &[KeyCode::KeyD, KeyCode::ArrowRight],
        Action::Move(Motion::Right),
        "",
        "",
    ),
    (&[KeyCode::KeyE], Action::Move(Motion::Up), "e q", "fly up / down"),
    (&[KeyCode::KeyQ], Action::Move(Motion::Down), "", ""),
    (
        &[KeyCode::ShiftLeft, KeyCode::ShiftRight],
        Action::Move(Motion::Fast),
        "shift",
        "fly faster (held)",
    ),
    (
        &[KeyCode::BracketLeft],
        Action::ChooseParam(-1),
        "[ ]",
        "choose the previous / next parameter",
    ),
    (&[KeyCode::BracketRight], Action::ChooseParam(1), "", ""),
    (
        &[KeyCode::Minus, KeyCode::NumpadSubtract],
        Action::StepParam(-1),
        "- =",
        "step the chosen parameter down / up",
    ),
    (&[KeyCode::Equal, KeyCode::NumpadAdd], Action::StepParam(1), "", ""),
    (&[KeyCode::Escape], Action::Quit, "esc", "quit"),
];

/// The mouse: not keys, but help all the same.
const MOUSE: &[(&str, &str)] = &[
    ("left drag", "orbit: turn about the target; fly: look"),
    ("right drag", "orbit: pan"),
    ("wheel", "orbit: nearer / farther"),
];

/// The action of `key`, if it has one.
pub fn action(key: KeyCode) -> Option<Action> {
    KEYS.iter().find(|(keys, ..)| keys.contains(&key)).map(|(_, a, ..)| *a)
}

/// The bindings as lines of help.
pub fn help() -> String {
    let mut lines = vec!["Keys and mouse in the window:".to_string()];
    let rows = KEYS
        .iter()
        .filter(|(_, _, name, _)| !name.is_empty())
        .map(|(_, _, name, what)| (*name, *what))
        .chain(MOUSE.iter().copied());
    for (name, what) in rows {
        lines.push(format!("  {name:<11} {what}"));
    }
    lines.join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_key_is_bound_twice() {
        let mut seen = Vec::new();
        for (keys, ..) in KEYS {
            for k in *keys {
                assert!(!seen.contains(k), "{k:?} is bound twice");
                seen.push(*k);
            }
        }
    }

    #[test]
    fn every_action_is_in_the_help_or_shares_a_line() {
        // A row without a name continues the named row above it.
        assert!(!KEYS[0].2.is_empty());
        let help = help();
        for (_, _, name, what) in KEYS.iter().filter(|r| !r.2.is_empty()) {
            assert!(help.contains(name) && help.contains(what), "{name}: {what}");
        }
        assert_eq!(action(KeyCode::Space), Some(Action::TogglePause));
        assert_eq!(action(KeyCode::ArrowUp), Some(Action::Move(Motion::Forward)));
        assert_eq!(action(KeyCode::KeyZ), None);
    }
}
