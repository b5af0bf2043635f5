// The browser test of cnets in the browser (docs/web.md), run by scripts/test-web.sh:
//   node tests/web/browser.test.mjs BASE_URL OUT_DIR
// Drives Debian's Chromium headless (software WebGL2: ANGLE + SwiftShader) with playwright-core.
// egui draws everything on one <canvas>: the test moves the mouse at coordinates and reads what the
// page reports in `window.cnets_test` (frames, pictures drawn, where the 3D view and the first
// slider are). Fails on any console error, page error or panic. Screenshots go to OUT_DIR.
import { chromium } from "playwright-core";
import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import zlib from "node:zlib";

const base = process.argv[2] ?? "http://127.0.0.1:8000";
const out = process.argv[3] ?? "target/web-test";
fs.mkdirSync(out, { recursive: true });
const figures = {};

const userData = fs.mkdtempSync(path.join(os.tmpdir(), "cnets-chromium-"));
const context = await chromium.launchPersistentContext(userData, {
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  headless: true,
  viewport: { width: 1400, height: 860 },
  args: [
    "--headless", "--no-sandbox", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
    // A software GPU process stalled by a busy machine is not a hung one.
    "--disable-gpu-watchdog",
  ],
});
// Playwright's own waits (navigation, screenshots) get the patience of the test's waits: a busy
// machine's software rendering can take more than its default 30 s.
context.setDefaultTimeout(180_000);
context.setDefaultNavigationTimeout(180_000);
// The page keeps its test state (window.cnets_test) only when asked, before its module starts.
const testing = () => { window.cnets_testing = true; };
await context.addInitScript(testing);
// What the first visit transfers (the browser's cache is empty: a fresh profile): every response's
// bytes on the wire (headers and the body as sent, compressed or not), until the first picture.
const transfers = [];
let counting = true;
context.on("requestfinished", async (request) => {
  if (!counting) return;
  const sizes = await request.sizes().catch(() => null);
  const response = await request.response().catch(() => null);
  if (!sizes) return;
  transfers.push({
    url: request.url(),
    bytes: sizes.responseBodySize + sizes.responseHeadersSize,
    encoding: response?.headers()["content-encoding"] ?? "",
  });
});
const problems = [];
function watch(page) {
  page.on("console", (m) => {
    // (The browser asks for /favicon.ico on the plain page that clears the storage.)
    const from = m.location()?.url ?? "";
    if (m.type() === "error" && !from.endsWith("/favicon.ico")) {
      problems.push(`console error: ${m.text()} (${from})`);
    }
  });
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  page.on("crash", () => problems.push("the page crashed"));
  return page;
}
function noProblems(when) {
  assert.deepEqual(problems, [], `${when}: ${problems.join("\n")}`);
}

const state = (page) => page.evaluate(() => window.cnets_test ?? null);

/** Waits until `ok(state)` holds; returns the state. */
async function until(page, what, ok, timeout = 180_000) {
  const start = Date.now();
  for (;;) {
    const s = await state(page);
    if (s && ok(s)) return s;
    noProblems(`waiting for ${what}`);
    if (Date.now() - start > timeout) throw new Error(`timed out waiting for ${what}: ${JSON.stringify(s)}`);
    await page.waitForTimeout(100);
  }
}

/** Waits for the view to settle: no evaluation in the worker or picture pending, and the picture
 *  count unchanged for a while (an evaluation may take longer than that while). */
async function settled(page) {
  let last = -1;
  let still = 0;
  for (let k = 0; k < 600 && still < 8; k++) {
    const s = await state(page);
    if (s && !s.busy && !s.evaluating && s.pictures === last) still++;
    else still = 0;
    last = s?.pictures ?? -1;
    await page.waitForTimeout(100);
  }
  return state(page);
}

/** RGBA pixels of a PNG screenshot region, decoded by the page's own canvas (no npm PNG reader)
 *  and handed back as base64 of the raw bytes (a JSON array of millions of numbers took seconds). */
async function pixels(page, png, rect) {
  const b64 = await page.evaluate(async ({ b64, rect }) => {
    const img = new Image();
    img.src = "data:image/png;base64," + b64;
    await img.decode();
    const c = document.createElement("canvas");
    const [x0, y0, x1, y1] = rect.map(Math.round);
    c.width = x1 - x0;
    c.height = y1 - y0;
    const g = c.getContext("2d");
    g.drawImage(img, -x0, -y0);
    const bytes = g.getImageData(0, 0, c.width, c.height).data;
    const url = await new Promise((resolve) => {
      const reader = new FileReader();
      reader.onload = () => resolve(reader.result);
      reader.readAsDataURL(new Blob([bytes]));
    });
    return url.slice(url.indexOf(",") + 1);
  }, { b64: png.toString("base64"), rect });
  return new Uint8Array(Buffer.from(b64, "base64"));
}

/** How much of the region differs from its most common colour, and how many colours it has. */
function coverage(px) {
  const counts = new Map();
  for (let i = 0; i < px.length; i += 4) {
    const key = (px[i] << 16) | (px[i + 1] << 8) | px[i + 2];
    counts.set(key, (counts.get(key) ?? 0) + 1);
  }
  const n = px.length / 4;
  const background = Math.max(...counts.values());
  return { covered: 1 - background / n, colours: counts.size };
}

/** The share of pixels that differ (by more than a little) between two equally sized regions. */
function difference(a, b) {
  let differ = 0;
  for (let i = 0; i < a.length; i += 4) {
    const d = Math.abs(a[i] - b[i]) + Math.abs(a[i + 1] - b[i + 1]) + Math.abs(a[i + 2] - b[i + 2]);
    if (d > 24) differ++;
  }
  return differ / (a.length / 4);
}

async function shot(page, name, view) {
  const png = await page.screenshot({ path: path.join(out, `${name}.png`) });
  const px = await pixels(page, png, view);
  return { png, px, ...coverage(px) };
}

/** Opens `url` in a new page; `keep` keeps what earlier pages autosaved (else it is cleared). */
async function open(url, keep = false) {
  const page = watch(await context.newPage());
  if (!keep) {
    await page.goto(`${base}/cnets_web.js`);
    await page.evaluate(() => localStorage.clear());
  }
  const t0 = Date.now();
  await page.goto(url);
  const s = await until(page, `the first picture of ${url}`, (s) => s.first_picture_ms !== null && s.vertices > 0);
  const wall = Date.now() - t0;
  return { page, first: s.first_picture_ms, wall, state: await settled(page) };
}

