//! The `[[objects]]` tables: inserted object classes (text on walls, traffic signs, user
//! meshes), each with its annotation label, count and placement ranges.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// One class of inserted objects. A key that does not apply to the `kind` (a `model` on a
/// `traffic_light`) is an error, as an unknown key is: [`KIND_KEYS`] says which kinds each
/// key applies to, and the schema carries it as one `if kind … then` rule per kind, so
/// editors flag such a key too.
///
/// `count` objects are attempted; one that does not fit is drawn again a few times (other
/// words and size, another body, a tree's size); when the city still has no room for
/// them all (walls, curbs or strips nearly full), fewer are placed and the build reports
/// the shortfall.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = kind_rules)]
pub struct ObjectSpec {
    /// What to insert: `"text"` (words on walls facing a road), `"sign"` (traffic signs on
    /// poles beside the roads), `"mesh"` (a user OBJ model), `"car"` (cars, vans, buses
    /// and trucks parked at the curbs and standing in the lanes), `"tree"` (street trees
    /// in the sidewalk strips and on the blocks' open paving), `"person"` (pedestrians in
    /// the sidewalk strips, walking along the street or standing) or `"street_name"`
    /// (street-name signs on poles at the street corners: two double-sided plates naming
    /// the two streets, four text objects; `count` counts poles) or `"traffic_light"`
    /// (signal poles at the street corners, each with two heads looking along the two
    /// roads, one lit red, amber or green; `count` counts poles) or `"bicycle"` (bicycles
    /// parked in the sidewalk strips and ridden in the driving lanes, each ridden one with
    /// a rider of class `rider`; `count` counts bicycles). A map layout (`[layout.osm]`)
    /// takes every kind (`mesh` seeded or at the map's nodes, `street_name` with the map's
    /// names).
    pub kind: EntryKind,
    /// Annotation category of these objects, e.g. `"text"`, `"traffic_sign"`, `"bench"`.
    /// Default: the kind's own (`text`, `traffic_sign`, `car`, `tree`, `person`,
    /// `traffic_light`, `bicycle`); a mesh needs one.
    #[serde(default)]
    #[schemars(regex(pattern = r"^[a-z][a-z0-9_]{0,31}$"))]
    pub label: String,
    /// How many to place (fewer when they do not fit).
    #[serde(default = "default_count")]
    #[schemars(range(max = 100000))]
    pub count: u32,
    /// text, street_name: letter height range `[low, high]` in metres.
    #[serde(default = "default_letter_height")]
    #[schemars(inner(range(min = 0.05, max = 20.0)))]
    pub letter_height: [f64; 2],
    /// text, street_name: letter case of the words.
    #[serde(default)]
    pub case: TextCase,
    /// text: words per sign, range `[low, high]`.
    #[serde(default = "default_words")]
    #[schemars(inner(range(min = 1, max = 8)))]
    pub words: [u32; 2],
    /// text, street_name: a UTF-8 word file (words separated by spaces or line breaks, lines starting
    /// with `#` skipped, at most 1 MiB), relative to the spec's folder; its bytes are part
    /// of the build's cache key. The built-in list of 401 common English words when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "String", length(min = 1))]
    pub words_file: Option<String>,
    /// sign: which signs to draw from (all when empty).
    #[serde(default)]
    #[schemars(length(max = 64))]
    pub signs: Vec<SignKind>,
    /// mesh: the OBJ model, relative to the spec's folder; its MTL and textures lie beside it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "String", length(min = 1))]
    pub model: Option<String>,
    /// mesh: uniform scale range `[low, high]` applied to the model's units (metres).
    #[serde(default = "default_scale")]
    #[schemars(inner(range(min = 0.001, max = 1000.0)))]
    pub scale: [f64; 2],
    /// mesh: rotation about the vertical axis, range `[low, high]` in degrees. On a lane it
    /// is added to the lane's heading (the model's front is its −z side).
    #[serde(default = "default_rotation")]
    #[schemars(inner(range(min = -3600.0, max = 3600.0)))]
    pub rotation: [f64; 2],
    /// mesh: where the models stand.
    #[serde(default)]
    pub on: Ground,
    /// mesh, on a map layout only: the tag of the map's nodes the models stand at, as the
    /// map writes it (`"amenity=bench"`; also `"highway=bench"`, `"natural=tree"`): one at
    /// each such node off the carriageways and out of the buildings, in node order, up to
    /// `count`, its front (−z) towards the nearest paved road within 15 m (turned from
    /// there by `rotation`; farther off, turned by `rotation` alone). Without it a map's
    /// models are seeded on its sidewalks or lanes (`on`), as on a layout.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(length(min = 3))]
    pub at: Option<String>,
    /// car: body types to draw from (all when empty); list one twice to draw it twice as often.
    #[serde(default)]
    #[schemars(length(max = 64))]
    pub bodies: Vec<CarBody>,
    /// car: share of the cars parked along the curbs; the others stand in the driving lanes.
    /// bicycle: share of the bicycles parked in the sidewalk strips; the others are ridden.
    #[serde(default = "default_parked")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub parked: f64,
    /// tree: crown shapes to draw from (all when empty).
    #[serde(default)]
    #[schemars(length(max = 64))]
    pub species: Vec<TreeSpecies>,
    /// tree, person, bicycle: height range `[low, high]` in metres (a bicycle's: its
    /// rider's, standing, which sets the saddle). Default `[5, 10]` for trees (2–40
    /// allowed), `[1.5, 1.95]` for people and riders (0.8–2.3 allowed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(inner(range(min = 0.8, max = 40.0)))]
    pub height: Option<[f64; 2]>,
    /// person: share of the people walking across the zebra crossings (in the road's
    /// inner 2.4 m either side of its centre line, clear of the line a roads camera drives
    /// by default; on a map, clear of its cameras' lane); the others are in the sidewalk
    /// strips.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub crossing: f64,
    /// person: share of the people not crossing who stand at the curb at a zebra
    /// crossing's end, facing the road as if waiting to cross; the others stand or walk
    /// along the sidewalk strips.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub waiting: f64,
    /// person: share of the people neither crossing nor waiting who stand or walk on the
    /// paths across a map's parks (its footways, paths and cycleways over green ground),
    /// along the path; where there are none (a layout, or a map without them), they stand
    /// in the sidewalk strips like the others.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub parks: f64,
    /// person: share of the people neither crossing, waiting nor in the parks who stand or
    /// walk on a map's squares (its squares, pedestrian areas and surface car parks),
    /// facing any way; where there are none (a layout, or a map without them), they
    /// stand in the sidewalk strips like the others.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub squares: f64,
    /// tree: share of the trees planted on the blocks' open paving (plazas, yards) instead
    /// of the sidewalk strips.
    #[serde(default = "default_plazas")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub plazas: f64,
}

