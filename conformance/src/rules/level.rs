//! What each specification requires of what a rule checks.
//!
//! A rule's sources differ: a tie rule exact to the bit is D3D11.3's and refrast's, where Vulkan
//! and OpenGL ask only that a shared edge's sample be covered once; a NaN vertex discarded is
//! D3D11.3's, where Vulkan and OpenGL leave it unspecified. A profile says which specification
//! it claims ([`refrast::Spec`]); a failure of something that specification does not require is
//! reported as *beyond the specification*, with the sentence it rests on, not as a failure of
//! conformance. Quotes are from Vulkan 1.4.360 (Vulkan-Docs 090f1b1), OpenGL 4.6 core
//! (2022-05-05), OpenGL ES 3.2 (2019-05-14) and the D3D11.3 functional specification.

use refrast::Spec;

use super::Run;

/// What one specification says of what a rule checks.
#[derive(Clone, Copy, Debug)]
pub enum Level {
    /// It requires all of it (given the profile's declared grid, tie rule and conventions).
    Required,
    /// It requires part of it: `part` runs the rule on that part alone. A failure the part
    /// reproduces is a failure; one only the whole rule finds is beyond the specification.
    Partly {
        /// The rule restricted to what the specification requires.
        part: Run,
        /// What it leaves out, and the sentence that says so.
        note: &'static str,
    },
    /// It leaves the outcome undefined or unspecified: the sentence that says so.
    Undefined(&'static str),
    /// It says nothing of it (or defines another outcome): why, with the nearest sentence.
    NotCovered(&'static str),
}

impl Level {
    /// A one-word name: `required`, `partly`, `undefined`, `not covered`.
    #[must_use]
    pub fn word(&self) -> &'static str {
        match self {
            Self::Required => "required",
            Self::Partly { .. } => "partly",
            Self::Undefined(_) => "undefined",
            Self::NotCovered(_) => "not covered",
        }
    }

    /// Why a failure under this level is beyond the specification; `None` when it is required.
    #[must_use]
    pub fn note(&self) -> Option<&'static str> {
        match self {
            Self::Required => None,
            Self::Partly { note, .. } | Self::Undefined(note) | Self::NotCovered(note) => Some(note),
        }
    }
}

/// A rule's level under each specification but refrast's own, where every rule is required.
#[derive(Clone, Copy, Debug)]
pub struct Levels {
    /// Under Vulkan 1.4.
    pub vulkan: Level,
    /// Under OpenGL 4.6.
    pub opengl: Level,
    /// Under D3D11.3.
    pub d3d11: Level,
    /// Under OpenGL ES 3.2: OpenGL 4.6's unless a rule says otherwise.
    pub opengles: Level,
}

impl Levels {
    /// Required by every specification.
    pub const REQUIRED: Levels = Levels {
        vulkan: Level::Required,
        opengl: Level::Required,
        d3d11: Level::Required,
        opengles: Level::Required,
    };

    /// The level under `spec`.
    #[must_use]
    pub fn of(&self, spec: Spec) -> Level {
        match spec {
            Spec::Refrast => Level::Required,
            Spec::Vulkan => self.vulkan,
            Spec::OpenGl => self.opengl,
            Spec::D3d11 => self.d3d11,
            Spec::OpenGlEs => self.opengles,
        }
    }

    /// Each specification but refrast's with its level, in the order the tables show them.
    #[must_use]
    pub fn each(&self) -> [(Spec, Level); 4] {
        [
            (Spec::Vulkan, self.vulkan),
            (Spec::OpenGl, self.opengl),
            (Spec::OpenGlEs, self.opengles),
            (Spec::D3d11, self.d3d11),
        ]
    }
}

/// The text of [`SHARED_EDGE_ONLY`], for notes that join it with another.
macro_rules! shared_edge_only {
    () => {
        "Vulkan (Basic Polygon Rasterization) and OpenGL 4.6 §14.6.1 ask only that \"if two polygons lie on either side of a common edge (with identical endpoints) on which a sample point lies, then exactly one of the polygons must result in a covered sample\": a sample on a vertex shared by three or more triangles is not covered"
    };
}

