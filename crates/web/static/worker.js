// The evaluation worker of cnets in the browser (docs/web.md): the page's own wasm module,
// instantiated in a Web Worker, evaluates the graph while the page answers input. The page
// sends the compiled module first; the worker says "ready" once it takes requests.
import init, { worker_start } from "./cnets_web.js";

self.onmessage = async (event) => {
  self.onmessage = null;
  await init({ module_or_path: event.data });
  worker_start();
};
