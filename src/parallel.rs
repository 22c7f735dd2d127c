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
    par_map_owned(range.collect(), f)
}

/// `f(item)` for every item of `items`, taken by value, in order.
pub(crate) fn par_map_owned<T: Send, U: Send>(
    items: Vec<T>,
    f: impl Fn(T) -> U + Sync + Send,
) -> Vec<U> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        use rayon::prelude::*;
        // One item per task: items differ widely in cost (a long flight's IMM station against
        // its DR drone), so each is left free to be stolen by an idle core.
        items.into_par_iter().with_max_len(1).map(f).collect()
    }
    #[cfg(target_arch = "wasm32")]
    {
        items.into_iter().map(f).collect()
    }
}

/// Whether `tasks` tasks keep every core busy natively (at least two per core, so that one
/// costly task does not leave a core idle); always in WebAssembly, which runs them in turn.
pub(crate) fn enough_tasks(tasks: usize) -> bool {
    #[cfg(not(target_arch = "wasm32"))]
    {
        tasks >= 2 * rayon::current_num_threads()
    }
    #[cfg(target_arch = "wasm32")]
    {
        let _ = tasks;
        true
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

/// Calls `tick` up to `n` times, until one asks to stop; whether none did.
pub(crate) fn ticks(n: usize, tick: &mut dyn FnMut() -> bool) -> bool {
    (0..n).all(|_| tick())
}

/// [`par_map`] calling `tick(i)` once per item `i`: after each item in WebAssembly (so a long
/// run can report progress between items), after all of them natively. A tick that returns
/// `false` asks to stop: in WebAssembly no further item starts, natively nothing more is left to
/// start; either way the result is `None`, so that the caller stops too (a page's run that a
/// newer one replaced, `docs/reference.md` §9).
pub(crate) fn par_map_ticking<T: Send>(
    range: core::ops::Range<usize>,
    f: impl Fn(usize) -> T + Sync + Send,
    tick: &mut dyn FnMut(usize) -> bool,
) -> Option<Vec<T>> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let out = par_map(range.clone(), f);
        let mut range = range;
        range.all(tick).then_some(out)
    }
    #[cfg(target_arch = "wasm32")]
    {
        range
            .map(|i| {
                let r = f(i);
                tick(i).then_some(r)
            })
            .collect()
    }
}

/// [`par_map_ticking`] over `0..n`, starting the items in decreasing `cost` (ties in index
/// order) and returning the results in index order. With a few items of very different cost
/// (one long flight's four stations), the costliest then never starts last on a core that has
/// already done its share while the other core idles.
pub(crate) fn par_map_costliest_first<T: Send>(
    n: usize,
    cost: impl Fn(usize) -> u32,
    f: impl Fn(usize) -> T + Sync + Send,
    tick: &mut dyn FnMut(usize) -> bool,
) -> Option<Vec<T>> {
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| core::cmp::Reverse(cost(i)));
    let done = par_map_ticking(0..n, |k| f(order[k]), &mut |k| tick(order[k]))?;
    let mut slots: Vec<Option<T>> = (0..n).map(|_| None).collect();
    for (i, r) in order.into_iter().zip(done) {
        slots[i] = Some(r);
    }
    Some(slots.into_iter().flatten().collect())
}

/// `f(i, tick)` for every `i` in `range`, in order, where `f` calls `tick` as its item
/// progresses (a run's flights flown in order): in WebAssembly the items run in turn and each
/// tick is passed on as it comes; natively they run side by side, each item's ticks are counted,
/// and as many are passed on once all are done, as [`par_map_ticking`] does. A tick passed on
/// that returns `false` stops as there: no further tick is passed on, no further item starts,
/// and the result is `None`.
pub(crate) fn par_map_progressing<T: Send>(
    range: core::ops::Range<usize>,
    f: impl Fn(usize, &mut dyn FnMut()) -> T + Sync + Send,
    tick: &mut dyn FnMut() -> bool,
) -> Option<Vec<T>> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let counted = par_map(range, |i| {
            let mut count = 0usize;
            let r = f(i, &mut || count += 1);
            (r, count)
        });
        let mut go = true;
        let out = counted
            .into_iter()
            .map(|(r, n)| {
                go = go && ticks(n, tick);
                r
            })
            .collect();
        go.then_some(out)
    }
    #[cfg(target_arch = "wasm32")]
    {
        range
            .map(|i| {
                let mut go = true;
                let r = f(i, &mut || go = go && tick());
                go.then_some(r)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_come_back_in_index_order_with_one_tick_each() {
        let mut ticked = Vec::new();
        let out = par_map_ticking(0..100, |i| i * i, &mut |i| {
            ticked.push(i);
            true
        });
        assert_eq!(out, Some((0..100).map(|i| i * i).collect::<Vec<_>>()));
        assert_eq!(ticked, (0..100).collect::<Vec<_>>());
    }

    #[test]
    fn a_tick_that_says_stop_ends_the_map_with_none() {
        let started = std::sync::atomic::AtomicUsize::new(0);
        let out = par_map_ticking(
            0..10,
            |i| {
                started.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                i
            },
            &mut |i| i < 3,
        );
        assert_eq!(out, None);
        // In WebAssembly the items run in turn, and none starts after the fourth's tick.
        #[cfg(target_arch = "wasm32")]
        assert_eq!(started.into_inner(), 4);
        let mut ticks = 0;
        let out = par_map_progressing(0..4, |i, tick| tick_times(i, tick), &mut || {
            ticks += 1;
            ticks < 2
        });
        assert_eq!(out, None);
        // The tick that said stop was the last one passed on (of the 0 + 1 + 2 + 3 counted).
        assert_eq!(ticks, 2);
    }

    /// Ticks `n` times and returns `n`.
    fn tick_times(n: usize, tick: &mut dyn FnMut()) -> usize {
        (0..n).for_each(|_| tick());
        n
    }

    #[test]
    fn progressing_items_pass_on_every_tick_and_keep_index_order() {
        let mut ticks = 0;
        let out = par_map_progressing(
            0..8,
            |i, tick| {
                (0..i).for_each(|_| tick());
                i * 2
            },
            &mut || {
                ticks += 1;
                true
            },
        );
        assert_eq!(out, Some((0..8).map(|i| i * 2).collect::<Vec<_>>()));
        assert_eq!(ticks, (0..8).sum::<usize>());
    }

    #[test]
    fn the_costliest_start_first_and_results_keep_index_order() {
        let started = std::sync::Mutex::new(Vec::new());
        let mut ticked = Vec::new();
        let out = par_map_costliest_first(
            6,
            |i| [1, 5, 0, 5, 9, 2][i],
            |i| {
                started.lock().unwrap().push(i);
                10 * i
            },
            &mut |i| {
                ticked.push(i);
                true
            },
        );
        assert_eq!(out, Some(vec![0, 10, 20, 30, 40, 50]));
        // Each tick names its item, in the order the items were started.
        assert_eq!(ticked, vec![4, 1, 3, 5, 0, 2]);
        #[cfg(target_arch = "wasm32")]
        assert_eq!(*started.lock().unwrap(), vec![4, 1, 3, 5, 0, 2]);
        // Natively the cores take the items in that order, but finish them in any.
        let mut all = started.into_inner().unwrap();
        all.sort();
        assert_eq!(all, (0..6).collect::<Vec<_>>());
    }
}
