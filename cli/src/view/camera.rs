//! The viewer's camera: an eye that flies and turns by yaw and pitch, as the labs' cameras do
//! (seed 002 turns about the vertical axis by yaw, seed 000 moves and rotates its camera each
//! update), kept apart from the window so that it is tested without one.

use glam::Vec3;
use refrast::camera::Camera;
use refrast_render::scene::Framed;
use refrast_render::{Lens, View};

/// How far from straight up or down the camera may pitch, so that it never looks along the up axis.
const MAX_PITCH: f32 = 89.0_f32 * std::f32::consts::PI / 180.0;

/// How the keys held in one frame want the camera to move, each component in `[-1, 1]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Motion {
    /// Along the view direction (W, S).
    pub forward: f32,
    /// Sideways (D, A).
    pub right: f32,
    /// Along the world's up (E, Q).
    pub up: f32,
    /// Turn right (→) or left (←).
    pub yaw: f32,
    /// Tilt up (↑) or down (↓).
    pub pitch: f32,
}

impl Motion {
    /// Whether nothing is held.
    #[cfg(test)]
    #[must_use]
    pub fn is_still(&self) -> bool {
        *self == Self::default()
    }
}

/// An eye with a yaw and a pitch, in refrast's left-handed world: y up, yaw 0 looks along +z.
///
/// Built on refrast's [`Camera`] ([`FlyCamera::pose`]); it keeps yaw and pitch instead of a
/// direction so that turns add up and the pitch is held short of straight up or down.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    /// Where the eye is.
    pub eye: Vec3,
    /// Turn about +y, radians; positive turns towards +x.
    pub yaw: f32,
    /// Tilt, radians; positive looks up.
    pub pitch: f32,
    /// The lens and planes of the view the camera started from.
    lens: Lens,
    near: f32,
    far: f32,
    /// World units per second for moving, radians per second for turning.
    speed: f32,
    turn_speed: f32,
}

