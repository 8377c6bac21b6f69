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
