//! The viewer's key bindings: which held keys move the camera and which presses act, one table
//! that the loop, the help text and docs/render.md share.

use minifb::Key;
use refrast_render::Mode;

use super::camera::Motion;

/// What a key press does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// Show this mode (number keys 1 to 7, in [`Mode::ALL`]'s order).
    Mode(Mode),
    /// Draw with the next implementation of the cycle.
    NextImpl,
    /// Switch culling between none and back faces (or the scene's own choice).
    ToggleCull,
    /// Switch between one sample per pixel and four (box-filtered).
    ToggleSamples,
    /// Make the movement keys move the light instead of the camera, or back.
    ToggleLight,
    /// Write the picture to a PNG.
    Save,
    /// Put the camera back where it started.
    Reset,
    /// Close the viewer.
    Quit,
}

/// The action of a press of `key`, if it has one.
#[must_use]
pub fn action(key: Key) -> Option<Action> {
    let mode = |i: usize| Some(Action::Mode(Mode::ALL[i]));
    match key {
        Key::Key1 | Key::NumPad1 => mode(0),
        Key::Key2 | Key::NumPad2 => mode(1),
        Key::Key3 | Key::NumPad3 => mode(2),
        Key::Key4 | Key::NumPad4 => mode(3),
        Key::Key5 | Key::NumPad5 => mode(4),
        Key::Key6 | Key::NumPad6 => mode(5),
        Key::Key7 | Key::NumPad7 => mode(6),
        Key::I => Some(Action::NextImpl),
        Key::C => Some(Action::ToggleCull),
        Key::M => Some(Action::ToggleSamples),
        Key::L => Some(Action::ToggleLight),
        Key::P => Some(Action::Save),
        Key::R => Some(Action::Reset),
        Key::Escape => Some(Action::Quit),
        _ => None,
    }
}

/// How the held keys want the camera (or the light) to move; `held` says whether a key is down.
#[must_use]
pub fn motion(held: impl Fn(Key) -> bool) -> Motion {
    let axis = |plus: Key, minus: Key| f32::from(u8::from(held(plus))) - f32::from(u8::from(held(minus)));
    Motion {
        forward: axis(Key::W, Key::S),
        right: axis(Key::D, Key::A),
        up: axis(Key::E, Key::Q),
        yaw: axis(Key::Right, Key::Left),
        pitch: axis(Key::Up, Key::Down),
    }
}

/// The bindings as `(keys, what they do)`: printed when the window opens, and docs/render.md's table.
pub const HELP: [(&str, &str); 12] = [
    ("W A S D", "move forward, left, back, right"),
    ("Q E", "move down, up"),
    ("← → ↑ ↓", "yaw and pitch the camera"),
    ("mouse drag", "look around while the left button is held"),
    (
        "1 … 7",
        "points, wire, fill, depth, normals, barycentric, overdraw",
    ),
    ("I", "next implementation (reference, fast, course labs, mutants)"),
    ("C", "culling on or off"),
    ("M", "4 samples per pixel on or off (box-filtered)"),
    (
        "L",
        "the movement keys move the light instead (again: the camera)",
    ),
    ("P", "save the picture as a PNG (without the status lines)"),
    ("R", "camera back to the start"),
    ("Esc", "quit (as does closing the window)"),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_keys_pick_the_modes_in_order() {
        let row = [
            Key::Key1,
            Key::Key2,
            Key::Key3,
            Key::Key4,
            Key::Key5,
            Key::Key6,
            Key::Key7,
        ];
        for (key, mode) in row.into_iter().zip(Mode::ALL) {
            assert_eq!(action(key), Some(Action::Mode(mode)));
        }
        assert_eq!(action(Key::NumPad7), Some(Action::Mode(Mode::Overdraw)));
        assert_eq!(action(Key::Key8), None);
    }

    #[test]
    fn letters_act() {
        assert_eq!(action(Key::I), Some(Action::NextImpl));
        assert_eq!(action(Key::C), Some(Action::ToggleCull));
        assert_eq!(action(Key::L), Some(Action::ToggleLight));
        assert_eq!(action(Key::P), Some(Action::Save));
        assert_eq!(action(Key::M), Some(Action::ToggleSamples));
        assert_eq!(action(Key::Escape), Some(Action::Quit));
        // Movement keys are held, not pressed: they have no action.
        assert_eq!(action(Key::W), None);
        assert_eq!(action(Key::Left), None);
    }

    #[test]
    fn the_render_page_shows_every_binding() {
        let page = include_str!("../../../docs/render.md");
        for (keys, what) in HELP {
            let row = format!("| {keys} | {what} |");
            assert!(page.contains(&row), "docs/render.md lacks the row {row}");
        }
    }

    #[test]
    fn held_keys_become_a_motion() {
        assert!(motion(|_| false).is_still());
        let m = motion(|k| matches!(k, Key::W | Key::A | Key::Right | Key::Down));
        assert_eq!(
            m,
            Motion {
                forward: 1.0,
                right: -1.0,
                up: 0.0,
                yaw: 1.0,
                pitch: -1.0
            }
        );
        // Opposite keys together cancel.
        assert!(motion(|k| matches!(k, Key::W | Key::S | Key::Q | Key::E)).is_still());
    }
}
