//! Screenshots and what is found in them: rectangles of pixels, differences between
//! two screenshots, empty canvas, a node's pins.

/// Pin colours (`widgets::type_color`): float, vec2, vec3, colour.
pub(super) const PIN_COLOURS: [[u8; 3]; 4] = [
    [160, 160, 160],
    [90, 200, 120],
    [100, 140, 230],
    [230, 200, 60],
];

/// Around the mouse, the canvas a new node and its search popup need empty: this far
/// left, right, up and down of the mouse, in pixels.
pub(super) const ROOM: (i32, i32, i32, i32) = (110, 310, 50, 230);

/// A rectangle of pixels, `x0..x1` × `y0..y1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rect {
    pub(super) x0: i32,
    pub(super) y0: i32,
    pub(super) x1: i32,
    pub(super) y1: i32,
}

impl Rect {
    pub(super) fn around((x, y): (i32, i32), radius: i32) -> Rect {
        Rect {
            x0: x - radius,
            y0: y - radius,
            x1: x + radius + 1,
            y1: y + radius + 1,
        }
    }

    /// The canvas a node added at `at` (and its popup) may cover.
    pub(super) fn room(at: (i32, i32)) -> Rect {
        let (left, right, up, down) = ROOM;
        Rect {
            x0: at.0 - left,
            y0: at.1 - up,
            x1: at.0 + right,
            y1: at.1 + down,
        }
    }

    pub(super) fn contains(&self, (x, y): (i32, i32)) -> bool {
        (self.x0..self.x1).contains(&x) && (self.y0..self.y1).contains(&y)
    }

    pub(super) fn overlaps(&self, other: &Rect) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    pub(super) fn clip(&self, shot: &Shot) -> Rect {
        Rect {
            x0: self.x0.max(0),
            y0: self.y0.max(0),
            x1: self.x1.min(shot.width as i32),
            y1: self.y1.min(shot.height as i32),
        }
    }

    pub(super) fn include(rect: Option<Rect>, (x, y): (i32, i32)) -> Rect {
        match rect {
            None => Rect::around((x, y), 0),
            Some(r) => Rect {
                x0: r.x0.min(x),
                y0: r.y0.min(y),
                x1: r.x1.max(x + 1),
                y1: r.y1.max(y + 1),
            },
        }
    }
}

/// The whole of a screenshot.
pub(super) fn full(shot: &Shot) -> Rect {
    Rect {
        x0: 0,
        y0: 0,
        x1: shot.width as i32,
        y1: shot.height as i32,
    }
}

/// A screenshot, 8-bit RGB.
#[derive(Clone)]
pub(super) struct Shot {
    pub(super) width: usize,
    pub(super) height: usize,
    pub(super) rgb: Vec<u8>,
}

impl Shot {
    /// Reads a binary PPM (P6, maxval 255), as `import -depth 8 ppm:` writes it.
    pub(super) fn from_ppm(bytes: &[u8]) -> Option<Shot> {
        let mut fields = Vec::new();
        let mut at = 0;
        while fields.len() < 4 {
            while bytes.get(at)?.is_ascii_whitespace() {
                at += 1;
            }
            let start = at;
            while !bytes.get(at)?.is_ascii_whitespace() {
                at += 1;
            }
            fields.push(std::str::from_utf8(&bytes[start..at]).ok()?.to_string());
        }
        let data = &bytes[at + 1..];
        let (width, height): (usize, usize) = (fields[1].parse().ok()?, fields[2].parse().ok()?);
        (fields[0] == "P6" && fields[3] == "255" && data.len() >= width * height * 3).then(|| {
            Shot {
                width,
                height,
                rgb: data[..width * height * 3].to_vec(),
            }
        })
    }

    pub(super) fn px(&self, x: i32, y: i32) -> [u8; 3] {
        let i = 3 * (y as usize * self.width + x as usize);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
}

/// Whether a pixel is coloured rather than grey (the text cursor is pale blue, text grey).
pub(super) fn tinted([r, g, b]: [u8; 3]) -> bool {
    r.max(g).max(b) - r.min(g).min(b) > 8
}

/// Pixels of `rect` that differ between `a` and `b` (with `ignore_tinted`, only between
/// grey pixels: the blinking text cursor does not count), and their bounding box.
pub(super) fn diff(a: &Shot, b: &Shot, rect: Rect, ignore_tinted: bool) -> (usize, Option<Rect>) {
    if (a.width, a.height) != (b.width, b.height) {
        return (a.width * a.height, Some(full(a)));
    }
    let rect = rect.clip(a);
    let (mut count, mut bounds) = (0, None);
    for y in rect.y0..rect.y1 {
        for x in rect.x0..rect.x1 {
            let (p, q) = (a.px(x, y), b.px(x, y));
            if p != q && !(ignore_tinted && (tinted(p) || tinted(q))) {
                count += 1;
                bounds = Some(Rect::include(bounds, (x, y)));
            }
        }
    }
    (count, bounds)
}

/// The bounds of each island of pixels that are `inside` in `area` (eight-connected).
pub(super) fn islands_where(
    shot: &Shot,
    area: Rect,
    inside: impl Fn([u8; 3]) -> bool,
) -> Vec<Rect> {
    let area = area.clip(shot);
    let width = (area.x1 - area.x0).max(0) as usize;
    let height = (area.y1 - area.y0).max(0) as usize;
    let mut seen = vec![false; width * height];
    let index = |x: i32, y: i32| (y - area.y0) as usize * width + (x - area.x0) as usize;
    let mut found = Vec::new();
    for y in area.y0..area.y1 {
        for x in area.x0..area.x1 {
            if seen[index(x, y)] || !inside(shot.px(x, y)) {
                continue;
            }
            seen[index(x, y)] = true;
            let mut bounds = Rect::around((x, y), 0);
            let mut todo = vec![(x, y)];
            while let Some((px, py)) = todo.pop() {
                bounds = Rect::include(Some(bounds), (px, py));
                for (nx, ny) in (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (px + dx, py + dy))) {
                    if area.contains((nx, ny)) && !seen[index(nx, ny)] && inside(shot.px(nx, ny)) {
                        seen[index(nx, ny)] = true;
                        todo.push((nx, ny));
                    }
                }
            }
            found.push(bounds);
        }
    }
    found
}

