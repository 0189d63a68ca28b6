//! What an inserted object is to moving traffic (`[traffic]`), as the objects stage
//! placed it: the traffic stage reads it to drive the lanes.

use super::Axis;

/// An object's part in the traffic.
#[derive(Clone, Debug, PartialEq)]
pub enum TrafficRole {
    /// A vehicle standing in a lane (a car, or a ridden bicycle), which drives when the
    /// traffic moves.
    Vehicle(LaneVehicle),
    /// Moves with the object `back` places before it in the scene (a car's number plate,
    /// a bicycle's rider).
    Carried { back: u32 },
    /// A signal head at a street corner, showing the state of the road it looks along.
    Signal { corner: [f64; 2], axis: Axis },
    /// A person walking: along a sidewalk strip, or across a road on a zebra crossing.
    Pedestrian(Walk),
}

/// A person's walk, in world metres (x east, z south): straight on, never turning.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Walk {
    /// Unit direction it walks (x, z).
    pub travel: [f64; 2],
    /// Where it stands in the scene.
    pub centre: [f64; 2],
    /// The radius of the ground it takes.
    pub room: f64,
    /// The road it walks beside or crosses ([`crate::model::Road::id`]).
    pub road: u32,
    /// How far it may walk: on a sidewalk, to the first thing standing in its way (or the
    /// strip's end); on a zebra crossing, to its place on the far side (a way the objects
    /// stage kept clear).
    pub reach: f64,
    /// `Some` for a person crossing a road, or waiting at a zebra's end to.
    pub crossing: Option<Crossing>,
}

/// The zebra crossing a person crosses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The zebra's range along the road crossed, metres.
    pub zebra: [f64; 2],
    /// Waiting at the zebra's end at time 0 (it crosses when its signal lets it); else
    /// already on the zebra (it walks on at once).
    pub waiting: bool,
}

/// A vehicle in a lane, in world metres (x east, z south).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneVehicle {
    /// The road it stands on ([`crate::model::Road::id`]).
    pub road: u32,
    /// Unit direction it drives, (x, z): along its road.
    pub travel: [f64; 2],
    /// The middle of the rectangle of road it takes.
    pub centre: [f64; 2],
    /// Half its length (along `travel`) and half its width.
    pub half: [f64; 2],
    /// A ridden bicycle (slower than a car).
    pub bicycle: bool,
}
