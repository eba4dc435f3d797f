//! The square block lattice: neighbour tables and spring constants.
//!
//! Blocks are numbered row-major, `i = iy · N_x + ix`. Each block has up to
//! eight neighbours, in the fixed order of [`DIRECTIONS`]. A missing neighbour
//! (at the edge) points back to the block itself with stiffness 0, so the
//! force loop needs no branch: its spring vector is the nonzero rest offset,
//! and zero stiffness gives zero force.

use super::params::SpringBlockParams;

/// Lattice offsets (Δix, Δiy) of the eight neighbours: four axial, then four
/// diagonal.
pub const DIRECTIONS: [(i32, i32); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (-1, -1),
    (1, -1),
    (-1, 1),
];

/// Neighbour tables and spring constants of an N_x × N_y lattice.
#[derive(Debug, Clone)]
pub struct Lattice {
    /// N_x.
    pub nx: usize,
    /// N_y.
    pub ny: usize,
    /// l, spacing \[m\].
    pub spacing: f64,
    /// Neighbour index per block and direction, `nbr[8 i + d]` (the block
    /// itself where there is none).
    pub nbr: Vec<u32>,
    /// Spring stiffness per block and direction, `k[8 i + d]` [N/m]: K_int on
    /// the axes, K_int/2 on the diagonals, 0 where there is no neighbour.
    pub k: Vec<f64>,
    /// Rest offset x of direction d, Δix · l \[m\].
    pub dx0: [f64; 8],
    /// Rest offset y of direction d, Δiy · l \[m\].
    pub dy0: [f64; 8],
    /// Rest length l_ij of direction d: l or √2 l \[m\].
    pub rest: [f64; 8],
    /// K_s, shear spring stiffness [N/m].
    pub k_shear: f64,
    /// m, block mass \[kg\].
    pub mass: f64,
}

impl Lattice {
    /// Builds the tables for validated parameters.
    pub fn new(p: &SpringBlockParams) -> Self {
        let (nx, ny) = (p.nx, p.ny);
        let l = p.spacing;
        let kint = p.k_internal();
        let mut nbr = Vec::with_capacity(8 * nx * ny);
        let mut k = Vec::with_capacity(8 * nx * ny);
        for iy in 0..ny as i64 {
            for ix in 0..nx as i64 {
                let i = (iy * nx as i64 + ix) as u32;
                for (d, &(ddx, ddy)) in DIRECTIONS.iter().enumerate() {
                    let (jx, jy) = (ix + ddx as i64, iy + ddy as i64);
                    if jx >= 0 && jx < nx as i64 && jy >= 0 && jy < ny as i64 {
                        nbr.push((jy * nx as i64 + jx) as u32);
                        k.push(if d < 4 { kint } else { kint / 2.0 });
                    } else {
                        nbr.push(i);
                        k.push(0.0);
                    }
                }
            }
        }
        let dx0 = DIRECTIONS.map(|(a, _)| a as f64 * l);
        let dy0 = DIRECTIONS.map(|(_, b)| b as f64 * l);
        let rest = DIRECTIONS.map(|(a, b)| ((a * a + b * b) as f64).sqrt() * l);
        Lattice {
            nx,
            ny,
            spacing: l,
            nbr,
            k,
            dx0,
            dy0,
            rest,
            k_shear: p.k_shear(),
            mass: p.block_mass(),
        }
    }

    /// Number of blocks.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Whether the lattice is empty (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_has_three_springs_and_interior_eight() {
        let p = SpringBlockParams {
            nx: 4,
            ny: 3,
            ..Default::default()
        };
        let lat = Lattice::new(&p);
        let count = |i: usize| lat.k[8 * i..8 * i + 8].iter().filter(|&&k| k > 0.0).count();
        assert_eq!(count(0), 3);
        assert_eq!(count(5), 8);
        assert_eq!(count(3), 3);
        // Each spring is seen from both ends with the same stiffness.
        for i in 0..lat.len() {
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                if lat.k[8 * i + d] > 0.0 {
                    let back = (0..8).find(|&e| lat.nbr[8 * j + e] as usize == i).unwrap();
                    assert_eq!(lat.k[8 * j + back].to_bits(), lat.k[8 * i + d].to_bits());
                }
            }
        }
    }
}