/// Two places for the mouse whose [`Rect::room`]s are empty canvas and apart, side by
/// side if there is room.
pub(super) fn free_spots(shot: &Shot) -> Option<((i32, i32), (i32, i32))> {
    let (w, h) = (shot.width as i32, shot.height as i32);
    // The canvas colour: the commonest in the left half, where the graph is.
    let mut counts = std::collections::HashMap::new();
    for y in (h / 10..h * 9 / 10).step_by(3) {
        for x in (0..w / 2).step_by(3) {
            *counts.entry(shot.px(x, y)).or_insert(0usize) += 1;
        }
    }
    let canvas = counts.into_iter().max_by_key(|(_, n)| *n)?.0;
    // Summed-area table of pixels that are not canvas.
    let stride = (w + 1) as usize;
    let mut sums = vec![0u32; stride * (h + 1) as usize];
    for y in 0..h {
        let mut row = 0;
        for x in 0..w {
            let p = shot.px(x, y);
            row += u32::from((0..3).any(|c| p[c].abs_diff(canvas[c]) > 3));
            sums[(y + 1) as usize * stride + (x + 1) as usize] =
                sums[y as usize * stride + (x + 1) as usize] + row;
        }
    }
    let empty = |r: Rect| {
        r.x0 >= 0 && r.y0 >= 0 && r.x1 <= w && r.y1 <= h && {
            let at = |x: i32, y: i32| sums[y as usize * stride + x as usize];
            at(r.x1, r.y1) + at(r.x0, r.y0) - at(r.x0, r.y1) - at(r.x1, r.y0) == 0
        }
    };
    let spots: Vec<(i32, i32)> = (0..h)
        .step_by(10)
        .flat_map(|y| (0..w).step_by(10).map(move |x| (x, y)))
        .filter(|&at| empty(Rect::room(at)))
        .collect();
    let apart = |a: (i32, i32), b: (i32, i32)| !Rect::room(a).overlaps(&Rect::room(b));
    let side_by_side = spots.iter().find_map(|&a| {
        spots
            .iter()
            .find(|&&b| b.1 == a.1 && b.0 > a.0 && apart(a, b))
            .map(|&b| (a, b))
    });
    side_by_side.or_else(|| {
        spots
            .iter()
            .find_map(|&a| spots.iter().find(|&&b| apart(a, b)).map(|&b| (a, b)))
    })
}

/// Pixels of the orange "connect" hint of a required input that has no wire, in `rect`.
pub(super) fn hint_pixels(shot: &Shot, rect: Rect) -> usize {
    let rect = rect.clip(shot);
    let mut count = 0;
    for y in rect.y0..rect.y1 {
        for x in rect.x0..rect.x1 {
            let [r, g, b] = shot.px(x, y);
            count += usize::from(r > 200 && (100..=150).contains(&g) && b < 90);
        }
    }
    count
}

/// Discs of a pin colour inside `rect`: their centres.
pub(super) fn pins(shot: &Shot, rect: Rect) -> Vec<(i32, i32)> {
    let rect = rect.clip(shot);
    let core = |x: i32, y: i32| {
        let p = shot.px(x, y);
        PIN_COLOURS.contains(&p)
            && (-1..=1).all(|dy| (-1..=1).all(|dx| shot.px(x + dx, y + dy) == p))
    };
    let mut cores: Vec<(i32, i32)> = Vec::new();
    for y in rect.y0 + 1..rect.y1 - 1 {
        for x in rect.x0 + 1..rect.x1 - 1 {
            if core(x, y) {
                cores.push((x, y));
            }
        }
    }
    // Group cores closer than 3 pixels; a disc's centre is its cores' mean.
    let mut groups: Vec<Vec<(i32, i32)>> = Vec::new();
    for point in cores {
        match groups.iter_mut().find(|group| {
            group
                .iter()
                .any(|q| (q.0 - point.0).abs() <= 2 && (q.1 - point.1).abs() <= 2)
        }) {
            Some(group) => group.push(point),
            None => groups.push(vec![point]),
        }
    }
    groups
        .iter()
        .map(|group| {
            let n = group.len() as i32;
            (
                group.iter().map(|p| p.0).sum::<i32>() / n,
                group.iter().map(|p| p.1).sum::<i32>() / n,
            )
        })
        .collect()
}
