//! Finite or null, enforced where numbers leave the program.
//!
//! serde_json writes a NaN or an infinity as `null`, silently: a value that could not be computed
//! would reach a user's file looking like a value that was deliberately left out. Every JSON the
//! program prints or writes goes through [`to_json_pretty`], which first walks the value with
//! [`check_finite`] and refuses any non-finite number with an internal error naming its key path
//! (`points[3].friction_n`). A value that cannot be computed is an `Option` set to `None` with a
//! reason beside it, never a NaN.

use std::fmt;

/// A number that is not finite (NaN or infinite) reached an output: an internal error naming its
/// place (`mu_apparent`, `points[3].friction_n`). A value that cannot be computed is written as an
/// explicit null with a reason, never as a NaN that a serialiser would turn into a silent null.
#[derive(Debug)]
pub struct NonFinite(pub String);

impl fmt::Display for NonFinite {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

impl std::error::Error for NonFinite {}

impl serde::ser::Error for NonFinite {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        NonFinite(msg.to_string())
    }
}

/// Checks that every number in `value`, as serialised, is finite, and that every null has a reason
/// beside it ([`is_reason_key`]); the error names the key path.
pub fn check_finite<T: serde::Serialize + ?Sized>(value: &T) -> Result<(), NonFinite> {
    let mut path = Vec::new();
    value.serialize(FiniteCheck { path: &mut path }).map(|_| ())
}

/// Whether a key names the reason for the nulls of its object: `reason`, `note`, `notes`,
/// `reasons`, `why`, `no_prediction`, or a name ending in `_reason`, `_note`, `_reasons` or `_notes`
/// (`friction_slope_null_reason`, `fit_note`, `autocorrelation_length_note`).
pub fn is_reason_key(key: &str) -> bool {
    ["reason", "note", "reasons", "notes", "no_prediction", "why"].contains(&key)
        || ["_reason", "_note", "_reasons", "_notes"].iter().any(|end| key.ends_with(end))
}

/// What a serialised value was, as far as the null-reason rule cares.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Kind {
    /// `null` (a `None`, a unit).
    Null,
    /// A non-empty string, or a non-empty list: can be a reason.
    Text,
    /// A list with a null among its elements: needs a reason like a null.
    ListWithNull,
    /// Anything else.
    Other,
}

/// A serialiser that writes nothing: it walks the value and refuses a non-finite float and a
/// null without a reason.
struct FiniteCheck<'a> {
    path: &'a mut Vec<String>,
}

/// `path` as `points[3].friction_n`.
fn path_text(path: &[String]) -> String {
    let mut at = String::new();
    for p in path.iter() {
        if p.starts_with('[') || at.is_empty() {
            at.push_str(p);
        } else {
            at.push('.');
            at.push_str(p);
        }
    }
    if at.is_empty() {
        at.push_str("(the value itself)");
    }
    at
}

impl<'a> FiniteCheck<'a> {
    fn float(self, v: f64) -> Result<Kind, NonFinite> {
        if v.is_finite() {
            return Ok(Kind::Other);
        }
        Err(NonFinite(format!(
            "internal error: the output value at `{}` is {v}, not a finite number (it must be a number or an \
             explicit null with a reason); please report this",
            path_text(self.path)
        )))
    }

    fn nested<T: serde::Serialize + ?Sized>(&mut self, key: String, value: &T) -> Result<Kind, NonFinite> {
        self.path.push(key);
        let r = value.serialize(FiniteCheck { path: self.path });
        self.path.pop();
        r
    }

    fn compound(self) -> FiniteCompound<'a> {
        FiniteCompound { check: self, index: 0, key: None, nulls: Vec::new(), reasoned: false, list_null: false }
    }
}

/// The compound part of [`FiniteCheck`]: counts elements for the path, and collects the keys of
/// an object that are null (or lists with a null) and whether the object gives a reason.
struct FiniteCompound<'a> {
    check: FiniteCheck<'a>,
    index: usize,
    key: Option<String>,
    nulls: Vec<String>,
    reasoned: bool,
    list_null: bool,
}

impl FiniteCompound<'_> {
    fn element<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        let k = format!("[{}]", self.index);
        self.index += 1;
        if self.check.nested(k, value)? == Kind::Null {
            self.list_null = true;
        }
        Ok(())
    }

    fn field<T: serde::Serialize + ?Sized>(&mut self, key: String, value: &T) -> Result<(), NonFinite> {
        let kind = self.check.nested(key.clone(), value)?;
        // A reason key is never a null that needs a reason (`reason: null` where all is well,
        // `mu_reasons: [null, "no slip"]` beside `mu: [0.7, null]`).
        match kind {
            Kind::Text | Kind::ListWithNull if is_reason_key(&key) => self.reasoned = true,
            Kind::Null | Kind::ListWithNull if !is_reason_key(&key) => self.nulls.push(key),
            _ => {}
        }
        Ok(())
    }

    fn end_list(self) -> Result<Kind, NonFinite> {
        Ok(if self.list_null {
            Kind::ListWithNull
        } else if self.index > 0 {
            Kind::Text
        } else {
            Kind::Other
        })
    }

    fn end_object(self) -> Result<Kind, NonFinite> {
        if let Some(key) = self.nulls.first()
            && !self.reasoned
        {
            let mut at = self.check.path.clone();
            at.push(key.clone());
            return Err(NonFinite(format!(
                "internal error: the output value at `{}` is null without a reason beside it (a `reason` or a \
                 `..._note`); please report this",
                path_text(&at)
            )));
        }
        Ok(Kind::Other)
    }
}

