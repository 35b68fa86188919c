//! The measured profile, once per process and driver, and kept on disk per driver and version:
//! `refrast certify` builds the driver in a child process per rule, and each would otherwise
//! run `vulkaninfo` (half a second for lavapipe) and the probes again.
//!
//! The file is `<target>/refrast-profiles/<driver>.txt`, `<target>` being the Cargo target
//! folder holding the running executable (found by its `CACHEDIR.TAG`); `REFRAST_PROFILE_CACHE`
//! names another folder, or `off` for none. Its first line is the key: the driver, the adapter
//! as wgpu reports it (name, IDs, driver and its version), the size and modification time of an
//! ICD chosen by `VK_ICD_FILENAMES` and its library (SwiftShader reports no version through
//! wgpu), and a hash of the probes' and the choices' source. Any difference measures again and
//! rewrites the file; a file that does not read back is measured over too.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use refrast::{
    DepthSlope, FillConvention, LineRule, PointClipping, SamplePattern, SnapAccuracy, Snapping, Unavailable,
};

use crate::device::{Context, Driver};
use crate::measured::Measured;

/// The sources whose change must measure again.
const SOURCES: [&str; 11] = [
    include_str!("probe/mod.rs"),
    include_str!("probe/band.rs"),
    include_str!("probe/bias.rs"),
    include_str!("probe/coverage.rs"),
    include_str!("probe/fill.rs"),
    include_str!("probe/grid.rs"),
    include_str!("probe/precision.rs"),
    include_str!("probe/primitives.rs"),
    include_str!("probe/snap.rs"),
    include_str!("measured.rs"),
    include_str!("reported.rs"),
];

/// What measuring a driver gave in this process.
type Found = Result<Arc<Measured>, Unavailable>;

static MEASURED: OnceLock<Mutex<HashMap<Driver, Found>>> = OnceLock::new();

/// `driver`'s measured profile: from this process's first measurement, else from the file,
/// else measured now by `measure` (and written to the file).
pub fn measured(
    driver: Driver,
    ctx: &Context,
    measure: impl FnOnce() -> Result<Measured, Unavailable>,
) -> Found {
    let all = MEASURED.get_or_init(|| Mutex::new(HashMap::new()));
    let mut all = all.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    all.entry(driver)
        .or_insert_with(|| {
            let key = key(driver, &ctx.info);
            let file = folder().map(|f| f.join(format!("{}.txt", driver.name())));
            if let Some(m) = file.as_deref().and_then(|f| load(f, &key)) {
                return Ok(Arc::new(m));
            }
            let m = measure()?;
            if let Some(f) = file {
                store(&f, &key, &m);
            }
            Ok(Arc::new(m))
        })
        .clone()
}

/// The folder of the files, if there is one.
fn folder() -> Option<PathBuf> {
    match std::env::var_os("REFRAST_PROFILE_CACHE") {
        Some(v) if v == "off" || v.is_empty() => None,
        Some(v) => Some(PathBuf::from(v)),
        None => std::env::current_exe()
            .ok()?
            .ancestors()
            .find(|d| d.join("CACHEDIR.TAG").is_file())
            .map(|target| target.join("refrast-profiles")),
    }
}

/// Everything whose change must measure again, on one line.
#[must_use]
pub fn key(driver: Driver, info: &wgpu::AdapterInfo) -> String {
    // FNV-1a: stable across Rust releases, unlike `DefaultHasher`.
    let hash = SOURCES
        .iter()
        .flat_map(|s| s.bytes())
        .fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
        });
    let icds: Vec<String> = driver
        .env()
        .iter()
        .filter(|(name, _)| *name == "VK_ICD_FILENAMES")
        .flat_map(|(_, files)| files.split(':'))
        .map(|icd| format!("{} {}", stamp(Path::new(icd)), stamp(&library(Path::new(icd)))))
        .collect();
    format!(
        "{} | {} | {:#x} {:#x} | {} | {} | icd {} | probes {hash:016x}",
        driver.name(),
        info.name,
        info.vendor,
        info.device,
        info.driver,
        info.driver_info,
        icds.join(", ")
    )
    .replace('\n', " ")
}

