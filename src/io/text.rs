//! Fast text output for the large ASCII files (OpenFOAM, SU2, Gmsh): numbers formatted into
//! byte buffers without `std::fmt`, and long lists formatted in parallel chunks that are
//! written in order.
//!
//! [`push_f64`] writes exactly what `format!("{x}")` writes (the shortest decimal that reads
//! back to the same f64, never an exponent), from the shortest digits of `zmij` (Schubfach),
//! about ten times faster than `Display`; [`push_int`] writes integers through `itoa`. So the
//! files are byte for byte what the writers produced through `Display`, only faster.
//! [`write_par`] formats item ranges on rayon's threads into one buffer per chunk and writes
//! the buffers in item order: the bytes do not depend on the thread count or the chunk size,
//! since every item is formatted on its own.

use rayon::prelude::*;
use std::io::Write;

/// Items per chunk of [`write_par`] (a chunk's buffer holds a few MB at most).
pub const CHUNK: usize = 1 << 15;

/// Chunks formatted before their buffers are written (bounds the memory held at once).
const BATCH: usize = 16;

/// Appends `x` as `Display` writes it: the shortest digits that read back to `x`, in
/// positional notation (`1`, `-0.001`, `100000000000000000000`, `NaN`, `inf`, `-0`).
pub fn push_f64(out: &mut Vec<u8>, x: f64) {
    if !x.is_finite() {
        out.extend_from_slice(if x.is_nan() {
            b"NaN"
        } else if x > 0.0 {
            b"inf"
        } else {
            b"-inf"
        });
        return;
    }
    let mut buf = zmij::Buffer::new();
    let s = buf.format_finite(x).as_bytes();
    // zmij's exponent is among the last five bytes ("e-324"); memchr would cost more
    if !s.iter().rev().take(5).any(|&c| c == b'e') && matches!(exact_digits(x), None | Some(0)) {
        // positional and no tie possible: zmij's text is std's, but for a trailing ".0"
        out.extend_from_slice(s.strip_suffix(b".0").unwrap_or(s));
        return;
    }
    // zmij writes `[-]digits[.digits][e[-]exp]`; read its digits and decimal exponent.
    let (neg, s) = match s.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, s),
    };
    let (mant, exp10) = match s.iter().position(|&c| c == b'e') {
        Some(k) => (&s[..k], parse_exp(&s[k + 1..])),
        None => (s, 0),
    };
    // digits without the point; `point`: digits before the point
    let mut digits = [0u8; 32];
    let mut nd = 0;
    let mut point = mant.len() as i32;
    for (k, &c) in mant.iter().enumerate() {
        if c == b'.' {
            point = k as i32;
        } else if nd < digits.len() {
            digits[nd] = c;
            nd += 1;
        }
    }
    // leading zeros move the point left, trailing zeros are dropped
    let lead = digits[..nd].iter().take_while(|&&c| c == b'0').count();
    let mut d = &digits[lead..nd];
    point -= lead as i32;
    while let Some((b'0', rest)) = d.split_last() {
        d = rest;
    }
    if d.len() >= 15 && exact_digits(x) == Some(d.len() + 1) {
        // x lies exactly halfway between two shortest candidates: zmij rounds such a tie to
        // even, std away from zero; std decides (rare: x needs few binary digits)
        use std::io::Write as _;
        let _ = write!(out, "{x}");
        return;
    }
    if neg {
        out.push(b'-');
    }
    if d.is_empty() {
        out.push(b'0');
        return;
    }
    // value = 0.d × 10^e
    let e = point + exp10;
    let n = d.len() as i32;
    if e <= 0 {
        out.extend_from_slice(b"0.");
        out.extend(std::iter::repeat_n(b'0', (-e) as usize));
        out.extend_from_slice(d);
    } else if e < n {
        out.extend_from_slice(&d[..e as usize]);
        out.push(b'.');
        out.extend_from_slice(&d[e as usize..]);
    } else {
        out.extend_from_slice(d);
        out.extend(std::iter::repeat_n(b'0', (e - n) as usize));
    }
}

/// The number of significant decimal digits of x's exact value if x is not an integer and
/// that number is at most 18 (a tie between two shortest candidates of n digits needs exactly
/// n + 1), else `None`. Integers give `Some(0)`: they never tie (one ending in 5 is odd, so
/// below 2^53, where its own digits are the shortest).
fn exact_digits(x: f64) -> Option<usize> {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    let (mut m, mut e) = if biased == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), biased - 1075)
    };
    if m == 0 {
        return None;
    }
    let tz = m.trailing_zeros();
    m >>= tz;
    e += tz as i32;
    if e >= 0 {
        return Some(0);
    }
    // x = m · 5^p / 10^p with m odd: m · 5^p has no trailing zeros
    let p = (-e) as u32;
    if p > 27 {
        return None; // 5^28 > 10^18: more than 18 digits
    }
    let v = u128::from(m) * 5u128.pow(p);
    Some(v.checked_ilog10().map_or(1, |l| l as usize + 1))
}

