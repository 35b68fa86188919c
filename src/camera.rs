//! The camera (a look-at orthonormal basis, labs 000 and 003) and the projections.
//!
//! World space is left-handed as in lab 000: x right, y up, z forward into the screen.

use glam::{Mat4, Vec3, Vec4};

/// A camera: an origin and an orthonormal basis built from where it looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Position in world space.
    pub origin: Vec3,
    /// Unit direction of view.
    pub forward: Vec3,
    /// Which way is up in the world: the picture's up is this, made square to `forward`.
    pub up: Vec3,
}

impl Camera {
    /// A camera at `origin` looking along `forward` (normalised; `+z` if it is zero or not finite).
    #[must_use]
    pub fn new(origin: Vec3, forward: Vec3) -> Self {
        Self {
            origin,
            forward: forward.try_normalize().unwrap_or(Vec3::Z),
            up: Vec3::Y,
        }
    }

    /// The same camera with another world up (normalised; `+y` if it is zero or not finite).
    #[must_use]
    pub fn with_up(self, up: Vec3) -> Self {
        Self {
            up: up.try_normalize().unwrap_or(Vec3::Y),
            ..self
        }
    }

    /// A camera at `origin` looking at `target`.
    #[must_use]
    pub fn look_at(origin: Vec3, target: Vec3) -> Self {
        Self::new(origin, target - origin)
    }

    /// A camera from yaw (radians about +y, 0 looks along +z) and pitch (radians, positive looks up).
    #[must_use]
    pub fn from_yaw_pitch(origin: Vec3, yaw: f32, pitch: f32) -> Self {
        let forward = Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), yaw.cos() * pitch.cos());
        Self::new(origin, forward)
    }

    /// The basis `(right, up, forward)`: right = up_world × forward, up = forward × right.
    ///
    /// When looking along the world up, a unit vector square to it stands in for right.
    #[must_use]
    pub fn basis(&self) -> (Vec3, Vec3, Vec3) {
        let right = self
            .up
            .cross(self.forward)
            .try_normalize()
            .unwrap_or_else(|| self.up.any_orthonormal_vector());
        let up = self.forward.cross(right);
        (right, up, self.forward)
    }

    /// Camera to world: the basis as columns and the origin as translation.
    #[must_use]
    pub fn camera_to_world(&self) -> Mat4 {
        let (right, up, forward) = self.basis();
        Mat4::from_cols(
            right.extend(0.0),
            up.extend(0.0),
            forward.extend(0.0),
            self.origin.extend(1.0),
        )
    }

    /// World to view space: the inverse of [`camera_to_world`](Self::camera_to_world).
    #[must_use]
    pub fn view(&self) -> Mat4 {
        // The basis is orthonormal, so the inverse is the transpose with the origin moved back.
        let (right, up, forward) = self.basis();
        let rotation = Mat4::from_cols(
            right.extend(0.0),
            up.extend(0.0),
            forward.extend(0.0),
            Vec3::ZERO.extend(1.0),
        )
        .transpose();
        rotation * Mat4::from_translation(-self.origin)
    }
}

/// A projection from view space to clip space, with `0 ≤ z ≤ w` and `w` the view depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Perspective with a vertical field of view.
    Perspective {
        /// Vertical field of view in radians.
        fov_y: f32,
        /// Width over height.
        aspect: f32,
        /// Near plane distance (> 0).
        near: f32,
        /// Far plane distance (> near).
        far: f32,
    },
    /// Orthographic over a `width × height` window centred on the view axis.
    Orthographic {
        /// Window width in view units.
        width: f32,
        /// Window height in view units.
        height: f32,
        /// Near plane distance.
        near: f32,
        /// Far plane distance.
        far: f32,
    },
}

