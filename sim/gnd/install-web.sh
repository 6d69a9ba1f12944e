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
echo "npm packages in $out/node_modules, page assets in $out/vendor"
