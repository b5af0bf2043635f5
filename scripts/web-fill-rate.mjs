// The software rasterizer's floor for the browser editor (docs/web.md, "Frame rate on a software
// rasterizer"): headless Chromium with the browser test's flags (ANGLE + SwiftShader), a page of
// one full-window WebGL2 canvas that draws N blended full-window quads every animation frame, and
// the animation frames a second it gets. Two shaders: a flat colour, and egui's own per-pixel work
// (a bilinear texture sample, the colour multiply and the dithering noise of egui-wgpu's
// `fs_main_gamma_framebuffer`). An egui frame fills the window at least once with that shader
// (panels, canvas, 3D view's picture), so the second line bounds what any egui page reaches here.
//   node scripts/web-fill-rate.mjs [WIDTH HEIGHT]      (needs: npm ci; Debian's chromium)
import { chromium } from "playwright-core";

const width = +(process.argv[2] ?? 1400);
const height = +(process.argv[3] ?? 860);
const page = (shader, quads) => `<!doctype html><body style="margin:0"><canvas id=c></canvas><script>
const c = document.getElementById("c"); c.width = innerWidth; c.height = innerHeight;
c.style.cssText = "width:100vw;height:100vh;display:block";
const gl = c.getContext("webgl2", { antialias: false });
const compile = (type, src) => { const s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s); return s; };
const program = gl.createProgram();
gl.attachShader(program, compile(gl.VERTEX_SHADER, "#version 300 es\\nin vec2 p; void main() { gl_Position = vec4(p, 0, 1); }"));
gl.attachShader(program, compile(gl.FRAGMENT_SHADER, "#version 300 es\\nprecision mediump float; out vec4 o; uniform float t; uniform sampler2D tex;\\n" + ${JSON.stringify(shader)}));
gl.linkProgram(program); gl.useProgram(program);
gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 1, -1, -1, 1, 1, 1]), gl.STATIC_DRAW);
gl.enableVertexAttribArray(0); gl.vertexAttribPointer(0, 2, gl.FLOAT, false, 0, 0);
gl.bindTexture(gl.TEXTURE_2D, gl.createTexture());
gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, 256, 256, 0, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(256 * 256 * 4).map((_, i) => i * 7));
gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
gl.enable(gl.BLEND); gl.blendFunc(gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
const t = gl.getUniformLocation(program, "t");
window.frames = 0;
const frame = (now) => {
  window.frames++;
  gl.clearColor(0, 0, 0, 1); gl.clear(gl.COLOR_BUFFER_BIT);
  for (let k = 0; k < ${quads}; k++) { gl.uniform1f(t, (now % 1000) / 1000); gl.drawArrays(gl.TRIANGLE_STRIP, 0, 4); }
  requestAnimationFrame(frame);
};
requestAnimationFrame(frame);
</script>`;
const shaders = {
  "flat colour": "void main() { o = vec4(0.2, 0.3, t, 0.5); }",
  "egui's per-pixel work": `void main() {
    vec4 c = texture(tex, gl_FragCoord.xy / 256.0) * vec4(0.2, 0.3, t, 0.5);
    float n = fract(52.9829189 * fract(0.06711056 * gl_FragCoord.x + 0.00583715 * gl_FragCoord.y));
    o = vec4(c.rgb + (n - 0.5) * 0.95 / 255.0, c.a); }`,
};

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  headless: true,
  args: ["--headless", "--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
});
console.log(`animation frames a second, ${width} × ${height}, by full-window quads drawn each frame`);
for (const [name, shader] of Object.entries(shaders)) {
  const rates = [];
  for (const quads of [0, 1, 2, 4]) {
    const tab = await browser.newPage({ viewport: { width, height } });
    await tab.setContent(page(shader, quads));
    await tab.waitForTimeout(1000);
    const start = await tab.evaluate(() => window.frames);
    await tab.waitForTimeout(2000);
    rates.push(`${quads}: ${((await tab.evaluate(() => window.frames)) - start) / 2} Hz`);
    await tab.close();
  }
  console.log(`${name.padEnd(22)} ${rates.join(", ")}`);
}
await browser.close();
