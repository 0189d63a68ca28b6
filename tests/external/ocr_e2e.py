#!/usr/bin/env python3
"""Runs an off-the-shelf OCR system end to end on whole frames of a built camera path, as a
deployed reader would, and scores its line detections against the path's labels.

    python3 -m venv /dev/shm/ocr && /dev/shm/ocr/bin/pip install rapidocr-onnxruntime
    /dev/shm/ocr/bin/python tests/external/ocr_e2e.py out/text/frames/words [--json]

RapidOCR (PP-OCRv4 detector, then its recogniser; trained on real photos) reads every
`rgb/` frame. Its detections are line-level quadrilaterals with a transcription each. They
are matched to the ICDAR word quads of `icdar/gt_*.txt` by coverage, in pixels (both
polygons filled on the frame's pixel grid):

- a word is *found* when one detection polygon covers at least `--cover` (0.5) of the
  word quad's area;
- a word is *read* when it is found and the text of a detection that covers it (by that
  rule) contains the word, case-insensitive;
- a detection is *on text* when at least `--cover` of its area lies on labelled text: the
  union of the frame's word quads (`###` ones included) and of the pixels of its COCO text
  annotations (positives and `iscrowd` ignore regions alike; a COCO mask is exactly the
  `ids/` pixels of its `cityspec_instance`, so the ids image is read instead of decoding
  RLE), or when it finds a labelled word (covers `--cover` of its quad, `###` ones
  included: a detector's box round a small plate is larger than the plate). Precision is
  the share of detections on text. *latin* is the precision over the detections whose
  reading has a Latin letter or digit: every label is Latin script, and the recogniser
  reads a cross-barred window as `田`.

Only words at least `--min-height` px tall (the quad's left and right edges, averaged) and
not `###` count for found and read. As a diagnostic, the share of detections on any text
pixel (every instance of kind `text` or `street_name` in `instances.json`, labelled or
not) is printed too: a gap between the two is text the labels miss.

Not run by CI (it needs the model package); about 0.5-1 s a frame on one core.
"""

import argparse
import glob
import json
import math
import os
import sys

import cv2
import numpy as np
from rapidocr_onnxruntime import RapidOCR

from ocr_words import quads as icdar_lines

TEXT_KINDS = {"text", "street_name"}
EDGES = (0, 12, 16, 24, 32, 48)  # height buckets, px: [0, 12), [12, 16), ..., 48+


def quads(gt_path):
    """The ICDAR lines of `gt_path` as ([(x, y)] * 4, word), read by the crop measure's parser."""
    for xs, ys, word in icdar_lines(gt_path):
        yield list(zip(xs, ys)), word


def quad_height(pts):
    (x0, y0), (x1, y1), (x2, y2), (x3, y3) = pts
    return (math.hypot(x3 - x0, y3 - y0) + math.hypot(x2 - x1, y2 - y1)) / 2


def fill(shape, pts):
    """The polygon's pixels (centres inside it, as cv2.fillPoly draws at 1/256 px)."""
    mask = np.zeros(shape, np.uint8)
    poly = np.round(np.asarray(pts, np.float64) * 256).astype(np.int32)
    cv2.fillPoly(mask, [poly], 1, lineType=cv2.LINE_8, shift=8)
    return mask.astype(bool)


def read_ids(path):
    rgb = cv2.imread(path, cv2.IMREAD_COLOR)
    if rgb is None:
        return None
    rgb = rgb[:, :, ::-1].astype(np.uint32)
    return rgb[:, :, 0] + 256 * rgb[:, :, 1] + 65536 * rgb[:, :, 2]


def load_coco(path_dir):
    """Per image stem: the instance ids of its text annotations (positives and ignored)."""
    with open(os.path.join(path_dir, "coco.json"), encoding="utf-8") as f:
        coco = json.load(f)
    text_cats = {c["id"] for c in coco["categories"] if c["name"] in ("text", "word")}
    stems = {im["id"]: os.path.splitext(os.path.basename(im["file_name"]))[0] for im in coco["images"]}
    per_image = {}
    for a in coco["annotations"]:
        if a["category_id"] in text_cats and a.get("cityspec_instance") is not None:
            per_image.setdefault(stems[a["image_id"]], set()).add(a["cityspec_instance"])
    return per_image


def load_text_instances(path_dir):
    """Every instance id whose kind is text, labelled or not (instances.json)."""
    path = os.path.join(path_dir, "instances.json")
    if not os.path.exists(path):
        return set()
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    entries = data.get("instances", data) if isinstance(data, dict) else data
    ids = set()
    for i, e in enumerate(entries):
        if isinstance(e, dict) and e.get("kind") in TEXT_KINDS:
            ids.add(e.get("id", i + 1))
    return ids


