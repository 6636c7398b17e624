//! Colour bars: a strip of the colour map with the value range written at its ends, appended
//! below a picture so that coloured meshes and slices can be read. O(width × bar height).

use super::colormap::Colormap;
use super::font::{draw_text, text_height, text_width};
use super::Image;

/// Compact number for labels: up to 4 significant digits, scientific outside 1e-3..1e5.
pub fn label_num(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        format!("{v:.2e}")
    } else {
        let dec = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{v:.dec$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    }
}

/// Height in pixels that [`with_colorbar`] adds.
pub const BAR_BAND: u32 = 8 + 12 + 6 + 14 + 8;

/// `img` with a colour bar of `colormap` over `[lo, hi]` appended at the bottom (on the
/// image's background taken from its top-left pixel), `lo` written at the left end, `hi` at the
/// right end and `name` (if any) in the middle.
pub fn with_colorbar(
    img: &Image,
    colormap: Colormap,
    lo: f64,
    hi: f64,
    name: Option<&str>,
) -> Image {
    let bg = if img.rgba.len() >= 4 {
        [img.rgba[0], img.rgba[1], img.rgba[2], img.rgba[3]]
    } else {
        [255; 4]
    };
    let w = img.width.max(1);
    let mut out = Image::new(w, img.height + BAR_BAND, bg);
    out.rgba[..img.rgba.len()].copy_from_slice(&img.rgba);
    let margin = (w / 40).clamp(2, 12).min(w / 2);
    let bw = w.saturating_sub(2 * margin).max(1);
    let y0 = img.height + 8;
    for bx in 0..bw {
        let c = colormap.color((bx as f64 + 0.5) / bw as f64);
        for by in 0..12 {
            let x = (margin + bx).min(w - 1);
            out.put(x, y0 + by, [c[0], c[1], c[2], 255]);
        }
    }
    let ink = [0, 0, 0, 255];
    let scale = 2;
    let ty = (y0 + 12 + 6) as i64;
    draw_text(&mut out, margin as i64, ty, &label_num(lo), scale, ink);
    let hs = label_num(hi);
    let hw = text_width(&hs, scale) as i64;
    draw_text(&mut out, w as i64 - margin as i64 - hw, ty, &hs, scale, ink);
    if let Some(n) = name {
        let nw = text_width(n, scale) as i64;
        draw_text(&mut out, (w as i64 - nw) / 2, ty, n, scale, ink);
    }
    debug_assert_eq!(text_height(scale), 14);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn label_numbers() {
        assert_eq!(label_num(12.0), "12");
        assert_eq!(label_num(0.25), "0.25");
        assert_eq!(label_num(-3.25159), "-3.252");
        assert_eq!(label_num(1e-7), "1.00e-7");
        assert_eq!(label_num(0.0), "0");
    }

    #[test]
    fn bar_is_appended() {
        let img = Image::new(100, 50, [255, 255, 255, 255]);
        let out = with_colorbar(&img, Colormap::Greys, 0.0, 1.0, Some("z"));
        assert_eq!((out.width, out.height), (100, 50 + BAR_BAND));
        assert_eq!(out.get(5, 10), [255; 4]);
        // Left end of the bar is black, right end white-ish.
        let l = out.get(3, 50 + 8 + 5);
        let r = out.get(96, 50 + 8 + 5);
        assert!(l[0] < 10 && r[0] > 245, "{l:?} {r:?}");
        // Tiny image: no panic.
        let _ = with_colorbar(
            &Image::new(1, 1, [0; 4]),
            Colormap::Viridis,
            0.0,
            1.0,
            Some("long name"),
        );
    }
}
