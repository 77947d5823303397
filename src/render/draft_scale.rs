//! How coarse the live preview's drafts are. A draft is drawn for every frame of a drag,
//! on the same cores as the window on a software rasteriser: drawn too finely it takes
//! the CPU the window needs and the whole editor stutters. The drafts' drawing times (a
//! running estimate: one slow draft alone changes nothing) pick the next one's
//! resolution — the finest of 1/1 … 1/4 of the view each way that keeps a draft within
//! [`DRAFT_BUDGET`] — so a GPU drafts at full resolution and llvmpipe at a half to a
//! quarter for a heavy material like wood, depending on what else the cores draw.

use std::time::Duration;

/// The time a draft may take, readback included.
pub const DRAFT_BUDGET: Duration = Duration::from_millis(16);
/// The coarsest draft: a quarter of the view each way.
const COARSEST: u32 = 4;
/// Drafts go finer only when the finer one is expected to take this share of the budget
/// at most, so that the resolution does not flip between two steps.
const HEADROOM: f64 = 0.8;
/// The weight of the newest draft in the running estimate of a draft's cost (the rest
/// is the estimate before): one slow draft alone does not coarsen the next.
const NEWEST: f64 = 0.3;

/// The divisor of the view's size that drafts draw at, adapted to their drawing time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DraftScale {
    divisor: u32,
    /// What a draft at full resolution would take, in seconds: each draft's time times
    /// the pixels it left out (its divisor squared), averaged over recent drafts.
    full_cost: Option<f64>,
}

impl Default for DraftScale {
    /// Half the view each way until a draft has been timed.
    fn default() -> DraftScale {
        DraftScale {
            divisor: 2,
            full_cost: None,
        }
    }
}

impl DraftScale {
    /// The divisor of each side: 1 (full resolution) to 4.
    pub fn divisor(self) -> u32 {
        self.divisor
    }

    /// The draft size for a view of `size` pixels.
    pub fn scaled(self, size: (u32, u32)) -> (u32, u32) {
        (
            size.0.div_ceil(self.divisor).max(1),
            size.1.div_ceil(self.divisor).max(1),
        )
    }

    /// Takes in that a draft at the present divisor took `took`: coarser when drafts are
    /// expected to go over the budget, finer when the finer draft (its time scaling with
    /// its pixels) is expected to stay well inside it.
    pub fn after_draft(&mut self, took: Duration) {
        let sample = took.as_secs_f64() * f64::from(self.divisor * self.divisor);
        let cost = match self.full_cost {
            Some(before) => before + NEWEST * (sample - before),
            None => sample,
        };
        self.full_cost = Some(cost);
        let budget = DRAFT_BUDGET.as_secs_f64();
        // The finest divisor whose draft fits `share` of the budget.
        let fitting =
            |share: f64| ((cost / (budget * share)).sqrt().ceil() as u32).clamp(1, COARSEST);
        let needed = fitting(1.0);
        let comfortable = fitting(HEADROOM);
        if needed > self.divisor {
            self.divisor = needed;
        } else if comfortable < self.divisor {
            self.divisor = comfortable;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(milliseconds: u64) -> Duration {
        Duration::from_millis(milliseconds)
    }

    fn at(divisor: u32) -> DraftScale {
        DraftScale {
            divisor,
            full_cost: None,
        }
    }

    #[test]
    fn slow_drafts_coarsen_to_what_fits_and_no_further_than_a_quarter() {
        let mut scale = DraftScale::default();
        assert_eq!(scale.scaled((443, 434)), (222, 217));
        // 30 ms at 1/2: 120 ms at full resolution, 13 ms at 1/3.
        scale.after_draft(ms(30));
        assert_eq!(scale.divisor(), 3);
        // Far too slow even at a quarter: a quarter.
        let mut slow = DraftScale::default();
        slow.after_draft(ms(500));
        assert_eq!(slow.divisor(), 4);
        assert_eq!(slow.scaled((443, 434)), (111, 109));
    }

    #[test]
    fn fast_drafts_refine_to_full_resolution() {
        let mut scale = DraftScale::default();
        scale.after_draft(ms(1));
        assert_eq!(scale.divisor(), 1);
        assert_eq!(scale.scaled((443, 434)), (443, 434));
        scale.after_draft(ms(1));
        assert_eq!(scale.divisor(), 1);
    }

    #[test]
    fn one_slow_draft_among_quick_ones_changes_nothing() {
        let mut scale = at(2);
        for _ in 0..10 {
            scale.after_draft(ms(10));
        }
        assert_eq!(scale.divisor(), 2);
        scale.after_draft(ms(25));
        assert_eq!(scale.divisor(), 2, "{scale:?}");
        // Slow drafts that go on do coarsen (the estimate: 40, 58, then 70.6 ms at full
        // resolution, 4.4 times the budget: 1/3).
        scale.after_draft(ms(25));
        assert_eq!(scale.divisor(), 3, "{scale:?}");
        // Drawn at 1/3 they take 9/4 less, and stay there.
        for _ in 0..10 {
            scale.after_draft(Duration::from_secs_f64(0.025 * 4.0 / 9.0));
        }
        assert_eq!(scale.divisor(), 3, "{scale:?}");
    }

    #[test]
    fn a_draft_inside_the_budget_but_not_with_room_to_spare_stays() {
        // At 1/3, 6 ms: 1/2 would take 6 · 9/4 = 13.5 ms, inside 16 ms but not 80% of it.
        let mut scale = at(3);
        scale.after_draft(ms(6));
        assert_eq!(scale.divisor(), 3);
        // 5 ms at 1/3 predicts 11.25 ms at 1/2: within 80% of 16 ms.
        let mut quicker = at(3);
        quicker.after_draft(ms(5));
        assert_eq!(quicker.divisor(), 2);
    }

    #[test]
    fn sizes_never_reach_zero() {
        assert_eq!(at(4).scaled((1, 3)), (1, 1));
    }
}
