//! Mitsuba's binary voxel-grid files (`.vol`, the format of Mitsuba 0.6 that Mitsuba 3's
//! `gridvolume` reads), little-endian:
//!
//! - bytes 0-2: `VOL`; byte 3: the format version, 3;
//! - bytes 4-7: the encoding (int32), 1 = float32, the only one defined;
//! - bytes 8-19: the resolution along x, y and z (int32 each);
//! - bytes 20-23: channels per voxel (int32): 1, 3, or 6 (an SGGX matrix per voxel: `xx, yy, zz,
//!   xy, xz, yz`);
//! - bytes 24-47: the grid's bounding box (float32: x, y, z of its minimum, then of its maximum);
//! - then the voxels, x fastest, then y, then z, channels interleaved.
//!
//! Every departure (a short or long file, another magic, version or encoding, a value that is
//! not finite, or negative in a grid of 1 or 3 channels) is an error naming the file and what was
//! found. Which channel counts a parameter takes is its plugin's to check.
use std::path::Path;
use tessera_core::medium::VoxelGrid;

/// Bytes before the voxel data.
pub const HEADER_BYTES: usize = 48;

/// A `.vol` file's contents.
#[derive(Debug)]
pub struct VolFile {
    /// The voxels.
    pub grid: VoxelGrid,
    /// The bounding box the file states: minimum then maximum corner.
    pub bbox: [[f32; 3]; 2],
}

fn i32_at(b: &[u8], at: usize) -> i32 {
    i32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

fn f32_at(b: &[u8], at: usize) -> f32 {
    f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

/// Parses the bytes of a `.vol` file; the error says what is wrong (without the file's name).
pub fn parse_vol(b: &[u8]) -> Result<VolFile, String> {
    if b.len() < HEADER_BYTES {
        return Err(format!(
            "truncated .vol header: {} bytes, the header has {HEADER_BYTES}",
            b.len()
        ));
    }
    if &b[0..3] != b"VOL" {
        return Err(format!(
            "not a .vol file: it starts with {:?}, not \"VOL\"",
            String::from_utf8_lossy(&b[0..3])
        ));
    }
    if b[3] != 3 {
        return Err(format!(
            ".vol format version {}: only version 3 is read",
            b[3]
        ));
    }
    let encoding = i32_at(b, 4);
    if encoding != 1 {
        return Err(format!(
            ".vol encoding {encoding}: only 1 (float32) is defined"
        ));
    }
    let res = [i32_at(b, 8), i32_at(b, 12), i32_at(b, 16)];
    if res.iter().any(|&r| r <= 0) {
        return Err(format!(
            ".vol resolution {} x {} x {}: each must be positive",
            res[0], res[1], res[2]
        ));
    }
    let channels = i32_at(b, 20);
    if !matches!(channels, 1 | 3 | 6) {
        return Err(format!(
            ".vol with {channels} channels per voxel: only 1, 3 or 6 are read"
        ));
    }
    let count = res
        .iter()
        .try_fold(channels as u64, |a, &r| a.checked_mul(r as u64))
        .filter(|&n| n <= (isize::MAX as u64) / 4)
        .ok_or_else(|| {
            format!(
                ".vol resolution {} x {} x {} is too large",
                res[0], res[1], res[2]
            )
        })? as usize;
    let need = HEADER_BYTES + 4 * count;
    if b.len() != need {
        let what = if b.len() < need {
            "truncated"
        } else {
            "too long"
        };
        return Err(format!(
            "{what} .vol file: {} x {} x {} voxels of {channels} float32 need {need} bytes, \
             found {}",
            res[0],
            res[1],
            res[2],
            b.len()
        ));
    }
    let mut data = Vec::with_capacity(count);
    for i in 0..count {
        let v = f32_at(b, HEADER_BYTES + 4 * i);
        if !(v.is_finite() && (v >= 0.0 || channels == 6)) {
            let voxel = i / channels as usize;
            return Err(format!(
                ".vol value {v} at voxel {voxel} (channel {}): values must be finite and \
                 non-negative (negative only in a matrix's off-diagonal, of 6 channels)",
                i % channels as usize
            ));
        }
        data.push(v);
    }
    let bbox = [
        [f32_at(b, 24), f32_at(b, 28), f32_at(b, 32)],
        [f32_at(b, 36), f32_at(b, 40), f32_at(b, 44)],
    ];
    let grid = VoxelGrid::new(res.map(|r| r as u32), channels as u32, data)
        .ok_or_else(|| "inconsistent .vol grid".to_string())?;
    Ok(VolFile { grid, bbox })
}

/// Reads and parses the `.vol` file at `path`.
pub fn read_vol(path: &Path) -> Result<VolFile, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read the .vol file: {e}"))?;
    parse_vol(&bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file of `res` voxels, `channels` each, all `value`.
    fn file(res: [i32; 3], channels: i32, value: f32) -> Vec<u8> {
        let mut b = b"VOL\x03".to_vec();
        for v in [1, res[0], res[1], res[2], channels] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for v in [0.0f32, 0.0, 0.0, 1.0, 2.0, 3.0] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for _ in 0..(res[0] * res[1] * res[2] * channels) {
            b.extend_from_slice(&value.to_le_bytes());
        }
        b
    }

    #[test]
    fn reads_a_grid_and_its_box() {
        let f = parse_vol(&file([2, 3, 4], 3, 0.5)).expect("valid");
        assert_eq!(f.grid.res(), [2, 3, 4]);
        assert_eq!(f.grid.channels(), 3);
        assert_eq!(f.bbox, [[0.0; 3], [1.0, 2.0, 3.0]]);
        assert_eq!(f.grid.max_value(), 0.5);
    }

    #[test]
    fn refuses_each_kind_of_bad_file_saying_what() {
        let good = file([2, 2, 2], 1, 1.0);
        let cases: Vec<(Vec<u8>, &str)> = vec![
            (good[..20].to_vec(), "truncated .vol header: 20 bytes"),
            (good[..good.len() - 1].to_vec(), "truncated .vol file"),
            ([good.clone(), vec![0]].concat(), "too long .vol file"),
            (
                [b"VOX".to_vec(), good[3..].to_vec()].concat(),
                "not a .vol file",
            ),
            (
                [b"VOL\x02".to_vec(), good[4..].to_vec()].concat(),
                "version 2",
            ),
            (
                {
                    let mut b = good.clone();
                    b[4] = 2;
                    b
                },
                "encoding 2",
            ),
            (file([2, 2, 2], 5, 1.0), "5 channels"),
            (file([2, 2, 2], 6, f32::INFINITY), "value inf"),
            (file([2, 0, 2], 1, 1.0), "resolution 2 x 0 x 2"),
            (file([2, 2, 2], 1, -1.0), "value -1 at voxel 0"),
            (file([2, 2, 2], 1, f32::NAN), "value NaN"),
        ];
        for (bytes, words) in cases {
            let e = parse_vol(&bytes).expect_err(words);
            assert!(e.contains(words), "{e:?} should say {words:?}");
        }
        // Controls: the good file reads, and so does a 6-channel grid with negative values.
        assert!(parse_vol(&good).is_ok());
        assert_eq!(
            parse_vol(&file([2, 2, 2], 6, -0.5))
                .expect("6 channels")
                .grid
                .channels(),
            6
        );
    }
}
