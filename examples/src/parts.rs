//! A picture rendered in parts on several machines: `render --tile K/N`
//! renders band `K` of `N` bands of rows ([`band`]) through
//! [`rt_runtime::Context::launch_part`], so every program sees the whole
//! picture's size and its pixel's place in it (the same seeds, the same
//! rays), and writes it as a part file ([`Part`]); `render --merge`
//! checks that the parts belong together and cover the picture once, and
//! puts them together bit for bit ([`merge`]). A job runner spreads the
//! parts (a Slurm array, a Kubernetes indexed Job, GNU parallel); there is
//! no scheduler here.
//!
//! A part file is a text header, then the band's pixels as little-endian
//! f32 RGBA in launch-index order (row 0 at the bottom):
//!
//! ```text
//! rt-part 1
//! size 640 480
//! tile 2 4
//! rows 240 360
//! settings <the render's settings, one line>
//! pixels <FNV-1a 64 of the pixel bytes, hex>
//!
//! ```

use crate::scene::{Error, Image};
use glam::Vec4;
use std::ops::Range;
use std::path::{Path, PathBuf};

const MAGIC: &str = "rt-part 1";

/// The most parts a picture is cut into.
pub const MAX_PARTS: u32 = 4096;

/// The longest header a part file has (its settings line is what grows).
const MAX_HEADER: usize = 64 << 10;

/// `text` cut to a length an error line can quote.
fn quoted(text: &str) -> String {
    const MAX: usize = 80;
    match text.char_indices().nth(MAX) {
        Some((i, _)) => format!("{}...", &text[..i]),
        None => text.to_string(),
    }
}

/// The rows of band `k` of `n` of a picture `height` rows high: bands
/// start on multiples of 8 rows (the launch's block grid), the last ends at
/// the top. An error when `k >= n` or when a band would be empty.
pub fn band(height: u32, k: u32, n: u32) -> Result<Range<u32>, Error> {
    if n == 0 || k >= n {
        return Err(Error::Settings(format!("--tile {k}/{n}: K must be below N (parts are numbered from 0)")));
    }
    if n > MAX_PARTS || n > height.div_ceil(8).max(1) {
        return Err(Error::Settings(format!(
            "--tile {k}/{n}: {height} rows make at most {} parts (bands of whole 8-row blocks, at most {MAX_PARTS})",
            height.div_ceil(8).clamp(1, MAX_PARTS)
        )));
    }
    let edge = |i: u32| if i == n { height } else { ((i as u64 * height as u64 / n as u64) as u32) / 8 * 8 };
    let rows = edge(k)..edge(k + 1);
    if (0..n).any(|i| edge(i) >= edge(i + 1)) {
        return Err(Error::Settings(format!(
            "--tile {k}/{n}: {height} rows make at most {} parts (bands of whole 8-row blocks)",
            height.div_ceil(8).max(1)
        )));
    }
    Ok(rows)
}

/// Parses `K/N`.
pub fn parse_tile(text: &str) -> Result<(u32, u32), Error> {
    let bad = || Error::Settings(format!("--tile `{text}`: expected K/N, as in 0/4 (part K of N, from 0)"));
    let (k, n) = text.split_once('/').ok_or_else(bad)?;
    Ok((k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?))
}

/// One band of a picture, with what it belongs to.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    /// The whole picture's size.
    pub width: u32,
    pub height: u32,
    /// Which part of how many.
    pub tile: (u32, u32),
    /// The band's rows.
    pub rows: Range<u32>,
    /// The settings it was rendered with (one line): parts merge only with
    /// parts of the same settings.
    pub settings: String,
    /// The band's pixels, row by row.
    pub pixels: Vec<Vec4>,
}

impl Part {
    /// Band `tile` of `image` (which holds the whole picture, of which
    /// only the band's rows need be rendered).
    pub fn of(image: &Image, tile: (u32, u32), settings: &str) -> Result<Part, Error> {
        let rows = band(image.height, tile.0, tile.1)?;
        let w = image.width as usize;
        let pixels = image.pixels[rows.start as usize * w..rows.end as usize * w].to_vec();
        let settings = settings.replace(['\n', '\r'], " ");
        Ok(Part { width: image.width, height: image.height, tile, rows, settings, pixels })
    }

