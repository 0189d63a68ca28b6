"""Checks `cityspec osm`'s map of an extract against pyosmium, an independent OSM reader
(libosmium): its own node locations, its own multipolygon assembly (the area handler) and
its own haversine lengths.

    python check_osm.py EXTRACT MAP.json

- every building area osmium assembles (closed ways and multipolygon relations tagged
  building=*, not building=no) whose nodes all lie in the map's box is in the map, and the
  map holds no other; each one's footprint area (outer rings less holes, on a sphere of
  radius 6,371,008.8 m, equirectangular at the building's own latitude) within 2 %;
  an area tagged building:part=* is a part, not a building, whatever its building tag;
- every building part osmium assembles inside the box is one of the map's buildings'
  parts (its area within 2 %, at least half of it inside that building's footprint), or
  counted among the parts in no building (as many as osmium's parts the map lacks);
- every drivable highway way wholly inside the box is in the map uncut, its centreline
  length within 2 % of osmium's haversine length; a way the box cuts is in the map with
  pieces no longer than the whole way (2 % slack); every mapped road's class and way are
  osmium's;
- (shapely) no building osmium assembles overlaps the map's street (carriageway and
  sidewalks) by more than 0.01 m²; every paved segment's centreline lies on the
  carriageway; blocks, sidewalks and carriageway tile the box without overlap;
- (shapely) the map's green ground is the union of the green areas osmium assembles
  (parks, gardens, grass, woods: the tags of docs/osm.md) cut to the blocks, and its
  squares the union of the squares, pedestrian areas and car parks less the green, cut
  to the blocks: each within 2 % of the map's area, each piece inside the block it
  names and none on the street;
- (shapely) the map's paths across the green are the footways, paths, cycleways,
  bridleways and tracks on the ground (no bridge, tunnel or layer but 0) osmium reads,
  each buffered to half its width (`width`, else lanes × 3.25 m, else 2 m) with round
  ends, their union cut to the green ground and the blocks: within 2 % of the map's area,
  each piece on the green of its block.
Prints the counts and the worst differences; exits 1 on the first failed check.
"""
import json
import math
import sys

import osmium
import osmium.geom
import shapely
from shapely.geometry import LineString, Polygon, box

R = 6371008.8
DRIVABLE = {
    "motorway", "trunk", "primary", "secondary", "tertiary", "unclassified", "residential",
    "living_street", "service", "road", "motorway_link", "trunk_link", "primary_link",
    "secondary_link", "tertiary_link",
}


def green(tags):
    """docs/osm.md's green ground, as `osm::tags::green` reads it."""
    grassy = tags.get("surface") in (None, "grass")
    leisure, landuse, natural = tags.get("leisure"), tags.get("landuse"), tags.get("natural")
    return (
        leisure in ("park", "garden", "dog_park", "common", "nature_reserve")
        or (leisure in ("pitch", "playground") and grassy)
        or landuse in (
            "grass", "meadow", "village_green", "recreation_ground", "forest", "cemetery",
            "allotments", "flowerbed", "orchard", "greenfield", "plant_nursery",
        )
        or natural in ("wood", "scrub", "grassland", "heath")
    )


def square(tags):
    """docs/osm.md's paved open ground, as `osm::tags::square` reads it."""
    area = tags.get("area") == "yes"
    return (
        tags.get("place") == "square"
        or (area and tags.get("highway") in ("pedestrian", "footway"))
        or (tags.get("amenity") in ("parking", "marketplace") and tags.get("parking") in (None, "surface"))
    )


def ring_area(points):
    """|shoelace area| in m² of (lat, lon) points, equirectangular at their mean latitude."""
    lat0 = math.radians(sum(p[0] for p in points) / len(points))
    xy = [(R * math.cos(lat0) * math.radians(lon), R * math.radians(lat)) for lat, lon in points]
    twice = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(xy, xy[1:] + xy[:1]))
    return abs(twice) / 2


