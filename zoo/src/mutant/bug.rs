//! The bugs the mutants carry, their names and the rule family that must catch each.

/// A classic rasterizer bug.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bug {
    /// Every edge owns its samples (`E ≥ 0`): shared edges are drawn twice.
    InclusiveEdges,
    /// No edge owns its samples (`E > 0`): gaps where shared edges pass through samples.
    ExclusiveEdges,
    /// A consistent bottom-right rule, declared as top-left: watertight, wrong owner.
    BottomRightAsTopLeft,
    /// Edge functions in f32 on unsnapped coordinates: cracks and order effects at large coordinates.
    FloatEdges,
    /// Snaps to 7 subpixel bits while declaring 8.
    DroppedSubpixelBit,
    /// Attributes interpolated affinely (screen space) while declaring perspective-correct.
    AffineAttributes,
    /// Barycentrics divided by the triangle's area instead of twice it: they sum to 2.
    WrongArea,
    /// Depth written without the depth test: the last fragment wins, whatever its depth.
    DepthWithoutTest,
    /// Depth interpolated perspective-correctly instead of linearly in screen space.
    PerspectiveDepth,
    /// No near-plane clipping: vertices behind the eye are divided by negative w.
    NoNearClip,
    /// Clip intersections computed in f32 from the vertex met first: shared edges cut differently.
    DirectionalClip,
    /// The bounding box stops one pixel short of its maximum.
    ExclusiveBboxMax,
    /// The bounding box is clamped to the viewport size instead of its last pixel.
    UnclampedBbox,
    /// Edge functions in 32-bit integers: products overflow at large coordinates.
    Edge32Bit,
    /// Only one winding handled: clockwise triangles are lost even with culling off.
    OneWinding,
    /// Front and back facing swapped.
    InvertedFacing,
    /// Each edge evaluated in f32 from the first vertex: coverage changes when vertices rotate.
    RotatedEdgeOrigin,
    /// Zero-area triangles emit the samples on their line.
    DegenerateFragments,
    /// Under OpenGL's `−w ≤ z ≤ w` range, window depth taken as `z/w` instead of
    /// `(z/w + 1)/2` (found by mutation testing of the reference: no rule judged it).
    UnmappedGlDepth,
    /// `LessOrEqual` tested as `Less` and `GreaterOrEqual` as `Greater`: ties lost (found by
    /// mutation testing of the reference: the depth rules met no tie and replayed fragments
    /// through the reference's own compare).
    StrictCompare,
    /// Clipped triangles' attributes interpolated affinely (screen space), as if the clipped
    /// fan's code path forgot the perspective correction: no rule compared clipped triangles'
    /// barycentrics with the ray cast, and they stay in [0, 1] and sum to 1.
    AffineClipped,
    /// A cut vertex's window depth taken as the corners' window depths mixed by its
    /// barycentrics instead of its own z/w: depth goes wrong on clipped triangles only.
    LerpedCutDepth,
    /// A cut vertex's screen-space weights taken as its clip-space (perspective) ones: one `t`
    /// for both kinds of output, which Vulkan's "Clipping Shader Outputs" forbids for
    /// `NoPerspective` ones (found by mutation testing: no rule judged clipped triangles' screen
    /// weights).
    PerspectiveCutScreen,
    /// Snapping as `floor(v·256 + ½)`, the rounding written by hand most often: a coordinate
    /// halfway between two grid points rounds up, not to even as declared (no rule drew a snap
    /// tie at 8 bits before the exact rules learnt to, when a profile declares `ties_to_even`).
    HalfUpSnap,
    /// Barycentrics numbered from the last vertex instead of the first, as a setup that starts
    /// from its provoking vertex: each weight goes to the wrong vertex, though they still sum
    /// to 1 and lie in [0, 1].
    PermutedBarycentrics,
    /// Facing and culling of a triangle drawn whole taken from its unsnapped area: a sliver
    /// that snapping turns over faces (and is culled) the wrong way.
    UnsnappedFacing,
    /// Zero area decided on the clipped, snapped polygon while the profile claims the
    /// reference's order (on the snapped input, before clipping): a collinear triangle the near
    /// plane cuts draws a sliver along its line.
    ZeroAreaAfterClipping,
    /// Lines drawn with both end pixels under a diamond-exit claim: the last end's diamond is
    /// not left out, as a DDA from end pixel to end pixel draws them (seed 004's lines).
    BothEndsDrawn,
    /// A strip whose segments each draw their last end too: every joint is drawn twice, while a
    /// list is drawn right.
    DoubledJoints,
    /// Samples mirrored in x from the standard locations it declares.
    MirroredSamples,
    /// Samples on an ordered grid (2 × 2, 4 × 4) while declaring Vulkan's standard locations.
    OrderedGridSamples,
    /// Coverage from the pixel's centre only, copied to every sample.
    CentreOnlyCoverage,
    /// One depth per pixel (its first covered sample's) instead of one per sample.
    PixelDepth,
    /// One set of barycentrics per pixel (its first covered sample's, as a shader run once per
    /// pixel reads them) instead of each sample's own, declared as interpolated at the sample.
    PixelBarycentrics,
    /// Points drawn in the pixel `round(x)` names instead of the one that holds them.
    RoundedPoints,
    /// Line ends floored to the grid, as `(v · 256) as i32` does, under a claim of rounding
    /// to nearest: seen only where an end lies off the grid.
    FlooredLineEnds,
    /// Diamond-exit lines tested at each sample's position instead of the pixel's centre: seen
    /// only on multisampled lines.
    PerSampleDiamonds,
    /// Points behind the eye or beyond a depth plane kept (turned to face the eye, their depth
    /// put on the plane) instead of clipped away.
    UnclippedPoints,
    /// Point `i` drawn at vertex `i`, the index buffer ignored.
    VertexOrderPoints,
    /// A line's near cut placed between its projected ends, by the fraction found in clip
    /// space: right only where both ends share one `w`.
    ScreenSpaceLineCut,
    /// The scissor's right and bottom sides inclusive: `x ≤ column ≤ x + width`.
    InclusiveScissor,
    /// The scissor applied to triangles only (as a clamp of their traversal): lines and points
    /// are drawn outside it.
    TrianglesOnlyScissor,
    /// The scissor's rows counted from the bottom, as OpenGL's window coordinates count them,
    /// without the flip to raster space.
    BottomUpScissor,
    /// The scissor keeps the colour (the primitive buffer) but not the depth writes: the depth
    /// test writes depth outside the rectangle.
    DepthPastScissor,
    /// The sample mask ignored: every covered sample drawn.
    IgnoredSampleMask,
    /// The sample mask read from its top sample down: bit `i` taken for sample `n − 1 − i`.
    ReversedSampleMask,
    /// The sample mask applied to triangles only: lines and points drawn at every sample.
    TrianglesOnlySampleMask,
    /// The sample mask applied only above one sample, as OpenGL's multisample operations are,
    /// under a specification that applies bit 0 at one sample too.
    MultisampleOnlySampleMask,
    /// The sample mask keeps the colour (the primitive buffer) but not the depth writes: the
    /// depth test writes depth at masked samples.
    DepthPastSampleMask,
    /// Centroid interpolation ignored for the pixel centre's, outside the triangle or not (a
    /// shader input interpolated at the centre, WGSL's `center`).
    CentreCentroid,
    /// Centroid interpolation ignored for each sample's own barycentrics: inside the pixel and
    /// the triangle, but not one location.
    IgnoredCentroid,
    /// The centroid always at the first covered sample the mask keeps, never at the centre.
    FirstSampleCentroid,
    /// The centroid at the first covered sample before the sample mask, though masked.
    UnmaskedCentroid,
    /// The centroid at the centre wherever every sample the mask keeps is covered (coverage
    /// counted after the mask), inside the triangle or not.
    PostMaskCentroid,
    /// Conservative rasterization ignored: the fill rule's samples drawn.
    SampledConservative,
    /// Conservative overestimation as the box of pixels the triangle's pixels span.
    BoxConservative,
    /// The extra overestimation size ignored: only the pixels the triangle itself touches.
    UnextendedConservative,
    /// A conservative pixel drawn at its sample 0 alone, not at every sample.
    OneSampleConservative,
    /// Underestimation drawn as overestimation: the pixels touched, not those held.
    OverForUnder,
    /// Degenerate triangles drawn (their edges, as lines) where the profile declares them culled.
    RasterizedDegenerates,
    /// Culling of both faces taken as culling of front faces: back faces drawn.
    FrontOnlyForBoth,
    /// Culling of both faces applied to every primitive: lines and points culled too.
    BothCullsLines,
    /// A strip's triangle `i` taken as vertices `i, i + 1, i + 2` whatever its parity: every
    /// other triangle turns the other way, so it faces and culls wrong.
    UnalternatedStrip,
    /// A strip's or fan's last triangle dropped (its triangles counted as vertices − 3).
    ShortStrip,
    /// A fan drawn as a strip of the same vertices: its hub left out of every triangle after
    /// the first.
    FanAsStrip,
    /// Under the last provoking vertex, a triangle's flat values from its third corner in
    /// Vulkan's order: right for a list, wrong for every odd strip triangle and every fan.
    LastCornerFlat,
    /// A triangle whose provoking vertex the near plane cuts away takes its flat values from
    /// its first corner left standing.
    ClippedFlat,
    /// The provoking mode ignored: flat values always from the first vertex.
    FirstOnlyFlat,
    /// The viewport's depth range ignored: window depth always in `[0, 1]`.
    IgnoredViewportDepth,
    /// A reversed depth range put in order (`minDepth` taken as the smaller end), as an API that
    /// rejects `minDepth > maxDepth` might: depth runs the wrong way.
    SortedDepthRange,
    /// Depth clipping off taken as far clipping off alone: the near plane still cuts.
    NearClippedAnyway,
    /// Depth bias with the slope factor's sign lost.
    FlippedBiasSlope,
    /// The depth bias clamp ignored.
    IgnoredBiasClamp,
    /// Depth bias given to the fragments but not to what the depth test stores.
    FragmentOnlyBias,
    /// The slope measured as `max(|∂z/∂x|, |∂z/∂y|)` by a rasterizer that declares the exact
    /// length.
    MaxSlopeDeclaredExact,
    /// `r` taken as `2^-24` on an f32 depth buffer, whatever the triangle's depths (the
    /// exponent of the largest depth ignored).
    FixedBiasExponent,
    /// Line and point modes declared but never honoured: triangles filled.
    FilledPolygonModes,
    /// Culling applied after a triangle became lines or points, which nothing culls: culled
    /// triangles drawn in line and point mode.
    UnculledPolygonModes,
    /// Fragments of triangles in line or point mode reporting front-facing, as a line's do.
    FrontFacingPolygonModes,
    /// The loop of edges left open in line mode: the third edge, third corner to first, missing.
    OpenPolygonLoop,
    /// Clip distances declared but never honoured.
    IgnoredClipDistances,
    /// Clip distances interpolated linearly in screen space, not perspective-correctly: the
    /// cut of a triangle in perspective lands in the wrong place.
    ScreenLinearClipDistances,
    /// A primitive kept only where each clip distance exceeds `2^-10`, not where it is `≥ 0`:
    /// a draw by `d` and one by `−d` both lose a sliver along the cut.
    EpsilonClipDistances,
    /// Clip distances honoured on triangles, ignored on lines and points.
    TrianglesOnlyClipDistances,
    /// A primitive culled when any vertex, not every vertex, is negative in a cull distance.
    AnyVertexCulls,
}

