//! The can label of Fig. 6 (`raytrace make-label`, shipped as `tools/render/assets/label.png`).

use crate::font;

/// The can label the project ships in `tools/render/assets/label.png`: a red soda-can wrap with a
/// white wave, the name in a bitmap font, and a few iridescent-looking stripes.
pub fn make_label() -> image::RgbImage {
    let (w, h) = (512u32, 256u32);
    let mut img = image::RgbImage::new(w, h);
    for (x, y, px) in img.enumerate_pixels_mut() {
        let (fx, fy) = (x as f64 / w as f64, y as f64 / h as f64);
        // Deep red with a slight vertical gradient.
        let shade = 0.8 + 0.2 * (1.0 - (fy - 0.4).abs() * 2.0);
        let mut c = [200.0 * shade, 24.0 * shade, 32.0 * shade];
        // A white wave band through the middle.
        let wave = 0.6 + 0.06 * (fx * std::f64::consts::TAU * 2.0).sin();
        if (fy - wave).abs() < 0.035 {
            c = [245.0, 245.0, 240.0];
        }
        // Thin gold rims top and bottom.
        if !(0.05..=0.95).contains(&fy) {
            c = [210.0, 170.0, 60.0];
        }
        // Rainbow stripes (a nod to the subject) on the right half.
        if (0.37..0.63).contains(&fx) && (0.83..0.9).contains(&fy) {
            let hue = (fx - 0.37) / 0.26 * 0.8;
            let rgb = hue_to_rgb(hue);
            c = [rgb[0] * 255.0, rgb[1] * 255.0, rgb[2] * 255.0];
        }
        *px = image::Rgb([c[0] as u8, c[1] as u8, c[2] as u8]);
    }
    // Centred, so that the middle of the image faces +z on an unrotated cylinder; narrow,
    // since the camera sees less than half of the circumference.
    let centred = |text: &str, scale: u32| (w - font::text_width(text, scale).min(w)) / 2;
    font::draw_text(&mut img, "AGU", centred("AGU", 6), 22, 6, [255, 240, 220]);
    font::draw_text(&mut img, "HILL", centred("HILL", 6), 74, 6, [255, 240, 220]);
    font::draw_text(
        &mut img,
        "DIFFRACTION",
        centred("DIFFRACTION", 2),
        182,
        2,
        [255, 255, 255],
    );
    img
}

/// A fully saturated hue, h in [0, 1): red, yellow, green, cyan, blue, magenta.
fn hue_to_rgb(h: f64) -> [f64; 3] {
    let h6 = h.rem_euclid(1.0) * 6.0;
    let x = 1.0 - (h6 % 2.0 - 1.0).abs();
    match h6 as u32 {
        0 => [1.0, x, 0.0],
        1 => [x, 1.0, 0.0],
        2 => [0.0, 1.0, x],
        3 => [0.0, x, 1.0],
        4 => [x, 0.0, 1.0],
        _ => [1.0, 0.0, x],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn the_shipped_label_is_the_generated_one() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/label.png");
        let shipped = image::open(&path).expect("assets/label.png").to_rgb8();
        assert_eq!(
            shipped,
            make_label(),
            "run `cargo run -p diffraction-render --bin raytrace -- make-label`"
        );
    }
}