impl ObjectSpec {
    /// The label an entry of `kind` gets when the spec gives none; mesh entries have none.
    pub fn default_label(kind: EntryKind) -> Option<&'static str> {
        match kind {
            EntryKind::Text | EntryKind::StreetName => Some("text"),
            EntryKind::Sign => Some("traffic_sign"),
            EntryKind::Car => Some("car"),
            EntryKind::Tree => Some("tree"),
            EntryKind::Person => Some("person"),
            EntryKind::TrafficLight => Some("traffic_light"),
            EntryKind::Bicycle => Some("bicycle"),
            EntryKind::Mesh => None,
        }
    }

    /// Classes an entry of `kind` gives objects besides its `label`: the poles of
    /// street-name signs and traffic lights, the riders of bicycles.
    pub fn companion_classes(kind: EntryKind) -> &'static [&'static str] {
        match kind {
            EntryKind::StreetName | EntryKind::TrafficLight => &["pole"],
            EntryKind::Bicycle => &[RIDER_CLASS],
            _ => &[],
        }
    }

    /// Of [`ObjectSpec::companion_classes`], those a camera path annotates when the spec
    /// lists no classes: the riders (people), not the poles (street furniture).
    pub fn annotated_companions(kind: EntryKind) -> &'static [&'static str] {
        match kind {
            EntryKind::Bicycle => &[RIDER_CLASS],
            _ => &[],
        }
    }

    /// The height range of a tree or a person entry: `height`, else the kind's default.
    pub fn height_range(&self) -> [f64; 2] {
        self.height.unwrap_or(match self.kind {
            EntryKind::Person | EntryKind::Bicycle => PERSON_HEIGHT,
            _ => TREE_HEIGHT,
        })
    }

    /// The heights an entry of `kind` may have, when it has one.
    pub fn height_bounds(kind: EntryKind) -> Option<[f64; 2]> {
        match kind {
            EntryKind::Tree => Some([2.0, 40.0]),
            EntryKind::Person | EntryKind::Bicycle => Some([0.8, 2.3]),
            _ => None,
        }
    }
}

