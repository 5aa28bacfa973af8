//! The JSON Schema of the scene format, generated from the scene types so it
//! cannot drift from what the loader accepts (a test compares it with the
//! committed `schema/scene.schema.json`).

use crate::desc::SceneDesc;

/// The schema as pretty-printed JSON, newline-terminated.
pub fn schema_json() -> String {
    let mut schema = schemars::schema_for!(SceneDesc);
    schema.insert("$id".into(), "https://ronray.dev/schema/scene.schema.json".into());
    schema.insert(
        "description".into(),
        "A ronray scene. Write it in RON (`#![schema = \"…/scene.schema.json\"]` header allowed) or JSON."
            .into(),
    );
    serde_json::to_string_pretty(&schema).unwrap_or_default() + "\n"
}
