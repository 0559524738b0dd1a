// SPDX-License-Identifier: MIT
// A Flamenco 3 job type for npr: put this file in the Manager's `scripts/`
// directory. Like farm/openjd/npr-render.yaml, a job is a checkpoint task
// (the whole range rendered once without images, the renderer's state saved
// every `chunk_size` frames) and one render task per chunk, each depending
// on it and starting from the checkpoint at its first frame, so the chunks
// run in parallel on the Workers without replaying earlier frames. A style
// whose frames do not depend on earlier ones makes the checkpoint task
// return at once. Flamenco's `frameChunker` writes a chunk of two frames as
// `A,B` (and longer ones as `A-B`), so each chunk is given to npr as the
// `A-B` range it spans (`asRange`).

const JOB_TYPE = {
  label: "npr render",
  description: "Render an npr style's sequence in chunks from state checkpoints",
  settings: [
    { key: "npr", type: "string", required: true, default: "npr", description: "The npr program" },
    { key: "style", type: "string", subtype: "file_path", required: true, description: "The style (.npr)" },
    { key: "scene", type: "string", subtype: "file_path", required: true, description: "The scene (.toml)" },
    { key: "frames", type: "string", required: true, default: "0-47", description: "Frames, first-last inclusive" },
    { key: "chunk_size", type: "int32", default: 24, propargs: { min: 1 }, description: "Frames per task" },
    { key: "size", type: "string", default: "512x512", description: "WIDTHxHEIGHT" },
    { key: "fps", type: "string", default: "24", description: "Frame rate" },
    { key: "output", type: "string", subtype: "file_path", required: true, description: "Images; {frame} is the frame number" },
    { key: "checkpoints", type: "string", subtype: "dir_path", required: true, description: "State checkpoints (shared)" },
  ],
};

/// The arguments every task of the job shares.
function commonArgs(settings) {
  return [
    "render", settings.style,
    "--scene", settings.scene,
    "--size", settings.size,
    "--fps", settings.fps,
    "--checkpoints", settings.checkpoints,
  ];
}

/// A chunk of a contiguous range as `first-last`, the form `npr render
/// --frames` reads (frameChunker writes `8,9` for two frames).
function asRange(chunk) {
  const frames = chunk.split(/[,-]/).map(Number);
  return `${Math.min(...frames)}-${Math.max(...frames)}`;
}

function compileJob(job) {
  const settings = job.settings;
  const checkpoints = author.Task("checkpoints", "misc");
  checkpoints.addCommand(
    author.Command("exec", {
      exe: settings.npr,
      args: commonArgs(settings).concat([
        "--frames", settings.frames,
        "--checkpoint-every", String(settings.chunk_size),
      ]),
    })
  );
  job.addTask(checkpoints);
  for (const chunk of frameChunker(settings.frames, settings.chunk_size)) {
    const task = author.Task(`render-${chunk}`, "misc");
    task.addCommand(
      author.Command("exec", {
        exe: settings.npr,
        args: commonArgs(settings).concat(["--frames", asRange(chunk), "-o", settings.output]),
      })
    );
    task.addDependency(checkpoints);
    job.addTask(task);
  }
}
