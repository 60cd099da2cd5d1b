// The example embedding page (web/embed.html): two labs, scripted together through
// bvhlab-embed.js. `window.labs` is there for the browser test, which drives this page.
import { BvhLab } from './bvhlab-embed.js';

const labs = {
  left: new BvhLab(document.getElementById('left')),
  right: new BvhLab(document.getElementById('right')),
};
window.labs = labs;
const status = document.getElementById('embed-status');

function numbers(id) {
  return document.getElementById(id).value.split(',').map(Number);
}

function show(name, report) {
  const row = document.getElementById(`row-${name}`);
  const lane = report.playback?.[0];
  const hit = report.query?.hit;
  const cells = [
    report.structure,
    hit ? `#${hit.primitive} at t = ${hit.t.toFixed(3)}` : 'none',
    lane ? `${lane.step} / ${lane.steps}` : '–',
    lane ? lane.so_far[0] : '–',
    report.query ? report.query.primitive_tests : '–',
    report.query ? report.query.brute_force_tests : '–',
    report.query ? (report.query.agrees ? 'yes' : 'NO') : '–',
  ];
  row.replaceChildren(row.firstElementChild, ...cells.map((text) => {
    const td = document.createElement('td');
    td.textContent = String(text);
    return td;
  }));
}

async function both(action) {
  try {
    const [left, right] = await Promise.all([action(labs.left), action(labs.right)]);
    show('left', left);
    show('right', right);
    status.textContent = 'Both labs answered.';
  } catch (error) {
    status.textContent = `A lab refused: ${error.message}`;
  }
}

document.getElementById('cast').onclick = () => both((lab) => lab.setRay(numbers('origin'), numbers('direction')));
document.getElementById('step').onclick = () => both((lab) => lab.step(1));
document.getElementById('back').onclick = () => both((lab) => lab.step(-1));
document.getElementById('end').onclick = () => both((lab) => lab.goToStep(1e9));

await both((lab) => lab.ready());
window.labsReady = true;