// 1. ?example=torus-monge: the first picture, not blank.
const torus = await open(`${base}/index.html?example=torus-monge`);
figures.first_picture_ms = Math.round(torus.first);
const view = torus.state.view;
assert.ok(view[2] - view[0] > 100 && view[3] - view[1] > 100, `the 3D view is laid out: ${view}`);
const t1 = await shot(torus.page, "1-torus-monge", view);
console.log(`torus-monge: first picture after ${figures.first_picture_ms} ms (page load included), ` +
  `${(t1.covered * 100).toFixed(1)} % of the 3D view drawn, ${t1.colours} colours`);
assert.ok(t1.covered > 0.02 && t1.colours > 16, "the 3D view is not blank");
// The first visit: compressed delivery (scripts/serve.py sends the .br copies), under 5 MB, and the
// module's bytes counted by the loader's bar while it was compiled.
counting = false;
const firstVisit = transfers.reduce((sum, t) => sum + t.bytes, 0);
const wasm = transfers.find((t) => t.url.endsWith("/cnets_web_bg.wasm"));
figures.first_visit = {
  bytes: firstVisit,
  requests: transfers.length,
  wasm_bytes: wasm?.bytes ?? null,
  wasm_encoding: wasm?.encoding ?? null,
  loader_counted_bytes: await torus.page.evaluate(() => window.cnets_loaded_bytes ?? null),
};
console.log(`first visit: ${(firstVisit / 1e6).toFixed(2)} MB in ${transfers.length} responses ` +
  `(the module ${((wasm?.bytes ?? 0) / 1e6).toFixed(2)} MB, ${wasm?.encoding || "uncompressed"})`);
assert.ok(wasm, `the module was fetched: ${JSON.stringify(transfers.map((t) => t.url))}`);
assert.ok(["br", "gzip"].includes(wasm.encoding), `the module arrives compressed: ${wasm.encoding}`);
assert.ok(firstVisit < 5e6, `the first visit transfers under 5 MB: ${firstVisit} bytes`);
assert.ok(figures.first_visit.loader_counted_bytes > 10e6,
  `the loader counted the module's bytes: ${figures.first_visit.loader_counted_bytes}`);

// 2. Drag the first slider: its value and the picture change.
/** The slider to drag: the first on the canvas, else the parameter panel's first number slider
 *  (else its first integer editor); its rail, node and how to read its value from the state. */
// The figures drawn over the 3D view (statistics, legend, picker, axes, size, the grid's name):
// each inside the view, no two intersecting (the page's test state, CSS pixels).
function overlaysApart(s, what) {
  const over = s.overlays ?? [];
  assert.ok(over.length >= 2, `${what}: the figures over the 3D view are reported: ${JSON.stringify(over)}`);
  const [vx0, vy0, vx1, vy1] = s.view;
  for (const [k, [a, ra]] of over.entries()) {
    assert.ok(ra[0] >= vx0 - 1 && ra[1] >= vy0 - 1 && ra[2] <= vx1 + 1 && ra[3] <= vy1 + 1,
      `${what}: ${a} ${ra} lies in the view ${s.view}`);
    for (const [b, rb] of over.slice(k + 1)) {
      const apart = ra[2] <= rb[0] || rb[2] <= ra[0] || ra[3] <= rb[1] || rb[3] <= ra[1];
      assert.ok(apart, `${what}: ${a} ${ra} overlaps ${b} ${rb}`);
    }
  }
  return over.map(([name]) => name);
}
function pickSlider(s, preferPanel = false) {
  const docked = (s.panel ?? []).some((p) => p.type === "param.number" || p.type === "param.integer");
  if (s.slider && !(preferPanel && docked)) {
    return { rail: s.slider, node: s.slider_node, valueOf: (t) => t.slider_value };
  }
  const e = (s.panel ?? []).find((p) => p.type === "param.number") ??
    (s.panel ?? []).find((p) => p.type === "param.integer");
  assert.ok(e, `a slider on the canvas or in the parameter panel: ${JSON.stringify(s.panel)}`);
  return { rail: e.rect, node: e.id, valueOf: (t) => t.panel.find((p) => p.id === e.id)?.value };
}
async function drag(page, back = false) {
  const s = await state(page);
  const slider = pickSlider(s);
  const [x0, y0, x1, y1] = slider.rail;
  const y = (y0 + y1) / 2;
  let from = x0 + (x1 - x0) * 0.25;
  let to = x0 + (x1 - x0) * 0.85;
  if (back) [from, to] = [to, from];
  const before = slider.valueOf(s);
  await page.mouse.move(from, y);
  await page.mouse.down();
  for (let k = 1; k <= 12; k++) {
    await page.mouse.move(from + ((to - from) * k) / 12, y);
    await page.waitForTimeout(30);
  }
  await page.mouse.up();
  const after = await until(page, "the slider's new value", (t) => slider.valueOf(t) !== before, 20_000);
  return { node: slider.node, before, after: slider.valueOf(after) };
}
const moved = await drag(torus.page);
console.log(`dragged ${moved.node}: ${moved.before} → ${moved.after}`);
await settled(torus.page);
const t2 = await shot(torus.page, "2-torus-monge-dragged", view);
const changed = difference(t1.px, t2.px);
console.log(`the drag changed ${(changed * 100).toFixed(1)} % of the 3D view`);
assert.ok(changed > 0.005, "the picture changed after the drag");
noProblems("torus-monge");

// 3. Autosave: the dragged (unsaved) torus is in the page's local storage. The restore offer
//    belongs to the document it was saved from: another example opens without it (the torus's
//    work kept aside, listed in File), and the torus's own page offers to restore it, as the
//    desktop editor does after a crash.
const autosaved = await torus.page.evaluate(() => localStorage.getItem("cnets.recovery.ron") ?? "");
assert.ok(autosaved.includes("torus"), "the edited graph is autosaved in local storage");
await torus.page.close();
const elsewhere = await open(`${base}/index.html?example=facade`, true);
assert.ok(!elsewhere.state.restore_offered, "no other document's restore offer over the facade");
assert.match(elsewhere.state.document, /facade/, `the facade is open: ${elsewhere.state.document}`);
assert.match(elsewhere.state.kept_recovery ?? "", /torus-monge/,
  `the torus's work is kept and listed: ${elsewhere.state.kept_recovery}`);
