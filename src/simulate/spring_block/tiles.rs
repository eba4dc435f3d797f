//! Hole clusters and their tiles: the geometry the parking of
//! [`super::park`] works on. A cluster is a connected set of free (hole)
//! blocks (8-neighbour springs); one wider or taller than [`TILE`] blocks
//! (the grooves of pattern S) is cut into [`TILE`] × [`TILE`] tiles, the
//! unit of parking. Each tile knows its blocks (in index order), the
//! contact blocks bordering it and the tiles of its cluster next to it.

use crate::models::spring_block::{Interface, Lattice};

/// Largest extent of a cluster kept whole (blocks); larger clusters are cut
/// into tiles of this many columns and rows.
pub const TILE: usize = 8;

/// Clusters of free blocks and their tiles, as flat index ranges.
#[derive(Debug, Clone)]
pub(crate) struct Tiling {
    /// Tiles of cluster c: `cstart[c]..cstart[c + 1]`.
    pub cstart: Vec<usize>,
    /// Whether cluster c is cut into several tiles.
    pub cut: Vec<bool>,
    /// Blocks of tile t: `blocks[start[t]..start[t + 1]]`.
    pub start: Vec<usize>,
    pub blocks: Vec<u32>,
    /// Contact blocks bordering tile t: `border[bstart[t]..bstart[t + 1]]`.
    pub bstart: Vec<usize>,
    pub border: Vec<u32>,
    /// Tiles of the same cluster next to tile t: `adj[astart[t]..astart[t + 1]]`.
    pub astart: Vec<usize>,
    pub adj: Vec<u32>,
    /// Cluster of each tile.
    pub tile_cluster: Vec<u32>,
    /// Tile of each block (u32::MAX for contact blocks).
    pub tile_of: Vec<u32>,
}

impl Tiling {
    /// Finds the clusters of the interface's free blocks and cuts those
    /// larger than [`TILE`].
    pub fn new(lat: &Lattice, iface: &Interface) -> Self {
        let n = lat.len();
        let nx = lat.nx;
        let mut cluster_of = vec![u32::MAX; n];
        let mut tile_of = vec![u32::MAX; n];
        let mut cstart = vec![0usize];
        let mut cut = Vec::new();
        let (mut start, mut blocks) = (vec![0usize], Vec::<u32>::new());
        let mut tile_cluster = Vec::new();
        let mut members = Vec::<u32>::new();
        for seed in 0..n {
            if !iface.is_free(seed) || cluster_of[seed] != u32::MAX {
                continue;
            }
            let c = cut.len() as u32;
            flood(lat, iface, seed, c, &mut cluster_of, &mut members);
            let xs = members.iter().map(|&i| i as usize % nx);
            let (x0, x1) = (xs.clone().min().unwrap(), xs.max().unwrap());
            let ys = members.iter().map(|&i| i as usize / nx);
            let (y0, y1) = (ys.clone().min().unwrap(), ys.max().unwrap());
            let whole = x1 - x0 < TILE && y1 - y0 < TILE;
            cut.push(!whole);
            let key = |i: u32| {
                let (x, y) = (i as usize % nx, i as usize / nx);
                ((y - y0) / TILE, (x - x0) / TILE)
            };
            let mut keys: Vec<(usize, usize)> = if whole {
                vec![(0, 0)]
            } else {
                members.iter().map(|&i| key(i)).collect()
            };
            keys.sort_unstable();
            keys.dedup();
            for kk in keys {
                let t = tile_cluster.len() as u32;
                for &i in &members {
                    if whole || key(i) == kk {
                        tile_of[i as usize] = t;
                        blocks.push(i);
                    }
                }
                start.push(blocks.len());
                tile_cluster.push(c);
            }
            cstart.push(tile_cluster.len());
        }
        let nt = tile_cluster.len();
        let (bstart, border, astart, adj) = neighbours(lat, &blocks, &start, &tile_of, nt);
        Tiling {
            cstart,
            cut,
            start,
            blocks,
            bstart,
            border,
            astart,
            adj,
            tile_cluster,
            tile_of,
        }
    }

