// Editing a large design in the browser (docs/web.md, "Large files"): serves a built site from a
// folder on a loopback port, opens torus-monge in headless Chromium (the browser test's flags),
// drops a generated graph holding a `param.list` of N numbers beside an integer slider that picks
// one of them (`list.item`), then drags the parameter panel's slider in steps and records the
// page's long tasks (over 50 ms) from the press until the worker has answered the last step.
//   node scripts/web-large-edit.mjs SITE_DIR [N]   (needs: npm ci; Debian's chromium)
// With PROFILE=1 the page's main thread is profiled from the drop until the file is open, and the
// functions with the most time of their own are listed.
import { openSite } from "./web-site.mjs";

const dir = process.argv[2];
const count = Number(process.argv[3] ?? 3_000_000);
if (!dir) throw new Error("usage: node scripts/web-large-edit.mjs SITE_DIR [N]");
const { page, close } = await openSite(dir, "?example=torus-monge");
const state = () => page.evaluate(() => window.cnets_test ?? null);
const until = async (what, ok, timeout = 300_000) => {
  const start = Date.now();
  for (;;) {
    const s = await state();
    if (s && ok(s)) return s;
    if (Date.now() - start > timeout) throw new Error(`timed out waiting for ${what}`);
    await page.waitForTimeout(100);
  }
};
await until("the first picture", (s) => s.first_picture_ms !== null && !s.busy);
await page.evaluate(() => {
  window.cnets_long_tasks = [];
  new PerformanceObserver((list) => {
    for (const e of list.getEntries()) window.cnets_long_tasks.push([e.startTime, e.duration]);
  }).observe({ type: "longtask", buffered: false });
});
const s0 = await state();
const [x0, y0, x1, y1] = s0.canvas;
const cdp = process.env.PROFILE ? await page.context().newCDPSession(page) : null;
if (cdp) {
  await cdp.send("Profiler.enable");
  await cdp.send("Profiler.setSamplingInterval", { interval: 200 });
  await cdp.send("Profiler.start");
}
const dropped = await page.evaluate(async ([x, y, n]) => {
  const numbers = Array.from({ length: n }, (_, k) => (k * 0.0001 + 0.5).toFixed(6));
  const text = `(\n    version: 1,\n    name: "big list",\n    nodes: {\n` +
    `        "pick": (type: "param.integer", position: (0.0, 0.0), inputs: {"value": 0, "min": 0, "max": 1000}),\n` +
    `        "numbers": (type: "param.list", position: (0.0, 160.0), inputs: {"values": [${numbers.join(", ")}], "item_type": "number"}),\n` +
    `        "item": (type: "list.item", position: (400.0, 80.0)),\n    },\n` +
    `    edges: [\n        "numbers.values -> item.list",\n        "pick.value -> item.index",\n    ],\n)\n`;
  const transfer = new DataTransfer();
  transfer.items.add(new File([text], "big.ron"));
  const at = performance.now();
  document.getElementById("cnets").dispatchEvent(new DragEvent("drop",
    { dataTransfer: transfer, bubbles: true, cancelable: true, clientX: x, clientY: y }));
  return { bytes: text.length, at };
}, [(x0 + x1) / 2, (y0 + y1) / 2, count]);
const opened = await until("the large file opened and evaluated", (t) => t.title.startsWith("big.ron") &&
  t.large_open && t.large_open.open_ms !== null && !t.busy && t.worker_answers > s0.worker_answers);
