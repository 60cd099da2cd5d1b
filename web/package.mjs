// Writes a SCORM package of the lab: a zip file that Moodle, Canvas, Blackboard and
// Brightspace take as a SCORM activity. web/package.sh runs it (after building the page);
// README, "For teachers", says how to use it.
//
//   node web/package.mjs scorm12|scorm2004 [--lessons a,b] [--lesson-file F.toml]...
//        [--mastery 80] [--title TEXT] [--sandbox] [--dist DIR] [--out DIR]
//
// The package holds imsmanifest.xml, the launch page (index.html, with web/scorm/*.js and
// bvhlab-embed.js inside it), the lab as one file (lab.html, its WebAssembly inside), and
// the teacher's lesson files under lessons/. Nothing is fetched as a script, a module or
// WebAssembly: an LMS file server that sends a wrong content type for .js or .wasm, or
// leaves compressed files encoded, cannot stop it. The zip is made with Info-ZIP's `zip`.
import { execFileSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { builtInLessons, lessonName, outline } from './scorm/lessons.mjs';

const repo = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const fail = (message) => {
  console.error(`web/package.sh: ${message}`);
  process.exit(1);
};

const args = process.argv.slice(2);
const version = args.shift();
if (!['scorm12', 'scorm2004'].includes(version)) {
  fail('say which package: scorm12 (SCORM 1.2) or scorm2004 (SCORM 2004 4th edition)');
}
const options = { lessons: null, files: [], mastery: 80, title: 'bvh-lab', sandbox: false, dist: join(repo, 'dist'), out: join(repo, 'target', 'packages') };
while (args.length) {
  const flag = args.shift();
  const value = () => args.shift() ?? fail(`${flag} needs a value`);
  if (flag === '--lessons') options.lessons = value().split(',').map((s) => s.trim()).filter(Boolean);
  else if (flag === '--lesson-file') options.files.push(value());
  else if (flag === '--mastery') options.mastery = Number(value());
  else if (flag === '--title') options.title = value();
  else if (flag === '--sandbox') options.sandbox = true;
  else if (flag === '--dist') options.dist = resolve(value());
  else if (flag === '--out') options.out = resolve(value());
  else fail(`unknown option ${flag}`);
}
if (!Number.isInteger(options.mastery) || options.mastery < 0 || options.mastery > 100) {
  fail('--mastery is a whole number from 0 to 100');
}

const catalog = builtInLessons(repo);
const lessons = [];
for (const name of options.lessons ?? (options.files.length ? [] : catalog.map((l) => l.name))) {
  const lesson = catalog.find((l) => l.name === name);
  if (!lesson) fail(`no lesson "${name}"; the lab has ${catalog.map((l) => l.name).join(', ')}`);
  lessons.push({ ...lesson, file: null });
}
for (const path of options.files) {
  if (!existsSync(path)) fail(`${path}: no such file`);
  const bytes = readFileSync(path);
  if (bytes.length > 256 * 1024) fail(`${path}: ${Math.ceil(bytes.length / 1024)} KiB; a lesson may have at most 256 KiB`);
  const file = `lessons/${basename(path)}`;
  let lesson;
  try {
    lesson = { name: lessonName(path, true), ...outline(bytes.toString('utf8'), path) };
  } catch (error) {
    fail(error.message);
  }
  lessons.push({ ...lesson, file, source: path });
}
if (!lessons.length) fail('no lessons: name some with --lessons or --lesson-file');

const lab = join(options.dist, 'bvh-lab-offline.html');
if (!existsSync(lab)) fail(`${lab} is missing: build the page first (bash web/build.sh)`);

const escape = (text) => text.replace(/[<>&"']/g, (c) => `&#${c.charCodeAt(0)};`);
const id = `bvhlab-${version}-${lessons.map((l) => l.name).join('-')}`.replace(/[^A-Za-z0-9_.-]/g, '-').slice(0, 120);
const files = ['index.html', 'lab.html', ...lessons.flatMap((l) => (l.file ? [l.file] : []))];

/// What differs between the two versions' manifests: the root's namespaces, the schema
/// version, how the item says what passes, and the spelling of scormtype.
const VERSIONS = {
  scorm12: {
    root: `version="1.0"
  xmlns="http://www.imsproject.org/xsd/imscp_rootv1p1p2"
  xmlns:adlcp="http://www.adlnet.org/xsd/adlcp_rootv1p2"
  xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
  xsi:schemaLocation="http://www.imsproject.org/xsd/imscp_rootv1p1p2 imscp_rootv1p1p2.xsd http://www.imsglobal.org/xsd/imsmd_rootv1p2p1 imsmd_rootv1p2p1.xsd http://www.adlnet.org/xsd/adlcp_rootv1p2 adlcp_rootv1p2.xsd"`,
    schema: '1.2',
    mastery: (score) => `        <adlcp:masteryscore>${score}</adlcp:masteryscore>`,
    scormType: 'adlcp:scormtype',
  },
  scorm2004: {
    root: `version="1"
  xmlns="http://www.imsglobal.org/xsd/imscp_v1p1"
  xmlns:adlcp="http://www.adlnet.org/xsd/adlcp_v1p3"
  xmlns:adlseq="http://www.adlnet.org/xsd/adlseq_v1p3"
  xmlns:adlnav="http://www.adlnet.org/xsd/adlnav_v1p3"
  xmlns:imsss="http://www.imsglobal.org/xsd/imsss"
  xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
  xsi:schemaLocation="http://www.imsglobal.org/xsd/imscp_v1p1 imscp_v1p1.xsd http://www.adlnet.org/xsd/adlcp_v1p3 adlcp_v1p3.xsd http://www.adlnet.org/xsd/adlseq_v1p3 adlseq_v1p3.xsd http://www.adlnet.org/xsd/adlnav_v1p3 adlnav_v1p3.xsd http://www.imsglobal.org/xsd/imsss imsss_v1p0.xsd"`,
    schema: '2004 4th Edition',
    // Passed once the score (cmi.score.scaled) reaches the measure; the package itself says
    // when it is complete and whether it passed.
    mastery: (score) => `        <imsss:sequencing>
          <imsss:objectives>
            <imsss:primaryObjective objectiveID="bvhlab-mastery" satisfiedByMeasure="true">
              <imsss:minNormalizedMeasure>${(score / 100).toFixed(2)}</imsss:minNormalizedMeasure>
            </imsss:primaryObjective>
          </imsss:objectives>
          <imsss:deliveryControls completionSetByContent="true" objectiveSetByContent="true"/>
        </imsss:sequencing>`,
    scormType: 'adlcp:scormType',
  },
};

/// imsmanifest.xml: one organization with one item, the SCO, launched at index.html.
function manifest() {
  const v = VERSIONS[version];
  const fileList = files.map((f) => `      <file href="${escape(f)}"/>`).join('\n');
  const title = escape(options.title);
  return `<?xml version="1.0" encoding="UTF-8"?>
<manifest identifier="${id}" ${v.root}>
  <metadata>
    <schema>ADL SCORM</schema>
    <schemaversion>${v.schema}</schemaversion>
  </metadata>
  <organizations default="bvhlab-organization">
    <organization identifier="bvhlab-organization">
      <title>${title}</title>
      <item identifier="bvhlab-item" identifierref="bvhlab-sco" isvisible="true">
        <title>${title}</title>
${v.mastery(options.mastery)}
      </item>
    </organization>
  </organizations>
  <resources>
    <resource identifier="bvhlab-sco" type="webcontent" ${v.scormType}="sco" href="index.html">
${fileList}
    </resource>
  </resources>
</manifest>
`;
}

/// The launch page's modules as one inline module: each file without its import lines and
/// with its exports as plain declarations (they share one scope, and no names clash).
function script() {
  const modules = [join(repo, 'web', 'bvhlab-embed.js'), ...['lms.js', 'record.js', 'launch.js'].map((f) => join(repo, 'web', 'scorm', f))];
  const text = modules.map((path) => {
    const body = readFileSync(path, 'utf8')
      .replace(/^import [^;]*;\n/gm, '')
      .replace(/^export /gm, '');
    if (/^\s*(import|export)\b/m.test(body)) fail(`${path}: an import or export this bundling does not handle`);
    return `// ${basename(path)}\n${body}`;
  }).join('\n');
  if (/<\/script/i.test(text)) fail('a launch script contains "</script", which would end it early');
  return text;
}

const stage = mkdtempSync(join(tmpdir(), 'bvhlab-package-'));
try {
  const config = {
    version,
    title: options.title,
    mastery: options.mastery,
    sandbox: options.sandbox,
    lessons: lessons.map(({ name, title, steps, goals, file }) => ({ name, title, steps, goals, file })),
  };
  // JSON inside a <script>: "<" escaped, so no text in it can end the element.
  const json = JSON.stringify(config).replace(/</g, '\\u003c');
  const launch = readFileSync(join(repo, 'web', 'scorm', 'launch.html'), 'utf8')
    .replace('CONFIG', () => json)
    .replace('<script type="module" src="launch.js"></script>', () => `<script type="module">\n${script()}</script>`)
    .replaceAll('TITLE', () => escape(options.title));
  writeFileSync(join(stage, 'index.html'), launch);
  copyFileSync(lab, join(stage, 'lab.html'));
  mkdirSync(join(stage, 'lessons'), { recursive: true });
  for (const lesson of lessons) if (lesson.file) copyFileSync(lesson.source, join(stage, lesson.file));
  writeFileSync(join(stage, 'imsmanifest.xml'), manifest());
  mkdirSync(options.out, { recursive: true });
  const name = lessons.length === 1 ? `bvh-lab-${lessons[0].name}-${version}.zip` : `bvh-lab-${version}.zip`;
  const zip = join(options.out, name);
  rmSync(zip, { force: true });
  execFileSync('zip', ['-q', '-r', '-X', zip, 'imsmanifest.xml', ...files], { cwd: stage, stdio: 'inherit' });
  const goals = lessons.reduce((n, l) => n + l.goals.length, 0);
  console.log(`Wrote ${zip}: ${version === 'scorm12' ? 'SCORM 1.2' : 'SCORM 2004 4th edition'}, ` +
    `${lessons.length} lesson${lessons.length === 1 ? '' : 's'} (${lessons.map((l) => l.name).join(', ')}), ` +
    `${goals} checked steps, passing at ${options.mastery}.`);
} finally {
  rmSync(stage, { recursive: true, force: true });
}
