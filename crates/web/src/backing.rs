//! The canvas drawn at the device's pixel ratio.
//!
//! eframe sizes the canvas's backing store from the browser's `devicePixelContentBoxSize` and
//! lays out at `devicePixelRatio` pixels a point. Where the two disagree — Chromium's emulated
//! device scale (DevTools' device mode, an automated browser's `deviceScaleFactor`) reports the
//! content box in CSS pixels while `devicePixelRatio` is 2 or 3 — the canvas kept its CSS size and
//! the editor laid out in half or a third of the width: a laptop got the phone layout, blurred.
//! Each frame the backing store is checked against the CSS size × `devicePixelRatio` and set
//! again when it is off by more than rounding (a fractional ratio snaps to device pixels
//! differently: a pixel or two is left to the browser's own answer).

/// How many device pixels the backing store may differ from CSS size × ratio before it is set.
#[cfg(target_arch = "wasm32")]
const SLACK: u32 = 2;

/// The backing size the canvas should have: its CSS size × `devicePixelRatio`, rounded.
pub fn device_size(css: (i32, i32), ratio: f64) -> (u32, u32) {
    let scale = |v: i32| (f64::from(v.max(0)) * ratio).round() as u32;
    (scale(css.0), scale(css.1))
}

/// Sets the canvas's backing store to its CSS size × `devicePixelRatio` when the browser left it
/// elsewhere; returns whether it did (the next frame lays out at the new size).
#[cfg(target_arch = "wasm32")]
pub fn keep_device_pixels(ctx: &egui::Context) -> bool {
    use wasm_bindgen::JsCast;
    let Some(window) = web_sys::window() else {
        return false;
    };
    let Some(canvas) = window
        .document()
        .and_then(|d| d.get_element_by_id("cnets"))
        .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
    else {
        return false;
    };
    let (w, h) = device_size(
        (canvas.client_width(), canvas.client_height()),
        window.device_pixel_ratio(),
    );
    if w == 0 || h == 0 {
        return false;
    }
    let off = |a: u32, b: u32| a.abs_diff(b) > SLACK;
    if !(off(canvas.width(), w) || off(canvas.height(), h)) {
        return false;
    }
    canvas.set_width(w);
    canvas.set_height(h);
    ctx.request_repaint();
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_backing_size_is_the_css_size_times_the_ratio() {
        assert_eq!(device_size((1400, 860), 2.0), (2800, 1720));
        assert_eq!(device_size((390, 844), 3.0), (1170, 2532));
        assert_eq!(device_size((1001, 3), 1.25), (1251, 4));
        assert_eq!(device_size((-5, 10), 2.0), (0, 20));
    }
}
