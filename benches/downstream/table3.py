#!/usr/bin/env python3
"""Paper Table 3 (4.4), reproduced: a traffic-sign detector trained on day images, then
fine-tuned on night images, tested on night images of another city.

    /tmp/trainvenv/bin/python benches/downstream/table3.py            # CPU, default small scale
    T3_DEVICE=0 T3_SIGN_FRAMES=2000 ... python benches/downstream/table3.py   # see README.md

Steps (each one's output under --out, default /dev/shm/table3):

1. `cityspec build` of the four specs beside this file: `day.toml` and `night.toml` (the
   training city, seed 101, split into train and val) and `day_test.toml` and
   `night_test.toml` (the test city, seed 202, every frame a test frame). One class,
   `traffic_sign`, YOLO layout. The frame counts are set with `--set`.
2. YOLOv8n from its model yaml (no downloaded weights) trained on day train, the best
   epoch by day val kept (the paper: 30 epochs, best on validation).
3. That model evaluated on day test (a sanity row) and night test (the paper's first row).
4. That model fine-tuned on night train, the best epoch by night val kept, evaluated on
   night test (the paper's second row).

Precision, recall and F-score are counted at one operating point fixed beforehand, not
tuned on the test set: detections with confidence >= --conf (0.25, ultralytics' default)
after NMS, matched greedily by confidence to the unmatched label box of highest IoU, a
match at IoU >= 0.5. The positives are the YOLO label boxes: the signs cityspec judges
visible. Signs under its pixel and contrast floors are COCO ignore regions (`iscrowd: 1`
in `coco/train.json`), not YOLO labels; an unmatched detection lying at least half inside
one is counted apart (`on_ignored`), neither right nor wrong, as COCO's evaluation treats
crowd regions. mAP50 from ultralytics' own val is printed beside, for reference.
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
PAPER = {  # Table 3: training set -> (precision, recall, F-score) on night test images
    "Day imagery only": (40.42, 32.75, 36.19),
    "Day and Night imagery": (48.48, 34.78, 40.50),
}


def env(name, default, kind=str):
    return kind(os.environ.get(name, default))


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=env("T3_OUT", "/dev/shm/table3"))
    ap.add_argument("--cityspec", default=env("T3_CITYSPEC", ""),
                    help="the cityspec binary (default: $CARGO_TARGET_DIR/release/cityspec, else target/release)")
    ap.add_argument("--sign-frames", type=int, default=env("T3_SIGN_FRAMES", 500, int),
                    help="frames of the training city's sign-aimed path (each of day and night)")
    ap.add_argument("--street-frames", type=int, default=env("T3_STREET_FRAMES", 60, int),
                    help="frames of the training city's street drive (each of day and night)")
    ap.add_argument("--test-sign-frames", type=int, default=env("T3_TEST_SIGN_FRAMES", 120, int))
    ap.add_argument("--test-street-frames", type=int, default=env("T3_TEST_STREET_FRAMES", 30, int))
    ap.add_argument("--epochs-day", type=int, default=env("T3_EPOCHS_DAY", 20, int))
    ap.add_argument("--epochs-night", type=int, default=env("T3_EPOCHS_NIGHT", 10, int))
    ap.add_argument("--imgsz", type=int, default=env("T3_IMGSZ", 320, int))
    ap.add_argument("--batch", type=int, default=env("T3_BATCH", 16, int))
    ap.add_argument("--device", default=env("T3_DEVICE", "cpu"), help="cpu, or a CUDA index such as 0")
    ap.add_argument("--workers", type=int, default=env("T3_WORKERS", 1, int))
    ap.add_argument("--threads", type=int, default=env("T3_THREADS", 2, int), help="torch CPU threads")
    ap.add_argument("--model", default=env("T3_MODEL", "yolov8n.yaml"))
    ap.add_argument("--conf", type=float, default=env("T3_CONF", 0.25, float))
    ap.add_argument("--seed", type=int, default=env("T3_SEED", 0, int), help="training seed")
    ap.add_argument("--skip-build", action="store_true", help="reuse the datasets already under --out")
    ap.add_argument("--eval-only", action="store_true",
                    help="reuse the datasets and the trained runs/day and runs/night under --out")
    return ap.parse_args()


def cityspec_binary(args):
    if args.cityspec:
        return args.cityspec
    target = os.environ.get("CARGO_TARGET_DIR", str(ROOT / "target"))
    return str(Path(target) / "release" / "cityspec")


def build(args):
    """Builds the four specs; returns {spec name: its yolo folder}."""
    binary = cityspec_binary(args)
    if not Path(binary).exists():
        sys.exit(f"error: no cityspec binary at {binary} (cargo build --release, or --cityspec)")
    frames = {
        "day": (args.sign_frames, args.street_frames),
        "night": (args.sign_frames, args.street_frames),
        "day_test": (args.test_sign_frames, args.test_street_frames),
        "night_test": (args.test_sign_frames, args.test_street_frames),
    }
    out = Path(args.out)
    folders = {}
    for name, (signs, street) in frames.items():
        if not args.skip_build:
            cmd = [binary, "-q", "build", str(HERE / f"{name}.toml"), "--out", str(out / "data"),
                   "--cache", str(out / "cache"), "--set", f"cameras.signs.frames={signs}",
                   "--set", f"cameras.street.frames={street}"]
            print("+", " ".join(cmd), flush=True)
            subprocess.run(cmd, check=True)
        folders[name] = out / "data" / name / "yolo"
    return folders


def data_yaml(args, folder, name, val_split):
    """An ultralytics data file over a build's yolo folder: train on `train`, val on `val_split`."""
    path = Path(args.out) / "yaml" / f"{name}.yaml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(f"path: {folder}\ntrain: images/train\nval: images/{val_split}\n"
                    "names:\n  0: traffic_sign\n")
    return str(path)


