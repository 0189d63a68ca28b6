#!/usr/bin/env python3
"""Draws assets/readme/traffic.jpg: two frames of a timed drive through moving traffic
(`[traffic]`), each vehicle and person that moves boxed in its track's colour (from the
MOT ground truth, gt/gt.txt), with the trail of its box's foot over the frames between.

usage: traffic.py <frames/<camera> folder> <out.jpg> <first frame> <last frame>

    cityspec build specs/drive.toml --set 'cameras.street.heading=[-8, 8]' --set seed=2 \\
        --out OUT && python3 assets/readme/traffic.py OUT/drive/frames/street \\
        assets/readme/traffic.jpg 0 19

(the README's picture: the drive looking ahead, in the city of seed 2).

Needs Pillow.
"""

import colorsys
import json
import sys
from pathlib import Path

from PIL import Image, ImageDraw

WIDTH = 400  # each panel's width, px


def colour(track):
    r, g, b = colorsys.hsv_to_rgb((track * 0.618034) % 1.0, 0.9, 1.0)
    return int(r * 255), int(g * 255), int(b * 255)


def main(folder, out, first, last):
    folder = Path(folder)
    first, last = int(first), int(last)
    poses = json.loads((folder / "poses.json").read_text())
    frames = poses["frames"]
    moved = set()
    for key, offset in frames[last]["traffic"]["objects"].items():
        start = frames[first]["traffic"]["objects"][key]
        if sum((a - b) ** 2 for a, b in zip(offset, start)) > 0.25:
            moved.add(int(key))
    boxes = {}  # frame -> [(track, box)]
    for line in (folder / "gt" / "gt.txt").read_text().splitlines():
        f, track, x, y, w, h, conf = line.split(",")[:7]
        if int(track) in moved and conf == "1":
            boxes.setdefault(int(f) - 1, []).append((int(track), float(x) - 1, float(y) - 1, float(w), float(h)))
    panels = []
    for k in (first, last):
        image = Image.open(folder / "rgb" / f"{k:06d}.png").convert("RGB")
        scale = WIDTH / image.width
        image = image.resize((WIDTH, round(image.height * scale)), Image.LANCZOS)
        draw = ImageDraw.Draw(image)
        # The trail: each box's foot from the first frame to this one.
        for j in range(first, k):
            for track, x, y, w, h in boxes.get(j, []):
                fx, fy = (x + w / 2) * scale, (y + h) * scale
                draw.ellipse([fx - 1.5, fy - 1.5, fx + 1.5, fy + 1.5], fill=colour(track))
        for track, x, y, w, h in boxes.get(k, []):
            draw.rectangle([x * scale, y * scale, (x + w) * scale, (y + h) * scale], outline=colour(track), width=2)
        draw.text((6, 4), f"t = {frames[k]['time']:.1f} s", fill=(255, 255, 255))
        panels.append(image)
    sheet = Image.new("RGB", (2 * WIDTH + 6, panels[0].height), (255, 255, 255))
    sheet.paste(panels[0], (0, 0))
    sheet.paste(panels[1], (WIDTH + 6, 0))
    sheet.save(out, quality=85)


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
