//! ISO 25178-72 XML 3D surface profile (`.x3p`): a zip archive holding `main.xml` (the ISO
//! 5436-2 record: axes, matrix size, the data file's name and its MD5) and the binary heights
//! (`bindata/data.bin`: `SizeX * SizeY` little-endian values of the z axis' `DataType`, I =
//! i16, L = i32, F = f32, D = f64, x varying fastest), and `md5checksum.hex` (the MD5 of
//! `main.xml`). Heights are the stored values times the z axis' `Increment` plus its `Offset`
//! [m]; the x and y axes must be incremental (`AxisType` I), their `Increment` the spacing [m].
//!
//! Reading never allocates more than the archive's entries can hold: a declared size is
//! checked against the entry's compressed size times deflate's largest ratio.

use super::{Measurement, Number, ReadOptions, Surface, header};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use md5::{Digest, Md5};
use ndarray::Array2;
use quick_xml::events::Event;
use std::io::{Read, Write};
use std::path::Path;

/// Deflate expands by at most about 1032:1; a declared size beyond this times the compressed
/// size is a lie (a zip bomb).
const MAX_RATIO: u64 = 1100;
/// The largest `main.xml` read [bytes].
const MAX_XML: u64 = 16 << 20;

/// The text of every element of `xml`, keyed by its path of local names (`Record1/Axes/CX/Increment`).
fn elements(xml: &str) -> std::result::Result<Vec<(String, String)>, String> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut path: Vec<String> = Vec::new();
    let mut out = Vec::new();
    loop {
        match reader.read_event().map_err(|e| e.to_string())? {
            Event::Start(e) => path.push(e.local_name().as_ref().to_string()),
            Event::End(_) => {
                path.pop();
            }
            Event::Text(t) => {
                let text = t
                    .xml_content(quick_xml::XmlVersion::Implicit1_0)
                    .trim()
                    .to_string();
                if !text.is_empty() && path.len() > 1 {
                    out.push((path[1..].join("/"), text));
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    Ok(out)
}

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let bad = |m: String| SurfError::parse(path, None, m);
    let file = std::fs::File::open(path).map_err(|e| SurfError::io(path, e))?;
    let mut archive =
        zip::ZipArchive::new(file).map_err(|e| bad(format!("not an X3P file (a zip archive): {e}")))?;
    let xml = {
        let entry = archive
            .by_name("main.xml")
            .map_err(|_| bad("the archive has no main.xml".into()))?;
        if entry.size() > MAX_XML || entry.size() > MAX_RATIO * entry.compressed_size().max(1) {
            return Err(bad(format!("main.xml claims {} bytes", entry.size())));
        }
        let mut text = String::new();
        entry
            .take(MAX_XML)
            .read_to_string(&mut text)
            .map_err(|e| bad(format!("reading main.xml: {e}")))?;
        text
    };
    let fields = elements(&xml).map_err(|e| bad(format!("main.xml: {e}")))?;
    let get = |key: &str| fields.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str());
    let number = |key: &str| -> Result<Option<f64>> {
        get(key)
            .map(|v| {
                v.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| bad(format!("main.xml: cannot read {key} '{v}'")))
            })
            .transpose()
    };
    let count = |key: &str| -> Result<usize> {
        let v = get(key).ok_or_else(|| bad(format!("main.xml lacks {key}")))?;
        v.parse::<usize>().ok().filter(|&n| n >= 1).ok_or_else(|| {
            bad(format!(
                "main.xml: {key} must be a positive whole number, got '{v}'"
            ))
        })
    };
    if let Some(kind) = get("Record1/FeatureType")
        && kind != "SUR"
    {
        return Err(bad(format!(
            "a {kind} feature, not a surface (SUR): profiles and point clouds are not read"
        )));
    }
    for axis in ["CX", "CY"] {
        if let Some(t) = get(&format!("Record1/Axes/{axis}/AxisType"))
            && t != "I"
        {
            return Err(bad(format!(
                "axis {axis} is not incremental (AxisType {t}): only gridded surfaces are read"
            )));
        }
    }
    let (nx, ny) = (
        count("Record3/MatrixDimension/SizeX")?,
        count("Record3/MatrixDimension/SizeY")?,
    );
    if count("Record3/MatrixDimension/SizeZ").unwrap_or(1) != 1 {
        return Err(bad("SizeZ is not 1: several layers are not read".into()));
    }
    let dx =
        number("Record1/Axes/CX/Increment")?.ok_or_else(|| bad("main.xml lacks the x increment".into()))?;
    let dy =
        number("Record1/Axes/CY/Increment")?.ok_or_else(|| bad("main.xml lacks the y increment".into()))?;
    let dx = header(path, "Record1/Axes/CX/Increment", dx, Number::Size)?;
    let dy = header(path, "Record1/Axes/CY/Increment", dy, Number::Size)?;
    let z_scale = header(
        path,
        "Record1/Axes/CZ/Increment",
        number("Record1/Axes/CZ/Increment")?.unwrap_or(1.0),
        Number::Scale,
    )?;
    let z_offset = super::offset(
        path,
        "Record1/Axes/CZ/Offset",
        number("Record1/Axes/CZ/Offset")?.unwrap_or(0.0),
        "Record1/Axes/CZ/Increment",
        z_scale,
    )?;
    let kind = get("Record1/Axes/CZ/DataType").unwrap_or("D");
    let size = match kind {
        "I" => 2,
        "L" | "F" => 4,
        "D" => 8,
        other => return Err(bad(format!("unknown z DataType '{other}' (I, L, F or D)"))),
    };
    let link = get("Record3/DataLink/PointDataLink")
        .unwrap_or("bindata/data.bin")
        .to_string();
    let expected = (nx as u64)
        .checked_mul(ny as u64)
        .and_then(|n| n.checked_mul(size))
        .ok_or_else(|| bad(format!("{nx} x {ny} points overflow")))?;
    let raw = data(
        &mut archive,
        (&link, &format!("{nx} x {ny} {kind} heights")),
        expected,
        get("Record3/DataLink/MD5ChecksumPointData"),
        &bad,
    )?;
    let values: Vec<f64> = raw
        .chunks_exact(size as usize)
        .map(|c| match kind {
            "I" => i16::from_le_bytes([c[0], c[1]]) as f64,
            "L" => i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
            "F" => f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
            _ => f64::from_le_bytes(c.try_into().expect("8 bytes")),
        })
        .map(|v| (v * z_scale + z_offset) * options.unit)
        .collect();
    let grid = Grid::new(
        nx,
        ny,
        nx as f64 * dx * options.unit,
        ny as f64 * dy * options.unit,
    )
    .map_err(|e| bad(e.to_string()))?;
    let heights = Array2::from_shape_vec((ny, nx), values).expect("counted");
    if let Some((k, _)) = heights.iter().enumerate().find(|(_, h)| !h.is_finite()) {
        return Err(bad(format!(
            "point (x {}, y {}) is not measured (invalid); fill such points before a contact calculation",
            k % nx,
            k / nx
        )));
    }
    Measurement::new(heights, grid, options.periodic)
}

