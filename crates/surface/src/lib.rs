//! stiction-surface: the rough sidewall as a list of spherical summits.
//!
//! The Greenwood-Williamson picture of the paper (section 3.1): a rough face is a set of summits,
//! each a sphere cap of radius R with its top at a height above the reference plane, over the
//! apparent contact area A_a. This crate
//!
//! * stores such a list memory-lean as a struct of arrays ([`Surface`], 16-24 bytes per summit),
//! * generates it from the statistical parameters with a portable seeded generator ([`generate`]:
//!   Poisson or jittered-grid positions of density eta, Gaussian or exponential heights of SD sigma,
//!   fixed or lognormal radii), for two faces as the paper's composite ([`generate_composite`]) or
//!   explicitly, shoe summits meeting wall summits ([`generate_two_face`]); version 2 of the
//!   random stream ([`generate_v2`], [`generate_composite_v2`], `surface.generator: 2`) draws the
//!   same field about twice as fast, block-wise and on several threads,
//! * reports sample statistics to compare with the requested parameters ([`Surface::stats`]),
//! * writes and reads CSV (`x_m,y_m,height_m,radius_m`, SI) and NumPy `.npy` (an N x 4 float64
//!   array, a structured array, or heights alone) so measured summit lists can be used,
//! * finds summits on a patch of a measured height map (`source` = "height_map", via
//!   `stiction-topography`),
//! * and describes all of this for scenario files ([`SurfaceSpec`]).
//!
//! All quantities are SI (metres, m^-2).

mod blockwise_xoshiro;
mod build;
mod csv_io;
mod error;
mod face;
mod height_map;
mod npy_io;
mod sequential_chacha;
mod spec;
mod surface;

pub use blockwise_xoshiro::{Xoshiro256pp, generate_composite_v2, generate_v2};
pub use csv_io::CSV_HEADER;
pub use error::SurfaceError;
pub use face::{FaceParams, HeightDistribution, Layout, MAX_SUMMITS, Placement, RadiusDistribution};
pub use height_map::{MapSummitStatistics, height_map_patch, height_map_tiling, map_summit_statistics};
pub use npy_io::{
    NPY_MAX_BYTES_PER_SUMMIT, NPY_MAX_HEADER_BYTES, NpySummits, npy_header, npy_surface, read_npy_summits,
    read_npy_summits_file,
};
pub use sequential_chacha::{
    generate, generate_composite, generate_two_face, generate_two_face_limited, uniform_positions,
};
pub use spec::{
    DEFAULT_MAX_SUMMITS, ESTIMATED_BYTES_PER_SUMMIT, FaceSpec, MAX_LENGTH_M, SurfaceSource, SurfaceSpec, TwoFaceMode,
};
pub use surface::{Radii, Surface, SurfaceStats};
