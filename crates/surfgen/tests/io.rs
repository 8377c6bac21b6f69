//! Every format round-trips, and every malformed file gets an error that names it.

use ndarray::Array2;
use std::path::{Path, PathBuf};
use surfgen::io::{self, ReadOptions};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfError, Surface, SurfaceSpec, generate};

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("surfgen-io-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn sample(nx: usize, ny: usize) -> Surface {
    let grid = Grid::new(nx, ny, 1e-4, 0.5e-4).unwrap();
    let spec = SurfaceSpec {
        grid,
        psd: Psd::self_affine(0.8, 4e-5, 2.5e-5),
        normalization: Normalization::RmsHeight(1e-6),
        amplitudes: Amplitudes::Rayleigh,
        seed: 9,
    };
    Surface::new(generate(&spec).unwrap().heights, grid, true).unwrap()
}

fn bits_equal(a: &Array2<f64>, b: &Array2<f64>) -> bool {
    a.dim() == b.dim() && a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits())
}

#[test]
fn npy_with_sidecar_round_trips_exactly() {
    let s = sample(48, 40);
    let p = tmp("a.npy");
    io::write(&s, &p, None).unwrap();
    let back = io::read(&p, &ReadOptions::default()).unwrap();
    assert!(bits_equal(&s.heights, &back.heights));
    assert_eq!(back.grid, s.grid);
    assert!(back.periodic);
    // Without its sidecar a bare .npy needs the lateral size.
    std::fs::remove_file(io::sidecar_path(&p)).unwrap();
    let err = io::read(&p, &ReadOptions::default()).unwrap_err();
    assert!(err.to_string().contains("lateral size"), "{err}");
    let back = io::read(
        &p,
        &ReadOptions {
            length_x: Some(1e-4),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(back.grid.length_y, 1e-4 * 40.0 / 48.0);
}

#[test]
fn text_formats_round_trip_exactly() {
    let s = sample(33, 20);
    for name in ["b.txt", "b.xyz"] {
        let p = tmp(name);
        io::write(&s, &p, None).unwrap();
        let back = io::read(&p, &ReadOptions::default()).unwrap();
        assert!(bits_equal(&s.heights, &back.heights), "{name}");
        assert!(
            (back.grid.length_x / s.grid.length_x - 1.0).abs() < 1e-14,
            "{name}"
        );
        assert!(
            (back.grid.length_y / s.grid.length_y - 1.0).abs() < 1e-14,
            "{name}"
        );
    }
}

#[test]
fn gsf_round_trips_exactly_at_f32_precision() {
    let mut s = sample(17, 12);
    s.heights.mapv_inplace(|h| h as f32 as f64);
    let p = tmp("c.gsf");
    io::write(&s, &p, None).unwrap();
    let back = io::read(&p, &ReadOptions::default()).unwrap();
    assert!(bits_equal(&s.heights, &back.heights));
    assert_eq!(back.grid, s.grid);
}

#[test]
fn units_convert_file_lengths_to_metres() {
    // The contact-mechanics challenge writes lengths and heights in units of 0.1 mm.
    let p = tmp("challenge.xyz");
    let mut text = String::new();
    for j in 0..4 {
        for i in 0..4 {
            text += &format!(
                "{} {} {}\n",
                i as f64 * 0.25,
                j as f64 * 0.25,
                0.01 * (i + j) as f64
            );
        }
        text += "\n";
    }
    std::fs::write(&p, text).unwrap();
    let s = io::read(
        &p,
        &ReadOptions {
            unit: 1e-4,
            ..Default::default()
        },
    )
    .unwrap();
    assert!((s.grid.length_x - 1e-4).abs() < 1e-18);
    assert!((s.heights[(1, 2)] - 3e-6).abs() < 1e-18);
}

fn parse_error(name: &str, content: &[u8], options: ReadOptions) -> (Option<usize>, String) {
    let p = tmp(name);
    std::fs::write(&p, content).unwrap();
    match io::read(&p, &options) {
        Err(SurfError::Parse { path, line, message }) => {
            assert_eq!(path, p);
            (line, message)
        }
        Err(SurfError::NonFinite { row, col, value }) => (Some(row), format!("non-finite {value} at {col}")),
        other => panic!("{name}: expected an error, got {other:?}"),
    }
}

#[test]
fn malformed_files_are_refused_with_their_line() {
    let lx = ReadOptions {
        length_x: Some(1e-4),
        ..Default::default()
    };
    let (line, msg) = parse_error("ragged.txt", b"1 2 3\n4 5 6\n7 8\n", lx);
    assert_eq!(line, Some(3));
    assert!(msg.contains("ragged"), "{msg}");
    let (line, msg) = parse_error("inf.txt", b"1 2\ninf 4\n", lx);
    assert_eq!(line, Some(2));
    assert!(msg.contains("non-finite"), "{msg}");
    // NaN marks an unmeasured point (Gwyddion's export), refused unless filled.
    let (_, msg) = parse_error("nan.txt", b"1 2\nNaN 4\n", lx);
    assert!(msg.contains("1 of 4 points are not measured"), "{msg}");
    let (line, msg) = parse_error("word.txt", b"1 2\n3 abc\n", lx);
    assert_eq!(line, Some(2));
    assert!(msg.contains("'abc'"), "{msg}");
    let (_, msg) = parse_error("one.txt", b"1 2 3\n", lx);
    assert!(msg.contains("a line scan (a profile of 3 points"), "{msg}");
    let (_, msg) = parse_error("single.txt", b"1\n", lx);
    assert!(msg.contains("need at least 2 heights"), "{msg}");
    let (_, msg) = parse_error("nolength.txt", b"1 2\n3 4\n", ReadOptions::default());
    assert!(msg.contains("lateral size"), "{msg}");

    let (line, msg) = parse_error("pairs.xyz", b"0 0 1\n1 0 2\n\n0 1 3\n1 1\n", lx);
    assert_eq!(line, Some(5));
    assert!(msg.contains("expected 'x y h'"), "{msg}");
    let (line, msg) = parse_error("ragged.xyz", b"0 0 1\n1 0 2\n2 0 2\n\n0 1 3\n1 1 4\n\n", lx);
    assert_eq!(line, Some(7));
    assert!(msg.contains("ragged"), "{msg}");
    let (line, msg) = parse_error("ymix.xyz", b"0 0 1\n1 0 2\n\n0 1 3\n1 2 4\n", lx);
    assert_eq!(line, Some(5));
    assert!(msg.contains("changes within a row"), "{msg}");
    let (_, msg) = parse_error("uneven.xyz", b"0 0 1\n1 0 2\n3 0 3\n\n0 1 1\n1 1 2\n3 1 3\n", lx);
    assert!(msg.contains("the x spacing is not uniform: x = 0 to 1"), "{msg}");
    let (_, msg) = parse_error(
        "uneven-y.xyz",
        b"0 0 1\n1 0 2\n\n0 1 1\n1 1 2\n\n0 5 1\n1 5 2\n",
        lx,
    );
    assert!(msg.contains("the y spacing is not uniform"), "{msg}");
    let (line, msg) = parse_error("inf.xyz", b"0 0 1\n1 0 inf\n\n0 1 3\n1 1 4\n", lx);
    assert_eq!(line, Some(2));
    assert!(msg.contains("non-finite"), "{msg}");

    let (line, _) = parse_error("magic.gsf", b"Gwyddion Simple Field 2.0\nXRes = 2\n\0\0", lx);
    assert_eq!(line, Some(1));
    let (_, msg) = parse_error(
        "short.gsf",
        b"Gwyddion Simple Field 1.0\nXRes = 2\nYRes = 2\n\0\0\0\0\0\0\0\0",
        lx,
    );
    assert!(msg.contains("data bytes"), "{msg}");
    let (line, msg) = parse_error("res.gsf", b"Gwyddion Simple Field 1.0\nXRes = two\n\0\0\0", lx);
    assert_eq!(line, Some(2));
    assert!(msg.contains("XRes"), "{msg}");

    let (_, msg) = parse_error("bad.npy", b"not an npy file", lx);
    assert!(msg.contains(".npy"), "{msg}");
    let s = sample(8, 8);
    let p = tmp("mismatch.npy");
    io::write(&s, &p, None).unwrap();
    let side = io::sidecar_path(&p);
    let json = std::fs::read_to_string(&side)
        .unwrap()
        .replace("\"nx\": 8", "\"nx\": 9");
    std::fs::write(&side, json).unwrap();
    let err = io::read(&p, &lx).unwrap_err();
    assert!(err.to_string().contains("does not match"), "{err}");
}

#[test]
fn unknown_extensions_and_missing_files_are_named() {
    let err = io::read(Path::new("surface.bmp"), &ReadOptions::default()).unwrap_err();
    assert!(err.to_string().contains(".bmp"));
    let err = io::read(Path::new("/nonexistent/s.npy"), &ReadOptions::default()).unwrap_err();
    assert!(err.to_string().contains("/nonexistent/s.npy"), "{err}");
}

#[test]
fn an_npy_header_larger_than_its_file_is_refused_before_allocating() {
    // A valid 8 x 8 file whose header is edited to claim 100000 x 100000 values (80 GB).
    let s = sample(8, 8);
    let p = tmp("small.npy");
    io::write(&s, &p, None).unwrap();
    let bytes = std::fs::read(&p).unwrap();
    // The header text after the 10-byte preamble, its length kept: the added characters come
    // out of its space padding.
    let header = std::str::from_utf8(&bytes[10..128]).unwrap();
    let edited = header
        .replace("(8, 8)", "(100000, 100000)")
        .replacen("            ", "  ", 1);
    assert_eq!(edited.len(), header.len());
    let mut huge = bytes[..10].to_vec();
    huge.extend_from_slice(edited.as_bytes());
    huge.extend_from_slice(&bytes[128..]);
    let (_, message) = parse_error(
        "huge.npy",
        &huge,
        ReadOptions {
            length_x: Some(1e-4),
            ..Default::default()
        },
    );
    assert!(
        message.contains("100000, 100000") && message.contains("truncated"),
        "{message}"
    );
    // A file cut short is refused the same way.
    let (_, message) = parse_error(
        "cut.npy",
        &bytes[..bytes.len() - 8],
        ReadOptions {
            length_x: Some(1e-4),
            ..Default::default()
        },
    );
    assert!(message.contains("truncated"), "{message}");
}
