// Runs a Flamenco 3 job type script's `compileJob` outside a Flamenco
// Manager and prints the tasks it made as JSON, for tests/general/farm.rs:
//   node harness.js JOB_TYPE.js '{"settings": ...}'
// What the Manager provides is written here after its documentation and
// source (internal/manager/job_compilers): `author.Task(name, type)` with
// `addCommand` and `addDependency`, `author.Command(name, params)`,
// `job.addTask`, and `frameChunker(range, size)`, which splits the range's
// frames into chunks of at most `size` and writes each as ranges merged
// from consecutive frames: one frame `N`, two `A,B`, more `A-B`.
const fs = require("fs");
const vm = require("vm");

function explode(range) {
  const frames = new Set();
  for (const part of range.split(",").map((p) => p.trim())) {
    const m = part.match(/^(\d+)(?:(?:-|\.\.)(\d+))?$/);
    if (!m) throw new Error(`invalid range ${range}`);
    const [a, b] = [Number(m[1]), m[2] === undefined ? Number(m[1]) : Number(m[2])];
    for (let f = a; f <= b; f++) frames.add(f);
  }
  return [...frames].sort((x, y) => x - y);
}

function merge(frames) {
  const out = [];
  let start = frames[0];
  let prev = frames[0];
  const flush = (a, b) => {
    if (a === b) out.push(`${a}`);
    else if (a + 1 === b) out.push(`${a}`, `${b}`);
    else out.push(`${a}-${b}`);
  };
  for (const f of frames.slice(1)) {
    if (f > prev + 1) {
      flush(start, prev);
      start = f;
    }
    prev = f;
  }
  flush(start, prev);
  return out.join(",");
}

function frameChunker(range, size) {
  const frames = explode(range);
  const chunks = [];
  for (let i = 0; i < frames.length; i += size) chunks.push(merge(frames.slice(i, i + size)));
  return chunks;
}

const author = {
  Task(name, type) {
    return {
      name,
      type,
      commands: [],
      dependencies: [],
      addCommand(c) {
        this.commands.push(c);
      },
      addDependency(t) {
        this.dependencies.push(t.name);
      },
    };
  },
  Command(name, params) {
    return { name, ...params };
  },
};

const [script, jobJson] = process.argv.slice(2);
const context = { author, frameChunker, console };
vm.createContext(context);
vm.runInContext(fs.readFileSync(script, "utf8") + "\n;this.JOB_TYPE = JOB_TYPE; this.compileJob = compileJob;", context);
const job = JSON.parse(jobJson);
for (const s of context.JOB_TYPE.settings) {
  if (job.settings[s.key] === undefined && s.default !== undefined) job.settings[s.key] = s.default;
  if (s.required && job.settings[s.key] === undefined) throw new Error(`setting ${s.key} is required`);
}
job.tasks = [];
job.addTask = (t) => job.tasks.push(t);
context.compileJob(job);
process.stdout.write(
  JSON.stringify(job.tasks.map((t) => ({ name: t.name, dependencies: t.dependencies, commands: t.commands })))
);