impl Bug {
    /// Every bug.
    pub const ALL: [Bug; 85] = [
        Self::InclusiveEdges,
        Self::ExclusiveEdges,
        Self::BottomRightAsTopLeft,
        Self::FloatEdges,
        Self::DroppedSubpixelBit,
        Self::AffineAttributes,
        Self::WrongArea,
        Self::DepthWithoutTest,
        Self::PerspectiveDepth,
        Self::NoNearClip,
        Self::DirectionalClip,
        Self::ExclusiveBboxMax,
        Self::UnclampedBbox,
        Self::Edge32Bit,
        Self::OneWinding,
        Self::InvertedFacing,
        Self::RotatedEdgeOrigin,
        Self::DegenerateFragments,
        Self::UnmappedGlDepth,
        Self::StrictCompare,
        Self::AffineClipped,
        Self::LerpedCutDepth,
        Self::PerspectiveCutScreen,
        Self::HalfUpSnap,
        Self::PermutedBarycentrics,
        Self::UnsnappedFacing,
        Self::ZeroAreaAfterClipping,
        Self::BothEndsDrawn,
        Self::DoubledJoints,
        Self::MirroredSamples,
        Self::OrderedGridSamples,
        Self::CentreOnlyCoverage,
        Self::PixelDepth,
        Self::PixelBarycentrics,
        Self::RoundedPoints,
        Self::FlooredLineEnds,
        Self::PerSampleDiamonds,
        Self::UnclippedPoints,
        Self::VertexOrderPoints,
        Self::ScreenSpaceLineCut,
        Self::InclusiveScissor,
        Self::TrianglesOnlyScissor,
        Self::BottomUpScissor,
        Self::DepthPastScissor,
        Self::IgnoredSampleMask,
        Self::ReversedSampleMask,
        Self::TrianglesOnlySampleMask,
        Self::MultisampleOnlySampleMask,
        Self::DepthPastSampleMask,
        Self::CentreCentroid,
        Self::IgnoredCentroid,
        Self::FirstSampleCentroid,
        Self::UnmaskedCentroid,
        Self::PostMaskCentroid,
        Self::SampledConservative,
        Self::BoxConservative,
        Self::UnextendedConservative,
        Self::OneSampleConservative,
        Self::OverForUnder,
        Self::RasterizedDegenerates,
        Self::FrontOnlyForBoth,
        Self::BothCullsLines,
        Self::UnalternatedStrip,
        Self::ShortStrip,
        Self::FanAsStrip,
        Self::LastCornerFlat,
        Self::ClippedFlat,
        Self::FirstOnlyFlat,
        Self::IgnoredViewportDepth,
        Self::SortedDepthRange,
        Self::NearClippedAnyway,
        Self::FlippedBiasSlope,
        Self::IgnoredBiasClamp,
        Self::FragmentOnlyBias,
        Self::MaxSlopeDeclaredExact,
        Self::FixedBiasExponent,
        Self::FilledPolygonModes,
        Self::UnculledPolygonModes,
        Self::FrontFacingPolygonModes,
        Self::OpenPolygonLoop,
        Self::IgnoredClipDistances,
        Self::ScreenLinearClipDistances,
        Self::EpsilonClipDistances,
        Self::TrianglesOnlyClipDistances,
        Self::AnyVertexCulls,
    ];