/// The text of [`CUT_VERTICES`], for notes that join it with another.
macro_rules! cut_vertices {
    () => {
        "a shared edge is covered exactly once only \"with identical endpoints\"; no specification requires two triangles clipped at a plane to compute the identical cut vertex (Vulkan: floating-point results \"accurate to about 1 part in 10^5\"; D3D11.3 §15.4: \"at least float32 precision\"), so along a cut shared edge only the samples away from it are required"
    };
}

/// Vulkan's and OpenGL's sentences on a sample on a shared edge speak of two polygons with
/// identical endpoints: a vertex shared by three or more, and which polygon owns a tie, are
/// theirs to choose.
pub const SHARED_EDGE_ONLY: &str = shared_edge_only!();

/// Vulkan and OpenGL fix neither a tie rule nor how a coordinate rounds to the subpixel grid.
pub const NO_TIE_RULE: &str = "Vulkan fixes no tie rule (only \"exactly one of the polygons\" covers a sample on a shared edge) and no rounding of x_f and y_f (\"x_f and y_f have limited precision\", Controlling the Viewport); OpenGL 4.6 §14.6.1 likewise: only samples away from every edge are required, and the declared tie rule and rounding are the profile's own claim";

/// No specification bounds interpolation error; refrast holds the claimed precision where the
/// triangle stays near the viewport.
pub const FAR_VALUES: &str = "no specification bounds interpolation error: Vulkan asks each floating-point operation to be \"accurate to about 1 part in 10^5\" (Floating-Point Computation; OpenGL 4.6 §2.3.4.1 likewise; D3D11.3 §3.1 half an ulp of f32), which on a triangle with a vertex a thousand times its largest |w| off axis in clip space (thousands of pixels beyond the viewport) allows errors of a pixel's worth and more; there only finite values are required (a NaN is no convex combination, Basic Polygon Rasterization). Nearer, on triangles whole or clipped, the values are required within the claimed precision: a clipped polygon's vertices carry exactly defined values (Clipping Shader Outputs), and any triangulation of it interpolates them as the ray cast does";

/// D3D11.3 has no barycentric output.
pub const NO_BARYCENTRICS: &str = "D3D11.3 defines no barycentric output (only interpolation modes, §16.4)";

/// No specification makes two triangles sharing an edge cut it at the same point.
pub const CUT_VERTICES: &str = cut_vertices!();

/// Vulkan and OpenGL on a clipped mesh: both of the above.
pub const CUT_VERTICES_AND_SHARED_EDGES: &str = concat!(cut_vertices!(), "; and ", shared_edge_only!());

/// Exact coverage at edges is a refrast convention under Vulkan and OpenGL.
pub const EDGES_NOT_PINNED: &str = "Vulkan and OpenGL pin neither which polygon owns a sample on an edge nor that this is independent of vertex order or of the rest of the draw (\"The Vulkan specification is not pixel exact\", Invariance): only samples away from every edge are required";

/// A strip or fan against its list: edges, and clipped or thin triangles' values, which
/// another vertex order than Vulkan's may move.
pub const STRIP_ORDER_NOT_PINNED: &str = "Vulkan and OpenGL pin neither which polygon owns a sample on an edge nor that this is independent of vertex order or of the rest of the draw (\"The Vulkan specification is not pixel exact\", Invariance); OpenGL and OpenGL ES make a strip's or fan's triangle from the same vertices in another order (§10.1.5–§10.1.7: A, B, then the new vertex, a rotation of Vulkan's), and D3D11.3 gives its order only in a diagram (§8.10); another order may move the vertices a clipping plane cuts, and the weights of a triangle too thin for the claimed precision: only samples away from every edge and from the near and far planes' cuts are required to be covered alike, and values and facing only on triangles no plane cuts and wide enough for the claimed precision";

/// What zero area means in every specification.
pub const ZERO_AREA_LINE: &str = "zero area only makes a triangle back-facing (Vulkan: \"Any triangle which is not front-facing is back-facing, including zero-area triangles\"; D3D11.3 §15.11.1: \"Zero area geometry is considered back facing\"): samples away from its line are never inside it, but no specification says whether the samples on the line are covered";

