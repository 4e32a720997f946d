//! Structure-aware mutations of mesh files. Each input is a seed with one to
//! four mutations stacked, every choice drawn from a [`SplitMix64`] seeded by
//! (format, seed, iteration), so an input is rebuilt exactly from those three
//! numbers. Mutations know what mesh files are made of: numbers (counts,
//! indices, coordinates, byte lengths), lines, tokens, quoted JSON strings,
//! 32-bit binary fields; and they aim at what readers get wrong: counts set
//! to 0, -1, huge or off by one, NaN and infinite coordinates, long lines,
//! invalid UTF-8, truncation, duplicated and missing lines.

use mesh_testkit::SplitMix64;

use super::rng::pick;

/// Largest mutated input, in bytes (long-line mutations are capped to it).
pub const MAX_SIZE: usize = 4 << 20;

/// The kinds of mutation, in the order of [`mutate_once`]'s table.
pub const KINDS: &[&str] = &[
    "bit flips",
    "byte insertion",
    "byte deletion",
    "truncation",
    "number replaced",
    "header number replaced",
    "face index replaced",
    "binary u32 field",
    "binary float field",
    "long line",
    "bad UTF-8",
    "line duplicated",
    "line removed",
    "lines swapped",
    "tokens swapped",
    "NaN or inf token",
    "JSON string replaced",
    "splice from another seed",
];

/// One mutated input: the seed's bytes with 1-4 mutations, and their names.
pub fn mutate(rng: &mut SplitMix64, seed: &[u8], other: &[u8]) -> (Vec<u8>, Vec<&'static str>) {
    let mut data = seed.to_vec();
    let mut applied = Vec::new();
    let count = 1 + usize::from(rng.one_in(2)) + usize::from(rng.one_in(4)) + usize::from(rng.one_in(8));
    for _ in 0..count {
        let kind = rng.below(KINDS.len());
        mutate_once(rng, kind, &mut data, other);
        applied.push(KINDS[kind]);
        data.truncate(MAX_SIZE);
    }
    (data, applied)
}

/// Integers that break counts and indices: zero, negatives, the edges of
/// 32- and 64-bit ranges, and values no file of this size can back.
const INTEGERS: &[&str] = &[
    "0",
    "-1",
    "1",
    "2",
    "3",
    "-2147483648",
    "2147483647",
    "2147483648",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "18446744073709551615",
    "18446744073709551616",
    "99999999999999999999999999",
    "1000000000",
    "65536",
    "255",
    "256",
];

/// Floats that break coordinates.
const FLOATS: &[&str] =
    &["nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e308", "1e309", "-1e400", "1e-320", "4.9e-324", "0.0", "-0"];

/// JSON strings that break glTF: paths out of the folder, devices, empty
/// and truncated data URIs, wrong enumerations.
const STRINGS: &[&str] = &[
    "\"\"",
    "\"/dev/zero\"",
    "\"/dev/urandom\"",
    "\"../../etc/passwd\"",
    "\"buffer.bin\"",
    "\"data:,\"",
    "\"data:application/octet-stream;base64,\"",
    "\"data:application/octet-stream;base64,AAAA\"",
    "\"data:application/octet-stream;base64,!!\"",
    "\"SCALAR\"",
    "\"VEC2\"",
    "\"MAT4\"",
    "\"POSITION\"",
    "\"_quality\"",
];

