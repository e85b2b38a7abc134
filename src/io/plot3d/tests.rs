//! Round trips of every Plot3D flavour, autodetection, and malformed input.

use crate::io::plot3d::*;
use std::path::PathBuf;

/// Irregular coordinate values; with `extreme` also ±0, subnormals and huge/tiny magnitudes.
fn val(k: usize, seed: usize, extreme: bool) -> f64 {
    let t = (k * 31 + seed * 7) as f64 * 0.731_058_578_630_004_9 + 0.1;
    let v = (3.0 * t.sin()).exp() / 7.0 * if k % 3 == 1 { -1.0 } else { 1.0 };
    if !extreme {
        return v;
    }
    match k % 13 {
        2 => v * 1e-300,
        5 => v * 1e300,
        7 => -0.0,
        11 => 5e-324,
        _ => v,
    }
}

fn arr(n: usize, seed: usize, extreme: bool) -> Vec<f64> {
    (0..n).map(|k| val(k, seed, extreme)).collect()
}

fn planar(ni: usize, nj: usize, s: usize, e: bool) -> Block {
    let n = ni * nj;
    Block::Planar(Grid2::from_coords(ni, nj, [arr(n, s, e), arr(n, s + 1, e)]))
}

fn surface(ni: usize, nj: usize, s: usize, e: bool) -> Block {
    let n = ni * nj;
    Block::Surface(Grid2::from_coords(
        ni,
        nj,
        [arr(n, s, e), arr(n, s + 1, e), arr(n, s + 2, e)],
    ))
}

fn volume(ni: usize, nj: usize, nk: usize, s: usize, e: bool) -> Block {
    let n = ni * nj * nk;
    Block::Volume(Grid3::from_coords(
        ni,
        nj,
        nk,
        [arr(n, s, e), arr(n, s + 1, e), arr(n, s + 2, e)],
    ))
}

/// What a block reads back as: planar blocks in a 3D file become surfaces with z = 0.
fn as_read(b: &Block, two_d: bool) -> Block {
    match b {
        Block::Planar(g) if !two_d => {
            let z = vec![0.0; g.len()];
            Block::Surface(Grid2::from_coords(
                g.ni(),
                g.nj(),
                [g.coord(0).to_vec(), g.coord(1).to_vec(), z],
            ))
        }
        b => b.clone(),
    }
}

fn all_formats() -> Vec<Plot3dFormat> {
    let mut v = Vec::new();
    for encoding in [Encoding::Unformatted, Encoding::Formatted, Encoding::Stream] {
        for precision in [Precision::Single, Precision::Double] {
            for byte_order in [ByteOrder::Little, ByteOrder::Big] {
                for multi_block in [true, false] {
                    for two_d in [true, false] {
                        for iblank in [false, true] {
                            v.push(Plot3dFormat {
                                encoding,
                                precision,
                                byte_order,
                                multi_block,
                                two_d,
                                iblank,
                            });
                        }
                    }
                }
            }
        }
    }
    v
}

fn blocks_for(fmt: &Plot3dFormat, case: usize) -> Vec<Block> {
    let e = fmt.precision == Precision::Double;
    match (fmt.multi_block, fmt.two_d) {
        (true, true) => vec![planar(5, 3, 1, e), planar(2, 7, 2, e), planar(4, 4, 3, e)],
        (false, true) => vec![planar(6, 5, 4, e)],
        (true, false) => vec![
            planar(3, 4, 5, e),
            surface(5, 2, 6, e),
            volume(4, 3, 2, 7, e),
            volume(2, 2, 5, 8, e),
        ],
        (false, false) if case % 2 == 0 => vec![volume(3, 4, 5, 9, e)],
        (false, false) => vec![surface(7, 3, 10, e)],
    }
}

fn iblank_pattern(blocks: &[Block]) -> Vec<Vec<i32>> {
    blocks
        .iter()
        .enumerate()
        .map(|(b, blk)| {
            (0..blk.nnodes())
                .map(|p| ((p + b) % 4) as i32 - 1)
                .collect()
        })
        .collect()
}