figures.restore_elsewhere = { document: elsewhere.state.document, kept: elsewhere.state.kept_recovery };
await elsewhere.page.screenshot({ path: path.join(out, "3a-no-offer-over-facade.png") });
// File ▸ Restore kept work (through the test hook) opens it.
await elsewhere.page.evaluate(() => { window.cnets_request = "restore_kept"; });
let restoredKept = null;
for (let k = 0; k < 100 && !restoredKept; k++) {
  await elsewhere.page.mouse.move(700 + (k % 2), 850);
  await elsewhere.page.waitForTimeout(100);
  const s = await state(elsewhere.page);
  if (/torus-monge/.test(s?.document ?? "") && s.kept_recovery === null) restoredKept = s;
}
assert.ok(restoredKept, `File ▸ Restore kept work opens the torus: ${JSON.stringify(await state(elsewhere.page))}`);
// Autosaved again as the torus's own recovery (the next page offers it).
let resaved = "";
for (let k = 0; k < 100 && !resaved.includes("torus"); k++) {
  await elsewhere.page.mouse.move(700 + (k % 2), 850);
  await elsewhere.page.waitForTimeout(100);
  resaved = await elsewhere.page.evaluate(() => localStorage.getItem("cnets.recovery.ron") ?? "");
}
assert.ok(resaved.includes("torus"), "the restored work is autosaved as its own recovery");
await elsewhere.page.close();
const offer = await open(`${base}/index.html?example=torus-monge`, true);
assert.ok(offer.state.restore_offered, "the torus's own page offers to restore it");
await offer.page.screenshot({ path: path.join(out, "3b-restore-offer.png") });
await offer.page.close();
noProblems("autosave");

// 3. ?example=facade differs.
const facade = await open(`${base}/index.html?example=facade`);
const f1 = await shot(facade.page, "3-facade", view);
const vsTorus = difference(t1.px, f1.px);
console.log(`facade: ${(f1.covered * 100).toFixed(1)} % drawn, differs from torus-monge in ${(vsTorus * 100).toFixed(1)} %`);
assert.ok(f1.covered > 0.02, "the facade is drawn");
assert.ok(vsTorus > 0.02, "the facade differs from the torus");
noProblems("facade");

// 4. Share link round trip: File ▸ Copy link (the same action through the test hook) puts
//    #graph=… in the address bar; it decodes here (Node's own inflate) to the facade graph, and
//    opening it in a new page draws the same picture.
await facade.page.evaluate(() => { window.cnets_request = "copy_link"; });
let link = "";
for (let k = 0; k < 100 && !link.includes("#graph="); k++) {
  // (egui paints on input: a mouse move over the status bar gives it the frame.)
  await facade.page.mouse.move(700 + (k % 2), 850);
  await facade.page.waitForTimeout(100);
  link = facade.page.url();
}
assert.ok(link.includes("#graph="), `a share link in the address bar: ${link}`);
figures.facade_link_chars = link.length;
const ron = zlib.inflateRawSync(Buffer.from(link.split("#graph=")[1], "base64url")).toString("utf8");
assert.ok(ron.includes("facade") || ron.includes("cnets."), "the link holds the graph");
const shared = await open(link);
const s1 = await shot(shared.page, "4-facade-from-link", view);
const vsFacade = difference(f1.px, s1.px);
console.log(`the link (${link.length} characters) opens a picture that differs from the facade in ${(vsFacade * 100).toFixed(2)} %`);
assert.ok(vsFacade < 0.01, "the link opens the same graph");
assert.match(shared.state.message, /link/, "the page says it opened a link");
assert.equal(shared.state.title, "shared design", "a link's graph is titled 'shared design'");
assert.equal(shared.state.tab_title, "shared design — cnets", "the tab's title follows");
const said = (await state(facade.page)).message;
assert.ok(said.includes(`(${link.length} characters)`), `the link's length is said right: "${said}" vs ${link.length}`);
noProblems("share link");
await facade.page.close();
await shared.page.close();

// 5. Change-to-picture at 100 × 100: torus-monge with 100 columns and 100 rows, opened from a link
//    this test makes (Node's deflate), then slider drags measured by the editor (edit → the frame
//    that hands the scene to WebGL).
const torusRon = fs.readFileSync(new URL("../../graphs/torus-monge.ron", import.meta.url), "utf8");
/** The graph text with the first `"field": N` (default `"value"`) after `"node": (` set to
 *  `value`. */
function setValue(text, node, value, field = "value") {
  const at = text.indexOf(`"${node}": (`);
  assert.ok(at >= 0, `node ${node} in torus-monge.ron`);
  const v = text.indexOf(`"${field}": `, at) + `"${field}": `.length;
  const end = text.indexOf(",", v);
  return text.slice(0, v) + value + text.slice(end);
}
const big = setValue(setValue(torusRon, "columns", 100), "rows", 100);
assert.notEqual(big, torusRon, "the grid size was set");
const bigLink = `${base}/index.html#graph=${zlib.deflateRawSync(Buffer.from(big), { level: 9 }).toString("base64url")}`;
const hundred = await open(bigLink);
figures.first_picture_100_ms = Math.round(hundred.first);
const latencies = [];
for (let k = 0; k < 3; k++) {
  const before = (await state(hundred.page)).latencies;
  await drag(hundred.page, k % 2 === 0);
  const s = await until(hundred.page, "a change-to-picture figure", (t) => t.latencies > before, 60_000);
  await settled(hundred.page);
  latencies.push(Math.round((await state(hundred.page)).latency_ms ?? s.latency_ms));
}
await shot(hundred.page, "5-torus-monge-100x100", view);
figures.change_to_picture_100_ms = latencies;
console.log(`100 × 100: ${hundred.state.vertices} vertices, change-to-picture ${latencies.join(", ")} ms`);
noProblems("100 × 100");


