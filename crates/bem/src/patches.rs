//! Contact patches: connected components of the contact mask on the periodic grid, or on a
//! bounded (non-periodic) patch.

/// Number of 4-connected components of the `true` points of `mask` (row-major, `nx` columns,
/// `ny` rows), with periodic wrap-around in both directions (a patch crossing the cell edge counts
/// once). Iterative flood fill with an explicit stack, O(n) time and memory.
pub fn count_patches(mask: &[bool], nx: usize, ny: usize) -> usize {
    label_patches(mask, nx, ny).1
}

/// As [`count_patches`] without the wrap-around (a finite patch: its edges do not meet).
pub fn count_patches_bounded(mask: &[bool], nx: usize, ny: usize) -> usize {
    label(mask, nx, ny, false).1
}

/// Patch label of every point (0 outside contact, 1..=count inside) and the count (periodic).
pub fn label_patches(mask: &[bool], nx: usize, ny: usize) -> (Vec<u32>, usize) {
    label(mask, nx, ny, true)
}

fn label(mask: &[bool], nx: usize, ny: usize, periodic: bool) -> (Vec<u32>, usize) {
    let mut label = vec![0u32; mask.len()];
    let mut count = 0usize;
    let mut stack = Vec::new();
    for start in 0..mask.len() {
        if !mask[start] || label[start] != 0 {
            continue;
        }
        count += 1;
        let id = count as u32;
        label[start] = id;
        stack.push(start);
        while let Some(i) = stack.pop() {
            let (x, y) = (i % nx, i / nx);
            let nbrs = [
                (y * nx + (x + 1) % nx, periodic || x + 1 < nx),
                (y * nx + (x + nx - 1) % nx, periodic || x > 0),
                (((y + 1) % ny) * nx + x, periodic || y + 1 < ny),
                (((y + ny - 1) % ny) * nx + x, periodic || y > 0),
            ];
            for (j, inside) in nbrs {
                if inside && mask[j] && label[j] == 0 {
                    label[j] = id;
                    stack.push(j);
                }
            }
        }
    }
    (label, count)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_components() {
        // 4 x 3 grid: columns 0 and 3 of row 0 touch through the x wrap (one patch); the point at
        // column 2 of row 2 has no contact neighbour, also not through the y wrap: two patches.
        #[rustfmt::skip]
        let m = [
            true,  false, false, true,
            false, false, false, false,
            false, false, true,  false,
        ];
        assert_eq!(count_patches(&m, 4, 3), 2);
        // Without the wrap the two corners of row 0 are apart: three patches.
        assert_eq!(count_patches_bounded(&m, 4, 3), 3);
        // Diagonal neighbours are not connected (4-connectivity).
        #[rustfmt::skip]
        let d = [
            true,  false, false,
            false, true,  false,
            false, false, false,
        ];
        assert_eq!(count_patches(&d, 3, 3), 2);
        assert_eq!(count_patches(&[false; 9], 3, 3), 0);
        assert_eq!(count_patches(&[true; 9], 3, 3), 1);
    }
}
