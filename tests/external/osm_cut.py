"""Cuts a few blocks out of an OpenStreetMap extract, with every node of the ways that
touch the box (so buildings and roads stay whole), into the formats the output names'
endings ask for (.osm XML, .osm.pbf), the box in the header. Made the fixtures in
tests/fixtures/osm/ from assets/osm/helsinki.osm.pbf:

    python tests/external/osm_cut.py assets/osm/helsinki.osm.pbf 60.1665,24.9380,60.1700,24.9460 \
        tests/fixtures/osm/kamppi.osm tests/fixtures/osm/kamppi.osm.pbf
"""
import sys

import osmium


def main(source, box, outputs):
    south, west, north, east = (float(v) for v in box.split(","))
    inside = lambda loc: south <= loc.lat <= north and west <= loc.lon <= east

    class Touching(osmium.SimpleHandler):
        def __init__(self):
            super().__init__()
            self.nodes, self.ways = set(), set()

        def way(self, w):
            if any(n.location.valid() and inside(n.location) for n in w.nodes):
                self.ways.add(w.id)
                self.nodes.update(n.ref for n in w.nodes)

        def node(self, n):
            if inside(n.location):
                self.nodes.add(n.id)

    touching = Touching()
    touching.apply_file(source, locations=True)

    class Copy(osmium.SimpleHandler):
        def __init__(self, writer):
            super().__init__()
            self.writer = writer

        def node(self, n):
            if n.id in touching.nodes:
                self.writer.add_node(n)

        def way(self, w):
            if w.id in touching.ways:
                self.writer.add_way(w)

        def relation(self, r):
            if any(m.type == "w" and m.ref in touching.ways for m in r.members):
                self.writer.add_relation(r)

    for output in outputs:
        header = osmium.io.Header()
        header.add_box(osmium.osm.Box(osmium.osm.Location(west, south), osmium.osm.Location(east, north)))
        writer = osmium.SimpleWriter(output, 0, header)
        Copy(writer).apply_file(source)
        writer.close()


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3:])
