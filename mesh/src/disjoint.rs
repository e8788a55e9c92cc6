//! Union–find with path halving and the smaller root winning each union, so every root is the
//! smallest element of its set and labels taken in element order are stable: the one used for
//! the repair's components and fans, the sectors' corner classes, the crease detection's
//! components and the sharp-feature measure's flat regions.

/// Disjoint sets over `0..n` (module docs).
#[derive(Clone, Debug)]
pub struct DisjointSets(Vec<usize>);

impl DisjointSets {
    /// `n` singletons.
    pub fn new(n: usize) -> Self {
        DisjointSets((0..n).collect())
    }

    /// The root of `x`'s set: its smallest element.
    pub fn find(&mut self, mut x: usize) -> usize {
        while self.0[x] != x {
            self.0[x] = self.0[self.0[x]];
            x = self.0[x];
        }
        x
    }

    /// Joins the sets of `a` and `b` (the smaller root wins).
    pub fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.0[hi] = lo;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_are_the_smallest_elements() {
        let mut d = DisjointSets::new(6);
        d.union(4, 2);
        d.union(5, 4);
        d.union(3, 1);
        assert_eq!(
            (0..6).map(|x| d.find(x)).collect::<Vec<_>>(),
            [0, 1, 2, 1, 2, 2]
        );
    }
}
