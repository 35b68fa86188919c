//! Finding the driver asked for, and the one device per process and driver that draws.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use refrast::Spec;
use refrast::{PolygonMode, Supported, Unavailable};

/// The driver a built-in asks for; never quietly another.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Driver {
    /// Mesa's lavapipe: llvmpipe behind Vulkan.
    Lavapipe,
    /// Mesa's llvmpipe behind OpenGL ES, over EGL.
    Llvmpipe,
    /// Mesa's older softpipe behind OpenGL ES (`GALLIUM_DRIVER=softpipe`), over EGL.
    Softpipe,
    /// Google's SwiftShader (Vulkan on the CPU), as Chromium ships it: chosen by pointing the
    /// Vulkan loader at its ICD file ([`SWIFTSHADER_ICD`]).
    Swiftshader,
    /// Whatever Vulkan adapter the machine has, a GPU before a CPU one.
    Vulkan,
}

/// SwiftShader's Vulkan ICD file, where Debian's `chromium` package installs it.
pub const SWIFTSHADER_ICD: &str = "/usr/lib/chromium/vk_swiftshader_icd.json";

impl Driver {
    /// Every driver, as `--impl` names them.
    pub const ALL: [Driver; 5] = [
        Self::Lavapipe,
        Self::Llvmpipe,
        Self::Softpipe,
        Self::Swiftshader,
        Self::Vulkan,
    ];

    /// The name `--impl` takes.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Lavapipe => "lavapipe",
            Self::Llvmpipe => "llvmpipe",
            Self::Softpipe => "softpipe",
            Self::Swiftshader => "swiftshader",
            Self::Vulkan => "vulkan",
        }
    }

    /// One line on what it is, as `refrast impls` prints it.
    #[must_use]
    pub fn description(self) -> &'static str {
        match self {
            Self::Lavapipe => "Mesa's lavapipe (Vulkan on the CPU) through wgpu",
            Self::Llvmpipe => "Mesa's llvmpipe through wgpu's OpenGL ES backend (EGL)",
            Self::Softpipe => "Mesa's softpipe (GALLIUM_DRIVER=softpipe) through wgpu's OpenGL ES backend",
            Self::Swiftshader => {
                "Google's SwiftShader (Vulkan on the CPU, as Chromium ships it) through wgpu"
            }
            Self::Vulkan => "whatever Vulkan adapter this machine has (a GPU first) through wgpu",
        }
    }

    /// The environment its process needs: Mesa picks softpipe only when told before it loads,
    /// and the Vulkan loader reads the ICD files to load (only SwiftShader's) when an instance
    /// is created.
    #[must_use]
    pub fn env(self) -> &'static [(&'static str, &'static str)] {
        match self {
            Self::Softpipe => &[("GALLIUM_DRIVER", "softpipe")],
            Self::Swiftshader => &[("VK_ICD_FILENAMES", SWIFTSHADER_ICD)],
            _ => &[],
        }
    }

    /// Why the driver cannot be here at all, before looking for adapters.
    fn missing(self) -> Option<String> {
        (self == Self::Swiftshader && !std::path::Path::new(SWIFTSHADER_ICD).is_file()).then(|| {
            format!(
                "SwiftShader's Vulkan ICD file {SWIFTSHADER_ICD} is absent; on Debian, apt-get \
                 install chromium (which ships libvk_swiftshader.so beside it)"
            )
        })
    }

    /// The wgpu backend it is behind.
    pub(crate) fn backends(self) -> wgpu::Backends {
        match self {
            Self::Lavapipe | Self::Swiftshader | Self::Vulkan => wgpu::Backends::VULKAN,
            Self::Llvmpipe | Self::Softpipe => wgpu::Backends::GL,
        }
    }

    /// The specification it claims: Vulkan's drivers Vulkan 1.4; those driven through wgpu's
    /// OpenGL ES backend OpenGL ES 3.2, the API they are driven through (not desktop OpenGL).
    #[must_use]
    pub fn spec(self) -> Spec {
        match self {
            Self::Lavapipe | Self::Swiftshader | Self::Vulkan => Spec::Vulkan,
            Self::Llvmpipe | Self::Softpipe => Spec::OpenGlEs,
        }
    }

    /// The Debian packages that bring it.
    fn install(self) -> &'static str {
        match self {
            Self::Swiftshader => "chromium libvulkan1",
            _ => "mesa-vulkan-drivers libvulkan1 libegl1 libegl-mesa0 libgl1-mesa-dri",
        }
    }

    /// Whether an adapter is this driver.
    fn accepts(self, info: &wgpu::AdapterInfo) -> bool {
        let named = |what: &str| {
            [&info.name, &info.driver, &info.driver_info]
                .iter()
                .any(|s| s.to_lowercase().contains(what))
        };
        match self {
            Self::Lavapipe => info.backend == wgpu::Backend::Vulkan && named("llvmpipe"),
            Self::Llvmpipe => info.backend == wgpu::Backend::Gl && named("llvmpipe"),
            Self::Softpipe => info.backend == wgpu::Backend::Gl && named("softpipe"),
            Self::Swiftshader => info.backend == wgpu::Backend::Vulkan && named("swiftshader"),
            Self::Vulkan => info.backend == wgpu::Backend::Vulkan,
        }
    }
}

