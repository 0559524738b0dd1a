//! The Flamenco job type `farm/flamenco/npr-render.js`, as far as it can be
//! run without a Flamenco Manager: `tests/data/flamenco/harness.js` (node)
//! gives it what the Manager gives a job type (`author`, `frameChunker`)
//! and prints the tasks it compiles; this test checks their shape (one
//! checkpoint task, every chunk depending on it, the chunks covering the
//! range) and runs their commands as Workers would, the chunks in reverse
//! order to show they do not need each other, and compares the frames
//! with one `npr render` of the whole range.

use crate::common::cli::{npr, scratch, stderr};
use crate::common::root;

#[test]
fn the_job_type_renders_the_frames_of_one_run() {
    let dir = scratch("flamenco", "afterimage");
    let path = |p: &str| dir.join(p).to_str().expect("utf-8").to_string();
    let style = root()
        .join("examples/afterimage.npr")
        .to_str()
        .expect("utf-8")
        .to_string();
    let scene = root()
        .join("examples/scenes/orbit.toml")
        .to_str()
        .expect("utf-8")
        .to_string();
    let job = serde_json::json!({"settings": {
        "npr": env!("CARGO_BIN_EXE_npr"),
        "style": style,
        "scene": scene,
        "frames": "0-9",
        "chunk_size": 4,
        "size": "48x40",
        "output": path("farm/f_{frame}.png"),
        "checkpoints": path("ck"),
    }});
    let node = std::process::Command::new("node")
        .arg("tests/data/flamenco/harness.js")
        .arg("farm/flamenco/npr-render.js")
        .arg(job.to_string())
        .current_dir(root())
        .output();
    let node = node.unwrap_or_else(|e| panic!("this test runs the job type with node: install nodejs ({e})"));
    assert!(node.status.success(), "{}", stderr(&node));
    let tasks: serde_json::Value = serde_json::from_slice(&node.stdout).expect("tasks as JSON");
    let tasks = tasks.as_array().expect("a task list");
    let names: Vec<&str> = tasks.iter().map(|t| t["name"].as_str().expect("name")).collect();
    // frameChunker writes the last chunk of two frames as "8,9".
    assert_eq!(names, ["checkpoints", "render-0-3", "render-4-7", "render-8,9"]);
    for t in &tasks[1..] {
        assert_eq!(t["dependencies"], serde_json::json!(["checkpoints"]), "{t}");
    }
    let run = |task: &serde_json::Value| {
        for c in task["commands"].as_array().expect("commands") {
            let args: Vec<&str> = c["args"]
                .as_array()
                .expect("args")
                .iter()
                .map(|a| a.as_str().expect("arg"))
                .collect();
            let o = std::process::Command::new(c["exe"].as_str().expect("exe"))
                .args(&args)
                .current_dir(root())
                .output()
                .expect("the task's command runs");
            assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        }
    };
    run(&tasks[0]);
    for t in tasks[1..].iter().rev() {
        run(t);
    }
    let one = npr(&[
        "render",
        &style,
        "--scene",
        &scene,
        "--size",
        "48x40",
        "--frames",
        "0-9",
        "-o",
        &path("one/f_{frame}.png"),
    ]);
    assert!(one.status.success(), "{}", stderr(&one));
    for f in 0..10 {
        let name = format!("f_{f:04}.png");
        let farm = std::fs::read(dir.join("farm").join(&name)).unwrap_or_else(|e| panic!("{name} from the job: {e}"));
        assert!(
            farm == std::fs::read(dir.join("one").join(&name)).expect("one run's frame"),
            "frame {f} differs"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
