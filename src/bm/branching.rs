//! Samples of the branching diagram on the cell's faces (Moebius diagram of the other faces' sites).
use super::cell_input::CellInput;
use super::complex::Complex;

/// Branching samples: (slot, (u,v) in the slot's plane, 3D position).
pub fn samples(_input: &CellInput, _cx: &Complex) -> Vec<(usize, [f64; 2], [f64; 3])> {
    Vec::new()
}
