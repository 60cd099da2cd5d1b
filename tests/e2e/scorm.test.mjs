// bvh-lab's SCORM packages in an LMS, with scorm-again (the SCORM 1.2 and 2004 run-time LMS
// vendors use) standing in for the LMS:
//
// 1. The record's suspend_data stays within SCORM 1.2's 4,096 characters over a long session
//    (web/scorm/record.js, run here in Node).
// 2. SCORM 1.2 (`web/package.sh scorm12 --lessons slab-test --mastery 60`), launched in a
//    frame of an LMS page that provides window.API: the student does the lesson's first step
//    through the lab's API (incomplete, score 33), then the second (passed, 67); the test
//    reads cmi.core.* back and the commits the run-time posts; the frame is closed: LMSFinish
//    once, and no call after it; a second launch with that suspend_data resumes the student
//    at step 2 with both goals reached.
// 3. SCORM 2004 with a teacher's lesson file, launched in a new window (the API on its
//    opener) with the lab in a sandboxed frame: completed, passed, score.scaled 1.
//
// The packages are served by a careless file server (everything but .html as
// application/octet-stream): they must start all the same.
//
//   node tests/e2e/scorm.test.mjs

import { execFileSync } from 'node:child_process';
import { createReadStream, existsSync, mkdirSync, rmSync, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { dirname, extname, join, normalize, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { BASE_ARGS, Failure, check, seconds } from './browser.mjs';
import { SUSPEND_DATA_LIMIT, decode, emptyRecord, encode, score, takeProgress } from '../../web/scorm/record.js';
import { xapiStatements } from '../../web/bvhlab-embed.js';
import { builtInLessons } from '../../web/scorm/lessons.mjs';

const began = performance.now();
const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const work = join(repo, 'target', 'e2e', 'scorm');
const TIMEOUT_MS = 90_000;

// 1. A long session, in Node: 400 Predict exercises with long names, every step of two lessons.
{
  const course = { lessons: [{ name: 'slab-test', goals: [1, 2, 3], steps: 3 }, { name: 'kd-tree', goals: [1, 2], steps: 2 }], mastery: 80 };
  const record = emptyRecord();
  let longest = 0;
  for (let i = 0; i < 400; i += 1) {
    takeProgress(record, { exercise: `3D bounding volume hierarchy with a long name ${i}: k nearest neighbours`, score: { first_time: i % 3, after_hint: 1, shown: 0 } }, course);
    takeProgress(record, { lesson: i % 2 ? 'slab-test' : 'kd-tree', step: 1 + (i % 2), steps: 3, goal_reached: true }, course);
    longest = Math.max(longest, encode(record, course).length);
  }
  check(longest <= SUSPEND_DATA_LIMIT, `suspend_data reached ${longest} characters; SCORM 1.2 allows ${SUSPEND_DATA_LIMIT}`);
  const back = decode(encode(record, course), course).record;
  check(JSON.stringify(back.reached) === JSON.stringify({ 'slab-test': [2], 'kd-tree': [1] }), `the reached steps came back as ${JSON.stringify(back.reached)}`);
  check(Object.keys(back.predict).length > 10 && back.predict['3D bounding volume hierarchy with a long name 399: k nearest neighbours'], 'the latest exercises are kept');
  const s = score(back, course);
  check(s.goals === 5 && s.reached === 2 && s.value > 0 && s.value < 100, `score ${JSON.stringify(s)}`);
  check(decode('not json', course).problem, 'unreadable suspend_data is said');
  console.log(`scorm: a long session's suspend_data stays at ${longest} characters at most`);
  // Predict's score as an xAPI statement (the lesson's are checked on the course page, embed.test.mjs).
  const [answered] = xapiStatements({ exercise: '2D AABB tree: first hit', score: { first_time: 2, after_hint: 1, shown: 1 } }, { activity: 'https://course.example/lab', timestamp: '2026-12-03T08:00:00Z' });
  check(answered.verb.id === 'http://adlnet.gov/expapi/verbs/answered' && answered.object.id === 'https://course.example/lab/predict/2D%20AABB%20tree%3A%20first%20hit' &&
    answered.result.score.raw === 2.5 && answered.result.score.max === 4 && answered.result.score.scaled === 0.625 && answered.result.success === false,
  `Predict's xAPI statement: ${JSON.stringify(answered)}`);
  check(xapiStatements({ exercise: 'x', score: { first_time: 0, after_hint: 0, shown: 0 } }).length === 0, 'no statement before a prediction is settled');
}

// The packages.
rmSync(work, { recursive: true, force: true });
mkdirSync(join(work, 'lms'), { recursive: true });
const pack = (dir, ...args) => {
  execFileSync('bash', ['web/package.sh', ...args, '--out', join(work, 'zips')], { cwd: repo, stdio: 'inherit' });
};
pack('scorm12', 'scorm12', '--lessons', 'slab-test', '--mastery', '60', '--title', 'Slab test <week 3>');
pack('scorm2004', 'scorm2004', '--lesson-file', 'tests/e2e/fixtures/exam-warm-up.toml', '--mastery', '100');
for (const [zip, dir] of [['bvh-lab-slab-test-scorm12.zip', 'scorm12'], ['bvh-lab-exam-warm-up-scorm2004.zip', 'scorm2004']]) {
  execFileSync('unzip', ['-q', join(work, 'zips', zip), '-d', join(work, 'lms', dir)], { stdio: 'inherit' });
  check(existsSync(join(work, 'lms', dir, 'imsmanifest.xml')), `${zip} has imsmanifest.xml at its root`);
}
const manifest12 = execFileSync('cat', [join(work, 'lms', 'scorm12', 'imsmanifest.xml')], { encoding: 'utf8' });
check(manifest12.includes('<adlcp:masteryscore>60</adlcp:masteryscore>') && manifest12.includes('adlcp:scormtype="sco"') && manifest12.includes('Slab test &#60;week 3&#62;'), 'the SCORM 1.2 manifest has the mastery score, the SCO and the escaped title');
const manifest2004 = execFileSync('cat', [join(work, 'lms', 'scorm2004', 'imsmanifest.xml')], { encoding: 'utf8' });
check(manifest2004.includes('<imsss:minNormalizedMeasure>1.00</imsss:minNormalizedMeasure>') && manifest2004.includes('<file href="lessons/exam-warm-up.toml"/>'), 'the SCORM 2004 manifest has the measure and the lesson file');

// The LMS: its page, the run-time, and a file server that does not care about content types.
const commits = [];
const server = createServer((request, response) => {
  if (request.method === 'POST') {
    let body = '';
    request.on('data', (chunk) => { body += chunk; });
    request.on('end', () => {
      commits.push(JSON.parse(body || 'null'));
      response.writeHead(200, { 'content-type': 'application/json' }).end('{"result": true, "errorCode": 0}');
    });
    return;
  }
  const path = decodeURIComponent(new URL(request.url, 'http://x').pathname);
  const file = path.startsWith('/scorm-again/')
    ? join(repo, 'tests/e2e/node_modules/scorm-again/dist', path.slice('/scorm-again/'.length))
    : join(work, 'lms', normalize(path));
  if (path === '/lms.html') {
    response.writeHead(200, { 'content-type': 'text/html' }).end('<!DOCTYPE html><title>LMS</title><link rel="icon" href="data:,">');
    return;
  }
  if (!file.startsWith(repo) || !existsSync(file) || !statSync(file).isFile()) {
    response.writeHead(404).end();
    return;
  }
  const type = extname(file) === '.html' ? 'text/html' : 'application/octet-stream';
  response.writeHead(200, { 'content-type': type });
  createReadStream(file).pipe(response);
});
await new Promise((done) => server.listen(0, '127.0.0.1', done));
const origin = `http://127.0.0.1:${server.address().port}`;

const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', args: BASE_ARGS });
try {
  const context = await browser.newContext({ viewport: { width: 1280, height: 720 } });

  /// An LMS page with the run-time of `version`, holding `cmi` from an earlier session, and
  /// every call the content makes logged in `window.calls`.
  const lms = async (version, cmi) => {
    const page = await context.newPage();
    page.on('pageerror', (error) => console.log(`scorm: page error: ${error.message}`));
    page.on('console', (message) => {
      if (message.type() === 'error') console.log(`scorm: console ${message.type()}: ${message.text()}`);
    });
    await page.goto(`${origin}/lms.html`);
    await page.addScriptTag({ url: `/scorm-again/${version === 'scorm12' ? 'scorm12' : 'scorm2004'}.min.js` });
    await page.evaluate(({ version, cmi }) => {
      const settings = { lmsCommitUrl: '/commit', autocommit: false, logLevel: 5 };
      const api = version === 'scorm12' ? new window.Scorm12API(settings) : new window.Scorm2004API(settings);
      if (cmi) api.loadFromJSON(cmi, '');
      window.calls = [];
      const methods = version === 'scorm12'
        ? ['LMSInitialize', 'LMSGetValue', 'LMSSetValue', 'LMSCommit', 'LMSFinish', 'LMSGetLastError', 'LMSGetErrorString']
        : ['Initialize', 'GetValue', 'SetValue', 'Commit', 'Terminate', 'GetLastError', 'GetErrorString'];
      const logged = {};
      for (const method of methods) {
        const call = api[method].bind(api);
        logged[method] = (...args) => {
          const answer = call(...args);
          window.calls.push([method, ...args, String(answer)]);
          return answer;
        };
      }
      window[version === 'scorm12' ? 'API' : 'API_1484_11'] = logged;
      window.runtime = api;
    }, { version, cmi });
    return page;
  };
  /// Launches the package at `src` in a frame of the LMS page, as Moodle does by default.
  const inFrame = (page, src) => page.evaluate((src) => {
    const frame = document.createElement('iframe');
    frame.id = 'content';
    frame.style.cssText = 'width: 1260px; height: 700px; border: 0';
    frame.src = src;
    document.body.append(frame);
  }, src);
  /// The frame of `page` whose address matches `url`, once it is there.
  const frameOf = async (page, url) => {
    for (let i = 0; i < 100; i += 1) {
      const frame = page.frames().find((f) => url.test(f.url()));
      if (frame) return frame;
      await page.waitForTimeout(100);
    }
    throw new Failure(`no frame at ${url}`);
  };
  const launched = async (target) => {
    await target.waitForFunction(() => document.body.dataset.ready, null, { timeout: TIMEOUT_MS }).catch(async (error) => {
      console.log(`scorm: the launch page says: ${await target.evaluate(() => document.getElementById('lms-status')?.textContent)}`);
      throw error;
    });
    const state = await target.evaluate(() => [document.body.dataset.ready, document.getElementById('lms-status').textContent]);
    check(state[0] === 'true', `the package did not start: ${state[1]}`);
  };
  const student = (target, script, arg) => target.evaluate(script, arg);
  const waitFor = async (page, accept, what) => {
    const start = performance.now();
    while (performance.now() - start < TIMEOUT_MS) {
      const values = await page.evaluate(() => JSON.parse(JSON.stringify(window.runtime.cmi)));
      if (accept(values)) return values;
      await page.waitForTimeout(200);
    }
    const values = await page.evaluate(() => JSON.stringify(window.runtime.cmi));
    throw new Failure(`${what}: the LMS holds ${values}`);
  };
  const finishedOnce = async (page, finish) => {
    const calls = await page.evaluate(() => window.calls);
    const at = calls.findIndex(([m]) => m === finish);
    check(at >= 0 && calls.filter(([m]) => m === finish).length === 1, `${finish} was called ${calls.filter(([m]) => m === finish).length} times`);
    check(at === calls.length - 1, `calls after ${finish}: ${JSON.stringify(calls.slice(at + 1))}`);
    check(calls[at].at(-1) === 'true', `${finish} answered ${calls[at].at(-1)}`);
    const initialised = calls.filter(([m]) => m === 'LMSInitialize' || m === 'Initialize');
    check(initialised.length === 1, `initialised ${initialised.length} times`);
    const suspend = calls.filter(([m, e]) => m.endsWith('SetValue') && e === 'cmi.suspend_data');
    check(suspend.length > 0 && suspend.every(([, , value]) => value.length <= SUSPEND_DATA_LIMIT), 'every suspend_data within 4,096 characters');
    return calls;
  };

  // 2. SCORM 1.2 in a frame.
  let page = await lms('scorm12', null);
  await inFrame(page, '/scorm12/index.html');
  let launch = await frameOf(page, /\/scorm12\/index\.html/);
  await launched(launch);
  let cmi = await waitFor(page, (c) => c.core.lesson_status === 'incomplete' && c.core.lesson_location === 'slab-test/1', 'at launch: incomplete at slab-test step 1');
  check(cmi.core.score.raw === '0' || cmi.core.score.raw === '', `no score at launch: ${cmi.core.score.raw}`);
  await student(launch, () => window.bvhlabPackage.lab.setRay([2, -1], [0, 1]));
  cmi = await waitFor(page, (c) => c.core.score.raw === '33', 'after step 1 the score is 33');
  check(cmi.core.lesson_status === 'incomplete' && cmi.core.score.min === '0' && cmi.core.score.max === '100', `after step 1: ${JSON.stringify(cmi.core)}`);
  await student(launch, async () => {
    await window.bvhlabPackage.lab.goToLesson('slab-test', 2);
    await window.bvhlabPackage.lab.setRay([0.8, 3], [0, 1]);
  });
  cmi = await waitFor(page, (c) => c.core.score.raw === '67' && c.core.lesson_status === 'passed', 'after step 2: 67, passed');
  check(cmi.core.lesson_location === 'slab-test/2', `location ${cmi.core.lesson_location}`);
  const status12 = await launch.evaluate(() => document.getElementById('lms-status').textContent);
  check(/2 of 3 checked steps done: score 67 of 100/.test(status12), `the launch page says: ${status12}`);
  await page.screenshot({ path: join(repo, 'target', 'e2e', 'scorm12-lms.png') });
  check(commits.length >= 3 && commits.some((c) => c?.cmi?.core?.score?.raw === '67'), `the run-time posted ${commits.length} commits, the last ${JSON.stringify(commits.at(-1))?.slice(0, 300)}`);
  await page.evaluate(() => document.getElementById('content').remove());
  await page.waitForTimeout(500);
  await finishedOnce(page, 'LMSFinish');
  cmi = await page.evaluate(() => JSON.parse(JSON.stringify(window.runtime.cmi)));
  check(/^\d{2,4}:\d{2}:\d{2}(\.\d+)?$/.test(cmi.core.session_time) && cmi.core.session_time !== "0000:00:00.00", `session_time ${cmi.core.session_time}`);
  const kept = cmi.suspend_data;
  check(kept.length > 0 && kept.length <= SUSPEND_DATA_LIMIT, `suspend_data: ${kept}`);
  await page.close();

  // The second launch resumes from what the LMS kept.
  page = await lms('scorm12', { suspend_data: kept, core: { lesson_status: 'passed', lesson_location: 'slab-test/2', entry: 'resume' } });
  await inFrame(page, '/scorm12/index.html');
  launch = await frameOf(page, /\/scorm12\/index\.html/);
  await launched(launch);
  const resumed = await student(launch, () => window.bvhlabPackage.lab.report());
  check(resumed.lesson?.lesson === 'slab-test' && resumed.lesson.step === 2 && resumed.lesson.goals_reached === 2, `the second launch is at ${JSON.stringify(resumed.lesson)}`);
  cmi = await waitFor(page, (c) => c.core.score.raw === '67', 'the score after resuming');
  check(cmi.core.lesson_status === 'passed', `resumed status ${cmi.core.lesson_status}`);
  // The steps the package counts (web/scorm/lessons.mjs reads the files) are those the lab
  // itself counts, for every lesson.
  const counted = await student(launch, async (catalog) => {
    const lab = window.bvhlabPackage.lab;
    const wrong = [];
    for (const lesson of catalog) {
      const { lesson: open } = await lab.goToLesson(lesson.name, 1);
      if (open.steps !== lesson.steps || open.goals !== lesson.goals.length) wrong.push({ lesson, open });
    }
    return wrong;
  }, builtInLessons(repo));
  check(counted.length === 0, `the package counts other steps than the lab: ${JSON.stringify(counted)}`);
  await page.close(); // pagehide in the frame: LMSFinish
  console.log('scorm: SCORM 1.2 scored, passed, finished once and resumed');

  // 3. SCORM 2004, a teacher's lesson, in a new window with the lab sandboxed.
  page = await lms('scorm2004', null);
  const [popup] = await Promise.all([
    page.waitForEvent('popup'),
    page.evaluate(() => { window.content = window.open('/scorm2004/index.html?sandbox=1', 'content', 'width=1280,height=720'); }),
  ]);
  await launched(popup);
  check(await popup.evaluate(() => document.getElementById('lab').getAttribute('sandbox') === 'allow-scripts allow-downloads allow-popups'), 'the lab is in a sandboxed frame');
  let report = await student(popup, () => window.bvhlabPackage.lab.report());
  check(report.lesson?.lesson === 'exam-warm-up' && report.lesson.step === 1, `the teacher's lesson opened: ${JSON.stringify(report.lesson)}`);
  await student(popup, async () => {
    await window.bvhlabPackage.lab.goToLesson('exam-warm-up', 2);
    await window.bvhlabPackage.lab.setRay([2, -1], [0, 1]);
  });
  cmi = await waitFor(page, (c) => c.success_status === 'passed', 'the 2004 package passed');
  check(cmi.completion_status === 'completed' && cmi.score.raw === '100' && Number(cmi.score.scaled) === 1 && cmi.location === 'exam-warm-up/2', `2004: ${JSON.stringify({ ...cmi, suspend_data: undefined }).slice(0, 600)}`);
  check(/^P(T(\d+H)?(\d+M)?[\d.]+S)$/.test(cmi.session_time), `2004 session_time ${cmi.session_time}`);
  await popup.screenshot({ path: join(repo, 'target', 'e2e', 'scorm2004-window.png') });
  await popup.close({ runBeforeUnload: true });
  await page.waitForTimeout(500);
  await finishedOnce(page, 'Terminate');
  console.log('scorm: SCORM 2004 with a teacher\'s lesson, in a new window and a sandboxed frame: completed, passed, terminated once');
  await page.close();

  // 4. An LMS page of another origin (localhost against 127.0.0.1): its windows throw when the
  // launch page looks for the API there; the package says it records nothing, and the lab runs.
  page = await context.newPage();
  const foreign = origin.replace('127.0.0.1', 'localhost');
  await page.goto(`${foreign}/lms.html`);
  await page.evaluate(() => { window.API = { LMSInitialize: () => { throw new Error('must not be reached'); } }; });
  await inFrame(page, `${origin}/scorm12/index.html`);
  launch = await frameOf(page, /\/scorm12\/index\.html/);
  await launched(launch);
  const alone = await launch.evaluate(() => document.getElementById('lms-status').textContent);
  check(alone.startsWith('No LMS found: this session is not recorded.'), `without a reachable LMS the page says: ${alone}`);
  report = await student(launch, () => window.bvhlabPackage.lab.setRay([2, -1], [0, 1]));
  check(report.lesson?.goal_reached, 'the lab works without an LMS');
  console.log('scorm: inside an LMS page of another origin: no API reachable, said so, the lab runs');
} finally {
  await browser.close();
  server.close();
}
console.log(`scorm: passed in ${seconds(performance.now() - began)}`);