    fn pixel_bytes(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.to_array()).flat_map(f32::to_le_bytes).collect()
    }

    /// Writes the part file whole or not at all.
    pub fn save(&self, path: &Path) -> Result<(), Error> {
        let bytes = self.pixel_bytes();
        let mut out = format!(
            "{MAGIC}\nsize {} {}\ntile {} {}\nrows {} {}\nsettings {}\npixels {:016x}\n\n",
            self.width,
            self.height,
            self.tile.0,
            self.tile.1,
            self.rows.start,
            self.rows.end,
            self.settings,
            fnv1a(&bytes)
        )
        .into_bytes();
        out.extend(bytes);
        crate::scene::write_whole(path, out)
    }

    /// Reads a part file, checking its header, its length and its pixels'
    /// hash. Only a regular file no longer than the largest picture's
    /// part is read, and the header's sizes are checked against the
    /// file's length before anything is allocated for its pixels.
    pub fn load(path: &Path) -> Result<Part, Error> {
        let bad = |problem: String| Error::Part { path: path.display().to_string(), problem };
        let max_bytes = MAX_HEADER as u64 + crate::Settings::MAX_PIXELS * 16;
        let limits = rt_scene::LoadLimits { max_file_bytes: max_bytes, ..Default::default() };
        let bytes = rt_scene::limits::read_file(path, &limits).map_err(bad)?;
        let end = bytes[..bytes.len().min(MAX_HEADER)]
            .windows(2)
            .position(|w| w == b"\n\n")
            .ok_or_else(|| bad(format!("not a part file (no header in its first {MAX_HEADER} bytes)")))?;
        let header = std::str::from_utf8(&bytes[..end]).map_err(|_| bad("not a part file (header not text)".into()))?;
        let mut lines = header.lines();
        if lines.next() != Some(MAGIC) {
            return Err(bad(format!("not a part file (it does not begin with `{MAGIC}`)")));
        }
        let mut field = |name: &str| -> Result<String, Error> {
            let line = lines.next().unwrap_or_default();
            line.strip_prefix(name)
                .and_then(|rest| rest.strip_prefix(' '))
                .map(str::to_string)
                .ok_or_else(|| bad(format!("header line `{}` should begin with `{name}`", quoted(line))))
        };
        let pair = |text: String, name: &str| -> Result<(u32, u32), Error> {
            let mut it = text.split(' ').map(str::parse::<u32>);
            match (it.next(), it.next(), it.next()) {
                (Some(Ok(a)), Some(Ok(b)), None) => Ok((a, b)),
                _ => Err(bad(format!("`{name} {}` is not two numbers", quoted(&text)))),
            }
        };
        let (width, height) = pair(field("size")?, "size")?;
        let pixels = width as u64 * height as u64;
        if pixels == 0 || pixels > crate::Settings::MAX_PIXELS {
            return Err(bad(format!("size {width}x{height} is not a picture a render makes")));
        }
        let tile = pair(field("tile")?, "tile")?;
        let (y0, y1) = pair(field("rows")?, "rows")?;
        let settings = field("settings")?;
        let hash = field("pixels")?;
        let expected = band(height, tile.0, tile.1).map_err(|e| bad(e.to_string()))?;
        if expected != (y0..y1) {
            return Err(bad(format!("rows {y0}..{y1} are not band {} of {} ({expected:?})", tile.0, tile.1)));
        }
        let data = &bytes[end + 2..];
        let want = (y1 - y0) as usize * width as usize * 16;
        if data.len() != want {
            return Err(bad(format!("{} bytes of pixels where rows {y0}..{y1} of {width} need {want}", data.len())));
        }
        if format!("{:016x}", fnv1a(data)) != hash {
            return Err(bad("its pixels do not match their hash (the file is damaged)".into()));
        }
        let pixels = data
            .chunks_exact(16)
            .map(|c| {
                Vec4::from_array(std::array::from_fn(|i| f32::from_le_bytes(c[i * 4..i * 4 + 4].try_into().unwrap())))
            })
            .collect();
        Ok(Part { width, height, tile, rows: y0..y1, settings, pixels })
    }
}

/// Puts parts together: they must share the size, the count of parts and
/// the settings, and hold every part once.
pub fn merge(parts: &[(PathBuf, Part)]) -> Result<Image, Error> {
    let Some((first_path, first)) = parts.first() else {
        return Err(Error::Settings("--merge needs at least one part file".into()));
    };
    let n = first.tile.1;
    let mut seen: Vec<Option<&Path>> = vec![None; n as usize];
    for (path, p) in parts {
        let differ = |what: &str, a: String, b: String| Error::Part {
            path: path.display().to_string(),
            problem: format!("its {what} ({b}) is not that of {} ({a})", first_path.display()),
        };
        if (p.width, p.height) != (first.width, first.height) {
            return Err(differ(
                "size",
                format!("{}x{}", first.width, first.height),
                format!("{}x{}", p.width, p.height),
            ));
        }
        if p.tile.1 != n {
            return Err(differ("count of parts", n.to_string(), p.tile.1.to_string()));
        }
        if p.settings != first.settings {
            return Err(differ("settings", quoted(&first.settings), quoted(&p.settings)));
        }
        if let Some(other) = seen[p.tile.0 as usize].replace(path) {
            return Err(Error::Part {
                path: path.display().to_string(),
                problem: format!("it is part {} of {n}, as {} is", p.tile.0, other.display()),
            });
        }
    }
    let missing: Vec<u32> = (0..n).filter(|&k| seen[k as usize].is_none()).collect();
    if !missing.is_empty() {
        let mut list: Vec<String> = missing.iter().take(8).map(u32::to_string).collect();
        if missing.len() > 8 {
            list.push(format!("and {} more", missing.len() - 8));
        }
        return Err(Error::Settings(format!("--merge: part {} of {n} missing", list.join(", "))));
    }
    let (w, h) = (first.width as usize, first.height as usize);
    let mut pixels = vec![Vec4::ZERO; w * h];
    for (_, p) in parts {
        pixels[p.rows.start as usize * w..p.rows.end as usize * w].copy_from_slice(&p.pixels);
    }
    Ok(Image { width: first.width, height: first.height, pixels })
}

/// FNV-1a, 64 bits: a part's pixels' check, and the model file's in its
/// settings.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ *b as u64).wrapping_mul(0x0000_0100_0000_01b3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_start_on_whole_blocks_and_cover_the_rows_once() {
        for (h, n) in [(480, 4), (37, 3), (8, 1), (100, 12), (1, 1)] {
            let mut next = 0;
            for k in 0..n {
                let rows = band(h, k, n).unwrap();
                assert_eq!(rows.start, next);
                assert!(rows.start.is_multiple_of(8) && rows.end > rows.start);
                next = rows.end;
            }
            assert_eq!(next, h);
        }
        assert_eq!(band(480, 2, 4).unwrap(), 240..360);
        assert!(band(16, 0, 3).unwrap_err().to_string().contains("16 rows make at most 2 parts"));
        assert!(band(16, 3, 3).unwrap_err().to_string().contains("K must be below N"));
        assert_eq!(parse_tile("1/4").unwrap(), (1, 4));
        assert!(parse_tile("1-4").unwrap_err().to_string().contains("expected K/N"));
    }
}