/// The keys of an `[[objects]]` table that apply to some kinds only, with those kinds; the
/// others (`kind`, `label`, `count`) apply to every kind. A key written for a kind it does
/// not apply to is an error.
pub const KIND_KEYS: &[(&str, &[EntryKind])] = {
    use EntryKind::*;
    &[
        ("letter_height", &[Text, StreetName]),
        ("case", &[Text, StreetName]),
        ("words", &[Text]),
        ("words_file", &[Text, StreetName]),
        ("signs", &[Sign]),
        ("model", &[Mesh]),
        ("scale", &[Mesh]),
        ("rotation", &[Mesh]),
        ("on", &[Mesh]),
        ("at", &[Mesh]),
        ("bodies", &[Car]),
        ("parked", &[Car, Bicycle]),
        ("species", &[Tree]),
        ("height", &[Tree, Person, Bicycle]),
        ("crossing", &[Person]),
        ("waiting", &[Person]),
        ("parks", &[Person]),
        ("squares", &[Person]),
        ("plazas", &[Tree]),
    ]
};

/// The kinds `key` applies to; None when it applies to every kind (or is no key of an
/// `[[objects]]` table).
pub fn kinds_of_key(key: &str) -> Option<&'static [EntryKind]> {
    KIND_KEYS
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, kinds)| *kinds)
}

/// Adds to the `[[objects]]` schema one rule per kind: `if` the kind is this one, `then`
/// each key of [`KIND_KEYS`] that does not apply to it is `false` (allowed no value). An
/// unknown key stays `additionalProperties`' alone, so nothing is reported twice.
fn kind_rules(schema: &mut schemars::Schema) {
    use serde_json::{Map, Value, json};
    let rules: Vec<Value> = EntryKind::ALL
        .iter()
        .map(|kind| {
            let refused: Map<String, Value> = KIND_KEYS
                .iter()
                .filter(|(_, kinds)| !kinds.contains(kind))
                .map(|(key, _)| ((*key).to_string(), Value::Bool(false)))
                .collect();
            json!({
                "if": {"properties": {"kind": {"const": kind.name()}}, "required": ["kind"]},
                "then": {"properties": refused},
            })
        })
        .collect();
    schema.insert("allOf".to_string(), Value::Array(rules));
}

/// The class of the riders a bicycle entry puts on its ridden bicycles.
pub const RIDER_CLASS: &str = "rider";

/// Default height range of trees, metres.
pub const TREE_HEIGHT: [f64; 2] = [5.0, 10.0];
/// Default height range of people, metres.
pub const PERSON_HEIGHT: [f64; 2] = [1.5, 1.95];

/// Gives every entry without a `label` its kind's default (a mesh entry keeps none, and
/// the checks report it).
pub(crate) fn fill_default_labels(objects: &mut [ObjectSpec]) {
    for object in objects.iter_mut().filter(|o| o.label.is_empty()) {
        if let Some(label) = ObjectSpec::default_label(object.kind) {
            object.label = label.to_owned();
        }
    }
}

/// A car body cityspec builds.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum CarBody {
    Sedan,
    Hatchback,
    Estate,
    Coupe,
    Suv,
    Minivan,
    Pickup,
    Van,
    Bus,
    Truck,
}

