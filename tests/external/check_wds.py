"""Reads a camera path's WebDataset tars with the `webdataset` package and checks every
sample against the path's COCO file: one sample per COCO image, in order; the sample's
JSON holds that image entry and exactly its annotations; its RGB and ids images decode to
the image's size; every box lies inside the image.

    python check_wds.py frames/<camera>/coco.json frames/<camera>/wds/*.tar
"""

import io
import json
import sys

import webdataset as wds
from PIL import Image


def main(coco_path, tars):
    coco = json.load(open(coco_path))
    images = coco["images"]
    by_image = {}
    for ann in coco["annotations"]:
        by_image.setdefault(ann["image_id"], []).append(ann)
    dataset = wds.WebDataset(sorted(tars), shardshuffle=False, empty_check=False)
    seen = 0
    for sample in dataset:
        assert seen < len(images), f"more samples than the {len(images)} COCO images"
        image = images[seen]
        key = sample["__key__"]
        assert key == f"{seen:06d}", f"sample {seen} has key {key}"
        meta = json.loads(sample["json"])
        assert meta["image"] == image, f"{key}: image entry differs from COCO"
        assert meta["annotations"] == by_image.get(image["id"], []), f"{key}: annotations differ"
        for kind in ("rgb.png", "ids.png"):
            picture = Image.open(io.BytesIO(sample[kind]))
            assert picture.size == (image["width"], image["height"]), f"{key}.{kind}: size"
        assert "depth.png" in sample or "depth.npy" in sample, f"{key}: no depth"
        for ann in meta["annotations"]:
            x, y, w, h = ann["bbox"]
            assert 0 <= x and 0 <= y and x + w <= image["width"] and y + h <= image["height"]
        seen += 1
    assert seen == len(images), f"{seen} samples for {len(images)} COCO images"
    print(f"{coco_path}: {seen} WebDataset samples match COCO ({len(coco['annotations'])} annotations)")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
