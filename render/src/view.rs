//! Where the eye is: a look-at camera with a perspective or orthographic lens, automatic
//! framing of a mesh, and the command line's overrides.

use glam::{Mat4, Vec3};
use refrast::camera::{Camera, Projection};

/// The lens of a [`View`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lens {
    /// Perspective with a vertical field of view in degrees.
    Perspective {
        /// Vertical field of view, degrees in (0, 180).
        fov_y_degrees: f32,
    },
    /// Orthographic, `height` world units tall (the width follows the aspect ratio).
    Orthographic {
        /// Height of the window in world units.
        height: f32,
    },
}

/// A camera and its lens, as the command line gives them.
///
/// Built on refrast's [`Camera`] ([`View::camera`]), and keeps the point looked at, which a
/// camera does not: framing a mesh and placing the headlight measure the distance to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Where the eye is.
    pub eye: Vec3,
    /// The point looked at.
    pub target: Vec3,
    /// Which way is up in the world.
    pub up: Vec3,
    /// Perspective or orthographic.
    pub lens: Lens,
    /// Near plane distance (> 0).
    pub near: f32,
    /// Far plane distance (> near).
    pub far: f32,
}

/// A view that cannot be used, and what to fix.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ViewError {
    /// A coordinate or distance is NaN or infinite.
    #[error("--{0} must be finite")]
    NotFinite(&'static str),
    /// The eye is where it looks.
    #[error("--eye and --target are the same point; the camera needs a direction")]
    NoDirection,
    /// The up vector is zero.
    #[error("--up must not be zero")]
    NoUp,
    /// The field of view is out of range.
    #[error("--fov {0} is out of range; give degrees strictly between 0 and 180")]
    FieldOfView(f32),
    /// The planes are out of order.
    #[error("--near {near} and --far {far}: need 0 < near < far")]
    Planes {
        /// Near.
        near: f32,
        /// Far.
        far: f32,
    },
    /// The orthographic window is empty.
    #[error("--ortho {0}: the window height must be positive")]
    OrthoHeight(f32),
}

/// What the command line says about the camera; `None` keeps the scene's (or the framing's) choice.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Overrides {
    /// `--eye`.
    pub eye: Option<Vec3>,
    /// `--target`.
    pub target: Option<Vec3>,
    /// `--up`.
    pub up: Option<Vec3>,
    /// `--fov` in degrees.
    pub fov_y_degrees: Option<f32>,
    /// `--near`.
    pub near: Option<f32>,
    /// `--far`.
    pub far: Option<f32>,
    /// `--ortho [HEIGHT]`: `Some(None)` for orthographic with the framing's height.
    pub ortho: Option<Option<f32>>,
}

impl Overrides {
    /// Whether any camera option was given.
    #[must_use]
    pub fn any(&self) -> bool {
        *self != Self::default()
    }
}

/// The field of view the framing uses when none is given.
pub const DEFAULT_FOV_DEGREES: f32 = 50.0;

impl View {
    /// A camera that shows all of `bounds` from in front (towards −z) and a little above,
    /// the near and far planes hugging it.
    #[must_use]
    pub fn frame(bounds: (Vec3, Vec3), aspect: f32) -> Self {
        let (lo, hi) = bounds;
        let center = (lo + hi) / 2.0;
        let radius = ((hi - lo).length() / 2.0).max(1e-3);
        // The narrower of the vertical and the horizontal half-angles must hold the sphere.
        let vertical = DEFAULT_FOV_DEGREES.to_radians() / 2.0;
        let horizontal = (vertical.tan() * aspect.max(1e-3)).atan();
        let half_fov = vertical.min(horizontal);
        let distance = radius / half_fov.sin() * 1.05;
        let direction = Vec3::new(0.0, 0.35, -1.0).normalize();
        Self {
            eye: center + direction * distance,
            target: center,
            up: Vec3::Y,
            lens: Lens::Perspective {
                fov_y_degrees: DEFAULT_FOV_DEGREES,
            },
            near: (distance - radius * 1.5).max(distance * 1e-3),
            far: distance + radius * 1.5,
        }
    }

    /// This view with the command line's choices applied; planes that are not given follow a
    /// moved eye so that `bounds` stays between them.
    #[must_use]
    pub fn with(self, o: &Overrides, bounds: (Vec3, Vec3)) -> Self {
        let (lo, hi) = bounds;
        let center = (lo + hi) / 2.0;
        let radius = ((hi - lo).length() / 2.0).max(1e-3);
        let eye = o.eye.unwrap_or(self.eye);
        let target = o
            .target
            .unwrap_or(if o.eye.is_some() { center } else { self.target });
        let distance = (center - eye).length();
        let moved = o.eye.is_some() || o.target.is_some();
        let near = o.near.unwrap_or(if moved {
            (distance - radius * 1.5).max(distance.max(radius) * 1e-3)
        } else {
            self.near
        });
        let far = o
            .far
            .unwrap_or(if moved { distance + radius * 1.5 } else { self.far });
        let lens = match (o.ortho, o.fov_y_degrees) {
            (Some(Some(height)), _) => Lens::Orthographic { height },
            (Some(None), _) => Lens::Orthographic {
                height: match self.lens {
                    Lens::Orthographic { height } => height,
                    Lens::Perspective { fov_y_degrees } => {
                        2.0 * (target - eye).length() * (fov_y_degrees.to_radians() / 2.0).tan()
                    }
                },
            },
            (None, Some(fov_y_degrees)) => Lens::Perspective { fov_y_degrees },
            (None, None) => self.lens,
        };
        Self {
            eye,
            target,
            up: o.up.unwrap_or(self.up),
            lens,
            near,
            // A far plane that only followed the eye stays beyond the near one; one that was
            // given is checked by `validate`.
            far: if o.far.is_some() {
                far
            } else {
                far.max(near * 1.001)
            },
        }
    }

