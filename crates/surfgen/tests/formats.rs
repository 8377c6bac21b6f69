//! The instrument formats (X3P, SDF, NetCDF-3, Gwyddion's text export) on real files against what an independent reader
//! (SurfaceTopography 1.27) gets from them, round trips, and bad files refused clearly.

use ndarray::Array2;
use serde_json::Value;
use std::io::Write;

mod common;
use common::{tiny_di, tiny_frt, tiny_gwy, tiny_ibw, tiny_mnt, tiny_opd};
use std::path::{Path, PathBuf};
use surfgen::io::{self, ReadOptions};
use surfgen::{Grid, Surface};

fn samples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/topography-samples")
}

fn unit(name: &str) -> f64 {
    match name {
        "m" => 1.0,
        "mm" => 1e-3,
        "µm" => 1e-6,
        "nm" => 1e-9,
        other => panic!("unit {other}"),
    }
}

#[test]
fn sample_files_read_as_surfacetopography_reads_them() {
    let readings: Value =
        serde_json::from_str(&std::fs::read_to_string(samples().join("readings.json")).unwrap()).unwrap();
    for name in [
        "x3p-2.x3p",
        "sdf-1.sdf",
        "nc-1.nc",
        "matrix-3.txt",
        "tmd-1.tmd",
        "mi-1.mi",
        "nid-1.nid",
        "di-1.di",
        "di-3.di",
        "sur-2.sur",
        "opd-1.opd",
        "spot_1-1000nm.ibw",
        "frt-1.frt",
        "mnt-1.mnt",
    ] {
        let r = &readings[name];
        // SurfaceTopography's statistics skip the points it masks as unmeasured.
        let s = io::read_measurement(&samples().join(name), &ReadOptions::default()).unwrap();
        let measured: Vec<f64> = s.heights.iter().copied().filter(|h| !h.is_nan()).collect();
        let u = unit(r["unit"].as_str().unwrap());
        let (nx, ny) = (
            r["nb_grid_pts"][0].as_u64().unwrap() as usize,
            r["nb_grid_pts"][1].as_u64().unwrap() as usize,
        );
        assert_eq!((s.grid.nx, s.grid.ny), (nx, ny), "{name}");
        // A measurement is not periodic, whatever the options assume for bare files.
        let ours = ["matrix-3.txt", "sdf-1.sdf", "x3p-2.x3p"].contains(&name); // nc-1 says it is not
        assert_eq!(s.periodic, ours, "{name}");
        let close = |ours: f64, theirs: f64, what: &str| {
            let scale = theirs.abs().max(r["rms_height"].as_f64().unwrap() * u);
            assert!(
                (ours - theirs).abs() <= 1e-6 * scale,
                "{name}: {what} {ours:e} against {theirs:e}"
            );
        };
        close(
            s.grid.length_x,
            r["physical_sizes"][0].as_f64().unwrap() * u,
            "length x",
        );
        close(
            s.grid.length_y,
            r["physical_sizes"][1].as_f64().unwrap() * u,
            "length y",
        );
        let n = measured.len() as f64;
        let mean = measured.iter().sum::<f64>() / n;
        let rms = (measured.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / n).sqrt();
        close(mean, r["mean"].as_f64().unwrap() * u, "mean height");
        close(rms, r["rms_height"].as_f64().unwrap() * u, "RMS height");
        let (min, max) = measured
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &h| (a.min(h), b.max(h)));
        close(min, r["min"].as_f64().unwrap() * u, "min");
        close(max, r["max"].as_f64().unwrap() * u, "max");
        println!(
            "{name}: {nx} x {ny}, {:e} x {:e} m, Rq {rms:e} m, {} unmeasured: as SurfaceTopography",
            s.grid.length_x,
            s.grid.length_y,
            s.unmeasured()
        );
    }
}

fn surface() -> Surface {
    // Not square, not periodic-looking, heights spanning decades: orientation and digits show.
    let grid = Grid::new(7, 4, 3.5e-6, 1.2e-6).unwrap();
    let h = Array2::from_shape_fn((4, 7), |(j, i)| {
        1e-7 * (i as f64 + 0.1 * j as f64).sin() + 1e-12 * (i * j) as f64
    });
    Surface::new(h, grid, false).unwrap()
}

