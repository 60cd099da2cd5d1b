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
    // Sandboxed without allow-same-origin, or inside a page that is (a sandbox holds for the
    // frames within): the lab's messages come from the origin "null".
    const opaque = (frame.sandbox.length > 0 && !frame.sandbox.contains('allow-same-origin')) ||
      self.origin === 'null';
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

  /// Calls `listener(statement)` with each progress event as an xAPI statement (see
  /// xapiStatements below), for a course page or an LMS plugin that records xAPI: a step
  /// opened is "experienced", a goal reached "completed" (once per step and page), a change
  /// of Predict's score "answered". `options`: `actor` (the learner, as the LRS knows them:
  /// `{mbox: 'mailto:...'}` or `{account: {homePage, name}}`; statements need one, so without
  /// it the listener must add it) and `activity`, the IRI the statements' activities start
  /// with (by default the lab's address without its query).
  onStatement(listener, options = {}) {
    const activity = options.activity ?? new URL(this.frame.src, location.href).href.split(/[?#]/)[0];
    const completed = new Set();
    const scores = new Map();
    this.onProgress((p) => {
      for (const statement of xapiStatements(p, { ...options, activity })) {
        const verb = statement.verb.id;
        const key = statement.object.id;
        if (verb === XAPI_VERBS.completed.id) {
          if (completed.has(key)) continue;
          completed.add(key);
        }
        if (verb === XAPI_VERBS.answered.id) {
          const score = JSON.stringify(statement.result.score);
          if (scores.get(key) === score) continue;
          scores.set(key, score);
        }
        listener(statement);
      }
    });
  }

  /// Calls `listener({height})` with the height in CSS pixels the lab would like its frame
  /// to have: when it starts, and when the student shows or hides its panels (720 with the
  /// panels beside the view, 600 for the view and the tree diagram, 480 for the view alone).
  /// A listener added later is called at once with the last height heard, if any.
  onSize(listener) {
    this.listeners.size.push(listener);
    if (this.height) listener({ height: this.height });
  }

  /// Opens lesson `name` at `step` (1 is its first). `reached`: steps (from 1) whose goals
  /// the student reached in an earlier session (what an LMS kept), marked reached again.
  goToLesson(lesson, step = 1, reached = []) {
    return this.send({ type: 'go-to-lesson', lesson, step, ...(reached.length ? { reached } : {}) });
  }
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

/// The xAPI verbs the lab's statements use (ADL's vocabulary).
export const XAPI_VERBS = {
  experienced: { id: 'http://adlnet.gov/expapi/verbs/experienced', display: { 'en-US': 'experienced' } },
  completed: { id: 'http://adlnet.gov/expapi/verbs/completed', display: { 'en-US': 'completed' } },
  answered: { id: 'http://adlnet.gov/expapi/verbs/answered', display: { 'en-US': 'answered' } },
};

/// A progress event (onProgress) as xAPI 1.0.3 statements: for a lesson step, "completed"
/// when its goal is reached (result: success, completion, and the lesson's goals reached as
/// the score, raw of max) or "experienced" when it is only open; for Predict, "answered" with
/// the exercise's score (raw: right first time plus half of right after a hint, max: every
/// prediction settled; success when none had to be shown). Activities are named
/// `ACTIVITY/lessons/NAME/steps/N` (its parent `ACTIVITY/lessons/NAME`) and
/// `ACTIVITY/predict/EXERCISE`. `options`: `actor`, `activity` (an IRI), `timestamp` (ISO
/// 8601; now by default).
export function xapiStatements(progress, options = {}) {
  const { actor, activity = 'urn:bvh-lab', timestamp = new Date().toISOString() } = options;
  const base = { ...(actor ? { actor } : {}), timestamp };
  const statements = [];
  if (progress.lesson) {
    const lesson = `${activity}/lessons/${encodeURIComponent(progress.lesson)}`;
    const done = Boolean(progress.goal_reached);
    statements.push({
      ...base,
      verb: done ? XAPI_VERBS.completed : XAPI_VERBS.experienced,
      object: {
        objectType: 'Activity',
        id: `${lesson}/steps/${progress.step}`,
        definition: {
          type: 'http://adlnet.gov/expapi/activities/lesson',
          name: { 'en-US': `${progress.lesson}, step ${progress.step} of ${progress.steps}` },
        },
      },
      ...(done ? {
        result: {
          success: true,
          completion: true,
          score: {
            raw: progress.goals_reached,
            min: 0,
            max: progress.goals,
            scaled: progress.goals ? progress.goals_reached / progress.goals : 1,
          },
        },
      } : {}),
      context: { contextActivities: { parent: [{ objectType: 'Activity', id: lesson }] } },
    });
  }
  if (progress.exercise && progress.score) {
    const { first_time: first = 0, after_hint: hint = 0, shown = 0 } = progress.score;
    const settled = first + hint + shown;
    if (settled > 0) {
      statements.push({
        ...base,
        verb: XAPI_VERBS.answered,
        object: {
          objectType: 'Activity',
          id: `${activity}/predict/${encodeURIComponent(progress.exercise)}`,
          definition: {
            type: 'http://adlnet.gov/expapi/activities/interaction',
            name: { 'en-US': `Predict: ${progress.exercise}` },
          },
        },
        result: {
          success: shown === 0,
          score: { raw: first + hint / 2, min: 0, max: settled, scaled: (first + hint / 2) / settled },
        },
      });
    }
  }
  return statements;
}
