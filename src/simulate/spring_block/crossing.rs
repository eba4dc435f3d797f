//! Threshold-crossing times of stuck blocks in a tournament (min) tree, so
//! that finding the blocks due at time t costs O(due · log N) instead of
//! O(N), and the earliest crossing is at the root.

/// Smallest τ ≥ 0 with |g + r τ| = th, for |g| ≤ th; ∞ if never.
#[inline]
pub fn crossing_time(g: (f64, f64), r: (f64, f64), th: f64) -> f64 {
    let a = r.0 * r.0 + r.1 * r.1;
    let b = 2.0 * (g.0 * r.0 + g.1 * r.1);
    let c = g.0 * g.0 + g.1 * g.1 - th * th;
    if c >= 0.0 {
        return 0.0;
    }
    if a <= 0.0 {
        return f64::INFINITY;
    }
    let disc = (b * b - 4.0 * a * c).sqrt();
    if b >= 0.0 {
        -2.0 * c / (b + disc)
    } else {
        (-b + disc) / (2.0 * a)
    }
}

/// Crossing time of each block (∞ if it slides) and the min tree over them.
#[derive(Debug, Clone)]
pub(crate) struct CrossingTree {
    /// Time at which each stuck block reaches its threshold \[s\].
    time: Vec<f64>,
    /// Min tree: leaves at `leaves + i`, root at 1.
    tree: Vec<f64>,
    leaves: usize,
    /// Blocks found due by the last [`Self::collect_due`], in index order.
    due: Vec<u32>,
    /// Search stack of [`Self::collect_due`], kept to allocate nothing.
    stack: Vec<usize>,
}

impl CrossingTree {
    /// A tree over `n` blocks, all at ∞.
    pub fn new(n: usize) -> Self {
        let leaves = n.next_power_of_two();
        CrossingTree {
            time: vec![f64::INFINITY; n],
            tree: vec![f64::INFINITY; 2 * leaves],
            leaves,
            due: Vec::new(),
            // A depth-first search holds at most one sibling per level.
            stack: Vec::with_capacity(2 * (leaves.trailing_zeros() as usize + 2)),
        }
    }

    /// Crossing time of block `i` \[s\].
    #[inline]
    pub fn time(&self, i: usize) -> f64 {
        self.time[i]
    }

    /// Sets every crossing time from `f` and rebuilds the tree.
    pub fn rebuild(&mut self, mut f: impl FnMut(usize) -> f64) {
        for i in 0..self.time.len() {
            self.time[i] = f(i);
            self.tree[self.leaves + i] = self.time[i];
        }
        for k in (1..self.leaves).rev() {
            self.tree[k] = self.tree[2 * k].min(self.tree[2 * k + 1]);
        }
    }

    /// Sets the crossing time of block `i` and updates its path to the root.
    pub fn set(&mut self, i: usize, value: f64) {
        self.time[i] = value;
        let mut k = self.leaves + i;
        self.tree[k] = value;
        while k > 1 {
            k /= 2;
            let m = self.tree[2 * k].min(self.tree[2 * k + 1]);
            if m.to_bits() == self.tree[k].to_bits() {
                break;
            }
            self.tree[k] = m;
        }
    }

    /// Earliest crossing and its block (`None` if every time is ∞).
    pub fn earliest(&self) -> Option<(f64, usize)> {
        let m = self.tree[1];
        if !m.is_finite() {
            return None;
        }
        let mut k = 1;
        while k < self.leaves {
            k = if self.tree[2 * k].to_bits() == m.to_bits() {
                2 * k
            } else {
                2 * k + 1
            };
        }
        Some((m, k - self.leaves))
    }

    /// Collects the blocks whose crossing time is ≤ t, in index order, and
    /// sets their times to ∞. Returns them.
    pub fn collect_due(&mut self, t: f64) -> &[u32] {
        self.due.clear();
        if self.tree[1] > t {
            return &self.due;
        }
        self.stack.clear();
        self.stack.push(1);
        while let Some(k) = self.stack.pop() {
            if self.tree[k] > t {
                continue;
            }
            if k >= self.leaves {
                self.due.push((k - self.leaves) as u32);
            } else {
                self.stack.push(2 * k + 1);
                self.stack.push(2 * k);
            }
        }
        self.due.sort_unstable();
        for n in 0..self.due.len() {
            let i = self.due[n] as usize;
            self.set(i, f64::INFINITY);
        }
        &self.due
    }

    /// The blocks of the last [`Self::collect_due`].
    pub fn due(&self) -> &[u32] {
        &self.due
    }
}