impl CarBody {
    /// Every body, in declaration order.
    pub const ALL: [CarBody; 10] = [
        CarBody::Sedan,
        CarBody::Hatchback,
        CarBody::Estate,
        CarBody::Coupe,
        CarBody::Suv,
        CarBody::Minivan,
        CarBody::Pickup,
        CarBody::Van,
        CarBody::Bus,
        CarBody::Truck,
    ];

    /// The snake_case name the spec uses (the `body` attribute of a car).
    pub fn name(self) -> &'static str {
        match self {
            CarBody::Sedan => "sedan",
            CarBody::Hatchback => "hatchback",
            CarBody::Estate => "estate",
            CarBody::Coupe => "coupe",
            CarBody::Suv => "suv",
            CarBody::Minivan => "minivan",
            CarBody::Pickup => "pickup",
            CarBody::Van => "van",
            CarBody::Bus => "bus",
            CarBody::Truck => "truck",
        }
    }
}

/// A tree crown shape cityspec builds.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum TreeSpecies {
    // A round broadleaf crown of a ball and a few lobes (lime, maple).
    Round,
    // A tall narrow crown (poplar, hornbeam).
    Columnar,
    // Stacked, ragged tiers of foliage, widest at the bottom (spruce, fir).
    Conifer,
    // A wide, irregular crown of several blobs (plane, acacia).
    Spreading,
    // A thin white trunk under a loose crown of small blobs.
    Birch,
    // A dome with a curtain of foliage hanging round it (willow).
    Weeping,
    // A tall bare trunk under a few flat clumps (Scots pine, stone pine).
    Pine,
}

impl TreeSpecies {
    /// Every species, in declaration order.
    pub const ALL: [TreeSpecies; 7] = [
        TreeSpecies::Round,
        TreeSpecies::Columnar,
        TreeSpecies::Conifer,
        TreeSpecies::Spreading,
        TreeSpecies::Birch,
        TreeSpecies::Weeping,
        TreeSpecies::Pine,
    ];

    /// The snake_case name the spec uses (the `species` attribute of a tree).
    pub fn name(self) -> &'static str {
        match self {
            TreeSpecies::Round => "round",
            TreeSpecies::Columnar => "columnar",
            TreeSpecies::Conifer => "conifer",
            TreeSpecies::Spreading => "spreading",
            TreeSpecies::Birch => "birch",
            TreeSpecies::Weeping => "weeping",
            TreeSpecies::Pine => "pine",
        }
    }
}

// Not `model::ObjectKind`, the kind of a scene object the stages made.
/// Which kind of object an `[[objects]]` entry inserts (its `kind`).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum EntryKind {
    // Plain comments, not doc comments: so the schema is a simple `enum` and a wrong value
    // reads "expected one of …".
    Text,
    Sign,
    Mesh,
    Car,
    Tree,
    StreetName,
    Person,
    TrafficLight,
    Bicycle,
}

impl EntryKind {
    /// Every kind, in declaration order.
    pub const ALL: [EntryKind; 9] = [
        EntryKind::Text,
        EntryKind::Sign,
        EntryKind::Mesh,
        EntryKind::Car,
        EntryKind::Tree,
        EntryKind::StreetName,
        EntryKind::Person,
        EntryKind::TrafficLight,
        EntryKind::Bicycle,
    ];

    /// The snake_case name the spec uses.
    pub fn name(self) -> &'static str {
        match self {
            EntryKind::Text => "text",
            EntryKind::Sign => "sign",
            EntryKind::Mesh => "mesh",
            EntryKind::Car => "car",
            EntryKind::Tree => "tree",
            EntryKind::StreetName => "street_name",
            EntryKind::Person => "person",
            EntryKind::TrafficLight => "traffic_light",
            EntryKind::Bicycle => "bicycle",
        }
    }
}

/// Letter case of text objects.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TextCase {
    Lower,
    Upper,
    #[default]
    Title,
    // One of the three others, chosen per object.
    Mixed,
}

