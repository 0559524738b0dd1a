//! A compiled style as the runner sees it: the manifest plus WGSL per pass,
//! either straight from the compiler or read back from `npr compile -o DIR`.

use compiler::manifest::Manifest;
use std::collections::BTreeMap;
use std::path::Path;

#[derive(Debug, Clone)]
pub struct StyleProgram {
    pub manifest: Manifest,
    /// WGSL source by shader file name (`<pass>.wgsl`).
    pub shaders: BTreeMap<String, String>,
}

impl StyleProgram {
    pub fn from_compiled(c: &compiler::Compiled) -> StyleProgram {
        StyleProgram {
            manifest: c.manifest.clone(),
            shaders: c.shaders.iter().cloned().collect(),
        }
    }

    /// Read `manifest.json` and the WGSL files beside it.
    pub fn load_dir(dir: &Path) -> Result<StyleProgram, String> {
        let text = std::fs::read_to_string(dir.join("manifest.json"))
            .map_err(|e| format!("cannot read {}: {e}", dir.join("manifest.json").display()))?;
        let manifest: Manifest = serde_json::from_str(&text).map_err(|e| format!("bad manifest.json: {e}"))?;
        if manifest.version != compiler::manifest::MANIFEST_VERSION {
            return Err(format!(
                "manifest version {} is not supported (expected {}); recompile the style",
                manifest.version,
                compiler::manifest::MANIFEST_VERSION
            ));
        }
        let mut shaders = BTreeMap::new();
        for p in &manifest.passes {
            let wgsl = std::fs::read_to_string(dir.join(&p.shader))
                .map_err(|e| format!("cannot read {}: {e}", dir.join(&p.shader).display()))?;
            shaders.insert(p.shader.clone(), wgsl);
        }
        Ok(StyleProgram { manifest, shaders })
    }
}
