//! `vulkaninfo`'s text parsed whatever its layout, and the device wgpu picked chosen from it.

use refrast::PointClipping;

use super::{Reported, choose, parse};

/// `vulkaninfo` 1.3.239 with lavapipe's and SwiftShader's ICDs both loaded, trimmed to the lines
/// read and a few of the same shape that must not be (`GPU id = …`, `subTexelPrecisionBits`, the
/// driver name printed twice).
const TWO: &str = include_str!("two-devices.txt");

fn info(name: &str, vendor: u32, device: u32) -> wgpu::AdapterInfo {
    wgpu::AdapterInfo {
        name: name.to_owned(),
        vendor,
        device,
        ..wgpu::AdapterInfo::new(wgpu::DeviceType::Cpu, wgpu::Backend::Vulkan)
    }
}

#[test]
fn every_device_is_read() {
    let devices = parse(TWO);
    assert_eq!(devices.len(), 2);
    assert_eq!(
        devices[0],
        Reported {
            device_name: "SwiftShader Device (Subzero)".into(),
            vendor_id: 0x1ae0,
            device_id: 0xc0de,
            driver_name: "SwiftShader driver".into(),
            driver_info: String::new(),
            driver_version: "5.0.0 (20971520)".into(),
            api_version: "1.3.0 (4206592)".into(),
            subpixel_bits: Some(4),
            point_clipping: Some(PointClipping::AllClipPlanes),
        }
    );
    assert_eq!(devices[1].subpixel_bits, Some(8));
    assert_eq!(devices[1].driver_info, "Mesa 22.3.6 (LLVM 15.0.6)");
    assert_eq!(
        devices[1].describe(),
        "llvmpipe Mesa 22.3.6 (LLVM 15.0.6) (driverVersion 0.0.1 (1), Vulkan 1.3.230 (4206822))"
    );
}

/// CRLF line endings and spaces for tabs read the same.
#[test]
fn layout_does_not_matter() {
    let crlf = TWO.replace('\t', "    ").replace('\n', "\r\n");
    assert_eq!(parse(&crlf), parse(TWO));
    assert!(parse("no devices here\nGPU id = 0 (x)\n").is_empty());
}

/// The adapter wgpu picked, by IDs and name; by name alone when the IDs differ; none when
/// neither matches or the device prints no subpixel precision.
#[test]
fn the_adapter_is_chosen() {
    let devices = parse(TWO);
    let lavapipe = info("llvmpipe (LLVM 15.0.6, 256 bits)", 0x10005, 0);
    assert_eq!(
        choose(&devices, &lavapipe).map(|d| d.subpixel_bits),
        Some(Some(8))
    );
    let renamed = info("SwiftShader Device (Subzero)", 0, 0);
    assert_eq!(choose(&devices, &renamed).map(|d| d.device_id), Some(0xc0de));
    assert!(choose(&devices, &info("NVIDIA GeForce", 0x10de, 1)).is_none());
    let no_limits = parse(&TWO.replace("subPixelPrecisionBits", "somethingElse"));
    assert!(choose(&no_limits, &lavapipe).is_none());
}

/// `pointClippingBehavior` reads either way Vulkan spells it, and a device printing none has
/// none read (the profile then takes Vulkan 1.0's `ALL_CLIP_PLANES`).
#[test]
fn point_clipping_is_read() {
    let user = TWO.replacen(
        "CLIPPING_BEHAVIOR_ALL_CLIP_PLANES",
        "CLIPPING_BEHAVIOR_USER_CLIP_PLANES_ONLY",
        1,
    );
    let devices = parse(&user);
    assert_eq!(devices[0].point_clipping, Some(PointClipping::UserClipPlanesOnly));
    assert_eq!(devices[1].point_clipping, Some(PointClipping::AllClipPlanes));
    assert_eq!(
        PointClipping::from_name("VK_POINT_CLIPPING_BEHAVIOR_USER_CLIP_PLANES_ONLY"),
        Some(PointClipping::UserClipPlanesOnly)
    );
    assert_eq!(
        PointClipping::from_name("all-clip-planes"),
        Some(PointClipping::AllClipPlanes)
    );
    assert_eq!(PointClipping::from_name("SOMETIMES"), None);
    let silent = parse(&TWO.replace("pointClippingBehavior", "somethingElse"));
    assert_eq!(silent[0].point_clipping, None);
}
