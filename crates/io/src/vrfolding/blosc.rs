//! Blosc, the compressor of a VR-Folding store's chunks, decoded by c-blosc built from
//! source (`blosc-src`) with the codecs a store's chunks name: Blosc's own BloscLZ, LZ4
//! (numcodecs' default, which zarr 2.x writes), Zstd (what the GarmentTracking code writes)
//! and Zlib, all C. Snappy, Blosc's one C++ codec, is left out, so a build needs a C
//! compiler and no C++ one; a chunk compressed with Snappy is refused by name.
//!
//! zarrs' own Blosc codec builds every codec, Snappy too: so zarrs reads a store's arrays
//! with their compressor taken out, and is handed the chunks this module decodes.
//!
//! A chunk's header (Blosc 1, 16 bytes, little endian): version, codec version, flags
//! (bit 1: stored as it is; bits 5–7: the codec), element size, decoded size, block size,
//! encoded size.

use std::ffi::c_void;

/// Bytes of a Blosc chunk's header.
pub const HEADER: usize = 16;

/// The flag of a chunk stored as it is, uncompressed (its codec bits are then unused).
const MEMCPYED: u8 = 0x02;

/// The codecs a Blosc 1 chunk's flags can name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Codec {
    BloscLz,
    Lz4,
    Snappy,
    Zlib,
    Zstd,
}

impl Codec {
    /// The codec named by a header's flags byte (its top three bits); `None` for a number
    /// Blosc 1 does not have.
    pub fn of_flags(flags: u8) -> Option<Codec> {
        match flags >> 5 {
            0 => Some(Codec::BloscLz),
            1 => Some(Codec::Lz4),
            2 => Some(Codec::Snappy),
            3 => Some(Codec::Zlib),
            4 => Some(Codec::Zstd),
            _ => None,
        }
    }

    /// Its name, as a store's `.zarray` spells it (`cname`).
    pub fn name(self) -> &'static str {
        match self {
            Codec::BloscLz => "blosclz",
            Codec::Lz4 => "lz4",
            Codec::Snappy => "snappy",
            Codec::Zlib => "zlib",
            Codec::Zstd => "zstd",
        }
    }

    /// Whether this build decodes it: every codec but Snappy.
    pub fn built(self) -> bool {
        self != Codec::Snappy
    }
}

/// A little-endian `u32` of the header at `at` (the caller checked the header's length).
fn word(encoded: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([encoded[at], encoded[at + 1], encoded[at + 2], encoded[at + 3]])
}

/// The decoded size a chunk's header declares (which the decoder allocates at once), or
/// `None` when the chunk is shorter than a header.
pub fn declared_size(encoded: &[u8]) -> Option<u64> {
    (encoded.len() >= HEADER).then(|| u64::from(word(encoded, 4)))
}

