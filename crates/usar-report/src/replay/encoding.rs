//! The replay's binary encoding: every value quantised to an integer ([`super::Channel`]),
//! delta-coded along time per robot, zigzag-mapped to unsigned, written as LEB128 varints,
//! then compressed with raw deflate (RFC 1951, which browsers inflate with
//! `DecompressionStream("deflate-raw")`) and put in the page as base64. See `docs/replay.md`.
//!
//! Stream layout (before compression), all varints:
//! 1. for each channel in [`super::Channel::ALL`] order, for each robot, for each sample:
//!    `zigzag(v[i] - v[i - 1])` with `v[-1] = 0`;
//! 2. the number of rescuee changes, then per change: the sample's delta from the previous
//!    change's sample, the rescuee's index, its code.

use std::io::{Read, Write};

use flate2::Compression;
use flate2::read::DeflateDecoder;
use flate2::write::DeflateEncoder;

use super::channels::{Channel, RescueeCode};
use super::error::ReplayError;
use super::recording::{Recording, RescueeChange};

/// Maps a signed integer to an unsigned one so that small magnitudes stay small:
/// 0, -1, 1, -2, ... to 0, 1, 2, 3, ... (protocol buffers' zigzag encoding).
pub fn zigzag(v: i64) -> u64 {
    ((v << 1) ^ (v >> 63)) as u64
}

/// The inverse of [`zigzag`].
pub fn unzigzag(u: u64) -> i64 {
    ((u >> 1) as i64) ^ -((u & 1) as i64)
}

/// Appends `u` as an unsigned LEB128 varint: 7 bits per byte, low bits first, the high bit set
/// on every byte but the last (1 byte below 128, at most 10).
pub fn write_varint(mut u: u64, out: &mut Vec<u8>) {
    while u >= 0x80 {
        out.push((u as u8 & 0x7f) | 0x80);
        u >>= 7;
    }
    out.push(u as u8);
}

/// Reads one varint of [`write_varint`] at `*pos`, moving `*pos` past it.
///
/// # Errors
/// [`ReplayError::Decode`] if the bytes end inside the varint or it is longer than 10 bytes.
pub fn read_varint(bytes: &[u8], pos: &mut usize) -> Result<u64, ReplayError> {
    let mut u = 0u64;
    for shift in (0..64).step_by(7) {
        let b = *bytes
            .get(*pos)
            .ok_or_else(|| ReplayError::Decode(format!("stream ends at byte {}", *pos)))?;
        *pos += 1;
        u |= u64::from(b & 0x7f) << shift;
        if b & 0x80 == 0 {
            return Ok(u);
        }
    }
    Err(ReplayError::Decode(format!(
        "varint longer than 10 bytes before byte {}",
        *pos
    )))
}

/// The recording's uncompressed stream (see the module docs).
pub fn encode_recording(rec: &Recording) -> Vec<u8> {
    let (n, robots) = (rec.samples, rec.robots);
    let mut out = Vec::with_capacity(n * robots * Channel::ALL.len() + 16);
    for values in &rec.channels {
        for r in 0..robots {
            let mut prev = 0i64;
            for i in 0..n {
                let v = i64::from(values[i * robots + r]);
                write_varint(zigzag(v - prev), &mut out);
                prev = v;
            }
        }
    }
    write_varint(rec.rescuee_changes.len() as u64, &mut out);
    let mut prev = 0u32;
    for c in &rec.rescuee_changes {
        write_varint(u64::from(c.sample - prev), &mut out);
        write_varint(u64::from(c.rescuee), &mut out);
        write_varint(c.code as u64, &mut out);
        prev = c.sample;
    }
    out
}

/// What [`decode_recording`] reads back: the channels and the rescuee changes.
#[derive(Debug, Clone, PartialEq)]
pub struct DecodedRecording {
    /// Per channel, sample-major (as [`Recording::channels`]).
    pub channels: Vec<Vec<i32>>,
    /// The rescuee changes (as [`Recording::rescuee_changes`]).
    pub rescuee_changes: Vec<RescueeChange>,
}

/// Reads a stream of [`encode_recording`] of `samples` samples of `robots` robots (the Rust
/// twin of the page's decoder, for tests and tools).
///
/// # Errors
/// [`ReplayError::Decode`] for a truncated stream, a value out of `i32` range, an unknown
/// rescuee code or bytes left over.
pub fn decode_recording(
    bytes: &[u8],
    samples: usize,
    robots: usize,
) -> Result<DecodedRecording, ReplayError> {
    let mut pos = 0usize;
    let mut channels = vec![vec![0i32; samples * robots]; Channel::ALL.len()];
    for values in &mut channels {
        for r in 0..robots {
            let mut v = 0i64;
            for i in 0..samples {
                v += unzigzag(read_varint(bytes, &mut pos)?);
                values[i * robots + r] = i32::try_from(v)
                    .map_err(|_| ReplayError::Decode(format!("value {v} out of range")))?;
            }
        }
    }
    let count = read_varint(bytes, &mut pos)?;
    let mut rescuee_changes = Vec::new();
    let mut sample = 0u64;
    for _ in 0..count {
        sample += read_varint(bytes, &mut pos)?;
        let rescuee = read_varint(bytes, &mut pos)?;
        let code = read_varint(bytes, &mut pos)?;
        let code = *RESCUEE_CODES
            .get(code as usize)
            .ok_or_else(|| ReplayError::Decode(format!("unknown rescuee code {code}")))?;
        rescuee_changes.push(RescueeChange {
            sample: u32::try_from(sample)
                .map_err(|_| ReplayError::Decode(format!("sample {sample} out of range")))?,
            rescuee: u32::try_from(rescuee)
                .map_err(|_| ReplayError::Decode(format!("rescuee {rescuee} out of range")))?,
            code,
        });
    }
    if pos != bytes.len() {
        return Err(ReplayError::Decode(format!(
            "{} bytes left over",
            bytes.len() - pos
        )));
    }
    Ok(DecodedRecording {
        channels,
        rescuee_changes,
    })
}