def read_labels(label_path, width, height):
    boxes = []
    if label_path.exists():
        for line in label_path.read_text().split("\n"):
            parts = line.split()
            if len(parts) >= 5:
                cx, cy, w, h = (float(v) for v in parts[1:5])
                boxes.append(((cx - w / 2) * width, (cy - h / 2) * height,
                              (cx + w / 2) * width, (cy + h / 2) * height))
    return boxes


def iou(a, b):
    ix = max(0.0, min(a[2], b[2]) - max(a[0], b[0]))
    iy = max(0.0, min(a[3], b[3]) - max(a[1], b[1]))
    inter = ix * iy
    union = (a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1]) - inter
    return inter / union if union > 0 else 0.0


def ignore_regions(folder):
    """Per YOLO image stem (`<camera>_NNNNNN`): the boxes of the build's COCO ignore regions
    (`iscrowd: 1`, signs under the pixel or contrast floor), as x0, y0, x1, y1."""
    with open(folder.parent / "coco" / "train.json", encoding="utf-8") as f:
        coco = json.load(f)
    stems = {}
    for im in coco["images"]:
        parts = Path(im["file_name"]).parts  # frames/<camera>/rgb/NNNNNN.png
        stems[im["id"]] = f"{parts[1]}_{Path(parts[-1]).stem}"
    regions = {}
    for a in coco["annotations"]:
        if a.get("iscrowd"):
            x, y, w, h = a["bbox"]
            regions.setdefault(stems[a["image_id"]], []).append((x, y, x + w, y + h))
    return regions


def inside(box, region):
    """The share of `box`'s area inside `region`."""
    ix = max(0.0, min(box[2], region[2]) - max(box[0], region[0]))
    iy = max(0.0, min(box[3], region[3]) - max(box[1], region[1]))
    area = (box[2] - box[0]) * (box[3] - box[1])
    return ix * iy / area if area > 0 else 0.0


def prf(model, folder, args):
    """Precision, recall, F-score (percent) at --conf and IoU 0.5 over a test folder."""
    images = sorted((folder / "images" / "train").glob("*.png"))
    ignored = ignore_regions(folder)
    tp = fp = positives = on_ignored = 0
    for start in range(0, len(images), 32):
        chunk = images[start:start + 32]
        results = model.predict([str(p) for p in chunk], imgsz=args.imgsz, conf=args.conf,
                                device=args.device, verbose=False)
        for image, result in zip(chunk, results):
            height, width = result.orig_shape
            truth = read_labels(folder / "labels" / "train" / (image.stem + ".txt"), width, height)
            positives += len(truth)
            used = [False] * len(truth)
            order = result.boxes.conf.argsort(descending=True).tolist()
            xyxy = result.boxes.xyxy.tolist()
            for k in order:
                best, best_iou = -1, 0.5
                for j, t in enumerate(truth):
                    if not used[j]:
                        v = iou(xyxy[k], t)
                        if v >= best_iou:
                            best, best_iou = j, v
                if best >= 0:
                    used[best] = True
                    tp += 1
                elif any(inside(xyxy[k], g) >= 0.5 for g in ignored.get(image.stem, ())):
                    on_ignored += 1  # on an ignore region: neither right nor wrong (COCO's rule)
                else:
                    fp += 1
    p = 100.0 * tp / (tp + fp) if tp + fp else 0.0
    r = 100.0 * tp / positives if positives else 0.0
    f = 2 * p * r / (p + r) if p + r else 0.0
    return {"precision": p, "recall": r, "f": f, "tp": tp, "fp": fp, "on_ignored": on_ignored,
            "positives": positives, "images": len(images)}