fn key_text<T: serde::Serialize + ?Sized>(key: &T) -> String {
    match serde_json::to_value(key) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(v) => v.to_string(),
        Err(_) => "?".into(),
    }
}

macro_rules! finite_ok {
    ($($name:ident: $t:ty),*) => {
        $(fn $name(self, _v: $t) -> Result<Kind, NonFinite> { Ok(Kind::Other) })*
    };
}

impl<'a> serde::Serializer for FiniteCheck<'a> {
    type Ok = Kind;
    type Error = NonFinite;
    type SerializeSeq = FiniteCompound<'a>;
    type SerializeTuple = FiniteCompound<'a>;
    type SerializeTupleStruct = FiniteCompound<'a>;
    type SerializeTupleVariant = FiniteCompound<'a>;
    type SerializeMap = FiniteCompound<'a>;
    type SerializeStruct = FiniteCompound<'a>;
    type SerializeStructVariant = FiniteCompound<'a>;

    finite_ok!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32, serialize_i64: i64,
        serialize_u8: u8, serialize_u16: u16, serialize_u32: u32, serialize_u64: u64, serialize_char: char,
        serialize_bytes: &[u8], serialize_i128: i128, serialize_u128: u128);

    fn serialize_str(self, v: &str) -> Result<Kind, NonFinite> {
        Ok(if v.trim().is_empty() { Kind::Other } else { Kind::Text })
    }
    fn serialize_f32(self, v: f32) -> Result<Kind, NonFinite> {
        self.float(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<Kind, NonFinite> {
        self.float(v)
    }
    fn serialize_none(self) -> Result<Kind, NonFinite> {
        Ok(Kind::Null)
    }
    fn serialize_some<T: serde::Serialize + ?Sized>(self, value: &T) -> Result<Kind, NonFinite> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<Kind, NonFinite> {
        Ok(Kind::Null)
    }
    fn serialize_unit_struct(self, _name: &'static str) -> Result<Kind, NonFinite> {
        Ok(Kind::Null)
    }
    fn serialize_unit_variant(self, _n: &'static str, _i: u32, _v: &'static str) -> Result<Kind, NonFinite> {
        Ok(Kind::Text)
    }
    fn serialize_newtype_struct<T: serde::Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<Kind, NonFinite> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: serde::Serialize + ?Sized>(
        mut self,
        _name: &'static str,
        _i: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<Kind, NonFinite> {
        self.nested(variant.to_string(), value).map(|_| Kind::Other)
    }
    fn serialize_seq(self, _len: Option<usize>) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_tuple(self, _len: usize) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_tuple_struct(self, _n: &'static str, _len: usize) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_tuple_variant(
        self,
        _n: &'static str,
        _i: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<FiniteCompound<'a>, NonFinite> {
        self.path.push(variant.to_string());
        Ok(self.compound())
    }
    fn serialize_map(self, _len: Option<usize>) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_struct(self, _n: &'static str, _len: usize) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_struct_variant(
        self,
        _n: &'static str,
        _i: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<FiniteCompound<'a>, NonFinite> {
        self.path.push(variant.to_string());
        Ok(self.compound())
    }
}

impl serde::ser::SerializeSeq for FiniteCompound<'_> {
    type Ok = Kind;
    type Error = NonFinite;
    fn serialize_element<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        self.element(value)
    }
    fn end(self) -> Result<Kind, NonFinite> {
        self.end_list()
    }
}

impl serde::ser::SerializeTuple for FiniteCompound<'_> {
    type Ok = Kind;
    type Error = NonFinite;
    fn serialize_element<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        self.element(value)
    }
    fn end(self) -> Result<Kind, NonFinite> {
        self.end_list()
    }
}

impl serde::ser::SerializeTupleStruct for FiniteCompound<'_> {
    type Ok = Kind;
    type Error = NonFinite;
    fn serialize_field<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        self.element(value)
    }
    fn end(self) -> Result<Kind, NonFinite> {
        self.end_list()
    }
}

impl serde::ser::SerializeTupleVariant for FiniteCompound<'_> {
    type Ok = Kind;
    type Error = NonFinite;
    fn serialize_field<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        self.element(value)
    }
    fn end(self) -> Result<Kind, NonFinite> {
        self.check.path.pop();
        Ok(Kind::Other)
    }
}

