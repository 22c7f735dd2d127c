//! Work spread over every core natively, run in turn in WebAssembly (one thread, and no
//! SharedArrayBuffer, so the page stays embeddable and statically hosted).
//!
//! Every item carries its own random streams (derived from the seed and its index), and the
//! results come back in index order, so the numbers never depend on the thread count.

/// `f(i)` for every `i` in `range`, in order.
pub(crate) fn par_map<T: Send>(
    range: core::ops::Range<usize>,
    f: impl Fn(usize) -> T + Sync + Send,
) -> Vec<T> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        use rayon::prelude::*;
        range.into_par_iter().map(f).collect()
    }
    #[cfg(target_arch = "wasm32")]
    {
        range.map(f).collect()
    }
}

/// `f(item)` for every item of `items`, in parallel natively and in turn in WebAssembly.
pub(crate) fn par_each<T: Send>(items: &mut [T], f: impl Fn(&mut T) + Sync + Send) {
    #[cfg(not(target_arch = "wasm32"))]
    {
        use rayon::prelude::*;
        items.par_iter_mut().for_each(f);
    }
    #[cfg(target_arch = "wasm32")]
    {
        items.iter_mut().for_each(f);
    }
}

/// [`par_map`] calling `tick` once per item: after each item in WebAssembly (so a long run can
/// report progress between items), after all of them natively.
pub(crate) fn par_map_ticking<T: Send>(
    range: core::ops::Range<usize>,
    f: impl Fn(usize) -> T + Sync + Send,
    tick: &mut dyn FnMut(),
) -> Vec<T> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let out = par_map(range, f);
        out.iter().for_each(|_| tick());
        out
    }
    #[cfg(target_arch = "wasm32")]
    {
        range
            .map(|i| {
                let r = f(i);
                tick();
                r
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_come_back_in_index_order_with_one_tick_each() {
        let mut ticks = 0;
        let out = par_map_ticking(0..100, |i| i * i, &mut || ticks += 1);
        assert_eq!(out, (0..100).map(|i| i * i).collect::<Vec<_>>());
        assert_eq!(ticks, 100);
    }
}
