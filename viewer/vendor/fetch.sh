#!/usr/bin/env bash
# Reproduces viewer/vendor/three.min.js and viewer/vendor/LICENSE from the npm registry:
# three.js (MIT) at the pinned version, bundled and minified by esbuild from entry.js into one
# classic script defining the global `THREE`. three 0.187 ships no minified build (and its
# module build is split into three.module.js + three.core.js), hence the bundling step.
set -euo pipefail
THREE_VERSION=0.187.0
ESBUILD_VERSION=0.28.2
here="$(cd "$(dirname "$0")" && pwd)"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cd "$scratch"
npm init -y >/dev/null
npm install --no-audit --no-fund --save-exact "three@$THREE_VERSION" "esbuild@$ESBUILD_VERSION" >/dev/null
cp "$here/entry.js" entry.js
./node_modules/.bin/esbuild entry.js --bundle --minify --format=iife --global-name=THREE \
  --legal-comments=inline --outfile=three.min.js
cp three.min.js "$here/three.min.js"
cp node_modules/three/LICENSE "$here/LICENSE"
echo "three $THREE_VERSION: $(wc -c < "$here/three.min.js") bytes in $here/three.min.js"