/// The exponent after zmij's `e` (an optional sign and decimal digits).
fn parse_exp(s: &[u8]) -> i32 {
    let (neg, s) = match s.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, s),
    };
    let v = s
        .iter()
        .fold(0i32, |v, &c| v * 10 + i32::from(c.wrapping_sub(b'0')));
    if neg {
        -v
    } else {
        v
    }
}

/// Appends an integer in decimal.
pub fn push_int<I: itoa::Integer>(out: &mut Vec<u8>, v: I) {
    out.extend_from_slice(itoa::Buffer::new().format(v).as_bytes());
}

/// Writes items `0..n`: `f(k, buf)` appends item k's text to `buf`. Chunks of [`CHUNK`]
/// items are formatted in parallel and written in order, so the bytes are those of a serial
/// loop, whatever the thread count.
///
/// # Errors
/// The writer's.
pub fn write_par(
    w: &mut dyn Write,
    n: usize,
    f: impl Fn(usize, &mut Vec<u8>) + Sync,
) -> std::io::Result<()> {
    write_ranges(w, n.div_ceil(CHUNK), |c, buf| {
        for k in c * CHUNK..((c + 1) * CHUNK).min(n) {
            f(k, buf);
        }
    })
}

/// Writes `nchunks` pieces of text, piece c appended by `f(c, buf)`: formatted in parallel
/// (16 at a time), written in order.
///
/// # Errors
/// The writer's.
pub fn write_ranges(
    w: &mut dyn Write,
    nchunks: usize,
    f: impl Fn(usize, &mut Vec<u8>) + Sync,
) -> std::io::Result<()> {
    let mut bufs: Vec<Vec<u8>> = vec![Vec::new(); BATCH.min(nchunks)];
    let mut start = 0;
    while start < nchunks {
        let m = BATCH.min(nchunks - start);
        bufs[..m].par_iter_mut().enumerate().for_each(|(k, b)| {
            b.clear();
            f(start + k, b);
        });
        for b in &bufs[..m] {
            w.write_all(b)?;
        }
        start += m;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shown(x: f64) -> String {
        let mut v = Vec::new();
        push_f64(&mut v, x);
        String::from_utf8(v).unwrap()
    }

    #[test]
    fn floats_as_display_writes_them() {
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            0.3,
            1.0 / 3.0,
            2.0 / 3.0,
            100.0,
            1e15,
            1e16,
            1e17,
            1e21,
            1e22,
            1e23,
            123456789012345680000.0,
            1e-5,
            1e-7,
            1.5e-300,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::EPSILON,
            5e-324,
            -5e-324,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            9007199254740993.0,
            f64::from_bits(0xc318_625d_b787_6155), // -1715888522909781.25: a tie at 17 digits
            4503599627370497.5,
            1e15 + 0.5,
            0.000123456,
            1234.5,
        ];
        for x in special {
            assert_eq!(shown(x), format!("{x}"), "{x:e}");
        }
        // every exponent range, random mantissas (a fixed linear congruential sequence)
        let mut s: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..400_000 {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let x = f64::from_bits(s);
            assert_eq!(shown(x), format!("{x}"), "bits {s:#x}");
            // grid-like values: moderate magnitudes with all digits
            let y = (s >> 11) as f64 / (1u64 << 53) as f64 * 10f64.powi((s % 9) as i32 - 4);
            assert_eq!(shown(y), format!("{y}"), "{y:e}");
            // few fractional bits: where ties between two shortest candidates happen
            let z =
                (s >> 11) as f64 / f64::from(1u32 << (s % 6)) * if s & 1 == 0 { 1.0 } else { -1.0 };
            assert_eq!(shown(z), format!("{z}"), "{z:e}");
        }
    }

    #[test]
    fn floats_read_back_bit_identically() {
        let mut s: u64 = 7;
        for _ in 0..100_000 {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let x = f64::from_bits(s);
            if x.is_finite() {
                assert_eq!(shown(x).parse::<f64>().unwrap().to_bits(), x.to_bits());
            }
        }
    }

    #[test]
    fn integers() {
        let mut v = Vec::new();
        push_int(&mut v, 0u32);
        v.push(b' ');
        push_int(&mut v, u32::MAX);
        v.push(b' ');
        push_int(&mut v, 1234567usize);
        assert_eq!(v, b"0 4294967295 1234567");
    }

    #[test]
    fn parallel_writes_are_in_order_at_any_thread_count() {
        let n = 3 * CHUNK + 17;
        let serial: Vec<u8> = (0..n).flat_map(|k| format!("{k}\n").into_bytes()).collect();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut out = Vec::new();
            pool.install(|| {
                write_par(&mut out, n, |k, b| {
                    push_int(b, k);
                    b.push(b'\n');
                })
            })
            .unwrap();
            assert_eq!(out, serial, "{threads} threads");
        }
    }
}
