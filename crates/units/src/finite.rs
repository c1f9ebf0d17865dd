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

/// Checks that every number in `value`, as serialised, is finite; the error names the key path.
pub fn check_finite<T: serde::Serialize + ?Sized>(value: &T) -> Result<(), NonFinite> {
    let mut path = Vec::new();
    value.serialize(FiniteCheck { path: &mut path })
}

/// A serialiser that writes nothing: it walks the value and refuses a non-finite float.
struct FiniteCheck<'a> {
    path: &'a mut Vec<String>,
}

impl FiniteCheck<'_> {
    fn float(self, v: f64) -> Result<(), NonFinite> {
        if v.is_finite() {
            return Ok(());
        }
        let mut at = String::new();
        for p in self.path.iter() {
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
        Err(NonFinite(format!(
            "internal error: the output value at `{at}` is {v}, not a finite number (it must be a number or an \
             explicit null with a reason); please report this"
        )))
    }

    fn nested<T: serde::Serialize + ?Sized>(&mut self, key: String, value: &T) -> Result<(), NonFinite> {
        self.path.push(key);
        let r = value.serialize(FiniteCheck { path: self.path });
        self.path.pop();
        r
    }
}

/// The compound part of [`FiniteCheck`]: counts elements for the path.
struct FiniteCompound<'a> {
    check: FiniteCheck<'a>,
    index: usize,
    key: Option<String>,
}

impl FiniteCompound<'_> {
    fn element<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        let k = format!("[{}]", self.index);
        self.index += 1;
        self.check.nested(k, value)
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
        $(fn $name(self, _v: $t) -> Result<(), NonFinite> { Ok(()) })*
    };
}

impl<'a> serde::Serializer for FiniteCheck<'a> {
    type Ok = ();
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
        serialize_str: &str, serialize_bytes: &[u8], serialize_i128: i128, serialize_u128: u128);

    fn serialize_f32(self, v: f32) -> Result<(), NonFinite> {
        self.float(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<(), NonFinite> {
        self.float(v)
    }
    fn serialize_none(self) -> Result<(), NonFinite> {
        Ok(())
    }
    fn serialize_some<T: serde::Serialize + ?Sized>(self, value: &T) -> Result<(), NonFinite> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), NonFinite> {
        Ok(())
    }
    fn serialize_unit_struct(self, _name: &'static str) -> Result<(), NonFinite> {
        Ok(())
    }
    fn serialize_unit_variant(self, _n: &'static str, _i: u32, _v: &'static str) -> Result<(), NonFinite> {
        Ok(())
    }
    fn serialize_newtype_struct<T: serde::Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<(), NonFinite> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: serde::Serialize + ?Sized>(
        mut self,
        _name: &'static str,
        _i: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), NonFinite> {
        self.nested(variant.to_string(), value)
    }
    fn serialize_seq(self, _len: Option<usize>) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(FiniteCompound { check: self, index: 0, key: None })
    }
    fn serialize_tuple(self, _len: usize) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(FiniteCompound { check: self, index: 0, key: None })
    }
    fn serialize_tuple_struct(self, _n: &'static str, _len: usize) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(FiniteCompound { check: self, index: 0, key: None })
    }
    fn serialize_tuple_variant(
        self,
        _n: &'static str,
        _i: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<FiniteCompound<'a>, NonFinite> {
        self.path.push(variant.to_string());
        Ok(FiniteCompound { check: self, index: 0, key: None })
    }
    fn serialize_map(self, _len: Option<usize>) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(FiniteCompound { check: self, index: 0, key: None })
    }
    fn serialize_struct(self, _n: &'static str, _len: usize) -> Result<FiniteCompound<'a>, NonFinite> {
        Ok(FiniteCompound { check: self, index: 0, key: None })
    }
    fn serialize_struct_variant(
        self,
        _n: &'static str,
        _i: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<FiniteCompound<'a>, NonFinite> {
        self.path.push(variant.to_string());
        Ok(FiniteCompound { check: self, index: 0, key: None })
    }
}

impl serde::ser::SerializeSeq for FiniteCompound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_element<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        self.element(value)
    }
    fn end(self) -> Result<(), NonFinite> {
        Ok(())
    }
}

impl serde::ser::SerializeTuple for FiniteCompound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_element<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        self.element(value)
    }
    fn end(self) -> Result<(), NonFinite> {
        Ok(())
    }
}

impl serde::ser::SerializeTupleStruct for FiniteCompound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_field<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        self.element(value)
    }
    fn end(self) -> Result<(), NonFinite> {
        Ok(())
    }
}

impl serde::ser::SerializeTupleVariant for FiniteCompound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_field<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        self.element(value)
    }
    fn end(self) -> Result<(), NonFinite> {
        self.check.path.pop();
        Ok(())
    }
}

impl serde::ser::SerializeMap for FiniteCompound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_key<T: serde::Serialize + ?Sized>(&mut self, key: &T) -> Result<(), NonFinite> {
        self.key = Some(key_text(key));
        Ok(())
    }
    fn serialize_value<T: serde::Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        let k = self.key.take().unwrap_or_else(|| "?".into());
        self.check.nested(k, value)
    }
    fn end(self) -> Result<(), NonFinite> {
        Ok(())
    }
}

impl serde::ser::SerializeStruct for FiniteCompound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_field<T: serde::Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), NonFinite> {
        self.check.nested(key.to_string(), value)
    }
    fn end(self) -> Result<(), NonFinite> {
        Ok(())
    }
}

impl serde::ser::SerializeStructVariant for FiniteCompound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_field<T: serde::Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), NonFinite> {
        self.check.nested(key.to_string(), value)
    }
    fn end(self) -> Result<(), NonFinite> {
        self.check.path.pop();
        Ok(())
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
                Point { load_n: 1.0, friction_n: None },
                Point { load_n: 2.0, friction_n: Some(3.0) },
                Point { load_n: 3.0, friction_n: Some(bad) },
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
}