/// A traffic sign cityspec draws: Germany's catalogue (StVO, Vienna convention), its
/// official number (VZ, Verkehrszeichen) beside each. New types are appended, so a type's
/// place in [`SignKind::ALL`] (and its per-type category id) never moves.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum SignKind {
    // Plain comments: the schema stays a simple enum.
    // VZ 206, regulatory: stop (octagon).
    Stop,
    // VZ 205, regulatory: give way (inverted triangle).
    Yield,
    // VZ 274, regulatory: maximum speed (round).
    SpeedLimit,
    // VZ 267, regulatory: no entry (round).
    NoEntry,
    // VZ 350, information: pedestrian crossing (zebra) (square).
    PedestrianCrossing,
    // VZ 220, information: one-way street (rectangle).
    OneWay,
    // VZ 286, regulatory: restricted stopping (no parking) (round).
    NoParking,
    // VZ 314, information: parking (square).
    Parking,
    // VZ 283, regulatory: no stopping (round).
    NoStopping,
    // VZ 276, regulatory: no overtaking (round).
    NoOvertaking,
    // VZ 250, regulatory: no vehicles (round).
    NoVehicles,
    // VZ 251, regulatory: no motor vehicles (round).
    NoMotorVehicles,
    // VZ 254, regulatory: no bicycles (round).
    NoBicycles,
    // VZ 209, regulatory: turn right ahead (round).
    TurnRight,
    // VZ 214, regulatory: straight on or right (round).
    StraightOrRight,
    // VZ 237, regulatory: cycle path (round).
    CyclePath,
    // VZ 239, regulatory: footpath (round).
    Footpath,
    // VZ 240, regulatory: shared foot and cycle path (round).
    SharedPath,
    // VZ 306, priority: priority road (diamond).
    PriorityRoad,
    // VZ 301, priority: priority at the next junction (triangle).
    PriorityJunction,
    // VZ 101, warning: danger (triangle).
    Danger,
    // VZ 102, warning: crossroads, priority from the right (triangle).
    Crossroads,
    // VZ 103-10, warning: bend to the left (triangle).
    BendLeft,
    // VZ 103-20, warning: bend to the right (triangle).
    BendRight,
    // VZ 114, warning: slippery road (triangle).
    Slippery,
    // VZ 120, warning: road narrows (triangle).
    RoadNarrows,
    // VZ 123, warning: road works (triangle).
    RoadWorks,
    // VZ 131, warning: traffic signals ahead (triangle).
    TrafficSignals,
    // VZ 133, warning: pedestrians (triangle).
    Pedestrians,
    // VZ 136, warning: children (triangle).
    Children,
    // VZ 138, warning: cyclists (triangle).
    Cyclists,
    // VZ 357, information: dead end (square).
    DeadEnd,
    // VZ 224, information: bus stop (round).
    BusStop,
}

/// What a sign is for, as the StVO groups them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SignGroup {
    Regulatory,
    Warning,
    Priority,
    Information,
}

impl SignKind {
    /// Every sign, in declaration order (the order of per-type categories).
    pub const ALL: [SignKind; 33] = [
        SignKind::Stop,
        SignKind::Yield,
        SignKind::SpeedLimit,
        SignKind::NoEntry,
        SignKind::PedestrianCrossing,
        SignKind::OneWay,
        SignKind::NoParking,
        SignKind::Parking,
        SignKind::NoStopping,
        SignKind::NoOvertaking,
        SignKind::NoVehicles,
        SignKind::NoMotorVehicles,
        SignKind::NoBicycles,
        SignKind::TurnRight,
        SignKind::StraightOrRight,
        SignKind::CyclePath,
        SignKind::Footpath,
        SignKind::SharedPath,
        SignKind::PriorityRoad,
        SignKind::PriorityJunction,
        SignKind::Danger,
        SignKind::Crossroads,
        SignKind::BendLeft,
        SignKind::BendRight,
        SignKind::Slippery,
        SignKind::RoadNarrows,
        SignKind::RoadWorks,
        SignKind::TrafficSignals,
        SignKind::Pedestrians,
        SignKind::Children,
        SignKind::Cyclists,
        SignKind::DeadEnd,
        SignKind::BusStop,
    ];