/// A file's path, size and modification time, or that it is missing.
fn stamp(path: &Path) -> String {
    let meta = std::fs::metadata(path);
    let modified = meta
        .as_ref()
        .ok()
        .and_then(|m| m.modified().ok())
        .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok());
    match (meta, modified) {
        (Ok(m), Some(t)) => format!(
            "{} {} bytes {}.{:09}",
            path.display(),
            m.len(),
            t.as_secs(),
            t.subsec_nanos()
        ),
        _ => format!("{} missing", path.display()),
    }
}

/// The library an ICD file names (`"library_path": "…"`), beside it when relative.
fn library(icd: &Path) -> PathBuf {
    let text = std::fs::read_to_string(icd).unwrap_or_default();
    let value = text
        .split_once("\"library_path\"")
        .and_then(|(_, rest)| rest.split('"').nth(1))
        .unwrap_or_default();
    icd.parent().unwrap_or(Path::new("")).join(value)
}

/// The measured profile the file holds under `key`, if it does.
fn load(file: &Path, key: &str) -> Option<Measured> {
    let text = std::fs::read_to_string(file).ok()?;
    let mut lines = text.lines();
    if lines.next()? != key {
        return None;
    }
    let fields: HashMap<&str, &str> = lines.filter_map(|l| l.split_once(" = ")).collect();
    let get = |name: &str| fields.get(name).copied();
    Some(Measured {
        snapping: match get("snapping")? {
            "float" => Snapping::Float,
            bits => Snapping::Grid(bits.parse().ok()?),
        },
        fill: match get("fill")? {
            "none" => None,
            name => Some(*FillConvention::ALL.iter().find(|c| format!("{c:?}") == name)?),
        },
        ties_to_even: get("ties_to_even")?.parse().ok()?,
        snap: {
            let snap = get("snap")?;
            *SnapAccuracy::ALL.iter().find(|a| format!("{a:?}") == snap)?
        },
        guard_band: get("guard_band")?.parse().ok()?,
        precision_bits: get("precision_bits")?.parse().ok()?,
        tolerance_subpixels: get("tolerance_subpixels")?.parse().ok()?,
        lines: match get("lines")? {
            "none" => None,
            name => Some(LineRule::from_name(name)?),
        },
        points: get("points")?.parse().ok()?,
        point_snapping: match get("point_snapping")? {
            "triangles" => None,
            "float" => Some(Snapping::Float),
            bits => Some(Snapping::Grid(bits.parse().ok()?)),
        },
        endpoint_snapping: match get("endpoint_snapping")? {
            "triangles" => None,
            "float" => Some(Snapping::Float),
            bits => Some(Snapping::Grid(bits.parse().ok()?)),
        },
        point_clipping: PointClipping::from_name(get("point_clipping")?)?,
        bias_slope: DepthSlope::from_name(get("bias_slope")?)?,
        multisample: match get("samples")? {
            "none" => Vec::new(),
            list => {
                let positions: Option<Vec<[u8; 2]>> = list
                    .split(' ')
                    .map(|p| {
                        let (x, y) = p.split_once(',')?;
                        Some([x.parse().ok()?, y.parse().ok()?])
                    })
                    .collect();
                vec![SamplePattern::new(&positions?).ok()?]
            }
        },
        reported: get("reported")?.to_owned(),
        why: get("why")?.to_owned(),
    })
}

/// A grid of its own as the file holds it: `triangles` for none, `float`, or its bits.
fn grid_name(snapping: Option<Snapping>) -> String {
    match snapping {
        None => "triangles".to_owned(),
        Some(Snapping::Float) => "float".to_owned(),
        Some(Snapping::Grid(bits)) => bits.to_string(),
    }
}