// 6. The first visit at 1400 × 860, every gallery graph: the parameter panel docked, the
//    first-visit hint shown, the construction node on the canvas (or the canvas's overview
//    shown), the tab titled after the document. Then the hint is dismissed, and stays so.
const gallery = fs.readdirSync(new URL("../../graphs/", import.meta.url))
  .filter((f) => f.endsWith(".ron"))
  .map((f) => f.slice(0, -4))
  .sort();
assert.ok(gallery.length >= 10, `the gallery: ${gallery}`);
/** Opens `url` on a fresh storage and waits for the first picture (any geometry). */
async function openAny(url, page = null) {
  page = page ?? watch(await context.newPage());
  await page.goto(`${base}/cnets_web.js`);
  await page.evaluate(() => localStorage.clear());
  await page.goto(url);
  // (180 s: ≥ 50× the first picture's 1.6–3.4 s under load, issue 30.)
  await until(page, `the first picture of ${url}`, (s) => s.first_picture_ms !== null || s.load_failure, 180_000);
  return { page, state: await settled(page) };
}
const constructions = (ron) =>
  [...ron.matchAll(/"([^"]+)": \(\s*type: "cnets\.construct(?:_coplanar)?"/g)].map((m) => m[1]);
figures.gallery = {};
for (const name of gallery) {
  const ron = fs.readFileSync(new URL(`../../graphs/${name}.ron`, import.meta.url), "utf8");
  const { page, state: s } = await openAny(`${base}/index.html?example=${name}`);
  await page.screenshot({ path: path.join(out, `6-first-visit-${name}.png`) });
  assert.ok(s.parameters && s.parameters[2] - s.parameters[0] > 150, `${name}: the parameter panel is docked: ${s.parameters}`);
  assert.ok(s.welcome, `${name}: the first-visit hint is shown`);
  const [vx0, vy0, vx1, vy1] = s.view;
  const [wx0, wy0, wx1, wy1] = s.welcome;
  assert.ok(wx0 >= vx0 && wx1 <= vx1 && wy0 >= vy0 && wy1 <= vy1, `${name}: the hint sits in the 3D view: ${s.welcome} in ${s.view}`);
  const hiddenConstructions = constructions(ron).filter((id) => s.hidden.includes(id));
  assert.ok(hiddenConstructions.length === 0 || s.overview,
    `${name}: construction nodes ${hiddenConstructions} are off the canvas and there is no overview`);
  assert.equal(s.title, `untitled (copy of example ${name}.ron)`);
  assert.equal(s.tab_title, `${s.title} — cnets`, `${name}: the tab's title`);
  for (const failed of s.failed) {
    assert.ok(failed.in_view || s.view_errors.some((e) => e.startsWith(`${failed.id}:`)),
      `${name}: the error of ${failed.id} is neither on the canvas nor in the 3D view`);
  }
  figures.gallery[name] = { hidden: s.hidden.length, overview: s.overview, failed: s.failed.length };
  console.log(`${name}: ${s.hidden.length} nodes off the canvas${s.overview ? " (overview shown)" : ""}, ` +
    `constructions ${constructions(ron).join(", ") || "none"} in view, ${s.failed.length} failed`);
  if (name !== gallery[gallery.length - 1]) await page.close();
  else {
    // Escape dismisses the hint (after a click in the 3D view gives the page the keyboard); it
    // stays dismissed on the next visit.
    await page.mouse.click((vx0 + vx1) / 2, (vy0 + vy1) / 2);
    await page.keyboard.press("Escape");
    await until(page, "the hint to go", (t) => t.welcome === null, 10_000);
    assert.equal(await page.evaluate(() => localStorage.getItem("cnets.welcomed")), "1");
    await page.reload();
    const again = await until(page, "the page again", (t) => t.first_picture_ms !== null, 180_000);
    assert.equal(again.welcome, null, "the hint is not shown again");
    await page.close();
  }
  noProblems(`first visit of ${name}`);
}

