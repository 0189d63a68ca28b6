//! An [`OsmMap`] + facades → the 3D city of a real place: its street surface and its
//! buildings on their real footprints, at their mapped heights.
//!
//! | object | class | geometry | material |
//! |---|---|---|---|
//! | `ground` | ground | one quad under the box, [`GROUND_MARGIN`] beyond it | `grass` |
//! | `block_0007` | block; ground (terrain) without a building | block 7's polygon at kerb height, less the map's green ground and squares on it | `paving`; `grass` without a building (a park, a square or a yard) |
//! | `green_0002` | ground (terrain) | a piece of the map's green ground (parks, gardens, grass, woods: `OsmMap::green`) at kerb height, less the paths across it | `grass` |
//! | `path_0002` | sidewalk | a piece of the paths across the green ground (`OsmMap::paths`) at kerb height | `paving` |
//! | `square_0002` | block | a piece of the map's paved open ground (squares, pedestrian areas, car parks: `OsmMap::squares`) at kerb height | `paving` |
//! | `sidewalk_0007` | sidewalk | a sidewalk polygon at kerb height | `concrete` |
//! | `road_0003` | road | a carriageway polygon (junctions included) at road height | `asphalt` |
//! | `kerb_0003` | sidewalk | the kerb faces around carriageway polygon 3, from road height up to kerb height, facing the road (none on the box's edge) | `concrete` |
//! | `marking_0003` | marking | road 3's centre and lane lines and zebra crossings, following its centreline, clear of junctions (`map_markings`) | `marking` |
//! | `lamp_0003` | lamp | a street lamp where the map has one, or seeded where it has none (`lamps::map_lamps`) | `lamp_metal`, `lamp_head` |
//! | `building_0042` | building | per volume (`model::geometry::massing`: the building, or its parts and the rest of its footprint, each from its `min_height`): a wall per footprint edge (courtyards' too), a flat roof with the courtyards cut out, or the roof its `roof:shape` makes (`model::geometry::roofs`: gabled, gambrel, round, hipped, pyramidal, dome) with its gables in the walls | `facade_*`, `roof_*` |
//!
//! A building is as tall as the map says, else a seeded 3 to 7 floors of its facade. Its
//! facade is seeded per building, or the one nearest its mapped `building:colour`, and its
//! roof the facade's or the one nearest its `roof:colour` ([`map_cladding`], which the wall
//! text reads too). The facade keeps its own
//! scale on every wall: one facade width along u per its width in metres, and one floor of
//! the facade per floor of the building. The facade's ground floor runs along the bottom
//! of every wall, its upper floors repeat above it, and the top repeat is cut at the roof
//! line (so windows are never stretched). A volume lifted off the ground carries on the
//! floors below it: the pattern counts from the ground.
//!
//! The buildings the place stage put on blocks without any (`fill_empty_blocks`) come in
//! the map's list after its own, each clad in the facade it was sized for, as tall as it.
//!
//! Not here yet (issue 43): roof shapes other than `model::geometry::roofs`' (skillion,
//! mansard, half-hipped …) and hipped roofs on more than four corners are flat. Trees,
//! signals, signs and benches are objects (`objects::insert_map`).

use super::object;
use super::surfaces::Surfaces;
use crate::model::geometry::massing::volumes;
use crate::model::geometry::polygon::{distance, left_normal, signed_area};
use crate::model::geometry::polygon_set::difference;
use crate::model::geometry::{KERB_Y, MaterialBook, MeshBuilder, ROAD_Y};
use crate::model::{
    Facade, FacadeSet, Lamp, MapCladding, MapPolygon, ObjectKind, OsmMap, Scene, SceneObject,
    map_cladding,
};

/// How far the ground reaches beyond the box, metres.
pub const GROUND_MARGIN: f64 = 200.0;
/// Metres one repeat of a roof texture covers, and of the plain roof.
const ROOF_TILE: f64 = 4.0;