#[test]
fn round_trip_every_flavour() {
    let dir = tempfile::tempdir().unwrap();
    for (case, fmt) in all_formats().into_iter().enumerate() {
        let blocks = blocks_for(&fmt, case);
        let ib = iblank_pattern(&blocks);
        let given = (fmt.iblank && case % 4 < 2).then_some(&ib[..]);
        let path = dir.path().join(format!("g{case}.x"));
        write_plot3d(&path, &blocks, &fmt, given).unwrap_or_else(|e| panic!("{fmt}: {e}"));
        let file = read_plot3d(&path).unwrap_or_else(|e| panic!("{fmt}: {e}"));

        let mut want_fmt = fmt;
        if fmt.encoding == Encoding::Formatted {
            want_fmt.precision = Precision::Double;
            want_fmt.byte_order = ByteOrder::Little;
        }
        assert_eq!(file.format, want_fmt, "autodetection of {fmt}");
        assert_eq!(file.blocks.len(), blocks.len(), "{fmt}");
        let want_ib = match given {
            Some(ib) => Some(ib.to_vec()),
            None if fmt.iblank => Some(blocks.iter().map(|b| vec![1; b.nnodes()]).collect()),
            None => None,
        };
        assert_eq!(file.iblank, want_ib, "{fmt}");
        for (b, (got, orig)) in file.blocks.iter().zip(&blocks).enumerate() {
            let want = as_read(orig, fmt.two_d);
            assert_eq!(got.dims(), want.dims(), "{fmt} block {b}");
            assert_eq!(got.kind(), want.kind(), "{fmt} block {b}");
            for c in 0..want.ncoords() {
                for (p, (&g, &w)) in got.coord(c).iter().zip(want.coord(c)).enumerate() {
                    let ok = match fmt.precision {
                        Precision::Double => g.to_bits() == w.to_bits(),
                        Precision::Single => g as f32 == w as f32,
                    };
                    assert!(
                        ok,
                        "{fmt}: block {b} coord {c} node {p}: read {g:e}, wrote {w:e}"
                    );
                }
            }
        }
    }
}

/// A Fortran-unformatted little-endian file from record payloads.
fn fortran(records: &[Vec<u8>]) -> Vec<u8> {
    let mut out = Vec::new();
    for r in records {
        out.extend((r.len() as i32).to_le_bytes());
        out.extend(r);
        out.extend((r.len() as i32).to_le_bytes());
    }
    out
}

fn le_ints(v: &[i32]) -> Vec<u8> {
    v.iter().flat_map(|n| n.to_le_bytes()).collect()
}

fn read_bytes(dir: &Path, name: &str, data: &[u8]) -> Result<Plot3dFile> {
    let path = dir.join(name);
    std::fs::write(&path, data).unwrap();
    read_plot3d(&path)
}

fn read_err(dir: &Path, data: &[u8]) -> String {
    match read_bytes(dir, "bad.x", data) {
        Ok(f) => panic!("accepted bad input as {}", f.format),
        Err(e) => e.to_string(),
    }
}

fn written(dir: &Path, fmt: &Plot3dFormat) -> Vec<u8> {
    let path = dir.join("ok.x");
    let blocks = [volume(2, 3, 2, 1, false), surface(3, 2, 2, false)];
    let n = if fmt.multi_block { 2 } else { 1 };
    write_plot3d(&path, &blocks[..n], fmt, None).unwrap();
    std::fs::read(&path).unwrap()
}

#[test]
fn truncated_files_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for multi_block in [true, false] {
        let fmt = Plot3dFormat {
            multi_block,
            ..Default::default()
        };
        let data = written(d, &fmt);
        for len in 0..data.len() {
            let e = read_err(d, &data[..len]);
            assert!(e.contains("bad.x"), "{e}");
        }
        let e = read_err(d, &data[..data.len() - 5]);
        assert!(e.contains("truncated") && e.contains("block"), "{e}");
    }
    // Stream and formatted files: no panic on any truncation, error when one byte/value is gone.
    for encoding in [Encoding::Stream, Encoding::Formatted] {
        let data = written(
            d,
            &Plot3dFormat {
                encoding,
                ..Default::default()
            },
        );
        for len in 0..data.len() {
            let _ = read_bytes(d, "t.x", &data[..len]);
        }
        let cut = if encoding == Encoding::Stream {
            data.len() - 1
        } else {
            data.len() - 26
        };
        read_err(d, &data[..cut]);
    }
}

