#!/usr/bin/env python3
"""Draws assets/readme/normals.jpg: a street frame beside its surface normals.

usage: normals.py <frames/<camera> folder> <out.jpg> <frame number>

    cityspec build specs/sensors.toml --out OUT && python3 assets/readme/normals.py \\
        OUT/sensors/frames/street assets/readme/normals.jpg 8

Needs Pillow. The normals PNG is 16-bit RGB (n = value / 65535 * 2 - 1, camera axes x
right, y down, z forward); Pillow reads its high bytes, which is what a picture needs:
red, green and blue are x, y and z from -1 to 1, so the road (normal up, -y, and a little
towards the camera) is purple, a wall facing the camera's left green, the sky black.
"""

import sys
from pathlib import Path

from PIL import Image

SIZE = (320, 240)


def main():
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    folder, out, frame = Path(sys.argv[1]), sys.argv[2], int(sys.argv[3])
    rgb = Image.open(folder / "rgb" / f"{frame:06d}.png").convert("RGB")
    normals = Image.open(folder / "normals" / f"{frame:06d}.png").convert("RGB")
    sheet = Image.new("RGB", (SIZE[0] * 2, SIZE[1]))
    sheet.paste(rgb.resize(SIZE, Image.LANCZOS), (0, 0))
    sheet.paste(normals.resize(SIZE, Image.NEAREST), (SIZE[0], 0))
    sheet.save(out, quality=85)
    return 0


if __name__ == "__main__":
    sys.exit(main())
