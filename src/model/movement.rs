//! Where moving traffic stands at one instant, relative to the scene as built: what the
//! renderer, the LiDAR, the flow and the labels apply to a frame ([`crate::traffic`]).

/// The scene's moving objects at one instant.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Movement {
    /// Every object that can move (instance id = object index + 1), ascending, with how
    /// far it stands from where the scene has it, world metres (x, y, z). Objects standing
    /// still at this instant are listed too, with a zero offset: the list is the same
    /// objects at every instant.
    pub moves: Vec<(u32, [f64; 3])>,
    /// Material swaps: in object `instance`, every triangle of material `from` takes
    /// material `to` (a signal lamp lit or put out). Ascending by instance.
    pub recolour: Vec<Recolour>,
    /// Per signal head (instance id, ascending), the lamp it shows: `red`, `amber` or
    /// `green` (its COCO attribute `state`).
    pub signals: Vec<(u32, &'static str)>,
}

/// One material swap of [`Movement::recolour`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Recolour {
    pub instance: u32,
    pub from: u32,
    pub to: u32,
}

impl Movement {
    /// Object `instance`'s offset, zero when it does not move.
    pub fn offset(&self, instance: u32) -> [f64; 3] {
        self.moves
            .binary_search_by_key(&instance, |(id, _)| *id)
            .map_or([0.0; 3], |k| self.moves[k].1)
    }

    /// Whether object `instance` is one that can move.
    pub fn moves(&self, instance: u32) -> bool {
        self.moves
            .binary_search_by_key(&instance, |(id, _)| *id)
            .is_ok()
    }
}