/// The sample pattern as the file holds it: `x,y` per sample, or `none`.
fn samples(m: &Measured) -> String {
    match m.multisample.first() {
        Some(pattern) => pattern
            .positions()
            .iter()
            .map(|[x, y]| format!("{x},{y}"))
            .collect::<Vec<_>>()
            .join(" "),
        None => "none".to_owned(),
    }
}

/// Writes `m` under `key`, through a file of this process's own renamed into place, so that
/// rules measuring at once never read half a file; a failure to write only costs measuring.
fn store(file: &Path, key: &str, m: &Measured) {
    let text = format!(
        "{key}\nsnapping = {}\nfill = {}\nties_to_even = {}\nsnap = {:?}\nguard_band = {}\n\
         precision_bits = {}\ntolerance_subpixels = {}\nlines = {}\npoints = {}\npoint_snapping = {}\nendpoint_snapping = {}\n\
         samples = {}\n\
         point_clipping = {}\nbias_slope = {}\nreported = {}\nwhy = {}\n",
        match m.snapping {
            Snapping::Grid(bits) => bits.to_string(),
            Snapping::Float => "float".to_owned(),
        },
        m.fill.map_or_else(|| "none".to_owned(), |c| format!("{c:?}")),
        m.ties_to_even,
        m.snap,
        m.guard_band,
        m.precision_bits,
        m.tolerance_subpixels,
        m.lines.map_or("none", LineRule::name),
        m.points,
        grid_name(m.point_snapping),
        grid_name(m.endpoint_snapping),
        samples(m),
        m.point_clipping.name(),
        m.bias_slope.name(),
        m.reported,
        m.why
    );
    let partial = file.with_extension(format!("{}.partial", std::process::id()));
    let written = file
        .parent()
        .map_or(Ok(()), std::fs::create_dir_all)
        .and_then(|()| std::fs::write(&partial, text))
        .and_then(|()| std::fs::rename(&partial, file));
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What is stored reads back as it was, under its key only.
    #[test]
    fn a_stored_profile_reads_back() {
        let dir = std::env::temp_dir().join(format!("refrast-cache-test-{}", std::process::id()));
        let file = dir.join("lavapipe.txt");
        let m = Measured {
            snapping: Snapping::Grid(4),
            fill: Some(FillConvention::BottomRight),
            ties_to_even: true,
            snap: SnapAccuracy::WithinOneStep,
            guard_band: 0,
            precision_bits: 11,
            tolerance_subpixels: 1,
            lines: Some(LineRule::Parallelogram),
            points: true,
            point_snapping: None,
            endpoint_snapping: Some(Snapping::Grid(4)),
            multisample: SamplePattern::standard(4).into_iter().collect(),
            point_clipping: PointClipping::AllClipPlanes,
            bias_slope: DepthSlope::Max,
            reported: "SwiftShader driver (driverVersion 5.0.0)".into(),
            why: "4 subpixel bits (vulkaninfo; probe agrees), top-left (38/38)".into(),
        };
        store(&file, "the key", &m);
        assert_eq!(load(&file, "the key"), Some(m.clone()));
        assert_eq!(load(&file, "another key"), None);
        let float = Measured {
            snapping: Snapping::Float,
            fill: None,
            lines: None,
            points: false,
            point_snapping: Some(Snapping::Grid(4)),
            endpoint_snapping: None,
            multisample: vec![SamplePattern::new(&[[1, 2], [3, 4], [5, 6], [7, 8]]).expect("4 samples")],
            point_clipping: PointClipping::UserClipPlanesOnly,
            bias_slope: DepthSlope::Either,
            ..m
        };
        store(&file, "the key", &float);
        assert_eq!(load(&file, "the key"), Some(float));
        std::fs::remove_dir_all(&dir).expect("the test's folder");
    }
}
