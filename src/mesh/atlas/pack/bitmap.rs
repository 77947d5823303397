//! Grids of cells, one bit each, as the shape packer rasterises charts and marks what
//! is taken: set, test against another grid at an offset, grow by a margin.

/// A grid of cells, one bit each, in rows of 64-bit words.
#[derive(Clone, Debug)]
pub(super) struct Bitmap {
    pub width: usize,
    pub height: usize,
    words: usize,
    bits: Vec<u64>,
}

impl Bitmap {
    /// An empty grid of `width` × `height` cells.
    pub fn new(width: usize, height: usize) -> Bitmap {
        let words = width.div_ceil(64).max(1);
        Bitmap {
            width,
            height,
            words,
            bits: vec![0; words * height],
        }
    }

    /// Sets cell (i, j).
    pub fn set(&mut self, i: usize, j: usize) {
        self.bits[j * self.words + i / 64] |= 1 << (i % 64);
    }

    /// The words of row `j`, cell i in bit i % 64 of word i / 64.
    pub fn row(&self, j: usize) -> &[u64] {
        &self.bits[j * self.words..(j + 1) * self.words]
    }

    /// The bitmap grown by `by` cells on every side (a cell is set when one within `by`
    /// cells across and along was), `by` cells larger on every side.
    pub fn dilated(&self, by: usize) -> Bitmap {
        let mut grown = Bitmap::new(self.width + 2 * by, self.height + 2 * by);
        let mut along = vec![0u64; grown.words];
        for j in 0..self.height {
            along.fill(0);
            for shift in 0..=2 * by {
                or_shifted(self.row(j), shift, &mut along);
            }
            for y in j..=j + 2 * by {
                let row = &mut grown.bits[y * grown.words..(y + 1) * grown.words];
                row.iter_mut()
                    .zip(&along)
                    .for_each(|(cell, &bits)| *cell |= bits);
            }
        }
        grown
    }

    /// Whether `mask` with its lower corner at cell (x, y) meets no set cell.
    pub fn fits(&self, mask: &Bitmap, x: usize, y: usize) -> bool {
        let (offset, bit) = (x / 64, x % 64);
        (0..mask.height).all(|j| {
            let row = self.row(y + j);
            mask.row(j).iter().enumerate().all(|(index, &word)| {
                word == 0
                    || (row[offset + index] & (word << bit) == 0
                        && (bit == 0
                            || word >> (64 - bit) == 0
                            || row[offset + index + 1] & (word >> (64 - bit)) == 0))
            })
        })
    }

    /// For each row, its set cells' count, first and last column (`None` when it has
    /// none).
    pub fn spans(&self) -> Vec<Option<(usize, usize, usize)>> {
        (0..self.height)
            .map(|j| {
                let row = self.row(j);
                let count: usize = row.iter().map(|w| w.count_ones() as usize).sum();
                let first = row.iter().position(|&w| w != 0)?;
                let last = row.iter().rposition(|&w| w != 0)?;
                Some((
                    count,
                    64 * first + row[first].trailing_zeros() as usize,
                    64 * last + 63 - row[last].leading_zeros() as usize,
                ))
            })
            .collect()
    }

    /// Sets the cells of `mask` with its lower corner at cell (x, y).
    pub fn or_at(&mut self, mask: &Bitmap, x: usize, y: usize) {
        for j in 0..mask.height {
            let start = (y + j) * self.words;
            or_shifted(mask.row(j), x, &mut self.bits[start..start + self.words]);
        }
    }
}

/// Sets in `into` the cells of `row` moved `shift` cells along.
fn or_shifted(row: &[u64], shift: usize, into: &mut [u64]) {
    let (offset, bit) = (shift / 64, shift % 64);
    for (index, &word) in row.iter().enumerate().filter(|(_, word)| **word != 0) {
        into[offset + index] |= word << bit;
        if bit > 0 && word >> (64 - bit) != 0 {
            into[offset + index + 1] |= word >> (64 - bit);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dilation_grows_a_cell_into_a_square() {
        let mut bitmap = Bitmap::new(70, 3);
        bitmap.set(63, 1);
        let grown = bitmap.dilated(2);
        assert_eq!((grown.width, grown.height), (74, 7));
        for j in 0..7 {
            for i in 0..74 {
                let set = grown.row(j)[i / 64] >> (i % 64) & 1 == 1;
                let expected = (63..=67).contains(&i) && (1..=5).contains(&j);
                assert_eq!(set, expected, "{i}, {j}");
            }
        }
    }
}
