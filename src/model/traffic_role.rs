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
