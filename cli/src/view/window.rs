//! The window: minifb's X11 window, its keys and mouse read once a frame, and the framebuffer
//! shown in it with the status line on top. Everything that needs a display is here.

use std::cell::RefCell;
use std::rc::Rc;

use minifb::{InputCallback, Key, MouseButton, MouseMode, Window, WindowOptions};
use refrast::pipeline::Framebuffer;

use super::overlay::{status_line, to_0rgb};

/// An open window and what it shows.
pub struct Screen {
    window: Window,
    /// The last frame shown, 0RGB.
    pixels: Vec<u32>,
    /// Where the mouse was last frame while the left button was held.
    drag_from: Option<(f32, f32)>,
    /// Keys pressed since the last frame, in order, as the window's callback saw them.
    presses: Rc<RefCell<Presses>>,
}

/// Every key press, however short: a press and its release that arrive between two frames
/// leave no trace in minifb's key states, but they pass through its callback.
#[derive(Default)]
struct Presses {
    keys: Vec<Key>,
    down: Vec<Key>,
}

/// The window's callback, sharing [`Presses`] with the [`Screen`].
struct Recorder(Rc<RefCell<Presses>>);

impl InputCallback for Recorder {
    fn add_char(&mut self, _: u32) {}

    fn set_key_state(&mut self, key: Key, down: bool) {
        let mut p = self.0.borrow_mut();
        // The keyboard's auto-repeat sends presses without releases: only the first counts.
        if down && !p.down.contains(&key) {
            p.down.push(key);
            p.keys.push(key);
        } else if !down {
            p.down.retain(|&k| k != key);
        }
    }
}

/// Why no window could be opened, in one line that says how to get one.
#[must_use]
pub fn no_display(display: Option<&str>, why: &str) -> String {
    match display {
        None | Some("") => "no display to open a window on: DISPLAY is not set; run refrast view \
                            in a desktop session, or under a virtual X server (xvfb-run refrast view ...)"
            .to_owned(),
        Some(d) => format!(
            "could not open a window on DISPLAY={d} ({why}); is an X server running there? \
             (Wayland desktops need XWayland; without a screen, use xvfb-run)"
        ),
    }
}

impl Screen {
    /// Opens a resizable window of `width`×`height` titled `title`; without a display, says so.
    pub fn open(title: &str, width: usize, height: usize) -> Result<Self, String> {
        let display = std::env::var("DISPLAY").ok();
        if display.as_deref().unwrap_or("").is_empty() {
            return Err(no_display(None, ""));
        }
        let options = WindowOptions {
            resize: true,
            ..WindowOptions::default()
        };
        let mut window = Window::new(title, width, height, options)
            .map_err(|e| no_display(display.as_deref(), &e.to_string()))?;
        // The loop paces itself (and `--frames` measures unpaced); minifb's own 4 ms limit would
        // hide the frame time.
        window.set_target_fps(0);
        let presses = Rc::new(RefCell::new(Presses::default()));
        window.set_input_callback(Box::new(Recorder(Rc::clone(&presses))));
        Ok(Self {
            window,
            pixels: Vec::new(),
            drag_from: None,
            presses,
        })
    }

    /// Whether the window is still open (closing it ends the viewer).
    #[must_use]
    pub fn is_open(&self) -> bool {
        self.window.is_open()
    }

    /// The window's inner size in pixels.
    #[must_use]
    pub fn size(&self) -> (usize, usize) {
        self.window.get_size()
    }

    /// The keys pressed since the last frame, in order, without the keyboard's auto-repeat.
    pub fn pressed(&mut self) -> Vec<Key> {
        std::mem::take(&mut self.presses.borrow_mut().keys)
    }

    /// Whether `key` is held down.
    #[must_use]
    pub fn held(&self, key: Key) -> bool {
        self.window.is_key_down(key)
    }

    /// How far the mouse moved since the last frame while the left button was held, in pixels.
    pub fn drag(&mut self) -> (f32, f32) {
        let now = self
            .window
            .get_mouse_down(MouseButton::Left)
            .then(|| self.window.get_mouse_pos(MouseMode::Pass))
            .flatten();
        let delta = match (self.drag_from, now) {
            (Some((x0, y0)), Some((x1, y1))) => (x1 - x0, y1 - y0),
            _ => (0.0, 0.0),
        };
        self.drag_from = now;
        delta
    }

    /// Shows `target` with `status` written across its top, and reads the input for the next frame.
    pub fn show(&mut self, target: &Framebuffer, status: &str) -> Result<(), String> {
        let (width, height) = (
            target.viewport().width() as usize,
            target.viewport().height() as usize,
        );
        to_0rgb(target.color(), &mut self.pixels);
        status_line(&mut self.pixels, width, status);
        self.window
            .update_with_buffer(&self.pixels, width, height)
            .map_err(|e| format!("could not show the frame: {e}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_press_counts_once_however_short_or_long() {
        let presses = Rc::new(RefCell::new(Presses::default()));
        let mut callback = Recorder(Rc::clone(&presses));
        // P tapped within one frame; I held with two auto-repeats; P again.
        for (key, down) in [
            (Key::P, true),
            (Key::P, false),
            (Key::I, true),
            (Key::I, true),
            (Key::I, true),
        ] {
            callback.set_key_state(key, down);
        }
        callback.set_key_state(Key::I, false);
        callback.set_key_state(Key::P, true);
        assert_eq!(presses.borrow().keys, vec![Key::P, Key::I, Key::P]);
        assert_eq!(presses.borrow().down, vec![Key::P]);
    }

    #[test]
    fn no_display_says_how_to_get_one() {
        let unset = no_display(None, "");
        assert!(
            unset.contains("DISPLAY is not set") && unset.contains("xvfb-run"),
            "{unset}"
        );
        assert!(!unset.contains('\n'));
        let failed = no_display(Some(":42"), "XOpenDisplay failed");
        assert!(
            failed.contains("DISPLAY=:42") && failed.contains("XOpenDisplay failed"),
            "{failed}"
        );
    }
}
