//! The elements of an extract, streamed to a [`Sink`] in the file's order: PBF blocks
//! decoded one at a time (`osmpbf`), XML read event by event (`quick-xml`). Nothing here
//! keeps an element after handing it on.

use std::io::Cursor;

use osmpbf::{BlobDecode, BlobReader, Element, RelMemberType};
use quick_xml::events::{BytesStart, Event};

use super::OsmError;

/// Receives an extract's elements.
pub trait Sink {
    /// The file's own bounds (`<bounds>` in XML, the header's box in PBF), south, west,
    /// north, east in degrees.
    fn bounds(&mut self, south: f64, west: f64, north: f64, east: f64);
    /// A node at `lat`, `lon` in OSM's own unit, 10⁻⁷ degrees (PBF stores nanodegrees
    /// rounded to it, XML writes 7 decimals): both formats give the same integers, and so
    /// the same map to the bit.
    fn node(&mut self, id: i64, lat: i32, lon: i32, tags: &[(&str, &str)]);
    fn way(&mut self, id: i64, refs: &[i64], tags: &[(&str, &str)]);
    /// Only the relation's way members, as `(way id, role)`.
    fn relation(&mut self, id: i64, ways: &[(i64, &str)], tags: &[(&str, &str)]);
}

/// Whether `bytes` look like a PBF file: a 4-byte header length, then a `BlobHeader`
/// whose first field is the type string `OSMHeader`.
pub fn is_pbf(bytes: &[u8]) -> bool {
    bytes.len() > 8 && bytes[4] == 0x0a && bytes[6..].starts_with(b"OSMHeader")
}

/// Streams a PBF extract.
pub fn read_pbf(bytes: &[u8], sink: &mut impl Sink) -> Result<(), OsmError> {
    let pbf = |e: osmpbf::Error| OsmError::Pbf(e.to_string());
    for blob in BlobReader::new(Cursor::new(bytes)) {
        let blob = blob.map_err(pbf)?;
        match blob.decode().map_err(pbf)? {
            BlobDecode::OsmHeader(header) => {
                if let Some(b) = header.bbox() {
                    let (south, north) = (b.top.min(b.bottom), b.top.max(b.bottom));
                    sink.bounds(
                        round7(south),
                        round7(b.left),
                        round7(north),
                        round7(b.right),
                    );
                }
            }
            BlobDecode::OsmData(block) => {
                // Per block: the tags borrow the block's string table.
                let (mut refs, mut members, mut tags) = (Vec::new(), Vec::new(), Vec::new());
                for element in block.elements() {
                    match element {
                        Element::Node(n) => {
                            tags.clear();
                            tags.extend(n.tags());
                            sink.node(n.id(), n.decimicro_lat(), n.decimicro_lon(), &tags);
                        }
                        Element::DenseNode(n) => {
                            tags.clear();
                            tags.extend(n.tags());
                            sink.node(n.id(), n.decimicro_lat(), n.decimicro_lon(), &tags);
                        }
                        Element::Way(w) => {
                            refs.clear();
                            refs.extend(w.refs());
                            tags.clear();
                            tags.extend(w.tags());
                            sink.way(w.id(), &refs, &tags);
                        }
                        Element::Relation(r) => {
                            members.clear();
                            members.extend(r.members().filter_map(|m| {
                                (m.member_type == RelMemberType::Way)
                                    .then(|| (m.member_id, m.role().unwrap_or("")))
                            }));
                            tags.clear();
                            tags.extend(r.tags());
                            sink.relation(r.id(), &members, &tags);
                        }
                    }
                }
            }
            BlobDecode::Unknown(_) => {}
        }
    }
    Ok(())
}

/// The element being read from XML: its attributes and the children seen so far.
#[derive(Default)]
struct Open {
    kind: OpenKind,
    id: i64,
    lat: f64,
    lon: f64,
    tags: Vec<(String, String)>,
    refs: Vec<i64>,
    members: Vec<(i64, String)>,
}

#[derive(Default, Clone, Copy, PartialEq)]
enum OpenKind {
    #[default]
    None,
    Node,
    Way,
    Relation,
}

