//! The thumbnail atlas's tiles: which output pin each shows, where it sits in the atlas
//! texture, what each was last sent to draw, and the pixels that came back.

use crate::graph::PinRef;
use crate::render::AtlasLayout;

/// A tile's width and height in pixels.
pub const TILE_PIXELS: u32 = 64;
/// Tiles to a row of the atlas.
pub(in crate::app) const ATLAS_COLUMNS: u32 = 8;

/// The tiles of the thumbnail atlas and the texture they are drawn into.
pub struct Tiles {
    /// Output pins with a tile, in tile order.
    pins: Vec<PinRef>,
    layout: AtlasLayout,
    /// What each tile was last sent to draw (`None`: never, or since the layout changed).
    sent: Vec<Option<u64>>,
    /// Whether each tile has pixels in the texture for the current layout.
    ready: Vec<bool>,
    texture: Option<egui::TextureHandle>,
    /// The atlas as last read back (RGBA8 rows).
    pixels: Vec<u8>,
    /// The tiles as they were before the pins or layout last changed: shown for pins
    /// whose new tile is not drawn yet (a texture graph's atlas takes seconds to
    /// render its passes again), until every new tile is.
    stale: Option<Stale>,
}

/// Tiles of an earlier layout, kept on screen while the new ones are drawn.
struct Stale {
    pins: Vec<PinRef>,
    ready: Vec<bool>,
    layout: AtlasLayout,
    texture: egui::TextureHandle,
}

impl Default for Tiles {
    fn default() -> Tiles {
        Tiles {
            pins: Vec::new(),
            layout: AtlasLayout::for_tiles(0, ATLAS_COLUMNS, TILE_PIXELS),
            sent: Vec::new(),
            ready: Vec::new(),
            texture: None,
            pixels: Vec::new(),
            stale: None,
        }
    }
}

impl Tiles {
    /// The output pins that have a tile, in tile order.
    pub fn pins(&self) -> &[PinRef] {
        &self.pins
    }

    /// Where the tiles sit in the atlas.
    pub fn layout(&self) -> AtlasLayout {
        self.layout
    }

    /// No tiles at all.
    pub fn clear(&mut self) {
        self.pins.clear();
        self.stale = None;
    }

    /// Gives `pins` the tiles; when they or their layout change, every tile is to be
    /// drawn again.
    pub fn lay_out(&mut self, pins: Vec<PinRef>) {
        let layout = AtlasLayout::for_tiles(pins.len(), ATLAS_COLUMNS, TILE_PIXELS);
        if pins != self.pins || layout != self.layout {
            if let Some(texture) = self.texture.take() {
                self.stale = Some(Stale {
                    pins: std::mem::take(&mut self.pins),
                    ready: std::mem::take(&mut self.ready),
                    layout: self.layout,
                    texture,
                });
            }
            self.sent = vec![None; pins.len()];
            self.ready = vec![false; pins.len()];
            self.pins = pins;
            self.layout = layout;
        }
    }

    /// The tiles whose `key` (what they depend on) changed since they were last sent,
    /// marked as sent with it.
    pub fn take_changed(&mut self, key: impl Fn(&PinRef) -> u64) -> Vec<usize> {
        let mut changed = Vec::new();
        for (index, pin) in self.pins.iter().enumerate() {
            let key = key(pin);
            if self.sent[index] != Some(key) {
                self.sent[index] = Some(key);
                changed.push(index);
            }
        }
        changed
    }

    /// Whether every tile has pixels for the current layout.
    pub fn all_ready(&self) -> bool {
        self.ready.iter().all(|ready| *ready)
    }

    /// Takes in `pixels`, the whole atlas drawn at `layout`, for the tiles `drawn`: they
    /// go into the texture (only those parts of it), unless the layout changed since.
    pub fn take_in(
        &mut self,
        ctx: &egui::Context,
        layout: AtlasLayout,
        drawn: &[usize],
        pixels: Vec<u8>,
    ) {
        if layout != self.layout {
            return;
        }
        let (width, height) = layout.size();
        let image =
            egui::ColorImage::from_rgba_unmultiplied([width as usize, height as usize], &pixels);
        let options = egui::TextureOptions::LINEAR;
        match &mut self.texture {
            Some(texture) if texture.size() == [width as usize, height as usize] => {
                for index in drawn {
                    let (x, y) = layout.origin(*index);
                    let tile = TILE_PIXELS as usize;
                    let part = image.region_by_pixels([x as usize, y as usize], [tile, tile]);
                    texture.set_partial([x as usize, y as usize], part, options);
                }
            }
            _ => self.texture = Some(ctx.load_texture("node thumbnails", image, options)),
        }
        for index in drawn {
            if let Some(ready) = self.ready.get_mut(*index) {
                *ready = true;
            }
        }
        if self.all_ready() {
            self.stale = None;
        }
        self.pixels = pixels;
    }