/// The map scene's input.
pub struct MapSceneInput<'a> {
    pub map: &'a OsmMap,
    /// The map's lamps (`lamps::map_lamps`), in metres.
    pub lamps: &'a [Lamp],
    pub facades: &'a FacadeSet,
    pub seed: u64,
}

/// The 3D city of `input.map`. Pure and deterministic.
pub fn map_city(input: &MapSceneInput) -> Scene {
    let mut book = MaterialBook::default();
    let surfaces = Surfaces::register(&mut book);
    let map = input.map;
    let mut objects: Vec<SceneObject> = Vec::new();
    let [x0, z0, x1, z1] = map.extent;
    let mut ground = MeshBuilder::new(surfaces.grass);
    let m = GROUND_MARGIN;
    ground.floor(
        [x0 - m, x1 + m],
        [z0 - m, z1 + m],
        0.0,
        super::procedural::GRASS_TILE,
    );
    objects.push(object(
        ObjectKind::Ground,
        "ground".to_owned(),
        vec![ground],
    ));
    objects.extend(blocks(map, &surfaces));
    objects.extend(flat(
        &map.sidewalks,
        ObjectKind::Sidewalk,
        surfaces.concrete,
        KERB_Y,
        2.0,
    ));
    objects.extend(flat(
        &map.carriageway,
        ObjectKind::Road,
        surfaces.asphalt,
        ROAD_Y,
        4.0,
    ));
    objects.extend(kerbs(map, surfaces.concrete));
    objects.extend(super::map_markings::map_marking_objects(
        map,
        surfaces.marking,
    ));
    objects.extend(super::street_lamps::lamp_objects(
        input.lamps,
        1.0,
        &surfaces,
    ));
    objects.extend(buildings(input, &mut book));
    let (textures, materials) = book.finish();
    Scene {
        textures,
        materials,
        objects,
    }
}

/// Every block at kerb height, less the map's open ground on it: paved where a building
/// stands in the block, grass (terrain) where none does (a park, a square or a yard); then
/// the green ground, grass, less the paths across it, the paths, paved, and the squares,
/// paved.
fn blocks(map: &OsmMap, surfaces: &Surfaces) -> Vec<SceneObject> {
    let mut objects: Vec<SceneObject> = map
        .blocks
        .iter()
        .enumerate()
        .map(|(n, block)| {
            let open = map.open_on(n);
            let (kind, material, tile) = if map.block_is_built(block) {
                (ObjectKind::Block, surfaces.paving, 2.0)
            } else {
                let tile = super::procedural::GRASS_TILE;
                (ObjectKind::Ground, surfaces.grass, tile)
            };
            let mut mesh = MeshBuilder::new(material);
            for part in difference(block, &open) {
                mesh.polygon(&part.outer, &part.holes, KERB_Y, tile);
            }
            object(kind, format!("block_{n:04}"), vec![mesh])
        })
        .collect();
    objects.extend(map.green.iter().enumerate().map(|(i, g)| {
        let mut mesh = MeshBuilder::new(surfaces.grass);
        let tile = super::procedural::GRASS_TILE;
        let paths: Vec<&MapPolygon> = (map.paths.iter())
            .filter(|p| p.block == g.block)
            .map(|p| &p.shape)
            .collect();
        if paths.is_empty() {
            mesh.polygon(&g.shape.outer, &g.shape.holes, KERB_Y, tile);
        } else {
            for part in difference(&g.shape, &paths) {
                mesh.polygon(&part.outer, &part.holes, KERB_Y, tile);
            }
        }
        object(ObjectKind::Ground, format!("green_{i:04}"), vec![mesh])
    }));
    objects.extend(map.paths.iter().enumerate().map(|(i, p)| {
        let mut mesh = MeshBuilder::new(surfaces.paving);
        mesh.polygon(&p.shape.outer, &p.shape.holes, KERB_Y, 2.0);
        object(ObjectKind::Sidewalk, format!("path_{i:04}"), vec![mesh])
    }));
    objects.extend(map.squares.iter().enumerate().map(|(i, g)| {
        let mut mesh = MeshBuilder::new(surfaces.paving);
        mesh.polygon(&g.shape.outer, &g.shape.holes, KERB_Y, 2.0);
        object(ObjectKind::Block, format!("square_{i:04}"), vec![mesh])
    }));
    objects
}