    /// Number of clusters.
    pub fn clusters(&self) -> usize {
        self.cut.len()
    }

    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.tile_cluster.len()
    }

    /// Tiles of cluster c.
    pub fn tiles_of_cluster(&self, c: usize) -> std::ops::Range<usize> {
        self.cstart[c]..self.cstart[c + 1]
    }

    /// Cluster of tile t.
    pub fn cluster_of_tile(&self, t: usize) -> usize {
        self.tile_cluster[t] as usize
    }

    /// Tile of block i, if it is free.
    pub fn tile_of(&self, i: usize) -> Option<usize> {
        let t = self.tile_of[i];
        (t != u32::MAX).then_some(t as usize)
    }

    /// Range of tile t's blocks in `blocks`.
    pub fn block_range(&self, t: usize) -> std::ops::Range<usize> {
        self.start[t]..self.start[t + 1]
    }

    /// Blocks of tile t, in index order.
    pub fn blocks_of(&self, t: usize) -> &[u32] {
        &self.blocks[self.block_range(t)]
    }

    /// Contact blocks bordering tile t.
    pub fn border_of(&self, t: usize) -> &[u32] {
        &self.border[self.bstart[t]..self.bstart[t + 1]]
    }

    /// Tiles of the same cluster next to tile t.
    pub fn adjacent(&self, t: usize) -> &[u32] {
        &self.adj[self.astart[t]..self.astart[t + 1]]
    }

    /// Blocks in the largest cluster.
    pub fn largest_cluster(&self) -> usize {
        (0..self.clusters())
            .map(|c| self.start[self.cstart[c + 1]] - self.start[self.cstart[c]])
            .max()
            .unwrap_or(0)
    }
}

/// The free blocks 8-connected to `seed` (not yet in a cluster), marked as
/// cluster `c`, into `members` in index order.
fn flood(
    lat: &Lattice,
    iface: &Interface,
    seed: usize,
    c: u32,
    cluster_of: &mut [u32],
    members: &mut Vec<u32>,
) {
    members.clear();
    cluster_of[seed] = c;
    members.push(seed as u32);
    let mut k = 0;
    while k < members.len() {
        let i = members[k] as usize;
        k += 1;
        for d in 0..8 {
            let j = lat.nbr[8 * i + d] as usize;
            if j != i && iface.is_free(j) && cluster_of[j] == u32::MAX {
                cluster_of[j] = c;
                members.push(j as u32);
            }
        }
    }
    members.sort_unstable();
}

/// Flat (start, list) of the contact blocks bordering each of the `nt`
/// tiles and of the tiles adjacent to each, both sorted.
type Neighbours = (Vec<usize>, Vec<u32>, Vec<usize>, Vec<u32>);

fn neighbours(
    lat: &Lattice,
    blocks: &[u32],
    start: &[usize],
    tile_of: &[u32],
    nt: usize,
) -> Neighbours {
    let n = lat.len();
    let (mut bstart, mut border) = (vec![0usize], Vec::new());
    let (mut astart, mut adj) = (vec![0usize], Vec::new());
    let mut seen = vec![u32::MAX; n.max(nt)];
    let mut seen_tile = vec![u32::MAX; nt];
    for t in 0..nt {
        let b0 = border.len();
        let a0 = adj.len();
        for &i in &blocks[start[t]..start[t + 1]] {
            let i = i as usize;
            for d in 0..8 {
                let j = lat.nbr[8 * i + d] as usize;
                if j == i {
                    continue;
                }
                let tj = tile_of[j];
                if tj == u32::MAX {
                    if seen[j] != t as u32 {
                        seen[j] = t as u32;
                        border.push(j as u32);
                    }
                } else if tj != t as u32 && seen_tile[tj as usize] != t as u32 {
                    seen_tile[tj as usize] = t as u32;
                    adj.push(tj);
                }
            }
        }
        border[b0..].sort_unstable();
        adj[a0..].sort_unstable();
        bstart.push(border.len());
        astart.push(adj.len());
    }
    (bstart, border, astart, adj)
}
