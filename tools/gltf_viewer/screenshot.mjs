// Renders a GLB in index.html with headless Chromium (Debian's /usr/bin/chromium through playwright-core)
// and writes a PNG screenshot; prints what the page saw and pixel statistics of the picture as JSON:
// the share of pixels that are not background, and their mean colour (a photo shows as skin, an untextured
// mesh as grey).
//
// Usage: node screenshot.mjs <file.glb> <out.png>   (after `npm install` in this folder)
import { chromium } from 'playwright-core';
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const [glb, out] = process.argv.slice(2);
if (!glb || !out) { console.error('usage: node screenshot.mjs <file.glb> <out.png>'); process.exit(2); }
const here = path.dirname(fileURLToPath(import.meta.url));
const types = { '.html': 'text/html', '.js': 'text/javascript', '.glb': 'model/gltf-binary' };
// The page and three.js from this folder, the model from its own path: localhost only.
const server = http.createServer((req, res) => {
  const url = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
  const file = url === '/model.glb' ? path.resolve(glb) : path.join(here, path.normalize(url));
  if (!file.startsWith(here) && file !== path.resolve(glb)) { res.writeHead(403); res.end(); return; }
  fs.readFile(file, (err, data) => {
    if (err) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    res.end(data);
  });
});
await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
const port = server.address().port;
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-quic',
         '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage({ viewport: { width: 800, height: 800 } });
  await page.goto(`http://127.0.0.1:${port}/index.html?file=/model.glb`);
  await page.waitForFunction(() => document.title.startsWith('{'), null, { timeout: 60000 });
  const seen = JSON.parse(await page.title());
  const stats = await page.evaluate(() => {
    const canvas = document.querySelector('canvas');
    const copy = document.createElement('canvas');
    copy.width = canvas.width; copy.height = canvas.height;
    const ctx = copy.getContext('2d');
    ctx.drawImage(canvas, 0, 0);
    const px = ctx.getImageData(0, 0, copy.width, copy.height).data;
    let n = 0, r = 0, g = 0, b = 0, spread = 0;
    for (let i = 0; i < px.length; i += 4) {
      if (px[i] + px[i + 1] + px[i + 2] === 0) continue;
      ++n; r += px[i]; g += px[i + 1]; b += px[i + 2];
      spread += Math.max(px[i], px[i + 1], px[i + 2]) - Math.min(px[i], px[i + 1], px[i + 2]);
    }
    return { covered: n / (px.length / 4), mean_rgb: n ? [r / n, g / n, b / n] : null,
             mean_saturation: n ? spread / n : 0 };
  });
  await page.screenshot({ path: out });
  console.log(JSON.stringify({ ...seen, ...stats }));
} finally {
  await browser.close();
  server.close();
}
