//! The minimal examples' image output: an 8-bit RGB PNG (RFC 2083) whose image data sits in
//! stored (uncompressed) deflate blocks (RFC 1951), so that the examples need no image crate,
//! and a write that never destroys an existing file when it fails.

use std::path::Path;

pub fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 == 1 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

pub fn adler32(bytes: &[u8]) -> u32 {
    let (mut a, mut b) = (1u32, 0u32);
    for &x in bytes {
        a = (a + x as u32) % 65521;
        b = (b + a) % 65521;
    }
    (b << 16) | a
}

fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend_from_slice(&(data.len() as u32).to_be_bytes());
    let start = out.len();
    out.extend_from_slice(kind);
    out.extend_from_slice(data);
    let crc = crc32(&out[start..]);
    out.extend_from_slice(&crc.to_be_bytes());
}

/// A PNG of `width`×`height` RGB pixels (row-major, 3 bytes a pixel).
pub fn png(width: usize, height: usize, rgb: &[u8]) -> Vec<u8> {
    let mut raw = Vec::with_capacity((3 * width + 1) * height);
    for row in rgb.chunks(3 * width) {
        raw.push(0); // filter: none
        raw.extend_from_slice(row);
    }
    let mut z = vec![0x78, 0x01]; // zlib header: deflate, 32 KiB window, no dictionary
    let blocks = raw.chunks(65535).count(); // raw has a filter byte a row: never empty
    for (i, block) in raw.chunks(65535).enumerate() {
        z.push((i + 1 == blocks) as u8); // BFINAL, BTYPE = 00 (stored)
        let len = block.len() as u16;
        z.extend_from_slice(&len.to_le_bytes());
        z.extend_from_slice(&(!len).to_le_bytes());
        z.extend_from_slice(block);
    }
    z.extend_from_slice(&adler32(&raw).to_be_bytes());
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut header = Vec::new();
    header.extend_from_slice(&(width as u32).to_be_bytes());
    header.extend_from_slice(&(height as u32).to_be_bytes());
    header.extend_from_slice(&[8, 2, 0, 0, 0]); // 8 bits, RGB, deflate, adaptive, no interlace
    chunk(&mut out, b"IHDR", &header);
    chunk(&mut out, b"IDAT", &z);
    chunk(&mut out, b"IEND", &[]);
    out
}

/// Writes the PNG of `rgb` to `path` through a temporary file beside it, renamed over `path`
/// once complete: a failed write leaves an existing `path` as it was.
pub fn write(path: &Path, width: usize, height: usize, rgb: &[u8]) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    let tmp = Path::new(&tmp);
    let result =
        std::fs::write(tmp, png(width, height, rgb)).and_then(|()| std::fs::rename(tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The check values of the PNG specification's CRC (the IEND chunk's, fixed by RFC 2083)
    /// and of Adler-32 (RFC 1950's definition, "Wikipedia" → 0x11E60398).
    #[test]
    fn checksums_match_their_specifications() {
        assert_eq!(crc32(b"IEND"), 0xAE42_6082);
        assert_eq!(adler32(b"Wikipedia"), 0x11E6_0398);
        let p = png(2, 1, &[255, 0, 0, 0, 0, 255]);
        assert_eq!(&p[..8], b"\x89PNG\r\n\x1a\n");
        assert_eq!(&p[p.len() - 8..p.len() - 4], b"IEND");
    }

    /// A write into a missing folder fails and leaves nothing; one over an existing file
    /// replaces it whole.
    #[test]
    fn a_failed_write_leaves_the_old_file() {
        let dir = std::env::temp_dir().join(format!("diffraction-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.png");
        std::fs::write(&path, b"old").unwrap();
        // A directory where the temporary file would go: the write fails.
        std::fs::create_dir_all(dir.join("a.png.partial")).unwrap();
        assert!(write(&path, 1, 1, &[1, 2, 3]).is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        std::fs::remove_dir(dir.join("a.png.partial")).unwrap();
        write(&path, 1, 1, &[1, 2, 3]).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), png(1, 1, &[1, 2, 3]));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
