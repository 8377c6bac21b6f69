//! Files the readers' tests build by hand.

/// A 3 x 2 Wyko OPD file made by hand: the directory, then Raw (f32 waves, column by column,
/// each from the top), Wavelength 500 nm, Pixel_size 0.002 mm, Aspect 2.
pub fn tiny_opd(values: [f32; 6]) -> Vec<u8> {
    let raw: Vec<u8> = [3i16, 2, 4]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .chain(values.iter().flat_map(|v| v.to_le_bytes()))
        .collect();
    let blocks: [(&str, i16, Vec<u8>); 4] = [
        ("Raw", 3, raw),
        ("Wavelength", 7, 500f32.to_le_bytes().to_vec()),
        ("Pixel_size", 7, 0.002f32.to_le_bytes().to_vec()),
        ("Aspect", 7, 2f32.to_le_bytes().to_vec()),
    ];
    let mut b = vec![1u8, 0];
    let mut entry = |name: &str, kind: i16, length: usize| {
        let mut e = [0u8; 24];
        e[..name.len()].copy_from_slice(name.as_bytes());
        e[16..18].copy_from_slice(&kind.to_le_bytes());
        e[18..22].copy_from_slice(&(length as i32).to_le_bytes());
        b.extend(e);
    };
    entry("Directory", 1, 24 * (blocks.len() + 1));
    for (name, kind, data) in &blocks {
        entry(name, *kind, data.len());
    }
    for (_, _, data) in blocks {
        b.extend(data);
    }
    b
}

/// A Nanoscope file made by hand: a phase image (degrees), then a 3 x 2 height image of 16 bits
/// stored from the top, 3 x 2 µm; a height is `raw * 6.5536 V / 2^16 * 10 nm/V = raw` pm.
pub fn tiny_di(values: [i16; 6]) -> Vec<u8> {
    let image = |name: &str, offset: usize, scale: &str| {
        format!(
            "\\*Ciao image list\r\n\\Data offset: {offset}\r\n\\Data length: 12\r\n\\Bytes/pixel: 2\r\n\
             \\Samps/line: 3\r\n\\Number of lines: 2\r\n\\Scan Size: 3 2 ~m\r\n\
             \\@2:Image Data: S [{name}] \"{name}\"\r\n\\@2:Z scale: {scale}\r\n"
        )
    };
    let header = format!(
        "\\*File list\r\n\\Data length: 1024\r\n\\*Scanner list\r\n\\@Sens. Zsens: V 10.00 nm/V\r\n\
         \\@Sens. Phase: V 1.000 deg/V\r\n{}{}\\*File list end\r\n",
        image("Phase", 1024, "V [Sens. Phase] (0.0001 V/LSB) 6.5536 V"),
        image("Height", 1036, "V [Sens. Zsens] (0.0001 V/LSB) 6.5536 V"),
    );
    let mut b = header.into_bytes();
    b.resize(1024, 0);
    b.extend([0u8; 12]);
    b.extend(values.iter().flat_map(|v| v.to_le_bytes()));
    b
}

/// An Igor binary wave (version 5, little-endian) made by hand: 3 x 2 x 2 f32 in metres, x
/// fastest, spacing 1 µm along x and 2 µm along y, channels `HeightTrace` and `PhaseTrace`.
pub fn tiny_ibw(values: [f32; 12]) -> Vec<u8> {
    let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let mut labels = vec![0u8; 3 * 32];
    for (k, name) in ["", "HeightTrace", "PhaseTrace"].iter().enumerate() {
        labels[32 * k..32 * k + name.len()].copy_from_slice(name.as_bytes());
    }
    let mut b = vec![0u8; 64 + 320];
    let mut put = |o: usize, bytes: &[u8]| b[o..o + bytes.len()].copy_from_slice(bytes);
    put(0, &5i16.to_le_bytes());
    put(4, &((320 + data.len()) as u32).to_le_bytes());
    put(36 + 8, &(labels.len() as u32).to_le_bytes());
    put(64 + 12, &12u32.to_le_bytes());
    put(64 + 16, &2i16.to_le_bytes());
    for (d, n) in [3u32, 2, 2].iter().enumerate() {
        put(64 + 68 + 4 * d, &n.to_le_bytes());
    }
    put(64 + 84, &1e-6f64.to_le_bytes());
    put(64 + 92, &2e-6f64.to_le_bytes());
    put(64 + 148, b"m");
    put(64 + 152, b"m");
    put(64 + 156, b"m");
    b.extend(data);
    b.extend(labels);
    b
}