impl FlyCamera {
    /// The camera of `view`, moving `speed` world units a second (scaled to the scene so that
    /// a room and a mesh ten thousand units wide take about as long to cross).
    #[must_use]
    pub fn new(view: &View, speed: f32) -> Self {
        let d = (view.target - view.eye).normalize_or(Vec3::Z);
        Self {
            eye: view.eye,
            yaw: d.x.atan2(d.z),
            pitch: d.y.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH, MAX_PITCH),
            lens: view.lens,
            near: view.near,
            far: view.far,
            speed,
            turn_speed: 90f32.to_radians(),
        }
    }

    /// Where the eye is and which way it looks, as refrast's camera.
    #[must_use]
    pub fn pose(&self) -> Camera {
        Camera::from_yaw_pitch(self.eye, self.yaw, self.pitch)
    }

    /// The unit vector the eye looks along.
    #[must_use]
    pub fn forward(&self) -> Vec3 {
        self.pose().forward
    }

    /// The unit vector to the eye's right, level with the ground (left-handed: up × forward).
    #[must_use]
    pub fn right(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        Vec3::new(cy, 0.0, -sy)
    }

    /// Moves and turns the camera as `motion` asks for `dt` seconds.
    pub fn update(&mut self, motion: &Motion, dt: f32) {
        self.eye += self.displacement(motion, dt);
        self.steer(motion, dt);
    }

    /// Turns the camera as `motion`'s yaw and pitch ask for `dt` seconds, without moving it.
    pub fn steer(&mut self, motion: &Motion, dt: f32) {
        self.turn(
            motion.yaw * self.turn_speed * dt,
            motion.pitch * self.turn_speed * dt,
        );
    }

    /// Where `motion` held for `dt` seconds takes a point: forward, sideways and up as the camera sees them.
    #[must_use]
    pub fn displacement(&self, motion: &Motion, dt: f32) -> Vec3 {
        let step = self.speed * dt;
        (self.forward() * motion.forward + self.right() * motion.right + Vec3::Y * motion.up) * step
    }

    /// Turns by `yaw` and `pitch` radians, the pitch held short of straight up or down.
    pub fn turn(&mut self, yaw: f32, pitch: f32) {
        self.yaw = (self.yaw + yaw).rem_euclid(std::f32::consts::TAU);
        self.pitch = (self.pitch + pitch).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// The view from the eye, one unit ahead.
    #[must_use]
    pub fn view(&self) -> View {
        View {
            eye: self.eye,
            target: self.eye + self.forward(),
            up: Vec3::Y,
            lens: self.lens,
            near: self.near,
            far: self.far,
        }
    }

    /// The camera for a target of aspect ratio `aspect`.
    #[must_use]
    pub fn camera(&self, aspect: f32) -> Framed {
        let view = self.view();
        Framed {
            view_projection: view.view_projection(aspect),
            eye: view.eye,
            view: Some(view),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seed 002's room camera: at (0, 0, −3.001) looking at the origin.
    fn room() -> FlyCamera {
        let view = View {
            eye: Vec3::new(0.0, 0.0, -3.001),
            target: Vec3::ZERO,
            up: Vec3::Y,
            lens: Lens::Perspective { fov_y_degrees: 53.0 },
            near: 0.5,
            far: 10.0,
        };
        FlyCamera::new(&view, 2.0)
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn starts_looking_where_the_view_looked() {
        let c = room();
        assert!(close(c.forward(), Vec3::Z), "{:?}", c.forward());
        assert!(close(c.right(), Vec3::X));
        let seen = c.view();
        assert_eq!(
            (seen.eye, seen.near, seen.far),
            (Vec3::new(0.0, 0.0, -3.001), 0.5, 10.0)
        );
        // A view from above and to the side: the same direction comes back.
        let view = View {
            eye: Vec3::new(2.0, 3.0, -1.0),
            target: Vec3::new(0.5, 0.0, 1.0),
            ..room().view()
        };
        let from = FlyCamera::new(&view, 1.0);
        assert!(close(from.forward(), (view.target - view.eye).normalize()));
    }

    #[test]
    fn keys_move_along_the_view_and_sideways() {
        let mut c = room();
        let forward = Motion {
            forward: 1.0,
            ..Motion::default()
        };
        c.update(&forward, 0.5);
        assert!(close(c.eye, Vec3::new(0.0, 0.0, -2.001)), "{:?}", c.eye);
        c.update(
            &Motion {
                right: -1.0,
                up: 1.0,
                ..Motion::default()
            },
            0.25,
        );
        assert!(close(c.eye, Vec3::new(-0.5, 0.5, -2.001)), "{:?}", c.eye);
        // Still: nothing changes however long the frame.
        let before = c;
        c.update(&Motion::default(), 10.0);
        assert_eq!(c, before);
    }

    #[test]
    fn yaw_turns_right_and_pitch_stops_short_of_vertical() {
        let mut c = room();
        // A second of → at 90° a second: looking along +x, and forward now walks along +x.
        c.update(
            &Motion {
                yaw: 1.0,
                ..Motion::default()
            },
            1.0,
        );
        assert!(close(c.forward(), Vec3::X), "{:?}", c.forward());
        assert!(close(c.right(), Vec3::NEG_Z));
        // Ten seconds of ↑ would look straight up; the pitch stops at 89°.
        c.update(
            &Motion {
                pitch: 1.0,
                ..Motion::default()
            },
            10.0,
        );
        assert!((c.pitch - MAX_PITCH).abs() < 1e-6);
        assert!(c.forward().y > 0.99 && c.forward().y < 1.0);
        c.view().validate().expect("never looking along up");
    }

    #[test]
    fn the_camera_projects_what_lies_ahead_into_view() {
        let c = room();
        let camera = c.camera(4.0 / 3.0);
        let ahead = camera.view_projection * Vec3::new(0.0, 0.0, 1.0).extend(1.0);
        let behind = camera.view_projection * Vec3::new(0.0, 0.0, -5.0).extend(1.0);
        assert!(ahead.w > 0.0 && ahead.x.abs() < ahead.w && ahead.y.abs() < ahead.w);
        assert!(behind.w < 0.0);
    }
}