const openedAt = await page.evaluate(() => performance.now());
if (cdp) {
  await page.waitForTimeout(1500);
  const { profile } = await cdp.send("Profiler.stop");
  const self = new Map();
  const byId = new Map(profile.nodes.map((n) => [n.id, n]));
  const dt = profile.timeDeltas;
  profile.samples.forEach((id, k) => {
    const f = byId.get(id).callFrame;
    const name = `${f.functionName || "(anonymous)"} ${f.url.split("/").pop()}`;
    self.set(name, (self.get(name) ?? 0) + (dt[k] ?? 0) / 1000);
  });
  const top = [...self.entries()].sort((a, b) => b[1] - a[1]).slice(0, 25);
  for (const [name, ms] of top) console.log(`${ms.toFixed(0).padStart(7)} ms  ${name}`);
  // The callers (four levels up) of the wasm functions with the most time of their own.
  const parent = new Map();
  for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
  const short = (f) => (f.functionName || "(anonymous)").replace(/::h[0-9a-f]{16}$/, "").slice(-70);
  const chains = new Map();
  profile.samples.forEach((id, k) => {
    const frames = [];
    for (let at = id; at !== undefined && frames.length < 5; at = parent.get(at)) frames.push(short(byId.get(at).callFrame));
    if (!byId.get(id).callFrame.url.endsWith(".wasm")) return;
    const key = frames.join(" < ");
    chains.set(key, (chains.get(key) ?? 0) + (dt[k] ?? 0) / 1000);
  });
  console.log("callers:");
  for (const [chain, ms] of [...chains.entries()].sort((a, b) => b[1] - a[1]).slice(0, 12)) {
    console.log(`${ms.toFixed(0).padStart(7)} ms  ${chain}`);
  }
}
const openTasks = await page.evaluate(() => window.cnets_long_tasks.splice(0));
await page.waitForTimeout(1000);
const slider = (opened.panel ?? []).find((p) => p.id === "pick");
if (!slider) throw new Error(`no slider in the panel: ${JSON.stringify(opened.panel)}`);
const [sx0, sy0, sx1, sy1] = slider.rect;
const y = (sy0 + sy1) / 2;
const before = await state();
await page.evaluate(() => { window.cnets_long_tasks = []; window.cnets_press_at = performance.now(); });
await page.mouse.move(sx0 + 4, y);
await page.mouse.down();
const steps = 5;
for (let k = 1; k <= steps; k++) {
  await page.mouse.move(sx0 + 4 + ((sx1 - sx0 - 8) * k) / (steps * 4), y);
  await page.waitForTimeout(200);
}
await page.mouse.up();
const after = await until("the last step answered", (t) => !t.busy && t.worker_answers > before.worker_answers &&
  t.panel.find((p) => p.id === "pick")?.value !== 0, 120_000);
await page.waitForTimeout(1500);
const edit = await page.evaluate(() => ({ tasks: window.cnets_long_tasks, at: window.cnets_press_at }));
const last = await state();
const sum = (tasks) => Math.round(tasks.reduce((a, [, d]) => a + d, 0));
const max = (tasks) => Math.round(Math.max(0, ...tasks.map(([, d]) => d)));
console.log(JSON.stringify({
  numbers: count,
  bytes: dropped.bytes,
  drop_to_evaluated_ms: Math.round(openedAt - dropped.at),
  open_parse_ms: Math.round(opened.large_open.open_ms),
  open_page_ms: opened.large_open.page_ms === undefined ? null : Math.round(opened.large_open.page_ms),
  open_decode_ms: Math.round(opened.worker_read_decode_ms ?? 0),
  open_frames_while_reading: opened.large_open.frames_while_reading ?? null,
  open_long_tasks: { count: openTasks.length, max_ms: max(openTasks), total_ms: sum(openTasks),
    at_ms_after_drop: openTasks.map(([t, d]) => [Math.round(t - dropped.at), Math.round(d)]) },
  edit: {
    steps,
    value: last.panel.find((p) => p.id === "pick")?.value,
    requests: last.worker_sent - before.worker_sent,
    long_tasks: { count: edit.tasks.length, max_ms: max(edit.tasks), total_ms: sum(edit.tasks) },
    last_request_prepared_ms: last.worker_send_ms ?? null,
    literals_sent_in_all: last.worker_literals_sent ?? null,
  },
  failed: last.failed,
  message: last.message,
}, null, 1));
await close();
