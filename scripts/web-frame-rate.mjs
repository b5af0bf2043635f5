// The browser editor's animation frames a second (docs/web.md, "Frame rate on a software
// rasterizer"): serves a built site from a folder on a loopback port, opens an example in headless
// Chromium with the browser test's flags (ANGLE + SwiftShader, 1400 × 860), and counts
// requestAnimationFrame callbacks while pointer moves are dispatched every 16 ms: first hovering
// (nothing changes), then dragging the parameter panel's first slider (the worker evaluates).
// Three rounds of each.
//   node scripts/web-frame-rate.mjs SITE_DIR [EXAMPLE] [QUERY]   (needs: npm ci; Debian's chromium)
// QUERY is appended to the page's address (for builds that read more parameters).
import { openSite } from "./web-site.mjs";

const dir = process.argv[2];
const example = process.argv[3] ?? "facade";
const query = process.argv[4] ?? "";
if (!dir) throw new Error("usage: node scripts/web-frame-rate.mjs SITE_DIR [EXAMPLE] [QUERY]");
const { page, close } = await openSite(dir, `?example=${example}${query}`);
const state = () => page.evaluate(() => window.cnets_test ?? null);
for (let k = 0; k < 600; k++) {
  const s = await state();
  if (s && s.first_picture_ms !== null && !s.busy) break;
  await page.waitForTimeout(100);
}
await page.waitForTimeout(2000);
const s = await state();
const slider = (s.panel ?? []).find((p) => p.type === "param.number");
// Without a slider (no parameter panel, no slider on the canvas) only the hover is measured, over
// the middle of the page.
const found = slider ? slider.rect : s.slider;
const rail = found ?? [500, 330, 900, 340];

/** Animation frames a second while 120 pointer moves are dispatched 16 ms apart. */
const rate = (drag) => page.evaluate(async ([x0, y0, x1, y1, drag]) => {
  const canvas = document.getElementById("cnets");
  // Hovering: 200 px below the slider (the panel), so nothing is pressed.
  const y = (y0 + y1) / 2 + (drag ? 0 : 200);
  const raf = [];
  let go = true;
  const tick = (t) => { raf.push(t); if (go) requestAnimationFrame(tick); };
  requestAnimationFrame(tick);
  const pause = (ms) => new Promise((r) => setTimeout(r, ms));
  // (eframe takes presses and releases as pointer events, moves as mouse events.)
  const fire = (type, x, buttons) => {
    const init = { bubbles: true, cancelable: true, composed: true, clientX: x, clientY: y, button: 0, buttons };
    canvas.dispatchEvent(type === "mousemove" ? new MouseEvent(type, init)
      : new PointerEvent(type, { ...init, pointerId: 1, pointerType: "mouse", isPrimary: true }));
  };
  fire("mousemove", x0 + 4, 0);
  await pause(300);
  if (drag) {
    fire("pointerdown", x0 + 4, 1);
    await pause(300);
  }
  const t0 = performance.now();
  for (let k = 1; k <= 120; k++) {
    await pause(16);
    fire("mousemove", x0 + 4 + ((x1 - x0 - 8) * (k % 60)) / 60, drag ? 1 : 0);
  }
  const t1 = performance.now();
  if (drag) fire("pointerup", x1 - 4, 0);
  go = false;
  return raf.filter((t) => t >= t0 && t <= t1).length / ((t1 - t0) / 1000);
}, [...rail, drag]);

const rounds = [];
for (let k = 0; k < 3; k++) {
  const hover = `hover ${(await rate(false)).toFixed(1)} Hz`;
  rounds.push(found ? `${hover}, drag ${(await rate(true)).toFixed(1)} Hz` : `${hover}, no slider to drag`);
  await page.waitForTimeout(1500);
}
console.log(`${example}${query}, 1400 × 860, animation frames a second: ${rounds.join("; ")}`);
await close();