#[test]
fn garbage_never_panics() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut s = 0x2545_f491_4f6c_dd1d_u64;
    let mut rnd = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    for len in (0..300).chain([1000, 4096]) {
        let data: Vec<u8> = (0..len).map(|_| rnd() as u8).collect();
        let r = read_bytes(d, "g.x", &data);
        if len >= 100 {
            assert!(r.is_err(), "random bytes accepted");
        }
    }
    // Byte flips of valid files of each encoding.
    for encoding in [Encoding::Unformatted, Encoding::Stream, Encoding::Formatted] {
        let data = written(
            d,
            &Plot3dFormat {
                encoding,
                iblank: true,
                ..Default::default()
            },
        );
        for _ in 0..400 {
            let mut v = data.clone();
            for _ in 0..1 + rnd() % 3 {
                let p = (rnd() % v.len() as u64) as usize;
                v[p] = rnd() as u8;
            }
            let _ = read_bytes(d, "f.x", &v);
        }
    }
    let e = read_err(d, b"hello world\n");
    assert!(e.contains("fits no Plot3D layout"), "{e}");
    // Fits single-block 2D with IBLANK by count only: the IBLANK value 'x' is reported.
    let e = read_err(d, b"1\n2 2 1\n1.0 2.0 x 4.0\n");
    assert!(e.contains("'x' is not an integer"), "{e}");
    let e = read_err(d, b"2 2 1\n1 2 3 4 5 6 7 8 9 10 11 zz\n");
    assert!(
        e.contains("block 1 of 1, z at node (i, j, k) = (1, 1, 0)") && e.contains("'zz'"),
        "{e}"
    );
    let e = read_err(d, b"1 1000000 1000000 1000000 1000000000000*0.0\n");
    assert!(e.contains("implausibly many"), "{e}");
}

#[test]
fn bad_headers_and_records() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let coords = |n: usize| vec![0u8; 24 * n];
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (
            fortran(&[le_ints(&[0]), le_ints(&[]), coords(1)]),
            "block count 0",
        ),
        (fortran(&[le_ints(&[1]), le_ints(&[0, 2, 2])]), "ni = 0"),
        (
            fortran(&[le_ints(&[1]), le_ints(&[2, -2, 2]), coords(8)]),
            "nj = -2",
        ),
        (
            fortran(&[le_ints(&[1]), le_ints(&[2, 2, 2, 2])]),
            "record 2 (block dimensions) holds 16 bytes",
        ),
        (
            fortran(&[le_ints(&[1]), le_ints(&[i32::MAX; 3]), coords(8)]),
            "block 1 of 1",
        ),
        (
            fortran(&[
                le_ints(&[2]),
                le_ints(&[2, 2, 2, 2, 2, 1]),
                coords(8),
                vec![0; 16 * 4],
            ]),
            "block 2 of 2",
        ),
        (
            fortran(&[le_ints(&[1]), le_ints(&[2, 2, 2]), coords(8), le_ints(&[1])]),
            "trailing",
        ),
        (
            fortran(&[le_ints(&[1]), le_ints(&[2, 2, 2]), coords(7)]),
            "expected one of",
        ),
    ];
    for (data, want) in cases {
        let e = read_err(d, &data);
        assert!(e.contains(want), "expected '{want}' in: {e}");
    }
    // Huge dimensions fail on the record length without allocating.
    let e = read_err(
        d,
        &fortran(&[le_ints(&[1]), le_ints(&[i32::MAX; 3]), coords(8)]),
    );
    assert!(
        e.contains("absurd dimensions") && e.contains("holds 192 bytes"),
        "{e}"
    );

    let good = written(d, &Plot3dFormat::default());
    let mut bad_marker = good.clone();
    let n = bad_marker.len();
    bad_marker[n - 4] ^= 1;
    let e = read_err(d, &bad_marker);
    assert!(
        e.contains("end marker") && e.contains("block 2 of 2"),
        "{e}"
    );
    let mut nan = good.clone();
    nan[48..56].copy_from_slice(&f64::NAN.to_le_bytes()); // x[0]: after [nb] (12), [dims] (32), marker
    let e = read_err(d, &nan);
    assert!(
        e.contains("block 1 of 2: coordinate x = NaN") && e.contains("not finite"),
        "{e}"
    );
    let mut trailing = good;
    trailing.extend(b"junk");
    assert!(read_err(d, &trailing).contains("trailing"));
}

