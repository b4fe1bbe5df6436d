"""Writes scenes/lenses/grid.gltf, the scene docs/camera-model.md's pictures of a realistic lens
use ("Realistic lenses"): a grid of emissive tiles of radiance 1 on the plane 2 m in front of
camera `grid` (50 mm, 36 x 24 mm sensor, 3:2), wider than its view, and camera `sky` looking the
other way at nothing, for the lens' relative illumination against a uniform background
(`--background 1`). Standard library only; the glTF writer is scenes/hard/make_scenes.py's.

Run from anywhere: python3 scenes/lenses/make_grid.py [FOLDER] (default: this script's folder).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "hard"))
from make_scenes import Scene  # noqa: E402

PITCH_M, TILE_M, DEPTH_M = 0.1, 0.08, 2.0
COLUMNS, ROWS = 24, 16  # 2.4 x 1.6 m: the view at 2 m is 1.44 x 0.96 m


def grid_scene():
    s = Scene("realistic lens grid")
    points, indices = [], []
    for i in range(COLUMNS):
        for j in range(ROWS):
            x = (i - (COLUMNS - 1) / 2) * PITCH_M
            y = (j - (ROWS - 1) / 2) * PITCH_M
            h = TILE_M / 2
            base = len(points)
            points += [(x - h, y - h, 0.0), (x + h, y - h, 0.0), (x + h, y + h, 0.0),
                       (x - h, y + h, 0.0)]
            indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    tiles = s.triangles("tiles", points, indices, s.emitter("white", (1.0, 1.0, 1.0)))
    s.node(name="tiles", mesh=tiles, translation=[0.0, 0.0, -DEPTH_M])
    s.camera("grid", 384, 256, 50.0, clip=(0.01, 100.0))
    s.camera("sky", 384, 256, 50.0, clip=(0.01, 100.0), rotation=[0.0, 1.0, 0.0, 0.0])
    return s


if __name__ == "__main__":
    folder = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    grid_scene().write(folder / "grid.gltf")
