// bvhlab-embed.js: script an embedded bvh-lab from the course page that holds it.
//
//   import { BvhLab } from './bvhlab-embed.js';
//   const lab = new BvhLab(document.querySelector('iframe'));
//   await lab.ready();
//   const report = await lab.setRay([0, 0], [1, 0.2]);
//   console.log(report.query.hit, report.playback[0].total);
//
// Every method sends one command with postMessage and resolves with the lab's report once the
// lab has applied it (its structures built and its answers recorded), or rejects with the
// lab's reason (an unknown structure, a ray with a zero direction...). The lab accepts
// commands only from its own origin and from origins its address names with origin=...;
// replies go only to the window that asked. The commands are documented in the README
// ("Embedding the lab") and in crates/bvhlab-app/src/embed/command.rs.
//
//   const lab = new BvhLab(frame, { fitHeight: true });   // the iframe takes the lab's height
//   lab.onSize(({ height }) => console.log(`the lab would like ${height} px`));
//
// A frame sandboxed without allow-same-origin (<iframe sandbox="allow-scripts">) has the
// origin "null": its messages are taken from that frame's window alone, and commands go to it
// with the target origin "*" (the browser cannot name an opaque origin).

export class BvhLab {
  /// `frame`: the <iframe> showing the lab. `options`: `origin`, the lab's origin (by
  /// default, that of the iframe's address; a string in place of the options is taken as
  /// it), and `fitHeight`: when true, the iframe's height follows the height the lab asks
  /// for (its `size` message, see onSize).
  constructor(frame, options = {}) {
    const { origin = new URL(frame.src, location.href).origin, fitHeight = false } =
      typeof options === 'string' ? { origin: options } : options;
    this.frame = frame;
    // Sandboxed without allow-same-origin: the lab's messages come from the origin "null".
    const opaque = frame.sandbox.length > 0 && !frame.sandbox.contains('allow-same-origin');
    this.origin = opaque ? 'null' : origin;
    this.target = opaque ? '*' : origin;
    this.next = 1;
    this.waiting = new Map();
    this.listeners = { panic: [], progress: [], size: [] };
    if (fitHeight) this.onSize(({ height }) => { frame.style.height = `${height}px`; });
    window.addEventListener('message', (event) => {
      if (event.source !== frame.contentWindow || event.origin !== this.origin) return;
      const data = event.data;
      if (data?.bvhlab === 'reply' && this.waiting.has(data.id)) {
        const { resolve, reject } = this.waiting.get(data.id);
        this.waiting.delete(data.id);
        if (data.ok) resolve(data.scene ?? data.report);
        else reject(new Error(data.error));
      } else if (data?.bvhlab === 'panic') {
        for (const listener of this.listeners.panic) listener(data.message);
      } else if (data?.bvhlab === 'progress') {
        const { lesson, step, steps, goal_reached, goals_reached, goals, exercise, score } = data;
        for (const listener of this.listeners.progress) {
          listener({ lesson, step, steps, goal_reached, goals_reached, goals, exercise, score });
        }
      } else if (data?.bvhlab === 'size' && Number.isFinite(data.height) && data.height > 0) {
        this.height = data.height;
        for (const listener of this.listeners.size) listener({ height: data.height });
      }
    });
  }

  /// Sends `command` ({type: ..., ...}); resolves with the report (or the scene, for
  /// exportScene).
  send(command) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.waiting.set(id, { resolve, reject });
      this.frame.contentWindow.postMessage({ bvhlab: 'command', id, command }, this.target);
    });
  }

  /// Resolves with the first report once the lab answers (it asks again every 200 ms until
  /// then: the lab may still be loading), or rejects after `timeoutMs`.
  async ready(timeoutMs = 60000) {
    const start = performance.now();
    while (performance.now() - start < timeoutMs) {
      const answer = await Promise.race([
        this.send({ type: 'report' }),
        new Promise((resolve) => setTimeout(() => resolve(null), 200)),
      ]);
      if (answer) return answer;
    }
    throw new Error(`the lab at ${this.origin} did not answer within ${timeoutMs} ms`);
  }

  /// Calls `listener(message)` if the lab stops on an error.
  onPanic(listener) { this.listeners.panic.push(listener); }

  /// Calls `listener({lesson, step, steps, goal_reached, goals_reached, goals, exercise,
  /// score})` whenever the student opens a lesson step, reaches its goal, or settles a
  /// prediction (steps count from 1). The lesson's fields are there while a lesson is open;
  /// `exercise` ("2D AABB tree: first hit") and `score` ({first_time, after_hint, shown})
  /// while Predict is on.
  onProgress(listener) { this.listeners.progress.push(listener); }

  /// Calls `listener({height})` with the height in CSS pixels the lab would like its frame
  /// to have: when it starts, and when the student shows or hides its panels (720 with the
  /// panels beside the view, 600 for the view and the tree diagram, 480 for the view alone).
  /// A listener added later is called at once with the last height heard, if any.
  onSize(listener) {
    this.listeners.size.push(listener);
    if (this.height) listener({ height: this.height });
  }

  /// Opens lesson `name` at `step` (1 is its first).
  goToLesson(lesson, step = 1) { return this.send({ type: 'go-to-lesson', lesson, step }); }
  /// Opens a teacher's lesson from the text of its .toml file (the format of the lab's own
  /// lessons, crates/bvhlab-app/lessons/README.md) at `step`; rejects with `file:line: why`
  /// when the file is wrong, changing nothing.
  loadLesson(text, file = 'lesson.toml', step = 1) {
    return this.send({ type: 'load-lesson', text, file, step });
  }

  /// Switches Predict on or off: the lab asks before each step that decides something.
  predict(on = true) { return this.send({ type: 'predict', on }); }
  /// Answers Predict's question: `choice` counts the report's `predict.question.choices`
  /// from 1.
  answer(choice) { return this.send({ type: 'answer', choice }); }
  /// Shows the answer of Predict's question (it counts as shown).
  showAnswer() { return this.send({ type: 'show-answer' }); }

  report() { return this.send({ type: 'report' }); }
  loadScene(scene) { return this.send({ type: 'load-scene', scene }); }
  loadPreset(preset) { return this.send({ type: 'load-preset', preset }); }
  loadMesh(mesh) { return this.send({ type: 'load-mesh', mesh }); }
  show(view) { return this.send({ type: 'show', view }); }
  setStructure(structure) { return this.send({ type: 'set-structure', structure }); }
  setTask(task) { return this.send({ type: 'set-task', task }); }
  setRay(origin, direction) { return this.send({ type: 'set-ray', origin, direction }); }
  setPoint(point) { return this.send({ type: 'set-point', point }); }
  step(by = 1) { return this.send({ type: 'step', by }); }
  goToStep(step) { return this.send({ type: 'go-to-step', step }); }
  play(playing = true) { return this.send({ type: 'play', playing }); }
  exportScene() { return this.send({ type: 'export-scene' }); }
}