class Reader(osmium.SimpleHandler):
    def __init__(self, box):
        super().__init__()
        self.box = box
        self.buildings = {}  # ("way"|"relation", id) -> area
        self.parts = {}  # ("way"|"relation", id) -> area
        self.part_shapes = {}  # ("way"|"relation", id) -> [(+1 | -1, [(lat, lon)])]
        self.shapes = {}  # ("way"|"relation", id) -> [(+1 outer | -1 inner, [(lat, lon)])]
        self.outside = 0
        self.ways = {}  # id -> (class, length m, nodes inside, node count)
        self.green = []  # [(+1 outer | -1 inner, [(lat, lon)])] per green area
        self.squares = []  # the same per square
        self.paths = []  # [(width m, [(lat, lon)])] per ground path

    def inside(self, loc):
        s, w, n, e = self.box
        return s <= loc.lat <= n and w <= loc.lon <= e

    def area(self, a):
        building = a.tags.get("building")
        part = a.tags.get("building:part") not in (None, "no")
        if (building is None or building == "no") and not part:
            kind = self.green if green(a.tags) else self.squares if square(a.tags) else None
            if kind is not None:
                kind.append([
                    (sign, [(n.lat, n.lon) for n in ring])
                    for outer in a.outer_rings()
                    for sign, ring in [(1, outer)] + [(-1, i) for i in a.inner_rings(outer)]
                ])
            return
        key = ("way" if a.from_way() else "relation", a.orig_id())
        rings = []
        for outer in a.outer_rings():
            rings.append((1, [n.location for n in outer]))
            for inner in a.inner_rings(outer):
                rings.append((-1, [n.location for n in inner]))
        if not all(self.inside(l) for _, ring in rings for l in ring):
            self.outside += int(not part)
            return
        if part:
            self.parts[key] = sum(
                sign * ring_area([(l.lat, l.lon) for l in ring[:-1]]) for sign, ring in rings
            )
            self.part_shapes[key] = [(sign, [(l.lat, l.lon) for l in ring]) for sign, ring in rings]
            return
        self.buildings[key] = sum(
            sign * ring_area([(l.lat, l.lon) for l in ring[:-1]]) for sign, ring in rings
        )
        self.shapes[key] = [(sign, [(l.lat, l.lon) for l in ring]) for sign, ring in rings]

    def way(self, w):
        highway = w.tags.get("highway")
        if highway in GROUND_PATHS and ground(w.tags) and w.tags.get("area") != "yes":
            if all(n.location.valid() for n in w.nodes):
                points = [(n.lat, n.lon) for n in w.nodes]
                self.paths.append((width(w.tags), points))
        if highway not in DRIVABLE or w.tags.get("area") == "yes":
            return
        if not all(n.location.valid() for n in w.nodes):
            return
        inside = sum(self.inside(n.location) for n in w.nodes)
        self.ways[w.id] = (highway, osmium.geom.haversine_distance(w.nodes), inside, len(w.nodes))


GROUND_PATHS = {"footway", "path", "cycleway", "bridleway", "track"}


def ground(tags):
    """docs/osm.md's paths on the ground: no bridge, tunnel, cover, indoor or layer but 0."""
    def layer():
        try:
            return int(tags.get("layer", "0").strip())
        except ValueError:
            return 0
    return (
        tags.get("bridge", "no") == "no"
        and tags.get("tunnel", "no") == "no"
        and tags.get("covered", "no") == "no"
        and tags.get("indoor", "no") == "no"
        and tags.get("location") != "underground"
        and layer() == 0
    )