/// An adapter as reports name it: name, backend, driver and its version.
#[must_use]
pub fn describe(info: &wgpu::AdapterInfo) -> String {
    format!(
        "{} ({:?} backend, {:?}, driver {} {})",
        info.name, info.backend, info.device_type, info.driver, info.driver_info
    )
}

/// A device of the driver asked for, with what it drew with.
pub struct Context {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter it came from.
    pub info: wgpu::AdapterInfo,
    /// The device's largest texture side.
    pub max_side: u32,
    /// Whether it can render to `Rgba32Float` targets (the capture without storage buffers).
    pub renders_floats: bool,
    /// Whether it can copy a depth texture to a buffer (OpenGL ES cannot).
    pub copies_depth: bool,
    /// Why it cannot draw at 4 samples per pixel and capture each sample, if it cannot: a
    /// multisampled depth and id target, and fragment shaders run per sample.
    pub no_multisampling: Option<String>,
    /// Whether it draws with depth clipping off (`unclipped_depth`): the adapter reports
    /// `Features::DEPTH_CLIP_CONTROL` (Vulkan's `depthClamp`, OpenGL ES's `EXT_depth_clamp`).
    pub unclipped_depth: bool,
    /// Whether it clamps depth bias: the adapter reports `DownlevelFlags::DEPTH_BIAS_CLAMP`
    /// (Vulkan's `depthBiasClamp`; wgpu's OpenGL ES backend has none).
    pub bias_clamp: bool,
    /// The polygon modes besides fill it draws: `Features::POLYGON_MODE_LINE` and
    /// `POLYGON_MODE_POINT` (Vulkan's `fillModeNonSolid`; `glPolygonMode` on wgpu's GL backend,
    /// which Mesa's EGL drivers report though OpenGL ES 3.2 has no polygon modes).
    pub polygon_modes: Supported<PolygonMode>,
    /// Whether its vertex stages write clip distances: the adapter reports
    /// `Features::CLIP_DISTANCES` (Vulkan's `shaderClipDistance`; OpenGL ES's
    /// `EXT_clip_cull_distance`).
    pub clip_distances: bool,
    /// Whether it draws filled triangles conservatively: the adapter reports
    /// `Features::CONSERVATIVE_RASTERIZATION` (Vulkan's `VK_EXT_conservative_rasterization`,
    /// overestimation with no extra size through wgpu).
    pub conservative: bool,
}

/// What opening a driver gave: its device, or why there is none.
type Opened = Result<Arc<Context>, Unavailable>;

/// One device per process and driver, created on first use.
static CONTEXTS: OnceLock<Mutex<HashMap<Driver, Opened>>> = OnceLock::new();

/// The device of `driver`, created once per process; why not, when there is none.
pub fn context(driver: Driver) -> Result<Arc<Context>, Unavailable> {
    let contexts = CONTEXTS.get_or_init(|| Mutex::new(HashMap::new()));
    let mut contexts = contexts.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    contexts
        .entry(driver)
        .or_insert_with(|| open(driver).map(Arc::new))
        .clone()
}

