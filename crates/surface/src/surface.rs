//! The summit list of a rough face: a struct of arrays, lean enough for 1e8 summits.

use crate::SurfaceError;

/// Summit radii: one value for all summits (the paper's model) or one value per summit.
#[derive(Debug, Clone, PartialEq)]
pub enum Radii {
    /// Every summit has this radius \[m\] (costs no memory per summit).
    Uniform(f64),
    /// Radius of each summit \[m\], in summit order.
    PerSummit(Vec<f64>),
}

/// A rough face reduced to its summits (Greenwood-Williamson picture, paper section 3.1).
///
/// Summit `i` is a sphere cap of radius `radius_m(i)` whose top lies at height `height_m(i)` above
/// the reference plane (x = 0 of the paper's Fig. 1) at the lateral position `(x_m(i), y_m(i))`.
/// The apparent contact area is the rectangle `[0, apparent_length_m) x [0, apparent_width_m)`.
///
/// Storage is a struct of arrays: lateral positions as `f32` metres (relative precision 6e-8,
/// i.e. 3e-13 m over the paper's 5 um x 20 um face and 3e-10 m over a 5 mm face; lateral positions
/// only enter moment arms), heights and per-summit radii as `f64`. That is 16 bytes per summit with
/// a uniform radius and 24 bytes with per-summit radii.
///
/// Generated surfaces list their summits in descending height order (see [`crate::generate`]);
/// surfaces from CSV keep the file order.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    apparent_length_m: f64,
    apparent_width_m: f64,
    x_m: Vec<f32>,
    y_m: Vec<f32>,
    height_m: Vec<f64>,
    radius_m: Radii,
}

/// Sample statistics of a surface, to compare with the requested parameters.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SurfaceStats {
    /// Number of summits.
    pub count: usize,
    /// Summits per apparent area, eta \[m^-2\].
    pub summit_density_per_m2: f64,
    /// Mean summit height \[m\] (0 for the generators: heights are measured from the mean summit plane).
    pub height_mean_m: f64,
    /// Sample standard deviation of the summit heights, sigma \[m\] (n - 1 in the denominator).
    pub height_sd_m: f64,
    /// Lowest summit \[m\].
    pub height_min_m: f64,
    /// Highest summit \[m\].
    pub height_max_m: f64,
    /// Mean summit radius \[m\].
    pub radius_mean_m: f64,
    /// Sample standard deviation of the summit radii \[m\].
    pub radius_sd_m: f64,
    /// Smallest summit radius \[m\].
    pub radius_min_m: f64,
    /// Largest summit radius \[m\].
    pub radius_max_m: f64,
}

impl Surface {
    /// Builds a surface from its arrays, checking them.
    ///
    /// Errors when the arrays differ in length, when a value is not finite, when a radius is not
    /// positive, when a summit lies outside the apparent area, or when the apparent area is not a
    /// positive finite rectangle.
    pub fn new(
        apparent_length_m: f64,
        apparent_width_m: f64,
        x_m: Vec<f32>,
        y_m: Vec<f32>,
        height_m: Vec<f64>,
        radius_m: Radii,
    ) -> Result<Self, SurfaceError> {
        check_positive("apparent_length", apparent_length_m, "m")?;
        check_positive("apparent_width", apparent_width_m, "m")?;
        let n = height_m.len();
        if x_m.len() != n || y_m.len() != n {
            return Err(SurfaceError::Inconsistent(format!(
                "x_m has {} entries, y_m {}, height_m {}: expected equal lengths",
                x_m.len(),
                y_m.len(),
                n
            )));
        }
        match &radius_m {
            Radii::Uniform(r) => check_positive("summit_radius", *r, "m")?,
            Radii::PerSummit(r) => {
                if r.len() != n {
                    return Err(SurfaceError::Inconsistent(format!(
                        "radius_m has {} entries, height_m {}: expected equal lengths",
                        r.len(),
                        n
                    )));
                }
                if let Some((i, v)) = r.iter().enumerate().find(|(_, v)| !(v.is_finite() && **v > 0.0)) {
                    return Err(SurfaceError::Inconsistent(format!(
                        "radius_m[{i}] = {v}: expected a finite radius > 0 m"
                    )));
                }
            }
        }
        // Each check first runs as a branch-free fold (vectorised: about 1 instruction per summit
        // instead of 20 for `enumerate().find`); the failing index is only searched for on failure.
        let height_ok = |v: &f64| v.is_finite();
        if !height_m.iter().fold(true, |ok, v| ok & height_ok(v))
            && let Some((i, v)) = height_m.iter().enumerate().find(|(_, v)| !height_ok(v))
        {
            return Err(SurfaceError::Inconsistent(format!("height_m[{i}] = {v}: expected a finite height in m")));
        }
        for (name, arr, lim) in [("x_m", &x_m, apparent_length_m), ("y_m", &y_m, apparent_width_m)] {
            // f32 -> f64 is exact, so comparing in f32 against the f64 limit is the same test.
            let inside = |v: &f32| v.is_finite() & (*v >= 0.0) & (f64::from(*v) <= lim);
            if !arr.iter().fold(true, |ok, v| ok & inside(v))
                && let Some((i, v)) = arr.iter().enumerate().find(|(_, v)| !inside(v))
            {
                return Err(SurfaceError::Inconsistent(format!(
                    "{name}[{i}] = {v}: expected a position inside [0, {lim}] m (the apparent area)"
                )));
            }
        }
        Ok(Self { apparent_length_m, apparent_width_m, x_m, y_m, height_m, radius_m })
    }