/// Streams an OSM XML extract.
pub fn read_xml(bytes: &[u8], sink: &mut impl Sink) -> Result<(), OsmError> {
    let mut reader = quick_xml::Reader::from_reader(bytes);
    let mut buf = Vec::new();
    let mut open = Open::default();
    let mut seen_osm = false;
    loop {
        let at = reader.buffer_position();
        let event = reader
            .read_event_into(&mut buf)
            .map_err(|e| OsmError::Xml {
                offset: at,
                message: e.to_string(),
            })?;
        let xml = |message: String| OsmError::Xml {
            offset: at,
            message,
        };
        match event {
            Event::Start(e) | Event::Empty(e) if e.name().as_ref() == b"osm" => seen_osm = true,
            Event::Start(ref e) => start(e, &mut open, sink).map_err(xml)?,
            Event::Empty(ref e) => {
                start(e, &mut open, sink).map_err(xml)?;
                if matches!(e.name().as_ref(), b"node" | b"way" | b"relation") {
                    finish(&mut open, sink);
                }
            }
            Event::End(e) if matches!(e.name().as_ref(), b"node" | b"way" | b"relation") => {
                finish(&mut open, sink)
            }
            Event::Eof => break,
            _ => {}
        }
        buf.clear();
    }
    if seen_osm {
        Ok(())
    } else {
        Err(OsmError::NotOsm)
    }
}

/// An element's start tag (or a child's: `tag`, `nd`, `member`, `bounds`).
fn start(e: &BytesStart, open: &mut Open, sink: &mut impl Sink) -> Result<(), String> {
    let name = e.name();
    let tag = String::from_utf8_lossy(name.as_ref()).into_owned();
    let attr = |key: &str| -> Result<Option<String>, String> {
        match e.try_get_attribute(key) {
            Ok(Some(a)) => a
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map(|v| Some(v.into_owned()))
                .map_err(|err| format!("<{tag}> attribute {key}: {err}")),
            Ok(None) => Ok(None),
            Err(err) => Err(format!("<{tag}>: {err}")),
        }
    };
    let need = |key: &str| attr(key)?.ok_or_else(|| format!("<{tag}> has no {key}"));
    match name.as_ref() {
        b"node" | b"way" | b"relation" => {
            *open = Open {
                kind: match name.as_ref() {
                    b"node" => OpenKind::Node,
                    b"way" => OpenKind::Way,
                    _ => OpenKind::Relation,
                },
                id: number(&tag, "id", &need("id")?)?,
                ..Open::default()
            };
            if open.kind == OpenKind::Node {
                open.lat = number(&tag, "lat", &need("lat")?)?;
                open.lon = number(&tag, "lon", &need("lon")?)?;
                if !(open.lat.abs() <= 90.0 && open.lon.abs() <= 180.0) {
                    return Err(format!(
                        "<node id=\"{}\"> lies at lat {}, lon {}: outside [-90, 90] × [-180, 180]",
                        open.id, open.lat, open.lon
                    ));
                }
            }
        }
        b"tag" if open.kind != OpenKind::None => open.tags.push((need("k")?, need("v")?)),
        b"nd" if open.kind == OpenKind::Way => open.refs.push(number(&tag, "ref", &need("ref")?)?),
        b"member" if open.kind == OpenKind::Relation && need("type")? == "way" => {
            let role = attr("role")?.unwrap_or_default();
            open.members
                .push((number(&tag, "ref", &need("ref")?)?, role));
        }
        b"bounds" => {
            let corner = |key: &str| -> Result<f64, String> { number(&tag, key, &need(key)?) };
            let (s, w) = (corner("minlat")?, corner("minlon")?);
            let (n, e) = (corner("maxlat")?, corner("maxlon")?);
            sink.bounds(round7(s), round7(w), round7(n), round7(e));
        }
        _ => {}
    }
    Ok(())
}

/// Hands the open element to the sink.
fn finish(open: &mut Open, sink: &mut impl Sink) {
    let tags: Vec<(&str, &str)> = open
        .tags
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    match open.kind {
        OpenKind::Node => {
            let e7 = |deg: f64| (deg * 1e7).round() as i32;
            sink.node(open.id, e7(open.lat), e7(open.lon), &tags)
        }
        OpenKind::Way => sink.way(open.id, &open.refs, &tags),
        OpenKind::Relation => {
            let members: Vec<(i64, &str)> = open
                .members
                .iter()
                .map(|(id, r)| (*id, r.as_str()))
                .collect();
            sink.relation(open.id, &members, &tags)
        }
        OpenKind::None => {}
    }
    open.kind = OpenKind::None;
}

/// Degrees rounded to OSM's 10⁻⁷.
fn round7(deg: f64) -> f64 {
    (deg * 1e7).round() / 1e7
}

fn number<T: std::str::FromStr>(tag: &str, key: &str, text: &str) -> Result<T, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("<{tag}> {key}=\"{text}\" is not a number"))
}