// 7. Input during a drag with the facade open: pointer events are dispatched in the page every
//    16 ms (a 60 Hz mouse) on the first slider; the page's main thread handles them at the
//    mouse's rate while the worker evaluates (issue 29's target is ≥ 30 Hz; the assertion's
//    bound is below, with its margin; an evaluation on the page's thread would hold them back
//    for its whole time). Playwright's own mouse waits for each frame of the software
//    rasterizer, so it cannot be the clock here. The frame rates are reported.
{
  const { page } = await openAny(`${base}/index.html?example=facade`);
  const s = await state(page);
  // The docked parameter panel's slider: it stays where it is (a canvas node's slider can sit
  // partly under the 3D view, and the canvas may still be framed after the first results).
  const slider = pickSlider(s, true);
  const before = await state(page);
  await page.screenshot({ path: path.join(out, "7-facade-before-drag.png") });
  const drag = await page.evaluate(async ([[x0, y0, x1, y1], node]) => {
    const canvas = document.getElementById("cnets");
    const y = (y0 + y1) / 2;
    const raf = [];
    let go = true;
    const tick = (t) => { raf.push(t); if (go) requestAnimationFrame(tick); };
    requestAnimationFrame(tick);
    // (eframe takes presses and releases as pointer events, moves as mouse events.)
    const fire = (type, x, buttons) => {
      const init = { bubbles: true, cancelable: true, composed: true, clientX: x, clientY: y, button: 0, buttons };
      canvas.dispatchEvent(type === "mousemove" ? new MouseEvent(type, init)
        : new PointerEvent(type, { ...init, pointerId: 1, pointerType: "mouse", isPrimary: true }));
    };
    const handled = [];
    const steps = 60;
    // The editor must see the press before the moves, and the last move before the release (on
    // a busy machine a frame of the software rasterizer takes 100 ms or more, and a press, moves
    // and release in one frame are a click, not a drag): it waits for the editor's own frames
    // (its test state: `frames`, and `dragging` once the slider holds the pointer), not for a
    // time or the page's animation frames.
    const editor = () => window.cnets_test ?? {};
    const editorFrames = async (n, ok = () => true) => {
      const start = editor().frames ?? 0;
      for (let k = 0; k < 600; k++) {
        if ((editor().frames ?? 0) >= start + n && ok(editor())) return true;
        await new Promise((r) => setTimeout(r, 10));
      }
      return false;
    };
    fire("mousemove", x0 + 4, 0);
    await editorFrames(1);
    fire("pointerdown", x0 + 4, 1);
    const held = await editorFrames(1, (t) => t.dragging);
    const t0 = performance.now();
    const pictures0 = editor().pictures ?? 0;
    // The slider's values seen during the drag (each a change the worker is asked to draw).
    const valueNow = () => (editor().panel ?? []).find((p) => p.id === node)?.value;
    const values = [valueNow()];
    for (let k = 1; k <= steps; k++) {
      await new Promise((r) => setTimeout(r, 16));
      fire("mousemove", x0 + 4 + ((x1 - x0 - 8) * k) / steps, 1);
      handled.push(performance.now());
      if (valueNow() !== values[values.length - 1]) values.push(valueNow());
    }
    // The last change's picture: a moment more with the pointer still held.
    await editorFrames(3);
    const t1 = performance.now();
    const pictures1 = editor().pictures ?? 0;
    await editorFrames(1);
    fire("pointerup", x1 - 4, 0);
    go = false;
    let gap = 0;
    for (let k = 1; k < handled.length; k++) gap = Math.max(gap, handled[k] - handled[k - 1]);
    return { seconds: (t1 - t0) / 1000, events: handled.length, gap, held, pictures: pictures1 - pictures0,
      changes: values.length - 1,
      raf: raf.filter((t) => t >= t0 && t <= t1).length };
  }, [slider.rail, slider.node]);
  const after = await settled(page);
  await page.screenshot({ path: path.join(out, "7-facade-dragged.png") });
  const inputHz = drag.events / drag.seconds;
  figures.drag_facade = {
    seconds: +drag.seconds.toFixed(2), input_hz: +inputHz.toFixed(1),
    longest_input_gap_ms: Math.round(drag.gap), held: drag.held, raf_hz: +(drag.raf / drag.seconds).toFixed(1),
    // New pictures of the worker's scenes drawn while the pointer was held, and the slider's
    // changes in that time (it has 7 values).
    pictures_during_drag: drag.pictures, changes_during_drag: drag.changes,
    pictures_hz: +(drag.pictures / drag.seconds).toFixed(1),
    editor_frames: after.frames - before.frames, requests: after.worker_sent - before.worker_sent,
    answers: after.worker_answers - before.worker_answers,
    slider: slider.node, rail: slider.rail.map(Math.round),
    value: [slider.valueOf(before), slider.valueOf(after)],
    change_to_picture_ms: Math.round(after.latency_ms),
  };
  console.log(`facade drag: ${JSON.stringify(figures.drag_facade)}`);
  assert.notEqual(slider.valueOf(after), slider.valueOf(before), "the drag moved the slider");
  assert.ok(after.worker_sent > before.worker_sent, "the drag sent evaluations to the worker");
  // Measured 53–59 Hz under load; an evaluation on the page's thread gave about 4 Hz. The bound is
  // 5× under the measured rate, so a busy machine cannot reach it and that regression still does
  // (issue 30).
  assert.ok(inputHz >= 10, `the page handles pointer input at ≥ 10 Hz during the drag: ${inputHz.toFixed(1)} Hz`);
  // A drag's pictures never wait for the facade's nest (not previewed, seconds in the page): the
  // changes are drawn while the pointer is held. They come about 5 a second (the slider has 7
  // values), so drawing them is the rate asked for (≥ 5 pictures a second) as far as this slider
  // can ask; one change may be overtaken by the next before a frame draws it (the software
  // rasterizer draws about 6 frames a second). Before the worker waited for newer requests, its
  // nest held every later picture back: 1 picture for 6 changes.
  assert.ok(drag.changes >= 4, `the drag changed the slider several times: ${drag.changes}`);
  assert.ok(drag.pictures >= drag.changes - 1,
    `a picture for each change while the pointer is held: ${drag.pictures} pictures, ${drag.changes} changes`);
  noProblems("facade drag");
  await page.close();
}

// 8. A phone (390 × 844): the 3D view on top, the parameters below it, nothing overlapping.
{
  const page = watch(await context.newPage());
  await page.setViewportSize({ width: 390, height: 844 });
  const { state: s } = await openAny(`${base}/index.html?example=facade`, page);
  await page.screenshot({ path: path.join(out, "8-phone-facade.png") });
  assert.ok(s.narrow, "the narrow layout is used");
  const [vx0, vy0, vx1, vy1] = s.view;
  assert.ok(vx1 - vx0 > 300 && vy1 - vy0 > 200 && vx1 <= 390 && vy1 <= 844, `the 3D view is shown: ${s.view}`);
  // The 3D view takes most of the phone's screen (its controls in one row above it).
  const viewShare = (vy1 - vy0) / 844;
  figures.phone_view_share = +viewShare.toFixed(3);
  console.log(`phone: the 3D view is ${(viewShare * 100).toFixed(1)} % of the screen's height`);
  assert.ok(viewShare >= 0.6, `the 3D view covers at least 60 % of the phone's height: ${(viewShare * 100).toFixed(1)} %`);
  figures.phone_overlays = overlaysApart(s, "phone");
  assert.ok(s.parameters, "the parameters are shown");
  const [px0, py0, px1, py1] = s.parameters;
  assert.ok(py0 >= vy1 - 1 && py1 - py0 > 100 && px1 <= 390, `the parameters sit below the view: ${s.parameters} / ${s.view}`);
  noProblems("phone");
  await page.close();
}

