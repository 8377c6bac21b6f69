//! Every reader on arbitrary bytes: it returns a surface or an error, never panics or aborts,
//! and never allocates more than a bound set by the file's length. One test in this binary, so
//! that the allocation count sees this reader alone.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use surfgen::io::{self, ReadOptions};
use surfgen::{Grid, Surface};

mod common;
use common::{tiny_di, tiny_frt, tiny_gwy, tiny_ibw, tiny_mnt, tiny_opd};

/// The system allocator, counting the bytes live and their peak since the last reset. A single
/// request above `CAP` is refused (the process aborts: the test fails) rather than granted.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
const CAP: usize = 1 << 30;

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if layout.size() > CAP {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded with the caller's layout.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let live = LIVE.fetch_add(layout.size(), Ordering::SeqCst) + layout.size();
            PEAK.fetch_max(live, Ordering::SeqCst);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::SeqCst);
        // SAFETY: `ptr` was allocated by `alloc` with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Reads `bytes` as a file named `name`; the peak of the bytes allocated meanwhile above what
/// was live before.
fn read(path: &PathBuf, bytes: &[u8], options: &ReadOptions) -> (bool, usize) {
    std::fs::write(path, bytes).unwrap();
    let before = LIVE.load(Ordering::SeqCst);
    PEAK.store(before, Ordering::SeqCst);
    let outcome = std::panic::catch_unwind(|| io::read(path, options).is_ok());
    let peak = PEAK.load(Ordering::SeqCst) - before;
    match outcome {
        Ok(ok) => (ok, peak),
        Err(_) => {
            let kept = path.with_extension(format!("panic.{}", path.extension().unwrap().to_string_lossy()));
            std::fs::copy(path, &kept).unwrap();
            panic!(
                "reading {} panicked (input kept as {})",
                path.display(),
                kept.display()
            );
        }
    }
}

