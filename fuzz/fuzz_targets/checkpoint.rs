//! Fuzz target: arbitrary bytes as a checkpoint file (`tessera render --resume`). The reader must
//! refuse anything malformed with one line (never a panic, never an allocation sized by an
//! unchecked field), and whatever it accepts must be self-consistent.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match tessera::checkpoint::read_checkpoint(data) {
        Ok(c) => {
            let n = c.meta.width as usize * c.meta.height as usize;
            assert_eq!(c.pixels.len(), n, "pixel count differs from the header");
        }
        Err(e) => assert!(!e.contains('\n'), "multi-line error: {e}"),
    }
});