/// Decode a Blosc chunk. The caller has checked its [`declared_size`]; here its header is
/// checked against its length and its codec against those built, before c-blosc reads it.
/// The error says what is wrong with the chunk, for a message that names it.
pub fn decode(encoded: &[u8]) -> Result<Vec<u8>, String> {
    if encoded.len() < HEADER {
        return Err(format!(
            "{} bytes: shorter than a Blosc header ({HEADER} bytes)",
            encoded.len()
        ));
    }
    let flags = encoded[2];
    let (decoded, stored) = (word(encoded, 4) as usize, word(encoded, 12) as usize);
    // c-blosc is given no length: it reads as far as the header says, so the header must
    // say the chunk's own length.
    if stored != encoded.len() {
        return Err(format!(
            "its Blosc header says {stored} bytes, but the chunk has {}",
            encoded.len()
        ));
    }
    if flags & MEMCPYED == 0 {
        match Codec::of_flags(flags) {
            Some(codec) if codec.built() => {}
            Some(codec) => {
                return Err(format!(
                    "compressed with Blosc's {} codec, which this build of close leaves out (it is C++): re-compress the store with lz4, zstd, zlib or blosclz, e.g. numcodecs.Blosc(cname=\"lz4\")",
                    codec.name()
                ))
            }
            None => {
                return Err(format!(
                    "its Blosc header names codec number {}, which Blosc 1 does not have",
                    flags >> 5
                ))
            }
        }
    }
    if decoded == 0 {
        return Ok(Vec::new());
    }
    let mut out = Vec::<u8>::with_capacity(decoded);
    // SAFETY: `encoded` holds the whole chunk its header describes (checked above, and
    // c-blosc checks every block's offset against that length); `out` has room for
    // `decoded` bytes, the most c-blosc writes when given that size; one thread.
    let written = unsafe {
        blosc_src::blosc_decompress_ctx(
            encoded.as_ptr().cast::<c_void>(),
            out.as_mut_ptr().cast::<c_void>(),
            decoded,
            1,
        )
    };
    let Ok(written) = usize::try_from(written) else {
        return Err(format!("Blosc cannot decode it (error {written}): the chunk is damaged"));
    };
    // SAFETY: c-blosc wrote `written` bytes, at most the `decoded` it was given.
    unsafe { out.set_len(written.min(decoded)) };
    if written != decoded {
        return Err(format!("it decodes to {written} bytes, but its Blosc header says {decoded}"));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `data` compressed by c-blosc with `codec`, byte shuffle of 4-byte elements.
    fn compress(data: &[u8], codec: Codec) -> Vec<u8> {
        let name = std::ffi::CString::new(codec.name()).unwrap();
        let mut out = vec![0u8; data.len() + blosc_src::BLOSC_MAX_OVERHEAD as usize];
        // SAFETY: `data` and `out` are valid for the lengths given; `out` has room for the
        // worst case (data + Blosc's overhead); `name` is NUL-terminated.
        let n = unsafe {
            blosc_src::blosc_compress_ctx(
                5,
                1,
                4,
                data.len(),
                data.as_ptr().cast::<c_void>(),
                out.as_mut_ptr().cast::<c_void>(),
                out.len(),
                name.as_ptr(),
                0,
                1,
            )
        };
        assert!(n > 0, "{codec:?} is not built");
        out.truncate(n as usize);
        out
    }

    fn floats() -> Vec<u8> {
        (0..3000).flat_map(|i| (0.001f32 * (i % 97) as f32).to_le_bytes()).collect()
    }

    #[test]
    fn every_built_codec_round_trips_and_its_header_names_it() {
        let data = floats();
        for codec in [Codec::BloscLz, Codec::Lz4, Codec::Zlib, Codec::Zstd] {
            let encoded = compress(&data, codec);
            assert!(encoded.len() < data.len() / 2, "{codec:?} compressed");
            assert_eq!(Codec::of_flags(encoded[2]), Some(codec));
            assert_eq!(declared_size(&encoded), Some(data.len() as u64));
            assert_eq!(decode(&encoded).unwrap(), data, "{codec:?}");
        }
    }

    #[test]
    fn a_chunk_naming_a_codec_left_out_is_refused_by_name() {
        let mut encoded = compress(&floats(), Codec::Lz4);
        // The flags' codec bits set to Snappy's number, 2: as a store written with
        // `numcodecs.Blosc(cname="snappy")` names it.
        encoded[2] = (encoded[2] & 0x1f) | (2 << 5);
        let e = decode(&encoded).unwrap_err();
        assert!(e.contains("Blosc's snappy codec") && e.contains("leaves out"), "{e}");
        encoded[2] = (encoded[2] & 0x1f) | (6 << 5);
        let e = decode(&encoded).unwrap_err();
        assert!(e.contains("codec number 6"), "{e}");
    }

    #[test]
    fn a_cut_or_damaged_chunk_is_an_error() {
        let encoded = compress(&floats(), Codec::Zstd);
        let e = decode(&encoded[..encoded.len() - 1]).unwrap_err();
        assert!(e.contains("header says") && e.contains("the chunk has"), "{e}");
        assert!(decode(&encoded[..10]).unwrap_err().contains("shorter than a Blosc header"));
        let mut damaged = encoded.clone();
        for b in &mut damaged[HEADER + 4 * 4..] {
            *b = 0xff;
        }
        assert!(decode(&damaged).unwrap_err().contains("cannot decode"), "damaged");
    }
}
