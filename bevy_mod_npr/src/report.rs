//! Diagnostics in Bevy's log, as npr prints them (`error[E0602]: ...`),
//! once per camera: a problem that lasts (a tag no entity has) is not
//! repeated every frame. A camera's record is cleared when it gets a new
//! style, so the new style's problems are logged again.

use bevy::log::{error, warn};
use bevy::platform::collections::{HashMap, HashSet};
use bevy::prelude::Entity;
use npr_diag::Diagnostic;

/// What was logged, per camera (render entity).
#[derive(Default)]
pub(crate) struct Reports {
    logged: HashMap<Entity, HashSet<String>>,
    /// Every code logged, in order (what tests read).
    codes: Vec<&'static str>,
    /// And its text, as logged.
    messages: Vec<String>,
}

impl Reports {
    /// Log each of `diags` not logged for `camera` before.
    pub fn log(&mut self, camera: Entity, diags: &[Diagnostic]) {
        for d in diags {
            let text = npr_diag::diagnostic::render(std::slice::from_ref(d), &npr_diag::SourceMap::new(), false);
            if self.logged.entry(camera).or_default().insert(text.clone()) {
                self.codes.push(d.code);
                self.messages.push(text.trim_end().to_string());
                if d.is_error() {
                    error!("{}", text.trim_end());
                } else {
                    warn!("{}", text.trim_end());
                }
            }
        }
    }

    pub fn forget(&mut self, camera: Entity) {
        self.logged.remove(&camera);
    }

    /// Forget what was logged for `camera` with one of `codes` (a problem
    /// that is gone: logged again if it comes back).
    pub fn forget_codes(&mut self, camera: Entity, codes: &[&str]) {
        if let Some(logged) = self.logged.get_mut(&camera) {
            logged.retain(|text| !codes.iter().any(|c| text.contains(&format!("[{c}]"))));
        }
    }

    /// The text of every diagnostic logged, in order (what tests read).
    pub fn messages(&self) -> Vec<String> {
        self.messages.clone()
    }

    pub fn codes(&self) -> Vec<&'static str> {
        self.codes.clone()
    }
}