    /// The index of `pin`'s tile, once drawn.
    fn drawn(&self, pin: &PinRef) -> Option<usize> {
        let index = self.pins.iter().position(|p| p == pin)?;
        self.ready.get(index).copied()?.then_some(index)
    }

    /// The texture and the part of it showing `pin`, once drawn (until then, its tile
    /// of the layout before, if it had one).
    pub fn tile(&self, pin: &PinRef) -> Option<(egui::TextureId, egui::Rect)> {
        if let (Some(index), Some(texture)) = (self.drawn(pin), &self.texture) {
            return Some((texture.id(), part(self.layout, index)));
        }
        let stale = self.stale.as_ref()?;
        let index = stale.pins.iter().position(|p| p == pin)?;
        (stale.ready.get(index).copied()?).then(|| (stale.texture.id(), part(stale.layout, index)))
    }

    /// The RGBA8 pixels of `pin`'s tile, rows from the top, once drawn.
    pub fn tile_pixels(&self, pin: &PinRef) -> Option<Vec<[u8; 4]>> {
        let index = self.drawn(pin)?;
        let (width, _) = self.layout.size();
        let (x, y) = self.layout.origin(index);
        let mut tile = Vec::with_capacity((TILE_PIXELS * TILE_PIXELS) as usize);
        for row in y..y + TILE_PIXELS {
            for column in x..x + TILE_PIXELS {
                let at = ((row * width + column) * 4) as usize;
                let pixel = self.pixels.get(at..at + 4)?;
                tile.push([pixel[0], pixel[1], pixel[2], pixel[3]]);
            }
        }
        Some(tile)
    }
}

/// The part of an atlas of `layout` (in texture coordinates) that tile `index` fills.
fn part(layout: AtlasLayout, index: usize) -> egui::Rect {
    let (width, height) = layout.size();
    let (x, y) = layout.origin(index);
    let tile = TILE_PIXELS as f32;
    let min = egui::pos2(x as f32 / width as f32, y as f32 / height as f32);
    let size = egui::vec2(tile / width as f32, tile / height as f32);
    egui::Rect::from_min_size(min, size)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::NodeId;

    fn pin(node: u32) -> PinRef {
        PinRef::new(NodeId(node), "value")
    }

    /// Hands `tiles` the whole atlas drawn, every tile grey.
    fn draw_all(tiles: &mut Tiles, ctx: &egui::Context) {
        let layout = tiles.layout();
        let (width, height) = layout.size();
        let drawn: Vec<usize> = (0..tiles.pins().len()).collect();
        tiles.take_changed(|_| 1);
        tiles.take_in(
            ctx,
            layout,
            &drawn,
            vec![128; (width * height * 4) as usize],
        );
    }

    #[test]
    fn a_new_layout_shows_the_old_tiles_until_every_new_one_is_drawn() {
        let ctx = egui::Context::default();
        let mut tiles = Tiles::default();
        tiles.lay_out(vec![pin(1), pin(2)]);
        draw_all(&mut tiles, &ctx);
        let (old, _) = tiles.tile(&pin(2)).expect("drawn");
        // A node added: every tile is to be drawn again, in a new texture.
        tiles.lay_out(vec![pin(1), pin(2), pin(3)]);
        assert!(!tiles.all_ready());
        let (shown, part) = tiles.tile(&pin(2)).expect("the old tile meanwhile");
        assert_eq!(shown, old);
        assert_eq!(
            part,
            super::part(AtlasLayout::for_tiles(2, ATLAS_COLUMNS, TILE_PIXELS), 1)
        );
        assert!(
            tiles.tile(&pin(3)).is_none(),
            "a new pin has nothing to show yet"
        );
        assert!(
            tiles.tile_pixels(&pin(2)).is_none(),
            "pixels are the new layout's only"
        );
        draw_all(&mut tiles, &ctx);
        let (now, _) = tiles.tile(&pin(2)).expect("drawn again");
        assert_ne!(now, old, "the new texture");
        assert!(tiles.stale.is_none(), "the old tiles are let go");
    }
}
