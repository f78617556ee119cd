//! Synthetic pictures for simulated cameras, grey, of the declared size: a DC-only baseline
//! JPEG (as the Python runtime's images.jpeg: one DC coefficient per 8x8 block, the standard
//! DC luminance Huffman table, an AC table holding end-of-block only) or a PNG with stored
//! (uncompressed) deflate blocks; other MIME types get raw 8-bit grey (image/x-gray8's layout).
//! The picture is a ramp that moves with `frame`, so successive pictures differ.

const DC_BITS: [u8; 16] = [0, 1, 5, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0];
const DC_QUANT: u8 = 8;

/// The grey level of block (bx, by) (JPEG) or pixel / 8 (others) of a picture.
fn level(bx: usize, by: usize, frame: u32) -> u8 {
    ((bx * 5 + by * 3 + frame as usize * 16) % 200 + 28) as u8
}

struct Bits {
    out: Vec<u8>,
    acc: u32,
    n: u32,
}

impl Bits {
    fn put(&mut self, code: u32, len: u32) {
        for i in (0..len).rev() {
            self.acc = (self.acc << 1) | ((code >> i) & 1);
            self.n += 1;
            if self.n == 8 {
                let b = self.acc as u8;
                self.out.push(b);
                if b == 0xFF {
                    self.out.push(0); // byte stuffing
                }
                self.acc = 0;
                self.n = 0;
            }
        }
    }
    fn finish(mut self) -> Vec<u8> {
        while self.n != 0 {
            self.put(1, 1); // pad with 1s
        }
        self.out
    }
}

fn segment(out: &mut Vec<u8>, marker: u8, body: &[u8]) {
    out.extend_from_slice(&[0xFF, marker]);
    out.extend_from_slice(&((body.len() + 2) as u16).to_be_bytes());
    out.extend_from_slice(body);
}

/// DC Huffman codes (category -> (code, length)) from DC_BITS, values 0..11 in order.
fn dc_codes() -> [(u32, u32); 12] {
    let mut codes = [(0u32, 0u32); 12];
    let (mut code, mut k) = (0u32, 0usize);
    for (i, count) in DC_BITS.iter().enumerate() {
        for _ in 0..*count {
            codes[k] = (code, i as u32 + 1);
            code += 1;
            k += 1;
        }
        code <<= 1;
    }
    codes
}

pub fn jpeg(width: u16, height: u16, frame: u32) -> Vec<u8> {
    let codes = dc_codes();
    let mut bits = Bits { out: Vec::new(), acc: 0, n: 0 };
    let (bw, bh) = ((width as usize).div_ceil(8), (height as usize).div_ceil(8));
    let mut pred = 0i32;
    for by in 0..bh {
        for bx in 0..bw {
            let dc = level(bx, by, frame) as i32 - 128;
            let diff = dc - pred;
            pred = dc;
            let cat = 32 - diff.unsigned_abs().leading_zeros();
            let (code, len) = codes[cat as usize];
            bits.put(code, len);
            if cat > 0 {
                let extra = if diff > 0 { diff } else { diff + (1 << cat) - 1 };
                bits.put(extra as u32, cat);
            }
            bits.put(0, 1); // end of block: the AC table's only code, "0"
        }
    }
    let mut out = vec![0xFF, 0xD8];
    segment(&mut out, 0xE0, b"JFIF\x00\x01\x01\x00\x00\x01\x00\x01\x00\x00");
    let mut quant = vec![0u8, DC_QUANT];
    quant.extend([16u8; 63]);
    segment(&mut out, 0xDB, &quant);
    let mut sof = vec![8u8];
    sof.extend_from_slice(&height.to_be_bytes());
    sof.extend_from_slice(&width.to_be_bytes());
    sof.extend_from_slice(&[1, 1, 0x11, 0]);
    segment(&mut out, 0xC0, &sof);
    let mut dht = vec![0x00];
    dht.extend_from_slice(&DC_BITS);
    dht.extend(0u8..12);
    segment(&mut out, 0xC4, &dht);
    let mut ac = vec![0x10, 1];
    ac.extend([0u8; 15]);
    ac.push(0x00);
    segment(&mut out, 0xC4, &ac);
    segment(&mut out, 0xDA, &[1, 1, 0x00, 0x00, 0x3F, 0x00]);
    out.extend(bits.finish());
    out.extend_from_slice(&[0xFF, 0xD9]);
    out
}

fn crc32(data: &[u8]) -> u32 {
    let mut crc = 0xFFFF_FFFFu32;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], body: &[u8]) {
    out.extend_from_slice(&(body.len() as u32).to_be_bytes());
    let start = out.len();
    out.extend_from_slice(kind);
    out.extend_from_slice(body);
    let crc = crc32(&out[start..]);
    out.extend_from_slice(&crc.to_be_bytes());
}

fn grey_rows(width: usize, height: usize, frame: u32, filter_byte: bool) -> Vec<u8> {
    let mut raw = Vec::with_capacity((width + 1) * height);
    for y in 0..height {
        if filter_byte {
            raw.push(0);
        }
        raw.extend((0..width).map(|x| level(x / 8, y / 8, frame)));
    }
    raw
}

pub fn png(width: u32, height: u32, frame: u32) -> Vec<u8> {
    let raw = grey_rows(width as usize, height as usize, frame, true);
    let mut z = vec![0x78, 0x01];
    let blocks: Vec<&[u8]> = raw.chunks(65535).collect();
    for (i, b) in blocks.iter().enumerate() {
        z.push(u8::from(i + 1 == blocks.len()));
        z.extend_from_slice(&(b.len() as u16).to_le_bytes());
        z.extend_from_slice(&(!(b.len() as u16)).to_le_bytes());
        z.extend_from_slice(b);
    }
    let (mut a, mut b) = (1u32, 0u32);
    for &x in &raw {
        a = (a + x as u32) % 65521;
        b = (b + a) % 65521;
    }
    z.extend_from_slice(&((b << 16) | a).to_be_bytes());
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = width.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
    chunk(&mut out, b"IHDR", &ihdr);
    chunk(&mut out, b"IDAT", &z);
    chunk(&mut out, b"IEND", &[]);
    out
}

/// A picture of `mime` (image/jpeg, image/png; anything else raw grey) of width x height
/// (clamped to 1..=8192 a side).
pub fn synthetic(mime: &str, width: i32, height: i32, frame: u32) -> Vec<u8> {
    let (w, h) = (width.clamp(1, 8192), height.clamp(1, 8192));
    match mime.to_ascii_lowercase().as_str() {
        "image/jpeg" | "image/jpg" | "image/pjpeg" => jpeg(w as u16, h as u16, frame),
        "image/png" => png(w as u32, h as u32, frame),
        _ => grey_rows(w as usize, h as usize, frame, false),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_checksums() {
        // the CRC of "IEND" alone is fixed by the PNG specification
        assert_eq!(crc32(b"IEND"), 0xAE42_6082);
        let p = png(3, 2, 0);
        assert_eq!(&p[..8], b"\x89PNG\r\n\x1a\n");
        assert!(p.ends_with(&[0xAE, 0x42, 0x60, 0x82]));
    }

    #[test]
    fn jpeg_frame() {
        let j = jpeg(20, 10, 1);
        assert_eq!(&j[..2], &[0xFF, 0xD8]);
        assert_eq!(&j[j.len() - 2..], &[0xFF, 0xD9]);
        assert_ne!(j, jpeg(20, 10, 2));
    }
}
