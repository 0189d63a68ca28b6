#!/usr/bin/env python3
"""Check a cityspec build's dataset-level COCO files (`[splits]`) with pycocotools.

usage: check_splits.py <output-folder>

For every <output-folder>/coco/<split>.json: pycocotools loads it; every image's
file_name (and depth.file_name) is a file of the output folder; annotation ids are
unique in the file. Over all the split files: image ids are unique, no frame is in two
splits, and every frame of every camera (frames/<camera>/coco.json) is in one split,
with the same number of annotations as its camera's document gives it.

Exits 0 when all hold, 1 with a message on the first failure, 2 on bad usage.
Needs: pycocotools.
"""

import contextlib
import io
import json
import sys
from pathlib import Path

from pycocotools.coco import COCO


def fail(message):
    print(f"check_splits: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    out = Path(sys.argv[1])
    splits = sorted((out / "coco").glob("*.json"))
    if not splits:
        fail(f"no {out}/coco/<split>.json")
    image_ids, files = set(), {}
    for path in splits:
        with contextlib.redirect_stdout(io.StringIO()):
            coco = COCO(str(path))
        anns = coco.dataset["annotations"]
        if len({a["id"] for a in anns}) != len(anns):
            fail(f"{path}: annotation ids repeat")
        for image in coco.dataset["images"]:
            if image["id"] in image_ids:
                fail(f"{path}: image id {image['id']} is in another split too")
            image_ids.add(image["id"])
            name = image["file_name"]
            if name in files:
                fail(f"{path}: {name} is in {files[name][0]} too")
            if not (out / name).is_file():
                fail(f"{path}: {name} is not a file of {out}")
            depth = image.get("depth")
            if depth and not (out / depth["file_name"]).is_file():
                fail(f"{path}: {depth['file_name']} is not a file of {out}")
            files[name] = (path.name, len(coco.getAnnIds(imgIds=[image["id"]])))
        print(f"{path.relative_to(out)}: {len(coco.dataset['images'])} images, "
              f"{len(anns)} annotations, {len(coco.dataset['categories'])} categories")
    for camera in sorted((out / "frames").iterdir()):
        doc = json.loads((camera / "coco.json").read_text())
        per_image = {}
        for a in doc["annotations"]:
            per_image[a["image_id"]] = per_image.get(a["image_id"], 0) + 1
        for image in doc["images"]:
            name = f"frames/{camera.name}/{image['file_name']}"
            if name not in files:
                fail(f"{name} is in no split")
            if files[name][1] != per_image.get(image["id"], 0):
                fail(f"{name}: {files[name][1]} annotations in {files[name][0]}, "
                     f"{per_image.get(image['id'], 0)} in its camera's coco.json")
    print(f"check_splits: {len(files)} frames, each in one split, ids unique")


if __name__ == "__main__":
    main()
