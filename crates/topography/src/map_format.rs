//! The height-map file formats: names, extensions and whether a format has magic bytes (a leaf
//! of the module graph, used by the readers in `read` and `formats`).

use std::path::Path;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A height-map file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MapFormat {
    /// NumPy `.npy`: a 2-D float32 or float64 array, C or Fortran order; rows are y.
    Npy,
    /// A text grid: one row of heights per line, separated by commas, semicolons, tabs or spaces;
    /// `#` lines may carry Gwyddion's ASCII export header (`Width`, `Height`, `Value units`).
    Text,
    /// Gwyddion simple field `.gsf` (float32 heights with `XRes`, `YRes`, `XReal`, `YReal`,
    /// `XYUnits`, `ZUnits`).
    Gsf,
    /// x y z points (one per line) on a regular grid, in any order; absent points are missing.
    Xyz,
    /// Bruker / Veeco NanoScope (`.spm`, `.di`, `.001`, ...): int16/int32 images with a text header.
    Nanoscope,
    /// Igor binary wave version 5 (`.ibw`, Asylum Research AFMs): channels as layers.
    Ibw,
    /// ISO 25178-71 surface data file (`.sdf`), ASCII or binary.
    Sdf,
    /// ISO 25178-72 XML surface profile (`.x3p`): a zip of `main.xml` and the binary points.
    X3p,
    /// Digital Surf / MountainsMap `.sur` (uncompressed): int16/int32 with non-measured points.
    Sur,
    /// Wyko / Bruker Vision `.opd` (white-light interferometers), undefined points missing.
    Opd,
    /// Sensofar `.plu` (confocal and interferometric profilers): float32 µm heights, non-measured points missing.
    Plu,
    /// Zygo MetroPro `.dat` (interferometers): int32 phase with the scale in the header, invalid points missing.
    Metropro,
    /// netCDF classic or 64-bit offset `.nc` as contact.engineering writes a map (`heights(x, y)`, `x:length`, `x:unit`, `mask`).
    Netcdf,
    /// WSxM `.stp`, `.top` (Nanotec AFMs): a text header and double, float or int16 samples.
    Wsxm,
    /// Agilent / Keysight PicoView `.mi` (AFMs): int16/int32 buffers with their range and unit.
    Mi,
    /// Nanosurf `.nid`, `.ezd` (AFMs): an INI header and binary data sets, one channel each.
    Nid,
    /// Alicona `.al3d` (focus-variation microscopes): float32 depth in metres, invalid points missing.
    Al3d,
    /// Park Systems AFM TIFF (`.tiff`, `.tif` with the Park tags): int16/int32/float32 with gain, scale and offset.
    Park,
}

impl MapFormat {
    /// The format a file name suggests: `.npy`, `.gsf`, `.xyz`, else a text grid (`.csv`, `.txt`,
    /// `.asc`, `.dat`, ...).
    pub fn from_path(path: &Path) -> MapFormat {
        MapFormat::from_extension(path).unwrap_or(MapFormat::Text)
    }

    /// The format a file's extension names, if it names one: `.npy`, `.gsf`, `.xyz`, `.txt`,
    /// `.csv`, `.asc` (text), `.spm`, `.di` and three-digit extensions `.001`... (NanoScope),
    /// `.ibw`, `.sdf`, `.x3p`, `.sur`, `.opd`.
    pub fn from_extension(path: &Path) -> Option<MapFormat> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase)?;
        Some(match ext.as_str() {
            "npy" => MapFormat::Npy,
            "gsf" => MapFormat::Gsf,
            "xyz" => MapFormat::Xyz,
            "txt" | "csv" | "asc" | "tsv" => MapFormat::Text,
            "spm" | "di" => MapFormat::Nanoscope,
            e if e.len() == 3 && e.bytes().all(|b| b.is_ascii_digit()) => MapFormat::Nanoscope,
            "ibw" => MapFormat::Ibw,
            "sdf" => MapFormat::Sdf,
            "x3p" => MapFormat::X3p,
            "sur" => MapFormat::Sur,
            "opd" => MapFormat::Opd,
            "plu" => MapFormat::Plu,
            "nc" => MapFormat::Netcdf,
            "stp" | "top" => MapFormat::Wsxm,
            "mi" => MapFormat::Mi,
            "nid" | "ezd" => MapFormat::Nid,
            "al3d" => MapFormat::Al3d,
            "tiff" | "tif" => MapFormat::Park,
            _ => return None,
        })
    }

    /// Whether the format is recognised by its first bytes ([`crate::detect`]).
    pub fn has_magic(self) -> bool {
        !matches!(self, MapFormat::Text | MapFormat::Xyz)
    }

    /// The format's name as in scenario files and flags.
    pub fn name(self) -> &'static str {
        match self {
            MapFormat::Npy => "npy",
            MapFormat::Text => "text",
            MapFormat::Gsf => "gsf",
            MapFormat::Xyz => "xyz",
            MapFormat::Nanoscope => "nanoscope",
            MapFormat::Ibw => "ibw",
            MapFormat::Sdf => "sdf",
            MapFormat::X3p => "x3p",
            MapFormat::Sur => "sur",
            MapFormat::Opd => "opd",
            MapFormat::Plu => "plu",
            MapFormat::Metropro => "metropro",
            MapFormat::Netcdf => "netcdf",
            MapFormat::Wsxm => "wsxm",
            MapFormat::Mi => "mi",
            MapFormat::Nid => "nid",
            MapFormat::Al3d => "al3d",
            MapFormat::Park => "park",
        }
    }
}