// 9. Bad links: a truncated one and a garbage one each say what is wrong in a dialog, with no
//    other graph standing in; the title says so.
{
  const cut = link.slice(0, link.indexOf("#graph=") + 7 + Math.floor((link.length - link.indexOf("#graph=") - 7) / 2));
  for (const [what, url, says] of [
    ["truncated", cut, /truncated/],
    ["garbage", `${base}/index.html#graph=*not*a*link*`, /corrupted/],
  ]) {
    const { page, state: s } = await openAny(url);
    await page.screenshot({ path: path.join(out, `9-${what}-link.png`) });
    assert.match(s.load_failure ?? "", says, `the ${what} link's dialog: ${s.load_failure}`);
    assert.equal(s.title, "shared design (not opened)", `the ${what} link's title`);
    assert.equal(s.tab_title, "shared design (not opened) — cnets");
    assert.equal(s.vertices, 0, "no other graph stands in for the link's");
    // The dialog is whole on the screen and nothing (the first visit's hint) lies over it.
    const [sw, sh] = s.screen;
    assert.ok(s.dialog, `the ${what} link's dialog is drawn`);
    const [dx0, dy0, dx1, dy1] = s.dialog;
    assert.ok(dx0 >= 0 && dy0 >= 0 && dx1 <= sw && dy1 <= sh, `the ${what} link's dialog ${s.dialog} on the screen ${s.screen}`);
    if (s.welcome) {
      const [wx0, wy0, wx1, wy1] = s.welcome;
      assert.ok(wx1 <= dx0 || dx1 <= wx0 || wy1 <= dy0 || dy1 <= wy0, `the hint ${s.welcome} over the dialog ${s.dialog}`);
    }
    noProblems(`${what} link`);
    await page.close();
  }
}

// 10. An oversized construction (100 000 × 100 000): its error is in view.
{
  let huge = torusRon;
  for (const node of ["columns", "rows"]) {
    huge = setValue(setValue(huge, node, 100000, "max"), node, 100000);
  }
  const url = `${base}/index.html#graph=${zlib.deflateRawSync(Buffer.from(huge), { level: 9 }).toString("base64url")}`;
  const { page, state: s0 } = await openAny(url);
  const s = await until(page, "the construction's error", (t) => t.failed.length > 0, 60_000);
  await page.screenshot({ path: path.join(out, "10-oversized.png") });
  for (const failed of s.failed) {
    assert.ok(failed.in_view || s.view_errors.some((e) => e.startsWith(`${failed.id}:`)),
      `the error of ${failed.id} is in view (canvas or 3D view): ${JSON.stringify(s.failed)} ${s.view_errors}`);
  }
  // Scrolled off the canvas, the error moves into the 3D view.
  const [cx0, cy0, cx1, cy1] = s.canvas;
  await page.mouse.move((cx0 + cx1) / 2, (cy0 + cy1) / 2);
  for (let k = 0; k < 30; k++) await page.mouse.wheel(0, -400);
  const off = await until(page, "the error in the 3D view",
    (t) => t.failed.some((f) => !f.in_view) && t.view_errors.length > 0, 20_000).catch(() => null);
  await page.screenshot({ path: path.join(out, "10-oversized-scrolled.png") });
  figures.oversized = { failed: s.failed.map((f) => f.message.slice(0, 120)), error_in_3d_view_when_scrolled: off !== null };
  console.log(`oversized: ${JSON.stringify(figures.oversized)}`);
  noProblems("oversized construction");
  await page.close();
}

// 11. A large graph dropped on the page (a `param.list` of 1.2 million numbers, about 14 MB): the
//     evaluation worker reads it while the page keeps drawing, under a notice (held up here by a
//     test flag, before the file is handed over, to picture it). Then a slider of it is dragged:
//     the list, which the worker kept, is not sent to it again.
{
  const { page, state: s0 } = await openAny(`${base}/index.html?example=torus-monge`);
  const [x0, y0, x1, y1] = s0.canvas;
  const centre = [(x0 + x1) / 2, (y0 + y1) / 2];
  const before = await page.screenshot();
  const dropped = await page.evaluate(async ([x, y]) => {
    const numbers = Array.from({ length: 1_200_000 }, (_, k) => (k * 0.0001 + 0.5).toFixed(6));
    const text = `(\n    version: 1,\n    name: "big list",\n    nodes: {\n        "numbers": (\n` +
      `            type: "param.list",\n            position: (0.0, 0.0),\n            inputs: {\n` +
      `                "values": [${numbers.join(", ")}],\n                "item_type": "number",\n` +
      `            },\n        ),\n` +
      `        "pick": (type: "param.integer", position: (0.0, -160.0), inputs: {"value": 0, "min": 0, "max": 1000}),\n` +
      `        "item": (type: "list.item", position: (400.0, -80.0)),\n    },\n` +
      `    edges: ["numbers.values -> item.list", "pick.value -> item.index"],\n)\n`;
    window.cnets_hold_opening = true;
    const transfer = new DataTransfer();
    transfer.items.add(new File([text], "big-list.ron"));
    document.getElementById("cnets").dispatchEvent(new DragEvent("drop",
      { dataTransfer: transfer, bubbles: true, cancelable: true, clientX: x, clientY: y }));
    return { bytes: text.length, at: performance.now() };
  }, centre);
  const held = await until(page, "the large file's notice", (t) => t.opening_notice !== null, 60_000);
  const png = await page.screenshot({ path: path.join(out, "11-large-file-notice.png") });
  assert.match(held.opening_notice, /^Opening big-list\.ron \(1\d\.\d MB\): it is read in the background/,
    `the notice names the file and its size: ${held.opening_notice}`);
  // The notice is drawn over the middle of the page (its text: a share of the pixels there change).
  const box = [490, 395, 910, 465];
  const changed = difference(await pixels(page, before, box), await pixels(page, png, box));
  assert.ok(changed > 0.02, `the notice is drawn in the middle of the page: ${(changed * 100).toFixed(1)} % of its pixels changed`);
  await page.evaluate(() => {
    window.cnets_long_tasks = [];
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) window.cnets_long_tasks.push(e.duration);
    }).observe({ type: "longtask" });
    window.cnets_hold_opening = false;
  });
  const opened = await until(page, "the large file opened", (t) => t.title.startsWith("big-list.ron") &&
    t.large_open && t.large_open.open_ms !== null, 120_000);
  const titledMs = (await page.evaluate(() => performance.now())) - dropped.at;
  await page.screenshot({ path: path.join(out, "11-large-file-opened.png") });
  assert.equal(opened.large_open.name, "big-list.ron");
  assert.equal(opened.large_open.bytes, dropped.bytes);
  assert.ok(opened.large_open.frames_while_reading >= 1,
    `the page drew frames while the worker read the file: ${opened.large_open.frames_while_reading}`);
  const openTasks = await page.evaluate(() => window.cnets_long_tasks.splice(0));
  assert.equal(opened.opening_notice, null, "the notice is gone once the file is open");
  // Editing the design does not carry the list to the worker (docs/web.md, "Large files"): the
  // worker kept it when it read the file; each request names it. The slider picks an item of it,
  // so the worker evaluates with the list it holds.
  await settled(page);
  const beforeEdit = await state(page);
  assert.equal(beforeEdit.worker_literals_sent, 0, "the worker kept the list it read");
  const picked = await drag(page);
  await settled(page);
  const edited = await state(page);
  assert.ok(picked.after !== picked.before && edited.worker_sent > beforeEdit.worker_sent,
    `the slider was dragged and evaluated: ${JSON.stringify(picked)}`);
  assert.equal(edited.worker_literals_sent, 0, "the list was not sent by the edits");
  assert.equal(edited.failed.length, 0, `no node failed: ${JSON.stringify(edited.failed)}`);
  figures.large_file = { bytes: dropped.bytes, frames_while_reading: opened.large_open.frames_while_reading,
    open_ms: Math.round(opened.large_open.open_ms), page_ms: Math.round(opened.large_open.page_ms),
    longest_page_task_while_opening_ms: Math.round(Math.max(0, ...openTasks)),
    drop_to_titled_ms_with_hold: Math.round(titledMs),
    edit_requests: edited.worker_sent - beforeEdit.worker_sent,
    last_request_prepared_ms: Math.round(edited.worker_send_ms * 10) / 10,
    literals_sent: edited.worker_literals_sent };
  console.log(`large file: ${JSON.stringify(figures.large_file)}`);
  noProblems("large file dropped");
  await page.close();
}

