#!/bin/sh
# Installs the page's npm packages (pinned by package-lock.json) into OUT and
# copies the files the page serves into OUT/vendor (no CDN at run time):
#   sim/gnd/install-web.sh build/dev/gnd
# `petra gnd serve` built in that tree serves OUT/vendor at /vendor/.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:?usage: install-web.sh OUT_DIR}
mkdir -p "$out"
cp "$here/package.json" "$here/package-lock.json" "$out/"
cd "$out"
npm ci --ignore-scripts --no-audit --no-fund --loglevel=error
rm -rf vendor
mkdir -p vendor/three/examples/jsm
cp -r node_modules/three/build vendor/three/build
cp -r node_modules/three/examples/jsm/controls vendor/three/examples/jsm/controls
cp node_modules/three/LICENSE vendor/three/LICENSE
# The 3D view's surface mesh: Delaunay triangulation (and its exact predicates).
mkdir -p vendor/delaunator vendor/robust-predicates
cp node_modules/delaunator/index.js node_modules/delaunator/LICENSE vendor/delaunator/
cp -r node_modules/robust-predicates/index.js node_modules/robust-predicates/esm \
  node_modules/robust-predicates/LICENSE vendor/robust-predicates/
# Open MCT (operator panels, /openmct.html): its built distribution.
cp -r node_modules/openmct/dist vendor/openmct
cp node_modules/openmct/LICENSE.md vendor/openmct/
echo "npm packages in $out/node_modules, page assets in $out/vendor"