#[test]
fn x3p_sdf_and_netcdf_read_back_what_was_written() {
    let dir = std::env::temp_dir().join(format!("surfgen-formats-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let s = surface();
    for ext in ["x3p", "sdf", "nc"] {
        let path = dir.join(format!("surface.{ext}"));
        io::write(&s, &path, None).unwrap();
        let back = io::read(&path, &ReadOptions::default()).unwrap();
        assert_eq!(back.heights, s.heights, ".{ext}: heights");
        assert_eq!((back.grid.nx, back.grid.ny), (7, 4), ".{ext}");
        for (a, b) in [(back.grid.length_x, 3.5e-6), (back.grid.length_y, 1.2e-6)] {
            assert!((a / b - 1.0).abs() < 1e-15, ".{ext}: size {a:e} against {b:e}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A zip archive of the named entries (deflated).
fn zip_of(path: &Path, entries: &[(&str, &[u8])]) {
    let mut zip = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in entries {
        zip.start_file(*name, options).unwrap();
        zip.write_all(bytes).unwrap();
    }
    zip.finish().unwrap();
}

fn main_xml(nx: usize, ny: usize) -> String {
    format!(
        "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1><FeatureType>SUR</FeatureType><Axes>\
         <CX><AxisType>I</AxisType><Increment>1e-6</Increment></CX><CY><AxisType>I</AxisType><Increment>1e-6</Increment></CY>\
         <CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1><Record3><MatrixDimension>\
         <SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataLink>\
         <PointDataLink>bindata/data.bin</PointDataLink></DataLink></Record3></p:ISO5436_2>"
    )
}

#[test]
fn bad_files_are_refused_with_a_reason() {
    let dir = std::env::temp_dir().join(format!("surfgen-bad-formats-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let refused = |name: &str, bytes: Option<&[u8]>, reason: &str| {
        let path = dir.join(name);
        if let Some(b) = bytes {
            std::fs::write(&path, b).unwrap();
        }
        let e = io::read(&path, &ReadOptions::default()).unwrap_err().to_string();
        assert!(e.contains(reason), "{name}: {e}");
    };
    // Wrong magic, truncated, a header claiming more data than the file holds.
    refused("magic.x3p", Some(b"PK not really a zip"), "not an X3P file");
    refused("magic.sdf", Some(b"ISO-1.0\n*\n"), "aISO-1.0 or bISO-1.0");
    refused("magic.nc", Some(b"CDX\x01junk"), "not a NetCDF-3 file");
    refused(
        "document.mnt",
        Some(b"\xd0\xcf\x11\xe0"),
        "not a MountainsMap document",
    );
    let sample = std::fs::read(samples().join("x3p-2.x3p")).unwrap();
    refused("cut.x3p", Some(&sample[..sample.len() / 2]), "");
    let sdf = std::fs::read_to_string(samples().join("sdf-1.sdf")).unwrap();
    refused(
        "more.sdf",
        Some(sdf.replace("NumProfiles = 4", "NumProfiles = 5").as_bytes()),
        "declared",
    );
    refused(
        "huge.sdf",
        Some(sdf.replace("NumPoints = 7", "NumPoints = 99999999").as_bytes()),
        "cannot fit",
    );
    let binary = b"bISO-1.0\nNumPoints = 4\nNumProfiles = 4\nXscale = 1\nYscale = 1\nZscale = 1\nDataType = 7\n*\n\0\0";
    refused("short.sdf", Some(binary), "need 128 data bytes, found 2");
    let nc = std::fs::read(samples().join("nc-1.nc")).unwrap();
    refused("cut.nc", Some(&nc[..nc.len() - 100]), "");
    // An X3P whose main.xml claims more points than its data holds, and a zip bomb: data that
    // inflates far beyond what main.xml declares.
    let small = vec![0u8; 10 * 10 * 8];
    zip_of(
        &dir.join("claims.x3p"),
        &[
            ("main.xml", main_xml(1000, 1000).as_bytes()),
            ("bindata/data.bin", &small),
        ],
    );
    refused("claims.x3p", None, "need 8000000 bytes");
    let bomb = vec![0u8; 64 << 20];
    zip_of(
        &dir.join("bomb.x3p"),
        &[
            ("main.xml", main_xml(10, 10).as_bytes()),
            ("bindata/data.bin", &bomb),
        ],
    );
    refused("bomb.x3p", None, "need 800 bytes");
    std::fs::remove_dir_all(&dir).ok();
}

/// A 3 x 2 Digital Surf surface made by hand (16 bits, spacings in mm, heights in µm).
fn tiny_sur(special: i16, values: [i16; 6]) -> Vec<u8> {
    let mut b = vec![0u8; 512];
    b[..12].copy_from_slice(b"DIGITAL SURF");
    let mut put = |o: usize, bytes: &[u8]| b[o..o + bytes.len()].copy_from_slice(bytes);
    put(18, &2i16.to_le_bytes());
    put(86, &special.to_le_bytes());
    put(98, &16i16.to_le_bytes());
    put(100, &(-100i32).to_le_bytes());
    put(108, &3i32.to_le_bytes());
    put(112, &2i32.to_le_bytes());
    put(120, &0.5f32.to_le_bytes());
    put(124, &0.25f32.to_le_bytes());
    put(128, &0.001f32.to_le_bytes());
    put(180, b"mm");
    put(196, b"mm");
    put(212, b"um");
    for v in values {
        b.extend(v.to_le_bytes());
    }
    b
}

#[test]
fn digital_surf_reads_its_header_and_refuses_unmeasured_points() {
    let dir = std::env::temp_dir().join(format!("surfgen-sur-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tiny.sur");
    std::fs::write(&path, tiny_sur(1, [1, 2, 3, -4, 5, 600])).unwrap();
    let s = io::read(&path, &ReadOptions::default()).unwrap();
    assert_eq!((s.grid.nx, s.grid.ny), (3, 2));
    assert!((s.grid.length_x - 1.5e-3).abs() < 1e-15 && (s.grid.length_y - 0.5e-3).abs() < 1e-15);
    let dz = 0.001f32 as f64 * 1e-6;
    assert_eq!(s.heights[[1, 2]], 600.0 * dz);
    assert_eq!(s.heights[[1, 0]], -4.0 * dz);
    // Points marked unmeasured (below the smallest stored value) are refused, counted.
    std::fs::write(&path, tiny_sur(1, [1, -102, 3, -4, -101, 600])).unwrap();
    let e = io::read(&path, &ReadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("2 of 6 points are not measured"), "{e}");
    // The real sample holds 117 of them; SurfaceTopography masks them (readings.json).
    let e = io::read(&samples().join("sur-2.sur"), &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("117 of 272492 points are not measured"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn wyko_opd_reads_its_blocks_and_refuses_unmeasured_points() {
    let dir = std::env::temp_dir().join(format!("surfgen-opd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tiny.opd");
    std::fs::write(&path, tiny_opd([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])).unwrap();
    let s = io::read(&path, &ReadOptions::default()).unwrap();
    assert_eq!((s.grid.nx, s.grid.ny), (3, 2));
    let pixel = 0.002f32 as f64 * 1e-3;
    assert!((s.grid.length_x / (3.0 * pixel) - 1.0).abs() < 1e-15);
    assert!((s.grid.length_y / (2.0 * 2.0 * pixel) - 1.0).abs() < 1e-15);
    // Column x holds (top, bottom) = values[2x], values[2x + 1]; our row 0 is the bottom.
    let waves = |j: usize| s.heights.row(j).mapv(|h| h / 500e-9).to_vec();
    let near = |a: Vec<f64>, b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x / y - 1.0).abs() < 1e-15);
    assert!(near(waves(0), [2.0, 4.0, 6.0]), "{:?}", waves(0));
    assert!(near(waves(1), [1.0, 3.0, 5.0]), "{:?}", waves(1));
    std::fs::write(&path, tiny_opd([1.0, 1e38, 3.0, 4.0, 5.0, f32::NAN])).unwrap();
    let e = io::read(&path, &ReadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("2 of 6 points are not measured"), "{e}");
    // The real sample holds 116 of them; SurfaceTopography masks them (readings.json).
    let e = io::read(&samples().join("opd-1.opd"), &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("116 of 307200 points are not measured"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn harmonic_fill_restores_a_discrete_harmonic_surface_and_fills_the_samples() {
    // x^2 - y^2 and planes are harmonic for the 5-point Laplacian too: the fill restores them
    // exactly inside, whatever the holes' shape.
    let exact = Array2::from_shape_fn((20, 30), |(j, i)| {
        let (x, y) = (i as f64, j as f64);
        1e-6 * (3.0 * x - 2.0 * y + 0.1 * (x * x - y * y))
    });
    let mut holed = exact.clone();
    for (j, i) in [
        (5, 5),
        (5, 6),
        (6, 5),
        (10, 10),
        (10, 11),
        (10, 12),
        (11, 12),
        (12, 12),
        (15, 25),
    ] {
        holed[[j, i]] = f64::NAN;
    }
    for j in 3..9 {
        holed[[j, 18]] = f64::NAN;
    }
    io::fill_harmonic(&mut holed, false);
    let worst = (&holed - &exact).iter().fold(0.0f64, |m, d| m.max(d.abs()));
    assert!(worst < 1e-16, "largest error {worst:e} m");
    // The real samples' unmeasured points, filled, lie within the measured range.
    for name in ["sur-2.sur", "opd-1.opd", "frt-1.frt"] {
        let path = samples().join(name);
        let m = io::read_measurement(&path, &ReadOptions::default()).unwrap();
        let measured = m.heights.iter().copied().filter(|h| !h.is_nan());
        let (lo, hi) = measured.fold((f64::MAX, f64::MIN), |(a, b), h| (a.min(h), b.max(h)));
        // frt-1 is 31 % unmeasured: beyond the default limit of filled points.
        let options = ReadOptions {
            unmeasured: io::Unmeasured::FillUpTo(1.0),
            ..Default::default()
        };
        let s = io::read(&path, &options).unwrap();
        for (h, m) in s.heights.iter().zip(&m.heights) {
            if m.is_nan() {
                assert!(
                    (lo..=hi).contains(h),
                    "{name}: filled {h:e} outside [{lo:e}, {hi:e}]"
                );
            } else {
                assert_eq!(h, m);
            }
        }
    }
}

#[test]
fn nanoscope_lists_its_channels_reads_the_height_one_and_refuses_the_others() {
    let dir = std::env::temp_dir().join(format!("surfgen-di-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tiny.spm");
    std::fs::write(&path, tiny_di([1, 2, 3, -4, 5, 600])).unwrap();
    let channels = io::channels(&path, &ReadOptions::default()).unwrap();
    let names: Vec<(&str, &str, bool)> = channels
        .iter()
        .map(|c| (c.name.as_str(), c.unit.as_str(), c.height))
        .collect();
    assert_eq!(names, [("Phase", "deg", false), ("Height", "nm", true)]);
    assert_eq!((channels[1].nx, channels[1].ny), (3, 2));
    assert!((channels[1].length_x.unwrap() - 3e-6).abs() < 1e-18);
    // The height channel by default; stored from the top, so the second line is our y = 0.
    let s = io::read(&path, &ReadOptions::default()).unwrap();
    let pm = |v: f64| v * 1e-12;
    let near = |a: f64, b: f64| (a - b).abs() < 1e-9 * b.abs();
    assert!(near(s.heights[[0, 0]], pm(-4.0)) && near(s.heights[[0, 2]], pm(600.0)));
    assert!(near(s.heights[[1, 0]], pm(1.0)), "{:?}", s.heights);
    let by_index = ReadOptions {
        channel: Some(1),
        ..Default::default()
    };
    assert_eq!(io::read(&path, &by_index).unwrap(), s);
    for (channel, reason) in [
        (0, "channel 0 'Phase' holds deg, not heights"),
        (2, "no channel 2"),
    ] {
        let options = ReadOptions {
            channel: Some(channel),
            ..Default::default()
        };
        let e = io::read(&path, &options).unwrap_err().to_string();
        assert!(e.contains(reason), "{e}");
    }
    // A format of one surface has channel 0 only.
    let e = io::read(&samples().join("tmd-1.tmd"), &by_index)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no channel 1: the file holds one surface"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn igor_wave_names_its_channels_and_reads_the_height_one() {
    let dir = std::env::temp_dir().join(format!("surfgen-ibw-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tiny.ibw");
    let values: Vec<f32> = (1..=12).map(|v| v as f32).collect();
    std::fs::write(&path, tiny_ibw(values.clone().try_into().unwrap())).unwrap();
    let channels = io::channels(&path, &ReadOptions::default()).unwrap();
    let names: Vec<(&str, bool)> = channels.iter().map(|c| (c.name.as_str(), c.height)).collect();
    assert_eq!(names, [("HeightTrace", true), ("PhaseTrace", false)]);
    let s = io::read(&path, &ReadOptions::default()).unwrap();
    assert_eq!((s.grid.length_x, s.grid.length_y), (3e-6, 4e-6));
    // x fastest; the wave's last y is our y = 0 (as SurfaceTopography and Gwyddion show it).
    assert_eq!(s.heights.row(0).to_vec(), [4.0, 5.0, 6.0]);
    assert_eq!(s.heights.row(1).to_vec(), [1.0, 2.0, 3.0]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn frt_reads_its_blocks_and_marks_unmeasured_points() {
    let dir = std::env::temp_dir().join(format!("surfgen-frt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tiny.frt");
    std::fs::write(&path, tiny_frt([2, 3, 4, 5, 6, 700])).unwrap();
    let s = io::read(&path, &ReadOptions::default()).unwrap();
    assert_eq!(
        (s.grid.nx, s.grid.ny, s.grid.length_x, s.grid.length_y),
        (3, 2, 3e-3, 1e-3)
    );
    // Rows stored from the top: the second is our y = 0.
    assert_eq!(s.heights.row(0).to_vec(), [5.0 * 1e-9, 6.0 * 1e-9, 700.0 * 1e-9]);
    std::fs::write(&path, tiny_frt([2, 1, 4, 5, 6, 1])).unwrap();
    let e = io::read(&path, &ReadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("2 of 6 points are not measured"), "{e}");
    // The real sample: 76456 of its 250000 points.
    let m = io::read_measurement(&samples().join("frt-1.frt"), &ReadOptions::default()).unwrap();
    assert_eq!(m.unmeasured(), 76456);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn gwyddion_lists_its_images_reads_the_heights_and_their_mask() {
    let dir = std::env::temp_dir().join(format!("surfgen-gwy-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tiny.gwy");
    let h = [1e-9, 2e-9, 3e-9, 4e-9, 5e-9, 6e-9];
    std::fs::write(&path, tiny_gwy(h, [false; 6])).unwrap();
    let channels = io::channels(&path, &ReadOptions::default()).unwrap();
    let names: Vec<(&str, &str, bool)> = channels
        .iter()
        .map(|c| (c.name.as_str(), c.unit.as_str(), c.height))
        .collect();
    assert_eq!(names, [("Phase", "deg", false), ("Topography", "m", true)]);
    let s = io::read(&path, &ReadOptions::default()).unwrap();
    assert_eq!(
        (s.grid.nx, s.grid.ny, s.grid.length_x, s.grid.length_y),
        (3, 2, 3e-6, 2e-6)
    );
    assert_eq!(s.heights.row(1).to_vec(), h[3..]);
    std::fs::write(&path, tiny_gwy(h, [false, true, false, false, false, true])).unwrap();
    let m = io::read_measurement(&path, &ReadOptions::default()).unwrap();
    assert!(m.heights[[0, 1]].is_nan() && m.heights[[1, 2]].is_nan() && m.unmeasured() == 2);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn hdf5_written_by_the_c_library_lists_its_arrays_and_reads_them() {
    // h5-1.h5 was written by h5py 3.16 (HDF5 2.0.0): `surface` (6 x 8, f64, gzip-compressed
    // chunks) = 1e-7 sin(i + 0.3 j) + 1e-9 i j, its f32 copy `channels/height32`, a 1-D
    // `profile` (a line scan) and a string array (not a topography).
    let path = samples().join("h5-1.h5");
    let options = ReadOptions {
        length_x: Some(8e-6),
        ..Default::default()
    };
    let channels = io::channels(&path, &options).unwrap();
    let names: Vec<&str> = channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["channels/height32", "profile", "surface"]);
    let grids: Vec<(usize, usize)> = channels.iter().map(|c| (c.nx, c.ny)).collect();
    assert_eq!(grids, [(8, 6), (5, 1), (8, 6)]);
    let formula = |j: usize, i: usize| 1e-7 * (i as f64 + 0.3 * j as f64).sin() + 1e-9 * (i * j) as f64;
    let surface = io::read(
        &path,
        &ReadOptions {
            channel: Some(io::channel_index(&path, &options, "surface").unwrap()),
            ..options
        },
    )
    .unwrap();
    assert_eq!(
        surface.heights,
        Array2::from_shape_fn((6, 8), |(j, i)| formula(j, i))
    );
    assert_eq!((surface.grid.length_x, surface.grid.length_y), (8e-6, 6e-6));
    let single = io::read(&path, &options).unwrap();
    assert_eq!(
        single.heights,
        Array2::from_shape_fn((6, 8), |(j, i)| formula(j, i) as f32 as f64)
    );
    // Without a size the file cannot say, it is refused with the reason.
    let e = io::read(&path, &ReadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("does not say its lateral size"), "{e}");
}

#[test]
fn line_scans_read_as_profiles_and_are_refused_as_surfaces() {
    let dir = std::env::temp_dir().join(format!("surfgen-profiles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let options = ReadOptions {
        length_x: Some(4e-6),
        ..Default::default()
    };
    // A text file of one row (or one column), NaN unmeasured.
    let row = dir.join("row.txt");
    std::fs::write(&row, "1e-9 2e-9 NaN 4e-9\n").unwrap();
    let column = dir.join("column.txt");
    std::fs::write(&column, "1e-9\n2e-9\nnan\n4e-9\n").unwrap();
    for path in [&row, &column] {
        let Ok(io::Topography::Profile(p)) = io::read_topography(path, &options) else {
            panic!("{} is a profile", path.display());
        };
        assert_eq!((p.heights.len(), p.length), (4, Some(4e-6)));
        assert!(p.heights[2].is_nan() && p.heights[3] == 4e-9);
        let e = io::read(path, &options).unwrap_err().to_string();
        assert!(
            e.contains("a line scan (a profile of 4 points over 4e-6 m), not a surface"),
            "{e}"
        );
    }
    // A 1-D HDF5 dataset, chosen by name (h5py's file); by default the surfaces come first.
    let h5 = samples().join("h5-1.h5");
    let profile = ReadOptions {
        channel: Some(io::channel_index(&h5, &options, "profile").unwrap()),
        ..options
    };
    let Ok(io::Topography::Profile(p)) = io::read_topography(&h5, &profile) else {
        panic!("the HDF5 profile");
    };
    assert_eq!(p.heights, [0.0, 1.0, 2.0, 3.0, 4.0]);
    assert!(matches!(
        io::read_topography(&h5, &options),
        Ok(io::Topography::Surface(_))
    ));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn mountains_documents_read_their_axes_heights_and_mask() {
    let dir = std::env::temp_dir().join(format!("surfgen-mnt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tiny.mnt");
    std::fs::write(&path, tiny_mnt([1, 2, 3, 4, 5, 600], &[])).unwrap();
    let channels = io::channels(&path, &ReadOptions::default()).unwrap();
    assert_eq!(
        (channels[0].name.as_str(), channels[0].unit.as_str()),
        ("tiny", "µm")
    );
    let s = io::read(&path, &ReadOptions::default()).unwrap();
    assert_eq!((s.grid.nx, s.grid.ny), (3, 2));
    assert!((s.grid.length_x - 1.5e-3).abs() < 1e-18 && (s.grid.length_y - 0.5e-3).abs() < 1e-18);
    // count * 2 nm + 1 µm, x fastest, row by row from y = 0.
    let h = |c: f64| c * 2e-9 + 1e-6;
    assert_eq!(s.heights.row(0).to_vec(), [h(1.0), h(2.0), h(3.0)]);
    assert_eq!(s.heights.row(1).to_vec(), [h(4.0), h(5.0), h(600.0)]);
    std::fs::write(&path, tiny_mnt([1, 2, 3, 4, 5, 6], &[1, 5])).unwrap();
    let m = io::read_measurement(&path, &ReadOptions::default()).unwrap();
    assert!(m.heights[[0, 1]].is_nan() && m.heights[[1, 2]].is_nan() && m.unmeasured() == 2);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn zygo_datx_reads_its_surface_in_its_unit_with_unmeasured_points() {
    // zygo-like.datx, written by h5py as Zygo lays out a measurement: `Measurement/Surface`
    // (f32, `Unit` nm, `No Data` the largest f32 at one point, the spacing in a compound
    // `X Converter`), and a unitless `Measurement/Intensity`.
    let path = samples().join("zygo-like.datx");
    let options = ReadOptions {
        length_x: Some(3e-6),
        ..Default::default()
    };
    let channels = io::channels(&path, &options).unwrap();
    let heights: Vec<(&str, &str, bool)> = channels
        .iter()
        .map(|c| (c.name.as_str(), c.unit.as_str(), c.height))
        .collect();
    assert_eq!(
        heights,
        [
            ("Measurement/Intensity", "", false),
            ("Measurement/Surface", "nm", true)
        ]
    );
    let m = io::read_measurement(&path, &options).unwrap();
    assert_eq!(m.channel, 1);
    assert!(m.heights[[0, 2]].is_nan() && m.unmeasured() == 1);
    assert_eq!(m.heights.row(1).to_vec(), [4.0 * 1e-9, -5.0 * 1e-9, 6.25 * 1e-9]);
    // The spacing is not decoded: without a size from the user the file is refused.
    let e = io::read(&path, &ReadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("does not say its lateral size"), "{e}");
}