impl Projection {
    /// The clip-from-view matrix.
    ///
    /// Perspective: `x_ndc = x / (aspect · tan(fov/2) · z)` and `y_ndc = y / (tan(fov/2) · z)`,
    /// lab 000's formulas, with `w = z` and `z/w` mapped so that near → 0 and far → 1.
    /// Orthographic: x and y scaled to `[−1, 1]`, `z` mapped linearly, `w = 1`.
    #[must_use]
    pub fn matrix(&self) -> Mat4 {
        match *self {
            Self::Perspective {
                fov_y,
                aspect,
                near,
                far,
            } => {
                let (sy, range) = (1.0 / (fov_y / 2.0).tan(), far / (far - near));
                Mat4::from_cols(
                    Vec4::new(sy / aspect, 0.0, 0.0, 0.0),
                    Vec4::new(0.0, sy, 0.0, 0.0),
                    Vec4::new(0.0, 0.0, range, 1.0),
                    Vec4::new(0.0, 0.0, -near * range, 0.0),
                )
            }
            Self::Orthographic {
                width,
                height,
                near,
                far,
            } => {
                let depth = 1.0 / (far - near);
                Mat4::from_cols(
                    Vec4::new(2.0 / width, 0.0, 0.0, 0.0),
                    Vec4::new(0.0, 2.0 / height, 0.0, 0.0),
                    Vec4::new(0.0, 0.0, depth, 0.0),
                    Vec4::new(0.0, 0.0, -near * depth, 1.0),
                )
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn default_basis_is_the_world_axes() {
        let cam = Camera::new(Vec3::new(0.0, 0.0, -10.0), Vec3::Z);
        assert_eq!(cam.basis(), (Vec3::X, Vec3::Y, Vec3::Z));
        let p = cam.view().transform_point3(Vec3::new(1.0, 2.0, 0.0));
        assert_relative_eq!(p, Vec3::new(1.0, 2.0, 10.0));
    }

    #[test]
    fn view_inverts_camera_to_world() {
        let cam = Camera::from_yaw_pitch(Vec3::new(3.0, -1.0, 2.0), 0.7, -0.3);
        let m = cam.view() * cam.camera_to_world();
        assert!(m.abs_diff_eq(Mat4::IDENTITY, 1e-5), "{m}");
    }

    #[test]
    fn look_at_points_forward_at_the_target() {
        let cam = Camera::look_at(Vec3::ZERO, Vec3::new(0.0, 0.0, 5.0));
        assert_eq!(cam.forward, Vec3::Z);
        let straight_up = Camera::look_at(Vec3::ZERO, Vec3::Y);
        let (right, up, _) = straight_up.basis();
        assert_relative_eq!(right.dot(Vec3::Y), 0.0);
        assert_relative_eq!(up.dot(Vec3::Y), 0.0);
        assert_relative_eq!(right.length(), 1.0);
        // Away from the origin the direction is target − origin (mutation testing: `+`, `/`).
        let cam = Camera::look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 2.0, -1.0));
        assert_eq!(cam.forward, -Vec3::Z);
    }

    #[test]
    fn up_turns_the_picture() {
        // Looking along +z with +x as the world up: the picture's up is +x, its right is −y.
        let cam = Camera::new(Vec3::ZERO, Vec3::Z).with_up(Vec3::X);
        assert_eq!(cam.basis(), (-Vec3::Y, Vec3::X, Vec3::Z));
        assert_eq!(Camera::new(Vec3::ZERO, Vec3::Z).with_up(Vec3::ZERO).up, Vec3::Y);
    }

    #[test]
    fn yaw_turns_right_and_pitch_looks_up() {
        let cam = Camera::from_yaw_pitch(Vec3::ZERO, 0.5, 0.3);
        let (cy, sy, cp, sp) = (0.5f32.cos(), 0.5f32.sin(), 0.3f32.cos(), 0.3f32.sin());
        assert_relative_eq!(cam.forward, Vec3::new(sy * cp, sp, cy * cp), epsilon = 1e-6);
    }

    #[test]
    fn perspective_matches_the_lab_formula() {
        let (fov, aspect) = (60f32.to_radians(), 4.0 / 3.0);
        let proj = Projection::Perspective {
            fov_y: fov,
            aspect,
            near: 0.1,
            far: 100.0,
        };
        let clip = proj.matrix() * glam::Vec4::new(1.0, 2.0, 10.0, 1.0);
        let tan = (fov / 2.0).tan();
        assert_relative_eq!(clip.x / clip.w, 1.0 / (aspect * tan * 10.0), epsilon = 1e-6);
        assert_relative_eq!(clip.y / clip.w, 2.0 / (tan * 10.0), epsilon = 1e-6);
        assert_relative_eq!(clip.w, 10.0);
        let near = proj.matrix() * glam::Vec4::new(0.0, 0.0, 0.1, 1.0);
        let far = proj.matrix() * glam::Vec4::new(0.0, 0.0, 100.0, 1.0);
        assert_relative_eq!(near.z / near.w, 0.0);
        assert_relative_eq!(far.z / far.w, 1.0, epsilon = 1e-6);
    }

    #[test]
    fn orthographic_maps_the_window_to_ndc() {
        let proj = Projection::Orthographic {
            width: 4.0,
            height: 2.0,
            near: 1.0,
            far: 3.0,
        };
        let clip = proj.matrix() * glam::Vec4::new(2.0, -1.0, 2.0, 1.0);
        assert_relative_eq!(clip, glam::Vec4::new(1.0, -1.0, 0.5, 1.0));
        // Near → 0 and far → 1 where `near · depth ≠ near − depth` (mutation testing).
        let deep = Projection::Orthographic {
            width: 2.0,
            height: 2.0,
            near: 2.0,
            far: 6.0,
        };
        assert_relative_eq!((deep.matrix() * glam::Vec4::new(0.0, 0.0, 2.0, 1.0)).z, 0.0);
        assert_relative_eq!((deep.matrix() * glam::Vec4::new(0.0, 0.0, 6.0, 1.0)).z, 1.0);
    }
}