/// A valid small file of each format, to mutate.
fn seeds(dir: &std::path::Path) -> Vec<(&'static str, Vec<u8>)> {
    let grid = Grid::new(6, 5, 1e-5, 1e-5).unwrap();
    let heights = ndarray::Array2::from_shape_fn((5, 6), |(j, i)| 1e-7 * ((i * 7 + j * 3) % 5) as f64);
    let surface = Surface::new(heights, grid, true).unwrap();
    let mut seeds: Vec<(&'static str, Vec<u8>)> = ["npy", "txt", "xyz", "gsf", "x3p", "sdf", "nc"]
        .into_iter()
        .map(|ext| {
            let p = dir.join(format!("seed.{ext}"));
            io::write(&surface, &p, None).unwrap();
            (ext, std::fs::read(&p).unwrap())
        })
        .collect();
    // TrueMap is read only: a 3 x 2 file by hand.
    let mut tmd = b"Binary TrueMap Data File v2.0\r\n\0a comment\r\n\0".to_vec();
    for v in [3u32, 2] {
        tmd.extend(v.to_le_bytes());
    }
    for v in [1.5f32, 1.0, 0.0, 0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6] {
        tmd.extend(v.to_le_bytes());
    }
    seeds.push(("tmd", tmd));
    // A PicoView image by hand: 3 x 2 pixels, one height channel, 16 bits.
    let mut mi =
        b"fileType      Image\nxPixels       3\nyPixels       2\nxLength       1e-6\nyLength       1e-6\n\
bufferLabel   Topography\nbufferRange   1.5\nbufferUnit    um\ndata          BINARY\n"
            .to_vec();
    for v in [1i16, -2, 300, 4000, -5000, 6] {
        mi.extend(v.to_le_bytes());
    }
    seeds.push(("mi", mi));
    // A Nanosurf file by hand: a force channel, then a 3 x 2 height channel, 16 bits.
    let mut nid = b"[DataSet]\nGroupCount=1\nGr0-Count=2\nGr0-Ch0=DataSet-0:0\nGr0-Ch1=DataSet-0:1\n\
[DataSet-0:0]\nPoints=3\nLines=2\nDim2Unit=N\nSaveBits=16\n\
[DataSet-0:1]\nPoints=3\nLines=2\nDim0Range=1e-6\nDim0Unit=m\nDim1Range=1e-6\nDim1Unit=m\n\
Dim2Min=-1e-7\nDim2Range=2e-7\nDim2Unit=m\nSaveBits=16\nSaveSign=Signed\n#!"
        .to_vec();
    for v in [0i16, 1, 2, 3, 4, 5, 10, -20, 300, 4000, -5000, 6] {
        nid.extend(v.to_le_bytes());
    }
    seeds.push(("nid", nid));
    // A Digital Surf surface by hand: the 512-byte header, 3 x 2 points of 16 bits.
    let mut sur = vec![0u8; 512];
    sur[..12].copy_from_slice(b"DIGITAL SURF");
    for (o, v) in [(18, 2i16), (98, 16)] {
        sur[o..o + 2].copy_from_slice(&v.to_le_bytes());
    }
    for (o, v) in [(108, 3i32), (112, 2)] {
        sur[o..o + 4].copy_from_slice(&v.to_le_bytes());
    }
    for (o, v) in [(120, 0.5f32), (124, 0.5), (128, 0.01)] {
        sur[o..o + 4].copy_from_slice(&v.to_le_bytes());
    }
    for o in [180, 196, 212] {
        sur[o..o + 2].copy_from_slice(b"um");
    }
    for v in [1i16, 2, 3, 4, 5, 6] {
        sur.extend(v.to_le_bytes());
    }
    seeds.push(("sur", sur));
    seeds.push(("opd", tiny_opd([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])));
    seeds.push(("di", tiny_di([1, 2, 3, 4, 5, 6])));
    seeds.push(("frt", tiny_frt([2, 3, 1, 5, 6, 7])));
    seeds.push(("mnt", tiny_mnt([1, 2, 3, 4, 5, 6], &[4])));
    // HDF5 as the C library writes it (h5py): the committed sample.
    let h5 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/topography-samples/h5-1.h5");
    seeds.push(("h5", std::fs::read(h5).unwrap()));
    seeds.push(("gwy", tiny_gwy([1e-9, 2e-9, 3e-9, 4e-9, 5e-9, 6e-9], [false; 6])));
    seeds.push((
        "ibw",
        tiny_ibw([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0]),
    ));
    seeds
}

/// One arbitrary input made from a valid file: random bytes, bytes flipped, cut, repeated, or
/// digits put where digits were (sizes in headers grow).
fn mutate(rng: &mut ChaCha8Rng, seed: &[u8]) -> Vec<u8> {
    let mut b = seed.to_vec();
    match rng.random_range(0..6) {
        0 => (0..rng.random_range(0..400)).map(|_| rng.random()).collect(),
        1 => {
            for _ in 0..rng.random_range(1..8) {
                let k = rng.random_range(0..b.len());
                b[k] = rng.random();
            }
            b
        }
        2 => {
            b.truncate(rng.random_range(0..b.len()));
            b
        }
        3 => {
            let k = rng.random_range(0..b.len());
            let tail = b[k..].to_vec();
            b.extend_from_slice(&tail);
            b
        }
        4 => {
            for v in b.iter_mut() {
                if v.is_ascii_digit() && rng.random_bool(0.3) {
                    *v = b'9';
                }
            }
            b
        }
        _ => {
            let k = rng.random_range(0..b.len());
            let alphabet = b"0123456789 .,-e\n\tnaNinf#=";
            let junk: Vec<u8> = (0..rng.random_range(1..40))
                .map(|_| alphabet[rng.random_range(0..alphabet.len())])
                .collect();
            b.splice(k..k, junk);
            b
        }
    }
}

#[test]
fn readers_never_panic_and_allocate_at_most_a_multiple_of_the_file() {
    let dir = std::env::temp_dir().join(format!("surfgen-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Unmeasured points filled, so that the fill is fuzzed too.
    let options = ReadOptions {
        length_x: Some(1e-5),
        unmeasured: io::Unmeasured::FillUpTo(1.0),
        ..Default::default()
    };
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    for (ext, seed) in seeds(&dir) {
        let path = dir.join(format!("fuzz.{ext}"));
        // The box is given only to a file that does not carry it (a bare .npy, the HDF5
        // sample): a size given beside a file's own is refused.
        let own = ReadOptions {
            length_x: None,
            ..options
        };
        let options = if read(&path, &seed, &own).0 { own } else { options };
        assert!(read(&path, &seed, &options).0, ".{ext}: the unmutated file reads");
        let (mut read_ok, mut worst) = (0, 0.0f64);
        for _ in 0..400 {
            let bytes = mutate(&mut rng, &seed);
            let (ok, peak) = read(&path, &bytes, &options);
            read_ok += usize::from(ok);
            // Parsing keeps each number as an f64 (8 bytes from as few as 2 characters), in a
            // growing vector, then in the array: a few dozen bytes per byte of file at most.
            let bound = 64 * bytes.len() + (1 << 20);
            assert!(
                peak <= bound,
                ".{ext}: {peak} bytes allocated reading a {}-byte file",
                bytes.len()
            );
            worst = worst.max(peak as f64 / bytes.len().max(1) as f64);
        }
        println!(
            ".{ext}: 400 inputs, {read_ok} read as surfaces, the rest refused; at most {worst:.0} bytes allocated per byte of file"
        );
    }
}
