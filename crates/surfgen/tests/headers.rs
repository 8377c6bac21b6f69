//! Every number a reader takes from a file's header, set to any value (NaN, infinities, zero,
//! negative, huge, tiny): the file reads as a surface with finite heights that are not all one
//! value on a finite box, or is refused with an error naming that header field. On top of the
//! byte fuzzing of `fuzz.rs`, which rarely hits a header number exactly.

// The builders of the other formats serve the other test files.
#[allow(dead_code)]
mod common;

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use surfgen::ReadOptions;
use surfgen::io;

/// Any f64 a header could hold, the awkward ones often.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(1e300),
        Just(1e-300),
        -1e3..1e3f64,
        any::<f64>(),
    ]
}

fn file(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("surfgen-headers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// The outcome's rule: a surface that is a surface, or an error that names `field`.
fn judged(path: &Path, field: &str, value: f64) -> Result<(), TestCaseError> {
    match io::read(path, &ReadOptions::default()) {
        Ok(s) => {
            prop_assert!(
                s.heights.iter().all(|h| h.is_finite()),
                "{field} = {value:?}: non-finite heights read"
            );
            let first = s.heights[[0, 0]];
            prop_assert!(
                s.heights.iter().any(|&h| h != first),
                "{field} = {value:?}: read as a flat surface without a word"
            );
            prop_assert!(s.grid.length_x.is_finite() && s.grid.length_x > 0.0);
            prop_assert!(s.grid.length_y.is_finite() && s.grid.length_y > 0.0);
        }
        Err(e) => {
            let message = e.to_string();
            prop_assert!(
                message.contains(field),
                "{field} = {value:?}: the error does not name the field: {message}"
            );
        }
    }
    Ok(())
}

/// A Digital Surf surface by hand (3 x 2 points of 16 bits) with `f32` header numbers at
/// `(offset, value)`.
fn sur(numbers: &[(usize, f32)]) -> Vec<u8> {
    let mut b = vec![0u8; 512];
    b[..12].copy_from_slice(b"DIGITAL SURF");
    for (o, v) in [(18, 2i16), (98, 16)] {
        b[o..o + 2].copy_from_slice(&v.to_le_bytes());
    }
    for (o, v) in [(108, 3i32), (112, 2)] {
        b[o..o + 4].copy_from_slice(&v.to_le_bytes());
    }
    for (o, v) in [(120, 0.5f32), (124, 0.5), (128, 0.01)].iter().chain(numbers) {
        b[*o..o + 4].copy_from_slice(&v.to_le_bytes());
    }
    for o in [180, 196, 212] {
        b[o..o + 2].copy_from_slice(b"um");
    }
    for v in [1i16, 2, 3, 4, 5, 6] {
        b.extend(v.to_le_bytes());
    }
    b
}

/// A TrueMap file by hand: 3 x 2 heights on a box of `lx` x `ly` mm.
fn tmd(lx: f32, ly: f32) -> Vec<u8> {
    let mut b = b"Binary TrueMap Data File v2.0\r\n\0a comment\r\n\0".to_vec();
    for v in [3u32, 2] {
        b.extend(v.to_le_bytes());
    }
    for v in [lx, ly, 0.0, 0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6] {
        b.extend(v.to_le_bytes());
    }
    b
}

/// `seed` with the value of the header line that starts with `key` (after its separator, `=`
/// or spaces) replaced by `v`.
fn with_value(seed: &[u8], key: &str, v: f64) -> Vec<u8> {
    let at = seed
        .windows(key.len() + 1)
        .position(|w| w.starts_with(key.as_bytes()) && (w[key.len()] == b'=' || w[key.len()] == b' '))
        .expect("the key is in the seed");
    let start = at
        + key.len()
        + seed[at + key.len()..]
            .iter()
            .position(|&b| b != b'=' && b != b' ')
            .unwrap();
    let end = start
        + seed[start..]
            .iter()
            .position(|&b| b == b'\n' || b == b'\r')
            .unwrap();
    [&seed[..start], format!("{v:?}").as_bytes(), &seed[end..]].concat()
}

/// The PicoView and Nanosurf files of `fuzz.rs`: 3 x 2 heights of 16 bits after a text header.
fn mi() -> Vec<u8> {
    let mut b =
        b"fileType      Image\nxPixels       3\nyPixels       2\nxLength       1e-6\nyLength       1e-6\n\
bufferLabel   Topography\nbufferRange   1.5\nbufferUnit    um\ndata          BINARY\n"
            .to_vec();
    b.extend(
        [1i16, -2, 300, 4000, -5000, 6]
            .iter()
            .flat_map(|v| v.to_le_bytes()),
    );
    b
}

fn nid() -> Vec<u8> {
    let mut b = b"[DataSet]\nGroupCount=1\nGr0-Count=1\nGr0-Ch0=DataSet-0:1\n\
[DataSet-0:1]\nPoints=3\nLines=2\nDim0Range=1e-6\nDim0Unit=m\nDim1Range=1e-6\nDim1Unit=m\n\
Dim2Min=-1e-7\nDim2Range=2e-7\nDim2Unit=m\nSaveBits=16\nSaveSign=Signed\n#!"
        .to_vec();
    b.extend(
        [10i16, -20, 300, 4000, -5000, 6]
            .iter()
            .flat_map(|v| v.to_le_bytes()),
    );
    b
}

/// A text SDF file as our writer makes it, 4 x 3 points.
fn sdf() -> Vec<u8> {
    let grid = surfgen::Grid::new(4, 3, 4e-6, 3e-6).unwrap();
    let heights = ndarray::Array2::from_shape_fn((3, 4), |(j, i)| 1e-7 * (i + 2 * j) as f64);
    let path = file("seed.sdf", b"");
    io::write(&surfgen::Surface::new(heights, grid, false).unwrap(), &path, None).unwrap();
    std::fs::read(&path).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn digital_surf_header_numbers(field in 0..4usize, v in number()) {
        let (offset, name) = [(120, "x spacing"), (124, "y spacing"), (128, "height step dz"), (474, "height offset")][field];
        let path = file("h.sur", &sur(&[(offset, v as f32)]));
        judged(&path, name, v)?;
    }

    #[test]
    fn truemap_header_numbers(field in 0..2usize, v in number()) {
        let (lx, ly) = if field == 0 { (v as f32, 1.0) } else { (1.5, v as f32) };
        let path = file("h.tmd", &tmd(lx, ly));
        judged(&path, ["x length", "y length"][field], v)?;
    }

    #[test]
    fn text_header_numbers(format in 0..3usize, field in 0..3usize, v in number()) {
        let (name, seed, keys): (&str, Vec<u8>, [&str; 3]) = match format {
            0 => ("h.mi", mi(), ["xLength", "yLength", "bufferRange"]),
            1 => ("h.nid", nid(), ["Dim0Range", "Dim2Min", "Dim2Range"]),
            _ => ("h.sdf", sdf(), ["Xscale", "Yscale", "Zscale"]),
        };
        let path = file(name, &with_value(&seed, keys[field], v));
        judged(&path, keys[field], v)?;
    }

    #[test]
    fn nanoscope_header_numbers(field in 0..4usize, v in number(), length in 0..40usize) {
        let seed = String::from_utf8_lossy(&common::tiny_di([1, 2, 3, 4, 5, 6])).into_owned();
        // The height image is the second: its fields are the last of each name.
        let replace_last = |text: &str, from: &str, to: &str| {
            let i = text.rfind(from).expect("in the seed");
            format!("{}{to}{}", &text[..i], &text[i + from.len()..])
        };
        let (text, name) = match field {
            0 => (replace_last(&seed, "(0.0001 V/LSB) 6.5536 V", &format!("(0.0001 V/LSB) {v:?} V")), "Z scale"),
            1 => (replace_last(&seed, "Scan Size: 3 2", &format!("Scan Size: {v:?} 2")), "Scan Size"),
            2 => (replace_last(&seed, "Scan Size: 3 2", &format!("Scan Size: 3 {v:?}")), "Scan Size"),
            _ => (replace_last(&seed, "Data length: 12", &format!("Data length: {length}")), "Data length"),
        };
        // The header keeps its length, so that the images' offsets stay where they were.
        let mut bytes: Vec<u8> = text.chars().map(|c| c as u8).collect();
        let end = bytes.windows(14).position(|w| w == b"File list end\r").unwrap() + 15;
        let pad = seed.find("File list end\r").unwrap() + 15;
        if end > pad {
            return Ok(());
        }
        bytes.splice(end..end, std::iter::repeat_n(0u8, pad - end));
        let path = file("h.di", &bytes);
        judged(&path, name, v)?;
    }
}

/// The header faults met on real files, each refused naming its field.
#[test]
fn bad_headers_are_refused_naming_the_field() {
    let seed = String::from_utf8_lossy(&common::tiny_di([1, 2, 3, 4, 5, 6])).into_owned();
    // `from` replaced in the last image (the heights) or the first (phase, before them).
    let di_in = |last: bool, from: &str, to: &str| -> Vec<u8> {
        let i = if last { seed.rfind(from) } else { seed.find(from) }.expect("in the seed");
        let text = format!("{}{to}{}", &seed[..i], &seed[i + from.len()..]);
        let mut bytes: Vec<u8> = text.chars().map(|c| c as u8).collect();
        // Keep the header's length, so that the images stay where their offsets say.
        let end = bytes.windows(14).position(|w| w == b"File list end\r").unwrap() + 15;
        let pad = seed.find("File list end\r").unwrap() + 15;
        bytes.splice(end..end, std::iter::repeat_n(0u8, pad.saturating_sub(end)));
        bytes
    };
    let di = |from: &str, to: &str| di_in(true, from, to);
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "nan-z.di",
            di("6.5536 V", "NaN V"),
            "image 1's \\@2:Z scale (with its \\@Sens.) is NaN",
        ),
        (
            "zero-z.di",
            di("6.5536 V", "0 V"),
            "image 1's \\@2:Z scale (with its \\@Sens.) is 0.0",
        ),
        // The phase image, 4 pixels a line, would run into the heights after it.
        (
            "long.di",
            di_in(false, "Samps/line: 3", "Samps/line: 4"),
            "image 0 (Phase): \\Data length is 12 bytes, but \\Samps/line 4",
        ),
        (
            "nan-dz.sur",
            sur(&[(128, f32::NAN)]),
            "the header's height step dz is NaN",
        ),
        (
            "zero-dz.sur",
            sur(&[(128, 0.0)]),
            "the header's height step dz is 0.0",
        ),
        ("zero-dx.sur", sur(&[(120, 0.0)]), "the header's x spacing is 0.0"),
        ("nan.tmd", tmd(f32::NAN, 1.0), "the header's x length is NaN"),
    ];
    for (name, bytes, fragment) in cases {
        let e = io::read(&file(name, &bytes), &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains(fragment), "{name}: `{fragment}` not in: {e}");
    }
    // An X3P whose data no longer matches the checksum main.xml records.
    let grid = surfgen::Grid::new(4, 3, 4e-6, 3e-6).unwrap();
    let heights = ndarray::Array2::from_shape_fn((3, 4), |(j, i)| 1e-7 * (i + 2 * j) as f64);
    let path = file("good.x3p", b"");
    io::write(&surfgen::Surface::new(heights, grid, false).unwrap(), &path, None).unwrap();
    let mut archive = zip::ZipArchive::new(std::fs::File::open(&path).unwrap()).unwrap();
    let mut entries = Vec::new();
    for k in 0..archive.len() {
        let mut entry = archive.by_index(k).unwrap();
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut entry, &mut bytes).unwrap();
        let name = entry.name().unwrap().to_string();
        if name == "bindata/data.bin" {
            bytes[3] ^= 0x40;
        }
        entries.push((name, bytes));
    }
    let damaged = file("damaged.x3p", b"");
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&damaged).unwrap());
    for (name, bytes) in &entries {
        zip.start_file(name.as_str(), zip::write::SimpleFileOptions::default())
            .unwrap();
        std::io::Write::write_all(&mut zip, bytes).unwrap();
    }
    zip.finish().unwrap();
    assert!(io::read(&path, &ReadOptions::default()).is_ok());
    let e = io::read(&damaged, &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("does not match main.xml's MD5ChecksumPointData"),
        "{e}"
    );
}