/// One object of `kind` per polygon, flat at height `y`.
fn flat(
    polygons: &[MapPolygon],
    kind: ObjectKind,
    material: u32,
    y: f64,
    tile: f64,
) -> Vec<SceneObject> {
    polygons
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut mesh = MeshBuilder::new(material);
            mesh.polygon(&p.outer, &p.holes, y, tile);
            object(kind, format!("{}_{i:04}", kind.name()), vec![mesh])
        })
        .collect()
}

/// Per carriageway polygon, `kerb_0003` (class sidewalk, as a layout's curb faces): along
/// every edge of its rings (an island's too) but those on the box's edge, a vertical face
/// from road height up to kerb height facing into the carriageway. Everything that meets
/// a carriageway (sidewalks, blocks, green ground, squares) lies at kerb height, so the
/// faces close the step that otherwise shows the ground through it.
fn kerbs(map: &OsmMap, concrete: u32) -> Vec<SceneObject> {
    let [x0, z0, x1, z1] = map.extent;
    let edge = |a: f64, b: f64, side: f64| (a - side).abs() < 0.01 && (b - side).abs() < 0.01;
    let on_box = |a: [f64; 2], b: [f64; 2]| {
        edge(a[0], b[0], x0) || edge(a[0], b[0], x1) || edge(a[1], b[1], z0) || edge(a[1], b[1], z1)
    };
    (map.carriageway.iter().enumerate())
        .map(|(i, p)| {
            let mut mesh = MeshBuilder::new(concrete);
            let rings = std::iter::once((&p.outer, true)).chain(p.holes.iter().map(|h| (h, false)));
            for (ring, outer) in rings {
                // A ring of positive area turns from +x towards +z: its left normal points
                // out of it. Into the carriageway is into the outer ring, out of a hole.
                let left_is_road = (signed_area(ring) > 0.0) != outer;
                let sign = if left_is_road { 1.0 } else { -1.0 };
                for (k, &a) in ring.iter().enumerate() {
                    let b = ring[(k + 1) % ring.len()];
                    let Some(n) = left_normal(a, b).filter(|_| !on_box(a, b)) else {
                        continue;
                    };
                    let length = distance(a, b);
                    // + 0.0: no negative zero in a normal.
                    let normal = [sign * n[0] + 0.0, 0.0, sign * n[1] + 0.0];
                    let v = (KERB_Y - ROAD_Y) / 2.0;
                    mesh.wall(
                        a,
                        b,
                        [ROAD_Y, KERB_Y],
                        normal,
                        [0.0, length / 2.0],
                        [0.0, v],
                    );
                }
            }
            object(ObjectKind::Sidewalk, format!("kerb_{i:04}"), vec![mesh])
        })
        .collect()
}

/// Each building's material per facade and per roof (registered once, when used), and
/// the plain ones.
struct Cladding {
    wall: Vec<Option<u32>>,
    roof: Vec<Option<u32>>,
    plain_wall: u32,
    plain_roof: u32,
}

impl Cladding {
    /// Registers, in building order, the facades' then the roofs' materials `cladding`
    /// (one per building) uses.
    fn register(
        set: &crate::model::FacadeSet,
        cladding: &[MapCladding],
        book: &mut MaterialBook,
    ) -> Cladding {
        let none = [0.0; 3];
        let mut wall = vec![None; set.facades.len()];
        for f in cladding.iter().filter_map(|c| c.facade.as_ref()) {
            let facade = &set.facades[*f];
            wall[*f].get_or_insert_with(|| {
                book.add(
                    &format!("facade_{}", facade.name),
                    [1.0; 3],
                    Some(&facade.texture),
                    none,
                )
            });
        }
        let mut roof = vec![None; set.roofs.len()];
        for index in cladding.iter().filter_map(|c| c.roof) {
            if let Some(r) = set.roofs.get(index) {
                roof[index].get_or_insert_with(|| {
                    book.add(
                        &format!("roof_{}", r.name),
                        [1.0; 3],
                        Some(&r.texture),
                        none,
                    )
                });
            }
        }
        Cladding {
            wall,
            roof,
            plain_wall: book.add("facade_plain", [0.55, 0.5, 0.45], None, none),
            plain_roof: book.add("roof_plain", [0.3, 0.3, 0.3], None, none),
        }
    }
}

