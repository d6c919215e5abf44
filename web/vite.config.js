// `npm run build` writes the console to dist/, which the link server serves (`--web web/dist`).
// `npm run dev` serves the sources and forwards /ws to a running server: MARSOKHOD_URL, default
// http://127.0.0.1:8080 (open http://localhost:5173/?token=… with that server's token).
import { defineConfig } from 'vite';

const server = process.env.MARSOKHOD_URL ?? 'http://127.0.0.1:8080';

export default defineConfig({
  base: './',
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    chunkSizeWarningLimit: 1000,  // three.js alone is ~700 kB before gzip
  },
  server: {
    proxy: { '/ws': { target: server, ws: true } },
  },
});