/// Opens the adapter that is `driver`, or says which adapters there are instead.
fn open(driver: Driver) -> Result<Context, Unavailable> {
    if let Some(why) = driver.missing() {
        return Err(Unavailable(why));
    }
    for (name, value) in driver.env() {
        if std::env::var(name).as_deref() != Ok(*value) {
            return Err(Unavailable(format!(
                "{} needs {name}={value} set before its process starts; `refrast certify` sets it",
                driver.name()
            )));
        }
    }
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: driver.backends(),
        // Validating indirect draws needs a compute pipeline, which softpipe's OpenGL ES cannot
        // build (wgpu then reports the device lost); the adapter draws nothing indirectly.
        flags: wgpu::InstanceFlags::default() - wgpu::InstanceFlags::VALIDATION_INDIRECT_CALL,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    let adapters = pollster::block_on(instance.enumerate_adapters(driver.backends()));
    let infos: Vec<wgpu::AdapterInfo> = adapters.iter().map(wgpu::Adapter::get_info).collect();
    let mut chosen: Vec<(usize, &wgpu::AdapterInfo)> = infos
        .iter()
        .enumerate()
        .filter(|(_, i)| driver.accepts(i))
        .collect();
    // "Whatever Vulkan adapter": a GPU first, then anything else.
    chosen.sort_by_key(|(_, i)| u8::from(i.device_type == wgpu::DeviceType::Cpu));
    let Some(&(index, info)) = chosen.first() else {
        let found: Vec<String> = infos.iter().map(describe).collect();
        let found = if found.is_empty() {
            "none".to_owned()
        } else {
            found.join("; ")
        };
        return Err(Unavailable(format!(
            "no {} adapter here ({:?} adapters found: {found}); on Debian, apt-get install {}",
            driver.name(),
            driver.backends(),
            driver.install()
        )));
    };
    let adapter = &adapters[index];
    // Softpipe cannot write storage buffers from fragment shaders, whatever its downlevel flags
    // say; the capture then renders one triangle at a time into float targets instead.
    let renders_floats = adapter
        .get_texture_format_features(wgpu::TextureFormat::Rgba32Float)
        .allowed_usages
        .contains(wgpu::TextureUsages::RENDER_ATTACHMENT);
    let limits = adapter.limits();
    let no_multisampling = multisampling(adapter);
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("refrast"),
        required_limits: limits.clone(),
        // WebGPU's core formats hold no 32-bit integer at several samples; the id targets of a
        // multisampled resolve need the adapter's own format features.
        // Depth clipping off, polygon modes and clip distances where the adapter has them.
        required_features: adapter.features()
            & (wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES
                | wgpu::Features::DEPTH_CLIP_CONTROL
                | wgpu::Features::POLYGON_MODE_LINE
                | wgpu::Features::POLYGON_MODE_POINT
                | wgpu::Features::CLIP_DISTANCES
                | wgpu::Features::CONSERVATIVE_RASTERIZATION),
        ..wgpu::DeviceDescriptor::default()
    }))
    .map_err(|e| Unavailable(format!("{} refused a device: {e}", describe(info))))?;
    Ok(Context {
        device,
        queue,
        info: info.clone(),
        max_side: limits.max_texture_dimension_2d,
        renders_floats,
        copies_depth: adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::DEPTH_TEXTURE_AND_BUFFER_COPIES),
        no_multisampling,
        unclipped_depth: adapter.features().contains(wgpu::Features::DEPTH_CLIP_CONTROL),
        bias_clamp: adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::DEPTH_BIAS_CLAMP),
        clip_distances: adapter.features().contains(wgpu::Features::CLIP_DISTANCES),
        conservative: adapter
            .features()
            .contains(wgpu::Features::CONSERVATIVE_RASTERIZATION),
        polygon_modes: Supported::only(
            &[
                (wgpu::Features::POLYGON_MODE_LINE, PolygonMode::Line),
                (wgpu::Features::POLYGON_MODE_POINT, PolygonMode::Point),
            ]
            .into_iter()
            .filter(|(feature, _)| adapter.features().contains(*feature))
            .map(|(_, mode)| mode)
            .collect::<Vec<_>>(),
        ),
    })
}

/// Why `adapter` cannot draw and capture at 4 samples per pixel, if it cannot: what wgpu
/// reports of its per-sample shading and of its depth and integer formats.
fn multisampling(adapter: &wgpu::Adapter) -> Option<String> {
    if !adapter
        .get_downlevel_capabilities()
        .flags
        .contains(wgpu::DownlevelFlags::MULTISAMPLED_SHADING)
    {
        return Some("its fragment shaders cannot run per sample (no MULTISAMPLED_SHADING)".into());
    }
    if !adapter
        .features()
        .contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES)
    {
        return Some(
            "WebGPU's core formats have no 4-sample R32Uint target, and it reports no others".into(),
        );
    }
    let formats = [wgpu::TextureFormat::Depth32Float, wgpu::TextureFormat::R32Uint];
    formats
        .into_iter()
        .find(|&f| {
            !adapter
                .get_texture_format_features(f)
                .flags
                .sample_count_supported(4)
        })
        .map(|f| format!("it has no 4-sample {f:?} target"))
}
