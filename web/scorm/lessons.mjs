// The lessons a SCORM package counts, read in Node by web/package.mjs (and by its test): each
// lesson's name, title, number of steps and the steps that have a goal.
import { readFileSync, readdirSync } from 'node:fs';
import { basename, join } from 'node:path';

/// `slab-test` for `03-slab-test.toml` (the lab's own rule, lessons/format.rs lesson_name).
export function lessonName(file, teacher) {
  const stem = basename(file).replace(/\.toml$/, '');
  const dash = stem.indexOf('-');
  const unnumbered = dash > 0 && /^\d+$/.test(stem.slice(0, dash)) ? stem.slice(dash + 1) : stem;
  if (!teacher) return unnumbered;
  const name = unnumbered.replace(/[^A-Za-z0-9]/g, '-').toLowerCase();
  return name.replace(/-/g, '') ? name : 'teachers-lesson';
}

/// A lesson file's title, its number of steps and the steps (from 1) that have a goal:
/// what the score counts. The lab reads the file in full when it opens it; this reads only
/// the keys at the start of a line, outside multi-line strings.
export function outline(text, file) {
  let title = null;
  let steps = 0;
  const goals = [];
  let open = null; // the delimiter of the multi-line string being read
  for (const line of text.split('\n')) {
    if (open) {
      if (line.includes(open)) open = null;
      continue;
    }
    const trimmed = line.trim();
    if (trimmed === '[[step]]') steps += 1;
    const key = /^([A-Za-z_]+)\s*=\s*(.*)$/.exec(trimmed);
    if (!key) continue;
    const [, name, value] = key;
    for (const quote of ['"""', "'''"]) {
      if (value.startsWith(quote) && !value.slice(3).includes(quote)) open = quote;
    }
    if (name === 'title' && steps === 0) title = /^"(.*)"$/.exec(value)?.[1] ?? value;
    if (name === 'goal' && steps > 0 && !goals.includes(steps)) goals.push(steps);
  }
  if (steps === 0) throw new Error(`${file}: no [[step]]: is it a lesson file?`);
  return { title: title ?? file, steps, goals };
}

/// The lab's own lessons (crates/bvhlab-app/lessons/*.toml, in the lab's order).
export function builtInLessons(repo) {
  const dir = join(repo, 'crates', 'bvhlab-app', 'lessons');
  return readdirSync(dir).filter((f) => f.endsWith('.toml')).sort()
    .map((f) => ({ name: lessonName(f, false), ...outline(readFileSync(join(dir, f), 'utf8'), f) }));
}