def width(tags):
    """A path's width: `width` in metres, else lanes × 3.25 m, else 2 m."""
    def number(key):
        value = tags.get(key, "").strip().replace(",", ".")
        value = value[:-1].strip() if value.endswith("m") else value
        try:
            return float(value)
        except ValueError:
            return None
    w = number("width")
    if w is not None and w > 0:
        return w
    lanes = number("lanes")
    if lanes is not None and lanes >= 1:
        return lanes * 3.25
    return 2.0


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def main(extract, map_path):
    with open(map_path) as f:
        m = json.load(f)
    b = m["bounds"]
    reader = Reader((b["south"], b["west"], b["north"], b["east"]))
    reader.apply_file(extract, locations=True)

    ours = {}
    for building in m["buildings"]:
        (kind, oid), = building["element"].items()
        ours[(kind, oid)] = ours.get((kind, oid), 0.0) + building["area"]
    theirs = reader.buildings
    missing = sorted(set(theirs) - set(ours))
    extra = sorted(set(ours) - set(theirs))
    if missing:
        fail(f"{len(missing)} buildings osmium assembles inside the box are not in the map: {missing[:10]}")
    if extra:
        fail(f"{len(extra)} buildings in the map are not osmium's: {extra[:10]}")
    worst = max(theirs, key=lambda k: abs(ours[k] / theirs[k] - 1))
    worst_rel = abs(ours[worst] / theirs[worst] - 1)
    if worst_rel > 0.02:
        fail(f"building {worst}: area {ours[worst]:.1f} m², osmium {theirs[worst]:.1f} m²")
    print(
        f"buildings: {len(theirs)} inside the box, all in the map and no other "
        f"({reader.outside} cross the box); footprint areas agree within {100 * worst_rel:.3f} % "
        f"(worst {worst[0]} {worst[1]}); {sum(theirs.values()):.0f} m² against the map's "
        f"{sum(ours.values()):.0f} m²"
    )
    check_parts(m, reader)


def check_parts(m, reader):
    """Every part osmium assembles is a part of the map building it mostly lies in."""
    def shape(rings):
        outer = [Polygon([(lon, lat) for lat, lon in r]).buffer(0) for s, r in rings if s > 0]
        inner = [Polygon([(lon, lat) for lat, lon in r]).buffer(0) for s, r in rings if s < 0]
        whole = shapely.union_all(outer)
        return shapely.difference(whole, shapely.union_all(inner)) if inner else whole

    ours = {}
    for building in m["buildings"]:
        owner = next(iter(building["element"].items()))
        for p in building.get("parts", []):
            key = next(iter(p["element"].items()))
            if key in ours:
                fail(f"part {key} is in the map twice")
            ours[key] = (owner, p["area"])
    theirs = reader.parts
    extra = sorted(set(ours) - set(theirs))
    if extra:
        fail(f"{len(extra)} parts in the map are not osmium's: {extra[:10]}")
    alone = len(set(theirs) - set(ours))
    if alone != m["left_out"]["parts_alone"]:
        fail(f"{alone} of osmium's parts are in no map building; the map counts {m['left_out']['parts_alone']}")
    worst_rel, worst_in = 0.0, 1.0
    for key, (owner, area) in ours.items():
        rel = abs(area / theirs[key] - 1)
        if rel > 0.02:
            fail(f"part {key}: area {area:.1f} m², osmium {theirs[key]:.1f} m²")
        worst_rel = max(worst_rel, rel)
        part = shape(reader.part_shapes[key])
        inside = shapely.intersection(part, shape(reader.shapes[owner])).area / part.area
        if inside < 0.5:
            fail(f"part {key}: {100 * inside:.0f} % of it in building {owner}")
        worst_in = min(worst_in, inside)
    print(
        f"parts: {len(theirs)} inside the box, {len(ours)} in {len({o for o, _ in ours.values()})} "
        f"buildings, {alone} in none (as the map counts); areas within {100 * worst_rel:.3f} %, "
        f"each at least {100 * worst_in:.1f} % inside its building"
    )

    pieces = {}
    for road in m["roads"]:
        pieces.setdefault(road["way"], []).append(road)
    whole, cut, worst_rel, worst_way = 0, 0, 0.0, None
    for way, (highway, length, inside, count) in sorted(reader.ways.items()):
        mine = pieces.get(way, [])
        if inside == count:
            if len(mine) != 1 or mine[0]["clipped"]:
                fail(f"way {way} ({highway}) lies inside the box: expected it whole, got {len(mine)} pieces")
            rel = abs(mine[0]["length"] / length - 1) if length > 0 else abs(mine[0]["length"])
            if rel > 0.02:
                fail(f"way {way}: centreline {mine[0]['length']:.2f} m, osmium {length:.2f} m")
            if rel > worst_rel:
                worst_rel, worst_way = rel, way
            whole += 1
        elif mine:
            total = sum(p["length"] for p in mine)
            if total > length * 1.02:
                fail(f"way {way}: pieces inside the box {total:.2f} m, the whole way {length:.2f} m")
            cut += 1
        if any(p["class"] != highway or not p["drivable"] for p in mine):
            fail(f"way {way}: class {[p['class'] for p in mine]} in the map, {highway} in osmium")
    stray = [
        r["way"] for r in m["roads"] if r["drivable"] and r["way"] not in reader.ways
    ]
    if stray:
        fail(f"{len(stray)} drivable roads in the map are not osmium's drivable ways: {stray[:10]}")
    km = sum(r[1] for r in reader.ways.values() if r[2] == r[3]) / 1000
    print(
        f"roads: {whole} drivable ways inside the box ({km:.2f} km), each whole in the map with "
        f"its length within {100 * worst_rel:.4f} % (worst way {worst_way}); {cut} cut by the box"
    )
    check_street(m, reader)
    check_green(m, reader)


