//! An EXR image written with its pixel blocks compressed on every core, stored in file order.
//!
//! Deflating the blocks of a multichannel image (a `moment` or `aov` render) took a few tenths
//! of a second on one core after a render that used all of them. The `exr` crate compresses in
//! parallel only through `rayon`, and its parallel writer stores blocks in the order they
//! finish when the line order is unspecified; here each core compresses a contiguous run of
//! blocks and the runs are written one after another, so the file's bytes are those the crate's
//! sequential writer produces, whatever the number of cores.
use exr::block::chunk::Chunk;
use exr::block::writer::ChunksWriter;
use exr::block::UncompressedBlock;
use exr::image::write::layers::{LayersWriter, WritableLayers};
use exr::image::Image;
use exr::meta::header::Header;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Writes `image` to `path` (which it creates or replaces), compressing its blocks on up to
/// `threads` threads.
pub(crate) fn write_parallel<'i, L>(
    image: &'i Image<L>,
    path: &Path,
    threads: usize,
) -> Result<(), String>
where
    L: WritableLayers<'i>,
    L::Writer: Sync,
{
    let file = std::fs::File::create(path).map_err(|e| e.to_string())?;
    let headers = image.layer_data.infer_headers(&image.attributes);
    let layers = image.layer_data.create_writer(&headers);
    let mut out = BufWriter::new(file);
    exr::block::write(&mut out, headers, true, |meta, chunks| {
        let blocks: Vec<(usize, UncompressedBlock)> = meta
            .collect_ordered_block_data(|b| layers.extract_uncompressed_block(&meta.headers, b))
            .collect();
        for (index, chunk) in compress_in_order(blocks, &meta.headers, threads) {
            chunks.write_chunk(index, chunk?)?;
        }
        Ok(())
    })
    .map_err(|e| e.to_string())?;
    out.flush().map_err(|e| e.to_string())
}

/// The blocks compressed, in their order: each of up to `threads` scoped threads takes a
/// contiguous run.
fn compress_in_order(
    blocks: Vec<(usize, UncompressedBlock)>,
    headers: &[Header],
    threads: usize,
) -> Vec<(usize, exr::error::Result<Chunk>)> {
    let per_thread = blocks.len().div_ceil(threads.max(1)).max(1);
    let mut runs: Vec<Vec<(usize, UncompressedBlock)>> = Vec::new();
    let mut rest = blocks.into_iter().peekable();
    while rest.peek().is_some() {
        runs.push(rest.by_ref().take(per_thread).collect());
    }
    std::thread::scope(|s| {
        let handles: Vec<_> = runs
            .into_iter()
            .map(|run| {
                s.spawn(move || {
                    run.into_iter()
                        .map(|(i, b)| (i, b.compress_to_chunk(headers)))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("a compression thread panicked"))
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use exr::prelude::{
        AnyChannel, AnyChannels, Encoding, FlatSamples, Layer, LayerAttributes, SmallVec, Text,
        Vec2, WritableImage,
    };

    fn image(values: &[Vec<f32>], w: usize, h: usize) -> Image<Layer<AnyChannels<FlatSamples>>> {
        let list = ["B", "G", "R"]
            .iter()
            .zip(values)
            .map(|(n, v)| AnyChannel::new(Text::from(*n), FlatSamples::F32(v.clone())))
            .collect();
        Image::from_layer(Layer::new(
            Vec2(w, h),
            LayerAttributes::default(),
            Encoding::SMALL_LOSSLESS,
            AnyChannels::sort(SmallVec::from_vec(list)),
        ))
    }

    /// The file's bytes are those of the crate's own sequential writer for any number of
    /// threads, on an image of many blocks (53 rows: four blocks of sixteen, the last short).
    /// Control: one value changed changes the bytes, so the comparison sees the pixels.
    #[test]
    fn bytes_are_the_sequential_writers() {
        let (w, h) = (37, 53);
        let mut state = 0x9e37_79b9u32;
        let mut values: Vec<Vec<f32>> = (0..3)
            .map(|_| {
                (0..w * h)
                    .map(|_| {
                        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                        (state >> 8) as f32 / (1 << 24) as f32
                    })
                    .collect()
            })
            .collect();
        let dir = std::env::temp_dir().join(format!("tessera_exr_blocks_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let want = dir.join("sequential.exr");
        image(&values, w, h)
            .write()
            .non_parallel()
            .to_file(&want)
            .unwrap();
        let want = std::fs::read(&want).unwrap();
        for threads in 1..=5 {
            let p = dir.join(format!("parallel_{threads}.exr"));
            write_parallel(&image(&values, w, h), &p, threads).unwrap();
            assert!(std::fs::read(&p).unwrap() == want, "{threads} threads");
        }
        values[1][w * h - 1] += 0.25;
        let p = dir.join("changed.exr");
        write_parallel(&image(&values, w, h), &p, 2).unwrap();
        assert!(std::fs::read(&p).unwrap() != want, "control");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
