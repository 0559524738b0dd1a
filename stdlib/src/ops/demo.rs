//! An operator's demo: what `npr doc` renders to show what the operator
//! does (a small image per operator in `docs/reference/img/`), declared
//! next to the operator in its family's `demos.rs`. Every operator has one:
//! a style that calls it and the example scene to render it on, or an
//! explicit reason why no image can show it (`stdlib/tests/completeness.rs`
//! fails on a missing demo, a style that does not call its operator, a
//! scene that does not exist and a reason left empty).

/// How an operator is shown in the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Demo {
    /// No demo declared yet: the completeness test fails.
    Missing,
    /// A style that calls the operator, compiled and rendered by the runner.
    Render(DemoRender),
    /// No image, and why (printed in the reference in its place).
    NoDemo(&'static str),
}

/// A demo image: the style, the scene, and what the image shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DemoRender {
    /// What the image shows, in a sentence: the image's alt text.
    pub shows: &'static str,
    /// The scene, relative to the repository's `examples/` directory.
    pub scene: &'static str,
    /// The style's text. It calls the operator; its relative paths
    /// (textures, `use`) are resolved against `examples/`.
    pub style: &'static str,
    /// The time of the frame shown, in seconds (path-dependent styles
    /// replay from frame 0).
    pub time_s: f64,
}

/// The size of every demo image, in pixels.
pub const DEMO_SIZE: (u32, u32) = (128, 96);

/// A demo rendered at time 0.
pub const fn render(shows: &'static str, scene: &'static str, style: &'static str) -> Demo {
    Demo::Render(DemoRender {
        shows,
        scene,
        style,
        time_s: 0.0,
    })
}

/// Whether the style text `text` calls the operator `name`: `name(` not
/// preceded by a name's character (`sample(` is not found in
/// `sample_biased(` or in `resample(`). The completeness test checks each
/// demo with it, and `npr doc` finds the benchmark rows of an operator.
pub fn style_calls(text: &str, name: &str) -> bool {
    let call = format!("{name}(");
    text.match_indices(&call).any(|(at, _)| {
        !text[..at]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_')
    })
}
