#!/usr/bin/env python3
"""Check a cityspec COCO file with pycocotools against its instance-id images.

usage: check_coco.py <coco.json> <instance-png-folder>

The instance image of an image entry is <instance-png-folder>/<stem of file_name>.png: a
16-bit grayscale PNG, 0 = background, k = object index + 1 (the annotation's
`instance_id`). Checks, in order:

1. pycocotools loads the file;
2. every annotation's bbox is the tight box [x, y, w, h] of the pixels of its instance,
   its area is their count, iscrowd is 0, and its RLE segmentation decodes to exactly
   those pixels and is, character for character, what maskUtils.encode makes of them;
3. every annotation's full_bbox (the box of the pixels the object would cover with nothing
   in front) contains its bbox, and its visible_fraction lies in (0, 1];
4. when there are annotations, COCOeval of the ground truth against itself (every
   annotation as a detection with score 1) gives AP 1.0 for bbox and for segm.

Exits 0 when all hold, 1 with a message on the first failure, 2 on bad usage.
Needs: pycocotools, numpy, pillow.
"""

import contextlib
import io
import os
import sys

import numpy as np
from PIL import Image
from pycocotools import mask as mask_utils
from pycocotools.coco import COCO
from pycocotools.cocoeval import COCOeval


class CheckFailed(Exception):
    pass


def quietly(fn, *args):
    """pycocotools prints progress on stdout; keep it for failures only."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        return fn(*args)


def instance_path(folder, file_name):
    stem = os.path.splitext(os.path.basename(file_name))[0]
    return os.path.join(folder, stem + ".png")


def check_pixels(gt, folder):
    for img in gt.dataset["images"]:
        path = instance_path(folder, img["file_name"])
        try:
            ids = np.array(Image.open(path))
        except OSError as e:
            raise CheckFailed(f"image {img['id']}: cannot read instance image {path}: {e}")
        if ids.shape != (img["height"], img["width"]):
            raise CheckFailed(
                f"image {img['id']}: instance image {path} is {ids.shape[1]}x{ids.shape[0]}, "
                f"the entry says {img['width']}x{img['height']}"
            )
        for ann in gt.imgToAnns[img["id"]]:
            where = f"annotation {ann['id']} (image {img['id']}, instance {ann['instance_id']})"
            mask = ids == ann["instance_id"]
            ys, xs = np.nonzero(mask)
            if len(xs) == 0:
                raise CheckFailed(f"{where}: no pixel of that instance in {path}")
            x0, y0 = int(xs.min()), int(ys.min())
            tight = [x0, y0, int(xs.max()) - x0 + 1, int(ys.max()) - y0 + 1]
            if [float(v) for v in ann["bbox"]] != [float(v) for v in tight]:
                raise CheckFailed(f"{where}: bbox {ann['bbox']} is not the tight box {tight}")
            if ann["area"] != int(mask.sum()):
                raise CheckFailed(f"{where}: area {ann['area']} but {int(mask.sum())} pixels")
            if ann.get("iscrowd") != 0:
                raise CheckFailed(f"{where}: iscrowd is {ann.get('iscrowd')!r}, not 0")
            try:
                decoded = gt.annToMask(ann).astype(bool)
            except Exception as e:  # pycocotools raises ValueError or KeyError on bad RLE
                raise CheckFailed(f"{where}: segmentation does not decode: {e}")
            if decoded.shape != mask.shape or not np.array_equal(decoded, mask):
                raise CheckFailed(f"{where}: segmentation does not decode to its pixels")
            full, fraction = ann.get("full_bbox"), ann.get("visible_fraction")
            if full is None or fraction is None:
                raise CheckFailed(f"{where}: full_bbox or visible_fraction is missing")
            fx, fy, fw, fh = full
            bx, by, bw, bh = ann["bbox"]
            if not (fx <= bx and fy <= by and bx + bw <= fx + fw and by + bh <= fy + fh):
                raise CheckFailed(f"{where}: bbox {ann['bbox']} is not inside full_bbox {full}")
            if not 0.0 < fraction <= 1.0:
                raise CheckFailed(f"{where}: visible_fraction {fraction} is not in (0, 1]")
            expected = mask_utils.encode(np.asfortranarray(mask.astype(np.uint8)))
            if ann["segmentation"] != {"size": expected["size"], "counts": expected["counts"].decode()}:
                raise CheckFailed(f"{where}: segmentation is not what maskUtils.encode gives")


def check_self_eval(gt):
    anns = gt.dataset["annotations"]
    most = max(len(v) for v in gt.imgToAnns.values())
    results = {}
    for iou_type, key in (("bbox", "bbox"), ("segm", "segmentation")):
        dets = [
            {
                "image_id": a["image_id"],
                "category_id": a["category_id"],
                key: a[key],
                "score": 1.0,
            }
            for a in anns
        ]
        dt = quietly(gt.loadRes, dets)
        ev = COCOeval(gt, dt, iou_type)
        ev.params.maxDets = [1, 10, max(100, most)]
        quietly(ev.evaluate)
        quietly(ev.accumulate)
        quietly(ev.summarize)
        ap = float(ev.stats[0])
        if abs(ap - 1.0) > 1e-12:
            raise CheckFailed(f"COCOeval {iou_type} of the ground truth against itself: AP {ap}, not 1.0")
        results[iou_type] = ap
    return results


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    coco_path, folder = argv[1], argv[2]
    try:
        try:
            gt = quietly(COCO, coco_path)
        except Exception as e:  # pycocotools raises whatever json or its asserts raise
            raise CheckFailed(f"pycocotools cannot load it: {type(e).__name__}: {e}")
        check_pixels(gt, folder)
        aps = check_self_eval(gt) if gt.dataset["annotations"] else {}
    except CheckFailed as e:
        print(f"check_coco: {coco_path}: {e}", file=sys.stderr)
        return 1
    summary = ", ".join(f"AP {k} {v:.1f}" for k, v in aps.items()) or "no annotations"
    print(
        f"check_coco: {coco_path}: ok: {len(gt.dataset['images'])} images, "
        f"{len(gt.dataset['annotations'])} annotations, {summary}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
