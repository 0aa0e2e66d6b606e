//! Byte-level mutations, and the GLB container put around a (mutated)
//! document: header words (version, lengths, chunk types) set to values
//! at the edges, chunks truncated, bytes flipped.

use crate::fuzz::generate::Rng;

/// A GLB of `json` and `bin` (both padded to four bytes).
pub fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |b: &[u8], with: u8| {
        let mut v = b.to_vec();
        while !v.len().is_multiple_of(4) {
            v.push(with);
        }
        v
    };
    let (json, bin) = (pad(json, b' '), pad(bin, 0));
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((28 + json.len() + bin.len()) as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(&bin);
    out
}

const WORDS: &[u32] = &[0, 1, 2, 3, 11, 12, 20, 0x7fff_ffff, 0x8000_0000, 0xffff_ffff, 0xffff_fff0, 0x4e4f_534a];

/// Overwrites one of a GLB's header or chunk-header words.
pub fn glb_header(rng: &mut Rng, bytes: &mut [u8]) {
    // Version, length, JSON chunk length and type; the BIN chunk's words
    // sit after the JSON chunk.
    let json_len = bytes.get(12..16).map_or(0, |w| u32::from_le_bytes(w.try_into().unwrap()) as usize);
    let offsets = [4, 8, 12, 16, 20 + json_len, 24 + json_len];
    let at = rng.pick(&offsets);
    let word = if rng.chance(70) { rng.pick(WORDS) } else { rng.next_u64() as u32 };
    if let Some(w) = bytes.get_mut(at..at + 4) {
        w.copy_from_slice(&word.to_le_bytes());
    }
}

/// One to eight random bytes set, flipped or removed, or the tail cut.
pub fn noise(rng: &mut Rng, bytes: &mut Vec<u8>) {
    if bytes.is_empty() {
        return;
    }
    if rng.chance(15) {
        let keep = rng.below(bytes.len() as u64) as usize;
        bytes.truncate(keep);
        return;
    }
    for _ in 0..rng.range(1, 8) {
        if bytes.is_empty() {
            return;
        }
        let i = rng.below(bytes.len() as u64) as usize;
        match rng.below(3) {
            0 => bytes[i] ^= 1 << rng.below(8),
            1 => bytes[i] = rng.pick(&[0, 0xff, b'0', b'9', b'-', b'"', b'{', b'[', b'\t', b'\n']),
            _ => {
                bytes.remove(i);
            }
        }
    }
}