    /// The name after `mutant:` in `--impl`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::InclusiveEdges => "inclusive-edges",
            Self::ExclusiveEdges => "exclusive-edges",
            Self::BottomRightAsTopLeft => "bottom-right-as-top-left",
            Self::FloatEdges => "float-edges",
            Self::DroppedSubpixelBit => "dropped-subpixel-bit",
            Self::AffineAttributes => "affine-attributes",
            Self::WrongArea => "wrong-area",
            Self::DepthWithoutTest => "depth-without-test",
            Self::PerspectiveDepth => "perspective-depth",
            Self::NoNearClip => "no-near-clip",
            Self::DirectionalClip => "directional-clip",
            Self::ExclusiveBboxMax => "exclusive-bbox-max",
            Self::UnclampedBbox => "unclamped-bbox",
            Self::Edge32Bit => "edge-32-bit",
            Self::OneWinding => "one-winding",
            Self::InvertedFacing => "inverted-facing",
            Self::RotatedEdgeOrigin => "rotated-edge-origin",
            Self::DegenerateFragments => "degenerate-fragments",
            Self::UnmappedGlDepth => "unmapped-gl-depth",
            Self::StrictCompare => "strict-compare",
            Self::AffineClipped => "affine-clipped",
            Self::LerpedCutDepth => "lerped-cut-depth",
            Self::PerspectiveCutScreen => "perspective-cut-screen",
            Self::HalfUpSnap => "half-up-snap",
            Self::PermutedBarycentrics => "permuted-barycentrics",
            Self::UnsnappedFacing => "unsnapped-facing",
            Self::ZeroAreaAfterClipping => "zero-area-after-clipping",
            Self::BothEndsDrawn => "both-ends-drawn",
            Self::DoubledJoints => "doubled-joints",
            Self::MirroredSamples => "mirrored-samples",
            Self::OrderedGridSamples => "ordered-grid-samples",
            Self::CentreOnlyCoverage => "centre-only-coverage",
            Self::PixelDepth => "pixel-depth",
            Self::PixelBarycentrics => "pixel-barycentrics",
            Self::RoundedPoints => "rounded-points",
            Self::FlooredLineEnds => "floored-line-ends",
            Self::PerSampleDiamonds => "per-sample-diamonds",
            Self::UnclippedPoints => "unclipped-points",
            Self::VertexOrderPoints => "vertex-order-points",
            Self::ScreenSpaceLineCut => "screen-space-line-cut",
            Self::InclusiveScissor => "inclusive-scissor",
            Self::TrianglesOnlyScissor => "triangles-only-scissor",
            Self::BottomUpScissor => "bottom-up-scissor",
            Self::DepthPastScissor => "depth-past-scissor",
            Self::IgnoredSampleMask => "ignored-sample-mask",
            Self::ReversedSampleMask => "reversed-sample-mask",
            Self::TrianglesOnlySampleMask => "triangles-only-sample-mask",
            Self::MultisampleOnlySampleMask => "multisample-only-sample-mask",
            Self::DepthPastSampleMask => "depth-past-sample-mask",
            Self::CentreCentroid => "centre-centroid",
            Self::IgnoredCentroid => "ignored-centroid",
            Self::FirstSampleCentroid => "first-sample-centroid",
            Self::UnmaskedCentroid => "unmasked-centroid",
            Self::PostMaskCentroid => "post-mask-centroid",
            Self::SampledConservative => "sampled-conservative",
            Self::BoxConservative => "box-conservative",
            Self::UnextendedConservative => "unextended-conservative",
            Self::OneSampleConservative => "one-sample-conservative",
            Self::OverForUnder => "over-for-under",
            Self::RasterizedDegenerates => "rasterized-degenerates",
            Self::FrontOnlyForBoth => "front-only-for-both",
            Self::BothCullsLines => "both-culls-lines",
            Self::UnalternatedStrip => "unalternated-strip",
            Self::ShortStrip => "short-strip",
            Self::FanAsStrip => "fan-as-strip",
            Self::LastCornerFlat => "last-corner-flat",
            Self::ClippedFlat => "clipped-flat",
            Self::FirstOnlyFlat => "first-only-flat",
            Self::IgnoredViewportDepth => "ignored-viewport-depth",
            Self::SortedDepthRange => "sorted-depth-range",
            Self::NearClippedAnyway => "near-clipped-anyway",
            Self::FlippedBiasSlope => "flipped-bias-slope",
            Self::IgnoredBiasClamp => "ignored-bias-clamp",
            Self::FragmentOnlyBias => "fragment-only-bias",
            Self::MaxSlopeDeclaredExact => "max-slope-declared-exact",
            Self::FixedBiasExponent => "fixed-bias-exponent",
            Self::FilledPolygonModes => "filled-polygon-modes",
            Self::UnculledPolygonModes => "unculled-polygon-modes",
            Self::FrontFacingPolygonModes => "front-facing-polygon-modes",
            Self::OpenPolygonLoop => "open-polygon-loop",
            Self::IgnoredClipDistances => "ignored-clip-distances",
            Self::ScreenLinearClipDistances => "screen-linear-clip-distances",
            Self::EpsilonClipDistances => "epsilon-clip-distances",
            Self::TrianglesOnlyClipDistances => "triangles-only-clip-distances",
            Self::AnyVertexCulls => "any-vertex-culls",
        }
    }

    /// The name of the rule family whose rules must catch it (`fill`, `bary`, …: the first part
    /// of their IDs; the zoo's tests check that the catalogue has it and that it catches it).
    #[must_use]
    pub fn caught_by(self) -> &'static str {
        match self {
            Self::InclusiveEdges
            | Self::ExclusiveEdges
            | Self::BottomRightAsTopLeft
            | Self::DroppedSubpixelBit
            | Self::HalfUpSnap => "fill",
            Self::ExclusiveBboxMax | Self::Edge32Bit => "fill",
            // Its cracks come from evaluating a shared edge from either end in f32: reversing one
            // triangle's winding shows the same on a single triangle.
            Self::FloatEdges => "meta",
            Self::AffineAttributes
            | Self::WrongArea
            | Self::AffineClipped
            | Self::PerspectiveCutScreen
            | Self::PermutedBarycentrics => "bary",
            Self::DepthWithoutTest
            | Self::PerspectiveDepth
            | Self::UnmappedGlDepth
            | Self::StrictCompare
            | Self::LerpedCutDepth => "depth",
            Self::NoNearClip | Self::DirectionalClip => "clip",
            Self::OneWinding
            | Self::InvertedFacing
            | Self::RotatedEdgeOrigin
            | Self::DegenerateFragments
            | Self::UnsnappedFacing
            | Self::ZeroAreaAfterClipping => "meta",
            Self::UnclampedBbox => "robust",
            Self::BothEndsDrawn | Self::DoubledJoints => "line",
            Self::MirroredSamples
            | Self::OrderedGridSamples
            | Self::CentreOnlyCoverage
            | Self::PixelDepth
            | Self::PixelBarycentrics => "msaa",
            Self::RoundedPoints | Self::UnclippedPoints | Self::VertexOrderPoints => "point",
            Self::FlooredLineEnds | Self::ScreenSpaceLineCut => "line",
            Self::PerSampleDiamonds => "msaa",
            Self::InclusiveScissor | Self::TrianglesOnlyScissor | Self::BottomUpScissor => "clip",
            Self::DepthPastScissor => "depth",
            Self::IgnoredSampleMask
            | Self::ReversedSampleMask
            | Self::TrianglesOnlySampleMask
            | Self::MultisampleOnlySampleMask => "msaa",
            Self::DepthPastSampleMask => "depth",
            Self::CentreCentroid
            | Self::IgnoredCentroid
            | Self::FirstSampleCentroid
            | Self::UnmaskedCentroid
            | Self::PostMaskCentroid => "msaa",
            Self::SampledConservative
            | Self::BoxConservative
            | Self::UnextendedConservative
            | Self::OneSampleConservative
            | Self::OverForUnder
            | Self::RasterizedDegenerates => "fill",
            Self::FrontOnlyForBoth | Self::BothCullsLines => "meta",
            Self::UnalternatedStrip | Self::ShortStrip | Self::FanAsStrip => "meta",
            Self::LastCornerFlat | Self::ClippedFlat | Self::FirstOnlyFlat => "bary",
            Self::IgnoredViewportDepth | Self::SortedDepthRange => "depth",
            Self::NearClippedAnyway => "clip",
            Self::FlippedBiasSlope
            | Self::IgnoredBiasClamp
            | Self::FragmentOnlyBias
            | Self::MaxSlopeDeclaredExact
            | Self::FixedBiasExponent => "depth",
            Self::FilledPolygonModes | Self::UnculledPolygonModes | Self::OpenPolygonLoop => "line",
            Self::FrontFacingPolygonModes => "meta",
            Self::IgnoredClipDistances
            | Self::ScreenLinearClipDistances
            | Self::EpsilonClipDistances
            | Self::TrianglesOnlyClipDistances
            | Self::AnyVertexCulls => "clip",
        }
    }

    /// Whether only lines and points beyond the 8-bit grid at `w = 1` show it: the mutant then
    /// declares no polygon modes, whose rules compare a triangle's edges and corners with the
    /// same implementation's lists and would see a bug in lists alone.
    #[must_use]
    pub fn is_reach(self) -> bool {
        matches!(
            self,
            Self::FlooredLineEnds
                | Self::PerSampleDiamonds
                | Self::UnclippedPoints
                | Self::VertexOrderPoints
                | Self::ScreenSpaceLineCut
        )
    }

    /// Whether it is a bug of lines, points or multisampling: the mutant then declares them
    /// and draws them with it, and draws triangles at one sample right (but a sample mask's
    /// bug, also [`is_state`](Self::is_state), which reads the mask wrong at every count).
    #[must_use]
    pub fn is_primitive(self) -> bool {
        matches!(self.caught_by(), "line" | "point" | "msaa")
    }

    /// Whether it is a bug of the draw state beyond the first contract (the scissor, the sample mask, culling of
    /// both faces, strips and fans, flat values, the depth range and clamp, depth bias, polygon modes, clip and cull distances): the mutant then declares everything the
    /// reference does, and draws with it.
    #[must_use]
    pub fn is_state(self) -> bool {
        matches!(
            self,
            Self::InclusiveScissor
                | Self::TrianglesOnlyScissor
                | Self::BottomUpScissor
                | Self::DepthPastScissor
                | Self::IgnoredSampleMask
                | Self::ReversedSampleMask
                | Self::TrianglesOnlySampleMask
                | Self::MultisampleOnlySampleMask
                | Self::DepthPastSampleMask
                | Self::CentreCentroid
                | Self::IgnoredCentroid
                | Self::FirstSampleCentroid
                | Self::UnmaskedCentroid
                | Self::PostMaskCentroid
                | Self::SampledConservative
                | Self::BoxConservative
                | Self::UnextendedConservative
                | Self::OneSampleConservative
                | Self::OverForUnder
                | Self::RasterizedDegenerates
                | Self::FrontOnlyForBoth
                | Self::BothCullsLines
                | Self::UnalternatedStrip
                | Self::ShortStrip
                | Self::FanAsStrip
                | Self::LastCornerFlat
                | Self::ClippedFlat
                | Self::FirstOnlyFlat
                | Self::IgnoredViewportDepth
                | Self::SortedDepthRange
                | Self::NearClippedAnyway
                | Self::FlippedBiasSlope
                | Self::IgnoredBiasClamp
                | Self::FragmentOnlyBias
                | Self::MaxSlopeDeclaredExact
                | Self::FixedBiasExponent
                | Self::FilledPolygonModes
                | Self::UnculledPolygonModes
                | Self::FrontFacingPolygonModes
                | Self::OpenPolygonLoop
                | Self::IgnoredClipDistances
                | Self::ScreenLinearClipDistances
                | Self::EpsilonClipDistances
                | Self::TrianglesOnlyClipDistances
                | Self::AnyVertexCulls
        )
    }
}
