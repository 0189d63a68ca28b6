//! What a scene object is, set by the stage that makes it: the scene's ground, blocks,
//! roads, markings, sidewalks, buildings and lamps; the objects stage's text plates, signs
//! (plates), poles, traffic lights, cars, bicycles and riders, people, trees and user meshes.
//!
//! Stages and tools ask an object's kind, never its name: names (`car_0042`) are stable
//! labels for people and files, and a user mesh is named after its label.

use serde::{Deserialize, Serialize};

/// An object's kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObjectKind {
    Ground,
    Block,
    Road,
    Marking,
    Sidewalk,
    Building,
    Lamp,
    /// A text plate on a wall, or a street-name sign's plate.
    Text,
    /// A traffic sign's plate (face and back); its pole is a [`ObjectKind::SignPole`].
    Sign,
    SignPole,
    SignalPole,
    TrafficLight,
    StreetPole,
    Car,
    Bicycle,
    Rider,
    Person,
    Tree,
    /// A user's OBJ model.
    Mesh,
    /// The wooded hills round the city, beyond its ground.
    Hills,
}

impl ObjectKind {
    /// Every kind, in declaration order.
    pub const ALL: [ObjectKind; 20] = [
        ObjectKind::Ground,
        ObjectKind::Block,
        ObjectKind::Road,
        ObjectKind::Marking,
        ObjectKind::Sidewalk,
        ObjectKind::Building,
        ObjectKind::Lamp,
        ObjectKind::Text,
        ObjectKind::Sign,
        ObjectKind::SignPole,
        ObjectKind::SignalPole,
        ObjectKind::TrafficLight,
        ObjectKind::StreetPole,
        ObjectKind::Car,
        ObjectKind::Bicycle,
        ObjectKind::Rider,
        ObjectKind::Person,
        ObjectKind::Tree,
        ObjectKind::Mesh,
        ObjectKind::Hills,
    ];

    /// Its name in `instances.json` and `cityspec stats` (snake case).
    pub fn name(self) -> &'static str {
        match self {
            ObjectKind::Ground => "ground",
            ObjectKind::Block => "block",
            ObjectKind::Road => "road",
            ObjectKind::Marking => "marking",
            ObjectKind::Sidewalk => "sidewalk",
            ObjectKind::Building => "building",
            ObjectKind::Lamp => "lamp",
            ObjectKind::Text => "text",
            ObjectKind::Sign => "sign",
            ObjectKind::SignPole => "sign_pole",
            ObjectKind::SignalPole => "signal_pole",
            ObjectKind::TrafficLight => "traffic_light",
            ObjectKind::StreetPole => "street_pole",
            ObjectKind::Car => "car",
            ObjectKind::Bicycle => "bicycle",
            ObjectKind::Rider => "rider",
            ObjectKind::Person => "person",
            ObjectKind::Tree => "tree",
            ObjectKind::Mesh => "mesh",
            ObjectKind::Hills => "hills",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_s_name_is_its_serialized_form() {
        for kind in ObjectKind::ALL {
            let json = serde_json::to_string(&kind).expect("kinds serialize");
            assert_eq!(json, format!("\"{}\"", kind.name()));
        }
    }
}
