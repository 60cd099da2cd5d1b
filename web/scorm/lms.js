// The LMS's SCORM run-time as the launch page talks to it: found in the windows around the
// page, started once, written and committed after each change, finished exactly once.
//
// SCORM 1.2 calls its object `API` (LMSInitialize, LMSGetValue, ...); SCORM 2004 calls it
// `API_1484_11` (Initialize, GetValue, ...). The LMS puts it on a window above the content:
// a parent frame, or the window that opened the content's window. Frames of another origin
// throw when touched: the search steps over them.

/// The run-time's object, searched in `start`'s parents, then in its opener and the opener's
/// parents (ADL's search, with a bound on the depth); null when there is none.
export function findApi(start, name) {
  const look = (win) => {
    for (let depth = 0; win && depth < 64; depth += 1) {
      try {
        if (win[name]) return win[name];
      } catch {
        // A frame of another origin: nothing to read there, but its parent may have it.
      }
      let parent = null;
      try {
        parent = win.parent;
      } catch {
        return null;
      }
      if (!parent || parent === win) return null;
      win = parent;
    }
    return null;
  };
  let opener = null;
  try {
    opener = start.opener;
  } catch {
    // The opener is of another origin.
  }
  return look(start) ?? (opener ? look(opener) : null);
}

/// SCORM 1.2 and 2004 behind the same calls: `get(element)`, `set(element, value)`,
/// `commit()`, `finish()`; the elements named as in 1.2 are mapped to 2004's.
const VERSIONS = {
  scorm12: {
    apiName: 'API',
    init: 'LMSInitialize',
    get: 'LMSGetValue',
    set: 'LMSSetValue',
    commit: 'LMSCommit',
    finish: 'LMSFinish',
    error: 'LMSGetLastError',
    errorText: 'LMSGetErrorString',
  },
  scorm2004: {
    apiName: 'API_1484_11',
    init: 'Initialize',
    get: 'GetValue',
    set: 'SetValue',
    commit: 'Commit',
    finish: 'Terminate',
    error: 'GetLastError',
    errorText: 'GetErrorString',
  },
};

export class Lms {
  /// `version`: 'scorm12' or 'scorm2004'; `api`: the run-time's object (findApi).
  constructor(version, api) {
    this.version = version;
    this.calls = VERSIONS[version];
    this.api = api;
    this.started = false;
    this.finished = false;
    this.problems = [];
  }

  /// Starts the session (once); false when the LMS refuses.
  initialize() {
    if (this.started || this.finished) return this.started;
    this.started = this.call(this.calls.init, '') === true;
    return this.started;
  }

  get(element) {
    if (!this.live()) return '';
    return String(this.call(this.calls.get, element) ?? '');
  }

  set(element, value) {
    if (!this.live()) return false;
    return this.call(this.calls.set, element, String(value)) === true;
  }

  commit() {
    if (!this.live()) return false;
    return this.call(this.calls.commit, '') === true;
  }

  /// Ends the session: exactly once; no call reaches the LMS after it.
  finish() {
    if (!this.live()) return false;
    this.finished = true;
    return this.call(this.calls.finish, '') === true;
  }

  live() {
    return this.started && !this.finished;
  }

  /// Calls the run-time; SCORM answers "true"/"false" as strings (1.2) or booleans.
  call(method, ...args) {
    let answer;
    try {
      answer = this.api[method](...args);
    } catch (error) {
      this.problems.push(`${method} threw: ${error.message}`);
      return false;
    }
    if (method === this.calls.get) return answer;
    const ok = answer === true || answer === 'true';
    if (!ok) {
      let code = '';
      try {
        code = String(this.api[this.calls.error]());
        code = `${code} ${this.api[this.calls.errorText](code)}`;
      } catch {
        // The error itself could not be read.
      }
      this.problems.push(`${method}(${args.join(', ')}) failed: ${code}`.trim());
    }
    return ok;
  }
}

/// Seconds as SCORM 1.2's CMITimespan (HHHH:MM:SS.SS) or 2004's ISO 8601 duration (PT1H2M3.4S).
export function sessionTime(version, seconds) {
  const whole = Math.max(0, seconds);
  const h = Math.floor(whole / 3600);
  const m = Math.floor((whole % 3600) / 60);
  const s = whole - h * 3600 - m * 60;
  if (version === 'scorm2004') return `PT${h}H${m}M${s.toFixed(2)}S`;
  const pad = (n, width) => String(n).padStart(width, '0');
  return `${pad(h, 4)}:${pad(m, 2)}:${s.toFixed(2).padStart(5, '0')}`;
}
