#!/usr/bin/env python3
"""Reads every ICDAR word quad of a built camera path with an off-the-shelf OCR model and
prints the share read exactly (case-insensitive).

    python3 -m venv /dev/shm/ocr && /dev/shm/ocr/bin/pip install rapidocr-onnxruntime
    /dev/shm/ocr/bin/python tests/external/ocr_words.py out/text/frames/words [--min-height 12]

Each word whose transcription is not `###` and whose quad is at least `--min-height` px
tall (the quad's left and right edge lengths, averaged) is cut from `rgb/` as the quad's
axis-aligned box grown by a quarter of its height, and given to RapidOCR's recogniser
(PP-OCRv4, trained on real photos) alone: detection is not measured, only whether the
pixels of a word a detector would box are legible. Not run by CI (it needs the model
package); it takes about a second per hundred words on one core.
"""

import argparse
import glob
import math
import os
import sys

import cv2
from rapidocr_onnxruntime import RapidOCR


def quads(gt_path):
    with open(gt_path, encoding="utf-8-sig") as f:
        for line in f:
            parts = line.rstrip("\n").split(",", 8)
            if len(parts) < 9:
                continue
            xs = [float(v) for v in parts[0:8:2]]
            ys = [float(v) for v in parts[1:8:2]]
            yield xs, ys, parts[8]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("path_dir", help="frames/<camera> folder of a build")
    ap.add_argument("--min-height", type=float, default=12.0)
    ap.add_argument("--show", type=int, default=15, help="misreads to print")
    args = ap.parse_args()
    engine = RapidOCR()
    total = exact = 0
    by_height = {}
    misses = []
    for gt in sorted(glob.glob(os.path.join(args.path_dir, "icdar", "gt_*.txt"))):
        frame = os.path.basename(gt)[3:-4]
        image = cv2.imread(os.path.join(args.path_dir, "rgb", frame + ".png"))
        if image is None:
            continue
        h_img, w_img = image.shape[:2]
        for xs, ys, word in quads(gt):
            if word == "###":
                continue
            left = math.hypot(xs[3] - xs[0], ys[3] - ys[0])
            right = math.hypot(xs[2] - xs[1], ys[2] - ys[1])
            height = (left + right) / 2
            if height < args.min_height:
                continue
            m = 0.25 * height
            x0, x1 = max(0, int(min(xs) - m)), min(w_img, int(math.ceil(max(xs) + m)))
            y0, y1 = max(0, int(min(ys) - m)), min(h_img, int(math.ceil(max(ys) + m)))
            if x1 - x0 < 2 or y1 - y0 < 2:
                continue
            crop = image[y0:y1, x0:x1]
            result, _ = engine(crop, use_det=False, use_cls=False, use_rec=True)
            read = result[0][0] if result else ""
            ok = read.strip().lower() == word.strip().lower()
            total += 1
            exact += ok
            bucket = min(int(height // 8) * 8, 48)
            n, k = by_height.get(bucket, (0, 0))
            by_height[bucket] = (n + 1, k + ok)
            if not ok and len(misses) < args.show:
                misses.append(f"  frame {frame}: {word!r} ({height:.0f} px) read {read!r}")
    if total == 0:
        print("no word quads at or above the height")
        return 1
    print(f"{exact} of {total} words >= {args.min_height:g} px read exactly: {exact / total:.1%}")
    for bucket in sorted(by_height):
        n, k = by_height[bucket]
        label = f"{bucket}+" if bucket == 48 else f"{bucket}-{bucket + 8}"
        print(f"  {label:>6} px: {k:4} of {n:4} ({k / n:.0%})")
    if misses:
        print("some misreads:")
        print("\n".join(misses))
    return 0


if __name__ == "__main__":
    sys.exit(main())
