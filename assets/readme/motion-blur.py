#!/usr/bin/env python3
"""Draws assets/readme/motion-blur.jpg: one frame of a timed drive through moving traffic
(`[traffic]`) without and with motion blur over the shutter, side by side. With a
shutter, the world streaks past the moving camera, and a car driving beside it at its
speed stays sharp, as it would in a photograph.

usage: motion-blur.py <sharp frames/<camera> folder> <blurred folder> <frame> <out.jpg>

    cityspec build specs/drive.toml --set cameras.street.frames=12 --out SHARP
    cityspec build specs/drive.toml --set cameras.street.frames=12 \\
        --set cameras.street.sensor.motion_blur=0.5 --out BLURRED
    python3 assets/readme/motion-blur.py SHARP/drive/frames/street \\
        BLURRED/drive/frames/street 11 assets/readme/motion-blur.jpg

(the picture: 0.5 m at the drive's 30 km/h, a 60 ms shutter).

Needs Pillow.
"""

import sys
from pathlib import Path

from PIL import Image, ImageDraw

WIDTH = 400  # each panel's width, px


def main(sharp, blurred, frame, out):
    name = f"rgb/{int(frame):06d}.png"
    panels = [Image.open(Path(folder) / name).convert("RGB") for folder in (sharp, blurred)]
    height = panels[0].height * WIDTH // panels[0].width
    sheet = Image.new("RGB", (2 * WIDTH, height), "white")
    for k, (panel, label) in enumerate(zip(panels, ["no blur", "motion_blur = 0.5"])):
        sheet.paste(panel.resize((WIDTH, height), Image.LANCZOS), (k * WIDTH, 0))
        draw = ImageDraw.Draw(sheet)
        draw.rectangle([k * WIDTH + 4, 4, k * WIDTH + 8 + 7 * len(label), 20], fill="black")
        draw.text((k * WIDTH + 7, 6), label, fill="white")
    sheet.save(out, quality=85)


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
