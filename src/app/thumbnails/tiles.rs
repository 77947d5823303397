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
    }

    /// Gives `pins` the tiles; when they or their layout change, every tile is to be
    /// drawn again.
    pub fn lay_out(&mut self, pins: Vec<PinRef>) {
        let layout = AtlasLayout::for_tiles(pins.len(), ATLAS_COLUMNS, TILE_PIXELS);
        if pins != self.pins || layout != self.layout {
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
        self.pixels = pixels;
    }

    /// The index of `pin`'s tile, once drawn.
    fn drawn(&self, pin: &PinRef) -> Option<usize> {
        let index = self.pins.iter().position(|p| p == pin)?;
        self.ready.get(index).copied()?.then_some(index)
    }

    /// The texture and the part of it showing `pin`, once drawn.
    pub fn tile(&self, pin: &PinRef) -> Option<(egui::TextureId, egui::Rect)> {
        let index = self.drawn(pin)?;
        let texture = self.texture.as_ref()?;
        let (width, height) = self.layout.size();
        let (x, y) = self.layout.origin(index);
        let tile = TILE_PIXELS as f32;
        let min = egui::pos2(x as f32 / width as f32, y as f32 / height as f32);
        let size = egui::vec2(tile / width as f32, tile / height as f32);
        Some((texture.id(), egui::Rect::from_min_size(min, size)))
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