// 12. A graph dropped on a design with unsaved changes: the unsaved-changes question first
//     (Escape answers Cancel: the design stays, the dropped graph is let go).
{
  const { page } = await openAny(`${base}/index.html?example=torus-monge`);
  await drag(page);
  await settled(page);
  const dirty = await state(page);
  assert.ok(dirty.title.endsWith("*"), `the design has unsaved changes: ${dirty.title}`);
  const [x0, y0, x1, y1] = dirty.canvas;
  await page.evaluate(([text, x, y]) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([text], "other.ron"));
    document.getElementById("cnets").dispatchEvent(new DragEvent("drop",
      { dataTransfer: transfer, bubbles: true, cancelable: true, clientX: x, clientY: y }));
  }, [setValue(torusRon, "columns", 12), (x0 + x1) / 2, (y0 + y1) / 2]);
  const asked = await until(page, "the unsaved-changes question", (t) => t.question !== null, 20_000);
  await page.screenshot({ path: path.join(out, "12-drop-on-unsaved.png") });
  assert.equal(asked.question, "Opening other.ron");
  assert.equal(asked.title, dirty.title, "not replaced before the answer");
  await page.keyboard.press("Escape");
  const kept = await until(page, "the question answered", (t) => t.question === null, 20_000);
  await settled(page);
  const after = await state(page);
  assert.equal(after.title, dirty.title, "Cancel keeps the design");
  assert.equal(after.vertices, dirty.vertices, "and its mesh");
  figures.drop_on_unsaved = { question: asked.question, kept: kept.title };
  console.log(`drop on unsaved work: ${JSON.stringify(figures.drop_on_unsaved)}`);
  noProblems("drop on unsaved work");
  await page.close();
}

// 13. Drag the net (the Drag net tool, key G) on the start-up torus: the solves run in the page's
//     drag worker (a second Web Worker), never in the page's frames; the release's answer closes
//     one undo step, and Ctrl+Z restores every slider. The figures (solves, their rate, the page's
//     time a frame while dragging) are reported.
{
  const { page, state: opened } = await openAny(`${base}/index.html?example=torus-monge`);
  // The Top view (key 1): the pointer moves the vertex in the view's plane.
  const [cx, cy] = [(opened.view[0] + opened.view[2]) / 2, (opened.view[1] + opened.view[3]) / 2];
  await page.mouse.move(cx, cy);
  await page.keyboard.press("1");
  await settled(page);
  // Pictures with the pointer off the view (no hover highlight in them); the page reports a
  // vertex to grab when asked (it picks).
  await page.mouse.move(5, 5);
  await page.evaluate(() => { window.cnets_report_net_vertex = true; });
  await until(page, "a vertex of the net to grab", (t) => t.net_vertex !== undefined, 20_000);
  const before = await settled(page);
  const pictured = await shot(page, "13-torus-top-before", before.view);
  assert.ok(before.net_vertex, `a vertex of the net in view: ${JSON.stringify(before.view)}`);
  const [vx, vy, node, i, j] = before.net_vertex;
  await page.mouse.move(vx, vy);
  await page.keyboard.press("g");
  const drag = await page.evaluate(async ([x0, y0]) => {
    const canvas = document.getElementById("cnets");
    const fire = (type, x, y, buttons) => {
      const init = { bubbles: true, cancelable: true, composed: true, clientX: x, clientY: y, button: 0, buttons };
      canvas.dispatchEvent(type === "mousemove" ? new MouseEvent(type, init)
        : new PointerEvent(type, { ...init, pointerId: 1, pointerType: "mouse", isPrimary: true }));
    };
    const editor = () => window.cnets_test ?? {};
    const editorFrames = async (n) => {
      const start = editor().frames ?? 0;
      for (let k = 0; k < 600 && (editor().frames ?? 0) < start + n; k++) {
        await new Promise((r) => setTimeout(r, 10));
      }
    };
    fire("mousemove", x0, y0, 0);
    await editorFrames(1);
    fire("pointerdown", x0, y0, 1);
    await editorFrames(2);
    const t0 = performance.now();
    const steps = 30;
    for (let k = 1; k <= steps; k++) {
      fire("mousemove", x0 + (60 * k) / steps, y0 + (20 * k) / steps, 1);
      await editorFrames(1);
    }
    const t1 = performance.now();
    fire("pointerup", x0 + 60, y0 + 20, 0);
    return { seconds: (t1 - t0) / 1000 };
  }, [vx, vy]);
  const dragged = await until(page, "the drag's last answer", (t) => t.net_drag !== null, 60_000);
  await page.mouse.move(5, 5);
  const after = await settled(page);
  const moved = await shot(page, "13-torus-net-dragged", before.view);
  const d = dragged.net_drag;
  figures.drag_net = {
    node, vertex: [i, j], seconds: +drag.seconds.toFixed(2), solves: d.solves,
    worker_answers: after.drag_worker_answers, solves_per_second: +d.rate.toFixed(1),
    mean_solve_ms: +d.solve_ms.toFixed(1), ui_frame_median_ms: +(d.ui_frame_median_ms ?? 0).toFixed(1),
    ui_frame_max_ms: +(d.ui_frame_max_ms ?? 0).toFixed(1), frames: d.frames,
    release_ms: +d.release_ms.toFixed(1), distance_left: d.distance_left, not_convex: d.not_convex,
  };
  console.log(`drag the net: ${JSON.stringify(figures.drag_net)}`);
  assert.equal(d.node, node);
  assert.ok(d.solves >= 1, "the drag was solved");
  assert.ok(after.drag_worker_answers >= d.solves, "every solve came from the drag worker");
  assert.ok(after.message.startsWith(`dragged ${node}`), after.message);
  assert.equal(d.not_convex, 0, "every face (++)(++)");
  const changed = difference(pictured.px, moved.px);
  assert.ok(changed > 0.002, `the drag changed the picture: ${(changed * 100).toFixed(2)} %`);
  await page.keyboard.press("Control+z");
  await settled(page);
  const undone = await shot(page, "13-torus-net-undone", before.view);
  const left = difference(pictured.px, undone.px);
  figures.drag_net.picture_changed = +changed.toFixed(4);
  figures.drag_net.picture_left_after_undo = +left.toFixed(4);
  console.log(`drag the net: the picture changed ${(changed * 100).toFixed(2)} %, after Ctrl+Z ${(left * 100).toFixed(3)} %`);
  assert.ok(left < 0.0005, `one undo restores the picture: ${(left * 100).toFixed(3)} % differ`);
  noProblems("drag the net");
  await page.close();
}

