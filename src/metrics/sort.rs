//! Sorting samples in [`f64::total_cmp`]'s order, the order every statistic here reads them in.

/// Sorts `data` ascending in [`f64::total_cmp`]'s order: bit for bit the order
/// `data.sort_unstable_by(f64::total_cmp)` leaves (values with equal keys have equal bits, so
/// which of them an unstable sort puts first cannot show).
///
/// Each value's bits become an integer of the same order (a negative one's bits all flipped, any
/// other's sign bit set), in place, the integers are sorted and turned back. The standard library
/// sorts primitive integers without branching on each comparison, which a comparator on floats
/// does not: 400 000 errors in 8 ms instead of 16 ms. In place, without a copy of the keys: a
/// swarm's pooled errors (500 drones × 3600 s: 144 MB) once needed as much again to be sorted.
///
/// ```
/// use loratrack::sort_total;
/// let mut v = [3.0, -0.0, f64::INFINITY, 0.0, -2.5];
/// sort_total(&mut v);
/// assert_eq!(v.map(f64::to_bits), [-2.5, -0.0, 0.0, 3.0, f64::INFINITY].map(f64::to_bits));
/// ```
pub fn sort_total(data: &mut [f64]) {
    let keys: &mut [u64] = bytemuck::cast_slice_mut(data);
    for k in keys.iter_mut() {
        *k = key(*k);
    }
    keys.sort_unstable();
    for k in keys.iter_mut() {
        *k = value(*k);
    }
}

const SIGN: u64 = 1 << 63;

/// An integer whose order is that of the f64 with bits `b` in [`f64::total_cmp`].
fn key(b: u64) -> u64 {
    if b & SIGN != 0 {
        !b
    } else {
        b | SIGN
    }
}

/// The f64 bits whose [`key`] is `k`.
fn value(k: u64) -> u64 {
    if k & SIGN != 0 {
        k & !SIGN
    } else {
        !k
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    fn compared(mut v: Vec<f64>) -> Vec<u64> {
        v.sort_unstable_by(f64::total_cmp);
        v.into_iter().map(f64::to_bits).collect()
    }

    fn keyed(mut v: Vec<f64>) -> Vec<u64> {
        sort_total(&mut v);
        v.into_iter().map(f64::to_bits).collect()
    }

    #[test]
    fn leaves_the_order_of_total_cmp_bit_for_bit() {
        let specials = [
            0.0,
            -0.0,
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::from_bits(1),
            -f64::from_bits(1),
            f64::MAX,
            f64::MIN,
            1.0,
            -1.0,
        ];
        let mut rng = Rng::new(7);
        // Specials repeated among random values of both signs.
        let v: Vec<f64> = (0..40_000)
            .map(|i| {
                if i % 97 == 0 {
                    specials[(i / 97) % specials.len()]
                } else {
                    (rng.uniform() - 0.3) * 1e3
                }
            })
            .collect();
        assert_eq!(keyed(v.clone()), compared(v));
        assert_eq!(keyed(specials.to_vec()), compared(specials.to_vec()));
    }

    #[test]
    fn keys_keep_every_bit() {
        for v in [0.0, -0.0, f64::NAN, -3.5e-310, 2.0, f64::NEG_INFINITY] {
            assert_eq!(value(key(v.to_bits())), v.to_bits());
        }
    }
}
