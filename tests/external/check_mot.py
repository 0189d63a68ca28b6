#!/usr/bin/env python3
"""Check a timed drive's MOT Challenge ground truth with motmetrics.

usage: check_mot.py <frames/<camera> folder>

1. `seqinfo.ini` names `rgb` as the image folder, its seqLength frames are there, and its
   frameRate is poses.json's `fps`;
2. motmetrics loads `gt/gt.txt` (MOT 15-2D format); every row's frame is in 1..seqLength,
   an id appears at most once a frame, and the rows of each frame are that frame's COCO
   annotations (words aside): the same boxes under the same instance ids, conf 0 exactly
   for the ignore regions;
3. the frames are a drive in time: `time` is i / fps, and consecutive eyes are
   speed / fps apart (within 1 mm of rounding) - so the tracks are real: several ids
   persist over at least 5 frames;
4. the ground truth (conf 1 rows) scored against itself by motmetrics gives MOTA 1.0 and
   IDF1 1.0, and by TrackEval (the MOT Challenge's own evaluation code, its `trackeval`
   package; box IoUs by its dataset code) HOTA 1.0.
"""

import configparser
import json
import math
import statistics
import sys
from collections import Counter, defaultdict
from pathlib import Path

import motmetrics as mm
import numpy as np
from trackeval.datasets._base_dataset import _BaseDataset
from trackeval.metrics import HOTA


def iou_distances(a, b, max_distance=0.5):
    """1 - IoU of every box of `a` with every box of `b` (x, y, w, h), NaN above
    `max_distance` (no match), as motmetrics' distance matrices are."""
    ax0, ay0 = a[:, 0:1], a[:, 1:2]
    ax1, ay1 = ax0 + a[:, 2:3], ay0 + a[:, 3:4]
    bx0, by0 = b[:, 0], b[:, 1]
    bx1, by1 = bx0 + b[:, 2], by0 + b[:, 3]
    w = np.clip(np.minimum(ax1, bx1) - np.maximum(ax0, bx0), 0, None)
    h = np.clip(np.minimum(ay1, by1) - np.maximum(ay0, by0), 0, None)
    inter = w * h
    union = a[:, 2:3] * a[:, 3:4] + b[:, 2] * b[:, 3] - inter
    d = 1.0 - inter / np.where(union > 0, union, 1.0)
    return np.where(d > max_distance, np.nan, d)


def trackeval_hota(positive):
    """TrackEval's HOTA (averaged over its IoU thresholds) of `positive` against itself."""
    frames = sorted(set(positive.index.get_level_values(0)))
    ids = sorted(set(positive.index.get_level_values(1)))
    index = {oid: k for k, oid in enumerate(ids)}
    gt_ids, similarity = [], []
    for frame in frames:
        rows_of = positive.loc[frame]
        boxes = rows_of[["X", "Y", "Width", "Height"]].to_numpy(dtype=float)
        gt_ids.append(np.array([index[o] for o in rows_of.index], dtype=int))
        similarity.append(_BaseDataset._calculate_box_ious(boxes, boxes, box_format="xywh"))
    data = {
        "num_gt_dets": len(positive), "num_tracker_dets": len(positive),
        "num_gt_ids": len(ids), "num_tracker_ids": len(ids), "num_timesteps": len(frames),
        "gt_ids": gt_ids, "tracker_ids": gt_ids, "similarity_scores": similarity,
    }
    return float(np.mean(HOTA().eval_sequence(data)["HOTA"]))


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    folder = Path(sys.argv[1])
    ini = configparser.ConfigParser()
    ini.read(folder / "seqinfo.ini")
    seq = ini["Sequence"]
    frames = int(seq["seqLength"])
    assert seq["imDir"] == "rgb" and seq["imExt"] == ".png", dict(seq)
    assert len(list((folder / "rgb").glob("*.png"))) == frames
    poses = json.loads((folder / "poses.json").read_text())
    fps = poses["fps"]
    assert float(seq["frameRate"]) == fps, (seq["frameRate"], fps)

    # 3. time and spacing.
    eyes = [f["eye"] for f in poses["frames"]]
    for i, f in enumerate(poses["frames"]):
        assert abs(f["time"] - i / fps) < 1e-9, (i, f["time"])
    steps = [math.dist(a, b) for a, b in zip(eyes, eyes[1:])]
    step = statistics.median(steps)
    assert all(abs(s - step) < 2e-3 for s in steps), steps

    # 2. gt.txt against COCO.
    gt = mm.io.loadtxt(folder / "gt" / "gt.txt", fmt="mot15-2D", min_confidence=-1)
    assert len(gt) > 0, "empty gt.txt"
    frame_ids = gt.index.get_level_values(0)
    assert frame_ids.min() >= 1 and frame_ids.max() <= frames
    assert not gt.index.duplicated().any(), "an id twice in one frame"
    coco = json.loads((folder / "coco.json").read_text())
    words = {c["id"] for c in coco["categories"] if c["name"] == "word"}
    expected = defaultdict(dict)
    for a in coco["annotations"]:
        if a["category_id"] in words:
            continue
        expected[a["image_id"]][a["cityspec_instance"]] = (a["bbox"], 0 if a["iscrowd"] else 1)
    rows = 0
    for (frame, oid), row in gt.iterrows():
        box = [row["X"], row["Y"], row["Width"], row["Height"]]
        want_box, want_conf = expected[frame][oid]
        assert box == want_box and row["Confidence"] == want_conf, (frame, oid, box, want_box)
        rows += 1
    assert rows == sum(len(v) for v in expected.values()), "COCO annotations missing from gt.txt"

    # Tracks over frames.
    positive = gt[gt["Confidence"] == 1]
    lengths = Counter(positive.index.get_level_values(1))
    long_tracks = sum(1 for n in lengths.values() if n >= 5)
    assert long_tracks >= 3, f"only {long_tracks} ids over 5 frames or more"

    # 4. Ground truth against itself, frame by frame through motmetrics' accumulator. The
    # IoU distances are worked out here: motmetrics 1.4's own (`iou_matrix`) calls
    # np.asfarray, which NumPy 2 removed.
    acc = mm.MOTAccumulator(auto_id=False)
    for frame, rows_of in positive.groupby(level=0):
        ids = list(rows_of.index.get_level_values(1))
        boxes = rows_of[["X", "Y", "Width", "Height"]].to_numpy(dtype=float)
        acc.update(ids, ids, iou_distances(boxes, boxes), frameid=frame)
    summary = mm.metrics.create().compute(acc, metrics=["mota", "idf1", "num_switches"], name="gt")
    mota, idf1 = summary["mota"]["gt"], summary["idf1"]["gt"]
    assert mota == 1.0 and idf1 == 1.0 and summary["num_switches"]["gt"] == 0, summary

    # TrackEval's HOTA of the ground truth against itself, as its MOT Challenge dataset
    # hands a sequence to the metric: per frame the ids (0-based) and the IoU matrix.
    hota = trackeval_hota(positive)
    assert hota == 1.0, f"HOTA {hota}"

    print(
        f"{folder}: {frames} frames at {fps:g} fps, {step:.3f} m a frame; {rows} rows "
        f"({len(positive)} positive) = COCO; {len(lengths)} tracks, median length "
        f"{np.median(list(lengths.values())):.0f} frames, {long_tracks} over >= 5; "
        f"motmetrics of gt against itself: MOTA {mota:.3f}, IDF1 {idf1:.3f}; "
        f"TrackEval HOTA {hota:.3f}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