/// An FRT file (version 1.00) made by hand: a text block, then 3 x 2 points of 16 bits, a box
/// of 3 x 1 mm, 1 nm a count, x fastest; a count of 1 is unmeasured.
pub fn tiny_frt(counts: [u16; 6]) -> Vec<u8> {
    let mut b = b"FRTM_GLIDERV1.00".to_vec();
    b.extend(5u16.to_le_bytes());
    let mut block = |id: u16, body: Vec<u8>| {
        b.extend(id.to_le_bytes());
        b.extend((body.len() as u32).to_le_bytes());
        b.extend(body);
    };
    block(0x65, b"note\0".to_vec());
    block(0x66, [3u32, 2, 16].iter().flat_map(|v| v.to_le_bytes()).collect());
    let mut sizes: Vec<u8> = [3e-3f64, 1e-3].iter().flat_map(|v| v.to_le_bytes()).collect();
    sizes.extend([0u8; 28]);
    block(0x67, sizes);
    let mut range = 0u32.to_le_bytes().to_vec();
    range.extend(1e-9f64.to_le_bytes());
    block(0x6c, range);
    block(0x0b, counts.iter().flat_map(|v| v.to_le_bytes()).collect());
    b
}

/// A serialized Gwyddion object: class name, size, components (name, type, value bytes).
fn gwy_object(class: &str, components: &[(&str, u8, Vec<u8>)]) -> Vec<u8> {
    let mut body = Vec::new();
    for (name, kind, value) in components {
        body.extend(name.as_bytes());
        body.push(0);
        body.push(*kind);
        body.extend(value);
    }
    let mut b = class.as_bytes().to_vec();
    b.push(0);
    b.extend((body.len() as u32).to_le_bytes());
    b.extend(body);
    b
}

fn gwy_field(values: &[f64], unit_z: &str) -> Vec<u8> {
    let unit = |u: &str| gwy_object("GwySIUnit", &[("unitstr", b's', [u.as_bytes(), &[0]].concat())]);
    let mut data = (values.len() as u32).to_le_bytes().to_vec();
    data.extend(values.iter().flat_map(|v| v.to_le_bytes()));
    gwy_object(
        "GwyDataField",
        &[
            ("xres", b'i', 3i32.to_le_bytes().to_vec()),
            ("yres", b'i', 2i32.to_le_bytes().to_vec()),
            ("xreal", b'd', 3e-6f64.to_le_bytes().to_vec()),
            ("yreal", b'd', 2e-6f64.to_le_bytes().to_vec()),
            ("si_unit_xy", b'o', unit("m")),
            ("si_unit_z", b'o', unit(unit_z)),
            ("data", b'D', data),
        ],
    )
}

/// A Gwyddion file made by hand: image 0 a phase (deg), image 1 heights (3 x 2 over 3 x 2 µm,
/// rows in order) with a mask over the points where `masked` is true.
pub fn tiny_gwy(heights: [f64; 6], masked: [bool; 6]) -> Vec<u8> {
    let mask: Vec<f64> = masked.iter().map(|&m| if m { 1.0 } else { 0.0 }).collect();
    let text = |t: &str| [t.as_bytes(), &[0]].concat();
    let container = gwy_object(
        "GwyContainer",
        &[
            ("/0/data/title", b's', text("Phase")),
            ("/0/data", b'o', gwy_field(&[0.0; 6], "deg")),
            ("/1/data/title", b's', text("Topography")),
            ("/1/data", b'o', gwy_field(&heights, "m")),
            ("/1/mask", b'o', gwy_field(&mask, "")),
            ("/1/data/visible", b'b', vec![1]),
        ],
    );
    [b"GWYP".as_slice(), &container].concat()
}

/// A tag-size-value entry of a MountainsMap document.
fn mnt_entry(tag: u16, value: &[u8]) -> Vec<u8> {
    [&tag.to_le_bytes()[..], &(value.len() as u64).to_le_bytes(), value].concat()
}

fn mnt_text(s: &str) -> Vec<u8> {
    std::iter::once(4u8)
        .chain(s.encode_utf16().flat_map(|u| u.to_le_bytes()))
        .collect()
}

