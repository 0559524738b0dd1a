//! What the compiler may know about the scene a style will run on. The
//! runner produces it (`Scene::summary`); the compiler folds `scene_has(tag)`
//! with it. It lives here so that neither crate needs the other.

/// What the compiler may know about the scene: the tags its objects carry.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SceneSummary {
    /// Every tag of every object.
    pub tags: std::collections::BTreeSet<String>,
    /// A name for messages and the report (e.g. the scene file).
    pub name: String,
}
