//! Materials, referred to by name from objects.

use super::Color;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum MaterialDesc {
    /// Ideal diffuse: f = albedo/π. Each channel in [0, 1].
    Lambert { albedo: Color },
}
