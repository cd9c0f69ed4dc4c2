import { defineConfig } from 'vite';

// `npm run build` writes web/dist; the CMake target passes --outDir to build into the build tree.
// `npm run dev` proxies the API (and its WebSocket) to a running `tourmap serve`.
const apiTarget = process.env.TOURMAP_API ?? 'http://127.0.0.1:8080';

export default defineConfig({
  base: '/',
  build: {
    target: 'es2022',
    outDir: 'dist',
    assetsDir: 'assets',
    sourcemap: true,
  },
  server: {
    proxy: {
      '/api': { target: apiTarget, ws: true },
    },
  },
});
