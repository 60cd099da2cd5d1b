// The example course page (web/course.html): one lab opened on a lesson, and the student's
// progress as the lab reports it. `window.lab` and `window.progress` are there for the
// browser test, which drives this page.
import { BvhLab } from './bvhlab-embed.js';

const lab = new BvhLab(document.getElementById('lab'));
window.lab = lab;
window.progress = [];
// The same progress as xAPI statements, as an LMS plugin that speaks xAPI would record them
// (here kept for the browser test; a real page would send them to its LRS).
window.statements = [];
lab.onStatement((statement) => window.statements.push(statement), {
  actor: { objectType: 'Agent', account: { homePage: location.origin, name: 'example-student' } },
});
const list = document.getElementById('progress');
const status = document.getElementById('course-status');

lab.onProgress((p) => {
  window.progress.push(p);
  const item = document.createElement('li');
  const parts = [];
  if (p.lesson) {
    parts.push(p.goal_reached
      ? `${p.lesson}, step ${p.step} of ${p.steps}: done (${p.goals_reached} of ${p.goals} tasks of the lesson done)`
      : `${p.lesson}, step ${p.step} of ${p.steps}: opened`);
  }
  if (p.exercise) {
    const s = p.score;
    parts.push(`predicting ${p.exercise}: ${s.first_time} right first time, ${s.after_hint} after a hint, ${s.shown} shown`);
  }
  item.textContent = parts.join('; ');
  list.append(item);
});

document.getElementById('open').onclick = async () => {
  const name = document.getElementById('lesson').value;
  try {
    await lab.goToLesson(name, 1);
    status.textContent = `The lab opened ${name}.`;
  } catch (error) {
    status.textContent = `The lab refused: ${error.message}`;
  }
};

await lab.ready();
status.textContent = 'The lab is ready.';
window.courseReady = true;
