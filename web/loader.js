// The lab page's first script: a classic script, not a module, so that it runs where the lab's
// module scripts cannot, and says why the lab did not start instead of "Loading bvh-lab…" for
// ever. It watches for:
//
// - a page opened from disk (file://): browsers run no module scripts and fetch no WebAssembly
//   there, so it says at once how to serve the folder;
// - a browser without WebAssembly (turned off by a policy or a "strict" security mode);
// - a script that fails to load (missing, sent with a wrong MIME type, or refused by CORS in a
//   frame sandboxed without allow-same-origin): it asks the server for the file to say which;
// - a start that takes long: after STILL_LOADING_S it says the lab is still loading and what
//   may be wrong (the page stays usable if the lab starts later).
//
// main.js calls bvhlabLoader.failed(error) when starting the lab throws (the same diagnosis of
// its files), and bvhlabLoader.started() once the lab reports. Every failure message starts
// with "The lab could not start:" (the browser tests look for it).
(function () {
  'use strict';

  var STILL_LOADING_S = 20;
  var FAILED = 'The lab could not start: ';
  var done = false;
  // The single-file page (web/offline.mjs) carries its code inside and runs from disk.
  var offline = document.documentElement.hasAttribute('data-offline');
  // The lab's files, as the page names them (relative: the page may live in any folder).
  var FILES = ['main.js', 'app.js', 'app_bg.wasm'];

  function status() {
    return document.getElementById('status');
  }

  // Shows `text` in the loading line; `failed` marks it as final.
  function say(text, failed) {
    var line = status();
    // The lab itself may have said why it stopped (web.rs writes into the same line).
    if (!line || done || line.textContent.indexOf(FAILED) === 0) return;
    line.textContent = text;
    line.setAttribute('data-state', failed ? 'failed' : 'slow');
    if (failed) done = true;
  }

  function servedHint() {
    return 'run "bash web/serve.sh" in the bvh-lab repository, or any static web server in ' +
      'this folder (for example "python3 -m http.server 8000", then open ' +
      'http://localhost:8000/index.html), or open bvh-lab-offline.html from this folder, ' +
      'the lab in one file that runs from disk';
  }

  function sandboxed() {
    // A frame sandboxed without allow-same-origin has an opaque origin, "null".
    return window.origin === 'null';
  }

  var sandboxText = 'it runs in a frame sandboxed without allow-same-origin, where the browser ' +
    'loads the lab\'s scripts and WebAssembly only if their server allows any origin: the ' +
    'server must send "Access-Control-Allow-Origin: *" with the lab\'s .js and .wasm files ' +
    '(web/server.mjs does), or the frame needs sandbox="allow-scripts allow-same-origin".';

  // What is wrong with `name` as the server sends it, or null when nothing is.
  function check(name) {
    var address = new URL(name, document.baseURI).href;
    return fetch(address, { cache: 'no-store' }).then(function (response) {
      if (!response.ok) {
        return name + ' could not be downloaded (HTTP ' + response.status + ' ' +
          response.statusText + ' for ' + address + '): copy the whole built folder (dist/) ' +
          'to the server, not only index.html.';
      }
      var type = (response.headers.get('Content-Type') || '').toLowerCase();
      if (/\.js$/.test(name) && !/javascript|ecmascript/.test(type)) {
        return 'the server sends ' + name + ' as "' + (type || 'no type') + '", and browsers ' +
          'run module scripts only when they are sent as JavaScript ' +
          '("Content-Type: text/javascript"): set that type for .js files in the server.';
      }
      return null;
    }, function () {
      return sandboxed() ? sandboxText : name + ' could not be downloaded from ' + address +
        ' (the network or the server refused it).';
    });
  }

  // Finds the first of the lab's files the server does not send right; says it, or `fallback`.
  function diagnose(fallback) {
    if (offline) {
      say(FAILED + fallback, true);
      return;
    }
    var found = null;
    var chain = Promise.resolve();
    FILES.forEach(function (name) {
      chain = chain.then(function () {
        return found ? null : check(name).then(function (problem) { found = problem; });
      });
    });
    chain.then(function () {
      say(FAILED + (found || fallback), true);
    });
  }

  window.bvhlabLoader = {
    // Starting the lab threw `error` (main.js): find out why.
    failed: function (error) {
      var text = String(error && error.message ? error.message : error);
      diagnose(text.replace(/\.?$/, '.') + ' Open the browser\'s console (F12) for details.');
    },
    // The lab runs: the loading line goes.
    started: function () {
      done = true;
      var line = status();
      if (line) line.remove();
    },
  };

  if (location.protocol === 'file:' && !offline) {
    say(FAILED + 'this page was opened as a file (file://), and browsers run the lab\'s code ' +
      'only from a web server: it must be served over http(s). To do so, ' + servedHint() + '.',
      true);
    return;
  }
  if (typeof WebAssembly !== 'object' || typeof WebAssembly.instantiate !== 'function') {
    say(FAILED + 'this browser runs no WebAssembly (it is missing, or turned off by a policy ' +
      'or a strict security mode), and the lab is WebAssembly. Use a current Firefox, ' +
      'Chrome, Edge or Safari with WebAssembly allowed.', true);
    return;
  }

  // A script of the page that fails to load (error events do not bubble, but are captured).
  window.addEventListener('error', function (event) {
    var target = event.target;
    if (target && target.tagName === 'SCRIPT' && target.src) {
      diagnose(target.getAttribute('src') + ' could not be loaded. Open the browser\'s ' +
        'console (F12) for the reason.');
    }
  }, true);

  setTimeout(function () {
    say('bvh-lab is still loading after ' + STILL_LOADING_S + ' s. Its code is one large ' +
      'file (app_bg.wasm, several megabytes), which may take a while on a slow connection. ' +
      'If nothing changes, open the browser\'s console (F12) for the reason, or reload the ' +
      'page.', false);
  }, STILL_LOADING_S * 1000);
})();