#[test]
fn fortran_style_formatted_input() {
    let dir = tempfile::tempdir().unwrap();
    let text = "1\n 2, 2, 1\n 1.0D0, 2*0.5 1.0-1\n4*0.0\n 1.5E+00 2.5d-1 -3. .5\n";
    let f = read_bytes(dir.path(), "f.x", text.as_bytes()).unwrap();
    assert!(f.format.multi_block && !f.format.two_d && !f.format.iblank);
    assert_eq!(f.blocks[0].coord(0), &[1.0, 0.5, 0.5, 0.1]);
    assert_eq!(f.blocks[0].coord(2), &[1.5, 0.25, -3.0, 0.5]);
    // Single-block 2D with IBLANK.
    let f = read_bytes(dir.path(), "g.x", b"2 1\n0.1 0.2\n0.3 0.4\n1 0\n").unwrap();
    assert!(!f.format.multi_block && f.format.two_d && f.format.iblank);
    assert_eq!(f.iblank, Some(vec![vec![1, 0]]));
    assert!(matches!(f.blocks[0], Block::Planar(_)));
}

#[test]
fn writer_rejects_bad_requests() {
    let dir = tempfile::tempdir().unwrap();
    let path: PathBuf = dir.path().join("w.x");
    let two_d = Plot3dFormat {
        two_d: true,
        ..Default::default()
    };
    let single = Plot3dFormat {
        multi_block: false,
        ..Default::default()
    };
    let with_ib = Plot3dFormat {
        iblank: true,
        ..Default::default()
    };
    let sp = Plot3dFormat {
        precision: Precision::Single,
        ..Default::default()
    };
    let s = surface(3, 3, 1, false);
    let mut nan = volume(2, 2, 2, 1, false);
    if let Block::Volume(g) = &mut nan {
        g.coords_mut()[1][5] = f64::NAN;
    }
    type Case = (
        Vec<Block>,
        Plot3dFormat,
        Option<Vec<Vec<i32>>>,
        &'static str,
    );
    let cases: Vec<Case> = vec![
        (vec![s.clone()], two_d, None, "planar blocks"),
        (vec![s.clone(), s.clone()], single, None, "one block, got 2"),
        (
            vec![s.clone()],
            Plot3dFormat::default(),
            Some(vec![vec![1; 9]]),
            "no IBLANK",
        ),
        (
            vec![s.clone()],
            with_ib,
            Some(vec![vec![1; 8]]),
            "8 IBLANK values for 9 nodes",
        ),
        (
            vec![nan],
            Plot3dFormat::default(),
            None,
            "y = NaN at node (i, j, k) = (1, 0, 1)",
        ),
        (
            vec![planar(3, 2, 1, true)],
            sp,
            None,
            "overflows single precision",
        ),
        (vec![], Plot3dFormat::default(), None, "no blocks"),
    ];
    for (blocks, fmt, ib, want) in cases {
        let e = write_plot3d(&path, &blocks, &fmt, ib.as_deref())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(want) && e.contains("w.x"),
            "expected '{want}' in: {e}"
        );
        assert!(!path.exists());
    }
}