/// Rescuee codes by number.
const RESCUEE_CODES: [RescueeCode; 7] = [
    RescueeCode::Waiting,
    RescueeCode::Claimed,
    RescueeCode::Carried,
    RescueeCode::Delivered,
    RescueeCode::Abandoned,
    RescueeCode::Unreachable,
    RescueeCode::Skipped,
];

/// Raw deflate (RFC 1951, no zlib or gzip header) at the default level.
///
/// # Errors
/// [`ReplayError::Encode`] if the compressor fails (it does not on memory buffers).
pub fn compress(bytes: &[u8]) -> Result<Vec<u8>, ReplayError> {
    let mut enc = DeflateEncoder::new(Vec::new(), Compression::default());
    enc.write_all(bytes)
        .and_then(|()| enc.finish())
        .map_err(|e| ReplayError::Encode(format!("deflate: {e}")))
}

/// The inverse of [`compress`].
///
/// # Errors
/// [`ReplayError::Decode`] for data that are not raw deflate.
pub fn decompress(bytes: &[u8]) -> Result<Vec<u8>, ReplayError> {
    let mut out = Vec::new();
    DeflateDecoder::new(bytes)
        .read_to_end(&mut out)
        .map_err(|e| ReplayError::Decode(format!("inflate: {e}")))?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::replay::sampling::SampleClock;

    fn recording(
        samples: usize,
        robots: usize,
        values: &[i32],
        changes: &[(u32, u32, u8)],
    ) -> Recording {
        let channels = (0..Channel::ALL.len())
            .map(|c| {
                (0..samples * robots)
                    .map(|i| values[(c * 31 + i) % values.len()])
                    .collect()
            })
            .collect();
        let mut rescuee_changes: Vec<RescueeChange> = changes
            .iter()
            .map(|&(s, r, c)| RescueeChange {
                sample: s,
                rescuee: r,
                code: RESCUEE_CODES[c as usize % RESCUEE_CODES.len()],
            })
            .collect();
        rescuee_changes.sort_by_key(|c| c.sample);
        Recording {
            method: "RNE".into(),
            trial: 0,
            seed: 1,
            dt_s: 0.02,
            clock: SampleClock {
                every_steps: 5,
                total_steps: 5 * samples as u64,
            },
            robots,
            samples,
            channels,
            rescuee_changes,
            marks: Vec::new(),
            rounds: Vec::new(),
        }
    }

    proptest! {
        #[test]
        fn zigzag_round_trips(v in any::<i64>()) {
            prop_assert_eq!(unzigzag(zigzag(v)), v);
        }

        #[test]
        fn varints_round_trip(us in proptest::collection::vec(any::<u64>(), 0..50)) {
            let mut out = Vec::new();
            for &u in &us {
                write_varint(u, &mut out);
            }
            let mut pos = 0;
            for &u in &us {
                prop_assert_eq!(read_varint(&out, &mut pos).unwrap(), u);
            }
            prop_assert_eq!(pos, out.len());
        }

        #[test]
        fn recordings_round_trip_through_the_stream_and_deflate(
            samples in 0usize..20,
            robots in 0usize..6,
            values in proptest::collection::vec(any::<i32>(), 1..40),
            changes in proptest::collection::vec((0u32..20, 0u32..1000, 0u8..7), 0..30),
        ) {
            let rec = recording(samples, robots, &values, &changes);
            let stream = encode_recording(&rec);
            let back = decode_recording(&decompress(&compress(&stream).unwrap()).unwrap(), samples, robots).unwrap();
            prop_assert_eq!(&back.channels, &rec.channels);
            prop_assert_eq!(&back.rescuee_changes, &rec.rescuee_changes);
        }
    }

    #[test]
    fn small_values_take_one_byte_and_bad_streams_are_refused() {
        let mut out = Vec::new();
        for v in [-64i64, 63, 0] {
            write_varint(zigzag(v), &mut out);
        }
        assert_eq!(out.len(), 3);
        let rec = recording(3, 2, &[5, -7, 1_000_000], &[(1, 4, 2)]);
        let stream = encode_recording(&rec);
        assert!(decode_recording(&stream[..stream.len() - 1], 3, 2).is_err());
        let mut longer = stream.clone();
        longer.push(0);
        assert!(decode_recording(&longer, 3, 2).is_err());
        assert!(read_varint(&[0xff; 11], &mut 0).is_err());
        assert!(decompress(b"not deflate at all").is_err());
    }
}