    /// [`Surface::new`] for the arrays of the version 2 generator, whose values are valid by
    /// construction: positions come from `clamp_f32` of values in [0, limit] (inside the area),
    /// heights are finite draws in descending order (so only the first and last are checked), and
    /// per-summit radii are checked as by [`Surface::new`]. Saves the pass over the positions
    /// and heights (about 1-2 ns per summit, docs/performance.md).
    pub(crate) fn from_generated_descending(
        apparent_length_m: f64,
        apparent_width_m: f64,
        x_m: Vec<f32>,
        y_m: Vec<f32>,
        height_m: Vec<f64>,
        radius_m: Radii,
    ) -> Result<Self, SurfaceError> {
        let ends_finite =
            height_m.first().is_none_or(|v| v.is_finite()) && height_m.last().is_none_or(|v| v.is_finite());
        if !ends_finite {
            // Not expected (finite draws of a finite SD); the full check names the summit.
            return Self::new(apparent_length_m, apparent_width_m, x_m, y_m, height_m, radius_m);
        }
        debug_assert!(height_m.windows(2).all(|w| w[0] >= w[1]));
        let heightless =
            Self::new(apparent_length_m, apparent_width_m, Vec::new(), Vec::new(), Vec::new(), Radii::Uniform(1.0))?;
        let n = height_m.len();
        if x_m.len() != n || y_m.len() != n {
            return Err(SurfaceError::Inconsistent(format!(
                "x_m has {} entries, y_m {}, height_m {n}: expected equal lengths",
                x_m.len(),
                y_m.len()
            )));
        }
        match &radius_m {
            Radii::Uniform(r) => check_positive("summit_radius", *r, "m")?,
            Radii::PerSummit(r) => {
                if r.len() != n || r.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
                    return Self::new(apparent_length_m, apparent_width_m, x_m, y_m, height_m, radius_m);
                }
            }
        }
        Ok(Self { x_m, y_m, height_m, radius_m, ..heightless })
    }

    /// Number of summits.
    pub fn len(&self) -> usize {
        self.height_m.len()
    }

    /// True when the surface has no summit.
    pub fn is_empty(&self) -> bool {
        self.height_m.is_empty()
    }

    /// Length of the apparent contact area along x \[m\].
    pub fn apparent_length_m(&self) -> f64 {
        self.apparent_length_m
    }

    /// Width of the apparent contact area along y \[m\].
    pub fn apparent_width_m(&self) -> f64 {
        self.apparent_width_m
    }

    /// Apparent contact area A_a = length x width \[m^2\].
    pub fn apparent_area_m2(&self) -> f64 {
        self.apparent_length_m * self.apparent_width_m
    }

    /// Lateral x position of summit `i` \[m\].
    pub fn x_m(&self, i: usize) -> f64 {
        f64::from(self.x_m[i])
    }

    /// Lateral y position of summit `i` \[m\].
    pub fn y_m(&self, i: usize) -> f64 {
        f64::from(self.y_m[i])
    }

    /// Height of summit `i` above the reference plane \[m\].
    pub fn height_m(&self, i: usize) -> f64 {
        self.height_m[i]
    }

    /// Radius of summit `i` \[m\].
    pub fn radius_m(&self, i: usize) -> f64 {
        match &self.radius_m {
            Radii::Uniform(r) => *r,
            Radii::PerSummit(r) => r[i],
        }
    }

    /// All x positions \[m, f32\].
    pub fn xs_m(&self) -> &[f32] {
        &self.x_m
    }

    /// All y positions \[m, f32\].
    pub fn ys_m(&self) -> &[f32] {
        &self.y_m
    }

    /// All heights \[m\].
    pub fn heights_m(&self) -> &[f64] {
        &self.height_m
    }

    /// The radii \[m\].
    pub fn radii(&self) -> &Radii {
        &self.radius_m
    }

    /// True when the heights are in descending order (as the generators produce them).
    pub fn is_sorted_by_height_descending(&self) -> bool {
        self.height_m.windows(2).all(|w| w[0] >= w[1])
    }

    /// Reorders the summits by descending height and returns, for each new position, the index the
    /// summit had before (a stable sort: equal heights keep their order).
    pub fn sort_by_height_descending(&mut self) -> Vec<u32> {
        let n = self.len();
        let mut order: Vec<u32> = (0..n as u32).collect();
        if self.is_sorted_by_height_descending() {
            return order;
        }
        let h = &self.height_m;
        order.sort_by(|&a, &b| h[b as usize].total_cmp(&h[a as usize]));
        self.x_m = order.iter().map(|&i| self.x_m[i as usize]).collect();
        self.y_m = order.iter().map(|&i| self.y_m[i as usize]).collect();
        self.height_m = order.iter().map(|&i| self.height_m[i as usize]).collect();
        if let Radii::PerSummit(r) = &self.radius_m {
            self.radius_m = Radii::PerSummit(order.iter().map(|&i| r[i as usize]).collect());
        }
        order
    }

    /// Heap bytes held per summit by this surface (arrays only, excluding the fixed-size header).
    pub fn bytes_per_summit(&self) -> f64 {
        let n = self.len().max(1) as f64;
        let mut b = self.x_m.capacity() * 4 + self.y_m.capacity() * 4 + self.height_m.capacity() * 8;
        if let Radii::PerSummit(r) = &self.radius_m {
            b += r.capacity() * 8;
        }
        b as f64 / n
    }

    /// Mean summit radius \[m\]: the `radius_mean_m` of [`Surface::stats`] (same value, bit for
    /// bit), without the height moments (a division per summit). NaN for an empty surface.
    pub fn mean_radius_m(&self) -> f64 {
        match &self.radius_m {
            Radii::Uniform(r) => {
                if self.is_empty() {
                    f64::NAN
                } else {
                    *r
                }
            }
            Radii::PerSummit(r) => moments(r.iter().copied(), r.len()).0,
        }
    }

    /// Sample statistics: count, density, height mean/SD/extremes, radius mean/SD/extremes.
    /// Uses Welford's algorithm (stable for 1e8 summits). For an empty surface the moments are NaN.
    pub fn stats(&self) -> SurfaceStats {
        let (hm, hsd, hmin, hmax) = moments(self.height_m.iter().copied(), self.len());
        let (rm, rsd, rmin, rmax) = match &self.radius_m {
            Radii::Uniform(r) => {
                if self.is_empty() {
                    (f64::NAN, f64::NAN, f64::NAN, f64::NAN)
                } else {
                    (*r, 0.0, *r, *r)
                }
            }
            Radii::PerSummit(r) => moments(r.iter().copied(), r.len()),
        };
        SurfaceStats {
            count: self.len(),
            summit_density_per_m2: self.len() as f64 / self.apparent_area_m2(),
            height_mean_m: hm,
            height_sd_m: hsd,
            height_min_m: hmin,
            height_max_m: hmax,
            radius_mean_m: rm,
            radius_sd_m: rsd,
            radius_min_m: rmin,
            radius_max_m: rmax,
        }
    }

    /// A portable 64-bit FNV-1a hash of the apparent area and every summit value (bit patterns,
    /// little-endian). Equal surfaces give equal hashes on every machine; used for golden tests.
    pub fn content_hash(&self) -> u64 {
        let mut h = Fnv::new();
        h.write(&(self.len() as u64).to_le_bytes());
        h.write(&self.apparent_length_m.to_bits().to_le_bytes());
        h.write(&self.apparent_width_m.to_bits().to_le_bytes());
        for i in 0..self.len() {
            h.write(&self.x_m[i].to_bits().to_le_bytes());
            h.write(&self.y_m[i].to_bits().to_le_bytes());
            h.write(&self.height_m[i].to_bits().to_le_bytes());
            h.write(&self.radius_m(i).to_bits().to_le_bytes());
        }
        h.0
    }

    /// Splits the surface into (apparent_length_m, apparent_width_m, x_m, y_m, height_m, radii).
    pub fn into_parts(self) -> (f64, f64, Vec<f32>, Vec<f32>, Vec<f64>, Radii) {
        (self.apparent_length_m, self.apparent_width_m, self.x_m, self.y_m, self.height_m, self.radius_m)
    }
}

fn moments(values: impl Iterator<Item = f64>, n: usize) -> (f64, f64, f64, f64) {
    if n == 0 {
        return (f64::NAN, f64::NAN, f64::NAN, f64::NAN);
    }
    let (mut mean, mut m2, mut min, mut max) = (0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY);
    for (k, v) in values.enumerate() {
        let delta = v - mean;
        mean += delta / (k + 1) as f64;
        m2 += delta * (v - mean);
        min = min.min(v);
        max = max.max(v);
    }
    let sd = if n > 1 { (m2 / (n - 1) as f64).sqrt() } else { 0.0 };
    (mean, sd, min, max)
}

pub(crate) fn check_positive(field: &str, value: f64, unit: &str) -> Result<(), SurfaceError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(SurfaceError::InvalidParameter {
            field: field.to_string(),
            value: value.to_string(),
            expected: format!("a finite value > 0 {unit}"),
        })
    }
}

pub(crate) fn check_nonnegative(field: &str, value: f64, unit: &str) -> Result<(), SurfaceError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(SurfaceError::InvalidParameter {
            field: field.to_string(),
            value: value.to_string(),
            expected: format!("a finite value >= 0 {unit}"),
        })
    }
}

struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 ^= u64::from(*b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}