/// Every building: walls with its facade, a flat roof or its `roof:shape`'s.
fn buildings(input: &MapSceneInput, book: &mut MaterialBook) -> Vec<SceneObject> {
    let cladding = map_cladding(input.map, input.facades, input.seed);
    let clad = Cladding::register(input.facades, &cladding, book);
    input
        .map
        .buildings
        .iter()
        .zip(&cladding)
        .enumerate()
        .map(|(i, (b, c))| {
            let (f, facade) = (c.facade, c.usable(input.facades));
            let mut walls =
                MeshBuilder::new(f.and_then(|f| clad.wall[f]).unwrap_or(clad.plain_wall));
            let roof = c.roof.and_then(|r| clad.roof.get(r).copied().flatten());
            let mut top = MeshBuilder::new(roof.unwrap_or(clad.plain_roof));
            for v in volumes(b, c.height) {
                for ring in std::iter::once(&v.outer).chain(&v.holes) {
                    for e in 0..ring.len() {
                        let (a, z) = (ring[e], ring[(e + 1) % ring.len()]);
                        wall(&mut walls, a, z, [v.base, v.eave], facade);
                    }
                }
                let (y, eave) = (KERB_Y + v.base, v.eave - v.base);
                match &v.roof {
                    Some(shape) => shape.build(y, eave, ROOF_TILE, &mut top, &mut walls),
                    None => top.polygon(&v.outer, &v.holes, KERB_Y + v.eave, ROOF_TILE),
                }
            }
            object(
                ObjectKind::Building,
                format!("building_{i:04}"),
                vec![walls, top],
            )
        })
        .collect()
}

/// The wall along footprint edge `a → b` (facing left of it: outwards on an outer ring,
/// into the courtyard on a hole), from `y0` to `y1` above the kerb, clad in facade `f` at
/// its own scale (see the module's note: the facade's floors counted from the ground, so a
/// volume on an upper floor carries on the floors below it), or plain.
fn wall(mesh: &mut MeshBuilder, a: [f64; 2], b: [f64; 2], [y0, y1]: [f64; 2], f: Option<&Facade>) {
    let Some(n) = left_normal(a, b).filter(|_| y1 > y0) else {
        return;
    };
    let (dx, dz) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dz * dz).sqrt();
    // + 0.0: no negative zero in a normal.
    let normal = [n[0] + 0.0, 0.0, n[1] + 0.0];
    let Some(f) = f else {
        let y = [KERB_Y + y0, KERB_Y + y1];
        mesh.wall(a, b, y, normal, [0.0, len / 3.0], [0.0, 1.0]);
        return;
    };
    let u = [0.0, len / f.width];
    let floor = f.height / f64::from(f.floors);
    // v runs 0 at the facade's top to 1 at its ground line; its ground floor is the last
    // 1 / floors of v, the floors above it the rest: pieces of (bottom, top, v at the
    // bottom, v at the top), each cut to y0…y1.
    let ground_v = 1.0 - 1.0 / f64::from(f.floors);
    let upper = f.height - floor;
    let mut piece = (0.0, floor, 1.0, ground_v);
    while piece.0 < y1 {
        let (s, e, vs, ve) = piece;
        let (lo, hi) = (s.max(y0), e.min(y1));
        if hi > lo {
            let v = |y: f64| vs + (ve - vs) * (y - s) / (e - s);
            mesh.wall(a, b, [KERB_Y + lo, KERB_Y + hi], normal, u, [v(hi), v(lo)]);
        }
        if upper <= 0.0 {
            break;
        }
        piece = (e, e + upper, ground_v, 0.0);
    }
}
