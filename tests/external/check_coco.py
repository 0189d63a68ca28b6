#!/usr/bin/env python3
"""Check a cityspec COCO file with pycocotools against its instance-id images.

usage: check_coco.py <coco.json> <instance-png-folder>

The instance image of an image entry is <instance-png-folder>/<stem of file_name>.png: an
8-bit RGB PNG packing 24-bit ids as COCO panoptic does, id = R + 256*G + 256**2*B
(0 = background, k = object index + 1, the annotation's `cityspec_instance`). A 16-bit
grayscale PNG (cityspec before ids were packed) is read as the ids directly. Checks, in
order:

1. pycocotools loads the file;
2. every annotation's bbox is the tight box [x, y, w, h] of the pixels of its instance,
   its area is their count, iscrowd is 0 or 1 (1: an ignore region, an object under the
   thresholds), and its RLE segmentation decodes to exactly those pixels and is,
   character for character, what maskUtils.encode makes of them;
3. every annotation's full_bbox (the box of the pixels the object would cover with nothing
   in front) contains its bbox, and its visible_fraction lies in (0, 1] (both may be null
   on an ignore region);
4. an image entry's `depth`, when given, names a file beside the COCO file that reads as
   height x width (a 16-bit PNG, or a .npy of float32 metres), with a positive `scale`;
5. the `word` annotations (category `word`: a text object's words, beside its plate) are
   checked apart from 2-3: an RLE of the image's size whose pixels lie on their plate's
   (a positive word; a hidden one, a crowd region, may cover what hides it), bbox its mask's
   tight box and area its pixel count, inside the bbox of their plate (the annotation of
   the same image and `cityspec_instance`), `text` is a string, and `iscrowd` is 1
   exactly where `cityspec_ignored` says why;
6. when there are annotations, COCOeval of the ground truth against itself (every
   annotation as a detection with score 1) gives AP 1.0 for bbox and for segm, the
   ignore regions matched and ignored as pycocotools does with iscrowd.

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


def read_ids(path):
    """Instance ids of an ids PNG: RGB-packed (id = R + 256 G + 256^2 B), or 16-bit grey."""
    arr = np.array(Image.open(path))
    if arr.ndim == 3:
        arr = arr[..., :3].astype(np.uint32)
        return arr[..., 0] + (arr[..., 1] << 8) + (arr[..., 2] << 16)
    return arr.astype(np.uint32)


def check_depth(img, base):
    depth = img.get("depth")
    if depth is None:
        return
    where = f"image {img['id']}: depth {depth}"
    if not (isinstance(depth.get("scale"), (int, float)) and depth["scale"] > 0):
        raise CheckFailed(f"{where}: scale is not a positive number")
    path = os.path.join(base, depth["file_name"])
    try:
        if path.endswith(".npy"):
            arr = np.load(path)
            if arr.dtype != np.float32:
                raise CheckFailed(f"{where}: {path} holds {arr.dtype}, not float32")
        else:
            arr = np.array(Image.open(path))
            if arr.dtype != np.uint16:
                raise CheckFailed(f"{where}: {path} holds {arr.dtype}, not 16-bit")
    except (OSError, ValueError) as e:
        raise CheckFailed(f"{where}: cannot read {path}: {e}")
    if arr.shape != (img["height"], img["width"]):
        raise CheckFailed(f"{where}: {path} is {arr.shape}, not {img['height']}x{img['width']}")


def check_box_and_area(ann, mask, where):
    """The annotation's bbox is the tight box of `mask` and its area the mask's pixel count."""
    ys, xs = np.nonzero(mask)
    if len(xs) == 0:
        raise CheckFailed(f"{where}: an empty mask")
    x0, y0 = int(xs.min()), int(ys.min())
    tight = [x0, y0, int(xs.max()) - x0 + 1, int(ys.max()) - y0 + 1]
    if [float(v) for v in ann["bbox"]] != [float(v) for v in tight]:
        raise CheckFailed(f"{where}: bbox {ann['bbox']} is not the tight box {tight}")
    if ann["area"] != int(mask.sum()):
        raise CheckFailed(f"{where}: area {ann['area']} but {int(mask.sum())} pixels")


def check_word(gt, ann, img, where, words, ids):
    seg = ann["segmentation"]
    if not (isinstance(seg, dict) and seg.get("size") == [img["height"], img["width"]]):
        raise CheckFailed(f"{where}: a word's segmentation is not an RLE of the image's size: {seg}")
    mask = gt.annToMask(ann).astype(bool)
    check_box_and_area(ann, mask, f"{where}: word")
    # A word shows where its plate shows (or, hidden, is a crowd region of its quad).
    on_plate = ids[mask] == ann["cityspec_instance"]
    if ann["iscrowd"] == 0 and not on_plate.all():
        raise CheckFailed(f"{where}: a positive word covers {int((~on_plate).sum())} pixels off its plate")
    plates = [
        a
        for a in gt.imgToAnns[img["id"]]
        if a["cityspec_instance"] == ann["cityspec_instance"] and a["category_id"] not in words
    ]
    if len(plates) != 1:
        raise CheckFailed(f"{where}: a word with {len(plates)} plate annotations, not 1")
    px, py, pw, ph = plates[0]["bbox"]
    bx, by, bw, bh = ann["bbox"]
    if not (px <= bx and py <= by and bx + bw <= px + pw and by + bh <= py + ph):
        raise CheckFailed(f"{where}: word bbox {ann['bbox']} is not inside its plate's {plates[0]['bbox']}")
    if not isinstance(ann.get("text"), str):
        raise CheckFailed(f"{where}: a word without its text")
    if ann["iscrowd"] not in (0, 1) or (ann["iscrowd"] == 1) != ("cityspec_ignored" in ann):
        raise CheckFailed(f"{where}: iscrowd {ann['iscrowd']} but cityspec_ignored {ann.get('cityspec_ignored')!r}")


def check_pixels(gt, folder, base):
    words = {c["id"] for c in gt.dataset["categories"] if c["name"] == "word"}
    for img in gt.dataset["images"]:
        check_depth(img, base)
        path = instance_path(folder, img["file_name"])
        try:
            ids = read_ids(path)
        except OSError as e:
            raise CheckFailed(f"image {img['id']}: cannot read instance image {path}: {e}")
        if ids.shape != (img["height"], img["width"]):
            raise CheckFailed(
                f"image {img['id']}: instance image {path} is {ids.shape[1]}x{ids.shape[0]}, "
                f"the entry says {img['width']}x{img['height']}"
            )
        for ann in gt.imgToAnns[img["id"]]:
            where = f"annotation {ann['id']} (image {img['id']}, instance {ann['cityspec_instance']})"
            if ann["category_id"] in words:
                check_word(gt, ann, img, where, words, ids)
                continue
            mask = ids == ann["cityspec_instance"]
            if not mask.any():
                raise CheckFailed(f"{where}: no pixel of that instance in {path}")
            check_box_and_area(ann, mask, where)
            crowd = ann.get("iscrowd")
            if crowd not in (0, 1):
                raise CheckFailed(f"{where}: iscrowd is {crowd!r}, not 0 or 1")
            try:
                decoded = gt.annToMask(ann).astype(bool)
            except Exception as e:  # pycocotools raises ValueError or KeyError on bad RLE
                raise CheckFailed(f"{where}: segmentation does not decode: {e}")
            if decoded.shape != mask.shape or not np.array_equal(decoded, mask):
                raise CheckFailed(f"{where}: segmentation does not decode to its pixels")
            full, fraction = ann.get("full_bbox"), ann.get("visible_fraction")
            if crowd == 0 and (full is None or fraction is None):
                raise CheckFailed(f"{where}: full_bbox or visible_fraction is missing")
            if full is not None:
                fx, fy, fw, fh = full
                bx, by, bw, bh = ann["bbox"]
                if not (fx <= bx and fy <= by and bx + bw <= fx + fw and by + bh <= fy + fh):
                    raise CheckFailed(f"{where}: bbox {ann['bbox']} is not inside full_bbox {full}")
            if fraction is not None and not 0.0 < fraction <= 1.0:
                raise CheckFailed(f"{where}: visible_fraction {fraction} is not in (0, 1]")
            expected = mask_utils.encode(np.asfortranarray(mask.astype(np.uint8)))
            if ann["segmentation"] != {"size": expected["size"], "counts": expected["counts"].decode()}:
                raise CheckFailed(f"{where}: segmentation is not what maskUtils.encode gives")


def check_self_eval(gt):
    # The regular annotations as detections; ignore regions stay ground truth only (a
    # detection on one is neither a hit nor a false positive).
    anns = [a for a in gt.dataset["annotations"] if a["iscrowd"] == 0]
    most = max(len(v) for v in gt.imgToAnns.values())
    results = {}
    for iou_type, key in (("bbox", "bbox"), ("segm", "segmentation")):
        dets = [
            {
                "image_id": a["image_id"],
                "category_id": a["category_id"],
                # Words are polygons; loadRes reads segmentations as RLE.
                key: gt.annToRLE(a) if key == "segmentation" else a[key],
                "score": 1.0,
            }
            for a in anns
        ]
        dt = quietly(gt.loadRes, dets)
        ev = COCOeval(gt, dt, iou_type)
        ev.params.maxDets = [1, 10, max(100, most)]
        # Only the "all" area range, the one read below: evaluateImg runs once per range,
        # and it is most of this script's time (84 s of an aerial path's 12 images).
        ev.params.areaRng = ev.params.areaRng[:1]
        ev.params.areaRngLbl = ev.params.areaRngLbl[:1]
        quietly(ev.evaluate)
        quietly(ev.accumulate)
        # AP at IoU .50:.95 over all areas at the largest maxDets, as summarize() computes
        # stats[0] but without its fixed maxDets=100 (with more detections in an image,
        # summarize finds no matching maxDets column and reports -1).
        precision = ev.eval["precision"][:, :, :, 0, -1]
        valid = precision[precision > -1]
        ap = float(np.mean(valid)) if valid.size else -1.0
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
        check_pixels(gt, folder, os.path.dirname(os.path.abspath(coco_path)))
        regular = [a for a in gt.dataset["annotations"] if a["iscrowd"] == 0]
        aps = check_self_eval(gt) if regular else {}
    except CheckFailed as e:
        print(f"check_coco: {coco_path}: {e}", file=sys.stderr)
        return 1
    summary = ", ".join(f"AP {k} {v:.1f}" for k, v in aps.items()) or "no annotations"
    crowd = sum(1 for a in gt.dataset["annotations"] if a["iscrowd"] == 1)
    print(
        f"check_coco: {coco_path}: ok: {len(gt.dataset['images'])} images, "
        f"{len(gt.dataset['annotations']) - crowd} annotations and {crowd} ignore regions, "
        f"{summary}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
