//! Sorting a query's answer, a list of distinct primitive indices, in ascending order.
//!
//! A range query over a large region reports thousands of indices in the tree's order and
//! must give them ascending. A comparison sort spends `n log n` comparisons on that; an LSD
//! radix sort (Knuth, *The Art of Computer Programming* vol. 3, §5.2.5) spends one counting
//! pass and one scatter pass per byte of the largest index: three for 200k primitives. On a
//! large ball over 200k points (about 3,800 indices) it took the 4-wide tree's `range` from
//! the comparison sort's time to below a plain scan's (issue 33).

/// Below this many indices the comparison sort is as fast (the radix sort's passes over its
/// 256 counters cost more than the comparisons).
const RADIX_FROM: usize = 256;

/// Bits of the index each radix pass sorts by.
const DIGIT_BITS: u32 = 8;

/// Sorts `indices` ascending (equal values keep no particular order, as with
/// `sort_unstable`).
pub(crate) fn sort_indices(indices: &mut Vec<usize>) {
    if indices.len() < RADIX_FROM {
        indices.sort_unstable();
        return;
    }
    let max = indices.iter().copied().max().unwrap_or(0);
    let mut scratch = vec![0usize; indices.len()];
    let mut shift = 0;
    // Each pass is a stable counting sort by one digit, from the lowest: after the pass of
    // the highest nonzero digit the list is sorted.
    while shift < usize::BITS && (max >> shift) != 0 {
        let digit = |value: usize| (value >> shift) & ((1 << DIGIT_BITS) - 1);
        let mut starts = [0usize; 1 << DIGIT_BITS];
        for &value in indices.iter() {
            starts[digit(value)] += 1;
        }
        let mut next = 0;
        for start in &mut starts {
            let count = *start;
            *start = next;
            next += count;
        }
        for &value in indices.iter() {
            let slot = &mut starts[digit(value)];
            scratch[*slot] = value;
            *slot += 1;
        }
        std::mem::swap(indices, &mut scratch);
        shift += DIGIT_BITS;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sorts_as_the_comparison_sort_does_at_every_size_and_spread() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            // xorshift64*: a fixed sequence, the same on every run.
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            state.wrapping_mul(0x2545_f491_4f6c_dd1d)
        };
        for len in [0, 1, 2, 255, 256, 257, 3_800, 20_000] {
            for bits in [1, 8, 9, 18, 32, 63] {
                let mut values: Vec<usize> =
                    (0..len).map(|_| (next() >> (64 - bits)) as usize).collect();
                let mut want = values.clone();
                want.sort_unstable();
                sort_indices(&mut values);
                assert_eq!(values, want, "{len} values of {bits} bits");
            }
        }
    }
}
