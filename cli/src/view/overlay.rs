//! The status lines: text in refrast's 8×8 font on a darkened band across the top of the
//! window, drawn into the pixels shown (never into the framebuffer that `P` saves).

use refrast_render::shapes::glyph;

/// Lines of text on the band.
const LINES: usize = 2;

/// Rows of the band at the top of the window that the status lines darken and write on: two
/// lines of 8 px, 2 px apart and around; the picture below it is the framebuffer's, untouched
/// (scripts/check_viewer.py compares below it).
pub const BAND: usize = 2 + LINES * 10;

/// The text's colour, 0RGB.
const INK: u32 = 0x00ff_ffff;

/// Darkens the top [`BAND`] rows of `pixels` (0RGB, `width` wide) and writes the first two
/// lines of `text` on them, cut at the right edge.
pub fn status_line(pixels: &mut [u32], width: usize, text: &str) {
    let rows = BAND.min(pixels.len() / width.max(1));
    for p in &mut pixels[..rows * width] {
        // A quarter of each channel: the picture still shows through, the text stands out.
        *p = (*p >> 2) & 0x003f_3f3f;
    }
    for (line, text) in text.lines().take(LINES).enumerate() {
        let (left, top) = (4, 2 + 10 * line);
        for (i, ch) in text.chars().enumerate() {
            let x0 = left + 8 * i;
            if x0 >= width {
                break;
            }
            for (dy, bits) in glyph(ch).into_iter().enumerate() {
                let y = top + dy;
                if y >= rows {
                    break;
                }
                for dx in (0..8).filter(|dx| bits & (1 << dx) != 0) {
                    if x0 + dx < width {
                        pixels[y * width + x0 + dx] = INK;
                    }
                }
            }
        }
    }
}

/// The framebuffer's RGBA pixels as the 0RGB words a window shows, into `out`.
pub fn to_0rgb(color: &[[u8; 4]], out: &mut Vec<u32>) {
    out.clear();
    out.extend(
        color
            .iter()
            .map(|&[r, g, b, _]| (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b)),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_text_on_a_dark_band_and_leaves_the_rest() {
        let (w, h) = (40, 30);
        let mut pixels = vec![0x00c0_c0c0; w * h];
        status_line(&mut pixels, w, "I\nI\nthird line not drawn");
        // Above the band's text: darkened; below the band: untouched.
        assert_eq!(pixels[0], 0x0030_3030);
        assert!(pixels[BAND * w..].iter().all(|&p| p == 0x00c0_c0c0));
        // Each 'I' is lit somewhere in its cell, and nowhere past it.
        let lit = |x: usize, y: usize| pixels[y * w + x] == INK;
        assert!((2..10).any(|y| (4..12).any(|x| lit(x, y))));
        assert!((12..20).any(|y| (4..12).any(|x| lit(x, y))));
        assert!(!(0..BAND).any(|y| (12..w).any(|x| lit(x, y))));
    }

    #[test]
    fn a_window_smaller_than_the_band_or_the_text_is_fine() {
        let mut tiny = vec![0u32; 3 * 2];
        status_line(&mut tiny, 3, "a long status line");
        assert!(tiny.iter().all(|&p| p == 0 || p == INK));
        let mut out = Vec::new();
        to_0rgb(&[[1, 2, 3, 255], [255, 0, 128, 0]], &mut out);
        assert_eq!(out, vec![0x0001_0203, 0x00ff_0080]);
    }
}
