"""Checks a build's Cityscapes folder (`[annotations] cityscapes = true` with `[splits]`)
with the `cityscapesscripts` package itself:

1. `cityscapes/labels.json` holds Cityscapes' own label table exactly as the installed
   package has it (every field of ids 0-33); its extra labels (`text`, the user's model
   classes) are registered into the package's tables, as Cityscapes' README asks of
   custom labels.
2. Every split's `gtFine` images are consistent: `labelIds` is the label of `instanceIds`
   (value // 1000 from 1000 up), `color` is each label's colour, every frame has its
   `leftImg8bit` image of the same size, and each object of the frame's `ids/` image (the
   renderer's instance ids) is one `instanceIds` value that no other object shares.
3. `evalPixelLevelSemanticLabeling` of the labels against themselves: IoU 1.0 for every
   class present.
4. `createPanopticImgs` converts `gtFine` into COCO panoptic; the build's own
   `cityscapes_panoptic_<split>.json` and PNGs equal it, and `evalPanopticSemanticLabeling`
   of the build's panoptic files against the package's gives PQ 1.0.

    python check_cityscapes.py out/day
"""

import glob
import io
import json
import os
import sys
import tempfile
from contextlib import redirect_stdout

import numpy as np
from PIL import Image

from cityscapesscripts.helpers import labels as cs

FIELDS = ("name", "id", "trainId", "category", "categoryId", "hasInstances", "ignoreInEval")


def register(table):
    """Checks the Cityscapes rows against the package and adds the extra labels to it."""
    own = [row for row in table if not row["extra"]]
    package = [label for label in cs.labels if label.id >= 0]
    assert len(own) == len(package), f"{len(own)} Cityscapes labels, the package has {len(package)}"
    for row, label in zip(own, package):
        got = (row["name"], row["id"], row["trainId"], row["category"], row["catId"],
               row["hasInstances"], row["ignoreInEval"], tuple(row["color"]))
        want = tuple(getattr(label, f) for f in FIELDS) + (tuple(label.color),)
        assert got == want, f"labels.json has {got}, cityscapesscripts {want}"
    extras = [row for row in table if row["extra"]]
    for row in extras:
        assert row["id"] not in cs.id2label, f"extra label {row['name']} reuses id {row['id']}"
        label = cs.Label(row["name"], row["id"], row["trainId"], row["category"], row["catId"],
                         row["hasInstances"], row["ignoreInEval"], tuple(row["color"]))
        # In place: the evaluation modules hold these very objects.
        cs.labels.append(label)
        cs.name2label[label.name] = label
        cs.id2label[label.id] = label
        cs.trainId2label[label.trainId] = label
        cs.category2labels.setdefault(label.category, []).append(label)
    return [row["name"] for row in extras]


def ids_of(path):
    rgb = np.array(Image.open(path).convert("RGB")).astype(np.uint32)
    return rgb[..., 0] + (rgb[..., 1] << 8) + (rgb[..., 2] << 16)