/// The data entry `link` (`what` it holds) of `expected` bytes, checked against its MD5 checksum where main.xml
/// records one (`recorded`): a file changed or damaged after it was written is refused, not
/// read silently.
fn data(
    archive: &mut zip::ZipArchive<std::fs::File>,
    (link, what): (&str, &str),
    expected: u64,
    recorded: Option<&str>,
    bad: &dyn Fn(String) -> SurfError,
) -> Result<Vec<u8>> {
    let mut entry = archive
        .by_name(link)
        .map_err(|_| bad(format!("the archive has no {link}, which main.xml names")))?;
    if entry.size() != expected || expected > MAX_RATIO * entry.compressed_size().max(1) {
        return Err(bad(format!(
            "{what} need {expected} bytes; {link} holds {} ({} compressed)",
            entry.size(),
            entry.compressed_size()
        )));
    }
    let mut raw = Vec::with_capacity(expected as usize);
    (&mut entry)
        .take(expected)
        .read_to_end(&mut raw)
        .map_err(|e| bad(format!("reading {link}: {e}")))?;
    if raw.len() as u64 != expected {
        return Err(bad(format!(
            "{link} ends after {} of {expected} bytes",
            raw.len()
        )));
    }
    // The data's checksum, where main.xml records it, must be the data's: a file changed or
    // damaged after it was written is refused, not read silently.
    if let Some(recorded) = recorded {
        let actual = hex(&Md5::digest(&raw));
        if !recorded.trim().eq_ignore_ascii_case(&actual) {
            return Err(bad(format!(
                "{link} does not match main.xml's MD5ChecksumPointData (recorded {recorded}, the data's \
                 {actual}): the file was changed or damaged after it was written"
            )));
        }
    }
    Ok(raw)
}

fn hex(digest: &[u8]) -> String {
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

pub(super) fn write(surface: &Surface, path: &Path) -> Result<()> {
    let g = surface.grid;
    let mut data = Vec::with_capacity(g.len() * 8);
    for h in surface.heights.iter() {
        data.extend_from_slice(&h.to_le_bytes());
    }
    let xml = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:schemaLocation="http://www.opengps.eu/2008/ISO5436_2 http://www.opengps.eu/2008/ISO5436_2/ISO5436_2_XML.xsd">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{dx:e}</Increment><Offset>0</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{dy:e}</Increment><Offset>0</Offset></CY>
      <CZ><AxisType>A</AxisType><DataType>D</DataType><Increment>1</Increment><Offset>0</Offset></CZ>
    </Axes>
  </Record1>
  <Record2>
    <Date>1970-01-01T00:00:00.0+00:00</Date>
    <Instrument><Manufacturer>roughcontact</Manufacturer><Model>roughcontact</Model><Serial>none</Serial><Version>{version}</Version></Instrument>
    <CalibrationDate>1970-01-01T00:00:00.0+00:00</CalibrationDate>
    <ProbingSystem><Type>Software</Type><Identification>roughcontact</Identification></ProbingSystem>
    <Comment>heights in metres</Comment>
  </Record2>
  <Record3>
    <MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
    <DataLink><PointDataLink>bindata/data.bin</PointDataLink><MD5ChecksumPointData>{md5}</MD5ChecksumPointData></DataLink>
  </Record3>
  <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>
"#,
        dx = g.dx(),
        dy = g.dy(),
        version = env!("CARGO_PKG_VERSION"),
        nx = g.nx,
        ny = g.ny,
        md5 = hex(&Md5::digest(&data)),
    );
    let io = |e: std::io::Error| SurfError::io(path, e);
    let zipped = |e: zip::result::ZipError| SurfError::parse(path, None, format!("writing the archive: {e}"));
    let file = std::fs::File::create(path).map_err(io)?;
    let mut zip = zip::ZipWriter::new(file);
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("main.xml", options).map_err(zipped)?;
    zip.write_all(xml.as_bytes()).map_err(io)?;
    zip.start_file("bindata/data.bin", options).map_err(zipped)?;
    zip.write_all(&data).map_err(io)?;
    zip.start_file("md5checksum.hex", options).map_err(zipped)?;
    zip.write_all(format!("{} *main.xml\n", hex(&Md5::digest(xml.as_bytes()))).as_bytes())
        .map_err(io)?;
    zip.finish().map_err(zipped)?;
    Ok(())
}
