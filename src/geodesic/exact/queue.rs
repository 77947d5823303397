//! The queue of work waiting: windows and vertices to settle, in buckets of distance.

use super::window::Window;

/// Work waiting: windows and vertices to settle, in buckets of distance.
///
/// Propagation is label-correcting: a window may be propagated before a nearer one,
/// since every pruning compares lengths of real paths, and the result is the same. So
/// the queue only orders by bucket, `width` of distance each (Xu et al.'s fast wavefront
/// propagation, 2015); within a bucket the newest comes first, while its data is still
/// in the cache. A binary heap ordering every window took half of the time.
pub struct Queue {
    width: f64,
    buckets: Vec<Bucket>,
    /// The bucket taken from: keys below it (rounding) join it.
    current: usize,
    /// Emptied buckets, kept for their memory (fresh ones cost page faults as they grow).
    spare: Vec<Bucket>,
}

#[derive(Default)]
struct Bucket {
    vertices: Vec<(f64, u32)>,
    windows: Vec<Window>,
}

impl Queue {
    pub fn new(width: f64) -> Self {
        Queue {
            width,
            buckets: Vec::new(),
            current: 0,
            spare: Vec::new(),
        }
    }

    fn bucket(&mut self, key: f64) -> &mut Bucket {
        let index = ((key / self.width) as usize).max(self.current);
        while index >= self.buckets.len() {
            let bucket = self.spare.pop().unwrap_or_default();
            self.buckets.push(bucket);
        }
        &mut self.buckets[index]
    }

    pub fn push_vertex(&mut self, key: f64, v: u32) {
        self.bucket(key).vertices.push((key, v));
    }

    pub fn push_window(&mut self, key: f64, window: Window) {
        self.bucket(key).windows.push(window);
    }

    /// The next event of the nearest bucket: a vertex to settle with the distance it was
    /// queued at, or a window.
    pub fn pop(&mut self) -> Option<Result<(f64, u32), Window>> {
        while let Some(bucket) = self.buckets.get_mut(self.current) {
            if let Some(vertex) = bucket.vertices.pop() {
                return Some(Ok(vertex));
            }
            if let Some(window) = bucket.windows.pop() {
                return Some(Err(window));
            }
            let emptied = std::mem::take(bucket);
            self.spare.push(emptied);
            self.current += 1;
        }
        None
    }
}