def check_frames(out, split, colours):
    """Point 2 for one split; returns the labelIds files."""
    label_files = sorted(glob.glob(f"{out}/cityscapes/gtFine/{split}/*/*_gtFine_labelIds.png"))
    assert label_files, f"no gtFine/{split} labelIds"
    sources = source_frames(out)
    objects = 0
    for label_file in label_files:
        name = os.path.basename(label_file)[: -len("_gtFine_labelIds.png")]
        label_ids = np.array(Image.open(label_file))
        instance_ids = np.array(Image.open(label_file.replace("_labelIds", "_instanceIds")))
        colour = np.array(Image.open(label_file.replace("_labelIds", "_color")).convert("RGB"))
        assert label_ids.dtype == np.uint8 and instance_ids.dtype in (np.uint16, np.int32), name
        expected = np.where(instance_ids < 1000, instance_ids, instance_ids // 1000)
        assert (label_ids == expected).all(), f"{name}: labelIds is not the label of instanceIds"
        assert (colour == colours[label_ids]).all(), f"{name}: a colour is not its label's"
        city = os.path.basename(os.path.dirname(label_file))
        left = f"{out}/cityscapes/leftImg8bit/{split}/{city}/{name}_leftImg8bit.png"
        assert Image.open(left).size == Image.open(label_file).size, f"{name}: leftImg8bit size"
        # Each object of the renderer's instance image is one instanceIds value of its own.
        ids = ids_of(sources[name])
        assert ids.shape == instance_ids.shape, name
        pairs = np.unique((ids.ravel().astype(np.uint64) << 16) | instance_ids.ravel())
        objects_, values_ = pairs >> 16, pairs & 0xFFFF
        per_object = np.unique(objects_, return_counts=True)[1]
        assert (per_object == 1).all(), f"{name}: an object has two instanceIds values"
        things = values_[values_ >= 1000]
        values, counts = np.unique(things, return_counts=True)
        assert (counts == 1).all(), f"{name}: objects {values[counts > 1]} share a value"
        objects += len(things)
    print(f"{split}: {len(label_files)} frames consistent, {objects} numbered objects")
    return label_files


def source_frames(out):
    """Cityscapes name -> the camera path's ids image it was made from."""
    names = {}
    for index, camera in enumerate(camera_order(out)):
        for path in sorted(glob.glob(f"{out}/frames/{camera}/ids/*.png")):
            frame = int(os.path.basename(path)[:6])
            names[f"{camera.replace('_', '-')}_{index:06d}_{frame:06d}"] = path
    return names


def camera_order(out):
    """The cameras in spec order: that of the COCO splits' images (camera, then frame)."""
    order = []
    for split in ("train", "val", "test"):
        path = f"{out}/coco/{split}.json"
        if os.path.exists(path):
            for image in sorted(json.load(open(path))["images"], key=lambda i: i["id"]):
                camera = image["file_name"].split("/")[1]
                if camera not in order:
                    order.append(camera)
    return order


def check_pixels(label_files):
    from cityscapesscripts.evaluation import evalPixelLevelSemanticLabeling as pixel

    args = pixel.args
    args.quiet = True
    args.JSONOutput = False
    # The instance-weighted IoU wants each class's mean instance size in pixels, which the
    # package knows for Cityscapes' classes only: the extra ones get theirs from this data.
    sizes = {}
    for f in label_files:
        values, counts = np.unique(np.array(Image.open(f.replace("_labelIds", "_instanceIds"))),
                                   return_counts=True)
        for value, count in zip(values, counts):
            if value >= 1000:
                sizes.setdefault(cs.id2label[value // 1000].name, []).append(count)
    for name, counts in sizes.items():
        args.avgClassSize.setdefault(name, float(np.mean(counts)))
    results = pixel.evaluateImgLists(label_files, label_files, args)
    present = set()
    for f in label_files:
        present |= set(np.unique(np.array(Image.open(f))).tolist())
    scores = {}
    for label_id in sorted(present):
        label = cs.id2label[label_id]
        if label.ignoreInEval:
            continue
        iou = results["classScores"][label.name]
        assert iou == 1.0, f"{label.name}: IoU {iou}"
        scores[label.name] = iou
    print(f"evalPixelLevelSemanticLabeling: IoU 1.0 for all {len(scores)} present classes: "
          + ", ".join(sorted(scores)))


def check_panoptic(out, split, scratch):
    from cityscapesscripts.evaluation.evalPanopticSemanticLabeling import evaluatePanoptic
    from cityscapesscripts.preparation.createPanopticImgs import convert2panoptic

    ours_json = f"{out}/cityscapes/gtFine/cityscapes_panoptic_{split}.json"
    ours_folder = ours_json[: -len(".json")]
    with redirect_stdout(io.StringIO()):
        convert2panoptic(f"{out}/cityscapes/gtFine", scratch, setNames=[split])
    theirs_json = f"{scratch}/cityscapes_panoptic_{split}.json"
    theirs_folder = theirs_json[: -len(".json")]
    ours, theirs = json.load(open(ours_json)), json.load(open(theirs_json))
    key = lambda item: item.get("image_id", item.get("id"))
    for part in ("images", "annotations"):
        assert sorted(ours[part], key=key) == sorted(theirs[part], key=key), \
            f"{ours_json}: {part} differ from createPanopticImgs'"
    assert sorted(ours["categories"], key=key) == sorted(
        [dict(c, color=list(c["color"])) for c in theirs["categories"]], key=key
    ), f"{ours_json}: categories differ"
    for annotation in theirs["annotations"]:
        a = np.array(Image.open(f"{ours_folder}/{annotation['file_name']}"))
        b = np.array(Image.open(f"{theirs_folder}/{annotation['file_name']}"))
        assert (a == b).all(), f"{annotation['file_name']}: pixels differ from createPanopticImgs'"
    with redirect_stdout(io.StringIO()):
        results = evaluatePanoptic(theirs_json, theirs_folder, ours_json, ours_folder,
                                   f"{scratch}/pq_{split}.json")
    pq = results["All"]["pq"]
    assert pq == 1.0, f"{split}: PQ {pq}"
    print(f"{split}: panoptic = createPanopticImgs' ({len(ours['annotations'])} images, "
          f"{sum(len(a['segments_info']) for a in ours['annotations'])} segments); "
          f"evalPanopticSemanticLabeling PQ {pq} (things {results['Things']['pq']}, "
          f"stuff {results['Stuff']['pq']})")


def main(out):
    table = json.load(open(f"{out}/cityscapes/labels.json"))["labels"]
    extras = register(table)
    print(f"labels.json: Cityscapes' {len(table) - len(extras)} labels as cityscapesscripts "
          f"has them; extra: {', '.join(extras)}")
    colours = np.zeros((256, 3), dtype=np.uint8)
    for row in table:
        colours[row["id"]] = row["color"]
    splits = [s for s in ("train", "val", "test")
              if os.path.isdir(f"{out}/cityscapes/gtFine/{s}")]
    assert splits, "no split in cityscapes/gtFine"
    label_files = []
    for split in splits:
        label_files += check_frames(out, split, colours)
    check_pixels(label_files)
    with tempfile.TemporaryDirectory() as scratch:
        for split in splits:
            check_panoptic(out, split, scratch)


if __name__ == "__main__":
    main(sys.argv[1])