    /// Checks that the view can be projected, saying which option to fix.
    pub fn validate(&self) -> Result<(), ViewError> {
        for (name, v) in [("eye", self.eye), ("target", self.target), ("up", self.up)] {
            if !v.is_finite() {
                return Err(ViewError::NotFinite(name));
            }
        }
        if !(self.near.is_finite() && self.far.is_finite()) {
            return Err(ViewError::NotFinite("near/--far"));
        }
        if (self.target - self.eye).length_squared() == 0.0 {
            return Err(ViewError::NoDirection);
        }
        if self.up.length_squared() == 0.0 {
            return Err(ViewError::NoUp);
        }
        if !(self.near > 0.0 && self.near < self.far) {
            return Err(ViewError::Planes {
                near: self.near,
                far: self.far,
            });
        }
        match self.lens {
            Lens::Perspective { fov_y_degrees } if !(fov_y_degrees > 0.0 && fov_y_degrees < 180.0) => {
                Err(ViewError::FieldOfView(fov_y_degrees))
            }
            Lens::Orthographic { height } if !(height > 0.0 && height.is_finite()) => {
                Err(ViewError::OrthoHeight(height))
            }
            _ => Ok(()),
        }
    }

    /// The camera of this view.
    #[must_use]
    pub fn camera(&self) -> Camera {
        Camera::look_at(self.eye, self.target).with_up(self.up)
    }

    /// World to clip space for a target of the given aspect ratio (width / height).
    #[must_use]
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        let projection = match self.lens {
            Lens::Perspective { fov_y_degrees } => Projection::Perspective {
                fov_y: fov_y_degrees.to_radians(),
                aspect,
                near: self.near,
                far: self.far,
            },
            Lens::Orthographic { height } => Projection::Orthographic {
                width: height * aspect,
                height,
                near: self.near,
                far: self.far,
            },
        };
        projection.matrix() * self.camera().view()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clip(view: &View, aspect: f32, p: Vec3) -> glam::Vec4 {
        view.view_projection(aspect) * p.extend(1.0)
    }

    fn inside(c: glam::Vec4) -> bool {
        c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w && c.z >= 0.0 && c.z <= c.w
    }

    #[test]
    fn framing_shows_every_corner_at_any_aspect() {
        let bounds = (Vec3::new(-3.0, 0.0, 2.0), Vec3::new(5.0, 1.0, 4.0));
        for aspect in [0.25, 1.0, 4.0] {
            let view = View::frame(bounds, aspect);
            view.validate().unwrap();
            for i in 0..8 {
                let corner = Vec3::select(
                    glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0),
                    bounds.1,
                    bounds.0,
                );
                assert!(
                    inside(clip(&view, aspect, corner)),
                    "aspect {aspect}, corner {corner}"
                );
            }
            // The eye is in front (towards −z) and above the centre.
            assert!(view.eye.z < 3.0 && view.eye.y > 0.5);
        }
    }

    #[test]
    fn overrides_replace_and_planes_follow_a_moved_eye() {
        let bounds = (Vec3::splat(-1.0), Vec3::ONE);
        let base = View::frame(bounds, 1.0);
        assert_eq!(base.with(&Overrides::default(), bounds), base);
        let moved = base.with(
            &Overrides {
                eye: Some(Vec3::new(0.0, 0.0, -20.0)),
                ..Overrides::default()
            },
            bounds,
        );
        assert_eq!(moved.target, Vec3::ZERO);
        assert!(moved.near < 19.0 && moved.far > 21.0, "{moved:?}");
        let ortho = base.with(
            &Overrides {
                ortho: Some(None),
                ..Overrides::default()
            },
            bounds,
        );
        let Lens::Orthographic { height } = ortho.lens else {
            panic!("{ortho:?}")
        };
        // The window the perspective view shows at the target.
        let distance = (base.target - base.eye).length();
        assert!((height - 2.0 * distance * (DEFAULT_FOV_DEGREES.to_radians() / 2.0).tan()).abs() < 1e-4);
        assert!(inside(clip(&ortho, 1.0, Vec3::new(0.9, 0.9, 0.0))));
        // A given far plane is kept, and `validate` judges it.
        let bad = base.with(
            &Overrides {
                near: Some(5.0),
                far: Some(1.0),
                ..Overrides::default()
            },
            bounds,
        );
        assert_eq!(bad.validate(), Err(ViewError::Planes { near: 5.0, far: 1.0 }));
    }

    #[test]
    fn validate_names_what_to_fix() {
        let good = View::frame((Vec3::splat(-1.0), Vec3::ONE), 1.0);
        let check = |change: &dyn Fn(&mut View)| {
            let mut v = good;
            change(&mut v);
            v.validate().unwrap_err().to_string()
        };
        assert!(check(&|v| v.eye = v.target).contains("same point"));
        assert!(check(&|v| v.up = Vec3::ZERO).contains("--up"));
        assert!(check(&|v| v.eye.x = f32::NAN).contains("--eye must be finite"));
        assert!(check(&|v| v.lens = Lens::Perspective { fov_y_degrees: 0.0 }).contains("--fov 0"));
        assert!(check(&|v| v.lens = Lens::Orthographic { height: -1.0 }).contains("--ortho -1"));
        assert!(check(&|v| v.near = 0.0).contains("0 < near < far"));
    }
}