def check_green(m, reader):
    """The map's green ground and squares against osmium's areas cut to the map's blocks."""
    lat0, lon0 = m["origin"]
    kx, kz = m["metres_per_degree"]
    project = lambda pts: [((lon - lon0) * kx, -(lat - lat0) * kz) for lat, lon in pts]

    def union(shapes):
        areas = []
        for rings in shapes:
            outer = shapely.union_all([Polygon(project(r)).buffer(0) for s, r in rings if s > 0])
            inner = [Polygon(project(r)).buffer(0) for s, r in rings if s < 0]
            areas.append(shapely.difference(outer, shapely.union_all(inner)) if inner else outer)
        return shapely.union_all(areas)

    green = union(reader.green)
    squares = shapely.difference(union(reader.squares), green)
    check_open("green", green, len(reader.green), m, m["green"])
    check_open("squares", squares, len(reader.squares), m, m["squares"])
    check_paths(reader.paths, green, m, project)


def check_paths(paths, green, m, project):
    """The paths across the green: osmium's ground paths buffered, cut to green and blocks."""
    strokes = shapely.union_all([
        LineString(project(points)).buffer(w / 2, quad_segs=6, cap_style="round")
        for w, points in paths
        if len(points) >= 2
    ])
    blocks = polygons(m["blocks"])
    theirs = shapely.intersection(
        shapely.intersection(strokes, green), shapely.union_all(blocks)
    ).area
    pieces = [(g["block"], Polygon(g["shape"]["outer"], g["shape"]["holes"])) for g in m["paths"]]
    ours = sum(p.area for _, p in pieces)
    if theirs > 0 and abs(ours / theirs - 1) > 0.02 or (theirs == 0) != (ours == 0):
        fail(f"paths: {ours:.1f} m² in the map, {theirs:.1f} m² of osmium's on the green")
    greens = {}
    for g in m["green"]:
        shape = Polygon(g["shape"]["outer"], g["shape"]["holes"])
        greens[g["block"]] = shapely.union_all([greens.get(g["block"], Polygon()), shape])
    worst = max(
        (shapely.difference(p, greens.get(n, Polygon())).area for n, p in pieces), default=0.0
    )
    if worst > 0.01:
        fail(f"paths: a piece leaves the green of its block by {worst:.3f} m²")
    print(
        f"paths: {len(paths)} ground paths osmium reads, {theirs:.0f} m² of them on the "
        f"green against the map's {ours:.0f} m² in {len(pieces)} pieces "
        f"({100 * abs(ours / theirs - 1) if theirs else 0:.3f} %); each piece on its "
        f"block's green (worst {worst:.4f} m²)"
    )


