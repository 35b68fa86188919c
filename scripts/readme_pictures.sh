#!/usr/bin/env bash
# Regenerates the pictures of docs/render.md, in docs/pictures/, with `refrast render` and, under Xvfb,
# `refrast view` (release build).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p refrast-cli
refrast=target/release/refrast
out=docs/pictures
mkdir -p "$out"
r() { "$refrast" render "$@" >/dev/null; }
# Seed 002's room: lit per pixel by the lab's light, then as the lab's wireframe and depth.
r room --size 300x300 -o "$out/room.png"
r room --size 300x300 --mode wire -o "$out/room-wire.png"
r room --size 300x300 --mode depth -o "$out/room-depth.png"
# Flat, Gouraud and Phong (Blinn) shading of one sphere.
for s in flat gouraud phong; do
  r sphere --size 240x240 --shading "$s" --blinn -o "$out/sphere-$s.png"
done
# Overdraw of a plane whose diagonals run through pixel centres: the reference covers every
# pixel once; inclusive edges cover the diagonals twice, exclusive edges leave them open.
for i in reference mutant:inclusive-edges mutant:exclusive-edges; do
  r aligned-plane --size 256x256 --mode overdraw --impl "$i" -o "$out/overdraw-${i#mutant:}.png"
done
# A checkerboard on a floor of two triangles: perspective-correct uv, then the affine mutant's.
r floor --size 320x240 --texture checker --sampling nearest -o "$out/floor-checker.png"
r floor --size 320x240 --texture checker --sampling nearest --impl mutant:affine-attributes \
  -o "$out/floor-checker-affine.png"
# Lab 004's meshes: the star as lines, the torus's normals, and the plane in overdraw through
# seed 002's scanline course rasterizer, which covers pixels of shared edges twice.
r star --size 320x240 --mode wire -o "$out/star-wire.png"
r torus --size 320x240 --mode normals -o "$out/torus-normals.png"
r plane --size 320x240 --mode overdraw --impl lab002-scanline -o "$out/plane-overdraw-lab002.png"
# The star at one sample and at four (Vulkan's standard locations), resolved with a box filter.
r star --size 160x120 -o "$out/star-1x.png"
r star --size 160x120 --samples 4 -o "$out/star-4x.png"
r star --size 160x120 --samples 4 --sample-mask 0b0011 -o "$out/star-4x-mask.png"
# The checkered floor at four samples: uv at each sample (the checker's edges smoothed), then at
# one centroid a pixel (one texel a pixel: its edges stepped).
for at in sample centroid; do
  r floor --size 320x240 --texture checker --sampling nearest --samples 4 --interpolation "$at" \
    -o "$out/floor-4x-$at.png"
done
# The star's overdraw, then drawn conservatively: every pixel a triangle touches, shared edges twice.
r star --size 160x120 --mode overdraw -o "$out/star-overdraw.png"
r star --size 160x120 --mode overdraw --conservative over -o "$out/star-overdraw-conservative.png"
# Seed 003's overlaps (a cycle of bars, two triangles through each other): a depth buffer draws
# them, the painter's algorithm cannot (docs/zoo.md).
r overlaps --size 480x240 -o "$out/overlaps-reference.png"
r overlaps --size 480x240 --impl lab003-painter -o "$out/overlaps-painter.png"
# The viewer's window under Xvfb (scripts/check_viewer.py keeps its screenshots): the room, and
# the aligned plane's overdraw once I reaches mutant:inclusive-edges.
shots=$(mktemp -d)
trap 'rm -rf "$shots"' EXIT
python3 scripts/check_viewer.py --refrast "$refrast" --out "$shots" >/dev/null
cp "$shots/room.png" "$out/view-room.png"
cp "$shots/overdraw-mutant.png" "$out/view-overdraw-mutant.png"
ls -1 "$out"
