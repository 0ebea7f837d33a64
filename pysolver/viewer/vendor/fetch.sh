#!/usr/bin/env bash
# Rebuild three.min.js (and copy three.js's LICENSE) from the npm registry: three.js
# $THREE and its OrbitControls (examples/jsm), bundled and minified by esbuild $ESBUILD into
# one classic script that defines the global THREE. The npm package no longer ships minified
# builds, hence esbuild. Needs node and npm; run it from anywhere:
#   bash pysolver/viewer/vendor/fetch.sh
set -euo pipefail
THREE=0.187.0
ESBUILD=0.28.2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
npm pack --silent "three@$THREE" >/dev/null
sha256sum "three-$THREE.tgz"
npm init -y >/dev/null
npm install --silent --no-audit --no-fund "./three-$THREE.tgz" "esbuild@$ESBUILD"
cat > entry.js <<'JS'
export * from 'three';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
JS
npx esbuild entry.js --bundle --minify --format=iife --global-name=THREE \
    --legal-comments=eof --outfile="$here/three.min.js"
cp node_modules/three/LICENSE "$here/LICENSE"
sha256sum "$here/three.min.js"
