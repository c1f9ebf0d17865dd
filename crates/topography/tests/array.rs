//! `read_array`: a height map from an array in memory, in any layout, against the `.npy` reader
//! on the same values (an independent path: the file's bytes parsed by `read_npy`). The two must
//! give bit-identical maps, since `stiction.topography(array)` promises the numbers of
//! `stiction topography FILE.npy`.

use stiction_topography::{ArrayLayout, BorrowedHeights, HeightMap, MapMetadata, NpyDtype, read_array, read_npy};

fn meta() -> MapMetadata {
    MapMetadata { pixel_size_x_m: Some(3.90625e-6), pixel_size_y_m: None, height_unit_m: Some(1e-3), xy_unit_m: None }
}

/// A 5 x 7 map (rows = y) whose every height differs, in metres per `meta()` (mm).
fn values(ny: usize, nx: usize) -> Vec<f64> {
    (0..ny * nx).map(|k| ((k * 37 % 11) as f64 - 5.0) * 1.3e-5 + k as f64 * 1e-7).collect()
}

fn via_npy(c_order: &[f64], ny: usize, nx: usize, dtype: NpyDtype) -> HeightMap {
    // A map in "mm units" written as .npy: the writer takes metres, so build it with pixel 1 m and
    // heights as the array's numbers.
    let m = HeightMap::new(nx, ny, 1.0, 1.0, c_order.to_vec()).unwrap();
    read_npy(&m.to_npy_bytes(dtype, false), "t.npy", &meta()).unwrap().0
}

#[test]
fn c_and_fortran_order_f64_and_f32_equal_the_npy_reader_bit_for_bit() {
    let (ny, nx) = (5, 7);
    let c = values(ny, nx);
    let fortran: Vec<f64> =
        (0..nx).flat_map(|ix| (0..ny).map(move |iy| (ix, iy))).map(|(ix, iy)| c[iy * nx + ix]).collect();
    let want = via_npy(&c, ny, nx, NpyDtype::F64);
    let (got, info) = read_array(BorrowedHeights::F64(&c), ArrayLayout::c_order(ny, nx), "heights", &meta()).unwrap();
    assert_eq!(got, want);
    assert_eq!(info.height_unit_m, 1e-3);
    let got =
        read_array(BorrowedHeights::F64(&fortran), ArrayLayout::fortran_order(ny, nx), "heights", &meta()).unwrap().0;
    assert_eq!(got, want);
    let c32: Vec<f32> = c.iter().map(|&v| v as f32).collect();
    let f32s: Vec<f32> = fortran.iter().map(|&v| v as f32).collect();
    let want32 = via_npy(&c, ny, nx, NpyDtype::F32);
    assert_ne!(want32, want, "float32 rounding must show, or the dtype is not tested");
    assert_eq!(read_array(BorrowedHeights::F32(&c32), ArrayLayout::c_order(ny, nx), "h", &meta()).unwrap().0, want32);
    assert_eq!(
        read_array(BorrowedHeights::F32(&f32s), ArrayLayout::fortran_order(ny, nx), "h", &meta()).unwrap().0,
        want32
    );
}

#[test]
fn strided_and_reversed_views_read_the_elements_they_name() {
    // A 10 x 7 buffer; the view is every other row, reversed (NumPy's a[::-2]): rows 9, 7, 5, 3, 1.
    let (ny, nx) = (10, 7);
    let buf = values(ny, nx);
    let layout = ArrayLayout { ny: 5, nx, row_stride: -2 * nx as isize, col_stride: 1, offset: 9 * nx };
    let got = read_array(BorrowedHeights::F64(&buf), layout, "h", &meta()).unwrap().0;
    let picked: Vec<f64> = [9, 7, 5, 3, 1].iter().flat_map(|&iy| buf[iy * nx..(iy + 1) * nx].to_vec()).collect();
    assert_eq!(got, via_npy(&picked, 5, nx, NpyDtype::F64));
    // The transpose of the C-ordered buffer (a.T): 7 rows of 10.
    let t = ArrayLayout { ny: nx, nx: ny, row_stride: 1, col_stride: nx as isize, offset: 0 };
    let got = read_array(BorrowedHeights::F64(&buf), t, "h", &meta()).unwrap().0;
    let transposed: Vec<f64> =
        (0..nx).flat_map(|ix| (0..ny).map(move |iy| (iy, ix))).map(|(iy, ix)| buf[iy * nx + ix]).collect();
    assert_eq!(got, via_npy(&transposed, nx, ny, NpyDtype::F64));
}

#[test]
fn a_layout_beyond_the_slice_is_refused_not_read() {
    let buf = values(4, 4);
    for layout in [
        ArrayLayout::c_order(4, 5),
        ArrayLayout { ny: 4, nx: 4, row_stride: -4, col_stride: 1, offset: 0 },
        ArrayLayout { ny: 4, nx: 4, row_stride: 4, col_stride: 1, offset: 1 },
    ] {
        let e = read_array(BorrowedHeights::F64(&buf), layout, "heights", &meta()).unwrap_err().to_string();
        assert!(e.contains("heights") && e.contains("strides"), "{e}");
    }
    let e = read_array(BorrowedHeights::F64(&buf), ArrayLayout::c_order(1, 16), "heights", &meta()).unwrap_err();
    assert!(e.to_string().contains("too small"), "{e}");
    let mut inf = buf.clone();
    inf[5] = f64::INFINITY;
    assert!(read_array(BorrowedHeights::F64(&inf), ArrayLayout::c_order(4, 4), "heights", &meta()).is_err());
    let nan = vec![f64::NAN; 16];
    let e = read_array(BorrowedHeights::F64(&nan), ArrayLayout::c_order(4, 4), "heights", &meta()).unwrap_err();
    assert!(e.to_string().contains("missing"), "{e}");
}
