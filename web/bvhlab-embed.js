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

export class BvhLab {
  /// `frame`: the <iframe> showing the lab. `origin`: the lab's origin (by default, that of
  /// the iframe's address).
  constructor(frame, origin = new URL(frame.src, location.href).origin) {
    this.frame = frame;
    this.origin = origin;
    this.next = 1;
    this.waiting = new Map();
    this.listeners = { panic: [], progress: [] };
    window.addEventListener('message', (event) => {
      if (event.source !== frame.contentWindow || event.origin !== origin) return;
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
      }
    });
  }

  /// Sends `command` ({type: ..., ...}); resolves with the report (or the scene, for
  /// exportScene).
  send(command) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.waiting.set(id, { resolve, reject });
      this.frame.contentWindow.postMessage({ bvhlab: 'command', id, command }, this.origin);
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

  /// Opens lesson `name` at `step` (1 is its first).
  goToLesson(lesson, step = 1) { return this.send({ type: 'go-to-lesson', lesson, step }); }

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
