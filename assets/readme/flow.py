#!/usr/bin/env python3
"""Draws assets/readme/flow.jpg: a timed drive's frame beside its optical flow to the next
frame, colour-coded as Middlebury's flow pictures are (hue: direction, saturation: length,
up to the frame's 99th percentile; black: no valid flow, the sky and what the next frame
does not see).

usage: flow.py <frames/<camera> folder> <out.jpg> <frame>

    cityspec build specs/drive.toml --out OUT && python3 assets/readme/flow.py \\
        OUT/drive/frames/street assets/readme/flow.jpg 5

Needs Pillow, numpy and pypng (the flow PNG is 16-bit RGB, which Pillow would cut to 8).
"""

import colorsys
import sys
from pathlib import Path

import numpy as np
import png
from PIL import Image

WIDTH = 400  # each panel's width, px


def main(folder, out, frame):
    folder = Path(folder)
    stem = f"{int(frame):06d}"
    w, h, rows, _ = png.Reader(filename=str(folder / "flow" / f"{stem}.png")).read()
    data = np.vstack([np.asarray(r, dtype=np.float64) for r in rows]).reshape(h, w, 3)
    u, v, valid = (data[..., 0] - 32768) / 64, (data[..., 1] - 32768) / 64, data[..., 2] == 1
    length = np.hypot(u, v)
    top = max(np.percentile(length[valid], 99), 1e-6) if valid.any() else 1.0
    hue = (np.arctan2(-v, -u) / (2 * np.pi) + 0.5) % 1.0
    sat = np.clip(length / top, 0, 1)
    to_rgb = np.vectorize(lambda hh, ss: colorsys.hsv_to_rgb(hh, ss, 1.0), otypes=[float, float, float])
    r, g, b = to_rgb(hue, sat)
    colour = (np.stack([r, g, b], -1) * 255).astype(np.uint8)
    colour[~valid] = 0
    rgb = Image.open(folder / "rgb" / f"{stem}.png").convert("RGB")
    size = (WIDTH, round(rgb.height * WIDTH / rgb.width))
    sheet = Image.new("RGB", (2 * WIDTH + 8, size[1]), (255, 255, 255))
    sheet.paste(rgb.resize(size, Image.LANCZOS), (0, 0))
    sheet.paste(Image.fromarray(colour).resize(size, Image.NEAREST), (WIDTH + 8, 0))
    sheet.save(out, quality=88)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
