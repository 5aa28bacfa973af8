//! EXR output with AOV layers: the beauty pass as `R`, `G`, `B` (unchanged)
//! and each layer `film.aovs` asks for as channels in the same single-part
//! file, named as compositors expect them:
//!
//! | layer | channels | type |
//! |---|---|---|
//! | `Albedo` | `albedo.R`, `albedo.G`, `albedo.B` | f32 |
//! | `Normal` | `N.X`, `N.Y`, `N.Z` | f32 |
//! | `Depth` | `Z` | f32 |
//! | `Position` | `P.X`, `P.Y`, `P.Z` | f32 |
//! | `MaterialIndex` | `materialId` | u32 |
//! | `ObjectIndex` | `objectId` | u32 |
//!
//! `Z` is OpenEXR's standard depth channel name; `N` and `P` are the
//! layer names Nuke uses for normals and positions; `layer.channel` is the
//! prefix convention Nuke's EXR reader splits into layer and channel
//! (`ExrChannelNameToNuke` in the Nuke NDK) and Blender's multilayer EXRs
//! use. `materialId` and `objectId` have no standard name: an integer channel (u32), so no
//! reader filters it into ids that exist nowhere. One part rather than
//! OpenEXR 2 multi-part, which not every reader opens.

use super::{Aov, AovLayers};
use crate::imageio::{Image, ImageError, write_atomic};
use std::path::Path;

/// Writes `img` and the layers `layers.written` lists to the EXR file `path`
/// atomically, byte-reproducibly (blocks in increasing order).
pub fn write_exr_layers(img: &Image, layers: &AovLayers, path: &Path) -> Result<(), ImageError> {
    let err = |reason: String| ImageError::Write {
        path: path.to_path_buf(),
        reason,
    };
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    if !ext.eq_ignore_ascii_case("exr") {
        return Err(err("AOV layers are written only to EXR files".into()));
    }
    let n = img.width as usize * img.height as usize;
    if img.pixels.len() != n || (layers.width, layers.height) != (img.width, img.height) {
        return Err(err("size mismatch between the image and its layers".into()));
    }
    write_atomic(path, |w| encode(img, layers, w))
}

fn encode(img: &Image, layers: &AovLayers, w: &mut std::io::BufWriter<&std::fs::File>) -> Result<(), String> {
    use exr::prelude::{AnyChannel, AnyChannels, Encoding, FlatSamples, LineOrder, SmallVec, WritableImage};
    let f32s = |name: &str, v: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(v));
    let rgb = |prefix: &str, names: [&str; 3], v: &[glam::Vec3A]| -> Vec<AnyChannel<FlatSamples>> {
        (0..3)
            .map(|k| f32s(&format!("{prefix}{}", names[k]), v.iter().map(|p| p[k]).collect()))
            .collect()
    };
    let mut channels = rgb("", ["R", "G", "B"], &img.pixels);
    for aov in layers.written.iter() {
        match aov {
            Aov::Albedo => channels.extend(rgb("albedo.", ["R", "G", "B"], &layers.albedo)),
            Aov::Normal => channels.extend(rgb("N.", ["X", "Y", "Z"], &layers.normal)),
            Aov::Depth => channels.push(f32s("Z", layers.depth.clone())),
            Aov::Position => channels.extend(rgb("P.", ["X", "Y", "Z"], &layers.position)),
            Aov::MaterialIndex => channels.push(AnyChannel::new(
                "materialId",
                FlatSamples::U32(layers.material_id.clone()),
            )),
            Aov::ObjectIndex => channels.push(AnyChannel::new(
                "objectId",
                FlatSamples::U32(layers.object_id.clone()),
            )),
        }
    }
    let encoding = Encoding {
        line_order: LineOrder::Increasing,
        ..Encoding::FAST_LOSSLESS
    };
    let size = (img.width as usize, img.height as usize);
    let channels = AnyChannels::sort(SmallVec::from_vec(channels));
    exr::prelude::Image::from_encoded_channels(size, encoding, channels)
        .write()
        .to_buffered(w)
        .map_err(|e| e.to_string())
}