def score_frame(engine, path_dir, frame, coco_ids, any_text_ids, args, tally, examples):
    image = cv2.imread(os.path.join(path_dir, "rgb", frame + ".png"))
    ids = read_ids(os.path.join(path_dir, "ids", frame + ".png"))
    if image is None or ids is None:
        return
    shape = image.shape[:2]
    words = list(quads(os.path.join(path_dir, "icdar", f"gt_{frame}.txt")))
    result, _ = engine(image)
    dets = [(fill(shape, box), text, conf) for box, text, conf in (result or [])]

    labelled = np.isin(ids, list(coco_ids.get(frame, ()))) if coco_ids.get(frame) else np.zeros(shape, bool)
    for pts, _ in words:
        labelled |= fill(shape, pts)
    any_text = labelled | np.isin(ids, list(any_text_ids)) if any_text_ids else labelled
    word_masks = [m for m in (fill(shape, pts) for pts, _ in words) if m.any()]
    for mask, text, _ in dets:
        area = mask.sum()
        if area == 0:
            continue
        tally["dets"] += 1
        # On text: mostly on labelled pixels, or it finds a labelled word (covers `cover` of
        # its quad, `###` included), as ICDAR's matching counts it: a detector's box round a
        # small plate is larger than the plate.
        finds = any((mask & q).sum() / q.sum() >= args.cover for q in word_masks)
        on = bool((mask & labelled).sum() / area >= args.cover) or finds
        tally["on_text"] += int(on)
        tally["on_any_text"] += int(finds or (mask & any_text).sum() / area >= args.cover)
        latin = any(c.isascii() and c.isalnum() for c in text)
        tally["latin"] += int(latin)
        tally["latin_on_text"] += int(latin and on)
        if not on and len(examples["false"]) < args.show:
            examples["false"].append(f"  frame {frame}: detection {text!r} off labelled text")

    for pts, word in words:
        if word == "###":
            continue
        height = quad_height(pts)
        if height < args.min_height:
            continue
        qmask = fill(shape, pts)
        qarea = qmask.sum()
        if qarea == 0:
            continue
        covering = [t for m, t, _ in dets if (m & qmask).sum() / qarea >= args.cover]
        found = bool(covering)
        read = any(word.strip().lower() in t.lower() for t in covering)
        bucket = max(e for e in EDGES if e <= max(height, EDGES[0]))
        b = tally["by_height"].setdefault(bucket, [0, 0, 0])
        b[0] += 1
        b[1] += int(found)
        b[2] += int(read)
        tally["words"] += 1
        tally["found"] += int(found)
        tally["read"] += int(read)
        if not found and len(examples["missed"]) < args.show:
            examples["missed"].append(f"  frame {frame}: {word!r} ({height:.0f} px) not found")
        elif found and not read and len(examples["misread"]) < args.show:
            examples["misread"].append(f"  frame {frame}: {word!r} ({height:.0f} px) in {covering!r}")


def pct(k, n):
    return 100.0 * k / n if n else None


def show(v, width):
    return f"{v:>{width - 1}.1f}%" if v is not None else f"{'-':>{width}}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("path_dirs", nargs="+", help="frames/<camera> folders of a build")
    ap.add_argument("--min-height", type=float, default=12.0)
    ap.add_argument("--cover", type=float, default=0.5, help="coverage share for found and on-text")
    ap.add_argument("--frames", type=int, default=0, help="at most this many frames a path (0: all)")
    ap.add_argument("--show", type=int, default=0, help="examples of misses to print")
    ap.add_argument("--json", action="store_true", help="print one JSON object instead of the table")
    args = ap.parse_args()
    engine = RapidOCR()
    report = {}
    for path_dir in args.path_dirs:
        gts = sorted(glob.glob(os.path.join(path_dir, "icdar", "gt_*.txt")))
        if not gts:
            print(f"error: no icdar/gt_*.txt under {path_dir}", file=sys.stderr)
            return 2
        if args.frames:
            gts = gts[: args.frames]
        coco_ids = load_coco(path_dir)
        any_text_ids = load_text_instances(path_dir)
        tally = {"frames": 0, "words": 0, "found": 0, "read": 0, "dets": 0, "on_text": 0,
                 "on_any_text": 0, "latin": 0, "latin_on_text": 0, "by_height": {}}
        examples = {"missed": [], "misread": [], "false": []}
        for gt in gts:
            frame = os.path.basename(gt)[3:-4]
            tally["frames"] += 1
            score_frame(engine, path_dir, frame, coco_ids, any_text_ids, args, tally, examples)
        tally["found_pct"] = pct(tally["found"], tally["words"])
        tally["read_pct"] = pct(tally["read"], tally["words"])
        tally["precision_pct"] = pct(tally["on_text"], tally["dets"])
        tally["on_any_text_pct"] = pct(tally["on_any_text"], tally["dets"])
        tally["latin_precision_pct"] = pct(tally["latin_on_text"], tally["latin"])
        tally["by_height"] = {str(k): v for k, v in sorted(tally["by_height"].items())}
        report[path_dir] = tally
        if not args.json and args.show:
            for kind, lines in examples.items():
                if lines:
                    print(f"{path_dir}: {kind}")
                    print("\n".join(lines))
    if args.json:
        print(json.dumps({"min_height": args.min_height, "cover": args.cover, "paths": report}, indent=1))
        return 0
    print(f"words >= {args.min_height:g} px (not ###); found: a detection covers >= {args.cover:.0%} "
          f"of the quad; read: found and its line text contains the word")
    print(f"{'path':<40} {'frames':>6} {'words':>6} {'found':>7} {'read':>7} {'dets':>6} {'precision':>9} {'any text':>8} {'latin':>7}")
    for path_dir, t in report.items():
        print(f"{path_dir:<40} {t['frames']:>6} {t['words']:>6} {show(t['found_pct'], 7)} {show(t['read_pct'], 7)} "
              f"{t['dets']:>6} {show(t['precision_pct'], 9)} {show(t['on_any_text_pct'], 8)} {show(t['latin_precision_pct'], 7)}")
        for bucket, (n, f, r) in t["by_height"].items():
            b = EDGES.index(int(bucket))
            label = f"{EDGES[b]}+" if b + 1 == len(EDGES) else f"{EDGES[b]}-{EDGES[b + 1]}"
            print(f"  {label:>6} px: {n:5} words, found {show(pct(f, n), 6)}, read {show(pct(r, n), 6)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
