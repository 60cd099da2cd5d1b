// The SCORM package's launch page: finds the LMS's run-time, puts the lab (lab.html, the
// single-file build) in a frame, opens the package's lesson where the student left off, and
// turns the lab's progress into SCORM calls. Its settings are the JSON in
// <script id="bvhlab-package"> (written by web/package.mjs).
import { BvhLab } from './bvhlab-embed.js';
import { Lms, findApi, sessionTime } from './lms.js';
import { decode, emptyRecord, encode, score, takeProgress } from './record.js';

const course = JSON.parse(document.getElementById('bvhlab-package').textContent);
const status = document.getElementById('lms-status');
const say = (text) => { status.textContent = text; };
const params = new URLSearchParams(location.search);

const api = findApi(window, course.version === 'scorm2004' ? 'API_1484_11' : 'API');
const lms = api ? new Lms(course.version, api) : null;
const v12 = course.version === 'scorm12';
const started = performance.now();
let record = emptyRecord();
let note = '';

if (lms && lms.initialize()) {
  const decoded = decode(lms.get('cmi.suspend_data'), course);
  record = decoded.record;
  note = decoded.problem ? ` (${decoded.problem})` : '';
  // A first attempt is incomplete until the student does something: never passed at load.
  if (v12 && ['not attempted', ''].includes(lms.get('cmi.core.lesson_status'))) {
    lms.set('cmi.core.lesson_status', 'incomplete');
  } else if (!v12 && ['not attempted', 'unknown', ''].includes(lms.get('cmi.completion_status'))) {
    lms.set('cmi.completion_status', 'incomplete');
  }
  lms.set(v12 ? 'cmi.core.exit' : 'cmi.exit', 'suspend');
  lms.commit();
}

/// Writes the record to the LMS and commits.
function report() {
  const { value, goals, reached, exercises } = score(record, course);
  const passed = value >= course.mastery;
  const complete = goals > 0 && reached === goals;
  const words = `${reached} of ${goals} checked steps done` +
    (exercises ? `, ${exercises} Predict exercise${exercises === 1 ? '' : 's'}` : '') +
    `: score ${value} of 100 (${course.mastery} or more passes)`;
  if (!lms?.live()) {
    const why = !lms
      ? 'No LMS found: this session is not recorded'
      : !lms.started
        ? `The LMS did not start a session (${lms.problems.join('; ') || 'it said no'}): this session is not recorded`
        : 'The LMS session has ended';
    say(`${why}. ${words}.`);
    return;
  }
  const place = record.lesson ? `${record.lesson}/${record.step}` : '';
  const seconds = (performance.now() - started) / 1000;
  if (v12) {
    lms.set('cmi.core.lesson_location', place.slice(0, 255));
    lms.set('cmi.core.score.min', 0);
    lms.set('cmi.core.score.max', 100);
    lms.set('cmi.core.score.raw', value);
    lms.set('cmi.core.lesson_status', passed ? 'passed' : complete ? 'failed' : 'incomplete');
    lms.set('cmi.core.session_time', sessionTime('scorm12', seconds));
  } else {
    lms.set('cmi.location', place.slice(0, 1000));
    lms.set('cmi.score.min', 0);
    lms.set('cmi.score.max', 100);
    lms.set('cmi.score.raw', value);
    lms.set('cmi.score.scaled', (value / 100).toFixed(2));
    lms.set('cmi.progress_measure', goals ? (reached / goals).toFixed(2) : '0');
    lms.set('cmi.completion_status', complete ? 'completed' : 'incomplete');
    lms.set('cmi.success_status', passed ? 'passed' : complete ? 'failed' : 'unknown');
    lms.set('cmi.session_time', sessionTime('scorm2004', seconds));
  }
  lms.set('cmi.suspend_data', encode(record, course, v12 ? 4096 : 64000));
  lms.commit();
  say(`Recorded in the course: ${words}.${note}`);
}

/// Ends the LMS session once, when the page goes away (the frame is closed, the window
/// shut, the LMS moves on); nothing is sent after it.
function finish() {
  if (!lms?.live()) return;
  const seconds = (performance.now() - started) / 1000;
  lms.set(v12 ? 'cmi.core.session_time' : 'cmi.session_time', sessionTime(course.version, seconds));
  lms.set(v12 ? 'cmi.core.exit' : 'cmi.exit', 'suspend');
  lms.commit();
  lms.finish();
}
addEventListener('pagehide', finish);
addEventListener('beforeunload', finish);

// The lab. Its own browser storage stays out of it (fresh=1): the LMS keeps each student's
// work, and a shared computer must not hand one student's progress to the next.
const frame = document.getElementById('lab');
const address = new URL('lab.html', location.href);
address.searchParams.set('fresh', '1');
// Sandboxed (the package's setting or ?sandbox=1 in the launch address): the lab's origin is
// opaque, so it must be told to take commands from this page's origin.
if (course.sandbox || params.get('sandbox') === '1') {
  frame.setAttribute('sandbox', 'allow-scripts allow-downloads allow-popups');
  if (self.origin !== 'null') address.searchParams.set('origin', self.origin);
}
frame.src = address.href;

const lab = new BvhLab(frame);
window.bvhlabPackage = { lab, course, lms };
lab.onProgress((p) => {
  if (takeProgress(record, p, course)) report();
});
lab.onPanic((message) => say(`The lab stopped: ${message}. Reload the page to go on; what is recorded stays.`));

say('The lab is starting…');
try {
  await lab.ready();
  await open();
  report();
  document.body.dataset.ready = 'true';
} catch (error) {
  say(`The lab could not open the lesson: ${error.message}`);
  document.body.dataset.ready = 'failed';
}

/// Opens the student's lesson and step (the package's first lesson on a first visit), with
/// the goals they reached before.
async function open() {
  const known = course.lessons.find((l) => l.name === record.lesson);
  const lesson = known ?? course.lessons[0];
  const step = known ? Math.min(record.step, lesson.steps) : 1;
  if (lesson.file) {
    const response = await fetch(new URL(lesson.file, location.href));
    if (!response.ok) throw new Error(`${lesson.file}: the LMS answered ${response.status}`);
    await lab.loadLesson(await response.text(), lesson.file.split('/').pop(), step);
  }
  await lab.goToLesson(lesson.name, step, record.reached[lesson.name] ?? []);
}
