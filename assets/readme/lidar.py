#!/usr/bin/env python3
"""Draws assets/readme/lidar.jpg: one frame's LiDAR scan coloured by its SemanticKITTI
labels (SemanticKITTI's own colours), projected into the camera's frame through the KITTI
calib on the left and seen from above (40 m around the car, forward up) on the right.

usage: lidar.py <frames/<camera> folder> <out.jpg> <frame>

    cityspec build specs/sensors.toml --out OUT && python3 assets/readme/lidar.py \\
        OUT/sensors/frames/street assets/readme/lidar.jpg 12

Needs Pillow and numpy.
"""

import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

# SemanticKITTI's colour map (semantic-kitti.yaml, there BGR), as RGB.
COLOURS = {
    0: (0, 0, 0), 10: (100, 150, 245), 11: (100, 230, 245), 30: (30, 30, 255),
    31: (255, 40, 200), 40: (255, 0, 255), 48: (75, 0, 75), 50: (255, 200, 0),
    60: (170, 255, 150), 70: (0, 175, 0), 72: (150, 240, 80), 80: (255, 240, 150),
    81: (255, 0, 0), 99: (255, 255, 50),
}
SIDE = 360  # the top view's side, px
METRES = 40.0  # the top view's half side


def main(folder, out, frame):
    folder = Path(folder)
    stem = f"{int(frame):06d}"
    points = np.fromfile(folder / "velodyne" / f"{stem}.bin", dtype="<f4").reshape(-1, 4)
    labels = np.fromfile(folder / "labels" / f"{stem}.label", dtype="<u4") & 0xFFFF
    colours = np.array([COLOURS.get(int(l), (255, 255, 255)) for l in labels], dtype=np.uint8)
    calib = {}
    for line in (folder / "calib" / f"{stem}.txt").read_text().splitlines():
        name, values = line.split(":", 1)
        calib[name] = np.array([float(v) for v in values.split()])
    r0 = np.eye(4)
    r0[:3, :3] = calib["R0_rect"].reshape(3, 3)
    tr = np.eye(4)
    tr[:3] = calib["Tr_velo_to_cam"].reshape(3, 4)
    pix = calib["P2"].reshape(3, 4) @ r0 @ tr @ np.hstack([points[:, :3], np.ones((len(points), 1))]).T

    rgb = Image.open(folder / "rgb" / f"{stem}.png").convert("RGB")
    frame_img = Image.eval(rgb, lambda v: v // 2)
    draw = ImageDraw.Draw(frame_img)
    front = pix[2] > 0.5
    # Far points first, so near ones are drawn over them.
    for k in np.flatnonzero(front)[np.argsort(-pix[2, front])]:
        u, v = pix[0, k] / pix[2, k], pix[1, k] / pix[2, k]
        if 0 <= u < rgb.width and 0 <= v < rgb.height:
            draw.point((u, v), fill=tuple(int(c) for c in colours[k]))
    scale = SIDE / rgb.height
    frame_img = frame_img.resize((round(rgb.width * scale), SIDE), Image.LANCZOS)

    top = np.full((SIDE, SIDE, 3), 24, dtype=np.uint8)
    # x forward (up in the picture), y left (left); lower points first, so that a
    # building's or a car's top covers the ground under it.
    order = np.argsort(points[:, 2])
    col = (SIDE / 2 - points[order, 1] * SIDE / (2 * METRES)).astype(int)
    row = (SIDE / 2 - points[order, 0] * SIDE / (2 * METRES)).astype(int)
    keep = (col >= 0) & (col < SIDE) & (row >= 0) & (row < SIDE)
    # Each point as 2 x 2 pixels.
    for dr in (0, 1):
        for dc in (0, 1):
            r, c = np.minimum(row[keep] + dr, SIDE - 1), np.minimum(col[keep] + dc, SIDE - 1)
            top[r, c] = colours[order][keep]
    top_img = Image.fromarray(top)
    ImageDraw.Draw(top_img).polygon(
        [(SIDE / 2, SIDE / 2 - 8), (SIDE / 2 - 5, SIDE / 2 + 6), (SIDE / 2 + 5, SIDE / 2 + 6)],
        fill=(255, 255, 255),
    )
    sheet = Image.new("RGB", (frame_img.width + 8 + SIDE, SIDE), (255, 255, 255))
    sheet.paste(frame_img, (0, 0))
    sheet.paste(top_img, (frame_img.width + 8, 0))
    sheet.save(out, quality=88)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
