//! Model names as messages are read: a former name (a recording or a daemon from before each model was
//! published under its registry name) becomes the current one, through the registry's one table
//! (`impact::registry::FORMER_NAMES`; docs/topics.md).

use std::collections::BTreeMap;

use serde::{Deserialize, Deserializer};

use crate::impact::registry::current_name;

/// A `model` field.
pub fn one<'de, D: Deserializer<'de>>(d: D) -> Result<String, D::Error> {
    let name = String::deserialize(d)?;
    Ok(current_name(&name).to_string())
}

/// A `models` list.
pub fn list<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
    let names = Vec::<String>::deserialize(d)?;
    Ok(names.iter().map(|n| current_name(n).to_string()).collect())
}

/// A map keyed by model.
pub fn keys<'de, D: Deserializer<'de>, V: Deserialize<'de>>(d: D) -> Result<BTreeMap<String, V>, D::Error> {
    let map = BTreeMap::<String, V>::deserialize(d)?;
    Ok(map.into_iter().map(|(n, v)| (current_name(&n).to_string(), v)).collect())
}

#[cfg(test)]
mod tests {
    use crate::wire::{ClubChange, LaunchPrediction};

    #[test]
    fn former_names_read_as_current_ones() {
        let line = include_str!("../../../../tests/data/web-launch.json");
        let old = line.replacen("\"model\":\"adjusted\"", "\"model\":\"impulse/adjusted\"", 1);
        assert_ne!(old, line);
        let p: LaunchPrediction = serde_json::from_str(&old).unwrap();
        assert_eq!(p.model, "adjusted");
        let c: ClubChange = serde_json::from_str(
            r#"{"rig":"a","club":{"name":"driver","file":"driver","sha256":"00"},"source":"config","models":["continuous/two_layer","ground"]}"#,
        )
        .unwrap();
        assert_eq!(c.models, ["continuous", "ground"]);
    }
}
