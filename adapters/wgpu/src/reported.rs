//! What a Vulkan driver reports about itself, read from `vulkaninfo`: wgpu's adapter gives no
//! `VkPhysicalDeviceLimits`, and `subPixelPrecisionBits` is the grid Vulkan holds it to.

use std::process::{Command, Stdio};

use refrast::{PointClipping, Unavailable};

use crate::device::Driver;

/// One device's properties, as `vulkaninfo` prints them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Reported {
    /// `deviceName`.
    pub device_name: String,
    /// `vendorID`.
    pub vendor_id: u32,
    /// `deviceID`.
    pub device_id: u32,
    /// `driverName` (Vulkan 1.2's driver properties; empty when not printed).
    pub driver_name: String,
    /// `driverInfo`, likewise.
    pub driver_info: String,
    /// `driverVersion`, as printed (`5.0.0 (20971520)`).
    pub driver_version: String,
    /// `apiVersion`, as printed.
    pub api_version: String,
    /// `subPixelPrecisionBits`, when printed.
    pub subpixel_bits: Option<u8>,
    /// `pointClippingBehavior` (Vulkan 1.1's point clipping properties), when printed.
    pub point_clipping: Option<PointClipping>,
}

impl Reported {
    /// The driver and its version, as a report names them.
    #[must_use]
    pub fn describe(&self) -> String {
        let name = if self.driver_name.is_empty() {
            &self.device_name
        } else {
            &self.driver_name
        };
        format!(
            "{name} {} (driverVersion {}, Vulkan {})",
            self.driver_info, self.driver_version, self.api_version
        )
        .replace("  ", " ")
    }
}

/// How `vulkaninfo` is installed, for the message when it is not.
const INSTALL: &str = "on Debian, apt-get install vulkan-tools";

/// Runs `vulkaninfo` with `driver`'s environment and returns the device that is the adapter
/// wgpu chose (`info`): same vendor and device IDs and name, or the same name alone.
pub fn read(driver: Driver, info: &wgpu::AdapterInfo) -> Result<Reported, Unavailable> {
    let mut command = Command::new("vulkaninfo");
    for (name, value) in driver.env() {
        command.env(name, value);
    }
    let output = command
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output()
        .map_err(|e| {
            Unavailable(format!(
                "{} reports its subpixel precision only through Vulkan's limits, read with \
                 vulkaninfo, which could not be run ({e}); {INSTALL}",
                driver.name()
            ))
        })?;
    let text = String::from_utf8_lossy(&output.stdout);
    let devices = parse(&text);
    choose(&devices, info).cloned().ok_or_else(|| {
        let found: Vec<&str> = devices.iter().map(|d| d.device_name.as_str()).collect();
        Unavailable(format!(
            "vulkaninfo ({}) lists no device {:?} (vendor {:#x}, device {:#x}) with its \
             subPixelPrecisionBits; it lists {found:?}",
            output.status, info.name, info.vendor, info.device
        ))
    })
}

/// Why `driver` cannot be measured here, when it is a Vulkan driver and `vulkaninfo` is on no
/// folder of `PATH` (checked even when the profile is cached, so that a driver is available or
/// not whatever was measured before).
#[must_use]
pub fn missing(driver: Driver) -> Option<Unavailable> {
    let vulkan = driver.backends() == wgpu::Backends::VULKAN;
    let found = std::env::var_os("PATH")
        .is_some_and(|path| std::env::split_paths(&path).any(|dir| dir.join("vulkaninfo").is_file()));
    (vulkan && !found).then(|| {
        Unavailable(format!(
            "{}'s subpixel grid is its Vulkan subPixelPrecisionBits, which wgpu does not give and \
             vulkaninfo is not installed to read; {INSTALL}",
            driver.name()
        ))
    })
}

/// The device that is `info`, among `devices` that print a subpixel precision.
#[must_use]
pub fn choose<'a>(devices: &'a [Reported], info: &wgpu::AdapterInfo) -> Option<&'a Reported> {
    let usable = || devices.iter().filter(|d| d.subpixel_bits.is_some());
    usable()
        .find(|d| d.device_name == info.name && d.vendor_id == info.vendor && d.device_id == info.device)
        .or_else(|| usable().find(|d| d.device_name == info.name))
}

/// Every device section (`GPU0:`, `GPU1:` …, at the start of a line) of `vulkaninfo`'s text
/// output, each from its first `key = value` of each key; line endings and indentation may be
/// anything.
#[must_use]
pub fn parse(text: &str) -> Vec<Reported> {
    let mut devices: Vec<Reported> = Vec::new();
    let mut seen: Vec<&str> = Vec::new();
    for line in text.lines() {
        let line = line.trim_end();
        if is_section(line) {
            devices.push(Reported::default());
            seen.clear();
            continue;
        }
        let (Some(device), Some((key, value))) = (devices.last_mut(), line.split_once('=')) else {
            continue;
        };
        let (key, value) = (key.trim(), value.trim());
        if seen.contains(&key) {
            continue;
        }
        seen.push(key);
        let hex = |v: &str| u32::from_str_radix(v.trim_start_matches("0x"), 16).ok();
        match key {
            "deviceName" => device.device_name = value.to_owned(),
            "vendorID" => device.vendor_id = hex(value).unwrap_or(u32::MAX),
            "deviceID" => device.device_id = hex(value).unwrap_or(u32::MAX),
            "driverName" => device.driver_name = value.to_owned(),
            "driverInfo" => device.driver_info = value.to_owned(),
            "driverVersion" => device.driver_version = value.to_owned(),
            "apiVersion" => device.api_version = value.to_owned(),
            "subPixelPrecisionBits" => device.subpixel_bits = value.parse().ok(),
            "pointClippingBehavior" => device.point_clipping = PointClipping::from_name(value),
            _ => {}
        }
    }
    devices
}

/// Whether `line` opens a device's section: `GPU` and a number, then a colon, unindented.
fn is_section(line: &str) -> bool {
    line.strip_prefix("GPU")
        .and_then(|rest| rest.strip_suffix(':'))
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
}

#[cfg(test)]
mod tests;