def check_open(name, theirs_union, count, m, mine):
    blocks = polygons(m["blocks"])
    theirs = shapely.intersection(theirs_union, shapely.union_all(blocks)).area
    pieces = [(g["block"], Polygon(g["shape"]["outer"], g["shape"]["holes"])) for g in mine]
    ours = sum(p.area for _, p in pieces)
    if theirs > 0 and abs(ours / theirs - 1) > 0.02:
        fail(f"{name}: {ours:.1f} m² in the map, {theirs:.1f} m² of osmium's areas on the blocks")
    street = shapely.union_all(polygons(m["carriageway"]) + polygons(m["sidewalks"]))
    worst = 0.0
    for n, piece in pieces:
        outside = shapely.difference(piece, blocks[n]).area
        on_street = shapely.intersection(piece, street).area
        worst = max(worst, outside, on_street)
    if worst > 0.01:
        fail(f"{name}: a piece leaves its block or lies on the street by {worst:.3f} m²")
    print(
        f"{name}: {count} areas osmium assembles, {theirs:.0f} m² of them on the "
        f"blocks against the map's {ours:.0f} m² in {len(pieces)} pieces "
        f"({100 * abs(ours / theirs - 1) if theirs else 0:.3f} %); each piece in its block, "
        f"none on the street (worst {worst:.4f} m²)"
    )


def polygons(items):
    return [Polygon(p["outer"], p["holes"]) for p in items]


def check_street(m, reader):
    """The street's polygons against osmium's buildings, projected as the map documents."""
    lat0, lon0 = m["origin"]
    kx, kz = m["metres_per_degree"]
    project = lambda pts: [((lon - lon0) * kx, -(lat - lat0) * kz) for lat, lon in pts]
    carriageway = shapely.union_all(polygons(m["carriageway"]))
    sidewalks = shapely.union_all(polygons(m["sidewalks"]))
    blocks = shapely.union_all(polygons(m["blocks"]))
    street = shapely.union_all([carriageway, sidewalks])
    worst, worst_key, touching = 0.0, None, 0
    for key, rings in reader.shapes.items():
        outer = [Polygon(project(r)) for sign, r in rings if sign > 0]
        inner = [Polygon(project(r)) for sign, r in rings if sign < 0]
        footprint = shapely.difference(shapely.union_all(outer), shapely.union_all(inner)) if inner else shapely.union_all(outer)
        overlap = shapely.intersection(footprint.buffer(0), street).area
        if overlap > 1e-6:
            touching += 1
        if overlap > worst:
            worst, worst_key = overlap, key
    if worst > 0.01:
        fail(f"building {worst_key} overlaps the street by {worst:.3f} m²")
    x0, z0, x1, z1 = m["extent"]
    whole = box(x0, z0, x1, z1).area
    tiled = carriageway.area + sidewalks.area + blocks.area
    overlaps = (
        shapely.intersection(carriageway, sidewalks).area
        + shapely.intersection(street, blocks).area
    )
    if abs(tiled / whole - 1) > 1e-4 or overlaps > 1.0:
        fail(f"street and blocks cover {tiled:.1f} m² of the box's {whole:.1f} m², overlapping by {overlaps:.2f} m²")
    paved = grown = 0
    reach = carriageway.buffer(0.01)
    for road in m["roads"]:
        for (a, b), (width, _, _) in zip(zip(road["centreline"], road["centreline"][1:]), road["fitted"]):
            if width > 0:
                paved += 1
                if not reach.contains(LineString([a, b])):
                    fail(f"way {road['way']}: a paved segment {a}–{b} leaves the carriageway")
    left = m["left_out"]
    print(
        f"street: {len(reader.shapes)} buildings clear of carriageway and sidewalks (worst overlap "
        f"{worst:.4f} m², {touching} touch by more than 1e-6 m²); {paved} paved segments on the "
        f"carriageway ({left['segments_narrowed']} narrowed, {left['segments_blocked']} unpaved under "
        f"buildings); carriageway {carriageway.area:.0f} m², sidewalks {sidewalks.area:.0f} m², "
        f"{len(m['blocks'])} blocks {blocks.area:.0f} m² tile the box ({overlaps:.3f} m² overlap)"
    )


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
