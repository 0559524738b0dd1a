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
}

impl Reports {
    /// Log each of `diags` not logged for `camera` before.
    pub fn log(&mut self, camera: Entity, diags: &[Diagnostic]) {
        for d in diags {
            let text = npr_diag::diagnostic::render(std::slice::from_ref(d), &npr_diag::SourceMap::new(), false);
            if self.logged.entry(camera).or_default().insert(text.clone()) {
                self.codes.push(d.code);
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

    pub fn codes(&self) -> Vec<&'static str> {
        self.codes.clone()
    }
}
