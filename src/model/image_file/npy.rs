//! A float32 image → a NumPy `.npy` file (format 1.0): the renderer's `f32` depth, and every
//! WebDataset sample's depth member, written the same way.

/// A NumPy `.npy` (format 1.0) of little-endian float32, shape `(height, width)`, C order
/// (`values` row by row): `numpy.load` reads it.
pub fn npy_f32(width: u32, height: u32, values: &[f32]) -> Vec<u8> {
    let mut header =
        format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({height}, {width}), }}");
    // Magic (6) + version (2) + length (2) + header + '\n' is a multiple of 64.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + values.len() * 4);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}