    /// The snake_case name the spec uses.
    pub fn name(self) -> &'static str {
        match self {
            SignKind::Stop => "stop",
            SignKind::Yield => "yield",
            SignKind::SpeedLimit => "speed_limit",
            SignKind::NoEntry => "no_entry",
            SignKind::PedestrianCrossing => "pedestrian_crossing",
            SignKind::OneWay => "one_way",
            SignKind::NoParking => "no_parking",
            SignKind::Parking => "parking",
            SignKind::NoStopping => "no_stopping",
            SignKind::NoOvertaking => "no_overtaking",
            SignKind::NoVehicles => "no_vehicles",
            SignKind::NoMotorVehicles => "no_motor_vehicles",
            SignKind::NoBicycles => "no_bicycles",
            SignKind::TurnRight => "turn_right",
            SignKind::StraightOrRight => "straight_or_right",
            SignKind::CyclePath => "cycle_path",
            SignKind::Footpath => "footpath",
            SignKind::SharedPath => "shared_path",
            SignKind::PriorityRoad => "priority_road",
            SignKind::PriorityJunction => "priority_junction",
            SignKind::Danger => "danger",
            SignKind::Crossroads => "crossroads",
            SignKind::BendLeft => "bend_left",
            SignKind::BendRight => "bend_right",
            SignKind::Slippery => "slippery",
            SignKind::RoadNarrows => "road_narrows",
            SignKind::RoadWorks => "road_works",
            SignKind::TrafficSignals => "traffic_signals",
            SignKind::Pedestrians => "pedestrians",
            SignKind::Children => "children",
            SignKind::Cyclists => "cyclists",
            SignKind::DeadEnd => "dead_end",
            SignKind::BusStop => "bus_stop",
        }
    }

    /// Its number in the StVO catalogue (`"206"` for stop).
    pub fn number(self) -> &'static str {
        match self {
            SignKind::Stop => "206",
            SignKind::Yield => "205",
            SignKind::SpeedLimit => "274",
            SignKind::NoEntry => "267",
            SignKind::PedestrianCrossing => "350",
            SignKind::OneWay => "220",
            SignKind::NoParking => "286",
            SignKind::Parking => "314",
            SignKind::NoStopping => "283",
            SignKind::NoOvertaking => "276",
            SignKind::NoVehicles => "250",
            SignKind::NoMotorVehicles => "251",
            SignKind::NoBicycles => "254",
            SignKind::TurnRight => "209",
            SignKind::StraightOrRight => "214",
            SignKind::CyclePath => "237",
            SignKind::Footpath => "239",
            SignKind::SharedPath => "240",
            SignKind::PriorityRoad => "306",
            SignKind::PriorityJunction => "301",
            SignKind::Danger => "101",
            SignKind::Crossroads => "102",
            SignKind::BendLeft => "103-10",
            SignKind::BendRight => "103-20",
            SignKind::Slippery => "114",
            SignKind::RoadNarrows => "120",
            SignKind::RoadWorks => "123",
            SignKind::TrafficSignals => "131",
            SignKind::Pedestrians => "133",
            SignKind::Children => "136",
            SignKind::Cyclists => "138",
            SignKind::DeadEnd => "357",
            SignKind::BusStop => "224",
        }
    }

    /// Its group in the catalogue.
    pub fn group(self) -> SignGroup {
        match self {
            SignKind::Stop
            | SignKind::Yield
            | SignKind::SpeedLimit
            | SignKind::NoEntry
            | SignKind::NoParking
            | SignKind::NoStopping
            | SignKind::NoOvertaking
            | SignKind::NoVehicles
            | SignKind::NoMotorVehicles
            | SignKind::NoBicycles
            | SignKind::TurnRight
            | SignKind::StraightOrRight
            | SignKind::CyclePath
            | SignKind::Footpath
            | SignKind::SharedPath => SignGroup::Regulatory,
            SignKind::Danger
            | SignKind::Crossroads
            | SignKind::BendLeft
            | SignKind::BendRight
            | SignKind::Slippery
            | SignKind::RoadNarrows
            | SignKind::RoadWorks
            | SignKind::TrafficSignals
            | SignKind::Pedestrians
            | SignKind::Children
            | SignKind::Cyclists => SignGroup::Warning,
            SignKind::PriorityRoad | SignKind::PriorityJunction => SignGroup::Priority,
            SignKind::PedestrianCrossing
            | SignKind::OneWay
            | SignKind::Parking
            | SignKind::DeadEnd
            | SignKind::BusStop => SignGroup::Information,
        }
    }
}

