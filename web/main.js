// Starts the lab (app.js, from wasm-bindgen) and shows what happened if it stops.
//
// A panic in the lab's Rust code cannot be recovered from inside WebAssembly: the module is
// dead afterwards. The lab's panic hook calls bvhlabPanicked(message, storageKey) first; the
// overlay then says what happened and offers a reload, which restores the state the lab saved
// in this browser (it saves every half second while the student works), a download of that
// saved state as a scene file, and a fresh start from the page's own scene.

const status = document.getElementById('status');
const crash = document.getElementById('crash');

globalThis.bvhlabPanicked = (message, storageKey) => {
  document.getElementById('crash-message').textContent = message;
  let saved = null;
  try {
    saved = storageKey ? localStorage.getItem(storageKey) : null;
  } catch {
    // No storage in this frame (sandboxed without allow-same-origin): nothing was saved.
  }
  const download = document.getElementById('crash-download');
  download.hidden = saved == null;
  download.onclick = () => {
    const url = URL.createObjectURL(new Blob([saved], { type: 'application/json' }));
    const a = document.createElement('a');
    a.href = url;
    a.download = 'bvh-lab-saved-scene.json';
    a.click();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  };
  crash.hidden = false;
  document.body.dataset.crashed = 'true';
};

document.getElementById('crash-reload').onclick = () => location.reload();
document.getElementById('crash-fresh').onclick = () => {
  const address = new URL(location.href);
  address.searchParams.set('fresh', '1');
  address.hash = '';
  location.replace(address);
};

// web/loader.js (a classic script that runs first) explains a start that fails or hangs.
const loader = globalThis.bvhlabLoader;
try {
  const app = await import('./app.js');
  await app.default();
  // The lab starts its renderer after this; the loading line goes with its first report, and
  // stays to show why if the renderer cannot start (web.rs writes the reason into it).
  const report = document.getElementById('lab-status');
  const started = () => (loader ? loader.started() : status.remove());
  if (report.hasAttribute('data-report')) {
    started();
  } else {
    const watch = new MutationObserver(() => {
      watch.disconnect();
      started();
    });
    watch.observe(report, { attributes: true, attributeFilter: ['data-report'] });
  }
} catch (error) {
  if (loader) {
    loader.failed(error);
  } else {
    status.textContent = `The lab could not start: ${error.message}.`;
  }
}