fn mutate_once(rng: &mut SplitMix64, kind: usize, data: &mut Vec<u8>, other: &[u8]) {
    let len = data.len();
    match kind {
        0 => {
            for _ in 0..1 + rng.below(8) {
                if len > 0 {
                    let i = rng.below(len);
                    data[i] ^= 1 << rng.below(8);
                }
            }
        }
        1 => {
            let at = rng.below(len + 1);
            let bytes: Vec<u8> = (0..1 + rng.below(16))
                .map(|_| if rng.one_in(2) { *pick(rng, b"\0\xff\n\r \t-+.e9/#") } else { rng.next_u64() as u8 })
                .collect();
            data.splice(at..at, bytes);
        }
        2 => {
            if len > 0 {
                let at = rng.below(len);
                let end = (at + 1 + rng.below(64)).min(len);
                data.drain(at..end);
            }
        }
        3 => data.truncate(rng.below(len + 1)),
        4..=6 => {
            let spans = number_spans(data);
            let chosen = match kind {
                // Counts live in the first numbers of every header.
                5 => spans.iter().take(16).copied().collect::<Vec<_>>(),
                // Faces come last in OBJ, OFF and PLY.
                6 => spans[spans.len() / 2..].to_vec(),
                _ => spans,
            };
            if !chosen.is_empty() {
                let (start, end) = *pick(rng, &chosen);
                let replacement = number_replacement(rng, &data[start..end]);
                data.splice(start..end, replacement.into_bytes());
            }
        }
        7 | 8 => binary_field(rng, data, kind == 8),
        9 => {
            let at = line_start(rng, data);
            let n = [100, 4096, 70_000, 1 << 20][rng.below(4)];
            const UNITS: [&[u8]; 7] = [b"1 ", b"9", b" ", b"1/1/1 ", b"-", b"\t", b"0.5e-3 "];
            let unit = *pick(rng, &UNITS);
            let mut line: Vec<u8> = unit.iter().copied().cycle().take(n).collect();
            line.push(b'\n');
            data.splice(at..at, line);
        }
        10 => {
            const BAD: [&[u8]; 6] =
                [b"\xff", b"\xc3", b"\xed\xa0\x80", b"\xf8\x88\x80\x80\x80", b"\xe2\x82", b"\xc0\xaf"];
            let bad = *pick(rng, &BAD);
            let at = rng.below(len + 1);
            if rng.one_in(2) && at < len {
                data.splice(at..at + 1, bad.iter().copied());
            } else {
                data.splice(at..at, bad.iter().copied());
            }
        }
        11..=13 => lines(rng, kind, data),
        14 => swap_tokens(rng, data),
        15 => {
            let spans = number_spans(data);
            if !spans.is_empty() {
                let (start, end) = *pick(rng, &spans);
                data.splice(start..end, pick(rng, FLOATS).bytes());
            }
        }
        16 => {
            let spans = string_spans(data);
            if !spans.is_empty() {
                let (start, end) = *pick(rng, &spans);
                data.splice(start..end, pick(rng, STRINGS).bytes());
            }
        }
        _ => {
            if !other.is_empty() {
                let from = rng.below(other.len());
                let chunk = &other[from..(from + 1 + rng.below(256)).min(other.len())];
                let at = rng.below(len + 1);
                let end = if rng.one_in(2) { (at + chunk.len()).min(len) } else { at };
                data.splice(at..end, chunk.iter().copied());
            }
        }
    }
}

/// A replacement for a number token: an extreme integer, an off-by-one
/// neighbour of the value, or a non-finite / extreme float.
fn number_replacement(rng: &mut SplitMix64, old: &[u8]) -> String {
    let text = String::from_utf8_lossy(old);
    match rng.below(4) {
        0 | 1 => (*pick(rng, INTEGERS)).to_owned(),
        2 => match text.parse::<i64>() {
            Ok(v) => v.saturating_add(if rng.one_in(2) { 1 } else { -1 }).to_string(),
            Err(_) => (*pick(rng, FLOATS)).to_owned(),
        },
        _ => (*pick(rng, FLOATS)).to_owned(),
    }
}

/// A 32-bit field overwritten at a random (often 4-aligned, often early)
/// offset: an extreme count in either byte order, or a NaN / infinite float.
fn binary_field(rng: &mut SplitMix64, data: &mut [u8], float: bool) {
    if data.len() < 4 {
        return;
    }
    let limit = if rng.one_in(2) { data.len().min(128) } else { data.len() };
    let mut at = rng.below(limit - 3);
    if rng.one_in(2) {
        at &= !3;
    }
    let len = data.len() as u32;
    let old = u32::from_le_bytes([data[at], data[at + 1], data[at + 2], data[at + 3]]);
    let value: u32 = if float {
        *pick(rng, &[f32::NAN.to_bits(), f32::INFINITY.to_bits(), f32::NEG_INFINITY.to_bits(), f32::MAX.to_bits(), 1])
    } else {
        *pick(
            rng,
            &[
                0,
                1,
                u32::MAX,
                i32::MAX as u32,
                1 << 31,
                len,
                len.wrapping_add(1),
                old.wrapping_add(1),
                old.wrapping_sub(1),
                1 << 24,
            ],
        )
    };
    let bytes = if rng.one_in(2) { value.to_le_bytes() } else { value.to_be_bytes() };
    data[at..at + 4].copy_from_slice(&bytes);
}