impl serde::ser::SerializeMap for FiniteCompound<'_> {
    type Ok = Kind;
    type Error = NonFinite;
    fn serialize_key<T: serde::Serialize + ?Sized>(&mut self, key: &T) -> Result<(), NonFinite> {
        self.key = Some(key_text(key));
        Ok(())
    }
    fn serialize_value<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        let k = self.key.take().unwrap_or_else(|| "?".into());
        self.field(k, value)
    }
    fn end(self) -> Result<Kind, NonFinite> {
        self.end_object()
    }
}

impl serde::ser::SerializeStruct for FiniteCompound<'_> {
    type Ok = Kind;
    type Error = NonFinite;
    fn serialize_field<T: serde::Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), NonFinite> {
        self.field(key.to_string(), value)
    }
    fn end(self) -> Result<Kind, NonFinite> {
        self.end_object()
    }
}

impl serde::ser::SerializeStructVariant for FiniteCompound<'_> {
    type Ok = Kind;
    type Error = NonFinite;
    fn serialize_field<T: serde::Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), NonFinite> {
        self.field(key.to_string(), value)
    }
    fn end(mut self) -> Result<Kind, NonFinite> {
        let r = std::mem::take(&mut self.nulls);
        let reasoned = self.reasoned;
        self.check.path.pop();
        match r.first() {
            Some(key) if !reasoned => Err(NonFinite(format!(
                "internal error: the output value at `{}.{key}` is null without a reason beside it (a `reason` or \
                 a `..._note`); please report this",
                path_text(self.check.path)
            ))),
            _ => Ok(Kind::Other),
        }
    }
}

/// `value` as pretty JSON with a final newline, after [`check_finite`].
pub fn to_json_pretty<T: serde::Serialize + ?Sized>(value: &T) -> Result<String, NonFinite> {
    check_finite(value)?;
    serde_json::to_string_pretty(value).map(|s| s + "\n").map_err(|e| NonFinite(format!("internal error: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[derive(serde::Serialize)]
    struct Point {
        load_n: f64,
        friction_n: Option<f64>,
        #[serde(skip_serializing_if = "Option::is_none")]
        reason: Option<String>,
    }

    #[derive(serde::Serialize)]
    struct Report {
        name: String,
        points: Vec<Point>,
        by_model: BTreeMap<String, (f64, f64)>,
    }

    fn report(bad: f64) -> Report {
        Report {
            name: "x".into(),
            points: vec![
                Point { load_n: 1.0, friction_n: None, reason: Some("no slip".into()) },
                Point { load_n: 2.0, friction_n: Some(3.0), reason: None },
                Point { load_n: 3.0, friction_n: Some(bad), reason: None },
            ],
            by_model: BTreeMap::from([("gw".to_string(), (1.0, 2.0))]),
        }
    }

    #[test]
    fn finite_values_and_nulls_pass_and_round_trip() {
        let text = to_json_pretty(&report(4.0)).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["points"][0]["friction_n"], serde_json::Value::Null);
        assert_eq!(v["points"][2]["friction_n"], 4.0);
        assert_eq!(text, serde_json::to_string_pretty(&report(4.0)).unwrap() + "\n");
    }

    #[test]
    fn a_nan_or_infinity_is_refused_naming_its_path() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let e = to_json_pretty(&report(bad)).unwrap_err().to_string();
            assert!(e.contains("`points[2].friction_n`") && e.contains("internal error"), "{e}");
        }
        let mut r = report(1.0);
        r.by_model.insert("dmt".into(), (1.0, f64::NAN));
        let e = check_finite(&r).unwrap_err().to_string();
        assert!(e.contains("`by_model.dmt[1]`"), "{e}");
        // A serde_json::Value cannot hold a NaN (it is null there already); an f32 is checked too.
        assert!(check_finite(&vec![1.0f32, f32::NAN]).unwrap_err().to_string().contains("`[1]`"));
        assert!(check_finite(&f64::NAN).unwrap_err().to_string().contains("(the value itself)"));
    }

    /// Every null needs a reason beside it: a null without one (the eq. 10 slope of a flat line
    /// printed as `mu_apparent: null` and nothing else) is an internal error naming the key; an
    /// empty reason is no reason; a list holding a null needs one too.
    #[test]
    fn a_null_without_a_reason_is_refused_naming_its_path() {
        let mut r = report(1.0);
        r.points[0].reason = None;
        let e = to_json_pretty(&r).unwrap_err().to_string();
        assert!(e.contains("`points[0].friction_n`") && e.contains("without a reason"), "{e}");
        r.points[0].reason = Some("  ".into());
        assert!(check_finite(&r).is_err());
        for key in ["fit_note", "friction_slope_null_reason", "reason", "notes"] {
            let ok = serde_json::json!({ "mu": null, key: "three distinct loads are needed" });
            assert!(check_finite(&ok).is_ok(), "{key}");
        }
        let bare = serde_json::json!({ "a": { "mu": [0.7, null] } });
        assert!(check_finite(&bare).unwrap_err().to_string().contains("`a.mu`"));
        let with = serde_json::json!({ "a": { "mu": [0.7, null], "mu_reasons": [null, "no slip"] } });
        assert!(check_finite(&with).is_ok());
        assert!(is_reason_key("autocorrelation_length_note") && !is_reason_key("notebook"));
    }
}
