//! Seeded generators for test inputs, so that random inputs are the same on every run
//! and tests need no dependency. Tests assert figures on meshes built from these
//! sequences: never change a generator's output, add a new one instead.

/// xorshift64 (shifts 13, 7, 17): the generator of most tests. The state must not be 0.
#[derive(Clone, Debug)]
pub struct XorShift64(pub u64);

impl XorShift64 {
    /// The next state (the next 64 random bits).
    #[allow(clippy::should_implement_trait)] // not an iterator: it never ends
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// A number in `0..n` (`n` > 0), the next state modulo `n`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    /// A number in `[0, 1)`: the top 53 bits of the next state.
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Shuffles `v` (Fisher-Yates from the back, one [`below`](Self::below) per slot).
    pub fn shuffle<T>(&mut self, v: &mut [T]) {
        for i in (1..v.len()).rev() {
            v.swap(i, self.below(i + 1));
        }
    }
}

/// xorshift64* (shifts 12, 25, 27, then a multiply): the matching tests' generator.
/// The state must not be 0.
#[derive(Clone, Debug)]
pub struct XorShift64Star(pub u64);

impl XorShift64Star {
    /// The next 64 random bits.
    #[allow(clippy::should_implement_trait)] // not an iterator: it never ends
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545F4914F6CDD1D)
    }
    /// A number in `0..n` (`n` > 0).
    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    /// A number in `lo..=hi`.
    pub fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + self.below((hi - lo + 1) as u64) as i64
    }
}

/// A 64-bit linear congruential generator (Knuth's MMIX constants) returning the top
/// 31 bits of its state: the generator of the asset round-trip tests.
#[derive(Clone, Debug)]
pub struct Lcg(pub u64);

impl Lcg {
    /// The next 31 random bits (the state's top bits).
    #[allow(clippy::should_implement_trait)] // not an iterator: it never ends
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        self.0 >> 33
    }
    /// A number in `0..n` (`n` > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    /// Shuffles `v` (Fisher-Yates from the back, one [`below`](Self::below) per slot).
    pub fn shuffle<T>(&mut self, v: &mut [T]) {
        for i in (1..v.len()).rev() {
            v.swap(i, self.below(i + 1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first outputs of each generator, pinned: tests elsewhere assert figures on
    /// inputs drawn from these sequences.
    #[test]
    fn sequences_are_pinned() {
        let mut x = XorShift64(1);
        assert_eq!([x.next(), x.next(), x.next()], [1082269761, 1152992998833853505, 11177516664432764457]);
        let mut s = XorShift64Star(1);
        assert_eq!(s.next(), 5180492295206395165);
        let mut l = Lcg(1);
        assert_eq!(l.next(), 908834774);
    }
}
