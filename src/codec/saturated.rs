//! Which payload fields a state did not fit: a set of [`FIELDS`] rows, small enough to keep with
//! every packet.

use super::{FieldSpec, FIELDS};
use serde::{Serialize, Serializer};

/// The payload fields whose value lay beyond the field's range and was sent as the range's edge
/// (reference §5): a speed over 25.5 m/s is sent as 25.5, a position 7 km from the flight's start
/// as 6553.4 m. A station decoding such a packet starts from a state other than the drone's
/// estimate. Serialised as the fields' names in state order (`["x", "v"]`).
///
/// ```
/// use loratrack::{encode, ModelKind};
/// let e = encode(ModelKind::Dr, &[9000.0, 0.0, 0.0, 0.0, 0.0, 30.0], [0.0; 3]).unwrap();
/// assert_eq!(e.saturated.names().collect::<Vec<_>>(), ["x", "v"]);
/// assert!(e.saturated.contains("v") && !e.saturated.contains("y"));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SaturatedFields(u16);

impl SaturatedFields {
    /// Adds the field at `index` in [`FIELDS`].
    pub(crate) fn insert(&mut self, index: usize) {
        self.0 |= 1 << index;
    }

    /// Takes out the field at `index` in [`FIELDS`].
    pub(crate) fn remove(&mut self, index: usize) {
        self.0 &= !(1 << index);
    }

    /// Whether no field saturated.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Whether the field named `name` (`x`, `v`, …) saturated.
    pub fn contains(self, name: &str) -> bool {
        self.fields().any(|f| f.name == name)
    }

    /// The fields of both sets.
    pub fn union(self, other: Self) -> Self {
        SaturatedFields(self.0 | other.0)
    }

    /// The saturated fields, in state order.
    pub fn fields(self) -> impl Iterator<Item = &'static FieldSpec> {
        FIELDS
            .iter()
            .enumerate()
            .filter(move |(i, _)| self.0 & (1 << i) != 0)
            .map(|(_, f)| f)
    }

    /// Their names, in state order.
    pub fn names(self) -> impl Iterator<Item = &'static str> {
        self.fields().map(|f| f.name)
    }

    /// Each field and its range, in words ([`FieldSpec::words`]), joined by semicolons: `turn
    /// rate ω, ±2 rad/s; tilt rate ψ, ±2 rad/s`.
    pub fn words(self) -> String {
        self.fields()
            .map(FieldSpec::words)
            .collect::<Vec<_>>()
            .join("; ")
    }
}

impl Serialize for SaturatedFields {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.names())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_union_holds_both_sets_fields_in_state_order() {
        let (mut a, mut b) = (SaturatedFields::default(), SaturatedFields::default());
        a.insert(5);
        b.insert(0);
        b.insert(5);
        assert_eq!(a.union(b).names().collect::<Vec<_>>(), ["x", "v"]);
        assert!(SaturatedFields::default().is_empty() && !a.is_empty());
    }

    #[test]
    fn serialises_as_the_fields_names() {
        let mut s = SaturatedFields::default();
        s.insert(6);
        s.insert(2);
        assert_eq!(serde_json::to_string(&s).unwrap(), r#"["z","a"]"#);
        assert_eq!(
            serde_json::to_string(&SaturatedFields::default()).unwrap(),
            "[]"
        );
    }
}
