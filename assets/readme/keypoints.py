#!/usr/bin/env python3
"""Draws assets/readme/keypoints.jpg: a crop of a street frame with every person's and
rider's COCO keypoints and skeleton from its coco.json (visible joints solid, hidden ones
hollow and their limbs dim).

usage: keypoints.py <frames/<camera> folder> <out.jpg> <image id>

    cityspec build specs/sensors.toml --out OUT && python3 assets/readme/keypoints.py \\
        OUT/sensors/frames/street assets/readme/keypoints.jpg 20

Needs Pillow. The crop is 320 x 180 px of the frame, scaled 2x, placed where the most
of the frame's annotated people (by their height) fit in it.
"""

import json
import sys
from pathlib import Path

from PIL import Image, ImageDraw

CROP = (320, 180)
SCALE = 2
# Limb colours by side: left (odd COCO numbers from the shoulders down), right, middle.
LEFT, RIGHT, MIDDLE = (60, 170, 255), (255, 140, 30), (120, 230, 120)


def limb_colour(a, b):
    sides = {(i - 6) % 2 if i >= 6 else None for i in (a, b)}
    if sides == {0} or a in (2, 4) or b in (2, 4):
        return LEFT
    if sides == {1} or a in (3, 5) or b in (3, 5):
        return RIGHT
    return MIDDLE


def crop_origin(people, width, height):
    """The crop's top-left that holds the most of `people`'s box heights."""
    best, origin = -1, (0, 0)
    for a in people:
        x, y, w, h = a["bbox"]
        left = min(max(int(x + w / 2 - CROP[0] / 2), 0), width - CROP[0])
        top = min(max(int(y + h / 2 - CROP[1] / 2), 0), height - CROP[1])
        inside = sum(
            b["bbox"][3]
            for b in people
            if left <= b["bbox"][0] and b["bbox"][0] + b["bbox"][2] <= left + CROP[0]
            and top <= b["bbox"][1] and b["bbox"][1] + b["bbox"][3] <= top + CROP[1]
        )
        if inside > best:
            best, origin = inside, (left, top)
    return origin


def main(folder, out, image_id):
    folder = Path(folder)
    coco = json.loads((folder / "coco.json").read_text())
    skeleton = next(c["skeleton"] for c in coco["categories"] if "skeleton" in c)
    people = {}
    for a in coco["annotations"]:
        if a.get("num_keypoints", 0) > 0:
            people.setdefault(a["image_id"], []).append(a)
    images = {i["id"]: i for i in coco["images"]}
    image = images[image_id]
    left, top = crop_origin(people[image_id], image["width"], image["height"])
    frame = Image.open(folder / image["file_name"]).convert("RGB")
    crop = frame.crop((left, top, left + CROP[0], top + CROP[1]))
    crop = crop.resize((CROP[0] * SCALE, CROP[1] * SCALE), Image.LANCZOS)
    draw = ImageDraw.Draw(crop)

    def at(k, i):
        return ((k[3 * i] - left) * SCALE, (k[3 * i + 1] - top) * SCALE)

    for a in people[image_id]:
        k = a["keypoints"]
        for p, q in skeleton:
            va, vb = k[3 * p - 1], k[3 * q - 1]
            if va == 0 or vb == 0:
                continue
            colour = limb_colour(p, q)
            if min(va, vb) < 2:
                colour = tuple(c // 3 for c in colour)
            draw.line([at(k, p - 1), at(k, q - 1)], fill=colour, width=2)
        for i in range(17):
            v = k[3 * i + 2]
            if v == 0:
                continue
            x, y = at(k, i)
            r = 2.5
            if v == 2:
                draw.ellipse([x - r, y - r, x + r, y + r], fill=(255, 255, 255))
            else:
                draw.ellipse([x - r, y - r, x + r, y + r], outline=(150, 150, 150))
    crop.save(out, quality=85, optimize=True)
    print(f"{out}: image {image_id}, crop at ({left}, {top}), {len(people[image_id])} people")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
