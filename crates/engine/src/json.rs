//! Results as JSON values checked finite, for front ends other than the command line.

/// `value` as a JSON value after [`stiction_units::finite::check_finite`]: a NaN or an infinity is
/// refused with its key path (`points[3].friction_n`) as the command line refuses it when it
/// prints, instead of the silent null of `serde_json::to_value`.
pub fn finite_value<T: serde::Serialize + ?Sized>(
    value: &T,
) -> Result<serde_json::Value, stiction_units::finite::NonFinite> {
    stiction_units::finite::check_finite(value)?;
    serde_json::to_value(value).map_err(|e| stiction_units::finite::NonFinite(format!("internal error: {e}")))
}

#[cfg(test)]
mod tests {
    #[test]
    fn finite_value_refuses_a_nan_that_to_value_would_null() {
        #[derive(serde::Serialize)]
        struct Point {
            load_n: f64,
            friction_n: Option<f64>,
        }
        let points =
            vec![Point { load_n: 1.0, friction_n: Some(2.0) }, Point { load_n: 2.0, friction_n: Some(f64::NAN) }];
        assert_eq!(serde_json::to_value(&points).unwrap()[1]["friction_n"], serde_json::Value::Null);
        let e = super::finite_value(&points).unwrap_err().to_string();
        assert!(e.contains("[1].friction_n"), "{e}");
        // A null needs its reason beside it.
        let bare = vec![Point { load_n: 1.0, friction_n: None }];
        assert!(super::finite_value(&bare).unwrap_err().to_string().contains("without a reason"));
        let ok = serde_json::json!([{"load_n": 1.0, "friction_n": null, "reason": "no slip"}]);
        assert_eq!(super::finite_value(&ok).unwrap(), ok);
    }
}