// 14. Every screen: a laptop (1400 × 860) and a phone (390 × 844, touch) at device pixel ratios
//     1, 2 and 3 (Chromium's emulated ratio, where the canvas's device-pixel box is not scaled:
//     the page sets its backing store itself). The editor lays out by CSS size — the laptop gets
//     the desktop layout, the phone the narrow one — drawn at the device's pixels, and on the
//     phone a touch drag on a slider changes its value.
{
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    headless: true,
    args: ["--headless", "--no-sandbox", "--disable-quic", "--use-gl=angle", "--use-angle=swiftshader",
      "--enable-unsafe-swiftshader", "--disable-gpu-watchdog"],
  });
  figures.screens = {};
  for (const [device, width, height, touch] of [["laptop", 1400, 860, false], ["phone", 390, 844, true]]) {
    for (const ratio of [1, 2, 3]) {
      const ctx = await browser.newContext({
        viewport: { width, height }, deviceScaleFactor: ratio, hasTouch: touch, isMobile: touch,
      });
      ctx.setDefaultTimeout(180_000);
      await ctx.addInitScript(testing);
      const page = watch(await ctx.newPage());
      await page.goto(`${base}/index.html?example=torus-monge`);
      await until(page, `${device} at ${ratio}×`, (t) => t.first_picture_ms !== null && t.vertices > 0);
      const s = await settled(page);
      const backing = await page.evaluate(() => {
        const c = document.getElementById("cnets");
        return [c.width, c.height];
      });
      const what = `${device} ${width} × ${height} at ${ratio}×`;
      assert.ok(Math.abs(s.screen[0] - width) <= 1 && Math.abs(s.screen[1] - height) <= 1,
        `${what}: the layout is the CSS size, got ${s.screen}`);
      assert.ok(Math.abs(backing[0] - width * ratio) <= 2 && Math.abs(backing[1] - height * ratio) <= 2,
        `${what}: the canvas is drawn at the device's pixels, got ${backing}`);
      assert.equal(s.pixels_per_point, ratio, `${what}: pixels a point`);
      assert.equal(s.narrow, device === "phone", `${what}: the ${device === "phone" ? "narrow" : "desktop"} layout`);
      const entry = { screen: s.screen, backing, narrow: s.narrow };
      entry.overlays = overlaysApart(s, what);
      if (device === "phone") {
        const share = (s.view[3] - s.view[1]) / height;
        entry.view_share = +share.toFixed(3);
        assert.ok(share >= 0.6, `${what}: the 3D view covers ${(share * 100).toFixed(1)} % of the height`);
      }
      if (ratio === 2) await page.screenshot({ path: path.join(out, `14-${device}-at-2x.png`) });
      if (touch && ratio === 2) {
        const slider = pickSlider(s, true);
        const [x0, y0, x1, y1] = slider.rail;
        assert.ok(y1 <= height && x1 <= width, `${what}: the slider is on the screen: ${slider.rail}`);
        const y = (y0 + y1) / 2;
        const cdp = await ctx.newCDPSession(page);
        const touchAt = (type, x) => cdp.send("Input.dispatchTouchEvent",
          { type, touchPoints: type === "touchEnd" ? [] : [{ x, y }] });
        const before = slider.valueOf(s);
        const [from, to] = [x0 + (x1 - x0) * 0.2, x0 + (x1 - x0) * 0.8];
        await touchAt("touchStart", from);
        for (let k = 1; k <= 10; k++) {
          await touchAt("touchMove", from + ((to - from) * k) / 10);
          await page.waitForTimeout(30);
        }
        await touchAt("touchEnd", to);
        const after = await until(page, `${what}: the slider's new value`, (t) => slider.valueOf(t) !== before, 20_000);
        entry.touch_drag = { node: slider.node, before, after: slider.valueOf(after) };
        console.log(`${what}: a touch drag moved ${slider.node} ${before} → ${slider.valueOf(after)}`);
      }
      figures.screens[`${device}@${ratio}`] = entry;
      noProblems(what);
      await ctx.close();
    }
  }
  console.log(`screens: ${JSON.stringify(figures.screens)}`);
  await browser.close();
}

await context.close();
fs.rmSync(userData, { recursive: true, force: true });
fs.writeFileSync(path.join(out, "figures.json"), JSON.stringify(figures, null, 2) + "\n");
console.log(`browser test passed; figures: ${JSON.stringify(figures)}`);
