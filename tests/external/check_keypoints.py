#!/usr/bin/env python3
"""Check a camera path's COCO keypoints (`keypoints = true`) with pycocotools.

usage: check_keypoints.py <frames/<camera> folder>

1. pycocotools loads `coco.json`; every category with keypoints lists COCO's 17 names in
   COCO's order and its 19 limbs (1-based), and the person category is among them;
2. every annotation of such a category has `keypoints` (51 numbers) and `num_keypoints`
   equal to its count of v > 0; an ignore region (`iscrowd` 1) has none labelled; an
   unlabelled keypoint is written [0, 0, 0];
3. every visible keypoint (v = 2) lies in the image and inside its annotation's bbox
   (within 1 px), and the ids image shows that object at its pixel or one beside it for
   at least 90 % of them;
4. COCOeval with iouType 'keypoints' of the ground truth against itself (each annotation
   with a labelled keypoint as a detection of score 1) over the categories with keypoints
   gives OKS AP 1.0. maxDets is raised from COCO's 20 to 100: a street frame may show
   more than 20 people.
"""

import contextlib
import io
import json
import sys
from pathlib import Path

import numpy as np
from PIL import Image
from pycocotools.coco import COCO
from pycocotools.cocoeval import COCOeval

NAMES = [
    "nose", "left_eye", "right_eye", "left_ear", "right_ear", "left_shoulder",
    "right_shoulder", "left_elbow", "right_elbow", "left_wrist", "right_wrist", "left_hip",
    "right_hip", "left_knee", "right_knee", "left_ankle", "right_ankle",
]
SKELETON = [
    [16, 14], [14, 12], [17, 15], [15, 13], [12, 13], [6, 12], [7, 13], [6, 7], [6, 8],
    [7, 9], [8, 10], [9, 11], [2, 3], [1, 2], [1, 3], [2, 4], [3, 5], [4, 6], [5, 7],
]


def instance_ids(path):
    """The ids image: RGB-packed, id = R + 256 G + 256^2 B."""
    rgb = np.asarray(Image.open(path).convert("RGB")).astype(np.uint32)
    return rgb[..., 0] + 256 * rgb[..., 1] + 65536 * rgb[..., 2]


def check_annotations(folder, coco, kp_categories):
    counts = {0: 0, 1: 0, 2: 0}
    people, near, seen = 0, 0, 0
    for image_id, image in coco.imgs.items():
        anns = [a for a in coco.imgToAnns[image_id] if a["category_id"] in kp_categories]
        if not anns:
            continue
        ids = instance_ids(folder / "ids" / Path(image["file_name"]).name)
        height, width = ids.shape
        for a in anns:
            k = a["keypoints"]
            assert len(k) == 51, a["id"]
            v = k[2::3]
            assert all(x in (0, 1, 2) for x in v), a["id"]
            assert a["num_keypoints"] == sum(1 for x in v if x > 0), a["id"]
            if a["iscrowd"]:
                assert a["num_keypoints"] == 0, a["id"]
            for x, y, flag in zip(k[0::3], k[1::3], v):
                counts[flag] += 1
                if flag == 0:
                    assert x == 0 and y == 0, a["id"]
                    continue
                assert 0 <= x <= width and 0 <= y <= height, (a["id"], x, y)
                if flag != 2:
                    continue
                bx, by, bw, bh = a["bbox"]
                assert bx - 1 <= x <= bx + bw + 1 and by - 1 <= y <= by + bh + 1, (a["id"], x, y)
                seen += 1
                col, row = min(int(x), width - 1), min(int(y), height - 1)
                window = ids[max(row - 1, 0):row + 2, max(col - 1, 0):col + 2]
                near += bool((window == a["cityspec_instance"]).any())
            people += a["iscrowd"] == 0
    return counts, people, near, seen


def self_eval(coco, kp_categories):
    """OKS AP of the ground truth against itself, over the categories with keypoints."""
    detections = [
        {"image_id": a["image_id"], "category_id": a["category_id"],
         "keypoints": a["keypoints"], "score": 1.0}
        for a in coco.dataset["annotations"]
        if a.get("num_keypoints", 0) > 0
    ]
    assert detections, "no annotation with a labelled keypoint"
    with contextlib.redirect_stdout(io.StringIO()):
        results = coco.loadRes(detections)
        evaluation = COCOeval(coco, results, "keypoints")
        evaluation.params.catIds = sorted(kp_categories)
        evaluation.params.maxDets = [100]
        evaluation.evaluate()
        evaluation.accumulate()
    # summarize() reads 20 detections per image whatever maxDets says: AP over OKS 0.5 to
    # 0.95 at area "all" and 100 detections, as its stats[0] is made.
    precision = evaluation.eval["precision"][:, :, :, 0, -1]
    return float(np.mean(precision[precision > -1])), len(detections)


def main(folder):
    folder = Path(folder)
    with contextlib.redirect_stdout(io.StringIO()):
        coco = COCO(str(folder / "coco.json"))
    kp_categories = {}
    for c in coco.dataset["categories"]:
        if "keypoints" in c:
            assert c["keypoints"] == NAMES, c
            assert c["skeleton"] == SKELETON, c
            kp_categories[c["id"]] = c["name"]
    assert "person" in kp_categories.values(), f"no person category with keypoints: {kp_categories}"
    for a in coco.dataset["annotations"]:
        has = "keypoints" in a
        assert has == (a["category_id"] in kp_categories), a["id"]
    counts, people, near, seen = check_annotations(folder, coco, kp_categories)
    assert seen > 0, "no visible keypoint"
    share = near / seen
    assert share >= 0.9, f"only {share:.1%} of visible keypoints on their object in ids/"
    ap, detections = self_eval(coco, kp_categories)
    assert ap == 1.0, f"OKS AP of the ground truth against itself: {ap}"
    print(
        f"{folder}: {len(coco.imgs)} frames, {people} people and riders "
        f"({', '.join(sorted(kp_categories.values()))}), keypoints v=2 {counts[2]}, v=1 "
        f"{counts[1]}, v=0 {counts[0]}; {share:.1%} of v=2 on their object in ids/; "
        f"OKS AP of {detections} self-detections {ap:.3f}"
    )


if __name__ == "__main__":
    main(sys.argv[1])
