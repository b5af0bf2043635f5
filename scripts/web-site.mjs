// Shared by the measurement scripts (web-frame-rate.mjs, web-large-edit.mjs): serves a built site
// from a folder on a loopback port and opens a page in headless Chromium with the browser test's
// flags (ANGLE + SwiftShader), 1400 × 860.
import { chromium } from "playwright-core";
import fs from "node:fs";
import http from "node:http";
import path from "node:path";

const types = { ".html": "text/html", ".js": "text/javascript", ".wasm": "application/wasm" };

/** Serves `dir` and opens `index.html` with `query` (e.g. "?example=facade"): the page, and how to close. */
export async function openSite(dir, query) {
  const server = http.createServer((request, response) => {
    const file = path.join(dir, path.normalize(decodeURIComponent(request.url.split("?")[0])));
    fs.readFile(file, (error, body) => {
      if (error) {
        response.writeHead(404);
        response.end();
        return;
      }
      response.writeHead(200, { "content-type": types[path.extname(file)] ?? "application/octet-stream" });
      response.end(body);
    });
  });
  await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    headless: true,
    args: ["--headless", "--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  });
  const page = await browser.newPage({ viewport: { width: 1400, height: 860 } });
  // The page keeps its test state (window.cnets_test) only when asked, before its module starts.
  await page.addInitScript(() => { window.cnets_testing = true; });
  await page.goto(`http://127.0.0.1:${server.address().port}/index.html${query}`);
  const close = async () => {
    await browser.close();
    server.close();
  };
  return { page, close };
}
