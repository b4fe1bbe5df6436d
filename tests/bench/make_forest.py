#!/usr/bin/python3
"""Issue 17's forest as a glTF file: COPIES nodes (default 10,000) that all draw one mesh of about
TRIANGLES triangles (default 100,000: 10^9 flattened), on a square grid 3 m apart, each turned
and scaled by a hash of its index, seen by a camera above one corner and lit by a sun. Used by
docs/benchmarks.md ("Instances") to render it under /usr/bin/time:

  /usr/bin/python3 tests/bench/make_forest.py /tmp/forest.gltf
  /usr/bin/time -v build/bin/filmback render /tmp/forest.gltf -o /tmp/forest.png ...
"""
import argparse
import json
import math
import pathlib

import numpy as np


def tree(segments):
    """A bumpy closed sphere of radius about 1 m standing on y = 0: segments^2 triangles."""
    bands = segments // 2 + 1
    theta = np.pi * np.arange(1, bands) / bands
    phi = 2 * np.pi * np.arange(segments) / segments
    t, p = np.meshgrid(theta, phi, indexing="ij")
    r = 1.0 + 0.08 * np.sin(12 * t) * np.cos(10 * p) + 0.03 * np.sin(31 * p + 3 * t)
    ring = np.stack([r * np.sin(t) * np.cos(p), r * np.cos(t) + 1.0, r * np.sin(t) * np.sin(p)], -1)
    positions = np.concatenate([[[0, 2.0, 0]], ring.reshape(-1, 3), [[0, 0.0, 0]]]).astype(np.float32)
    south = len(positions) - 1

    def v(band, s):
        return 1 + (band - 1) * segments + s % segments

    s = np.arange(segments)
    tris = [np.stack([np.zeros_like(s), v(1, s + 1), v(1, s)], -1)]
    for band in range(1, bands - 1):
        a, b, c, d = v(band, s), v(band, s + 1), v(band + 1, s), v(band + 1, s + 1)
        tris += [np.stack([a, b, c], -1), np.stack([b, d, c], -1)]
    tris.append(np.stack([v(bands - 1, s), v(bands - 1, s + 1), np.full_like(s, south)], -1))
    return positions, np.concatenate(tris).astype(np.uint32)


def hash01(i, salt):
    """A deterministic fraction in [0, 1) per index (Knuth's multiplicative hash)."""
    return ((i * 2654435761 + salt * 40503) % 2**32) / 2**32


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output", type=pathlib.Path)
    parser.add_argument("--copies", type=int, default=10000)
    parser.add_argument("--triangles", type=int, default=100000)
    args = parser.parse_args()
    positions, indices = tree(max(4, round(math.sqrt(args.triangles))))
    blob = positions.tobytes() + indices.tobytes()
    bin_path = args.output.with_suffix(".bin")
    bin_path.write_bytes(blob)
    side = math.ceil(math.sqrt(args.copies))
    nodes = []
    for i in range(args.copies):
        turn = 2 * math.pi * hash01(i, 1)
        size = 0.7 + 0.6 * hash01(i, 2)
        nodes.append({"mesh": 0, "translation": [3.0 * (i % side), 0, -3.0 * (i // side)],
                      "rotation": [0, math.sin(turn / 2), 0, math.cos(turn / 2)],
                      "scale": [size] * 3})
    # The camera above the first row's middle, looking across the grid; the sun from the side.
    nodes.append({"camera": 0, "translation": [1.5 * side, 12.0, 8.0],
                  "rotation": [-0.2588190, 0, 0, 0.9659258]})
    nodes.append({"extensions": {"KHR_lights_punctual": {"light": 0}},
                  "rotation": [-0.4619398, 0.1913417, 0.0990458, 0.8604181]})
    gltf = {
        "asset": {"version": "2.0", "generator": "filmback tests/bench/make_forest.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "intensity": 683.0 * 3, "color": [1, 0.95, 0.9]}]}},
        "buffers": [{"byteLength": len(blob), "uri": bin_path.name}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": positions.nbytes},
                        {"buffer": 0, "byteOffset": positions.nbytes, "byteLength": indices.nbytes}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": positions.min(0).tolist(), "max": positions.max(0).tolist()},
            {"bufferView": 1, "componentType": 5125, "count": indices.size, "type": "SCALAR"}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.15, 1],
                                                "metallicFactor": 0, "roughnessFactor": 0.8}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5,
                                                              "znear": 0.1}}],
        "nodes": nodes,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "scene": 0,
    }
    args.output.write_text(json.dumps(gltf))
    print(f"{args.output}: {args.copies} copies of {len(indices)} triangles "
          f"({args.copies * len(indices):.3g} flattened)")


if __name__ == "__main__":
    main()
