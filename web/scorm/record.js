// What the SCORM launch page keeps of a student's work, and the score it reports to the LMS.
//
// The record is built from the lab's progress messages (bvhlab-embed.js, onProgress): the
// lesson and step open, which steps' goals the student reached in the package's lessons, and
// Predict's score for each exercise the student played. It goes to the LMS as `suspend_data`
// (SCORM 1.2 allows 4,096 characters there), so that a student who comes back on another
// computer resumes at their lesson and step with their goals reached.
//
// The score rule (README, "For teachers"): every step of the package's lessons that has a goal
// counts 1 point, earned when its goal is reached; every Predict exercise the student played
// (a structure and a task, "2D AABB tree: first hit") counts 1 point more, earned in part: the
// share of its predictions right the first time, a prediction right after a hint counting
// half. The score is the points earned over the points counted, 0 to 100. Predict is optional:
// a student who never uses it is scored on the goals alone.

/// SCORM 1.2's limit on `cmi.suspend_data`, in characters.
export const SUSPEND_DATA_LIMIT = 4096;

/// An empty record.
export function emptyRecord() {
  return { lesson: null, step: 1, reached: {}, predict: {} };
}

/// Takes the progress message `p` into `record` (changing it); returns whether anything the
/// LMS keeps changed.
export function takeProgress(record, p, course) {
  const before = encode(record, course);
  if (p.lesson) {
    record.lesson = p.lesson;
    record.step = p.step;
    if (p.goal_reached && inCourse(course, p.lesson)) {
      const steps = new Set(record.reached[p.lesson] ?? []);
      steps.add(p.step);
      record.reached[p.lesson] = [...steps].sort((a, b) => a - b);
    }
  }
  if (p.exercise && p.score) {
    const { first_time: first = 0, after_hint: hint = 0, shown = 0 } = p.score;
    // Most recent last: what is dropped first when suspend_data runs out of room.
    delete record.predict[p.exercise];
    record.predict[p.exercise] = [first, hint, shown];
  }
  return encode(record, course) !== before;
}

const inCourse = (course, name) => course.lessons.some((l) => l.name === name);

/// The points counted and earned, and the score 0-100 (a whole number).
export function score(record, course) {
  let counted = 0;
  let earned = 0;
  let goals = 0;
  let reached = 0;
  for (const lesson of course.lessons) {
    const done = new Set(record.reached[lesson.name] ?? []);
    for (const step of lesson.goals) {
      goals += 1;
      if (done.has(step)) reached += 1;
    }
  }
  counted += goals;
  earned += reached;
  for (const [first, hint, shown] of Object.values(record.predict)) {
    const asked = first + hint + shown;
    if (asked === 0) continue;
    counted += 1;
    earned += (first + hint / 2) / asked;
  }
  const value = counted === 0 ? 0 : Math.round((100 * earned) / counted);
  return { value, goals, reached, exercises: counted - goals };
}

/// The record as `suspend_data`: compact JSON of at most `limit` characters. Reached steps go
/// as one string per lesson ("1101": steps 1, 2 and 4); when Predict's exercises do not all
/// fit, the oldest are left out (their points no longer count: the rule scores what the LMS
/// keeps).
export function encode(record, course, limit = SUSPEND_DATA_LIMIT) {
  const r = {};
  for (const lesson of course.lessons) {
    const done = record.reached[lesson.name];
    if (!done?.length) continue;
    const bits = Array.from({ length: Math.max(...done) }, (_, i) => (done.includes(i + 1) ? '1' : '0'));
    r[lesson.name] = bits.join('');
  }
  const predict = Object.entries(record.predict);
  for (let skip = 0; skip <= predict.length; skip += 1) {
    const data = { v: 1, l: record.lesson, s: record.step, r, p: Object.fromEntries(predict.slice(skip)) };
    const text = JSON.stringify(data);
    if (text.length <= limit) return text;
  }
  // Only the reached steps and the place: these always fit (they are bounded by the course).
  return JSON.stringify({ v: 1, l: record.lesson, s: record.step, r, p: {} });
}

/// The record `suspend_data` holds; an empty one for no data or data it cannot read (what
/// another package, or a hand-edited gradebook, left there), with the reason.
export function decode(text, course) {
  const record = emptyRecord();
  if (!text) return { record, problem: null };
  let data;
  try {
    data = JSON.parse(text);
  } catch {
    return { record, problem: 'the LMS kept data this lab cannot read; starting afresh' };
  }
  if (data?.v !== 1 || typeof data !== 'object') {
    return { record, problem: 'the LMS kept data of another version; starting afresh' };
  }
  if (typeof data.l === 'string') record.lesson = data.l;
  if (Number.isInteger(data.s) && data.s >= 1) record.step = data.s;
  for (const [name, bits] of Object.entries(data.r ?? {})) {
    if (!inCourse(course, name) || typeof bits !== 'string') continue;
    record.reached[name] = [...bits].flatMap((bit, i) => (bit === '1' ? [i + 1] : []));
  }
  for (const [exercise, counts] of Object.entries(data.p ?? {})) {
    if (Array.isArray(counts) && counts.length === 3 && counts.every((n) => Number.isInteger(n) && n >= 0)) {
      record.predict[exercise] = counts;
    }
  }
  return { record, problem: null };
}