/// Where mesh objects stand.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Ground {
    // Mid-strip on the sidewalk beside a road.
    #[default]
    Sidewalk,
    // In the middle of a road's right-hand lane, heading with the traffic.
    Lane,
}

fn default_count() -> u32 {
    10
}
fn default_letter_height() -> [f64; 2] {
    [0.4, 1.0]
}
fn default_words() -> [u32; 2] {
    [1, 2]
}
fn default_scale() -> [f64; 2] {
    [1.0, 1.0]
}
fn default_rotation() -> [f64; 2] {
    [0.0, 360.0]
}
fn default_parked() -> f64 {
    0.75
}
fn default_plazas() -> f64 {
    0.25
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_fill_in() {
        let spec: ObjectSpec = toml::from_str("kind = \"text\"\nlabel = \"text\"\n").unwrap();
        assert_eq!(spec.count, 10);
        assert_eq!(spec.letter_height, [0.4, 1.0]);
        assert_eq!(spec.case, TextCase::Title);
        assert_eq!(spec.words, [1, 2]);
        assert!(spec.signs.is_empty());
        assert_eq!(spec.words_file, None);
        assert_eq!(spec.model, None);
        assert_eq!(spec.scale, [1.0, 1.0]);
        assert_eq!(spec.rotation, [0.0, 360.0]);
        assert_eq!(spec.on, Ground::Sidewalk);
    }

    #[test]
    fn kind_names_are_what_the_spec_reads() {
        for kind in EntryKind::ALL {
            let spec: ObjectSpec = toml::from_str(&format!("kind = {:?}\n", kind.name())).unwrap();
            assert_eq!(spec.kind, kind);
        }
    }

    #[test]
    fn labels_default_to_the_kind_except_for_meshes() {
        let kinds = [
            "car",
            "tree",
            "sign",
            "text",
            "mesh",
            "street_name",
            "person",
            "traffic_light",
        ];
        let mut specs: Vec<ObjectSpec> = kinds
            .iter()
            .map(|kind| toml::from_str(&format!("kind = {kind:?}\n")).unwrap())
            .collect();
        specs.push(toml::from_str("kind = \"car\"\nlabel = \"vehicle\"\n").unwrap());
        fill_default_labels(&mut specs);
        let labels: Vec<&str> = specs.iter().map(|s| s.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "car",
                "tree",
                "traffic_sign",
                "text",
                "",
                "text",
                "person",
                "traffic_light",
                "vehicle"
            ]
        );
        assert_eq!(specs[0].parked, 0.75);
        // Heights default by kind: trees' and people's.
        assert_eq!(specs[1].height_range(), [5.0, 10.0]);
        assert_eq!(specs[6].height_range(), [1.5, 1.95]);
        let tall: ObjectSpec = toml::from_str("kind = \"person\"\nheight = [1.8, 2]\n").unwrap();
        assert_eq!(tall.height_range(), [1.8, 2.0]);
    }

    #[test]
    fn every_key_applies_to_every_kind_or_is_listed() {
        let schema = schemars::schema_for!(ObjectSpec);
        let keys = schema.as_value()["properties"].as_object().unwrap();
        for key in keys.keys() {
            let general = ["kind", "label", "count"].contains(&key.as_str());
            assert!(general != kinds_of_key(key).is_some(), "{key}");
        }
        for (key, kinds) in KIND_KEYS {
            assert!(keys.contains_key(*key), "{key} is no key of ObjectSpec");
            assert!(!kinds.is_empty(), "{key}");
        }
        assert_eq!(schema.as_value()["allOf"].as_array().unwrap().len(), 9);
    }

    #[test]
    fn sign_names_match_serde() {
        for sign in SignKind::ALL {
            let json = serde_json::to_string(&sign).unwrap();
            assert_eq!(json, format!("\"{}\"", sign.name()));
        }
    }
}