/// Vulkan and OpenGL leave non-finite input unspecified.
pub const NON_FINITE_UNSPECIFIED: &str = "\"providing a NaN or Inf yields unspecified results\" (Vulkan, General Requirements; OpenGL 4.6 §2.3.4.1); only no \"interruption or termination\" is required";

/// D3D11.3 discards NaN positions but lets infinities go either way.
pub const INFINITY_EITHER_WAY: &str = "D3D11.3 §15.4 discards \"Coordinates with NaN at x,y,z or w coming out of clipping\" but says \"Coordinates coming in to clipping with infinities at x,y,z may or may not result in a discarded primitive\"";

/// Vulkan and OpenGL: well-formed output for finite input in range only.
pub const IN_RANGE_ONLY: &str = "NaN and Inf yield \"unspecified results\" and floats need only reach 2^32 in magnitude (Vulkan, General Requirements and Floating-Point Computation; OpenGL 4.6 §2.3.4.1): fragments inside the viewport are required whatever the input (\"Samples with coordinates outside the scissor rectangle … will have their coverage set to 0\", Scissor Test), well-formed values only where drawing stays within that range (finite input within 2^32, and every vertex of the clipped polygon at w ≥ 2^-32, since perspective interpolation divides by w), and a depth outside [0, 1] not even there (\"If z_f is not in the range [z_min, z_max], then z_f is undefined\", Depth Clamping and Range Adjustment)";

/// Vulkan and OpenGL leave a depth outside the range undefined; refrast clamps.
pub const DEPTH_OUT_OF_RANGE: &str = "\"If z_f is not in the range [z_min, z_max], then z_f is undefined following this step\" (Vulkan, Depth Clamping and Range Adjustment; OpenGL 4.6 clamps only under DEPTH_CLAMP, §13.7 and §17.3.4): a sample a grid step outside a steep clipped polygon, covered because of snapping, extrapolates its depth plane beyond [0, 1], where refrast clamps and these specifications leave the value undefined";

/// D3D11.3 says nothing of barycentrics, so their finiteness is not required.
pub const BARYCENTRICS_UNJUDGED: &str = "D3D11.3 requires fragments inside the viewport (§15.6) and depth clamped (§17.10) whatever the input, but defines no barycentric output to be finite";

/// A bad index: an API error is refrast's convention.
pub const BAD_INDEX_UNDEFINED: &str = "an index past the vertex buffer reads as Shader Out-of-Bounds Memory Access describes (Vulkan, Vertex Input Extraction), undefined without robust access; OpenGL 4.6 §6.4 may raise an error or give \"undefined results\": a draw failing with an error is refrast's API convention";

/// D3D11.3 defines another outcome for a bad index.
pub const BAD_INDEX_D3D: &str = "D3D11.3 §8.19.2 reads a vertex past the buffer as zeros (\"the return is 0 in all non-missing components\") and draws on; it does not fail the draw";

/// Depth clipping off: what crosses the eye's plane is cut where no bound holds.
pub const EYE_CROSSING_UNCLIPPED: &str = "with depth clipping off, only the x and y planes (−w ≤ x, y ≤ w) remove what lies behind the eye (Vulkan, Primitive Clipping: \"there is no near or far plane clipping\"; OpenGL 4.6 §13.7 likewise), and an implementation cuts them in floating point, at a guard band far outside the viewport: on a triangle crossing w = 0 a cut vertex's w is a difference of nearly equal numbers, and \"accurate to about 1 part in 10^5\" (Floating-Point Computation; OpenGL 4.6 §2.3.4.1) then puts it anywhere on screen, so only triangles wholly in front of the eye are required, crossing the near and far planes; and as everywhere, no specification bounds interpolation error thousands of pixels beyond the viewport (there only finite depth is required)";

/// D3D11.3 has no −w ≤ z volume.
pub const NO_GL_RANGE: &str = "D3D11.3 has only the 0 ≤ z ≤ w volume (§15.4)";
