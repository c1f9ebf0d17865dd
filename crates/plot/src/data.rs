//! The plotted numbers of a chart as CSV and JSON ([`Chart::data_csv`], [`Chart::data_json`]), with
//! the axis units in the column names ([`column_key`]).

use crate::chart::{Chart, Series, SeriesStyle};

impl Chart {
    /// The CSV column names of x and y (with their units).
    pub fn column_keys(&self) -> (String, String) {
        (
            self.x_key.clone().unwrap_or_else(|| column_key(&self.x_label)),
            self.y_key.clone().unwrap_or_else(|| column_key(&self.y_label)),
        )
    }

    /// The data columns after `series` and `style`: x, y, x error, y error, upper y edge, upper x edge.
    pub fn data_columns(&self) -> [String; 6] {
        let (xk, yk) = self.column_keys();
        [xk.clone(), yk.clone(), format!("{xk}_err"), format!("{yk}_err"), format!("{yk}_upper"), format!("{xk}_upper")]
    }

    /// The plotted numbers of series `s`, one row per point, in the order of [`Chart::data_columns`]
    /// (None: empty). A span is one row: an x range has x = low and `x_upper` = high, a y range y = low
    /// and `y_upper` = high.
    fn rows(s: &Series) -> Vec<[Option<f64>; 6]> {
        let fin = |v: f64| v.is_finite().then_some(v);
        s.points
            .iter()
            .enumerate()
            .map(|(i, &(x, y))| {
                let pick = |v: &Option<Vec<f64>>| v.as_ref().and_then(|v| v.get(i)).copied().and_then(fin);
                match s.style {
                    SeriesStyle::XSpan => [fin(x), None, None, None, None, fin(y)],
                    SeriesStyle::YSpan => [None, fin(x), None, None, fin(y), None],
                    _ => [fin(x), fin(y), pick(&s.x_err), pick(&s.y_err), pick(&s.upper), None],
                }
            })
            .collect()
    }

    /// The plotted numbers as CSV: one row per point, columns `series`, `style`, (`label` when a
    /// series names its points), x and y with their
    /// units, the error bars, band edges and span ends where a series has them
    /// ([`Chart::data_columns`]).
    pub fn data_csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        let mut header = vec!["series".to_string(), "style".into()];
        let labelled = self.series.iter().any(|s| s.labels.is_some());
        if labelled {
            header.push("label".into());
        }
        header.extend(self.data_columns());
        // Writing to a Vec cannot fail.
        w.write_record(&header).ok();
        let num = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
        for s in &self.series {
            for (i, row) in Self::rows(s).into_iter().enumerate() {
                let mut rec = vec![s.name.clone(), s.style.name().to_string()];
                if labelled {
                    rec.push(s.labels.as_ref().and_then(|l| l.get(i)).cloned().unwrap_or_default());
                }
                rec.extend(row.iter().map(|v| num(*v)));
                w.write_record(&rec).ok();
            }
        }
        String::from_utf8(w.into_inner().unwrap_or_default()).unwrap_or_default()
    }

    /// The same numbers as [`Chart::data_csv`] as JSON, for results files: `title`, `x_label`,
    /// `y_label`, and `series`, each with `name`, `style` and one array per column that has a value
    /// (keys as the CSV columns, with units: `load_un`, `friction_un`, `friction_un_err`, ...;
    /// null where a point has none).
    pub fn data_json(&self) -> serde_json::Value {
        use serde_json::{Value, json};
        let cols = self.data_columns();
        let series: Vec<Value> = self
            .series
            .iter()
            .map(|s| {
                let rows = Self::rows(s);
                let mut obj = serde_json::Map::new();
                obj.insert("name".into(), json!(s.name));
                obj.insert("style".into(), json!(s.style.name()));
                for (c, key) in cols.iter().enumerate() {
                    if rows.iter().any(|r| r[c].is_some()) {
                        obj.insert(key.clone(), Value::Array(rows.iter().map(|r| json!(r[c])).collect()));
                    }
                }
                Value::Object(obj)
            })
            .collect();
        json!({"title": self.title, "x_label": self.x_label, "y_label": self.y_label, "series": series})
    }
}

/// A CSV column name from an axis label: the quantity's words and its unit, lower case, ASCII,
/// e.g. `load L (µN)` -> `load_l_un`, `V_pull² (V²)` -> `v_pull2_v2`; the micro sign µ becomes `u`,
/// the Greek letter μ `mu`.
pub fn column_key(label: &str) -> String {
    let mut out = String::new();
    for c in label.chars() {
        let mapped: String = match c {
            'µ' => "u".into(),
            'μ' => "mu".into(),
            '²' => "2".into(),
            '³' => "3".into(),
            '⁻' => "-".into(),
            'θ' => "theta".into(),
            'σ' => "sigma".into(),
            'α' => "alpha".into(),
            'κ' => "kappa".into(),
            '*' => "star".into(),
            '%' => "percent".into(),
            c if c.is_ascii_alphanumeric() => c.to_ascii_lowercase().to_string(),
            _ => "_".into(),
        };
        out.push_str(&mapped);
    }
    let mut key = String::new();
    for part in out.split('_').filter(|p| !p.is_empty()) {
        if !key.is_empty() {
            key.push('_');
        }
        key.push_str(part);
    }
    if key.is_empty() { "value".into() } else { key }
}