def evaluate(model, folder, name, args):
    row = prf(model, folder, args)
    val = model.val(data=data_yaml(args, folder, f"{name}_eval", "train"), imgsz=args.imgsz,
                    batch=args.batch, device=args.device, workers=args.workers, plots=False,
                    verbose=False, project=str(Path(args.out) / "runs"), name=f"val_{name}",
                    exist_ok=True)
    row["map50"] = 100.0 * float(val.box.map50)
    return row


def train(model_src, data, name, epochs, args):
    from ultralytics import YOLO

    model = YOLO(model_src)
    model.train(data=data, epochs=epochs, imgsz=args.imgsz, batch=args.batch, device=args.device,
                workers=args.workers, amp=False, plots=False, seed=args.seed, deterministic=True,
                project=str(Path(args.out) / "runs"), name=name, exist_ok=True, verbose=False)
    best = Path(args.out) / "runs" / name / "weights" / "best.pt"
    return YOLO(str(best))


def table(rows):
    lines = ["Traffic sign detection (paper Table 3 layout), percent; paper's numbers beside:",
             f"{'Training set':<24} {'tested on':<10} {'Precision':>9} {'Recall':>7} {'F-score':>8} "
             f"{'mAP50':>6}   {'paper P':>7} {'R':>6} {'F':>6}"]
    for label, tested, r in rows:
        paper = PAPER.get(label) if tested == "night" else None
        ref = f"{paper[0]:>7.2f} {paper[1]:>6.2f} {paper[2]:>6.2f}" if paper else f"{'-':>7} {'-':>6} {'-':>6}"
        lines.append(f"{label:<24} {tested:<10} {r['precision']:>9.2f} {r['recall']:>7.2f} {r['f']:>8.2f} "
                     f"{r['map50']:>6.2f}   {ref}")
    return "\n".join(lines)


def main():
    args = parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    # Ultralytics' settings and any font lookups stay inside the run's folder; plots are off,
    # so it draws nothing and needs no font (an offline machine downloads nothing).
    os.environ.setdefault("YOLO_CONFIG_DIR", str(out / "ultralytics"))
    os.environ.setdefault("YOLO_OFFLINE", "1")
    import torch

    torch.set_num_threads(args.threads)
    start = time.time()
    args.skip_build |= args.eval_only
    folders = build(args)
    built = time.time()
    if args.eval_only:
        from ultralytics import YOLO

        day = YOLO(str(out / "runs" / "day" / "weights" / "best.pt"))
    else:
        if (out / "runs").exists():
            shutil.rmtree(out / "runs")
        day = train(args.model, data_yaml(args, folders["day"], "day", "val"), "day", args.epochs_day, args)
    day_on_day = evaluate(day, folders["day_test"], "day_on_day", args)
    day_on_night = evaluate(day, folders["night_test"], "day_on_night", args)
    if args.eval_only:
        night = YOLO(str(out / "runs" / "night" / "weights" / "best.pt"))
    else:
        night = train(str(out / "runs" / "day" / "weights" / "best.pt"),
                      data_yaml(args, folders["night"], "night", "val"), "night", args.epochs_night, args)
    night_on_night = evaluate(night, folders["night_test"], "night_on_night", args)
    rows = [("Day imagery only", "day", day_on_day), ("Day imagery only", "night", day_on_night),
            ("Day and Night imagery", "night", night_on_night)]
    done = time.time()
    config = {k: v for k, v in vars(args).items() if k not in ("skip_build", "eval_only")}
    report = {"config": config, "build_s": round(built - start, 1), "train_eval_s": round(done - built, 1),
              "rows": [{"training": a, "tested_on": b, **r} for a, b, r in rows]}
    (out / "table3.json").write_text(json.dumps(report, indent=1))
    print()
    print(table(rows))
    print(f"at conf >= {args.conf}, IoU >= 0.5; test images: day {day_on_day['images']} "
          f"({day_on_day['positives']} signs), night {day_on_night['images']} ({day_on_night['positives']} signs)")
    for label, tested, r in rows:
        print(f"  {label}, {tested}: {r['tp']} true, {r['fp']} false, {r['on_ignored']} on ignore regions (not counted)")
    print(f"config: {json.dumps(config)}")
    print(f"wall time: build {built - start:.0f} s, train and evaluate {done - built:.0f} s; "
          f"{out / 'table3.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