/// An array of one zlib block.
fn mnt_array(class: u32, count: usize, bytes: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    z.write_all(bytes).unwrap();
    let z = z.finish().unwrap();
    let data = [
        &(bytes.len() as u64).to_le_bytes()[..],
        &0u64.to_le_bytes(),
        &(count as u32).to_le_bytes(),
        &(z.len() as u32).to_le_bytes(),
        &z,
    ]
    .concat();
    let body = [mnt_entry(1, &(count as u32).to_le_bytes()), mnt_entry(2, &data)].concat();
    [
        mnt_entry(1, &mnt_entry(1, &class.to_le_bytes())),
        mnt_entry(2, &body),
    ]
    .concat()
}

/// A MountainsMap document made by hand (an OLE compound file): one measured surface of 3 x 2
/// points, steps 0.5 mm and 0.25 mm, heights `count * 2 nm + 1 µm` stored row by row, x
/// fastest; `unmeasured` points marked in a mask.
pub fn tiny_mnt(counts: [i32; 6], unmeasured: &[usize]) -> Vec<u8> {
    use std::io::Write;
    let scale = |step: f64, unit: &str, display: &str, origin: f64| {
        [
            mnt_entry(1, &step.to_le_bytes()),
            mnt_entry(2, &mnt_text(unit)),
            mnt_entry(3, &mnt_text(display)),
            mnt_entry(5, &origin.to_le_bytes()),
        ]
        .concat()
    };
    let lateral = |n: u32, step: f64| {
        let axis = [
            mnt_entry(0xFFFF, &scale(step, "mm", "mm", 0.0)),
            mnt_entry(1, &n.to_le_bytes()),
        ]
        .concat();
        mnt_entry(0xFFFF, &axis)
    };
    let mut image = vec![9u8; 5 * 4];
    for &k in unmeasured {
        image[(k / 3 + 1) * 5 + k % 3 + 1] = 22;
    }
    let mask_body = [
        mnt_entry(1, &3u32.to_le_bytes()),
        mnt_entry(2, &2u32.to_le_bytes()),
        mnt_entry(5, &mnt_array(9048, 20, &image)),
    ]
    .concat();
    let mask = [
        mnt_entry(1, &mnt_entry(1, &9056u32.to_le_bytes())),
        mnt_entry(2, &mask_body),
    ]
    .concat();
    let grid = [
        mnt_entry(0xFFFF, &mnt_entry(0xFFFF, &mnt_entry(1, &mnt_text("tiny")))),
        mnt_entry(1, &lateral(3, 0.5)),
        mnt_entry(2, &lateral(2, 0.25)),
        mnt_entry(3, &mask),
    ]
    .concat();
    let heights: Vec<u8> = counts.iter().flat_map(|c| c.to_le_bytes()).collect();
    let measurement = [
        mnt_entry(0xFFFF, &grid),
        mnt_entry(1, &mnt_array(9049, 6, &heights)),
        mnt_entry(2, &mnt_entry(0xFFFF, &scale(2.0, "nm", "µm", 1.0))),
    ]
    .concat();
    let data = [
        mnt_entry(1, &mnt_entry(1, &9062u32.to_le_bytes())),
        mnt_entry(2, &mnt_entry(0xFFFF, &measurement)),
    ]
    .concat();
    let surface_body = [
        mnt_entry(0xFFFF, &mnt_entry(4, &mnt_text("title"))),
        mnt_entry(1, &data),
    ]
    .concat();
    let object = [
        mnt_entry(1, &mnt_entry(1, &9012u32.to_le_bytes())),
        mnt_entry(2, &surface_body),
    ]
    .concat();
    let listed = mnt_entry(1, &object);
    let objects = [&(listed.len() as u64).to_le_bytes()[..], &listed].concat();
    let document = [mnt_entry(1, &[1]), mnt_entry(2, &mnt_entry(1, &objects))].concat();
    let main = mnt_entry(1, &mnt_entry(0x02BD, &document));
    let contents = [&(main.len() as u64).to_le_bytes()[..], &main].concat();
    let mut file = cfb::CompoundFile::create(std::io::Cursor::new(Vec::new())).unwrap();
    file.create_stream("/ScopedContents")
        .unwrap()
        .write_all(&contents)
        .unwrap();
    file.flush().unwrap();
    file.into_inner().into_inner()
}
