//! A bake's maps as one pipeline: while the GPU renders band n + 1, a writer thread
//! converts band n and encodes it into its map's temporary file; the next map starts
//! rendering while the writer of the one before finishes its last bands. Band buffers
//! circulate between them (and on from map to map), so memory stays bounded and nothing
//! is allocated per band.

use super::encode::encode;
use super::maps::{Converter, Map, NormalConvention};
use super::{BakeError, Format};
use crate::fsutil::{Naming, Staged};
use crate::render::{RenderError, non_finite};
use std::path::Path;
use std::sync::mpsc;
use std::thread::ScopedJoinHandle;

/// Where a renderer hands each band of rows: `sink(first row, pixels)` returns a buffer
/// to fill next.
pub type BandSink<'s> = dyn FnMut(u32, Vec<[f32; 4]>) -> Result<Vec<[f32; 4]>, RenderError> + 's;

/// What one map is and where it goes.
pub struct MapTarget<'p> {
    pub path: &'p Path,
    pub map: Map,
    /// The material's lighting model (which roughness the maps carry).
    pub shading: crate::graph::Shading,
    pub size: u32,
    pub format: Format,
    /// Plane distance between pixels in x and z.
    pub spacing: (f64, f64),
    pub convention: NormalConvention,
    /// For one tile of a repeating texture: the heights of the rows just above and just
    /// below the image ([`Converter::tiling`]).
    pub beyond: Option<&'p (Vec<f32>, Vec<f32>)>,
}

/// Bakes `targets` in order: `render(index, sink)` renders the material outputs of map
/// `index` and hands every band, in order, to `sink`, while a writer thread converts
/// and encodes them into the map's temporary file. The maps are put in place together
/// once all are written; on any failure none is, and the old files are unchanged. With
/// `overlap`, a map renders while the writer of the one before is still at work (two
/// maps' writers at once: for EXR, whose writers hold a band each; PNG writers hold
/// their whole image, so they go one at a time).
pub fn bake_maps(
    targets: &[MapTarget<'_>],
    overlap: bool,
    mut render: impl FnMut(usize, &mut BandSink<'_>) -> Result<(), RenderError>,
) -> Result<(), BakeError> {
    let (free, recycled) = mpsc::channel::<Vec<[f32; 4]>>();
    let mut written = Vec::with_capacity(targets.len());
    std::thread::scope(|scope| {
        let mut writing: Option<Writing<'_, '_>> = None;
        for (index, target) in targets.iter().enumerate() {
            if !overlap && let Some(before) = writing.take() {
                written.push(before.finish()?);
            }
            // One band may wait while the writer is on the band before.
            let (full, bands) = mpsc::sync_channel::<Vec<[f32; 4]>>(1);
            let free = free.clone();
            let writer = scope.spawn(move || write_map(target, bands, free));
            let mut writer_stopped = false;
            let rendered = render(index, &mut |_, band| {
                full.send(band).map_err(|_| {
                    writer_stopped = true;
                    RenderError::Stopped("the map writer stopped")
                })?;
                Ok(recycled.try_recv().unwrap_or_default())
            });
            drop(full);
            if let Some(before) = writing.replace(Writing {
                target,
                writer,
                rendered,
                writer_stopped,
            }) {
                written.push(before.finish()?);
            }
        }
        if let Some(last) = writing {
            written.push(last.finish()?);
        }
        Ok::<(), BakeError>(())
    })?;
    crate::fsutil::commit(written).map_err(|(path, error)| BakeError::Write { path, error })
}

/// One map whose rendering is done and whose writer may still be at work.
struct Writing<'scope, 'p> {
    target: &'scope MapTarget<'p>,
    writer: ScopedJoinHandle<'scope, std::io::Result<Staged>>,
    rendered: Result<(), RenderError>,
    writer_stopped: bool,
}

impl Writing<'_, '_> {
    /// Waits for the writer and gives the map written to its temporary file; a render
    /// that failed first explains why the writer got too few rows.
    fn finish(self) -> Result<Staged, BakeError> {
        let path = || self.target.path.to_path_buf();
        let written = self
            .writer
            .join()
            .map_err(|_| BakeError::WriterPanicked { path: path() })?
            .map_err(|error| BakeError::Write {
                path: path(),
                error,
            });
        match self.rendered {
            Err(error) if !self.writer_stopped => Err(BakeError::from(error)),
            _ => written,
        }
    }
}

/// The writer of one map: converts and encodes every band from `bands` into the map's
/// temporary file, handing each buffer back through `free`; a non-finite sample fails it.
fn write_map(
    target: &MapTarget<'_>,
    bands: mpsc::Receiver<Vec<[f32; 4]>>,
    free: mpsc::Sender<Vec<[f32; 4]>>,
) -> std::io::Result<Staged> {
    let mut converter = Converter::new(
        target.map,
        target.shading,
        target.size,
        target.spacing,
        target.convention,
    );
    if let Some((above, below)) = target.beyond {
        converter = converter.tiling(above.clone(), below.clone());
    }
    let (width, mut rows) = (target.size as usize, 0);
    crate::fsutil::stage(target.path, Naming::Implied, |file| {
        encode(file, target.size, target.format, |emit| {
            let mut finite = |pixels: &[[f32; 4]]| {
                if let Some(why) = non_finite(target.map.name(), pixels, width, rows) {
                    return Err(std::io::Error::other(why));
                }
                rows += pixels.len() / width;
                emit(pixels)
            };
            for mut band in bands {
                converter.band(&mut band, &mut finite)?;
                let _ = free.send(band);
            }
            converter.finish(&mut finite)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A map with a NaN or an infinity is refused, naming the map and the pixel, and
    /// nothing is written: not an infinity in an EXR, nor a black PNG pixel.
    #[test]
    fn a_map_with_a_non_finite_sample_is_refused_by_name_and_not_written() {
        let dir = std::env::temp_dir().join(format!("veneer-finite-maps-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch folder");
        for (format, bad) in [(Format::Exr, f32::INFINITY), (Format::Png8, f32::NAN)] {
            let path = dir.join(format!("stones_albedo.{}", format.extension()));
            let target = MapTarget {
                path: &path,
                map: Map::Albedo,
                shading: crate::graph::Shading::BlinnPhong,
                size: 2,
                format,
                spacing: (1.0, 1.0),
                convention: NormalConvention::OpenGl,
                beyond: None,
            };
            let result = bake_maps(&[target], false, |_, sink| {
                let mut band = vec![[0.5f32, 0.5, 0.5, 1.0]; 4];
                band[3][0] = bad;
                sink(0, band).map(drop)
            });
            let message = result.expect_err("refused").to_string();
            assert!(
                message.contains("albedo map") && message.contains("pixel (1, 1)"),
                "{message}"
            );
            assert!(!path.exists(), "{format:?}: nothing is written");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