/// Byte ranges of ASCII number tokens (digits with sign, point, exponent).
pub fn number_spans(data: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < data.len() {
        let starts = data[i].is_ascii_digit()
            || (matches!(data[i], b'-' | b'+' | b'.') && data.get(i + 1).is_some_and(u8::is_ascii_digit));
        let boundary = i == 0 || !(data[i - 1].is_ascii_alphanumeric() || data[i - 1] == b'_');
        if starts && boundary {
            let start = i;
            i += 1;
            while i < data.len() && (data[i].is_ascii_digit() || matches!(data[i], b'.' | b'e' | b'E' | b'-' | b'+')) {
                i += 1;
            }
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

/// Byte ranges of double-quoted strings (JSON), quotes included.
fn string_spans(data: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut open = None;
    for (i, b) in data.iter().enumerate() {
        if *b == b'"' && (i == 0 || data[i - 1] != b'\\') {
            match open.take() {
                Some(start) => spans.push((start, i + 1)),
                None => open = Some(i),
            }
        }
    }
    spans
}

/// Start offsets of every line.
fn line_starts(data: &[u8]) -> Vec<usize> {
    std::iter::once(0).chain(data.iter().enumerate().filter(|(_, b)| **b == b'\n').map(|(i, _)| i + 1)).collect()
}

fn line_start(rng: &mut SplitMix64, data: &[u8]) -> usize {
    *pick(rng, &line_starts(data))
}

/// The line containing `start`, as a byte range with its newline.
fn line_at(data: &[u8], start: usize) -> (usize, usize) {
    let end = data[start..].iter().position(|b| *b == b'\n').map_or(data.len(), |p| start + p + 1);
    (start, end)
}

/// Duplicates (up to 100 times), removes or swaps whole lines.
fn lines(rng: &mut SplitMix64, kind: usize, data: &mut Vec<u8>) {
    let starts = line_starts(data);
    let (a, b) = line_at(data, *pick(rng, &starts));
    match kind {
        11 => {
            let line = data[a..b].to_vec();
            let copies = if rng.one_in(4) { 1 + rng.below(100) } else { 1 };
            let at = if rng.one_in(2) { b } else { *pick(rng, &starts) };
            let repeated: Vec<u8> = line.iter().copied().cycle().take(line.len() * copies).collect();
            data.splice(at..at, repeated);
        }
        12 => {
            data.drain(a..b);
        }
        _ => {
            let (c, d) = line_at(data, *pick(rng, &starts));
            if d <= a || b <= c {
                let ((a, b), (c, d)) = if b <= c { ((a, b), (c, d)) } else { ((c, d), (a, b)) };
                let mut out = data[..a].to_vec();
                out.extend_from_slice(&data[c..d]);
                out.extend_from_slice(&data[b..c]);
                out.extend_from_slice(&data[a..b]);
                out.extend_from_slice(&data[d..]);
                *data = out;
            }
        }
    }
}

/// Swaps two whitespace-separated tokens of one line.
fn swap_tokens(rng: &mut SplitMix64, data: &mut Vec<u8>) {
    let starts = line_starts(data);
    let (a, b) = line_at(data, *pick(rng, &starts));
    let line = &data[a..b];
    let mut tokens: Vec<(usize, usize)> = Vec::new();
    let mut i = 0;
    while i < line.len() {
        if line[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let s = i;
        while i < line.len() && !line[i].is_ascii_whitespace() {
            i += 1;
        }
        tokens.push((s, i));
    }
    if tokens.len() < 2 {
        return;
    }
    let x = rng.below(tokens.len());
    let y = rng.below(tokens.len());
    let (x, y) = (tokens[x.min(y)], tokens[x.max(y)]);
    if x == y {
        return;
    }
    let mut out = line[..x.0].to_vec();
    out.extend_from_slice(&line[y.0..y.1]);
    out.extend_from_slice(&line[x.1..y.0]);
    out.extend_from_slice(&line[x.0..x.1]);
    out.extend_from_slice(&line[y.1..]);
    data.splice(a..b, out);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_numbers_and_strings() {
        let text = b"element vertex 12\nv -1.5e3 x2 .5\n{\"uri\":\"a\"}";
        let spans: Vec<&[u8]> = number_spans(text).into_iter().map(|(a, b)| &text[a..b]).collect();
        assert_eq!(spans, [&b"12"[..], b"-1.5e3", b".5"]);
        assert_eq!(string_spans(text), [(34, 39), (40, 43)]);
    }

    #[test]
    fn reproducible() {
        let seed = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        for i in 0..200 {
            let a = mutate(&mut super::super::rng::for_input(0, 0, i), seed, seed);
            let b = mutate(&mut super::super::rng::for_input(0, 0, i), seed, seed);
            assert_eq!(a, b);
            assert!(a.0.len() <= MAX_SIZE);
        }
    }
}
