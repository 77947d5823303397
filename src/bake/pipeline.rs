//! One map's bake as a pipeline: while the GPU renders band n + 1, a writer thread
//! converts band n and encodes it into the map's temporary file. Two band buffers
//! circulate between them (and on to the next map), so memory stays bounded and
//! nothing is allocated per band.

use super::encode::encode;
use super::maps::{Converter, Map, NormalConvention};
use super::{BakeError, Format};
use crate::render::RenderError;
use std::path::Path;
use std::sync::mpsc;

/// Where a renderer hands each band of rows: `sink(first row, pixels)` returns a buffer
/// to fill next.
pub type BandSink<'s> = dyn FnMut(u32, Vec<[f32; 4]>) -> Result<Vec<[f32; 4]>, RenderError> + 's;

/// What one map is and where it goes.
pub struct MapTarget<'p> {
    pub path: &'p Path,
    pub map: Map,
    pub size: u32,
    pub format: Format,
    /// Plane distance between pixels in x and z.
    pub spacing: (f64, f64),
    pub convention: NormalConvention,
}

/// Bakes one map: `render(sink)` renders the material outputs and hands every band, in
/// order, to `sink`, while a writer thread converts and encodes them into `target.path`
/// (atomically: on any failure the old file, if any, is unchanged). `spare` holds band
/// buffers to reuse and gets them back afterwards.
pub fn bake_map(
    target: &MapTarget<'_>,
    spare: &mut Vec<Vec<[f32; 4]>>,
    render: impl FnOnce(&mut BandSink<'_>) -> Result<(), RenderError>,
) -> Result<(), BakeError> {
    // A rendezvous: the renderer waits while the writer is still on the band before.
    let (full, bands) = mpsc::sync_channel::<Vec<[f32; 4]>>(0);
    let (free, recycled) = mpsc::channel::<Vec<[f32; 4]>>();
    spare.drain(..).for_each(|buffer| drop(free.send(buffer)));
    std::thread::scope(|scope| {
        let writer = scope.spawn(move || {
            let mut converter =
                Converter::new(target.map, target.size, target.spacing, target.convention);
            crate::fsutil::write_atomic_with(target.path, |file| {
                encode(file, target.size, target.format, |emit| {
                    for mut band in bands {
                        converter.band(&mut band, emit)?;
                        let _ = free.send(band);
                    }
                    converter.finish(emit)
                })
            })
        });
        let mut writer_stopped = false;
        let rendered = render(&mut |_, band| {
            full.send(band).map_err(|_| {
                writer_stopped = true;
                RenderError::Stopped("the map writer stopped")
            })?;
            Ok(recycled.try_recv().unwrap_or_default())
        });
        drop(full);
        let written = writer.join();
        spare.extend(recycled.try_iter());
        let path = || target.path.to_path_buf();
        let written = written
            .map_err(|_| BakeError::WriterPanicked { path: path() })?
            .map_err(|error| BakeError::Write {
                path: path(),
                error,
            });
        match rendered {
            // A render that failed first explains why the writer got too few rows.
            Err(error) if !writer_stopped => Err(BakeError::from(error)),
            _ => written,
        }
    })
}
