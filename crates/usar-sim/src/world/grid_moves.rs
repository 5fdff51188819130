//! The grid moves out of a cell and their costs, as bit masks tabulated per inflation.
//!
//! The grid moves out of a cell as an 8-bit mask, and a table of every cell's mask for one
//! inflation, built once: grid searches (A* detours, distance fields, their descents) then
//! read one byte per expanded cell instead of testing up to twelve neighbour clearances.
//!
//! Bit `b` of a mask is the move `MOVES[b]`; a mask's moves come out in ascending bit order,
//! which is the order [`super::clearance_grid::ClearanceGrid::successors`] documents (east, west,
//! north, south, then north-east, north-west, south-east, south-west), so a table changes no
//! search result.

/// A* cost of a straight grid move (a diagonal costs [`DIAGONAL_COST`]).
pub const STRAIGHT_COST: u32 = 1000;
/// A* cost of a diagonal grid move (~ sqrt(2) * [`STRAIGHT_COST`]).
pub const DIAGONAL_COST: u32 = 1414;

/// The eight grid moves in successor order: (dx, dy, cost in planner cost units).
pub(super) const MOVES: [(i64, i64, u32); 8] = [
    (1, 0, STRAIGHT_COST),
    (-1, 0, STRAIGHT_COST),
    (0, 1, STRAIGHT_COST),
    (0, -1, STRAIGHT_COST),
    (1, 1, DIAGONAL_COST),
    (-1, 1, DIAGONAL_COST),
    (1, -1, DIAGONAL_COST),
    (-1, -1, DIAGONAL_COST),
];

/// The moves out of cell `cell` of a grid `nx` cells wide whose mask is `mask`, as (cell,
/// cost), in ascending bit order.
#[derive(Debug, Clone, Copy)]
pub(super) struct Moves {
    cell: u32,
    nx: u32,
    mask: u8,
}

impl Moves {
    /// The moves of `mask` out of `cell` (the mask must only hold moves that stay in the grid).
    pub(super) fn new(cell: u32, nx: u32, mask: u8) -> Self {
        Self { cell, nx, mask }
    }
}

impl Iterator for Moves {
    type Item = (u32, u32);

    fn next(&mut self) -> Option<(u32, u32)> {
        if self.mask == 0 {
            return None;
        }
        let b = self.mask.trailing_zeros() as usize;
        self.mask &= self.mask - 1;
        let (dx, dy, cost) = MOVES[b];
        let to = i64::from(self.cell) + dy * i64::from(self.nx) + dx;
        Some((to as u32, cost))
    }
}

/// Every cell's move mask for one inflation (one byte per cell).
#[derive(Debug, Clone)]
pub(super) struct MoveTable {
    inflation_bits: u32,
    masks: Vec<u8>,
}

impl MoveTable {
    /// The table of `cells` cells for inflation `inflation` metres, cell `c`'s mask being
    /// `mask_of(c)`.
    pub(super) fn new(inflation: f32, cells: u32, mask_of: impl Fn(u32) -> u8) -> Self {
        Self {
            inflation_bits: inflation.to_bits(),
            masks: (0..cells).map(mask_of).collect(),
        }
    }

    /// Whether this is the table for `inflation` metres (the same `f32`, bit for bit).
    pub(super) fn is_for(&self, inflation: f32) -> bool {
        self.inflation_bits == inflation.to_bits()
    }

    /// Cell `cell`'s mask.
    pub(super) fn mask(&self, cell: u32) -> u8 {
        self.masks[cell as usize]
    }
}
