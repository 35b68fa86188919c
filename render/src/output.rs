//! Writing pictures: PNG through a temporary file renamed into place, so an interrupted run
//! never leaves a broken image where one is expected.

use std::io::Write;
use std::path::Path;

use refrast::pipeline::Framebuffer;

/// Writes `target`'s colour buffer to `path` as a PNG: encoded in memory, written to a
/// temporary file beside `path`, then renamed over it.
pub fn save_png(target: &Framebuffer, path: &Path) -> std::io::Result<()> {
    let mut png = Vec::new();
    target
        .to_image()
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(std::io::Error::other)?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let name = path.file_name().ok_or_else(|| {
        std::io::Error::new(std::io::ErrorKind::InvalidInput, "the output path names no file")
    })?;
    let temporary = dir.join(format!(".{}.{}.tmp", name.to_string_lossy(), std::process::id()));
    let written = std::fs::File::create(&temporary).and_then(|mut file| {
        file.write_all(&png)?;
        file.sync_all()
    });
    match written.and_then(|()| std::fs::rename(&temporary, path)) {
        Ok(()) => Ok(()),
        Err(e) => {
            // Best effort: the temporary file is ours and useless now.
            let _ = std::fs::remove_file(&temporary);
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_a_png_and_leaves_no_temporary_file() {
        let dir = std::env::temp_dir().join(format!("refrast-render-output-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.png");
        let mut target = Framebuffer::new(3, 2).unwrap();
        target.clear([10, 20, 30, 255], 1.0);
        save_png(&target, &path).unwrap();
        let image = image::open(&path).unwrap().to_rgba8();
        assert_eq!(image.dimensions(), (3, 2));
        assert_eq!(image.get_pixel(2, 1).0, [10, 20, 30, 255]);
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("a.png")]);
        // A folder that does not exist: an error, and nothing written.
        assert!(save_png(&target, &dir.join("missing/b.png")).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
