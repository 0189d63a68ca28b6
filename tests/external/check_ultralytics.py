#!/usr/bin/env python3
"""Train ultralytics on a cityspec build's yolo/ folder: every label found, one epoch.

usage: check_ultralytics.py <output-folder> [--epochs N] [--imgsz N]

Copies <output-folder>/yolo/ to a temporary folder (ultralytics writes label caches
beside the labels), then:

1. `check_det_dataset` reads data.yaml: its train/val folders exist, its names are
   yolo's classes;
2. the train and val datasets (`YOLODataset`, as training builds them) find a label
   file for every image, and hold exactly the boxes the label files have (no "missing"
   label, none corrupt);
3. `YOLO("yolov8n.yaml")` (no weights to download) trains one epoch on the CPU at
   imgsz 128 and validates.

Offline: no weights, no fonts (plots off), no hub. Exits 0 when all hold, 1 with a
message on the first failure, 2 on bad usage. Not run by CI (torch is a large install);
needs: ultralytics (and torch).
"""

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("YOLO_OFFLINE", "1")


def fail(message):
    print(f"check_ultralytics: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("--epochs", type=int, default=1)
    parser.add_argument("--imgsz", type=int, default=128)
    args = parser.parse_args()
    from ultralytics import YOLO, settings
    from ultralytics.data.dataset import YOLODataset
    from ultralytics.data.utils import check_det_dataset

    settings.update({"sync": False})
    with tempfile.TemporaryDirectory() as tmp:
        yolo = Path(tmp) / "yolo"
        shutil.copytree(Path(args.out) / "yolo", yolo)
        data = check_det_dataset(str(yolo / "data.yaml"))
        print(f"check_det_dataset: {data['nc']} classes {list(data['names'].values())}, "
              f"train {data['train']}, val {data['val']}")
        for split in ("train", "val"):
            images = sorted(Path(data[split]).glob("*.png"))
            labels = [Path(str(i).replace("/images/", "/labels/")).with_suffix(".txt") for i in images]
            boxes = sum(len(l.read_text().splitlines()) for l in labels if l.exists())
            dataset = YOLODataset(img_path=data[split], data=data, task="detect", imgsz=args.imgsz, augment=False)
            found = sum(len(label["cls"]) for label in dataset.labels)
            missing = sum(not l.exists() for l in labels)
            print(f"{split}: {len(images)} images, {len(dataset.labels)} read, {boxes} boxes in "
                  f"the label files, {found} found by ultralytics, {missing} label files missing")
            if missing or len(dataset.labels) != len(images) or found != boxes:
                fail(f"{split}: ultralytics did not find every label")
            if found == 0 and split == "train":
                fail("train: no box at all")
        start = time.time()
        model = YOLO("yolov8n.yaml")
        model.train(data=str(yolo / "data.yaml"), epochs=args.epochs, imgsz=args.imgsz,
                    device="cpu", workers=0, plots=False, amp=False, project=tmp,
                    name="train", exist_ok=True, verbose=False)
        print(f"check_ultralytics: trained {args.epochs} epoch(s) at imgsz {args.imgsz} "
              f"in {time.time() - start:.1f} s")


if __name__ == "__main__":
    main()
