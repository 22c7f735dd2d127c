/** The package version (package.json), set by Vite at build time. */
declare const __LORATRACK_VERSION__: string;
