#!/usr/bin/env python3
"""Train torchvision's Faster R-CNN a few steps on a cityspec build's coco/<split>.json, on the CPU.

usage: train_torchvision.py <output-folder> [--split train] [--steps 4] [--batch 2]

Reads the split with the plain `torchvision.datasets.CocoDetection(root=OUT,
annFile=OUT/coco/<split>.json)` (`file_name` is relative to the output folder), turns
each image's annotations into a detection target (COCO `[x, y, w, h]` to `[x1, y1, x2,
y2]`, `category_id` as the label, 0 being the background; `iscrowd: 1` annotations are
cityspec's ignore regions, too small or too hidden to be objects, and are left out), and
runs `--steps` SGD steps of `fasterrcnn_mobilenet_v3_large_320_fpn(weights=None,
weights_backbone=None)` (no weights to download).

Checks, so it can fail: the dataset has one item per image of the file, every item
loads at the image's own width and height, the targets hold exactly the file's non-crowd
annotations of those images, every box has a positive size, and every step's losses are
finite. Exits 0 when all hold, 1 with a message on the first failure. Not run by CI
(torch is a large install: about 6 GB with PyPI's default CUDA wheels); by hand:

    python3 -m venv /tmp/trainvenv
    /tmp/trainvenv/bin/pip install torch torchvision pycocotools
    /tmp/trainvenv/bin/python tests/external/train_torchvision.py out/day
"""

import argparse
import json
import math
import sys
import time
from pathlib import Path


def fail(message):
    print(f"train_torchvision: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("--split", default="train")
    parser.add_argument("--steps", type=int, default=4)
    parser.add_argument("--batch", type=int, default=2)
    args = parser.parse_args()
    import torch
    import torchvision
    from torchvision.transforms.functional import to_tensor

    out = Path(args.out)
    ann_file = out / "coco" / f"{args.split}.json"
    doc = json.loads(ann_file.read_text())
    categories = [c["id"] for c in doc["categories"]]
    num_classes = max(categories) + 1  # ids from 1; 0 is the background
    images = {i["id"]: i for i in doc["images"]}

    dataset = torchvision.datasets.CocoDetection(root=str(out), annFile=str(ann_file))
    if len(dataset) != len(images):
        fail(f"{len(images)} images in {ann_file}, {len(dataset)} in the dataset")

    def target(anns):
        kept = [a for a in anns if not a.get("iscrowd", 0)]
        boxes = [[x, y, x + w, y + h] for x, y, w, h in (a["bbox"] for a in kept)]
        return {
            "boxes": torch.tensor(boxes, dtype=torch.float32).reshape(-1, 4),
            "labels": torch.tensor([a["category_id"] for a in kept], dtype=torch.int64),
        }

    torch.manual_seed(0)
    model = torchvision.models.detection.fasterrcnn_mobilenet_v3_large_320_fpn(
        weights=None, weights_backbone=None, num_classes=num_classes)
    model.train()
    optimizer = torch.optim.SGD(model.parameters(), lr=0.005, momentum=0.9,
                                weight_decay=0.0005)
    print(f"{ann_file}: {len(dataset)} images, {len(doc['annotations'])} annotations "
          f"({sum(a.get('iscrowd', 0) for a in doc['annotations'])} iscrowd, left out), "
          f"{num_classes - 1} classes")

    order = list(range(len(dataset)))
    fed_boxes = 0
    fed_ids = []
    start = time.time()
    for step in range(args.steps):
        batch = [order[(step * args.batch + k) % len(order)] for k in range(args.batch)]
        pictures, targets = [], []
        for index in batch:
            image, anns = dataset[index]
            info = images[dataset.ids[index]]
            if image.size != (info["width"], info["height"]):
                fail(f"{info['file_name']}: {image.size}, the file says "
                     f"{info['width']}x{info['height']}")
            t = target(anns)
            if len(t["boxes"]) and not bool(((t["boxes"][:, 2:] - t["boxes"][:, :2]) > 0).all()):
                fail(f"{info['file_name']}: a box of no size")
            pictures.append(to_tensor(image))
            targets.append(t)
            fed_boxes += len(t["boxes"])
            fed_ids.append(info["id"])
        losses = model(pictures, targets)
        loss = sum(losses.values())
        if not all(math.isfinite(v.item()) for v in losses.values()):
            fail(f"step {step}: a loss is not finite: {losses}")
        optimizer.zero_grad()
        loss.backward()
        optimizer.step()
        parts = ", ".join(f"{k} {v.item():.3f}" for k, v in losses.items())
        print(f"step {step + 1}/{args.steps}: loss {loss.item():.3f} ({parts})")
    want = sum(1 for i in fed_ids for a in doc["annotations"]
               if a["image_id"] == i and not a.get("iscrowd", 0))
    if fed_boxes != want:
        fail(f"fed {fed_boxes} boxes, the file has {want} non-crowd annotations for those images")
    print(f"train_torchvision: {args.steps} steps of {args.batch} images, {fed_boxes} boxes, "
          f"{time.time() - start:.1f} s")


if __name__ == "__main__":
    main()
