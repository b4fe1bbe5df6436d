"""Renders the pictures of docs/camera-model.md's "Realistic lenses" with filmback and Debian's
numpy, OpenImageIO, SciPy and matplotlib (/usr/bin/python3):

- docs/realistic_dgauss50_grid.png: scenes/lenses/grid.gltf through a pinhole of 50 mm (left) and
  through the double Gauss (dgauss50.dat) at f/2 focused on the grid at 2 m (right): vignetting,
  distortion and the larger image of a lens that focuses by moving its film;
- docs/realistic_dgauss50_illumination.png: the double Gauss' relative illumination E(r) / E(0)
  against a uniform background along the image's diagonal at f/2, f/4 and f/8, beside cos^4 of the
  field angle (what an ideal thin lens gives);
and prints the grid's distortion: each tile's distance from the centre against the pinhole's,
scaled to agree near the centre.

Run: /usr/bin/python3 scenes/lenses/make_figures.py FILMBACK (the built binary) from the
repository's root.
"""

import math
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import OpenImageIO as oiio  # noqa: E402
from scipy import ndimage  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "lenses" / "grid.gltf"
LENS = ROOT / "scenes" / "lenses" / "dgauss50.dat"
WIDTH, HEIGHT, SENSOR_MM, FOCAL_MM = 384, 256, 36.0, 50.0


def render(filmback, folder, name, *options):
    out = Path(folder) / (name + ".exr")
    subprocess.run([filmback, "render", SCENE, "-q", "--integrator", "path:max_depth=0",
                    "--filter", "box", "-o", out, *options], check=True)
    return oiio.ImageInput.open(str(out)).read_image()[:, :, 0].astype(np.float64)


def tile_centres(image):
    """Centroids (x, y from the image centre, px) of the tiles wholly inside the frame."""
    labels, count = ndimage.label(image > 0.05)  # the corners' tiles keep 17 % at f/2
    centres = ndimage.center_of_mass(image, labels, range(1, count + 1))
    boxes = ndimage.find_objects(labels)
    inside = [c for c, b in zip(centres, boxes)
              if b[0].start > 0 and b[1].start > 0 and b[0].stop < HEIGHT and b[1].stop < WIDTH]
    return np.array([(x + 0.5 - WIDTH / 2, y + 0.5 - HEIGHT / 2) for y, x in inside])


def distortion(pinhole, lens):
    """Radial distortion of the lens' tiles against the pinhole's nearest, the scale fitted on
    tiles within a fifth of the half diagonal."""
    p, q = tile_centres(pinhole), tile_centres(lens)
    r_p = np.hypot(p[:, 0], p[:, 1])
    pairs = []
    for c in q:
        k = np.argmin(np.hypot(*(p / np.hypot(*p.T)[:, None] - c / np.hypot(*c)).T)
                      + np.abs(r_p - np.hypot(*c)) / 40)
        pairs.append((r_p[k], np.hypot(*c)))
    pairs = np.array(pairs)
    half_diagonal = math.hypot(WIDTH, HEIGHT) / 2
    near = pairs[:, 0] < 0.2 * half_diagonal
    scale = np.sum(pairs[near, 1] * pairs[near, 0]) / np.sum(pairs[near, 0] ** 2)
    outer = pairs[np.argmax(pairs[:, 0])]
    return scale, outer[0] / half_diagonal, outer[1] / (scale * outer[0]) - 1


def main():
    filmback = sys.argv[1]
    lens = "realistic:lens=%s" % LENS
    with tempfile.TemporaryDirectory() as folder:
        pinhole = render(filmback, folder, "pinhole", "--camera", "grid", "--spp", "16")
        grid = render(filmback, folder, "grid", "--camera", "grid", "--spp", "64",
                      "--camera-model", lens + ",focus_distance_m=2")
        scale, at, d = distortion(pinhole, grid)
        print("double Gauss at 2 m: image scale %.4f of the pinhole's; distortion %+.2f %% at %.0f %%"
              " of the half diagonal" % (scale, 100 * d, 100 * at))
        picture = np.concatenate([pinhole, grid], axis=1)
        picture = picture.reshape(HEIGHT // 2, 2, WIDTH, 2).mean(axis=(1, 3))  # half size
        picture = picture.clip(0, 1) ** (1 / 2.2)
        rgb = np.repeat(picture[:, :, None], 3, axis=2).astype(np.float32)
        oiio.ImageBuf(rgb).write(str(ROOT / "docs" / "realistic_dgauss50_grid.png"))
        # Along the diagonal, centre to corner: 3 x 3 px means.
        steps = np.linspace(0, 1, 40)
        film_mm = steps * math.hypot(SENSOR_MM, SENSOR_MM * HEIGHT / WIDTH) / 2
        plt.figure(figsize=(5, 3.2), dpi=100)
        for fstop in ("0", "4", "8"):
            sky = render(filmback, folder, "sky" + fstop, "--camera", "sky", "--background", "1",
                         "--spp", "64", "--camera-model", lens + ",fstop=" + fstop)
            values = []
            for s in steps:
                x = int(WIDTH / 2 + s * (WIDTH / 2 - 2)), int(HEIGHT / 2 + s * (HEIGHT / 2 - 2))
                values.append(sky[x[1] - 1:x[1] + 2, x[0] - 1:x[0] + 2].mean())
            label = "f/2 (open)" if fstop == "0" else "f/" + fstop
            plt.plot(film_mm, values, label=label)
        plt.plot(film_mm, np.cos(np.arctan(film_mm / FOCAL_MM)) ** 4, "k--",
                 label="cos$^4$ of the field angle")
        plt.xlabel("film radius (mm), 36 x 24 mm sensor")
        plt.ylabel("relative illumination E / E(0)")
        plt.title("dgauss50.dat focused at infinity", fontsize=10)
        plt.ylim(0, 1.05)
        plt.grid(alpha=0.3)
        plt.legend(fontsize=8)
        plt.tight_layout()
        plt.savefig(ROOT / "docs" / "realistic_dgauss50_illumination.png")


if __name__ == "__main__":
    main()
